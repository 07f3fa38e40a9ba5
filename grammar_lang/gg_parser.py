"""Parse `.gg` example files: lark LALR grammar → syntax tree (`gg_ast`) → `ExampleSource`.

`parse_file(path)` and `parse_text(text, path)` are the entry points; `parse_syntax` stops after
the syntax tree (imports use it). Every failure is a `UserError` with file:line:col, a caret
excerpt and a hint; lark's own errors are translated into plain words here.
"""

from __future__ import annotations

import math
import re
from functools import lru_cache
from pathlib import Path

from lark import Lark, Token, Transformer, v_args
from lark.exceptions import LarkError, UnexpectedCharacters, UnexpectedEOF, UnexpectedInput, \
    UnexpectedToken, VisitError

from . import gg_ast as A
from .diagnostics import Span, UserError, did_you_mean, error
from .lark_cache import lalr_parser
from . import limits
from .fileio import read_text
from .source import ExampleSource

GRAMMAR = Path(__file__).with_name("gg_grammar.lark")

STATEMENT_KEYWORDS = ("example", "import", "exterior", "face", "colour", "color", "class",
                      "options", "limits", "point", "polygon", "polyline", "loop", "edge",
                      "border", "primitive", "decorate", "shape", "rename")

# Words for the grammar's regex terminals; string terminals are shown as their quoted text.
_TERMINAL_WORDS = {
    "NUMBER": "a number",
    "NAME": "a name",
    "COLOUR": "a colour like #c0f0ff",
    "STRING": 'a "string"',
    "_NL": "the end of the statement (a new line or ';')",
    "$END": "the end of the file",
}

_NUMBER = re.compile(r"([+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?)(.*)", re.S)
_ESCAPES = {"n": "\n", "t": "\t", "r": "\r", "0": "\0", "\\": "\\", '"': '"', "'": "'"}


class _Lines:
    """Post-lexer: statements end at a newline or ';', except inside ( ) and [ ].

    Runs of separators collapse into one, leading ones are dropped and a final one is added, so
    the grammar sees exactly one `_NL` after each statement. It never looks ahead, which keeps
    lark's contextual lexer (keywords vs names) working.
    """

    always_accept = ("_NL",)

    def process(self, stream):
        depth = 0
        prev = "_NL"
        last = None
        for tok in stream:
            if tok.type == "_NL" and (depth or prev == "_NL"):
                continue
            if tok.type in ("LPAR", "LSQB"):
                depth += 1
            elif tok.type in ("RPAR", "RSQB"):
                depth = max(0, depth - 1)
            prev, last = tok.type, tok
            yield tok
        if prev != "_NL":
            if last is None:
                yield Token("_NL", "")
            else:  # placed just after the last token, where a missing ')' or value belongs
                yield Token("_NL", "", last.end_pos, last.end_line, last.end_column,
                            last.end_line, last.end_column, last.end_pos)


@lru_cache(maxsize=1)
def _lark() -> Lark:
    return lalr_parser(GRAMMAR, {"postlex": _Lines()}, propagate_positions=True,
                       maybe_placeholders=False)


# ---- lark errors → diagnostics ------------------------------------------------------------------

def _terminal_words(names) -> list[str]:
    terminals = {t.name: t for t in _lark().terminals}
    words: list[str] = []
    keywords = []
    for name in sorted(set(names)):
        if name in _TERMINAL_WORDS:
            words.append(_TERMINAL_WORDS[name])
            continue
        term = terminals.get(name)
        if term is not None and term.pattern.type == "str":
            if term.pattern.value in STATEMENT_KEYWORDS:
                keywords.append(term.pattern.value)
            else:
                words.append(f"'{term.pattern.value}'")
        else:
            words.append(name.lower())
    if len(keywords) > 4:
        words.insert(0, "a statement (" + ", ".join(k for k in STATEMENT_KEYWORDS
                                                    if k in keywords and k != "color") + ")")
    else:
        words.extend(f"'{k}'" for k in keywords)
    return sorted(set(words), key=words.index)


