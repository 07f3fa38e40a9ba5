"""Drawings as SVG: faces filled by label, edges stroked by class, decorations where simple.

The picture is made to be read back: every face is one filled path (its holes cut out with
`evenodd`) carrying `data-label`, and every edge class is one stroked path carrying
`data-class`, which is what the SVG importer reads. Coordinates stay in drawing units with y
negated, so y points up on screen; the viewBox fits the drawing with a margin.

Colours: a face label's decoration `fill` wins, then the label itself when it is a colour
(`#rrggbb`, as SVG examples label faces), then a fixed palette by the label's position among
the example's face labels; an edge class's `stroke` likewise, then the class when it is a
colour, then a palette. The exterior is left unpainted unless decorated. Decorations
(`decorate face|edge|vertex TARGET {...}`; a named target beats `*`, and among equals the
later decoration wins)
supply face fill/opacity/pattern, edge stroke/width/opacity/image, and vertex
marker/size/fill/stroke/image, and edge bend/bend-step: bending (Appendix B, see
`bending`) changes the picture's geometry only, so a bent picture no longer reads back as the
drawing, which keeps the unbent geometry.
"""

from __future__ import annotations

import functools
import math
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Iterable
from xml.sax.saxutils import escape, quoteattr

import numpy as np

from grammar_lang.fileio import atomic_write
from grammar_lang.svg_colors import contrast, same_colour
from grammar_lang.xml_text import xml_text

from .bending import Bend, bend_picture
from .drawing import Drawing
from ..geometry.faces import UNBOUNDED, compute_faces, cycle_points

# Colour-blind-friendly fills (light) and strokes (dark), used in order.
FILL_PALETTE = ("#a6cee3", "#b2df8a", "#fdbf6f", "#cab2d6", "#fb9a99", "#ffff99", "#8dd3c7",
                "#bebada", "#fccde5", "#d9d9d9", "#ccebc5", "#ffed6f")
STROKE_PALETTE = ("#1a1a1a", "#1f78b4", "#e31a1c", "#33a02c", "#6a3d9a", "#ff7f00", "#b15928")
# Sizes relative to the example's unit length (its median edge), when not decorated.
STROKE_WIDTH = 0.02
MARGIN = 0.05           # of the drawing's larger side
# A stroke that stands out from a fill beside it (WCAG 2's ratio for graphics), and the fill
# behind an unpainted face.
LEGIBLE = 3.0
PAGE = "#ffffff"
BEND_STEP = 0.25        # bend-step when not decorated, in units
SCREEN = 800.0          # px along the larger side, for the width/height attributes


def element(tag: str, attrs, body: str | None = None) -> str:
    """An XML element, every attribute value escaped here and nowhere else: no value, from
    whatever input file, can end its attribute and start another, or start an element, nor
    hold a character XML cannot (grammar_lang.xml_text).
    `attrs` is a sequence of (name, value) pairs; a None value leaves the attribute out."""
    text = "".join(f" {k}={quoteattr(xml_text(str(v)))}" for k, v in attrs if v is not None)
    return f"<{tag}{text}/>" if body is None else f"<{tag}{text}>{body}</{tag}>"


def _hex_colour(label: str) -> bool:
    return len(label) == 7 and label[0] == "#" and all(c in "0123456789abcdefABCDEF" for c in label[1:])


class _Fmt:
    """Fixed-precision numbers: enough decimals for the drawing's size, no exponents."""

    def __init__(self, extent: float):
        self.decimals = int(min(9, max(0, 5 - math.floor(math.log10(extent))))) if extent > 0 else 3

    def __call__(self, x: float) -> str:
        text = f"{x:.{self.decimals}f}"
        if "." in text:
            text = text.rstrip("0").rstrip(".")
        return "0" if text in ("-0", "") else text


def decorations(reference, kind: str) -> list[tuple[str, dict]]:
    if reference is None:
        return []
    return [(d.target, dict(d.props)) for d in getattr(reference, "decorations", ())
            if d.kind == kind]


def _style_for(decos: list[tuple[str, dict]], *names: str) -> dict:
    """Merged properties of the decorations aimed at `names` or '*': a named target beats '*'
    (as in CSS), and among equals the later one wins."""
    out: dict = {}
    for target, props in decos:
        if target == "*":
            out.update(props)
    for target, props in decos:
        if target != "*" and target in names:
            out.update(props)
    return out


