"""DPO rewriting in both directions, and the SPO variant.

A rule's two sides share one boundary string, position by position; the open slots at the same
position are the same interface point (grammar_lang.rules). Applying a rule in a direction
matches its `pattern` side, removes the matched vertices, adds a fresh copy of the other side
and glues each of its open slots to whatever the matched slot at the same position was glued
to. Forward is lhs → rhs (destructive in the paper, §6.1), backward is rhs → lhs (constructive).
A starter's empty side matches everywhere once, so backward it creates a component and forward
it deletes one.

The DPO gluing condition is the dangling condition: an interface slot must not be glued to a
vertex inside the match, since that edge would lose its end. In SPO mode such an edge is
deleted instead and both its slots are left open in the result.

The gluing of the replacement into the hole is the kernel's (grammar_lang.algorithms.dpo); this
module finds the contexts (dangling condition, SPO, the host edges matched by wires) and
applies the change. `plan` only computes the change (a `Change`, runtime.geometry.change);
geometry decides the positions and `commit` applies it through the host's journal, returning
the operations so that a step can be undone and redone.
"""

from __future__ import annotations

from dataclasses import dataclass

from grammar_lang import boundary as bd
from grammar_lang.algorithms.dpo import join_interface
from grammar_lang.graph import Side, Slot
from grammar_lang.rules import Rule

from ..geometry.change import Change
from .host import Host, Point
from .matching import Match, Pattern


@dataclass(frozen=True)
class DirectedRule:
    rule: Rule
    forward: bool
    pattern: Pattern
    replacement: Side
    # Open slot of `replacement` for each open slot of the pattern, in boundary order.
    interface: tuple[tuple[Slot, Slot], ...]

    @property
    def name(self) -> str:
        return self.rule.name + ("" if self.forward else " (backward)")

    @property
    def creates_component(self) -> bool:
        return not self.pattern.side.vertices

    @staticmethod
    def build(rule: Rule, forward: bool, rings) -> "DirectedRule":
        pat, rep = (rule.lhs, rule.rhs) if forward else (rule.rhs, rule.lhs)
        p_open, r_open = pat.open_slots(), rep.open_slots()
        # Half-edges must agree position by position (turns differ for a starter's ∧ vs ε).
        if bd.halves(pat.tokens(rings)) != bd.halves(rep.tokens(rings)):
            raise ValueError(f"rule {rule.name}: the two sides' boundary strings differ")
        return DirectedRule(rule, forward, Pattern.build(pat, rings), rep,
                            tuple(zip(p_open, r_open)))


def plan(host: Host, rule: DirectedRule, match: Match, spo: bool = False) -> Change:
    removed = tuple(sorted(match.vmap))
    gone = set(removed)
    rep = rule.replacement
    ids = [host.new_id() for _ in rep.vertices]
    new = tuple(zip(ids, rep.vertices))
    partner: dict = {}
    glue = []
    for v, i, w, j in rep.edges:
        a, b = (ids[v], i), (ids[w], j)
        glue.append((a, b))
        partner[a], partner[b] = b, a
    cut = tuple(s0 for s0, _ in match.wmap)
    for s0, s1 in match.wmap:
        partner[s0] = partner[s1] = None
    contexts, ends = [], []
    for p_slot, r_slot in rule.interface:
        c = match.partner_of(host, p_slot)
        if c is not None and c[0] in gone:
            if not spo:
                raise ValueError("dangling edge in DPO mode; the match should have been refused")
            c = None
        contexts.append(c)
        ends.append(r_slot if r_slot[0] < 0 else (ids[r_slot[0]], r_slot[1]))
    joined, opened = join_interface(contexts, ends)
    for a, c in joined:
        glue.append((a, c))
        partner[a], partner[c] = c, a
    for s in opened:
        partner[s] = None
    for k, (v, prim) in enumerate(new):
        for i in range(len(host.t.rings[prim])):
            partner.setdefault((v, i), None)
    return Change(rule, match, removed, new, tuple(glue), cut, partner)


def commit(host: Host, change: Change, positions: dict[int, Point]) -> list[tuple]:
    """Apply the change with the given positions (new and moved vertices); the journal."""
    host.begin()
    try:
        for s in change.cut:
            host.unglue(s)
        for v in change.removed:
            for i, s in enumerate(host.link[v]):
                if s is not None:
                    host.unglue((v, i))
            host.remove_vertex(v)
        for v in sorted(positions):
            if v in host.prim:
                host.move(v, positions[v])
        for v, prim in change.new:
            host.add_vertex(v, prim, positions[v])
        for a, b in change.glue:
            host.glue(a, b)
    except BaseException:
        host.undo_ops(host.end())
        raise
    return host.end()
