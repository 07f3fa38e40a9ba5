"""The rules of a `.ggr` file: each side's vertices, wires, glued edges and boundary, checked
against its rotation system (`graph.face_walk`), and ∂L = ∂R for each rule."""

from __future__ import annotations

from dataclasses import dataclass, replace

from lark import Tree

from . import boundary as bd
from .diagnostics import Span
from .ggr_reader import Reader, _Slot
from .graph import EMPTY, Side, face_walk
from .rules import Header, Rule


def unicode(tokens, names) -> str:
    """The paper's notation, spaced out when label names are longer than a letter (x01 y01)."""
    if all(len(n) == 1 for n in names):
        return bd.format_tokens(tokens, names)
    return " ".join(bd.format_tokens([t], names) for t in tokens)


def _turn_text(n: int) -> str:
    return " ".join(["+"] * n if n > 0 else ["-"] * -n)



class SideReader(Reader):
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

    def _frame_start(self, node: Tree, header: Header) -> Header:
        """`frame-start { … }`: the complete graph a frame whose sides change label starts
        from. It holds each of the frame's corners once; generation solves the rest."""
        kw = self._first_token(node)
        if header.frame is None:
            raise self.fail("'frame-start' without a 'frame' line", kw,
                            "a start graph belongs to a frame: give its corners with "
                            "'frame P x y …' first")
        ctx = _Context(header, {p.name: i for i, p in enumerate(header.primitives)},
                       {l.name: i for i, l in enumerate(header.labels)})
        table, edges, boundary_nodes = self._declarations(
            [c for c in node.children if isinstance(c, Tree)], ctx)
        if boundary_nodes:
            raise self.fail("a frame's start graph has no boundary", self._first_token(boundary_nodes[0]),
                            "it is a complete graph: every half-edge is glued")
        if table.wires:
            raise self.fail("a frame's start graph has no wires", kw)
        glued, out_edges = self._glue(table, edges)
        side = Side(tuple(table.vertices), tuple(out_edges), ())
        rings = ctx.rings
        for v, p in enumerate(side.vertices):
            for i in range(len(rings[p])):
                if (v, i) not in glued:
                    raise self.fail(f"the frame's start graph is not complete: {table.show(v, i)} "
                                    "is not glued", kw, "glue every half-edge of every vertex")
        for c in header.frame.corners:
            if side.vertices.count(c.prim) != 1:
                raise self.fail(f"the frame's start graph holds its corner "
                                f"{header.primitives[c.prim].name} "
                                f"{side.vertices.count(c.prim)} times, not once", kw,
                                "the corners in the 'frame' line are vertices of the start graph")
        return replace(header, frame=replace(header.frame, start=side))

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
        table, edges, boundary_nodes = self._declarations(lines, ctx)
        if not table.vertices and not table.wires and not edges and not boundary_nodes:
            return EMPTY
        if len(boundary_nodes) > 1:
            raise self.fail("a side has one boundary line", self._first_token(boundary_nodes[1]))
        if not boundary_nodes:
            raise self.fail(f"the {which} has no boundary line", which,
                            "list its open half-edges counter-clockwise with the turns between "
                            "them, e.g. 'boundary a.x + b.y -'; a complete graph has 'boundary +'")
        glued, out_edges = self._glue(table, edges)
        bnode = boundary_nodes[0]
        items = self._boundary(table, bnode, glued)
        names = tuple(table.names)
        default = tuple(f"v{k}" for k in range(len(names)))
        side = Side(tuple(table.vertices), tuple(out_edges), tuple(items),
                    () if names == default else names, tuple(table.wires))
        self._check_walk(side, bnode, ctx, table.show)
        return side

    def _declarations(self, lines: list[Tree], ctx: "_Context"):
        """The side's vertices and wires (a `_SideTable`), its edges as slot pairs, and its
        boundary lines."""
        table = _SideTable(ctx)
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
                if vname in table.index:
                    raise self.fail(f"'{vname}' is declared twice in this side", vtok)
                if not vname:
                    raise self.fail("a vertex needs a name", vtok)
                if item.data == "vertex":
                    table.add_vertex(vname, self.lookup("primitive", ptok, ctx.prims,
                                                        "declare it with a 'primitive' line"))
                else:
                    table.add_wire(vname, self.lookup("edge label", ptok, ctx.labels))
        return table, edges, boundary_nodes

    def _resolve(self, table: "_SideTable", slot: _Slot) -> tuple[int, int]:
        """A slot as (vertex key, index in its ring)."""
        key = self.lookup("vertex", slot.vertex, table.index,
                          "declare it in this side as 'name: primitive'")
        ring = table.ring_of(key)
        if isinstance(slot.ref, int):
            if slot.ref >= len(ring):
                what, shown = table.describe(key)
                raise self.fail(f"{what} has no slot {slot.ref}: it has {len(ring)} "
                                f"half-edges", slot.span,
                                f"its half-edges are {shown}, slots 0 to {len(ring) - 1}")
            return key, slot.ref
        bar, ltok = slot.ref
        token = bd.half(self.lookup("edge label", ltok, table.ctx.labels), bar)
        if token not in ring:
            what, shown = table.describe(key)
            raise self.fail(f"{self.name(slot.vertex)} ({what}) has no half-edge "
                            f"{'~' if bar else ''}{self.name(ltok)}", slot.span,
                            f"its half-edges are {shown}")
        return key, ring.index(token)

    def _glue(self, table: "_SideTable", edges) -> tuple[dict, list]:
        """Check each edge (opposite half-edges, on two vertices, each slot once)."""
        glued: dict[tuple[int, int], Span] = {}
        out_edges = []
        show = table.show
        for a, b in edges:
            sa, sb = self._resolve(table, a), self._resolve(table, b)
            for slot, where in ((sa, a.span), (sb, b.span)):
                if slot[0] < 0:
                    raise self.fail("the ends of a wire are open, not glued", where,
                                    "list both ends of the wire on the boundary")
                if slot in glued:
                    raise self.fail("this half-edge is glued twice", where,
                                    f"it is already glued on line {glued[slot].line}")
                glued[slot] = where
            ta, tb = table.ring_of(sa[0])[sa[1]], table.ring_of(sb[0])[sb[1]]
            if sa == sb:
                raise self.fail("a half-edge cannot be glued to itself", a.span)
            if tb != bd.opposite(ta):
                want = bd.format_tokens([bd.opposite(ta)], table.label_names, ascii=True)
                raise self.fail(f"cannot glue {show(*sa)} to {show(*sb)}", b.span,
                                f"a half-edge glues only to its opposite: "
                                f"{show(*sa)} glues to a {want}")
            if sa[0] == sb[0]:
                raise self.fail("an edge cannot join a vertex to itself", b.span,
                                "edges are straight lines between two different vertices")
            out_edges.append(sa + sb if sa < sb else sb + sa)
        return glued, out_edges

    def _boundary(self, table: "_SideTable", bnode: Tree, glued: dict) -> list:
        """The boundary items: every open slot once, no glued one, P − N = 1."""
        items: list = []
        seen: dict[tuple[int, int], Span] = {}
        for item in bnode.children:
            if item.type != "SLOT":
                items.append(bd.UP if item.type == "UP" else bd.DOWN)
                continue
            slot = self._slot(item)
            s = self._resolve(table, slot)
            if s in glued:
                raise self.fail("a glued half-edge cannot be on the boundary", slot.span,
                                f"it is glued on line {glued[s].line}")
            if s in seen:
                raise self.fail("this half-edge is on the boundary twice", slot.span)
            seen[s] = slot.span
            items.append(s)
        keys = list(range(len(table.vertices))) + [-1 - e for e in range(len(table.wires))]
        missing = [(k, i) for k in keys for i in range(len(table.ring_of(k)))
                   if (k, i) not in glued and (k, i) not in seen]
        if missing:
            shown = ", ".join(table.show(k, i) for k, i in missing[:6])
            raise self.fail(f"open half-edges missing from the boundary: {shown}"
                            + (" …" if len(missing) > 6 else ""), self._first_token(bnode),
                            "every half-edge that is not glued appears once on the boundary")
        turn = bd.winding(t for t in items if isinstance(t, int))
        if turn != 1:
            raise self.fail(f"the boundary turns {turn:+d} times (P − N = {turn}), not once",
                            self._first_token(bnode),
                            "a closed walk around a graph has one more '+' than '-' (P − N = 1)")
        return items

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
            written = _written_walk(items, where[first], c, component)
            walk = face_walk(side, first, ctx.rings)
            if list(written) == walk:
                continue
            message, bad = _walk_error(written, walk, first, show)
            expect = " ".join(show(*slot) + (" " + _turn_text(n) if n else "") for slot, n in walk)
            raise self.fail(message, self._slot(bnode.children[where[bad]]).span,
                            f"walking counter-clockwise around the graph from {show(*first)}, "
                            f"its open half-edges are: {expect}")


