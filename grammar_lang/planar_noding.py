"""Snap-merging and noding of segments: the first half of building a planar graph.

Points closer than the merge distance become one vertex, vertices closer than it to a segment
split that segment (hand-drawn T-junctions), and crossing segments are split at their crossing.
Each output piece remembers which input segments it came from and in which direction, so the
planar builder can attribute labels, classes and places to it. shapely's own noding cannot
keep that attribution or snap with a tolerance, so this uses shapely only as a spatial index.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely

from .algorithms.components import component_labels

MAX_ROUNDS = 32
CROSSING_BLOCK = 512     # segments per crossing query: bounds the pairs held at once
SNAP_ROUNDS = 8


class TooManyCrossings(Exception):
    def __init__(self, count: int):
        super().__init__(f"{count} crossings")
        self.count = count


class NodingError(Exception):
    """The geometry kept producing new splits: near-degenerate input at this merge distance."""


@dataclass
class Pieces:
    """Non-crossing segments between distinct vertices, each with its sources.

    `sources[i]` lists (source id, forward) pairs: forward when the source runs from
    `ends[i, 0]` to `ends[i, 1]`. `is_input[v]` tells whether vertex v is (a merge of) input
    points rather than a crossing found by noding.
    """

    vertices: np.ndarray          # (n, 2) float
    ends: np.ndarray              # (m, 2) int, ends[i, 0] < ends[i, 1]
    sources: list[list[tuple[int, bool]]]
    is_input: np.ndarray          # (n,) bool


def cluster(points: np.ndarray, distance: float) -> tuple[np.ndarray, np.ndarray]:
    """Merge points closer than `distance` (transitively) → (centres, index of each point).

    Centres are means of their members, so a point drawn several times weighs more than a
    stray one. Re-run until no two centres are within `distance` of each other.
    """
    index = np.arange(len(points))
    centres = np.asarray(points, dtype=float)
    for _ in range(MAX_ROUNDS):
        if len(centres) < 2:
            break
        pairs = _pairs_within(centres, distance)
        if len(pairs) == 0:
            break
        n = len(centres)
        count, labels = component_labels(n, pairs)
        weights = np.bincount(index, minlength=n).astype(float)
        sums = np.zeros((count, 2))
        np.add.at(sums, labels, centres * weights[:, None])
        totals = np.bincount(labels, weights=weights, minlength=count)
        centres = sums / totals[:, None]
        index = labels[index]
    return centres, index


def _pairs_within(points: np.ndarray, distance: float) -> np.ndarray:
    """(k, 2) pairs i < j of points at most `distance` apart. Shapely's tree, already loaded
    for the segments, spares the import of scipy.spatial (a third of a second per process)."""
    geoms = shapely.points(points)
    i, j = shapely.STRtree(geoms).query(geoms, predicate="dwithin", distance=distance)
    keep = i < j
    return np.stack([i[keep], j[keep]], axis=1)


def _nearest_within(vertices: np.ndarray, queries: np.ndarray, bound: float) -> np.ndarray:
    """For each query point, its nearest vertex closer than `bound`, or -1."""
    out = np.full(len(queries), -1, dtype=np.int64)
    if len(vertices) == 0 or len(queries) == 0:
        return out
    (qi, vi), dist = shapely.STRtree(shapely.points(vertices)).query_nearest(
        shapely.points(queries), max_distance=bound, return_distance=True, all_matches=False)
    keep = dist < bound
    out[qi[keep]] = vi[keep]
    return out


def node(vertices: np.ndarray, ends: np.ndarray, source_ids: np.ndarray,
         distance: float, max_vertices: int | None = None) -> Pieces:
    """Split segments (pairs of vertex indices) at crossings and near vertices, dedupe overlaps.
    More crossings than `max_vertices` leaves room for raise `TooManyCrossings`.

    `vertices` must already be merged (no two closer than `distance`). The first round snaps
    with the full merge distance; later rounds, which only mop up crossings the bending
    created, route crossings through near vertices for a few rounds and then only split where
    geometry really meets, so that snapping cannot oscillate.
    """
    vertices = np.asarray(vertices, dtype=float)
    is_input = np.ones(len(vertices), dtype=bool)
    ends = np.asarray(ends, dtype=np.int64).reshape(-1, 2)
    sources: list[list[tuple[int, bool]]] = [[(int(s), True)] for s in source_ids]
    ends, sources = _dedupe(ends, sources)
    extent = np.ptp(vertices, axis=0).max() if len(vertices) else 0.0
    exact = 1e-9 * max(float(extent), 1.0)
    for round_ in range(MAX_ROUNDS):
        if len(ends) == 0:
            break
        near = max(distance, exact) if round_ == 0 else exact
        snap = max(distance, exact) if round_ < SNAP_ROUNDS else exact
        room = None if max_vertices is None else max(0, max_vertices - len(vertices))
        splits, new_points = _find_splits(vertices, ends, near, snap, room)
        if not splits:
            return Pieces(vertices, ends, sources, is_input)
        if len(new_points):
            centres, index = cluster(np.asarray(new_points), snap)
            # A cluster of crossings that lands near a vertex is that vertex.
            target = _nearest_within(vertices, centres, snap)
            fresh = np.flatnonzero(target < 0)
            target[fresh] = len(vertices) + np.arange(len(fresh))
            vertices = np.vstack([vertices, centres[fresh]])
            is_input = np.concatenate([is_input, np.zeros(len(fresh), dtype=bool)])
            splits = {seg: [v if v >= 0 else int(target[index[-v - 1]]) for v in vs]
                      for seg, vs in splits.items()}
        ends, sources = _split(vertices, ends, sources, splits)
        ends, sources = _dedupe(ends, sources)
    else:
        raise NodingError("noding did not converge")
    return Pieces(vertices, ends, sources, is_input)


def _find_splits(vertices: np.ndarray, ends: np.ndarray, near: float, snap: float,
                 max_crossings: int | None = None):
    """{segment: [vertex ids to route it through]} and new crossing points (ids -1, -2, …).

    A vertex within `near` of a segment's interior splits it (T-junctions, overlaps); a
    crossing within `snap` of a vertex routes both segments through that vertex.
    """
    a, b = vertices[ends[:, 0]], vertices[ends[:, 1]]
    lines = shapely.linestrings(np.stack([a, b], axis=1))
    tree = shapely.STRtree(lines)
    splits: dict[int, list[int]] = {}

    pts = shapely.points(vertices)
    vi, si = tree.query(pts, predicate="dwithin", distance=near)
    keep = (ends[si, 0] != vi) & (ends[si, 1] != vi)
    vi, si = vi[keep], si[keep]
    if len(vi):
        d = b[si] - a[si]
        t = np.einsum("ij,ij->i", vertices[vi] - a[si], d) / np.einsum("ij,ij->i", d, d)
        inside = (t > 0.0) & (t < 1.0)
        for v, s in zip(vi[inside].tolist(), si[inside].tolist()):
            splits.setdefault(s, []).append(v)

    i, j, crossings = _crossings(lines, tree, ends, a, b, max_crossings)
    new_points: list[np.ndarray] = []
    if len(i):
        if len(crossings):
            nearest = _nearest_within(vertices, crossings, snap)
            for k in range(len(crossings)):
                if nearest[k] >= 0:
                    target = int(nearest[k])
                else:
                    new_points.append(crossings[k])
                    target = -len(new_points)
                splits.setdefault(int(i[k]), []).append(target)
                splits.setdefault(int(j[k]), []).append(target)
    return splits, new_points


def _crossings(lines, tree, ends, a, b, most: int | None):
    """Proper crossings of segments: (first segment, second segment, point) arrays. Queried a
    block of segments at a time, so that a tangle is refused (`TooManyCrossings`) before the
    pairs of all segments are held at once."""
    found_i, found_j, found_p, total = [], [], [], 0
    for start in range(0, len(lines), CROSSING_BLOCK):
        i, j = tree.query(lines[start:start + CROSSING_BLOCK], predicate="intersects")
        i = i + start
        keep = (i < j) & (ends[i, 0] != ends[j, 0]) & (ends[i, 0] != ends[j, 1]) \
            & (ends[i, 1] != ends[j, 0]) & (ends[i, 1] != ends[j, 1])
        i, j = i[keep], j[keep]
        r, s = b[i] - a[i], b[j] - a[j]
        denom = r[:, 0] * s[:, 1] - r[:, 1] * s[:, 0]
        qp = a[j] - a[i]
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (qp[:, 0] * s[:, 1] - qp[:, 1] * s[:, 0]) / denom
            u = (qp[:, 0] * r[:, 1] - qp[:, 1] * r[:, 0]) / denom
        proper = np.isfinite(t) & np.isfinite(u) & (t > 0) & (t < 1) & (u > 0) & (u < 1)
        found_i.append(i[proper])
        found_j.append(j[proper])
        found_p.append(a[i[proper]] + t[proper][:, None] * r[proper])
        total += int(proper.sum())
        if most is not None and total > most:
            raise TooManyCrossings(total)
    if not found_i:
        return np.zeros(0, np.int64), np.zeros(0, np.int64), np.zeros((0, 2))
    return np.concatenate(found_i), np.concatenate(found_j), np.concatenate(found_p)


def _split(vertices, ends, sources, splits):
    out_ends: list[tuple[int, int]] = []
    out_sources: list[list[tuple[int, bool]]] = []
    for seg in range(len(ends)):
        u, w = int(ends[seg, 0]), int(ends[seg, 1])
        through = splits.get(seg)
        if not through:
            out_ends.append((u, w))
            out_sources.append(sources[seg])
            continue
        p, d = vertices[u], vertices[w] - vertices[u]
        ids = np.array(sorted(set(through) - {u, w}), dtype=np.int64)
        t = (vertices[ids] - p) @ d / (d @ d)
        chain = [u, *ids[np.argsort(t, kind="stable")].tolist(), w]
        for x, y in zip(chain, chain[1:]):
            if x != y:
                out_ends.append((x, y))
                out_sources.append(sources[seg])
    return np.asarray(out_ends, dtype=np.int64).reshape(-1, 2), out_sources


def _dedupe(ends, sources):
    """One piece per unordered vertex pair, lower id first, merging (and flipping) sources.

    A source that runs over one piece twice is listed twice: region winding numbers count it.
    """
    merged: dict[tuple[int, int], list[tuple[int, bool]]] = {}
    for (u, w), srcs in zip(ends.tolist(), sources):
        if u == w:
            continue
        key = (u, w) if u < w else (w, u)
        flip = u > w
        merged.setdefault(key, []).extend((src, forward != flip) for src, forward in srcs)
    keys = sorted(merged)
    return (np.asarray(keys, dtype=np.int64).reshape(-1, 2),
            [sorted(merged[k]) for k in keys])
