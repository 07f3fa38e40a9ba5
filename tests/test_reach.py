"""What a grammar's drawings can hold, by label (grammar_lang/reach.py), and the warning for a
`connected` example whose pieces no rule joins (issue "Scenes": `connected` on a grammar
whose starters cannot build one connected structure)."""

import functools

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from compiler.cli import main as ggc
from compiler.infer import compile_example
from grammar_lang.loader import load_example
from grammar_lang.reach import connected_warning, reachable_labels, start_labels
from report.ggrun import main as ggrun
from runtime.engine.generate import Engine

from conftest import ILLUSTRATIONS, ROOT

PIECES = ('example "two pieces"\noptions { connected }\nface a #cc8\nface b #8cc\n'
          "polygon a rect (0, 0) (100, 100)\npolygon b rect (300, 0) (400, 100)\n")
CONNECTED = {"tree": ROOT / "examples" / "tree.gg",
             "station": ILLUSTRATIONS / "space-station.gg"}


@functools.lru_cache(maxsize=None)
def _grammar(path):
    return compile_example(load_example(path)).grammar


@functools.lru_cache(maxsize=None)
def _pieces():
    """The pieces example compiled once, for the property test's many draws."""
    import tempfile
    from pathlib import Path
    with tempfile.TemporaryDirectory() as d:
        path = Path(d) / "pieces.gg"
        path.write_text(PIECES)
        return compile_example(load_example(path)).grammar


@pytest.fixture
def pieces(tmp_path):
    gg = tmp_path / "pieces.gg"
    gg.write_text(PIECES)
    return gg


def test_separate_pieces_under_connected_are_a_warning_naming_what_each_start_lacks(pieces):
    w = connected_warning(_grammar(pieces))
    assert w is not None and w.severity == "warning"
    assert "never holds face label b" in w.message and "never holds face label a" in w.message
    assert "leave `connected` out" in w.hint


@pytest.mark.parametrize("name", sorted(CONNECTED))
def test_a_connected_example_of_one_structure_has_no_warning(name):
    assert connected_warning(_grammar(CONNECTED[name])) is None


def test_an_example_without_connected_has_no_warning(tmp_path):
    gg = tmp_path / "apart.gg"
    gg.write_text(PIECES.replace("options { connected }\n", ""))
    assert connected_warning(_grammar(gg)) is None


def test_both_commands_say_it_and_quiet_leaves_it_out(pieces, tmp_path, capsys):
    assert ggc(["compile", str(pieces), "-o", str(tmp_path / "p.ggr")]) == 0
    assert "warning: with `connected`" in capsys.readouterr().err
    out = str(tmp_path / "p.svg")
    assert ggrun([str(tmp_path / "p.ggr"), "--steps", "5", "--out", out]) == 0
    assert "never holds face label" in capsys.readouterr().err
    assert ggrun([str(pieces), "--steps", "5", "--out", out, "--quiet"]) == 0
    assert capsys.readouterr().err == ""


def _labels_in(host) -> set[int]:
    return {host.t.label[host.prim[v]][i] for v, i, _, _ in host.edges()}


@settings(deadline=None, max_examples=12)
@given(st.sampled_from(sorted(CONNECTED) + ["pieces"]), st.integers(0, 2 ** 16))
def test_a_drawing_holds_only_labels_its_start_can_reach(name, seed):
    """The reach is an over-approximation: whatever a run draws lies inside the reach of what
    it started with, and that start is the starter's and the frame's labels."""
    grammar = _grammar(CONNECTED[name]) if name in CONNECTED else _pieces()
    eng = Engine(grammar, seed=seed)
    first = next(r for r in grammar.rules if r.name == eng.history[0].rule)
    assert _labels_in(eng.host) <= start_labels(grammar, first)
    eng.run(60)
    assert _labels_in(eng.host) <= reachable_labels(grammar, start_labels(grammar, first))


def test_the_reach_of_every_label_is_every_label():
    for path in [ILLUSTRATIONS / f"{n}.gg" for n in ("castle", "flowers", "village")]:
        grammar = _grammar(path)
        every = set(range(len(grammar.header.labels)))
        assert reachable_labels(grammar, every) == every
