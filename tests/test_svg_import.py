"""SVG import: shapes, path data, transforms, styles, labels, classes and diagnostics."""

from __future__ import annotations

import math

import pytest

from grammar_lang.diagnostics import UserError
from grammar_lang.planar import build_planar_graph
from grammar_lang.source import DEFAULT_CLASS, Region, Stroke
from grammar_lang.svg_import import import_svg
from grammar_lang.svg_colors import normalize_color
from grammar_lang.svg_paths import parse_path, parse_transform, SvgValueError

HEAD = '<svg xmlns="http://www.w3.org/2000/svg">\n'


def svg(body: str, head: str = HEAD) -> str:
    return head + body + "\n</svg>\n"


def load(body: str, **kw):
    return import_svg("drawing.svg", svg(body, **kw))


def fails(body: str, **kw) -> UserError:
    with pytest.raises(UserError) as info:
        load(body, **kw)
    return info.value


def close(points, expected, tol=1e-9):
    assert len(points) == len(expected)
    for (x, y), (ex, ey) in zip(points, expected):
        assert math.isclose(x, ex, abs_tol=tol) and math.isclose(y, ey, abs_tol=tol), \
            (points, expected)


# --- path data -------------------------------------------------------------------------------

def test_path_commands_absolute_and_relative():
    (sub,) = parse_path("M10 20 l5,0 h5 v-5 H10 V10 L 0 0")
    assert sub.points == [(10, 20), (15, 20), (20, 20), (20, 15), (10, 15), (10, 10), (0, 0)]
    assert not sub.closed


def test_path_implicit_lineto_subpaths_and_compact_numbers():
    subs = parse_path("m1,1 2,0 0,2z m-1-1.5.5.5e1Z")
    assert subs[0].points == [(1, 1), (3, 1), (3, 3)] and subs[0].closed
    # After z the current point is the subpath start (1,1); m is relative to it.
    assert subs[1].points == [(0, -0.5), (0.5, 4.5)] and subs[1].closed


def test_path_drawing_after_close_continues_from_the_start():
    subs = parse_path("M0 0 L4 0 L4 4 Z L0 4")
    assert subs[1].points == [(0, 0), (0, 4)]


@pytest.mark.parametrize("d, offset", [("M0 0 C1 1 2 2 3 3", 5), ("M0 0 L1 1 a1 1 0 0 1 2 2", 10),
                                       ("M0 0 Q1 1 2 2", 5), ("M0 0 s1 1 2 2", 5)])
def test_curves_are_refused_with_a_flattening_hint(d, offset):
    with pytest.raises(SvgValueError) as info:
        parse_path(d)
    assert info.value.offset == offset
    assert "Flatten Beziers" in info.value.hint


@pytest.mark.parametrize("d", ["L1 1", "M0", "M0 0 L1", "M 0 0 X 1", "M1e999 0"])
def test_bad_path_data(d):
    with pytest.raises(SvgValueError):
        parse_path(d)


def test_curve_diagnostic_points_into_the_d_attribute():
    err = fails('  <path d="M 0,0 L 10,0 C 1 1 2 2 3 3" fill="none" stroke="#000"/>')
    d = err.diagnostics[0]
    assert (d.span.line, d.span.column) == (2, 25)
    assert "Flatten Beziers" in d.hint
    assert "^" in d.render()


# --- transforms ------------------------------------------------------------------------------

def test_transform_lists_compose_left_to_right():
    m = parse_transform("translate(10, 20) scale(2) rotate(90)")
    x, y = (m @ [1.0, 0.0, 1.0])[:2]
    assert math.isclose(x, 10) and math.isclose(y, 22)
    m = parse_transform("rotate(90 5 5)")
    assert all(math.isclose(a, b, abs_tol=1e-12) for a, b in zip(m @ [5.0, 0.0, 1.0], [10, 5, 1]))
    m = parse_transform("matrix(1 2 3 4 5 6) skewX(45) skewY(0)")
    assert all(math.isclose(a, b) for a, b in zip(m @ [1.0, 1.0, 1.0], [10, 14, 1]))


