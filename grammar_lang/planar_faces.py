"""Faces of a noded planar straight-line graph, and point-in-ring tests (winding numbers).

Half-edge 2e runs along edge e from ends[e, 0] to ends[e, 1], half-edge 2e+1 back; each
half-edge has its face on its left (the walk is the kernel's, grammar_lang.algorithms.faces).
Face 0 is the unbounded face.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely

from .algorithms.components import component_labels
from .algorithms.faces import boundary_cycles, half_ends

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
    origin, target = half_ends(ends)
    cycle, walks = boundary_cycles(vertices, ends)
    cycles = len(walks)
    p, q = vertices[origin], vertices[target]
    area = np.bincount(cycle, weights=(p[:, 0] * q[:, 1] - q[:, 0] * p[:, 1]) / 2.0,
                       minlength=cycles)

    _, component = component_labels(len(vertices), ends)
    cycle_comp = np.zeros(cycles, dtype=np.int64)
    cycle_comp[cycle] = component[origin]
    # Each component's outer boundary is its most negative cycle (minus the sum of the rest).
    by_comp = np.lexsort((area, cycle_comp))
    comps, first_of = np.unique(cycle_comp[by_comp], return_index=True)
    outer = by_comp[first_of]
    is_outer = np.zeros(cycles, dtype=bool)
    is_outer[outer] = True
    inner = np.flatnonzero(~is_outer)
    face_of_cycle = np.zeros(cycles, dtype=np.int64)
    face_of_cycle[inner] = np.arange(1, len(inner) + 1)
    face_area = np.concatenate([[0.0], area[inner]])
    if len(inner) and len(comps) > 1:
        face_of_cycle[outer] = _enclosing_faces(p, q, cycle, area, cycle_comp, comps, outer,
                                                inner, face_of_cycle)
    return Faces(face_of_cycle[cycle], len(inner) + 1, face_area)


def _enclosing_faces(p, q, cycle, area, cycle_comp, comps, outer, inner, face_of_cycle):
    """The face each component sits in: the smallest other component's face around it."""
    by_cycle = np.argsort(cycle, kind="stable")
    starts = np.searchsorted(cycle[by_cycle], np.arange(len(area) + 1))
    probes = p[by_cycle[starts[outer]]]               # a vertex of each component
    lo = np.full((len(area), 2), np.inf)
    hi = np.full((len(area), 2), -np.inf)
    np.minimum.at(lo, cycle, p)
    np.maximum.at(hi, cycle, p)
    boxes = shapely.box(lo[inner, 0], lo[inner, 1], hi[inner, 0], hi[inner, 1])
    probe, k = shapely.STRtree(boxes).query(shapely.points(probes))
    other = cycle_comp[inner[k]] != comps[probe]
    probe, k = probe[other], k[other]
    inside = np.zeros(len(probe), dtype=bool)
    order = np.argsort(k, kind="stable")
    probe, k = probe[order], k[order]
    group = np.searchsorted(k, np.arange(len(inner) + 1))
    for j in np.unique(k).tolist():
        rows = slice(group[j], group[j + 1])
        hs = by_cycle[starts[inner[j]]:starts[inner[j] + 1]]
        inside[rows] = winding(probes[probe[rows]], p[hs], q[hs]) != 0
    probe, k = probe[inside], k[inside]
    enclosing = np.zeros(len(outer), dtype=np.int64)
    if len(probe):
        smallest = np.lexsort((area[inner[k]], probe))
        found, first = np.unique(probe[smallest], return_index=True)
        enclosing[found] = face_of_cycle[inner[k[smallest[first]]]]
    return enclosing
