"""`ggc verify`: check a grammar against every complete graph up to N primitives.

The complete graphs are enumerated independently of the grammar: every connected graph glued
from the primitives (branch gluing, and loop gluing of consecutive half-edges, companion §3.1)
with at most N vertices, without duplicates. Each complete one must reduce to ∅ by applying the
rules destructively (§5.2). Components reduce independently, so the search is a memoised
recursion over connected components: a component reduces when some rule application turns it
into components that all reduce.

A grammar drawn in a frame (Appendix A) starts from its frame, not from ∅: no rule creates or
deletes the frame, so a component that holds it reduces when it becomes the frame itself (bare,
or its start graph), which generation places before the first step.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Callable, Sequence

from grammar_lang.frame import bare_sides
from grammar_lang.rules import Grammar

from .apply import apply, side_graph, wired_pairs
from .canon import Key, canonical_key, split
from .gluing import Graph, Slot, block_slots, children, primitive_graph
from .grouping import forced_groups
from .occurrence import Host, Pattern, matches


@dataclass
class VerifyResult:
    checked: int = 0
    failed: list[Graph] = field(default_factory=list)
    stopped: str = ""               # why the check is partial: "graph cap", "time limit" or ""
    skipped_rules: list[str] = field(default_factory=list)
    enumerated: int = 0             # complete graphs found (all checked unless stopped)

    @property
    def ok(self) -> bool:
        return not self.failed

    @property
    def enumeration_capped(self) -> bool:
        return self.stopped == "graph cap"


class _SizeBound:
    """How many vertices a partial graph still needs at least. From its open half-edges: those
    of token t beyond the open ones of token t̄ must each meet a new vertex's t̄ slot. And from
    forced groups (companion §3.3): a complete graph that holds one primitive of a group holds
    every other one too, so each primitive missing from a group the graph has begun is one
    more vertex (a rigid blossom of nine primitives cannot be part of a complete graph of
    five)."""

    def __init__(self, rings: Sequence[Sequence[int]], prims: Sequence[Graph], max_prims: int,
                 groups: bool = True):
        self.rings, self.max_prims = rings, max_prims
        self.group = {p: frozenset(g) for g in forced_groups(rings) if len(g) > 1
                      for p in g} if groups else {}
        self.mult: dict[int, int] = {}
        for r in rings:
            for t in set(r):
                self.mult[t] = max(self.mult.get(t, 0), r.count(t))
        self.widest = max((len(r) for r in rings), default=1) or 1
        self.prim_open = [self.open_counts(p) for p in prims]

    def open_counts(self, g: Graph) -> dict[int, int]:
        count: dict[int, int] = {}
        for (v, i), _ in g.gaps:
            t = self.rings[g.verts[v]][i]
            count[t] = count.get(t, 0) + 1
        return count

    def begun(self, present: set[int]) -> set[frozenset[int]]:
        """The groups that `present` holds some primitive of."""
        return {self.group[p] for p in present if p in self.group}

    def missing(self, present: set[int]) -> int:
        """The primitives the groups begun in `present` still lack."""
        return sum(len(g - present) for g in self.begun(present))

    def too_big(self, n: int, count: dict[int, int]) -> bool:
        """Whether `n` vertices with these open half-edges need more than `max_prims`: some
        token's excess needs more new vertices than there is room for, or all of them do."""
        room = self.max_prims - n
        if room < 0:
            return True
        total = 0
        for t, c in count.items():
            extra = c - count.get(t ^ 1, 0)
            if extra > 0:
                m = self.mult.get(t ^ 1)
                total += extra
                if m is None or extra > m * room or total > self.widest * room:
                    return True
        return False

    def rejects(self, g: Graph) -> bool:
        n = len(g.verts)
        return (n + self.missing(set(g.verts)) > self.max_prims
                or self.too_big(n, self.open_counts(g)))

    def admit_for(self, g: Graph) -> Callable[[Slot, int, Slot], bool]:
        """The bound applied to a branch gluing before the child is built. (The glued t and t̄
        leave every token's excess over its opposite as it was: they are left in the count.)"""
        base, n = self.open_counts(g), len(g.verts)
        present = set(g.verts)
        begun = self.begun(present)
        lacking = self.missing(present)

        def admit(s: Slot, b: int, t: Slot) -> bool:
            more = lacking
            if b not in present and b in self.group:
                grp = self.group[b]
                more += -1 if grp in begun else len(grp) - 1
            if n + 1 + more > self.max_prims:
                return False
            count = dict(base)
            for tok, c in self.prim_open[b].items():
                count[tok] = count.get(tok, 0) + c
            return not self.too_big(n + 1, count)
        return admit


