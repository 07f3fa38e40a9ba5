"""Rules for an example drawn in a frame (paper Appendix A).

The frame is the border of the space, not a shape to copy. Generation starts from it, so:
- no starter may create any part of it (a starter holding a border half-edge would draw a
  second, free-floating piece of border);
- no rule may touch its corners, the vertices where the border turns. A rule replaces every
  vertex of its matched side, so one holding a corner would move, delete or duplicate it;
- the only free-standing parts are those the example has free-standing (a window inside a
  tower). A smaller complete graph the hierarchy met, say a roof with no tower under it, is
  locally similar too, but a scene is made of structures that stand on its frame.
Rules may still hold the vertices on its straight sides, where structures stand and lines end:
the side runs on through them, and a rule's boundary keeps the border half-edges it cuts.
"""

from __future__ import annotations

from grammar_lang import boundary as bd
from grammar_lang.algorithms.components import glued_components
from dataclasses import replace

from grammar_lang.frame import (Frame, bare_sides, border_labels, border_primitives,
                                corner_primitives, across_labels)
from grammar_lang.graph import Side, face_walk
from grammar_lang.rules import Rule

from .apply import side_graph
from .canon import canonical_key


def frame_rules(rules: tuple[Rule, ...], example, own: set) -> tuple[tuple[Rule, ...], int]:
    """The rules that leave the frame alone, and how many were dropped; `own` holds the
    canonical keys of the example's own components."""
    ring_len = [len(p.ring) for p in example.primitives]
    border = border_labels(example.labels, example.classes)
    corners = corner_primitives(example.primitives, example.labels, border)
    on_border = border_primitives(example.primitives, border)
    kept = []
    for r in rules:
        verts = set(r.lhs.vertices) | set(r.rhs.vertices)
        wires = {w >> 1 for w in r.lhs.wires + r.rhs.wires}
        if r.is_starter and (verts & on_border or wires & border
                             or canonical_key(side_graph(r.lhs), ring_len) not in own):
            continue
        if verts & corners:
            continue
        kept.append(r)
    return tuple(kept), len(rules) - len(kept)


def frame_with_start(frame: Frame, example, slot_edges) -> Frame:
    """The frame, with the example's frame component as its start when a side cannot be
    drawn bare (lines meet it, so its border label changes along it)."""
    if all(s is not None for s in bare_sides(frame, example.primitives, example.labels)):
        return frame
    corners = {c.prim for c in frame.corners}
    prims = example.vertex_primitive
    comp = next(c for c in glued_components(range(len(prims)), slot_edges)
                if any(prims[v] in corners for v in c))
    idx = {v: k for k, v in enumerate(comp)}
    edges = tuple(sorted((idx[v], i, idx[w], j) for v, i, w, j in slot_edges if v in idx))
    return replace(frame, start=Side(tuple(prims[v] for v in comp), edges, ()))


def frame_starters(example, slot_edges) -> tuple[Rule, ...]:
    """Rules that stand the example's structures on a bare side of the frame.

    With the frame as the start, nothing would grow: the inferred starters drew whole example
    components, frame included. Instead, every structure that stands on a side between two
    stretches of bare side (its two cut border half-edges carry a label that a corner carries,
    the side as it is with nothing on it) becomes a rule `structure ⇄ that one side edge`,
    a wired rule (§4.3): grown, it puts a copy of an example structure on the side, so the
    drawing stays locally similar. A structure that stands on several feet takes the bare
    side between its feet with it. Structures that stand on a line across the frame from
    side to side are `line_starters`'.
    """
    border = border_labels(example.labels, example.classes)
    corners = corner_primitives(example.primitives, example.labels, border)
    prims = example.vertex_primitive
    rings = [example.primitives[p].ring for p in prims]
    prim_rings = [p.ring for p in example.primitives]
    bare = {bd.label_of(t) for v, p in enumerate(prims) if p in corners
            for t in rings[v] if bd.label_of(t) in border}
    keep = [e for e in slot_edges
            if prims[e[0]] not in corners and prims[e[2]] not in corners
            and bd.label_of(rings[e[0]][e[1]]) not in bare]
    ring_len = [len(r) for r in prim_rings]
    return tuple(_standing(glued_components(range(len(prims)), keep), slot_edges, prims,
                           prim_rings, ring_len, "stand",
                           lambda comp: prims[comp[0]] not in corners))


