"""SVG output: what it draws is what the importer reads back, decorations are applied, and the
text is deterministic."""

import re
from dataclasses import replace

import defusedxml.ElementTree as ET
import numpy as np
import pytest
from hypothesis import given, strategies as st
from scipy.spatial import cKDTree

from conftest import corpus_names
from grammar_lang.loader import load_example, load_source
from grammar_lang.planar import build_planar_graph
from runtime.output.drawing import Drawing, DVertex, drawing_from_example
from grammar_lang.svg_colors import contrast, same_colour
from runtime.output.svg_out import (FILL_PALETTE, LEGIBLE, STROKE_PALETTE, legible_stroke,
                                   render_svg, write_svg)
from test_verifier import example, inner_faces, nested_copy, own_drawing, transformed, union

SVG = "{http://www.w3.org/2000/svg}"
XLINK = "{http://www.w3.org/1999/xlink}href"


def edge_key(u, v, left, right, cls):
    return (u, v, left, right, cls) if u < v else (v, u, right, left, cls)


def drawing_edges(d: Drawing):
    return {edge_key(e.u, e.v, e.left, e.right, e.cls) for e in d.edges}


def read_back(tmp_path, d, ref, name="out.svg"):
    """The edges the importer finds in the written SVG, named by the drawing's vertex ids."""
    path = tmp_path / name
    write_svg(d, ref, path)
    g = build_planar_graph(load_source(path))
    ids = [v.id for v in d.vertices]
    pts = np.array([(v.x, v.y) for v in d.vertices])
    dist, nearest = cKDTree(pts).query(np.array(g.vertices))
    assert dist.max() < 1e-3 * np.ptp(pts, axis=0).max()
    assert len(set(nearest.tolist())) == len(g.vertices) == len(d.vertices)
    return {edge_key(ids[nearest[u]], ids[nearest[v]], left, right, cls)
            for u, v, left, right, cls in g.edges}


@pytest.mark.parametrize("name", corpus_names())
def test_corpus_drawings_read_back_as_drawn(tmp_path, name):
    d = own_drawing(name)
    assert read_back(tmp_path, d, example(name)) == drawing_edges(d)


@pytest.mark.parametrize("name", ["square-hollow", "house-hollow", "star-hollow"])
def test_nested_copies_read_back_as_drawn(tmp_path, name):
    """A copy inside an exterior-labelled hole: the hole stays unpainted around it."""
    d = own_drawing(name)
    _, poly = max(inner_faces(d), key=lambda lp: lp[1].area)
    both, _ = nested_copy(d, poly)
    assert read_back(tmp_path, both, example(name)) == drawing_edges(both)


def test_a_face_with_a_hole_reads_back(tmp_path, decorated):
    """The pond is cut out of the lawn, and painted itself. Face and edge decorations keep the
    picture readable; vertex markers (clones) and a painted exterior (a background with the
    viewBox's outline) would not be, so they are left out here."""
    ex = replace(decorated, decorations=tuple(
        x for x in decorated.decorations if x.kind != "vertex" and x.target != "exterior"))
    d = drawing_from_example(ex)
    assert read_back(tmp_path, d, ex) == drawing_edges(d)


def test_many_copies_and_classes_read_back(tmp_path):
    d = own_drawing("h-complex")          # two edge classes
    grid = d
    for k in range(1, 4):
        grid = union(grid, transformed(d, lambda q: q + np.array([k * 1000.0, k * 37.0])))
    assert read_back(tmp_path, grid, example("h-complex")) == drawing_edges(grid)


def parse(text):
    return ET.fromstring(text)


