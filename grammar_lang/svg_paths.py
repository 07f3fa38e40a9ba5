"""SVG attribute micro-languages: path data, point lists, transforms and lengths.

The functions here know nothing about files. They raise `SvgValueError` with the offset of the
problem inside the attribute value; `svg_import` turns that into a diagnostic with a caret.
"""

from __future__ import annotations

import math
import re

import numpy as np

Point = tuple[float, float]

_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")
_SEPARATORS = " \t\r\n\f,"
_CURVES = "CcSsQqTtAa"
_COMMANDS = "MmLlHhVvZz" + _CURVES

FLATTEN_HINT = ("flatten curves into straight segments first: in Inkscape select the shape, "
                "Path > Object to Path, then Extensions > Modify Path > Flatten Beziers")


class SvgValueError(ValueError):
    def __init__(self, message: str, offset: int = 0, hint: str | None = None):
        super().__init__(message)
        self.message = message
        self.offset = offset
        self.hint = hint


def _finite(value: float, offset: int) -> float:
    if not math.isfinite(value):
        raise SvgValueError("number out of range", offset)
    return value


def _skip(text: str, i: int) -> int:
    while i < len(text) and text[i] in _SEPARATORS:
        i += 1
    return i


def _over(limit, count: int, offset: int) -> SvgValueError:
    return SvgValueError(limit.message(count, "points in this attribute"), offset, limit.hint())


