"""isolator.solver.kernel: the piece length that keeps the velocity unimodal and the exact Gram matrix."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from isolator.solver.kernel import fastest_rate, full_step_coefficients, substeps_per_interval
from isolator.solver.segments import ramp_basis


@pytest.mark.parametrize("c, kappa", [(0.0, 4.9), (0.3, 4.9), (10.0, 4.9), (4.0, 4.0), (0.1, 1e6)])
def test_fastest_rate_is_the_largest_root(c, kappa):
    roots = np.roots([1.0, c, kappa])  # λ² + c λ + κ = 0, the free motion
    assert fastest_rate(c, kappa) == pytest.approx(max(abs(roots.real)) + max(abs(roots.imag)), rel=1e-12)


@pytest.mark.parametrize("dt, c, kappa", [(0.01, 0.3, 4.9), (0.02, 0.0, 1e6), (0.005, 1.0, 1e8), (0.01, 50.0, 4.9)])
def test_substeps_keep_pieces_below_a_quarter_damped_period(dt, c, kappa):
    n = substeps_per_interval(dt, c, kappa)
    d2 = 0.25 * c * c - kappa
    if d2 >= 0:
        assert n == 1  # over-damped: the acceleration has at most one zero anyway
        return
    half_quarter = 0.5 * math.pi / math.sqrt(-d2)  # π/(2 ω_d)
    assert dt / n <= half_quarter * (1 + 1e-12)
    assert n == 1 or dt / (n - 1) > half_quarter  # and no more pieces than needed


@pytest.mark.parametrize("h, c, kappa", [(0.01, 0.3, 4.9), (0.02, 5.0, 100.0), (0.01, 0.0, 4.9)])
def test_gram_matrix_against_adaptive_quadrature(h, c, kappa):
    basis, gram = full_step_coefficients(h, c, kappa)
    np.testing.assert_allclose(basis, ramp_basis(h, c, kappa), rtol=0, atol=0)
    functions = [lambda t, i=i: ramp_basis(t, c, kappa)[i] for i in range(3)]  # E0, E1, H1
    for i in range(3):
        for j in range(3):
            value, error = quad(lambda t, i=i, j=j: functions[i](t) * functions[j](t), 0.0, h, epsabs=0,
                                epsrel=1e-13)
            assert gram[i, j] == pytest.approx(value, rel=1e-11, abs=1e-300), (i, j)
    np.testing.assert_array_equal(gram, gram.T)
