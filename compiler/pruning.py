"""Graphs with no complete irreducible descendants (§5.6, Appendix C, companion §6.4-6.6).

Every face of a complete planar graph is a closed walk that turns +1 (the outer face) or −1 (an
inner face). A walk is a sequence of moves: a move leaves a vertex along slot (P, i) and crosses
the edge into slot (Q, j) of a neighbour with the opposite token (a ∨ when the token left along
is barred: the direction turns through −180°). The next move leaves Q along slot j + 1, and
turning around Q from j to j + 1 is a ∧ when it wraps past the end of the ring. Moves are the
nodes of the directed graph of companion §6.6 (pairs of half-edges glued together), and one move
followed by the next is an edge weighted by the turns between them; its closed walks are the
possible faces.

Rules shrink it (companion §6.6): an irreducible graph holds no left side of a rule, so a rule
whose left side is one block removes every move touching its primitives; two blocks joined by
one edge remove that kind of move; three blocks joined in a chain whose two joining edges leave
the middle one from consecutive slots remove that move-after-move transition. (Only rules that
shrink the vertex count count: see `infer._add_rule`.)

The test on a graph G: the face through G's boundary gap k (from open slot h_k to h_{k+1}, net
t_k turns) is the walk from the move that lands on h_k, through G, to the move that leaves along
h_{k+1}, closed by some walk back, all inside one strongly connected component. Within a
component whose closed walks never turn negative ("turning strictly upward"), shortest walks are
finite, so the face turns at least t_k plus the shortest way back; if that exceeds +1 the face
cannot close, and neither can any descendant of G (gluing only adds to the walk back).
Symmetrically for components turning strictly downward and faces below −1. A gap with no way
back at all is also a dead end.
"""

from __future__ import annotations

from typing import Sequence

import numpy as np

from grammar_lang import boundary as bd

from .gluing import Graph

INF = float("inf")
Move = tuple[int, int, int, int]     # leave (P, i), land on (Q, j)


class TurnAnalysis:
    def __init__(self, rings: Sequence[Sequence[int]]):
        self.rings = [tuple(r) for r in rings]
        carriers: dict[int, list[tuple[int, int]]] = {}
        for p, r in enumerate(self.rings):
            for i, t in enumerate(r):
                carriers.setdefault(t, []).append((p, i))
        self.moves: list[Move] = []
        for p, r in enumerate(self.rings):
            for i, t in enumerate(r):
                for q, j in carriers.get(bd.opposite(t), ()):
                    self.moves.append((p, i, q, j))
        self.index = {m: k for k, m in enumerate(self.moves)}
        self.leaving: dict[tuple[int, int], list[int]] = {}
        self.landing: dict[tuple[int, int], list[int]] = {}
        for k, (p, i, q, j) in enumerate(self.moves):
            self.leaving.setdefault((p, i), []).append(k)
            self.landing.setdefault((q, j), []).append(k)
        self.dead: set[int] = set()
        self.dead_pairs: set[tuple[int, int]] = set()
        self._solved = False

    # --- the rule-reduced directed graph ---------------------------------------------------

    def forbid_primitive(self, p: int) -> None:
        self.dead.update(k for k, m in enumerate(self.moves) if m[0] == p or m[2] == p)
        self._solved = False

    def forbid_edge(self, p: int, i: int, q: int, j: int) -> None:
        for m in ((p, i, q, j), (q, j, p, i)):
            if m in self.index:
                self.dead.add(self.index[m])
        self._solved = False

    def forbid_pair(self, first: Move, second: Move) -> None:
        """No face walk makes move `second` right after `first`."""
        if first in self.index and second in self.index:
            self.dead_pairs.add((self.index[first], self.index[second]))
            self._solved = False

    def _solve(self) -> None:
        n = len(self.moves)
        w = np.full((n, n), INF)
        for a, (p, i, q, j) in enumerate(self.moves):
            if a in self.dead:
                continue
            ring = len(self.rings[q])
            turn = (-1 if bd.is_bar(self.rings[p][i]) else 0) + (1 if j == ring - 1 else 0)
            for b in self.leaving.get((q, (j + 1) % ring), ()):
                if b not in self.dead and (a, b) not in self.dead_pairs:
                    w[a, b] = turn
        reach = np.isfinite(w) | np.eye(n, dtype=bool)
        for k in range(n):
            reach |= reach[:, k:k + 1] & reach[k:k + 1, :]
        self.comp = np.full(n, -1)
        c = 0
        for a in range(n):
            if self.comp[a] < 0:
                self.comp[np.nonzero(reach[a] & reach[:, a])[0]] = c
                c += 1
        self.low = self._floyd(w)                                  # −inf: a negative cycle
        self.high = -self._floyd(np.where(np.isfinite(w), -w, INF))  # +inf: a positive cycle
        self._solved = True

    @staticmethod
    def _floyd(w: np.ndarray) -> np.ndarray:
        d = w.copy()
        # The empty walk: the move that leaves along h_{k+1} may itself land on h_k.
        np.fill_diagonal(d, np.minimum(np.diag(d), 0.0))
        for k in range(len(d)):
            d = np.minimum(d, d[:, k:k + 1] + d[k:k + 1, :])
        neg = np.diag(d) < 0
        if neg.any():
            # A walk that can pass through a negative cycle can be made as low as we like.
            bad = np.isfinite(d[:, neg])[:, :, None] & np.isfinite(d[neg, :])[None, :, :]
            d = np.where(bad.any(axis=1), -INF, d)
        return d

    # --- the test ---------------------------------------------------------------------------

    def dead_end(self, g: Graph) -> bool:
        """True when no complete irreducible graph has g as a part."""
        if not g.gaps or not self.moves:
            return False
        if not self._solved:
            self._solve()
        m = len(g.gaps)
        for k in range(m):
            (hk, tk), (hn, _) = g.gaps[k], g.gaps[(k + 1) % m]
            starts = [a for a in self.leaving.get((g.verts[hn[0]], hn[1]), ())
                      if a not in self.dead]
            ends = [b for b in self.landing.get((g.verts[hk[0]], hk[1]), ())
                    if b not in self.dead]
            lo, hi, any_way = INF, -INF, False
            for a in starts:
                for b in ends:
                    if self.comp[a] != self.comp[b]:
                        continue
                    p, i = self.moves[b][:2]
                    base = tk + (-1 if bd.is_bar(self.rings[p][i]) else 0)
                    lo = min(lo, base + self.low[a, b])
                    hi = max(hi, base + self.high[a, b])
                    any_way = True
            if not any_way or lo > 1 or hi < -1:
                return True
        return False
