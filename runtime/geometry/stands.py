"""How narrow a structure stood on a stretch of a frame's side can be drawn.

A move that stands a structure on a bare stretch of a side (a castle's block and keep on the
ground) joins its new part to the stretch's two ends. Its edges keep their directions and
their lengths stay in their classes, so the part cannot be drawn narrower than some width:
the least distance between the two ends over every drawing of it, a linear program over its
edge lengths (positions follow from them). A stretch shorter than that cannot hold it unless
the structures at the stretch's ends move apart.

On the paper's castle at its N, once structures stand along the whole ground, its stand moves
are mostly proposed on the gaps of a few pixels between two structures (the median stretch
at seed 80: 4 px): 529 of 533 such proposals were on stretches under 100 px, none placed, and
they took a third of the run's time (21 ms each, for one of them). The engine refuses such a
proposal before any geometry (Engine.apply).

The same holds towards the frame's sides for any new part: joined to an old vertex, it
reaches at least some distance beyond it in each direction (`least_reach`, a linear program
per direction and old vertex). Where the frame's side is nearer than that, the part cannot be
placed unless that old vertex moves away from the side. The paper's space station proposed
a module above its top module (`r19` backwards) 523 times at seed 22, whose top lies 35 px
under the frame's: every one failed outside the frame, at 9.8 ms each, 41 % of the run. The
engine asks this only of moves that have failed outside the frame before, in a rectangular
frame; over the four illustrations at seeds 22, 42, 80 and 0, none of the proposals it would
refuse placed.

A rigid part (vertices joined by edges of fixed length) keeps its exact shape wherever it is
drawn, so a frame narrower or lower than its box cannot hold it at all (`rigid_box`, which
`ggrun --extent` checks: the paper's flowers' largest blossoms take 160 × 140 px, and at
100 × 100 a run stalled with no word of why).
"""

from __future__ import annotations

import math

import numpy as np

from .change import Change, HostView


def narrowest(host: HostView, change: Change) -> float | None:
    """The least length of the stretch `change` stands its new part on, over every drawing of
    the part (directions kept, lengths within their classes, tiles and floors relaxed, so that
    it is a lower bound); None when the change is no such stand or the bound is not found."""
    if change.removed or len(change.cut) != 1:
        return None
    (p, i), = change.cut
    t, new = host.t, dict(change.new)
    if t.label[host.prim[p]][i] not in host.side_labels:
        # Elsewhere the stretch's ends are free to move apart (a flag on a tower's side
        # takes a side shorter than it, and the solver lengthens it), so no bound holds.
        return None
    q = host.link[p][i][0]
    ends = {p: 0, q: 1}
    if any(a[0] not in new and a[0] not in ends or b[0] not in new and b[0] not in ends
           for a, b in change.glue):
        return None            # it joins more than the stretch's ends
    along = t.direction[host.prim[p]][i]          # from p towards q, along the side
    order = {v: k for k, v in enumerate(sorted(new))}
    nv = len(order)

    def place(v: int, c: int) -> list[tuple[int, float]]:
        # p at the origin, q at s·along: the stretch's length s is column 2·nv.
        if v in order:
            return [(2 * order[v] + c, 1.0)]
        return [(2 * nv, along[c])] if ends[v] == 1 else []

    # Columns: each new vertex's x and y, the stretch's length s, then each edge's length.
    A, lengths = _glued_rows(host, change, place, 2 * nv + 1)
    ne, cols = len(change.glue), A.shape[1]
    bounds = [(None, None)] * (2 * nv) + [(0.0, None)] + lengths
    cost = np.zeros(cols)
    cost[2 * nv] = 1.0
    from scipy.optimize import linprog      # first use only: ggrun starts without scipy
    res = linprog(cost, A_eq=A, b_eq=np.zeros(2 * ne), bounds=bounds, method="highs")
    return float(res.x[2 * nv]) if res.status == 0 else None


# Towards each side of a rectangular frame: +x, −x, +y, −y.
SIDES = ((1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0))


