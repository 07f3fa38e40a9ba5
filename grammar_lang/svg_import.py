"""SVG drawings → `ExampleSource`, following the corpus conventions (corpus README).

Filled shapes are face regions (label: `data-label`, else the fill colour as `#rrggbb`) in
painter's order; unfilled shapes and lines are strokes (class: `data-class`, else the stroke
colour, black being the default class). y is flipped into the y-up frame. Parsing is hardened
(defusedxml: no DTD entities, no external references) and every problem is a `UserError`
pointing at the element, or into the attribute, that caused it.
"""

from __future__ import annotations

import io
import re
import xml.sax
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from defusedxml import DefusedXmlException
from defusedxml import sax as defused_sax

from .diagnostics import Span, UserError, error
from . import limits
from .fileio import read_text
from .source import (COLOUR_PROPERTY, DEFAULT_CLASS, MAX_COORDINATE, Decoration, EdgeClass, ExampleSource, Region,
                     Stroke)
from .svg_colors import normalize_color
from .svg_paths import (FLATTEN_HINT, IDENTITY, SvgValueError, apply, parse_length,
                        parse_path, parse_points, parse_transform)

SVG_NS = "http://www.w3.org/2000/svg"
MAX_DEPTH = 256

# Elements that paint nothing we model (definitions, metadata, text): their subtrees are skipped.
_SKIPPED = {"defs", "symbol", "clipPath", "mask", "marker", "pattern", "linearGradient",
            "radialGradient", "metadata", "title", "desc", "text", "image", "foreignObject",
            "filter", "script", "view", "cursor", "font", "font-face", "animate", "set",
            "animateTransform", "animateMotion"}
_CONTAINERS = {"svg", "g", "a", "switch"}
_INHERITED = ("fill", "stroke", "fill-rule", "color", "visibility", "data-label", "data-class")
_QUOTED = r"(?:\"[^\"]*\"|'[^']*')"
_EXTERNAL_DTD = re.compile(r"(<!DOCTYPE\s+[\w:.-]+)(\s+(?:PUBLIC\s+" + _QUOTED + r"\s+" + _QUOTED
                           + r"|SYSTEM\s+" + _QUOTED + r"))", re.IGNORECASE)
_STYLE_PROPS = {"fill", "stroke", "fill-rule", "color", "visibility", "display"}


@dataclass
class _Node:
    tag: str                 # local name; '' for elements outside the SVG namespace
    attrs: dict[str, str]    # attributes without a namespace
    line: int
    column: int              # 1-based, in characters
    children: list["_Node"] = field(default_factory=list)
    text: str = ""


class _TreeBuilder(xml.sax.ContentHandler):
    """Builds a small tree that remembers where each element starts (ElementTree forgets)."""

    def __init__(self):
        super().__init__()
        self.locator = None
        self.stack: list[_Node] = []
        self.root: _Node | None = None
        self.count = 0
        self.max_elements = limits.ELEMENTS.value()

    def setDocumentLocator(self, locator):
        self.locator = locator

    def _position(self) -> tuple[int, int]:
        # expat counts 0-based columns in characters.
        line = self.locator.getLineNumber() if self.locator else 0
        col = self.locator.getColumnNumber() if self.locator else 0
        return line, col + 1

    def startElementNS(self, name, qname, attrs):
        uri, local = name
        line, column = self._position()
        self.count += 1
        if self.count > self.max_elements:
            raise _Refused(limits.ELEMENTS.message(self.count, "elements so far"), line, column,
                           limits.ELEMENTS.hint())
        if len(self.stack) >= MAX_DEPTH:
            raise _Refused(f"elements are nested more than {MAX_DEPTH} deep", line, column)
        plain = {k[1]: v for k, v in attrs.items() if k[0] is None}
        node = _Node(local if uri in (SVG_NS, None) else "", plain, line, column)
        if self.stack:
            self.stack[-1].children.append(node)
        else:
            self.root = node
        self.stack.append(node)

    def endElementNS(self, name, qname):
        self.stack.pop()

    def characters(self, content):
        if self.stack and self.stack[-1].tag in ("title", "style"):
            self.stack[-1].text += content


class _Refused(Exception):
    def __init__(self, message: str, line: int, column: int,
                 hint: str = "this does not look like a hand-drawn example"):
        super().__init__(message)
        self.message, self.line, self.column, self.hint = message, line, column, hint


