"""Every corpus example compiles within the default limits, with an honest report."""

import pytest

from conftest import CORPUS, corpus_names
from compiler.apply import side_graph
from compiler.canon import canonical_key
from compiler.infer import EXAMPLE_CHECK_STEPS, compile_example, example_graphs
from compiler.verify import Reducer, verify
from grammar_lang import boundary as bd
from grammar_lang.loader import load_example

# Examples the original tool solved with a few rule classes (corpus README table).
SOLVED_BY_ORIGINAL = ["l", "house-filled", "square-filled", "square-hollow", "triangle", "h",
                      "t", "u", "z", "angle", "line", "right-angles"]


@pytest.mark.parametrize("name", corpus_names())
def test_compiles_within_default_limits(name):
    ex = load_example(CORPUS / f"{name}.svg")
    res = compile_example(ex)
    rep = res.report
    limits = ex.options.limits
    assert rep.primitives == len(ex.primitives)
    assert rep.rules + rep.starters == len(res.grammar.rules)
    assert rep.generations <= limits.generations
    # The default limits count work, never seconds: the same rules on any machine.
    assert limits.seconds is None and "time" not in rep.limits_hit
    assert rep.hierarchy_graphs <= limits.graphs + 1
    assert res.grammar.header.complete is rep.complete
    if rep.complete:
        assert not rep.limits_hit and rep.remaining == 0
        # The claim, checked independently: every complete graph of ≤ 6 primitives reduces.
        assert verify(res.grammar, 6).ok
    else:
        assert rep.limits_hit or rep.remaining
        assert len(rep.remaining_boundaries) == min(5, rep.remaining)
    rings = res.grammar.rings
    for r in res.grammar.rules:
        if r.is_starter:
            assert r.lhs.tokens(rings) == (bd.UP,) and not r.lhs.open_slots()
        else:
            assert bd.canonical(r.lhs.tokens(rings)) == bd.canonical(r.rhs.tokens(rings))
    # Whatever the verdict, the grammar builds something: the example's own pieces.
    assert rep.starters >= 1
    ring_len = [len(r) for r in rings]
    starters = {canonical_key(side_graph(r.lhs), ring_len)
                for r in res.grammar.rules if r.is_starter}
    reducer = Reducer(res.grammar, apply_budget=EXAMPLE_CHECK_STEPS)
    for g in example_graphs(ex):
        assert g.is_complete
        assert canonical_key(g, ring_len) in starters or reducer.reduces(g)


@pytest.mark.parametrize("name", SOLVED_BY_ORIGINAL)
def test_examples_the_original_tool_solved_are_complete(name):
    res = compile_example(load_example(CORPUS / f"{name}.svg"))
    assert res.report.complete, res.report.verdict


def test_output_is_deterministic():
    ex = load_example(CORPUS / "star-hollow.svg")
    a, b = compile_example(ex), compile_example(ex)
    assert a.grammar == b.grammar


def test_a_limited_compile_is_deterministic_and_an_explicit_time_limit_is_reported():
    """x-box-square stops at the graph limit; under a time limit it says so."""
    import dataclasses
    ex = load_example(CORPUS / "x-box-square.svg")
    a, b = compile_example(ex), compile_example(ex)
    assert "graphs" in a.report.limits_hit and a.grammar == b.grammar
    timed = dataclasses.replace(ex.options.limits, seconds=1e-3, graphs=10**6)
    ex = dataclasses.replace(ex, options=dataclasses.replace(ex.options, limits=timed))
    assert "time" in compile_example(ex).report.limits_hit
