r"""The compiled loop of a shear building on a double or triple friction pendulum, 1-D, exact.

Pure arrays in, arrays out (numba, cached on disk).  The state is the building kernel's
augmented vector (:mod:`isolator.solver.building_kernel`)

    w = [x_b, v_b, u_1..u_n, u̇_1..u̇_n, a_g, ȧ_g, f]

with x_b the bearing's total displacement (the slab relative to the ground).  The bearing is
the series model of :mod:`isolator.solver.multisurface_series` (massless sliders): while the
slab moves one way its force is the known piecewise-linear function of one excursion,
F = W (r_k + (x_b − x_k)/R̄_k) on regime k (R̄_k the compliance of the sliding elements), i.e.
a spring K_k = W/R̄_k and a constant f_k = W r_k − K_k x_k.  So on each regime the system is
linear with a forcing linear in time, w' = Ã(K_k) w, with Ã(K) = Ã₀ + K ΔÃ (the 1-D building's
sliding matrix with the isolator stiffness K), and it is propagated exactly as the building
kernel propagates its partial pieces: the Taylor series of the exact solution on its Krylov
vectors, pieces short enough (‖Ã_bal‖ h ≤ THETA) for the series to reach rounding.

Events, located as roots of those series to rounding:

* **break-away** — the stuck bearing holds the force D the slab needs (D = −m_b a_g +
  1ᵀ(K_s u + C_s u̇)) while W r_lo ≤ D ≤ W r_hi (:func:`stick_window`); at the first instant it
  leaves, the excursion towards sign starts;
* **stop** — v_b = 0; the elements settle at the force then, and the slab sticks if D lies in
  the new window, otherwise reverses;
* **regime** — x_b reaches the next breakpoint of the excursion (an element starts or reaches
  its rim); x_b is monotone between stops, so it is one root of x_b(τ) − x_{k+1};
* **rim reached** — an intermediate rigid regime: the force jumps to the next element's level,
  v_b continuous (massless sliders, a finite force);
* **ultimate** — the last regime is rigid (every element on its rim): a plastic impact of the
  slab, v_b → 0 while the floors keep their absolute velocities (the story springs and dampers
  carry finite forces), so u̇ → u̇ + v_b; the impulse m_b |v_b| and the energy ½ m_b v_b² are
  reported; the bearing then holds any outward force.

Energies [J]: input ∫ −a_g (M v_b + mᵀ(v_b + u̇)) dt and viscous ∫ (c v_b² + u̇ᵀC_s u̇) dt as exact
quadratic integrals of the series, the bearing's friction work W Σ µ_i |Δū_i| = (W Σ_k µ_i R̄_i / R̄_k)
|Δx_b| per regime, the impacts' ½ m_b v_b².
"""

from __future__ import annotations

import math

import numpy as np

from isolator.solver.building_kernel import (
    N_TAYLOR,
    dot,
    krylov,
    matvec,
    poly,
    poly_root,
    quadratic_integral,
    state_at,
)
from isolator.solver.events import record_event
from isolator.solver.jit import njit
from isolator.solver.multisurface_series import excursion, settle, stick_window

MAX_EVENTS_PER_INTERVAL = 1000

BREAKAWAY = 0
STICK = 1
REVERSAL = 2
REGIME = 3
RIM_REACHED = 4
ULTIMATE = 5
EVENT_NAMES = ("breakaway", "stick", "reversal", "regime", "rim reached", "ultimate")

STATUS_OK = 0
STATUS_CHATTER = 1
STATUS_EVENTS_TRUNCATED = 2

# summary vector
S_E_INPUT = 0
S_E_FRICTION = 1
S_E_VISCOUS = 2
S_E_IMPACT = 3
S_SLIP_TIME = 4
S_N_EVENTS = 5
S_STATUS = 6
S_N_RIM_CONTACTS = 7
S_N_ULTIMATE = 8
S_IMPULSE = 9  #: Σ |v_b| at impacts [m/s] (the slab's velocity lost)
S_MAX_IMPACT_V = 10
S_FIRST_ULTIMATE_T = 11  #: time of the first impact at the ultimate displacement [s] (-1: none)
S_PEAK_R = 12  #: largest |F/W| of the bearing (friction + springs, no dashpot) [-]
S_N_PIECES = 13
SUMMARY_SIZE = 14


