"""Algorithm 1: build the concrete hierarchy from the primitives and find rules as it grows.

Each new graph is, in this order: a duplicate (skipped); over the half-edge limit (§5.7); a
holder of an earlier rule's left side (reducible, dropped with all it would grow into, §5.2.1);
complete (a starter rule, §5.3.1); matched by simpler graphs (a rule, Algorithm 2); proven to
have no complete irreducible descendants (pruned, §5.6); or else irreducible, kept as a piece
for later matches and expanded in the next generation. After each generation every irreducible
graph is tried again as a left side, since simpler graphs may have appeared since (this is how
rules whose right side holds descendants of the left are found, §5.4-5.5). When such a rule turns
one whole block into graphs that hold it, the hierarchy is restructured (§5.4): those graphs
replace the block, and the hierarchy starts again from the new blocks (`_restructure`).

The grammar is complete when a generation leaves nothing to expand and no limit cut anything
off: then every graph of the abstract hierarchy is reducible, pruned or a duplicate, so every
complete graph reduces to ∅ (§5.2).
"""

from __future__ import annotations

import hashlib
import time
from collections import Counter
from dataclasses import asdict, dataclass, field, replace
from pathlib import Path
from typing import Callable

from grammar_lang import __version__
from grammar_lang import boundary as bd
from grammar_lang.example import Example
from grammar_lang.frame import Frame, border_labels, border_primitives, find_frame
from grammar_lang.graph import EMPTY, Side
from grammar_lang.rules import Grammar, Header, Rule

from . import grouping
from .regroup import regroup
from .canon import canonical_key, split
from .apply import side_graph
from .framing import frame_rules, frame_starters, frame_with_start, line_starters
from .gluing import Graph, block_slots, children, unit_places
from .hierarchy import KEPT, OVER, PRUNED, REDUCIBLE, RULE, Hierarchy, Node
from .boundary_match import Match, Matcher, Piece
from .occurrence import Host, Pattern, contains
from .pruning import TurnAnalysis

# Work of the example-starter stage per allowed hierarchy graph (a component of n vertices costs
# n²): the default 1000 graphs admit components up to 1000 vertices.
STARTER_WORK_PER_GRAPH = 1000
SELF_CHECK_PRIMITIVES = 5     # complete graphs this small are verified before claiming "complete"
SELF_CHECK_GRAPHS = 1500
HIERARCHY_SHARE = 0.85     # of the time limit; the rest is for the example's starters
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
    frame_rules_dropped: int = 0      # rules that would create, move or delete the frame
    rules_beside: int = 0             # of `rules`, those grown beside a complete set
    rules_stood: int = 0              # of `rules`, those that stand a structure on the frame
                                      # or on a line across it (framing)
    # The same few remaining graphs, for drawing (`ggc report`); not part of the JSON summary.
    remaining_sides: tuple[Side, ...] = field(default=(), compare=False)

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
        del d["remaining_sides"]
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


def _covers(have: dict, need: dict) -> bool:
    """Whether `have` counts at least as many of each thing as `need`. A plain loop with
    .get: it runs for every rule an anchor may start and rejects most, and any() over a
    generator with Counter's __missing__ took a third of the time."""
    for key, n in need.items():
        if have.get(key, 0) < n:
            return False
    return True


