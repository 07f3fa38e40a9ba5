"""docs/ggr-language.md, hand-written productions: every production block runs, the automatic
placement does what the text says, and every function and built-in value is documented."""

from __future__ import annotations

import math
import re

import pytest

from conftest import ROOT
from grammar_lang.expr_functions import CONSTANTS, FUNCTIONS
from grammar_lang.free_rules import DERIVED
from grammar_lang.ggr_parser import parse_ggr
from runtime.engine.free_engine import FreeEngine

TEXT = (ROOT / "docs" / "ggr-language.md").read_text(encoding="utf-8")
BLOCKS = [(TEXT.count("\n", 0, m.start()) + 1, m.group(1))
          for m in re.finditer(r"```ggr\n(.*?)```", TEXT, re.S) if "production" in m.group(1)]


def test_there_are_production_examples():
    assert len(BLOCKS) >= 2


@pytest.mark.parametrize("line,block", BLOCKS, ids=[f"line{b[0]}" for b in BLOCKS])
def test_production_block_runs(line, block):
    summary = FreeEngine(parse_ggr(block, f"doc:{line}"), 0).run(40)
    assert summary.applied > 0 and summary.rejected == 0


def test_the_bump_example_stops_by_itself():
    block = next(b for _, b in BLOCKS if "production bump" in b)
    summary = FreeEngine(parse_ggr(block), 0).run(1000)
    assert summary.stop.startswith("no production applies") and summary.applied == 1 + 4 + 16


def test_the_fork_is_carried_by_a_similarity():
    block = next(b for _, b in BLOCKS if "production fork" in b)
    engine = FreeEngine(parse_ggr(block), 0)
    engine.run(15)
    host = engine.host
    for el in [e for e in host.elements.values() if e.kind == "vertex"]:
        stems = [host.elements[k] for k in host.incident[el.id]
                 if host.elements[k].ends[1] == el.id]
        if el.label != "pt" or not stems:
            continue            # the root has no stem
        stem = stems[0]
        (ax, ay), (tx, ty) = host.pos(stem.ends[0]), host.pos(el.id)
        dx, dy = tx - ax, ty - ay
        for k in host.incident[el.id]:
            child = host.elements[k]
            if child.ends[0] != el.id:
                continue
            cx, cy = host.pos(child.ends[1])
            along = ((cx - tx) * dx + (cy - ty) * dy) / (dx * dx + dy * dy)
            across = abs((cx - tx) * dy - (cy - ty) * dx) / (dx * dx + dy * dy)
            assert math.isclose(along, 0.6) and math.isclose(across, 0.4)


def test_every_function_and_built_in_value_is_documented():
    for name in FUNCTIONS:
        assert f"`{name}(" in TEXT, name
    for name in CONSTANTS:
        assert f"`{name}`" in TEXT, name
    for kind, values in DERIVED.items():
        for name in values:
            assert f"`{name}`" in TEXT, (kind, name)
