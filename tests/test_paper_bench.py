"""benchmarks/paper.py runs as documented: a short run over two seeds prints a row per seed
and the count of drawings that hold every label and class (the paper's N is for the
benchmark itself, not the suite)."""

import sys

from hypothesis import given
from hypothesis import strategies as st

from conftest import ILLUSTRATIONS, ROOT

sys.path.append(str(ROOT / "benchmarks"))  # last: benchmarks/report.py must not hide `report`

import paper  # noqa: E402


def test_seeds_are_a_range_or_a_list():
    assert paper._seeds("0-4") == [0, 1, 2, 3, 4]
    assert paper._seeds("1,5,80") == [1, 5, 80]
    assert paper._seeds("7") == [7]


def test_a_short_run_over_seeds_prints_a_row_each_and_the_count(monkeypatch, capsys):
    monkeypatch.setattr(paper, "ILLUSTRATIONS", ILLUSTRATIONS)
    assert paper.main(["flowers", "--iterations", "20", "--seeds", "3,4"]) == 0
    lines = capsys.readouterr().out.splitlines()
    rows = [line.split() for line in lines if line.startswith("flowers ")]
    assert [r[1] for r in rows[:2]] == ["3", "4"] and all(r[2] == "20" for r in rows[:2])
    # The flowers' start holds every part of the example: every drawing has them all.
    assert lines[-1].split()[-4:] == ["in", "2", "of", "2"]


@given(st.lists(st.integers(0, 10_000), min_size=1, max_size=60))
def test_full_at_is_the_first_iteration_that_holds_95_percent_of_the_most(counts):
    trace = [(50 * (k + 1), v) for k, v in enumerate(counts)]
    at = paper._full_at(trace)
    reached = [p for p, v in trace if v >= 0.95 * max(counts)]
    assert at == reached[0]
    assert all(v < 0.95 * max(counts) for p, v in trace if p < at)


def test_another_cost_is_the_one_ggrun_takes_and_a_bad_one_is_refused(monkeypatch, capsys):
    monkeypatch.setattr(paper, "ILLUSTRATIONS", ILLUSTRATIONS)
    assert paper.main(["flowers", "--iterations", "20", "--cost", "none"]) == 0
    assert [r for r in capsys.readouterr().out.splitlines() if r.startswith("flowers ")]
    assert paper.main(["flowers", "--iterations", "20", "--cost", "sise"]) == 0
    assert "does not run: unknown cost 'sise'" in capsys.readouterr().out
