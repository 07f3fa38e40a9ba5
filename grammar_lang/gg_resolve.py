"""From `.gg` statements (one file and its imports) to a checked `ExampleSource`.

Two passes over the statements, with imports expanded in place by `gg_imports`:
1. definitions: face labels, colours, classes, points, options, limits, SVG shapes;
2. uses: geometry, primitives and decorations, checked against the definitions.
So a name may be used before the line that defines it. A name defined twice in one file is an
error; a definition in an importing file overrides the imported one.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from pathlib import Path

from . import gg_ast as A
from . import gg_checks as C
from . import gg_schema as S
from .diagnostics import Span, did_you_mean, error
from .gg_imports import ParseSyntax, Unit, expand
from .source import (COLOUR_PROPERTY, DEFAULT_CLASS, EXTERIOR, Decoration, EdgeClass,
                     ExampleSource, ExplicitEdge, HalfEdgeSpec, Limits, Options, PrimitiveSpec, Region, Stroke)

BORDER_CLASS = "border"


@dataclass
class _Defs:
    """Definitions, each remembering (unit, span) of the statement that made it."""

    origin: dict = field(default_factory=dict)   # (table, name) → (Unit, Span)
    name: str | None = None
    exterior: str = EXTERIOR
    faces: dict[str, Span | None] = field(default_factory=dict)
    palette: dict[str, str] = field(default_factory=dict)
    classes: dict[str, A.ClassDef] = field(default_factory=dict)
    points: dict[str, tuple[float, float]] = field(default_factory=dict)
    settings: dict[str, dict[str, object]] = field(
        default_factory=lambda: {"options": {}, "limits": {}})
    svg: dict[int, ExampleSource] = field(default_factory=dict)   # id(ShapeFrom) → source
    renames: dict[str, tuple[str, A.Rename, "Unit"]] = field(default_factory=dict)


def resolve(text: str, path: Path, parse: ParseSyntax) -> ExampleSource:
    return _Resolver(parse).run(text, path)


class _Resolver:
    def __init__(self, parse: ParseSyntax):
        self.parse = parse
        self.flat: list[tuple[object, Unit]] = []
        self.defs = _Defs()
        self.prim_spans: dict[str, Span] = {}

    def run(self, text: str, path: Path) -> ExampleSource:
        root, self.flat = expand(text, path, self.parse)
        for stmt, unit in self.flat:
            self._define(stmt, unit)
        self._adopt_drawings()
        return self._build(root)

    # ---- pass 1: definitions ------------------------------------------------------------------

    def _claim(self, table: str, name: str, span: Span, unit: Unit, what: str) -> bool:
        """Whether this definition takes effect; a repeat in the same file is an error."""
        old = self.defs.origin.get((table, name))
        if old is not None:
            old_unit, old_span = old
            if old_unit.path == unit.path:
                raise error(f"{what} '{name}' is defined twice", span,
                            f"the first definition is at {old_span}; remove one",
                            source=unit.text)
            if old_unit.depth < unit.depth:
                return False
        self.defs.origin[(table, name)] = (unit, span)
        return True

    def _define(self, stmt, unit: Unit) -> None:
        d = self.defs
        if isinstance(stmt, A.ExampleName):
            if not stmt.name.strip():
                raise error("the example name is empty", stmt.span,
                            'give it a name, e.g. example "Castle", or leave the line out to '
                            "use the file name", source=unit.text)
            if self._claim("example", "", stmt.span, unit, "the example name"):
                d.name = stmt.name
        elif isinstance(stmt, A.Exterior):
            label = _label_text(stmt.label, unit)
            if self._claim("exterior", "", stmt.span, unit, "the exterior"):
                d.exterior = label
        elif isinstance(stmt, A.Face):
            label = _label_text(stmt.label, unit)
            if self._claim("face", label, stmt.span, unit, "face label"):
                d.faces[label] = stmt.label.span
        elif isinstance(stmt, A.ColourDef):
            value = S.colour(stmt.colour, d.palette, unit.text)
            if self._claim("colour", stmt.name, stmt.span, unit, "colour"):
                d.palette[stmt.name] = value
        elif isinstance(stmt, A.ClassDef):
            name = _label_text(stmt.name, unit)
            if self._claim("class", name, stmt.span, unit, "class"):
                d.classes[name] = stmt
        elif isinstance(stmt, A.Settings):
            schema = S.OPTIONS if stmt.block == "options" else S.LIMITS
            values = S.check_block(stmt.props, schema, stmt.block, d.palette, unit.base, unit.text)
            for key, value in values.items():
                prop = next(p for p in stmt.props if p.key == key)
                if self._claim(stmt.block, key, prop.span, unit, f"{stmt.block} setting"):
                    d.settings[stmt.block][key] = value
        elif isinstance(stmt, A.PointDef):
            xy = self._point(stmt.at, unit)
            if self._claim("point", stmt.name, stmt.span, unit, "point"):
                d.points[stmt.name] = xy
        elif isinstance(stmt, A.ShapeFrom):
            d.svg[id(stmt)] = self._load_svg(stmt, unit)
        elif isinstance(stmt, A.Rename):
            old, new = _label_text(stmt.old, unit), _label_text(stmt.new, unit)
            if self._claim("rename", old, stmt.span, unit, "the renaming of"):
                d.renames[old] = (new, stmt, unit)

    def _load_svg(self, stmt: A.ShapeFrom, unit: Unit) -> ExampleSource:
        path = unit.base / stmt.path
        if path.suffix.lower() != ".svg":
            raise error(f"'{stmt.path}' is not an SVG file", stmt.span,
                        "`shape from` takes a .svg drawing", source=unit.text)
        if not path.is_file():
            raise error(f"SVG file not found: {stmt.path}", stmt.span,
                        f"paths are relative to the .gg file's folder ({unit.base})",
                        source=unit.text)
        from .svg_import import import_svg
        return import_svg(path)

    def _adopt_drawings(self) -> None:
        """Apply `rename` to the drawings, then make their face labels known."""
        d = self.defs
        names = {n for svg in d.svg.values() for n in (*svg.face_labels, *svg.classes)}
        for old, (new, stmt, unit) in d.renames.items():
            if old not in names:
                hint = did_you_mean(old, names) or (
                    "the drawings have: " + ", ".join(sorted(names)) if names else
                    "rename applies to drawings taken with `shape from \"drawing.svg\"`")
                raise error(f"no drawing has a face label or class '{old}'", stmt.old.span,
                            hint, source=unit.text)
        mapping = {old: new for old, (new, _, _) in d.renames.items()}
        for key, svg in d.svg.items():
            if mapping:
                svg = d.svg[key] = _renamed(svg, mapping)
            for label in svg.face_labels:
                if label != d.exterior:
                    d.faces.setdefault(label, None)

    # ---- pass 2: uses -------------------------------------------------------------------------

    def _build(self, root: Unit) -> ExampleSource:
        d = self.defs
        classes = {name: self._edge_class(c, self._unit_of("class", name))
                   for name, c in d.classes.items()}
        for svg in d.svg.values():      # a class the .gg defines wins over the drawing's
            for name, cls in svg.classes.items():
                classes.setdefault(name, cls)
        frame = next((s for s, _ in self.flat
                      if isinstance(s, A.Polyline) and s.border and s.cls is None), None)
        if frame is not None and BORDER_CLASS not in classes:
            classes[BORDER_CLASS] = EdgeClass(BORDER_CLASS, border=True, span=frame.span)
        self.class_names = set(classes) | {DEFAULT_CLASS}
        paint, prims, decos, drawn = [], [], [], []
        for stmt, unit in self.flat:
            if isinstance(stmt, A.Face) and (stmt.colour is not None or stmt.props):
                decos.append((unit, self._face_decoration(stmt, unit)))
            elif isinstance(stmt, A.Polygon):
                paint.extend(self._polygon(stmt, unit))
            elif isinstance(stmt, A.Polyline):
                paint.append(self._polyline(stmt, unit, classes))
            elif isinstance(stmt, A.Edge):
                paint.extend(self._edges(stmt, unit))
            elif isinstance(stmt, A.PrimitiveDef):
                prims.append((self._primitive(stmt, unit), unit))
            elif isinstance(stmt, A.ShapeFrom):
                svg = d.svg[id(stmt)]
                paint.extend(svg.paint)
                drawn.extend((unit, deco) for deco in svg.decorations)
            elif isinstance(stmt, A.Decorate):
                decos.append((unit, self._decoration(stmt, unit)))
        if paint and prims:
            _, unit = prims[0]
            raise error("an example gives either a shape or its primitives, not both",
                        prims[0][0].span,
                        "remove the primitive blocks, or the polygons/lines/edges/shapes",
                        source=unit.text)
        if not paint and not prims:
            raise error("the example has no shape", Span(root.path, 1, 1),
                        "draw it with polygon, polyline, loop or edge, take it from an SVG "
                        "with `shape from \"drawing.svg\"`, or list its primitives",
                        source=root.text)
        C.partners([(p, unit.text) for p, unit in prims])
        return ExampleSource(
            path=root.path, name=d.name or Path(root.path).stem, exterior=d.exterior,
            face_labels={k: v for k, v in d.faces.items() if k != d.exterior},
            paint=paint, primitives=[p for p, _ in prims], classes=classes,
            options=self._options(), text=root.text,
            # Later decorations override earlier ones, so an importing file's come after its
            # imports' wherever its `import` lines are (a stable sort keeps file order).
            decorations=[deco for unit, deco in sorted(_undecorated(drawn, decos) + decos,
                                                       key=lambda t: -t[0].depth)])

    def _unit_of(self, table: str, name: str) -> Unit:
        return self.defs.origin[(table, name)][0]

    def _options(self) -> Options:
        o, li = self.defs.settings["options"], self.defs.settings["limits"]
        base, lim = Options(), Limits()
        limits = Limits(generations=li.get("generations", lim.generations),
                        half_edges=li.get("half-edges", lim.half_edges),
                        graphs=li.get("graphs", lim.graphs),
                        seconds=float(li["time"]) if "time" in li else lim.seconds)
        return Options(angle_tolerance=float(o.get("angle-tolerance", base.angle_tolerance)),
                       snap_angle=float(o.get("snap-angle", base.snap_angle)),
                       merge_distance=o.get("merge-distance", base.merge_distance),
                       unit=o.get("unit", base.unit),
                       connected=o.get("connected", base.connected),
                       no_loops=o.get("no-loops", base.no_loops),
                       limits=limits)

    # ---- names --------------------------------------------------------------------------------

    def _label(self, word: A.Word, unit: Unit) -> str:
        label = _label_text(word, unit)
        if label == self.defs.exterior or label in self.defs.faces:
            return label
        known = [self.defs.exterior, *self.defs.faces]
        raise error(f"unknown face label '{label}'", word.span,
                    did_you_mean(label, known) or
                    f"declare it first with `face {word.text}` (known: {', '.join(known)})",
                    source=unit.text)

    def _cls(self, word: A.Word | None, unit: Unit) -> str:
        if word is None:
            return DEFAULT_CLASS
        name = _label_text(word, unit)
        if name in self.class_names:
            return name
        raise error(f"unknown edge class '{name}'", word.span,
                    did_you_mean(name, self.class_names) or
                    f"define it with `class {word.text} {{ … }}`; the default class is "
                    f"'{DEFAULT_CLASS}'", source=unit.text)

    def _point(self, pt: A.Pt, unit: Unit) -> tuple[float, float]:
        if isinstance(pt, A.Ref):
            if pt.name in self.defs.points:
                return self.defs.points[pt.name]
            raise error(f"unknown point '{pt.name}'", pt.span,
                        did_you_mean(pt.name, self.defs.points) or
                        f"define it with `point {pt.name} (x, y)`", source=unit.text)
        for n in (pt.x, pt.y):
            if n.unit not in ("", "px"):
                raise error(f"a coordinate cannot have the unit '{n.unit}'", n.span,
                            "coordinates are plain numbers in drawing units (px)",
                            source=unit.text)
        return (pt.x.value, pt.y.value)

    # ---- geometry -----------------------------------------------------------------------------

    def _ring(self, ring: A.Ring, unit: Unit, closed: bool, what: str) -> tuple:
        pts = [self._point(p, unit) for p in ring.points]
        if ring.rect:
            (x0, y0), (x1, y1) = pts
            if x0 == x1 or y0 == y1:
                raise error("a rect needs two opposite corners with different x and y",
                            ring.span, "write rect (x0, y0) (x1, y1)", source=unit.text)
            lo_x, hi_x, lo_y, hi_y = min(x0, x1), max(x0, x1), min(y0, y1), max(y0, y1)
            return ((lo_x, lo_y), (hi_x, lo_y), (hi_x, hi_y), (lo_x, hi_y))
        for i in range(1, len(pts)):
            if pts[i] == pts[i - 1]:
                raise error(f"{what} repeats the point ({_fmt(pts[i])}) here; that would be a "
                            "zero-length edge", ring.points[i].span, "remove the repeated point",
                            source=unit.text)
        if closed and len(pts) > 1 and pts[0] == pts[-1]:
            pts.pop()       # a ring closes itself; an explicit closing point is harmless
        need = 3 if closed else 2
        if len(set(pts)) < need:
            raise error(f"{what} needs at least {need} different points, got {len(set(pts))}",
                        ring.span, "a closed shape needs 3 corners, a line 2 ends",
                        source=unit.text)
        return tuple(pts)

    def _polygon(self, stmt: A.Polygon, unit: Unit) -> list:
        label = self._label(stmt.label, unit)
        rings = (self._ring(stmt.outer, unit, True, "a polygon"),
                 *(self._ring(h, unit, True, "a hole") for h in stmt.holes))
        out: list = [Region(rings, label, evenodd=bool(stmt.holes), span=stmt.span)]
        if stmt.cls is not None:
            cls = self._cls(stmt.cls, unit)
            out.extend(Stroke(r, True, cls, span=stmt.span) for r in rings)
        return out

    def _polyline(self, stmt: A.Polyline, unit: Unit, classes: dict) -> Stroke:
        what = "a border" if stmt.border else ("a loop" if stmt.closed else "a polyline")
        pts = self._ring(stmt.ring, unit, stmt.closed, what)
        if stmt.border:
            cls = BORDER_CLASS if stmt.cls is None else self._cls(stmt.cls, unit)
            if cls not in classes or not classes[cls].border:
                where = stmt.cls.span if stmt.cls is not None else stmt.span
                raise error(f"class '{cls}' is not a border class", where,
                            f"add `border` to its definition: class {cls} {{ border }}",
                            source=unit.text)
        else:
            cls = self._cls(stmt.cls, unit)
        return Stroke(pts, stmt.closed, cls, span=stmt.span)

    def _edges(self, stmt: A.Edge, unit: Unit) -> list:
        sides = {"left": None, "right": None, "class": None}
        for s in stmt.sides:
            if sides[s.kind] is not None:
                raise error(f"'{s.kind}' is given twice", s.span, "remove one of them",
                            source=unit.text)
            sides[s.kind] = s.word
        left = self._label(sides["left"], unit) if sides["left"] else self.defs.exterior
        right = self._label(sides["right"], unit) if sides["right"] else self.defs.exterior
        cls = self._cls(sides["class"], unit)
        pts = [self._point(p, unit) for p in stmt.points]
        out = []
        for i in range(1, len(pts)):
            if pts[i] == pts[i - 1]:
                raise error("zero-length edge: both ends are the same point",
                            stmt.points[i].span, "an edge must join two different points",
                            source=unit.text)
            out.append(ExplicitEdge(pts[i - 1], pts[i], left, right, cls, span=stmt.span))
        return out

    # ---- classes, primitives, decorations -----------------------------------------------------

    def _edge_class(self, c: A.ClassDef, unit: Unit) -> EdgeClass:
        values = S.check_block(c.props, S.CLASS, "class", self.defs.palette, unit.base,
                               unit.text)
        return C.edge_class(_label_text(c.name, unit), values, {p.key: p.span for p in c.props},
                            c.span, unit.text)

    def _primitive(self, stmt: A.PrimitiveDef, unit: Unit) -> PrimitiveSpec:
        if not stmt.half_edges:
            raise error("a primitive needs at least one half-edge", stmt.span,
                        "list its half-edges by direction, e.g. primitive { 0  180 }",
                        source=unit.text)
        halves = []
        for h in stmt.half_edges:
            if h.angle.unit not in ("", "deg"):
                raise error(f"a direction cannot have the unit '{h.angle.unit}'", h.angle.span,
                            "directions are angles in degrees, e.g. 90 or 90deg",
                            source=unit.text)
            sides = {"left": None, "right": None, "class": None}
            for s in h.sides:
                if sides[s.kind] is not None:
                    raise error(f"'{s.kind}' is given twice", s.span, "remove one of them",
                                source=unit.text)
                sides[s.kind] = s.word
            angle = (h.angle.value + 180.0) % 360.0 - 180.0
            left = self._label(sides["left"], unit) if sides["left"] else self.defs.exterior
            right = self._label(sides["right"], unit) if sides["right"] else self.defs.exterior
            halves.append((HalfEdgeSpec(angle, left, right, self._cls(sides["class"], unit)), h))
        if stmt.name is not None:
            first = self.prim_spans.setdefault(stmt.name, stmt.span)
            if first is not stmt.span:
                raise error(f"primitive '{stmt.name}' is defined twice", stmt.span,
                            f"the first definition is at {first}; rename one",
                            source=unit.text)
        halves.sort(key=lambda t: t[0].angle)
        C.vertex_ring([(h, node.span) for h, node in halves], unit.text)
        return PrimitiveSpec(tuple(h for h, _ in halves), stmt.name, span=stmt.span)

    def _face_decoration(self, stmt: A.Face, unit: Unit) -> Decoration:
        props = dict(S.check_block(stmt.props, S.DECORATIONS["face"], "face", self.defs.palette,
                                   unit.base, unit.text))
        if stmt.colour is not None:
            if "fill" in props:
                raise error("the fill is given twice", stmt.colour.span,
                            "give the colour after the label or as fill: …, not both",
                            source=unit.text)
            props = {"fill": S.colour(stmt.colour, self.defs.palette, unit.text), **props}
        return Decoration("face", _label_text(stmt.label, unit), tuple(props.items()),
                          span=stmt.span)

    def _decoration(self, stmt: A.Decorate, unit: Unit) -> Decoration:
        kind = stmt.kind.text
        if kind not in S.DECORATIONS:
            raise error(f"cannot decorate '{kind}'", stmt.kind.span,
                        did_you_mean(kind, S.DECORATIONS) or "decorate face, edge or vertex",
                        source=unit.text)
        target = stmt.target
        if target.kind == "star":
            name = "*"
        elif kind == "face":
            name = self._label(target, unit)
        elif kind == "edge":
            name = self._cls(target, unit)
        else:
            name = target.text
            defs = [s for s, _ in self.flat if isinstance(s, A.PrimitiveDef)]
            named = [s.name for s in defs if s.name]
            if defs and name not in named:
                raise error(f"unknown primitive '{name}'", target.span,
                            did_you_mean(name, named) or
                            ("known primitives: " + ", ".join(named) if named else
                             "name the primitive: primitive NAME { … }"),
                            source=unit.text)
        props = S.check_block(stmt.props, S.DECORATIONS[kind], f"{kind} decoration",
                              self.defs.palette, unit.base, unit.text)
        return Decoration(kind, name, tuple(props.items()), span=stmt.span)


def _undecorated(drawn: list, decos: list) -> list:
    """The colours a drawing was painted in (`svg_import`), less those the user sets: a
    decoration that colours a label or class, or all of them (`*`), beats the drawing's."""
    set_by_user = {(d.kind, d.target) for _, d in decos
                   if COLOUR_PROPERTY.get(d.kind) in dict(d.props)}
    return [(unit, d) for unit, d in drawn
            if (d.kind, d.target) not in set_by_user and (d.kind, "*") not in set_by_user]


