"""The solver's length repair (runtime/geometry/solver.py, `repair`): alternating projections
between the system's affine space and the box of allowed lengths."""

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from runtime.geometry.solver import _factorise, repair


def _polygon(directions):
    """A closed polygon's system: one free vertex per corner, one edge per side, each side's
    direction fixed; unknowns are the positions, then the lengths."""
    k = len(directions)
    edges = [(e, (e + 1) % k, d, None, False, True) for e, d in enumerate(directions)]
    return _factorise((2,) * k, edges), np.zeros(2 * k)


def _project(fact, b, target):
    return target + fact.scale * fact.Mp.dot(b - fact.A.dot(target))


def _repair(fact, x, n, lo, hi):
    """As the solver calls it: the box less a margin, the margin as slack."""
    lo, hi = np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)
    m = np.minimum(1e-3 * np.maximum(lo, 1.0), 0.25 * (hi - lo))
    return repair(x, n, fact.P_len, lo + m, hi - m, m)


@st.composite
def rectangles(draw):
    """A rectangle's four sides, with a box per side that an actual rectangle fits (opposite
    sides' ranges overlap), and a random target."""
    w, h = draw(st.floats(1, 50)), draw(st.floats(1, 50))
    boxes = []
    for true in (w, h, w, h):
        below, above = draw(st.floats(0.1, 5)), draw(st.floats(0.1, 5))
        boxes.append((true - below, true + above))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    target = np.concatenate([rng.normal(0, 10, 8), rng.uniform(0.1, 60, 4)])
    return boxes, target


DIRS = [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)]


@settings(max_examples=200, deadline=None)
@given(rectangles())
def test_repair_stays_on_the_system_and_reaches_a_box_that_meets_it(case):
    boxes, target = case
    fact, b = _polygon(DIRS)
    lo = np.array([a for a, _ in boxes])
    hi = np.array([c for _, c in boxes])
    x = _project(fact, b, target)
    y = _repair(fact, x, 8, lo, hi)
    # Still a closed rectangle: every side's direction and the closure hold.
    assert np.abs(fact.A.dot(y) - b).max() < 1e-8 * (1 + np.abs(y).max())
    lengths = y[8:]
    # Opposite sides' boxes overlap by construction, so the sets meet: repaired.
    assert np.all(lengths >= lo) and np.all(lengths <= hi)


def test_repair_leaves_a_sample_already_in_range_alone():
    fact, b = _polygon(DIRS)
    x = _project(fact, b, np.concatenate([np.zeros(8), [4.0, 2.0, 4.0, 2.0]]))
    y = _repair(fact, x, 8, np.full(4, 1.0), np.full(4, 9.0))
    assert y is x


def test_repair_gives_up_where_no_length_fits():
    # Width in [1, 2] at the bottom and [5, 6] at the top: no rectangle has both. The sample
    # comes back as it was drawn, to fail the length test.
    fact, b = _polygon(DIRS)
    lo, hi = np.array([1.0, 1.0, 5.0, 1.0]), np.array([2.0, 9.0, 6.0, 9.0])
    x = _project(fact, b, np.concatenate([np.zeros(8), [1.5, 3.0, 5.5, 3.0]]))
    assert _repair(fact, x, 8, lo, hi) is x


def test_repair_of_a_triangle_with_a_short_side():
    # A right triangle whose hypotenuse came out below its minimum: the repair scales the
    # whole triangle up rather than breaking it.
    s = math.sqrt(0.5)
    fact, b = _polygon([(1.0, 0.0), (-s, s), (0.0, -1.0)])
    x = _project(fact, b, np.concatenate([np.zeros(6), [1.0, 1.4, 1.0]]))
    lo, hi = np.array([0.5, 3.0, 0.5]), np.array([10.0, 10.0, 10.0])
    y = _repair(fact, x, 6, lo, hi)
    a, h, c = y[6:]
    assert h >= 3.0 and math.isclose(a, c) and math.isclose(h, a * math.sqrt(2))