def _describe(tok: Token) -> str:
    if tok.type == "_NL":
        return "end of statement" if tok.value == ";" else "end of line"
    if tok.type == "$END":
        return "end of file"
    kind = {"NAME": "name", "NUMBER": "number", "STRING": "string", "COLOUR": "colour"}.get(tok.type)
    return f"{kind} {tok.value}" if kind else f"'{tok.value}'"


def _end_span(path: str, text: str) -> Span:
    lines = text.splitlines() or [""]
    return Span(path, len(lines), len(lines[-1]) + 1)


def _syntax_error(exc: UnexpectedInput, text: str, path: str) -> UserError:
    if isinstance(exc, UnexpectedCharacters):
        span = Span(path, exc.line, exc.column)
        ch = exc.char
        rest = text[exc.pos_in_stream:exc.pos_in_stream + 2]
        if ch == "#":
            return error("'#' must start a colour like #c0f0ff", span,
                         "comments start with // (or /* … */); colours are # and hex digits",
                         source=text)
        if ch in "\"'":
            return error("unterminated string", span,
                         f"close the string with {ch} on the same line; write \\{ch} for a "
                         f"{ch} inside it", source=text)
        if rest == "/*":
            return error("unterminated comment", span, "close it with */", source=text)
        expected = _terminal_words(exc.allowed or ())
        hint = ("expected " + " or ".join(expected)) if expected else None
        return error(f"unexpected character {ch!r}", span, hint, source=text)
    if isinstance(exc, UnexpectedToken):
        tok = exc.token
        if tok.type == "$END" or getattr(tok, "line", None) in (None, -1):
            span = _end_span(path, text)
        else:
            span = Span(path, tok.line, tok.column, max(1, len(str(tok.value))))
        expected = _terminal_words(exc.accepts or exc.expected or ())
        message = f"unexpected {_describe(tok)}"
        hint = ("expected " + ", ".join(expected[:-1]) + (" or " if len(expected) > 1 else "")
                + expected[-1]) if expected else None
        at_statement = "FACE" in (exc.accepts or exc.expected or ())
        if at_statement and tok.type == "NAME":
            message = f"unknown statement '{tok.value}'"
            hint = did_you_mean(tok.value, STATEMENT_KEYWORDS) or (
                "each statement starts with a keyword such as 'face', 'polygon', 'edge' or "
                "'class'; see docs/gg-language.md")
        return error(message, span, hint, source=text)
    if isinstance(exc, UnexpectedEOF):
        expected = _terminal_words(exc.expected or ())
        return error("unexpected end of file", _end_span(path, text),
                     ("expected " + " or ".join(expected)) if expected else None, source=text)
    return error(f"syntax error: {exc}", Span(path), source=text)


# ---- lark tree → syntax tree ------------------------------------------------------------------

def _span(path: str, item) -> Span:
    """The span of a token or a tree's meta, underlining it when it is on one line."""
    line = getattr(item, "line", None)
    column = getattr(item, "column", None)
    if not line or not column:
        return Span(path)
    end_line = getattr(item, "end_line", line)
    end_column = getattr(item, "end_column", None)
    length = (end_column - column) if (end_line == line and end_column) else 1
    return Span(path, line, column, max(1, length))