def test_y_points_up_and_the_viewbox_fits():
    d = own_drawing("house-filled")
    root = parse(render_svg(d, example("house-filled")))
    x0, y0, w, h = map(float, root.get("viewBox").split())
    xs = [v.x for v in d.vertices]
    ys = [-v.y for v in d.vertices]             # screen y
    assert x0 < min(xs) and max(xs) < x0 + w and y0 < min(ys) and max(ys) < y0 + h
    margin = min(min(xs) - x0, x0 + w - max(xs), min(ys) - y0, y0 + h - max(ys))
    assert margin == pytest.approx(0.05 * max(max(xs) - min(xs), max(ys) - min(ys)))
    # The roof (the face above the walls in the example) is higher on screen.
    faces = {p.get("data-label"): p.get("d") for p in root.iter(f"{SVG}path") if p.get("data-label")}
    top = lambda d_: min(float(t.split(",")[1]) for t in d_.split() if "," in t)
    assert top(faces["#ffc0c0"]) < top(faces["#c0f0ff"])


def test_output_is_deterministic():
    for name in ("star-filled", "triangle-complex"):
        d = own_drawing(name)
        assert render_svg(d, example(name)) == render_svg(d, example(name))
        copy = Drawing(tuple(DVertex(v.id, v.x, v.y) for v in d.vertices), d.edges, {})
        assert render_svg(copy, example(name)) == render_svg(d, example(name))


def test_numbers_have_fixed_precision_without_exponents():
    d = transformed(own_drawing("triangle"), lambda q: q * 1e-4 + 1e-7)
    text = render_svg(d, None)
    assert not re.search(r"\d[eE][-+]?\d", text)
    parse(text)


def test_colours_from_labels_and_palette():
    # Labels that are not colours get palette colours by order; the exterior stays unpainted.
    d = own_drawing("house-filled")
    renamed = {"#c0f0ff": "wall", "#ffc0c0": "roof"}
    plain = replace(d, edges=tuple(replace(e, left=renamed.get(e.left, e.left),
                                           right=renamed.get(e.right, e.right), label=None)
                                   for e in d.edges))
    root = parse(render_svg(plain, None))
    fills = {p.get("data-label"): p.get("fill") for p in root.iter(f"{SVG}path") if p.get("data-label")}
    assert set(fills) == {"wall", "roof"}
    assert set(fills.values()) <= set(FILL_PALETTE) and len(set(fills.values())) == 2
    root = parse(render_svg(d, example("house-filled")))
    fills = {p.get("data-label"): p.get("fill") for p in root.iter(f"{SVG}path") if p.get("data-label")}
    assert fills == {"#c0f0ff": "#c0f0ff", "#ffc0c0": "#ffc0c0"}


DECORATED = """\
face lawn #7fae5a
face pond
face exterior { fill: #fafafa }
class path { min: 20 }
polygon lawn rect (0, 0) (200, 120)
polygon pond rect (20, 20) (60, 50)
polyline (0, 60) (200, 60) class path
decorate face lawn { fill: yellowgreen; opacity: 90% }
decorate face pond { pattern: "water.png"; pattern-scale: 0.5 }
decorate edge path { stroke: "rgb(120, 90, 60)"; width: 4 }
decorate edge *    { stroke: black; width: 1 }
decorate vertex *  { marker: circle; size: 3; fill: black }
"""


@pytest.fixture
def decorated(tmp_path):
    (tmp_path / "water.png").write_bytes(b"\x89PNG\r\n\x1a\n")
    src = tmp_path / "pond.gg"
    src.write_text(DECORATED)
    return load_example(src)


