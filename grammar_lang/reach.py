"""What a grammar's drawings can ever hold, by label: a move applies only where the labels of
the side it matches are all in the drawing already, so the labels a drawing can reach from a
start are at most the fixed point of adding each applicable move's produced labels. That
over-approximates (a match needs more than its labels), so a label outside it is one no
drawing from that start ever holds.

With `connected` (Appendix A) a drawing grows from one starter and starters are never moves
again, so an example of separate pieces that no rule joins gives drawings that hold one
piece's parts only (a square of one label and a square of another, drawn apart: every drawing
was one square, and the other label never appeared). `connected_warning` says so, for `ggc
compile` and `ggrun` alike.
"""

from __future__ import annotations

from typing import Iterable, Sequence

from .diagnostics import Diagnostic
from .frame import border_labels
from .graph import Side
from .rules import Grammar


def side_labels(side: Side, rings: Sequence[Sequence[int]]) -> set[int]:
    """The edge labels of a side: of every slot of its vertices, and of its wires."""
    out = {t >> 1 for p in side.vertices for t in rings[p]}
    out.update(t >> 1 for t in side.wires)
    return out


def reachable_labels(grammar: Grammar, start: Iterable[int], both: bool = True) -> set[int]:
    """The labels a drawing holding `start` can come to hold through the grammar's moves
    (each rule forward, and backward too with `both`; starters are no moves)."""
    rings = grammar.rings
    moves = []
    for rule in grammar.rules:
        if rule.is_starter:
            continue
        lhs, rhs = side_labels(rule.lhs, rings), side_labels(rule.rhs, rings)
        moves.append((lhs, rhs))
        if both:
            moves.append((rhs, lhs))
    have = set(start)
    grown = True
    while grown:
        grown = False
        for matched, produced in moves:
            if matched <= have and not produced <= have:
                have |= produced
                grown = True
    return have


def start_labels(grammar: Grammar, starter) -> set[int]:
    """The labels a `connected` drawing starts with: its starter's, and its frame's (the
    corners' half-edges, or the frame's start graph where its sides cannot be bare)."""
    rings, frame = grammar.rings, grammar.header.frame
    out = side_labels(starter.lhs, rings)
    if frame is not None:
        out |= {t >> 1 for c in frame.corners for t in rings[c.prim]}
        if frame.start is not None:
            out |= side_labels(frame.start, rings)
    return out


def connected_warning(grammar: Grammar) -> Diagnostic | None:
    """With `connected`, the starters from which no drawing can hold every face label and
    edge class of the example, and what each lacks; None when every starter can (or the
    grammar is not `connected`)."""
    header = grammar.header
    if not header.options.connected or grammar.is_free:
        return None
    labels, rings = header.labels, grammar.rings
    border = border_labels(labels, header.classes)
    every = set(range(len(labels))) - border
    faces = _faces(labels, every) - {header.exterior}
    classes = {labels[k].cls for k in every}
    lacks = []
    for rule in grammar.rules:
        if not rule.is_starter:
            continue
        have = reachable_labels(grammar, start_labels(grammar, rule),
                                header.mode != "spo") - border
        missing = [f"face label {f}" for f in sorted(faces - _faces(labels, have))] + \
            [f"class {c}" for c in sorted(classes - {labels[k].cls for k in have})]
        if missing:
            lacks.append(f"one from {rule.name} never holds {', '.join(missing)}")
    if not lacks:
        return None
    return Diagnostic("with `connected` a drawing grows from one starter, and no rule joins "
                      "the example's other pieces to it: " + "; ".join(lacks),
                      None, "join the example's pieces into one structure, or leave "
                      "`connected` out", severity="warning")


def _faces(labels, ks) -> set[str]:
    return {f for k in ks for f in (labels[k].left, labels[k].right)}
