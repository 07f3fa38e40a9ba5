"""benchmarks/generate.py measures what its table documents: for a short window, the time per
proposal, the samples per applied step and the box area per vertex, consistent with its other
counts (the timing itself is for the benchmark, not the suite)."""

import sys

import pytest
from conftest import ROOT

sys.path.append(str(ROOT / "benchmarks"))  # last: benchmarks/report.py must not hide `report`

import generate  # noqa: E402


def test_a_short_window_reports_its_work_per_step_and_per_proposal():
    r = generate.measure(str(generate.CORPUS / "curl.svg"), 200, 40, seed=1)
    assert r["vertices"] >= 200 and r["applied"] == 40
    assert r["proposals"] >= r["applied"]
    # The same window's seconds, split per applied step and per proposal.
    assert r["us_per_proposal"] * r["proposals"] / 1000 == \
        pytest.approx(r["ms_per_step"] * r["applied"])
    # curl's new parts are placed by sampling (its removals draw none).
    assert r["samples_per_step"] > 0
    assert 0 < r["area_per_vertex"] < 100
