r"""The slide of a single pendulum's slider along its rim, compiled: one degree of freedom, DOP853 with its events.

On the rim |X| = d, at angle θ with tangential speed w (:mod:`isolator.solver.planar_rim`), per unit mass:

    θ' = w / d,    w' = F·e_t − µ(|w|) n sgn w − c w,    F·e_t = −a_g·e_t

with a_g and n = g + a_z linear inside a sample interval; the energies (input, friction, viscous) are
integrated with it (the state y = (θ, w, E_in, E_f, E_v)).  The step is DOP853 (Dormand & Prince's 8(5,3)
pair, scipy's tableau written out in :mod:`isolator.solver.planar_multisurface_tableau`, scipy's error norm
and step-size rule) at ``rtol`` 1e-12, ``atol`` 1e-15, as scipy's ``solve_ivp`` was run here before.

**Events** are located on the integrator's own solution, to machine precision: the accepted step from
(s, y) of length σ, Φ(σ) = y + σ Σ b_i k_i(σ), is a smooth function of σ, so an event g(Φ(σ)) = 0 is
found by bracketing on [0, h] (Illinois, with bisection whenever it stalls) until the bracket is one or
two units in the last place of the local time.  Terminal: the stop (sgn·w falls to 0) and the lift-off
(the rim's reaction λ = F·e_r + w²/d falls to 0).  Not terminal: the peaks of |w| (w' = 0, falling in
the direction of motion) and of the transmitted acceleration |A| (A·A' = 0 falling), which update the
response's peaks.  ``tests/solver/test_planar_rim.py`` measures the result against an independent
reference (scipy ``solve_ivp`` in Cartesian form with a stiff penalty-free constraint).
"""

from __future__ import annotations

import math

import numpy as np

from isolator.solver import planar_multisurface_tableau as _dop
from isolator.solver.jit import njit

#: Relative and absolute tolerance of the step (θ [rad], w [m/s], energies [J/kg]).
RTOL = 1e-12
ATOL = 1e-15
#: Bound on the accepted and rejected steps of one slide inside one sample interval.
MAX_STEPS = 1_000_000
#: Bound on the iterations locating one event (bisection alone needs ≤ ~1100 for doubles; Illinois far fewer).
MAX_ROOT_ITERATIONS = 200

#: The parameter vector p of :func:`rim_slide` (one sample interval's forcing and the bearing).
P_AX0, P_AX1, P_AY0, P_AY1, P_N0, P_N1 = 0, 1, 2, 3, 4, 5
P_D, P_C, P_INV_R, P_KAPPA, P_PENDULUM = 6, 7, 8, 9, 10
P_VELDEP, P_MU_K, P_MU_FAST, P_MU_SLOW, P_RATE, P_SIGN = 11, 12, 13, 14, 15, 16
P_SIZE = 17

#: How a slide ended (the return value of :func:`rim_slide`).
HOW_END, HOW_STOP, HOW_LEAVE, HOW_GUARD = 0, 1, 2, -1

_A = np.ascontiguousarray(_dop.A)
_B = np.ascontiguousarray(_dop.B)
_C = np.ascontiguousarray(_dop.C)
_E3 = np.ascontiguousarray(_dop.E3)
_E5 = np.ascontiguousarray(_dop.E5)
_NS = _dop.N_STAGES
_M = 5  #: the state's size


@njit(cache=True)
def friction_coefficient(p, speed):
    """µ(|w|) [-]: µ_fast − (µ_fast − µ_slow) e^(−a|w|) with µ(v), else µ_k."""
    if p[P_VELDEP] > 0.0:
        return p[P_MU_FAST] - (p[P_MU_FAST] - p[P_MU_SLOW]) * math.exp(-p[P_RATE] * speed)
    return p[P_MU_K]


@njit(cache=True)
def rim_rhs(s, y, p, out):
    """y' at local time s (see the module docstring)."""
    th, w = y[0], y[1]
    cs, sn = math.cos(th), math.sin(th)
    axx, ayy, nn = p[P_AX0] + p[P_AX1] * s, p[P_AY0] + p[P_AY1] * s, p[P_N0] + p[P_N1] * s
    d = p[P_D]
    kdot = p[P_N1] * p[P_INV_R] if p[P_PENDULUM] > 0.0 else 0.0
    ft = axx * sn - ayy * cs  # F·e_t = −a_g·e_t (κX is radial)
    fr = friction_coefficient(p, abs(w)) * nn
    out[0] = w / d
    out[1] = ft - p[P_SIGN] * fr - p[P_C] * w
    out[2] = w * ft + 0.5 * kdot * d * d
    out[3] = fr * abs(w)
    out[4] = p[P_C] * w * w


@njit(cache=True)
def reaction(s, y, p):
    """λ = F·e_r + w²/d [m/s²]: the rim's inward reaction that holds the slider on it."""
    th, w = y[0], y[1]
    nn = p[P_N0] + p[P_N1] * s
    kappa = nn * p[P_INV_R] if p[P_PENDULUM] > 0.0 else p[P_KAPPA]
    fr = -kappa * p[P_D] - ((p[P_AX0] + p[P_AX1] * s) * math.cos(th) + (p[P_AY0] + p[P_AY1] * s) * math.sin(th))
    return fr + w * w / p[P_D]