def least_reach(host: HostView, change: Change) -> list[tuple[float, ...]] | None:
    """Per old vertex the change joins its new part to (in the order they first appear among
    its glued edges) and per direction of SIDES: the least distance that some new vertex lies
    beyond that old vertex that way, over every drawing of the part (the other old vertices
    free, lengths within their classes, tiles and floors relaxed: a lower bound; −inf where
    there is none). None for a change with no new vertex or no old one."""
    new = dict(change.new)
    olds = joined(change)
    if not new or not olds:
        return None
    col = {v: 2 * k for k, v in enumerate(sorted(new))}
    col.update({v: 2 * (len(new) + k) for k, v in enumerate(olds)})
    npos, ne = 2 * (len(new) + len(olds)), len(change.glue)
    # Columns: every vertex's x and y, each edge's length, then the reach.
    A, lengths = _glued_rows(host, change, lambda v, c: [(col[v] + c, 1.0)], npos, extra=1)
    cols = A.shape[1]
    bounds = [(None, None)] * npos + lengths + [(None, None)]
    cost = np.zeros(cols)
    cost[-1] = 1.0
    # reach ≥ ⟨p_v, d⟩ for every new vertex v, with the old vertex asked about at the origin:
    # one set of rows per direction, the same for every old vertex.
    rows = []
    for dx, dy in SIDES:
        ub = np.zeros((len(new), cols))
        for r, v in enumerate(sorted(new)):
            ub[r, col[v]], ub[r, col[v] + 1], ub[r, -1] = dx, dy, -1.0
        rows.append(ub)
    from scipy.optimize import linprog      # first use only: ggrun starts without scipy
    out = []
    for c in olds:
        pinned = list(bounds)
        pinned[col[c]] = pinned[col[c] + 1] = (0.0, 0.0)
        row = []
        for ub in rows:
            res = linprog(cost, A_ub=ub, b_ub=np.zeros(len(new)), A_eq=A,
                          b_eq=np.zeros(2 * ne), bounds=pinned, method="highs")
            row.append(float(res.x[-1]) if res.status == 0 else -math.inf)
        out.append(tuple(row))
    return out


def rigid_box(t, sides) -> tuple[float, float]:
    """The largest width and the largest height of a rigid part in any of `sides` (rule
    sides, graphs of primitives), in drawing units: each part is laid out once from its
    fixed lengths and directions (`t`: the grammar's Tables)."""
    width = height = 0.0
    for side in sides:
        fixed: dict[int, list] = {}         # vertex → (neighbour, length, direction)
        for v, i, u, j in side.edges:
            p, q = side.vertices[v], side.vertices[u]
            length = t.lengths[t.label[p][i]][2]
            if length is not None:
                fixed.setdefault(v, []).append((u, length, t.direction[p][i]))
                fixed.setdefault(u, []).append((v, length, t.direction[q][j]))
        placed: set[int] = set()
        for start in sorted(fixed):
            if start in placed:
                continue
            pos, todo = {start: (0.0, 0.0)}, [start]
            while todo:
                v = todo.pop()
                x, y = pos[v]
                for u, length, (dx, dy) in fixed[v]:
                    if u not in pos:
                        pos[u] = (x + length * dx, y + length * dy)
                        todo.append(u)
            placed.update(pos)
            xs, ys = [p[0] for p in pos.values()], [p[1] for p in pos.values()]
            width, height = max(width, max(xs) - min(xs)), max(height, max(ys) - min(ys))
    return width, height


def joined(change: Change) -> list[int]:
    """The old vertices a change glues its new part to, in the order they first appear among
    its glued edges (the same order for every match of a move)."""
    new = {v for v, _ in change.new}
    out: list[int] = []
    for a, b in change.glue:
        for v in (a[0], b[0]):
            if v not in new and v not in out:
                out.append(v)
    return out


def _glued_rows(host: HostView, change: Change, place, first: int,
                extra: int = 0) -> tuple[np.ndarray, list]:
    """Two rows per edge the change glues, pos(b) − pos(a) − length·d = 0, over columns
    `place(v, c)` lists for vertex v's coordinate c as (column, coefficient) pairs (none: at
    the origin), edge e's length being column `first + e`, and `extra` columns after those;
    and each length's bounds (its class's, or its fixed length)."""
    t, new = host.t, dict(change.new)
    ne = len(change.glue)
    A = np.zeros((2 * ne, first + ne + extra))
    bounds = []
    for e, (a, b) in enumerate(change.glue):
        v, k = a
        prim = new.get(v, host.prim.get(v))
        d, (lo, hi, fixed, _) = t.direction[prim][k], t.lengths[t.label[prim][k]]
        bounds.append((fixed, fixed) if fixed is not None
                      else (max(lo, 0.0), hi if hi < math.inf else None))
        for c in (0, 1):
            for w, sign in ((b[0], 1.0), (v, -1.0)):
                for column, coef in place(w, c):
                    A[2 * e + c, column] += sign * coef
            A[2 * e + c, first + e] = -d[c]
    return A, bounds
