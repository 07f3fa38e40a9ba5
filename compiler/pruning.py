"""Graphs with no complete irreducible descendants (§5.6, Appendix C, companion §6.4-6.6).

Every face of a complete planar graph is a closed walk that turns +1 (the outer face) or −1 (an
inner face). The graphs of the hierarchy are glued from units (blocks: primitives, groups of
them, or the right sides of a §5.4 restructuring), and a face walk through a unit is fixed by the
unit, so the walk is a sequence of moves between units: a move leaves unit P along its open slot
i and crosses the edge into open slot j of unit Q, with the opposite token (a ∨ when the token
left along is barred: the direction turns through −180°). The next move leaves Q along its next
open slot j + 1, turning by the turns that follow slot j on Q's boundary (for a primitive, one ∧
where the ring wraps). Moves are the nodes of the directed graph of companion §6.6 (pairs of
half-edges glued together), and one move followed by the next is an edge weighted by the turns
between them; its closed walks are the possible faces.

Rules shrink it (companion §6.6): an irreducible graph holds no left side of a rule, so a rule
whose left side is one unit removes every move touching it; two units joined by one edge remove
that kind of move; three units joined in a chain whose two joining edges leave the middle one
from consecutive open slots remove that move-after-move transition. (Only rules that shrink the
vertex count count: see `infer._add_rule`.)

The test on a graph G: the face through G's boundary gap k (from open slot h_k to h_{k+1}, net
t_k turns) is the walk from the move that lands on h_k, through G, to the move that leaves along
h_{k+1}, closed by some walk back, all inside one strongly connected component. Within a
component whose closed walks never turn negative ("turning strictly upward"), shortest walks are
finite, so the face turns at least t_k plus the shortest way back; if that exceeds +1 the face
cannot close, and neither can any descendant of G (gluing only adds to the walk back).
Symmetrically for components turning strictly downward and faces below −1. A gap with no way
back at all is also a dead end.

Whole faces rule out more (faces.py, `kill_by_faces`): a move whose every face glues a rule's
left side is on no irreducible graph, whichever units the rule spans.
"""

from __future__ import annotations

from typing import Callable, Sequence

import numpy as np
from scipy.sparse import csr_matrix
from scipy.sparse.csgraph import connected_components

from grammar_lang import boundary as bd

from .faces import face_graph, iter_faces
from .gluing import Graph, Slot, primitive_graph, unit_places

INF = float("inf")
Move = tuple[int, int, int, int]     # leave (P, i), land on (Q, j)
Turns = tuple[float, float]          # the least and the greatest turns of some walks


