"""Random and mutated `.ggr` text: the loader answers with a Grammar or a located diagnostic,
never a Python exception. A grammar that loads emits text that loads as the same grammar."""

from __future__ import annotations

import re
from pathlib import Path

from hypothesis import HealthCheck, given, settings, strategies as st

from ggr_strategies import grammars
from grammar_lang.diagnostics import UserError
from grammar_lang.ggr_emit import emit_ggr
from grammar_lang.ggr_parser import parse_ggr

DOC = Path(__file__).resolve().parent.parent / "docs" / "ggr-language.md"
SEEDS = [m.group(1) for m in re.finditer(r"```ggr\n(.*?)```", DOC.read_text(encoding="utf-8"), re.S)]

# Pieces of the language, so that mutations often make text that almost parses.
VOCAB = ["ggr 1", "\n", " ", "{", "}", "=", ":", ".", "--", "~", "+", "-", "*", '"', "\\",
         "#", "rule", "starter", "lhs", "rhs", "boundary", "wire", "label", "primitive", "class",
         "faces", "decorate", "x", "xs", "~xs", "a", "b", "0", "1", "-1", "1e309", "9" * 5000,
         "angle=", "priority=", "weight=", "count=", "inf", "auto", "true", "\r\n", "\t", "\x00",
         "é", "₀", "\u2028", "∧"]


def check(text: str) -> None:
    try:
        grammar = parse_ggr(text, "fuzz.ggr")
    except UserError as exc:
        rendered = exc.render()
        assert rendered and all(d.span is not None for d in exc.diagnostics)
        for d in exc.diagnostics:
            assert d.span.file == "fuzz.ggr"
        return
    again = emit_ggr(grammar)
    assert parse_ggr(again) == grammar
    assert emit_ggr(parse_ggr(again)) == again


@st.composite
def mutated(draw, base):
    text = draw(base)
    for _ in range(draw(st.integers(1, 4))):
        n = len(text)
        i = draw(st.integers(0, n))
        j = draw(st.integers(i, min(n, i + 12)))
        op = draw(st.sampled_from(["delete", "insert", "replace", "duplicate-line", "swap-lines"]))
        if op == "delete":
            text = text[:i] + text[j:]
        elif op in ("insert", "replace"):
            piece = draw(st.sampled_from(VOCAB) | st.text(max_size=3))
            text = text[:i] + piece + text[j if op == "replace" else i:]
        else:
            lines = text.split("\n")
            k = draw(st.integers(0, len(lines) - 1))
            if op == "duplicate-line":
                lines.insert(k, lines[k])
            else:
                m = draw(st.integers(0, len(lines) - 1))
                lines[k], lines[m] = lines[m], lines[k]
            text = "\n".join(lines)
    return text


FUZZ = settings(max_examples=300, deadline=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])


@FUZZ
@given(st.text(max_size=200))
def test_random_text(text):
    check(text)


@FUZZ
@given(st.lists(st.sampled_from(VOCAB), max_size=40).map(" ".join))
def test_random_token_soup(text):
    check(text)


@FUZZ
@given(mutated(st.sampled_from(SEEDS)))
def test_mutated_documentation_examples(text):
    check(text)


@settings(max_examples=100, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(mutated(grammars().map(emit_ggr)))
def test_mutated_generated_files(text):
    check(text)
