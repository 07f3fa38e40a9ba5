"""The solver's minimum-norm inverse (runtime/geometry/min_norm.py) against its defining
conditions and against numpy's SVD-based pseudo-inverse on consistent systems, on matrices
shaped like the solver's: small, sparse, with entries of very different scales and often rank
deficient both ways."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from runtime.geometry.min_norm import min_norm_inverse


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


def _clear_rank(M) -> bool:
    """Whether M's rank is well separated from the cut-off: only then do two methods owe
    one answer."""
    sv = np.linalg.svd(M, compute_uv=False) if M.size else np.zeros(0)
    cut = 1e-10 * (sv[0] if sv.size else 0.0)
    return not (sv.size and np.any((sv > cut * 1e-3) & (sv < cut * 1e3)))


@settings(max_examples=300, deadline=None)
@given(systems())
def test_it_is_a_minimum_norm_generalised_inverse(M):
    X = min_norm_inverse(M)
    assert X.shape == M.shape[::-1]
    tol = 1e-8 * (1.0 + np.abs(M).max(initial=0.0)) * (1.0 + np.abs(X).max(initial=0.0)) ** 2
    assert np.abs(M @ X @ M - M).max(initial=0.0) <= tol * (1.0 + np.abs(M).max(initial=0.0))
    assert np.abs(X @ M @ X - X).max(initial=0.0) <= tol * (1.0 + np.abs(X).max(initial=0.0))
    assert np.abs((X @ M).T - X @ M).max(initial=0.0) <= tol


@settings(max_examples=200, deadline=None)
@given(systems(), st.integers(0, 2**32 - 1))
def test_consistent_systems_get_their_least_norm_solution(M, seed):
    if not _clear_rank(M):
        return
    b = M @ np.random.default_rng(seed).normal(size=M.shape[1])
    ref = np.linalg.pinv(M, rcond=1e-10) @ b
    x = min_norm_inverse(M) @ b
    assert np.allclose(x, ref, rtol=1e-7, atol=1e-8 * (1.0 + np.abs(ref).max(initial=0.0)))
    # X M is the orthogonal projection onto M's row space, as the solver's null-space
    # projection needs.
    assert np.allclose(min_norm_inverse(M) @ M, np.linalg.pinv(M, rcond=1e-10) @ M,
                       atol=1e-8)


@settings(max_examples=100, deadline=None)
@given(systems(), st.integers(0, 2**32 - 1))
def test_an_inconsistent_system_shows_in_its_residual(M, seed):
    # The solver takes b for consistent when M X b = b; a b off M's range must fail it.
    if not _clear_rank(M) or np.linalg.matrix_rank(M) == M.shape[0]:
        return
    rng = np.random.default_rng(seed)
    U = np.linalg.svd(M)[0] if M.size else np.eye(M.shape[0])
    off = U[:, -1] * (1.0 + np.abs(M).max(initial=0.0))       # orthogonal to M's range
    b = M @ rng.normal(size=M.shape[1]) + off
    assert np.abs(M @ min_norm_inverse(M) @ b - b).max() > 1e-6 * np.abs(off).max()


def test_a_solver_like_system_with_a_closed_cycle():
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
    X = min_norm_inverse(A)
    assert np.allclose(X @ A, np.linalg.pinv(A, rcond=1e-10) @ A, atol=1e-12)
