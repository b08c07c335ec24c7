"""Linear single-degree-of-freedom response: the friction-free case of the solver.

The same closed-form ramp segments as the friction kernel (first-order hold: the
record is linear between samples), so the response of an elastic oscillator to a
sampled record is exact — this is the Nigam–Jennings recursion, with the peaks
located between samples where the velocity changes sign.  Used for the elastic
response spectrum.  Samples need not be evenly spaced: with ``time_s`` each interval is
its own ramp (the basis evaluated per interval), the same closed forms.
"""

from __future__ import annotations

import math

import numpy as np

from isolator.solver.events import secant_guess, segment_root
from isolator.solver.jit import njit
from isolator.solver.segments import ramp_basis, segment_state

#: Sub-steps per sample interval allowed in :func:`linear_peak_displacement`.  A peak between
#: samples is located exactly only on pieces where the velocity is unimodal (a quarter of
#: the period), so the work per sample grows as dt/T: bounded here, which accepts dt up to
#: 25 T (0.5 s at the shortest period 0.02 s of the predominant-period search).
MAX_SUBSTEPS_PER_SAMPLE = 100


@njit(cache=True, inline="always")
def ramp_step(x, v, p, q, e0, e1, h1, h2, m, kappa):
    """One exact step of u'' + c u' + κ u = p + q t over a piece h, from (x, v) at its start.

    ``e0, e1, h1, h2`` are :func:`isolator.solver.segments.ramp_basis` over h, m = −c/2
    (the Nigam–Jennings recurrence, REVIEW_RULES 1.2).  Returns (x, v) at the piece's end.
    """
    return (e0 * x + e1 * (v - m * x) + p * h1 + q * h2,
            e0 * v + e1 * (m * v - kappa * x + p) + q * h1)


@njit(cache=True)
def _peak_displacement(acc, dt, c, kappa, n_sub, times, max_piece):
    # times: empty for a uniform record; otherwise sample times, each interval split
    # into pieces no longer than max_piece
    uniform = times.shape[0] == 0
    h = dt / n_sub
    e0, e1, h1, h2, _ = ramp_basis(h, c, kappa)
    m = -0.5 * c
    x = 0.0
    v = 0.0
    peak = 0.0
    n_sub_i = n_sub
    dt_i = dt
    for i in range(acc.shape[0] - 1):
        if not uniform:
            dt_i = times[i + 1] - times[i]
            n_sub_i = max(1, int(math.ceil(dt_i / max_piece)))
            h = dt_i / n_sub_i
            e0, e1, h1, h2, _ = ramp_basis(h, c, kappa)
        b = (acc[i + 1] - acc[i]) / dt_i
        q = -b
        for j in range(n_sub_i):
            p = -(acc[i] + b * (j * h))
            x1, v1 = ramp_step(x, v, p, q, e0, e1, h1, h2, m, kappa)
            # between samples |x| exceeds its ends by at most ~h max|v| (v changes sign there)
            if v * v1 < 0.0 and max(abs(x), abs(x1)) + h * max(abs(v), abs(v1)) > peak:
                # an extremum of x between the samples: locate it exactly
                sign = 1.0 if v > 0.0 else -1.0
                t_e = segment_root(np.int64(0), sign, 0.0, h, x, v, p, q, 0.0, 0.0, c, kappa, 0.0, secant_guess(0.0, h, v, v1))
                x_e, _, _, _ = segment_state(t_e, x, v, p, q, 0.0, 0.0, c, kappa, 0.0)
                if abs(x_e) > peak:
                    peak = abs(x_e)
            x = x1
            v = v1
            if abs(x) > peak:
                peak = abs(x)
    return peak


def linear_peak_displacement(acceleration_m_s2, dt_s: float, period_s: float, damping_ratio: float,
                             time_s=None) -> float:
    """Peak relative displacement of a linear oscillator under a sampled record.

    Parameters
    ----------
    acceleration_m_s2 : array_like
        Ground acceleration [m/s²], linear between samples.
    dt_s : float
        Sample interval [s].
    period_s : float
        Natural period T of the oscillator [s] > 0.
    damping_ratio : float
        Fraction of critical damping ζ [-] ≥ 0.
    time_s : array_like, optional
        Sample times [s] of a record whose steps are not all equal (``dt_s`` unused).

    Returns
    -------
    float
        max |X| [m], exact for the piecewise-linear record (peaks between samples included).

    Raises
    ------
    isolator.solver.record.RecordInputError
        If dt_s > 25 period_s (:data:`MAX_SUBSTEPS_PER_SAMPLE`): no accelerogram is that coarse.
    """
    omega = 2.0 * math.pi / period_s
    kappa = omega * omega
    c = 2.0 * damping_ratio * omega
    # pieces no longer than a quarter of the damped period keep the velocity unimodal
    n_sub = max(1, math.ceil(dt_s / (0.25 * period_s)))
    if n_sub > MAX_SUBSTEPS_PER_SAMPLE:
        from isolator.errors import RecordInputError

        raise RecordInputError(
            f"time step {dt_s:g} s is {dt_s / period_s:.4g} times the spectral period {period_s:g} s: the "
            f"exact peak needs {n_sub} sub-steps per sample (at most {MAX_SUBSTEPS_PER_SAMPLE}); accelerograms "
            "are sampled at 0.001 to 0.05 s")
    acc = np.ascontiguousarray(acceleration_m_s2, dtype=np.float64)
    times = np.empty(0) if time_s is None else np.ascontiguousarray(time_s, dtype=np.float64)
    return float(_peak_displacement(acc, float(dt_s), c, kappa, n_sub, times, 0.25 * period_s))


def pseudo_acceleration_spectrum(acceleration_m_s2, dt_s: float, periods_s, damping_ratio: float = 0.05,
                                 time_s=None):
    r"""Pseudo-acceleration response spectrum, exact for a piecewise-linear record.

    .. math::  PSA(T) = \left(\frac{2\pi}{T}\right)^2 \max_t |X(t)|

    Parameters
    ----------
    acceleration_m_s2 : array_like
        Ground acceleration [m/s²].
    dt_s : float
        Sample interval [s].
    periods_s : array_like
        Natural periods [s], each > 0.
    damping_ratio : float
        Fraction of critical damping [-] (5 % by default).
    time_s : array_like, optional
        Sample times [s] of a record whose steps are not all equal.

    Returns
    -------
    numpy.ndarray
        PSA at each period [m/s²].
    """
    periods = np.atleast_1d(np.asarray(periods_s, dtype=np.float64))
    if np.any(~np.isfinite(periods)) or np.any(periods <= 0.0):
        raise ValueError("periods must be finite and > 0")
    if not (math.isfinite(damping_ratio) and damping_ratio >= 0.0):
        raise ValueError(f"damping_ratio must be ≥ 0, got {damping_ratio!r}")
    return np.array([(2.0 * math.pi / T) ** 2
                     * linear_peak_displacement(acceleration_m_s2, dt_s, T, damping_ratio, time_s=time_s)
                     for T in periods])
