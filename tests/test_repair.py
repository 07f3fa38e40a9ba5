"""The solver's length repair (runtime/geometry/system.py, `repair`): the point of the system
nearest a sample whose lengths lie in their box, found by pinning the lengths out of it."""

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from runtime.geometry.system import factorise, repair


def _polygon(directions):
    """A closed polygon's system: one free vertex per corner, one edge per side, each side's
    direction fixed; unknowns are the positions, then the lengths."""
    k = len(directions)
    edges = [(e, (e + 1) % k, d, None, False, True) for e, d in enumerate(directions)]
    return factorise((2,) * k, edges), np.zeros(2 * k)


def _project(fact, b, target):
    return target + fact.scale * fact.Minv.dot(b - fact.A.dot(target))


def _repair(fact, x, n, lo, hi, pins=None):
    """As the solver calls it: the box less a margin, the margin as slack."""
    lo, hi = np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)
    m = np.minimum(1e-3 * np.maximum(lo, 1.0), 0.25 * (hi - lo))
    return repair(x, n, fact, lo + m, hi - m, m, pins or {})


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
    # Width in [1, 2] at the bottom and [5, 6] at the top: no rectangle has both. Nothing
    # comes back: the sample is left to fail the length test as drawn.
    fact, b = _polygon(DIRS)
    lo, hi = np.array([1.0, 1.0, 5.0, 1.0]), np.array([2.0, 9.0, 6.0, 9.0])
    x = _project(fact, b, np.concatenate([np.zeros(8), [1.5, 3.0, 5.5, 3.0]]))
    assert _repair(fact, x, 8, lo, hi) is None


def test_repair_keeps_its_pins_and_fits_the_rest_around_them():
    # A tiled bottom pinned at 3 units: the top follows it (a rectangle's opposite sides are
    # equal), the sides are brought into their box, and the pin is kept exactly.
    fact, b = _polygon(DIRS)
    lo, hi = np.array([1.0, 4.0, 1.0, 4.0]), np.array([9.0, 6.0, 9.0, 6.0])
    x = _project(fact, b, np.concatenate([np.zeros(8), [2.2, 1.0, 2.6, 1.2]]))
    y = _repair(fact, x, 8, lo, hi, {0: 3.0})
    assert np.abs(fact.A.dot(y) - b).max() < 1e-9
    assert y[8] == pytest.approx(3.0, abs=1e-12) and y[10] == pytest.approx(3.0)
    assert 4.0 <= y[9] <= 6.0 and y[9] == pytest.approx(y[11])


def test_repair_reports_pins_the_system_cannot_meet():
    # A rectangle's bottom and top pinned at different widths: no point of the system.
    fact, b = _polygon(DIRS)
    x = _project(fact, b, np.concatenate([np.zeros(8), [2.0, 1.0, 2.0, 1.0]]))
    assert _repair(fact, x, 8, np.zeros(4), np.full(4, 9.0), {0: 3.0, 2: 4.0}) is None


@settings(max_examples=200, deadline=None)
@given(rectangles(), st.floats(1.0, 60.0))
def test_a_repaired_rectangle_keeps_the_samples_height_or_the_nearest_in_range(case, width):
    """With its width pinned a rectangle has one free length, its height, and the nearest
    point in range is the sample's height clipped into the sides' common range (less the
    margin): the repair finds it, or returns the sample itself when that is in range."""
    boxes, target = case
    fact, b = _polygon(DIRS)
    h_lo, h_hi = max(boxes[1][0], boxes[3][0], 0.5), min(boxes[1][1], boxes[3][1])
    assume(h_lo < h_hi)
    lo = np.array([0.5, h_lo, 0.5, h_lo])
    hi = np.array([99.0, h_hi, 99.0, h_hi])
    x = _project(fact, b, target)
    y = _repair(fact, x, 8, lo, hi, {0: width})
    m = min(1e-3 * max(h_lo, 1.0), 0.25 * (h_hi - h_lo))
    h = x[9]
    want = h if h_lo <= h <= h_hi else (h_lo + m if h < h_lo else h_hi - m)
    assert y[8] == pytest.approx(width) and y[10] == pytest.approx(width)
    assert y[9] == pytest.approx(want) and y[11] == pytest.approx(want)


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


@settings(max_examples=300, deadline=None)
@given(st.floats(1.0, 40.0), st.floats(1.0, 40.0), st.sets(st.integers(0, 3), min_size=1),
       st.floats(-1e-12, 1e-12), st.integers(0, 2**32 - 1))