class Inference:
    def __init__(self, example: Example, progress: Progress | None = None, group: bool = True):
        self.ex = example
        self.rings = [p.ring for p in example.primitives]
        self.ring_len = [len(r) for r in self.rings]
        opts = example.options
        self.limits = opts.limits
        self.loops = not opts.no_loops
        self.splice = not (opts.connected or opts.no_loops)
        self.progress = progress
        self.frame = find_frame(example)      # a border that is not one loop is reported here
        self.t0 = time.perf_counter()
        self.structural: list[Rule] = []     # §5.4 rules that restructured the blocks
        # The next blocks to start from: with the §5.4 rule that restructured them, or with
        # None when the rules found so far regrouped them (and are kept).
        self.pending: tuple[list[Graph], set[int], Rule | None] | None = None
        self.limits_hit: set[str] = set()
        self.spent = 0        # graphs of the hierarchies started again from other blocks
        self.group = group
        self.carry = None     # what a regrouping passes on to the next turning analysis
        self.reached: set = set()     # starters a framed example's components reduce to
        self.faces = True             # faces rule out moves and force blocks (faces.py)
        self.left = None              # the blocks faces regrouped away from, and which group
        self.beside: set[str] = set()     # names of the rules _grow_beside found
        self._start(grouping.blocks(self.rings, enabled=group, loops=self.loops), original=None)

    def _start(self, blocks: list[Graph], original: set[int] | None,
               kept: list[_Rule] = ()) -> None:
        """A fresh hierarchy glued from `blocks`; `original` are those that group primitives
        (companion §3.3) rather than stand for a §5.4 rule's right side; `kept` are rules found
        before, which still reduce the graphs holding their left sides."""
        self.blocks = [replace(b, units=(k,)) for k, b in enumerate(blocks)]
        self.original = set(range(len(blocks))) if original is None else original
        self.slots = block_slots(self.blocks, self.rings)
        self.hier = Hierarchy(self.ring_len)
        self.matcher = Matcher(splice=self.splice)
        self.turns = TurnAnalysis(self.rings, self.blocks)
        self.turns.holds_left_side = self._face_holds_left_side
        self.state = _State(limits_hit=self.limits_hit)
        for r in kept:
            self._index_rule(r)
        self.frontier: list[int] = []
        self.generation = 0
        for lab in range(len(self.ex.labels)):
            a = 2 * lab
            self.matcher.add(Piece(-1 - lab, ((a + 1, 0), (a, 1)), (2, -1 - lab)))

    # --- driver -----------------------------------------------------------------------------

    def run(self) -> CompileResult:
        self._grow()
        while self.pending is not None:
            blocks, original, rule = self.pending
            self.pending = None
            self.spent += len(self.hier.nodes)
            kept: list[_Rule] = []
            if rule is None:
                kept = self.state.rules
            else:
                self.carry = None
                self.structural.append(replace(rule, name=f"r{len(self.structural)}"))
            self._start(blocks, original, kept)
            if self.carry is not None:
                self._carry_turns()
            self._grow()
        self._grow_beside()
        return self._result()

    def _grow_beside(self) -> None:
        """When faces merged blocks and the grammar came out complete, the hierarchy they
        regrouped away from is grown on, with the complete rules known and neither faces nor
        regrouping, within the graphs the verdict left, and the rules it finds are kept. A
        complete set builds each graph one way (the station's modules only hang from the one
        above); these build the same graphs other ways (a module put above another), so runs
        grow more. They leave the verdict alone: its hierarchy is put back, and so are its
        limits."""
        if self.left is None or self._limited():
            return
        verdict = (self.hier, self.frontier, self.generation, self.blocks, self.original,
                   self.slots, self.matcher, self.turns, self.spent, set(self.limits_hit))
        self.spent += len(self.hier.nodes)
        self.faces = self.group = False
        kept = len(self.state.rules)
        self._start(*self.left, self.state.rules)
        self._grow()
        self.beside = {r.rule.name for r in self.state.rules[kept:]}
        self.pending, self.faces, self.group = None, True, True
        state = self.state
        (self.hier, self.frontier, self.generation, self.blocks, self.original, self.slots,
         self.matcher, self.turns, self.spent, limits_hit) = verdict
        self.limits_hit.clear()
        self.limits_hit.update(limits_hit)
        self.state = state

    def _limited(self) -> bool:
        return bool(self.state.limits_hit) or \
            any(self.hier.nodes[i].status == KEPT for i in self.frontier)

    def _interrupted(self) -> bool:
        return self.pending is not None or self._out_of_time() or self._too_many()

    def _grow(self) -> None:
        self.generation = 1
        for b in self.blocks:
            self._process(b, 1, None, tuple(range(len(b.verts))))
            if self.pending is not None:
                return
        self._recheck()
        self._regroup()
        self._tick()
        while self._expandable() and self.pending is None and not self._out_of_time():
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
                    if self._interrupted():
                        break
                if self._interrupted():
                    break
            if self.pending is not None:
                return
            self._recheck()
            self._regroup()
            if self.pending is not None:
                return
            self._tick()
            if self._too_many():
                break

    def _expandable(self) -> bool:
        """Whether the frontier still holds a graph to expand: its graphs may have become
        rules or reducible since they were met, and a generation of none of them is empty."""
        nodes = self.hier.nodes
        return any(nodes[nid].status == KEPT for nid in self.frontier)

    def _tick(self) -> None:
        if self.progress:
            self.progress(self.generation, self.spent + len(self.hier.nodes),
                          len(self.structural) + len(self.state.rules))

    def _out_of_time(self) -> bool:
        if self.limits.seconds is None:
            return False
        if time.perf_counter() - self.t0 > self.limits.seconds * HIERARCHY_SHARE:
            self.state.limits_hit.add("time")
            return True
        return False

    def _too_many(self) -> bool:
        if self.spent + len(self.hier.nodes) >= self.limits.graphs:
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
        if rules is None:
            cand: set[int] = set()
            for a in anchors:
                cand.update(self.state.by_prim.get(g.verts[a], ()))
            rules = sorted(cand)
        size, have = len(g.verts), g.prim_counts
        for r in rules:
            rr = self.state.rules[r]
            if len(rr.lhs.verts) > size or not _covers(have, rr.prims):
                continue      # a match is one-to-one (and starters can be whole drawings)
            if not _covers(g.edge_counts, rr.lhs.edge_counts):
                continue
            if host is None:
                host = Host(g.verts, g.edges)
            if contains(rr.pattern, host, anchors) and not any(
                    contains(e, host) for e in rr.exceptions):
                return True
        return False

    def _face_holds_left_side(self, g: Graph) -> bool:
        """Whether a face's ring of units holds the left side of a rule that reduces every
        graph holding it (one with no §5.4 exceptions; a starter's is a whole graph)."""
        rules = [k for k, r in enumerate(self.state.rules) if not r.exceptions]
        return self._holds_left_side(g, None, rules)

    def _recheck(self) -> None:
        """Try every irreducible graph again as a left side against newer, simpler graphs;
        then prune those still to be expanded that the faces the rules leave (faces.py) rule
        out."""
        self._recheck_rules()
        if self.pending is not None or self._out_of_time() or not self.faces:
            return
        if not self.turns.kill_by_faces():
            return
        for nid in self.frontier:      # not yet expanded
            node = self.hier.nodes[nid]
            if node.status == KEPT and self.turns.dead_end(node.graph):
                node.status = PRUNED
                self.matcher.remove(node.id)

    def _recheck_rules(self) -> None:
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
                if self.pending is not None:
                    return

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
        name = f"{'s' if starter else 'r'}{len(self.structural) + len(self.state.rules)}"
        rule = Rule(name, lhs, rhs, priority=0, weight=1.0)
        if exceptions:
            plan = self._restructure(g, graphs)
            if plan is not None:
                node.status = RULE
                self.pending = (*plan, rule)
                return
        idx = self._index_rule(_Rule(g, Pattern.of(g), exceptions, rule, g.prim_counts))
        node.status = RULE
        if not exceptions:
            self.turns.rules_changed()     # the faces that glue this left side are gone
            if not starter:
                self._forbid(g)
        self._drop_holders(idx, node.id)

    def _index_rule(self, r: _Rule) -> int:
        idx = len(self.state.rules)
        self.state.rules.append(r)
        for p in sorted(set(r.lhs.verts)):
            self.state.by_prim.setdefault(p, []).append(idx)
        return idx

    def _regroup(self) -> None:
        """Start again from the live blocks, forced pairs glued (regroup.py), when the rules
        found so far pair slots off."""
        if self.pending is not None or not self.group:
            return
        found = regroup(self.turns, self.blocks, self.faces)
        if found is None:
            return
        parts, pairs, by_faces = found
        if by_faces and self.left is None:
            self.left = (list(self.blocks), set(self.original))
        merged, place = grouping.merge([self.blocks[u] for u in parts], pairs,
                                       self.rings, self.loops)
        size = [0] * len(merged)
        for b, _ in place:
            size[b] += 1
        # Blocks left alone keep their order and merged ones follow, smaller first: of two
        # with equal boundaries the earlier is the simpler, and a merged block is what the
        # old hierarchy would have met later, as a glued graph.
        order = sorted(range(len(merged)),
                       key=lambda b: (size[b] > 1, len(merged[b].verts) * (size[b] > 1), b))
        new_id = {b: n for n, b in enumerate(order)}
        where: dict[int, list[tuple[int, int]]] = {}      # old block → (new block, first vertex)
        for n, u in enumerate(parts):
            where.setdefault(u, []).append((new_id[place[n][0]], place[n][1]))
        original = {new_id[b] for b in range(len(merged))
                    if all(u in self.original for n, u in enumerate(parts) if place[n][0] == b)}
        self.carry = (self.turns, self.blocks, where)
        self.pending = ([merged[b] for b in order], original, None)

    def _carry_turns(self) -> None:
        """The moves and move pairs the old blocks' rules ruled out stay ruled out between the
        same slots of the new blocks: a graph gluing them holds the same left side."""
        old, old_blocks, where = self.carry
        self.carry = None
        new = self.turns

        def ends(u: int, k: int) -> list[tuple[int, int]]:
            out = []
            for b, first in where.get(u, ()):
                v, i = old_blocks[u].gaps[k][0]
                kk = new.slot_of[b].get((first + v, i))
                if kk is not None:
                    out.append((b, kk))
            return out

        def moves(m: int) -> list[int]:
            p, i, q, j = old.moves[m]
            return [new.index[(*a, *c)] for a in ends(p, i) for c in ends(q, j)
                    if (*a, *c) in new.index]

        for m in old.dead:
            new.dead.update(moves(m))
        for m1, m2 in old.dead_pairs:
            new.dead_pairs.update((n1, n2) for n1 in moves(m1) for n2 in moves(m2))
        new.unsolve()

    def _forbid(self, g: Graph) -> None:
        """Tell the turning analysis what an irreducible graph can no longer hold: a left side
        that is one whole unit removes the unit; two units joined by one edge remove that move;
        three joined in a chain whose two joining edges leave the middle one from consecutive
        open slots remove that move-after-move transition."""
        places = unit_places(g, [len(b.verts) for b in self.blocks])
        if places is None or len(g.edges) != len(g.units) - 1 + sum(
                len(self.blocks[u].edges) for u in g.units):
            return      # unknown units, or a left side that also closes a loop
        inter = [e for e in g.edges if places[e[0]][0] != places[e[2]][0]]

        def slot(v: int, i: int) -> tuple[int, int]:
            k, base = places[v]
            return g.units[k], self.turns.slot_of[g.units[k]][(v - base, i)]

        if len(g.units) == 1:
            self.turns.forbid_unit(g.units[0])
        elif len(g.units) == 2:
            v, i, w, j = inter[0]
            self.turns.forbid_edge(*slot(v, i), *slot(w, j))
        elif len(g.units) == 3:
            (v1, i1, w1, j1), (v2, i2, w2, j2) = inter
            for q, j, a, ai in ((v1, i1, w1, j1), (w1, j1, v1, i1)):
                for q2, j2_, c, ci in ((v2, i2, w2, j2), (w2, j2, v2, i2)):
                    if places[q][0] != places[q2][0]:
                        continue
                    ua, ka = slot(a, ai)
                    m, k1 = slot(q, j)
                    _, k2 = slot(q2, j2_)
                    uc, kc = slot(c, ci)
                    n = len(self.turns.rings[m])
                    if k2 == (k1 + 1) % n:     # walk a → middle (k1), on to k2, → c
                        self.turns.forbid_pair((ua, ka, m, k1), (m, k2, uc, kc))
                    if k1 == (k2 + 1) % n:     # walk c → middle (k2), on to k1, → a
                        self.turns.forbid_pair((uc, kc, m, k2), (m, k1, ua, ka))

    def _restructure(self, lhs: Graph, graphs: list[Graph]) -> tuple[list[Graph], set[int]] | None:
        """§5.4: a rule that turns one whole block X into right-side graphs that each hold X
        once. Applied destructively to every X that no right-side graph covers, it leaves a
        graph in which every X lies inside some right-side graph; when those graphs can claim
        disjoint parts (below), such a graph is glued from the right-side graphs and the other
        blocks alone. So X leaves the blocks and the right-side graphs become blocks: the
        hierarchy restarts from them, with this rule kept (it makes no graph reducible, since
        every graph of the new hierarchy holds X).

        Claims are disjoint when X is an original block, every other block of a right-side
        graph is an original block glued to X directly, and for each kind of block the sets of
        its slots glued to X pairwise meet: a block claimed by two X's would then have one slot
        glued to both."""
        if len(lhs.units) != 1 or len(lhs.edges) != len(self.blocks[lhs.units[0]].edges):
            return None
        x = lhs.units[0]
        if x not in self.original:
            return None
        sizes = [len(b.verts) for b in self.blocks]
        claims: dict[int, list[frozenset]] = {}
        new: list[Graph] = []
        keys: set = set()
        for h in graphs:
            if x not in h.units:
                continue
            places = unit_places(h, sizes)
            if places is None or h.units.count(x) != 1:
                return None
            xi = h.units.index(x)
            glued: dict[int, set] = {}
            for v, i, w, j in h.edges:
                for (a, ai), (b, bi) in (((v, i), (w, j)), ((w, j), (v, i))):
                    if places[a][0] != xi and places[b][0] == xi:
                        glued.setdefault(places[a][0], set()).add((a - places[a][1], ai))
            for k, u in enumerate(h.units):
                if k == xi:
                    continue
                if u not in self.original or k not in glued:
                    return None
                claims.setdefault(u, []).append(frozenset(glued[k]))
            key = canonical_key(h, self.ring_len)
            if key not in keys:
                keys.add(key)
                new.append(h)
        if not new:
            return None
        for sets in claims.values():
            if any(not (s & t) for s in sets for t in sets):
                return None
        kept = [k for k in range(len(self.blocks)) if k != x]
        original = {n for n, k in enumerate(kept) if k in self.original}
        return [self.blocks[k] for k in kept] + new, original

    def _drop_holders(self, idx: int, lhs_id: int) -> None:
        """Irreducible and over-limit graphs that hold the new left side are reducible now
        (with §5.4's exception for graphs that hold one of the rule's own right-side graphs).
        Only graphs with the left side's rarest primitive can hold it."""
        by_prim = self.hier.by_prim
        rarest = min(self.state.rules[idx].prims, key=lambda p: len(by_prim.get(p, ())))
        for nid in by_prim.get(rarest, ()):
            other = self.hier.nodes[nid]
            if other.id == lhs_id or other.status not in (KEPT, OVER):
                continue
            if self._holds_left_side(other.graph, None, [idx]):
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
        boundary = bd.from_gaps((items[k], n) for k, (_, n) in enumerate(lhs.gaps))
        return Side(tuple(verts), tuple(sorted(edges)), boundary,
                    wires=tuple(wires)), graphs

    # --- result -----------------------------------------------------------------------------

    def _self_check(self) -> None:
        """A last guard on the claim "complete": the smallest complete graphs must reduce to ∅.
        (The claim rests on every reduction making progress; a failure here means it did not,
        and the report says so rather than claim too much.)"""
        from .verify import verify
        grammar = Grammar(header(self.ex, True), self._rules())
        res = verify(grammar, SELF_CHECK_PRIMITIVES, cap=SELF_CHECK_GRAPHS)
        if res.failed:
            self.state.limits_hit.add("self-check")

    def _example_starters(self) -> None:
        """A starter for each of the example's own connected components that the rules cannot
        reduce to ∅. A complete grammar reduces them all, so this adds nothing to one; a limited
        grammar may never have met a complete graph (or met it only as the holder of a left side
        that reduces it through a vertex-less loop), and would otherwise draw nothing."""
        from .verify import Reducer
        # The stage counts against the graphs limit: big examples are a lot of work.
        work = self.limits.graphs * STARTER_WORK_PER_GRAPH
        if self.ex.graph is not None and self.ex.vertex_primitive:
            parts = split(self.ex.vertex_primitive, example_slots(self.ex))
            if len(affordable(parts, work)) < len(parts):
                self.state.limits_hit.add("graphs")
        graphs = example_graphs(self.ex, work)
        if not graphs:
            return
        on_border = set() if self.frame is None else \
            border_primitives(self.ex.primitives, border_labels(self.ex.labels, self.ex.classes))
        own = {canonical_key(g, self.ring_len) for g in graphs}
        self.reached = self._reached_starters(graphs, own)
        own |= self.reached
        for g in graphs:
            if not self.loops and len(g.edges) >= len(g.verts):
                continue      # the option forbids loops: a drawing with a cycle is no output
            if on_border.intersection(g.verts):
                continue      # it holds the frame, which generation starts from instead
            rules = self._rules()     # with the starters added for earlier components
            if self.frame is not None:
                # In a frame only the example's own components stand free: a component must
                # reduce without the starters framing drops (one module of a station, say).
                rules, _ = frame_rules(rules, self.ex, own)
            grammar = Grammar(header(self.ex, False), rules)
            # Past the time limit a component simply becomes a starter, which is always sound.
            deadline = float("inf") if self.limits.seconds is None \
                else self.t0 + self.limits.seconds
            # Runs open with the example's own structures, not with a smaller starter they
            # reduce to (`_reached_starters`): a starter for each, which builds nothing new.
            if not self.reached and Reducer(grammar, apply_budget=EXAMPLE_CHECK_STEPS,
                                            deadline=deadline).reduces(g):
                continue
            node, _ = self.hier.lookup_or_add(g, self.generation, None)
            self._add_rule(node, None)

    def _reached_starters(self, graphs: list[Graph], own: set) -> set:
        """In a frame, the starters framing would drop that an example component of a
        connected example reduces to: kept, they build nothing that the example's own starter
        would not (every rule keeps a connected graph connected, so the component reduces to
        that one graph, and back), and `ggc verify` finds that graph reducible. A lone module
        of the space station is one."""
        if self.frame is None or not self.ex.options.connected:
            return set()
        from .verify import Reducer

        def reduces(rules: tuple[Rule, ...], g: Graph) -> bool:
            grammar = Grammar(header(self.ex, False), rules)
            return Reducer(grammar, apply_budget=EXAMPLE_CHECK_STEPS).reduces(g)

        kept, _ = frame_rules(self._rules(), self.ex, own)
        border = border_primitives(self.ex.primitives,
                                   border_labels(self.ex.labels, self.ex.classes))
        # Components that hold the frame reduce to it whatever the starters; those that
        # reduce without a dropped starter do not show that they reach it.
        free = [g for g in graphs if not border.intersection(g.verts) and not reduces(kept, g)]
        out = set()
        for r in self._rules():
            if not r.is_starter or r in kept:
                continue
            key = canonical_key(side_graph(r.lhs), self.ring_len)
            if not frame_rules((r,), self.ex, {key})[0]:
                continue      # dropped for holding the frame, not for being no example part
            if any(reduces(kept + (r,), g) for g in free):
                out.add(key)
        return out

    def _reached_unopened(self, rules: tuple[Rule, ...]) -> tuple[Rule, ...]:
        """The reached starters with weight 0: they stay for reduction (`ggc verify`), but a
        run opens with the example's own structures. Opening with the station's lone module,
        whose only growing rule hangs a module under another, drew half the station."""
        def key(r: Rule):
            return canonical_key(side_graph(r.lhs), self.ring_len)
        return tuple(replace(r, weight=0.0) if r.is_starter and key(r) in self.reached else r
                     for r in rules)

    def _rules(self) -> tuple[Rule, ...]:
        return tuple(self.structural) + tuple(r.rule for r in self.state.rules)

    def _result(self) -> CompileResult:
        st = self.state
        self._example_starters()
        if self.hier.count(OVER):
            st.limits_hit.add("half-edges")
        if not self._limited():
            self._self_check()
        front = {i for i in self.frontier if self.hier.nodes[i].status == KEPT}
        remaining = [n for n in self.hier.nodes
                     if n.status == OVER or (n.status == KEPT and n.id in front)]
        limited = self._limited()
        shown = sorted(remaining, key=lambda n: n.rank)[:5]
        rules = self._rules()
        dropped = 0
        stood: tuple[Rule, ...] = ()
        if self.frame is not None:
            own = {canonical_key(g, self.ring_len) for g in example_graphs(self.ex)}
            rules, dropped = frame_rules(rules, self.ex, own | self.reached)
            rules = self._reached_unopened(rules)
            slots = example_slots(self.ex)
            stood = frame_starters(self.ex, slots)
            stood += line_starters(self.ex, slots, {canonical_key(side_graph(r.lhs),
                                                                  self.ring_len) for r in rules})
            rules += stood
            self.frame = frame_with_start(self.frame, self.ex, slots)
        report = Report(
            example=self.ex.name,
            primitives=len(self.rings),
            blocks=len(self.blocks),
            hierarchy_graphs=self.spent + len(self.hier.nodes),
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
            frame_rules_dropped=dropped,
            rules_beside=sum(1 for r in rules if r.name in self.beside),
            rules_stood=len(stood),
            remaining_sides=tuple(n.graph.side() for n in shown),
        )
        return CompileResult(Grammar(header(self.ex, not limited, self.frame), rules), report)


