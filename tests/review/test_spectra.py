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


#: RotD50's angles in the comparison with solve_ivp (every 10°: the reference solves each angle's extrema)
ANGLES_DEG = np.arange(0.0, 180.0, 10.0)


def _roots(f, grid) -> list:
    """Every zero of ``f`` at a sign change between two points of ``grid``, by brentq."""
    from scipy.optimize import brentq

    values = f(grid)
    return [brentq(f, grid[k], grid[k + 1], xtol=1e-16) for k in np.flatnonzero(values[:-1] * values[1:] < 0)]


def _continuous_peaks(ax, ay, dt, period, zeta=0.05):
    """Peaks of the continuous responses by solve_ivp on the piecewise-linear pair, written independently.

    Both oscillators integrate together (DOP853, rtol 1e-12) interval by interval, each with its dense output.
    Every extremum between samples is found from a sign change of its derivative on 24 points of the dense
    output, then brentq: of u_x and u_y (u' = 0), of each rotated component at ``ANGLES_DEG`` (RotD50), of
    |u| (u·u' = 0).  Returns (max|u_x|, max|u_y|, max|u|, peaks over the angles).
    """
    omega = 2 * math.pi / period
    theta = np.radians(ANGLES_DEG)
    state = np.zeros(4)
    px = py = pv = 0.0
    rotated = np.zeros(theta.size)
    grid = np.linspace(0.0, dt, 24)
    for i in range(ax.size - 1):
        def rhs(t, y, i=i):
            gx = ax[i] + (ax[i + 1] - ax[i]) * t / dt
            gy = ay[i] + (ay[i + 1] - ay[i]) * t / dt
            return [y[1], -gx - 2 * zeta * omega * y[1] - omega ** 2 * y[0],
                    y[3], -gy - 2 * zeta * omega * y[3] - omega ** 2 * y[2]]

        dense = solve_ivp(rhs, (0.0, dt), state, method="DOP853", rtol=1e-12, atol=1e-15, dense_output=True).sol
        times = np.concatenate([grid, _roots(lambda t, d=dense: d(t)[1], grid),
                                _roots(lambda t, d=dense: d(t)[3], grid),
                                _roots(lambda t, d=dense: d(t)[0] * d(t)[1] + d(t)[2] * d(t)[3], grid)])
        u = dense(times)
        px, py = max(px, np.max(np.abs(u[0]))), max(py, np.max(np.abs(u[2])))
        pv = max(pv, np.max(np.hypot(u[0], u[2])))
        on_grid = dense(grid)
        for a, (c, s) in enumerate(zip(np.cos(theta), np.sin(theta), strict=True)):
            rotated[a] = max(rotated[a], np.max(np.abs(c * on_grid[0] + s * on_grid[2])))
            at = _roots(lambda t, d=dense, c=c, s=s: c * d(t)[1] + s * d(t)[3], grid)
            if at:
                w = dense(np.array(at))
                rotated[a] = max(rotated[a], np.max(np.abs(c * w[0] + s * w[2])))
        state = dense(dt)
    return px, py, pv, rotated


@pytest.mark.parametrize("period", [0.25, 1.0, 3.0])
def test_psa_and_rotd_against_solve_ivp_between_samples(period):
    ax, ay, dt = _noise_pair(n=150)
    s = pair_spectra(ax, ay, dt, [period])
    px, py, pv, rotated = _continuous_peaks(ax, ay, dt, period)
    w2 = (2 * math.pi / period) ** 2
    assert s["psa_x_m_s2"][0] == pytest.approx(w2 * px, rel=1e-8)
    assert s["psa_y_m_s2"][0] == pytest.approx(w2 * py, rel=1e-8)
    assert s["rotd100_m_s2"][0] == pytest.approx(w2 * pv, rel=1e-8)
    assert pv >= rotated.max() * (1 - 1e-12)  # RotD100 is the maximum over angles too
    assert rotd50(ax, ay, dt, [period], angles_deg=ANGLES_DEG)[0] == pytest.approx(w2 * np.median(rotated), rel=1e-8)


def test_two_samplings_of_one_piecewise_linear_pair_give_the_same_spectra():
    """Collinear samples added (every interval halved, or a third of them cut in three) change nothing but rounding:
    the peaks are those of the continuous response (issue 26: at the sample instants they moved by 1.6e-5)."""
    ax, ay, dt = _noise_pair(n=600)
    periods = np.array([0.05, 0.1, 0.3, 1.0, 3.0])
    t = dt * np.arange(ax.size)
    fine = dt / 2 * np.arange(2 * ax.size - 1)
    reference = pair_spectra(ax, ay, dt, periods)
    halved = pair_spectra(np.interp(fine, t, ax), np.interp(fine, t, ay), dt / 2, periods)
    for key, values in reference.items():
        np.testing.assert_allclose(halved[key], values, rtol=1e-11, err_msg=key)
    np.testing.assert_allclose(rotd50(np.interp(fine, t, ax), np.interp(fine, t, ay), dt / 2, periods),
                               rotd50(ax, ay, dt, periods), rtol=1e-11)


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


def test_component_psa_equals_the_solver_spectrum():
    """The solver's spectrum (solver/linear.py, its own loop over the record) finds the same peaks between
    samples: the two agree to rounding at every period, short ones (pieces inside a sample) included."""
    from isolator.solver.linear import pseudo_acceleration_spectrum

    ax, ay, dt = _noise_pair(n=800)
    periods = np.array([0.03, 0.1, 1.0, 2.0, 4.0])
    np.testing.assert_allclose(pair_spectra(ax, ay, dt, periods)["psa_x_m_s2"],
                               pseudo_acceleration_spectrum(ax, dt, periods), rtol=1e-12)


def test_bad_inputs_are_refused():
    with pytest.raises(ValueError, match="same length"):
        pair_spectra(np.zeros(10), np.zeros(9), 0.01, [1.0])
    with pytest.raises(ValueError, match="periods"):
        pair_spectra(np.zeros(10), np.zeros(10), 0.01, [0.0])
