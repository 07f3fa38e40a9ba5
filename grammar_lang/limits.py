"""Input limits: how much a file may hold before the tools refuse it (docs/limits.md).

Each limit is checked before the big allocation it guards: the byte size before a file is
read, the count of statements, elements, numbers or points while a reader walks the text,
before geometry is built from them. A refusal is an ordinary located `UserError` that names
the limit and the environment variable that raises it, so a user with a truly big drawing can
go on. The defaults keep every accepted input well under 30 s and 1 GB.
"""

from __future__ import annotations

import os
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

    def exceeded(self, count: int, span: Span | None, source: str | None = None,
                 what: str | None = None) -> UserError:
        """The diagnostic for `count` (or more) of what this limit counts."""
        thing = what or self.doc
        return error(f"the input is over the {self.name} limit: {count:,} {thing}, "
                     f"at most {self.value():,} allowed", span,
                     f"this limit guards memory and time; to raise it, set "
                     f"{self.env}=N in the environment (see docs/limits.md)", source=source)

    def check(self, count: int, span: Span | None, source: str | None = None,
              what: str | None = None) -> None:
        if count > self.value():
            raise self.exceeded(count, span, source, what)


BYTES = InputLimit("bytes", "GG_MAX_BYTES", 4_000_000, "bytes")
# Statements of a .gg file, elements of an SVG file, entries of a JSON array, lines of a .ggr.
ELEMENTS = InputLimit("elements", "GG_MAX_ELEMENTS", 50_000, "elements")
# Numbers in one .gg file or SVG attribute: a cheap count made before anything is parsed.
NUMBERS = InputLimit("numbers", "GG_MAX_NUMBERS", 100_000, "numbers")
# Points of one example (every polygon, line and path point) or vertices of one drawing.
POINTS = InputLimit("points", "GG_MAX_POINTS", 20_000, "points")

ALL = (BYTES, ELEMENTS, NUMBERS, POINTS)
