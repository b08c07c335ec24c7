r"""Response spectra of record pairs: 5 %-damped PSA per component, RotD100 and RotD50.

The oscillator ``u'' + 2ζωu' + ω²u = −a_g(t)`` starts at rest and the record is linear
between samples (first-order hold), so one step of the solver's closed-form ramp segment
(:func:`isolator.solver.segments.ramp_basis`, the Nigam–Jennings recurrence of
:mod:`isolator.solver.linear`, REVIEW_RULES 1.2) is exact.  The peaks are those of the
continuous response, between samples included: each sample interval is cut into
``ceil(8 dt / T)`` equal pieces, and an extremum inside a piece is located to rounding from
the closed form (:func:`_interior_peak`; the resultant's maxima by :func:`_vector_peak`).
So the spectra of one piecewise-linear signal do not depend on how it is sampled (extra
collinear samples change them by rounding only: issue 26).  No padding, no filtering.

.. math::  PSA(T) = \omega^2 \max_t |u(t)|,\qquad
           RotD100(T) = \omega^2 \max_t \sqrt{u_x(t)^2 + u_y(t)^2}

(RotD100 is the maximum over horizontal angles of the rotated component's PSA, exactly
the vector form above: Boore 2010, REVIEW_RULES 1.3.)  RotD50 is the median over θ = 0…179°
(1° steps) of ω² max_t |u_x cos θ + u_y sin θ| — informational only.
"""

from __future__ import annotations

import math

import numpy as np

from isolator.solver.events import secant_guess
from isolator.solver.jit import njit
from isolator.solver.linear import ramp_step
from isolator.solver.segments import ramp_basis

#: Pieces per oscillator period at least (each sample interval is cut into ``ceil(8 dt / T)`` equal pieces).  A
#: piece of at most T/8 is shorter than half a damped period, so the relative acceleration (a damped sinusoid
#: between samples) changes sign at most once in it: the velocity is monotone on at most two parts, and each
#: part holds at most one extremum of the displacement, located exactly (:func:`_interior_peak`).
STEPS_PER_PERIOD = 8
#: Points per piece at which d|u|²/dt is looked at for the resultant's maxima where its derivative turns inside
#: the piece (RotD100, see :func:`_vector_peak`).
VECTOR_CHECKS = 4
ROTD50_ANGLES_DEG = np.arange(180.0)
#: Pieces per block of the second pass: a block whose piece ends all lie below the peaks less their margin is
#: skipped whole.
BLOCK = 64


@njit(cache=True)
def _coefficients(omega, zeta, dt, n_sub):
    """κ = ω², c = 2ζω, m = −ζω, the piece length h = dt/n_sub and the ramp basis (E0, E1, H1, H2) over h."""
    kappa = omega * omega
    c = 2.0 * zeta * omega
    h = dt / n_sub
    e0, e1, h1, h2, _ = ramp_basis(h, c, kappa)
    return kappa, c, -0.5 * c, h, e0, e1, h1, h2


@njit(cache=True, inline="always")
def _may_exceed(x0, x1, v0, v1, a0, a1, h, peak):
    """Whether |u| inside a piece may exceed ``peak`` (cheap, never false where it can).

    With no sign change of the acceleration, v is monotone: u has an interior extremum only
    if v changes sign, and it exceeds the nearer end by at most min(τ|v0|, (h − τ)|v1|) ≤
    h|v0||v1|/(|v0| + |v1|).  Otherwise (v turns inside) a Taylor bound of the excursion.
    """
    if a0 * a1 >= 0.0:
        if v0 * v1 >= 0.0:
            return False
        return max(abs(x0), abs(x1)) + h * abs(v0) * abs(v1) / (abs(v0) + abs(v1)) > peak
    return max(abs(x0), abs(x1)) + 2.0 * h * (max(abs(v0), abs(v1)) + h * max(abs(a0), abs(a1))) > peak


