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
"""

from __future__ import annotations

import math
import statistics
from collections import OrderedDict
from dataclasses import dataclass, field
from typing import Callable, Iterator

import numpy as np

from grammar_lang.algorithms.components import DisjointSet
from grammar_lang.frame import spans_the_space

from .change import Change, HostView
from .min_norm import min_norm_inverse
from .rejections import Rejection
from .slides import Slide, sliding_part
from .spatial import Point, seg_distance

I_ROUNDS, J_SAMPLES = 5, 10
# Column scales of the weighted projection: a larger scale is cheaper to move.
NEW_POS, OLD_POS, LENGTH = 10.0, 1.0, 1.0
# A new vertex glued to no old one (in a structure made whole, or stood on a frame's side) has
# only the change's centre to aim at: its place comes from the lengths, or the projection
# would squeeze the structure towards that point.
LOOSE_POS = 100.0
# A frame's sides are as long as the frame: a structure standing on one takes what it needs
# and the stretches of bare side beside it take the rest, so their lengths are cheapest.
FRAME_SIDE = 100.0
# A new edge's drawn length is stiffer than the old drawing: the projection lets old vertices
# (once freed) give way rather than squash the new part. At LENGTH the misfit of a part
# squeezed between old ones was shared equally, so its new edges came out far shorter than
# drawn, often negative: on the paper's castle most rounds could not pass ("length out of
# range", "edge length"). 0.1: ten times stiffer.
DRAWN_LENGTH = 0.1
# How many layers out from a failed edge `_free_one` looks for vertices to free.
HOPS = 4
# At most this many lengths `repair` pins where a projection left them out of range; a
# length is pinned REPAIR_MARGIN of its lower bound inside its range.
REPAIR = 12
REPAIR_MARGIN = 1e-3
# A round stops repairing after this many samples in a row it could not repair: what fails
# is mostly the round's system, not its sample (no room while only these vertices move). On
# the castle at its N, 281 of its 282 repairs come before such a pair, and the village's
# 7 of 7, for a fifth of the repairs tried (10,491 → 2,330; 19,057 → 3,817).
REPAIR_TRIES = 2
SHRINK = 0.75
# New edges are drawn between half and 1.8 times their label's typical length in the example
# (stretched as their neighbourhood is), or the local scale where the typical length is not
# known. Longer than short: a part that is to hold more than the example's part did (a
# station's module with a second connector under it, a castle's block with a keep on it)
# must be drawn wider than typical. Within ±50 % the paper's castle grew mostly thin poles
# and one keep, and its station covered less (over seeds 0-3 at the paper's N: station
# 117 → 153 vertices, 32 → 49 % of its frame covered; castle 272 → 291, 40 → 45 %).
_LOW, _HIGH = 0.5, 1.8
GROW_MAX = SHRINK ** -6
# Failures that a smaller sample may avoid (a part squeezed between old vertices).
CROWDED = (Rejection.CROSSING, Rejection.COINCIDENT, Rejection.CLOSE)
# Parts this many edges apart or more in the graph (or not joined at all) keep the gap
# between them (Tables.gap), not just the clearance. In the paper's four examples, vertices
# and edges 3 edges apart come as close as 20 px, and 4 apart no closer than 44 px.
FAR_HOPS = 4
# How far a length may miss its class's range (numerical noise): a ten-millionth of the unit,
# but never more than the verifier's 2e-6 leaves once a drawing's coordinates are rounded to
# 6 decimals (each end moves up to 0.71e-6). At 1e-7 of a 40 px unit (4e-6) a kept edge at
# its floor came out 2.1e-6 short, and the drawing failed its check.
LENGTH_NOISE = 5e-7


@dataclass(frozen=True)
class Placement:
    positions: dict[int, Point]      # new and moved vertices


class Solver:
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
        edges' lengths over their labels' typical lengths; 1 where none is known)."""
        host = self.host
        typical = host.t.typical
        lengths, ratios = [], []

        def seen(v, w, lab):
            d = _dist(host.pos[v], host.pos[w])
            lengths.append(d)
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
        return scale, (statistics.median(ratios) if ratios else 1.0)

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

    def _round_samples(self, free: list[int], rd: "_Round"):
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

    def _free_one(self, free: list[int]) -> bool:
        """Free more old vertices for the next round. When a length failed (fixed or doomed
        out of its class, or broken by the round's samples), the held vertices nearest that
        edge are freed, all of them: on the castle a new wall top fixed at a negative length
        needs the tower side beside it to slide, and a tower side split by a merlon needs both
        top corners to rise; a random neighbour (the paper's choice) rarely is the one, and in
        a drawing of straight lines one vertex freed alone is still held by its other edges.
        Otherwise (over-constrained, crossings), one random neighbour, as the paper does."""
        fs = set(free).union(self.attached)
        blamed = max(sorted(self.culprits.items()), key=lambda kv: kv[1])[0] \
            if self.culprits else None
        self.culprits = {}
        if blamed is not None and self._slide(blamed, free, fs):
            return True
        want = self._nearest_held(blamed, fs) if blamed is not None else []
        if not want:
            near = {w for v in free for _, (w, _) in self.adjacency(v)}
            near.update(s[0] for pair in self.bridges for s in pair)
            cands = sorted(near - fs - self.host.pinned)
            if not cands:
                return False
            want = [cands[int(self.rng.integers(len(cands)))]]
        for v in want:
            if v not in fs:
                part = self._rigid_part(v, fs)
                free.extend(part)
                fs.update(part)
        return True

    def _slide(self, ends: tuple[int, int], free: list[int], fs: set[int]) -> bool:
        """Free the part beyond a held end of the failed edge `ends` as one unit (slides.py),
        the smaller part where both ends are held; False when neither end has one."""
        if ends in self._no_slide:
            return False
        v, w = ends
        d, need = self.culprit_need[ends]
        best, hung = None, None
        # The edge runs from v to w along d: beyond w is +d, beyond v is −d.
        for held, other, sign in ((w, v, 1), (v, w, -1)):
            if held in fs or held in self.host.pinned:
                continue
            if hung is None:
                hung = {u for x in free for _, (u, _) in self.adjacency(x) if u not in fs}
            s = sliding_part(self.host, self.adjacency, self.prim, self._range_now, held,
                             hung | {other}, d, sign, need, fs)
            if s is not None and (best is None or len(s.offsets) < len(best.offsets)):
                best = s
        if best is None:
            # Later rounds blame the same edge more often than not, and the search would
            # mostly find no part again.
            self._no_slide.add(ends)
            return False
        self.slides[best.anchor] = best
        for m, (ox, oy) in best.offsets.items():
            self.attached[m] = (best.anchor, ox, oy)
        free.append(best.anchor)
        return True

    def _range_now(self, v: int, i: int, w: int, j: int) -> tuple[float, float, float]:
        """An existing edge's range (as a kept edge's, _edge_bounds) and its length now."""
        t, pv = self.host.t, self.prim(v)
        now, lt, ht = self._constants((v, i, w, j, t.direction[pv][i], t.label[pv][i]), True)
        return lt, ht, now

    def _nearest_held(self, ends: tuple[int, int], free: set[int]) -> list[int]:
        """The vertices not yet free (nor pinned) nearest the edge `ends`, by breadth-first
        layers out from its two ends, at most HOPS layers away: those that hold its length."""
        pinned = self.host.pinned
        layer, seen = sorted(set(ends)), set(ends)
        for _ in range(HOPS):
            held = [v for v in layer if v not in free and v not in pinned]
            if held:
                return held
            nxt = []
            for v in layer:
                for _, (w, _) in self.adjacency(v):
                    if w not in seen:
                        seen.add(w)
                        nxt.append(w)
            layer = sorted(nxt)
        return []

    def _rigid_part(self, v: int, free: set[int]) -> list[int]:
        """`v` and the old vertices joined to it by edges of fixed length (a rigid part):
        they move as one unit, as the paper's merged rigid parts do, since freeing one of
        them alone leaves it pinned by its fixed edges to the rest."""
        t, pinned = self.host.t, self.host.pinned
        part, todo, seen = [], [v], {v}
        while todo:
            u = todo.pop()
            part.append(u)
            pu = self.prim(u)
            for i, (w, _) in self.adjacency(u):
                if w not in seen and w not in free and w not in pinned \
                        and w not in self.new_prim and t.lengths[t.label[pu][i]][2] is not None:
                    seen.add(w)
                    todo.append(w)
        return part

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
                    if (v, i) in seen or slide is not None \
                            and (s[0] == a or attached.get(s[0], (None,))[0] == a):
                        continue
                    seen.add(s)
                    edges.append((v, i, *s, t.direction[pv][i], t.label[pv][i]))
        fs = set(free)
        for (v, i), (w, j) in self.bridges:
            if v not in fs and w not in fs:
                pv = host.prim[v]
                edges.append((v, i, w, j, t.direction[pv][i], t.label[pv][i]))
        return edges

    def _system(self, free: list[int]) -> "_Round | Rejection | None":
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
        shape = (tuple([(OLD_POS if v not in slides else _slid_pos(slides[v])) if v in prim
                        else NEW_POS if v in glued else LOOSE_POS for v in free]),
                 tuple([(idx.get(v, -1), idx.get(w, -1), d,
                         None if lengths is None else lengths[lab][2], lab in sides, not k)
                        for (v, _, w, _, d, lab), k in zip(edges, kept)]))
        fact = self.cache.get(shape)
        if fact is None:
            fact = self.cache.put(shape, _factorise(*shape))
        bl = _right_hand_side(shape[1], edges, host.pos, self.attached)
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

    def _fixed_out(self, edges, kept, fact: "Factor", c: list) -> bool:
        """Whether a length the system fixes whatever the target (its row of x = R t + c is
        constant) lies outside its class's range: then every sample fails."""
        tol = self.tol
        for e in fact.fixed_idx:
            _, lt, ht = self._constants(edges[e], kept[e])
            if not (c[e] > tol and lt <= c[e] <= ht):
                self._blame(edges[e], _need(c[e], c[e], lt, ht, tol))
                return True
        return False

    def _doomed(self, rd: "_Round", fact: "Factor", c: list):
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

    def _target_box(self, rd: "_Round") -> tuple[np.ndarray, np.ndarray]:
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
        tower's); else the local scale. A frame's sides have no typical length."""
        typical = self.host.t.typical
        ty = typical[lab] if typical and lab not in self.host.side_labels else math.nan
        return self.stretch * ty if ty == ty else self.scale

    def _round(self, free, edges, kept, fact: "Factor", b: np.ndarray) -> "_Round":
        """What stays the same for every sample of a round. Plain lists: they hold a few
        dozen numbers, where a numpy call costs more than the loop."""
        host, t = self.host, self.host.t
        base, moving, aimless = [], [], []      # see _Round
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
        return _Round(edges, fact, b, base, moving, aimless, known, drawn, lo, hi, centre,
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
        letter a's drawings lost half their variety). A frame's side has no floor."""
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
        if lab in self.host.side_labels or not t.least:
            return l - tol, h + tol, l - tol, None
        return max(l - tol, t.least[lab]), h + tol, l - tol, t.least[lab]

    def _targets(self, rd: "_Round", f: float = 1.0) -> np.ndarray:
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

    def _sample(self, free, rd: "_Round", f: float = 1.0) -> dict[int, Point] | None:
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
    def _tile_lengths(x, nF, rd: "_Round") -> list[float]:
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

    def _snap_tiles(self, x, nF, rd: "_Round", vals: list[float]):
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

    # --- planarity --------------------------------------------------------------------------
    def _planar_context(self, free) -> tuple[frozenset, frozenset]:
        """What a round's crossing tests leave out, the same for each of its samples: the
        vertices that are replaced or moved (`free`: the round's free vertices), and the host
        edges that are cut or touch them."""
        host = self.host
        gone = self.removed.union(v for v in free if v in host.prim)
        ignore = {min(s, host.link[s[0]][s[1]]) for s in self.change.cut}
        for v in gone:
            for i, s in enumerate(host.link[v]):
                if s is not None:
                    ignore.add(min((v, i), s))
        return frozenset(gone), frozenset(ignore)

    def _planar(self, pos: dict[int, Point], edges, rd: "_Round") -> bool:
        # Each test only asks whether some pair is too close, so the order in which pairs are
        # tried does not matter: the first one found decides. The new parts among themselves
        # come first: they need no grid, and most samples that fail cross themselves.
        clr = self.clearance
        if rd.context is None:
            # Made for the first sample tested: most rounds have none, their samples failing
            # their lengths first (castle, 1,000 proposals: 682 samples in 3,143 rounds).
            rd.context = self._planar_context(pos)
        gone, ignore = rd.context
        # Vertices: no two may coincide. A slide's members are tested by their edges (below):
        # a vertex that came too close to another would bring its edges as close.
        attached, slides = self.attached, self.slides
        pts = [p for v, p in pos.items() if v not in attached and v not in slides] \
            if attached else list(pos.values())
        for k, p in enumerate(pts):
            for p2 in pts[k + 1:]:
                if ((p[0] - p2[0]) ** 2 + (p[1] - p2[1]) ** 2) ** 0.5 < clr:     # _dist, inline
                    self._fail(Rejection.COINCIDENT)
                    return False
        grid = self.host.grid
        for p in pts:
            if grid.point_within(p, clr, gone):
                self._fail(Rejection.COINCIDENT)
                return False
        # Edges: no crossing or touching except at a shared end. Boxes first, since most
        # candidates are far: boxes farther apart than the clearance hold no closer pair.
        segs = self._segments(pos, edges)
        if _segments_meet(segs, None, clr) or self._meets_drawing(segs, ignore) \
                or slides and self._slides_meet(pos, segs, ignore):
            self._fail(Rejection.CROSSING)
            return False
        if self.gap > clr and self._crowds(pos, segs, ignore, rd):
            self._fail(Rejection.CLOSE)
            return False
        return True

    def _crowds(self, pos, segs, ignore, rd: "_Round") -> bool:
        """Whether the sample's edges, or a slide's own edges, come within the gap of a part
        far from them (`_near_far_part`)."""
        border = self.host.border_labels
        if rd.sides is None:
            rd.sides = [e[-1] in border for e in rd.edges]
        sides = rd.sides
        if self._near_far_part(segs, sides, ignore, rd):
            return True
        for a, slide in self.slides.items():
            own_sides = self._slide_sides.get(a)
            if own_sides is None:
                own_sides = self._slide_sides[a] = [self._label(x, y) in border
                                                    for x, y in slide.edges]
            if self._near_far_part(self._own_segments(pos, slide), own_sides, ignore, rd,
                                   (segs, sides)):
                return True
        return False

    def _label(self, v: int, w: int) -> int:
        """The label of the edge from v to w in the drawing as the change leaves it (a slide's
        own edge may be one the change glues)."""
        return next(self.host.t.label[self.prim(v)][i]
                    for i, (u, _) in self.adjacency(v) if u == w)

    def _near_far_part(self, segs, sides, ignore, rd: "_Round", against=None) -> bool:
        """Whether one of `segs` comes within the gap of an edge it shares no end with and
        that is far from it: of the drawing, or of `against` (segments and their `sides`;
        None: of `segs` themselves). Far: one of the two a frame's side (`sides`: per
        segment; the frame is not a part), else neither end of the other within FAR_HOPS − 1
        edges of either of its own (`_hood`, made when first needed: most samples have no
        edge that near). Drawing edges that a slide moves are tested where they go, by the
        caller, not where they lay."""
        grid, gap, t = self.host.grid, self.gap, self.host.t
        boxes, link, prim, border = grid.boxes, self.host.link, self.host.prim, \
            self.host.border_labels
        moving = self.attached.keys() | self.slides.keys() if self.slides else ()
        widen = gap - self.clearance
        for k, (v, w, a, c, lx, ly, hx, hy) in enumerate(segs):
            lx, ly, hx, hy = lx - widen, ly - widen, hx + gap, hy + gap
            for key in grid.segments_near(lx, ly, hx, hy):
                qlx, qly, qhx, qhy, p, q = boxes[key]
                if lx > qhx or qlx > hx or ly > qhy or qly > hy or key in ignore:
                    continue
                x = key[0]
                y = link[x][key[1]][0]
                if moving and x in moving and y in moving:
                    continue
                if self._too_near(v, w, a, c, x, y, p, q, rd,
                                  sides[k] or t.label[prim[x]][key[1]] in border):
                    return True
            pool = zip(segs[k + 1:], sides[k + 1:]) if against is None else zip(*against)
            for (x, y, p, q, qlx, qly, qhx, qhy), side in pool:
                if lx > qhx or qlx > hx or ly > qhy or qly > hy:
                    continue
                if self._too_near(v, w, a, c, x, y, p, q, rd, sides[k] or side):
                    return True
        return False

    def _too_near(self, v, w, a, c, x, y, p, q, rd: "_Round", side: bool) -> bool:
        """Whether edges v–w (from a to c) and x–y (from p to q) share no end, come within the
        gap, and are far apart: one of them a frame's side, or x and y out of their hood."""
        if x == v or x == w or y == v or y == w or seg_distance(a, c, p, q) >= self.gap:
            return False
        if side:
            return True
        near = self._hood(v, rd) | self._hood(w, rd)
        return x not in near and y not in near

    def _hood(self, v: int, rd: "_Round") -> frozenset:
        """The vertices within FAR_HOPS − 1 edges of `v` in the drawing as the change leaves
        it, not counting a way along the frame (its sides are as long as the frame: through
        them every corner is near whatever stands on one). The same in every sample of a
        round, so kept with it."""
        got = rd.hoods.get(v)
        if got is None:
            t, border = self.host.t, self.host.border_labels
            layer, seen = {v}, {v}
            for _ in range(FAR_HOPS - 1):
                layer = {u for x in layer for i, (u, _) in self.adjacency(x)
                         if t.label[self.prim(x)][i] not in border} - seen
                seen |= layer
            got = rd.hoods[v] = frozenset(seen)
        return got

    def _meets_drawing(self, segs, ignore, keys=None) -> bool:
        """Whether one of `segs` comes within the clearance of an edge of the drawing (but
        those in `ignore` and those it shares an end with); `keys`: per segment, the drawing's
        edges to try, else those the grid finds near it."""
        grid, clr = self.host.grid, self.clearance
        boxes, link = grid.boxes, self.host.link
        for k, (v, w, a, c, lx, ly, hx, hy) in enumerate(segs):
            for key in grid.segments_near(lx, ly, hx + clr, hy + clr) if keys is None else keys[k]:
                # The box first: most candidates are far, and the order of skips is free.
                qlx, qly, qhx, qhy, p, q = boxes[key]
                if lx > qhx or qlx - clr > hx or ly > qhy or qly - clr > hy or key in ignore:
                    continue
                x = key[0]
                y = link[x][key[1]][0]
                if x == v or x == w or y == v or y == w:
                    continue
                if seg_distance(a, c, p, q) < clr:
                    return True
        return False

    def _slides_meet(self, pos: dict[int, Point], segs, ignore) -> bool:
        """Whether a slide's own edges, moved with it, come within the clearance of the
        sample's edges, of another slide's or of the drawing. Within one slide nothing moves
        apart. Against the drawing, only the edges near where a slid edge was are tried: a
        translation by δ moves every point of it by |δ|, so it cannot reach an edge that lay
        farther than |δ| and the clearance from it."""
        clr, hpos = self.clearance, self.host.pos
        moved = []
        for a, slide in sorted(self.slides.items()):
            own = self._own_segments(pos, slide)
            if _segments_meet(own, segs, clr) or any(_segments_meet(own, o, clr) for o in moved):
                return True
            moved.append(own)
            reach = math.hypot(pos[a][0] - hpos[a][0], pos[a][1] - hpos[a][1]) + clr
            if self._meets_drawing(own, ignore, self._near_slide(slide, reach)):
                return True
        return False

    def _near_slide(self, slide: Slide, reach: float) -> list[list]:
        """Per edge of `slide` (as it lies now), the drawing's edges within `reach` of its
        box, or more: kept for the solver's life, made again only for a larger reach."""
        got = self._slide_near.get(slide.anchor)
        if got is None or got[0] < reach:
            r = max(reach, 2.0 * (got[0] if got else 0.0), 0.5 * self.host.t.unit)
            own = self._own_segments({}, slide)
            near = [list(self.host.grid.segments_near(lx - r, ly - r, hx + r, hy + r))
                    for _, _, _, _, lx, ly, hx, hy in own]
            got = self._slide_near[slide.anchor] = (r, near)
        return got[1]

    def _own_segments(self, pos: dict[int, Point], slide: Slide) -> list[tuple]:
        """`_segments` of a slide's own edges, its members at `pos` (or where they lie)."""
        return self._segments(pos, [(x, 0, y, 0, None, None) for x, y in slide.edges])

    def _segments(self, pos: dict[int, Point], edges) -> list[tuple]:
        """Each edge of a sample: its ends (ids), their points and its box, the low ends
        less the clearance."""
        hpos, clr = self.host.pos, self.clearance
        segs = []
        for v, _, w, _, _, _ in edges:
            a, c = pos.get(v), pos.get(w)
            a = hpos[v] if a is None else a
            c = hpos[w] if c is None else c
            lx, hx = (a[0], c[0]) if a[0] < c[0] else (c[0], a[0])
            ly, hy = (a[1], c[1]) if a[1] < c[1] else (c[1], a[1])
            segs.append((v, w, a, c, lx - clr, ly - clr, hx, hy))
        return segs


