"""Canonical forms of graphs of primitive instances (companion §2: a hierarchy without duplicates).

A graph here is plain data: `labels[v]`, the primitive of vertex v; `edges`, glued slot pairs
(v, i, w, j); and, for a graph with open slots, its cyclic boundary as `gaps`, (open slot,
turns after it) pairs. A primitive fixes the cyclic order of its vertex's slots, so once one
vertex of a connected graph is fixed, a breadth-first walk over slots in ring order numbers
every other vertex in one way only. The least encoding over all starting vertices (of the least
primitive present) is a canonical form: two graphs get the same key exactly when they are
isomorphic as labelled planar graphs with the same rotation system and the same boundary.
"""

from __future__ import annotations

from typing import Sequence

Slot = tuple[int, int]
Edge = tuple[int, int, int, int]
Key = tuple


def _partners(n: int, edges: Sequence[Edge]) -> list[dict[int, Slot]]:
    out: list[dict[int, Slot]] = [{} for _ in range(n)]
    for v, i, w, j in edges:
        out[v][i] = (w, j)
        out[w][j] = (v, i)
    return out


def _encode(labels: Sequence[int], part, start: int, ring_len) -> tuple[Key, dict[int, int]]:
    order = [start]
    num = {start: 0}
    enc: list = []
    k = 0
    while k < len(order):
        v = order[k]
        k += 1
        p = labels[v]
        enc.append(p)
        for i in range(ring_len[p]):
            q = part[v].get(i)
            if q is None:
                enc.append(-1)
                continue
            w, j = q
            if w not in num:
                num[w] = len(order)
                order.append(w)
            enc.append(num[w] * 64 + j)
    return tuple(enc), num


def canonical_key(labels: Sequence[int], edges: Sequence[Edge], ring_len: Sequence[int],
                  gaps: Sequence[tuple[Slot, int]] = ()) -> Key:
    """Key of a connected graph; equal keys mean the same graph up to renumbering vertices.
    `ring_len[p]` is the number of slots of primitive p."""
    if not labels:
        return ()
    part = _partners(len(labels), edges)
    least = min(labels)
    best = None
    for start, p in enumerate(labels):
        if p != least:
            continue
        enc, num = _encode(labels, part, start, ring_len)
        if best is not None and enc > best[0]:
            continue
        renumbered = [((num[v], i), n) for (v, i), n in gaps]
        if renumbered:
            r = renumbered.index(min(renumbered))
            renumbered = renumbered[r:] + renumbered[:r]
        cand = (enc, tuple(renumbered))
        if best is None or cand < best:
            best = cand
    return best