def face_paint(label: str, plain: list[str], exterior: str,
               face_decos: list[tuple[str, dict]]) -> tuple[str | None, dict]:
    """A face label's fill (None: unpainted) and decoration style; `plain` lists the face
    labels that take palette colours, in order."""
    style = _style_for(face_decos, label)
    if "fill" in style:
        return style["fill"], style
    if label == exterior:
        return None, style
    if _hex_colour(label):
        return label.lower(), style
    return FILL_PALETTE[plain.index(label) % len(FILL_PALETTE)], style


def edge_paint(cls: str, class_order: list[str], edge_decos: list[tuple[str, dict]],
               beside: Iterable[str | None] = ()) -> dict:
    """An edge class's decoration style, with its stroke colour filled in. `beside`: the
    fills of the faces its edges border (None: unpainted, the page's white)."""
    style = _style_for(edge_decos, cls)
    fills = {f or PAGE for f in beside}
    # A class named by its colour (an SVG line's stroke, as the importer names them).
    stroke = style.get("stroke", cls.lower() if _hex_colour(cls) else None)
    # A stroke of the very colour of every face beside it draws nothing: a station's trusses,
    # drawn black in its black space, left its antennas floating. The palette's instead.
    if stroke is None or fills and all(same_colour(stroke, f) for f in fills):
        stroke = legible_stroke(class_order.index(cls), fills)
    style["stroke"] = stroke
    return style


def legible_stroke(k: int, fills: set[str]) -> str:
    """The palette's k-th stroke, or the first after it that stands out from every fill in
    `fills` (the palette's first stroke is near-black); the one that stands out most when
    none stands out enough."""
    n = len(STROKE_PALETTE)
    best, best_c = STROKE_PALETTE[k % n], -1.0
    for i in range(n):
        stroke = STROKE_PALETTE[(k + i) % n]
        c = min((contrast(stroke, f) or LEGIBLE for f in fills), default=LEGIBLE)
        if c >= LEGIBLE:
            return stroke
        if c > best_c:
            best, best_c = stroke, c
    return best


@dataclass
class _Canvas:
    """What every part of the picture is drawn with: the drawing as arrays, its reference,
    the viewBox and number format, and the <defs> collected on the way."""

    drawing: Drawing
    ref: object                      # a verifier Reference, or None
    base: str | Path | None
    exterior: str
    ids: list[int]
    xy: np.ndarray                   # where vertices are drawn (bent, if edges bend)
    ends: np.ndarray
    topology: np.ndarray             # the drawing's own positions, which faces are found from
    paths: tuple | None              # per edge, the points a bent edge runs through
    unit: float
    vb: tuple[float, float, float, float]
    fmt: _Fmt
    defs: list[str] = field(default_factory=list)

    @functools.cached_property
    def plain(self) -> list[str]:
        """The face labels that take palette fills, in the order they take them (asked by
        the faces and by the edges, whose strokes must show against them)."""
        label_order = list(self.ref.face_labels) if self.ref else []
        for e in self.drawing.edges:
            for name in (e.left, e.right):
                if name not in label_order:
                    label_order.append(name)
        return [n for n in label_order if n != self.exterior and not _hex_colour(n)]

    def pt(self, p) -> str:
        return f"{self.fmt(p[0])},{self.fmt(-p[1])}"

    def ring(self, cycle) -> np.ndarray:
        """The points a cycle of half-edges runs through, bent edges' points included."""
        if self.paths is None:
            return cycle_points(self.xy, self.ends, cycle)
        return np.concatenate([self.paths[h >> 1][:-1] if h % 2 == 0
                               else self.paths[h >> 1][:0:-1] for h in cycle])

    def line(self, e: int) -> str:
        """An edge as path data."""
        if self.paths is None:
            return f"M {self.pt(self.xy[self.ends[e, 0]])} L {self.pt(self.xy[self.ends[e, 1]])}"
        return "M " + " L ".join(self.pt(p) for p in self.paths[e])

    def href(self, path: str) -> str:
        if self.base is not None:
            try:
                return Path(os.path.relpath(path, self.base)).as_posix()
            except ValueError:   # another drive on Windows
                pass
        return Path(path).as_uri()