def decode_string(raw: str, span: Span, text: str) -> str:
    """The value of a quoted string token, with escapes \\n \\t \\r \\0 \\\\ \\" \\' \\uXXXX
    and \\u{X…}."""
    body = raw[1:-1]
    out: list[str] = []
    i = 0
    while i < len(body):
        c = body[i]
        if c != "\\":
            out.append(c)
            i += 1
            continue
        where = Span(span.file, span.line, span.column + 1 + i, 2)
        nxt = body[i + 1] if i + 1 < len(body) else ""
        if nxt in _ESCAPES:
            out.append(_ESCAPES[nxt])
            i += 2
            continue
        if nxt == "u":
            m = re.match(r"u\{([0-9A-Fa-f]{1,6})\}|u([0-9A-Fa-f]{4})", body[i + 1:])
            code = int(m.group(1) or m.group(2), 16) if m else None
            if code is None or code > 0x10FFFF or 0xD800 <= code <= 0xDFFF or code == 0:
                raise error("bad unicode escape", where,
                            "write \\u followed by 4 hex digits, or \\u{…} with 1-6", source=text)
            out.append(chr(code))
            i += 1 + len(m.group(0))
            continue
        raise error(f"unknown escape '\\{nxt}' in string", where,
                    "known escapes: \\n \\t \\r \\\\ \\\" \\' \\uXXXX \\u{…}; write \\\\ for a "
                    "backslash", source=text)
    return "".join(out)


