"""Events and helpers of the planar kernel: the stick test, peaks between step ends, landing on an instant.

* :func:`stuck_until` / :func:`holds_at` — the closed-form first exit from a stuck state
  (quadratic in local time), the 2-D counterpart of
  :func:`isolator.solver.events.breakaway_time`, and the two-ends test of a whole stuck
  sample;
* :func:`locate_peak` — the largest |X|, |V| or transmitted |a| inside a step where its
  rate changes sign, by Illinois secant on DOP853 sub-steps from the step start, while
  the tangents at the bracket's ends (:func:`tangent_bound`) can still beat the best value;
* :func:`land_on` — the fraction of a step at which one state component reaches a
  target (a re-stop in the START form, the end of a LOG step exactly on a sample or on
  the instant n = 0), from the Hermite interpolant's crossing then Newton;
* :func:`coast_to_rest`, :func:`at_rest`, :func:`lift_off`, :func:`land`,
  :func:`record_event` — the phase changes of the kernel.
"""

from __future__ import annotations

import math

import numpy as np

from isolator.solver.jit import njit
from isolator.solver.planar_dop853 import dop853_step
from isolator.solver.planar_rk import (
    CARTESIAN,
    LOG,
    P_C,
    P_INV_R,
    P_KAPPA,
    P_MU_FAST,
    P_MU_K,
    P_MU_S,
    P_MU_SLOW,
    P_PENDULUM,
    P_VELDEP,
    POLAR,
    START,
    forcing,
    friction_coefficient,
    friction_slope,
    norm,
    rhs,
    start_direction,
)

# phases of the motion
PH_STUCK = 0
PH_SLIDE = 1
PH_APPROACH = 2
PH_START = 3
PH_FLIGHT = 4
PH_POLAR = 5  #: sliding slowly: speed and direction angle (POLAR form)


@njit(cache=True, _nrt=False)
def kappa_at(tau, prm, frc):
    """κ [1/s²] at local time τ of the interval."""
    return forcing(tau, 0.0, 0.0, prm, frc)[3]


@njit(cache=True, _nrt=False)
def kappa_of(nn, prm):
    """κ [1/s²] of a block in contact under the normal acceleration n: n/R (pendulum) or K/M."""
    return nn * prm[P_INV_R] if prm[P_PENDULUM] > 0.0 else prm[P_KAPPA]


@njit(cache=True, _nrt=False)
def holds_at(x1, x2, a_x, a_y, nn, prm):
    """Static friction holds a block at rest at X under ground acceleration a and normal n:
    n > 0 and |κX + a_g| ≤ µs n, with κ = n/R (pendulum) or K/M.

    Between two samples |κX + a_g| − µs n is convex in time (the norm of an affine
    function minus an affine function), so a block that holds at both ends of an
    interval holds throughout it.
    """
    if not nn > 0.0:
        return False
    kap = kappa_of(nn, prm)
    gx = kap * x1 + a_x
    gy = kap * x2 + a_y
    return norm(gx, gy) <= prm[P_MU_S] * nn