def render_svg(drawing: Drawing, reference=None, base: str | Path | None = None) -> str:
    """The drawing as SVG text. `reference` (an Example, Header or Grammar) supplies the
    exterior's name, the order of face labels and edge classes, the unit and decorations;
    `base` is the folder the SVG will be written to, so image links can be relative."""
    from ..verifier import as_reference

    cv = _canvas(drawing, as_reference(reference) if reference is not None else None, base)
    vb, k = cv.vb, SCREEN / max(cv.vb[2], cv.vb[3])
    svg = element("svg", [("xmlns", "http://www.w3.org/2000/svg"),
                          ("xmlns:xlink", "http://www.w3.org/1999/xlink"),
                          ("viewBox", " ".join(cv.fmt(x) for x in vb)),
                          ("width", cv.fmt(vb[2] * k)), ("height", cv.fmt(vb[3] * k))], "")
    head = [svg[: -len("</svg>")]]
    ref = cv.ref
    title = (ref.name if ref and ref.name else drawing.meta.get("example", "")) or "drawing"
    head.append(f"  <title>{escape(xml_text(str(title)))}: {len(cv.ids)} vertices, "
                f"{len(drawing.edges)} edges</title>")
    body = _faces_group(cv) + _edges_group(cv) + _vertices_group(cv)
    if cv.defs:
        head += ["  <defs>"] + cv.defs + ["  </defs>"]
    return "\n".join(head + body + ["</svg>"]) + "\n"


def _canvas(drawing: Drawing, ref, base) -> _Canvas:
    ids = [v.id for v in drawing.vertices]
    index = {v: i for i, v in enumerate(ids)}
    xy = np.array([(v.x, v.y) for v in drawing.vertices], dtype=float).reshape(-1, 2)
    ends = np.array([(index[e.u], index[e.v]) for e in drawing.edges],
                    dtype=np.int64).reshape(-1, 2)
    lengths = np.hypot(*(xy[ends[:, 1]] - xy[ends[:, 0]]).T) if len(ends) else np.zeros(0)
    unit = ref.unit if ref else (float(np.median(lengths[lengths > 0]))
                                 if np.any(lengths > 0) else 1.0)
    bent = _bend(drawing, ref, xy, ends, unit)
    drawn = np.concatenate(bent.paths + (bent.xy,)) if bent else xy
    lo = drawn.min(axis=0) if len(drawn) else np.zeros(2)
    hi = drawn.max(axis=0) if len(drawn) else np.zeros(2)
    size = float(max(hi - lo)) if len(drawn) else 0.0
    margin = MARGIN * size if size > 0 else unit
    vb = (lo[0] - margin, -hi[1] - margin, hi[0] - lo[0] + 2 * margin,
          hi[1] - lo[1] + 2 * margin)
    return _Canvas(drawing, ref, base, ref.exterior if ref else "exterior", ids,
                   bent.xy if bent else xy, ends, xy, bent.paths if bent else None, unit,
                   vb, _Fmt(size + 2 * margin))


def _bend(drawing: Drawing, ref, xy, ends, unit):
    """The bent picture, when an edge class is decorated with `bend`; else None. The frame
    and its vertices (those on border edges) stay where they are. Seeded by the drawing's seed."""
    edge_decos = decorations(ref, "edge")
    if not any("bend" in props for _, props in edge_decos):
        return None
    border = {c.name for c in ref.classes if c.border}
    per_class: dict[str, Bend | None] = {}
    for e in drawing.edges:
        if e.cls not in per_class and e.cls in border:
            per_class[e.cls] = None           # the frame is the border: it never bends
        elif e.cls not in per_class:
            style = _style_for(edge_decos, e.cls)
            angle = math.radians(float(style.get("bend", 0.0)))
            step = float(style.get("bend-step", BEND_STEP * unit))
            per_class[e.cls] = Bend(angle, step) if angle > 0 else None
    if not any(per_class.values()):
        return None
    pinned = np.zeros(len(xy), dtype=bool)
    for i, e in enumerate(drawing.edges):
        if e.cls in border:
            pinned[ends[i]] = True
    seed = drawing.meta.get("seed", 0)
    return bend_picture(xy, ends, [per_class[e.cls] for e in drawing.edges], pinned,
                        seed if isinstance(seed, int) else 0)


