"""Anchored matching of a rule side in a host graph (paper §6.1), for the compiler's
verification (compiler.occurrence) and the runtime's engine (runtime.engine.matching).

A vertex's primitive fixes its whole ring, so once one pattern vertex is mapped to a host
vertex of the same primitive, following the pattern's glued slots through the host's links maps
every other vertex of its component, or fails, in time linear in the pattern. A host is read
through two indexables: `link[v][i]`, the (vertex, slot) glued to slot i of v or None, and
`prim[v]`, v's primitive. Whether a complete placement is a match beyond that (the runtime's
dangling condition, the compiler's bare-loop test) is the caller's feasibility hook.

The runtime's search over spliced sides (several components and wires, found along the host
faces they share, `faces.corners`, or near each other through its spatial grid, with a budget)
is a layer over `extend`; it stays in the runtime because the grid is the drawing's geometry.
"""

from __future__ import annotations

from typing import Callable, Iterable, Iterator, Mapping, Sequence

Slot = tuple[int, int]
Step = tuple[int, int, int, int]       # from mapped u follow slot i to (w, j): w a w-primitive


def walk_plans(vertices: Iterable[int], partner: Mapping[Slot, Slot]
               ) -> tuple[tuple[Step, ...], ...]:
    """For each vertex of a connected pattern taken as the anchor, the breadth-first walk that
    maps the rest: every glued slot pair once, a vertex's slots in ring order."""
    plans = WalkPlans(partner)
    return tuple(plans[anchor] for anchor in vertices)


class WalkPlans:
    """`walk_plans` worked out for each anchor on first use: a big pattern (an example's
    component) is mostly matched from few of its vertices, and each plan costs its size."""

    def __init__(self, partner: Mapping[Slot, Slot]):
        self.partner = partner
        self.slots: dict[int, list[int]] = {}
        for v, i in sorted(partner):
            self.slots.setdefault(v, []).append(i)
        self._plans: dict[int, tuple[Step, ...]] = {}

    def __getitem__(self, anchor: int) -> tuple[Step, ...]:
        if anchor not in self._plans:
            self._plans[anchor] = self._walk(anchor)
        return self._plans[anchor]

    def _walk(self, anchor: int) -> tuple[Step, ...]:
        steps: list[Step] = []
        seen, queue, done = {anchor}, [anchor], set()
        for u in queue:                        # the queue grows while it is read
            for i in self.slots.get(u, ()):
                s = self.partner[(u, i)]
                key = min((u, i), s)
                if key in done:
                    continue
                done.add(key)
                steps.append((u, i, s[0], s[1]))
                if s[0] not in seen:
                    seen.add(s[0])
                    queue.append(s[0])
        return tuple(steps)


def extend(link, prim, want: Sequence[int], steps: Sequence[Step], anchor: int, h: int,
           vmap: dict[int, int]) -> bool:
    """Map pattern vertex `anchor` to host vertex `h` and walk `steps` from it, adding to
    `vmap` (pattern → host, injective); False as soon as the host disagrees."""
    if prim[h] != want[anchor] or h in vmap.values():
        return False
    vmap[anchor] = h
    used = set(vmap.values())
    for u, i, w, j in steps:
        s = link[vmap[u]][i]
        if s is None or s[1] != j:
            return False
        x = s[0]
        if w in vmap:
            if vmap[w] != x:
                return False
        else:
            if prim[x] != want[w] or x in used:
                return False
            vmap[w] = x
            used.add(x)
    return True


def anchored_matches(link, prim, want: Sequence[int],
                     plans: Sequence[Sequence[Step]] | WalkPlans,
                     roots: Iterable[tuple[int, int]],
                     feasible: Callable[[list[int]], bool] | None = None
                     ) -> Iterator[list[int]]:
    """The placements (pattern vertex → host vertex) of a connected pattern that map pattern
    vertex r to host vertex h, for each (r, h) of `roots` in turn, and pass `feasible`."""
    for r, h in roots:
        vmap: dict[int, int] = {}
        if not extend(link, prim, want, plans[r], r, h, vmap):
            continue
        img = [vmap[v] for v in range(len(want))]
        if feasible is None or feasible(img):
            yield img