@njit(cache=True, inline="always")
def _piece(tau, x0, v0, p, q, c, kappa):
    """(u, u', u'', jerk) at τ of u'' + c u' + κ u = p + q τ from (x0, v0), underdamped (c² < 4κ), closed form.

    u = (p − c q/κ)/κ + q τ/κ + e^{mτ}(A cos ω_d τ + B sin ω_d τ), m = −c/2, ω_d² = κ − m²:
    the ramp segment of :func:`isolator.solver.segments.segment_state` written for a spectrum's
    oscillator (ζ < 1), one exponential and one sine and cosine per call.
    """
    m = -0.5 * c
    wd = math.sqrt(kappa - m * m)
    a_h = x0 - (p - c * q / kappa) / kappa
    b_h = (v0 - q / kappa - m * a_h) / wd
    e = math.exp(m * tau)
    cs = math.cos(wd * tau)
    sn = math.sin(wd * tau)
    # each derivative of e^{mτ}(A cos + B sin) is e^{mτ}(A' cos + B' sin), A' = mA + ω_d B, B' = mB − ω_d A
    a1 = m * a_h + wd * b_h
    b1 = m * b_h - wd * a_h
    a2 = m * a1 + wd * b1
    b2 = m * b1 - wd * a1
    a3 = m * a2 + wd * b2
    b3 = m * b2 - wd * a2
    return ((p - c * q / kappa) / kappa + q * tau / kappa + e * (a_h * cs + b_h * sn),
            q / kappa + e * (a1 * cs + b1 * sn), e * (a2 * cs + b2 * sn), e * (a3 * cs + b3 * sn))


@njit(cache=True)
def _piece_root(which, sign, lo, hi, x0, v0, p, q, c, kappa):
    """The zero of u' (which = 1) or u'' (which = 2) in [lo, hi], where sign·f falls from > 0 to ≤ 0.

    Newton from the secant, kept inside the bracket (bisection otherwise), to rounding; at most
    200 iterations.
    """
    f_lo = sign * _piece(lo, x0, v0, p, q, c, kappa)[which]
    f_hi = sign * _piece(hi, x0, v0, p, q, c, kappa)[which]
    a = lo
    b = hi
    t = secant_guess(lo, hi, f_lo, f_hi)
    if not (lo < t < hi):
        t = 0.5 * (lo + hi)
    for _ in range(200):
        state = _piece(t, x0, v0, p, q, c, kappa)
        t, a, b, done = _newton_in_bracket(t, sign * state[which], sign * state[which + 1], a, b)
        if done:
            break
    return t


@njit(cache=True, inline="always")
def _newton_in_bracket(t, f, df, a, b):
    """One step of Newton's method kept inside [a, b] where f falls through zero: (t, a, b, converged).

    The bracket shrinks to the side of t where f keeps its sign; a Newton step that leaves it is
    replaced by bisection; converged when the bracket or the step reaches rounding.
    """
    if f == 0.0:
        return t, a, b, True
    if f > 0.0:
        a = t
    else:
        b = t
    if b - a <= 4e-16 * b:
        return b, a, b, True
    t_new = t - f / df if df != 0.0 else 0.5 * (a + b)
    if not (a < t_new < b):
        return 0.5 * (a + b), a, b, False
    return t_new, a, b, abs(t_new - t) <= 2e-16 * t


@njit(cache=True)
def _interior_peak(x0, v0, v1, a0, a1, p, q, h, c, kappa):
    """The largest |u| at an extremum strictly inside one piece (0 if none), exact.

    u'' + c u' + κ u = p + q τ on [0, h], from (x0, v0); v1, a1 the velocity and relative
    acceleration at h.  The acceleration is a damped sinusoid (it solves the homogeneous
    equation), so on a piece shorter than half a period it changes sign at most once: the
    velocity is monotone on each side of that instant, and every zero of the velocity (an
    extremum of u) is bracketed by a sign change, then located to rounding (:func:`_piece_root`).
    """
    s0 = v0 if v0 != 0.0 else a0  # the sign of v just after τ = 0
    best = 0.0
    if s0 * v1 < 0.0:  # one zero of v
        t = _piece_root(1, 1.0 if s0 > 0.0 else -1.0, 0.0, h, x0, v0, p, q, c, kappa)
        best = abs(_piece(t, x0, v0, p, q, c, kappa)[0])
    elif a0 * a1 < 0.0 and s0 != 0.0 and min(abs(v0), abs(v1)) <= 2.0 * h * max(abs(a0), abs(a1)):
        # v turns inside and comes near zero (it moves by at most ~h max|a| in the piece): it may cross zero twice
        ta = _piece_root(2, 1.0 if a0 > 0.0 else -1.0, 0.0, h, x0, v0, p, q, c, kappa)
        va = _piece(ta, x0, v0, p, q, c, kappa)[1]
        if va * s0 < 0.0:
            sign = 1.0 if s0 > 0.0 else -1.0
            t1 = _piece_root(1, sign, 0.0, ta, x0, v0, p, q, c, kappa)
            t2 = _piece_root(1, -sign, ta, h, x0, v0, p, q, c, kappa)
            best = max(abs(_piece(t1, x0, v0, p, q, c, kappa)[0]), abs(_piece(t2, x0, v0, p, q, c, kappa)[0]))
    return best


