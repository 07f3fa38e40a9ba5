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


def _partners(labels: Sequence[int], edges: Sequence[Edge], ring_len) -> list[list]:
    """Each vertex's slots in ring order: the (vertex, slot) glued to it, or None if open."""
    out: list[list] = [[None] * ring_len[p] for p in labels]
    for v, i, w, j in edges:
        out[v][i] = (w, j)
        out[w][j] = (v, i)
    return out


def _encode(labels: Sequence[int], part, start: int) -> tuple[Key, list[int]]:
    order = [start]
    num = [-1] * len(labels)
    num[start] = 0
    enc: list = []
    for v in order:                 # the order grows while it is read
        enc.append(labels[v])
        for q in part[v]:
            if q is None:
                enc.append(-1)
                continue
            w, j = q
            if num[w] < 0:
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
    part = _partners(labels, edges, ring_len)
    least = min(labels)
    best = None
    for start, p in enumerate(labels):
        if p != least:
            continue
        enc, num = _encode(labels, part, start)
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
