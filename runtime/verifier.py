"""Is a drawing locally similar to its example (paper §3.1)? `ggrun check` and its checks.

A drawing passes when
- every edge fits one of the example's edge labels (faces, class, direction within the angle
  tolerance), and every vertex's ring of half-edges is one of the example's primitives;
- all edges of one label point in one exact direction (to float noise);
- no two edges cross, touch or overlap, and no two vertices coincide;
- every length respects its class (min/max, fixed, tile multiples, rigid exact vector), but
  for a chord of the space (frame.spans_the_space), which has no maximum;
- the faces, found geometrically, agree with the labels the edges state on their sides: a
  component drawn inside a face must have that face's label around it.

The verifier is deliberately independent of the generator: it shares no geometry code with it,
so a bug there cannot hide itself here.
"""

from __future__ import annotations

import sys
from collections import Counter, defaultdict
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
import shapely
from scipy.spatial import cKDTree

from grammar_lang import boundary as bd
from grammar_lang.diagnostics import Span, did_you_mean, error
from grammar_lang.example import Example
from grammar_lang.frame import spans_the_space
from grammar_lang.rules import Grammar, Header
from grammar_lang.source import Decoration
from grammar_lang.vocabulary import EdgeLabel, Primitive, Vocabular, Vocabulary

from .output.drawing import Drawing, load_drawing
from .geometry.faces import UNBOUNDED, compute_faces

# "One exact direction": directions agree to this many degrees, plus what rounding the
# coordinates to 6 decimals (as gg-drawing/1 files do) can move an edge's end.
DIRECTION_EPS_DEG = 1e-6
COORD_SLACK = 2e-6
# Segments meeting at a smaller angle (its sine) run along each other: an overlap, whatever
# rounding says about where exactly they meet.
PARALLEL_SINE = 1e-9
# Coordinates beyond this are refused: float spacing there exceeds the precision checked.
MAX_COORD = 1e12
# Vertices closer than this fraction of the drawing's extent are one point.
COINCIDE_FRACTION = 1e-9

KINDS = ("label", "ring", "direction", "length", "degenerate", "coincident", "crossing",
         "touch", "overlap", "face", "nesting")


@dataclass(frozen=True)
class Reference(Vocabular):
    """What a drawing is checked against: the vocabulary of an `Example` or a `.ggr` `Header`
    (its unit at least 1 where none is given, every class resolved against it), the angle
    tolerance and the decorations."""

    name: str
    vocabulary: Vocabulary
    angle_tolerance: float
    decorations: tuple[Decoration, ...] = ()


def as_reference(obj: Example | Header | Grammar | Reference) -> Reference:
    """The reference an example, a grammar's header or a grammar is checked against."""
    if isinstance(obj, Reference):
        return obj
    if isinstance(obj, Grammar):
        obj = obj.header
    name = obj.name if isinstance(obj, Example) else obj.source
    unit = float(obj.unit or 1.0)
    classes = tuple(c if c.min_length is not None and c.max_length is not None
                    else c.resolved(unit) for c in obj.classes)
    vocabulary = replace(obj.vocabulary, classes=classes, unit=unit)
    return Reference(str(name or ""), vocabulary, float(obj.options.angle_tolerance),
                     tuple(obj.decorations))


@dataclass(frozen=True)
class Failure:
    """One reason a drawing is not locally similar to its example."""

    kind: str                              # one of KINDS
    message: str
    vertices: tuple[int, ...] = ()         # vertex ids, as in the drawing
    edges: tuple[int, ...] = ()            # edge indices into the drawing's edge list
    at: tuple[float, float] | None = None  # where to look, in the drawing's coordinates
    expected: str | None = None
    found: str | None = None

    def render(self) -> str:
        lines = [f"{self.kind}: {self.message}"]
        if self.at is not None:
            lines.append(f"  at {_pt(self.at)}")
        if self.expected is not None:
            lines.append(f"  expected: {self.expected}")
        if self.found is not None:
            lines.append(f"  found:    {self.found}")
        return "\n".join(lines)


def _pt(p) -> str:
    return f"({_num(p[0])}, {_num(p[1])})"


def _num(x: float) -> str:
    text = f"{x:.6f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def _deg(a: float) -> str:
    return f"{_num(a)}°"


def _wrap(a):
    """Degrees into [-180, 180), for scalars and arrays."""
    return (a + 180.0) % 360.0 - 180.0


