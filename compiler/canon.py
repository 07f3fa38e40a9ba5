"""Canonical forms of graphs of primitive instances (companion §2: a hierarchy without duplicates).

A primitive fixes the cyclic order of its vertex's half-edges, so once one vertex of a connected
graph is fixed, a breadth-first walk over slots in ring order numbers every other vertex in one
way only. The least encoding over all starting vertices (of the least primitive present) is a
canonical form: two graphs get the same key exactly when they are isomorphic as labelled planar
graphs with the same rotation system and the same boundary.
"""

from __future__ import annotations

from typing import Sequence

from grammar_lang.algorithms.components import glued_components

from .gluing import Edge, Graph

Key = tuple


def _partners(n: int, edges: Sequence[Edge]) -> list[dict[int, tuple[int, int]]]:
    out: list[dict[int, tuple[int, int]]] = [{} for _ in range(n)]
    for v, i, w, j in edges:
        out[v][i] = (w, j)
        out[w][j] = (v, i)
    return out


def _encode(g: Graph, part, start: int, ring_len) -> tuple[Key, dict[int, int]]:
    order = [start]
    num = {start: 0}
    enc: list = []
    k = 0
    while k < len(order):
        v = order[k]
        k += 1
        p = g.verts[v]
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


def canonical_key(g: Graph, ring_len: Sequence[int]) -> Key:
    """Key of a connected graph; equal keys mean the same graph up to renumbering vertices."""
    if not g.verts:
        return ()
    part = _partners(len(g.verts), g.edges)
    least = min(g.verts)
    best = None
    for start, p in enumerate(g.verts):
        if p != least:
            continue
        enc, num = _encode(g, part, start, ring_len)
        if best is not None and enc > best[0]:
            continue
        gaps = [((num[v], i), n) for (v, i), n in g.gaps]
        if gaps:
            r = gaps.index(min(gaps))
            gaps = gaps[r:] + gaps[:r]
        cand = (enc, tuple(gaps))
        if best is None or cand < best:
            best = cand
    return best


def split(verts: Sequence[int], edges: Sequence[Edge]) -> list[Graph]:
    """The connected components of a complete (boundary-free) graph, each renumbered from 0."""
    comps = glued_components(range(len(verts)), edges)
    where: dict[int, tuple[int, int]] = {}      # vertex → (its component, its new number)
    for c, comp in enumerate(comps):
        for k, v in enumerate(comp):
            where[v] = (c, k)
    local: list[list[Edge]] = [[] for _ in comps]   # each edge filed once: linear, not n × m
    for v, i, w, j in edges:
        c, a = where[v]
        local[c].append((a, i, where[w][1], j))
    return [Graph(tuple(verts[v] for v in comp), tuple(sorted(es)), ())
            for comp, es in zip(comps, local)]


