"""The token-level half of the `.ggr` reader: names, numbers, settings and slots from lark
tokens, and the error machinery every later stage reports through (`Reader.fail`).

ggr_parser checks the syntax and hands the tree to a reader built from these stages:
ggr_header (the header's definitions), ggr_sides (rules and their sides) and ggr_free
(hand-written productions), each a set of semantic checks on top of `Reader`.
"""

from __future__ import annotations

import math
import re
import sys
from dataclasses import dataclass

from lark import Token, Tree

from .diagnostics import Diagnostic, Span, UserError, did_you_mean

MAX_ERRORS = 20     # enough to fix a batch of mistakes, few enough to read


class _Stop(Exception):
    """Abandon the current statement or rule after an error; the error is already recorded."""


_ESCAPES = {"n": "\n", "t": "\t", "r": "\r", '"': '"', "\\": "\\"}
_ESCAPE_RE = re.compile(r"\\(u[0-9a-fA-F]{4}|U[0-9a-fA-F]{8}|.)", re.S)


@dataclass
class _Slot:
    vertex: Token
    ref: int | tuple[bool, Token]     # slot index, or (barred, label name)
    span: Span



class Reader:
    def __init__(self, text: str, path: str):
        self.text, self.path = text, path
        self.errors: list[Diagnostic] = []
        self.broken: set[str] = set()   # names whose definition had an error

    # -- helpers --

    def span(self, tok: Token, length: int | None = None) -> Span:
        return Span(self.path, tok.line or 0, tok.column or 0,
                    length if length is not None else max(1, len(str(tok))))

    def fail(self, message: str, where: Token | Span | None, hint: str | None = None) -> _Stop:
        span = where if isinstance(where, Span) or where is None else self.span(where)
        self.errors.append(Diagnostic(message, span, hint, source=self.text))
        if len(self.errors) >= MAX_ERRORS:
            raise UserError(*self.errors)
        return _Stop()

    def name(self, tok: Token) -> str:
        if tok.type != "STRING":
            return str(tok)

        def unescape(m: re.Match) -> str:
            esc = m.group(1)
            if esc[0] in "uU" and len(esc) > 1:
                code = int(esc[1:], 16)
                if code > 0x10FFFF or 0xD800 <= code <= 0xDFFF:
                    raise self.fail(f"'\\{esc}' is not a character", tok)
                return chr(code)
            if esc in _ESCAPES:
                return _ESCAPES[esc]
            raise self.fail(f"unknown escape '\\{esc}' in a string", tok,
                            'use \\" \\\\ \\n \\t \\r or \\uXXXX')

        return _ESCAPE_RE.sub(unescape, str(tok)[1:-1])

    def lookup(self, what: str, tok: Token, table: dict[str, int], hint: str | None = None) -> int:
        key = self.name(tok)
        if key in table:
            return table[key]
        if key in self.broken:      # its definition already has an error; say it once
            raise _Stop()
        if not did_you_mean(key, table) and not hint and 0 < len(table) <= 12:
            hint = "known: " + ", ".join(sorted(table))
        raise self.fail(f"unknown {what} '{key}'", tok, did_you_mean(key, table) or hint)

    # -- settings: `key=value` and bare flags --

    def settings(self, nodes, schema: dict[str, str], what: str) -> dict[str, object]:
        """Convert settings by their declared type; keys are checked against `schema`."""
        out: dict[str, object] = {}
        for node in nodes:
            key_tok = node.children[0]
            key = self.name(key_tok)
            if key not in schema:
                raise self.fail(f"unknown setting '{key}' for {what}", key_tok,
                                did_you_mean(key, schema) or
                                "known settings: " + ", ".join(sorted(schema)))
            if key in out:
                raise self.fail(f"'{key}' is given twice", key_tok)
            value = node.children[1] if len(node.children) > 1 else None
            out[key] = self.convert(schema[key], key_tok, value)
        return out

    def _key(self, nodes, key: str) -> Token:
        """The key token of setting `key` among `nodes` (it is known to be there)."""
        return next(n.children[0] for n in nodes if self.name(n.children[0]) == key)

    def convert(self, kind: str, key: Token, value: Tree | None) -> object:
        if value is None:
            if kind == "bool":
                return True
            raise self.fail(f"'{key}' needs a value: {key}=…", key)
        tok: Token = value.children[0]
        raw = str(tok)
        if kind == "bool":
            if value.data == "word" and raw in ("true", "false"):
                return raw == "true"
            raise self.fail(f"'{key}' is true or false, not {raw}", tok)
        if kind == "name":
            return self.name(tok) if value.data == "string" else raw
        if kind == "str":
            if value.data == "string":
                return self.name(tok)
            raise self.fail(f"'{key}' is a quoted string", tok, f'write {key}="{raw}"')
        if kind == "int":
            if value.data == "number" and re.fullmatch(r"[+-]?\d+", raw):
                return self.integer(tok)
            raise self.fail(f"'{key}' is a whole number, not {raw}", tok)
        if kind in ("float", "optfloat"):
            if kind == "optfloat" and value.data == "word" and raw == "auto":
                return None
            if value.data == "word" and raw == "inf":
                return math.inf
            if value.data == "number":
                return self.number(tok)
            allowed = "a number or auto" if kind == "optfloat" else "a number"
            raise self.fail(f"'{key}' is {allowed}, not {raw}", tok)
        raise AssertionError(kind)

    def integer(self, tok: Token) -> int:
        try:
            value = int(str(tok))
        except ValueError:      # more digits than Python converts
            raise self.fail(f"the number {str(tok)[:20]}… is too long", tok) from None
        # Whole numbers meet floats (a decoration's size, a weight): one beyond the largest
        # float is out of range, as a decimal one is (`number`).
        if abs(value) > sys.float_info.max:
            raise self.fail(f"{str(tok)[:20]}… is out of range", tok)
        return value

    def number(self, tok: Token) -> float:
        value = float(str(tok))
        if math.isnan(value) or math.isinf(value):
            raise self.fail(f"{str(tok)[:20]} is out of range", tok)
        return value

    def prop(self, value: Tree) -> object:
        tok: Token = value.children[0]
        raw = str(tok)
        if value.data == "string":
            return self.name(tok)
        if value.data == "word":
            return {"true": True, "false": False}.get(raw, raw)
        if re.fullmatch(r"[+-]?\d+", raw):
            return self.integer(tok)
        return self.number(tok)

    # -- the file --
    def _raise_errors(self) -> None:
        if self.errors:
            raise UserError(*self.errors)

    @staticmethod
    def _first_token(node: Tree) -> Token:
        for tok in node.scan_values(lambda t: isinstance(t, Token)):
            return tok
        return Token("NAME", "", line=0, column=0)

    def _guard(self, fn, *args):
        try:
            return fn(*args)
        except _Stop:
            return None

    def _defined(self, fn, nodes: list[Tree], *args) -> list:
        """Run fn over definitions; remember the names of failed ones, so that their uses
        do not repeat the error."""
        out = []
        for node in nodes:
            item = self._guard(fn, node, *args)
            if item is None:
                name = self._guard(self.name, node.children[0])
                if name is not None:
                    self.broken.add(name)
            else:
                out.append(item)
        return out
    def _label_list(self, node: Tree | None) -> tuple[str, ...]:
        out: list[str] = []
        for tok in node.children if node is not None else ():
            label = self.name(tok)
            if label in out:
                self.fail(f"label '{label}' is listed twice", tok)
            out.append(label)
        return tuple(out)

    def _unique(self, nodes: list[Tree], what: str) -> None:
        seen: dict[str, int] = {}
        for node in nodes:
            tok = node.children[0]
            name = self._guard(self.name, tok)
            if name in seen:
                self.fail(f"{what} '{name}' is defined twice", tok,
                          f"the first definition is on line {seen[name]}")
            elif name is not None:
                seen[name] = tok.line

    def _slot(self, tok: Token) -> _Slot:
        """Split a SLOT token (`a.x`, `a.~x`, `a.0`, quoted names allowed) into its parts."""
        m = _SLOT_RE.fullmatch(str(tok))
        vertex, bar, ref = m.group(1), m.group(2), m.group(3)
        span = Span(self.path, tok.line, tok.column, len(tok))
        vtok = Token("STRING" if vertex.startswith('"') else "NAME", vertex,
                     line=tok.line, column=tok.column)
        if re.fullmatch(r"\d+", ref):
            itok = Token("INT", ref, line=tok.line, column=tok.column + m.start(3))
            return _Slot(vtok, self.integer(itok), span)
        ltok = Token("STRING" if ref.startswith('"') else "NAME", ref,
                     line=tok.line, column=tok.column + m.start(3))
        return _Slot(vtok, (bool(bar), ltok), span)


    def _split_vertex(self, tok: Token) -> tuple[Token, Token]:
        m = _VERTEX_RE.fullmatch(str(tok))
        parts = []
        for g in (1, 2):
            text = m.group(g)
            parts.append(Token("STRING" if text.startswith('"') else "NAME", text,
                               line=tok.line, column=tok.column + m.start(g)))
        return parts[0], parts[1]


_NAME_OR_STRING = r'[^\W\d]\w*|"(?:[^"\\\n]|\\.)*"'
_SLOT_RE = re.compile(rf"({_NAME_OR_STRING})\.(~?)({_NAME_OR_STRING}|\d+)")
_VERTEX_RE = re.compile(rf"({_NAME_OR_STRING})[ \t]*:[ \t]*({_NAME_OR_STRING})")