def _some(items, limit: int = 8) -> str:
    items = list(items)
    head = ", ".join(str(i) for i in items[:limit])
    return head + (f" (+{len(items) - limit} more)" if len(items) > limit else "")


class _Index:
    """Lookups into the reference, built once per check."""

    def __init__(self, ref: Reference):
        self.ref = ref
        self.by_name = {l.name: i for i, l in enumerate(ref.labels)}
        self.by_sides: dict[tuple[str, str, str], list[tuple[int, bool]]] = defaultdict(list)
        for i, l in enumerate(ref.labels):
            self.by_sides[(l.cls, l.left, l.right)].append((i, False))
            self.by_sides[(l.cls, l.right, l.left)].append((i, True))
        # Labels alike in every respect (rigid edges give one label each) are one token here.
        first: dict[tuple, int] = {}
        canon = [first.setdefault((l.angle, l.left, l.right, l.cls, l.length), i)
                 for i, l in enumerate(ref.labels)]
        # Per token (2 per label): its canonical token, and a sort key by direction.
        self.canon = [bd.half(canon[t >> 1], bool(t & 1)) for t in range(2 * len(canon))]
        self.order = [(l.direction(bar), bd.half(i, bar)) for i, l in enumerate(ref.labels)
                      for bar in (False, True)]
        self.canon_arr = np.array(self.canon, dtype=np.int64)
        self.rank = np.empty(len(self.order), dtype=np.int64)
        by_direction = sorted(range(len(self.order)), key=self.order.__getitem__)
        self.rank[by_direction] = np.arange(len(self.order))
        self.rings: dict[bd.Tokens, int] = {}
        for k, p in enumerate(ref.primitives):
            self.rings.setdefault(self.canon_ring(p.ring), k)
        self.classes = {c.name: c for c in ref.classes}
        self.faces = set(ref.face_labels) | {ref.exterior}

    def canon_ring(self, ring) -> bd.Tokens:
        return tuple(sorted((self.canon[t] for t in ring), key=self.order.__getitem__))

    def nearest_primitive(self, ring: bd.Tokens) -> tuple[Primitive, list[int], list[int]]:
        """The primitive whose ring differs least from `ring`: (it, missing, unexpected)."""
        have = Counter(ring)
        best = None
        for k, p in enumerate(self.ref.primitives):
            want = Counter(self.canon_ring(p.ring))
            missing, extra = want - have, have - want
            score = (sum(missing.values()) + sum(extra.values()), k)
            if best is None or score < best[0]:
                best = (score, p, sorted(missing.elements()), sorted(extra.elements()))
        return best[1], best[2], best[3]


@dataclass
class _Geometry:
    ids: list[int]
    xy: np.ndarray        # (n, 2)
    ends: np.ndarray      # (m, 2) vertex indices
    angle: np.ndarray     # (m,) direction of u→v in degrees
    length: np.ndarray    # (m,)


def _geometry(drawing: Drawing) -> _Geometry:
    ids = [v.id for v in drawing.vertices]
    index = {v: i for i, v in enumerate(ids)}
    xy = np.array([(v.x, v.y) for v in drawing.vertices], dtype=float).reshape(-1, 2)
    ends = np.array([(index[e.u], index[e.v]) for e in drawing.edges], dtype=np.int64).reshape(-1, 2)
    with np.errstate(invalid="ignore", over="ignore"):
        d = xy[ends[:, 1]] - xy[ends[:, 0]]
    return _Geometry(ids, xy, ends, np.degrees(np.arctan2(d[:, 1], d[:, 0])), np.hypot(d[:, 0], d[:, 1]))


def check_drawing(reference, drawing: Drawing, tolerance: float | None = None) -> list[Failure]:
    """Every way `drawing` fails to be locally similar to `reference`; [] when it passes.

    `reference` is an `Example`, a `Header`, a `Grammar` or a `Reference`. `tolerance`
    overrides the example's angle tolerance (degrees) for matching edges to labels.
    """
    ref = as_reference(reference)
    ix = _Index(ref)
    tol = ref.angle_tolerance if tolerance is None else float(tolerance)
    g = _geometry(drawing)
    ctx = _Context(ref, ix, drawing, g, tol)
    with np.errstate(invalid="ignore"):
        bad = np.flatnonzero(~(np.abs(g.xy) <= MAX_COORD).all(axis=1))
    if len(bad):
        # Nothing geometric can be said about points that are nowhere (NaN, infinity), or so
        # far out that float spacing is coarser than the checks' precision.
        for i in bad.tolist():
            ctx.fail("degenerate", f"vertex {g.ids[i]} has a coordinate that is not a number "
                     f"within ±{MAX_COORD:g}", (g.ids[i],), found=f"({g.xy[i, 0]}, {g.xy[i, 1]})")
        return ctx.failures
    ctx.degenerate()
    ctx.assign_labels()
    ctx.rings()
    ctx.directions()
    ctx.lengths()
    if ctx.geometry() and not ctx.bad_edges:
        ctx.face_labels()
    return ctx.failures