def test_pins_the_system_ties_give_a_point_on_it_or_none(w, h, pinned, jitter, seed):
    """Pins on tied lengths (a rectangle's opposite sides) make the pinned block of the
    projection singular or nearly so. Whatever comes back lies on the system and has its
    pins; pins that agree (up to rounding) always give a point."""
    fact, b = _polygon(DIRS)
    rng = np.random.default_rng(seed)
    x = _project(fact, b, np.concatenate([rng.normal(0, 10, 8), rng.uniform(1, 60, 4)]))
    true = [w, h, w, h]
    pins = {e: true[e] + (jitter if e >= 2 else 0.0) for e in pinned}
    y = _repair(fact, x, 8, np.zeros(4), np.full(4, 99.0), pins)
    assert y is not None
    assert np.abs(fact.A.dot(y) - b).max() < 1e-6
    for e, v in pins.items():
        assert y[8 + e] == pytest.approx(v, abs=1e-6)


HEX = [(math.cos(math.radians(a)), math.sin(math.radians(a))) for a in range(0, 360, 60)]


@settings(max_examples=300, deadline=None)
@given(st.lists(st.floats(1.0, 40.0), min_size=4, max_size=4),
       st.sets(st.integers(0, 5), min_size=4), st.integers(0, 2**32 - 1))
def test_more_pins_than_a_hexagon_has_freedom_still_give_a_point_on_it(free4, pinned, seed):
    """A hexagon with its sides' directions fixed has four free lengths: five or six pins
    taken from a true hexagon agree, but make the pinned block singular in exact arithmetic
    and merely ill-conditioned in floating point, where a plain solve steps off the system
    (as it did on the castle: 0.04 px, and edges of the ground 3.97 px long against a
    minimum of 4)."""
    a, b_, c, d = free4
    # Closing the hexagon: with sides a, b, c, d chosen, e and f follow (u0..u5 at 60°).
    u = np.array(HEX)
    rest = -(a * u[0] + b_ * u[1] + c * u[2] + d * u[3])
    e, f = np.linalg.solve(np.column_stack([u[4], u[5]]), rest)
    assume(e > 0.5 and f > 0.5)
    true = [a, b_, c, d, e, f]
    fact, b = _polygon(HEX)
    rng = np.random.default_rng(seed)
    x = _project(fact, b, np.concatenate([rng.normal(0, 10, 12), rng.uniform(1, 60, 6)]))
    y = _repair(fact, x, 12, np.zeros(6), np.full(6, 999.0), {k: true[k] for k in pinned})
    assert y is not None
    assert np.abs(fact.A.dot(y) - b).max() < 1e-6
    assert np.allclose(y[12:][sorted(pinned)], [true[k] for k in sorted(pinned)], atol=1e-6)


def test_tied_pins_with_rounding_in_the_projection_stay_on_the_system():
    """Tied pins (a rectangle's bottom and top) make the pinned block of the projection
    singular; with the rounding a real projection carries (here 1e-9 noise on P), and pins
    a hair apart, a plain solve answers with huge multipliers that meet every pin and step
    far off the system (on the castle: 0.04 px, and ground pieces 3.97 px long against a
    minimum of 4). Whatever comes back must lie on the system; pins that agree give a
    point."""
    fact, b = _polygon(DIRS)
    rng = np.random.default_rng(7)
    noisy = dataclasses.replace(fact, P_len=fact.P_len + 1e-9 * rng.normal(size=fact.P_len.shape))
    x = _project(fact, b, np.concatenate([rng.normal(0, 10, 8), [5.0, 2.0, 5.0, 2.0]]))
    for apart in (0.0, 1e-7, 1e-4):
        y = noisy.project_pinned(x, 8, {0: 3.0, 2: 3.0 + apart})
        assert (y is not None) if apart == 0.0 else True
        if y is not None:
            assert np.abs(fact.A.dot(y) - b).max() < 1e-6
            assert y[8] == pytest.approx(3.0) and y[10] == pytest.approx(3.0 + apart)


def _general(fact, x, n, pins):
    """project_pinned's general path (a k×k solve), for comparison with its one-pin path."""
    idx = np.array(list(pins))
    r = np.array(list(pins.values())) - x[n + idx]
    cols = fact.P_len[:, idx]
    d = cols.dot(np.linalg.solve(cols[n + idx], r))
    return x + d


@settings(max_examples=300, deadline=None)
@given(st.sampled_from([DIRS, HEX]), st.integers(0, 5), st.floats(0.5, 80.0),
       st.integers(0, 2**32 - 1))
def test_one_pin_is_projected_exactly_as_the_general_solve_would(dirs, e, value, seed):
    """The one-pin path (one division) gives the general path's point to the last bit, so
    that drawings do not change with it; and that point lies on the system with its pin."""
    k = len(dirs)
    e %= k
    fact, b = _polygon(dirs)
    rng = np.random.default_rng(seed)
    x = _project(fact, b, np.concatenate([rng.normal(0, 10, 2 * k), rng.uniform(1, 60, k)]))
    y = fact.project_pinned(x, 2 * k, {e: value})
    assert y is not None
    assert np.array_equal(y, _general(fact, x, 2 * k, {e: value}))
    assert np.abs(fact.A.dot(y) - b).max() < 1e-6 and y[2 * k + e] == pytest.approx(value)
