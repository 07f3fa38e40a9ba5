"""Positions for a proposed change: Algorithm 3's inner loops (paper §6.2–6.3).

Every edge's direction is fixed by its label, so for the free vertices F and every edge e = uv
touching them, `p_v − p_u − s_e d_e = 0` with the length s_e unknown: a linear system A x = b
over positions and lengths, the fixed vertices moving to b. Its solutions are x̂ + K λ.

A sample is drawn by projecting a random target onto that affine space: target lengths are
drawn around the label's typical length in the example, within its class's range (or kept, for
edges that already exist), so that a structure made in one move keeps its parts' proportions
and its cycles close with every length positive; target positions are the place the change
happens (or kept, for old vertices; a new free-standing component gets a fresh place for every
sample); the projection is a weighted least squares step, so old vertices move least and new
ones most. Projecting a random point onto the space samples it as the null-space form does,
without forming K. For a change the caller wants (a part under its share), a sample whose
lengths leave their range is brought back into it where it can be (`repair`: the point of the
system nearest the sample with the worst lengths pinned in range, one at a time, its tiles
pinned at whole multiples). Samples whose lengths still break their class (min/max, fixed, tile
multiples, rigid), whose edges cross or touch others, or whose vertices coincide are rejected:
J samples per system. A sample that crosses or touches old parts makes the next one SHRINK
times smaller (target lengths and scatter), so that a change squeezed between old vertices
finds room; any other failure (say, an edge of a triangle below its class's minimum) makes it
larger again, up to the local scale; when that size turns back (crowded, then too short), the
part has no room and the round ends. When the system is inconsistent (over-constrained), fixes
some length outside its class whatever the sample, or a round's samples fail, more old vertices
are freed: those nearest the edge whose length failed, else one next to a free one: I rounds
(fewer when the caller, asked through `go_on` after the first, says the rest rarely pay). New
edges' drawn lengths are stiffer than the old drawing (DRAWN_LENGTH), so that freed old
vertices give way to a new part instead of squashing it.

Only the changed neighbourhood enters the system and the spatial grid answers the crossing
tests, so a step's cost does not grow with the drawing.

The system and its factorisation are in system.py, a round's constants in rounds.py, which
old vertices a round frees in freeing.py, and a sample's planarity tests in planarity.py.
"""

from __future__ import annotations

import math
import statistics
from dataclasses import dataclass
from typing import Callable, Iterator

import numpy as np

from grammar_lang.algorithms.components import DisjointSet
from grammar_lang.frame import spans_the_space

from .change import Change, HostView
from .freeing import Freeing
from .planarity import Planarity
from .rejections import Rejection
from .rounds import Round
from .slides import Slide
from .spatial import Point
from .system import (LOOSE_POS, NEW_POS, OLD_POS, Factor, SystemCache, factorise, repair,
                     right_hand_side, slid_pos)

I_ROUNDS, J_SAMPLES = 5, 10
# A round stops repairing after this many samples in a row it could not repair: what fails
# is mostly the round's system, not its sample (no room while only these vertices move). On
# the castle at its N, 281 of its 282 repairs come before such a pair, and the village's
# 7 of 7, for a fifth of the repairs tried (10,491 → 2,330; 19,057 → 3,817).
REPAIR_TRIES = 2
SHRINK = 0.75
GROW_MAX = SHRINK ** -6
# In a frame, new parts are drawn at no less than this share of the example's sizes, however
# squeezed their neighbourhood (Solver._local_scale). What squeezes a scene's parts is the
# fitting, not the example: repairs pin a length at its floor (a third of the paper's
# castle's edges lay there), and a part drawn at the squeezed scale of the piece it splits
# squeezes the next one, until towers are poles with no room on top (seed 80: 277 of 472
# failed proposals of a full castle found a top too short). Over seeds 0-9 at the paper's N
# the castle covered 62.2 % of its frame (52.2 % without; more at every seed) with 270.2
# vertices (273.4), in tiers that rise into its upper half; the station 34.2 % and 111.7
# (33.4 %, 113.0), the flowers 84.2 % and 260.3 (83.9 %, 266.2), the village 49.8 % and
# 100.8 (47.1 %, 101.3). At 1.0 the station drew 106.2 vertices (seeds 0-4, 124.2 without),
# at 0.75 the castle covered 59.9 % (66.7 % at 0.9). Not without a frame: a drawing grown by
# size packs denser as it grows, and its parts must shrink with it (at 0.9, h-complex at
# 20,000 vertices drew 8.2 samples a step against 6.1).
LEAST_STRETCH = 0.9
# Failures that a smaller sample may avoid (a part squeezed between old vertices).
CROWDED = (Rejection.CROSSING, Rejection.COINCIDENT, Rejection.CLOSE)
# How far a length may miss its class's range (numerical noise): a ten-millionth of the unit,
# but never more than the verifier's 2e-6 leaves once a drawing's coordinates are rounded to
# 6 decimals (each end moves up to 0.71e-6). At 1e-7 of a 40 px unit (4e-6) a kept edge at
# its floor came out 2.1e-6 short, and the drawing failed its check.
LENGTH_NOISE = 5e-7


