"""Parse and validate `.ggr` rule files (docs/ggr-language.md): text → `Grammar`.

Parsing has two stages. The lark grammar (ggr_grammar.lark) checks the shape of each line;
`_Builder` then resolves names and checks everything a hand edit can break: known faces,
classes, labels, primitives and vertices, rings in angle order, slots glued once and only to
their opposite half-edge, every open half-edge once on the boundary, P − N = 1 on each side,
boundaries that follow the rotation system (`graph.face_walk`), ∂L = ∂R, and starters with a
complete left side and no right side. Every problem is a `UserError` at its line and column,
with a caret excerpt and a hint.
"""

from __future__ import annotations

import functools
import math
import re
from dataclasses import dataclass
from pathlib import Path

from lark import Lark, Token, Tree
from lark.exceptions import UnexpectedCharacters, UnexpectedEOF, UnexpectedInput, UnexpectedToken

from . import boundary as bd
from . import ggr_free
from .diagnostics import Diagnostic, Span, UserError, did_you_mean
from .example import EdgeLabel, Primitive
from .fileio import read_text
from .frame import Corner, Frame
from .graph import EMPTY, Side, face_walk
from .rules import Grammar, Header, Rule
from .source import DEFAULT_CLASS, Decoration, EdgeClass, Limits, Options

FORMAT_VERSION = 1
SYNTAX_HINT = "see docs/ggr-language.md for the syntax"
MAX_ERRORS = 20     # enough to fix a batch of mistakes, few enough to read


@functools.lru_cache(maxsize=1)
def _lark() -> Lark:
    text = Path(__file__).with_name("ggr_grammar.lark").read_text(encoding="utf-8")
    return Lark(text, parser="lalr", lexer="contextual", propagate_positions=False)


def load_ggr(path: str | Path) -> Grammar:
    return parse_ggr(read_text(path), str(path))


def parse_ggr(text: str, path: str = "<ggr>") -> Grammar:
    # A final newline lets the last statement end like every other; it adds no line.
    source = text if text.endswith("\n") else text + "\n"
    try:
        tree = _lark().parse(source)
    except UnexpectedInput as exc:
        raise _syntax_error(exc, text, path) from None
    return _Builder(text, path).build(tree)


def unicode(tokens, names) -> str:
    """The paper's notation, spaced out when label names are longer than a letter (x01 y01)."""
    if all(len(n) == 1 for n in names):
        return bd.format_tokens(tokens, names)
    return " ".join(bd.format_tokens([t], names) for t in tokens)


# --- syntax errors ---------------------------------------------------------------------------

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

def _turn_text(n: int) -> str:
    return " ".join(["+"] * n if n > 0 else ["-"] * -n)


class _Stop(Exception):
    """Abandon the current statement or rule after an error; the error is already recorded."""


_ESCAPES = {"n": "\n", "t": "\t", "r": "\r", '"': '"', "\\": "\\"}
_ESCAPE_RE = re.compile(r"\\(u[0-9a-fA-F]{4}|U[0-9a-fA-F]{8}|.)", re.S)


@dataclass
class _Slot:
    vertex: Token
    ref: int | tuple[bool, Token]     # slot index, or (barred, label name)
    span: Span