@dataclass
class _Round:
    """A round's system (its edges, matrix, right-hand side, column scales, minimum-norm
    inverse) and constants: free vertices' base coordinates (old: where they are, new: their
    aim, nan: no aim, the change's centre per sample), which coordinates are new (`moving`)
    and which of those have no aim; edge lengths known in advance (fixed, or kept; nan:
    drawn), which edges are drawn, their class bounds, where drawn ones are centred, the
    tiled edges. Lists of indices, so that a sample's loops visit only the coordinates it
    changes. Draw ranges and what the crossing tests leave out are made once, when first
    needed."""

    edges: list
    fact: Factor             # the system's matrix, column scales and minimum-norm inverse
    b: np.ndarray
    base: list
    moving: list
    aimless: list
    known: list
    drawn: list
    lo: list
    hi: list
    centre: list             # per drawn edge
    tiles: list
    tiled: tuple             # the tiled edges alone: the key of their pinned system
    lo_tol: list             # the class bounds widened by the tolerance
    hi_tol: list
    context: tuple | None = None     # what the crossing tests leave out (_planar_context)
    sides: list | None = None        # per edge, whether it is a frame's side (_crowds)
    hoods: dict = field(default_factory=dict)   # vertex → those near it in the graph (_hood)
    unrepaired: int = 0              # samples in a row `repair` found no point for
    _ranges: dict = field(default_factory=dict)
    _clip: tuple | None = None       # clip_box's, made once

    def targets_at(self, centre: Point) -> list:
        """The base coordinates, those without an aim at `centre`, then the known lengths
        (nan where drawn): a new list, for a sample to fill in."""
        x = self.base + self.known
        cx, cy = centre
        for k in self.aimless:
            x[k] = cy if k & 1 else cx
        return x

    def clip_box(self, tol: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Each length's range for `repair`: the test's, less a margin on each side (the
        margin is `repair`'s slack), so that a repaired length passes the test."""
        box = self._clip
        if box is None:
            lo = np.array([max(lt, tol) for lt in self.lo_tol])
            hi = np.array(self.hi_tol, dtype=float)
            m = np.maximum(np.minimum(REPAIR_MARGIN * np.maximum(lo, 1.0), 0.25 * (hi - lo)), 0.0)
            box = self._clip = (lo + m, hi - m, m)
        return box

    def ranges(self, f: float) -> tuple[list, list, list]:
        """Where new edges' target lengths are drawn at size factor `f`: (low end, high end,
        width) per drawn edge. From _LOW·centre·f to _HIGH·centre·f, inside the range the
        length test allows (the class, above the label's floor), or that whole range when it
        misses it; when a shrunk range falls below it, its shortest length."""
        r = self._ranges.get(f)
        if r is None:
            los, his, widths = [], [], []
            # Asked for most samples (each failure changes f): max and min written out, as
            # the builtins decide them (a later argument wins only when strictly beyond).
            for e, c in zip(self.drawn, self.centre):
                # The shortest length the test lets through: the class's minimum, or the
                # label's floor when that is higher (drawn below it, a sample always failed).
                lo, hi = max(self.lo[e], self.lo_tol[e]), self.hi[e]
                a, bb = _LOW * c * f, _HIGH * c * f
                a = a if a > lo else lo
                bb = bb if bb < hi else hi
                if a > bb:
                    # The whole range, as wide as a usual draw where it has no end (a border
                    # class's).
                    a, bb = (lo, hi if hi < math.inf else lo * _HIGH / _LOW) \
                        if f == 1.0 or hi < a else (lo, lo)
                los.append(a)
                his.append(bb)
                widths.append(bb - a)
            r = self._ranges[f] = (los, his, widths)
        return r


@dataclass(frozen=True)
class Factor:
    """What a system's shape alone fixes: its matrix, column scales and a minimum-norm inverse,
    the rows of lengths that no target moves, and whether the solution is unique."""

    A: np.ndarray
    scale: np.ndarray
    M: np.ndarray
    Minv: np.ndarray
    R: np.ndarray
    fixed_idx: list          # the lengths that no target moves
    unique: bool
    absR: np.ndarray
    Minv_len: np.ndarray     # the rows of Minv and of the scales for the lengths
    scale_len: np.ndarray
    P_len: np.ndarray        # the null-space projection's columns for the lengths (`repair`)
    # By tiled edges: the system with their lengths pinned. Kept with the shape, since the
    # same tiled edges come back with it (castle: 969 of 1,367 pinned systems were repeats).
    _pinned: dict = field(default_factory=dict)

    def pinned_system(self, tiled: tuple[int, ...], nF: int) -> tuple[np.ndarray, np.ndarray]:
        """A with a row pinning each tiled length, and its minimum-norm inverse: the same for
        every sample (only the pinned values change)."""
        pinned = self._pinned.get(tiled)
        if pinned is None:
            rows = np.zeros((len(tiled), self.A.shape[1]))
            for r, e in enumerate(tiled):
                rows[r, 2 * nF + e] = 1.0
            A2 = np.vstack([self.A, rows])
            pinned = self._pinned[tiled] = (A2, min_norm_inverse(A2))
        return pinned

    def project_pinned(self, x: np.ndarray, n: int, pins: dict[int, float]) -> np.ndarray | None:
        """The point of the system nearest its point `x`, in the projection's weighted norm,
        whose lengths `pins` (by edge index; lengths start at index `n`) have the values given;
        None when the pins leave the system without a solution.

        The step d from `x` lies in the system's null space and is the shortest that sets the
        pinned lengths: d = P[:, E] · P[E, E]⁻¹ · r, with P the projection onto the null space
        (`P_len`: its columns for the lengths), E the pinned lengths and r how far each is
        from its pin. A k×k solve, where an inverse of the pinned system took 20 times
        as long and, made for every sample's pins, tripled the castle's time."""
        idx = np.fromiter(pins, dtype=int, count=len(pins))
        r = np.fromiter(pins.values(), dtype=float, count=len(pins)) - x[n + idx]
        cols = self.P_len[:, idx]
        G = cols[n + idx]
        tol = 1e-9 * (1.0 + float(np.abs(x).max()))
        # Pins the system ties together (a rectangle's two sides) make P[E, E] singular, or
        # nearly: a plain solve then gives a step off the system (0.04 px on the castle) that
        # the pins alone do not show. So the step is checked on the system too, and made
        # again by least squares when it fails there.
        for solve in (np.linalg.solve, _least_squares):
            try:
                d = cols.dot(solve(G, r))
            except np.linalg.LinAlgError:
                continue
            if float(np.abs(d[n + idx] - r).max(initial=0.0)) <= tol \
                    and float(np.abs(self.A.dot(d)).max(initial=0.0)) <= tol:
                return x + d
        return None


def _least_squares(G: np.ndarray, r: np.ndarray) -> np.ndarray:
    return np.linalg.lstsq(G, r, rcond=1e-10)[0]


class SystemCache:
    """Factorisations by system shape. A move's system depends only on its topology (which
    vertices are free and old, each edge's ends, direction and fixed length), never on where
    the old vertices are, and the same shapes come back step after step: one inverse each.
    Bounded: when full the least recently used shape goes. Emptying it instead threw away
    the shapes of the matches being retried (on the castle, 1,600 of 9,900 factorisations
    were of a shape seen before)."""

    def __init__(self, size: int = 4096):
        self.size, self.table = size, OrderedDict()

    def get(self, shape):
        fact = self.table.get(shape)
        if fact is not None:
            self.table.move_to_end(shape)
        return fact

    def put(self, shape, fact: Factor) -> Factor:
        if len(self.table) >= self.size:
            self.table.popitem(last=False)
        self.table[shape] = fact
        return fact


def _slid_pos(slide: Slide) -> float:
    # A slide moves all its vertices: the projection is charged as if each moved alone (the
    # squares of their moves add up), so a large part gives way less than a corner.
    return OLD_POS / math.sqrt(1 + len(slide.offsets))


def _factorise(pos_scale: tuple[float, ...], edges) -> Factor:
    """`A` over (positions of the free vertices, edge lengths): row pair e says
    p_w − p_v − s_e d_e = (fixed ends moved to b), then one row per fixed length. An edge of
    the shape is (free index of v or −1, of w or −1, direction, fixed length, frame side,
    drawn: new, not an existing edge kept); `pos_scale`: each free vertex's column scale."""
    nF, nE = len(pos_scale), len(edges)
    fixed = [e for e, (_, _, _, f, _, _) in enumerate(edges) if f is not None]
    A = np.zeros((2 * nE + len(fixed), 2 * nF + nE))
    # Cell by cell: on systems of this size numpy's index arrays cost more than the loop
    # (2,205 castle systems: 0.13 s by np.add.at, 0.095 s so).
    for e, (iv, iw, d, _, _, _) in enumerate(edges):
        for c in (0, 1):
            if iw >= 0:
                A[2 * e + c, 2 * iw + c] += 1.0
            if iv >= 0:
                A[2 * e + c, 2 * iv + c] -= 1.0
            A[2 * e + c, 2 * nF + e] = -d[c]
    A[2 * nE + np.arange(len(fixed)), 2 * nF + np.asarray(fixed, dtype=int)] = 1.0
    scale = np.empty(2 * nF + nE)
    scale[:2 * nF] = np.repeat(pos_scale, 2)
    scale[2 * nF:] = [FRAME_SIDE if side else DRAWN_LENGTH if drawn else LENGTH
                      for *_, side, drawn in edges]
    M = A * scale
    Minv = min_norm_inverse(M)
    P = np.eye(A.shape[1]) - scale[:, None] * (Minv @ A)
    R = P[2 * nF:]
    fixed_rows = np.abs(R).max(axis=1, initial=0.0) < 1e-9
    return Factor(A, scale, M, Minv, R, np.flatnonzero(fixed_rows).tolist(),
                  bool(np.abs(P).max(initial=0.0) < 1e-9), np.abs(R), Minv[2 * nF:],
                  scale[2 * nF:], np.ascontiguousarray(P[:, 2 * nF:]))


def repair(x: np.ndarray, n: int, fact: "Factor", lo: np.ndarray, hi: np.ndarray,
           slack: np.ndarray, pins: dict[int, float]) -> np.ndarray | None:
    """The point of the system nearest its point `x` (in the projection's weighted norm)
    whose lengths (from index `n` on) lie in [lo, hi] and whose lengths `pins` (tiled edges,
    by edge index) have the values given; None when none was found; `x` itself when it needs
    nothing.

    An active set: project with the pins; the length the projection leaves furthest out of
    range (by more than `slack`) is pinned at its nearest bound, and the projection is made
    again, until none is out (REPAIR pins at most). Pins are only added, so this may miss a
    point that exists, but it never returns one that is not there. Pinning every length out
    of range at once failed where lengths are tied (a rectangle's opposite sides, pinned at
    two bounds); one at a time, the worst first, the ties follow the first pin. This
    replaces alternating projections between the box and the system, which crawl where the
    two meet at a shallow angle: on the castle a keep on a 75 px block top needed hundreds
    of them, and a stall test gave up first; and whose tiles, rounded after, broke the
    lengths they had fitted."""
    pins = dict(pins)
    y = x
    for _ in range(REPAIR + 1):
        if pins:
            y = fact.project_pinned(x, n, pins)
            if y is None:
                return None
        lengths = y[n:]
        if not len(lengths):
            return y
        miss = np.maximum(lo - lengths, lengths - hi)
        if pins:
            miss[list(pins)] = 0.0
        e = int(np.argmax(miss))
        if miss[e] <= slack[e]:
            return y
        pins[e] = min(max(float(lengths[e]), float(lo[e])), float(hi[e]))
    return None


def _right_hand_side(shape_edges, edges, pos, attached) -> list[float]:
    """b: the fixed ends' positions (a slide's member: its offset from its anchor, whose
    column it shares), then the fixed lengths."""
    b = []
    for (iv, iw, _, _, _, _), (v, _, w, _, _, _) in zip(shape_edges, edges):
        bx = by = 0.0
        if iw < 0:
            pw = pos[w]
            bx -= pw[0]
            by -= pw[1]
        elif w in attached:
            bx -= attached[w][1]
            by -= attached[w][2]
        if iv < 0:
            pv = pos[v]
            bx += pv[0]
            by += pv[1]
        elif v in attached:
            bx += attached[v][1]
            by += attached[v][2]
        b += (bx, by)
    b.extend(f for _, _, _, f, _, _ in shape_edges if f is not None)
    return b


def _need(low: float, high: float, lo: float, hi: float, tol: float) -> float:
    """How much longer a length that ranges over [low, high] had to be to meet its class
    [lo, hi] and be positive (tol: the least positive length): negative when shorter."""
    return max(lo, tol) - high if low <= hi else hi - low


def _segments_meet(segs, others, clr: float) -> bool:
    """Whether two segments (of `segs` among themselves when `others` is None, else one of
    each) come within `clr` of each other, but where they share an end. Boxes first, since
    most candidates are far: boxes farther apart than the clearance hold no closer pair."""
    for k, (v, w, a, c, lx, ly, hx, hy) in enumerate(segs):
        for v2, w2, a2, c2, lx2, ly2, hx2, hy2 in segs[k + 1:] if others is None else others:
            if v2 == v or v2 == w or w2 == v or w2 == w:
                continue
            if lx > hx2 or lx2 > hx or ly > hy2 or ly2 > hy:
                continue
            if seg_distance(a, c, a2, c2) < clr:
                return True
    return False


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