@dataclass(frozen=True)
class Placement:
    positions: dict[int, Point]      # new and moved vertices


class Solver(Freeing, Planarity):
    """Placements for one proposed change: I rounds of J samples each (see above)."""

    def __init__(self, host: HostView, change: Change, rng: np.random.Generator,
                 center: Callable[[], Point], I: int = I_ROUNDS, J: int = J_SAMPLES,
                 floating: bool = False, cache: SystemCache | None = None,
                 strict: bool = True, go_on: Callable[[], bool] | None = None,
                 wanted: Callable[[], bool] | None = None):
        self.host, self.change, self.rng = host, change, rng
        # Asked when the first round did not place: whether to go on with the rest (None:
        # always). A generation step's proposal is one of many, and the engine knows how
        # often such rounds place for its move (LateRounds); `went_on` is the answer (None:
        # not asked), so the engine can count what came of it, and knows a proposal it cut
        # short.
        self.go_on, self.went_on = go_on, None
        # Whether the caller's cost wants this change (a part under its share): only then
        # are its samples repaired (see _sample). Asked once, when first needed.
        self.wanted, self._wants = wanted, None
        # Samples drawn, and how many of them came before the rounds after the first.
        self.samples = self.late_from = 0
        self.cache = SystemCache() if cache is None else cache
        # False: only directions and positive lengths are kept; no class ranges, fixed
        # lengths, tiles or crossing tests (the last resort of a figure, see place_side).
        self.strict = strict
        self.center, self.I, self.J = center, I, J
        # Where new vertices are aimed, for the doomed-round test; a floating component's
        # centre varies per sample, but only by a translation, which moves no length.
        self._box_centre = (0.0, 0.0) if floating else center()
        self.new_prim = dict(change.new)
        self.removed = set(change.removed)
        self.aim = self._aims()
        self.scale, self.stretch = self._local_scale()
        # A part placed in a frame with nothing around it may also be drawn larger than the
        # unit: a big module whose cycles close only with long sides (a space station's).
        self.f_max = GROW_MAX if floating and host.frame is not None else 1.0
        # The gap is a scene's (a framed drawing's). Unframed grammars grown by size pack
        # their parts densely, and with it they drew twice the samples per step (h-complex
        # at 5,000 vertices: 9.6 against 4.4).
        self.clearance = host.t.clearance
        self.gap = host.t.gap if host.frame is not None else self.clearance
        self._adjacency: dict[int, list] = {}
        self.failures: dict[Rejection, int] = {}
        self.last_failure = ""
        self.culprits: dict[tuple[int, int], int] = {}
        self.culprit_need: dict[tuple[int, int], tuple[Point, float]] = {}   # direction, need
        # Parts moved as rigid units (slides.py): their anchors are free vertices, and each
        # other member follows its anchor at a fixed offset.
        self.slides: dict[int, Slide] = {}
        self.attached: dict[int, tuple[int, float, float]] = {}     # member → anchor, offset
        self._slide_near: dict[int, tuple[float, list]] = {}       # see _near_slide
        self._slide_sides: dict[int, list[bool]] = {}               # see _crowds
        self._no_slide: set[tuple[int, int]] = set()                # failed edges without one
        self._consts: dict[tuple, tuple[float, float, float]] = {}  # see _constants
        self.blamed: dict[int, int] = {}        # edge label → failed lengths, for messages
        self._label_bounds: dict[int, tuple] = {}       # see _bounds_of
        self.tol = min(1e-7 * host.t.unit, LENGTH_NOISE)
        self.unique = False
        # New edges between two old vertices (a wire replaced): constraints from the start.
        self.bridges = [(a, b) for a, b in change.glue
                        if a[0] not in self.new_prim and b[0] not in self.new_prim]

    def _local_scale(self) -> tuple[float, float]:
        """The typical edge length where the change happens (the edges it removes or cuts),
        the unit when it removes none: new parts are drawn at the scale of what they replace,
        so that in a dense neighbourhood their edges do not reach across their neighbours.
        Second, how stretched that neighbourhood is against the example (the median of its
        edges' lengths over their labels' typical lengths; 1 where none is known), in a frame
        no less than LEAST_STRETCH, unless the change cuts a line across it (`through`): a
        stretch of such a line is the gap between what stands on it, and a part put there is
        drawn to fit it (with the floor there, the village scene's strips kept gaps a house
        wide: 436 vertices against 468 over five seeds)."""
        host = self.host
        typical, through = host.t.typical, host.t.through
        lengths, ratios = [], []
        on_line = False         # whether the change cuts a line across the frame

        def seen(v, w, lab):
            nonlocal on_line
            d = _dist(host.pos[v], host.pos[w])
            lengths.append(d)
            on_line = on_line or lab in through
            if typical and typical[lab] == typical[lab] and lab not in host.side_labels:
                ratios.append(d / typical[lab])

        for v in self.change.removed:
            for i, s in enumerate(host.link[v]):
                if s is not None:
                    seen(v, s[0], host.t.label[host.prim[v]][i])
        for v, i in self.change.cut:
            lab = host.t.label[host.prim[v]][i]
            if lab in host.side_labels:
                continue     # a frame's side is as long as the frame, not a local scale
            seen(v, host.link[v][i][0], lab)
        # statistics.median: the same value as numpy's for a handful of floats, at a tenth of
        # the cost (this runs once per proposal).
        scale = statistics.median(lengths) if lengths else host.t.unit
        stretch = statistics.median(ratios) if ratios else 1.0
        if host.frame is not None and not on_line and stretch < LEAST_STRETCH:
            stretch = LEAST_STRETCH
        return scale, stretch

    def _aims(self) -> dict[int, Point]:
        """Where each new vertex is aimed: beside the old vertices it is glued to, else beside
        those its part of the new side is glued to (so the parts of a spliced side go to their
        own places, near the match, not all to its middle), else the change's centre."""
        host = self.host
        parts = DisjointSet(self.new_prim)
        own: dict[int, list[Point]] = {v: [] for v in self.new_prim}
        for a, b in self.change.glue:
            na, nb = a[0] in self.new_prim, b[0] in self.new_prim
            if na and nb:
                parts.union(a[0], b[0])
            elif na != nb:
                (v, i), old = (a, b[0]) if na else (b, a[0])
                # A structure stood on a frame's side is not aimed at the ends of the stretch
                # it stands on (a corner, maybe): it goes where the change's centre says.
                if old not in host.pinned \
                        and host.t.label[self.new_prim[v]][i] not in host.side_labels:
                    own[v].append(host.pos[old])
        part: dict[int, list[Point]] = {}
        for v in sorted(self.new_prim):
            part.setdefault(parts.find(v), []).extend(own[v])
        aim = {}
        self.glued = frozenset(v for v in self.new_prim if own[v])
        for v in self.new_prim:
            pts = own[v] or part[parts.find(v)]
            if pts:
                aim[v] = (sum(p[0] for p in pts) / len(pts), sum(p[1] for p in pts) / len(pts))
        return aim

    def prim(self, v: int) -> int:
        p = self.new_prim.get(v)
        return self.host.prim[v] if p is None else p

    def adjacency(self, v: int):
        # Kept for the solver's life: the host is back as it was whenever a round is built
        # (a placement that fails its face test is undone before the next one is asked for).
        adj = self._adjacency.get(v)
        if adj is None:
            adj = self._adjacency[v] = self.change.adjacency(self.host, v, self.prim(v))
        return adj

    def _fail(self, why: Rejection) -> None:
        self.failures[why] = self.failures.get(why, 0) + 1
        self.last_failure = why

    def _blame(self, edge, need: float) -> None:
        """Count a failed length against its edge: the next round frees what holds it.
        `need`: how much longer it had to be (negative: shorter)."""
        key = (edge[0], edge[2])
        self.culprits[key] = self.culprits.get(key, 0) + 1
        self.culprit_need[key] = (edge[4], need)
        self.blamed[edge[-1]] = self.blamed.get(edge[-1], 0) + 1

    def placements(self) -> Iterator[Placement]:
        """Candidate placements that pass every local test, at most I·J of them."""
        free = [v for v, _ in self.change.new]
        if not free and not self.bridges:
            yield Placement({})
            return
        for rnd in range(1, self.I + 1):
            rd = self._system(free)
            if rd is None:
                self._fail(Rejection.OVER_CONSTRAINED)
            elif isinstance(rd, Rejection):
                self._fail(rd)
            else:
                yield from self._round_samples(free, rd)
            if rnd == self.I:
                return
            if rnd == 1 and self.go_on is not None:
                # The first round, the new part alone, did not place: whether freeing old
                # vertices pays for this move is the caller's to say (LateRounds).
                self.went_on = self.go_on()
                if not self.went_on:
                    return
                self.late_from = self.samples
            if not self._free_one(free):
                return

    def _round_samples(self, free: list[int], rd: Round):
        """A round's samples (up to J), yielding each that passes; the round ends early when
        the part has no room while only these vertices move."""
        f, last = 1.0, 0        # the way f last moved: −1 smaller, +1 larger
        for _ in range(1 if self.unique else self.J):
            self.samples += 1
            pos = self._sample(free, rd, f)
            if pos is not None:
                yield Placement(pos)
                continue
            g = f * SHRINK if self.last_failure in CROWDED else min(self.f_max, f / SHRINK)
            way = (g > f) - (g < f)
            if way and way == -last:
                # Crowded at one size and too short at the next smaller (or the other way
                # round): the part has no room while only these vertices move. Such a round's
                # further samples rarely pass (h-complex at 20,000 vertices: 16 % of first
                # samples pass, 1-2.5 % from the sixth on), so the next round, which frees
                # more, starts now.
                return
            f, last = g, way or last

    # --- the linear system ------------------------------------------------------------------
    def _edges(self, free: list[int]) -> list[tuple]:
        """The system's edges, each once: (v, slot, w, slot, direction, label)."""
        host, t = self.host, self.host.t
        edges, seen = [], set()       # the slots of the edges listed
        slides, attached = self.slides, self.attached
        for a in free:
            # A slide's edges are those from any of its members to what is not in it.
            slide = slides.get(a) if slides else None
            for v in (a, *slide.offsets) if slide is not None else (a,):
                pv = self.prim(v)
                for i, s in self.adjacency(v):
                    if (v, i) in seen:
                        continue
                    # An edge inside the slide moves with it, as long as it is; but a new
                    # one between two of its vertices (a rule's bridge) must still be
                    # tested: untested, a castle's slid block was joined to its neighbour
                    # by a slope 112 px long where its class allows 89.
                    if slide is not None and (s[0] == a or attached.get(s[0], (None,))[0] == a) \
                            and host.link[v][i] == s:
                        continue
                    seen.add(s)
                    edges.append((v, i, *s, t.direction[pv][i], t.label[pv][i]))
        fs = set(free)
        for (v, i), (w, j) in self.bridges:
            if v not in fs and w not in fs and (v, i) not in seen and (w, j) not in seen:
                pv = host.prim[v]
                edges.append((v, i, w, j, t.direction[pv][i], t.label[pv][i]))
        return edges

    def _system(self, free: list[int]) -> Round | Rejection | None:
        """The round's system and constants; None when it is inconsistent, the reason when
        no sample of it can pass."""
        host, t = self.host, self.host.t
        edges = self._edges(free)
        kept = self._kept(edges)
        idx = {v: k for k, v in enumerate(free)}
        for m, (a, _, _) in self.attached.items():
            idx[m] = idx[a]
        prim, glued, sides = host.prim, self.glued, host.side_labels
        lengths = t.lengths if self.strict else None
        # Built from lists: tuple() of a list is cheaper than of a generator.
        slides = self.slides
        shape = (tuple([(OLD_POS if v not in slides else slid_pos(slides[v])) if v in prim
                        else NEW_POS if v in glued else LOOSE_POS for v in free]),
                 tuple([(idx.get(v, -1), idx.get(w, -1), d,
                         None if lengths is None else lengths[lab][2], lab in sides, not k)
                        for (v, _, w, _, d, lab), k in zip(edges, kept)]))
        fact = self.cache.get(shape)
        if fact is None:
            fact = self.cache.put(shape, factorise(*shape))
        bl = right_hand_side(shape[1], edges, host.pos, self.attached)
        b = np.array(bl)
        res = (b - fact.M.dot(fact.Minv.dot(b))).tolist()
        # As numpy's max(|·|, initial=0): a NaN anywhere makes the test false.
        worst = max(map(abs, res), default=0.0)
        if worst > 1e-7 * t.unit * (1.0 + max(map(abs, bl), default=0.0) / t.unit) \
                and not any(r != r for r in res + bl):
            return None
        # A system with one solution gives the same sample every time: one try is enough.
        self.unique = fact.unique
        if not self.strict:
            return self._round(free, edges, kept, fact, b)
        # Half the castle's rounds fail here: tested before the round's constants are made.
        c = (fact.scale_len * fact.Minv_len.dot(b)).tolist()
        if self._fixed_out(edges, kept, fact, c):
            return Rejection.LENGTH_FIXED
        rd = self._round(free, edges, kept, fact, b)
        # A round with a slide is repaired (_repairing), and the doomed test reads the plain
        # projection, which slides a light part far past what its seams allow.
        return rd if self.slides else self._doomed(rd, fact, c)

    def _fixed_out(self, edges, kept, fact: Factor, c: list) -> bool:
        """Whether a length the system fixes whatever the target (its row of x = R t + c is
        constant) lies outside its class's range: then every sample fails."""
        tol = self.tol
        for e in fact.fixed_idx:
            _, lt, ht = self._constants(edges[e], kept[e])
            if not (c[e] > tol and lt <= c[e] <= ht):
                self._blame(edges[e], _need(c[e], c[e], lt, ht, tol))
                return True
        return False

    def _doomed(self, rd: Round, fact: Factor, c: list):
        """`rd`, or why no sample of it can pass. A length is affine in the target, which
        ranges over a box (positions within 3σ of their centre, lengths within their draw
        range): when a length's range over that box misses its class, no sample can pass
        (`c`: the lengths at a zero target)."""
        tol = self.tol
        mid, half = self._target_box(rd)
        centre = fact.R.dot(mid).tolist()
        spread = fact.absR.dot(half).tolist()
        for e, (ce, sp) in enumerate(zip(centre, spread)):
            ce += c[e]
            top = ce + sp
            if top <= tol or top < rd.lo_tol[e] or ce - sp > rd.hi_tol[e]:
                self._blame(rd.edges[e], _need(ce - sp, top, rd.lo_tol[e], rd.hi_tol[e], tol))
                return Rejection.LENGTH_RANGE
        return rd

    def _target_box(self, rd: Round) -> tuple[np.ndarray, np.ndarray]:
        """Middle and half-width of the box `_targets` draws from (3σ for positions)."""
        mid = rd.targets_at(self._box_centre)
        half = [0.0] * len(mid)
        u = 1.5 * self.scale
        for k in rd.moving:
            half[k] = u
        a = rd.ranges(SHRINK ** (self.J - 1))[0]
        bb = rd.ranges(1.0)[1]
        n = len(rd.base)
        for e, lo, hi in zip(rd.drawn, a, bb):
            mid[n + e] = 0.5 * (lo + hi)
            half[n + e] = 0.5 * (hi - lo)
        return np.array(mid), np.array(half)

    def _draw_centre(self, lab: int) -> float:
        """Around what length a new edge of label `lab` is drawn: its typical length in the
        example, stretched as the neighbourhood is, so that the parts of a structure grown
        in one move keep their proportions (a window's edges do not come out as long as a
        tower's); else the local scale. A frame's sides have no typical length, but where
        lines across the frame end on them (`Tables.gaps`: a strip's height)."""
        t = self.host.t
        typical = t.typical
        ty = typical[lab] if typical and lab not in self.host.unsized_sides else math.nan
        return self.stretch * ty if ty == ty else self.scale

    def _round(self, free, edges, kept, fact: Factor, b: np.ndarray) -> Round:
        """What stays the same for every sample of a round. Plain lists: they hold a few
        dozen numbers, where a numpy call costs more than the loop."""
        host, t = self.host, self.host.t
        base, moving, aimless = [], [], []      # see Round
        for v in free:
            p = host.pos.get(v)
            if p is None:
                k = len(base)
                moving += (k, k + 1)
                p = self.aim.get(v)
                if p is None:
                    aimless += (k, k + 1)
                    p = (math.nan, math.nan)
            base.extend(p)
        known, drawn = [], []
        lo, hi, tiles, lo_tol, hi_tol = [], [], [], [], []
        for e, edge in enumerate(edges):
            lab = edge[-1]
            l, h, fixed, tile = t.lengths[lab]
            kn, lt, ht = self._constants(edge, kept[e])
            known.append(kn)
            if kn != kn:
                drawn.append(e)
            lo.append(l)
            hi.append(h if ht < math.inf else math.inf)     # a chord's draw has no top either
            lo_tol.append(lt)
            hi_tol.append(ht)
            if tile and fixed is None:
                tiles.append((e, tile))
        centre = [self._draw_centre(edges[e][-1]) for e in drawn]
        return Round(edges, fact, b, base, moving, aimless, known, drawn, lo, hi, centre,
                      tiles, tuple(e for e, _ in tiles), lo_tol, hi_tol)

    def _kept(self, edges) -> list[bool]:
        """Per edge (v, i, w, j, ...): whether slot (v, i) to (w, j) is an edge the host has
        now (not one to draw)."""
        prim, link = self.host.prim, self.host.link
        return [v in prim and link[v][i] == (w, j) for v, i, w, j, _, _ in edges]

    def _constants(self, edge, kept: bool) -> tuple[float, float, float]:
        """An edge's known length (`_known`) and bounds (`_edge_bounds`): the same in every
        round of the solver (the host is as it was whenever a round is built), and most
        edges come back in each round, so they are worked out once."""
        key = (edge[0], edge[1], edge[2], edge[3], kept)
        got = self._consts.get(key)
        if got is None:
            kn = self._known(edge, kept)
            got = self._consts[key] = (kn, *self._edge_bounds(edge, kn))
        return got

    def _known(self, edge, kept: bool) -> float:
        """An edge's length known in advance: fixed by its class, or kept (an existing edge,
        as long as it is now); nan when it is drawn."""
        host = self.host
        v, _, w, _, d, lab = edge
        fixed = host.t.lengths[lab][2]
        if fixed is not None:
            return fixed
        if kept:
            pv, pw = host.pos[v], host.pos[w]
            return d[0] * (pw[0] - pv[0]) + d[1] * (pw[1] - pv[1])
        return math.nan

    def _edge_bounds(self, edge, kn: float) -> tuple[float, float]:
        """`_bounds` of an edge (v, i, w, j, direction, label): with no maximum for a chord
        of the space (frame.spans_the_space), whose length the frame sets."""
        lt, ht = self._bounds(edge[-1], kn)
        on = self.host.on_border
        if on and spans_the_space(edge[-1] in self.host.border_labels,
                                  self.prim(edge[0]) in on, self.prim(edge[2]) in on):
            return lt, math.inf
        return lt, ht

    def _bounds(self, lab: int, kn: float) -> tuple[float, float]:
        """A length's class range widened by the tolerance. A drawn edge also keeps its
        proportion (Tables.least); a kept one (`kn`: its length now) only as far as it keeps
        it already: the projection may shorten it when an end moves, down to the floor or to
        its present length when that is shorter (held to the floor outright, the corpus
        letter a's drawings lost half their variety). A frame's side has no floor, but where
        lines across the frame end on it (`Tables.gaps`)."""
        b = self._label_bounds.get(lab)
        if b is None:
            b = self._label_bounds[lab] = self._bounds_of(lab)
        lt, ht, floor, least = b
        if least is None or kn != kn:
            return lt, ht
        # A kept edge is held to the floor only as far as it already reaches it: with new
        # lengths stiff (DRAWN_LENGTH) the projection shortens old edges more, and unchecked
        # it squeezed the castle's old towers into slivers.
        return max(floor, min(least, kn) - self.tol), ht

    def _bounds_of(self, lab: int) -> tuple[float, float, float, float | None]:
        """A label's part of _bounds (asked for every edge of every round): a drawn edge's
        bounds, the class's minimum widened, and the floor (None: none)."""
        t = self.host.t
        tol = self.tol
        l, h = t.lengths[lab][:2]
        if lab in self.host.unsized_sides or not t.least:
            return l - tol, h + tol, l - tol, None
        return max(l - tol, t.least[lab]), h + tol, l - tol, t.least[lab]

    def _targets(self, rd: Round, f: float = 1.0) -> np.ndarray:
        rng = self.rng
        noise = rng.normal(0.0, 0.5 * self.scale * f, size=len(rd.base)).tolist()
        # Asked every sample: a floating part's centre draws a place.
        x = rd.targets_at(self.center())
        for k in rd.moving:
            x[k] += noise[k]
        draws = rng.random(len(rd.known)).tolist()
        a, _, width = rd.ranges(f)
        n = len(rd.base)
        for e, lo, w in zip(rd.drawn, a, width):
            x[n + e] = lo + w * draws[e]
        return np.array(x)

    def _sample(self, free, rd: Round, f: float = 1.0) -> dict[int, Point] | None:
        target = self._targets(rd, f)
        # ndarray.dot: the same BLAS product as @, without the ufunc machinery (half the cost).
        fact = rd.fact
        x = target + fact.scale * fact.Minv.dot(rd.b - fact.A.dot(target))
        nF = len(free)
        drawn = x
        # Only for a change the cost wants: a part under its share is often one that needs
        # old vertices moved to fit (the castle scene's gates, a station's modules), and
        # for those repair pays. Repairing every sample drew 5-15 % more samples per
        # placement on the corpus grammars, and drew the paper's flowers and station
        # 18 % and 14 % smaller at their N (seeds 0-4), its castle 20 % larger (measured
        # with the alternating projections this repair replaced). Not repaired, a sample
        # goes on as drawn: its tiles snapped, its lengths tested.
        fitted = tiles = None
        if rd.tiles and self.strict:
            tiles = self._tile_lengths(x, nF, rd)
        if self.strict and rd.unrepaired < REPAIR_TRIES and self._repairing():
            pins = dict(zip(rd.tiled, tiles)) if tiles else {}
            fitted = repair(x, 2 * nF, fact, *rd.clip_box(self.tol), pins)
            rd.unrepaired = 0 if fitted is not None else rd.unrepaired + 1
        if fitted is not None:
            x = fitted
        elif tiles:
            x = self._snap_tiles(x, nF, rd, tiles)
            if x is None:
                self._fail(Rejection.TILES)
                return None
        xs = x.tolist()
        tol = self.tol
        lengths = xs[2 * nF:]
        # Every length in its class (not strict: only positive). The length furthest out is
        # blamed, not the first in the system's order: which piece beside a new part is
        # blamed says which way a slide moves (slides.py), and the first was always the
        # piece on the same side, so a station's modules slid ever further left.
        if self.strict or not all(s > tol for s in lengths):
            worst, blamed = 0.0, None
            for e, (s, lt, ht) in enumerate(zip(lengths, rd.lo_tol, rd.hi_tol)):
                if not (s > tol and lt <= s <= ht):
                    need = _need(s, s, lt, ht, tol)
                    if blamed is None or abs(need) > abs(worst):
                        worst, blamed = need, e
            if blamed is not None:
                self._blame(rd.edges[blamed], worst)
                self._fail(Rejection.EDGE_LENGTH)
                return None
        pos = {v: (xs[2 * k], xs[2 * k + 1]) for k, v in enumerate(free)}
        for m, (a, ox, oy) in self.attached.items():
            pa = pos[a]
            pos[m] = (pa[0] + ox, pa[1] + oy)
        frame = self.host.frame
        # Vertices on the border lie on the frame's sides (held there by their directions);
        # every other vertex must be inside it.
        if frame is not None and not self._in_frame(frame, pos):
            self._fail(Rejection.OUTSIDE_FRAME)
            return None
        if self.strict and not self._planar(pos, rd.edges, rd):
            if x is not drawn:
                # As drawn, the sample broke a length: that is what the size of the next
                # sample goes by, and what ends a round with no room (crowded at one size, too
                # short at the next smaller). Read as crowded, a round whose repaired samples
                # crossed ran all its samples (every sample repaired, curl grown to 2,000
                # vertices: 5,257 first-round samples for 1,028 placements; 3,596 for 996
                # unrepaired).
                self.last_failure = Rejection.EDGE_LENGTH
            return None
        return pos

    def _in_frame(self, frame, pos: dict[int, Point]) -> bool:
        """Whether the sample's vertices lie inside the frame, but those on its sides (held
        there by their directions). A slid part of a rectangular frame is tested by its box:
        it moves as one, and a box inside a rectangle holds all it bounds."""
        attached, on, clr = self.attached, self.host.on_border, self.clearance
        rect = frame.rectangle
        if not all(frame.contains(*p, clr) for v, p in pos.items()
                   if (v not in attached or not rect) and self.prim(v) not in on):
            return False
        if rect:
            hpos = self.host.pos
            for a, slide in self.slides.items():
                dx, dy = pos[a][0] - hpos[a][0], pos[a][1] - hpos[a][1]
                box = slide.box
                if box is not None and not (frame.contains(box[0] + dx, box[1] + dy, clr)
                                            and frame.contains(box[2] + dx, box[3] + dy, clr)):
                    return False
        return True

    def _repairing(self) -> bool:
        """Whether this change's samples are repaired (`repair`): when the caller wants it."""
        if self._wants is None:
            self._wants = self.wanted is not None and self.wanted()
        # A slide's round as well: its seams are kept lengths, soft in the projection, and
        # unrepaired a light part slid past their ranges.
        return self._wants or bool(self.slides)

    @staticmethod
    def _tile_lengths(x, nF, rd: Round) -> list[float]:
        """Each tiled length of sample `x` rounded to a whole multiple of its tile: the nearest
        one inside the edge's class when there is one (rounding 1.3 tiles down to 1 would fall
        below a class whose minimum is 1.1 tiles)."""
        vals = []
        for e, tile in rd.tiles:
            k = max(1, round(float(x[2 * nF + e]) / tile))
            k_lo = math.ceil(rd.lo[e] / tile - 1e-9)
            k_hi = math.floor(rd.hi[e] / tile + 1e-9) if rd.hi[e] < math.inf else max(k, k_lo)
            if max(1, k_lo) <= k_hi:
                k = min(max(k, k_lo), k_hi)
            vals.append(k * tile)
        return vals

    def _snap_tiles(self, x, nF, rd: Round, vals: list[float]):
        """The system solved again with its tiled lengths pinned at `vals` (the sample's,
        rounded to whole multiples: `_tile_lengths`)."""
        A2, A2p = rd.fact.pinned_system(rd.tiled, nF)
        b2 = np.concatenate([rd.b, vals])
        # The nearest point to the sample that also meets the pins, in the plain norm: old
        # and new coordinates move alike. The repair's projection (Factor.project_pinned)
        # weights them as the sampler does, and moves the new part rather than its context;
        # used here as well, it cost the castle at seed 80 a third of its applied steps (291
        # → 204 at 4,000 iterations) and the village a third more time (3.9 → 5.1 s).
        y = x + A2p.dot(b2 - A2.dot(x))
        unit = self.host.t.unit
        if float(np.abs(A2.dot(y) - b2).max()) > 1e-7 * unit * (1 + float(np.abs(b2).max()) / unit):
            return None
        return y