@njit(cache=True, _nrt=False)
def stuck_until(x1, x2, tau0, length, prm, frc):
    """First instant in [τ0, τ0 + length] where a stuck block must move.

    ``Q(u) = |G(u)|² − µs² n(u)²`` with ``G = κX + a_g`` linear in u = τ − τ0 is a
    quadratic; the block breaks away at its first upward zero, or lifts off where
    n reaches 0.

    Returns
    -------
    tuple
        ``(u, uplift)``: the offset u [s] (−1 if stuck throughout) and whether the
        exit is an uplift (n ≤ 0) rather than a break-away.
    """
    mu_s = prm[P_MU_S]
    _, _, nn, _, kdot, fx, fy = forcing(tau0, x1, x2, prm, frc)
    n1 = frc[5]
    u_up = -1.0
    if nn <= 0.0:
        return 0.0, True
    if n1 < 0.0:
        uu = -nn / n1
        if uu <= length:
            u_up = uu
    gx = -fx
    gy = -fy
    g1x = kdot * x1 + frc[1]
    g1y = kdot * x2 + frc[3]
    if holds_at(x1, x2, frc[0] + frc[1] * tau0, frc[2] + frc[3] * tau0, nn, prm) and holds_at(
            x1, x2, frc[0] + frc[1] * (tau0 + length), frc[2] + frc[3] * (tau0 + length), nn + n1 * length, prm):
        return -1.0, False  # stuck at both ends, so throughout (see holds_at): no quadratic to solve
    a = g1x * g1x + g1y * g1y - mu_s * mu_s * n1 * n1
    b = 2.0 * (gx * g1x + gy * g1y - mu_s * mu_s * nn * n1)
    c = gx * gx + gy * gy - mu_s * mu_s * nn * nn
    u_b = -1.0
    if c > 0.0:
        u_b = 0.0  # already beyond the static friction (e.g. a record that starts above µs n)
    elif a == 0.0:
        if b > 0.0:
            uu = -c / b
            if uu <= length:
                u_b = uu
    else:
        disc = b * b - 4.0 * a * c
        if disc >= 0.0:
            sq = math.sqrt(disc)
            q = -0.5 * (b + (sq if b >= 0.0 else -sq))
            r1 = q / a
            r2 = c / q if q != 0.0 else r1
            lo = min(r1, r2)
            hi = max(r1, r2)
            if 0.0 <= lo <= length and 2.0 * a * lo + b > 0.0:
                u_b = lo
            elif 0.0 <= hi <= length and 2.0 * a * hi + b > 0.0:
                u_b = hi
    if u_up >= 0.0 and (u_b < 0.0 or u_up < u_b):
        return u_up, True
    return u_b, False


@njit(cache=True, _nrt=False)
def velocity(phase, x, tau, y, prm, frc):
    """Relative velocity (V_x, V_y) [m/s] in any phase."""
    if phase == PH_STUCK:
        return 0.0, 0.0
    if phase == PH_APPROACH:
        r = math.exp(x)
        return r * y[2], r * y[3]
    if phase == PH_START:
        _, _, nn, kap, kdot, fx, fy = forcing(tau, y[0], y[1], prm, frc)
        fr = friction_coefficient(abs(y[2]), prm) * nn if nn > 0.0 else 0.0
        e1, e2 = start_direction(y[2], y[0], y[1], fx, fy, kap, kdot, frc, fr, prm[P_C])
        return y[2] * e1, y[2] * e2
    if phase == PH_POLAR:
        return y[7] * y[2], y[7] * y[3]
    return y[2], y[3]


@njit(cache=True, _nrt=False)
def start_lag(tau, y, prm, frc):
    """|sin θ|, the angle by which the slaved (START form) velocity trails F [-]."""
    _, _, _, _, _, fx, fy = forcing(tau, y[0], y[1], prm, frc)
    fm = norm(fx, fy)
    if fm == 0.0 or y[2] == 0.0:
        return 0.0
    v1, v2 = velocity(np.int64(PH_START), 0.0, tau, y, prm, frc)
    return abs(fx * v2 - fy * v1) / (fm * abs(y[2]))


@njit(cache=True, _nrt=False)
def transmitted(phase, x, tau, y, prm, frc):
    """Absolute acceleration of the mass (a_x, a_y) [m/s²]: a_g when stuck, else −(friction + κX + cV)."""
    axx, ayy, nn, kap, kdot, fx, fy = forcing(tau, y[0], y[1], prm, frc)
    if phase == PH_STUCK:
        return axx, ayy
    v1, v2 = velocity(phase, x, tau, y, prm, frc)
    r = norm(v1, v2)
    c = prm[P_C]
    e1 = 0.0
    e2 = 0.0
    if phase == PH_START:
        fr0 = friction_coefficient(abs(y[2]), prm) * nn if nn > 0.0 else 0.0
        e1, e2 = start_direction(y[2], y[0], y[1], fx, fy, kap, kdot, frc, fr0, c)
    elif r > 0.0:
        e1 = v1 / r
        e2 = v2 / r
    fr = friction_coefficient(r, prm) * nn if (nn > 0.0 and phase != PH_FLIGHT) else 0.0
    return -fr * e1 - kap * y[0] - c * v1, -fr * e2 - kap * y[1] - c * v2