def _parse_xml(text: str, file: str) -> _Node:
    builder = _TreeBuilder()
    parser = defused_sax.make_parser()
    parser.setFeature(xml.sax.handler.feature_namespaces, True)
    parser.setContentHandler(builder)
    parser.setErrorHandler(xml.sax.ErrorHandler())
    parser.forbid_dtd = False        # a plain DOCTYPE is harmless; entities are not
    parser.forbid_entities = True
    parser.forbid_external = True
    # The text is already decoded; a declared legacy encoding must not re-decode it.
    cleaned = re.sub(r"^(\s*<\?xml[^>]*?encoding\s*=\s*)([\"'])[^\"']*\2", r"\1\2utf-8\2",
                     text, count=1)
    # Old editors name the SVG 1.1 DTD; blank the reference (keeping columns) rather than
    # refuse the file. It is never fetched either way.
    cleaned = _EXTERNAL_DTD.sub(lambda m: m.group(1) + re.sub(r"[^\n]", " ", m.group(2)),
                                cleaned, count=1)
    data = cleaned.encode("utf-8")
    source = xml.sax.xmlreader.InputSource()
    source.setByteStream(io.BytesIO(data))
    try:
        parser.parse(source)
    except _Refused as exc:
        raise error(exc.message, Span(file, exc.line, exc.column), source=text,
                    hint=exc.hint) from None
    except DefusedXmlException as exc:
        offset = text.find("<!ENTITY")
        span = _span_at(file, text, offset) if offset >= 0 else Span(file)
        raise error(f"refusing XML entity declarations or external references ({type(exc).__name__})",
                    span, "remove the DOCTYPE's entity definitions; SVG drawings do not need them",
                    source=text) from None
    except xml.sax.SAXParseException as exc:
        line, col = exc.getLineNumber() or 0, exc.getColumnNumber() or 0
        message = exc.getMessage()
        raise error(f"not well-formed XML: {message}", Span(file, line, col + 1),
                    "check the file is a complete, valid SVG document", source=text) from None
    except (ValueError, RecursionError, MemoryError) as exc:
        raise error(f"cannot parse the XML: {exc}", Span(file),
                    "check the file is a complete, valid SVG document", source=text) from None
    if builder.root is None:
        raise error("the file has no XML elements", Span(file), source=text)
    return builder.root


def _span_at(file: str, text: str, offset: int, length: int = 1) -> Span:
    line = text.count("\n", 0, offset) + 1
    column = offset - (text.rfind("\n", 0, offset) + 1) + 1
    return Span(file, line, column, max(1, length))