def vertex_primitives(reference, drawing: Drawing) -> dict[int, int]:
    """Vertex id → index of the primitive its ring matches, for the vertices that match one."""
    ref = as_reference(reference)
    ctx = _Context(ref, _Index(ref), drawing, _geometry(drawing), ref.angle_tolerance)
    ctx.degenerate()
    ctx.assign_labels()
    ctx.rings()
    return ctx.vertex_prim


class _Context:
    def __init__(self, ref: Reference, ix: _Index, drawing: Drawing, g: _Geometry, tol: float):
        self.ref, self.ix, self.d, self.g, self.tol = ref, ix, drawing, g, tol
        self.failures: list[Failure] = []
        self.bad_edges: set[int] = set()                     # degenerate: left out of geometry
        self.assigned: dict[int, tuple[int, bool]] = {}      # edge → (label, u→v walks along a)
        self.vertex_prim: dict[int, int] = {}                # vertex id → matching primitive

    def fail(self, *args, **kw) -> None:
        self.failures.append(Failure(*args, **kw))

    def edge_name(self, e: int) -> str:
        de = self.d.edges[e]
        return f"edge #{e} ({de.u}→{de.v})"

    def vertex_at(self, i: int) -> tuple[float, float]:
        return (float(self.g.xy[i, 0]), float(self.g.xy[i, 1]))

    def mid(self, e: int) -> tuple[float, float]:
        a, b = self.g.xy[self.g.ends[e]]
        return (float(a[0] + b[0]) / 2, float(a[1] + b[1]) / 2)

    # --- edges and their labels -------------------------------------------------------------
    def degenerate(self) -> None:
        ends = self.g.ends
        loops = ends[:, 0] == ends[:, 1]
        for e in np.flatnonzero(loops | (self.g.length <= COORD_SLACK)).tolist():
            u, v = (int(x) for x in ends[e])
            self.bad_edges.add(e)
            de = self.d.edges[e]
            if u == v:
                self.fail("degenerate", f"{self.edge_name(e)} is a loop from a vertex to itself",
                          (de.u,), (e,), self.vertex_at(u))
            else:
                self.fail("degenerate", f"{self.edge_name(e)} has zero length",
                          (de.u, de.v), (e,), self.vertex_at(u))

    def assign_labels(self) -> None:
        """Give each edge its label: among the labels with its faces and class (and its stated
        label name, if any), the nearest in direction; for rigid labels also in length."""
        ref, ix = self.ref, self.ix
        groups: dict[tuple, list[int]] = defaultdict(list)
        for e, de in enumerate(self.d.edges):
            if e not in self.bad_edges:
                groups[(de.cls, de.left, de.right, de.label)].append(e)
        for (cls, left, right, name), es in groups.items():
            problem = self._unknown_names(cls, left, right, name)
            if problem:
                for e in es:
                    self._label_failure(e, *problem)
                continue
            cands = ix.by_sides.get((cls, left, right), [])
            if name is not None:
                cands = [c for c in cands if c[0] == ix.by_name[name]]
            es_arr = np.array(es)
            theta = self.g.angle[es_arr]
            length = self.g.length[es_arr]
            best_dev = np.full(len(es), np.inf)
            best_key = np.full(len(es), np.inf)
            best_fit = np.full(len(es), np.inf)
            best = np.full(len(es), -1)
            # In label order, so ties go to the first label, as (dev, fit, label) would.
            for k, (li, bar) in enumerate(cands):
                lab = ref.labels[li]
                dev = np.abs(_wrap(theta - lab.direction(bar)))
                key = np.round(dev, 6)
                fit = np.abs(length - lab.length) if lab.length is not None else np.zeros(len(es))
                better = (key < best_key) | ((key == best_key) & (fit < best_fit))
                best_dev = np.where(better, dev, best_dev)
                best_key = np.where(better, key, best_key)
                best_fit = np.where(better, fit, best_fit)
                best = np.where(better, k, best)
            for e, k, dev in zip(es, best.tolist(), best_dev.tolist()):
                if k >= 0 and dev <= self.tol:
                    li, bar = cands[k]
                    self.assigned[e] = (li, not bar)
                else:
                    self._misfit(e, cands, cands[k] if k >= 0 else None, dev)

    def _unknown_names(self, cls, left, right, name):
        """(message, expected) when an edge names a face, class or label the example lacks."""
        ix = self.ix
        for f in (left, right):
            if f not in ix.faces:
                hint = did_you_mean(f, ix.faces)
                return (f"face label '{f}' is not one of the example's"
                        + (f" ({hint})" if hint else ""), ", ".join(sorted(ix.faces)))
        if cls not in ix.classes:
            hint = did_you_mean(cls, ix.classes)
            return (f"edge class '{cls}' is not one of the example's"
                    + (f" ({hint})" if hint else ""), ", ".join(sorted(ix.classes)))
        if name is not None and name not in ix.by_name:
            hint = did_you_mean(name, ix.by_name)
            return (f"no edge label '{name}' in the example" + (f" ({hint})" if hint else ""),
                    ", ".join(self.ref.label_names))
        return None

    def _found(self, e: int) -> str:
        de = self.d.edges[e]
        return (f"direction {_deg(float(self.g.angle[e]))}, faces {de.left}|{de.right}, "
                f"class {de.cls}" + (f", label {de.label}" if de.label is not None else ""))

    def _label_failure(self, e: int, message: str, expected: str) -> None:
        self.fail("label", f"{self.edge_name(e)}: {message}", edges=(e,), at=self.mid(e),
                  expected=expected, found=self._found(e))

    def _misfit(self, e: int, cands, best, dev: float) -> None:
        """An edge whose faces and class are known but that fits no label."""
        ref, de = self.ref, self.d.edges[e]
        if de.label is not None:
            lab = ref.labels[self.ix.by_name[de.label]]
            if not cands:
                self._label_failure(
                    e, f"its faces {de.left}|{de.right} and class {de.cls} do not fit its label "
                    f"'{de.label}'", f"faces {lab.left}|{lab.right} (or {lab.right}|{lab.left} "
                    f"walking against it), class {lab.cls}")
            else:
                self._label_failure(
                    e, f"it does not fit its label '{de.label}' within {_deg(self.tol)}",
                    f"label {lab.name}: direction {_deg(lab.angle)} with faces "
                    f"{lab.left}|{lab.right}, or {_deg(lab.direction(True))} with faces "
                    f"{lab.right}|{lab.left}, class {lab.cls}")
        elif best is None:
            self._label_failure(
                e, f"no edge label of the example has faces {de.left}|{de.right} and class "
                f"{de.cls}", "one of: " + "; ".join(
                    f"{l.left}|{l.right} class {l.cls}" for l in _unique_sides(ref)))
        else:
            lab = ref.labels[best[0]]
            self._label_failure(
                e, f"it points {_deg(dev)} away from the nearest edge label with its faces, "
                f"more than the tolerance {_deg(self.tol)}",
                f"label {lab.name}: direction {_deg(lab.direction(best[1]))} with faces "
                f"{de.left}|{de.right}")

    # --- vertices ---------------------------------------------------------------------------
    def rings(self) -> None:
        ix, g = self.ix, self.g
        n = len(g.ids)
        es = np.array(sorted(self.assigned), dtype=np.int64)
        tok = np.array([bd.half(li, not fwd) for li, fwd in (self.assigned[e] for e in es.tolist())],
                       dtype=np.int64)
        blocked = np.zeros(n, dtype=bool)
        unassigned = np.setdiff1d(np.arange(len(self.d.edges)), es)
        blocked[g.ends[unassigned].ravel()] = True   # an edge there fits no label: reported
        # Half-edges: the token at u points along the edge, its opposite at v back along it.
        hv = np.concatenate([g.ends[es, 0], g.ends[es, 1]])
        ht = np.concatenate([tok, tok ^ 1])
        ha = np.concatenate([g.angle[es], _wrap(g.angle[es] + 180.0)])
        he = np.concatenate([es, es])
        order = np.lexsort((ix.rank[ht] if len(ht) else ht, hv))
        hv, ht, ha, he = hv[order], ht[order], ha[order], he[order]
        hs = np.concatenate([np.ones(len(es), bool), np.zeros(len(es), bool)])[order]
        count = np.bincount(hv, minlength=n)
        start = np.concatenate([[0], np.cumsum(count)[:-1]])
        # Typed order must also be the geometric order: the angle steps sum to one turn.
        nxt = np.arange(len(hv)) + 1
        full = count > 0
        nxt[(start + count - 1)[full]] = start[full]
        steps = (ha[nxt] - ha) % 360.0 if len(hv) else ha
        turn = np.add.reduceat(steps, start[full]) if len(hv) else np.zeros(0)
        in_order = np.ones(n, dtype=bool)
        in_order[full] = (count[full] <= 2) | (np.abs(turn - 360.0) < 1e-6)
        canon = ix.canon_arr[ht].tolist()
        for i in range(n):
            if blocked[i]:
                continue
            s0, s1 = int(start[i]), int(start[i] + count[i])
            ring = tuple(canon[s0:s1])
            k = ix.rings.get(ring)
            if k is not None and in_order[i]:
                self.vertex_prim[g.ids[i]] = k
                continue
            halves = list(zip(ht[s0:s1].tolist(), ha[s0:s1].tolist(), he[s0:s1].tolist(),
                              hs[s0:s1].tolist()))
            self._ring_failure(i, ring, k, halves)

    def _ring_failure(self, i: int, ring, k, halves) -> None:
        vid, ix = self.g.ids[i], self.ix
        found = self._describe(halves)
        edges = tuple(h[2] for h in halves)
        if k is not None:
            prim = self.ref.primitives[k]
            self.fail("ring", f"the half-edges around vertex {vid} are not in the order of "
                      f"primitive {prim.name}", (vid,), edges, self.vertex_at(i),
                      expected=self.ref.format(prim.boundary), found=found)
            return
        if not self.ref.primitives:
            self.fail("ring", f"vertex {vid}: the example has no primitives", (vid,),
                      at=self.vertex_at(i), found=found)
            return
        prim, missing, extra = ix.nearest_primitive(ring)
        diff = []
        if missing:
            diff.append("missing " + " ".join(self.ref.format((t,)) for t in missing))
        if extra:
            diff.append("unexpected " + " ".join(self.ref.format((t,)) for t in extra))
        what = "has no edges" if not halves else "matches no primitive of the example"
        self.fail("ring", f"vertex {vid} {what}; nearest is {prim.name} ({', '.join(diff)})",
                  (vid,), edges, self.vertex_at(i),
                  expected=f"{prim.name}: {self.ref.format(prim.boundary)}", found=found)

    def _describe(self, halves) -> str:
        if not halves:
            return "no half-edges"
        ring = self.ref.format(tuple(h[0] for h in halves) + (bd.UP,))
        parts = []
        for t, angle, e, at_start in halves:
            de = self.d.edges[e]
            left, right = (de.left, de.right) if at_start else (de.right, de.left)
            parts.append(f"{self.ref.format((t,))} {_deg(angle)} {left}|{right}")
        return f"{ring}  [{'; '.join(parts)}]"

    # --- exact directions -------------------------------------------------------------------
    def directions(self) -> None:
        by_label: dict[int, list[int]] = defaultdict(list)
        for e in sorted(self.assigned):
            by_label[self.assigned[e][0]].append(e)
        for li, es in sorted(by_label.items()):
            lab = self.ref.labels[li]
            along = np.array([self.g.angle[e] if self.assigned[e][1] else self.g.angle[e] + 180.0
                              for e in es])
            dev = _wrap(along - lab.angle)
            eps = DIRECTION_EPS_DEG + np.degrees(COORD_SLACK / self.g.length[es])
            groups = _direction_groups(dev, eps)
            if len(groups) == 1:
                continue
            groups.sort(key=lambda gr: (-len(gr), abs(float(np.mean(dev[gr]))), gr[0]))
            main = groups[0]
            off = sorted(es[k] for gr in groups[1:] for k in gr)
            found = "; ".join(
                f"{_deg(lab.angle + float(np.mean(dev[gr])))}: "
                f"{_edges(es[k] for k in gr)}" for gr in groups)
            self.fail("direction", f"the {len(es)} edges of label {lab.name} point in "
                      f"{len(groups)} directions, not one", edges=tuple(off),
                      at=self.mid(off[0]),
                      expected=f"all at {_deg(lab.angle + float(np.mean(dev[main])))} "
                               f"(as {len(main)} of them)", found=found)

    # --- lengths ----------------------------------------------------------------------------
    def lengths(self) -> None:
        classes = self.ix.classes
        border = {c.name for c in classes.values() if c.border}
        on_border = {x for de in self.d.edges if de.cls in border for x in (de.u, de.v)}
        for e, de in enumerate(self.d.edges):
            if e in self.bad_edges or de.cls not in classes:
                continue
            c = classes[de.cls]
            chord = spans_the_space(de.cls in border, de.u in on_border, de.v in on_border)
            L = float(self.g.length[e])
            slack = COORD_SLACK + 1e-9 * L
            problem = expected = None
            label = self.ref.labels[self.assigned[e][0]] if e in self.assigned else None
            if c.rigid and label is not None and label.length is not None:
                if abs(L - label.length) > slack:
                    problem, expected = "is not its rigid length", f"exactly {_num(label.length)}"
            elif c.fixed is not None:
                if abs(L - c.fixed) > slack:
                    problem, expected = "is not its class's fixed length", f"exactly {_num(c.fixed)}"
            else:
                if c.tile:
                    k = round(L / c.tile)
                    if k < 1 or abs(L - k * c.tile) > slack:
                        problem = "is not a whole multiple of its class's tile"
                        expected = f"a multiple of {_num(c.tile)}"
                if problem is None and c.min_length is not None and L < c.min_length - slack:
                    problem, expected = "is shorter than its class allows", f"at least {_num(c.min_length)}"
                if problem is None and c.max_length is not None and L > c.max_length + slack \
                        and not chord:
                    problem, expected = "is longer than its class allows", f"at most {_num(c.max_length)}"
            if problem:
                self.fail("length", f"{self.edge_name(e)} (class {de.cls}) {problem}",
                          (de.u, de.v), (e,), self.mid(e), expected=expected, found=_num(L))

    # --- crossings, touches, overlaps, coincident vertices ----------------------------------
    def geometry(self) -> bool:
        """Report geometric conflicts; whether there were none (faces are then well defined).

        Vertices and edges closer than `near` count as touching: a file rounded to 6 decimals
        cannot tell them apart from touching ones anyway.
        """
        before = len(self.failures)
        g = self.g
        n = len(g.ids)
        extent = float(np.ptp(g.xy, axis=0).max()) if n else 0.0
        near = max(COORD_SLACK, COINCIDE_FRACTION * extent)
        if n >= 2:
            for i, j in sorted(cKDTree(g.xy).query_pairs(near)):
                self.fail("coincident", f"vertices {g.ids[i]} and {g.ids[j]} are at one point",
                          (g.ids[i], g.ids[j]), at=self.vertex_at(i))
        good = np.array([e for e in range(len(self.d.edges)) if e not in self.bad_edges],
                        dtype=np.int64)
        if len(good):
            ends = g.ends[good]
            segs = shapely.linestrings(np.stack([g.xy[ends[:, 0]], g.xy[ends[:, 1]]], axis=1))
            tree = shapely.STRtree(segs)
            a, b = tree.query(segs, predicate="dwithin", distance=near)
            keep = a < b
            self._pairs(good, ends, segs, a[keep], b[keep], near)
            degree = np.bincount(ends.ravel(), minlength=n)
            lonely = np.flatnonzero(degree == 0)
            if len(lonely):
                pi, si = tree.query(shapely.points(g.xy[lonely]), predicate="dwithin",
                                    distance=near)
                for p, s in sorted(zip(pi.tolist(), si.tolist())):
                    e = int(good[s])
                    self.fail("touch", f"vertex {g.ids[lonely[p]]} lies on {self.edge_name(e)}",
                              (g.ids[lonely[p]],), (e,), self.vertex_at(lonely[p]))
        return len(self.failures) == before

    def _pairs(self, good, ends, segs, a, b, near) -> None:
        ea, eb = ends[a], ends[b]
        same = ((ea[:, :, None] == eb[:, None, :]).sum(axis=(1, 2)))
        xy = self.g.xy
        da = xy[ea[:, 1]] - xy[ea[:, 0]]
        db = xy[eb[:, 1]] - xy[eb[:, 0]]
        sine = np.abs(da[:, 0] * db[:, 1] - da[:, 1] * db[:, 0]) / (
            np.hypot(*da.T) * np.hypot(*db.T))
        # Sharing one end: fine unless they leave it in the same direction.
        one = np.flatnonzero(same == 1)
        w = np.where((ea[one, 0] == eb[one, 0]) | (ea[one, 0] == eb[one, 1]), ea[one, 0], ea[one, 1])
        oa = np.where(ea[one, 0] == w, ea[one, 1], ea[one, 0])
        ob = np.where(eb[one, 0] == w, eb[one, 1], eb[one, 0])
        dot = ((xy[oa] - xy[w]) * (xy[ob] - xy[w])).sum(axis=1)
        bad = one[(sine[one] <= PARALLEL_SINE) & (dot > 0)]
        problems = sorted(set(bad.tolist()) | set(np.flatnonzero(same != 1).tolist()),
                          key=lambda k: (int(good[a[k]]), int(good[b[k]])))
        for k in problems:
            e, f = int(good[a[k]]), int(good[b[k]])
            vs = tuple(dict.fromkeys(self.g.ids[int(x)] for x in (*ea[k], *eb[k])))
            if same[k] >= 1 or sine[k] <= PARALLEL_SINE:
                self.fail("overlap", f"{self.edge_name(e)} and {self.edge_name(f)} overlap",
                          vs, (e, f), self.mid(e))
                continue
            on_b = [int(x) for x in ea[k] if shapely.distance(shapely.Point(xy[x]), segs[b[k]]) <= near]
            on_a = [int(x) for x in eb[k] if shapely.distance(shapely.Point(xy[x]), segs[a[k]]) <= near]
            if on_a and on_b:
                continue   # an end of each at one point: reported as coincident vertices
            if on_a or on_b:
                v, other = (on_a[0], e) if on_a else (on_b[0], f)
                self.fail("touch", f"vertex {self.g.ids[v]} lies on {self.edge_name(other)} "
                          f"without being one of its ends", vs, (e, f), self.vertex_at(v))
                continue
            p = shapely.intersection(segs[a[k]], segs[b[k]])
            self.fail("crossing", f"{self.edge_name(e)} and {self.edge_name(f)} cross",
                      vs, (e, f), (float(p.x), float(p.y)))

    # --- faces ------------------------------------------------------------------------------
    def face_labels(self) -> None:
        sides = _FaceSides(self.g, self.d.edges)
        for f, face in enumerate(sides.faces.faces):
            label = self.ref.exterior if f == UNBOUNDED else self._outer_label(sides, f, face.outer)
            for hole in face.holes:
                self._hole_label(sides, f, label, hole)

    def _outer_label(self, sides: _FaceSides, f: int, outer: int) -> str:
        """The label of bounded face f, from its outer cycle; a failure when that cycle's sides
        disagree (then the label most of them give)."""
        cyc = sides.faces.cycles[outer]
        label = sides.uniform(cyc)
        if label is not None:
            return label
        groups = sides.labels_on(cyc)
        # Which side is wrong cannot be told from the face alone: name them all.
        label = max(groups, key=lambda k: (len(groups[k]), k == self.ref.exterior))
        involved = tuple(sorted({h >> 1 for h in cyc}))
        self.fail("face", f"{sides.where(f)} has different labels on its sides",
                  edges=involved, at=self.mid(involved[0]),
                  expected="one label on every side facing the face", found=_listing(groups))
        return label

    def _hole_label(self, sides: _FaceSides, f: int, label: str, hole: int) -> None:
        """A component drawn inside face f (labelled `label`) must give its outside that label."""
        cyc = sides.faces.cycles[hole]
        outside = sides.uniform(cyc)
        if outside == label:
            return
        root = int(self.g.ends[cyc[0] >> 1, 0])
        vs = sides.members(root)
        involved = tuple(sorted({h >> 1 for h in cyc}))
        if outside is not None:
            self.fail("nesting", f"the component of vertices {_some(vs)} is drawn "
                      f"inside {sides.where(f)}, which is labelled '{label}', but its outside "
                      f"is labelled '{outside}'", tuple(vs), involved,
                      self.vertex_at(root), expected=f"'{label}' around it",
                      found=f"'{outside}'")
            return
        groups = sides.labels_on(cyc)
        if f == UNBOUNDED:
            wrong = tuple(e for k, es in groups.items() if k != label for e in es)
            self.fail("face", f"the outside of the component of vertices {_some(vs)} "
                      f"is {sides.where(f)}, but some edges give it another label", tuple(vs),
                      wrong, self.mid(wrong[0]), expected=f"'{label}' all around",
                      found=_listing(groups))
        else:
            self.fail("face", f"the outside of the component of vertices {_some(vs)} "
                      f"has different labels, inside {sides.where(f)} labelled '{label}'",
                      tuple(vs), involved, self.mid(involved[0]),
                      expected=f"'{label}' all around", found=_listing(groups))


