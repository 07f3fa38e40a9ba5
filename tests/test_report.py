"""`ggc report` and `ggc draw`: the page's structure, its figures' geometry, PNG output."""

from __future__ import annotations

import math
import re
from dataclasses import replace
from functools import lru_cache
from html.parser import HTMLParser
from pathlib import Path

import pytest
from hypothesis import given, settings, strategies as st

from grammar_lang.ggr_emit import emit_ggr
from grammar_lang.ggr_parser import parse_ggr
from report.build import load_subject
from report.figures import Drafter
from report.ggc import main as ggc
from report.page import Page

from conftest import CORPUS, ROOT, corpus_names

PIL = pytest.importorskip("PIL.Image")


@lru_cache(maxsize=None)
def _corpus_grammar(name: str):
    from compiler.infer import compile_example
    from grammar_lang.loader import load_example
    return compile_example(load_example(CORPUS / f"{name}.svg")).grammar


class Cards(HTMLParser):
    """Each rule card's inline SVG root attributes and how many drawn elements it holds."""

    def __init__(self):
        super().__init__()
        self.rules: list[dict] = []
        self.depth = 0          # inside a rule card's figure
        self.ids: list[str] = []

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if "id" in a:
            self.ids.append(a["id"])
        if tag == "div" and "rule" in (a.get("class") or "").split():
            self.rules.append({"svg": None, "drawn": 0, "id": a.get("id")})
        elif tag == "svg" and self.rules and self.rules[-1]["svg"] is None:
            self.rules[-1]["svg"] = a
        elif self.rules and tag in ("line", "text", "circle", "path"):
            self.rules[-1]["drawn"] += 1


def _structure(html: str) -> Cards:
    p = Cards()
    p.feed(html)
    return p


def _check_page(html: str, n_rules: int) -> None:
    p = _structure(html)
    assert len(p.rules) == n_rules
    for card in p.rules:
        svg = card["svg"]
        assert svg is not None, f"{card['id']} has no figure"
        x, y, w, h = (float(v) for v in svg["viewbox"].split())
        assert (x, y) == (0, 0) and 0 < w < 20000 and 0 < h < 20000
        assert float(svg["width"]) == w and float(svg["height"]) == h
        assert card["drawn"] > 0
    assert len(p.ids) == len(set(p.ids)), "element ids must be unique"
    assert "http://" not in html.replace('xmlns="http://www.w3.org/2000/svg"', "") \
        .replace("http://www.w3.org/1999/xlink", "")
    assert "<script src" not in html and "<link" not in html


@pytest.mark.parametrize("path", [ROOT / "examples" / "castle.gg", ROOT / "examples" / "house.gg",
                                  CORPUS / "double-branch.svg"])
def test_report_page_structure(path, tmp_path):
    out = tmp_path / "r.html"
    assert ggc(["report", str(path), "-o", str(out), "--gallery", "2", "--steps", "40"]) == 0
    html = out.read_text()
    # The castle's compile is time-limited, so its rule count is read off the page.
    n = int(re.search(r"<h2>Rules \((\d+)\)</h2>", html).group(1))
    assert n > 0
    _check_page(html, n)
    assert html.count('alt="seed ') == 2
    assert 'id="example"' in html and "data:image/svg+xml;base64," in html


@pytest.mark.parametrize("name", ["flowers", "village"])
def test_report_of_an_illustration(name, tmp_path):
    # Framed scenes: every rule is drawn; a gallery the runtime cannot grow is reported.
    out = tmp_path / "r.html"
    assert ggc(["report", str(CORPUS.parent / "illustrations" / f"{name}.gg"), "-o", str(out),
                "--gallery", "1", "--steps", "30"]) == 0
    html = out.read_text()
    n = int(re.search(r"<h2>Rules \((\d+)\)</h2>", html).group(1))
    _check_page(html, n)
    assert "(no placement found)" not in html
    assert html.count('alt="seed ') == 1 or "could not grow drawings" in html


def test_report_of_a_rule_file_names_its_lines(tmp_path):
    ggr = tmp_path / "square.ggr"
    assert ggc(["compile", str(ROOT / "examples" / "square-hollow.gg"), "-o", str(ggr)]) == 0
    out = tmp_path / "r.html"
    assert ggc(["report", str(ggr), "-o", str(out), "--gallery", "0"]) == 0
    html = out.read_text()
    grammar = parse_ggr(ggr.read_text(), str(ggr))
    _check_page(html, len(grammar.rules))
    for rule in grammar.rules:
        assert f"line {rule.span.line} of square.ggr" in html
        line = ggr.read_text().splitlines()[rule.span.line - 1]
        assert re.match(rf"(rule|starter) {rule.name} ", line)


def test_report_is_deterministic_without_times(tmp_path):
    a, b = tmp_path / "a.html", tmp_path / "b.html"
    for out in (a, b):
        assert ggc(["report", str(ROOT / "examples" / "tree.gg"), "-o", str(out),
                    "--gallery", "1", "--steps", "30", "--no-times"]) == 0
    assert a.read_bytes() == b.read_bytes()


