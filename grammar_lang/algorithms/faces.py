"""Walking the faces of a straight-line drawing: the rotation system from the geometry, then
its boundary cycles. Written once for the compiler's planarisation (grammar_lang.planar_faces)
and the runtime's face check (runtime.geometry.faces); each adds its own reading of the cycles.

Half-edge `2e` walks edge `e` from `edges[e, 0]` to `edges[e, 1]`, half-edge `2e + 1` back;
every half-edge has its face on its left. Around each vertex the outgoing half-edges are sorted
counter-clockwise by angle (ties by half-edge number); the face to the left of `u→v` continues
at `v` with the outgoing half-edge just clockwise of `v→u`.
"""

from __future__ import annotations

import functools

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


class FaceWalk:
    """The face of a graph of rings that a corner lies in, walked from that corner: at most
    `limit` corners (a random search's bound in a drawing with a huge face).

    `link[v][i]` is the (vertex, slot) glued to slot i of v, or None. Corner (v, i) is the
    sector of v between slot i and the next slot counter-clockwise; the face goes on along
    that next slot's edge, into the corner after the slot it reaches (graph.face_walk's rule,
    on a host instead of a rule side), so it lies on the walk's right. `pos[v]` places v.
    With `until`, the walk stops once it reaches that corner (asked only whether it does)."""

    def __init__(self, link, pos, corner: tuple[int, int], limit: int,
                 until: tuple[int, int] | None = None):
        self.start, self._pos = corner, pos
        walk, c = [], corner
        self.closed = False
        # The slots of `link` are corners already: each step appends one, building no tuple.
        for _ in range(limit):
            walk.append(c)
            if c == until:
                break
            ring = link[c[0]]
            c = ring[(c[1] + 1) % len(ring)]
            if c is None:
                break
            if c == corner:
                self.closed = True
                break
        self.corners = walk
        self.at = set(walk)

    @functools.cached_property
    def vertices(self) -> set:
        """The walk's vertices: made when asked (most walks are decided by their corners)."""
        return {v for v, _ in self.corners}

    @functools.cached_property
    def encloses(self) -> bool:
        """Whether the walk bounds its face from outside: closed, with its face on the right,
        it turns clockwise. One that turns the other way (or encloses nothing: a tree) runs
        round the outside of its structure, a hole in some face. Worked out when asked (a
        splice's walks mostly decide without it)."""
        if not self.closed:
            return False
        area = scale = 0.0
        pts = [self._pos[v] for v, _ in self.corners]
        for (x0, y0), (x1, y1) in zip(pts, pts[1:] + pts[:1]):
            area += x0 * y1 - x1 * y0
            scale += abs(x0 * y1) + abs(x1 * y0)
        return area < -1e-9 * scale

    def shares_face(self, other: "FaceWalk") -> bool | None:
        """Whether the two walks' corners lie in one face: True, False, or None when walks
        cannot tell (a face's holes are walked apart; which hole lies in which face is a
        question for the geometry)."""
        if other.start in self.at or self.start in other.at:
            return True
        if not (self.closed or other.closed):
            return None                 # both cut short: perhaps one walk, longer
        # Two walks. A connected structure meets each face along one walk only, and a face
        # has one walk round it from outside.
        if not self.vertices.isdisjoint(other.vertices) or (self.encloses and other.encloses):
            return False
        return None
