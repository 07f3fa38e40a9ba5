"""Parse and validate `.ggr` rule files (docs/ggr-language.md): text → `Grammar`.

Three stages, as for `.gg` files. The lark grammar (ggr_grammar.lark) checks the shape of each
line and gives a tree; `ggr_reader` turns its tokens into names, numbers and settings; the
semantic checks then resolve names and check everything a hand edit can break: the header
(`ggr_header`: known faces, classes and labels, rings in angle order), the rules (`ggr_sides`:
slots glued once and only to their opposite half-edge, every open half-edge once on the
boundary, P − N = 1, boundaries that follow the rotation system, ∂L = ∂R, starters complete)
and hand-written productions (`ggr_free`: labels, kept and wildcard vertices, the types of
every expression). Every problem is a `UserError` at its line and column, with a caret excerpt
and a hint.
"""

from __future__ import annotations

import functools
from pathlib import Path

from lark import Lark, Tree
from lark.exceptions import UnexpectedCharacters, UnexpectedEOF, UnexpectedInput, UnexpectedToken

from . import ggr_free, limits
from .diagnostics import Diagnostic, Span, UserError
from .fileio import read_text
from .lark_cache import lalr_parser
from .ggr_header import FORMAT_VERSION, HeaderReader
from .ggr_reader import _Stop
from .ggr_sides import SideReader, unicode
from .rules import Grammar, Header, Rule

__all__ = ["FORMAT_VERSION", "load_ggr", "parse_ggr", "unicode"]
SYNTAX_HINT = "see docs/ggr-language.md for the syntax"


@functools.lru_cache(maxsize=1)
def _lark() -> Lark:
    return lalr_parser(Path(__file__).with_name("ggr_grammar.lark"), propagate_positions=False)


def load_ggr(path: str | Path) -> Grammar:
    return parse_ggr(read_text(path), str(path))


def parse_ggr(text: str, path: str = "<ggr>") -> Grammar:
    limits.check_tokens(text, path)
    # A final newline lets the last statement end like every other; it adds no line.
    source = text if text.endswith("\n") else text + "\n"
    try:
        tree = _lark().parse(source)
    except UnexpectedInput as exc:
        raise _syntax_error(exc, text, path) from None
    return _Builder(text, path).build(tree)


_FRIENDLY = {
    "NAME": "a name", "STRING": "a quoted string", "NUMBER": "a number", "INT": "a whole number",
    "_NL": "the end of the line", "KIND": "'rule' or 'starter'", "SIDE": "'lhs' or 'rhs'",
    "BAR": "'~'", "UP": "'+'", "DOWN": "'-'", "STAR": "'*'", "$END": "the end of the file",
}


def _describe(terminal: str) -> str:
    if terminal in _FRIENDLY:
        return _FRIENDLY[terminal]
    try:
        pattern = _lark().get_terminal(terminal).pattern
    except KeyError:
        return terminal
    return f"'{pattern.value}'" if pattern.type == "str" else terminal


def _expected(names) -> str:
    words = sorted({_describe(n) for n in names})
    if not words:
        return ""
    if len(words) > 8:
        words = words[:8] + ["…"]
    return "; expected " + (words[0] if len(words) == 1 else ", ".join(words[:-1]) + " or " + words[-1])