def _need(low: float, high: float, lo: float, hi: float, tol: float) -> float:
    """How much longer a length that ranges over [low, high] had to be to meet its class
    [lo, hi] and be positive (tol: the least positive length): negative when shorter."""
    return max(lo, tol) - high if low <= hi else hi - low


def _dist(p: Point, q: Point) -> float:
    return ((p[0] - q[0]) ** 2 + (p[1] - q[1]) ** 2) ** 0.5


def place_side(host: HostView, side, rng: np.random.Generator,
               tries: int = 4) -> tuple[list[dict[int, Point]], bool]:
    """Positions for the vertices of an angle graph on its own (a rule side, say, drawn by
    `ggc report`), one dict per connected component (`side.components()` order), each placed
    around the origin by the same solver as a generation step: every edge has its label's
    direction and a length its class allows, and no edges cross. Components are placed apart
    (aimed at one spot they would almost always cross); how to arrange them is the caller's
    choice. Open half-edges stay open. The flag says whether every test held: a component
    for which `tries` rounds of samples find no placement is placed keeping only the
    directions and positive lengths (no class ranges, fixed lengths, tiles or crossings).
    `host` must be empty; it is left unchanged. ValueError when not even that is possible."""
    assert len(host) == 0, "place_side draws on an empty host"
    out, strict = [], True
    for comp in side.components():
        keep = set(comp)
        new = tuple((v, side.vertices[v]) for v in comp)
        glue = tuple(((v, i), (w, j)) for v, i, w, j in side.edges if v in keep)
        partner: dict = {(v, i): None for v, p in new for i in range(len(host.t.rings[p]))}
        for a, b in glue:
            partner[a], partner[b] = b, a
        change = Change(None, None, (), new, glue, (), partner)
        pos = None
        for k in range(tries + 1):
            solver = Solver(host, change, rng, lambda: (0.0, 0.0), floating=True,
                            strict=k < tries)
            pos = next((p.positions for p in solver.placements()), None)
            if pos is not None:
                break
        if pos is None:
            raise ValueError("no placement keeps the edge directions")
        strict = strict and k < tries
        out.append(pos)
    return out, strict