@pytest.mark.parametrize("text", ["translate(1,2", "spin(3)", "scale()", "matrix(1 2 3)", "rotate(1 2)"])
def test_bad_transforms(text):
    with pytest.raises(SvgValueError):
        parse_transform(text)


def test_nested_groups_compose_transforms_and_flip_y():
    src = load('<g transform="translate(100,0)"><g transform="scale(2,3)">'
               '<line x1="1" y1="1" x2="2" y2="1"/></g></g>')
    (stroke,) = src.paint
    close(stroke.points, [(102, -3), (104, -3)])


def test_skew_and_matrix_on_shapes():
    src = load('<polygon transform="skewX(45)" points="0,0 1,0 1,1" fill="red"/>'
               '<polyline transform="matrix(0 1 -1 0 0 0)" points="1,0 2,0" fill="none"/>')
    close(src.paint[0].rings[0], [(0, 0), (1, 0), (2, -1)])
    close(src.paint[1].points, [(0, -1), (0, -2)])


# --- shapes, labels and classes ----------------------------------------------------------------

def test_filled_shapes_become_regions_in_painting_order():
    src = load('<rect x="0" y="0" width="10" height="5" fill="#C0F0FF"/>\n'
               '<polygon points="0,0 5,0 5,5" style="fill: rgb(255, 0, 0); stroke:#000"/>\n'
               '<path d="M0 0 H4 V4 Z" fill="navy" data-label="water"/>\n'
               '<path d="M0 0 H4 V4 Z M1 1 H2 V2 Z" fill="#abc" fill-rule="evenodd"/>')
    labels = [p.label for p in src.paint]
    assert labels == ["#c0f0ff", "#ff0000", "water", "#aabbcc"]
    assert all(isinstance(p, Region) for p in src.paint)
    close(src.paint[0].rings[0], [(0, 0), (10, 0), (10, -5), (0, -5)])
    assert src.paint[3].evenodd and len(src.paint[3].rings) == 2
    assert set(src.face_labels) == set(labels)


def test_unfilled_shapes_and_lines_become_strokes_with_classes():
    src = load('<line x1="0" y1="0" x2="1" y2="0" stroke="#000000"/>\n'
               '<line x1="0" y1="0" x2="1" y2="0"/>\n'
               '<line x1="0" y1="0" x2="1" y2="0" stroke="#FF3232"/>\n'
               '<line x1="0" y1="0" x2="1" y2="0" stroke="#ff3232" data-class="1"/>\n'
               '<polyline points="0,0 1,1 2,0" fill="none" stroke="black"/>\n'
               '<path d="M0 0 L1 0 L1 1 Z" style="fill:none;stroke:#0f0"/>')
    assert all(isinstance(p, Stroke) for p in src.paint)
    assert [p.cls for p in src.paint] == [DEFAULT_CLASS, DEFAULT_CLASS, "#ff3232", "1",
                                          DEFAULT_CLASS, "#00ff00"]
    assert [p.closed for p in src.paint] == [False] * 5 + [True]
    assert set(src.classes) == {DEFAULT_CLASS, "#ff3232", "1", "#00ff00"}


def test_filled_shape_with_a_classed_outline_is_a_region_and_a_stroke():
    src = load('<polygon points="0,0 4,0 4,4" fill="#fff" stroke="red"/>')
    region, stroke = src.paint
    assert isinstance(region, Region) and isinstance(stroke, Stroke)
    assert stroke.cls == "#ff0000" and stroke.closed
    graph = build_planar_graph(src)
    assert {e[4] for e in graph.edges} == {"#ff0000"}