def _written_walk(items, k0: int, c: int, component) -> bd.Gaps:
    """The written walk of component c from item k0, in gap form: its slots with all turns
    between them (other components' slots dropped)."""
    rotated = items[k0:] + items[:k0]
    return bd.gaps(it for it in rotated if not isinstance(it, tuple) or component(it) == c)


def _walk_error(written: bd.Gaps, walk, first, show) -> tuple[str, tuple]:
    """What is wrong with a written walk that differs from the graph's, and where."""
    on_face = {slot for slot, _ in walk}
    stray = [w[0] for w in written if w[0] not in on_face]
    if stray:
        return (f"{show(*stray[0])} is not on the same face as {show(*first)}: "
                f"the edges close a face around one of them"), stray[0]
    k = next(k for k, (w, g) in enumerate(zip(written, walk)) if tuple(w) != g)
    got, want = written[k], walk[k]
    if got[0] != want[0]:
        message = (f"the boundary does not follow the graph: after "
                   f"{show(*written[k - 1][0])} the walk around the graph reaches "
                   f"{show(*want[0])}, not {show(*got[0])}")
    else:
        message = (f"the boundary does not follow the graph: after {show(*got[0])} "
                   f"the walk turns {want[1]:+d} times, not {got[1]:+d}")
    return message, written[k][0] if k < len(written) else first

