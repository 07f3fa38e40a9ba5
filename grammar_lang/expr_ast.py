"""The expression language's syntax tree, its types, and its printer.

Nodes are small frozen dataclasses. Their position (`at`: 0-based offset into the expression's
text) does not take part in equality, so `parse(show(e)) == e` compares structure only. Number
literals are finite and never negative: a minus sign is the `Unary('-')` node.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from enum import Enum


class Type(Enum):
    NUM = "num"
    STR = "str"
    BOOL = "bool"
    VEC = "vec"
    COLOUR = "colour"

    def __str__(self) -> str:
        return {"num": "a number", "str": "a string", "bool": "a boolean", "vec": "a vector",
                "colour": "a colour"}[self.value]


@dataclass(frozen=True)
class Node:
    """Every node's position: a 0-based offset into the expression's text, outside equality."""

    at: int = field(default=0, compare=False, kw_only=True)


@dataclass(frozen=True)
class Num(Node):
    value: float


@dataclass(frozen=True)
class Str(Node):
    value: str


@dataclass(frozen=True)
class Bool(Node):
    value: bool


@dataclass(frozen=True)
class Var(Node):
    name: str


@dataclass(frozen=True)
class Attr(Node):
    """`obj.name`: an attribute of a matched element, or a vector's `x`/`y`."""

    obj: "Expr"
    name: str


@dataclass(frozen=True)
class Call(Node):
    fn: str
    args: tuple["Expr", ...]


@dataclass(frozen=True)
class Unary(Node):
    op: str         # '-' or 'not'
    arg: "Expr"


@dataclass(frozen=True)
class Binary(Node):
    op: str
    left: "Expr"
    right: "Expr"


@dataclass(frozen=True)
class Cond(Node):
    test: "Expr"
    then: "Expr"
    other: "Expr"


@dataclass(frozen=True)
class Vec(Node):
    x: "Expr"
    y: "Expr"


Expr = Num | Str | Bool | Var | Attr | Call | Unary | Binary | Cond | Vec

# Binding strength of each operator (higher binds tighter), as in expr_grammar.lark.
PRECEDENCE = {"?": 1, "or": 2, "and": 3, "not": 4, "<": 5, "<=": 5, ">": 5, ">=": 5, "==": 5,
              "!=": 5, "+": 6, "-": 6, "*": 7, "/": 7, "%": 7, "neg": 8, "^": 9}
ATOM = 10


def children(e: Expr) -> tuple[Expr, ...]:
    if isinstance(e, Attr):
        return (e.obj,)
    if isinstance(e, Call):
        return e.args
    if isinstance(e, Unary):
        return (e.arg,)
    if isinstance(e, Binary):
        return (e.left, e.right)
    if isinstance(e, Cond):
        return (e.test, e.then, e.other)
    if isinstance(e, Vec):
        return (e.x, e.y)
    return ()


def size_and_depth(e: Expr) -> tuple[int, int]:
    """Node count and depth, without recursion (the tree may come from anywhere)."""
    size, depth, stack = 0, 0, [(e, 1)]
    while stack:
        node, d = stack.pop()
        size += 1
        depth = max(depth, d)
        stack.extend((c, d + 1) for c in children(node))
    return size, depth


def _strength(e: Expr) -> int:
    if isinstance(e, Binary):
        return PRECEDENCE[e.op]
    if isinstance(e, Unary):
        return PRECEDENCE["neg" if e.op == "-" else "not"]
    if isinstance(e, Cond):
        return PRECEDENCE["?"]
    return ATOM


def show(e: Expr) -> str:
    """Source text for `e`, with the fewest parentheses that keep its structure."""
    if isinstance(e, Num):
        v = float(e.value)
        return str(int(v)) if v.is_integer() and v < 1e16 else repr(v)
    if isinstance(e, Str):
        return json.dumps(e.value, ensure_ascii=False)
    if isinstance(e, Bool):
        return "true" if e.value else "false"
    if isinstance(e, Var):
        return e.name
    if isinstance(e, Attr):
        # A number before the dot would read as its decimal point: (2).x
        obj = f"({show(e.obj)})" if isinstance(e.obj, Num) else _wrap(e.obj, ATOM)
        return f"{obj}.{e.name}"
    if isinstance(e, Call):
        return f"{e.fn}({', '.join(show(a) for a in e.args)})"
    if isinstance(e, Vec):
        return f"({show(e.x)}, {show(e.y)})"
    if isinstance(e, Unary):
        if e.op == "-":
            return "-" + _wrap(e.arg, PRECEDENCE["neg"])
        return "not " + _wrap(e.arg, PRECEDENCE["not"])
    if isinstance(e, Cond):
        # The test binds tighter than '?'; the branches may be conditions themselves.
        return f"{_wrap(e.test, PRECEDENCE['or'])} ? {show(e.then)} : {show(e.other)}"
    p = PRECEDENCE[e.op]
    if e.op == "^":     # right associative; its left operand is an atom
        return f"{_wrap(e.left, ATOM)} ^ {_wrap(e.right, PRECEDENCE['neg'])}"
    if p == PRECEDENCE["<"]:    # comparisons do not chain
        return f"{_wrap(e.left, p + 1)} {e.op} {_wrap(e.right, p + 1)}"
    return f"{_wrap(e.left, p)} {e.op} {_wrap(e.right, p + 1)}"


def _wrap(e: Expr, weakest: int) -> str:
    """`e`'s text, in parentheses when it binds more loosely than `weakest`."""
    text = show(e)
    return text if _strength(e) >= weakest else f"({text})"