def _faces_group(cv: _Canvas) -> list[str]:
    """One filled path per painted face, its holes cut out."""
    drawing, ends, exterior, vb = cv.drawing, cv.ends, cv.exterior, cv.vb
    face_decos = decorations(cv.ref, "face")
    plain = cv.plain
    faces = compute_faces(cv.topology, ends)
    left = [drawing.edges[h >> 1].right if h & 1 else drawing.edges[h >> 1].left
            for h in range(2 * len(drawing.edges))]
    patterns: dict[tuple, str] = {}
    out = ['  <g id="faces" stroke="none">']
    for f, face in enumerate(faces.faces):
        if f == UNBOUNDED:
            label = exterior
            rings = [cv.ring(faces.cycles[c]) for c in face.holes]
        else:
            cyc = faces.cycles[face.outer]
            counts: dict[str, int] = {}
            for h in cyc:
                counts[left[h]] = counts.get(left[h], 0) + 1
            label = min(counts, key=lambda n: (-counts[n], n))
            rings = [cv.ring(cyc)] + [cv.ring(faces.cycles[c]) for c in face.holes]
        fill, style = face_paint(label, plain, exterior, face_decos)
        if fill is None and "pattern" not in style:
            continue
        if f == UNBOUNDED:
            box = [(vb[0], -vb[1]), (vb[0] + vb[2], -vb[1]), (vb[0] + vb[2], -vb[1] - vb[3]),
                   (vb[0], -vb[1] - vb[3])]
            rings.insert(0, np.array(box))
        paint = _pattern_paint(cv, style, patterns) if "pattern" in style else fill or "none"
        d = " ".join("M " + " L ".join(cv.pt(p) for p in ring) + " Z"
                     for ring in rings if len(ring))
        opacity = cv.fmt(style["opacity"]) if "opacity" in style else None
        out.append("    " + element("path", [("d", d), ("fill", paint), ("fill-rule", "evenodd"),
                                             ("fill-opacity", opacity), ("data-label", label)]))
    out.append("  </g>")
    return out


def _pattern_paint(cv: _Canvas, style: dict, patterns: dict[tuple, str]) -> str:
    """A face's pattern fill: one <pattern> per image and scale, defined on first use."""
    key = (style["pattern"], float(style.get("pattern-scale", 1.0)))
    if key not in patterns:
        pid = f"pattern{len(patterns)}"
        patterns[key] = pid
        w = cv.fmt(cv.unit * key[1])
        image = element("image", [("xlink:href", cv.href(key[0])), ("width", w), ("height", w)])
        cv.defs.append("    " + element("pattern", [("id", pid), ("patternUnits", "userSpaceOnUse"),
                                                    ("width", w), ("height", w)], image))
    return f"url(#{patterns[key]})"


def _edges_group(cv: _Canvas) -> list[str]:
    """One stroked path per edge class, then the edge images."""
    edges, xy, ends, fmt = cv.drawing.edges, cv.xy, cv.ends, cv.fmt
    edge_decos = decorations(cv.ref, "edge")
    class_order = [c.name for c in cv.ref.classes] if cv.ref else []
    for e in edges:
        if e.cls not in class_order:
            class_order.append(e.cls)
    by_class: dict[str, list[int]] = {}
    beside: dict[str, set[str]] = {}          # the face labels a class's edges border
    for i, e in enumerate(edges):
        by_class.setdefault(e.cls, []).append(i)
        beside.setdefault(e.cls, set()).update((e.left, e.right))
    plain, face_decos = cv.plain, decorations(cv.ref, "face")
    out = ['  <g id="edges" fill="none" stroke-linecap="round" stroke-linejoin="round">']
    images: list[str] = []
    for cls in sorted(by_class, key=class_order.index):
        fills = (face_paint(f, plain, cv.exterior, face_decos)[0] for f in sorted(beside[cls]))
        style = edge_paint(cls, class_order, edge_decos, fills)
        width = float(style.get("width", STROKE_WIDTH * cv.unit))
        d = " ".join(cv.line(i) for i in by_class[cls])
        opacity = fmt(style["opacity"]) if "opacity" in style else None
        if width > 0:
            out.append("    " + element("path", [("d", d), ("stroke", style["stroke"]),
                                                 ("stroke-width", fmt(width)),
                                                 ("stroke-opacity", opacity),
                                                 ("data-class", cls)]))
        if "image" in style:
            images.extend(_edge_images(xy, ends, by_class[cls], style, cv.unit, fmt, cv.href))
    out.append("  </g>")
    if images:
        out += ['  <g id="edge-images">'] + images + ["  </g>"]
    return out