def parse_numbers(text: str, limit=None) -> list[tuple[float, int]]:
    """Every number in a comma/whitespace separated list, with its offset. `limit` (a
    `limits.InputLimit` on points) bounds how many pairs are read."""
    out = []
    most = 2 * limit.value() if limit is not None else None
    i = _skip(text, 0)
    while i < len(text):
        match = _NUMBER.match(text, i)
        if not match:
            raise SvgValueError(f"expected a number, found {text[i]!r}", i)
        out.append((_finite(float(match.group()), i), i))
        if most is not None and len(out) > most:
            raise _over(limit, len(out) // 2, i)
        i = _skip(text, match.end())
    return out


def parse_points(text: str, limit=None) -> list[Point]:
    """The `points` attribute of `<polygon>` and `<polyline>`."""
    numbers = parse_numbers(text, limit)
    if len(numbers) % 2:
        raise SvgValueError("odd number of coordinates: the last point has no y",
                            numbers[-1][1])
    return [(numbers[k][0], numbers[k + 1][0]) for k in range(0, len(numbers), 2)]


class Subpath:
    """One subpath of path data: its points and whether `Z` closed it."""

    __slots__ = ("points", "closed")

    def __init__(self, start: Point):
        self.points: list[Point] = [start]
        self.closed = False


def parse_path(text: str, limit=None) -> list[Subpath]:
    """Straight-line path data (M/L/H/V/Z, absolute and relative) → subpaths.

    Curves are refused, with the offset of the first curve command, because guessing a
    flattening tolerance would silently invent vertices the user never drew.
    """
    pen = _Pen()
    most = limit.value() if limit is not None else None
    i = _skip(text, 0)
    command = None
    while i < len(text):
        ch = text[i]
        if ch in _COMMANDS:
            command, command_at = ch, i
            i = _skip(text, i + 1)
            _check_command(command, command_at, pen.subpaths)
            if command in "Zz":
                pen.close(command_at)
                command = None
                continue
        elif command is None:
            if not pen.subpaths and pen.current is None:
                raise SvgValueError("path data must start with 'M'", i)
            raise SvgValueError(f"expected a path command, found {ch!r}", i)
        args, i = _path_numbers(text, i, command)
        moved = command in "Mm"
        command = pen.draw(command, args)
        if not moved and most is not None and pen.count > most:
            raise _over(limit, pen.count, i)
    return pen.subpaths


def _check_command(command: str, at: int, subpaths: list[Subpath]) -> None:
    if not subpaths and command not in "Mm":
        raise SvgValueError("path data must start with 'M'", at)
    if command in _CURVES:
        kind = "arc" if command in "Aa" else "curve"
        raise SvgValueError(f"path has a {kind} ('{command}'); only straight segments "
                            "(M, L, H, V, Z) are supported", at, FLATTEN_HINT)


def _path_numbers(text: str, i: int, command: str) -> tuple[list[float], int]:
    """The numbers one use of `command` takes, from offset i; and the offset after them."""
    arity = 1 if command in "HhVv" else 2
    args = []
    for _ in range(arity):
        match = _NUMBER.match(text, i)
        if not match:
            found = repr(text[i]) if i < len(text) else "the end"
            raise SvgValueError(f"'{command}' needs {arity} number(s), found {found}", i)
        args.append(_finite(float(match.group()), i))
        i = _skip(text, match.end())
    return args, i


class _Pen:
    """The subpaths drawn so far, the open one, the pen's position, and the points drawn."""

    def __init__(self):
        self.subpaths: list[Subpath] = []
        self.current: Subpath | None = None
        self.x = self.y = 0.0
        self.count = 0

    def close(self, at: int) -> None:
        if self.current is None:
            raise SvgValueError("'Z' before any 'M'", at)
        self.current.closed = True
        self.x, self.y = self.current.points[0]
        self.current = None

    def draw(self, command: str, args: list[float]) -> str:
        """Apply one M, L, H or V with its numbers; the command that further numbers repeat."""
        relative = command.islower()
        upper = command.upper()
        x, y = self.x, self.y
        if upper == "M":
            self.x, self.y = (x + args[0], y + args[1]) if relative else (args[0], args[1])
            self.current = Subpath((self.x, self.y))
            self.subpaths.append(self.current)
            self.count += 1
            # Further pairs after a moveto are implicit linetos (SVG 1.1 §8.3.2).
            return "l" if relative else "L"
        if upper == "L":
            x, y = (x + args[0], y + args[1]) if relative else (args[0], args[1])
        elif upper == "H":
            x = x + args[0] if relative else args[0]
        else:  # V
            y = y + args[0] if relative else args[0]
        self.x, self.y = x, y
        if self.current is None:
            # Drawing after Z continues from the closed subpath's start (SVG 1.1 §8.3.3).
            self.current = Subpath((x, y) if not self.subpaths else self.subpaths[-1].points[0])
            self.subpaths.append(self.current)
        self.current.points.append((x, y))
        self.count += 1
        return command


# --- transforms -------------------------------------------------------------------------------

IDENTITY = np.eye(3)
_TRANSFORM = re.compile(r"\s*,?\s*([A-Za-z]+)\s*\(([^()]*)\)\s*")
_ARITY = {"matrix": (6,), "translate": (1, 2), "scale": (1, 2), "rotate": (1, 3),
          "skewX": (1,), "skewY": (1,)}


def parse_transform(text: str) -> np.ndarray:
    """A `transform` attribute → 3×3 affine matrix; the list composes left to right."""
    result = IDENTITY.copy()
    i = 0
    text_end = len(text.rstrip())
    while i < text_end:
        match = _TRANSFORM.match(text, i)
        if not match:
            raise SvgValueError("expected a transform such as translate(x, y)", i,
                                "supported: matrix, translate, scale, rotate, skewX, skewY")
        name, body = match.group(1), match.group(2)
        if name not in _ARITY:
            raise SvgValueError(f"unknown transform '{name}'", match.start(1),
                                "supported: matrix, translate, scale, rotate, skewX, skewY")
        values = [v for v, _ in parse_numbers(body)] if body.strip() else []
        if len(values) not in _ARITY[name]:
            counts = " or ".join(str(n) for n in _ARITY[name])
            raise SvgValueError(f"{name}() takes {counts} numbers, got {len(values)}",
                                match.start(1))
        with np.errstate(over="ignore", invalid="ignore"):  # apply() reports overflow
            result = result @ _matrix(name, values)
        i = match.end()
    return result


def _matrix(name: str, v: list[float]) -> np.ndarray:
    if name == "matrix":
        a, b, c, d, e, f = v
        return np.array([[a, c, e], [b, d, f], [0.0, 0.0, 1.0]])
    if name == "translate":
        tx, ty = v[0], (v[1] if len(v) > 1 else 0.0)
        return np.array([[1.0, 0.0, tx], [0.0, 1.0, ty], [0.0, 0.0, 1.0]])
    if name == "scale":
        sx, sy = v[0], (v[1] if len(v) > 1 else v[0])
        return np.diag([sx, sy, 1.0])
    if name == "rotate":
        a = math.radians(v[0])
        c, s = math.cos(a), math.sin(a)
        rot = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
        if len(v) == 3:
            cx, cy = v[1], v[2]
            return _matrix("translate", [cx, cy]) @ rot @ _matrix("translate", [-cx, -cy])
        return rot
    t = math.tan(math.radians(v[0]))
    if name == "skewX":
        return np.array([[1.0, t, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
    return np.array([[1.0, 0.0, 0.0], [t, 1.0, 0.0], [0.0, 0.0, 1.0]])


def apply(matrix: np.ndarray, points: list[Point]) -> list[Point]:
    """Transform SVG points and flip y into the y-up frame."""
    if not points:
        return []
    arr = np.asarray(points, dtype=float)
    with np.errstate(over="ignore", invalid="ignore"):
        out = arr @ matrix[:2, :2].T + matrix[:2, 2]
    if not np.all(np.isfinite(out)):
        raise SvgValueError("coordinates overflow after the transform")
    return [(float(px) + 0.0, 0.0 - float(py)) for px, py in out]


# --- lengths ----------------------------------------------------------------------------------

# Absolute units in user units (px) at the CSS reference 96 dpi.
_UNITS = {"": 1.0, "px": 1.0, "pt": 96.0 / 72.0, "pc": 16.0, "mm": 96.0 / 25.4,
          "cm": 96.0 / 2.54, "in": 96.0, "q": 96.0 / 101.6}
_LENGTH = re.compile(r"\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*([A-Za-z%]*)\s*")


def parse_length(text: str) -> float:
    match = _LENGTH.fullmatch(text)
    if not match:
        raise SvgValueError(f"expected a length, found {text.strip()!r}")
    unit = match.group(2).lower()
    if unit not in _UNITS:
        raise SvgValueError(f"unsupported unit '{match.group(2)}'", match.start(2),
                            "give coordinates in user units (px)")
    return _finite(float(match.group(1)) * _UNITS[unit], match.start(1))
