"""A sample's tests against itself and the drawing: no two vertices coincide, no edges cross
or touch but at a shared end (within the clearance), and in a frame no edge comes within the
gap of a part far from it in the graph. The spatial grid answers which of the drawing's edges
are near. A mixin of `Solver`, whose state it reads."""

from __future__ import annotations

import math

from .rejections import Rejection
from .rounds import Round
from .slides import Slide
from .spatial import Point, seg_distance

# Parts this many edges apart or more in the graph (or not joined at all) keep the gap
# between them (Tables.gap), not just the clearance. In the paper's four examples, vertices
# and edges 3 edges apart come as close as 20 px, and 4 apart no closer than 44 px.
FAR_HOPS = 4


class Planarity:
    """The planarity half of `Solver` (see solver.py for the attributes it uses)."""

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

    def _planar(self, pos: dict[int, Point], edges, rd: Round) -> bool:
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

    def _crowds(self, pos, segs, ignore, rd: Round) -> bool:
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

    def _near_far_part(self, segs, sides, ignore, rd: Round, against=None) -> bool:
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

    def _too_near(self, v, w, a, c, x, y, p, q, rd: Round, side: bool) -> bool:
        """Whether edges v–w (from a to c) and x–y (from p to q) share no end, come within the
        gap, and are far apart: one of them a frame's side, or x and y out of their hood."""
        if x == v or x == w or y == v or y == w or seg_distance(a, c, p, q) >= self.gap:
            return False
        if side:
            return True
        near = self._hood(v, rd) | self._hood(w, rd)
        return x not in near and y not in near

    def _hood(self, v: int, rd: Round) -> frozenset:
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
