"""Input limits: how much a file may hold before the tools refuse it (docs/limits.md).

Each limit is checked before the big allocation it guards: the byte size before a file is
read, the count of statements, elements, numbers or points while a reader walks the text,
before geometry is built from them. A refusal is an ordinary located `UserError` that names
the limit and the environment variable that raises it, so a user with a truly big drawing can
go on. The defaults keep every accepted input well under 30 s and 1 GB.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass

from .diagnostics import Span, UserError, error


@dataclass(frozen=True)
class InputLimit:
    name: str
    env: str            # the environment variable that overrides the default
    default: int
    doc: str            # what is counted

    def value(self) -> int:
        raw = os.environ.get(self.env)
        if raw is None or raw.strip() == "":
            return self.default
        try:
            value = int(raw.strip().replace("_", ""))
        except ValueError:
            value = 0
        if value < 1:
            raise error(f"{self.env}={raw!r} is not a valid limit", None,
                        f"set {self.env} to a whole number of at least 1 "
                        f"(default {self.default:,})")
        return value

    def message(self, count: int, what: str | None = None) -> str:
        return (f"the input is over the {self.name} limit: {count:,} {what or self.doc}, "
                f"at most {self.value():,} allowed")

    def hint(self) -> str:
        return (f"this limit guards memory and time; to raise it, set {self.env}=N in the "
                "environment (see docs/limits.md)")

    def exceeded(self, count: int, span: Span | None, source: str | None = None,
                 what: str | None = None) -> UserError:
        """The diagnostic for `count` (or more) of what this limit counts."""
        return error(self.message(count, what), span, self.hint(), source=source)

    def check(self, count: int, span: Span | None, source: str | None = None,
              what: str | None = None) -> None:
        if count > self.value():
            raise self.exceeded(count, span, source, what)


BYTES = InputLimit("bytes", "GG_MAX_BYTES", 4_000_000, "bytes")
# Words, numbers and symbols of one .gg or .ggr file, counted before it is parsed (the parser
# takes about 0.1 ms and 1 kB per token). Compiled grammars have a few thousand.
TOKENS = InputLimit("tokens", "GG_MAX_TOKENS", 100_000, "tokens (words, numbers, symbols)")
# Elements of an SVG file; entries of a JSON array.
ELEMENTS = InputLimit("elements", "GG_MAX_ELEMENTS", 10_000, "elements")
# Points of one example (every polygon, line and path point, every JSON vertex) or vertices of
# one drawing; also the coordinate pairs of one SVG attribute.
POINTS = InputLimit("points", "GG_MAX_POINTS", 10_000, "points")

# Vertices a generated drawing may reach: a run stops there, as memory grows with the drawing.
DRAWING = InputLimit("drawing", "GG_MAX_DRAWING", 500_000, "vertices in the drawing")
# Cells of the runtime's spatial grid along a frame's sides (`ggrun --extent`, or a frame drawn
# that large): a side is filed in every cell it crosses, and again each time a structure
# stood on it splits it. The paper's scenes at their extents span a few hundred; at 1,200,000
# (the castle at 10,000,000 × 5,000,000) twenty steps took 76 s and 736 MB.
EXTENT = InputLimit("extent", "GG_MAX_EXTENT", 40_000, "grid cells along the frame's sides")

ALL = (BYTES, TOKENS, ELEMENTS, POINTS, DRAWING, EXTENT)

_TOKEN = re.compile(r"[^\s(){}\[\],;:=]+|[(){}\[\],;:=]")


def check_tokens(text: str, path: str) -> None:
    """Refuse a text with more tokens than `TOKENS` allows, at the first token over, before
    a parser builds anything from it. (A rough count: a quoted string may count as several.)"""
    limit = TOKENS.value()
    if len(text) <= limit:      # a token is at least one character
        return
    for count, m in enumerate(_TOKEN.finditer(text), 1):
        if count > limit:
            line = text.count("\n", 0, m.start()) + 1
            col = m.start() - (text.rfind("\n", 0, m.start()) + 1) + 1
            raise TOKENS.exceeded(count, Span(path, line, col), text,
                                  what="tokens (words, numbers, symbols) so far")
