"""Walking the faces of a straight-line drawing: the rotation system from the geometry, then
its boundary cycles. Written once for the compiler's planarisation (grammar_lang.planar_faces)
and the runtime's face check (runtime.geometry.faces); each adds its own reading of the cycles.

Half-edge `2e` walks edge `e` from `edges[e, 0]` to `edges[e, 1]`, half-edge `2e + 1` back;
every half-edge has its face on its left. Around each vertex the outgoing half-edges are sorted
counter-clockwise by angle (ties by half-edge number); the face to the left of `u→v` continues
at `v` with the outgoing half-edge just clockwise of `v→u`.
"""

from __future__ import annotations

import numpy as np


def half_ends(edges: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Start and end vertex of every half-edge, for edges given as an (m, 2) index array."""
    src = np.empty(2 * len(edges), dtype=np.int64)
    src[0::2], src[1::2] = edges[:, 0], edges[:, 1]
    dst = np.empty_like(src)
    dst[0::2], dst[1::2] = edges[:, 1], edges[:, 0]
    return src, dst


def next_in_face(xy: np.ndarray, edges: np.ndarray) -> np.ndarray:
    """For each half-edge, the next half-edge along the face on its left."""
    src, dst = half_ends(edges)
    d = xy[dst] - xy[src]
    angle = np.arctan2(d[:, 1], d[:, 0])
    order = np.lexsort((np.arange(len(src)), angle, src))   # by vertex, then angle ccw
    s = src[order]
    start = np.r_[True, s[1:] != s[:-1]]
    end = np.r_[start[1:], True]
    # Each group's last position, spread back over the group.
    last = np.flatnonzero(end)
    group_end = np.repeat(last, np.diff(np.r_[-1, last]))
    pos = np.arange(len(s))
    prev_pos = np.where(start, group_end, pos - 1)
    clockwise = np.empty_like(src)
    clockwise[order] = order[prev_pos]
    twin = np.arange(len(src)) ^ 1
    return clockwise[twin]


def boundary_cycles(xy: np.ndarray, edges: np.ndarray
                    ) -> tuple[np.ndarray, list[tuple[int, ...]]]:
    """Each half-edge's boundary cycle, and the half-edges of each cycle in walk order; cycles
    are numbered in the order of their smallest half-edge."""
    m = len(edges)
    nxt = next_in_face(xy, edges).tolist() if m else []
    cycle_of = [-1] * (2 * m)
    cycles: list[tuple[int, ...]] = []
    for h0 in range(2 * m):
        if cycle_of[h0] >= 0:
            continue
        walk, h = [], h0
        while cycle_of[h] < 0:
            cycle_of[h] = len(cycles)
            walk.append(h)
            h = nxt[h]
        cycles.append(tuple(walk))
    return np.array(cycle_of, dtype=np.int64), cycles