@njit(cache=True, _nrt=False)
def rate_of_peak(which, mode, y, d):
    # d|X|²/2 dt (which 0) or d|V|²/2 dt (which 1) from a state and its derivative
    if which == 0:
        g = y[0] * d[0] + y[1] * d[1]
        if mode == LOG:
            g /= d[7]
        return g
    if mode == CARTESIAN:
        return y[2] * d[2] + y[3] * d[3]
    if mode == START:
        return y[2] * d[2]
    if mode == POLAR:
        return y[7] * d[7]
    return -1.0


@njit(cache=True, _nrt=False)
def peak_value(which, mode, y):
    if which == 0:
        return norm(y[0], y[1])
    if mode == CARTESIAN:
        return norm(y[2], y[3])
    if mode == POLAR:
        return abs(y[7])
    return abs(y[2])


@njit(cache=True, _nrt=False)
def acceleration_peak_rate(mode, x, y, d, prm, frc):
    """Transmitted acceleration of a sliding block in CARTESIAN, POLAR or LOG form: (|a|, a·a').

    a = V' + a_g = −µ(r) n e − κX − cV [m/s²] from the state and its derivative ``d``;
    a·a' [m²/s⁵] (half the time rate of |a|²) from
    a' = −(µ'(r) ṙ n + µ n') e − µ n e' − κ'X − κV − cV', every term known from (y, d):
    no extra evaluation of the right-hand side.  ``x`` is the independent variable
    (local time τ, or s = ln r in LOG form, where τ is y[7] and d/dt = d/ds ÷ dτ/ds).
    """
    tau = y[7] if mode == LOG else x
    axx, ayy, nn, kap, kdot, _, _ = forcing(tau, y[0], y[1], prm, frc)
    if mode == POLAR or mode == LOG:
        e1 = y[2]
        e2 = y[3]
        if mode == POLAR:
            r = y[7]
            rdot = d[7]
            ed1 = d[2]
            ed2 = d[3]
        else:
            r = math.exp(x)
            rdot = r / d[7]
            ed1 = d[2] / d[7]
            ed2 = d[3] / d[7]
        v1 = r * e1
        v2 = r * e2
        vd1 = rdot * e1 + r * ed1
        vd2 = rdot * e2 + r * ed2
    else:
        v1 = y[2]
        v2 = y[3]
        vd1 = d[2]
        vd2 = d[3]
        r = norm(v1, v2)
        e1 = 0.0
        e2 = 0.0
        rdot = 0.0
        ed1 = 0.0
        ed2 = 0.0
        if r > 0.0:
            e1 = v1 / r
            e2 = v2 / r
            rdot = e1 * vd1 + e2 * vd2
            ed1 = (vd1 - rdot * e1) / r
            ed2 = (vd2 - rdot * e2) / r
    a1 = vd1 + axx
    a2 = vd2 + ayy
    fr = 0.0
    frd = 0.0
    if frc[6] > 0.0 and nn > 0.0:
        fr = friction_coefficient(r, prm) * nn
        frd = friction_rate(r, rdot, nn, prm, frc)
    c = prm[P_C]
    ad1 = -frd * e1 - fr * ed1 - kdot * y[0] - kap * v1 - c * vd1
    ad2 = -frd * e2 - fr * ed2 - kdot * y[1] - kap * v2 - c * vd2
    return norm(a1, a2), a1 * ad1 + a2 * ad2


