"""benchmarks/generate.py measures what its table documents: for a short window, the samples
per applied step (counted here independently, solver by solver) and the box area per vertex
(the timing itself is for the benchmark, not the suite)."""

import sys

import pytest

from conftest import ROOT

from runtime.engine import generate as engine_module

sys.path.append(str(ROOT / "benchmarks"))  # last: benchmarks/report.py must not hide `report`

import generate  # noqa: E402


def test_the_window_counts_every_sample_of_its_solvers(monkeypatch):
    solvers, runs = [], []
    real_solver, real_run = engine_module.Solver, engine_module.Engine.run

    def solver(*a, **k):
        solvers.append(real_solver(*a, **k))
        return solvers[-1]

    def run(self, *a, **k):
        runs.append(len(solvers))          # where each run's solvers start: grow, then window
        return real_run(self, *a, **k)

    monkeypatch.setattr(engine_module, "Solver", solver)
    monkeypatch.setattr(engine_module.Engine, "run", run)
    r = generate.measure(str(generate.CORPUS / "curl.svg"), 200, 40, seed=1)
    # The window runs at its size: the size cost holds the count near it, either way.
    assert abs(r["vertices"] - 200) <= 20 and r["applied"] == 40 and r["proposals"] >= 40
    window = solvers[runs[-1]:]
    assert window and sum(s.samples for s in window) > 0
    assert r["samples_per_step"] * r["applied"] == sum(s.samples for s in window)
    assert 0 < r["area_per_vertex"] < 100
    # Iterations are proposals, applied or not, over the same window's time.
    assert r["iterations_per_s"] * r["applied"] == pytest.approx(r["steps_per_s"] * r["proposals"])
