"""The built-in functions and constants of the expression language: types and implementations,
each written once. Angles are in degrees, as everywhere in .ggr files.

Runtime values: numbers are floats, vectors `(x, y)` tuples of floats, colours '#rrggbb'
strings (told apart from strings by their static type), booleans and strings as in Python.
A function that cannot give a finite answer raises `EvalError`; nothing else escapes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

from .expr_ast import Type

N, S, B, V, C = Type.NUM, Type.STR, Type.BOOL, Type.VEC, Type.COLOUR


class EvalError(Exception):
    """An evaluation that has no finite answer: the step that needs it is rejected."""

    def __init__(self, message: str, at: int = 0):
        super().__init__(message)
        self.at = at


@dataclass(frozen=True)
class Signature:
    args: tuple[Type, ...]
    result: Type
    impl: Callable
    variadic: bool = False      # the last argument type repeats (one or more times)
    random: bool = False        # draws from the rule's random generator (its first argument)


def finite(x: float) -> float:
    if not math.isfinite(x):
        raise EvalError("the result is not a finite number")
    return x


def _sqrt(x):
    if x < 0:
        raise EvalError(f"sqrt of a negative number ({x:g})")
    return math.sqrt(x)


def _log(x):
    if x <= 0:
        raise EvalError(f"log of a number that is not positive ({x:g})")
    return math.log(x)


def _arc(fn, name):
    def inner(x):
        if not -1.0 <= x <= 1.0:
            raise EvalError(f"{name} of {x:g}, outside [-1, 1]")
        return math.degrees(fn(x))
    return inner


def _exp(x):
    if x > 700:
        raise EvalError(f"exp({x:g}) is too large")
    return math.exp(x)


def _length(v):
    return math.hypot(v[0], v[1])


def _unit(v):
    n = math.hypot(v[0], v[1])
    if n == 0:
        raise EvalError("unit of the zero vector")
    return (v[0] / n, v[1] / n)


def _rotate(v, deg):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return (c * v[0] - s * v[1], s * v[0] + c * v[1])


def _angle(v):
    if v == (0.0, 0.0):
        raise EvalError("the angle of the zero vector")
    return math.degrees(math.atan2(v[1], v[0]))


def _channel(x) -> int:
    return max(0, min(255, int(round(x))))


def _rgb(r, g, b):
    return "#%02x%02x%02x" % (_channel(r), _channel(g), _channel(b))


def hex_colour(text: str) -> str:
    t = text.strip().lower()
    if len(t) == 4 and t[0] == "#":
        t = "#" + "".join(ch * 2 for ch in t[1:])
    if len(t) != 7 or t[0] != "#" or any(ch not in "0123456789abcdef" for ch in t[1:]):
        raise EvalError(f"{text[:20]!r} is not a colour: write '#rrggbb' or '#rgb'")
    return t


def _mix(a, b, t):
    x, y = int(a[1:], 16), int(b[1:], 16)
    return _rgb(*((x >> s & 255) + ((y >> s & 255) - (x >> s & 255)) * t for s in (16, 8, 0)))


def _uniform(rng, lo, hi):
    return lo + (hi - lo) * rng.random()


def _normal(rng, mu, sigma):
    if sigma < 0:
        raise EvalError(f"normal with a negative spread ({sigma:g})")
    return rng.gauss(mu, sigma)


def _choice(rng, *options):
    return options[rng.randrange(len(options))]


def _num_text(x: float) -> str:
    return f"{x:.6f}".rstrip("0").rstrip(".") if x != int(x) or abs(x) >= 1e15 else str(int(x))


def _sig(args, result, impl, **kw) -> Signature:
    return Signature(tuple(args), result, impl, **kw)


FUNCTIONS: dict[str, tuple[Signature, ...]] = {
    "sqrt": (_sig([N], N, _sqrt),),
    "abs": (_sig([N], N, abs),),
    "sin": (_sig([N], N, lambda d: math.sin(math.radians(d))),),
    "cos": (_sig([N], N, lambda d: math.cos(math.radians(d))),),
    "tan": (_sig([N], N, lambda d: math.tan(math.radians(d))),),
    "asin": (_sig([N], N, _arc(math.asin, "asin")),),
    "acos": (_sig([N], N, _arc(math.acos, "acos")),),
    "atan2": (_sig([N, N], N, lambda y, x: math.degrees(math.atan2(y, x))),),
    "exp": (_sig([N], N, _exp),),
    "log": (_sig([N], N, _log),),
    "floor": (_sig([N], N, lambda x: float(math.floor(x))),),
    "ceil": (_sig([N], N, lambda x: float(math.ceil(x))),),
    "round": (_sig([N], N, lambda x: float(round(x))),),
    "min": (_sig([N, N], N, min, variadic=True),),
    "max": (_sig([N, N], N, max, variadic=True),),
    "clamp": (_sig([N, N, N], N, lambda x, lo, hi: min(max(x, lo), hi)),),
    "lerp": (_sig([N, N, N], N, lambda a, b, t: a + (b - a) * t),
             _sig([V, V, N], V, lambda a, b, t: (a[0] + (b[0] - a[0]) * t,
                                                 a[1] + (b[1] - a[1]) * t))),
    "vec": (_sig([N, N], V, lambda x, y: (x, y)),),
    "polar": (_sig([N, N], V, lambda r, deg: _rotate((r, 0.0), deg)),),
    "length": (_sig([V], N, _length),),
    "dist": (_sig([V, V], N, lambda p, q: math.hypot(q[0] - p[0], q[1] - p[1])),),
    "unit": (_sig([V], V, _unit),),
    "dot": (_sig([V, V], N, lambda u, v: u[0] * v[0] + u[1] * v[1]),),
    "cross": (_sig([V, V], N, lambda u, v: u[0] * v[1] - u[1] * v[0]),),
    "perp_left": (_sig([V], V, lambda v: (-v[1], v[0])),),
    "perp_right": (_sig([V], V, lambda v: (v[1], -v[0])),),
    "rotate": (_sig([V, N], V, _rotate),),
    "angle": (_sig([V], N, _angle),),
    "rgb": (_sig([N, N, N], C, _rgb),),
    "colour": (_sig([S], C, hex_colour),),
    "mix": (_sig([C, C, N], C, _mix),),
    "text": (_sig([N], S, _num_text), _sig([C], S, str), _sig([B], S,
                                                               lambda b: "true" if b else "false")),
    "uniform": (_sig([N, N], N, _uniform, random=True),),
    "normal": (_sig([N, N], N, _normal, random=True),),
    "choice": tuple(_sig([t, t], t, _choice, variadic=True, random=True) for t in Type),
}

CONSTANTS: dict[str, tuple[Type, object]] = {"pi": (N, math.pi), "tau": (N, math.tau)}


def resolve(name: str, types: tuple[Type, ...]) -> Signature | None:
    """The signature of `name` that takes arguments of `types`, or None."""
    for sig in FUNCTIONS.get(name, ()):
        if sig.variadic:
            fixed, rest = sig.args[:-1], sig.args[-1]
            if (len(types) >= len(sig.args) - 1 and types[:len(fixed)] == fixed
                    and all(t == rest for t in types[len(fixed):]) and len(types) >= 2):
                return sig
        elif types == sig.args:
            return sig
    return None


def describe(name: str) -> str:
    """The signatures of `name`, for a hint: 'lerp(num, num, num) or lerp(vec, vec, num)'."""
    shown = []
    for sig in FUNCTIONS[name]:
        args = [t.value for t in sig.args]
        if sig.variadic:
            args[-1] += ", …"
        shown.append(f"{name}({', '.join(args)}) → {sig.result.value}")
    return " or ".join(shown)