@njit(cache=True, inline="always")
def _pair_state(t, x1, v1, x2, v2, p1, q1, p2, q2, c, kappa):
    """(u_x, u_y, g = u·u', g' = |u'|² + u·u'') at τ of a piece."""
    ux, vx, ax, _ = _piece(t, x1, v1, p1, q1, c, kappa)
    uy, vy, ay, _ = _piece(t, x2, v2, p2, q2, c, kappa)
    return ux, uy, ux * vx + uy * vy, vx * vx + vy * vy + ux * ax + uy * ay


@njit(cache=True)
def _vector_peak(x1, v1, x2, v2, p1, q1, p2, q2, h, c, kappa, checks):
    """The largest |(u_x, u_y)|² at a maximum inside one piece (0 if none).

    Maxima of |u|² are where g = u·u' falls through zero.  g is looked at at ``checks`` + 1
    points of the piece and each fall is located to rounding by Newton in its bracket
    (g' = |u'|² + u·u'', closed form).  The caller asks for one check (the piece's ends)
    when g falls between them, and :data:`VECTOR_CHECKS` when g' changes sign in the piece
    (g may then rise and fall inside); near the peak of a response |u|² is dominated by the
    oscillator, g' ≈ |u'|² − κ|u|² < 0, and g falls once.
    """
    best = 0.0
    t_lo = 0.0
    _, _, g_lo, _ = _pair_state(0.0, x1, v1, x2, v2, p1, q1, p2, q2, c, kappa)
    for k in range(1, checks + 1):
        t_hi = h * k / checks
        _, _, g_hi, _ = _pair_state(t_hi, x1, v1, x2, v2, p1, q1, p2, q2, c, kappa)
        if g_lo > 0.0 and g_hi < 0.0:
            a = t_lo
            b = t_hi
            t = t_lo + (t_hi - t_lo) * g_lo / (g_lo - g_hi)
            for _ in range(200):
                _, _, g, dg = _pair_state(t, x1, v1, x2, v2, p1, q1, p2, q2, c, kappa)
                t, a, b, done = _newton_in_bracket(t, g, dg, a, b)
                if done:
                    break
            ux, uy, _, _ = _pair_state(t, x1, v1, x2, v2, p1, q1, p2, q2, c, kappa)
            best = max(best, ux * ux + uy * uy)
        t_lo = t_hi
        g_lo = g_hi
    return best


@njit(cache=True)
def _pair_states(ax, ay, dt, n_sub, kappa, m, h, e0, e1, h1, h2):
    """(u_x, u_x', u_y, u_y') at the start of every piece and the end of the last, by the exact recurrence."""
    n = ax.shape[0]
    states = np.empty(((n - 1) * n_sub + 1, 4))
    states[0, :] = 0.0
    x1 = 0.0
    v1 = 0.0
    x2 = 0.0
    v2 = 0.0
    piece = 0
    for i in range(n - 1):
        b1 = (ax[i + 1] - ax[i]) / dt
        b2 = (ay[i + 1] - ay[i]) / dt
        for j in range(n_sub):
            x1, v1 = ramp_step(x1, v1, -(ax[i] + b1 * (j * h)), -b1, e0, e1, h1, h2, m, kappa)
            x2, v2 = ramp_step(x2, v2, -(ay[i] + b2 * (j * h)), -b2, e0, e1, h1, h2, m, kappa)
            piece += 1
            states[piece, 0] = x1
            states[piece, 1] = v1
            states[piece, 2] = x2
            states[piece, 3] = v2
    return states