@njit(cache=True)
def acceleration_norm(s, y, p):
    """|A| = |V' + a_g| [m/s²] sliding along the rim: A = a_g + w' e_t − (w²/d) e_r."""
    th, w = y[0], y[1]
    c, sn = math.cos(th), math.sin(th)
    axx, ayy, nn = p[P_AX0] + p[P_AX1] * s, p[P_AY0] + p[P_AY1] * s, p[P_N0] + p[P_N1] * s
    wdot = axx * sn - ayy * c - friction_coefficient(p, abs(w)) * nn * p[P_SIGN] - p[P_C] * w
    wr = w * w / p[P_D]
    return math.hypot(axx - wdot * sn - wr * c, ayy + wdot * c - wr * sn)


@njit(cache=True)
def acceleration_rate(s, y, p):
    """A·A' [m²/s⁵] sliding along the rim in the direction ``p[P_SIGN]``: half the rate of |A|².

    With e_r' = (w/d) e_t, e_t' = −(w/d) e_r: A' = a_g' + (w'' − w³/d²) e_t − (3 w w'/d) e_r, where
    w'' = F_t' − µ'(|w|) n w' − sgn µ n' − c w' and F_t' = −a_g'·e_t + (w/d) a_g·e_r.
    """
    th, w = y[0], y[1]
    d, sign, cc = p[P_D], p[P_SIGN], p[P_C]
    ax1, ay1, n1 = p[P_AX1], p[P_AY1], p[P_N1]
    c, sn = math.cos(th), math.sin(th)
    axx, ayy, nn = p[P_AX0] + ax1 * s, p[P_AY0] + ay1 * s, p[P_N0] + n1 * s
    r = abs(w)
    mu = friction_coefficient(p, r)
    slope = p[P_RATE] * (p[P_MU_FAST] - p[P_MU_SLOW]) * math.exp(-p[P_RATE] * r) if p[P_VELDEP] > 0.0 else 0.0
    ft = axx * sn - ayy * c
    wdot = ft - sign * mu * nn - cc * w
    ft_dot = ax1 * sn - ay1 * c + (w / d) * (axx * c + ayy * sn)
    wddot = ft_dot - slope * nn * wdot - sign * mu * n1 - cc * wdot
    at = wddot - w ** 3 / (d * d)
    ar = -3.0 * w * wdot / d
    a1 = axx + wdot * -sn - (w * w / d) * c
    a2 = ayy + wdot * c - (w * w / d) * sn
    return a1 * (ax1 + at * -sn + ar * c) + a2 * (ay1 + at * c + ar * sn)


@njit(cache=True)
def _step(s, y, f0, h, p, ynew, fnew, kk, yt):
    """One DOP853 step of length h from (s, y), y' = f0; returns scipy's error norm (≤ 1: accepted)."""
    for j in range(_M):
        kk[0, j] = f0[j]
    for q in range(1, _NS):
        for j in range(_M):
            acc = 0.0
            for r in range(q):
                acc += _A[q, r] * kk[r, j]
            yt[j] = y[j] + h * acc
        rim_rhs(s + _C[q] * h, yt, p, kk[q])
    for j in range(_M):
        acc = 0.0
        for q in range(_NS):
            acc += _B[q] * kk[q, j]
        ynew[j] = y[j] + h * acc
    rim_rhs(s + h, ynew, p, fnew)
    for j in range(_M):
        kk[_NS, j] = fnew[j]
    e5 = 0.0
    e3 = 0.0
    for j in range(_M):
        sc = ATOL + RTOL * max(abs(y[j]), abs(ynew[j]))
        a5 = 0.0
        a3 = 0.0
        for q in range(_NS + 1):
            a5 += _E5[q] * kk[q, j]
            a3 += _E3[q] * kk[q, j]
        e5 += (a5 / sc) ** 2
        e3 += (a3 / sc) ** 2
    if e5 == 0.0 and e3 == 0.0:
        return 0.0
    return abs(h) * e5 / math.sqrt((e5 + 0.01 * e3) * _M)


@njit(cache=True)
def _event(k, s, y, f, p):
    """Event function k at (s, y) with y' = f: 0 stop (sgn·w), 1 lift-off (λ), 2 peak of |w| (w'), 3 peak of |A|
    (A·A'), each signed so that the event is a fall through zero."""
    if k == 0:
        return p[P_SIGN] * y[1]
    if k == 1:
        return reaction(s, y, p)
    if k == 2:
        return p[P_SIGN] * f[1]
    return acceleration_rate(s, y, p)


@njit(cache=True)
def _falls(g0, g1):
    """A fall through zero over the step (scipy's ``direction = -1``), not a start at zero that rises."""
    return (g0 > 0.0 and g1 <= 0.0) or (g0 == 0.0 and g1 < 0.0)


