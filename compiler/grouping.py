"""Grouping forced vertex combinations (companion §3.3).

When a token `t` is carried by exactly one slot (A, i) of all primitives and its opposite by
exactly one slot (B, j) of another primitive, every A has a B glued at slot i and every B an A at
slot j: the two are one unit. Following such forced pairs between distinct primitives gives
components; a spanning tree of each is glued once into a block, and the hierarchy is built from
blocks instead of primitives. Forced pairs outside the tree (a component with a cycle) are left
to the hierarchy: the same A may meet a different B instance there, so they are not forced to
close on the block itself.
"""

from __future__ import annotations

from typing import Sequence

from grammar_lang import boundary as bd

from .gluing import Graph, branch_glue, primitive_graph


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


def blocks(rings: Sequence[Sequence[int]], enabled: bool = True) -> list[Graph]:
    n = len(rings)
    if not enabled:
        return [primitive_graph(p, len(rings[p])) for p in range(n)]
    adj: dict[int, list[tuple[int, int, int, int]]] = {p: [] for p in range(n)}
    for p, i, q, j in forced_pairs(rings):
        adj[p].append((p, i, q, j))
        adj[q].append((q, j, p, i))
    done: set[int] = set()
    out = []
    for root in range(n):
        if root in done:
            continue
        g = primitive_graph(root, len(rings[root]))
        where = {root: 0}
        queue = [root]
        while queue:
            p = queue.pop(0)
            for _, i, q, j in sorted(adj[p]):
                if q in where:
                    continue
                where[q] = len(g.verts)
                g = branch_glue(g, (where[p], i), primitive_graph(q, len(rings[q])), (0, j), rings)
                queue.append(q)
        done.update(where)
        out.append(g)
    return out
