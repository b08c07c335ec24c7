"""PSA, RotD100 and RotD50 of pairs against independent computations written here."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from isolator.review.spectra import pair_spectra, rotd50

EXAMPLE = Path(__file__).resolve().parents[2] / "isolator" / "data" / "suites" / "example"


def _noise_pair(n=400, dt=0.01, seed=3):
    rng = np.random.default_rng(seed)
    kernel = np.hanning(15) / np.hanning(15).sum()
    ax = np.convolve(rng.standard_normal(n), kernel, mode="same") * 3.0
    ay = np.convolve(rng.standard_normal(n), kernel, mode="same") * 2.0 + 0.3 * ax
    return ax, ay, dt


def _histories_ivp(acc, dt, period, zeta=0.05):
    """u(t) at the samples by solve_ivp on the piecewise-linear record (one solve per interval)."""
    omega = 2 * math.pi / period
    u, v = 0.0, 0.0
    out = [0.0]
    for i in range(acc.size - 1):
        a0, a1 = acc[i], acc[i + 1]

        def rhs(t, y, a0=a0, a1=a1):
            ag = a0 + (a1 - a0) * t / dt
            return [y[1], -ag - 2 * zeta * omega * y[1] - omega * omega * y[0]]

        sol = solve_ivp(rhs, (0.0, dt), [u, v], method="DOP853", rtol=1e-12, atol=1e-15)
        u, v = sol.y[0, -1], sol.y[1, -1]
        out.append(u)
    return np.array(out)


@pytest.mark.parametrize("period", [0.25, 1.0, 3.0])
def test_psa_and_rotd_against_solve_ivp_and_brute_force_rotation(period):
    ax, ay, dt = _noise_pair()
    s = pair_spectra(ax, ay, dt, [period])
    ux, uy = _histories_ivp(ax, dt, period), _histories_ivp(ay, dt, period)
    w2 = (2 * math.pi / period) ** 2
    assert s["psa_x_m_s2"][0] == pytest.approx(w2 * np.max(np.abs(ux)), rel=1e-8)
    assert s["psa_y_m_s2"][0] == pytest.approx(w2 * np.max(np.abs(uy)), rel=1e-8)
    # RotD100: the maximum over angles of the rotated component, by brute force at 0.01° steps
    theta = np.radians(np.arange(0.0, 180.0, 0.01))
    rotated = np.max(np.abs(np.outer(np.cos(theta), ux) + np.outer(np.sin(theta), uy)), axis=1)
    assert s["rotd100_m_s2"][0] == pytest.approx(w2 * rotated.max(), rel=2e-8)
    # RotD50: the median over 0…179° at 1° steps
    at_degrees = rotated[::100]
    assert rotd50(ax, ay, dt, [period])[0] == pytest.approx(w2 * np.median(at_degrees), rel=1e-8)


def test_rotd100_is_rotation_invariant_and_bounded_on_a_real_pair():
    from isolator.motion import read_ground_motion

    x = read_ground_motion(EXAMPLE / "duzce1999_DZC" / "RSN1605_DUZCE_DZC180.AT2")
    y = read_ground_motion(EXAMPLE / "duzce1999_DZC" / "RSN1605_DUZCE_DZC270.AT2")
    periods = np.geomspace(0.1, 6.0, 25)
    s = pair_spectra(x.acceleration_m_s2, y.acceleration_m_s2, x.dt_s, periods)
    c, sn = math.cos(0.7), math.sin(0.7)
    ax, ay = x.acceleration_m_s2, y.acceleration_m_s2
    r = pair_spectra(c * ax - sn * ay, sn * ax + c * ay, x.dt_s, periods)
    np.testing.assert_allclose(r["rotd100_m_s2"], s["rotd100_m_s2"], rtol=1e-9)
    larger = np.maximum(s["psa_x_m_s2"], s["psa_y_m_s2"])
    assert np.all(s["rotd100_m_s2"] >= larger * (1 - 1e-12))
    assert np.all(s["rotd100_m_s2"] <= np.hypot(s["psa_x_m_s2"], s["psa_y_m_s2"]) * (1 + 1e-12))


def test_component_psa_matches_the_solver_spectrum_at_long_periods():
    """The solver's spectrum also finds peaks between samples: ours (at the samples) is never above it and
    below it by at most 1 − cos(π dt/T), the sampling error of a peak of period T."""
    from isolator.solver.linear import pseudo_acceleration_spectrum

    ax, ay, dt = _noise_pair(n=800)
    periods = np.array([1.0, 2.0, 4.0])
    ours = pair_spectra(ax, ay, dt, periods)["psa_x_m_s2"]
    exact = pseudo_acceleration_spectrum(ax, dt, periods)
    assert np.all(ours <= exact * (1 + 1e-12))
    assert np.all(ours >= exact * np.cos(np.pi * dt / periods))


def test_bad_inputs_are_refused():
    with pytest.raises(ValueError, match="same length"):
        pair_spectra(np.zeros(10), np.zeros(9), 0.01, [1.0])
    with pytest.raises(ValueError, match="periods"):
        pair_spectra(np.zeros(10), np.zeros(10), 0.01, [0.0])