class _SideTable:
    """The vertices and wires declared in one side, and how to show their slots."""

    def __init__(self, ctx: "_Context"):
        self.ctx = ctx
        self.vertices: list[int] = []       # primitive of each vertex
        self.wires: list[int] = []          # unbarred token of each wire
        self.names: list[str] = []
        self.index: dict[str, int] = {}     # name → vertex v, or -1 - e for wire e (as in slots)
        self.label_names = [l.name for l in ctx.header.labels]

    def add_vertex(self, name: str, prim: int) -> None:
        self.index[name] = len(self.vertices)
        self.vertices.append(prim)
        self.names.append(name)

    def add_wire(self, name: str, label: int) -> None:
        self.index[name] = -1 - len(self.wires)
        self.wires.append(bd.half(label, False))

    def ring_of(self, key: int) -> tuple[int, ...]:
        if key < 0:
            t = self.wires[-1 - key]
            return (t, bd.opposite(t))
        return self.ctx.header.primitives[self.vertices[key]].ring

    def show(self, key: int, i: int) -> str:
        vname = next(n for n, k in self.index.items() if k == key)
        return f"{vname}.{bd.format_tokens([self.ring_of(key)[i]], self.label_names, ascii=True)}"

    def describe(self, key: int) -> tuple[str, str]:
        what = "the wire" if key < 0 else self.ctx.header.primitives[self.vertices[key]].name
        return what, bd.format_tokens(self.ring_of(key), self.label_names, ascii=True)


@dataclass
class _Context:
    header: Header
    prims: dict[str, int]
    labels: dict[str, int]

    @property
    def rings(self):
        return [p.ring for p in self.header.primitives]


_RULE_KEYS = {"priority": "int", "weight": "float"}
