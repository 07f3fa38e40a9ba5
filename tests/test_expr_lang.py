"""The expression language of hand-written rules: printing and parsing are inverse, evaluation
agrees with an independent reference interpreter on random well-typed expressions, and bad
input is an ExprError or EvalError, never a Python exception."""

from __future__ import annotations

import functools
import math
import random
import re

import pytest
from hypothesis import given, settings, strategies as st

from grammar_lang import expr_ast as ast
from grammar_lang.expr_ast import Type, show
from grammar_lang.expr_eval import Scope, compile_expr
from grammar_lang.expr_functions import EvalError
from grammar_lang.expr_parse import MAX_DEPTH, ExprError, parse_expr

N, S, B, V, C = Type.NUM, Type.STR, Type.BOOL, Type.VEC, Type.COLOUR
NAMES = st.sampled_from(["a", "b", "v", "len2", "x_1", "é"])
NUMBERS = st.floats(min_value=0, max_value=1e6, allow_nan=False) | st.integers(0, 50).map(float)

# --- any tree: parse(show(e)) == e -------------------------------------------------------------

leaves = st.one_of(NUMBERS.map(ast.Num), st.text(max_size=5).map(ast.Str),
                   st.booleans().map(ast.Bool), NAMES.map(ast.Var))
BINOPS = st.sampled_from(["or", "and", "<", "<=", ">", ">=", "==", "!=", "+", "-", "*", "/",
                          "%", "^"])


def _compound(sub):
    return st.one_of(
        st.builds(ast.Binary, BINOPS, sub, sub),
        st.builds(ast.Unary, st.sampled_from(["-", "not"]), sub),
        st.builds(ast.Cond, sub, sub, sub),
        st.builds(ast.Vec, sub, sub),
        st.builds(ast.Attr, sub, NAMES),
        st.builds(ast.Call, st.sampled_from(["f", "lerp", "sqrt"]),
                  st.lists(sub, max_size=3).map(tuple)))


trees = st.recursive(leaves, _compound, max_leaves=12)


@settings(max_examples=400, deadline=None)
@given(trees)
def test_parse_inverts_show(e):
    text = show(e)
    assert parse_expr(text) == e, text


def test_show_uses_few_parentheses():
    assert show(parse_expr("A + v/2 + perp_left(v)/3")) == "A + v / 2 + perp_left(v) / 3"
    assert show(parse_expr("(a - b) - (c - d)")) == "a - b - (c - d)"
    assert show(parse_expr("-(2 ^ 2)")) == "-2 ^ 2"
    assert show(parse_expr("(-2) ^ 2")) == "(-2) ^ 2"
    assert show(parse_expr("2 ^ 3 ^ 2")) == "2 ^ 3 ^ 2"
    assert show(parse_expr("(2 ^ 3) ^ 2")) == "(2 ^ 3) ^ 2"


# --- well-typed trees: evaluation agrees with a reference ---------------------------------------

SCOPE = Scope({"u": V, "k": N, "s": S, "flag": B},
              {"a": {"x": N, "y": N, "pos": V, "name": S}})
VALUES = {"u": (3.0, -4.0), "k": 2.5, "s": "ab", "flag": True}
ELEMENT = {"x": 1.5, "y": -2.0, "pos": (1.5, -2.0), "name": "pt"}


class _Env:
    def __init__(self, seed: int):
        self.values, self.rng = dict(VALUES), random.Random(seed)

    def get(self, element, key):
        assert element == "a"
        return ELEMENT[key]


@functools.lru_cache(maxsize=None)
def typed(t: Type, depth: int = 3):
    leaf = {N: st.one_of(st.floats(0, 100).map(ast.Num), st.just(ast.Var("k")),
                         st.sampled_from([ast.Attr(ast.Var("a"), "x"),
                                          ast.Attr(ast.Var("u"), "y"), ast.Var("pi")])),
            V: st.one_of(st.just(ast.Var("u")), st.just(ast.Attr(ast.Var("a"), "pos"))),
            B: st.one_of(st.booleans().map(ast.Bool), st.just(ast.Var("flag"))),
            S: st.one_of(st.text(max_size=3).map(ast.Str), st.just(ast.Var("s")))}[t]
    if depth == 0:
        return leaf
    sub = {u: st.deferred(lambda u=u: typed(u, depth - 1)) for u in (N, V, B, S)}
    options = [leaf, st.builds(ast.Cond, sub[B], sub[t], sub[t])]
    if t == N:
        options += [st.builds(ast.Binary, st.sampled_from("+-*/%"), sub[N], sub[N]),
                    st.builds(ast.Binary, st.just("^"), sub[N], st.floats(0, 3).map(ast.Num)),
                    st.builds(ast.Unary, st.just("-"), sub[N]),
                    st.builds(lambda f, x: ast.Call(f, (x,)),
                              st.sampled_from(["sqrt", "abs", "sin", "cos", "floor", "log"]), sub[N]),
                    st.builds(lambda f, p, q: ast.Call(f, (p, q)),
                              st.sampled_from(["dot", "cross", "dist"]), sub[V], sub[V]),
                    st.builds(lambda x: ast.Call("length", (x,)), sub[V]),
                    st.builds(lambda p, q: ast.Call("uniform", (p, q)), sub[N], sub[N]),
                    st.builds(lambda x: ast.Attr(x, "x"), sub[V])]
    elif t == V:
        options += [st.builds(ast.Binary, st.sampled_from("+-"), sub[V], sub[V]),
                    st.builds(ast.Binary, st.just("*"), sub[N], sub[V]),
                    st.builds(ast.Binary, st.just("/"), sub[V], sub[N]),
                    st.builds(ast.Vec, sub[N], sub[N]),
                    st.builds(lambda f, x: ast.Call(f, (x,)),
                              st.sampled_from(["perp_left", "perp_right"]), sub[V]),
                    st.builds(lambda x, d: ast.Call("rotate", (x, d)), sub[V], sub[N]),
                    st.builds(lambda p, q, t: ast.Call("lerp", (p, q, t)), sub[V], sub[V], sub[N])]
    elif t == B:
        options += [st.builds(ast.Binary, st.sampled_from(["<", "<=", ">", ">=", "==", "!="]),
                              sub[N], sub[N]),
                    st.builds(ast.Binary, st.sampled_from(["and", "or"]), sub[B], sub[B]),
                    st.builds(ast.Unary, st.just("not"), sub[B])]
    else:
        options += [st.builds(ast.Binary, st.just("+"), sub[S], sub[S])]
    return st.one_of(*options)


