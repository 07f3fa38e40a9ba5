"""Algorithm 1: build the concrete hierarchy from the primitives and find rules as it grows.

Each new graph is, in this order: a duplicate (skipped); over the half-edge limit (§5.7); a
holder of an earlier rule's left side (reducible, dropped with all it would grow into, §5.2.1);
complete (a starter rule, §5.3.1); matched by simpler graphs (a rule, Algorithm 2); proven to
have no complete irreducible descendants (pruned, §5.6); or else irreducible, kept as a piece
for later matches and expanded in the next generation. After each generation every irreducible
graph is tried again as a left side, since simpler graphs may have appeared since (this is how
rules whose right side holds descendants of the left are found, §5.4-5.5).

The grammar is complete when a generation leaves nothing to expand and no limit cut anything
off: then every graph of the abstract hierarchy is reducible, pruned or a duplicate, so every
complete graph reduces to ∅ (§5.2).
"""

from __future__ import annotations

import hashlib
import time
from collections import Counter
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Callable

from grammar_lang import __version__
from grammar_lang import boundary as bd
from grammar_lang.example import Example
from grammar_lang.graph import EMPTY, Side
from grammar_lang.rules import Grammar, Header, Rule

from . import grouping
from .canon import canonical_key, components, split
from .gluing import Graph, block_slots, children
from .hierarchy import KEPT, OVER, PRUNED, REDUCIBLE, RULE, Hierarchy, Node
from .matching import Match, Matcher, Piece
from .occurrence import Host, Pattern, contains
from .pruning import TurnAnalysis

SELF_CHECK_PRIMITIVES = 5     # complete graphs this small are verified before claiming "complete"
SELF_CHECK_GRAPHS = 1500
EXAMPLE_CHECK_STEPS = 300  # rule applications tried on an example component before it gets a starter
Progress = Callable[[int, int, int], None]     # (generation, hierarchy graphs, rules)


@dataclass(frozen=True)
class Report:
    example: str
    primitives: int
    blocks: int
    hierarchy_graphs: int
    irreducible: int
    pruned: int
    rules: int
    starters: int
    generations: int
    seconds: float
    complete: bool
    limits_hit: tuple[str, ...] = ()
    remaining: int = 0
    remaining_boundaries: tuple[str, ...] = ()

    @property
    def verdict(self) -> str:
        if self.complete:
            return "complete: every locally similar graph can be built"
        if self.limits_hit == ("self-check",):
            return ("limited (self-check): the hierarchy closed, but a small complete graph "
                    "does not reduce to ∅; run `ggc verify` to see which")
        return (f"limited ({', '.join(self.limits_hit) or 'search cut short'}): "
                f"{self.remaining} irreducible graphs remain")

    def as_dict(self) -> dict:
        d = asdict(self)
        d["verdict"] = self.verdict
        return d


@dataclass(frozen=True)
class CompileResult:
    grammar: Grammar
    report: Report


@dataclass
class _Rule:
    lhs: Graph
    pattern: Pattern
    exceptions: tuple[Pattern, ...]      # §5.4: right-side graphs that hold the left side
    rule: Rule
    prims: Counter = field(default_factory=Counter)


@dataclass
class _State:
    rules: list[_Rule] = field(default_factory=list)
    by_prim: dict[int, list[int]] = field(default_factory=dict)
    limits_hit: set[str] = field(default_factory=set)


