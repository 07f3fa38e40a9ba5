"""For a fixed grammar and seed the drawing is byte-identical to the committed one."""

import os
from pathlib import Path

import pytest

from conftest import CORPUS, ROOT
from report.ggrun import main

GOLDEN = ROOT / "tests" / "golden"
CASES = [
    ("examples/tree.gg", "tree.json"),
    ("examples/house.gg", "house.json"),
    ("examples/house.gg", "house.svg"),
    ("examples/square-walls.ggr", "square-walls.json"),
    ("corpus:curl.svg", "curl.json"),
    ("corpus:diagonal-box.svg", "diagonal-box.json"),
]


def _source(spec: str) -> str:
    return str(CORPUS / spec[7:]) if spec.startswith("corpus:") else spec   # relative to ROOT


@pytest.mark.parametrize("spec,name", CASES, ids=[c[1] for c in CASES])
def test_drawing_matches_the_golden_file(spec, name, tmp_path, monkeypatch):
    monkeypatch.chdir(ROOT)         # the drawing records its grammar's name, not a tmp path
    out = tmp_path / name
    assert main([_source(spec), "--steps", "150", "--seed", "3", "--out", str(out),
                 "--quiet"]) == 0
    golden = GOLDEN / name
    if os.environ.get("GG_REGENERATE_GOLDEN"):
        golden.write_bytes(out.read_bytes())
    assert out.read_bytes() == golden.read_bytes(), f"{name} differs from the golden drawing"