def test_styles_inherit_and_style_beats_attributes():
    src = load('<g fill="blue" style="stroke:red" data-class="wall">'
               '<rect width="1" height="1"/>'
               '<rect width="1" height="1" fill="green" style="fill:yellow"/>'
               '<polyline points="0,0 1,1" fill="inherit" style="fill:none"/></g>')
    labels = [p.label for p in src.paint if isinstance(p, Region)]
    assert labels == ["#0000ff", "#ffff00"]
    assert {p.cls for p in src.paint if isinstance(p, Stroke)} == {"wall"}


def test_default_fill_is_black_and_hidden_elements_are_skipped():
    src = load('<polygon points="0,0 1,0 1,1"/>'
               '<g style="display:none"><rect width="3" height="3" fill="red"/></g>'
               '<rect width="3" height="3" fill="red" visibility="hidden"/>'
               '<defs><rect width="3" height="3" fill="red"/></defs>'
               '<text x="0" y="0">note</text>')
    assert [p.label for p in src.paint] == ["#000000"]


def test_flat_polyline_with_the_implicit_fill_is_only_a_line():
    src = load('<polyline points="0,0 1,1 2,2 3,3" stroke="red"/>'
               '<polyline points="0,0 1,1 2,0"/>')
    assert isinstance(src.paint[0], Stroke) and src.paint[0].cls == "#ff0000"
    assert isinstance(src.paint[1], Region)
    assert all(y == 0.0 and str(y) == "0.0" for p in src.paint[:1] for _, y in p.points[:1])


def test_title_names_the_example_else_the_file_stem():
    assert load("<title> My Shape </title><line x2='1'/>").name == "My Shape"
    assert load("<line x2='1'/>").name == "drawing"


def test_prefixed_svg_namespace_and_editor_metadata():
    head = ('<?xml version="1.0" encoding="ISO-8859-1"?>\n<svg:svg xmlns:svg="http://www.w3.org/2000/svg" '
            'xmlns:sodipodi="http://sodipodi.sourceforge.net/DTD/sodipodi-0.dtd">\n'
            '<sodipodi:namedview pagecolor="#fff"/>\n')
    text = head + '<svg:g><svg:line x2="1"/></svg:g>\n</svg:svg>\n'
    src = import_svg("x.svg", text)
    assert len(src.paint) == 1


def test_units_on_coordinates():
    (stroke,) = load('<line x1="1in" y1="0" x2="96px" y2="72pt"/>').paint
    close(stroke.points, [(96, 0), (96, -96)])


def test_colours():
    assert normalize_color("#ABC") == "#aabbcc"
    assert normalize_color("Crimson") == "#dc143c"
    assert normalize_color("rgb(100%, 0%, 50%)") == "#ff0080"
    assert normalize_color("#11223344") == "#112233"
    assert normalize_color("bogus") is None


# --- diagnostics -------------------------------------------------------------------------------

@pytest.mark.parametrize("body, message, line", [
    ('<line x2="1"/>\n  <rect width="2" height="2" fill="#12"/>', "fill colour", 3),
    ('\n<circle r="4"/>', "curve", 3),
    ('<rect width="0" height="2"/>', "zero or negative size", 2),
    ('<rect width="5" height="2" rx="1"/>', "rounded corners", 2),
    ('<use href="#a"/>', "clone", 2),
    ('<style>rect { fill: red }</style>', "style sheets", 2),
    ('<polygon points="0,0 1"/>', "odd number", 2),
    ('<line x2="1" transform="rotate(1,2)"/>', "transform", 2),
    ('<line x1="5%" x2="1"/>', "unit", 2),
    ('<rect width="1" height="1" fill="url(#grad)"/>', "gradient", 2),
    ('<g></g>', "no shapes", 1),
])
def test_diagnostics_point_at_the_element(body, message, line):
    err = fails(body)
    d = err.diagnostics[0]
    assert message in d.message
    assert d.span.file == "drawing.svg" and d.span.line == line and d.span.column >= 1