def header(ex: Example, complete: bool, frame: Frame | None = None) -> Header:
    digest = ""
    try:
        digest = hashlib.sha256(Path(ex.path).read_bytes()).hexdigest()
    except OSError:
        pass
    return Header(source=ex.path, source_hash=digest, compiler_version=__version__,
                  vocabulary=ex.vocabulary, options=ex.options, decorations=ex.decorations, complete=complete, frame=frame)


def example_slots(ex: Example) -> list[tuple[int, int, int, int]]:
    """The example drawing's edges as glued slot pairs (u, i, v, j), one per drawing edge."""
    rings = [ex.primitives[p].ring for p in ex.vertex_primitive]
    edges = []
    for (u, v, *_), (label, forward) in zip(ex.graph.edges, ex.edge_label):
        a = (u, rings[u].index(bd.half(label, not forward)))
        b = (v, rings[v].index(bd.half(label, forward)))
        edges.append(min(a, b) + max(a, b))
    return edges


def example_graphs(ex: Example, work: int | None = None) -> list[Graph]:
    """The example drawing's connected components as complete graphs of primitive instances,
    one per isomorphism class, in canonical order; with `work`, only those `affordable` picks."""
    if ex.graph is None or not ex.vertex_primitive:
        return []
    parts = split(ex.vertex_primitive, example_slots(ex))
    if work is not None:
        parts = affordable(parts, work)
    ring_len = [len(p.ring) for p in ex.primitives]
    unique = {canonical_key(g, ring_len): g for g in parts}
    return [unique[k] for k in sorted(unique)]


def affordable(parts: list[Graph], work: int) -> list[Graph]:
    """The components, smallest first, that fit in `work`: one of n vertices costs n² (its
    canonical key and match plans take that much)."""
    kept, spent = [], 0
    for g in sorted(parts, key=lambda g: len(g.verts)):
        spent += len(g.verts) ** 2
        if spent > work:
            break
        kept.append(g)
    return kept


def compile_example(example: Example, progress: Progress | None = None) -> CompileResult:
    return Inference(example, progress).run()