class _Importer:
    def __init__(self, file: str, text: str):
        self.file = file
        self.text = text
        self.line_starts = [0] + [m.end() for m in re.finditer("\n", text)]
        self.paint: list = []
        self.face_labels: dict[str, Span | None] = {}
        self.classes: dict[str, EdgeClass] = {}
        # The colours that named labels and classes were painted with: (kind, name) → colour
        # → count. See `drawn_colours`.
        self.painted: dict[tuple[str, str], dict[str, int]] = {}
        self.spans: dict[tuple[str, str], Span] = {}
        self.root: _Node | None = None

    # --- places ---------------------------------------------------------------------------

    def _offset(self, node: _Node) -> int:
        if 1 <= node.line <= len(self.line_starts):
            return self.line_starts[node.line - 1] + node.column - 1
        return -1

    def span(self, node: _Node) -> Span:
        return Span(self.file, node.line, node.column, len(node.tag or "x") + 1)

    def attr_span(self, node: _Node, name: str, within: int = 0, length: int = 1) -> Span:
        """The place of `within` characters into attribute `name`'s value, else the element."""
        start = self._offset(node)
        if start >= 0:
            end = self.text.find(">", start)
            match = re.compile(r"(?<![\w:-])" + re.escape(name) + r"\s*=\s*([\"'])").search(
                self.text, start, end if end >= 0 else len(self.text))
            if match:
                return _span_at(self.file, self.text, match.end() + within, length)
        return self.span(node)

    def fail(self, node: _Node, message: str, hint: str | None = None,
             attr: str | None = None, within: int = 0) -> UserError:
        span = self.attr_span(node, attr, within) if attr else self.span(node)
        return error(message, span, hint, source=self.text)

    # --- styles ---------------------------------------------------------------------------

    def style(self, node: _Node, parent: dict[str, str]) -> dict[str, str]:
        own: dict[str, str] = {}
        for key in _STYLE_PROPS | {"data-label", "data-class"}:
            if key in node.attrs:
                own[key] = node.attrs[key].strip()
        for declaration in node.attrs.get("style", "").split(";"):
            key, sep, value = declaration.partition(":")
            key = key.strip().lower()
            if sep and key in _STYLE_PROPS:
                own[key] = value.replace("!important", "").strip()
        computed = {k: parent[k] for k in _INHERITED if k in parent}
        for key, value in own.items():
            if value == "inherit":
                continue
            computed[key] = value
        return computed

    def colour(self, node: _Node, style: dict[str, str], prop: str) -> str | None:
        """Normalised colour of `fill`/`stroke`; None for `none`; raises on what we can't read."""
        value = style.get(prop)
        if value is None:
            return "#000000" if prop == "fill" else None
        if value.lower() in ("none", "transparent"):
            return None
        if value.lower() == "currentcolor":
            value = style.get("color", "black")
        if value.startswith("url("):
            # A paint server may name a fallback colour after the reference.
            fallback = value[value.find(")") + 1:].strip()
            if fallback:
                value = fallback
            else:
                return "url"
        colour = normalize_color(value)
        if colour is None:
            raise self.fail(node, f"cannot read the {prop} colour {value!r}",
                            "use #rrggbb, #rgb, rgb(r, g, b) or a CSS colour name")
        return colour

    # --- walking --------------------------------------------------------------------------

    def walk(self, node: _Node, matrix: np.ndarray, parent_style: dict[str, str]) -> None:
        style = self.style(node, parent_style)
        if style.get("display", "").lower() == "none":
            return
        if "transform" in node.attrs:
            try:
                with np.errstate(over="ignore", invalid="ignore"):  # apply() reports overflow
                    matrix = matrix @ parse_transform(node.attrs["transform"])
            except SvgValueError as exc:
                raise self.fail(node, f"bad transform: {exc.message}", exc.hint,
                                "transform", exc.offset) from None
        tag = node.tag
        if tag in _CONTAINERS:
            if tag == "svg" and node is not self.root:
                offset = [self.length(node, "x"), self.length(node, "y")]
                with np.errstate(over="ignore", invalid="ignore"):
                    matrix = matrix @ np.array([[1.0, 0, offset[0]], [0, 1.0, offset[1]],
                                                [0, 0, 1]])
            for child in node.children:
                self.walk(child, matrix, style)
            return
        if tag in ("", *_SKIPPED):
            return
        if tag == "style":
            if node.text.strip():
                raise self.fail(node, "CSS style sheets (<style>) are not supported",
                                "give fill and stroke on each shape, as attributes or in "
                                "style=\"...\"")
            return
        if style.get("visibility", "").lower() in ("hidden", "collapse"):
            return
        if tag in ("circle", "ellipse"):
            raise self.fail(node, f"<{tag}> is a curve; only straight segments are supported",
                            FLATTEN_HINT)
        if tag == "use":
            raise self.fail(node, "<use> (a clone) is not supported",
                            "unlink the clone first: Edit > Clone > Unlink Clone")
        shape = self.shape(node, tag)
        if shape is None:
            return
        subpaths, fillable = shape
        self.emit(node, style, matrix, subpaths, fillable)

    def length(self, node: _Node, name: str, default: float = 0.0) -> float:
        value = node.attrs.get(name)
        if value is None:
            return default
        try:
            return parse_length(value)
        except SvgValueError as exc:
            raise self.fail(node, f"bad {name}: {exc.message}", exc.hint, name,
                            exc.offset) from None

    def shape(self, node: _Node, tag: str):
        """(subpaths as (points, closed), whether fill applies) or None for unknown elements."""
        if tag == "path":
            try:
                subpaths = parse_path(node.attrs.get("d", ""), limits.POINTS)
            except SvgValueError as exc:
                raise self.fail(node, f"bad path data: {exc.message}", exc.hint, "d",
                                exc.offset) from None
            return [(sp.points, sp.closed) for sp in subpaths], True
        if tag in ("polygon", "polyline"):
            try:
                points = parse_points(node.attrs.get("points", ""), limits.POINTS)
            except SvgValueError as exc:
                raise self.fail(node, f"bad points: {exc.message}", exc.hint, "points",
                                exc.offset) from None
            return [(points, tag == "polygon")], True
        if tag == "line":
            p = (self.length(node, "x1"), self.length(node, "y1"))
            q = (self.length(node, "x2"), self.length(node, "y2"))
            return [([p, q], False)], False
        if tag == "rect":
            x, y = self.length(node, "x"), self.length(node, "y")
            w, h = self.length(node, "width"), self.length(node, "height")
            if w <= 0 or h <= 0:
                raise self.fail(node, "rectangle with zero or negative size",
                                "give it a positive width and height")
            if self.length(node, "rx") > 0 or self.length(node, "ry") > 0:
                raise self.fail(node, "rectangle with rounded corners (rx/ry): corners are curves",
                                "set the corner radius to 0, or " + FLATTEN_HINT)
            return [([(x, y), (x + w, y), (x + w, y + h), (x, y + h)], True)], True
        return None

    def emit(self, node: _Node, style: dict[str, str], matrix: np.ndarray,
             subpaths: list, fillable: bool) -> None:
        span = self.span(node)
        try:
            rings = [(tuple(apply(matrix, _open(points, closed))), closed)
                     for points, closed in subpaths if len(points) >= 2]
        except SvgValueError as exc:
            raise self.fail(node, exc.message) from None
        if not rings:
            return  # SVG renders nothing for empty path data
        # Refused here, where the shape is known, before any arithmetic on the coordinates
        # (the area test below would overflow on them).
        if any(abs(c) > MAX_COORDINATE for ring, _ in rings for pt in ring for c in pt):
            raise self.fail(node, f"coordinates beyond ±{MAX_COORDINATE:g}",
                            "scale the drawing down (in the editor, or with a transform)")
        fill = self.colour(node, style, "fill") if fillable else None
        if fill is not None and "fill" not in style and not any(_has_area(r) for r, _ in rings):
            fill = None  # SVG's implicit black fill of a flat polyline paints nothing
        stroke = self.stroke_class(node, style)
        if fill is not None:
            label = style.get("data-label") or fill
            if label == "url":
                raise self.fail(node, "gradient or pattern fill without a data-label",
                                "give the shape a data-label attribute, or a flat fill colour")
            self.face_labels.setdefault(label, span)
            self.note_colour("face", label, fill, span)
            self.paint.append(Region(tuple(r for r, _ in rings), label,
                                     style.get("fill-rule", "").lower() == "evenodd", span))
            # The outline of a region is an edge of the default class.
            self.classes.setdefault(DEFAULT_CLASS, EdgeClass(DEFAULT_CLASS, span=span))
            if stroke == DEFAULT_CLASS:
                return  # the region's outline already is a default-class edge
        self.note_colour("edge", stroke, self.colour(node, style, "stroke"), span)
        for points, closed in rings:
            self.paint.append(Stroke(points, closed, stroke, span))
        self.classes.setdefault(stroke, EdgeClass(stroke, span=span))

    def note_colour(self, kind: str, name: str, colour: str | None, span: Span) -> None:
        """Count `colour` for a label or class named apart from its colour (`data-label`,
        `data-class`): one named by its colour is drawn in it already."""
        if colour is not None and colour != "url" and colour != name:
            counts = self.painted.setdefault((kind, name), {})
            counts[colour] = counts.get(colour, 0) + 1
            self.spans.setdefault((kind, name), span)

    def drawn_colours(self) -> list[Decoration]:
        """A decoration per named label and class giving the colour it was drawn in (the
        commonest; the first drawn among equals), so that generated drawings look like the
        example: a flower's green stems stay green. `gg_resolve` drops one the user's own
        decorations colour."""
        return [Decoration(kind, name, ((COLOUR_PROPERTY[kind], max(counts, key=counts.get)),),
                           span=self.spans[(kind, name)])
                for (kind, name), counts in self.painted.items()]

    def stroke_class(self, node: _Node, style: dict[str, str]) -> str:
        if style.get("data-class"):
            return style["data-class"]
        colour = self.colour(node, style, "stroke")
        if colour == "url":
            raise self.fail(node, "gradient or pattern stroke without a data-class",
                            "give the line a data-class attribute, or a flat stroke colour")
        return DEFAULT_CLASS if colour in (None, "#000000") else colour


