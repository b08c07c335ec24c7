"""The compiled record loop: exact stick–slip response to a piecewise-linear record.

Pure arrays in, arrays out, no objects, so that numba compiles it (cached on disk)
and dask can ship it.

Why no stop is ever missed.  Inside a slip piece the forcing is ``p + q τ``, so the
relative acceleration ``A = X''`` obeys the *homogeneous* equation
``A'' + c A' + κ A = 0``.  A homogeneous solution has at most one zero on any
interval shorter than half its damped period ``π/ω_d`` (and at most one zero at all
when over- or critically damped).  Pieces are therefore at most ``π/(2 ω_d)`` long
(the sample interval is split into ``n_sub`` equal sub-steps when the system is
stiffer than the sampling), so the velocity is *unimodal* on every piece: it has at
most one interior extremum, found as the root of ``A`` when ``A`` changes sign.
Checking the velocity at the end of the piece and at that extremum decides, with no
tolerance, whether the block stops inside the piece, and gives a bracket holding
exactly one root.

Stick phases are fast-forwarded sample by sample: while the two ends of a sample
interval satisfy ``|κ X + a_g| <= µs g`` the whole (linear) interval does.

Non-uniform sampling.  Nothing above needs equal intervals: each interval is its own
ramp.  A uniform record (``times`` empty) uses constants computed once per run (the
basis and Gram matrix of a full sub-step); a non-uniform one (``times`` the sample
times) takes each interval's length, splits it into its own number of sub-steps
(``ceil(Δt_i / max_piece)``) and evaluates the basis of every piece, as the uniform
path already does for pieces that start inside an interval — the same closed forms,
so a uniform record with extra collinear samples inserted gives the uniform answer to
rounding.
"""

from __future__ import annotations

import math

import numpy as np

from isolator.solver.events import (
    BREAKAWAY,
    REVERSAL,
    STICK,
    breakaway_time,
    find_stop,
    record_event,
    secant_guess,
    segment_root,
)
from isolator.solver.jit import njit
from isolator.solver.segments import ramp_basis, segment_state

#: Safety net against stick–slip chatter: events allowed in one sample interval.
MAX_EVENTS_PER_INTERVAL = 1000

# status bits returned in summary[SUMMARY_STATUS]
STATUS_OK = 0
STATUS_CHATTER = 1  #: the chatter guard held the block for the rest of an interval
STATUS_EVENTS_TRUNCATED = 2  #: more events than the event arrays could hold

# layout of the summary vector
SUMMARY_PEAK_DISPLACEMENT = 0
SUMMARY_PEAK_VELOCITY = 1
SUMMARY_PEAK_ABS_ACCELERATION = 2
SUMMARY_SLIP_TIME = 3
SUMMARY_ENERGY_INPUT = 4
SUMMARY_ENERGY_FRICTION = 5
SUMMARY_ENERGY_VISCOUS = 6
SUMMARY_N_EVENTS = 7
SUMMARY_STATUS = 8
SUMMARY_SIZE = 9

# 8-point Gauss–Legendre on [0, 1] for the viscous energy of partial pieces; pieces
# longer than one time constant of the fastest exponent are split (composite rule)
_GL_X, _GL_W = np.polynomial.legendre.leggauss(8)
GL_NODES = 0.5 * (_GL_X + 1.0)
GL_WEIGHTS = 0.5 * _GL_W


def fastest_rate(damping_per_mass: float, stiffness_per_mass: float) -> float:
    """Largest |λ| of the free motion, |m| + |d| [1/s]: sets the quadrature pieces."""
    return 0.5 * damping_per_mass + math.sqrt(abs(0.25 * damping_per_mass ** 2 - stiffness_per_mass))


def max_piece_s(damping_per_mass: float, stiffness_per_mass: float) -> float:
    """Longest slip piece that keeps the velocity unimodal, π/(2 ω_d) [s] (inf if not oscillatory).

    Parameters
    ----------
    damping_per_mass, stiffness_per_mass : float
        c = γ/M [1/s] and κ = K/M [1/s²].
    """
    d2 = 0.25 * damping_per_mass ** 2 - stiffness_per_mass
    if d2 >= 0.0:
        return math.inf
    return 0.5 * math.pi / math.sqrt(-d2)


