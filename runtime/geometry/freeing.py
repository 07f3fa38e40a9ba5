"""Which old vertices a solver round frees when the last one could not place (paper §6.3):
those holding the length that failed, the part beyond it as one unit (slides.py), or a
random neighbour. A mixin of `Solver`, whose state it reads and extends (the round's free
vertices, `slides`, `attached`)."""

from __future__ import annotations

from .slides import NoPart, Slide, sliding_part

# How many layers out from a failed edge `_free_one` looks for vertices to free.
HOPS = 4


class Freeing:
    """The freeing half of `Solver` (see solver.py for the attributes it uses)."""

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
        # The edge runs from v to w along d: beyond w is +d, beyond v is −d.
        tries = [(held, other, sign) for held, other, sign in ((w, v, 1), (v, w, -1))
                 if held not in fs and held not in self.host.pinned]
        hung = {u for x in free for _, (u, _) in self.adjacency(x) if u not in fs} \
            if tries else set()

        def search(far: bool) -> list:
            return [sliding_part(self.host, self.adjacency, self.prim, self._range_now, held,
                                 hung | {other}, d, sign, need, fs, far=far)
                    for held, other, sign in tries]
        found = search(False)
        if (NoPart.HELD in found or NoPart.LARGE in found) \
                and not any(isinstance(s, Slide) for s in found):
            # A search met a vertex that cannot move, or a part too large to move: both ends
            # again, with seams further beyond as well (slides.FAR).
            found = search(True)
        parts = [s for s in found if isinstance(s, Slide)]
        best = min(parts, key=lambda s: len(s.offsets)) if parts else None
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
