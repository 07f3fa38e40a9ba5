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
    # The side it makes has more pieces than the one it matches, so where it matches it may
    # cut the drawing in two; in a frame such a move is tested where it matches (`cuts_off`).
    may_cut: bool = False

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


def cuts_off(host: Host, change: Change) -> bool:
    """Whether `change` leaves the old vertices it touches in more connected pieces than they
    are in now: a part of the drawing would be cut off to float. The old vertices are joined
    through the rest of the drawing, not only through the match, so a move whose own sides
    split (a divider removed between two lines that both reach the frame) may still keep
    them together. Two searches over the pieces touched, before and after."""
    gone = set(change.removed)
    ends = {s[0] for v in change.removed for s in host.link[v] if s is not None}
    ends.update(v for s in change.cut for v in (s[0], host.link[s[0]][s[1]][0]))
    ends -= gone
    new = dict(change.new)

    def now(v):
        return (s[0] for s in host.link[v] if s is not None)

    def after(v):
        prim = new.get(v)
        return (s[0] for _, s in change.adjacency(host, v, host.prim[v] if prim is None else prim)
                if s[0] not in gone)

    return _pieces(sorted(ends), after) > _pieces(sorted(ends), now)


def _pieces(ends: list[int], neighbours) -> int:
    """In how many connected pieces the vertices `ends` lie, following `neighbours`."""
    seen: set[int] = set()
    count = 0
    for v in ends:
        if v in seen:
            continue
        count += 1
        seen.add(v)
        todo = [v]
        while todo:
            for w in neighbours(todo.pop()):
                if w not in seen:
                    seen.add(w)
                    todo.append(w)
    return count


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