class _Builder:
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
            return int(str(tok))
        except ValueError:      # more digits than Python converts
            raise self.fail(f"the number {str(tok)[:20]}… is too long", tok) from None

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

    def _header(self, singles: dict[str, Tree], lists: dict[str, list[Tree]]) -> Header:
        version = singles["version"].children[0]
        if self.integer(version) != FORMAT_VERSION:
            self.fail(f"this tool reads .ggr version {FORMAT_VERSION}, not {version}", version,
                      "regenerate the file with this version of ggc")
        fields: dict[str, object] = {}
        if "source" in singles:
            node = singles["source"].children
            fields["source"] = self.name(node[0])
            if len(node) > 1:
                fields["source_hash"] = self.name(node[1])
        if "compiler" in singles:
            fields["compiler_version"] = self.name(singles["compiler"].children[0])
        if "mode" in singles:
            tok = singles["mode"].children[0]
            mode = self.name(tok)
            if mode not in ("dpo", "spo"):
                self.fail(f"unknown mode '{mode}'", tok,
                          "dpo (a rule needs its gluing conditions) or spo (dangling edges are deleted)")
            fields["mode"] = mode
        if "status" in singles:
            tok = singles["status"].children[0]
            status = self.name(tok)
            if status not in _STATUS:
                self.fail(f"unknown status '{status}'", tok,
                          did_you_mean(status, _STATUS) or "complete, limited or unknown")
            fields["complete"] = _STATUS.get(status)
        if "unit" in singles:
            tok = singles["unit"].children[0]
            unit = self._guard(self.number, tok)
            if unit is not None and unit <= 0:
                self.fail("the unit must be positive", tok)
            fields["unit"] = unit if unit is not None else 1.0
        if "options" in singles or "limits" in singles:
            fields["options"] = self._options(singles.get("options"), singles.get("limits"))
        exterior = "exterior"
        if "exterior" in singles:
            exterior = self.name(singles["exterior"].children[0])
        fields["exterior"] = exterior
        faces: list[str] = []
        if "faces" in singles:
            for tok in singles["faces"].children:
                face = self.name(tok)
                if face in faces:
                    self.fail(f"face label '{face}' is listed twice", tok)
                faces.append(face)
        fields["face_labels"] = tuple(faces)
        known_faces = set(faces) | {exterior}

        classes = self._defined(self._edge_class, lists["edge_class"])
        fields["classes"] = tuple(classes)
        class_names = {c.name for c in classes} | {DEFAULT_CLASS}
        labels = self._defined(self._label, lists["label"], known_faces, class_names)
        fields["labels"] = tuple(labels)
        if any(l.cls == DEFAULT_CLASS for l in labels) and DEFAULT_CLASS not in \
                {c.name for c in classes}:
            # The default class exists without a line of its own; list it like the others so
            # that every class a label uses is in the header.
            fields["classes"] = tuple(classes) + (EdgeClass(DEFAULT_CLASS),)
        self._unique(lists["label"], "edge label")
        self._unique(lists["edge_class"], "edge class")
        label_ids = {l.name: i for i, l in enumerate(labels)}
        prims = self._defined(self._primitive, lists["primitive"], labels, label_ids)
        self._unique(lists["primitive"], "primitive")
        fields["primitives"] = tuple(prims)
        fields["vertex_labels"] = self._label_list(singles.get("vertex_labels"))
        fields["edge_labels"] = self._label_list(singles.get("edge_labels"))
        declared: dict = {}
        reader = ggr_free.FreeReader(self)
        fields["attributes"] = tuple(a for a in (self._guard(reader.attribute, n, declared)
                                                 for n in lists["attribute"]) if a)
        targets = {"face": known_faces,
                   "edge": {c.name for c in classes} | {DEFAULT_CLASS} | set(fields["edge_labels"]),
                   "vertex": {p.name for p in prims} | set(fields["vertex_labels"])}
        fields["decorations"] = tuple(d for d in (self._guard(self._decoration, n, targets)
                                                  for n in lists["decorate"]) if d)
        if "frame" in singles:
            fields["frame"] = self._frame(singles["frame"], prims)
        return Header(**fields)

    def _frame(self, node: Tree, prims) -> Frame:
        """`frame P x y P x y …`: the corners of the border, in order round it."""
        index = {p.name: k for k, p in enumerate(prims)}
        parts, corners = node.children, []
        for k in range(0, len(parts), 3):
            tok, x, y = parts[k:k + 3]
            name = self.name(tok)
            if name not in index:
                self.fail(f"unknown primitive '{name}' in the frame", tok,
                          did_you_mean(name, index) or "a corner is one of the primitives above")
            corners.append(Corner(index[name], self.number(x), self.number(y)))
        if len(corners) < 3:
            self.fail("a frame has at least three corners", self._first_token(node))
        return Frame(tuple(corners))

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

    def _options(self, options: Tree | None, limits: Tree | None) -> Options:
        opts = self.settings(options.children if options else [], _OPTION_KEYS, "options") \
            if options else {}
        lims = self.settings(limits.children if limits else [], _LIMIT_KEYS, "limits") \
            if limits else {}
        for key, value in list(opts.items()) + list(lims.items()):
            if value is not None and value < 0:
                node = options if key in opts else limits
                tok = self._key(node.children, key)
                self.fail(f"'{key}' cannot be negative", tok)
        return Options(**opts, limits=Limits(**lims))

    def _edge_class(self, node: Tree) -> EdgeClass:
        tok, *rest = node.children
        s = self.settings(rest, _CLASS_KEYS, "an edge class")
        for key in ("min", "max", "fixed", "tile"):
            if s.get(key) is not None and s[key] <= 0:
                key_tok = self._key(rest, key)
                raise self.fail(f"'{key}' must be a positive length", key_tok)
        if s.get("min") is not None and s.get("max") is not None and s["min"] > s["max"]:
            raise self.fail("min is greater than max", tok)
        return EdgeClass(self.name(tok), s.get("min"), s.get("max"), s.get("fixed"),
                         s.get("tile"), s.get("rigid", False), s.get("border", False),
                         span=self.span(tok))

    def _label(self, node: Tree, faces: set[str], classes: set[str]) -> EdgeLabel:
        tok, *rest = node.children
        s = self.settings(rest, _LABEL_KEYS, "an edge label")
        for key in ("angle", "left", "right"):
            if key not in s:
                raise self.fail(f"edge label '{self.name(tok)}' has no {key}", tok,
                                "write: label x angle=0 left=inside right=exterior class=0")
        where = {self.name(r.children[0]): r.children[-1].children[0] for r in rest}
        angle = s["angle"]
        if not 0.0 <= angle < 180.0:
            raise self.fail(f"angle {angle:g} is outside [0, 180)", where["angle"],
                            "a label's angle is the direction of its half-edge x; ~x points "
                            "the opposite way, so use the angle modulo 180")
        for side in ("left", "right"):
            if s[side] not in faces:
                raise self.fail(f"unknown face label '{s[side]}'", where[side],
                                did_you_mean(s[side], faces) or "declare it in the 'faces' line")
        cls = s.get("class", DEFAULT_CLASS)
        if cls in self.broken and cls not in classes:
            raise _Stop()
        if cls not in classes:
            raise self.fail(f"unknown edge class '{cls}'", where["class"],
                            did_you_mean(cls, classes) or "declare it with a 'class' line")
        length = s.get("length")
        if length is not None and length <= 0:
            raise self.fail("the length must be positive", where["length"])
        name = self.name(tok)
        if not name:
            raise self.fail("an edge label needs a name", tok)
        return EdgeLabel(name, s["left"], s["right"], angle, cls, length)

    def _half(self, node: Tree, label_ids: dict[str, int]) -> tuple[int, Token]:
        bar = len(node.children) == 2
        tok = node.children[-1]
        lid = self.lookup("edge label", tok, label_ids, "declare it with a 'label' line")
        return bd.half(lid, bar), tok

    def _primitive(self, node: Tree, labels, label_ids: dict[str, int]) -> Primitive:
        tok, *rest = node.children
        halves = [self._half(n, label_ids) for n in rest if n.data == "half_edge"]
        s = self.settings([n for n in rest if n.data == "pair"], _PRIMITIVE_KEYS, "a primitive")
        ring = tuple(t for t, _ in halves)
        dirs = [labels[bd.label_of(t)].direction(bd.is_bar(t)) for t in ring]
        for k in range(1, len(ring)):
            if dirs[k] <= dirs[k - 1]:
                order = sorted(range(len(ring)), key=lambda i: dirs[i])
                names = [l.name for l in labels]
                fixed = bd.format_tokens([ring[i] for i in order], names, ascii=True)
                what = ("two half-edges point the same way" if dirs[k] == dirs[k - 1]
                        else "the ring is not in counter-clockwise order")
                shown = bd.format_tokens([ring[k]], [l.name for l in labels], ascii=True)
                raise self.fail(f"{what}: {shown} at {dirs[k]:g}° comes after "
                                f"{dirs[k - 1]:g}°", halves[k][1],
                                "list half-edges by direction from -180° up to 180°"
                                + (f": {fixed}" if dirs[k] != dirs[k - 1] else ""))
        count = s.get("count", 1)
        if count < 0:
            raise self.fail("count cannot be negative", tok)
        return Primitive(self.name(tok), ring, count)

    def _decoration(self, node: Tree, targets: dict[str, set[str]]) -> Decoration:
        kind_tok, target_node, *rest = node.children
        kind = self.name(kind_tok)
        if kind not in targets:
            raise self.fail(f"unknown decoration kind '{kind}'", kind_tok,
                            did_you_mean(kind, targets) or "face, edge or vertex")
        target_tok = target_node.children[0]
        target = "*" if target_tok.type == "STAR" else self.name(target_tok)
        if target != "*" and target not in targets[kind] and target in self.broken:
            raise _Stop()
        if target != "*" and target not in targets[kind]:
            what = {"face": "face label", "edge": "edge class", "vertex": "primitive"}[kind]
            raise self.fail(f"unknown {what} '{target}'", target_tok,
                            did_you_mean(target, targets[kind]) or "'*' decorates all of them")
        props = []
        seen = set()
        for s in rest:
            key = self.name(s.children[0])
            if key in seen:
                raise self.fail(f"'{key}' is given twice", s.children[0])
            seen.add(key)
            if len(s.children) < 2:
                raise self.fail(f"'{key}' needs a value: {key}=…", s.children[0])
            props.append((key, self.prop(s.children[1])))
        return Decoration(kind, target, tuple(props), span=self.span(kind_tok))

    # -- rules --

    def _rules(self, nodes: list[Tree], header: Header) -> list[Rule]:
        ctx = _Context(header, {p.name: i for i, p in enumerate(header.primitives)},
                       {l.name: i for i, l in enumerate(header.labels)})
        rules, seen = [], {}
        for node in nodes:
            rule = self._guard(self._rule, node, ctx)
            if rule is None:
                continue
            if rule.name in seen:
                self.fail(f"rule '{rule.name}' is defined twice", rule.span,
                          f"the first definition is on line {seen[rule.name]}")
            seen[rule.name] = rule.span.line
            rules.append(rule)
        return rules

    def _rule(self, node: Tree, ctx: "_Context") -> Rule:
        kind_tok, name_tok, *rest = node.children
        starter = str(kind_tok) == "starter"
        s = self.settings([n for n in rest if n.data == "setting"], _RULE_KEYS, "a rule")
        if s.get("weight", 1.0) < 0:
            raise self.fail("the weight cannot be negative", name_tok)
        sides: dict[str, tuple[Side, Tree]] = {}
        for side in (n for n in rest if n.data == "side"):
            which = side.children[0]
            if str(which) in sides:
                raise self.fail(f"the rule has two '{which}' sides", which)
            sides[str(which)] = (self._side(side, ctx), side)
        name = self.name(name_tok)
        where = self.span(name_tok)
        if "lhs" not in sides:
            raise self.fail(f"rule '{name}' has no left side", name_tok,
                            "add 'lhs { … }' with the rule's vertices, edges and boundary")
        lhs, lhs_node = sides["lhs"]
        if starter:
            if "rhs" in sides:
                raise self.fail("a starter rule has no right side", sides["rhs"][1].children[0],
                                "a starter turns its complete left side into nothing; "
                                "use 'rule' for a rule with two sides")
            if lhs.is_empty or lhs.open_slots():
                raise self.fail(f"the left side of starter '{name}' is not a complete graph",
                                lhs_node.children[0],
                                "every half-edge of a starter's left side must be glued, "
                                "and its boundary is '+'")
            rhs = EMPTY
        else:
            if "rhs" not in sides:
                raise self.fail(f"rule '{name}' has no right side", name_tok,
                                "add 'rhs { … }'; a rule whose right side is empty is a "
                                "'starter'")
            rhs, rhs_node = sides["rhs"]
            for side, side_node in ((lhs, lhs_node), (rhs, rhs_node)):
                if side.is_empty:
                    raise self.fail(f"the {side_node.children[0]} of rule '{name}' is empty",
                                    side_node.children[0],
                                    "only a starter has an empty side; write it as "
                                    "'starter NAME { lhs { … } }'")
            self._check_interface(name, lhs, rhs, rhs_node, ctx)
        return Rule(name, lhs, rhs, s.get("priority", 0), s.get("weight", 1.0), span=where)

    def _check_interface(self, name: str, lhs: Side, rhs: Side, rhs_node: Tree, ctx) -> None:
        left, right = lhs.tokens(ctx.rings), rhs.tokens(ctx.rings)
        if left == right:
            return
        names = [l.name for l in ctx.header.labels]
        k = next((i for i, (a, b) in enumerate(zip(left, right)) if a != b), min(len(left), len(right)))
        line = next(c for c in rhs_node.children[1:] if c.data == "boundary")
        at = line.children[min(k, len(line.children) - 1)]
        raise self.fail(
            f"the sides of rule '{name}' have different boundaries: "
            f"∂L = {unicode(left, names) or 'ε'} but "
            f"∂R = {unicode(right, names) or 'ε'} (they differ at item {k + 1})",
            self._slot(at).span if at.type == "SLOT" else at,
            "the i-th open half-edge of the left side is the same interface point as the i-th "
            "of the right side: list both boundaries in the same order, from the same start, "
            "with the same turns")

    def _side(self, node: Tree, ctx: "_Context") -> Side:
        which, *lines = node.children
        vertices: list[int] = []        # primitive of each vertex
        wires: list[int] = []           # unbarred token of each wire
        names: list[str] = []
        index: dict[str, int] = {}      # name → vertex v, or -1 - e for wire e (as in slots)
        edges: list[tuple[_Slot, _Slot]] = []
        boundary_nodes: list[Tree] = []
        for line in lines:
            if line.data == "boundary":
                boundary_nodes.append(line)
                continue
            for item in line.children:
                if item.data == "edge":
                    edges.append((self._slot(item.children[0]), self._slot(item.children[1])))
                    continue
                if item.children[0].type == "VERTEX":
                    vtok, ptok = self._split_vertex(item.children[0])
                    if item.data == "wire":
                        if ptok != "wire":
                            raise self.fail(f"expected 'wire' before the label, not {ptok}", ptok,
                                            "a wire is declared as 'name: wire label'")
                        ptok = item.children[1]
                else:
                    vtok, ptok = item.children
                vname = self.name(vtok)
                if vname in index:
                    raise self.fail(f"'{vname}' is declared twice in this side", vtok)
                if not vname:
                    raise self.fail("a vertex needs a name", vtok)
                if item.data == "vertex":
                    prim = self.lookup("primitive", ptok, ctx.prims,
                                       "declare it with a 'primitive' line")
                    index[vname] = len(vertices)
                    vertices.append(prim)
                    names.append(vname)
                else:
                    label = self.lookup("edge label", ptok, ctx.labels)
                    index[vname] = -1 - len(wires)
                    wires.append(bd.half(label, False))
        if not vertices and not wires and not edges and not boundary_nodes:
            return EMPTY
        if len(boundary_nodes) > 1:
            raise self.fail("a side has one boundary line", self._first_token(boundary_nodes[1]))
        if not boundary_nodes:
            raise self.fail(f"the {which} has no boundary line", which,
                            "list its open half-edges counter-clockwise with the turns between "
                            "them, e.g. 'boundary a.x + b.y -'; a complete graph has 'boundary +'")
        label_names = [l.name for l in ctx.header.labels]

        def ring_of(key: int) -> tuple[int, ...]:
            if key < 0:
                t = wires[-1 - key]
                return (t, bd.opposite(t))
            return ctx.header.primitives[vertices[key]].ring

        def show(key: int, i: int) -> str:
            vname = next(n for n, k in index.items() if k == key)
            return f"{vname}.{bd.format_tokens([ring_of(key)[i]], label_names, ascii=True)}"

        def describe(key: int) -> tuple[str, str]:
            what = "the wire" if key < 0 else ctx.header.primitives[vertices[key]].name
            return what, bd.format_tokens(ring_of(key), label_names, ascii=True)

        def resolve(slot: _Slot) -> tuple[int, int]:
            key = self.lookup("vertex", slot.vertex, index,
                              "declare it in this side as 'name: primitive'")
            ring = ring_of(key)
            if isinstance(slot.ref, int):
                if slot.ref >= len(ring):
                    what, shown = describe(key)
                    raise self.fail(f"{what} has no slot {slot.ref}: it has {len(ring)} "
                                    f"half-edges", slot.span,
                                    f"its half-edges are {shown}, slots 0 to {len(ring) - 1}")
                return key, slot.ref
            bar, ltok = slot.ref
            token = bd.half(self.lookup("edge label", ltok, ctx.labels), bar)
            if token not in ring:
                what, shown = describe(key)
                raise self.fail(f"{self.name(slot.vertex)} ({what}) has no half-edge "
                                f"{'~' if bar else ''}{self.name(ltok)}", slot.span,
                                f"its half-edges are {shown}")
            return key, ring.index(token)

        glued: dict[tuple[int, int], Span] = {}
        out_edges = []
        for a, b in edges:
            sa, sb = resolve(a), resolve(b)
            for slot, where in ((sa, a.span), (sb, b.span)):
                if slot[0] < 0:
                    raise self.fail("the ends of a wire are open, not glued", where,
                                    "list both ends of the wire on the boundary")
                if slot in glued:
                    raise self.fail("this half-edge is glued twice", where,
                                    f"it is already glued on line {glued[slot].line}")
                glued[slot] = where
            ta, tb = ring_of(sa[0])[sa[1]], ring_of(sb[0])[sb[1]]
            if sa == sb:
                raise self.fail("a half-edge cannot be glued to itself", a.span)
            if tb != bd.opposite(ta):
                want = bd.format_tokens([bd.opposite(ta)], label_names, ascii=True)
                raise self.fail(f"cannot glue {show(*sa)} to {show(*sb)}", b.span,
                                f"a half-edge glues only to its opposite: "
                                f"{show(*sa)} glues to a {want}")
            if sa[0] == sb[0]:
                raise self.fail("an edge cannot join a vertex to itself", b.span,
                                "edges are straight lines between two different vertices")
            out_edges.append(sa + sb if sa < sb else sb + sa)

        items: list = []
        seen: dict[tuple[int, int], Span] = {}
        bnode = boundary_nodes[0]
        for item in bnode.children:
            if item.type != "SLOT":
                items.append(bd.UP if item.type == "UP" else bd.DOWN)
                continue
            slot = self._slot(item)
            s = resolve(slot)
            if s in glued:
                raise self.fail("a glued half-edge cannot be on the boundary", slot.span,
                                f"it is glued on line {glued[s].line}")
            if s in seen:
                raise self.fail("this half-edge is on the boundary twice", slot.span)
            seen[s] = slot.span
            items.append(s)
        keys = list(range(len(vertices))) + [-1 - e for e in range(len(wires))]
        missing = [(k, i) for k in keys for i in range(len(ring_of(k)))
                   if (k, i) not in glued and (k, i) not in seen]
        if missing:
            shown = ", ".join(show(k, i) for k, i in missing[:6])
            raise self.fail(f"open half-edges missing from the boundary: {shown}"
                            + (" …" if len(missing) > 6 else ""), self._first_token(bnode),
                            "every half-edge that is not glued appears once on the boundary")
        turn = bd.winding(t for t in items if isinstance(t, int))
        if turn != 1:
            raise self.fail(f"the boundary turns {turn:+d} times (P − N = {turn}), not once",
                            self._first_token(bnode),
                            "a closed walk around a graph has one more '+' than '-' (P − N = 1)")
        default = tuple(f"v{k}" for k in range(len(names)))
        side = Side(tuple(vertices), tuple(out_edges), tuple(items),
                    () if tuple(names) == default else tuple(names), tuple(wires))
        self._check_walk(side, bnode, ctx, show)
        return side

    def _check_walk(self, side: Side, bnode: Tree, ctx: "_Context", show) -> None:
        """The boundary must be the walk around the graph that its edges and rings imply.

        Each connected component is checked on its own: walking the written boundary, the
        turns between two consecutive open slots of the component (other components spliced in
        between add up to none, paper §4.2) must equal those of the component's own face walk.
        """
        comp: dict[int, int] = {}
        for c, members in enumerate(side.components()):
            for v in members:
                comp[v] = c
        n_comp = len(side.components())

        def component(slot) -> int:
            return comp[slot[0]] if slot[0] >= 0 else n_comp + (-1 - slot[0])

        items = side.boundary
        where = {it: k for k, it in enumerate(items) if isinstance(it, tuple)}
        done: set[int] = set()
        for first in (it for it in items if isinstance(it, tuple)):
            c = component(first)
            if c in done:
                continue
            done.add(c)
            # The written walk of this component: its slots with all turns between them.
            written: list[list] = []
            k0 = where[first]
            for m in range(len(items)):
                it = items[(k0 + m) % len(items)]
                if isinstance(it, tuple):
                    if component(it) == c:
                        written.append([it, 0])
                else:
                    written[-1][1] += 1 if it == bd.UP else -1
            walk = face_walk(side, first, ctx.rings)
            if [tuple(w) for w in written] == walk:
                continue
            expect = " ".join(show(*slot) + (" " + _turn_text(n) if n else "") for slot, n in walk)
            on_face = {slot for slot, _ in walk}
            stray = [w[0] for w in written if w[0] not in on_face]
            if stray:
                message = (f"{show(*stray[0])} is not on the same face as {show(*first)}: "
                           f"the edges close a face around one of them")
            else:
                k = next(k for k, (w, g) in enumerate(zip(written, walk)) if tuple(w) != g)
                got, want = written[k], walk[k]
                if got[0] != want[0]:
                    message = (f"the boundary does not follow the graph: after "
                               f"{show(*written[k - 1][0])} the walk around the graph reaches "
                               f"{show(*want[0])}, not {show(*got[0])}")
                else:
                    message = (f"the boundary does not follow the graph: after {show(*got[0])} "
                               f"the walk turns {want[1]:+d} times, not {got[1]:+d}")
            bad = stray[0] if stray else written[k][0] if k < len(written) else first
            raise self.fail(message, self._slot(bnode.children[where[bad]]).span,
                            f"walking counter-clockwise around the graph from {show(*first)}, "
                            f"its open half-edges are: {expect}")

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