@njit(cache=True, _nrt=False)
def acceleration_bound(n0, n1, x_top, v_top, prm):
    """An upper bound of the transmitted acceleration |a| = |µ(r) n e + κX + cV| [m/s²] over a step.

    ``n0``, ``n1``: the normal acceleration at its ends (n is linear between); ``x_top``,
    ``v_top``: bounds of |X| [m] and |V| [m/s] over the step.  µ(r) ≤ max(µ_slow, µ_fast)
    (µk when constant), and κ ≤ n_max/R for a pendulum; an uplifted block (no friction, no
    restoring force on a pendulum) transmits less.
    """
    n_top = max(n0, n1, 0.0)
    mu = max(prm[P_MU_SLOW], prm[P_MU_FAST]) if prm[P_VELDEP] > 0.0 else prm[P_MU_K]
    return mu * n_top + kappa_of(n_top, prm) * x_top + prm[P_C] * v_top


@njit(cache=True, _nrt=False)
def tangent_bound(a0, g0, a1, g1, h):
    """Where the tangents at both ends of a step meet: the largest value a concave norm can take
    inside it, from its values a0, a1 and the rates of its square's half, g0 > 0 ≥ g1, over a
    time h [s].

    A value that rises and falls inside a step is concave around its peak: the peak is
    located (:func:`locate_peak`) only when this exceeds the largest value so far, and the
    location stops when it is within rounding of the best value found.
    """
    s0 = g0 / max(a0, 1e-300)
    s1 = g1 / max(a1, 1e-300)
    t = (a1 - a0 - s1 * h) / (s0 - s1)
    t = min(max(t, 0.0), h)
    return a0 + s0 * t


@njit(cache=True, _nrt=False)
def locate_peak(which, mode, x, y, f, h, v0, g0, v1, g1, span, prm, frc, yb, fb, atol, rtol, work):
    """Largest |X| (which 0), |V| (1) or transmitted |a| (2, not in START form) inside a step
    where its rate goes from + to −.

    ``v0``/``v1`` are the values at the step's ends, ``g0 > 0 ≥ g1`` half the time rates of
    their squares there (:func:`rate_of_peak`, :func:`acceleration_peak_rate`) and ``span``
    the step's duration [s].  Illinois secant on the rate, with DOP853 sub-steps from the
    step start, until the tangents at the bracket's ends (:func:`tangent_bound`, an upper
    bound around a concave peak) are within 1e-13 of the best value found.  ``work[1]``
    counts the sub-steps.
    """
    lo = 0.0
    hi = 1.0
    t_lo = 0.0
    t_hi = span
    v_lo = v0
    v_hi = v1
    r_lo = g0
    r_hi = g1
    glo = g0
    ghi = g1
    side = 0
    best = max(v0, v1)
    theta = glo / (glo - ghi)
    for _ in range(60):
        if not (lo < theta < hi):
            theta = 0.5 * (lo + hi)
        ok, _ = dop853_step(mode, x, y, f, theta * h, prm, frc, yb, fb, atol, rtol)
        work[1] += 1
        if not ok:
            hi = theta
            theta = 0.5 * (lo + hi)
            continue
        if which == 2:
            value, g = acceleration_peak_rate(mode, x + theta * h, yb, fb, prm, frc)
        else:
            value = peak_value(which, mode, yb)
            g = rate_of_peak(which, mode, yb, fb)
        best = max(best, value)
        t = yb[7] - y[7] if mode == LOG else theta * h
        if g > 0.0:
            lo = theta
            t_lo = t
            v_lo = value
            r_lo = g
            glo = g
            if side == 1:
                ghi *= 0.5
            side = 1
        else:
            hi = theta
            t_hi = t
            v_hi = value
            r_hi = g
            ghi = g
            if side == -1:
                glo *= 0.5
            side = -1
        if hi - lo < 1e-11 or tangent_bound(v_lo, r_lo, v_hi, r_hi, t_hi - t_lo) <= best * (1.0 + 1e-13):
            break
        theta = lo + (hi - lo) * glo / (glo - ghi)
    return best


