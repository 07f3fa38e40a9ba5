"""SVG of a host graph of hand-written productions, painted from its attributes.

Each element is drawn in creation order, faces first, then edges, then vertices. Its paint is
its label's decoration (`decorate face|edge|vertex LABEL key=value`, as for compiled grammars)
overridden by its own attributes of the same names: `fill`, `stroke`, `width`, `opacity`, and
for vertices `marker` (circle, square, diamond, triangle, cross) with `size`, or `d`, path data
in drawing coordinates (y up), drawn as it is. Everything is inside one group that turns y up,
so coordinates are written as they are. Every attribute is written through
`svg_out.element`, the one function that escapes them.
"""

from __future__ import annotations

import math
from pathlib import Path
from xml.sax.saxutils import escape

from grammar_lang.fileio import atomic_write
from grammar_lang.xml_text import xml_text

from .drawing import DEdge, Drawing, DVertex
from ..engine.free_host import FreeHost
from .svg_out import FILL_PALETTE, MARGIN, SCREEN, STROKE_WIDTH, _Fmt, _marker, _style_for, \
    decorations, element

PAINT = ("fill", "stroke", "width", "opacity", "marker", "size", "d")


def render_free_svg(host: FreeHost, header) -> str:
    verts = [el for el in host.elements.values() if el.kind == "vertex"]
    xs = [el.attrs["x"] for el in verts] or [0.0]
    ys = [el.attrs["y"] for el in verts] or [0.0]
    lengths = sorted(host.derived(el, "length") for el in host.elements.values()
                     if el.kind == "edge")
    unit = lengths[len(lengths) // 2] if lengths and lengths[len(lengths) // 2] > 0 else 1.0
    size = max(max(xs) - min(xs), max(ys) - min(ys))
    margin = MARGIN * size if size > 0 else unit
    fmt = _Fmt(size + 2 * margin)
    vb = (min(xs) - margin, -max(ys) - margin, max(xs) - min(xs) + 2 * margin,
          max(ys) - min(ys) + 2 * margin)
    k = SCREEN / max(vb[2], vb[3])
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="{" ".join(fmt(x) for x in vb)}" '
           f'width="{fmt(vb[2] * k)}" height="{fmt(vb[3] * k)}">',
           f"  <title>{escape(xml_text(header.source or 'drawing'))}: {host.counts['vertex']} "
           f"vertices, {host.counts['edge']} edges, {host.counts['face']} faces</title>",
           '  <g transform="scale(1,-1)" stroke-linecap="round" stroke-linejoin="round">']
    decos = {kind: decorations(header, kind) for kind in ("face", "edge", "vertex")}
    # A declared default yields to the label's decoration; what was set on an element wins.
    paint_defaults = {kind: {k: v for k, v in host.defaults[kind].items() if k in PAINT}
                      for kind in decos}
    faces = list(header.face_labels)
    for kind in ("face", "edge", "vertex"):
        for el in host.elements.values():
            if el.kind == kind:
                style = {**paint_defaults[kind], **_style_for(decos[kind], el.label),
                         **{key: el.attrs[key] for key in PAINT if key in el.attrs}}
                line = _draw(host, el, style, fmt, unit, faces)
                if line:
                    out.append("    " + line)
    out += ["  </g>", "</svg>"]
    return "\n".join(out) + "\n"


def _paint(style: dict, fmt, default_fill: str, default_stroke: str, unit: float) -> list:
    """(name, value) pairs; `element` escapes them."""
    width = _num(style["width"], fmt) if "width" in style else \
        fmt(STROKE_WIDTH * unit) if default_stroke != "none" or "stroke" in style else None
    return [("fill", style.get("fill", default_fill)),
            ("stroke", style.get("stroke", default_stroke)), ("stroke-width", width),
            ("opacity", _num(style["opacity"], fmt) if "opacity" in style else None)]


def _num(value, fmt) -> str:
    return fmt(float(value)) if isinstance(value, (int, float)) and not isinstance(value, bool) \
        else str(value)


def _draw(host: FreeHost, el, style: dict, fmt, unit: float, faces: list[str]) -> str:
    pt = lambda v: f"{fmt(host.pos(v)[0])},{fmt(host.pos(v)[1])}"     # noqa: E731
    label = [("data-label", el.label)]
    if el.kind == "face":
        fill = FILL_PALETTE[faces.index(el.label) % len(FILL_PALETTE)] \
            if el.label in faces else FILL_PALETTE[0]
        d = "M " + " L ".join(pt(v) for v in el.ends) + " Z"
        return element("path", [("d", d)] + label + _paint(style, fmt, fill, "none", unit))
    if el.kind == "edge":
        (x1, y1), (x2, y2) = host.pos(el.ends[0]), host.pos(el.ends[1])
        return element("line", [("x1", fmt(x1)), ("y1", fmt(y1)), ("x2", fmt(x2)),
                                ("y2", fmt(y2))] + label
                       + _paint(style, fmt, "none", "#1a1a1a", unit))
    if style.get("d"):
        return element("path", [("d", style["d"])] + label
                       + _paint(style, fmt, "none", "#1a1a1a", unit))
    marker = style.get("marker", "none")
    if marker not in ("circle", "square", "diamond", "triangle", "cross"):
        return ""
    x, y = host.pos(el.id)
    size = float(style["size"]) if isinstance(style.get("size"), (int, float)) else unit / 5
    if not math.isfinite(size) or size <= 0:
        return ""
    shape = _marker(marker, size, str(style.get("fill", "#1a1a1a")),
                    str(style.get("stroke", "none")), fmt, unit)
    return element("g", [("transform", f"translate({fmt(x)},{fmt(y)})")] + label, shape)


def write_free_svg(host: FreeHost, header, path: str | Path) -> None:
    atomic_write(path, render_free_svg(host, header))


def free_drawing(host: FreeHost, meta: dict) -> Drawing:
    """The host as a gg-drawing/1 document: vertices, edges (class = label), and the faces and
    every element's attributes as extra fields."""
    ids = {el.id: k for k, el in enumerate(e for e in host.elements.values() if e.kind == "vertex")}
    verts = tuple(DVertex(k, host.pos(i)[0], host.pos(i)[1]) for i, k in ids.items())
    edges = [el for el in host.elements.values() if el.kind == "edge"]
    faces = [el for el in host.elements.values() if el.kind == "face"]
    def plain(el) -> dict:
        return {k: v for k, v in sorted(host.attributes(el).items()) if k not in ("x", "y")}

    extra = {"faces": [{"label": f.label, "vertices": [ids[v] for v in f.ends],
                        "attributes": plain(f)} for f in faces],
             "vertex_labels": [host.elements[i].label for i in ids],
             "attributes": {"vertices": [plain(host.elements[i]) for i in ids],
                            "edges": [plain(e) for e in edges]}}
    return Drawing(verts, tuple(DEdge(ids[e.ends[0]], ids[e.ends[1]], "exterior", "exterior",
                                      e.label, e.label) for e in edges), {**meta, **extra})