@njit(cache=True, nogil=True)  # nogil: the review computes spectra while a thread collects the analyses
def _pair_peaks(ax, ay, dt, omegas, zeta, n_subs, out):
    """Per period: max|u_x|, max|u_y|, max|(u_x, u_y)| over time, between samples included → out[:, 0:3].

    Two passes per period: the recurrence, keeping the state at every piece end and the peaks
    there; then only the pieces whose inside may exceed those peaks are searched
    (:func:`_interior_peak`, :func:`_vector_peak`): a handful per period, not every piece
    where a running maximum grew.
    """
    n = ax.shape[0]
    g1 = np.max(np.abs(ax))
    g2 = np.max(np.abs(ay))
    gv = np.sqrt(np.max(ax * ax + ay * ay))
    for k in range(omegas.shape[0]):
        n_sub = n_subs[k]
        kappa, c, m, h, e0, e1, h1, h2 = _coefficients(omegas[k], zeta, dt, n_sub)
        total = (n - 1) * n_sub
        states = _pair_states(ax, ay, dt, n_sub, kappa, m, h, e0, e1, h1, h2)
        # per block of BLOCK pieces, the largest |u_x|, |u_y| and |u|² at the ends of its pieces
        blocks = np.zeros((total // BLOCK + 1, 3))
        p1 = 0.0
        p2 = 0.0
        pv = 0.0
        s1 = 0.0
        s2 = 0.0
        sv = 0.0
        for piece in range(1, total + 1):
            x1, v1, x2, v2 = states[piece, 0], states[piece, 1], states[piece, 2], states[piece, 3]
            p1 = max(p1, abs(x1))
            p2 = max(p2, abs(x2))
            pv = max(pv, x1 * x1 + x2 * x2)
            s1 = max(s1, abs(v1))
            s2 = max(s2, abs(v2))
            sv = max(sv, v1 * v1 + v2 * v2)
            # the state ends piece `piece - 1` and starts piece `piece`: it belongs to both their blocks
            for block in ((piece - 1) // BLOCK, piece // BLOCK):
                blocks[block, 0] = max(blocks[block, 0], abs(x1))
                blocks[block, 1] = max(blocks[block, 1], abs(x2))
                blocks[block, 2] = max(blocks[block, 2], x1 * x1 + x2 * x2)
        # a piece whose ends are below these cannot hold a higher peak: its inside exceeds its ends by at most
        # 2h(max|u'| + h max|u''|), with |u''| ≤ max|a_g| + c max|u'| + κ max|u| (the bounds of _may_exceed)
        low1 = p1 - 2.0 * h * (s1 + h * (g1 + c * s1 + kappa * p1))
        low2 = p2 - 2.0 * h * (s2 + h * (g2 + c * s2 + kappa * p2))
        rv = math.sqrt(pv)
        low_v = rv - 2.0 * h * (math.sqrt(sv) + h * (gv + c * math.sqrt(sv) + kappa * rv))
        low_v2 = low_v * low_v if low_v > 0.0 else -1.0
        for block in range(blocks.shape[0]):
            if blocks[block, 0] <= low1 and blocks[block, 1] <= low2 and blocks[block, 2] <= low_v2:
                continue
            for piece in range(block * BLOCK, min(total, (block + 1) * BLOCK)):
                i = piece // n_sub
                j = piece - i * n_sub
                b1 = (ax[i + 1] - ax[i]) / dt
                b2 = (ay[i + 1] - ay[i]) / dt
                x1, v1, x2, v2 = states[piece, 0], states[piece, 1], states[piece, 2], states[piece, 3]
                y1, w1, y2, w2 = states[piece + 1, 0], states[piece + 1, 1], states[piece + 1, 2], states[piece + 1, 3]
                if (max(abs(x1), abs(y1)) <= low1 and max(abs(x2), abs(y2)) <= low2
                        and max(x1 * x1 + x2 * x2, y1 * y1 + y2 * y2) <= low_v2):
                    continue
                f1 = -(ax[i] + b1 * (j * h))
                f2 = -(ay[i] + b2 * (j * h))
                a1s = f1 - c * v1 - kappa * x1
                a1e = f1 - b1 * h - c * w1 - kappa * y1
                a2s = f2 - c * v2 - kappa * x2
                a2e = f2 - b2 * h - c * w2 - kappa * y2
                if _may_exceed(x1, y1, v1, w1, a1s, a1e, h, p1):
                    p1 = max(p1, _interior_peak(x1, v1, w1, a1s, a1e, f1, -b1, h, c, kappa))
                if _may_exceed(x2, y2, v2, w2, a2s, a2e, h, p2):
                    p2 = max(p2, _interior_peak(x2, v2, w2, a2s, a2e, f2, -b2, h, c, kappa))
                # |u|² rises then falls inside (g = u·u' from + to −), or g' = |u'|² + u·u'' turns inside
                g_start = x1 * v1 + x2 * v2
                g_end = y1 * w1 + y2 * w2
                dg_start = v1 * v1 + v2 * v2 + x1 * a1s + x2 * a2s
                dg_end = w1 * w1 + w2 * w2 + y1 * a1e + y2 * a2e
                r0 = math.sqrt(x1 * x1 + x2 * x2)
                r1 = math.sqrt(y1 * y1 + y2 * y2)
                if dg_start * dg_end >= 0.0:  # g monotone: a maximum inside only where it falls through zero
                    if not (g_start > 0.0 and g_end < 0.0):
                        continue
                    # |u| rises at g0/r0 and falls at |g1|/r1 (radial speeds): above its ends by at most
                    # h s0 s1/(s0 + s1), doubled for the radial speed's own variation
                    s0 = g_start / r0
                    s1 = -g_end / r1
                    if (max(r0, r1) + 2.0 * h * s0 * s1 / (s0 + s1)) ** 2 <= pv:
                        continue
                    pv = max(pv, _vector_peak(x1, v1, x2, v2, f1, -b1, f2, -b2, h, c, kappa, 1))
                elif min(abs(g_start), abs(g_end)) <= 2.0 * h * max(abs(dg_start), abs(dg_end)):
                    # g turns inside and comes near zero (it moves by at most ~h max|g'|): it may fall through zero
                    reach = 2.0 * h * (math.sqrt(max(v1 * v1 + v2 * v2, w1 * w1 + w2 * w2))
                                       + h * math.sqrt(max(a1s * a1s + a2s * a2s, a1e * a1e + a2e * a2e)))
                    if (max(r0, r1) + reach) ** 2 > pv:
                        pv = max(pv, _vector_peak(x1, v1, x2, v2, f1, -b1, f2, -b2, h, c, kappa, VECTOR_CHECKS))
        out[k, 0] = p1
        out[k, 1] = p2
        out[k, 2] = math.sqrt(pv)


@njit(cache=True, nogil=True)
def _rotd50_peaks(ax, ay, dt, omega, zeta, n_sub, cosines, sines, out):
    """Peak |u_x cos θ + u_y sin θ| over time (between samples included) for each angle θ at one period → out[:].

    As :func:`_pair_peaks`: the recurrence with the peaks at the piece ends, then only the pieces whose ends
    may reach an angle's peak are searched, each rotated component being the response to the rotated record
    (the equation is linear).
    """
    n = ax.shape[0]
    kappa, c, m, h, e0, e1, h1, h2 = _coefficients(omega, zeta, dt, n_sub)
    states = _pair_states(ax, ay, dt, n_sub, kappa, m, h, e0, e1, h1, h2)
    sv = 0.0
    for a in range(out.shape[0]):
        out[a] = 0.0
    for piece in range(1, states.shape[0]):
        x1, v1, x2, v2 = states[piece, 0], states[piece, 1], states[piece, 2], states[piece, 3]
        sv = max(sv, v1 * v1 + v2 * v2)
        for a in range(out.shape[0]):
            out[a] = max(out[a], abs(x1 * cosines[a] + x2 * sines[a]))
    # an angle's component exceeds its piece ends by at most 2h(max|u'| + h max|u''|) (see _may_exceed)
    r_max = 0.0
    for a in range(out.shape[0]):
        r_max = max(r_max, out[a])
    speed = math.sqrt(sv)
    margin = 2.0 * h * (speed + h * (np.sqrt(np.max(ax * ax + ay * ay)) + c * speed + kappa * r_max))
    low = out - margin
    lowest = np.min(low)
    piece = 0
    for i in range(n - 1):
        b1 = (ax[i + 1] - ax[i]) / dt
        b2 = (ay[i + 1] - ay[i]) / dt
        for j in range(n_sub):
            x1, v1, x2, v2 = states[piece, 0], states[piece, 1], states[piece, 2], states[piece, 3]
            y1, w1, y2, w2 = states[piece + 1, 0], states[piece + 1, 1], states[piece + 1, 2], states[piece + 1, 3]
            piece += 1
            if max(x1 * x1 + x2 * x2, y1 * y1 + y2 * y2) <= lowest * abs(lowest):  # |u_θ| ≤ |u| at every angle
                continue
            f1 = -(ax[i] + b1 * (j * h))
            f2 = -(ay[i] + b2 * (j * h))
            a1s = f1 - c * v1 - kappa * x1
            a1e = f1 - b1 * h - c * w1 - kappa * y1
            a2s = f2 - c * v2 - kappa * x2
            a2e = f2 - b2 * h - c * w2 - kappa * y2
            for a in range(out.shape[0]):
                cs = cosines[a]
                sn = sines[a]
                u0 = x1 * cs + x2 * sn
                u1 = y1 * cs + y2 * sn
                if max(abs(u0), abs(u1)) <= low[a]:
                    continue
                s0 = v1 * cs + v2 * sn
                s1 = w1 * cs + w2 * sn
                g0 = a1s * cs + a2s * sn
                g1 = a1e * cs + a2e * sn
                if _may_exceed(u0, u1, s0, s1, g0, g1, h, out[a]):
                    out[a] = max(out[a], _interior_peak(u0, s0, s1, g0, g1, f1 * cs + f2 * sn, -(b1 * cs + b2 * sn),
                                                        h, c, kappa))


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
