"""Bending (paper Appendix B): the drawn picture's edges bent, its topology kept.

An edge whose class is decorated with `bend` is cut into segments about `bend-step` long, and
the heading of each segment turns from the last one's by a random angle of at most `bend`
(a random walk, so an edge curves rather than zig-zags; the walk's mean heading is the edge's
own, so it stays on course). Those segment vectors no longer close the drawing's cycles, so
the positions of every point are then found by linear least squares: each segment's vector,
and each straight edge's vector (weighted far more, so straight parts keep their shape), is
matched as closely as possible, with the frame's vertices held in place and every vertex
pulled weakly towards where it was. Cycles stay closed because positions, not vectors, are
the unknowns.

A bent picture must stay planar: edges whose segments cross or touch another's are drawn
straight and the positions solved again, a few rounds at most, after which the picture is
drawn unbent. Only the SVG is bent; the drawing (JSON) keeps the geometry the verifier checks.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

STRAIGHT_WEIGHT = 30.0   # a straight edge's vector against a bent segment's (weight 1)
ANCHOR_WEIGHT = 0.05     # every vertex pulled towards its unbent place: fixes translation
MOST_SEGMENTS = 48       # per edge
MOST_POINTS = 200_000    # in all: bounds the least-squares system of a huge drawing
ROUNDS = 4               # of straightening the edges that cross, before giving up


@dataclass(frozen=True)
class Bend:
    """How one edge bends: the largest turn per segment (radians) and the segment length."""

    angle: float
    step: float


@dataclass(frozen=True)
class Bent:
    """A bent picture: the vertices' new positions and, per edge, the points it runs through
    from its first end to its second (both ends included)."""

    xy: np.ndarray
    paths: tuple[np.ndarray, ...]


def bend_picture(xy: np.ndarray, ends: np.ndarray, bends: list[Bend | None],
                 pinned: np.ndarray, seed: int) -> Bent:
    """Bend the edges that have a `Bend` (None: straight). `pinned` marks vertices that must
    not move (the frame's). The same inputs and seed give the same picture."""
    xy = np.asarray(xy, dtype=float).reshape(-1, 2)
    ends = np.asarray(ends, dtype=np.int64).reshape(-1, 2)
    rng = np.random.default_rng([int(seed) & 0xFFFFFFFF, 0xBE9D])
    counts = _segment_counts(xy, ends, bends)
    turns = [_headings(rng, k, b) for k, b in zip(counts, bends)]
    bent = list(bends)
    for _ in range(ROUNDS):
        picture = _solve(xy, ends, [t if b is not None else None for t, b in zip(turns, bent)],
                         pinned)
        bad = _crossing_edges(picture.paths, ends)
        if not bad:
            return picture
        for e in bad:
            bent[e] = None
    return Bent(xy.copy(), tuple(xy[[u, v]] for u, v in ends))


def _segment_counts(xy, ends, bends) -> list[int]:
    """Segments per edge: its length over its step, bounded per edge and in all."""
    lengths = np.hypot(*(xy[ends[:, 1]] - xy[ends[:, 0]]).T) if len(ends) else np.zeros(0)
    counts = [1 if b is None or b.angle <= 0 or b.step <= 0
              else int(min(MOST_SEGMENTS, max(1, math.ceil(length / b.step))))
              for length, b in zip(lengths, bends)]
    total = sum(counts)
    if total > MOST_POINTS:
        scale = MOST_POINTS / total
        counts = [max(1, int(k * scale)) for k in counts]
    return counts


def _headings(rng, k: int, b: Bend | None) -> np.ndarray:
    """Each segment's turn from the edge's direction: a random walk of steps within ±angle,
    centred so that the edge keeps its mean heading. Drawn for every edge, bent or not, so
    one edge's numbers do not depend on another's class."""
    steps = rng.uniform(-1.0, 1.0, size=k)
    if b is None or b.angle <= 0 or k == 1:
        return np.zeros(k)
    walk = np.cumsum(steps * b.angle)
    return walk - walk.mean()


def _solve(xy, ends, headings, pinned) -> Bent:
    """Least-squares positions of every point for the given segment headings (None: the edge
    stays one straight segment)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.linalg import splu

    n = len(xy)
    starts, stops, vectors, weights, paths_idx = [], [], [], [], []
    for (u, v), turn in zip(ends, headings):
        d = xy[v] - xy[u]
        if turn is None or len(turn) == 1:
            starts.append(u), stops.append(v), vectors.append(d), weights.append(STRAIGHT_WEIGHT)
            paths_idx.append([u, v])
            continue
        k = len(turn)
        inner = list(range(n, n + k - 1))
        n += k - 1
        chain = [u] + inner + [v]
        base = math.atan2(d[1], d[0])
        size = math.hypot(d[0], d[1]) / k
        for i in range(k):
            a = base + turn[i]
            starts.append(chain[i]), stops.append(chain[i + 1])
            vectors.append((size * math.cos(a), size * math.sin(a))), weights.append(1.0)
        paths_idx.append(chain)
    start_xy = _initial(xy, paths_idx, n)
    fixed = np.zeros(n, dtype=bool)
    fixed[: len(xy)] = pinned
    free = np.flatnonzero(~fixed)
    if len(free) == 0:
        return Bent(xy.copy(), tuple(xy[p] for p in paths_idx))
    col = np.full(n, -1, dtype=np.int64)
    col[free] = np.arange(len(free))
    a, b = np.asarray(starts), np.asarray(stops)
    w = np.sqrt(np.asarray(weights))
    rhs = w[:, None] * np.asarray(vectors, dtype=float)
    # Fixed ends move to the right-hand side: p_b - p_a = d.
    rhs += (w * fixed[a])[:, None] * start_xy[a] - (w * fixed[b])[:, None] * start_xy[b]
    rows = np.arange(len(a))
    keep_a, keep_b = ~fixed[a], ~fixed[b]
    r = np.concatenate([rows[keep_b], rows[keep_a]])
    c = np.concatenate([col[b[keep_b]], col[a[keep_a]]])
    vals = np.concatenate([w[keep_b], -w[keep_a]])
    anchors = free[free < len(xy)]
    aw = math.sqrt(ANCHOR_WEIGHT)
    r = np.concatenate([r, len(a) + np.arange(len(anchors))])
    c = np.concatenate([c, col[anchors]])
    vals = np.concatenate([vals, np.full(len(anchors), aw)])
    rhs = np.vstack([rhs, aw * xy[anchors]])
    m = coo_matrix((vals, (r, c)), shape=(len(a) + len(anchors), len(free))).tocsc()
    normal = (m.T @ m).tocsc()
    solved = splu(normal).solve(np.asarray(m.T @ rhs))
    pos = start_xy.copy()
    pos[free] = solved
    return Bent(pos[: len(xy)], tuple(pos[p] for p in paths_idx))


def _initial(xy, paths_idx, n) -> np.ndarray:
    """Every point's unbent place: vertices where they are, a segment's points along its edge
    (what a fixed point keeps, and what the crossing test starts from)."""
    pos = np.zeros((n, 2))
    pos[: len(xy)] = xy
    for chain in paths_idx:
        if len(chain) > 2:
            t = np.linspace(0.0, 1.0, len(chain))[1:-1, None]
            pos[chain[1:-1]] = xy[chain[0]] * (1 - t) + xy[chain[-1]] * t
    return pos


def _crossing_edges(paths, ends) -> set[int]:
    """Edges whose segments cross, touch or overlap another edge's (or their own), apart from
    meeting at a shared vertex."""
    import shapely

    seg_edge, seg_a, seg_b = [], [], []
    for e, p in enumerate(paths):
        seg_edge += [e] * (len(p) - 1)
        seg_a.append(p[:-1]), seg_b.append(p[1:])
    if not seg_edge:
        return set()
    a, b = np.concatenate(seg_a), np.concatenate(seg_b)
    owner = np.asarray(seg_edge)
    lines = shapely.linestrings(np.stack([a, b], axis=1))
    i, j = shapely.STRtree(lines).query(lines, predicate="intersects")
    keep = i < j
    i, j = i[keep], j[keep]
    e, f = owner[i], owner[j]
    ee, ef = ends[e], ends[f]
    share_vertex = ((ee[:, :1] == ef).any(axis=1) | (ee[:, 1:] == ef).any(axis=1))
    may_share = np.where(e == f, j - i == 1, share_vertex)
    ok = may_share & _meet_at_end(a[i], b[i], a[j], b[j])
    return set(e[~ok].tolist()) | set(f[~ok].tolist())


def _meet_at_end(a, b, c, d) -> np.ndarray:
    """Per pair of intersecting segments ab and cd: whether they meet only at one common end
    point (not at both, and not overlapping beyond it)."""
    ac, ad = (a == c).all(axis=1), (a == d).all(axis=1)
    bc, bd = (b == c).all(axis=1), (b == d).all(axis=1)
    at_a, at_b = ac | ad, bc | bd
    p = np.where(at_a[:, None], a, b)
    u = np.where(at_a[:, None], b, a) - p
    v = np.where((ac | bc)[:, None], d, c) - p
    cross = u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]
    scale = (u * u).sum(axis=1) + (v * v).sum(axis=1)
    overlap = (np.abs(cross) <= 1e-12 * scale) & ((u * v).sum(axis=1) > 0)
    return (at_a ^ at_b) & ~overlap