def _syntax_error(exc: UnexpectedInput, text: str, path: str) -> UserError:
    line, col = max(getattr(exc, "line", 1) or 1, 1), max(getattr(exc, "column", 1) or 1, 1)
    if isinstance(exc, UnexpectedCharacters):
        char = text[exc.pos_in_stream] if 0 <= exc.pos_in_stream < len(text) else "?"
        message = f"unexpected character {char!r}" + _expected(exc.allowed or ())
        hint = ("names are letters, digits and '_'; write any other name in double quotes"
                if char.isprintable() and not char.isspace() else SYNTAX_HINT)
        return UserError(Diagnostic(message, Span(path, line, col), hint, source=text))
    if isinstance(exc, UnexpectedToken):
        tok = exc.token
        if tok.type == "$END":
            what = "end of file"
            line = text.count("\n") + 1
            col = len(text.rsplit("\n", 1)[-1]) + 1
        elif tok.type == "_NL":
            what = "end of line"
            col = len(text.splitlines()[line - 1]) + 1 if line <= len(text.splitlines()) else col
        else:
            what = repr(str(tok))
        length = len(str(tok)) if tok.type not in ("$END", "_NL") else 1
        hint = SYNTAX_HINT
        if tok.type == "_NL":
            hint = "this line ends too early; " + SYNTAX_HINT
        elif "_NL" in exc.expected:
            hint = "each statement ends at the end of its line; " + SYNTAX_HINT
        return UserError(Diagnostic(f"unexpected {what}" + _expected(exc.expected),
                                    Span(path, line, col, length), hint, source=text))
    if isinstance(exc, UnexpectedEOF):
        return UserError(Diagnostic("unexpected end of file" + _expected(exc.expected),
                                    Span(path, text.count("\n") + 1, 1), SYNTAX_HINT, source=text))
    return UserError(Diagnostic(f"cannot parse: {exc}", Span(path, line, col), SYNTAX_HINT,
                                source=text))


# --- resolution and validation ----------------------------------------------------------------

class _Builder(HeaderReader, SideReader):
    def build(self, tree: Tree) -> Grammar:
        singles: dict[str, Tree] = {}
        lists: dict[str, list[Tree]] = {k: [] for k in
                                        ("edge_class", "label", "primitive", "decorate", "rule",
                                         "attribute", "production")}
        for stmt in tree.children:
            if stmt.data in lists:
                lists[stmt.data].append(stmt)
            elif stmt.data in singles:
                self.fail(f"'{_KEYWORD[stmt.data]}' is given twice", self._first_token(stmt),
                          f"the first one is on line {self._first_token(singles[stmt.data]).line}")
            else:
                singles[stmt.data] = stmt
        if "version" not in singles:
            raise UserError(Diagnostic(
                "this is not a .ggr rule file: it has no 'ggr 1' line", Span(self.path, 1, 1),
                "a rule file starts with the line 'ggr 1'; see docs/ggr-language.md",
                source=self.text))
        try:
            header = self._header(singles, lists)
        except _Stop:       # recorded; later checks would only repeat it
            pass
        self._raise_errors()
        if "frame_start" in singles:
            header = self._guard(self._frame_start, singles["frame_start"], header) or header
            self._raise_errors()
        rules = self._rules(lists["rule"], header)
        self._raise_errors()
        productions, start = self._productions(lists, singles, header, rules)
        self._raise_errors()
        return Grammar(header, tuple(rules), productions, start)

    def _productions(self, lists, singles, header: Header, rules: list[Rule]):
        """The hand-written productions and start graph (ggr_free), after the header."""
        if not lists["production"] and "start_graph" not in singles:
            return (), None
        if rules:
            raise self.fail("this file holds both angle-graph rules and productions",
                            rules[0].span, "one file runs on one engine: keep the 'rule's or "
                            "the 'production's (mixing them is not supported yet)")
        reader = ggr_free.FreeReader(self)
        ctx = ggr_free.context_of(header)
        productions = self._defined(reader.production, lists["production"], ctx)
        self._unique(lists["production"], "production")
        start = self._guard(reader.start, singles["start_graph"], ctx) \
            if "start_graph" in singles else None
        return tuple(productions), start



_KEYWORD = {"version": "ggr", "checksum": "checksum", "source": "source", "compiler": "compiler",
            "mode": "mode", "status": "status", "unit": "unit", "exterior": "exterior",
            "faces": "faces", "options": "options", "limits": "limits", "frame": "frame",
            "frame_start": "frame-start", "vertex_labels": "vertices", "edge_labels": "edges", "start_graph": "start"}