@njit(cache=True, _nrt=False)
def land_on(mode, x, y, f, h, coord, target, end, end_rate, prm, frc, yb, fb, atol, rtol, work):
    """Fraction θ of a step at which component ``coord`` of the state reaches ``target``.

    The component must be monotone on the step, below the target at θ = 0 and
    at or beyond it at θ = 1 (sign-adjusted); ``end`` and ``end_rate`` are its value and
    derivative at θ = 1 (the caller has taken that step).  The first guess is where its
    cubic Hermite interpolant crosses; then Newton steps with the derivative of each
    DOP853 sub-step (from the step start), inside an Illinois bracket, to 1e-13 in θ;
    the state at θ is left in ``yb``/``fb``.  ``work[0]`` counts the sub-steps taken.
    """
    lo = 0.0
    hi = 1.0
    flo = y[coord] - target
    fhi = end - target
    sgn = 1.0 if fhi > flo else -1.0
    flo *= sgn
    fhi *= sgn
    close = 1e-13 * (fhi - flo)  # a crossing this close after the target is the target (θ to ~1e-13)
    theta = hermite_crossing(flo, sgn * h * f[coord], fhi, sgn * h * end_rate, 0.0)
    side = 0
    at_hi = False  # yb/fb hold the state at θ = hi
    for _ in range(80):
        if not (lo < theta < hi):
            theta = lo + (hi - lo) * (-flo) / (fhi - flo) if fhi != flo else 0.5 * (lo + hi)
            if not (lo < theta < hi):
                theta = 0.5 * (lo + hi)
        ok, _ = dop853_step(mode, x, y, f, theta * h, prm, frc, yb, fb, atol, rtol)
        work[0] += 1
        at_hi = False
        if not ok:
            hi = theta
            theta = -1.0
            continue
        val = sgn * (yb[coord] - target)
        if val < 0.0:
            lo = theta
            flo = val
            if side == 1:
                fhi *= 0.5
            side = 1
        else:
            hi = theta
            fhi = val
            at_hi = True
            if side == -1:
                flo *= 0.5
            side = -1
        if hi - lo < 1e-13 or 0.0 <= val <= close:
            break
        # Newton from here, aimed a hair past the target so that the next point lands on the crossed side
        slope = sgn * h * fb[coord]
        theta = theta - (val - 0.5 * close) / slope if slope > 0.0 else -1.0
    # finish on the upper end of the bracket: the crossing has happened there
    if not at_hi:
        dop853_step(mode, x, y, f, hi * h, prm, frc, yb, fb, atol, rtol)
        work[0] += 1
    return hi


@njit(cache=True, _nrt=False)
def hermite_crossing(y0, d0, y1, d1, target):
    """Fraction θ ∈ (0, 1) of a step where the cubic Hermite interpolant of one component reaches ``target``.

    ``y0``, ``y1`` are its values at the ends and ``d0``, ``d1`` its derivatives times the step, with
    y0 < target < y1; bisection on the cubic (60 halvings, no right-hand side evaluated).  A first guess:
    the caller takes a DOP853 sub-step to θ and checks where it lands.
    """
    lo = 0.0
    hi = 1.0
    for _ in range(60):
        th = 0.5 * (lo + hi)
        th2 = th * th
        th3 = th2 * th
        p = (2.0 * th3 - 3.0 * th2 + 1.0) * y0 + (th3 - 2.0 * th2 + th) * d0 + (3.0 * th2 - 2.0 * th3) * y1 \
            + (th3 - th2) * d1
        if p < target:
            lo = th
        else:
            hi = th
    return 0.5 * (lo + hi)


