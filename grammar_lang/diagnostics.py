"""User-facing diagnostics: a place in a file, a message, a caret excerpt and a hint.

Every error a user can cause is a `UserError`. The command-line front ends catch it, print it
and exit with status 2; only `--debug` shows a traceback.
"""

from __future__ import annotations

import difflib
from dataclasses import dataclass, field


EXCERPT_WIDTH = 120     # characters of a source line shown in an excerpt


@dataclass(frozen=True)
class Span:
    """A place in a source text: 1-based line and column, and how many columns to underline."""

    file: str
    line: int = 0
    column: int = 0
    length: int = 1

    def __str__(self) -> str:
        if self.line <= 0:
            return self.file
        return f"{self.file}:{self.line}:{self.column}"


@dataclass(frozen=True)
class Diagnostic:
    message: str
    span: Span | None = None
    hint: str | None = None
    severity: str = "error"
    # The text of the file the span points into, so the excerpt can be shown without re-reading.
    source: str | None = field(default=None, compare=False, repr=False)

    def excerpt(self) -> str:
        """The offending line with a caret under the span, or '' when there is nothing to show."""
        if self.span is None or self.span.line <= 0 or self.source is None:
            return ""
        # Lines end at "\n" only, as parsers count them (splitlines() would also break at
        # form feeds and U+2028, shifting every later line).
        lines = self.source.split("\n")
        if self.span.line > len(lines):
            return ""
        text = lines[self.span.line - 1].rstrip("\r").expandtabs(1)
        gutter = f"{self.span.line:>4} | "
        col = max(self.span.column, 1)
        if len(text) > EXCERPT_WIDTH:
            # A long line (one huge path or polyline) is shown around the column only.
            start = max(0, min(col - 1 - EXCERPT_WIDTH // 2, len(text) - EXCERPT_WIDTH))
            clipped = text[start:start + EXCERPT_WIDTH]
            text = ("…" if start else "") + clipped + ("…" if start + EXCERPT_WIDTH < len(text) else "")
            col = col - start + (1 if start else 0)
        width = max(1, min(self.span.length, max(1, len(text) - col + 1)))
        caret = " " * (len(gutter) - 2) + "| " + " " * (col - 1) + "^" * width
        return f"{gutter}{text}\n{caret}"

    def render(self) -> str:
        where = f"{self.span}: " if self.span else ""
        parts = [f"{where}{self.severity}: {self.message}"]
        excerpt = self.excerpt()
        if excerpt:
            parts.append(excerpt)
        if self.hint:
            parts.append(f"  hint: {self.hint}")
        return "\n".join(parts)


class UserError(Exception):
    """An error in the user's input or command line. Carries one or more diagnostics."""

    def __init__(self, *diagnostics: Diagnostic):
        if not diagnostics:
            raise ValueError("UserError needs at least one diagnostic")
        self.diagnostics = tuple(diagnostics)
        super().__init__(diagnostics[0].message)

    def render(self) -> str:
        return "\n".join(d.render() for d in self.diagnostics)


def error(message: str, span: Span | None = None, hint: str | None = None,
          source: str | None = None) -> UserError:
    """Shorthand for a one-diagnostic `UserError`, to be raised by the caller."""
    return UserError(Diagnostic(message, span, hint, source=source))


def did_you_mean(name: str, known) -> str | None:
    """A 'did you mean …?' hint for an unknown name, or None when nothing is close."""
    close = difflib.get_close_matches(name, sorted(set(known)), n=3, cutoff=0.6)
    if not close:
        return None
    return "did you mean " + " or ".join(f"'{c}'" for c in close) + "?"