def _renamed(svg: ExampleSource, mapping: dict[str, str]) -> ExampleSource:
    """The drawing with its face labels and classes renamed (names not in `mapping` stay)."""
    def f(name: str) -> str:
        return mapping.get(name, name)

    paint = []
    for p in svg.paint:
        if isinstance(p, Region):
            paint.append(replace(p, label=f(p.label)))
        elif isinstance(p, Stroke):
            paint.append(replace(p, cls=f(p.cls)))
        else:
            paint.append(replace(p, left=f(p.left), right=f(p.right), cls=f(p.cls)))
    classes: dict[str, EdgeClass] = {}
    for name, cls in svg.classes.items():
        classes.setdefault(f(name), replace(cls, name=f(name)))
    return replace(svg, paint=paint, classes=classes,
                   face_labels={f(k): v for k, v in svg.face_labels.items()},
                   decorations=[replace(x, target=f(x.target)) for x in svg.decorations])


def _label_text(word: A.Word, unit: Unit) -> str:
    """Face labels and class names written as colours take the SVG importer's form (lowercase
    #rrggbb), so that they match the labels and classes of an imported drawing."""
    if word.kind == "colour" or (word.kind == "string" and S.is_hex_colour(word.text)):
        return S.colour(word, {}, unit.text)
    if word.kind == "star":
        raise error("'*' is not a face label", word.span,
                    "'*' means \"all\" only as the target of a decoration", source=unit.text)
    return word.text


def _fmt(p) -> str:
    return f"{p[0]:g}, {p[1]:g}"