def substeps_per_interval(dt_s: float, damping_per_mass: float, stiffness_per_mass: float) -> int:
    """Sub-steps per sample interval so that each piece is ≤ π/(2 ω_d).

    Parameters
    ----------
    dt_s : float
        Sample interval [s].
    damping_per_mass, stiffness_per_mass : float
        c = γ/M [1/s] and κ = K/M [1/s²].

    Returns
    -------
    int
        1 for every realistic isolator (ω_d dt ≪ 1); more for very stiff systems.
    """
    d2 = 0.25 * damping_per_mass ** 2 - stiffness_per_mass
    if d2 >= 0.0:
        return 1  # A has at most one zero on the whole line
    omega_d = math.sqrt(-d2)
    return max(1, math.ceil(dt_s * omega_d / (0.5 * math.pi)))


_GRAM_NODES, _GRAM_WEIGHTS = np.polynomial.legendre.leggauss(12)


@njit(cache=True)
def _gram_matrix(h, c, kappa, n_pieces, nodes, weights):
    gram = np.zeros((3, 3))
    piece = h / n_pieces
    for j in range(n_pieces):
        for k in range(nodes.shape[0]):
            e0, e1, h1, _, _ = ramp_basis(piece * (j + 0.5 * (nodes[k] + 1.0)), c, kappa)
            w = 0.5 * piece * weights[k]
            gram[0, 0] += w * e0 * e0
            gram[0, 1] += w * e0 * e1
            gram[0, 2] += w * e0 * h1
            gram[1, 1] += w * e1 * e1
            gram[1, 2] += w * e1 * h1
            gram[2, 2] += w * h1 * h1
    gram[1, 0] = gram[0, 1]
    gram[2, 0] = gram[0, 2]
    gram[2, 1] = gram[1, 2]
    return gram


def full_step_coefficients(h_s: float, damping_per_mass: float, stiffness_per_mass: float):
    """Basis functions and Gram matrix of a full sub-step, computed once per run.

    Returns
    -------
    tuple of numpy.ndarray
        ``basis`` = (E0, E1, H1, H2, H3) at h, and ``gram`` (3×3) = ∫₀ʰ B_i B_j dτ for
        B = (E0, E1, H1), the functions the velocity is made of.
    """
    basis = np.array(ramp_basis(h_s, damping_per_mass, stiffness_per_mass))
    # Gram matrix by composite 12-point Gauss–Legendre, one piece per time constant of
    # the fastest exponent: the integrands are entire, so this is exact to rounding.
    n_pieces = min(4000, max(1, math.ceil(fastest_rate(damping_per_mass, stiffness_per_mass) * h_s)))
    gram = _gram_matrix(h_s, damping_per_mass, stiffness_per_mass, n_pieces, _GRAM_NODES, _GRAM_WEIGHTS)
    return basis, gram


@njit(cache=True)
def viscous_integral(tau, x0, v0, p, q, c, kappa):
    # ∫₀^τ V² dτ by composite Gauss–Legendre on the exact velocity (partial pieces only)
    rate = 0.5 * c + math.sqrt(abs(0.25 * c * c - kappa))
    n_pieces = min(4000, max(1, int(math.ceil(rate * tau))))
    piece = tau / n_pieces
    total = 0.0
    for j in range(n_pieces):
        for k in range(GL_NODES.shape[0]):
            _, v, _, _ = segment_state(piece * (j + GL_NODES[k]), x0, v0, p, q, 0.0, 0.0, c, kappa, 0.0)
            total += GL_WEIGHTS[k] * v * v
    return total * piece


