"""Grouping forced vertex combinations (companion §3.3).

When a token `t` is carried by exactly one slot (A, i) of all primitives and its opposite by
exactly one slot (B, j) of another primitive, every A has a B glued at slot i and every B an A at
slot j: the two are one unit. Following such forced pairs between distinct primitives gives
components; a spanning tree of each is glued once into a block, and the hierarchy is built from
blocks instead of primitives.

Forced pairs outside the tree (a component with a cycle) close on the block itself. Following
forced pairs from one instance of A visits instances of B, C, ... and comes back to an instance
of A, as each forced pair is one-to-one; after k rounds it closes. The walk visits distinct
vertices, so it is a simple cycle, and a simple cycle of a complete graph turns exactly once
(each face turns once and the angles round each vertex sum to 360°). The turns round the cycle
are fixed by the labels, the same in every round, so k rounds turn k times as much: k = 1, the
copy of A that the cycle comes back to is the same A. The block closes those cycles by loop
gluing, innermost first; a cycle that still has other open slots inside it is left to the
hierarchy, which must fill its inside before closing it (companion §3.1). Left open, each such
slot would be glued to another copy of the block by the hierarchy, which then grows spirals of
blocks (thousands, for the space station's connector) that no complete graph holds.

(Rigid parts are the case the paper names: it merges them into single units before building
its hierarchy, Table 1. A rigid edge is a label of its own, so its two ends are forced.)
"""

from __future__ import annotations

from typing import Sequence

from grammar_lang import boundary as bd

from .gluing import Graph, Slot, branch_glue, loop_glue, loop_gluable, primitive_graph


def forced_pairs(rings: Sequence[Sequence[int]]) -> list[tuple[int, int, int, int]]:
    carriers: dict[int, list[tuple[int, int]]] = {}
    for p, ring in enumerate(rings):
        for i, t in enumerate(ring):
            carriers.setdefault(t, []).append((p, i))
    out = []
    for t in sorted(carriers):
        if bd.is_bar(t):
            continue
        a, b = carriers[t], carriers.get(bd.opposite(t), [])
        if len(a) == 1 and len(b) == 1 and a[0][0] != b[0][0]:
            out.append((a[0][0], a[0][1], b[0][0], b[0][1]))
    return out


def forced_groups(rings: Sequence[Sequence[int]]) -> list[set[int]]:
    """The primitives joined by forced pairs, as components: a complete graph that holds one
    of a group's primitives holds every one of them."""
    group = {p: {p} for p in range(len(rings))}
    for p, _, q, _ in forced_pairs(rings):
        if group[p] is not group[q]:
            merged = group[p] | group[q]
            for r in merged:
                group[r] = merged
    return list({id(g): g for g in group.values()}.values())


def blocks(rings: Sequence[Sequence[int]], enabled: bool = True,
           loops: bool = True) -> list[Graph]:
    """The blocks the hierarchy is built from, each with its forced cycles closed (unless
    `loops` is off: then no gluing may close a loop)."""
    prims = [primitive_graph(p, len(rings[p])) for p in range(len(rings))]
    if not enabled:
        return prims
    pairs = [(p, (0, i), q, (0, j)) for p, i, q, j in forced_pairs(rings)]
    return merge(prims, pairs, rings, loops)[0]


def merge(parts: Sequence[Graph], pairs: Sequence[tuple[int, Slot, int, Slot]],
          rings, loops: bool = True) -> tuple[list[Graph], list[tuple[int, int]]]:
    """`parts` glued along forced `pairs` (part, open slot, part, open slot): each component
    once, along a spanning tree, with its forced cycles then closed if `loops`; in order of
    each component's first part. Also where each part went: (merged graph, its first vertex
    there)."""
    adj: dict[int, list[tuple[Slot, int, Slot]]] = {p: [] for p in range(len(parts))}
    for p, s, q, t in pairs:
        adj[p].append((s, q, t))
        adj[q].append((t, p, s))
    done: set[int] = set()
    out = []
    place = [(0, 0)] * len(parts)
    for root in range(len(parts)):
        if root in done:
            continue
        g = parts[root]
        where = {root: 0}      # part → the vertex its own vertex 0 became
        queue = [root]
        while queue:
            p = queue.pop(0)
            for s, q, t in sorted(adj[p]):
                if q in where:
                    continue
                where[q] = len(g.verts)
                g = branch_glue(g, (where[p] + s[0], s[1]), parts[q], t, rings)
                queue.append(q)
        done.update(where)
        for p, first in where.items():
            place[p] = (len(out), first)
        cycles = [((where[p] + s[0], s[1]), (where[q] + t[0], t[1]))
                  for p, s, q, t in pairs if p in where and q in where]
        out.append(_close(g, cycles, rings) if loops else g)
    return out, place


def _close(g: Graph, pairs: list[tuple[Slot, Slot]], rings) -> Graph:
    """`g` with each pair of its open slots loop glued, innermost cycle first (a pair whose
    slots are next to each other on the boundary); pairs the tree glued already are skipped."""
    open_slots = {s for s, _ in g.gaps}
    todo = {frozenset(pr) for pr in pairs if open_slots.issuperset(pr)}
    progress = True
    while todo and progress:
        progress = False
        m = len(g.gaps)
        for k in range(m):
            pair = frozenset((g.gaps[k][0], g.gaps[(k + 1) % m][0]))
            if pair in todo and loop_gluable(g, k, rings):
                g, progress = loop_glue(g, k), True
                todo.discard(pair)
                break
    return g
