"""Finding a rule's left side inside a bigger graph (the match m: L → G of §5, Fig. 7).

Primitives fix rotation systems, so a match of a connected L is fixed by where one vertex of L
goes: every other vertex is reached over L's edges, slot by slot. Open slots of L may be open or
glued to anything in G outside the match (they are the interface), so the dangling condition
holds by construction. Open slots of L glued to each other in G are fine, except where the
right side joins them by bare wires into a closed loop with no vertex: that is no graph, and no
starter builds it back, so such a placement is not a match (else the complete hollow house
"reduces" to ∅ through such a loop and never gets a starter).

The walk is the kernel's (grammar_lang.algorithms.matching); the bare-loop test is the
feasibility hook this module gives it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Iterator, Sequence

from grammar_lang.algorithms.matching import WalkPlans, anchored_matches

from .gluing import Edge, Graph

@dataclass(frozen=True)
class Pattern:
    """A connected graph prepared for matching from each of its vertices."""

    graph: Graph
    plans: WalkPlans                           # the walk from each anchor vertex (kernel)
    opens: tuple[tuple[int, int], ...] = ()    # open slots, in boundary order
    wires: tuple[tuple[int, int], ...] = ()    # open-slot index pairs the right side wires together

    @staticmethod
    def of(g: Graph, wires: Sequence[tuple[int, int]] = ()) -> "Pattern":
        partner = {}
        for v, i, w, j in g.edges:
            partner[(v, i)], partner[(w, j)] = (w, j), (v, i)
        return Pattern(g, WalkPlans(partner),
                       tuple(slot for slot, _ in g.gaps), tuple(sorted(wires)))


class Slots(dict):
    """A host vertex's glued slots: slot → partner; an open slot reads as None."""

    def __missing__(self, slot: int) -> None:
        return None


class Host:
    """A mutable graph to search in: primitive per vertex (None when deleted) and partners."""

    def __init__(self, verts: Sequence[int], edges: Sequence[Edge]):
        self.verts: list[int | None] = list(verts)
        self.part: list[Slots] = [Slots() for _ in verts]
        for v, i, w, j in edges:
            self.part[v][i] = (w, j)
            self.part[w][j] = (v, i)
        self.by_prim: dict[int, set[int]] = {}
        for v, p in enumerate(verts):
            self.by_prim.setdefault(p, set()).add(v)

    def add_vertex(self, p: int) -> int:
        self.verts.append(p)
        self.part.append(Slots())
        self.by_prim.setdefault(p, set()).add(len(self.verts) - 1)
        return len(self.verts) - 1

    def remove_vertex(self, v: int) -> None:
        for i, (w, j) in list(self.part[v].items()):
            if w != v:
                self.part[w].pop(j, None)
        self.part[v] = Slots()
        self.by_prim[self.verts[v]].discard(v)
        self.verts[v] = None

    def glue(self, a: tuple[int, int], b: tuple[int, int]) -> None:
        self.part[a[0]][a[1]] = b
        self.part[b[0]][b[1]] = a

    def live(self) -> list[int]:
        return [v for v, p in enumerate(self.verts) if p is not None]


def matches(pat: Pattern, host: Host, anchors: Sequence[int] | None = None
            ) -> Iterator[list[int]]:
    """Every injective placement of the pattern's vertices in the host (a list: pattern vertex →
    host vertex). With `anchors`, only placements that use one of those host vertices."""
    g = pat.graph
    if anchors is None:
        roots = [(0, h) for h in sorted(host.by_prim.get(g.verts[0], ()))]
    else:
        roots = [(r, h) for h in anchors for r in range(len(g.verts))
                 if host.verts[h] == g.verts[r]]
    feasible = (lambda img: not _bare_loop(pat, host, img)) if pat.wires else None
    yield from anchored_matches(host.part, host.verts, g.verts, pat.plans, roots, feasible)


def _bare_loop(pat: Pattern, host: Host, img: list[int]) -> bool:
    """Whether wires of the right side and edges of G between open slots of L close a loop."""
    index = {(img[v], i): k for k, (v, i) in enumerate(pat.opens)}
    inner = {}
    for k, (v, i) in enumerate(pat.opens):
        q = host.part[img[v]].get(i)
        if q is not None and q in index:
            inner[k] = index[q]
    partner = {}
    for a, b in pat.wires:
        partner[a], partner[b] = b, a
    for start in sorted(partner):
        cur = start
        for _ in range(len(pat.opens)):
            nxt = partner.get(cur)
            if nxt is None or nxt not in inner:
                break
            cur = inner[nxt]
            if cur == start:
                return True
    return False


def contains(pat: Pattern, host: Host, anchors: Sequence[int] | None = None) -> bool:
    return next(matches(pat, host, anchors), None) is not None
