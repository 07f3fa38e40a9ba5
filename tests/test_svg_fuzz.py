"""Hostile and random SVG text: always a diagnostic (UserError), never another exception."""

from __future__ import annotations

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from conftest import CORPUS
from grammar_lang.diagnostics import UserError
from grammar_lang.planar import build_planar_graph
from grammar_lang.svg_import import import_svg

FUZZ = settings(max_examples=60, deadline=None, suppress_health_check=list(HealthCheck))

BILLION_LAUGHS = """<?xml version="1.0"?>
<!DOCTYPE svg [
  <!ENTITY lol "lol">
  <!ENTITY lol2 "&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;">
  <!ENTITY lol3 "&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;">
  <!ENTITY lol4 "&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;">
  <!ENTITY lol9 "&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;">
]>
<svg xmlns="http://www.w3.org/2000/svg"><title>&lol9;</title><line x2="1"/></svg>
"""

EXTERNAL_ENTITY = """<?xml version="1.0"?>
<!DOCTYPE svg [<!ENTITY secret SYSTEM "file:///etc/passwd">]>
<svg xmlns="http://www.w3.org/2000/svg"><title>&secret;</title><line x2="1"/></svg>
"""

PARAMETER_ENTITY = """<?xml version="1.0"?>
<!DOCTYPE svg [<!ENTITY % remote SYSTEM "http://127.0.0.1:9/evil.dtd"> %remote;]>
<svg xmlns="http://www.w3.org/2000/svg"><line x2="1"/></svg>
"""


@pytest.mark.parametrize("text", [BILLION_LAUGHS, EXTERNAL_ENTITY, PARAMETER_ENTITY],
                         ids=["billion-laughs", "external-entity", "parameter-entity"])
def test_entities_are_refused(text):
    with pytest.raises(UserError) as info:
        import_svg("evil.svg", text)
    d = info.value.diagnostics[0]
    assert "entit" in d.message.lower() or "external" in d.message.lower()
    assert d.span.line >= 1


def test_a_plain_doctype_is_accepted():
    text = ('<!DOCTYPE svg PUBLIC "-//W3C//DTD SVG 1.1//EN" '
            '"http://www.w3.org/Graphics/SVG/1.1/DTD/svg11.dtd">\n'
            '<svg xmlns="http://www.w3.org/2000/svg"><line x2="1"/></svg>')
    assert len(import_svg("ok.svg", text).paint) == 1


def run(text: str) -> None:
    """Import and build; a UserError must carry a place and render without failing."""
    try:
        build_planar_graph(import_svg("fuzz.svg", text))
    except UserError as exc:
        rendered = exc.render()
        assert rendered and "Traceback" not in rendered
        assert all(d.span is not None for d in exc.diagnostics)


@FUZZ
@given(st.text(max_size=300))
def test_random_text(text):
    run(text)


SEEDS = sorted(CORPUS.glob("*.svg"))
TOKENS = ["<", ">", "/>", '"', "'", "=", " ", "\n", "M", "m", "L", "l", "H", "v", "Z", "C", "A",
          "-", ".", "e", "1e308", "-1e-320", "0", "nan", "inf", ",", "#", "#fff", "none",
          'transform="scale(0)"', 'transform="rotate(45 1 1) skewX(90)"', 'fill-rule="evenodd"',
          'style="fill:none;stroke:red"', 'data-label=""', 'data-class="1"', "<g>", "</g>",
          "&amp;", "&bogus;", "<![CDATA[x]]>", "<!-- -->", "<?pi x?>", "\x00", "\ufeff", "é"]


@st.composite
def mutated_corpus_file(draw):
    text = draw(st.sampled_from(SEEDS)).read_text()
    for _ in range(draw(st.integers(1, 4))):
        i = draw(st.integers(0, len(text)))
        j = draw(st.integers(i, min(len(text), i + 40)))
        action = draw(st.sampled_from(["delete", "insert", "duplicate", "replace"]))
        token = draw(st.sampled_from(TOKENS))
        if action == "delete":
            text = text[:i] + text[j:]
        elif action == "insert":
            text = text[:i] + token + text[i:]
        elif action == "duplicate":
            text = text[:j] + text[i:j] + text[j:]
        else:
            text = text[:i] + token + text[j:]
    return text


@FUZZ
@given(mutated_corpus_file())
def test_mutated_corpus_files(text):
    run(text)


number = st.one_of(st.integers(-50, 50).map(str), st.floats(-1e6, 1e6, allow_nan=False).map(repr),
                   st.sampled_from(["1e400", "-0", ".5", "5.", "1e-30", "x"]))
colour = st.sampled_from(["none", "#000", "#000000", "red", "#ff3232", "rgb(1,2,3)", "url(#g)",
                          "currentColor", "inherit", "#c0f0ff", "bogus"])


@st.composite
def shape(draw):
    kind = draw(st.sampled_from(["line", "rect", "polygon", "polyline", "path", "g"]))
    attrs = {"fill": draw(colour), "stroke": draw(colour)}
    if kind == "line":
        attrs.update({k: draw(number) for k in ("x1", "y1", "x2", "y2")})
    elif kind == "rect":
        attrs.update({k: draw(number) for k in ("x", "y", "width", "height")})
    elif kind in ("polygon", "polyline"):
        attrs["points"] = " ".join(draw(st.lists(number, max_size=8)))
    elif kind == "path":
        parts = draw(st.lists(st.tuples(st.sampled_from("MmLlHhVvZzC"), number, number),
                              max_size=8))
        attrs["d"] = " ".join(f"{c} {x} {y}" for c, x, y in parts)
    if draw(st.booleans()):
        attrs["transform"] = draw(st.sampled_from(
            ["translate(3)", "scale(0)", "rotate(30 1 2)", "matrix(1 0 0 1 0 0)", "skewY(89)",
             "scale(1e200)", "bogus(1)"]))
    if draw(st.booleans()):
        attrs["fill-rule"] = "evenodd"
    body = " ".join(f'{k}="{v}"' for k, v in attrs.items())
    if kind == "g":
        return f"<g {body}>{''.join(draw(st.lists(shape(), max_size=3)))}</g>"
    return f"<{kind} {body}/>"


@FUZZ
@given(st.lists(shape(), min_size=1, max_size=6))
def test_random_drawings(shapes):
    run('<svg xmlns="http://www.w3.org/2000/svg">\n' + "\n".join(shapes) + "\n</svg>")


def test_deep_nesting_is_refused_politely():
    text = ('<svg xmlns="http://www.w3.org/2000/svg">' + "<g>" * 5000 + '<line x2="1"/>'
            + "</g>" * 5000 + "</svg>")
    with pytest.raises(UserError, match="nested"):
        import_svg("deep.svg", text)