def test_text_from_user_files_is_escaped():
    subject = load_subject(str(ROOT / "examples" / "square-hollow.gg"))
    evil = '<script>alert("x")</script>&'
    g = subject.grammar
    g = replace(g, rules=(replace(g.rules[0], name=evil),) + g.rules[1:])
    subject.grammar = g
    html = Page(subject, Drafter(g.header), [], times=False).html()
    assert evil not in html
    assert "&lt;script&gt;alert(&quot;x&quot;)&lt;/script&gt;&amp;" in html


@pytest.mark.parametrize("args,message", [
    (["--gallery", "-1"], "--gallery -1 is out of range"),
    (["--png", "d", "--width", "0"], "--width 0 is out of range"),
    (["--scale", "2"], "they need --png DIR"),
])
def test_report_rejects_bad_options(args, message, tmp_path, capsys):
    code = ggc(["report", str(ROOT / "examples" / "tree.gg"), "-o", str(tmp_path / "x.html"),
                *args])
    assert code == 2 and message in capsys.readouterr().err


def test_report_refuses_hand_written_productions(capsys):
    assert ggc(["report", str(ROOT / "examples" / "koch.ggr"), "-o", "/dev/null"]) == 2
    assert "hand-written productions" in capsys.readouterr().err


def test_report_rejects_unknown_input(tmp_path, capsys):
    f = tmp_path / "x.txt"
    f.write_text("hello")
    assert ggc(["report", str(f)]) == 2
    assert "don't know how to report" in capsys.readouterr().err


# --- geometry of the drawn rule sides ----------------------------------------------------------

LINE = re.compile(r'<line class="e" x1="([-\d.]+)" y1="([-\d.]+)" x2="([-\d.]+)" '
                  r'y2="([-\d.]+)"[^>]*data-label="([^"]*)"')


@pytest.mark.parametrize("name", corpus_names())
@settings(max_examples=2, deadline=None)
@given(seed=st.integers(0, 2 ** 31))
def test_drawn_rule_sides_have_their_labels_directions(name, seed):
    grammar = _corpus_grammar(name)
    angle = {l.name: l.angle for l in grammar.header.labels}
    drafter = Drafter(grammar.header, seed)
    for rule in grammar.rules:
        svg = drafter.rule_svg(rule)
        edges = sum(len(s.edges) + len(s.wires) for s in (rule.lhs, rule.rhs))
        found = LINE.findall(svg)
        assert len(found) == edges
        for x1, y1, x2, y2, label in found:
            dx, dy = float(x2) - float(x1), -(float(y2) - float(y1))   # back to y up
            n = math.hypot(dx, dy)
            assert n > 0
            a = math.radians(angle[label])
            assert abs(dx / n - math.cos(a)) < 1e-6 and abs(dy / n - math.sin(a)) < 1e-6
    assert drafter.failed == []


# --- PNG ------------------------------------------------------------------------------------------

def _png(path: Path):
    im = PIL.open(path)
    im.load()
    return im


def _not_blank(im) -> bool:
    lo, hi = im.convert("L").getextrema()
    return hi - lo > 50


def test_ggrun_writes_png_of_the_asked_width(tmp_path):
    from report.ggrun import main as ggrun
    out = tmp_path / "t.png"
    assert ggrun([str(ROOT / "examples" / "tree.gg"), "--steps", "60", "--seed", "2",
                  "--out", str(out), "--width", "320", "--quiet"]) == 0
    im = _png(out)
    assert im.size[0] == 320 and _not_blank(im)


def test_report_png_folder(tmp_path):
    folder = tmp_path / "png"
    assert ggc(["report", str(ROOT / "examples" / "square-hollow.gg"), "-o",
                str(tmp_path / "r.html"), "--gallery", "1", "--steps", "30", "--png",
                str(folder), "--scale", "2"]) == 0
    names = sorted(p.name for p in folder.iterdir())
    grammar = load_subject(str(ROOT / "examples" / "square-hollow.gg")).grammar
    assert sum(n.startswith("rule-") for n in names) == len(grammar.rules)
    assert "example.png" in names and "gallery-seed0.png" in names
    drafter = Drafter(grammar.header)
    for k, rule in enumerate(grammar.rules):
        im = _png(next(folder.glob(f"rule-{k:03d}-*.png")))
        w = float(re.search(r'width="([\d.]+)"', drafter.rule_svg(rule)).group(1))
        assert abs(im.size[0] - 2 * w) <= 1 and _not_blank(im)


def test_ggc_draw_marks_every_vertex(tmp_path):
    from grammar_lang.loader import load_example
    out = tmp_path / "h.svg"
    assert ggc(["draw", str(CORPUS / "h-complex.svg"), "-o", str(out)]) == 0
    text = out.read_text()
    ex = load_example(CORPUS / "h-complex.svg")
    assert text.count("data-primitive=") == len(ex.graph.vertices)
    assert text.count("data-class=") >= 1
    png = tmp_path / "h.png"
    assert ggc(["draw", str(CORPUS / "h-complex.svg"), "-o", str(png), "--width", "200"]) == 0
    assert _png(png).size[0] == 200


def test_the_rule_file_text_round_trips():
    # The report numbers rules by the text `ggc compile` writes; it must parse back the same.
    g = _corpus_grammar("double-branch")
    again = parse_ggr(emit_ggr(g), "x.ggr")
    assert [r.name for r in again.rules] == [r.name for r in g.rules]