@pytest.mark.parametrize("body", [
    '<polyline points="0,0 1e200,1e200 3e200,-1e200"/>',          # the implicit fill's area test
    '<polygon points="0,0 2e13,0 0,1" fill="red"/>',
    '<path d="M 0 0 L 1 1 L 1e300 -1e300 Z"/>',
    '<line x2="1" transform="scale(1e13)"/>',                       # huge only after the transform
])
def test_huge_coordinates_are_a_located_error_without_warnings(body):
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")              # a numpy overflow warning fails the test
        d = fails(body).diagnostics[0]
    assert "coordinates beyond" in d.message and "scale the drawing down" in d.hint
    assert (d.span.file, d.span.line) == ("drawing.svg", 2)


def test_coordinates_at_the_limit_are_read():
    src = load('<polyline points="0,0 1e12,0 1e12,-1e12" fill="none"/>')
    assert max(abs(c) for pt in src.paint[0].points for c in pt) == 1e12


def test_gradient_fill_with_a_data_label_is_fine():
    src = load('<rect width="1" height="1" fill="url(#grad)" data-label="sky"/>')
    assert src.paint[0].label == "sky"


@pytest.mark.parametrize("text, message", [
    ("", "not well-formed"),
    ("<svg", "not well-formed"),
    ("<html xmlns='http://www.w3.org/1999/xhtml'/>", "not an SVG"),
    ("<svg xmlns='http://www.w3.org/2000/svg'><line></svg>", "not well-formed"),
])
def test_broken_files(text, message):
    with pytest.raises(UserError, match=message):
        import_svg("bad.svg", text)


def test_xml_error_columns_count_characters():
    text = '<svg xmlns="http://www.w3.org/2000/svg"><title>Ünïcödé</title> <line x2="1" <'
    with pytest.raises(UserError) as info:
        import_svg("bad.svg", text)
    span = info.value.diagnostics[0].span
    assert span.line == 1 and text[span.column - 1] == "<" and span.column > 60
    text = '<svg xmlns="http://www.w3.org/2000/svg"><title>Ünïcödé</title> <rect fill="#1"/></svg>'
    with pytest.raises(UserError) as info:
        import_svg("bad.svg", text)
    span = info.value.diagnostics[0].span
    assert text[span.column - 1:].startswith("<rect")


def test_reads_files_from_disk(tmp_path):
    path = tmp_path / "shape.svg"
    path.write_text(svg('<line x2="3"/>'), encoding="utf-8")
    assert import_svg(path).name == "shape"
    with pytest.raises(UserError, match="no such file"):
        import_svg(tmp_path / "missing.svg")


INKSCAPE = """<?xml version="1.0" encoding="UTF-8" standalone="no"?>
<!-- Created with Inkscape (http://www.inkscape.org/) -->
<svg width="210mm" height="297mm" viewBox="0 0 210 297" version="1.1" id="svg5"
   inkscape:version="1.2.2 (b0a8486541, 2022-12-01)" sodipodi:docname="house.svg"
   xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape"
   xmlns:sodipodi="http://sodipodi.sourceforge.net/DTD/sodipodi-0.dtd"
   xmlns="http://www.w3.org/2000/svg" xmlns:svg="http://www.w3.org/2000/svg"
   xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#" xmlns:cc="http://creativecommons.org/ns#">
  <sodipodi:namedview id="namedview7" pagecolor="#ffffff" inkscape:zoom="0.7"/>
  <defs id="defs2"><linearGradient id="g1"><stop offset="0" style="stop-color:#fff"/></linearGradient></defs>
  <metadata><rdf:RDF><cc:Work rdf:about=""><dc:title xmlns:dc="http://purl.org/dc/elements/1.1/">x</dc:title></cc:Work></rdf:RDF></metadata>
  <g inkscape:label="Layer 1" inkscape:groupmode="layer" id="layer1" transform="translate(-20,-30)">
    <path style="fill:#c0f0ff;fill-opacity:1;stroke:#000000;stroke-width:0.264583px;stroke-opacity:1"
       d="m 40,150 h 120 v -80 H 40 Z" id="rect1" inkscape:label="walls"/>
    <path style="fill:#ffc0c0;stroke:#000000;stroke-width:0.264583px"
       d="M 40,70 100,10 160,70 Z" id="roof" sodipodi:nodetypes="cccc"/>
    <path style="fill:none;stroke:#ff3232;stroke-width:1px" d="m 100,150 v -40" id="door"
       data-class="door"/>
  </g>
  <g inkscape:label="Notes" inkscape:groupmode="layer" style="display:none">
    <text x="0" y="0">hidden notes</text><rect width="5" height="5" style="fill:#f00"/>
  </g>
</svg>
"""


