"""Read the hand-written productions of a `.ggr` file: lark tree → `free_rules` model, checked.

The rule-file reader (ggr_parser) hands over the `attribute`, `production` and `start`
statements with its error helpers. Everything that can be known before running is checked
here: labels and names, kept and wildcard vertices, and every expression's types (at the
expression's own line and column); a daughter that would leave its match exactly as it found
it, so that it could apply to the same match forever, is an error too.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import networkx as nx
from lark import Token, Tree

from . import expr_ast as ast
from .diagnostics import Span, did_you_mean
from .expr_ast import Type
from .expr_eval import Scope, compile_expr
from .expr_functions import FUNCTIONS, EvalError
from .expr_parse import ExprError, parse_expr
from .free_rules import (DERIVED, KINDS, MATCH_CHOICES, SETTABLE_DERIVED, Assign, AttrDecl,
                         Condition, Daughter, FEdge, FFace, FSide, FVertex, Let, Production)
from .source import MAX_COORDINATE

PRODUCTION_KEYS = {"priority": "int", "weight": "float", "match": "name", "spatial": "bool"}
DAUGHTER_KEYS = {"weight": "float"}
# Elements in one side of a production (matching recurses once per element, and the load
# check for self-copies is a graph isomorphism), and in the start graph.
MAX_SIDE = 100
MAX_START = 100_000


@dataclass
class FreeContext:
    vertex_labels: set[str]
    edge_labels: set[str]
    face_labels: set[str]
    attributes: dict[str, dict[str, AttrDecl]] = field(default_factory=dict)

    def attr_types(self, kind: str) -> dict[str, Type]:
        return {**DERIVED[kind], **{k: a.type for k, a in self.attributes.get(kind, {}).items()}}


class _NoRandom:
    values: dict = {}
    rng = None

    def get(self, element, key):        # a default refers to no element (checked first)
        raise EvalError("no element here")


class FreeReader:
    def __init__(self, builder):
        self.b = builder        # ggr_parser._Builder: fail, name, settings, span

    # -- expressions --

    def expr(self, tok: Token, scope: Scope, want: Type | None = None,
             what: str = "this") -> tuple[Type, ast.Expr]:
        text = str(tok)
        try:
            e = parse_expr(text)
            t, _ = compile_expr(e, scope)
        except ExprError as exc:
            raise self.b.fail(exc.message, self._at(tok, exc.at, exc.length), exc.hint) from None
        if want is not None and t != want:
            raise self.b.fail(f"{what} must be {want}, not {t}", self._at(tok, 0, len(text)))
        return t, e

    def _at(self, tok: Token, offset: int, length: int) -> Span:
        text = str(tok)
        lead = len(text) - len(text.lstrip())
        offset = max(offset, lead)
        length = max(1, min(length, len(text.rstrip()) - offset))
        return Span(self.b.path, tok.line, tok.column + offset, length)

    def attribute(self, node: Tree, declared: dict[str, dict[str, AttrDecl]]) -> AttrDecl:
        kind_tok, name_tok, value_tok = node.children
        kind, name = self.b.name(kind_tok), self.b.name(name_tok)
        if kind not in KINDS:
            raise self.b.fail(f"unknown element kind '{kind}'", kind_tok,
                              did_you_mean(kind, KINDS) or "vertex, edge or face")
        if name in DERIVED[kind]:
            raise self.b.fail(f"'{name}' is built in for every {kind}", name_tok,
                              "built in: " + ", ".join(sorted(DERIVED[kind])))
        if name in declared.get(kind, {}):
            raise self.b.fail(f"the {kind} attribute '{name}' is declared twice", name_tok)
        t, e = self.expr(value_tok, Scope())
        if any(isinstance(n, ast.Call) and any(s.random for s in FUNCTIONS.get(n.fn, ()))
               for n in _nodes(e)):
            raise self.b.fail("a default value cannot be random", self._at(value_tok, 0, 99),
                              "draw random values in a production's 'set' lines")
        _, fn = compile_expr(e, Scope())
        try:
            value = fn(_NoRandom())
        except EvalError as exc:
            raise self.b.fail(str(exc), self._at(value_tok, 0, 99)) from None
        decl = AttrDecl(kind, name, t, e, value)
        declared.setdefault(kind, {})[name] = decl
        return decl

    # -- productions and the start graph --

    def production(self, node: Tree, ctx: FreeContext) -> Production:
        name_tok, *rest = node.children
        s = self.b.settings([n for n in rest if n.data == "setting"], PRODUCTION_KEYS,
                            "a production")
        name = self.b.name(name_tok)
        if s.get("weight", 1.0) < 0:
            raise self.b.fail("the weight cannot be negative", name_tok)
        match = s.get("match", "random")
        if match not in MATCH_CHOICES:
            raise self.b.fail(f"unknown match choice '{match}'", self.b._key(rest, "match"),
                              "random (any match) or oldest (breadth-first, by generation)")
        body = [n for n in rest if n.data != "setting"]
        sides = [n for n in body if n.data == "free_side"]
        if not sides or str(sides[0].children[0]) != "lhs":
            raise self.b.fail(f"production '{name}' must start with its 'lhs {{ … }}'", name_tok,
                              "then 'where' conditions, 'let' lines, and one or more "
                              "'rhs weight=W { … }' each followed by its 'set' lines")
        lhs = self.side(sides[0], ctx, None)
        if s.get("spatial") and sum(v.pattern is not None for v in lhs.vertices) < 2:
            raise self.b.fail("'spatial' compares pattern positions, and the lhs has fewer "
                              "than two", self.b._key(rest, "spatial"),
                              "give the lhs vertices pattern positions: 'a: pt (0, 0)'")
        scope = lhs_scope(lhs, ctx)
        conditions, lets, daughters = [], [], []
        for item in body[1:]:
            if item.data == "where":     # over the match alone: checked before any 'let'
                _, e = self.expr(item.children[0], lhs_scope(lhs, ctx), Type.BOOL,
                                 "a condition")
                conditions.append(Condition(e, self.b.span(item.children[0])))
            elif item.data == "let":
                if daughters:
                    daughters[-1][1].append(self.let(item, daughters[-1][3]))
                else:
                    lets.append(self.let(item, scope))
            elif item.data == "free_side":
                daughters.append(self._daughter_head(item, lhs, ctx, scope))
            elif not daughters:
                raise self.b.fail("a 'set' line follows the 'rhs' it sets",
                                  item.children[0], "write it after 'rhs { … }'")
            else:
                daughters[-1][2].append(self.assign(item, daughters[-1][0], lhs, ctx,
                                                    daughters[-1][3]))
        if not daughters:
            raise self.b.fail(f"production '{name}' has no right side", name_tok,
                              "add 'rhs { … }'; an empty 'rhs { }' deletes the match")
        out = tuple(self._daughter(d, lhs, name_tok, bool(conditions)) for d in daughters)
        return Production(name, lhs, out, tuple(conditions), tuple(lets),
                          s.get("priority", 0), s.get("weight", 1.0), match,
                          s.get("spatial", False), self.b.span(name_tok))

    def start(self, node: Tree, ctx: FreeContext) -> Production:
        items = [n for n in node.children if n.data == "free_items"]
        side = self._side_items(items, ctx, None, "start")
        scope = Scope()
        sets = [self.assign(n, side, FSide(), ctx, scope)
                for n in node.children if n.data == "start_set"]
        daughter = Daughter(side, 1.0, (), tuple(sets))
        self._positions(daughter, FSide(), self.b._first_token(node))
        return Production("start", FSide(), (daughter,))

    def let(self, node: Tree, scope: Scope) -> Let:
        name_tok, value_tok = node.children
        name = str(name_tok)
        if name in scope.variables or name in scope.elements:
            raise self.b.fail(f"'{name}' is already defined", name_tok)
        t, e = self.expr(value_tok, scope)
        scope.variables[name] = t
        return Let(name, e, t, self.b.span(name_tok))

    def _daughter_head(self, node: Tree, lhs: FSide, ctx: FreeContext, scope: Scope):
        if str(node.children[0]) != "rhs":
            raise self.b.fail("a production has one 'lhs', first", node.children[0])
        weight = self.b.settings([n for n in node.children[1:] if isinstance(n, Tree)
                                  and n.data == "setting"], DAUGHTER_KEYS, "a right side")
        if weight.get("weight", 1.0) < 0:
            raise self.b.fail("the weight cannot be negative", node.children[0])
        side = self.side(node, ctx, lhs)
        local = Scope(dict(scope.variables), dict(scope.elements))
        return (side, [], [], local, weight.get("weight", 1.0), node.children[0])

    def _daughter(self, head, lhs: FSide, name_tok: Token, conditional: bool) -> Daughter:
        side, lets, sets, _, weight, where = head
        daughter = Daughter(side, weight, tuple(lets), tuple(sets))
        self._positions(daughter, lhs, where)
        if _leaves_match(daughter, lhs):
            raise self.b.fail("this right side leaves its match exactly as it was", where,
                              "the production would apply to the same match forever; change "
                              "a label or an attribute, or delete something")
        if not conditional and lhs.vertices and _same_shape(side, lhs):
            raise self.b.fail("this right side makes a copy of the left side, so it recreates "
                              "its own match: the production would apply forever", where,
                              "add a 'where' condition that its 'set' lines make false, or "
                              "change what the right side makes")
        return daughter

    def _positions(self, d: Daughter, lhs: FSide, where: Token) -> None:
        placed = {a.element for a in d.sets if a.key == "pos"}
        both = {a.element for a in d.sets if a.key == "x"} & {a.element for a in d.sets
                                                               if a.key == "y"}
        anchors = [v for v in lhs.vertices if v.pattern is not None]
        for v in d.side.vertices:
            if v.kept or v.name in placed or v.name in both:
                continue
            if v.pattern is None:
                raise self.b.fail(f"the new vertex '{v.name}' has no position", where,
                                  f"write 'set {v.name}.pos = …', or give it a pattern position "
                                  f"'{v.name}: {v.label} (x, y)' to place it automatically")
            if lhs.vertices and not anchors:
                raise self.b.fail(f"'{v.name}' is placed by its pattern position, but the lhs "
                                  "has none", where, "give the lhs vertices pattern positions "
                                  "too, '(x, y)' after each")

    # -- assignments --

    def assign(self, node: Tree, side: FSide, lhs: FSide, ctx: FreeContext,
               scope: Scope) -> Assign:
        slot_tok, value_tok = node.children
        element, key = str(slot_tok).split(".", 1)
        kind = _kind_of(side, element)
        if kind is None:
            raise self.b.fail(f"'{element}' is not an element of this right side", slot_tok,
                              did_you_mean(element, _names(side)) or
                              "name a vertex, or an edge or face declared as 'e = …'")
        types = ctx.attr_types(kind)
        if key not in types:
            raise self.b.fail(f"a {kind} has no attribute '{key}'", slot_tok,
                              did_you_mean(key, types) or "declare it with an 'attribute' line")
        if key in DERIVED[kind] and key not in SETTABLE_DERIVED[kind]:
            raise self.b.fail(f"'{key}' is computed, it cannot be set", slot_tok,
                              "set x and y (or pos) and the rest follows")
        v = side.vertex(element) if kind == "vertex" else None
        if v is not None and v.label is None:
            raise self.b.fail(f"'{element}' is a wildcard: it is left as it is", slot_tok)
        _, e = self.expr(value_tok, scope, types[key], f"{element}.{key}")
        return Assign(element, key, e, self.b.span(slot_tok))

    # -- sides --

    def side(self, node: Tree, ctx: FreeContext, lhs: FSide | None) -> FSide:
        items = [n for n in node.children[1:] if isinstance(n, Tree) and n.data == "free_items"]
        return self._side_items(items, ctx, lhs, str(node.children[0]))

    def _side_items(self, lines: list[Tree], ctx: FreeContext, lhs: FSide | None,
                    which: str) -> FSide:
        vertices: dict[str, FVertex] = {}
        edges: list[FEdge] = []
        faces: list[FFace] = []
        names: set[str] = set()
        later = []
        for line in lines:
            for item in line.children:
                if item.data in ("fedge", "fface"):
                    later.append(item)
                else:
                    v = self._vertex(item, ctx, lhs, which)
                    if v.name in vertices:
                        raise self.b.fail(f"'{v.name}' is declared twice in this side",
                                          item.children[0])
                    vertices[v.name] = v
        if lhs is not None:     # wildcards stay, unnamed in the daughter
            for v in lhs.vertices:
                if v.label is None and v.name not in vertices:
                    vertices[v.name] = FVertex(v.name, None, v.pattern, True)
        for item in later:
            element = (self._edge if item.data == "fedge" else self._face)(item, ctx, vertices,
                                                                          lhs, which)
            if element.name is not None:
                if element.name in names or element.name in vertices:
                    raise self.b.fail(f"'{element.name}' is declared twice in this side",
                                      item.children[0])
                names.add(element.name)
            (edges if item.data == "fedge" else faces).append(element)
        limit = MAX_START if which == "start" else MAX_SIDE
        if len(vertices) + len(edges) + len(faces) > limit:
            raise self.b.fail(f"this {which} has {len(vertices) + len(edges) + len(faces)} "
                              f"elements, at most {limit}", self.b._first_token(lines[0]),
                              "split the production into smaller ones")
        return FSide(tuple(vertices.values()), tuple(edges), tuple(faces))

    def _vertex(self, item: Tree, ctx: FreeContext, lhs: FSide | None, which: str) -> FVertex:
        at = self._pattern(item.children[-1]) if isinstance(item.children[-1], Tree) else None
        if item.data == "fvertex":
            vtok, ltok = self.b._split_vertex(item.children[0])
            name, label = self.b.name(vtok), self.b.name(ltok)
            if label not in ctx.vertex_labels:
                raise self.b.fail(f"unknown vertex label '{label}'", ltok,
                                  did_you_mean(label, ctx.vertex_labels) or
                                  "declare it in the 'vertices' line")
            kept = lhs is not None and lhs.vertex(name) is not None
            if kept and lhs.vertex(name).label is None:
                raise self.b.fail(f"'{name}' is a wildcard: it is left as it is", vtok)
            return FVertex(name, label, at, kept)
        tok = item.children[0]
        name = str(tok)
        if item.data == "wildcard":
            if lhs is not None or which == "start":
                raise self.b.fail("wildcards belong to the left side", tok,
                                  "a wildcard matches any vertex and leaves it unchanged")
            return FVertex(name, None, at)
        if lhs is None or lhs.vertex(name) is None:
            raise self.b.fail(f"'{name}' is not a vertex of the left side", tok,
                              "a bare name keeps a vertex of the lhs; declare a new one as "
                              f"'{name}: LABEL'")
        old = lhs.vertex(name)
        return FVertex(name, old.label, at if at is not None else old.pattern, True)

    def _pattern(self, node: Tree) -> tuple[float, float]:
        x, y = (self.b.number(t) for t in node.children)
        if max(abs(x), abs(y)) > MAX_COORDINATE:
            raise self.b.fail("a pattern position beyond ±1e12", node.children[0])
        return (x, y)

    def _label(self, node: Tree, known: set[str], what: str, which: str) -> str | None:
        tok = node.children[0]
        if tok.type == "STAR":
            if which != "lhs":
                raise self.b.fail(f"'*' (any {what} label) belongs to the left side", tok)
            return None
        label = self.b.name(tok)
        if label not in known:
            raise self.b.fail(f"unknown {what} label '{label}'", tok,
                              did_you_mean(label, known) or
                              f"declare it in the '{'faces' if what == 'face' else what + 's'}' line")
        return label

    def _edge(self, item: Tree, ctx: FreeContext, vertices, lhs, which) -> FEdge:
        *name, utok, arrow, vtok, label_node = item.children
        for tok in (utok, vtok):
            if str(tok) not in vertices:
                raise self.b.fail(f"'{tok}' is not a vertex of this side", tok,
                                  did_you_mean(str(tok), vertices))
        if str(utok) == str(vtok):
            raise self.b.fail("an edge joins two different vertices", vtok)
        label = self._label(label_node, ctx.edge_labels, "edge", which)
        return FEdge(str(name[0]) if name else None, str(utok), str(vtok), label,
                     str(arrow) == "->")

    def _face(self, item: Tree, ctx: FreeContext, vertices, lhs, which) -> FFace:
        name = [c for c in item.children if isinstance(c, Token)][:1] \
            if isinstance(item.children[0], Token) else []
        label_node = next(c for c in item.children if isinstance(c, Tree))
        cycle = tuple(str(t) for t in item.children[item.children.index(label_node) + 1:])
        for tok in item.children[item.children.index(label_node) + 1:]:
            if str(tok) not in vertices:
                raise self.b.fail(f"'{tok}' is not a vertex of this side", tok)
        if len(cycle) < 3 or len(set(cycle)) != len(cycle):
            raise self.b.fail("a face goes round three or more different vertices",
                              label_node.children[0])
        label = self._label(label_node, ctx.face_labels, "face", which)
        return FFace(str(name[0]) if name else None, label, cycle)


def context_of(header) -> FreeContext:
    """The labels and attributes a header declares, as productions see them."""
    attrs: dict[str, dict[str, AttrDecl]] = {}
    for a in header.attributes:
        attrs.setdefault(a.kind, {})[a.name] = a
    return FreeContext(set(header.vertex_labels), set(header.edge_labels),
                       set(header.face_labels) | {header.exterior}, attrs)


def lhs_scope(lhs: FSide, ctx: FreeContext) -> Scope:
    """What a production's expressions may name: the mother graph's elements."""
    elements = {v.name: ctx.attr_types("vertex") for v in lhs.vertices}
    elements.update({e.name: ctx.attr_types("edge") for e in lhs.edges if e.name})
    elements.update({f.name: ctx.attr_types("face") for f in lhs.faces if f.name})
    return Scope({}, elements)


def _nodes(e: ast.Expr):
    stack = [e]
    while stack:
        n = stack.pop()
        yield n
        stack.extend(ast.children(n))


def _names(side: FSide) -> list[str]:
    return ([v.name for v in side.vertices] + [e.name for e in side.edges if e.name]
            + [f.name for f in side.faces if f.name])


def _kind_of(side: FSide, name: str) -> str | None:
    if side.vertex(name) is not None:
        return "vertex"
    if any(e.name == name for e in side.edges):
        return "edge"
    if any(f.name == name for f in side.faces):
        return "face"
    return None


def edge_key(e: FEdge) -> tuple:
    return (e.u, e.v) if e.directed else tuple(sorted((e.u, e.v)))


def face_key(f: FFace) -> tuple:
    k = f.cycle.index(min(f.cycle))
    return f.cycle[k:] + f.cycle[:k]


def _shape_graph(side: FSide) -> nx.MultiDiGraph:
    """A side as a labelled graph: vertices, and a node for each edge and face tied to its
    ends (tail/head, or end twice when undirected) and its corners in cycle order."""
    g = nx.MultiDiGraph()
    for v in side.vertices:
        g.add_node(("v", v.name), label=("vertex", v.label))
    for k, e in enumerate(side.edges):
        g.add_node(("e", k), label=("edge", e.label, e.directed))
        g.add_edge(("e", k), ("v", e.u), role="tail" if e.directed else "end")
        g.add_edge(("e", k), ("v", e.v), role="head" if e.directed else "end")
    for k, f in enumerate(side.faces):
        g.add_node(("f", k), label=("face", f.label))
        for a, b in zip(f.cycle, f.cycle[1:] + f.cycle[:1]):
            g.add_edge(("f", k), ("v", a), role="corner")
            g.add_edge(("v", a), ("v", b), role=("next", f.label))
    return g


def _same_shape(a: FSide, b: FSide) -> bool:
    """Whether two sides are the same labelled graph (a wildcard is its own label)."""
    if (len(a.vertices), len(a.edges), len(a.faces)) != (len(b.vertices), len(b.edges),
                                                          len(b.faces)):
        return False
    same = lambda x, y: x["label"] == y["label"]          # noqa: E731
    roles = lambda x, y: sorted(map(repr, (d["role"] for d in x.values()))) == \
        sorted(map(repr, (d["role"] for d in y.values())))  # noqa: E731
    return nx.is_isomorphic(_shape_graph(a), _shape_graph(b), node_match=same, edge_match=roles)


def _leaves_match(d: Daughter, lhs: FSide) -> bool:
    """True when applying `d` changes nothing: every lhs element is kept with its label, nothing
    is added, and nothing is set."""
    if d.sets or not lhs.vertices:
        return False
    same_v = {(v.name, v.label) for v in lhs.vertices} == {(v.name, v.label)
                                                         for v in d.side.vertices}
    same_e = sorted((edge_key(e), e.directed, e.label) for e in lhs.edges) == \
        sorted((edge_key(e), e.directed, e.label) for e in d.side.edges)
    same_f = sorted((face_key(f), f.label) for f in lhs.faces) == \
        sorted((face_key(f), f.label) for f in d.side.faces)
    return same_v and same_e and same_f and all(v.kept for v in d.side.vertices)

