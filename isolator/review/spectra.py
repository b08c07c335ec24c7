r"""Response spectra of record pairs: 5 %-damped PSA per component, RotD100 and RotD50.

The oscillator ``u'' + 2ζωu' + ω²u = −a_g(t)`` starts at rest and the record is linear
between samples (first-order hold), so one step of the solver's closed-form ramp segment
(:func:`isolator.solver.segments.ramp_basis`, the Nigam–Jennings recurrence of
:mod:`isolator.solver.linear`, REVIEW_RULES 1.2) is exact.  Conventions, stated in every
review: peaks are taken at the sample instants, with each sample interval cut into
``ceil(20 dt / T)`` equal pieces for periods shorter than 20 samples (a sampled sine of
≥ 20 points per period reads its peak within 1 − cos(π/20) = 1.2 %); no padding, no
filtering.

.. math::  PSA(T) = \omega^2 \max_t |u(t)|,\qquad
           RotD100(T) = \omega^2 \max_t \sqrt{u_x(t)^2 + u_y(t)^2}

(RotD100 is the maximum over horizontal angles of the rotated component's PSA, exactly
the vector form above: Boore 2010, REVIEW_RULES 1.3.)  RotD50 is the median over θ = 0…179°
(1° steps) of ω² max_t |u_x cos θ + u_y sin θ| — informational only.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from isolator.solver.linear import ramp_step
from isolator.solver.segments import ramp_basis

#: minimum number of recurrence steps per oscillator period (see the module docstring)
STEPS_PER_PERIOD = 20
ROTD50_ANGLES_DEG = np.arange(180.0)


@njit(cache=True)
def _coefficients(omega, zeta, dt, n_sub):
    """κ = ω², m = −ζω, the piece length h = dt/n_sub and the ramp basis (E0, E1, H1, H2) over h."""
    kappa = omega * omega
    c = 2.0 * zeta * omega
    h = dt / n_sub
    e0, e1, h1, h2, _ = ramp_basis(h, c, kappa)
    return kappa, -0.5 * c, h, e0, e1, h1, h2


@njit(cache=True)
def _pair_peaks(ax, ay, dt, omegas, zeta, n_subs, out):
    """Per period: max|u_x|, max|u_y|, max|(u_x, u_y)| at the (sub)sample instants → out[:, 0:3]."""
    n = ax.shape[0]
    for k in range(omegas.shape[0]):
        n_sub = n_subs[k]
        kappa, m, h, e0, e1, h1, h2 = _coefficients(omegas[k], zeta, dt, n_sub)
        x1 = 0.0
        v1 = 0.0
        x2 = 0.0
        v2 = 0.0
        p1 = 0.0
        p2 = 0.0
        pv = 0.0
        for i in range(n - 1):
            b1 = (ax[i + 1] - ax[i]) / dt
            b2 = (ay[i + 1] - ay[i]) / dt
            for j in range(n_sub):
                x1, v1 = ramp_step(x1, v1, -(ax[i] + b1 * (j * h)), -b1, e0, e1, h1, h2, m, kappa)
                x2, v2 = ramp_step(x2, v2, -(ay[i] + b2 * (j * h)), -b2, e0, e1, h1, h2, m, kappa)
                p1 = max(p1, abs(x1))
                p2 = max(p2, abs(x2))
                r2 = x1 * x1 + x2 * x2
                pv = max(pv, r2)
        out[k, 0] = p1
        out[k, 1] = p2
        out[k, 2] = math.sqrt(pv)


@njit(cache=True)
def _rotd50_peaks(ax, ay, dt, omega, zeta, n_sub, cosines, sines, out):
    """Peak |u_x cos θ + u_y sin θ| for each angle θ at one period → out[:]."""
    n = ax.shape[0]
    kappa, m, h, e0, e1, h1, h2 = _coefficients(omega, zeta, dt, n_sub)
    x1 = 0.0
    v1 = 0.0
    x2 = 0.0
    v2 = 0.0
    for a in range(out.shape[0]):
        out[a] = 0.0
    for i in range(n - 1):
        b1 = (ax[i + 1] - ax[i]) / dt
        b2 = (ay[i + 1] - ay[i]) / dt
        for j in range(n_sub):
            x1, v1 = ramp_step(x1, v1, -(ax[i] + b1 * (j * h)), -b1, e0, e1, h1, h2, m, kappa)
            x2, v2 = ramp_step(x2, v2, -(ay[i] + b2 * (j * h)), -b2, e0, e1, h1, h2, m, kappa)
            for a in range(out.shape[0]):
                u = abs(x1 * cosines[a] + x2 * sines[a])
                out[a] = max(out[a], u)


def _prepare(ax, ay, dt_s, periods_s, damping_ratio):
    ax = np.ascontiguousarray(ax, dtype=np.float64)
    ay = np.ascontiguousarray(ay, dtype=np.float64)
    if ax.shape != ay.shape or ax.ndim != 1 or ax.size < 2:
        raise ValueError("the two components must be 1-D arrays of the same length (≥ 2 samples)")
    periods = np.atleast_1d(np.asarray(periods_s, dtype=np.float64))
    if np.any(~np.isfinite(periods)) or np.any(periods <= 0.0):
        raise ValueError("periods must be finite and > 0")
    if not (dt_s > 0 and math.isfinite(dt_s)):
        raise ValueError(f"dt_s must be > 0, got {dt_s!r}")
    if not (math.isfinite(damping_ratio) and 0.0 <= damping_ratio < 1.0):
        raise ValueError(f"damping_ratio must be in [0, 1), got {damping_ratio!r}")
    omegas = 2.0 * np.pi / periods
    n_subs = np.maximum(1, np.ceil(STEPS_PER_PERIOD * dt_s / periods)).astype(np.int64)
    return ax, ay, periods, omegas, n_subs


def pair_spectra(ax_m_s2, ay_m_s2, dt_s: float, periods_s, damping_ratio: float = 0.05) -> dict:
    """PSA of each component and RotD100 of the pair.

    Parameters
    ----------
    ax_m_s2, ay_m_s2 : array_like
        The two horizontal ground accelerations, same length [m/s²].
    dt_s : float
        Sample interval [s].
    periods_s : array_like
        Oscillator periods [s], > 0.
    damping_ratio : float
        Fraction of critical damping [-] (5 %).

    Returns
    -------
    dict
        ``psa_x_m_s2``, ``psa_y_m_s2``, ``rotd100_m_s2`` (arrays over the periods [m/s²]).
    """
    ax, ay, periods, omegas, n_subs = _prepare(ax_m_s2, ay_m_s2, dt_s, periods_s, damping_ratio)
    out = np.empty((periods.size, 3))
    _pair_peaks(ax, ay, float(dt_s), omegas, float(damping_ratio), n_subs, out)
    w2 = omegas ** 2
    return {"psa_x_m_s2": w2 * out[:, 0], "psa_y_m_s2": w2 * out[:, 1], "rotd100_m_s2": w2 * out[:, 2]}


def rotd50(ax_m_s2, ay_m_s2, dt_s: float, periods_s, damping_ratio: float = 0.05,
           angles_deg=ROTD50_ANGLES_DEG) -> np.ndarray:
    """RotD50: median over angles of the rotated component's PSA (informational, Boore 2010) [m/s²].

    Parameters are those of :func:`pair_spectra`; ``angles_deg`` the rotation angles [°].
    """
    ax, ay, periods, omegas, n_subs = _prepare(ax_m_s2, ay_m_s2, dt_s, periods_s, damping_ratio)
    theta = np.radians(np.asarray(angles_deg, dtype=np.float64))
    cosines, sines = np.cos(theta), np.sin(theta)
    peaks = np.empty(theta.size)
    result = np.empty(periods.size)
    for k in range(periods.size):
        _rotd50_peaks(ax, ay, float(dt_s), float(omegas[k]), float(damping_ratio), int(n_subs[k]), cosines, sines,
                      peaks)
        result[k] = omegas[k] ** 2 * float(np.median(peaks))
    return result
