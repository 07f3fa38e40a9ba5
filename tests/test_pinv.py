"""The solver's pseudo-inverse (runtime/geometry/pinv.py) against the Moore–Penrose
conditions and numpy's SVD-based one, on matrices shaped like the solver's systems: small,
sparse, with entries of very different scales and often rank deficient both ways."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from runtime.geometry.pinv import pinv


@st.composite
def systems(draw):
    m, n = draw(st.integers(0, 24)), draw(st.integers(0, 24))
    rank = draw(st.integers(0, min(m, n)))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    # Low rank by construction, then sparsified rows and rescaled columns, as the solver's
    # direction rows and its scaled length columns are.
    M = rng.normal(size=(m, rank)) @ rng.normal(size=(rank, n))
    if draw(st.booleans()) and m and n:
        M[rng.random((m, n)) < 0.5] = 0.0        # sparse: the rank may drop further
    scale = 10.0 ** rng.integers(-2, 3, size=n)
    return M * scale


@settings(max_examples=300, deadline=None)
@given(systems())
def test_pinv_is_the_moore_penrose_inverse(M):
    X = pinv(M)
    assert X.shape == M.shape[::-1]
    tol = 1e-8 * (1.0 + np.abs(M).max(initial=0.0)) * (1.0 + np.abs(X).max(initial=0.0)) ** 2
    assert np.abs(M @ X @ M - M).max(initial=0.0) <= tol * (1.0 + np.abs(M).max(initial=0.0))
    assert np.abs(X @ M @ X - X).max(initial=0.0) <= tol * (1.0 + np.abs(X).max(initial=0.0))
    assert np.abs((M @ X).T - M @ X).max(initial=0.0) <= tol
    assert np.abs((X @ M).T - X @ M).max(initial=0.0) <= tol


@settings(max_examples=200, deadline=None)
@given(systems())
def test_pinv_agrees_with_numpys_where_the_rank_is_clear(M):
    sv = np.linalg.svd(M, compute_uv=False) if M.size else np.zeros(0)
    # Only where the rank is well separated from the cut-off do two methods owe one answer.
    cut = 1e-10 * (sv[0] if sv.size else 0.0)
    if sv.size and np.any((sv > cut * 1e-3) & (sv < cut * 1e3)):
        return
    ref = np.linalg.pinv(M, rcond=1e-10)
    assert np.allclose(pinv(M), ref, rtol=1e-7, atol=1e-9 * (1.0 + np.abs(ref).max(initial=0.0)))


def test_pinv_of_a_solver_like_system_with_a_closed_cycle():
    # A square's four edges between four free vertices: eight direction rows, twelve
    # unknowns (positions and lengths), free to move and scale: rank deficient by columns.
    d = [(1, 0), (0, 1), (-1, 0), (0, -1)]
    A = np.zeros((8, 12))
    for e, (dx, dy) in enumerate(d):
        v, w = e, (e + 1) % 4
        for c, dc in enumerate((dx, dy)):
            A[2 * e + c, 2 * w + c] += 1.0
            A[2 * e + c, 2 * v + c] -= 1.0
            A[2 * e + c, 8 + e] = -dc
    assert np.linalg.matrix_rank(A) < 12
    assert np.allclose(pinv(A), np.linalg.pinv(A, rcond=1e-10), atol=1e-12)