class TurnAnalysis:
    """The directed graph of moves between the open slots of units: the blocks the hierarchy is
    glued from (primitives by default). A face walk through a block is fixed by the block, so
    only its open slots, and the turns between them on its boundary, take part."""

    def __init__(self, rings: Sequence[Sequence[int]], blocks: Sequence[Graph] | None = None):
        if blocks is None:
            blocks = [primitive_graph(p, len(r)) for p, r in enumerate(rings)]
        self.blocks, self.prim_rings = list(blocks), rings
        self.sizes = [len(b.verts) for b in blocks]
        self.slot_of = [{s: k for k, (s, _) in enumerate(b.gaps)} for b in blocks]
        self.rings = [tuple(rings[b.verts[v]][i] for (v, i), _ in b.gaps) for b in blocks]
        self.after = [tuple(n for _, n in b.gaps) for b in blocks]
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
        # The turns of each move: −1 if it leaves along a barred token (the direction turns
        # through −180°), plus those of the gap it lands on.
        self.turns = [(-1 if bd.is_bar(self.rings[p][i]) else 0) + self.after[q][j]
                      for p, i, q, j in self.moves]
        self.leaving: dict[tuple[int, int], list[int]] = {}
        self.landing: dict[tuple[int, int], list[int]] = {}
        for k, (p, i, q, j) in enumerate(self.moves):
            self.leaving.setdefault((p, i), []).append(k)
            self.landing.setdefault((q, j), []).append(k)
        self.dead: set[int] = set()
        self.dead_pairs: set[tuple[int, int]] = set()
        # Whether a graph holds a left side (of a rule that reduces every graph holding it):
        # a face that glues one is no face of an irreducible graph. None: no rules known.
        self.holds_left_side: Callable[[Graph], bool] | None = None
        self._solved = False
        self._faced = False     # no rule or ruled-out move since the faces were last read
        self._w: np.ndarray | None = None    # the move graph's steps as of the last solve
        self._solved_dead: set[int] = set()
        self._solved_pairs: set[tuple[int, int]] = set()

    def unit_slots(self, g: Graph) -> list[tuple[int, int]] | None:
        """Each open slot of g as (unit, slot of that unit), or None if g's units are unknown."""
        places = unit_places(g, self.sizes)
        if places is None:
            return None
        out = []
        for (v, i), _ in g.gaps:
            k, base = places[v]
            u = g.units[k]
            slot = self.slot_of[u].get((v - base, i))
            if slot is None:
                return None
            out.append((u, slot))
        return out

    # --- the rule-reduced directed graph ---------------------------------------------------

    def forbid_unit(self, p: int) -> None:
        self._kill(k for k, m in enumerate(self.moves) if m[0] == p or m[2] == p)

    def forbid_edge(self, p: int, i: int, q: int, j: int) -> None:
        self._kill(self.index[m] for m in ((p, i, q, j), (q, j, p, i)) if m in self.index)

    def forbid_pair(self, first: Move, second: Move) -> None:
        """No face walk makes move `second` right after `first`."""
        if first in self.index and second in self.index:
            pair = (self.index[first], self.index[second])
            if pair not in self.dead_pairs:
                self.dead_pairs.add(pair)
                self.unsolve()

    def _kill(self, moves) -> None:
        # Walks are solved again only when a move really dies: most rules forbid what earlier
        # ones did (the village re-solved 16 times of 23 for nothing).
        new = set(moves) - self.dead
        if new:
            self.dead |= new
            self.unsolve()

    def unsolve(self) -> None:
        """The live moves changed: walks and faces are read again."""
        self._solved = self._faced = False

    def rules_changed(self) -> None:
        """A new left side rules out faces; the walks stay as they are."""
        self._faced = False

    def solve(self) -> None:
        if not self._solved:
            self._solve()

    def live_leaving(self, p: int, i: int) -> list[int]:
        return [a for a in self.leaving.get((p, i), ()) if a not in self.dead]

    def follow(self, a: int) -> list[int]:
        """The live moves a face walk can make right after move a (as of the last solve)."""
        return self._follow[a]

    def closing(self, e: int) -> tuple[list[float], list[float]]:
        """For each move b: the least and the greatest turns of a walk from b on to move e,
        e's own turns included (as of the last solve)."""
        if e not in self._closing:
            self._closing[e] = ((self.low[:, e] + self.turns[e]).tolist(),
                                (self.high[:, e] + self.turns[e]).tolist())
        return self._closing[e]

    def _solve(self) -> None:
        if self._w is None:
            self._solve_walks()
        else:
            self._resolve_walks()
        self._solved_dead, self._solved_pairs = set(self.dead), set(self.dead_pairs)
        self._solved = True

    def kill_by_faces(self) -> bool:
        """Kill the moves that lie on no face an irreducible complete graph can have: on none
        that turns ±1 at all, or only on faces that glue a rule's left side. (A move lies on
        the faces through the gap it lands on that end with it.) An edge has a move on each
        side, so its twin dies too. Until none dies; a search per move, so the hierarchy asks
        for it once a generation. Whether any died."""
        todo = None if self._faced else range(len(self.moves))
        any_died = False
        while todo:
            self.solve()
            died = set()
            for b in todo:
                if b in self.dead:
                    continue
                p, i, q, j = self.moves[b]
                # It lives on as soon as one face is possible (or the search gives up).
                if all(w is not None and self._forbidden(w)
                       for w in iter_faces(self, q, j, end=b)):
                    twin = self.index[(q, j, p, i)]
                    self.dead.update((b, twin))
                    died.update((self.comp_of[b], self.comp_of[twin]))
            if died:
                self._solved, any_died = False, True
            # A face stays in one strong component: only those that lost a move change.
            todo = [b for b in range(len(self.moves)) if self.comp_of[b] in died]
        self._faced = True
        return any_died

    def _forbidden(self, walk) -> bool:
        if self.holds_left_side is None:
            return False
        g = face_graph(self, walk)
        return g is not None and self.holds_left_side(g)

    def _solve_walks(self) -> None:
        n = len(self.moves)
        # Turns are small whole numbers, exact in float32, which halves the memory the
        # shortest-walk search streams through.
        w = np.full((n, n), INF, dtype=np.float32)
        for a, (p, i, q, j) in enumerate(self.moves):
            if a in self.dead:
                continue
            ring = len(self.rings[q])
            for b in self.leaving.get((q, (j + 1) % ring), ()):
                if b not in self.dead and (a, b) not in self.dead_pairs:
                    w[a, b] = self.turns[a]
        self._w = w
        # Moves that can follow each other both ways: the strong components of the move graph.
        self.comp = _strong_components(w)
        self.low, self.high = _component_bounds(w, self.comp)
        self._follow: list[list[int]] = [[] for _ in range(n)]
        for a, b in zip(*(x.tolist() for x in np.nonzero(np.isfinite(w)))):
            self._follow[a].append(b)
        self._read_components()

    def _resolve_walks(self) -> None:
        """The last solve, updated for the moves and steps ruled out since: a component that
        lost none keeps its walks (ruling out only splits components), so only those that
        did are solved again. Each rule ruling out one step solved all 254 moves of the
        village again."""
        w, comp = self._w, self.comp
        dead = self.dead - self._solved_dead
        pairs = self.dead_pairs - self._solved_pairs
        touched = {self.comp_of[m] for m in dead}
        touched.update(self.comp_of[a] for a, b in pairs if self.comp_of[a] == self.comp_of[b])
        rows = set(dead)
        for m in dead:
            rows.update(np.flatnonzero(np.isfinite(w[:, m])).tolist())     # steps onto m
            w[m, :] = w[:, m] = INF
        for a, b in pairs:
            w[a, b] = INF
            rows.add(a)
        for a in rows:
            self._follow[a] = np.flatnonzero(np.isfinite(w[a])).tolist()
        idx = np.flatnonzero(np.isin(comp, list(touched)))
        if len(idx):
            block = np.ix_(idx, idx)
            sub = _strong_components(w[block])
            comp[idx] = sub + comp.max() + 1        # fresh labels: only equality is read
            self.low[block], self.high[block] = _component_bounds(w[block], sub)
        self._read_components()

    def _read_components(self) -> None:
        self.comp_of = self.comp.tolist()
        self._ways: dict[tuple[Slot, Slot], Turns | None] = {}
        self._closing: dict[int, tuple[list[float], list[float]]] = {}

    # --- the test ---------------------------------------------------------------------------

    def dead_end(self, g: Graph) -> bool:
        """True when no complete irreducible graph has g as a part."""
        if not g.gaps or not self.moves:
            return False
        slots = self.unit_slots(g)
        if slots is None:
            return False
        if not self._solved:
            self._solve()
        m = len(g.gaps)
        for k in range(m):
            back = self._way_back(slots[(k + 1) % m], slots[k])
            tk = g.gaps[k][1]
            if back is None or tk + back[0] > 1 or tk + back[1] < -1:
                return True
        return False

    def _way_back(self, leave: Slot, land: Slot) -> Turns | None:
        """The least and the greatest turns of a walk from a move leaving along `leave` to one
        landing on `land`, with that landing's own turn, in one strong component; None if there
        is none. Many graphs share these slot pairs: each is worked out once per solve."""
        key = (leave, land)
        if key not in self._ways:
            self._ways[key] = self._walks_between(leave, land)
        return self._ways[key]

    def _walks_between(self, leave: Slot, land: Slot) -> Turns | None:
        starts = [a for a in self.leaving.get(leave, ()) if a not in self.dead]
        ends = [b for b in self.landing.get(land, ()) if b not in self.dead]
        lo, hi, any_way = INF, -INF, False
        for a in starts:
            for b in ends:
                if self.comp[a] != self.comp[b]:
                    continue
                p, i = self.moves[b][:2]
                turn = -1 if bd.is_bar(self.rings[p][i]) else 0
                lo = min(lo, turn + self.low[a, b])
                hi = max(hi, turn + self.high[a, b])
                any_way = True
        return (lo, hi) if any_way else None


