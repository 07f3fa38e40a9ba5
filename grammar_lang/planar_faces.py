"""Faces of a noded planar straight-line graph, and point-in-ring tests (winding numbers).

Half-edge 2e runs along edge e from ends[e, 0] to ends[e, 1], half-edge 2e+1 back; each
half-edge has its face on its left. Face 0 is the unbounded face.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

_CHUNK = 1 << 20   # point×segment pairs per numpy batch, to bound memory


def winding(points: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Winding number of each point around the closed chain of segments a[k] → b[k].

    Half-open upward/downward crossing rules make a point on a segment count as if nudged
    consistently to one side, so spikes and touching rings never count twice.
    """
    points = np.asarray(points, dtype=float).reshape(-1, 2)
    out = np.zeros(len(points), dtype=np.int64)
    if len(a) == 0 or len(points) == 0:
        return out
    step = max(1, _CHUNK // len(a))
    for start in range(0, len(points), step):
        p = points[start:start + step, None, :]
        ay, by = a[None, :, 1], b[None, :, 1]
        side = (b[None, :, 0] - a[None, :, 0]) * (p[..., 1] - ay) \
            - (p[..., 0] - a[None, :, 0]) * (by - ay)
        up = (ay <= p[..., 1]) & (by > p[..., 1]) & (side > 0)
        down = (ay > p[..., 1]) & (by <= p[..., 1]) & (side < 0)
        out[start:start + step] = up.sum(axis=1) - down.sum(axis=1)
    return out


@dataclass
class Faces:
    face_of: np.ndarray        # (2m,) face on the left of each half-edge
    count: int                 # faces, including the unbounded face 0
    area: np.ndarray           # (count,) area enclosed by each face's outer boundary (0: inf)


def compute_faces(vertices: np.ndarray, ends: np.ndarray) -> Faces:
    m = len(ends)
    origin = ends.reshape(-1)                 # origin of half-edge h = ends[h // 2, h % 2]
    target = ends[:, ::-1].reshape(-1)
    vec = vertices[target] - vertices[origin]
    angle = np.arctan2(vec[:, 1], vec[:, 0])
    order = np.lexsort((angle, origin))       # half-edges around each vertex, counter-clockwise
    position = np.empty(2 * m, dtype=np.int64)
    position[order] = np.arange(2 * m)
    first = np.searchsorted(origin[order], origin[order], side="left")
    last = np.searchsorted(origin[order], origin[order], side="right")
    # Arriving at v along h, leave by the half-edge just clockwise of h's twin: the face on the
    # left stays on the left.
    twin_pos = position[np.arange(2 * m) ^ 1]
    prev = np.where(twin_pos == first[twin_pos], last[twin_pos] - 1, twin_pos - 1)
    nxt = order[prev]

    cycle = np.full(2 * m, -1, dtype=np.int64)
    cycles = 0
    for h in range(2 * m):
        if cycle[h] >= 0:
            continue
        while cycle[h] < 0:
            cycle[h] = cycles
            h = nxt[h]
        cycles += 1
    p, q = vertices[origin], vertices[target]
    area = np.bincount(cycle, weights=(p[:, 0] * q[:, 1] - q[:, 0] * p[:, 1]) / 2.0,
                       minlength=cycles)

    graph = coo_matrix((np.ones(m), (ends[:, 0], ends[:, 1])),
                       shape=(len(vertices), len(vertices)))
    _, component = connected_components(graph, directed=False)
    cycle_comp = np.zeros(cycles, dtype=np.int64)
    cycle_comp[cycle] = component[origin]
    # Each component's outer boundary is its most negative cycle (minus the sum of the rest).
    comps = np.unique(cycle_comp)
    outer = np.array([np.flatnonzero(cycle_comp == c)[np.argmin(area[cycle_comp == c])]
                      for c in comps])
    is_outer = np.zeros(cycles, dtype=bool)
    is_outer[outer] = True
    inner = np.flatnonzero(~is_outer)
    face_of_cycle = np.zeros(cycles, dtype=np.int64)
    face_of_cycle[inner] = np.arange(1, len(inner) + 1)
    face_area = np.concatenate([[0.0], area[inner]])

    if len(inner):
        lo = np.full((cycles, 2), np.inf)
        hi = np.full((cycles, 2), -np.inf)
        np.minimum.at(lo, cycle, p)
        np.maximum.at(hi, cycle, p)
        for c, oc in zip(comps.tolist(), outer.tolist()):
            probe = p[np.flatnonzero(cycle == oc)[0]]
            cand = inner[(cycle_comp[inner] != c) & np.all(lo[inner] < probe, axis=1)
                         & np.all(hi[inner] > probe, axis=1)]
            best, best_area = 0, np.inf
            for k in cand[np.argsort(area[cand], kind="stable")].tolist():
                hs = np.flatnonzero(cycle == k)
                if winding(probe, p[hs], q[hs])[0] != 0:
                    best, best_area = face_of_cycle[k], area[k]
                    break
            face_of_cycle[oc] = best
    return Faces(face_of_cycle[cycle], len(inner) + 1, face_area)