@njit(cache=True)
def _setup(k, reg_x, reg_r, reg_rsum, reg_mask, rbar, mu, weight, a0, da, mon0, dmon, am, mon, mon_d):
    # Ã, the watched rows and their slopes on regime k; returns (f_k, the friction force per |Δx_b|)
    kk = weight / reg_rsum[k]
    nw = am.shape[0]
    for i in range(nw):
        for j in range(nw):
            am[i, j] = a0[i, j] + kk * da[i, j]
    for i in range(mon.shape[0]):
        for j in range(nw):
            mon[i, j] = mon0[i, j] + kk * dmon[i, j]
    for i in range(mon.shape[0]):
        for j in range(nw):
            acc = 0.0
            for m in range(nw):
                acc += mon[i, m] * am[m, j]
            mon_d[i, j] = acc
    mu_eff = 0.0
    for e in range(rbar.shape[0]):
        if reg_mask[k] >> e & 1:
            mu_eff += mu[e] * rbar[e]
    return weight * reg_r[k] - kk * reg_x[k], weight * mu_eff / reg_rsum[k]


@njit(cache=True)
def _stuck_rows(a_st, mon_st, am, mon, mon_d):
    nw = am.shape[0]
    for i in range(nw):
        for j in range(nw):
            am[i, j] = a_st[i, j]
    for i in range(mon.shape[0]):
        for j in range(nw):
            mon[i, j] = mon_st[i, j]
            acc = 0.0
            for m in range(nw):
                acc += mon_st[i, m] * a_st[m, j]
            mon_d[i, j] = acc


@njit(cache=True)
def _coef(row, kry, out):
    # Taylor coefficients of ℓ·w(τ): ℓ·Ã^j w0 from the Krylov vectors
    for j in range(kry.shape[0]):
        out[j] = dot(row, kry[j])


@njit(cache=True)
def _series(am, w, kry, have):
    # the Krylov vectors of the piece from w, once (a full sub-step needs them only to locate something)
    if not have[0]:
        krylov(am, w, kry)
        have[0] = True


@njit(cache=True)
def _extremes(mon, am, w, kry, have, length, y0, y1, d0, d1, peak_max, peak_min, coef):
    # the signed extremes of the watched functionals over a piece, interior extrema located
    for k in range(y0.shape[0]):
        hi_v = max(y0[k], y1[k])
        lo_v = min(y0[k], y1[k])
        peak_max[k] = max(peak_max[k], hi_v)
        peak_min[k] = min(peak_min[k], lo_v)
        reach = 2.0 * length * max(abs(d0[k]), abs(d1[k]))
        if ((d0[k] > 0.0 > d1[k] and hi_v + reach > peak_max[k])
                or (d0[k] < 0.0 < d1[k] and lo_v - reach < peak_min[k])):
            _series(am, w, kry, have)
            _coef(mon[k], kry, coef)
            t_e = poly_root(coef, np.int64(1), 0.0, 1.0 if d0[k] > 0.0 else -1.0, 0.0, length)
            v_e = poly(coef, np.int64(0), t_e)
            peak_max[k] = max(peak_max[k], v_e)
            peak_min[k] = min(peak_min[k], v_e)


@njit(cache=True)
def _surface_peaks(u, tmat, surf_peak):
    for j in range(tmat.shape[0]):
        total = 0.0
        for i in range(u.shape[0]):
            total += tmat[j, i] * u[i]
        surf_peak[j] = max(surf_peak[j], abs(total))