def line_starters(example, slot_edges, taken: set) -> tuple[Rule, ...]:
    """Rules that stand the example's structures on a line across the frame
    (`frame.across_labels`), as `frame_starters` stands them on a side: with every edge of
    one such label cut, each piece that hangs on the rest by two half-edges of that label
    only, and whose boundary is that label's bare edge, becomes a rule `structure ⇄ that
    edge`. Grown, it puts a copy of an example structure on any edge of the label, so the
    drawing stays locally similar. Lines that end in the air are left alone: on a castle's
    wall tops such a rule put a merlon into the side of a merlon, and rows of teeth came out
    as stairs. The hierarchy finds such a rule only once it has glued the whole structure:
    the paper's village, limited at 1,000 graphs, had one for its flat-roofed house and none
    for its two houses of two parts, which it could add only beside one of their kind.
    `taken`: the canonical keys of rules' left sides the grammar has already; structures on
    the border are the frame's."""
    border = border_labels(example.labels, example.classes)
    on_border = border_primitives(example.primitives, border)
    prims = example.vertex_primitive
    rings = [example.primitives[p].ring for p in prims]
    prim_rings = [p.ring for p in example.primitives]
    ring_len = [len(r) for r in prim_rings]
    labels = sorted(across_labels(example.primitives, example.labels, example.classes))
    rules: list[Rule] = []
    seen = set(taken)
    for lab in labels:
        keep = [e for e in slot_edges if bd.label_of(rings[e[0]][e[1]]) != lab]
        rules += _standing(glued_components(range(len(prims)), keep), slot_edges, prims,
                           prim_rings, ring_len, "line",
                           lambda comp: not any(prims[v] in on_border for v in comp), seen,
                           first=len(rules))
    return tuple(rules)


def _standing(comps, slot_edges, prims, prim_rings, ring_len, name: str, wanted,
              seen: set | None = None, first: int = 0) -> list[Rule]:
    """`structure ⇄ edge` for each of `comps` that `wanted` keeps and stands on one edge,
    one rule per shape (`seen`: canonical keys of left sides already had), named `name`
    and a number from `first`."""
    rules, seen = [], set() if seen is None else seen
    for comp in comps:
        if not wanted(comp):
            continue
        # A structure on several feet (a platform's legs) holds the side between them too.
        members = set(comp)
        inner = [e for e in slot_edges if e[0] in members and e[2] in members]
        side = _component_side(comp, inner, prims, prim_rings)
        rule = None if side is None else \
            _standing_rule(side, prim_rings, f"{name}{first + len(rules)}")
        if rule is not None:
            key = canonical_key(side_graph(rule.lhs), ring_len)    # one rule per shape
            if key not in seen:
                seen.add(key)
                rules.append(rule)
    return rules


def _component_side(comp, edges, prims, prim_rings) -> Side | None:
    """The component as a rule side whose boundary walks its open slots, or None when they
    lie on more than one face (it does not stand on the side as one piece)."""
    idx = {v: k for k, v in enumerate(comp)}
    es = tuple(sorted((idx[v], i, idx[w], j) for v, i, w, j in edges if v in idx))
    verts = tuple(prims[v] for v in comp)
    glued = {(v, i) for v, i, _, _ in es} | {(w, j) for _, _, w, j in es}
    opened = [(k, i) for k, p in enumerate(verts) for i in range(len(prim_rings[p]))
              if (k, i) not in glued]
    if len(opened) != 2:
        return None
    walk = face_walk(Side(verts, es, ()), opened[0], prim_rings)
    if len(walk) != len(opened):
        return None
    return Side(verts, es, bd.from_gaps(walk))


def _standing_rule(side: Side, rings, name: str) -> Rule | None:
    """`side ⇄ wire` when the side's boundary is one bare edge's, ā a ∧, from some start."""
    for r, start in enumerate(side.boundary):
        if not isinstance(start, tuple):
            continue
        lhs = Side(side.vertices, side.edges, side.boundary[r:] + side.boundary[:r])
        t = lhs.tokens(rings)
        if not bd.is_bar(t[0]):
            continue
        wire = Side((), (), ((-1, 1), (-1, 0), bd.UP), wires=(t[0] ^ 1,))
        if wire.tokens(rings) == t:
            return Rule(name, lhs, wire)
    return None