class Fail(Exception):
    pass


def _ok(x):
    if isinstance(x, float) and not math.isfinite(x):
        raise Fail
    if isinstance(x, tuple) and not all(math.isfinite(c) for c in x):
        raise Fail
    return x


def reference(e, env):
    """A plain recursive interpreter, written apart from expr_eval's closures."""
    r = lambda x: reference(x, env)     # noqa: E731
    if isinstance(e, (ast.Num, ast.Str, ast.Bool)):
        return e.value
    if isinstance(e, ast.Var):
        return {"pi": math.pi}.get(e.name, env.values.get(e.name))
    if isinstance(e, ast.Attr):
        if isinstance(e.obj, ast.Var) and e.obj.name == "a":
            return ELEMENT[e.name]
        return r(e.obj)[0 if e.name == "x" else 1]
    if isinstance(e, ast.Vec):
        return (r(e.x), r(e.y))
    if isinstance(e, ast.Cond):
        return r(e.then) if r(e.test) else r(e.other)
    if isinstance(e, ast.Unary):
        v = r(e.arg)
        return (not v) if e.op == "not" else (tuple(-c for c in v) if isinstance(v, tuple) else -v)
    if isinstance(e, ast.Binary):
        if e.op == "and":
            return r(e.left) and r(e.right)
        if e.op == "or":
            return r(e.left) or r(e.right)
        a, b = r(e.left), r(e.right)
        return _ok(_binary(e.op, a, b))
    return _ok(_call(e.fn, [r(x) for x in e.args], env))


def _binary(op, a, b):
    if op in ("/", "%") and b == 0:
        raise Fail
    if isinstance(a, tuple) or isinstance(b, tuple):
        if op == "*":
            k, v = (a, b) if isinstance(b, tuple) else (b, a)
            return (_ok(k * v[0]), _ok(k * v[1]))
        if op == "/":
            return (_ok(a[0] / b), _ok(a[1] / b))
        sign = 1 if op == "+" else -1
        return (_ok(a[0] + sign * b[0]), _ok(a[1] + sign * b[1]))
    if op == "^":
        try:
            value = a ** b
        except (OverflowError, ZeroDivisionError):
            raise Fail from None
        if isinstance(value, complex):
            raise Fail
        return value
    return {"+": lambda: a + b, "-": lambda: a - b, "*": lambda: a * b, "/": lambda: a / b,
            "%": lambda: a % b, "<": lambda: a < b, "<=": lambda: a <= b, ">": lambda: a > b,
            ">=": lambda: a >= b, "==": lambda: a == b, "!=": lambda: a != b}[op]()


def _call(fn, args, env):
    if fn == "sqrt":
        if args[0] < 0:
            raise Fail
        return math.sqrt(args[0])
    if fn == "log":
        if args[0] <= 0:
            raise Fail
        return math.log(args[0])
    if fn == "uniform":
        return args[0] + (args[1] - args[0]) * env.rng.random()
    if fn == "rotate":
        t = math.radians(args[1])
        (x, y) = args[0]
        return (_ok(math.cos(t) * x - math.sin(t) * y), _ok(math.sin(t) * x + math.cos(t) * y))
    if fn == "lerp":
        (p, q, t) = args
        return (_ok(p[0] + (q[0] - p[0]) * t), _ok(p[1] + (q[1] - p[1]) * t))
    table = {"abs": abs, "sin": lambda d: math.sin(math.radians(d)),
             "cos": lambda d: math.cos(math.radians(d)), "floor": lambda x: float(math.floor(x)),
             "dot": lambda u, v: u[0] * v[0] + u[1] * v[1],
             "cross": lambda u, v: u[0] * v[1] - u[1] * v[0],
             "dist": lambda u, v: math.hypot(v[0] - u[0], v[1] - u[1]),
             "length": lambda v: math.hypot(*v), "perp_left": lambda v: (-v[1], v[0]),
             "perp_right": lambda v: (v[1], -v[0])}
    return table[fn](*args)