@njit(cache=True)
def _exit(kry, row, row_d, w1, length, lo, hi, coef):
    """The first instant in [0, length] where y = row·w leaves [lo, hi], and the side (+1 hi, −1 lo); (-1, 0): none.

    ``row_d`` = row·Ã (the slope), ``w1`` the state at ``length``.  On a piece the slope of y changes sign
    at most once (pieces are short against every time scale), so y leaves through its end or through
    its one interior extremum, located as a root of the slope's series when it could reach a bound; the
    crossing is then a root of y's series on the bracket that holds it.  A start on a bound is inside.
    """
    h0 = dot(row, kry[0])
    if h0 > hi:
        return 0.0, 1.0
    if h0 < lo:
        return 0.0, -1.0
    h1 = dot(row, w1)
    hd0 = dot(row, kry[1])
    hd1 = dot(row_d, w1)
    t_ext = -1.0
    h_ext = 0.0
    reach = 2.0 * length * max(abs(hd0), abs(hd1))
    if hd0 * hd1 < 0.0 and (max(h0, h1) + reach > hi or min(h0, h1) - reach < lo):
        _coef(row, kry, coef)
        t_ext = poly_root(coef, np.int64(1), 0.0, 1.0 if hd0 > 0.0 else -1.0, 0.0, length)
        h_ext = poly(coef, np.int64(0), t_ext)
    side = 0.0
    seg_lo = 0.0
    seg_hi = length
    if t_ext >= 0.0 and (h_ext > hi or h_ext < lo):
        side = 1.0 if h_ext > hi else -1.0
        seg_hi = t_ext
    elif h1 > hi or h1 < lo:
        side = 1.0 if h1 > hi else -1.0
        if t_ext >= 0.0:
            seg_lo = t_ext
    if side == 0.0:
        return -1.0, 0.0
    _coef(row, kry, coef)
    level = hi if side > 0.0 else lo
    return poly_root(coef, np.int64(0), level, -side, seg_lo, seg_hi), side


@njit(cache=True)
def _begin(s, u, rbar, mu, rim, x, reg_x, reg_r, reg_rsum, reg_mask, weight, a0, da, mon0, dmon, am, mon, mon_d,
           state_first_time, t):
    """A new excursion in direction s from x: its regimes, the elements already on their rim that way, regime
    0's matrices; returns (n_reg, rim_before, f_0, friction per |Δx_b|) and marks the state's first time."""
    n_reg = excursion(s, u, rbar, mu, rim, x, reg_x, reg_r, reg_rsum, reg_mask)
    rim_before = 0
    for e in range(u.shape[0]):
        if s * u[e] >= rim[e]:
            rim_before |= 1 << e
    f_k, fric = _setup(np.int64(0), reg_x, reg_r, reg_rsum, reg_mask, rbar, mu, weight, a0, da, mon0, dmon, am, mon, mon_d)
    code = reg_mask[0] + (1 << u.shape[0]) * rim_before
    if state_first_time[code] < 0.0:
        state_first_time[code] = t
    return n_reg, rim_before, f_k, fric