@v_args(meta=True)
class _Build(Transformer):
    """Turns lark's tree into `gg_ast` nodes. Tokens reach here already positioned."""

    def __init__(self, path: str, text: str):
        super().__init__()
        self.path, self.text = path, text

    # -- leaves
    def _word(self, tok) -> A.Word:
        if isinstance(tok, (A.Word, A.Num)):
            return tok if isinstance(tok, A.Word) else A.Word(tok.text, "number", tok.span)
        span = _span(self.path, tok)
        if tok.type == "STRING":
            return A.Word(decode_string(str(tok), span, self.text), "string", span)
        kind = {"NAME": "name", "COLOUR": "colour", "STAR": "star"}[tok.type]
        return A.Word(str(tok), kind, span)

    def _value(self, item) -> A.Value:
        return item if isinstance(item, A.Num) else self._word(item)

    def number(self, meta, children) -> A.Num:
        tok = children[0]
        span = _span(self.path, tok)
        m = _NUMBER.fullmatch(str(tok))
        value = float(m.group(1))
        if not math.isfinite(value):
            raise error(f"number {m.group(1)} is too large", span, "use a smaller number",
                        source=self.text)
        unit = "deg" if m.group(2) == "°" else m.group(2)
        return A.Num(value, unit, str(tok), span)

    def xy(self, meta, children):
        return A.XY(children[0], children[1], _span(self.path, meta))

    def ref(self, meta, children):
        return A.Ref(str(children[0]), _span(self.path, children[0]))

    def points(self, meta, children):
        return (tuple(c for c in children if not isinstance(c, Token)), _span(self.path, meta))

    bracketed = points

    def rect(self, meta, children):
        return ((children[0], children[1]), _span(self.path, meta), True)

    def ring(self, meta, children):
        pts, span, *rect = children[0]
        return A.Ring(pts, bool(rect), span)

    def hole(self, meta, children):
        return children[0]

    def prop(self, meta, children):
        value = self._value(children[1]) if len(children) > 1 else None
        return A.Prop(str(children[0]), value, _span(self.path, meta))

    def block(self, meta, children):
        return tuple(c for c in children if isinstance(c, A.Prop))

    def _side(self, kind, meta, children):
        return A.Side(kind, self._word(children[0]), _span(self.path, meta))

    def left(self, meta, children):
        return self._side("left", meta, children)

    def right(self, meta, children):
        return self._side("right", meta, children)

    def edge_class(self, meta, children):
        return self._side("class", meta, children)

    # -- statements
    def start(self, meta, children):
        return tuple(children)

    def example(self, meta, children):
        return A.ExampleName(self._word(children[0]).text, _span(self.path, meta))

    def import_(self, meta, children):
        return A.Import(self._word(children[0]).text, _span(self.path, meta))

    def exterior(self, meta, children):
        return A.Exterior(self._word(children[0]), _span(self.path, meta))

    def face(self, meta, children):
        label = self._word(children[0])
        colour, props = None, ()
        for c in children[1:]:
            if isinstance(c, tuple):
                props = c
            else:
                colour = self._word(c)
        return A.Face(label, colour, props, _span(self.path, meta))

    def colour(self, meta, children):
        return A.ColourDef(str(children[0]), self._word(children[1]), _span(self.path, meta))

    def class_(self, meta, children):
        props = children[1] if len(children) > 1 else ()
        return A.ClassDef(self._word(children[0]), props, _span(self.path, meta))

    def options(self, meta, children):
        return A.Settings("options", children[0], _span(self.path, meta))

    def limits(self, meta, children):
        return A.Settings("limits", children[0], _span(self.path, meta))

    def point(self, meta, children):
        return A.PointDef(str(children[0]), children[1], _span(self.path, meta))

    def polygon(self, meta, children):
        label, outer, *rest = children
        holes = tuple(r for r in rest if isinstance(r, A.Ring))
        cls = next((r.word for r in rest if isinstance(r, A.Side)), None)
        return A.Polygon(self._word(label), outer, holes, cls, _span(self.path, meta))

    def _line(self, meta, children, closed, border):
        pts, span = children[0]
        ring = pts if isinstance(pts, A.Ring) else A.Ring(pts, False, span)
        cls = children[1].word if len(children) > 1 else None
        return A.Polyline(ring, closed, border, cls, _span(self.path, meta))

    def polyline(self, meta, children):
        return self._line(meta, children, False, False)

    def loop(self, meta, children):
        return self._line(meta, children, True, False)

    def border(self, meta, children):
        ring = children[0]
        cls = children[1].word if len(children) > 1 else None
        return A.Polyline(ring, True, True, cls, _span(self.path, meta))

    def edge(self, meta, children):
        pts = tuple(c for c in children if isinstance(c, (A.XY, A.Ref)))
        sides = tuple(c for c in children if isinstance(c, A.Side))
        return A.Edge(pts, sides, _span(self.path, meta))

    def shape(self, meta, children):
        return A.ShapeFrom(self._word(children[0]).text, _span(self.path, meta))

    def rename(self, meta, children):
        old, _, new = children
        return A.Rename(self._word(old), self._word(new), _span(self.path, meta))

    def half_edge(self, meta, children):
        return A.HalfEdge(children[0], tuple(children[1:]), _span(self.path, meta))

    def primitive(self, meta, children):
        name = next((str(c) for c in children if isinstance(c, Token) and c.type == "NAME"), None)
        halves = tuple(c for c in children if isinstance(c, A.HalfEdge))
        return A.PrimitiveDef(name, halves, _span(self.path, meta))

    def decorate(self, meta, children):
        kind, target, props = children
        return A.Decorate(self._word(kind), self._word(target), props, _span(self.path, meta))


def parse_syntax(text: str, path: str | Path = "<text>") -> tuple[A.Stmt, ...]:
    """The statements of one `.gg` text, without resolving imports or names."""
    path = str(path)
    limits.check_tokens(text, path)
    try:
        tree = _lark().parse(text)
    except UnexpectedInput as exc:
        raise _syntax_error(exc, text, path) from None
    except LarkError as exc:  # any other lark failure is still about this input
        raise error(f"cannot parse this file: {exc}", Span(path), source=text) from None
    try:
        return _Build(path, text).transform(tree)
    except VisitError as exc:
        if isinstance(exc.orig_exc, UserError):
            raise exc.orig_exc from None
        raise


def parse_text(text: str, path: str | Path = "<text>") -> ExampleSource:
    """Parse and resolve a `.gg` text; relative imports and files resolve against `path`."""
    from .gg_resolve import resolve
    return resolve(text, Path(path), parse_syntax)


def parse_file(path: str | Path) -> ExampleSource:
    p = Path(path)
    return parse_text(read_text(p), p)