class Inference:
    def __init__(self, example: Example, progress: Progress | None = None, group: bool = True):
        self.ex = example
        self.rings = [p.ring for p in example.primitives]
        self.ring_len = [len(r) for r in self.rings]
        opts = example.options
        self.limits = opts.limits
        self.loops = not opts.no_loops
        self.hier = Hierarchy(self.ring_len)
        self.matcher = Matcher(splice=not (opts.connected or opts.no_loops))
        self.turns = TurnAnalysis(self.rings)
        self.state = _State()
        self.progress = progress
        self.blocks = grouping.blocks(self.rings, enabled=group)
        self.slots = block_slots(self.blocks, self.rings)
        self.forced: set[tuple[int, int, int, int]] = set()
        for p, i, q, j in grouping.forced_pairs(self.rings):
            self.forced.update({(p, i, q, j), (q, j, p, i)})
        self.block_size = {p: len(b.verts) for b in self.blocks for p in b.verts}
        self.block_sizes = {p: {len(b.verts)} for b in self.blocks for p in b.verts}
        self.frontier: list[int] = []
        self.t0 = time.perf_counter()
        self.generation = 0
        for lab in range(len(example.labels)):
            a = 2 * lab
            self.matcher.add(Piece(-1 - lab, ((a + 1, 0), (a, 1)), (2, -1 - lab)))

    # --- driver -----------------------------------------------------------------------------

    def run(self) -> CompileResult:
        self.generation = 1
        for b in self.blocks:
            self._process(b, 1, None, tuple(range(len(b.verts))))
        self._recheck()
        self._tick()
        while self.frontier and not self._out_of_time():
            if self.generation >= self.limits.generations:
                self.state.limits_hit.add("generations")
                break
            self.generation += 1
            current, self.frontier = self.frontier, []
            for nid in current:
                node = self.hier.nodes[nid]
                if node.status != KEPT:
                    continue
                for _, child, anchors in children(node.graph, self.blocks, self.rings,
                                                  self.loops, self.slots):
                    self._process(child, self.generation, nid, anchors)
                    if self._out_of_time() or self._too_many():
                        break
                if self._out_of_time() or self._too_many():
                    break
            self._recheck()
            self._tick()
            if self._too_many():
                break
        return self._result()

    def _tick(self) -> None:
        if self.progress:
            self.progress(self.generation, len(self.hier.nodes), len(self.state.rules))

    def _out_of_time(self) -> bool:
        if time.perf_counter() - self.t0 > self.limits.seconds:
            self.state.limits_hit.add("time")
            return True
        return False

    def _too_many(self) -> bool:
        if len(self.hier.nodes) >= self.limits.graphs:
            self.state.limits_hit.add("graphs")
            return True
        return False

    # --- one new graph ----------------------------------------------------------------------

    def _process(self, g: Graph, gen: int, parent: int | None, anchors) -> None:
        node, new = self.hier.lookup_or_add(g, gen, parent)
        if not new:
            return
        # A graph that holds a rule's left side is reducible whatever its size.
        if self._holds_left_side(g, anchors):
            node.status = REDUCIBLE
            return
        if g.n_half > self.limits.half_edges:
            node.status = OVER
            return
        if g.is_complete:
            self._add_rule(node, None)
            return
        match = self.matcher.find(g.tokens(self.rings), node.rank)
        node.checked = self.matcher.version
        if match is not None:
            self._add_rule(node, match)
            return
        if self.turns.dead_end(g):
            node.status = PRUNED
            return
        self._keep(node)

    def _keep(self, node: Node) -> None:
        node.status = KEPT
        self.matcher.add(Piece(node.id, node.graph.tokens(self.rings), node.rank))
        self.frontier.append(node.id)

    def _holds_left_side(self, g: Graph, anchors, rules=None) -> bool:
        """Whether g holds a rule's left side; with `anchors`, one that uses a new vertex (the
        parent held none)."""
        host: Host | None = None
        have = Counter(g.verts)
        if rules is None:
            cand: set[int] = set()
            for a in anchors:
                cand.update(self.state.by_prim.get(g.verts[a], ()))
            rules = sorted(cand)
        for r in rules:
            rr = self.state.rules[r]
            if any(have[p] < n for p, n in rr.prims.items()):
                continue
            if host is None:
                host = Host(g.verts, g.edges)
            if contains(rr.pattern, host, anchors) and not any(
                    contains(e, host) for e in rr.exceptions):
                return True
        return False

    def _recheck(self) -> None:
        """Try every irreducible graph again as a left side against newer, simpler graphs."""
        for node in self.hier.kept():
            if node.status != KEPT or node.checked == self.matcher.version:
                continue
            if self._out_of_time():
                return
            match = self.matcher.find(node.graph.tokens(self.rings), node.rank)
            node.checked = self.matcher.version
            if match is not None:
                self.matcher.remove(node.id)
                self._add_rule(node, match)

    # --- rules ------------------------------------------------------------------------------

    def _add_rule(self, node: Node, match: Match | None) -> None:
        g = node.graph
        lhs = g.side()
        if match is None:
            rhs = EMPTY
            exceptions: tuple[Pattern, ...] = ()
        else:
            rhs, graphs = self._right_side(g, match)
            # A rule that does not shrink the vertex count reduces a graph holding its left
            # side only when the graph holds none of its right-side graphs (§5.4: otherwise
            # the rule may just turn R back into itself, or swap two equal-sized parts).
            exceptions = ()
            if len(rhs.vertices) >= len(g.verts):
                exceptions = tuple(Pattern.of(h) for h in graphs)
        starter = match is None
        name = f"{'s' if starter else 'r'}{len(self.state.rules)}"
        rule = Rule(name, lhs, rhs, priority=0, weight=1.0)
        idx = len(self.state.rules)
        self.state.rules.append(_Rule(g, Pattern.of(g), exceptions, rule, Counter(g.verts)))
        for p in sorted(set(g.verts)):
            self.state.by_prim.setdefault(p, []).append(idx)
        node.status = RULE
        if not exceptions and not starter:
            self._forbid(g)
        self._drop_holders(idx, node.id)

    def _forbid(self, g: Graph) -> None:
        """Tell the turning analysis what an irreducible graph can no longer hold: a left side
        that is one whole block removes its primitives; two blocks joined by one edge remove
        that kind of edge (blocks are glued whole, so the edge brings both blocks along)."""
        inter = [e for e in g.edges
                 if (g.verts[e[0]], e[1], g.verts[e[2]], e[3]) not in self.forced]
        if not inter and len(g.verts) in self.block_sizes.get(g.verts[0], ()):
            for p in sorted(set(g.verts)):
                self.turns.forbid_primitive(p)
        elif len(inter) == 1:
            v, i, w, j = inter[0]
            rest = tuple(e for e in g.edges if e != inter[0])
            parts = components(len(g.verts), rest)
            if len(parts) == 2 and all(len(c) == self.block_size[g.verts[c[0]]] for c in parts):
                self.turns.forbid_edge(g.verts[v], i, g.verts[w], j)
        elif len(inter) == 2:
            rest = tuple(e for e in g.edges if e not in inter)
            parts = components(len(g.verts), rest)
            if len(parts) != 3 or any(len(c) != self.block_size[g.verts[c[0]]] for c in parts):
                return
            ends1 = {(inter[0][0], inter[0][1]), (inter[0][2], inter[0][3])}
            ends2 = {(inter[1][0], inter[1][1]), (inter[1][2], inter[1][3])}
            for q, j1 in ends1:
                for q2, j2 in ends2:
                    if q2 != q:
                        continue
                    (a, ai), = ends1 - {(q, j1)}
                    (c, ci), = ends2 - {(q, j2)}
                    pa, pq, pc = g.verts[a], g.verts[q], g.verts[c]
                    n = self.ring_len[pq]
                    if j2 == (j1 + 1) % n:     # walk a → q (slot j1), on to j2, → c
                        self.turns.forbid_pair((pa, ai, pq, j1), (pq, j2, pc, ci))
                    if j1 == (j2 + 1) % n:     # walk c → q (slot j2), on to j1, → a
                        self.turns.forbid_pair((pc, ci, pq, j2), (pq, j1, pa, ai))

    def _drop_holders(self, idx: int, lhs_id: int) -> None:
        """Irreducible and over-limit graphs that hold the new left side are reducible now
        (with §5.4's exception for graphs that hold one of the rule's own right-side graphs)."""
        for other in self.hier.nodes:
            if other.id == lhs_id or other.status not in (KEPT, OVER):
                continue
            g = other.graph
            if self._holds_left_side(g, None, [idx]):
                other.status = REDUCIBLE
                self.matcher.remove(other.id)

    def _right_side(self, lhs: Graph, match: Match) -> tuple[Side, list[Graph]]:
        m = len(lhs.gaps)
        items: list = [None] * m
        verts: list[int] = []
        edges: list = []
        wires: list[int] = []
        graphs: list[Graph] = []
        for piece, pos in match:
            if piece.node < 0:
                e = len(wires)
                wires.append(2 * (-1 - piece.node))
                items[pos[0]] = (-1 - e, 1)       # ā end
                items[pos[1]] = (-1 - e, 0)       # a end
                continue
            h = self.hier.nodes[piece.node].graph
            graphs.append(h)
            off = len(verts)
            verts.extend(h.verts)
            edges.extend((v + off, i, w + off, j) for v, i, w, j in h.edges)
            for (slot, _), k in zip(h.gaps, pos):
                items[k] = (slot[0] + off, slot[1])
        boundary: list = []
        for k, (_, n) in enumerate(lhs.gaps):
            boundary.append(items[k])
            boundary.extend(bd.turns(n))
        return Side(tuple(verts), tuple(sorted(edges)), tuple(boundary),
                    wires=tuple(wires)), graphs

    # --- result -----------------------------------------------------------------------------

    def _self_check(self) -> None:
        """A last guard on the claim "complete": the smallest complete graphs must reduce to ∅.
        (The claim rests on every reduction making progress; a failure here means it did not,
        and the report says so rather than claim too much.)"""
        from .verify import verify
        grammar = Grammar(header(self.ex, True), tuple(r.rule for r in self.state.rules))
        res = verify(grammar, SELF_CHECK_PRIMITIVES, cap=SELF_CHECK_GRAPHS)
        if res.failed:
            self.state.limits_hit.add("self-check")

    def _example_starters(self) -> None:
        """A starter for each of the example's own connected components that the rules cannot
        reduce to ∅. A complete grammar reduces them all, so this adds nothing to one; a limited
        grammar may never have met a complete graph (or met it only as the holder of a left side
        that reduces it through a vertex-less loop), and would otherwise draw nothing."""
        from .verify import Reducer
        graphs = example_graphs(self.ex)
        if not graphs:
            return
        for g in graphs:
            if not self.loops and len(g.edges) >= len(g.verts):
                continue      # the option forbids loops: a drawing with a cycle is no output
            grammar = Grammar(header(self.ex, False), tuple(r.rule for r in self.state.rules))
            if Reducer(grammar, apply_budget=EXAMPLE_CHECK_STEPS).reduces(g):
                continue
            node, _ = self.hier.lookup_or_add(g, self.generation, None)
            self._add_rule(node, None)

    def _result(self) -> CompileResult:
        st = self.state
        self._example_starters()
        if self.hier.count(OVER):
            st.limits_hit.add("half-edges")
        if not st.limits_hit and not any(self.hier.nodes[i].status == KEPT for i in self.frontier):
            self._self_check()
        front = {i for i in self.frontier if self.hier.nodes[i].status == KEPT}
        remaining = [n for n in self.hier.nodes
                     if n.status == OVER or (n.status == KEPT and n.id in front)]
        limited = bool(st.limits_hit) or bool(front)
        shown = sorted(remaining, key=lambda n: n.rank)[:5]
        rules = tuple(r.rule for r in st.rules)
        report = Report(
            example=self.ex.name,
            primitives=len(self.rings),
            blocks=len(self.blocks),
            hierarchy_graphs=len(self.hier.nodes),
            irreducible=self.hier.count(KEPT),
            pruned=self.hier.count(PRUNED),
            rules=sum(1 for r in rules if not r.is_starter),
            starters=sum(1 for r in rules if r.is_starter),
            generations=self.generation,
            seconds=round(time.perf_counter() - self.t0, 4),
            complete=not limited,
            limits_hit=tuple(sorted(st.limits_hit)),
            remaining=len(remaining),
            remaining_boundaries=tuple(self.ex.format(n.graph.string(self.rings))
                                       for n in shown),
        )
        return CompileResult(Grammar(header(self.ex, not limited), rules), report)