@njit(cache=True)
def building_multisurface_kernel(acc, dt, times, h_max, a_st, a0, da, phi_modes, pin_modes, pvis_modes, mon_st, mon0,
                                 dmon, q_in, q_vis, ell_hold,
                                 weight, slab_mass, n_floors, rbar, mu, mu_static, rim, tmat, idx_ag, idx_bg,
                                 idx_f, out_state, out_mon, out_r, out_energy, peak_max, peak_min, ev_time, ev_kind, ev_x,
                                 summary, surf_peak, state_first_time, u):
    """Exact response of the slab + shear building on a multi-surface bearing.

    Parameters
    ----------
    acc : float64[n]
        Ground acceleration [m/s²], linear between samples.
    dt : float
        Sample interval [s] of a uniform record (``times`` empty).
    times : float64[n] or float64[0]
        Sample times from the first [s] of a non-uniform record.
    h_max : float
        Longest piece [s] (‖Ã_bal‖₁ h ≤ THETA in every mode and regime).
    a_st : float64[N, N]
        Ã of the stuck bearing.
    a0, da : float64[N, N]
        Ã of the sliding bearing with no spring, and its derivative in the spring K [1/(N/m)].
    phi_modes, pin_modes, pvis_modes : float64[1 + 2**ne, N, N]
        For a uniform record, per mode (0 stuck, 1 + the sliding set's mask): e^{Ãh} of a full sub-step
        h = dt / ceil(dt / h_max), and ∫₀ʰ e^{Ãᵀτ} Q e^{Ãτ} dτ for Q = q_in and q_vis.
    mon_st, mon0, dmon : float64[K, N]
        The watched functionals (:func:`isolator.solver.building.building_system`'s) stuck, sliding
        with K = 0, and their derivative in K.
    q_in, q_vis : float64[N, N]
        Quadratic forms of the input and viscous powers [W].
    ell_hold : float64[N]
        The force D the bearing must give to hold the slab [N].
    weight, slab_mass : float
        W = g M [N] and m_b [kg].
    n_floors : int
    rbar, mu, rim : float64[ne]
        The series elements (radius [m], kinetic friction [-], rim [m]).
    mu_static : float64[ne]
        Static friction [-] of the stuck bearing's window (above ``mu`` on a single surface only: at the
        break-away the force drops from µs W to µk W and the slab starts with the net force (µs − µk) W).
    tmat : float64[ns, ne]
        Displacement on each real surface from the elements' [-].
    idx_ag, idx_bg, idx_f : int
        Positions of a_g, ȧ_g and f in w (x_b, v_b are 0, 1).
    out_state, out_mon, out_r, out_energy : arrays
        Filled at the samples: w, the functionals, the bearing's F/W, and the cumulative input,
        friction, viscous and impact energies [J] (rows 0–3).
    peak_max, peak_min : float64[K]
        Filled with the signed extremes of the functionals over time (exact).
    ev_time, ev_kind, ev_x : arrays
        Events (time from the first sample [s], kind, x_b [m]) while room lasts.
    summary : float64[SUMMARY_SIZE]
    surf_peak : float64[ns]
        Peak |displacement| on each real surface (effective geometry) [m].
    state_first_time : float64[4**ne]
        First time [s] of each (sliding set, rims) state, index = mask + 2**ne × rims (-1: never).
    u : float64[ne]
        In: zeros; out: the elements' final displacements [m].
    """
    idx_xb = 0
    idx_vb = 1
    uniform = times.shape[0] == 0
    n = acc.shape[0]
    nw = a0.shape[0]
    nk = mon0.shape[0]
    ne = rbar.shape[0]
    n_masks = 1 << ne
    w = np.zeros(nw)
    w1 = np.zeros(nw)
    we = np.zeros(nw)
    kry = np.zeros((N_TAYLOR + 2, nw))
    have = np.zeros(1, dtype=np.bool_)
    mode = 0  # 0 stuck, else 1 + the sliding set's mask (the index of the full sub-step's propagators)
    coef = np.zeros(N_TAYLOR + 2)
    am = np.zeros((nw, nw))
    mon = np.zeros((nk, nw))
    mon_d = np.zeros((nk, nw))
    wt = np.zeros(nw)
    wq = np.zeros(nw)
    vrow = np.zeros(nw)
    vrow_d = np.zeros(nw)
    y0 = np.zeros(nk)
    d0 = np.zeros(nk)
    y1 = np.zeros(nk)
    d1 = np.zeros(nk)
    size = 2 * ne + 1
    reg_x = np.empty(size)
    reg_r = np.empty(size)
    reg_rsum = np.empty(size)
    reg_mask = np.zeros(size, dtype=np.int64)
    n_reg = 0
    k = 0
    rim_before = 0
    fric = 0.0
    stuck = True
    s = 0.0
    x_stuck = 0.0
    n_ev = 0
    status = 0
    e_in = 0.0
    e_f = 0.0
    e_v = 0.0
    e_imp = 0.0
    slip_time = 0.0
    n_rim = 0
    n_ult = 0
    impulse = 0.0
    max_imp_v = 0.0
    first_ult = -1.0
    peak_r = 0.0
    n_pieces = 0
    hold_d = np.zeros(nw)  # the hold force's rate: ℓ_D Ã_stuck
    for j in range(nw):
        for m in range(nw):
            hold_d[j] += ell_hold[m] * a_st[m, j]
    for j in range(state_first_time.shape[0]):
        state_first_time[j] = -1.0
    r_lo, r_hi = stick_window(u, rbar, mu_static, rim)
    _stuck_rows(a_st, mon_st, am, mon, mon_d)
    w[idx_ag] = acc[0]
    matvec(mon, w, y0)
    for j in range(nk):
        peak_max[j] = y0[j]
        peak_min[j] = y0[j]
        out_mon[0, j] = y0[j]
    for j in range(nw):
        out_state[0, j] = w[j]
    out_r[0] = dot(ell_hold, w) / weight
    peak_r = abs(out_r[0])
    for row in range(4):
        out_energy[row, 0] = 0.0
    for i in range(n - 1):
        a_i = acc[i]
        if uniform:
            dt_i = dt
            t_i = i * dt
        else:
            t_i = times[i]
            dt_i = times[i + 1] - t_i
        n_sub = max(1, int(math.ceil(dt_i / h_max)))
        h = dt_i / n_sub
        b = (acc[i + 1] - a_i) / dt_i
        events_here = 0
        for jsub in range(n_sub):
            w[idx_ag] = a_i + b * (jsub * h)
            w[idx_bg] = b
            tau = 0.0
            for _guard in range(8 * MAX_EVENTS_PER_INTERVAL + 16):
                if tau >= h:
                    break
                rem = h - tau
                full = uniform and tau == 0.0
                have[0] = False
                if full:
                    matvec(phi_modes[mode], w, w1)  # a full sub-step: the precomputed e^{Ãh}
                else:
                    _series(am, w, kry, have)
                    n_pieces += 1
                    state_at(kry, rem, w1)
                if stuck:
                    w1[idx_xb] = x_stuck
                    w1[idx_vb] = 0.0
                t_event = -1.0
                side = 0.0
                crossing = False
                if events_here > MAX_EVENTS_PER_INTERVAL:
                    pass  # chatter guard: no more events in this interval
                elif stuck:
                    # D leaves the window through an end or its one interior extremum, if at all
                    lo_f = weight * r_lo
                    hi_f = weight * r_hi
                    h0 = dot(ell_hold, w)
                    h1 = dot(ell_hold, w1)
                    hd0 = dot(hold_d, w)
                    hd1 = dot(hold_d, w1)
                    reach = 2.0 * rem * max(abs(hd0), abs(hd1))
                    if (not lo_f <= h0 <= hi_f or not lo_f <= h1 <= hi_f
                            or (hd0 * hd1 < 0.0 and (max(h0, h1) + reach > hi_f or min(h0, h1) - reach < lo_f))):
                        _series(am, w, kry, have)
                        t_event, side = _exit(kry, ell_hold, hold_d, w1, rem, lo_f, hi_f, coef)
                else:
                    v0 = s * w[idx_vb]
                    v1 = s * w1[idx_vb]
                    av0 = s * dot(am[idx_vb], w)
                    av1 = s * dot(am[idx_vb], w1)
                    t_stop = -1.0
                    if v0 <= 0.0 and av0 <= 0.0:
                        # from rest and not pushed towards s (at a break-away the net force starts at zero, its
                        # sign is rounding): a stop at once unless the velocity grew by the piece's end
                        if v1 <= 0.0:
                            t_stop = 0.0
                    elif v1 <= 0.0 or (v0 > 0.0 and av0 < 0.0 < av1
                                       and min(v0, v1) - 2.0 * rem * max(abs(av0), abs(av1)) <= 0.0):
                        # the stop: s·v_b leaves [0, ∞) (from rest, after its maximum)
                        _series(am, w, kry, have)
                        for j in range(nw):
                            vrow[j] = 0.0
                            vrow_d[j] = s * am[idx_vb, j]
                        vrow[idx_vb] = s
                        t_stop, _ = _exit(kry, vrow, vrow_d, w1, rem, 0.0, math.inf, coef)
                    t_event = t_stop
                    if k + 1 < n_reg:
                        # the next breakpoint: s·x_b leaves (−∞, s x_{k+1}) before the stop (x_b is monotone)
                        target = s * reg_x[k + 1]
                        if s * w[idx_xb] >= target:
                            t_event = 0.0
                            crossing = True
                        elif t_stop >= 0.0 or s * w1[idx_xb] >= target:
                            _series(am, w, kry, have)
                            t_h = rem
                            if t_stop >= 0.0:
                                t_h = t_stop
                                state_at(kry, t_stop, wt)
                            else:
                                for j in range(nw):
                                    wt[j] = w1[j]
                            for j in range(nw):
                                vrow[j] = 0.0
                                vrow_d[j] = s * am[idx_xb, j]
                            vrow[idx_xb] = s
                            if s * wt[idx_xb] >= target:
                                t_cross, _ = _exit(kry, vrow, vrow_d, wt, t_h, -math.inf, target, coef)
                                if t_cross < 0.0:
                                    t_cross = t_h  # reached exactly at the end of the bracket
                                t_event = t_cross
                                crossing = True
                piece = rem if t_event < 0.0 else t_event
                if t_event >= 0.0:
                    _series(am, w, kry, have)
                    state_at(kry, piece, we)
                    if stuck:
                        we[idx_xb] = x_stuck
                        we[idx_vb] = 0.0
                    elif crossing:
                        we[idx_xb] = reg_x[k + 1]  # the breakpoint itself (the root is exact to rounding)
                    else:
                        we[idx_vb] = 0.0  # the stop
                else:
                    for j in range(nw):
                        we[j] = w1[j]
                if piece > 0.0:
                    if full and t_event < 0.0:
                        # the energies of a full sub-step: quadratic forms with the Van Loan matrices
                        matvec(pin_modes[mode], w, wq)
                        e_in += dot(w, wq)
                        matvec(pvis_modes[mode], w, wq)
                        e_v += dot(w, wq)
                    else:
                        _series(am, w, kry, have)
                        e_in += quadratic_integral(kry, q_in, piece)
                        e_v += quadratic_integral(kry, q_vis, piece)
                    if not stuck:
                        e_f += fric * abs(we[idx_xb] - w[idx_xb])
                        slip_time += piece
                    matvec(mon, w, y0)
                    matvec(mon_d, w, d0)
                    matvec(mon, we, y1)
                    matvec(mon_d, we, d1)
                    _extremes(mon, am, w, kry, have, piece, y0, y1, d0, d1, peak_max, peak_min, coef)
                for j in range(nw):
                    w[j] = we[j]
                tau += piece
                if t_event < 0.0:
                    break
                # ---- the event ----
                events_here += 1
                t_abs = t_i + jsub * h + tau
                x = w[idx_xb]
                if stuck:
                    s = side
                    n_reg, rim_before, f_k, fric = _begin(s, u, rbar, mu, rim, x, reg_x, reg_r, reg_rsum, reg_mask,
                                                          weight, a0, da, mon0, dmon, am, mon, mon_d,
                                                          state_first_time, t_abs)
                    mode = 1 + reg_mask[0]
                    k = 0
                    stuck = False
                    # the friction absorbs the rounding of the instant: the net force on the slab starts at 0
                    excess = dot(ell_hold, w) - weight * reg_r[0]
                    if abs(excess) <= 1e-9 * weight * abs(reg_r[0]):
                        f_k += excess
                    w[idx_f] = f_k
                    n_ev = record_event(ev_time, ev_kind, ev_x, n_ev, t_abs, np.int64(BREAKAWAY), x)
                elif crossing:
                    left = reg_mask[k] & ~reg_mask[k + 1]
                    rim_before |= left
                    while left:
                        n_rim += left & 1
                        left >>= 1
                    k += 1
                    kind = REGIME
                    if reg_rsum[k] == 0.0 and k < n_reg - 1 and w[idx_vb] != 0.0:
                        # an intermediate rim: the force jumps to the next element's level, v_b continuous
                        peak_r = max(peak_r, abs(reg_r[k]))
                        k += 1
                        kind = RIM_REACHED
                    if reg_rsum[k] > 0.0:
                        f_k, fric = _setup(k, reg_x, reg_r, reg_rsum, reg_mask, rbar, mu, weight, a0, da,
                                               mon0, dmon, am, mon, mon_d)
                        mode = 1 + reg_mask[k]
                        w[idx_f] = f_k
                        code = reg_mask[k] + n_masks * rim_before
                        if state_first_time[code] < 0.0:
                            state_first_time[code] = t_abs
                        n_ev = record_event(ev_time, ev_kind, ev_x, n_ev, t_abs, kind, x)
                    else:
                        # rigid: the ultimate displacement (or a rigid regime reached at rest): plastic impact
                        v = w[idx_vb]
                        ultimate = k == n_reg - 1
                        if v != 0.0:
                            impulse += abs(v)
                            max_imp_v = max(max_imp_v, abs(v))
                            e_imp += 0.5 * slab_mass * v * v
                            for j in range(n_floors):
                                w[2 + n_floors + j] += v  # the floors keep their absolute velocities
                        w[idx_vb] = 0.0
                        settle(s, u, rbar, mu, rim, reg_r[k])
                        _surface_peaks(u, tmat, surf_peak)
                        r_lo, r_hi = stick_window(u, rbar, mu_static, rim)
                        stuck = True
                        x_stuck = x
                        w[idx_f] = 0.0
                        _stuck_rows(a_st, mon_st, am, mon, mon_d)
                        mode = 0
                        if ultimate:
                            n_ult += 1
                            if first_ult < 0.0:
                                first_ult = t_abs
                        n_ev = record_event(ev_time, ev_kind, ev_x, n_ev, t_abs, ULTIMATE if ultimate else STICK, x)
                    peak_r = max(peak_r, abs(reg_r[k]))
                else:
                    # the slab stops: settle the elements, then stick or reverse
                    r_end = reg_r[k] + (x - reg_x[k]) / reg_rsum[k]
                    peak_r = max(peak_r, abs(r_end))
                    settle(s, u, rbar, mu, rim, r_end)
                    _surface_peaks(u, tmat, surf_peak)
                    r_lo, r_hi = stick_window(u, rbar, mu_static, rim)
                    need = dot(ell_hold, w)
                    if weight * r_lo <= need <= weight * r_hi:
                        stuck = True
                        x_stuck = x
                        w[idx_f] = 0.0
                        _stuck_rows(a_st, mon_st, am, mon, mon_d)
                        mode = 0
                        n_ev = record_event(ev_time, ev_kind, ev_x, n_ev, t_abs, np.int64(STICK), x)
                    else:
                        s = 1.0 if need > weight * r_hi else -1.0
                        n_reg, rim_before, f_k, fric = _begin(s, u, rbar, mu, rim, x, reg_x, reg_r, reg_rsum,
                                                              reg_mask, weight, a0, da, mon0, dmon, am, mon, mon_d,
                                                              state_first_time, t_abs)
                        mode = 1 + reg_mask[0]
                        k = 0
                        w[idx_f] = f_k
                        peak_r = max(peak_r, abs(reg_r[0]))
                        n_ev = record_event(ev_time, ev_kind, ev_x, n_ev, t_abs, np.int64(REVERSAL), x)
                # the functionals jump with the mode or the regime: count the new side
                matvec(mon, w, y1)
                for j in range(nk):
                    peak_max[j] = max(peak_max[j], y1[j])
                    peak_min[j] = min(peak_min[j], y1[j])
                if events_here > MAX_EVENTS_PER_INTERVAL:
                    status |= STATUS_CHATTER
                    if not stuck:
                        settle(s, u, rbar, mu, rim, reg_r[k] + (w[idx_xb] - reg_x[k]) / reg_rsum[k])
                    stuck = True
                    x_stuck = w[idx_xb]
                    w[idx_vb] = 0.0
                    w[idx_f] = 0.0
                    _stuck_rows(a_st, mon_st, am, mon, mon_d)
                    mode = 0
                    r_lo = -math.inf
                    r_hi = math.inf
        if status & STATUS_CHATTER and stuck and r_lo == -math.inf:
            r_lo, r_hi = stick_window(u, rbar, mu_static, rim)
        # ---- sample i + 1 ----
        w[idx_ag] = acc[i + 1]
        for j in range(nw):
            out_state[i + 1, j] = w[j]
        matvec(mon, w, y1)
        for j in range(nk):
            out_mon[i + 1, j] = y1[j]
        if stuck:
            out_r[i + 1] = dot(ell_hold, w) / weight
        else:
            out_r[i + 1] = (weight * w[idx_xb] / reg_rsum[k] + w[idx_f]) / weight
        peak_r = max(peak_r, abs(out_r[i + 1]))
        out_energy[0, i + 1] = e_in
        out_energy[1, i + 1] = e_f
        out_energy[2, i + 1] = e_v
        out_energy[3, i + 1] = e_imp
    if not stuck and n_reg > 0 and reg_rsum[k] > 0.0:
        # the record ends mid-excursion: the elements' state at the current force
        settle(s, u, rbar, mu, rim, reg_r[k] + (w[idx_xb] - reg_x[k]) / reg_rsum[k])
    _surface_peaks(u, tmat, surf_peak)
    if n_ev > ev_time.shape[0]:
        status |= STATUS_EVENTS_TRUNCATED
    summary[S_E_INPUT] = e_in
    summary[S_E_FRICTION] = e_f
    summary[S_E_VISCOUS] = e_v
    summary[S_E_IMPACT] = e_imp
    summary[S_SLIP_TIME] = slip_time
    summary[S_N_EVENTS] = n_ev
    summary[S_STATUS] = status
    summary[S_N_RIM_CONTACTS] = n_rim
    summary[S_N_ULTIMATE] = n_ult
    summary[S_IMPULSE] = impulse
    summary[S_MAX_IMPACT_V] = max_imp_v
    summary[S_FIRST_ULTIMATE_T] = first_ult
    summary[S_PEAK_R] = peak_r
    summary[S_N_PIECES] = n_pieces


__all__ = ["building_multisurface_kernel", "EVENT_NAMES", "SUMMARY_SIZE"]
