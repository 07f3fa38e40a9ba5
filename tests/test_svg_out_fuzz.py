"""No value from an input file can add an attribute or an element to the SVG output.

Labels, class names, example names and decoration values are drawn from hostile text (quotes,
angle brackets, entities, control characters, lone surrogates are left to the readers) and the
written SVG is parsed back: it must be well-formed, hold only the elements and attributes the
writer makes, and carry each label exactly as given. Decorations are also fed through `.ggr`
text, where the schema must refuse what is not a colour, number, marker or image.
"""

from __future__ import annotations

import re
from pathlib import Path

import defusedxml.ElementTree as ET
from hypothesis import HealthCheck, given, settings, strategies as st

from grammar_lang.diagnostics import UserError
from grammar_lang.ggr_emit import emit_ggr
from grammar_lang.ggr_parser import parse_ggr
from grammar_lang.rules import Grammar, Header
from grammar_lang.source import Decoration, EdgeClass
from grammar_lang.vocabulary import Vocabulary
from grammar_lang.xml_text import xml_text
from runtime.output.drawing import DEdge, Drawing, DVertex
from runtime.output.svg_out import render_svg

SVG = "{http://www.w3.org/2000/svg}"
XLINK = "{http://www.w3.org/1999/xlink}href"
TAGS = {"svg", "title", "defs", "g", "path", "pattern", "image", "use", "circle", "rect"}
ATTRS = {"xmlns", "viewBox", "width", "height", "id", "d", "fill", "fill-rule", "fill-opacity",
         "stroke", "stroke-width", "stroke-opacity", "stroke-linecap", "stroke-linejoin",
         "data-label", "data-class", "patternUnits", XLINK, "x", "y", "r", "transform"}
HOSTILE = ['"', "'", "<", ">", "&", "&amp;", "&#34;", '" onload="x', "'/><script>x</script>",
           "]]>", "<!--", "\n", "\t", "\r", " ", "=", "/", "\\", "url(", ")", ";", "é", "#fff"]
# XML 1.0 cannot hold most C0 controls or lone surrogates at all; readers refuse them first.
xml_char = st.characters(blacklist_categories=("Cs",), min_codepoint=0x20) | st.sampled_from("\t\n")
# What a writer is handed may hold any of them, and U+FFFE too (a .ggr string spells any code
# point): it writes U+FFFD for each (grammar_lang.xml_text).
NOT_XML = ["\x00", "\x01", "\x1f", "\ufffe", "\uffff", "\ud800"]
hostile = st.lists(st.sampled_from(HOSTILE + NOT_XML) | st.text(xml_char, max_size=4),
                   min_size=1, max_size=5).map("".join)
FUZZ = settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def check_structure(svg: str, labels: set[str], classes: set[str]) -> None:
    root = ET.fromstring(svg)
    for el in root.iter():
        tag = el.tag.removeprefix(SVG)
        assert tag in TAGS, tag
        assert set(el.attrib) <= ATTRS, set(el.attrib) - ATTRS
        if "data-label" in el.attrib:
            assert el.attrib["data-label"] in {xml_text(s) for s in labels}
        if "data-class" in el.attrib:
            assert el.attrib["data-class"] in {xml_text(s) for s in classes}
    assert not list(root.iter("script")) and not list(root.iter(f"{SVG}script"))


def square(left: str, right: str, cls: str) -> Drawing:
    vs = tuple(DVertex(i, float(x), float(y)) for i, (x, y) in enumerate([(0, 0), (1, 0), (1, 1),
                                                                          (0, 1)]))
    es = tuple(DEdge(i, (i + 1) % 4, left, right, cls) for i in range(4))
    return Drawing(vs, es, {"example": left})


@FUZZ
@given(label=hostile, exterior=hostile, cls=hostile, name=hostile, fill=hostile, stroke=hostile,
       marker=hostile, image=hostile)
def test_hostile_names_and_raw_decorations_stay_inside_their_attributes(
        tmp_path_factory, label, exterior, cls, name, fill, stroke, marker, image):
    """Even decorations that skipped validation are escaped: escaping alone is enough.
    (Image paths are absolute once checked, so they are made absolute here.)"""
    base = tmp_path_factory.mktemp("svg")
    image = f"{base}/{image}"
    decos = (Decoration("face", "*", (("fill", fill), ("pattern", image))),
             Decoration("edge", "*", (("stroke", stroke), ("image", image))),
             Decoration("vertex", "*", (("marker", marker), ("fill", fill), ("stroke", stroke),
                                        ("image", image))))
    vocabulary = Vocabulary(exterior, (label, exterior), (EdgeClass(cls, 0.1, 10.0),))
    header = Header(source=name, vocabulary=vocabulary, decorations=decos)
    svg = render_svg(square(label, exterior, cls), header, base=base)
    check_structure(svg, {label, exterior}, {cls})


ROOT = Path(__file__).resolve().parent.parent
GGR = (ROOT / "examples" / "square-walls.ggr").read_text(encoding="utf-8")
# Decorations follow the primitives; a line appended at the end is one.
LINE = GGR.count("\n") + 1


