"""Graphs of primitive instances with boundary strings, and the two gluing operations (§4.2).

A `Graph` is connected while it lives in the hierarchy. Its boundary is kept in the gap form of
grammar_lang.boundary, over slots: the open slots in counter-clockwise order, each with the net
number of turns (∧ minus ∨) that follow it before the next open slot. Gaps are the reduced form
of a boundary string, so the string rewrite rules of §4.2 become small arithmetic on them:

- loop gluing of consecutive `a ā` (no turn between) or `ā ∨ a` (one ∨ between) removes both
  slots and adds their turns to the gap before them (companion §3.1: only consecutive slots);
- branch gluing replaces the open `a` by `B∨`, or `ā` by `∨B`, where B is the other graph's
  walk after its glued slot.
"""

from __future__ import annotations

import bisect
from collections import Counter
from dataclasses import dataclass, field
from typing import Callable, Iterator, Sequence

from grammar_lang import boundary as bd
from grammar_lang.graph import Side

Slot = tuple[int, int]
Edge = tuple[int, int, int, int]


@dataclass(frozen=True)
class Graph:
    verts: tuple[int, ...]        # primitive index of each vertex
    edges: tuple[Edge, ...]       # glued slot pairs (v, i, w, j), (v, i) < (w, j), sorted
    gaps: bd.Gaps                 # cyclic boundary: (open slot, turns after it)
    # The blocks glued, in order: each instance takes the next len(block.verts) vertices. Any
    # one way of building the graph will do, so this is not part of its identity.
    units: tuple[int, ...] = field(default=(), compare=False)

    @property
    def n_half(self) -> int:
        return len(self.gaps)

    @property
    def is_complete(self) -> bool:
        return not self.gaps and bool(self.verts)

    @property
    def prim_counts(self) -> Counter:
        """How many vertices of each primitive: a graph holds another only if it has as many
        of each, a test many left sides fail. Kept once asked for (the graph is immutable; by
        hand, as functools.cached_property takes a lock on every first use)."""
        counts = self.__dict__.get("_prim_counts")
        if counts is None:
            counts = self.__dict__["_prim_counts"] = Counter(self.verts)
        return counts

    @property
    def edge_counts(self) -> Counter:
        """How many glued edges of each kind (the primitives and slots at its two ends, in
        one order): a graph holds another only if it has as many of each, which rejects
        most of the left sides that pass the primitive counts. Kept once asked for."""
        counts = self.__dict__.get("_edge_counts")
        if counts is None:
            vs = self.verts
            counts = self.__dict__["_edge_counts"] = Counter(
                min((vs[v], i, vs[w], j), (vs[w], j, vs[v], i)) for v, i, w, j in self.edges)
        return counts

    def tokens(self, rings: Sequence[Sequence[int]]) -> bd.Gaps:
        """The boundary in gap form over tokens: (half-edge token, turns after it) pairs."""
        return tuple((rings[self.verts[v]][i], n) for (v, i), n in self.gaps)

    def string(self, rings: Sequence[Sequence[int]]) -> bd.Tokens:
        return bd.from_gaps(self.tokens(rings), complete=bool(self.verts))

    def side(self) -> Side:
        return Side(self.verts, self.edges, bd.from_gaps(self.gaps, complete=bool(self.verts)))


def primitive_graph(prim: int, ring_len: int) -> Graph:
    gaps = tuple(((0, i), 1 if i == ring_len - 1 else 0) for i in range(ring_len))
    return Graph((prim,), (), gaps, (prim,))


def _after(gaps: bd.Gaps, slot: Slot) -> tuple[int, bd.Gaps]:
    """The turns after open slot `slot`, and the other gaps in boundary order from there."""
    k = [s for s, _ in gaps].index(slot)
    return gaps[k][1], gaps[k + 1:] + gaps[:k]