def test_decorations_are_drawn(tmp_path, decorated):
    ex = decorated
    d = drawing_from_example(ex)
    out = tmp_path / "sub" / "pond.svg"
    write_svg(d, ex, out)
    text = out.read_text()
    root = parse(text)
    paths = list(root.iter(f"{SVG}path"))
    faces = [p for p in paths if p.get("data-label")]
    lawn = [p for p in faces if p.get("data-label") == "lawn"]
    assert len(lawn) == 2 and all(p.get("fill") == "#9acd32" and p.get("fill-opacity") == "0.9"
                                  for p in lawn)
    pond = [p for p in faces if p.get("data-label") == "pond"]
    assert pond[0].get("fill") == "url(#pattern0)"
    pattern = next(root.iter(f"{SVG}pattern"))
    assert float(pattern.get("width")) == pytest.approx(0.5 * ex.unit)   # pattern-scale × unit
    assert next(pattern.iter(f"{SVG}image")).get(XLINK) == "../water.png"
    # The exterior's decoration paints a background with the drawing cut out of it.
    assert [p.get("fill") for p in faces if p.get("data-label") == "exterior"] == ["#fafafa"]
    strokes = {p.get("data-class"): (p.get("stroke"), p.get("stroke-width"))
               for p in paths if p.get("data-class")}
    # A named target beats '*', whatever their order.
    assert strokes == {"0": ("#000000", "1"), "path": ("#785a3c", "4")}
    uses = list(root.iter(f"{SVG}use"))
    assert len(uses) == len(d.vertices)
    assert next(root.iter(f"{SVG}circle")).get("r") == "1.5"


def test_vertex_decorations_follow_primitives(decorated):
    from grammar_lang.source import Decoration
    ex = decorated
    first = ex.primitives[0]
    ex = replace(ex, decorations=(Decoration("vertex", first.name, (("marker", "square"),
                                                                      ("size", 2.0))),))
    d = drawing_from_example(ex)
    root = parse(render_svg(d, ex))
    uses = list(root.iter(f"{SVG}use"))
    assert len(uses) == first.count
    assert len(list(root.iter(f"{SVG}rect"))) == 1        # one shared marker definition


def test_empty_and_single_point_drawings():
    for d in (Drawing((), ()), Drawing((DVertex(0, 3.0, 4.0),), ())):
        root = parse(render_svg(d, None))
        assert len(root.get("viewBox").split()) == 4
        assert all(float(x) > 0 for x in root.get("viewBox").split()[2:])


def test_stroke_widths_scale_with_the_unit():
    d = own_drawing("square-hollow")
    small = transformed(d, lambda q: q / 100)
    w = lambda text: float(next(p for p in parse(text).iter(f"{SVG}path")
                                if p.get("data-class")).get("stroke-width"))
    assert w(render_svg(small, None)) == pytest.approx(w(render_svg(d, None)) / 100)


