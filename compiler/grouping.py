"""Grouping forced vertex combinations (companion §3.3).

When a token `t` is carried by exactly one slot (A, i) of all primitives and its opposite by
exactly one slot (B, j) of another primitive, every A has a B glued at slot i and every B an A at
slot j: the two are one unit. Following such forced pairs between distinct primitives gives
components; a spanning tree of each is glued once into a block, and the hierarchy is built from
blocks instead of primitives. Forced pairs outside the tree (a component with a cycle) are left
to the hierarchy: the same A may meet a different B instance there, so they are not forced to
close on the block itself.

Rigid parts are the exception (the paper merges them into single units before building its
hierarchy). A rigid edge is a label of its own, so its two ends are primitives with one instance
each, and a cycle of rigid edges has fixed vectors that sum to zero only once around: the copy of
A that B meets is the same A, and the block closes its rigid cycles by loop gluing. Left open,
each such slot would be glued to another copy of the block by the hierarchy, which grows
thousands of spirals of blossoms that no complete graph holds.
"""

from __future__ import annotations

from typing import Collection, Sequence

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


def blocks(rings: Sequence[Sequence[int]], enabled: bool = True,
           rigid: Collection[int] = ()) -> list[Graph]:
    """The blocks the hierarchy is built from; `rigid` are the labels of rigid edges, whose
    cycles each block closes."""
    n = len(rings)
    if not enabled:
        return [primitive_graph(p, len(rings[p])) for p in range(n)]
    pairs = forced_pairs(rings)
    adj: dict[int, list[tuple[int, int, int, int]]] = {p: [] for p in range(n)}
    for p, i, q, j in pairs:
        adj[p].append((p, i, q, j))
        adj[q].append((q, j, p, i))
    closing = [pr for pr in pairs if bd.label_of(rings[pr[0]][pr[1]]) in rigid]
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
        out.append(_close(g, [((where[p], i), (where[q], j)) for p, i, q, j in closing
                              if p in where and q in where], rings))
    return out


def _close(g: Graph, pairs: list[tuple[Slot, Slot]], rings) -> Graph:
    """`g` with each pair of its open slots loop glued, innermost cycle first (a pair whose
    slots are next to each other on the boundary); the tree's own edges are not in `pairs`."""
    todo = {frozenset(pr) for pr in pairs}
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
