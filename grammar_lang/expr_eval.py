"""Type checking and evaluation of expressions.

`compile_expr` checks a syntax tree against a `Scope` (the names a rule defines and the
attributes each element has) and returns its type with a function that evaluates it. The
function is built from closures, one per node: no Python code is generated or evaluated, and an
expression reaches nothing but the values its `Env` hands out. Its work is bounded by the
tree's size (expr_parse.MAX_NODES, no loops, no recursion). Type errors are `ExprError`s at the
node's offset; evaluation errors (division by zero, a result that is not finite, sqrt of a
negative number) are `EvalError`s, which reject the rewriting step that needed them.
"""

from __future__ import annotations

import operator
from dataclasses import dataclass, field
from typing import Callable, Protocol

from . import expr_ast as ast
from .diagnostics import did_you_mean
from .expr_ast import Type
from .expr_functions import CONSTANTS, FUNCTIONS, EvalError, describe, hex_colour, finite, resolve
from .expr_parse import ExprError

N, S, B, V, C = Type.NUM, Type.STR, Type.BOOL, Type.VEC, Type.COLOUR


class Env(Protocol):
    """What an expression sees while it runs."""

    values: dict            # let-bound names → values
    rng: object             # random.Random: the rule's seeded generator

    def get(self, element: str, key: str) -> object: ...


@dataclass
class Scope:
    variables: dict[str, Type] = field(default_factory=dict)
    # element name → its attributes and their types (derived values included)
    elements: dict[str, dict[str, Type]] = field(default_factory=dict)


Fn = Callable[[Env], object]


def compile_expr(expr: ast.Expr, scope: Scope) -> tuple[Type, Fn]:
    t, fn = _Compiler(scope).node(expr)
    return t, _guarded(fn)


def _guarded(fn: Fn) -> Fn:
    """`fn`, with the arithmetic errors of Python's math turned into EvalErrors once, at the
    top, rather than at every call."""
    def run(env):
        try:
            return fn(env)
        except (OverflowError, ValueError, ZeroDivisionError) as exc:
            raise EvalError(f"no finite result ({exc})") from None
    return run


def _div(a, b):
    if b == 0:
        raise EvalError("division by zero")
    return finite(a / b)


def _mod(a, b):
    if b == 0:
        raise EvalError("remainder of a division by zero")
    return finite(a % b)


def _pow(a, b):
    try:
        r = a ** b
    except (OverflowError, ZeroDivisionError):
        raise EvalError(f"{a:g} ^ {b:g} has no finite value") from None
    if isinstance(r, complex):
        raise EvalError(f"{a:g} ^ {b:g} is not a real number")
    return finite(r)


def _vdiv(v, b):
    if b == 0:
        raise EvalError("division by zero")
    return (finite(v[0] / b), finite(v[1] / b))


_ARITH: dict[tuple[str, Type, Type], tuple[Type, Callable]] = {
    ("+", N, N): (N, lambda a, b: finite(a + b)),
    ("-", N, N): (N, lambda a, b: finite(a - b)),
    ("*", N, N): (N, lambda a, b: finite(a * b)),
    ("/", N, N): (N, _div),
    ("%", N, N): (N, _mod),
    ("^", N, N): (N, _pow),
    ("+", V, V): (V, lambda a, b: (finite(a[0] + b[0]), finite(a[1] + b[1]))),
    ("-", V, V): (V, lambda a, b: (finite(a[0] - b[0]), finite(a[1] - b[1]))),
    ("*", N, V): (V, lambda a, b: (finite(a * b[0]), finite(a * b[1]))),
    ("*", V, N): (V, lambda a, b: (finite(a[0] * b), finite(a[1] * b))),
    ("/", V, N): (V, _vdiv),
    ("+", S, S): (S, operator.add),
}
_ORDER = {"<": operator.lt, "<=": operator.le, ">": operator.gt, ">=": operator.ge}
_EQUAL = {"==": operator.eq, "!=": operator.ne}
MAX_STRING = 100_000        # characters: '+' on strings would otherwise double without bound


