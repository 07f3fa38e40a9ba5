"""Reading JSON input files by a schema: types, finite numbers, ranges and sizes.

`json.loads` accepts `NaN`, `1e999` (as infinity), integers of thousands of digits (and then
fails converting them), and strings with lone surrogates, any of which breaks code far from
the file. Here each value is checked where it is read, and a problem is a diagnostic that names
the file and the value's path in the document (`edges[3].left`).
"""

from __future__ import annotations

import json
import math

from . import limits
from .diagnostics import Span, UserError, error

MAX_INT_DIGITS = 18      # ids and indices; a longer integer is certainly a mistake


class Reader:
    """Checks values of one document; `what` names the format in messages and `hint` says
    what the format holds."""

    def __init__(self, where: str, what: str, hint: str):
        self.where, self.what, self.hint = where, what, hint

    def fail(self, path: str, message: str) -> UserError:
        return error(f"{self.what}: {path}: {message}", Span(self.where), self.hint)

    def parse(self, text: str) -> object:
        def bad_constant(name: str):
            raise error(f"{self.what}: '{name}' is not a JSON number", _find(self.where, text, name),
                        "write a finite number", source=text)

        def integer(raw: str) -> int:
            if len(raw.lstrip("-")) > MAX_INT_DIGITS:
                raise error(f"{self.what}: the integer {raw[:20]}… is too long",
                            _find(self.where, text, raw), self.hint, source=text)
            return int(raw)

        try:
            return json.loads(text, parse_constant=bad_constant, parse_int=integer)
        except json.JSONDecodeError as exc:
            raise error(f"not valid JSON: {exc.msg}", Span(self.where, exc.lineno, exc.colno),
                        self.hint, source=text) from None

    def obj(self, value: object, path: str) -> dict:
        if not isinstance(value, dict):
            raise self.fail(path, f"expected an object, got {_kind(value)}")
        return value

    def key(self, value: dict, key: str, path: str) -> object:
        if key not in value:
            raise self.fail(path, f"missing \"{key}\"")
        return value[key]

    def array(self, value: object, path: str, length: int | None = None,
              limit: limits.InputLimit = limits.ELEMENTS) -> list:
        if not isinstance(value, list):
            raise self.fail(path, f"expected an array, got {_kind(value)}")
        if length is not None and len(value) != length:
            raise self.fail(path, f"expected {length} entries, got {len(value)}")
        limit.check(len(value), Span(self.where), what=f"entries in {path}")
        return value

    def number(self, value: object, path: str) -> float:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise self.fail(path, f"expected a number, got {_kind(value)}")
        x = float(value)
        if not math.isfinite(x) or abs(x) > 1e12:
            raise self.fail(path, f"the number {value!r} is out of range")
        return x

    def integer(self, value: object, path: str, lo: int | None = None,
                hi: int | None = None) -> int:
        if isinstance(value, float) and value.is_integer() and abs(value) < 2 ** 53:
            value = int(value)
        if isinstance(value, bool) or not isinstance(value, int):
            raise self.fail(path, f"expected a whole number, got {_kind(value)}")
        if (lo is not None and value < lo) or (hi is not None and value > hi):
            raise self.fail(path, f"{value} is out of range")
        return value

    def string(self, value: object, path: str) -> str:
        if not isinstance(value, str):
            raise self.fail(path, f"expected a string, got {_kind(value)}")
        try:
            value.encode("utf-8")
        except UnicodeEncodeError:
            raise self.fail(path, "the string holds a lone surrogate (\\ud800-\\udfff)") from None
        return value

    def boolean(self, value: object, path: str) -> bool:
        if not isinstance(value, bool):
            raise self.fail(path, f"expected true or false, got {_kind(value)}")
        return value


def _kind(value: object) -> str:
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return f"the number {value!r}"[:40]
    if isinstance(value, str):
        return f"the string {json.dumps(value)[:30]}"
    return {dict: "an object", list: "an array"}.get(type(value), type(value).__name__)


def _find(where: str, text: str, token: str) -> Span:
    i = text.find(token)
    if i < 0:
        return Span(where)
    line = text.count("\n", 0, i) + 1
    return Span(where, line, i - (text.rfind("\n", 0, i) + 1) + 1, len(token))
