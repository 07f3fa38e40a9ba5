"""The faces of a straight-line drawing, found geometrically (not from its labels).

The boundary cycles come from the kernel's face walk (grammar_lang.algorithms.faces: half-edge
`2e` walks edge `e` from `u` to `v` and `2e + 1` back, each with its face on its left). Each
connected component has one outer cycle (the one with the least signed area: negative, or zero
for a tree); its other cycles bound faces of their own. A component's outer cycle is a hole in
the innermost bounded face of another component that contains it, or in the unbounded face.
The results only mean something for a drawing with no crossings.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely

from grammar_lang.algorithms.components import component_labels
from grammar_lang.algorithms.faces import boundary_cycles, half_ends

UNBOUNDED = 0


@dataclass(frozen=True)
class Face:
    outer: int | None              # the cycle bounding it from outside; None for the unbounded face
    holes: tuple[int, ...]         # outer cycles of the components drawn inside it


@dataclass(frozen=True)
class Faces:
    cycles: tuple[tuple[int, ...], ...]   # half-edges of each boundary cycle, in walk order
    cycle_of: np.ndarray                  # half-edge → its cycle
    area: np.ndarray                      # signed area of each cycle (counter-clockwise > 0)
    component: np.ndarray                 # vertex → connected component
    outer_cycle: tuple[int, ...]          # component → its outer cycle (-1: isolated vertex)
    faces: tuple[Face, ...]               # faces[0] is the unbounded face
    face_of_cycle: np.ndarray             # cycle → the face it bounds (from inside or as a hole)

def compute_faces(xy: np.ndarray, edges: np.ndarray) -> Faces:
    """Faces of the drawing with vertex positions `xy` (n, 2) and `edges` (m, 2) of indices."""
    xy = np.asarray(xy, dtype=float).reshape(-1, 2)
    edges = np.asarray(edges, dtype=np.int64).reshape(-1, 2)
    n, m = len(xy), len(edges)
    cycle_of, cycles = boundary_cycles(xy, edges)
    src, dst = half_ends(edges)
    # About a vertex of the drawing, so far-off drawings keep their precision.
    q = xy - xy[0] if n else xy
    with np.errstate(over="ignore", invalid="ignore"):
        cross = q[src, 0] * q[dst, 1] - q[dst, 0] * q[src, 1]
    area = np.bincount(cycle_of, weights=cross, minlength=len(cycles)) / 2.0 if m else np.zeros(0)

    n_comp, component = component_labels(n, edges)
    outer = np.full(n_comp, -1, dtype=np.int64)
    for c, cyc in enumerate(cycles):
        k = component[src[cyc[0]]]
        if outer[k] < 0 or area[c] < area[outer[k]]:
            outer[k] = c
    is_outer = np.zeros(len(cycles), dtype=bool)
    is_outer[outer[outer >= 0]] = True

    bounded = [c for c in range(len(cycles)) if not is_outer[c]]
    face_of_cycle = np.zeros(len(cycles), dtype=np.int64)
    for f, c in enumerate(bounded, start=1):
        face_of_cycle[c] = f
    holes: list[list[int]] = [[] for _ in range(len(bounded) + 1)]
    container = _containers(xy, cycles, src, area, bounded, component, outer)
    for k in range(n_comp):
        if outer[k] >= 0:
            f = container[k]
            face_of_cycle[outer[k]] = f
            holes[f].append(int(outer[k]))
    faces = (Face(None, tuple(holes[0])),) + tuple(
        Face(c, tuple(holes[f])) for f, c in enumerate(bounded, start=1))
    return Faces(tuple(cycles), cycle_of, area, component, tuple(int(c) for c in outer), faces,
                 face_of_cycle)


def _containers(xy, cycles, src, area, bounded, component, outer) -> list[int]:
    """For each component, the face (index into bounded + 1, or 0) its outer cycle lies in."""
    n_comp = len(outer)
    result = [UNBOUNDED] * n_comp
    if not bounded:
        return result
    # Bounding boxes of the bounded cycles, from their half-edges' start points.
    halves = np.concatenate([cycles[c] for c in bounded])
    starts = np.cumsum([0] + [len(cycles[c]) for c in bounded[:-1]])
    p = xy[src[halves]]
    lo = np.minimum.reduceat(p, starts, axis=0)
    hi = np.maximum.reduceat(p, starts, axis=0)
    tree = shapely.STRtree(shapely.box(lo[:, 0], lo[:, 1], hi[:, 0], hi[:, 1]))
    # One vertex per component stands for it: components meet no other component.
    first = np.full(n_comp, -1, dtype=np.int64)
    first[component[::-1]] = np.arange(len(component))[::-1]
    probes = [k for k in range(n_comp) if outer[k] >= 0]
    points = shapely.points(xy[first[probes]])
    hit_probe, hit_box = tree.query(points, predicate="intersects")
    best: dict[int, tuple[float, int]] = {}
    for pi, bi in zip(hit_probe.tolist(), hit_box.tolist()):
        k, c = probes[pi], bounded[bi]
        if component[src[cycles[c][0]]] == k:
            continue
        if _inside(xy[first[k]], xy[src[list(cycles[c])]]):
            key = (float(area[c]), c)
            if k not in best or key < best[k]:
                best[k] = key
    face_index = {c: f for f, c in enumerate(bounded, start=1)}
    for k, (_, c) in best.items():
        result[k] = face_index[c]
    return result


def _inside(p: np.ndarray, ring: np.ndarray) -> bool:
    """Even-odd point-in-polygon; spikes walked there and back cancel out."""
    x, y = p
    a, b = ring, np.roll(ring, -1, axis=0)
    crosses = (a[:, 1] > y) != (b[:, 1] > y)
    # Horizontal edges divide by zero (never counted: `crosses` is false there); a hostile
    # drawing's coordinates near the float limit overflow to ±inf, which still compares.
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        xs = a[:, 0] + (y - a[:, 1]) * (b[:, 0] - a[:, 0]) / (b[:, 1] - a[:, 1])
    return bool(np.count_nonzero(crosses & (x < xs)) % 2)


def cycle_points(xy: np.ndarray, edges: np.ndarray, cycle: tuple[int, ...]) -> np.ndarray:
    """The positions a cycle walks through: the start vertex of each of its half-edges."""
    hs = np.asarray(cycle, dtype=np.int64)
    return np.asarray(xy, dtype=float)[np.asarray(edges, dtype=np.int64)[hs >> 1, hs & 1]]
