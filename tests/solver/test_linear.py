"""isolator.solver.linear: the exact linear oscillator behind the response spectrum, against closed forms."""

from __future__ import annotations

import math

import numpy as np
import pytest

from isolator.solver.linear import linear_peak_displacement, pseudo_acceleration_spectrum


@pytest.mark.parametrize("damping_ratio", [0.0, 0.05, 0.3])
@pytest.mark.parametrize("period_s", [0.3, 1.0, 2.5])
def test_step_response_peak(period_s, damping_ratio):
    """A constant ground acceleration a0 from rest: peak |x| = a0/ω² (1 + exp(-ζπ/√(1-ζ²))), at t = π/ω_d.

    The samples are far coarser than the period: the peak lies between samples and must still be exact.
    """
    a0, dt = 2.0, 0.37
    acc = np.full(int(10 * period_s / dt) + 20, a0)
    omega = 2 * math.pi / period_s
    overshoot = math.exp(-damping_ratio * math.pi / math.sqrt(1 - damping_ratio ** 2))
    expected = a0 / omega ** 2 * (1 + overshoot)
    assert linear_peak_displacement(acc, dt, period_s, damping_ratio) == pytest.approx(expected, rel=1e-10)
    psa = pseudo_acceleration_spectrum(acc, dt, [period_s], damping_ratio)
    assert psa[0] == pytest.approx(a0 * (1 + overshoot), rel=1e-10)


def test_ramp_undamped_closed_form():
    """a_g = r t, undamped: x = -(r/ω²)(t - sin(ωt)/ω), monotone, so the peak is at the end."""
    r, dt, n = 0.8, 0.05, 201
    t_end = dt * (n - 1)
    acc = r * dt * np.arange(n)
    for period_s in (0.2, 1.0, 4.0):
        omega = 2 * math.pi / period_s
        expected = r / omega ** 2 * (t_end - math.sin(omega * t_end) / omega)
        assert linear_peak_displacement(acc, dt, period_s, 0.0) == pytest.approx(expected, rel=1e-10)


def test_linearity_and_argument_checks():
    rng = np.random.default_rng(3)
    acc = rng.normal(size=400)
    periods = [0.1, 0.5, 2.0]
    base = pseudo_acceleration_spectrum(acc, 0.01, periods)
    np.testing.assert_allclose(pseudo_acceleration_spectrum(-3.0 * acc, 0.01, periods), 3.0 * base, rtol=1e-12)
    with pytest.raises(ValueError, match="periods"):
        pseudo_acceleration_spectrum(acc, 0.01, [0.0])
    with pytest.raises(ValueError, match="damping_ratio"):
        pseudo_acceleration_spectrum(acc, 0.01, [1.0], damping_ratio=-0.1)
