"""Hand-built grammars for the runtime tests (the compiler is tested separately)."""

from __future__ import annotations

from grammar_lang import boundary as bd
from grammar_lang.vocabulary import EdgeLabel, Primitive, Vocabulary
from grammar_lang.graph import EMPTY, Side
from grammar_lang.rules import Grammar, Header, Rule
from grammar_lang.source import EdgeClass

UP = bd.UP


def _header(labels, prims, faces, mode="dpo", classes=(EdgeClass("0"),)):
    return Header(source="hand-built", vocabulary=Vocabulary(
        "exterior", faces, classes, tuple(labels), tuple(prims), 1.0), mode=mode)


def square_labels():
    # Walking along each label's direction: bottom and right edges have the inside on the left.
    return [EdgeLabel("xb", "in", "exterior", 0.0, "0"),
            EdgeLabel("xt", "exterior", "in", 0.0, "0"),
            EdgeLabel("yl", "exterior", "in", 90.0, "0"),
            EdgeLabel("yr", "in", "exterior", 90.0, "0")]


def square_prims():
    h = bd.half
    return [Primitive("BL", (h(0, False), h(2, False))),
            Primitive("BR", (h(0, True), h(3, False))),
            Primitive("TR", (h(1, True), h(3, True))),
            Primitive("TL", (h(2, True), h(1, False)))]


RECT = Side((0, 1, 2, 3), ((0, 0, 1, 0), (0, 1, 3, 0), (1, 1, 2, 1), (2, 0, 3, 1)), (UP,))


def filled_square(mode="dpo") -> Grammar:
    """Rectangles: a starter, and a rule that re-places a rectangle's bottom edge."""
    header = _header(square_labels(), square_prims(), ("in", "exterior"), mode)
    bottom = Side((0, 1), ((0, 0, 1, 0),), ((1, 1), (0, 1), UP))
    rules = (Rule("rect", RECT, EMPTY), Rule("bottom", bottom, bottom, weight=0.5))
    return Grammar(header, rules)


def lines(mode="dpo") -> Grammar:
    """Horizontal segments that grow by inserting middle vertices: stubs and a chain rule."""
    labels = [EdgeLabel("x", "exterior", "exterior", 0.0, "0")]
    h = bd.half
    prims = [Primitive("L", (h(0, False),)), Primitive("R", (h(0, True),)),
             Primitive("M", (h(0, True), h(0, False)))]
    header = _header(labels, prims, ("exterior",), mode)
    seg = Side((0, 1), ((0, 0, 1, 0),), (UP,))
    # An end with a middle vertex is an end: lhs L–M, rhs L, both with boundary "x ∧".
    grow_l = Rule("grow", Side((0, 2), ((0, 0, 1, 0),), ((1, 1), UP)), Side((0,), (), ((0, 0), UP)))
    return Grammar(header, (Rule("segment", seg, EMPTY), grow_l))


def lines_with_wire(mode="dpo") -> Grammar:
    """Lines where a middle vertex can be removed (its neighbours glued by a wire) or inserted."""
    g = lines(mode)
    mid = Side((2,), (), ((0, 0), (0, 1), UP))
    wire = Side((), (), ((-1, 1), (-1, 0), UP), wires=(bd.half(0, False),))
    return Grammar(g.header, g.rules[:1] + (Rule("mid", mid, wire),))


def cut_pair(mode: str) -> Grammar:
    """A rule matching an end L and an end R as two components: on a bare segment L–R the two
    are glued to each other, which DPO refuses (dangling) and SPO allows (edge deleted)."""
    g = lines(mode)
    pair = Side((0, 1), (), ((0, 0), UP, (1, 0), UP, bd.DOWN))
    return Grammar(g.header, g.rules[:1] + (Rule("cut", pair, pair),))


def staged(limit_grow_priority: int = 1) -> Grammar:
    """Hand-written style (forward only): make segments at priority 0, grow them after."""
    g = lines("spo")
    seg = Side((0, 1), ((0, 0, 1, 0),), (UP,))
    make = Rule("make", seg, EMPTY, priority=0)      # a starter: forward only, it creates
    grow = Rule("grow", Side((0,), (), ((0, 0), UP)),
                Side((0, 2), ((0, 0, 1, 0),), ((1, 1), UP)), priority=limit_grow_priority)
    return Grammar(g.header, (make, grow))