@FUZZ
@given(kind=st.sampled_from(["face", "edge", "vertex"]),
       key=st.sampled_from(["fill", "stroke", "opacity", "width", "marker", "size", "image",
                            "pattern", "onmouseover", "style"]),
       value=hostile | st.sampled_from(["red", "#c0f0ff", "0.5", "circle", "1e-320"]))
def test_ggr_decoration_values_are_checked_by_the_gg_schema(kind, key, value):
    """A `.ggr` decoration holds a colour, a number in range, a marker or an image, or the
    file is refused at the value with a located diagnostic; what loads draws safe SVG."""
    quoted = '"' + value.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") \
        .replace("\t", "\\t").replace("\r", "\\r") + '"'
    text = GGR + f"decorate {kind} * {key}={quoted}\n"
    if kind == "vertex" and key in ("fill", "stroke") and value == "red":
        assert parse_ggr(text).header.decorations[0].props == ((key, "#ff0000"),)
    try:
        grammar = parse_ggr(text, "fuzz.ggr")
    except UserError as exc:
        assert [d.span.line for d in exc.diagnostics] == [LINE]
        return
    deco = grammar.header.decorations[0]
    for k, v in deco.props:
        if k in ("fill", "stroke"):
            assert re.fullmatch(r"#[0-9a-f]{6}", v)
        if k in ("opacity", "width", "size"):
            assert isinstance(v, float)
    svg = render_svg(square("exterior", "exterior", "0"), grammar)
    check_structure(svg, {"exterior"}, {"0"})
    assert parse_ggr(emit_ggr(grammar)) == grammar


def test_the_reported_injections_are_refused():
    for line in ['decorate edge * stroke="red\\" onmouseover=\\"alert(1)"',
                 'decorate face * fill="red\\" onmouseover=\\"alert(1)"',
                 'decorate vertex * fill="red\\"/><script>alert(1)</script><x a=\\""',
                 'decorate face * opacity="0.5"']:
        try:
            parse_ggr(GGR + line + "\n", "bad.ggr")
        except UserError as exc:
            assert exc.diagnostics[0].span.line == LINE
        else:
            raise AssertionError(f"accepted: {line}")


@FUZZ
@given(label=st.text(xml_char.filter(lambda c: c not in '"\\\n'), min_size=1, max_size=8),
       cls=st.text(xml_char.filter(lambda c: c not in '"\\\n'), min_size=1, max_size=8))
def test_gg_labels_and_classes_stay_inside_their_attributes(tmp_path_factory, label, cls):
    """From a `.gg` file through the loader and the writer."""
    from grammar_lang.loader import load_example
    from runtime.output.drawing import drawing_from_example
    src = (f'example "{label}"\nclass "{cls}" {{ }}\n'
           f'polygon "{label}" (0, 0) (10, 0) (10, 10) (0, 10) class "{cls}"\n')
    path = Path(tmp_path_factory.mktemp("gg")) / "x.gg"
    path.write_text(src, encoding="utf-8")
    try:
        ex = load_example(path)
    except UserError:
        return
    d = drawing_from_example(ex)
    check_structure(render_svg(d, ex), {e.left for e in d.edges} | {e.right for e in d.edges},
                    {e.cls for e in d.edges})


def test_valid_ggr_decorations_load_and_draw():
    grammar = parse_ggr(GGR + "decorate edge * stroke=red opacity=0.5 width=2\n")
    assert grammar.header.decorations[0].props == (("stroke", "#ff0000"), ("opacity", 0.5),
                                                   ("width", 2.0))
    svg = render_svg(square("exterior", "exterior", "0"), grammar)
    assert 'stroke="#ff0000" stroke-width="2" stroke-opacity="0.5"' in svg


@FUZZ
@given(label=hostile, cls=hostile, name=hostile)
def test_graphml_holds_any_name(tmp_path_factory, label, cls, name):
    """GraphML is XML too: any name reads back, with U+FFFD for what XML cannot hold."""
    import networkx as nx
    from runtime.output.graphml_out import write_graphml
    drawing = square(label, "exterior", cls)
    drawing = Drawing(drawing.vertices, drawing.edges, {"grammar": name})
    path = tmp_path_factory.mktemp("graphml") / "d.graphml"
    write_graphml(drawing, path)
    g = nx.read_graphml(path)

    def read(text: str) -> str:         # and a reader makes every line end a line feed
        return xml_text(text).replace("\r\n", "\n").replace("\r", "\n")

    assert g.graph["grammar"] == read(name)
    assert {d["left"] for _, _, d in g.edges(data=True)} == {read(label)}
    assert {d["class"] for _, _, d in g.edges(data=True)} == {read(cls)}


@FUZZ
@given(text=st.lists(st.sampled_from(NOT_XML) | st.text(max_size=4), max_size=6).map("".join))
def test_xml_text_is_always_xml(text):
    """Whatever a name holds, escaped after xml_text it reads back as XML, in an attribute and
    as content, the report's escaping too."""
    from xml.sax.saxutils import escape, quoteattr
    from report.markup import esc
    safe = xml_text(text)
    assert len(safe) == len(text)
    root = ET.fromstring(f"<a b={quoteattr(safe)} c=\"{esc(text)}\">{escape(safe)}{esc(text)}</a>")
    assert root.get("b") == safe
