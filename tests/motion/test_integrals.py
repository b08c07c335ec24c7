"""The trapezoidal integrals of the intensity measures: exact where the rule is, scipy's bits everywhere."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import cumulative_trapezoid as scipy_cumulative_trapezoid
from scipy.integrate import trapezoid as scipy_trapezoid

from isolator.motion.measures import arias_intensity_m_s, cumulative_trapezoid, velocity_m_s
from isolator.units import STANDARD_GRAVITY


def test_exact_on_a_ramp():
    """The trapezoidal rule is exact on a linear integrand: ∫0^t (2 + 3τ) dτ = 2t + 1.5t²."""
    dt = 0.02
    t = np.arange(501) * dt
    assert cumulative_trapezoid(2.0 + 3.0 * t, dt) == pytest.approx(2.0 * t + 1.5 * t**2, rel=1e-13, abs=1e-13)
    assert velocity_m_s(np.full(11, 9.80665), 0.1)[-1] == pytest.approx(9.80665, rel=1e-14)


@pytest.mark.parametrize("n", [1, 2, 3, 1000, 5901])
def test_same_bits_as_scipy(n):
    """Replacing scipy.integrate changes no number of a report (intensity measures, D5-95)."""
    values = np.random.default_rng(n).normal(size=n)
    assert np.array_equal(cumulative_trapezoid(values, 0.01), scipy_cumulative_trapezoid(values, dx=0.01, initial=0.0))
    expected = math.pi / (2.0 * STANDARD_GRAVITY) * scipy_trapezoid(values**2, dx=0.01)
    assert arias_intensity_m_s(values, 0.01) == float(expected)