@njit(cache=True)
def _locate(k, s, y, f0, h, p, ynew, fnew, kk, yt):
    """The step length σ ∈ (0, h] at which event k falls through zero on Φ(σ), to the last bits of s + σ; Φ(σ)
    is left in ynew, fnew (the side past the root: g ≤ 0)."""
    lo, hi = 0.0, h
    glo = _event(k, s, y, f0, p)
    _step(s, y, f0, hi, p, ynew, fnew, kk, yt)
    ghi = _event(k, s + hi, ynew, fnew, p)
    side = 0
    for _ in range(MAX_ROOT_ITERATIONS):
        if hi - lo <= 2.0 * np.finfo(np.float64).eps * max(abs(s + hi), abs(s)) or hi - lo <= 5e-324:
            break
        mid = hi - ghi * (hi - lo) / (ghi - glo) if ghi != glo else 0.5 * (lo + hi)
        if not (lo < mid < hi) or side == 3 or side == -3:  # Illinois stalled: bisect
            mid = 0.5 * (lo + hi)
            side = 0
        _step(s, y, f0, mid, p, ynew, fnew, kk, yt)
        gm = _event(k, s + mid, ynew, fnew, p)
        if gm > 0.0:
            lo, glo = mid, gm
            side = side + 1 if side > 0 else 1
            if side > 1:
                ghi *= 0.5
        else:
            hi, ghi = mid, gm
            side = side - 1 if side < 0 else -1
            if side < -1:
                glo *= 0.5
    _step(s, y, f0, hi, p, ynew, fnew, kk, yt)
    return hi


@njit(cache=True)
def rim_slide(p, tau, h_end, y, peaks):
    """Slide along the rim from local time tau to h_end, a stop or the lift-off; returns (local time, how).

    Parameters
    ----------
    p : numpy.ndarray
        The interval's forcing and the bearing (``P_*``); ``p[P_SIGN]`` is the direction of motion, ±1.
    tau, h_end : float
        Start and end of the slide inside the sample interval [s] (local time).
    y : numpy.ndarray
        (θ [rad], w [m/s], E_in, E_f, E_v [J/kg]) at tau, overwritten with the state at the returned time.
    peaks : numpy.ndarray
        (peak |w| [m/s], peak |A| [m/s²]), raised in place by the slide's step ends and peak events.

    Returns
    -------
    tuple
        (local time [s], ``HOW_END`` | ``HOW_STOP`` | ``HOW_LEAVE`` | ``HOW_GUARD``).
    """
    f0 = np.empty(_M)
    ynew = np.empty(_M)
    fnew = np.empty(_M)
    yev = np.empty(_M)
    fev = np.empty(_M)
    kk = np.empty((_NS + 1, _M))
    yt = np.empty(_M)
    g0 = np.empty(4)
    g1 = np.empty(4)
    s = tau
    rim_rhs(s, y, p, f0)
    for k in range(4):
        g0[k] = _event(k, s, y, f0, p)
    h = h_end - tau
    for _ in range(MAX_STEPS):
        if s >= h_end:
            return s, HOW_END
        hh = min(h, h_end - s)
        if h_end - (s + hh) <= 4.0 * np.finfo(np.float64).eps * abs(h_end):
            hh = h_end - s
        err = _step(s, y, f0, hh, p, ynew, fnew, kk, yt)
        if not err <= 1.0:
            h = hh * max(0.2, 0.9 * err ** (-1.0 / 8.0)) if err < np.inf else 0.2 * hh
            continue
        for k in range(4):
            g1[k] = _event(k, s + hh, ynew, fnew, p)
        # the first terminal event inside the step ends the slide there
        end = hh
        how = HOW_END
        for k in range(2):
            if _falls(g0[k], g1[k]):
                sigma = _locate(k, s, y, f0, hh, p, yev, fev, kk, yt)
                if sigma < end or how == HOW_END:
                    end = sigma
                    how = HOW_STOP if k == 0 else HOW_LEAVE
        # the peaks of |w| and |A| inside [s, s + end]
        for k in range(2, 4):
            if _falls(g0[k], g1[k]):
                sigma = _locate(k, s, y, f0, hh, p, yev, fev, kk, yt)
                if sigma <= end:
                    if k == 2:
                        peaks[0] = max(peaks[0], abs(yev[1]))
                    else:
                        peaks[1] = max(peaks[1], acceleration_norm(s + sigma, yev, p))
        if how != HOW_END:
            _step(s, y, f0, end, p, ynew, fnew, kk, yt)
            for j in range(_M):
                y[j] = ynew[j]
            peaks[0] = max(peaks[0], abs(y[1]))
            peaks[1] = max(peaks[1], acceleration_norm(s + end, y, p))
            return s + end, how
        s += hh
        for j in range(_M):
            y[j] = ynew[j]
            f0[j] = fnew[j]
        for k in range(4):
            g0[k] = g1[k]
        peaks[0] = max(peaks[0], abs(y[1]))
        peaks[1] = max(peaks[1], acceleration_norm(s, y, p))
        h = hh * (10.0 if err == 0.0 else min(10.0, max(0.2, 0.9 * err ** (-1.0 / 8.0))))
    return s, HOW_GUARD