def complete_graphs(rings: Sequence[Sequence[int]], max_prims: int, loops: bool = True,
                    cap: int = 200000, deadline: float | None = None,
                    progress: Callable[[int, int], None] | None = None,
                    prefilter: bool = True) -> tuple[list[Graph], str]:
    """Every complete connected graph with at most `max_prims` vertices, and why the
    enumeration stopped early ("graph cap" after `cap` graphs, "time limit" at `deadline`, a
    `time.perf_counter()` value), or "". `progress(graphs seen, vertices)` after each size.
    `prefilter` applies the size bound to a branch gluing before its child is built and
    counts the primitives that forced groups still lack (the same graphs are found either
    way; without it is only for testing that)."""
    ring_len = [len(r) for r in rings]
    prims = [primitive_graph(p, len(r)) for p, r in enumerate(rings)]
    slots = block_slots(prims, rings)
    bound = _SizeBound(rings, prims, max_prims, groups=prefilter)
    seen: set[Key] = set()
    out: list[Graph] = []
    frontier: list[Graph] = []
    for g in prims:
        if len(g.verts) + bound.missing(set(g.verts)) > max_prims:
            continue
        k = canonical_key(g, ring_len)
        if k not in seen:
            seen.add(k)
            (out if g.is_complete else frontier).append(g)
    while frontier:
        nxt: list[Graph] = []
        for g in frontier:
            if deadline is not None and time.perf_counter() > deadline:
                return out, "time limit"
            admit = bound.admit_for(g) if prefilter else None
            for kind, child, _ in children(g, prims, rings, loops, slots, admit):
                # An admitted branch child already passed the bound; a loop gluing drops a
                # t, t̄ pair, which leaves the bound as it was for the parent, but a parent
                # may be a primitive that never met it.
                if (admit is None or kind == "loop") and bound.rejects(child):
                    continue
                k = canonical_key(child, ring_len)
                if k in seen:
                    continue
                seen.add(k)
                if len(seen) > cap:
                    return out, "graph cap"
                (out if child.is_complete else nxt).append(child)
        frontier = nxt
        if progress and frontier:
            progress(len(seen), len(frontier[0].verts))
    return out, ""


MAX_DEPTH = 64