@njit(cache=True, _nrt=False)
def coast_to_rest(tau, y, r, rdot, target, prm, frc):
    """The last speed r [m/s] of a stop in closed form: r(t) = r + ṙ t + ½ r̈ t², direction e fixed.

    ``y[2], y[3]`` hold the direction e = V/|V|, ``rdot`` < 0 the deceleration [m/s²].  The speed's
    second derivative is r̈ = |F⊥|²/r + e·Ḟ − d(µn)/dt − c ṙ, with Ḟ = −κ'X − κ r e − a_g' (F⊥ the
    part of F across e; µ at the speed r, n and a_g linear in the interval).  The time to rest,
    the smallest root, is exact for a collinear motion under linear forcing (no spring, no
    dashpot); otherwise it errs by about the duration r/|ṙ| times (turn² + O(r)), and X by
    r²/|ṙ| times the turn, where turn = |de/ds| = |F⊥|/|ṙ| (tests/solver/test_planar_events.py):
    the kernel calls it at r = ``R_MIN_FACTOR`` of the speed scale (isolator.solver.planar) once
    the direction has settled (:func:`settled`), at a hundredth of that otherwise.
    X advances by the distance D = r t + ½ṙ t² + r̈ t³/6 along e (at most to ``target``), the
    input energy by the ground's work −a_g·e D at the mid-time and ½κ'|X|² t at the mid-point,
    the friction and viscous energies by µ(0) n D and c r² t/3.

    Returns
    -------
    float
        The time taken [s] (0 if rdot ≥ 0).
    """
    if not rdot < 0.0:
        return 0.0
    axx, ayy, nn, kap, kdot, fx, fy = forcing(tau, y[0], y[1], prm, frc)
    e1 = y[2]
    e2 = y[3]
    f_across = e1 * fy - e2 * fx
    rddot = f_across * f_across / r - kdot * (e1 * y[0] + e2 * y[1]) - kap * r - (e1 * frc[1] + e2 * frc[3]) \
        - prm[P_C] * rdot
    rddot -= friction_rate(r, rdot, nn, prm, frc)
    # smallest positive root of r + ṙt + ½r̈t² (the stable form); a discriminant kept ≥ ṙ²/4 bounds
    # the time at 4/3 of the constant-deceleration one where r̈ > 0 would keep the speed from zero
    disc = max(rdot * rdot - 2.0 * rddot * r, 0.25 * rdot * rdot)
    dtt = min(2.0 * r / (-rdot + math.sqrt(disc)), target - tau)
    dist = max(dtt * (r + dtt * (0.5 * rdot + dtt * rddot / 6.0)), 0.0)
    tm = tau + 0.5 * dtt
    # the work of the vertical motion ½κ'|X|² dt, at the mid-point position
    y[4] += 0.5 * kdot * ((y[0] + 0.5 * dist * e1) ** 2 + (y[1] + 0.5 * dist * e2) ** 2) * dtt
    y[0] += dist * e1
    y[1] += dist * e2
    y[4] -= ((frc[0] + frc[1] * tm) * e1 + (frc[2] + frc[3] * tm) * e2) * dist
    y[5] += friction_coefficient(0.0, prm) * max(nn, 0.0) * dist
    y[6] += prm[P_C] * r * r * dtt / 3.0
    return dtt


@njit(cache=True, _nrt=False)
def record_event(ev_t, ev_k, n_ev, time, kind):
    """Log an event (time [s], kind) while the arrays have room; returns the new count."""
    if n_ev < ev_t.shape[0]:
        ev_t[n_ev] = time
        ev_k[n_ev] = kind
    return n_ev + 1


@njit(cache=True, _nrt=False)
def at_rest(tau, y, prm, frc, f):
    """The block is at rest at τ: stick (returns PH_STUCK) or restart from rest (PH_START)."""
    y[2] = 0.0
    y[3] = 0.0
    if holds_at(y[0], y[1], frc[0] + frc[1] * tau, frc[2] + frc[3] * tau, frc[4] + frc[5] * tau, prm):
        return PH_STUCK
    rhs(np.int64(START), tau, y, prm, frc, f)
    return PH_START


@njit(cache=True, _nrt=False)
def lift_off(phase, x, tau, y, prm, frc, f):
    """Uplift: n reaches 0; the state becomes Cartesian, the phase FLIGHT."""
    v1, v2 = velocity(phase, x, tau, y, prm, frc)
    y[2] = v1
    y[3] = v2
    frc[6] = 0.0
    rhs(np.int64(CARTESIAN), tau, y, prm, frc, f)
    return PH_FLIGHT


