"""What the header says about each primitive slot, precomputed as plain tuples for the engine
and the geometry: rings, edge directions, the faces on either side, length ranges, typical
lengths and the clearance kept between distinct vertices and edges; and the spatial grid's
cell side that follows from them."""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, replace

from grammar_lang.frame import border_labels, through_labels as frame_through_labels
from grammar_lang.rules import Header
from grammar_lang.source import EdgeClass
from grammar_lang.vocabulary import Vocabular, Vocabulary

from .spatial import Point


@dataclass(frozen=True)
class Tables(Vocabular):
    """What the header says about each primitive slot, precomputed as plain tuples, with the
    header's vocabulary (its unit 1 where the header gives none)."""

    rings: tuple[tuple[int, ...], ...]
    direction: tuple[tuple[Point, ...], ...]   # unit vector pointing away from the vertex
    left: tuple[tuple[str, ...], ...]          # face on the left walking away from the vertex
    right: tuple[tuple[str, ...], ...]
    label: tuple[tuple[int, ...], ...]
    outer: tuple[str | None, ...]              # face label seen just below direction 180°
    # Per edge label: (min, max, fixed or None, tile or None)
    lengths: tuple[tuple[float, float, float | None, float | None], ...]
    label_class: tuple[str, ...]
    label_faces: tuple[tuple[str, str], ...]
    vocabulary: Vocabulary
    # Per edge label: the example's median length (nan when unknown): where new edges are drawn.
    typical: tuple[float, ...] = ()
    # Per edge label: the shortest a drawn edge may be (0: no floor), see `least_lengths`.
    least: tuple[float, ...] = ()
    # The lines across a frame that things stand on (`through_labels`).
    through: frozenset[int] = frozenset()
    # The frame's side labels at those lines' ends (`gap_labels`): their pieces are the
    # heights of the strips between the lines, and keep the floor of `least`.
    gaps: frozenset[int] = frozenset()

    # Read through Vocabular's property on every test of a step (27 reads per step on curl).
    unit = functools.cached_property(lambda self: self.vocabulary.unit)

    @functools.cached_property
    def clearance(self) -> float:
        """How far apart distinct vertices and edges must stay: a fiftieth of the unit, or a
        quarter of the shortest edge any class allows, whichever is less (never zero)."""
        u = self.unit
        c = min(0.02 * u, 0.25 * min((l[0] for l in self.lengths), default=u))
        return max(c, 1e-9 * u)

    @functools.cached_property
    def gap(self) -> float:
        """How far apart parts that are far apart in the graph must stay in a framed scene
        (FAR_HOPS in the solver): a tenth of the unit, never less than the clearance. The examples keep
        theirs a unit or more apart (the paper's four: 40-100 px at 40 px a unit); at the
        clearance alone a blossom was drawn 1 px from another plant's, and read as touching.
        A quarter of the unit cost the paper's castle, flowers and station 8-12 % of their
        vertices at the paper's N; a tenth, 0-5 %."""
        return max(0.1 * self.unit, self.clearance)

    @functools.cached_property
    def one_face_label(self) -> bool:
        """Every face has the same label, so no placement can put a face in the wrong place."""
        return all(l == self.exterior and r == self.exterior for l, r in self.label_faces)

    @staticmethod
    def build(header: Header) -> "Tables":
        labels = header.labels
        unit = header.unit if header.unit and header.unit > 0 else 1.0
        classes = {c.name: c.resolved(unit) for c in header.classes}
        rings, dirs, lefts, rights, labs, outer = [], [], [], [], [], []
        for prim in header.primitives:
            d, l, r, lb = [], [], [], []
            for t in prim.ring:
                lab = labels[t >> 1]
                d.append(unit_vector(lab.direction(bool(t & 1))))
                bar = bool(t & 1)
                l.append(lab.right if bar else lab.left)
                r.append(lab.left if bar else lab.right)
                lb.append(t >> 1)
            rings.append(tuple(prim.ring))
            dirs.append(tuple(d))
            lefts.append(tuple(l))
            rights.append(tuple(r))
            labs.append(tuple(lb))
            # The sector from the last half-edge (largest angle) round to the first holds 180°.
            outer.append(l[-1] if l else None)
        lengths = []
        for lab in labels:
            c = classes.get(lab.cls) or EdgeClass(lab.cls).resolved(unit)
            fixed = lab.length if (c.rigid and lab.length) else c.fixed
            lengths.append((float(c.min_length), float(c.max_length), fixed, c.tile))
        through = through_labels(header)
        gaps = gap_labels(header, through)
        return Tables(tuple(rings), tuple(dirs), tuple(lefts), tuple(rights), tuple(labs),
                      tuple(outer), tuple(lengths), tuple(l.cls for l in labels),
                      tuple((l.left, l.right) for l in labels),
                      replace(header.vocabulary, unit=unit),
                      tuple(math.nan if l.typical is None else l.typical for l in labels),
                      least_lengths(header, through), through, gaps)