@dataclass
class _Context:
    header: Header
    prims: dict[str, int]
    labels: dict[str, int]

    @property
    def rings(self):
        return [p.ring for p in self.header.primitives]


_STATUS = {"complete": True, "limited": False, "unknown": None}
_KEYWORD = {"version": "ggr", "checksum": "checksum", "source": "source", "compiler": "compiler",
            "mode": "mode", "status": "status", "unit": "unit", "exterior": "exterior",
            "faces": "faces", "options": "options", "limits": "limits", "frame": "frame",
            "vertex_labels": "vertices", "edge_labels": "edges", "start_graph": "start"}
_OPTION_KEYS = {"angle_tolerance": "float", "snap_angle": "float", "merge_distance": "optfloat",
                "unit": "optfloat", "connected": "bool", "no_loops": "bool"}
_LIMIT_KEYS = {"generations": "int", "half_edges": "int", "graphs": "int", "seconds": "float"}
_CLASS_KEYS = {"min": "optfloat", "max": "optfloat", "fixed": "optfloat", "tile": "optfloat",
               "rigid": "bool", "border": "bool"}
_LABEL_KEYS = {"angle": "float", "left": "name", "right": "name", "class": "name",
               "length": "optfloat"}
_PRIMITIVE_KEYS = {"count": "int"}
_RULE_KEYS = {"priority": "int", "weight": "float"}