class _FaceSides:
    """The faces of a drawing, with the label each half-edge gives the face on its left."""

    def __init__(self, g, edges):
        self.g = g
        self.faces = compute_faces(g.xy, g.ends)
        self.left = [edges[h >> 1].right if h & 1 else edges[h >> 1].left
                     for h in range(2 * len(edges))]

    def uniform(self, cycle) -> str | None:
        """The one label that every half-edge of the cycle gives, or None."""
        first = self.left[cycle[0]]
        return first if all(self.left[h] == first for h in cycle) else None

    def labels_on(self, cycle) -> dict[str, list[int]]:
        """Label → the edges of the cycle that give it."""
        out: dict[str, set[int]] = defaultdict(set)
        for h in cycle:
            out[self.left[h]].add(h >> 1)
        return {k: sorted(v) for k, v in sorted(out.items())}

    def where(self, f: int) -> str:
        if f == UNBOUNDED:
            return "the unbounded face (outside everything)"
        outer = self.faces.cycles[self.faces.faces[f].outer]
        return f"the face bounded by {_edges(sorted({h >> 1 for h in outer}))}"

    def members(self, root: int) -> list[int]:
        """The drawing's ids of the vertices in root's connected component."""
        comp = self.faces.component
        return [self.g.ids[v] for v in np.flatnonzero(comp == comp[root])]


