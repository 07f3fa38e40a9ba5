"""Generation on real examples: compiled corpus grammars grow valid, varied, large drawings.

The full acceptance sweep (every corpus example, 20 seeds) is benchmarks-scale; this keeps a
fast sample of the corpus in the test suite, every drawing checked by the verifier.
"""

from __future__ import annotations

import sys
from functools import lru_cache

import pytest

from runtime.engine.costs import SizeCost
from runtime.engine.generate import Engine
from runtime.verifier import check_drawing

from conftest import CORPUS, ROOT

sys.path.append(str(ROOT / "benchmarks"))  # last: benchmarks/report.py must not hide `report`
from acceptance import structure  # noqa: E402  (the sweep's own structure key)

SAMPLE = ["angle.svg", "branches.svg", "a.svg", "curl.svg", "square-filled.svg", "l.svg"]


@lru_cache(maxsize=None)
def _compiled(name: str):
    from compiler.infer import compile_example
    from grammar_lang.loader import load_example
    example = load_example(CORPUS / name)
    return example, compile_example(example).grammar


@pytest.mark.parametrize("name", SAMPLE)
def test_corpus_grammars_grow_valid_varied_drawings(name):
    example, grammar = _compiled(name)
    n_example = len(example.graph.vertices) if example.graph else len(example.primitives)
    grows = any(not r.is_starter for r in grammar.rules)
    structures = set()
    for seed in range(5):
        engine = Engine(grammar, seed=seed, cost=SizeCost(120))
        engine.run(120)
        drawing = engine.host.to_drawing()
        failures = check_drawing(example, drawing)
        assert failures == [], f"seed {seed}: " + "\n".join(f.render() for f in failures[:3])
        assert engine.host.check_consistency() == []
        structures.add(structure(engine))
        if grows:
            assert len(engine.host) >= min(10 * n_example, 100)
    assert len(structures) >= (3 if grows else 1)