@njit(cache=True)
def velocity_peak(peak_v, length, x, v, v_end, acc_start, acc_end, p, q, c, kappa):
    # The larger of peak_v and the interior extremum of |V| on a piece, which exists where
    # the acceleration changes sign; located only when it could beat the peak so far
    # (on a piece |V| moves beyond its ends by at most ~length max|A|).
    if acc_start * acc_end >= 0.0:
        return peak_v
    if max(abs(v), abs(v_end)) + 2.0 * length * max(abs(acc_start), abs(acc_end)) <= peak_v:
        return peak_v
    sign = 1.0 if acc_start > 0.0 else -1.0
    t_e = segment_root(np.int64(1), sign, 0.0, length, x, v, p, q, 0.0, 0.0, c, kappa, 0.0,
                       secant_guess(0.0, length, acc_start, acc_end))
    _, v_e, _, _ = segment_state(t_e, x, v, p, q, 0.0, 0.0, c, kappa, 0.0)
    return max(peak_v, abs(v_e))


@njit(cache=True)
def record_kernel(acc, dt, n_sub, c, kappa, mu_s_g, mu_k_g, full_basis, gram,
                  out_x, out_v, out_a, out_energy, ev_time, ev_kind, ev_x, summary,
                  times, max_piece):
    """Exact response of the friction–spring–dashpot block to a sampled record.

    Parameters
    ----------
    acc : float64[n]
        Ground acceleration samples [m/s²], linear between samples.
    dt : float
        Sample interval [s] of a uniform record (ignored when ``times`` is given).
    n_sub : int
        Sub-steps per interval (:func:`substeps_per_interval`) of a uniform record.
    c, kappa : float
        Damping [1/s] and stiffness [1/s²] per unit mass.
    mu_s_g, mu_k_g : float
        Static and kinetic friction per unit mass, µs g and µk g [m/s²].
    full_basis, gram : float64 arrays
        From :func:`full_step_coefficients` for h = dt / n_sub.
    out_x, out_v, out_a : float64[n]
        Filled with the relative displacement [m], relative velocity [m/s] and
        absolute acceleration of the mass [m/s²] at the samples.
    out_energy : float64[3, n]
        Filled with the cumulative input, friction and viscous energies per unit
        mass at the samples [J/kg] (the same closed forms as the totals).
    ev_time, ev_kind, ev_x : arrays
        Filled with the events (time [s], kind, displacement [m]) while room lasts.
    summary : float64[SUMMARY_SIZE]
        Filled with the peaks, slip time, energies (J/kg), event count and status.
    times : float64[n] or float64[0]
        Sample times from the first one [s] for a non-uniform record; empty for a
        uniform one (then ``dt``, ``n_sub``, ``full_basis`` and ``gram`` are used).
    max_piece : float
        :func:`max_piece_s` [s]: the longest sub-step of a non-uniform interval.
    """
    uniform = times.shape[0] == 0
    n = acc.shape[0]
    m = -0.5 * c
    x = 0.0
    v = 0.0
    stuck = True
    s = 0.0
    from_rest = False  # the current slip piece starts with V = 0
    exact_start = False  # ... and at a break-away, where the net force is known exactly
    n_ev = 0
    status = 0
    peak_x = 0.0
    peak_v = 0.0
    peak_a = abs(acc[0])
    slip_time = 0.0
    e_in = 0.0
    e_f = 0.0
    e_v = 0.0
    out_x[0] = 0.0
    out_v[0] = 0.0
    out_a[0] = acc[0]
    out_energy[0, 0] = 0.0
    out_energy[1, 0] = 0.0
    out_energy[2, 0] = 0.0
    i = 0
    while i < n - 1:
        if stuck:
            # fast-forward through whole sample intervals that stay stuck
            lo = -mu_s_g - kappa * x
            hi = mu_s_g - kappa * x
            # (both ends of the interval inside the window: a record may start beyond it)
            while i < n - 1 and lo <= acc[i] <= hi and lo <= acc[i + 1] <= hi:
                i += 1
                out_x[i] = x
                out_v[i] = 0.0
                out_a[i] = acc[i]
                out_energy[0, i] = e_in
                out_energy[1, i] = e_f
                out_energy[2, i] = e_v
                if abs(acc[i]) > peak_a:
                    peak_a = abs(acc[i])
            if i >= n - 1:
                break
        a0 = acc[i]
        if uniform:
            dt_i = dt
            n_sub_i = n_sub
            h = dt / n_sub
            t_i = i * dt
        else:
            t_i = times[i]
            dt_i = times[i + 1] - t_i
            n_sub_i = 1
            if dt_i > max_piece:
                n_sub_i = int(math.ceil(dt_i / max_piece))
            h = dt_i / n_sub_i
        b = (acc[i + 1] - a0) / dt_i
        q = -b
        events_here = 0
        for jsub in range(n_sub_i):
            a_sub = a0 + b * (jsub * h)
            t_sub = t_i + jsub * h
            tau = 0.0
            while tau < h:
                if stuck:
                    tb, direction, crossing = breakaway_time(x, a_sub, b, tau, h, kappa, mu_s_g)
                    if tb < 0.0:
                        break  # stuck to the end of the sub-step
                    stuck = False
                    s = float(direction)
                    tau = tb
                    from_rest = True
                    exact_start = crossing
                    n_ev = record_event(ev_time, ev_kind, ev_x, n_ev, t_sub + tb, np.int64(BREAKAWAY), x)
                    # the transmitted acceleration jumps at the break-away: a_g on the stuck side
                    # (|κx + a_g| = µs g there), −(µk g s + κx) on the sliding side; count both
                    jump = max(abs(mu_k_g * s + kappa * x), abs(a_sub + b * tb))
                    if jump > peak_a:
                        peak_a = jump
                    if tau >= h:
                        break
                # ---- sliding in direction s from local time tau ----
                rem = h - tau
                a_start = a_sub + b * tau
                if exact_start:
                    # at break-away the net force is exactly s (µs - µk) g
                    p = kappa * x + s * (mu_s_g - mu_k_g)
                else:
                    p = -(a_start + mu_k_g * s)
                if uniform and tau == 0.0 and not exact_start:
                    e0 = full_basis[0]
                    e1 = full_basis[1]
                    h1 = full_basis[2]
                    h2 = full_basis[3]
                    h3 = full_basis[4]
                else:
                    e0, e1, h1, h2, h3 = ramp_basis(rem, c, kappa)
                x1 = e0 * x + e1 * (v - m * x) + p * h1 + q * h2
                v1 = e0 * v + e1 * (m * v - kappa * x + p) + q * h1
                acc0 = p - kappa * x - c * v
                acc1 = p + q * rem - kappa * x1 - c * v1
                t_stop, t_ext, v_ext = find_stop(s, from_rest, rem, x, v, v1, acc0, acc1, p, q,
                                                 0.0, 0.0, c, kappa, 0.0)
                if t_ext >= 0.0 and abs(v_ext) > peak_v:
                    peak_v = abs(v_ext)
                if t_stop < 0.0:
                    # the block slides through to the end of the piece
                    if exact_start or tau > 0.0 or not uniform:
                        int_x = e1 * x + h1 * (v - 2.0 * m * x) + p * h2 + q * h3
                        int_v2 = viscous_integral(rem, x, v, p, q, c, kappa) if c > 0.0 else 0.0
                    else:
                        int_x = e1 * x + h1 * (v - 2.0 * m * x) + p * h2 + q * h3
                        if c > 0.0:
                            beta0 = v
                            beta1 = m * v - kappa * x + p
                            beta2 = q
                            int_v2 = (gram[0, 0] * beta0 * beta0 + gram[1, 1] * beta1 * beta1
                                      + gram[2, 2] * beta2 * beta2
                                      + 2.0 * (gram[0, 1] * beta0 * beta1 + gram[0, 2] * beta0 * beta2
                                               + gram[1, 2] * beta1 * beta2))
                        else:
                            int_v2 = 0.0
                    e_in -= a_start * (x1 - x) + b * (rem * x1 - int_x)
                    e_f += mu_k_g * abs(x1 - x)
                    e_v += c * int_v2
                    slip_time += rem
                    if t_ext < 0.0:
                        peak_v = velocity_peak(peak_v, rem, x, v, v1, acc0, acc1, p, q, c, kappa)
                    # interior extremum of the transmitted acceleration -(µk g s + κX + cV)
                    if c > 0.0:
                        d0 = kappa * v + c * acc0
                        d1 = kappa * v1 + c * acc1
                        a_ends = max(abs(mu_k_g * s + kappa * x + c * v), abs(mu_k_g * s + kappa * x1 + c * v1))
                        if d0 * d1 < 0.0 and a_ends + 2.0 * rem * max(abs(d0), abs(d1)) > peak_a:
                            sg = 1.0 if d0 > 0.0 else -1.0
                            t_e = segment_root(np.int64(2), sg, 0.0, rem, x, v, p, q, 0.0, 0.0, c, kappa, 0.0,
                                               secant_guess(0.0, rem, d0, d1))
                            x_e, v_e, _, _ = segment_state(t_e, x, v, p, q, 0.0, 0.0, c, kappa, 0.0)
                            a_e = abs(mu_k_g * s + kappa * x_e + c * v_e)
                            if a_e > peak_a:
                                peak_a = a_e
                    x = x1
                    v = v1
                    tau = h
                    from_rest = False
                    exact_start = False
                    if abs(x) > peak_x:
                        peak_x = abs(x)
                    if abs(v) > peak_v:
                        peak_v = abs(v)
                    a_abs = abs(mu_k_g * s + kappa * x + c * v)
                    if a_abs > peak_a:
                        peak_a = a_abs
                    break
                # ---- the block stops at tau + t_stop ----
                x_s, v_s, acc_s, _ = segment_state(t_stop, x, v, p, q, 0.0, 0.0, c, kappa, 0.0)
                _, e1s, h1s, h2s, h3s = ramp_basis(t_stop, c, kappa)
                int_x = e1s * x + h1s * (v - 2.0 * m * x) + p * h2s + q * h3s
                e_in -= a_start * (x_s - x) + b * (t_stop * x_s - int_x)
                e_f += mu_k_g * abs(x_s - x)
                if c > 0.0:
                    e_v += c * viscous_integral(t_stop, x, v, p, q, c, kappa)
                if t_ext < 0.0:
                    peak_v = velocity_peak(peak_v, t_stop, x, v, 0.0, acc0, acc_s, p, q, c, kappa)
                slip_time += t_stop
                tau += t_stop
                x = x_s
                v = 0.0
                from_rest = False
                exact_start = False
                if abs(x) > peak_x:
                    peak_x = abs(x)
                a_slide = abs(mu_k_g * s + kappa * x)
                if a_slide > peak_a:
                    peak_a = a_slide
                force = kappa * x + a_sub + b * tau
                if abs(force) <= mu_s_g:
                    stuck = True
                    kind = STICK
                    if abs(a_sub + b * tau) > peak_a:
                        peak_a = abs(a_sub + b * tau)
                else:
                    s = -1.0 if force > 0.0 else 1.0
                    from_rest = True
                    kind = REVERSAL
                n_ev = record_event(ev_time, ev_kind, ev_x, n_ev, t_sub + tau, kind, x)
                events_here += 1
                if events_here > MAX_EVENTS_PER_INTERVAL:
                    # chatter guard: let the static friction hold to the end of the interval
                    status |= STATUS_CHATTER
                    stuck = True
                    v = 0.0
                    break
            if events_here > MAX_EVENTS_PER_INTERVAL:
                break
        i += 1
        out_x[i] = x
        out_v[i] = v
        out_energy[0, i] = e_in
        out_energy[1, i] = e_f
        out_energy[2, i] = e_v
        if stuck:
            out_a[i] = acc[i]
        else:
            out_a[i] = -(mu_k_g * s + kappa * x + c * v)
        if abs(out_a[i]) > peak_a:
            peak_a = abs(out_a[i])
    if n_ev > ev_time.shape[0]:
        status |= STATUS_EVENTS_TRUNCATED
    summary[SUMMARY_PEAK_DISPLACEMENT] = peak_x
    summary[SUMMARY_PEAK_VELOCITY] = peak_v
    summary[SUMMARY_PEAK_ABS_ACCELERATION] = peak_a
    summary[SUMMARY_SLIP_TIME] = slip_time
    summary[SUMMARY_ENERGY_INPUT] = e_in
    summary[SUMMARY_ENERGY_FRICTION] = e_f
    summary[SUMMARY_ENERGY_VISCOUS] = e_v
    summary[SUMMARY_N_EVENTS] = n_ev
    summary[SUMMARY_STATUS] = status