def _has_area(ring: tuple) -> bool:
    if len(ring) < 3:
        return False
    v = np.asarray(ring, dtype=float)[1:] - ring[0]
    return bool(np.any(v[:-1, 0] * v[1:, 1] - v[:-1, 1] * v[1:, 0] != 0))


def _open(points: list, closed: bool) -> list:
    """Drop the repeated start point of a closed ring (`M a L b L a Z`)."""
    if closed and len(points) > 2 and points[0] == points[-1]:
        return points[:-1]
    return points


def import_svg(path: str | Path, text: str | None = None) -> ExampleSource:
    """Read an SVG drawing into an `ExampleSource` (y-up, painter's order kept)."""
    file = str(path)
    if text is None:
        text = read_text(path)
    root = _parse_xml(text, file)
    if root.tag != "svg":
        raise error("not an SVG drawing: the root element is not <svg>",
                    Span(file, root.line, root.column), "open an .svg file saved by a vector editor",
                    source=text)
    importer = _Importer(file, text)
    importer.root = root
    importer.walk(root, IDENTITY, {})
    if not importer.paint:
        raise error("the drawing has no shapes", Span(file, root.line, root.column),
                    "draw paths, polygons, polylines, lines or rectangles", source=text)
    title = next((c.text.strip() for c in root.children if c.tag == "title"), "")
    classes = dict(sorted(importer.classes.items()))
    return ExampleSource(path=file, name=title or Path(file).stem,
                         face_labels=importer.face_labels, paint=importer.paint,
                         classes=classes, decorations=importer.drawn_colours(), text=text)