@njit(cache=True, _nrt=False)
def land(tau, y, prm, frc, f):
    """Landing: n becomes positive; slide on, or (at rest) stick or start."""
    frc[6] = 1.0
    if y[2] != 0.0 or y[3] != 0.0:
        rhs(np.int64(CARTESIAN), tau, y, prm, frc, f)
        return PH_SLIDE
    return at_rest(tau, y, prm, frc, f)


@njit(cache=True, _nrt=False)
def mode_of(phase):
    """The integration form (mode) of a phase."""
    if phase == PH_APPROACH:
        return LOG
    if phase == PH_START:
        return START
    if phase == PH_POLAR:
        return POLAR
    return CARTESIAN


@njit(cache=True, _nrt=False)
def phase_of_mode(mode):
    """A moving phase whose state is in the integration form ``mode`` (for :func:`velocity`)."""
    if mode == LOG:
        return PH_APPROACH
    if mode == START:
        return PH_START
    if mode == POLAR:
        return PH_POLAR
    return PH_SLIDE


@njit(cache=True, _nrt=False)
def force_scale(tau, y, r, prm, frc):
    """|F| + µ(r) n [m/s²]: the force scale of the stop and LOG-entry tests."""
    return force_norm(tau, y, prm, frc) + friction_force(tau, r, prm, frc)


#: a stop's direction has settled when it turns by less than this angle per unit of ln r [rad]
SETTLED_TURN = 0.01


@njit(cache=True, _nrt=False)
def settled(tau, y, f, prm, frc):
    """Has the direction of a stop (LOG form: e = (y[2], y[3]), ``f`` = d/ds) settled?

    True when it turns by less than :data:`SETTLED_TURN` per unit of s = ln r (|de/ds| = |F⊥|/|ṙ|)
    and the force F = −κX − a_g is not behind the motion (e·F ≥ 0: behind, e sits near its
    unstable equilibrium −F/|F| and turns ever faster as r falls).  Then the closed-form finish
    along a fixed direction (:func:`coast_to_rest`) errs in the stop instant by about its duration
    r/|ṙ| times turn², and in X by r²/|ṙ| times the turn.
    """
    if norm(f[2], f[3]) > SETTLED_TURN:
        return False
    _, _, _, _, _, fx, fy = forcing(tau, y[0], y[1], prm, frc)
    return y[2] * fx + y[3] * fy >= 0.0


@njit(cache=True, _nrt=False)
def friction_rate(r, rdot, nn, prm, frc):
    """d(µ(r) n)/dt [m/s³] of a block sliding at speed r [m/s] with ṙ = ``rdot`` [m/s²] under the
    normal acceleration ``nn`` [m/s²] (its rate is ``frc[5]``); 0 out of contact."""
    if frc[6] > 0.0 and nn > 0.0:
        return friction_slope(r, prm) * rdot * nn + friction_coefficient(r, prm) * frc[5]
    return 0.0


@njit(cache=True, _nrt=False)
def friction_force(tau, r, prm, frc):
    """µ(r) n [m/s²] at local time τ (0 where n ≤ 0)."""
    nn = frc[4] + frc[5] * tau
    return friction_coefficient(r, prm) * nn if nn > 0.0 else 0.0


@njit(cache=True, _nrt=False)
def ground_norm(tau, frc):
    """|a_g| [m/s²] at local time τ of the interval."""
    return norm(frc[0] + frc[1] * tau, frc[2] + frc[3] * tau)


@njit(cache=True, _nrt=False)
def force_norm(tau, y, prm, frc):
    """|F| = |−κX − a_g| [m/s²]."""
    _, _, _, _, _, fx, fy = forcing(tau, y[0], y[1], prm, frc)
    return norm(fx, fy)