def header(ex: Example, complete: bool) -> Header:
    digest = ""
    try:
        digest = hashlib.sha256(Path(ex.path).read_bytes()).hexdigest()
    except OSError:
        pass
    return Header(source=ex.path, source_hash=digest, compiler_version=__version__,
                  exterior=ex.exterior, face_labels=ex.face_labels, classes=ex.classes,
                  labels=ex.labels, primitives=ex.primitives, options=ex.options, unit=ex.unit,
                  decorations=ex.decorations, complete=complete)


def example_graphs(ex: Example) -> list[Graph]:
    """The example drawing's connected components as complete graphs of primitive instances,
    one per isomorphism class, in canonical order."""
    if ex.graph is None or not ex.vertex_primitive:
        return []
    rings = [ex.primitives[p].ring for p in ex.vertex_primitive]
    edges = []
    for (u, v, *_), (label, forward) in zip(ex.graph.edges, ex.edge_label):
        a = (u, rings[u].index(bd.half(label, not forward)))
        b = (v, rings[v].index(bd.half(label, forward)))
        edges.append(min(a, b) + max(a, b))
    ring_len = [len(p.ring) for p in ex.primitives]
    unique = {canonical_key(g, ring_len): g for g in split(ex.vertex_primitive, edges)}
    return [unique[k] for k in sorted(unique)]


def compile_example(example: Example, progress: Progress | None = None) -> CompileResult:
    return Inference(example, progress).run()
