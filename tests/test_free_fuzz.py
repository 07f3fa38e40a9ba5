"""Mutated hand-written grammars: the loader answers with a Grammar or a located diagnostic, a
grammar that loads emits text that loads as the same grammar, and running it for a few steps
and drawing it raises nothing (errors of a step are counted rejections)."""

from __future__ import annotations

import re

from hypothesis import HealthCheck, given, settings, strategies as st

import test_ggr_fuzz
from conftest import ROOT
from grammar_lang.diagnostics import UserError
from grammar_lang.ggr_parser import parse_ggr
from runtime.engine.free_engine import FreeEngine
from runtime.output.free_svg import render_free_svg

DOC = (ROOT / "docs" / "ggr-language.md").read_text(encoding="utf-8")
SEEDS = sorted(p.read_text(encoding="utf-8") for p in (ROOT / "examples").glob("*.ggr")
               if "production" in p.read_text(encoding="utf-8")) + \
    [b for b in re.findall(r"```ggr\n(.*?)```", DOC, re.S) if "production" in b]
WORDS = ["production", "start", "where", "let", "set", "rhs weight=2 {", "lhs {", "->", "--",
         "face", "(", ")", ",", "vertices", "edges", "attribute vertex h = 1", "match=oldest",
         "spatial", "a.pos", "b.x", "e.length", "sqrt(", "1 / 0", "uniform(0, 1)",
         "perp_left(v)", "*", "?", ":", "^", '"#fff"', 'colour("#fff")', "1e308", "a: *",
         "(0, 0)", "x", "y", "pos", "v / (a.x - a.x)", "10 ^ (400 * a.x)", "set a.pos = ",
         "mode dpo", "\n  }", "sqrt(" * 45, "true", "not", "and", "==", "text(1)", "+"]


def check(text: str) -> None:
    test_ggr_fuzz.check(text)       # loads or reports, and round-trips
    try:
        grammar = parse_ggr(text, "fuzz.ggr")
    except UserError:
        return
    if not grammar.is_free:
        return
    try:
        engine = FreeEngine(grammar, 1, limits={})
    except UserError as exc:        # a start graph that cannot be built is reported
        assert exc.diagnostics
        return
    engine.run(25)
    render_free_svg(engine.host, grammar.header)


FUZZ = settings(max_examples=250, deadline=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])


@st.composite
def mutated(draw):
    text = draw(st.sampled_from(SEEDS))
    for _ in range(draw(st.integers(1, 4))):
        i = draw(st.integers(0, len(text)))
        j = draw(st.integers(i, min(len(text), i + 10)))
        piece = draw(st.sampled_from(WORDS) | st.text(max_size=3))
        op = draw(st.sampled_from(["delete", "insert", "replace"]))
        text = text[:i] + ("" if op == "delete" else piece) + text[j if op != "insert" else i:]
    return text


@FUZZ
@given(mutated())
def test_mutated_hand_written_grammars(text):
    check(text)


@FUZZ
@given(st.lists(st.sampled_from(WORDS + test_ggr_fuzz.VOCAB), max_size=30).map(" ".join))
def test_token_soup(text):
    check("ggr 1\nvertices a b\nedges e\n" + text)