def test_a_real_inkscape_document():
    src = import_svg("house.svg", INKSCAPE)
    assert src.name == "house"
    graph = build_planar_graph(src)
    assert len(graph.vertices) == 7 and len(graph.edges) == 8
    labels = {frozenset(e[2:4]) for e in graph.edges}
    assert labels == {frozenset(("#c0f0ff", "exterior")), frozenset(("#ffc0c0", "exterior")),
                      frozenset(("#c0f0ff", "#ffc0c0")), frozenset(("#c0f0ff",))}
    door = [e for e in graph.edges if e[4] == "door"]
    assert len(door) == 1
    assert sorted(graph.vertices[v] for v in door[0][:2]) == [(80.0, -120.0), (80.0, -80.0)]


def test_the_documented_example_means_what_the_doc_says():
    from pathlib import Path
    doc = (Path(__file__).resolve().parent.parent / "docs" / "svg-import.md").read_text()
    text = doc.split("```svg\n", 1)[1].split("```", 1)[0]
    src = import_svg("house.svg", text)
    graph = build_planar_graph(src)
    assert src.name == "House"
    assert {label for e in graph.edges for label in e[2:4]} == {"#c0f0ff", "roof", "exterior"}
    (door,) = [e for e in graph.edges if e[4] == "door"]
    assert (280.0, -520.0) in [graph.vertices[v] for v in door[:2]]
    bottom = [e for e in graph.edges
              if {graph.vertices[e[0]][1], graph.vertices[e[1]][1]} == {-520.0}]
    assert len(bottom) == 2                      # the door splits the wall's bottom edge


def test_data_class_on_a_filled_shape_classes_its_outline():
    graph = build_planar_graph(load('<rect width="4" height="4" fill="#c0f0ff" stroke="#000" '
                                    'data-class="wall"/>'))
    assert {e[4] for e in graph.edges} == {"wall"}


def test_named_labels_and_classes_keep_the_colours_they_were_drawn_in():
    # Named apart from their colours (data-label, data-class), a label and a class keep the
    # drawing's colours as decorations: the commonest, the first drawn among equals.
    src = load('<rect width="4" height="4" fill="#c0f0ff" data-label="sky"/>'
               '<line x2="4" stroke="#00a000" data-class="stem"/>'
               '<line y2="4" stroke="#00a000" data-class="stem"/>'
               '<line x1="1" x2="4" stroke="red" data-class="stem"/>'
               '<line y1="1" y2="4" stroke="#123456" data-class="petal"/>'
               '<line x1="2" y1="2" x2="3" y2="3" stroke="#ff3232"/>')
    deco = {(d.kind, d.target): dict(d.props) for d in src.decorations}
    assert deco == {("face", "sky"): {"fill": "#c0f0ff"}, ("edge", "stem"): {"stroke": "#00a000"},
                    ("edge", "petal"): {"stroke": "#123456"}}
    tie = load('<line x2="4" stroke="#0000ff" data-class="a"/><line y2="4" stroke="red" data-class="a"/>')
    assert [dict(d.props) for d in tie.decorations] == [{"stroke": "#0000ff"}]
    # Labels and classes named by their colours need none.
    assert load('<rect width="4" height="4" fill="#c0f0ff"/>'
                '<line x2="4" stroke="#ff3232"/>').decorations == []
