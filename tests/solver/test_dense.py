"""The kernels' in-place LU (isolator.solver.dense) against numpy's solve, real and complex, and its refusals."""

import numpy as np
import pytest

from isolator.solver.dense import lu_factor, lu_solve


@pytest.mark.parametrize("dtype", [np.float64, np.complex128])
def test_lu_solves_like_numpy_and_pivots(dtype):
    rng = np.random.default_rng(7)
    a = rng.standard_normal((9, 9)).astype(dtype)
    if dtype is np.complex128:
        a = a + 1j * rng.standard_normal((9, 9))
    a[0, 0] = 0.0  # a zero leading pivot: only row exchanges get past it
    b = rng.standard_normal(9).astype(dtype)
    lu, piv = a.copy(), np.zeros(9, dtype=np.int64)
    assert lu_factor(lu, piv)
    x = b.copy()
    lu_solve(lu, piv, x)
    np.testing.assert_allclose(x, np.linalg.solve(a, b), rtol=1e-12, atol=1e-12)
    # the factors are reusable: a second right-hand side with the same factors
    b2 = rng.standard_normal(9).astype(dtype)
    x2 = b2.copy()
    lu_solve(lu, piv, x2)
    np.testing.assert_allclose(a @ x2, b2, rtol=1e-12, atol=1e-12)


def test_lu_refuses_singular_and_non_finite_matrices():
    piv = np.zeros(3, dtype=np.int64)
    singular = np.array([[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 0.0, 0.0]])
    assert not lu_factor(singular.copy(), piv)
    non_finite = np.eye(3)
    non_finite[1, 1] = np.inf
    assert not lu_factor(non_finite, piv)
