"""Algorithm 3: grow a drawing by proposing rewrites and placing them (paper §6).

`Engine` holds the host drawing, the random generator and the history; one `step()` picks a
move and a match through the schedule, asks the cost whether to try it (Metropolis, on the
predicted counts), solves for positions (geometry.Solver: I rounds of J samples), commits the
first placement whose faces are labelled consistently, and records the journal so the step can
be undone and redone. The REPL drives the same engine one operation at a time (`matches`,
`apply`, `undo`, `redo`).
"""

from __future__ import annotations

import functools
import gc
import math
import time
from contextlib import contextmanager
from dataclasses import dataclass, field
from operator import add
from typing import Callable

import numpy as np

from grammar_lang import limits
from grammar_lang.algorithms.components import seed_groups
from grammar_lang.diagnostics import error
from grammar_lang.rules import Grammar

from ..geometry.change import Change
from ..geometry.framing import place_frame, random_inside
from ..geometry.landing import outer_label, sectors, spot
from ..geometry.rejections import Rejection
from ..geometry.solver import I_ROUNDS, J_SAMPLES, Solver, SystemCache
from ..geometry.spatial import Point
from ..geometry.stands import joined, least_reach, narrowest, rigid_box
from ..geometry.tables import Tables
from .costs import Cost, NoCost, Stats, metropolis_accepts
from .host import Host
from .late import LateRounds
from .matching import Match, iter_matches
from .rewrite import DirectedRule, commit, plan
from .schedule import Schedule

# Stop after this many proposals in a row that could not be placed or were refused.
MAX_STALL = 500
INTERRUPTED = "interrupted (Ctrl-C)"
# The level key under which edits outside the rules are counted; no schedule level uses it.
EDIT_LEVEL = -(2 ** 62)


@dataclass(frozen=True)
class StepRecord:
    """An applied step: enough to undo and redo it exactly."""

    rule: str
    forward: bool
    priority: int
    ops: tuple[tuple, ...]
    added: tuple[int, ...]
    removed: tuple[int, ...]
    moved: tuple[int, ...]


@dataclass
class Outcome:
    applied: StepRecord | None
    reason: Rejection | str = ""      # why not applied ("" when it was)
    # What step() proposed, applied or not (the REPL shows it).
    move: DirectedRule | None = None
    match: Match | None = None
    # Given up after its first round on its move's record (LateRounds): not tried in full.
    cut_short: bool = False


@dataclass
class Summary:
    applied: int = 0
    rejected: int = 0
    proposals: int = 0
    seconds: float = 0.0
    stop: str = ""
    reasons: dict[Rejection, int] = field(default_factory=dict)
    vertices: int = 0
    edges: int = 0


OPENING_TRIES = 50      # proposals for a connected grammar's one starter before giving up
# While run() holds the automatic garbage collection off, it collects the young generations
# itself after this many proposals.
COLLECT_EVERY = 1000


@contextmanager
def _collector_paused():
    """Automatic garbage collection off for a run, and back as the caller had it after;
    yields whether the caller had it on (then run() collects the young generations itself,
    every COLLECT_EVERY proposals). A step makes no reference cycles (1,000 steps of
    h-complex at 20,000 vertices left none for the collector), but the new parts of the
    drawing it keeps were walked by the young collections and then by full ones over the
    whole drawing: 0.7-1.9 s of the 9-11 s that growing h-complex to 20,000 vertices took."""
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield enabled
    finally:
        if enabled:
            gc.enable()