def test_edge_and_vertex_images(tmp_path, decorated):
    from grammar_lang.source import Decoration
    for f in ("rope.svg", "lamp.svg"):
        (tmp_path / f).write_text('<svg xmlns="http://www.w3.org/2000/svg"/>')
    ex = decorated
    corner = next(p for p in ex.primitives if len(p.ring) == 2)
    ex = replace(ex, decorations=(
        Decoration("edge", "path", (("image", str(tmp_path / "rope.svg")), ("spacing", 10.0))),
        Decoration("vertex", corner.name, (("image", str(tmp_path / "lamp.svg")),
                                           ("scale", 2.0), ("rotate", True)))))
    d = drawing_from_example(ex)
    out = tmp_path / "pic.svg"
    write_svg(d, ex, out)
    root = parse(out.read_text())
    images = list(root.iter(f"{SVG}image"))
    rope = [i for i in images if i.get(XLINK) == "rope.svg"]
    lamps = [i for i in images if i.get(XLINK) == "lamp.svg"]
    path_edges = [e for e in d.edges if e.cls == "path"]
    pos = {v.id: np.array([v.x, v.y]) for v in d.vertices}
    along = sum(int(np.linalg.norm(pos[e.v] - pos[e.u]) // 10) for e in path_edges)
    assert len(rope) == along > 0
    assert all(i.get("width") == "10" and "rotate(" in i.get("transform") for i in rope)
    assert len(lamps) == corner.count
    assert all(float(i.get("width")) == pytest.approx(2 * ex.unit) for i in lamps)
    assert all(i.get("transform", "").startswith("rotate(") for i in lamps)


DRAWN = """\
shape from "drawn.svg"
class stem { min: 1 }
"""
DRAWN_SVG = ('<svg xmlns="http://www.w3.org/2000/svg">'
             '<rect width="40" height="40" fill="#c0f0ff" data-label="sky"/>'
             '<line x1="0" y1="20" x2="40" y2="20" stroke="#00a000" data-class="stem"/>'
             '<line x1="20" y1="0" x2="20" y2="20" stroke="#ff3232"/></svg>')


@pytest.mark.parametrize("user, stem, sky", [
    ("", "#00a000", "#c0f0ff"),
    ('decorate edge stem { stroke: black }\ndecorate face sky { fill: white }\n',
     "#000000", "#ffffff"),
    ('decorate edge * { stroke: blue }\n', "#0000ff", "#c0f0ff"),
])
def test_an_imported_drawing_keeps_its_colours_unless_decorated(tmp_path, user, stem, sky):
    (tmp_path / "drawn.svg").write_text(DRAWN_SVG)
    (tmp_path / "drawn.gg").write_text(DRAWN + user)
    ex = load_example(tmp_path / "drawn.gg")
    root = parse(render_svg(drawing_from_example(ex), ex))
    strokes = {p.get("data-class"): p.get("stroke") for p in root.iter(f"{SVG}path")
               if p.get("data-class")}
    fills = {p.get("data-label"): p.get("fill") for p in root.iter(f"{SVG}path")
             if p.get("data-label")}
    assert strokes["stem"] == stem and fills["sky"] == sky
    # A class named by its colour is drawn in it, unless a `*` decoration says otherwise.
    assert strokes["#ff3232"] == ("#0000ff" if "*" in user else "#ff3232")


HIDDEN = """\
face space #000001
face module #bdc7cf
class truss { min: 20 }
class rim { min: 20 }
polygon space rect (0, 0) (400, 200)
polygon module rect (100, 50) (200, 150)
polyline (200, 100) (350, 100) class truss
decorate edge truss { stroke: #000000 }
decorate edge rim { stroke: #000000 }
"""


def test_a_stroke_the_colour_of_every_face_beside_it_is_drawn_legibly(tmp_path):
    # A station's trusses, drawn black in its black space, could not be seen at all: such a
    # class is drawn in a palette stroke that stands out instead. A stroke that shows against
    # one face it borders (the module's rim, black on grey) is the user's to keep.
    src = tmp_path / "station.gg"
    src.write_text(HIDDEN.replace("(200, 150)\n", "(200, 150) class rim\n"))
    ex = load_example(src)
    root = parse(render_svg(drawing_from_example(ex), ex))
    strokes = {p.get("data-class"): p.get("stroke") for p in root.iter(f"{SVG}path")
               if p.get("data-class")}
    assert strokes["rim"] == "#000000"
    assert strokes["truss"] in STROKE_PALETTE
    assert contrast(strokes["truss"], "#000001") >= LEGIBLE


@given(st.lists(st.integers(0, 0xFFFFFF).map(lambda c: f"#{c:06x}"), min_size=1, max_size=4),
       st.integers(0, 20))
def test_a_palette_stroke_stands_out_where_one_can(fills, k):
    stroke = legible_stroke(k, set(fills))
    assert stroke in STROKE_PALETTE
    def worst(s):
        return min(contrast(s, f) for f in fills)
    if any(worst(s) >= LEGIBLE for s in STROKE_PALETTE):
        assert worst(stroke) >= LEGIBLE
    else:
        assert worst(stroke) == max(worst(s) for s in STROKE_PALETTE)
    if worst(STROKE_PALETTE[k % len(STROKE_PALETTE)]) >= LEGIBLE:
        assert stroke == STROKE_PALETTE[k % len(STROKE_PALETTE)]


def test_contrast_and_same_colour():
    assert contrast("black", "#ffffff") == pytest.approx(21.0)
    assert contrast("#123456", "#123456") == pytest.approx(1.0)
    assert contrast("url(#p)", "#ffffff") is None
    assert same_colour("#000000", "#000001") and same_colour("black", "#0a0a0a")
    assert not same_colour("#ffff00", "#ffffff") and not same_colour("red", "url(#p)")