def _listing(groups) -> str:
    return "; ".join(f"{k} on {_edges(es)}" for k, es in groups.items())


def _edges(es) -> str:
    es = list(es)
    return ("edge " if len(es) == 1 else "edges ") + _some(f"#{e}" for e in es)


def _unique_sides(ref: Reference) -> list[EdgeLabel]:
    seen, out = set(), []
    for l in ref.labels:
        key = (l.left, l.right, l.cls)
        if key not in seen:
            seen.add(key)
            out.append(l)
    return out


def _direction_groups(dev: np.ndarray, eps: np.ndarray) -> list[list[int]]:
    """Indices grouped by equal direction; a group is anchored at its smallest deviation, so
    slow drift cannot chain many slightly different directions into one."""
    order = np.argsort(dev, kind="stable")
    groups: list[list[int]] = []
    anchor = None
    for k in order.tolist():
        if anchor is None or dev[k] - dev[anchor] > eps[k] + eps[anchor]:
            groups.append([k])
            anchor = k
        else:
            groups[-1].append(k)
    return groups


# --- the command ----------------------------------------------------------------------------

def load_reference(path: str | Path) -> Reference:
    """The example (.gg, .svg, .json) or compiled grammar (.ggr) a drawing is checked against."""
    p = Path(path)
    if p.suffix.lower() == ".ggr":
        from grammar_lang.ggr_parser import load_ggr
        return as_reference(load_ggr(p))
    if p.suffix.lower() not in (".gg", ".svg", ".json"):
        raise error(f"don't know how to read '{p.name}' as an example", Span(str(p)),
                    "give the example (.gg, .svg) or the grammar compiled from it (.ggr)")
    from grammar_lang.loader import load_example
    return as_reference(load_example(p))


def check_command(example: str, drawing: str, tolerance: float | None = None,
                  limit: int = 50, out=None) -> int:
    """`ggrun check`: 0 when the drawing passes, 1 when it fails; user errors raise."""
    out = out or sys.stdout
    ref = load_reference(example)
    d = load_drawing(drawing)
    if tolerance is not None and not (0 <= tolerance < 90):
        raise error(f"--tolerance {tolerance} is out of range", None,
                    "give an angle in degrees, at least 0 and below 90")
    failures = check_drawing(ref, d, tolerance)
    if not failures:
        out.write(f"ok: {len(d.vertices)} vertices, {len(d.edges)} edges\n")
        return 0
    shown = failures if limit <= 0 else failures[:limit]
    for f in shown:
        out.write(f.render() + "\n")
    kinds = Counter(f.kind for f in failures)
    summary = ", ".join(f"{kinds[k]} {k}" for k in KINDS if kinds[k])
    more = f" ({len(failures) - len(shown)} not shown; --all shows them)" if len(shown) < len(failures) else ""
    out.write(f"failed: {len(failures)} problem(s) in {len(d.vertices)} vertices, "
              f"{len(d.edges)} edges: {summary}{more}\n")
    return 1
