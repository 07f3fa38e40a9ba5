"""docs/gg-language.md: every ```gg block runs, and the doc covers every setting and module."""

from __future__ import annotations

import re

import pytest

from conftest import ROOT
from grammar_lang import gg_schema
from grammar_lang.gg_parser import STATEMENT_KEYWORDS, parse_syntax, parse_text
from grammar_lang.gg_imports import stdlib_modules
from grammar_lang.labelling import label_example
from grammar_lang.planar import build_planar_graph

DOC = ROOT / "docs" / "gg-language.md"
TEXT = DOC.read_text(encoding="utf-8")
# (info string after ```gg, body, line number) of every gg block; "fragment" marks blocks that
# refer to names or files defined elsewhere: they are checked for syntax only.
BLOCKS = [(m.group(1).strip(), m.group(2), TEXT.count("\n", 0, m.start()) + 1)
          for m in re.finditer(r"^```gg([^\n]*)\n(.*?)^```", TEXT, re.S | re.M)]


def test_the_doc_has_runnable_examples():
    assert len([b for b in BLOCKS if not b[0]]) >= 12
    assert {info for info, _, _ in BLOCKS} <= {"", "fragment"}


@pytest.mark.parametrize("info,body,line", BLOCKS, ids=[f"line{b[2]}" for b in BLOCKS])
def test_doc_block(info, body, line):
    # Blocks are read as if they were files in examples/, where the SVG they mention lives.
    path = ROOT / "examples" / f"doc-line{line}.gg"
    if info == "fragment":
        parse_syntax(body, path)
        return
    source = parse_text(body, path)
    example = label_example(source, build_planar_graph(source) if source.paint else None)
    assert example.primitives


def test_every_setting_and_statement_is_documented():
    for schema in (gg_schema.OPTIONS, gg_schema.LIMITS, gg_schema.CLASS,
                   *gg_schema.DECORATIONS.values()):
        for key in schema:
            assert f"`{key}`" in TEXT, key
    for marker in gg_schema.MARKERS:
        assert f"`{marker}`" in TEXT
    for keyword in STATEMENT_KEYWORDS:
        assert f"'{keyword}'" in TEXT or f"`{keyword}" in TEXT, keyword


def test_every_standard_module_is_documented():
    for name in stdlib_modules():
        assert f"| `{name}` |" in TEXT, name


def test_the_documented_defaults_are_the_models():
    from grammar_lang.source import EdgeClass, Limits, Options
    o, li = Options(), Limits()
    assert f"| {o.angle_tolerance:g}° |" in TEXT and f"| {o.snap_angle:g}° |" in TEXT
    assert f"| {li.generations} |" in TEXT and f"| {li.half_edges} |" in TEXT
    assert f"| {li.graphs} |" in TEXT and li.seconds is None and "| none |" in TEXT
    assert f"**{EdgeClass.DEFAULT_MIN:g} to {EdgeClass.DEFAULT_MAX:g} units**" in TEXT