def _same(x, y) -> bool:
    if isinstance(x, tuple):
        return all(_same(a, b) for a, b in zip(x, y))
    if isinstance(x, float):
        return x == y or math.isclose(x, y, rel_tol=1e-12, abs_tol=1e-300)
    return x == y


@settings(max_examples=300, deadline=None)
@given(st.sampled_from([N, V, B, S]).flatmap(lambda t: st.tuples(st.just(t), typed(t))),
       st.integers(0, 2 ** 32))
def test_evaluation_agrees_with_the_reference(typed_expr, seed):
    t, e = typed_expr
    try:
        got_type, fn = compile_expr(parse_expr(show(e)), SCOPE)
    except ExprError as exc:    # a constant part without a value: found before running
        assert "does not change" in exc.message
        return
    assert got_type == t
    try:
        want = reference(e, _Env(seed))
    except Fail:
        with pytest.raises(EvalError):
            fn(_Env(seed))
        return
    assert _same(fn(_Env(seed)), want)


# --- errors ------------------------------------------------------------------------------------

@pytest.mark.parametrize("text,message", [
    ("1e3081", "the number 1e3081 is out of range"),
    ("x + 2e400 * 3", "the number 2e400 is out of range"),
    ('"a\\qb"', "bad escape in a string"),
])
def test_bad_literals_are_expression_errors(text, message):
    """A literal that cannot be read is the input's fault: an ExprError at the literal, not
    the parser library's own exception (lark wraps what a rule's method raises)."""
    with pytest.raises(ExprError, match=re.escape(message)):
        parse_expr(text)


@pytest.mark.parametrize("text,message", [
    ("1 + true", "'+' does not apply to a number and a boolean"),
    ("a.height", "'a' has no attribute 'height'"),
    ("nope(1)", "unknown function 'nope'"),
    ("sqrt(u)", "sqrt(vec) does not exist"),
    ("flag ? 1 : u", "different types"),
    ("q + 1", "unknown name 'q'"),
    ("a + 1", "'a' is an element"),
    ('colour("red")', "is not a colour"),
    ("u < u", "compares numbers"),
    ("1 < 2 < 3", "unexpected '<'"),
])
def test_type_errors_are_found_before_running(text, message):
    with pytest.raises(ExprError, match=re.escape(message)):
        compile_expr(parse_expr(text), SCOPE)


@pytest.mark.parametrize("text", ["k / 0", "k % 0", "sqrt(-k)", "10 ^ (400 * k)",
                                  "exp(1000 * k)", "unit(u - u)", "log(k - k)", "u / 0",
                                  "asin(2 * k)", "1e300 * k * 1e300"])
def test_evaluation_errors_are_eval_errors(text):
    _, fn = compile_expr(parse_expr(text), SCOPE)
    with pytest.raises(EvalError):
        fn(_Env(0))


@pytest.mark.parametrize("text", ["1 / 0", "sqrt(-1)", "10 ^ 400", "log(0)", "k + 1 / 0"])
def test_constant_errors_are_found_when_the_file_loads(text):
    with pytest.raises(ExprError, match="does not change"):
        compile_expr(parse_expr(text), SCOPE)


def test_constant_parts_are_folded():
    _, fn = compile_expr(parse_expr("k + sqrt(3) / 6 + pi"), SCOPE)
    assert fn(_Env(0)) == 2.5 + math.sqrt(3) / 6 + math.pi


def test_bounds():
    with pytest.raises(ExprError, match="nested too deeply"):
        parse_expr("sqrt(" * (MAX_DEPTH + 5) + "1" + ")" * (MAX_DEPTH + 5))
    assert parse_expr("(" * 500 + "1" + ")" * 500) == ast.Num(1.0)    # brackets add no depth
    with pytest.raises(ExprError, match="nested too deeply"):
        parse_expr("-" * 1000 + "1")
    with pytest.raises(ExprError, match="too long"):
        parse_expr("1" + "+1" * 5000)
    with pytest.raises(ExprError, match="parts"):
        balanced = "k"
        for _ in range(8):      # 256 leaves, 511 nodes, shallow
            balanced = f"({balanced} + {balanced})"
        parse_expr(balanced)


@settings(max_examples=300, deadline=None)
@given(st.lists(st.sampled_from(list("ab1.(),+-*/^<=!?:\" #notrue") + ["pi", "and", "or", " "]),
                max_size=40).map("".join))
def test_any_text_gives_a_tree_or_an_expr_error(text):
    try:
        e = parse_expr(text)
    except ExprError as exc:
        assert 0 <= exc.at <= len(text)
        return
    assert parse_expr(show(e)) == e
    try:
        compile_expr(e, SCOPE)
    except ExprError:
        pass