class Engine:
    def __init__(self, grammar: Grammar, seed: int = 0, cost: Cost | None = None,
                 temperature: float = 1.0, I: int = I_ROUNDS, J: int = J_SAMPLES,
                 bidirectional: bool | None = None, limits: dict[int, int] | None = None,
                 extent: tuple[float, float] | None = None):
        self.grammar = grammar
        frame = grammar.header.frame
        self.frame = frame.scaled(*extent) if frame is not None and extent else frame
        self.schedule = Schedule.build(grammar, bidirectional, limits)
        self.cost = cost or NoCost()
        self.temperature = temperature
        self.I, self.J = I, J
        self._deltas: dict[int, tuple] = {}
        self._outer: dict[int, str | None] = {}     # move → outer label of what it creates
        self._feet: dict[int, float] = {}           # move → its footprint (_footprint)
        self._narrowest: dict[int, float | None] = {}   # move → its narrowest stand (_too_short)
        self._outside: set[int] = set()             # moves that failed outside the frame
        self._reach: dict[int, list | None] = {}    # move → its least reach (_no_room)
        self.tables = Tables.build(grammar.header)
        if extent and frame is not None:
            self._check_extent(*extent)
        self._corners = sectors(self.tables)
        self.systems = SystemCache()       # factorisations by system shape, across steps
        self.reset(seed)

    def _check_extent(self, w: float, h: float) -> None:
        """Refuse an extent narrower or lower than a rigid part of the grammar's rule sides
        (stands.rigid_box): the part keeps its shape, so no drawing of that size holds it."""
        bw, bh = rigid_box(self.tables, (side for rule in self.grammar.rules
                                         for side in (rule.lhs, rule.rhs)))
        # Laid out from rounded lengths and directions, a part's box is a few 1e-7 off.
        tol = 1e-6 * self.tables.unit
        if bw > w + tol or bh > h + tol:
            raise error(f"a frame of {w:g} × {h:g} cannot hold the example's largest rigid "
                        f"parts ({bw:.4g} units wide, {bh:.4g} high; a rigid part keeps its "
                        "shape)", None, f"give an --extent of at least {bw:.4g}x{bh:.4g}")

    def reset(self, seed: int) -> None:
        self.seed = seed
        self.rng = np.random.default_rng(seed)
        self.host = Host(self.grammar.header, self.tables)
        if self.frame is not None:
            place_frame(self.host, self.frame, self.rng)
        self.history: list[StepRecord] = []
        self.redo_stack: list[StepRecord] = []
        self.applied_by_level: dict[int, int] = {}
        self.late = LateRounds()
        self._open()

    def _open(self) -> None:
        """A connected grammar's one starter, placed before the first step; it is the first
        record of the history, so undo can take it back like any step."""
        move = self.schedule.opening_move(self.rng)
        if move is None:
            return
        match = next(iter(self.matches(move, 1)), None)
        for _ in range(OPENING_TRIES if match is not None else 0):
            if self.apply(move, match, use_cost=False).applied is not None:
                return
        raise error(f"the connected grammar's starter {move.rule.name} could not be placed",
                    None, "check the frame's extent, or leave `connected` out")

    def reseed(self, seed: int) -> None:
        """Seed the random choices from here on; the drawing and history stay."""
        self.seed = seed
        self.rng = np.random.default_rng(seed)

    # --- looking ----------------------------------------------------------------------------
    def stats(self, change: Change | None = None) -> Stats:
        h = self.host
        nv, ne, counts = len(h), h.n_edges, list(h.label_count)
        if change is not None:
            nv += len(change.new) - len(change.removed)
            seen = set()
            for v in change.removed:
                for i, s in enumerate(h.link[v]):
                    if s is not None and min((v, i), s) not in seen:
                        seen.add(min((v, i), s))
                        ne -= 1
                        counts[h.t.label[h.prim[v]][i]] -= 1
            # The host edges its wires matched are cut, and glued anew to what replaces them.
            for v, i in change.cut:
                ne -= 1
                counts[h.t.label[h.prim[v]][i]] -= 1
            prims = dict(change.new)
            for (v, i), _ in change.glue:
                ne += 1
                p = prims.get(v, h.prim.get(v))
                counts[h.t.label[p][i]] += 1
        b = h.grid.bounds()
        area = 0.0 if b is None else (b[2] - b[0]) * (b[3] - b[1]) / h.t.unit ** 2
        return Stats(nv, ne, tuple(counts), area)

    def moves(self) -> list[DirectedRule]:
        return self.schedule.moves()

    def matches(self, move: DirectedRule, limit: int | None = None) -> list[Match]:
        out = []
        for m in iter_matches(self.host, move.pattern, self.schedule.spo):
            out.append(m)
            if limit is not None and len(out) >= limit:
                break
        return out

    # --- doing ------------------------------------------------------------------------------
    def step(self) -> Outcome:
        # The Metropolis coin is tossed for each move before its match is searched, on the
        # counts the move usually produces (they do not depend on where it matches when every
        # interface slot is glued); a refused move costs no search. The exact counts are
        # checked once the match is known, and a move that predicted them wrongly is tested
        # again on them.
        now = self.cost.value(self.stats())
        rise: dict[tuple, float] = {}       # cost change per count change, within this step
        after: dict[tuple, Stats] = {}      # the counts each change predicts, for apply()

        def screen(move: DirectedRule) -> bool:
            key = self._delta(move)
            if key not in rise:
                after[key] = self._stats_after(key)
                rise[key] = self.cost.value(after[key]) - now
            return metropolis_accepts(rise[key], self.temperature, float(self.rng.random()))

        choice = self.schedule.choose(self.host, self.rng, self.applied_by_level, screen)
        if choice is None:
            return Outcome(None, Rejection.TERMINAL)
        level, move, match, refused = choice
        if refused:
            return Outcome(None, Rejection.COST, move, match)
        key = self._delta(move)
        out = self.apply(move, match, priority=level.priority,
                         screened=after.get(key) or self._stats_after(key))
        out.move, out.match = move, match
        return out

    def _delta(self, move: DirectedRule) -> tuple:
        """How `move` changes the counts (vertices, edges, per label) when every interface
        slot of its match is glued: the same wherever it matches."""
        delta = self._deltas.get(id(move))
        if delta is None:
            rings = self.grammar.rings
            counts = [0] * len(self.host.label_count)
            ne = 0
            for side, sign in ((move.replacement, 1), (move.pattern.side, -1)):
                for v, i, _, _ in side.edges:
                    counts[rings[side.vertices[v]][i] >> 1] += sign
                    ne += sign
                for tok in side.wires:
                    counts[tok >> 1] += sign
                    ne += sign
            # Across the interface: where a wire end of one side meets a vertex slot of the
            # other, the edge from that slot to the context is one the wire's side does not
            # have (a wire replaced by a part is glued to its ends by two new edges).
            for (pv, pi), (rv, ri) in move.interface:
                if (pv < 0) != (rv < 0):
                    side, v, i, sign = ((move.replacement, rv, ri, 1) if pv < 0
                                        else (move.pattern.side, pv, pi, -1))
                    counts[rings[side.vertices[v]][i] >> 1] += sign
                    ne += sign
            dv = len(move.replacement.vertices) - len(move.pattern.side.vertices)
            delta = self._deltas[id(move)] = (dv, ne, tuple(counts))
        return delta

    def _stats_after(self, delta: tuple) -> Stats:
        h = self.host
        dv, ne, counts = delta
        b = h.grid.bounds()
        area = 0.0 if b is None else (b[2] - b[0]) * (b[3] - b[1]) / h.t.unit ** 2
        return Stats(len(h) + dv, h.n_edges + ne,
                     tuple(map(add, h.label_count, counts)), area)

    def apply(self, move: DirectedRule, match: Match, priority: int | None = None,
              use_cost: bool = True, screened: Stats | None = None) -> Outcome:
        """Place and commit `move` at `match`, unless the cost refuses it (`screened`: the
        counts its coin was already tossed on, when step() tossed it)."""
        host = self.host
        change = plan(host, move, match, self.schedule.spo)
        if host.pinned and not host.pinned.isdisjoint(change.removed):
            return Outcome(None, Rejection.MOVES_FRAME)
        if (move.rule.name, move.forward) in self.schedule.guarded and self._cuts(change):
            return Outcome(None, Rejection.SPLITS)
        after = self.stats(change) if use_cost else None
        if after is not None:
            if after != screened:
                delta = self.cost.value(after) - self.cost.value(self.stats())
                if not metropolis_accepts(delta, self.temperature, float(self.rng.random())):
                    return Outcome(None, Rejection.COST)
        if self._too_short(change):
            return Outcome(None, Rejection.NO_ROOM)
        if self._no_room(change):
            return Outcome(None, Rejection.FRAME_ROOM)
        fixed = self._center(change)
        # A free-standing new component may go anywhere: a fresh place for every sample.
        floating = self._floating(change)
        center = (lambda: self._center(change)) if floating else (lambda: fixed)
        key = (move.rule.name, move.forward)
        # Asked by the solver at its first sample and again after its first round: once.
        wanted = functools.cache(lambda: self._wanted(after))
        solver = Solver(host, change, self.rng, center, self.I, self.J, floating,
                        self.systems, go_on=lambda: wanted() or self.late.go_on(key),
                        wanted=wanted)
        region = [host.pos[v] for v in change.removed]
        region += [host.pos[v] for s0 in change.cut for v in (s0[0], host.link[s0[0]][s0[1]][0])]
        for placement in solver.placements():
            moved = tuple(sorted(v for v in placement.positions if v in host.prim))
            pts = region + [host.pos[v] for v in moved] + list(placement.positions.values())
            ops = commit(host, change, placement.positions)
            if self._faces_ok(placement.positions, pts):
                rec = StepRecord(move.rule.name, move.forward,
                                 move.rule.priority if priority is None else priority,
                                 tuple(ops), tuple(v for v, _ in change.new), change.removed,
                                 moved)
                self.history.append(rec)
                self.redo_stack.clear()
                lv = rec.priority
                self.applied_by_level[lv] = self.applied_by_level.get(lv, 0) + 1
                self._spent(key, solver, True)
                return Outcome(rec)
            host.undo_ops(ops)
            solver._fail(Rejection.FACE_LABELS)
        self._spent(key, solver, False)
        why = max(sorted(solver.failures), key=lambda k: solver.failures[k]) \
            if solver.failures else Rejection.NO_PLACEMENT
        if why == Rejection.OUTSIDE_FRAME:
            self._outside.add(id(change.rule))
        return Outcome(None, why, cut_short=solver.went_on is False)

    def _wanted(self, after: Stats | None) -> bool:
        """Whether the cost wants the change that gives the counts `after` (None: no cost)
        for the example's proportions (it lowers their part of the cost): such a proposal
        goes on with its late rounds whatever its move's record, and its samples are repaired
        (solver.repair). A part under its share is often one that is hard to place (the
        castle's gates need a gap of the right width), and only late rounds make room for
        it."""
        c = self.cost
        return after is not None and c.proportions(after) < c.proportions(self.stats())

    def _spent(self, key, solver: Solver, placed: bool) -> None:
        late = solver.samples - solver.late_from if solver.went_on else 0
        self.late.spent(key if solver.went_on else None, solver.samples, late, placed)

    def undo(self) -> StepRecord | None:
        if not self.history:
            return None
        rec = self.history.pop()
        self.host.undo_ops(list(rec.ops))
        self.applied_by_level[rec.priority] -= 1
        self.redo_stack.append(rec)
        return rec

    def redo(self) -> StepRecord | None:
        if not self.redo_stack:
            return None
        rec = self.redo_stack.pop()
        self.host.redo_ops(list(rec.ops))
        self.applied_by_level[rec.priority] = self.applied_by_level.get(rec.priority, 0) + 1
        self.history.append(rec)
        return rec

    # --- edits outside the rules (the REPL's reset and open) ----------------------------------
    def record_edit(self, name: str, ops: list[tuple]) -> StepRecord:
        """File host operations made outside any rule (journaled by the caller) as one step,
        so that undo and redo treat it like a rule application. It counts at no level."""
        added = tuple(op[1] for op in ops if op[0] == "add")
        removed = tuple(op[1] for op in ops if op[0] == "remove")
        rec = StepRecord(name, True, EDIT_LEVEL, tuple(ops), added, removed, ())
        self.history.append(rec)
        self.redo_stack.clear()
        self.applied_by_level[EDIT_LEVEL] = self.applied_by_level.get(EDIT_LEVEL, 0) + 1
        return rec

    def run(self, steps: int | None, progress: Callable[[Summary], None] | None = None,
            every: int = 50, stop: Callable[[], bool] | None = None,
            iterations: int | None = None) -> Summary:
        """Apply up to `steps` steps (None: no bound), in at most `iterations` proposals,
        applied or not (the paper's N, Algorithm 3); stops early on a terminal drawing, when
        `stop()` says so (it is asked between steps, so the drawing is always whole), or,
        without `iterations`, on a stall: with them the work is bounded already, and the
        paper's walk goes on proposing however many fail."""
        with _collector_paused() as collect:
            return self._run(steps, progress, every, stop, iterations, collect)

    def _run(self, steps, progress, every, stop, iterations, collect: bool) -> Summary:
        s = Summary()
        t0 = time.perf_counter()
        stall = 0
        most = limits.DRAWING.value()
        while (steps is None or s.applied < steps) and \
                (iterations is None or s.proposals < iterations):
            if stop is not None and stop():
                s.stop = INTERRUPTED
                break
            if len(self.host) >= most:
                s.stop = (f"the drawing reached the vertex limit ({most:,}); set "
                          f"{limits.DRAWING.env}=N to raise it")
                break
            out = self.step()
            if out.reason == Rejection.TERMINAL:
                s.stop = ("no rule applies to the empty drawing: the grammar has no starter "
                          "rule that creates a component" if len(self.host) == 0 else
                          "no rule applies (the drawing is terminal)")
                break
            s.proposals += 1
            if collect and s.proposals % COLLECT_EVERY == 0:
                gc.collect(1)
            if out.applied is not None:
                s.applied += 1
                stall = 0
            else:
                s.rejected += 1
                s.reasons[out.reason] = s.reasons.get(out.reason, 0) + 1
                # A stall is MAX_STALL proposals in a row tried in full: one cut short on its
                # move's record says nothing of whether the drawing can still grow (with them
                # counted, the paper's castle at seed 80 stopped at 1,567 of 4,000 steps).
                stall += not out.cut_short
                if stall >= MAX_STALL and iterations is None:
                    common = max(sorted(s.reasons), key=lambda k: s.reasons[k])
                    s.stop = (f"stalled: {MAX_STALL} proposals in a row, tried in full, were "
                              f"rejected (most often: {common})")
                    break
            if progress is not None and s.proposals % every == 0:
                s.seconds = time.perf_counter() - t0
                s.vertices, s.edges = len(self.host), self.host.n_edges
                progress(s)
        if not s.stop:
            s.stop = (f"reached {steps} steps" if steps is not None and s.applied >= steps
                      else f"reached {iterations} iterations")
        s.seconds = time.perf_counter() - t0
        s.vertices, s.edges = len(self.host), self.host.n_edges
        return s

    # --- helpers ----------------------------------------------------------------------------
    def _cuts(self, change: Change) -> bool:
        """Whether `change` leaves the parts it touches in more pieces than they were: its
        new vertices and new bare edges, after it, against the vertices and edges it matched,
        before. Asked before any geometry, of the moves the schedule guards."""
        host, new = self.host, dict(change.new)
        seeds = list(new) + [v for a, b in change.glue for v in (a[0], b[0])
                             if a[0] not in new and b[0] not in new]

        def after(v):
            p = new.get(v)
            return [s[0] for _, s in change.adjacency(host, v, host.prim[v] if p is None else p)]

        pieces = seed_groups(seeds, after)
        if pieces <= 1:
            return False
        was = list(change.removed) + [v for s in change.cut
                                      for v in (s[0], host.link[s[0]][s[1]][0])]
        return pieces > seed_groups(was, lambda v: [s[0] for s in host.link[v] if s is not None])

    def _floating(self, change: Change) -> bool:
        return not change.removed and all(b[0] not in self.host.prim for _, b in change.glue)

    def _center(self, change: Change) -> Point:
        """Where the change happens: the replaced part, else its context, else somewhere new."""
        host = self.host
        pts = [host.pos[v] for v in change.removed]
        if not pts and host.frame is not None and len(change.cut) == 1:
            # A structure stood on a bare stretch of the frame's side: anywhere along it.
            (v, i), = change.cut
            p, q = host.pos[v], host.pos[host.link[v][i][0]]
            # Aimed where its footprint fits between the stretch's ends: aimed anywhere, a
            # wide structure (a castle's block with its keep) mostly overlaps an end of a
            # short stretch and never places.
            margin = max(0.1, min(0.5, 0.5 * self._footprint(change) / (math.dist(p, q) or 1.0)))
            f = margin + (1.0 - 2.0 * margin) * float(self.rng.random())
            return (p[0] + f * (q[0] - p[0]), p[1] + f * (q[1] - p[1]))
        if not pts:
            pts = [host.pos[b[0]] for _, b in change.glue if b[0] in host.prim]
        if pts:
            return (sum(p[0] for p in pts) / len(pts), sum(p[1] for p in pts) / len(pts))
        n = len(host)
        if n == 0:
            return (0.0, 0.0)
        label = self._landing_label(change)
        if host.frame is not None and label in (None, host.t.exterior, host.frame_face):
            return random_inside(host, self.rng)
        if label is not None and label != host.t.exterior:
            p = spot(host, self.rng, self._corners.get(label, []), 0.5 * host.t.unit)
            if p is not None:
                return p
        # A new component: near a random vertex, a few units away in a random direction.
        k = int(self.rng.integers(n))
        for lst in host.by_prim:
            if k < len(lst):
                base = host.pos[lst[k]]
                break
            k -= len(lst)
        ang = float(self.rng.random()) * 2 * math.pi
        r = host.t.unit * (1.0 + 2.0 * float(self.rng.random()))
        return (base[0] + r * math.cos(ang), base[1] + r * math.sin(ang))

    def _too_short(self, change: Change) -> bool:
        """Whether `change` stands a structure on a stretch of the frame's side shorter than
        the structure can be drawn (stands.py): the solver would have to move the structures
        at the stretch's ends apart, which on the paper's castle it never did (0 of 1,804
        proposals on such stretches, seeds 80 and 0-3)."""
        if self.host.frame is None:
            return False
        least = self._per_move(self._narrowest, narrowest, change)
        if least is None:
            return False
        (v, i), = change.cut
        host = self.host
        return math.dist(host.pos[v], host.pos[host.link[v][i][0]]) < least - 1e-6 * host.t.unit

    def _no_room(self, change: Change) -> bool:
        """Whether a side of the frame is nearer an old vertex the new part hangs from than
        the part must reach beyond that vertex (stands.least_reach): a module put above the
        space station's top module, whose top lies 35 px under the frame's. Asked only of
        moves that have failed outside the frame before, in a rectangular frame. The reach
        is measured from where the vertex lies, and a later round may move it: on the paper's
        station 2 of 2,116 such proposals could have placed (seeds 22, 0, 1 at 4,000
        iterations, tests/test_stands.py), each an antenna under a module's bottom raised."""
        frame, host = self.host.frame, self.host
        if frame is None or not frame.rectangle or id(change.rule) not in self._outside:
            return False
        reach = self._per_move(self._reach, least_reach, change)
        if reach is None:
            return False
        x0, y0, x1, y1 = frame.box
        tol = 1e-6 * host.t.unit
        for v, need in zip(joined(change), reach):
            x, y = host.pos[v]
            if any(room < least - tol for room, least in zip((x1 - x, x - x0, y1 - y, y - y0),
                                                             need)):
                return True
        return False

    def _per_move(self, table: dict, compute, change: Change):
        """`compute(host, change)`, once per move: what it reads of the change (its new part,
        what it glues and cuts) is the same at every match of the move."""
        key = id(change.rule)
        if key not in table:
            table[key] = compute(self.host, change)
        return table[key]

    def _footprint(self, change: Change) -> float:
        """How much of a frame's side a structure stood on it covers at typical lengths: its
        new edges of a border class (along the side), but for the two that join it to the
        stretch's ends."""
        def footprint(host, change: Change) -> float:
            t, new = host.t, dict(change.new)
            return sum(t.typical[lab] for a, b in change.glue if a[0] in new and b[0] in new
                       for lab in (t.label[new[a[0]]][a[1]],)
                       if lab in host.border_labels and t.typical[lab] == t.typical[lab])
        return self._per_move(self._feet, footprint, change)

    def _landing_label(self, change: Change) -> str | None:
        return self._per_move(self._outer, lambda host, change: outer_label(
            self.tables, dict(change.new), lambda v, i: change.partner_after(host, v, i)),
            change)

    def _faces_ok(self, placed: dict[int, Point], pts: list[Point]) -> bool:
        host = self.host
        if host.t.one_face_label:
            return True
        todo = set(placed)
        if pts:
            # Any vertex whose face can have changed lies in the changed box (see face_ok).
            pad = 0.05 * host.t.unit
            xs, ys = [p[0] for p in pts], [p[1] for p in pts]
            todo.update(host.grid.points_near(min(xs) - pad, min(ys) - pad,
                                              max(xs) + pad, max(ys) + pad, False))
        # Each vertex's test is independent of the others: the order does not matter.
        prim = host.prim
        for v in todo:
            if v in prim and not host.face_ok(v):
                return False
        return True