def branch_glue(g: Graph, s: Slot, h: Graph, t: Slot, rings, unit: int | None = None) -> Graph:
    """Glue open slot `s` of `g` to open slot `t` of `h` (disjoint graphs, opposite tokens);
    `unit` names h when it is a block glued whole."""
    off = len(g.verts)
    # In string form the open `a` becomes B∨ and `ā` becomes ∨B, B being h's walk after t:
    # in gap form, h's other gaps then g's, with h's turns after t and the ∨ added around.
    m0, h_rest = _after(h.gaps, t)
    n_s, g_rest = _after(g.gaps, s)
    gaps = [((v + off, i), n) for (v, i), n in h_rest]
    gaps += g_rest
    if gaps:
        barred = bd.is_bar(rings[g.verts[s[0]]][s[1]])
        lead, mid = (m0 - 1, n_s) if barred else (m0, n_s - 1)
        # The turns before B wrap round to the last gap; those after it end B's last gap.
        for k, more in ((-1, lead), (len(h_rest) - 1 if h_rest else -1, mid)):
            gaps[k] = (gaps[k][0], gaps[k][1] + more)
    edges = list(g.edges)
    edges += [(v + off, i, w + off, j) for v, i, w, j in h.edges]
    bisect.insort(edges, (s[0], s[1], t[0] + off, t[1]))   # both parts were sorted, h's last
    units = g.units + ((unit,) if unit is not None else h.units)
    return Graph(g.verts + h.verts, tuple(edges), tuple(gaps), units)


def loop_gluable(g: Graph, k: int, rings) -> bool:
    """Whether the k-th open slot can be loop glued to the next one."""
    m = len(g.gaps)
    if m < 2:
        return False
    (s1, n1), (s2, _) = g.gaps[k], g.gaps[(k + 1) % m]
    t1, t2 = rings[g.verts[s1[0]]][s1[1]], rings[g.verts[s2[0]]][s2[1]]
    if t2 != bd.opposite(t1):
        return False
    return n1 == (-1 if bd.is_bar(t1) else 0)


def loop_glue(g: Graph, k: int) -> Graph:
    m = len(g.gaps)
    (s1, n1), (s2, n2) = g.gaps[k], g.gaps[(k + 1) % m]
    a, b = sorted((s1, s2))
    edges = tuple(sorted(g.edges + ((a[0], a[1], b[0], b[1]),)))
    if m == 2:
        return Graph(g.verts, edges, (), g.units)
    gaps = list(g.gaps)
    p = (k - 1) % m
    gaps[p] = (gaps[p][0], gaps[p][1] + n1 + n2)
    rest = [gp for idx, gp in enumerate(gaps) if idx not in (k, (k + 1) % m)]
    return Graph(g.verts, edges, tuple(rest), g.units)


def children(g: Graph, blocks: Sequence[Graph], rings, allow_loops: bool = True,
             by_token: dict[int, list[tuple[int, Slot]]] | None = None,
             admit: Callable[[Slot, int, Slot], bool] | None = None,
             ) -> Iterator[tuple[str, Graph, tuple[int, ...]]]:
    """Every graph one gluing away from `g`: loop gluings of consecutive open slots, then branch
    gluings of each open slot with each block (only those `admit(slot, block, block slot)`
    lets through, when given: a filter that is cheaper than building the child). Yields (kind,
    child, new vertex ids)."""
    if allow_loops:
        for k in range(len(g.gaps)):
            if loop_gluable(g, k, rings):
                s = g.gaps[k][0]
                yield "loop", loop_glue(g, k), (s[0],)
    if by_token is None:
        by_token = block_slots(blocks, rings)
    n = len(g.verts)
    for s, _ in g.gaps:
        want = bd.opposite(rings[g.verts[s[0]]][s[1]])
        for b, t in by_token.get(want, ()):
            if admit is not None and not admit(s, b, t):
                continue
            h = blocks[b]
            yield ("branch", branch_glue(g, s, h, t, rings, b),
                   tuple(range(n, n + len(h.verts))))


def unit_places(g: Graph, sizes: Sequence[int]) -> list[tuple[int, int]] | None:
    """For each vertex of g: (its unit instance, that instance's first vertex); None when g's
    units are unknown."""
    out: list[tuple[int, int]] = []
    for k, u in enumerate(g.units):
        if u >= len(sizes):
            return None
        base = len(out)
        out.extend((k, base) for _ in range(sizes[u]))
    return out if len(out) == len(g.verts) else None


def block_slots(blocks: Sequence[Graph], rings) -> dict[int, list[tuple[int, Slot]]]:
    """Token → the (block, open slot) pairs carrying it, in block order."""
    out: dict[int, list[tuple[int, Slot]]] = {}
    for b, h in enumerate(blocks):
        for (v, i), _ in h.gaps:
            out.setdefault(rings[h.verts[v]][i], []).append((b, (v, i)))
    return out