def _strong_components(w: np.ndarray) -> np.ndarray:
    """Moves that can follow each other both ways (finite steps of w)."""
    return connected_components(csr_matrix(np.isfinite(w)), directed=True,
                                connection="strong")[1]


def _component_bounds(w: np.ndarray, comp: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The least (−inf: a negative cycle) and the greatest (+inf: a positive one) turns of
    walks between moves of one strong component."""
    return _by_component(w, comp), -_by_component(np.where(np.isfinite(w), -w, INF), comp)


def _by_component(w: np.ndarray, comp: np.ndarray) -> np.ndarray:
    """Shortest walks between moves of one strong component (the only ones `dead_end`
    reads): a walk between two of its moves never leaves it, so each component is solved
    on its own, in (size)³ instead of (all moves)³."""
    d = np.full_like(w, INF)
    # A move alone in its component walks nowhere or round its own loop: those at once.
    alone = np.flatnonzero(np.bincount(comp)[comp] == 1)
    loop = w[alone, alone]
    d[alone, alone] = np.where(loop < 0, -INF, np.minimum(loop, 0))
    order = np.argsort(comp, kind="stable")
    cuts = np.flatnonzero(np.diff(comp[order])) + 1
    for idx in np.split(order, cuts):
        if len(idx) > 1:
            block = np.ix_(idx, idx)
            d[block] = _component_walks(w[block])
    return d


def _component_walks(w: np.ndarray) -> np.ndarray:
    """Shortest walks (Floyd-Warshall) between the moves of one strong component. Any walk
    between two of its moves can go round any cycle of it, so one negative cycle makes every
    walk as low as we like: the search stops as soon as it meets one."""
    d = w.copy()
    # The empty walk: the move that leaves along h_{k+1} may itself land on h_k.
    np.fill_diagonal(d, np.minimum(np.diag(d), 0.0))
    through = np.empty_like(d)
    for k in range(len(d)):
        np.add(d[:, k, None], d[k], out=through)
        np.minimum(d, through, out=d)
        # A negative cycle shows on the diagonal by the step of its last move at the latest.
        if d[k, k] < 0:
            return np.full_like(d, -INF)
    return d
