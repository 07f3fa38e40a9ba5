"""Expression text → syntax tree (expr_ast), with bounded size and depth.

Errors are `ExprError`s at an offset into the text; the rule-file reader turns them into
file:line:col diagnostics. Every bound is checked before the tree is built, without recursion,
so no input can exhaust the stack: the text's length, the tree's depth and its node count.
"""

from __future__ import annotations

import functools
import json
import math
from dataclasses import dataclass
from pathlib import Path

from lark import Lark, Token, Transformer, Tree
from lark.exceptions import UnexpectedCharacters, UnexpectedInput, UnexpectedToken, VisitError

from . import expr_ast as ast
from .lark_cache import lalr_parser

MAX_TEXT = 2000         # characters in one expression
MAX_DEPTH = 40          # nesting of the syntax tree
MAX_NODES = 400         # nodes in one expression (each evaluation runs at most this many steps)
KEYWORDS = frozenset({"or", "and", "not", "true", "false"})


@dataclass
class ExprError(Exception):
    message: str
    at: int = 0             # 0-based offset into the expression's text
    length: int = 1
    hint: str | None = None

    def __str__(self) -> str:
        return self.message


@functools.lru_cache(maxsize=1)
def _lark() -> Lark:
    return lalr_parser(Path(__file__).with_name("expr_grammar.lark"), propagate_positions=True,
                       maybe_placeholders=False)


def parse_expr(text: str) -> ast.Expr:
    if len(text) > MAX_TEXT:
        raise ExprError(f"the expression is too long ({len(text)} characters, at most "
                        f"{MAX_TEXT})", 0, 1, "split it into several 'let' lines")
    try:
        tree = _lark().parse(text)
    except UnexpectedInput as exc:
        raise _syntax_error(exc, text) from None
    _check_depth(tree)
    try:
        expr = _ToAst().transform(tree) if isinstance(tree, Tree) else _token_leaf(tree)
    except VisitError as exc:       # lark wraps what a rule's method raises
        if isinstance(exc.orig_exc, ExprError):
            raise exc.orig_exc from None
        raise
    size, _ = ast.size_and_depth(expr)
    if size > MAX_NODES:
        raise ExprError(f"the expression has {size} parts, at most {MAX_NODES}", 0, 1,
                        "split it into several 'let' lines")
    return expr


def _check_depth(tree) -> None:
    stack = [(tree, 1)]
    while stack:
        node, d = stack.pop()
        if d > MAX_DEPTH:
            at = _offset(node)
            raise ExprError(f"the expression is nested too deeply (more than {MAX_DEPTH} "
                            "levels)", at, 1, "name parts of it with 'let' lines")
        if isinstance(node, Tree):
            stack.extend((c, d + 1) for c in node.children)


def _offset(node) -> int:
    if isinstance(node, Token):
        return node.start_pos or 0
    meta = getattr(node, "meta", None)
    return getattr(meta, "start_pos", 0) if meta is not None and not meta.empty else 0


_FRIENDLY = {"NAME": "a name", "NUMBER": "a number", "STRING": "a string", "$END": "the end",
             "CMP": "a comparison", "ADD": "'+' or '-'", "MUL": "'*', '/' or '%'", "NEG": "'-'",
             "POW": "'^'", "LPAR": "'('", "RPAR": "')'", "COMMA": "','", "DOT": "'.'",
             "QMARK": "'?'", "COLON": "':'", "OR": "'or'", "AND": "'and'", "NOT": "'not'",
             "TRUE": "'true'", "FALSE": "'false'"}


def _syntax_error(exc: UnexpectedInput, text: str) -> ExprError:
    expected = sorted({_FRIENDLY.get(t, t) for t in getattr(exc, "expected", None) or
                       getattr(exc, "allowed", None) or ()})
    want = ("; expected " + ", ".join(expected[:8])) if expected else ""
    if isinstance(exc, UnexpectedCharacters):
        pos = exc.pos_in_stream
        return ExprError(f"unexpected character {text[pos]!r} in the expression" + want, pos)
    if isinstance(exc, UnexpectedToken) and exc.token.type != "$END":
        tok = exc.token
        return ExprError(f"unexpected {str(tok)!r} in the expression" + want,
                         tok.start_pos or 0, max(1, len(str(tok))))
    return ExprError("the expression ends too early" + want, len(text))


def _token_leaf(tok: Token) -> ast.Expr:
    raise ExprError("not an expression", tok.start_pos or 0)     # the grammar makes trees


def _string(tok: Token) -> str:
    try:
        return json.JSONDecoder(strict=False).decode(str(tok))
    except ValueError:
        raise ExprError("bad escape in a string", tok.start_pos or 0, len(tok),
                        'use \\" \\\\ \\n \\t \\r or \\uXXXX') from None


class _ToAst(Transformer):
    """lark tree → expr_ast nodes; positions are offsets into the text."""

    def number(self, c):
        value = float(c[0])
        if not math.isfinite(value):
            raise ExprError(f"the number {str(c[0])[:20]} is out of range", c[0].start_pos,
                            len(c[0]))
        return ast.Num(value, at=c[0].start_pos)

    def string(self, c):
        return ast.Str(_string(c[0]), at=c[0].start_pos)

    def true(self, c):
        return ast.Bool(True, at=c[0].start_pos)

    def false(self, c):
        return ast.Bool(False, at=c[0].start_pos)

    def var(self, c):
        return ast.Var(str(c[0]), at=c[0].start_pos)

    def attr(self, c):
        return ast.Attr(c[0], str(c[1]), at=c[0].at)

    def call(self, c):
        return ast.Call(str(c[0]), tuple(c[1:]), at=c[0].start_pos)

    def vector(self, c):
        return ast.Vec(c[0], c[1], at=c[0].at)

    def unary(self, c):
        return ast.Unary(str(c[0]), c[1], at=c[0].start_pos)

    def binary(self, c):
        return ast.Binary(str(c[1]), c[0], c[2], at=c[1].start_pos)

    def cond(self, c):
        return ast.Cond(c[0], c[1], c[2], at=c[0].at)
