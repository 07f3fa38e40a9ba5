"""Graphs with no complete irreducible descendants (§5.6, Appendix C, companion §6.4-6.6).

Every face of a complete planar graph is a closed walk that turns +1 (the outer face) or −1 (an
inner face). A walk is a sequence of "leave" states, one per half-edge it leaves a vertex along;
from leaving along slot (P, i) it crosses the edge into some slot (Q, j) with the opposite token
(a ∨ when the token is barred: the direction turns through −180°) and turns on around Q to slot
j + 1 (a ∧ when that wraps past the end of the ring). These states and moves form the directed
graph of companion §6.5, with the turns as weights; its closed walks are the possible faces.

Rules shrink it (companion §6.6): an irreducible graph holds no left side of a rule, so when a
left side is one primitive, or two primitives joined by one edge, those states or moves cannot
occur in an irreducible graph and are removed.

The test on a graph G: the face through G's boundary gap k (from open slot h_k to h_{k+1}, net
t_k turns) is the walk from leaving the slot glued to h_k, through G to leaving h_{k+1}, closed
by some walk back, all inside one strongly connected component. Within a component whose
closed walks never turn negative (the half-edges "turn strictly upward"), shortest paths are
finite, so the face turns at least t_k plus the shortest way back; if that exceeds +1 the face
cannot close, and neither can any descendant of G (gluing only adds to the walk back).
Symmetrically for components that turn strictly downward and faces below −1. A gap whose
continuation cannot return at all is also a dead end.
"""

from __future__ import annotations

from typing import Sequence

import numpy as np

from grammar_lang import boundary as bd

from .gluing import Graph

INF = float("inf")


class TurnAnalysis:
    def __init__(self, rings: Sequence[Sequence[int]]):
        self.rings = [tuple(r) for r in rings]
        self.nodes = [(p, i) for p, r in enumerate(self.rings) for i in range(len(r))]
        self.index = {s: k for k, s in enumerate(self.nodes)}
        self.by_token: dict[int, list[int]] = {}
        for k, (p, i) in enumerate(self.nodes):
            self.by_token.setdefault(self.rings[p][i], []).append(k)
        self.dead_prims: set[int] = set()
        self.dead_edges: set[tuple[int, int, int, int]] = set()
        self._solved = False

    # --- the rule-reduced directed graph ---------------------------------------------------

    def forbid_primitive(self, p: int) -> None:
        self.dead_prims.add(p)
        self._solved = False

    def forbid_edge(self, p: int, i: int, q: int, j: int) -> None:
        self.dead_edges.add((p, i, q, j))
        self.dead_edges.add((q, j, p, i))
        self._solved = False

    def _moves(self):
        for k, (p, i) in enumerate(self.nodes):
            if p in self.dead_prims:
                continue
            tok = self.rings[p][i]
            cross = -1 if bd.is_bar(tok) else 0
            for k2 in self.by_token.get(bd.opposite(tok), ()):
                q, j = self.nodes[k2]
                if q in self.dead_prims or (p, i, q, j) in self.dead_edges:
                    continue
                n = len(self.rings[q])
                wrap = 1 if j == n - 1 else 0
                yield k, self.index[(q, (j + 1) % n)], cross + wrap

    def _solve(self) -> None:
        n = len(self.nodes)
        w = np.full((n, n), INF)
        for a, b, c in self._moves():
            w[a, b] = min(w[a, b], c)
        reach = np.isfinite(w) | np.eye(n, dtype=bool)
        for k in range(n):
            reach |= reach[:, k:k + 1] & reach[k:k + 1, :]
        self.comp = np.full(n, -1)
        c = 0
        for a in range(n):
            if self.comp[a] < 0:
                members = np.nonzero(reach[a] & reach[:, a])[0]
                self.comp[members] = c
                c += 1
        self.low = self._floyd(w)            # shortest walk turns (−inf: a negative cycle)
        wmax = np.where(np.isfinite(w), -w, INF)
        self.high = -self._floyd(wmax)       # longest walk turns (+inf: a positive cycle)
        self._solved = True

    def _floyd(self, w: np.ndarray) -> np.ndarray:
        d = w.copy()
        n = len(d)
        # The empty walk: a gap closed by gluing h_k straight to h_{k+1}.
        np.fill_diagonal(d, np.minimum(np.diag(d), 0.0))
        for k in range(n):
            d = np.minimum(d, d[:, k:k + 1] + d[k:k + 1, :])
        neg = np.diag(d) < 0
        if neg.any():
            # Any walk through a node on a negative cycle can be made as low as we like.
            bad = np.isfinite(d[:, neg])[:, :, None] & np.isfinite(d[neg, :])[None, :, :]
            d = np.where(bad.any(axis=1), -INF, d)
        return d

    # --- the test ---------------------------------------------------------------------------

    def dead_end(self, g: Graph) -> bool:
        """True when no complete irreducible graph has g as a part."""
        if not g.gaps:
            return False
        if not self._solved:
            self._solve()
        m = len(g.gaps)
        for k in range(m):
            (hk, tk), (hn, _) = g.gaps[k], g.gaps[(k + 1) % m]
            tok_k = self.rings[g.verts[hk[0]]][hk[1]]
            start = self.index[(g.verts[hn[0]], hn[1])]   # leaving along h_{k+1}
            base = tk + (-1 if bd.is_bar(bd.opposite(tok_k)) else 0)
            ends = [e for e in self.by_token.get(bd.opposite(tok_k), ())
                    if self.comp[e] == self.comp[start] and self.nodes[e][0] not in self.dead_prims]
            if not ends:
                return True
            lo = min(self.low[start, e] for e in ends)
            hi = max(self.high[start, e] for e in ends)
            if base + lo > 1 or base + hi < -1:
                return True
        return False