@njit(cache=True, _nrt=False)
def rim_gap(mode, x, y, f, h, theta, d2, prm, frc, yb, fb, atol, rtol, work):
    """|X|² − d² [m²] at the fraction θ of a step (a DOP853 sub-step from its start; state left in
    ``yb``/``fb``), +inf where the form is not valid there."""
    ok, _ = dop853_step(mode, x, y, f, theta * h, prm, frc, yb, fb, atol, rtol)
    work[0] += 1
    if not ok:
        return math.inf
    return yb[0] * yb[0] + yb[1] * yb[1] - d2


@njit(cache=True, _nrt=False)
def rim_crossing(mode, x, y, f, h, d2, prm, frc, yb, fb, atol, rtol, work):
    """Fraction θ of a step at which |X| first reaches the rim radius d (d² = ``d2``).

    The step starts at the independent variable ``x`` with state ``y`` and derivative ``f``
    in ``mode``, of size ``h``.  When its end is beyond the rim, the crossing is bracketed on
    [0, 1]; when it is not (a graze: |X| rises above d and falls back inside the step), the
    largest |X| is first located where the rate X·V changes sign (Illinois), and the crossing
    bracketed before it.  Then Illinois secant on |X(θ)|² − d², with DOP853 sub-steps from the
    step start, to 1e-15 in θ; the state on the crossed side (|X| ≥ d by rounding) is left in
    ``yb``/``fb``.  Returns −1 when the step never reaches the rim (every loop bounded).
    """
    g0 = y[0] * y[0] + y[1] * y[1] - d2
    if g0 >= 0.0:
        for k in range(y.shape[0]):
            yb[k] = y[k]
            fb[k] = f[k]
        return 0.0
    hi = 1.0
    fhi = rim_gap(mode, x, y, f, h, 1.0, d2, prm, frc, yb, fb, atol, rtol, work)
    if not fhi > 0.0:
        # a graze: the largest |X| where d|X|²/dt goes from + to −
        lo_p = 0.0
        hi_p = 1.0
        r_lo = rate_of_peak(np.int64(0), mode, y, f)
        r_hi = rate_of_peak(np.int64(0), mode, yb, fb)
        if not r_lo > 0.0 >= r_hi:
            return -1.0
        side = 0
        theta = r_lo / (r_lo - r_hi)
        best = -math.inf
        best_theta = -1.0
        for _ in range(100):
            if not (lo_p < theta < hi_p):
                theta = 0.5 * (lo_p + hi_p)
            gap = rim_gap(mode, x, y, f, h, theta, d2, prm, frc, yb, fb, atol, rtol, work)
            if gap > best and gap < math.inf:
                best = gap
                best_theta = theta
            if gap > 0.0:
                break
            rate = rate_of_peak(np.int64(0), mode, yb, fb)
            if rate > 0.0:
                lo_p = theta
                r_lo = rate
                if side == 1:
                    r_hi *= 0.5
                side = 1
            else:
                hi_p = theta
                r_hi = rate
                if side == -1:
                    r_lo *= 0.5
                side = -1
            if hi_p - lo_p < 1e-15:
                break
            theta = lo_p + (hi_p - lo_p) * r_lo / (r_lo - r_hi)
        if not best > 0.0:
            return -1.0
        hi = best_theta
        fhi = best
    lo = 0.0
    flo = g0
    side = 0
    for _ in range(200):
        theta = lo + (hi - lo) * (-flo) / (fhi - flo) if fhi < math.inf else 0.5 * (lo + hi)
        if not (lo < theta < hi):
            theta = 0.5 * (lo + hi)
        gap = rim_gap(mode, x, y, f, h, theta, d2, prm, frc, yb, fb, atol, rtol, work)
        if gap < 0.0:
            lo = theta
            flo = gap
            if side == 1:
                fhi *= 0.5
            side = 1
        else:
            hi = theta
            fhi = gap
            if side == -1:
                flo *= 0.5
            side = -1
        if hi - lo < 1e-15 or gap == 0.0:
            break
    rim_gap(mode, x, y, f, h, hi, d2, prm, frc, yb, fb, atol, rtol, work)
    return hi