class Reducer:
    def __init__(self, grammar: Grammar, budget: int = 3000, apply_budget: float = float("inf"),
                 deadline: float = float("inf")):
        self.rings = grammar.rings
        self.ring_len = [len(r) for r in self.rings]
        self.rules = []
        self.skipped: list[str] = []
        for r in grammar.rules:
            if len(r.lhs.components()) != 1 or r.lhs.wires:
                self.skipped.append(r.name)
                continue
            # No reduction may close R's wires into a loop with no vertex (see occurrence).
            self.rules.append((r, Pattern.of(side_graph(r.lhs), wired_pairs(r.rhs))))
        self.memo: dict[Key, bool] = {}
        axiom = frame_graph(grammar)
        if axiom is not None:
            self.memo[canonical_key(axiom, self.ring_len)] = True
        self.budget = budget
        self.apply_budget = apply_budget     # rule applications per graph (growing rules)
        self.steps = 0
        self.applied = 0
        self.depth = 0
        self.deadline = deadline              # time.perf_counter() value
        self.max_verts = 0

    def reduces(self, g: Graph) -> bool:
        self.steps = self.applied = 0
        # Rules that grow a graph (§5.4) could lead down an endless chain: a way down may pass
        # through graphs up to twice the size of the start, and no deeper than MAX_DEPTH.
        self.max_verts = 2 * len(g.verts) + 16
        ok = self._reduces(g)
        # A failure may only mean "every way down passed through a graph then in progress";
        # such failures are not final, so only successes (and the frame) are remembered.
        self.memo = {k: v for k, v in self.memo.items() if v}
        return ok

    def _reduces(self, g: Graph) -> bool:
        key = canonical_key(g, self.ring_len)
        hit = self.memo.get(key)
        if hit is not None:
            return hit
        self.memo[key] = False        # in progress: a cycle back here is no way down
        self.steps += 1
        self.depth += 1
        ok = (self.steps <= self.budget and self.depth <= MAX_DEPTH
              and len(g.verts) <= self.max_verts and self._try(g))
        self.depth -= 1
        self.memo[key] = ok
        return ok

    def _try(self, g: Graph) -> bool:
        host = Host(g.verts, g.edges)
        for rule, pat in self.rules:
            for img in matches(pat, host):
                self.applied += 1
                if (self.steps > self.budget or self.applied > self.apply_budget
                        or time.perf_counter() > self.deadline):
                    return False      # out of budget: no further way down is tried
                h = Host(g.verts, g.edges)
                apply(rule.lhs, rule.rhs, img, h)
                live = h.live()
                idx = {v: k for k, v in enumerate(live)}
                edges = sorted({tuple(sorted(((idx[v], i), (idx[w], j))))
                                for v in live for i, (w, j) in h.part[v].items()})
                flat = [(a[0], a[1], b[0], b[1]) for a, b in edges]
                parts = split([h.verts[v] for v in live], flat)
                if any(len(p.verts) and _open(p, self.ring_len) for p in parts):
                    continue   # a malformed result (a rule with inconsistent sides)
                if all(self._reduces(p) for p in parts):
                    return True
        return False


def frame_graph(grammar: Grammar) -> Graph | None:
    """What generation starts from, as a graph: the frame's start graph, or its corners with
    one border edge a side; None without a frame."""
    h = grammar.header
    if h.frame is None:
        return None
    if h.frame.start is not None:
        return side_graph(h.frame.start)
    n = len(h.frame.corners)
    sides = bare_sides(h.frame, h.primitives, h.labels)
    if any(s is None for s in sides):
        return None       # a frame generation cannot place either (ggrun says why)
    edges = []
    for k, (i, j) in enumerate(sides):
        a, b = sorted(((k, i), ((k + 1) % n, j)))
        edges.append((a[0], a[1], b[0], b[1]))
    return Graph(tuple(c.prim for c in h.frame.corners), tuple(sorted(edges)), ())


def _open(g: Graph, ring_len) -> bool:
    glued = {(v, i) for v, i, _, _ in g.edges} | {(w, j) for _, _, w, j in g.edges}
    return len(glued) != sum(ring_len[p] for p in g.verts)


def verify(grammar: Grammar, max_prims: int = 10, progress: Callable[[int, int], None] | None = None,
           cap: int = 200000, seconds: float | None = None,
           enumerating: Callable[[int, int], None] | None = None) -> VerifyResult:
    """Reduce every complete graph of at most `max_prims` primitives; with `seconds`, stop
    (enumerating or reducing) when they run out and say so in `stopped`."""
    deadline = None if seconds is None else time.perf_counter() + seconds
    loops = not grammar.header.options.no_loops
    graphs, stopped = complete_graphs(grammar.rings, max_prims, loops, cap, deadline, enumerating)
    red = Reducer(grammar)
    res = VerifyResult(stopped=stopped, skipped_rules=red.skipped, enumerated=len(graphs))
    for n, g in enumerate(sorted(graphs, key=lambda g: (len(g.verts), g.verts, g.edges))):
        if deadline is not None and time.perf_counter() > deadline:
            res.stopped = "time limit"
            break
        res.checked += 1
        if not red.reduces(g):
            res.failed.append(g)
        if progress:
            progress(n + 1, len(graphs))
    return res