class _Compiler:
    def __init__(self, scope: Scope):
        self.scope = scope

    def node(self, e: ast.Expr) -> tuple[Type, Fn]:
        method = getattr(self, "_" + type(e).__name__.lower())
        t, fn = method(e)
        if isinstance(e, (ast.Num, ast.Str, ast.Bool)) or not self._constant(e):
            return t, fn
        # A part that depends on nothing is computed once, here; if it has no value that is
        # known before the file runs (1/0, sqrt(-1)), it is an error of the file.
        try:
            value = fn(None)
        except EvalError as exc:
            raise ExprError(f"{exc} (in a part that does not change)", e.at, 1) from None
        return t, lambda env: value

    def _constant(self, e: ast.Expr) -> bool:
        if isinstance(e, ast.Var):
            return e.name in CONSTANTS and e.name not in self.scope.variables
        if isinstance(e, ast.Attr) and isinstance(e.obj, ast.Var) and \
                e.obj.name in self.scope.elements:
            return False
        if isinstance(e, ast.Call) and any(s.random for s in FUNCTIONS.get(e.fn, ())):
            return False
        return all(self._constant(c) for c in ast.children(e))

    def _num(self, e: ast.Num):
        value = float(e.value)
        return N, lambda env: value

    def _str(self, e: ast.Str):
        value = e.value
        return S, lambda env: value

    def _bool(self, e: ast.Bool):
        value = e.value
        return B, lambda env: value

    def _var(self, e: ast.Var):
        name = e.name
        if name in self.scope.variables:
            return self.scope.variables[name], lambda env: env.values[name]
        if name in CONSTANTS:
            t, value = CONSTANTS[name]
            return t, lambda env: value
        if name in self.scope.elements:
            raise ExprError(f"'{name}' is an element, not a value", e.at, len(name),
                            f"use one of its attributes: {name}.{_some(self.scope.elements[name])}")
        known = list(self.scope.variables) + list(CONSTANTS)
        raise ExprError(f"unknown name '{name}'", e.at, len(name),
                        did_you_mean(name, known) or "define it with a 'let' line")

    def _attr(self, e: ast.Attr):
        if isinstance(e.obj, ast.Var) and e.obj.name in self.scope.elements \
                and e.obj.name not in self.scope.variables:
            element, key = e.obj.name, e.name
            attrs = self.scope.elements[element]
            if key not in attrs:
                raise ExprError(f"'{element}' has no attribute '{key}'", e.at,
                                len(element) + 1 + len(key),
                                did_you_mean(key, attrs) or "declare it with an 'attribute' line")
            return attrs[key], lambda env: env.get(element, key)
        t, obj = self.node(e.obj)
        if t == V and e.name in ("x", "y"):
            k = 0 if e.name == "x" else 1
            return N, lambda env: obj(env)[k]
        raise ExprError(f"{t} has no part '.{e.name}'", e.at, 1,
                        "a vector has .x and .y; an element has its attributes")

    def _vec(self, e: ast.Vec):
        fx, fy = self._typed(e.x, N, "a vector's x"), self._typed(e.y, N, "a vector's y")
        return V, lambda env: (fx(env), fy(env))

    def _call(self, e: ast.Call):
        if e.fn not in FUNCTIONS:
            raise ExprError(f"unknown function '{e.fn}'", e.at, len(e.fn),
                            did_you_mean(e.fn, FUNCTIONS) or
                            "see docs/ggr-language.md for the functions")
        parts = [self.node(a) for a in e.args]
        if e.fn == "colour" and len(e.args) == 1 and isinstance(e.args[0], ast.Str):
            try:        # a literal colour is checked when the file loads
                hex_colour(e.args[0].value)
            except EvalError as exc:
                raise ExprError(str(exc), e.args[0].at, len(e.args[0].value) + 2) from None
        sig = resolve(e.fn, tuple(t for t, _ in parts))
        if sig is None:
            got = ", ".join(t.value for t, _ in parts)
            raise ExprError(f"{e.fn}({got}) does not exist", e.at, len(e.fn),
                            "it takes " + describe(e.fn))
        return sig.result, _call_fn(sig, [f for _, f in parts])

    def _unary(self, e: ast.Unary):
        t, f = self.node(e.arg)
        if e.op == "not":
            if t != B:
                raise ExprError(f"'not' needs a boolean, not {t}", e.at, 3)
            return B, lambda env: not f(env)
        if t == N:
            return N, lambda env: -f(env)
        if t == V:
            return V, lambda env: tuple(-c for c in f(env))
        raise ExprError(f"cannot negate {t}", e.at, 1)

    def _binary(self, e: ast.Binary):
        (lt, lf), (rt, rf) = self.node(e.left), self.node(e.right)
        op = e.op
        if op in ("and", "or"):
            if lt != B or rt != B:
                raise ExprError(f"'{op}' needs booleans, not {lt} and {rt}", e.at, len(op))
            if op == "and":
                return B, lambda env: lf(env) and rf(env)
            return B, lambda env: lf(env) or rf(env)
        if op in _ORDER:
            if lt != N or rt != N:
                raise ExprError(f"'{op}' compares numbers, not {lt} and {rt}", e.at, len(op))
            cmp = _ORDER[op]
            return B, lambda env: cmp(lf(env), rf(env))
        if op in _EQUAL:
            if lt != rt:
                raise ExprError(f"'{op}' compares values of one type, not {lt} and {rt}",
                                e.at, len(op))
            cmp = _EQUAL[op]
            return B, lambda env: cmp(lf(env), rf(env))
        if (op, lt, rt) not in _ARITH:
            raise ExprError(f"'{op}' does not apply to {lt} and {rt}", e.at, len(op),
                            _arith_hint(op))
        t, impl = _ARITH[(op, lt, rt)]
        if t == S:
            return S, lambda env: _bounded_text(impl(lf(env), rf(env)))
        return t, lambda env: impl(lf(env), rf(env))

    def _cond(self, e: ast.Cond):
        test = self._typed(e.test, B, "the test before '?'")
        (tt, tf), (ot, of) = self.node(e.then), self.node(e.other)
        if tt != ot:
            raise ExprError(f"the two branches of '?' have different types: {tt} and {ot}",
                            e.then.at, 1)
        return tt, lambda env: tf(env) if test(env) else of(env)

    def _typed(self, e: ast.Expr, want: Type, what: str) -> Fn:
        t, f = self.node(e)
        if t != want:
            raise ExprError(f"{what} must be {want}, not {t}", e.at, 1)
        return f


def _vfinite(v):
    return (finite(v[0]), finite(v[1]))


_CHECK = {N: finite, V: _vfinite}


def _call_fn(sig, fns: list[Fn]) -> Fn:
    """A call's closure, without building argument lists for the common arities."""
    impl, check = sig.impl, _CHECK.get(sig.result, lambda v: v)
    if sig.random:
        return lambda env: check(impl(env.rng, *[f(env) for f in fns]))
    if len(fns) == 1:
        (f0,) = fns
        return lambda env: check(impl(f0(env)))
    if len(fns) == 2:
        f0, f1 = fns
        return lambda env: check(impl(f0(env), f1(env)))
    return lambda env: check(impl(*[f(env) for f in fns]))


def _bounded_text(s: str) -> str:
    if len(s) > MAX_STRING:
        raise EvalError(f"a string longer than {MAX_STRING} characters")
    return s


def _some(attrs: dict[str, Type]) -> str:
    return next(iter(sorted(attrs)), "x")


def _arith_hint(op: str) -> str:
    pairs = [f"{a.value} {op} {b.value}" for (o, a, b) in _ARITH if o == op]
    return "it takes " + (", ".join(pairs) if pairs else "nothing")