# A drawn edge is at least this share of its label's typical length, or as short as the
# example's shortest edge of that label when that is shorter, whatever its class allows: the
# parts of a structure keep their proportions. Without it the paper's castle grew 2 px towers
# on wall tops, each in the room a thinner one had left. At 0.2 it still grew combs of 8 px
# poles: a part split into a held width is squeezed by the projection (drawn tops of 88 and
# 86 px came out 51 and 20), and the next part beside it is drawn at that squeezed scale, so
# 95 of its 148 tower tops ended within 30 % of the floor (seed 80). At 0.4 (16 px for a
# 40 px top, the example's narrowest is 20) towers keep their width: castle seeds 0-19 and
# 80 all have every label, 255 vertices on average against 388, 2-6 % of lengths near their
# floor against 30-37 %. At 0.5 castle seeds 2 and 18 lost their ropes and the village's
# start no longer fitted its frame.
PROPORTION = 0.4


def least_lengths(header: Header, through: frozenset[int] | None = None) -> tuple[float, ...]:
    """Per label, the shortest a drawn edge may be: min(PROPORTION·typical, the example's
    shortest); no floor (0) where either is unknown (a hand-written rule file), nor on the
    lines things stand on (`through`: `through_labels`, worked out when not given)."""
    through = through_labels(header) if through is None else through
    return tuple(min(PROPORTION * l.typical, l.shortest)
                 if l.typical is not None and l.shortest is not None and k not in through
                 else 0.0 for k, l in enumerate(header.labels))


def through_labels(header: Header) -> frozenset[int]:
    """`frame.through_labels` of a rule file's header (none without a frame)."""
    if header.frame is None:
        return frozenset()
    return frame_through_labels(header.primitives, header.labels, header.classes)


def gap_labels(header: Header, through: frozenset[int]) -> frozenset[int]:
    """The border labels that meet a line across the frame (`through_labels`) at its end: the
    frame's sides where the village's strip lines end. A piece of such a side is the height
    of a strip at the frame, not a length the frame sets, so it keeps its label's floor like
    any drawn edge (without it the paper's village at its seed, 65, ended its N with 29 side
    pieces, most of them 4 px, where the example's strips are 160-200 px tall at the sides)."""
    if not through:
        return frozenset()
    border = border_labels(header.labels, header.classes)
    return frozenset(t >> 1 for p in header.primitives
                     if any(u >> 1 in through for u in p.ring)
                     for t in p.ring if t >> 1 in border)


def grid_cell(t: Tables) -> float:
    """The grid's cell side: the unit, or a quarter of the longest edge a label allows when
    that is longer (compiled grammars allow 4 units, so this is their unit), so that no edge
    fills more than a few cells however the unit and the lengths were edited. A border's
    edges are left out: a frame's sides are as long as the frame, and cells sized for them
    would each hold hundreds of vertices (its few long edges are filed in many cells)."""
    border = {c.name for c in t.vocabulary.classes if c.border}
    longest = max((hi for (_, hi, _, _), cls in zip(t.lengths, t.label_class)
                   if math.isfinite(hi) and cls not in border), default=0.0)
    return max(t.unit, longest / 4)


def unit_vector(degrees: float) -> Point:
    """The direction as a unit vector, exact at multiples of 90° (where sin(pi) would leave
    1e-16 and put the ends of a horizontal edge at different heights)."""
    q, r = divmod(degrees, 90.0)
    if r == 0.0:
        return ((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))[int(q) % 4]
    ang = math.radians(degrees)
    return (math.cos(ang), math.sin(ang))