def _vertices_group(cv: _Canvas) -> list[str]:
    """Vertex images and markers, where decorations ask for them."""
    from ..verifier import vertex_primitives

    vertex_decos = decorations(cv.ref, "vertex")
    if not vertex_decos:
        return []
    ref, fmt, xy = cv.ref, cv.fmt, cv.xy
    prims = vertex_primitives(ref, cv.drawing) if ref else {}
    names = [p.name for p in ref.primitives] if ref else []
    first_dir = _first_directions(cv.drawing, xy, cv.ends)
    marks: list[str] = []
    shapes: dict[tuple, str] = {}
    for v, vid in enumerate(cv.ids):
        prim = names[prims[vid]] if vid in prims else None
        style = _style_for(vertex_decos, *([prim] if prim else []))
        if not style:
            continue
        x, y = fmt(xy[v, 0]), fmt(-xy[v, 1])
        if "image" in style:
            s = cv.unit * float(style.get("scale", 1.0)) / 2
            turn = None
            if style.get("rotate") and vid in first_dir:
                turn = f"rotate({fmt(-first_dir[vid])} {x} {y})"
            marks.append("    " + element("image", [
                ("xlink:href", cv.href(style["image"])), ("x", fmt(xy[v, 0] - s)),
                ("y", fmt(-xy[v, 1] - s)), ("width", fmt(2 * s)), ("height", fmt(2 * s)),
                ("transform", turn)]))
        marker = style.get("marker", "circle" if ("size" in style or "fill" in style) else "none")
        if marker == "none":
            continue
        size = float(style.get("size", 4 * STROKE_WIDTH * cv.unit))
        key = (marker, size, style.get("fill", "#1a1a1a"), style.get("stroke", "none"))
        if key not in shapes:
            shapes[key] = f"marker{len(shapes)}"
            cv.defs.append("    " + element("g", [("id", shapes[key])],
                                            _marker(*key, fmt, cv.unit)))
        marks.append("    " + element("use", [("xlink:href", f"#{shapes[key]}"), ("x", x),
                                              ("y", y)]))
    return ['  <g id="vertices">'] + marks + ["  </g>"] if marks else []


def _marker(shape: str, size: float, fill: str, stroke: str, fmt, unit: float) -> str:
    """A marker of the given size centred on the origin."""
    r = size / 2
    paint = [("fill", fill), ("stroke", stroke), ("stroke-width", fmt(STROKE_WIDTH * unit / 2))]
    if shape == "circle":
        return element("circle", [("r", fmt(r))] + paint)
    if shape == "square":
        return element("rect", [("x", fmt(-r)), ("y", fmt(-r)), ("width", fmt(size)),
                                ("height", fmt(size))] + paint)
    if shape == "diamond":
        return element("path", [("d", f"M 0,{fmt(-r)} L {fmt(r)},0 L 0,{fmt(r)} L {fmt(-r)},0 Z")]
                       + paint)
    if shape == "triangle":
        h = r * math.sqrt(3) / 2
        return element("path", [("d", f"M 0,{fmt(-r)} L {fmt(h)},{fmt(r / 2)} "
                                      f"L {fmt(-h)},{fmt(r / 2)} Z")] + paint)
    # cross: drawn with the fill colour, as it has no inside.
    return element("path", [("d", f"M {fmt(-r)},{fmt(-r)} L {fmt(r)},{fmt(r)} M {fmt(-r)},{fmt(r)} "
                                  f"L {fmt(r)},{fmt(-r)}"), ("fill", "none"), ("stroke", fill),
                            ("stroke-width", fmt(size / 5))])


def _edge_images(xy, ends, edges, style, unit, fmt, href) -> list[str]:
    """Copies of the edge image along each edge, `spacing` apart, turned with the edge."""
    step = float(style.get("spacing", unit / 4))
    link = href(style["image"])
    out = []
    for i in edges:
        a, b = xy[ends[i, 0]], xy[ends[i, 1]]
        length = float(np.hypot(*(b - a)))
        n = max(1, int(length // step))
        angle = math.degrees(math.atan2(b[1] - a[1], b[0] - a[0]))
        for j in range(n):
            c = a + (b - a) * ((j + 0.5) / n)
            x, y = fmt(c[0]), fmt(-c[1])
            out.append("    " + element("image", [
                ("xlink:href", link), ("x", fmt(c[0] - step / 2)), ("y", fmt(-c[1] - step / 2)),
                ("width", fmt(step)), ("height", fmt(step)),
                ("transform", f"rotate({fmt(-angle)} {x} {y})")]))
    return out


def _first_directions(drawing, xy, ends) -> dict[int, float]:
    """Each vertex's smallest outgoing direction in [-180, 180): its ring's first half-edge."""
    out: dict[int, float] = {}
    for i in range(len(ends)):
        for a, b in ((0, 1), (1, 0)):
            p, q = xy[ends[i, a]], xy[ends[i, b]]
            ang = math.degrees(math.atan2(q[1] - p[1], q[0] - p[0]))
            ang = (ang + 180.0) % 360.0 - 180.0
            vid = drawing.vertices[int(ends[i, a])].id
            if vid not in out or ang < out[vid]:
                out[vid] = ang
    return out


def write_svg(drawing: Drawing, reference, path: str | Path) -> None:
    """Render and write atomically, with image links relative to the file's folder."""
    p = Path(path)
    atomic_write(p, render_svg(drawing, reference, base=p.resolve().parent))
