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
    nv, ne = len(order), len(change.glue)
    # Columns: each new vertex's x and y, the stretch's length s, then each edge's length.
    cols = 2 * nv + 1 + ne
    A = np.zeros((2 * ne, cols))
    bounds = [(None, None)] * (2 * nv) + [(0.0, None)]
    for e, (a, b) in enumerate(change.glue):
        v, k = a
        prim = new.get(v, host.prim.get(v))
        d = t.direction[prim][k]
        lab = t.label[prim][k]
        lo, hi, fixed, _ = t.lengths[lab]
        bounds.append((fixed, fixed) if fixed is not None
                      else (max(lo, 0.0), hi if hi < math.inf else None))
        for c in (0, 1):
            # pos(b) − pos(a) − len·d = 0, with p at the origin and q at s·along.
            row = 2 * e + c
            for w, sign in ((b[0], 1.0), (a[0], -1.0)):
                if w in order:
                    A[row, 2 * order[w] + c] += sign
                elif ends[w] == 1:
                    A[row, 2 * nv] += sign * along[c]
            A[row, 2 * nv + 1 + e] = -d[c]
    cost = np.zeros(cols)
    cost[2 * nv] = 1.0
    from scipy.optimize import linprog      # first use only: ggrun starts without scipy
    res = linprog(cost, A_eq=A, b_eq=np.zeros(2 * ne), bounds=bounds, method="highs")
    return float(res.x[2 * nv]) if res.status == 0 else None
