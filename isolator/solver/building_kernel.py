r"""The compiled loop of the building model: exact piecewise-linear propagation with events.

Pure arrays in, arrays out (numba, cached on disk).  The state is the augmented vector

    w = [x_b, v_b, u_1..u_n, u̇_1..u̇_n, a_g, ȧ_g, f]

(slab displacement and velocity relative to the ground, floor displacements and velocities
relative to the slab, the ground acceleration and its slope within the current sample
interval, the friction force on the slab).  In each mode (0 stuck, 1 sliding) the motion
obeys w' = Ã w exactly (the record is linear between samples and the friction force is
constant between events), so

* a full sub-step of a uniform record is one product with the precomputed propagator
  e^{Ã h} (from :func:`scipy.linalg.expm`), and the energies over it are quadratic forms
  with precomputed Van Loan matrices;
* any shorter piece (after an event, or a sub-step of a non-uniform record) uses the
  Taylor series of the exact solution on its Krylov vectors k_j = Ã^j w0:
  w(τ) = Σ_j k_j τ^j / j!.  Sub-steps are short enough that ‖Ã_bal‖₁ h ≤ THETA (the
  balanced matrix, :func:`isolator.solver.building.prepare`), so N_TAYLOR terms reach
  rounding (THETA^21/21! < 1e-20); every scalar of the motion is then a polynomial in τ
  whose coefficients are ℓ·k_j, which is how events and interior peaks are located
  (safeguarded Newton on the polynomial, to rounding);
* energy integrals over a piece, ∫ wᵀQw dτ, are the double sum
  Σ_jk (k_jᵀ Q k_k) τ^{j+k+1} / (j! k! (j+k+1)) — exact to rounding, no quadrature.

Events: in the stuck mode the hold force D = −m_b a_g − K x_b + 1ᵀ(K_s u + C_s u̇) must stay
within µs W; break-away at the first instant |D| = µs W, sliding towards sign(D).  In the
sliding mode a stop is a zero of v_b; there the slab sticks if |D| ≤ µs W, otherwise it
reverses.  Both are found from the values and slopes at the ends of a piece and at the
one interior extremum (located when the slope changes sign), as in the 1-D kernel.
"""

from __future__ import annotations

import math

import numpy as np

from isolator.solver.jit import njit

#: Taylor terms of a piece (with ‖Ã_bal‖ h ≤ THETA the remainder is below 1e-20).
N_TAYLOR = 22
#: Longest sub-step, as ‖Ã_bal‖₁ h [-].
THETA = 0.75
MAX_EVENTS_PER_INTERVAL = 1000

STATUS_OK = 0
STATUS_CHATTER = 1
STATUS_EVENTS_TRUNCATED = 2

BREAKAWAY = 0
STICK = 1
REVERSAL = 2

# summary vector
S_E_INPUT = 0
S_E_FRICTION = 1
S_E_VISCOUS = 2
S_SLIP_TIME = 3
S_N_EVENTS = 4
S_STATUS = 5
S_N_SERIES = 6  #: pieces evaluated by their Taylor series (events, partial pieces)
S_N_LOCATED = 7  #: interior extrema located (peaks and hold force)
SUMMARY_SIZE = 8


@njit(cache=True)
def _krylov(a_mat, w0, out):
    # out[j] = Ã^j w0, j = 0 .. N_TAYLOR + 1
    n = w0.shape[0]
    for i in range(n):
        out[0, i] = w0[i]
    for j in range(1, out.shape[0]):
        for i in range(n):
            acc = 0.0
            for k in range(n):
                acc += a_mat[i, k] * out[j - 1, k]
            out[j, i] = acc


@njit(cache=True)
def _state_at(kry, tau, out):
    # w(τ) = Σ_j k_j τ^j / j!  (Horner from the highest term)
    n = out.shape[0]
    jmax = kry.shape[0] - 2
    for i in range(n):
        acc = kry[jmax, i]
        for j in range(jmax - 1, -1, -1):
            acc = kry[j, i] + acc * tau / (j + 1)
        out[i] = acc


@njit(cache=True)
def _coefficients(rows, w0, out):
    # out[j] = (ℓ Ã^j) · w0: the Taylor coefficients of ℓ·w(τ) from the precomputed rows ℓÃ^j
    for j in range(rows.shape[0]):
        acc = 0.0
        for i in range(rows.shape[1]):
            acc += rows[j, i] * w0[i]
        out[j] = acc


@njit(cache=True)
def _poly(c, shift, tau):
    # Σ_j c[j + shift] τ^j / j!, j = 0 .. N_TAYLOR (shift = 1: the derivative).  Shift 2 (Newton's slope of a
    # derivative's root in _poly_root) stops one term short, at c's last entry: reading past c read whatever word
    # followed it in memory, and a word near −1e74 there moved a located peak drift by 3.6e-6 (tests/solver/
    # test_building_state.py); the term dropped is below 1e-20 of the slope (‖Ã‖h ≤ THETA)
    jmax = min(c.shape[0] - 2, c.shape[0] - 1 - shift)
    acc = c[jmax + shift]
    for j in range(jmax - 1, -1, -1):
        acc = c[j + shift] + acc * tau / (j + 1)
    return acc


@njit(cache=True)
def _poly_root(c, shift, target, sign, lo, hi):
    """Root of sign·(p(τ) − target) going from > 0 (or 0 at lo) to ≤ 0 in [lo, hi]; p = _poly(c, shift)."""
    a = lo
    b = hi
    t = 0.5 * (a + b)
    resolution = 4e-16 * max(abs(hi), abs(lo), 1e-300)
    f_lo = sign * (_poly(c, shift, lo) - target)
    f_hi = sign * (_poly(c, shift, hi) - target)
    if f_lo != f_hi and f_lo > 0.0 >= f_hi:
        guess = lo + (hi - lo) * f_lo / (f_lo - f_hi)
        if lo < guess < hi:
            t = guess
    for _ in range(200):
        f = sign * (_poly(c, shift, t) - target)
        if f == 0.0:
            return t
        if f > 0.0:
            a = t
        else:
            b = t
        # rounding of the instant: relative to the piece (a few 1e-16 of it, ~1e-19 s)
        if b - a <= resolution:
            return b
        df = sign * _poly(c, shift + 1, t)
        t_new = t - f / df if df != 0.0 else 0.5 * (a + b)
        if not (a < t_new < b):
            t_new = 0.5 * (a + b)
        elif abs(t_new - t) <= resolution:
            return t_new
        t = t_new
    return t


@njit(cache=True)
def _quadratic_integral(kry, q_mat, tau):
    # ∫₀^τ wᵀ Q w dσ with w = Σ k_j σ^j / j!:  Σ_jk (k_jᵀ Q k_k) a_j a_k τ / (j + k + 1), a_j = τ^j / j!
    nj = kry.shape[0] - 1
    n = kry.shape[1]
    a = np.empty(nj)
    a[0] = 1.0
    for j in range(1, nj):
        a[j] = a[j - 1] * tau / j
    # z = Σ_k a_k/(j+k+1) … is not separable: form y_k = Q k_k once, then the double sum
    y = np.empty((nj, n))
    for k in range(nj):
        for i in range(n):
            acc = 0.0
            for m in range(n):
                acc += q_mat[i, m] * kry[k, m]
            y[k, i] = acc
    total = 0.0
    for j in range(nj):
        if a[j] == 0.0:
            break
        for k in range(nj):
            if a[k] == 0.0:
                break
            s = 0.0
            for i in range(n):
                s += kry[j, i] * y[k, i]
            total += s * a[j] * a[k] / (j + k + 1)
    return total * tau


@njit(cache=True)
def _dot(a, b):
    acc = 0.0
    for i in range(a.shape[0]):
        acc += a[i] * b[i]
    return acc


@njit(cache=True)
def _matvec(m, v, out):
    for i in range(m.shape[0]):
        acc = 0.0
        for k in range(m.shape[1]):
            acc += m[i, k] * v[k]
        out[i] = acc


@njit(cache=True)
def _monitor(mon_pow, w0, length, y0, y1, d0, d1, peak_max, peak_min, coef):
    """Update the signed extremes of the monitored functionals over one piece (interior extrema located).

    On a piece the slope of each functional changes sign at most once (pieces are short against
    every time scale), so |y| exceeds its ends by at most ~length × max|ẏ| and only an interior
    extremum that could beat the running extreme is located, as a root of ẏ's Taylor polynomial.
    """
    located = 0
    for k in range(y0.shape[0]):
        lo_v = min(y0[k], y1[k])
        hi_v = max(y0[k], y1[k])
        if hi_v > peak_max[k]:
            peak_max[k] = hi_v
        if lo_v < peak_min[k]:
            peak_min[k] = lo_v
        reach = 2.0 * length * max(abs(d0[k]), abs(d1[k]))
        interior_max = d0[k] > 0.0 and d1[k] < 0.0 and hi_v + reach > peak_max[k]
        interior_min = d0[k] < 0.0 and d1[k] > 0.0 and lo_v - reach < peak_min[k]
        if interior_max or interior_min:
            located += 1
            _coefficients(mon_pow[:, k, :], w0, coef)
            sign = 1.0 if d0[k] > 0.0 else -1.0
            t_e = _poly_root(coef, np.int64(1), 0.0, sign, 0.0, length)
            v_e = _poly(coef, np.int64(0), t_e)
            if v_e > peak_max[k]:
                peak_max[k] = v_e
            if v_e < peak_min[k]:
                peak_min[k] = v_e
    return located


@njit(cache=True)
def building_kernel(acc, dt, n_sub, times, h_max, a_modes, phi_modes, pin_modes, pvis_modes, q_in, q_vis,
                    mon_modes, mon_d_modes, mon_pow, ell_hold, ell_hold_d, hold_pow, vb_pow, mu_s_w, mu_k_w,
                    idx_xb, idx_vb, idx_ag,
                    idx_bg, idx_f, out_state, out_mon, out_energy, peak_max, peak_min, ev_time, ev_kind, ev_x,
                    summary):
    """Exact response of the slab + shear building on the friction isolation plane.

    Parameters
    ----------
    acc : float64[n]
        Ground acceleration [m/s²], linear between samples.
    dt : float
        Sample interval [s] of a uniform record (``times`` empty).
    n_sub : int
        Sub-steps per interval of a uniform record (the propagators are for h = dt / n_sub).
    times : float64[n] or float64[0]
        Sample times from the first [s] for a non-uniform record.
    h_max : float
        Longest sub-step [s] (non-uniform records).
    a_modes : float64[2, N, N]
        Ã of the stuck (0) and sliding (1) modes.
    phi_modes, pin_modes, pvis_modes : float64[2, N, N]
        e^{Ãh}, and ∫₀ʰ e^{Ãᵀτ} Q e^{Ãτ} dτ for Q = q_in (input power) and q_vis (viscous power).
    q_in, q_vis : float64[N, N]
        The quadratic forms of the input and viscous powers [W].
    mon_modes, mon_d_modes : float64[2, K, N]
        Monitored functionals ℓ and their derivatives ℓÃ, per mode.
    mon_pow : float64[2, N_TAYLOR + 2, K, N]
        ℓ Ã^j per mode: the Taylor coefficients of every functional are mon_pow[mode, j] · w0.
    ell_hold, ell_hold_d : float64[N]
        The hold force D and its derivative (stuck mode) [N, N/s].
    hold_pow, vb_pow : float64[N_TAYLOR + 2, N], float64[2, N_TAYLOR + 2, N]
        ℓ_D Ã_stuck^j and e_vb Ã^j per mode.
    mu_s_w, mu_k_w : float
        µs W and µk W [N].
    idx_xb, idx_vb, idx_ag, idx_bg, idx_f : int
        Positions of x_b, v_b, a_g, ȧ_g and f in w.
    out_state : float64[n, N]
        Filled with w at the samples.
    out_mon : float64[n, K]
        Filled with the monitored functionals at the samples.
    out_energy : float64[3, n]
        Cumulative input, friction and viscous energies at the samples [J].
    peak_max, peak_min : float64[K]
        Filled with the signed extremes of the functionals over time (exact).
    ev_time, ev_kind, ev_x : arrays
        Events (time from the first sample [s], kind, x_b [m]) while room lasts.
    summary : float64[SUMMARY_SIZE]
    """
    uniform = times.shape[0] == 0
    n = acc.shape[0]
    nw = a_modes.shape[1]
    nk = mon_modes.shape[1]
    w = np.zeros(nw)
    w1 = np.zeros(nw)
    we = np.zeros(nw)
    kry = np.zeros((N_TAYLOR + 2, nw))
    have_kry = np.zeros(1, dtype=np.bool_)
    coef = np.zeros(N_TAYLOR + 2)
    y0 = np.zeros(nk)
    d0 = np.zeros(nk)
    y1 = np.zeros(nk)
    d1 = np.zeros(nk)
    mode = 0
    s = 0.0
    x_stuck = 0.0
    y0_valid = False
    n_located = 0
    n_series = 0
    n_ev = 0
    status = 0
    e_in = 0.0
    e_f = 0.0
    e_v = 0.0
    slip_time = 0.0
    w[idx_ag] = acc[0]
    _matvec(mon_modes[0], w, y0)
    for k in range(nk):
        peak_max[k] = y0[k]
        peak_min[k] = y0[k]
        out_mon[0, k] = y0[k]
    for i in range(nw):
        out_state[0, i] = w[i]
    out_energy[0, 0] = 0.0
    out_energy[1, 0] = 0.0
    out_energy[2, 0] = 0.0
    for i in range(n - 1):
        a0 = acc[i]
        if uniform:
            dt_i = dt
            n_sub_i = n_sub
            t_i = i * dt
        else:
            t_i = times[i]
            dt_i = times[i + 1] - t_i
            n_sub_i = max(1, int(math.ceil(dt_i / h_max)))
        h = dt_i / n_sub_i
        b = (acc[i + 1] - a0) / dt_i
        events_here = 0
        y0_valid = False  # ȧ_g changes from one interval to the next
        for jsub in range(n_sub_i):
            w[idx_ag] = a0 + b * (jsub * h)
            w[idx_bg] = b
            tau = 0.0
            for _guard in range(4 * MAX_EVENTS_PER_INTERVAL + 8):
                if tau >= h:
                    break
                rem = h - tau
                am = a_modes[mode]
                full = uniform and tau == 0.0
                have_kry[0] = False
                if full:
                    _matvec(phi_modes[mode], w, w1)
                else:
                    _krylov(am, w, kry)
                    n_series += 1
                    have_kry[0] = True
                    _state_at(kry, rem, w1)
                if mode == 0:
                    w1[idx_xb] = x_stuck
                    w1[idx_vb] = 0.0
                # ---- event in this piece? ----
                t_event = -1.0
                if events_here > MAX_EVENTS_PER_INTERVAL:
                    pass  # chatter guard: no more events in this interval
                elif mode == 0:
                    h0 = _dot(ell_hold, w)
                    h1 = _dot(ell_hold, w1)
                    hd0 = _dot(ell_hold_d, w)
                    hd1 = _dot(ell_hold_d, w1)
                    # the interior extremum of D, when its slope changes sign and it could cross µs W
                    lo_seg = 0.0
                    hit_sign = 0.0
                    if abs(h0) > mu_s_w:
                        t_event = 0.0
                        hit_sign = 1.0 if h0 > 0.0 else -1.0
                    else:
                        reach = 2.0 * rem * max(abs(hd0), abs(hd1))
                        t_ext = -1.0
                        h_ext = 0.0
                        if hd0 * hd1 < 0.0 and max(abs(h0), abs(h1)) + reach > mu_s_w:
                            n_located += 1
                            _coefficients(hold_pow, w, coef)
                            t_ext = _poly_root(coef, np.int64(1), 0.0, 1.0 if hd0 > 0.0 else -1.0, 0.0, rem)
                            h_ext = _poly(coef, np.int64(0), t_ext)
                        if t_ext >= 0.0 and abs(h_ext) > mu_s_w:
                            hit_sign = 1.0 if h_ext > 0.0 else -1.0
                            seg_hi = t_ext
                        elif abs(h1) > mu_s_w:
                            hit_sign = 1.0 if h1 > 0.0 else -1.0
                            seg_hi = rem
                            if t_ext >= 0.0:
                                lo_seg = t_ext
                        if hit_sign != 0.0:
                            _coefficients(hold_pow, w, coef)
                            # root of hit·D − µs W from < 0 to >= 0: written as −(hit·D − µs W) from > 0
                            t_event = _poly_root(coef, np.int64(0), hit_sign * mu_s_w, -hit_sign, lo_seg, seg_hi)
                else:
                    v0 = s * w[idx_vb]
                    v1 = s * w1[idx_vb]
                    av0 = s * _dot(am[idx_vb], w)
                    av1 = s * _dot(am[idx_vb], w1)
                    lo_seg = 0.0
                    seg_hi = -1.0
                    if v1 <= 0.0:
                        seg_hi = rem
                        if v0 <= 0.0:
                            # from rest: the velocity first grows, and the stop lies after its maximum;
                            # a start that cannot move in direction s is a stop at once
                            if av0 > 0.0 and av1 < 0.0:
                                _coefficients(vb_pow[mode], w, coef)
                                lo_seg = _poly_root(coef, np.int64(1), 0.0, s, 0.0, rem)
                            else:
                                t_event = 0.0
                                seg_hi = -1.0
                    elif v0 > 0.0 and av0 < 0.0 and av1 > 0.0 and min(v0, v1) - 2.0 * rem * max(abs(av0),
                                                                                        abs(av1)) <= 0.0:
                        # (not from rest: with µs = µk the net force at a break-away is zero and the start's
                        # acceleration is rounding; the velocity that grew to v1 > 0 did not stop)
                        # an interior minimum of s·v_b: does it reach zero?
                        _coefficients(vb_pow[mode], w, coef)
                        t_min = _poly_root(coef, np.int64(1), 0.0, -s, 0.0, rem)
                        if s * _poly(coef, np.int64(0), t_min) <= 0.0:
                            seg_hi = t_min
                    if seg_hi >= 0.0:
                        _coefficients(vb_pow[mode], w, coef)
                        t_event = _poly_root(coef, np.int64(0), 0.0, s, lo_seg, seg_hi)
                piece = rem if t_event < 0.0 else t_event
                # ---- advance to the end of the piece (or the event) ----
                if t_event >= 0.0:
                    if not have_kry[0]:
                        _krylov(am, w, kry)
                        n_series += 1
                        have_kry[0] = True
                    _state_at(kry, piece, we)
                    if mode == 0:
                        we[idx_xb] = x_stuck
                        we[idx_vb] = 0.0
                    else:
                        we[idx_vb] = 0.0  # the stop: v_b = 0 exactly
                else:
                    for k in range(nw):
                        we[k] = w1[k]
                # energies over the piece
                if piece > 0.0:
                    if full and t_event < 0.0:
                        de_in = 0.0
                        de_v = 0.0
                        for r in range(nw):
                            ri = 0.0
                            rv = 0.0
                            for c in range(nw):
                                ri += pin_modes[mode, r, c] * w[c]
                                rv += pvis_modes[mode, r, c] * w[c]
                            de_in += w[r] * ri
                            de_v += w[r] * rv
                    else:
                        if not have_kry[0]:
                            _krylov(am, w, kry)
                            n_series += 1
                            have_kry[0] = True
                        de_in = _quadratic_integral(kry, q_in, piece)
                        de_v = _quadratic_integral(kry, q_vis, piece)
                    e_in += de_in
                    e_v += de_v
                    if mode == 1:
                        e_f += w[idx_f] * (we[idx_xb] - w[idx_xb])
                        slip_time += piece
                    # peaks over the piece (the values at its start are the last piece's end values
                    # while the mode and the sample interval are unchanged)
                    if not y0_valid:
                        _matvec(mon_modes[mode], w, y0)
                        _matvec(mon_d_modes[mode], w, d0)
                    _matvec(mon_modes[mode], we, y1)
                    _matvec(mon_d_modes[mode], we, d1)
                    n_located += _monitor(mon_pow[mode], w, piece, y0, y1, d0, d1, peak_max, peak_min, coef)
                    for k in range(nk):
                        y0[k] = y1[k]
                        d0[k] = d1[k]
                    y0_valid = True
                else:
                    _matvec(mon_modes[mode], we, y1)
                    for k in range(nk):
                        peak_max[k] = max(peak_max[k], y1[k])
                        peak_min[k] = min(peak_min[k], y1[k])
                for k in range(nw):
                    w[k] = we[k]
                tau += piece
                if t_event < 0.0:
                    break
                # ---- the event ----
                y0_valid = False
                events_here += 1
                t_abs = t_i + jsub * h + tau
                hold = _dot(ell_hold, w)
                if mode == 0:
                    s = 1.0 if hold > 0.0 else -1.0
                    # the friction absorbs the rounding of the instant: the net force is s(µs − µk)W exactly
                    excess = hold - s * mu_s_w
                    f_val = s * mu_k_w
                    if abs(excess) <= 1e-9 * mu_s_w:
                        f_val += excess
                    w[idx_f] = f_val
                    mode = 1
                    kind = BREAKAWAY
                elif abs(hold) <= mu_s_w:
                    mode = 0
                    x_stuck = w[idx_xb]
                    w[idx_f] = 0.0
                    kind = STICK
                else:
                    s = 1.0 if hold > 0.0 else -1.0
                    w[idx_f] = s * mu_k_w
                    kind = REVERSAL
                if n_ev < ev_time.shape[0]:
                    ev_time[n_ev] = t_abs
                    ev_kind[n_ev] = kind
                    ev_x[n_ev] = w[idx_xb]
                n_ev += 1
                # the functionals jump with the mode (the slab's acceleration): count the new side
                _matvec(mon_modes[mode], w, y1)
                for k in range(nk):
                    peak_max[k] = max(peak_max[k], y1[k])
                    peak_min[k] = min(peak_min[k], y1[k])
                if events_here > MAX_EVENTS_PER_INTERVAL:
                    status |= STATUS_CHATTER
                    mode = 0
                    x_stuck = w[idx_xb]
                    w[idx_vb] = 0.0
                    w[idx_f] = 0.0
        # ---- sample i + 1 ----
        w[idx_ag] = acc[i + 1]
        for k in range(nw):
            out_state[i + 1, k] = w[k]
        _matvec(mon_modes[mode], w, y1)
        for k in range(nk):
            out_mon[i + 1, k] = y1[k]
        out_energy[0, i + 1] = e_in
        out_energy[1, i + 1] = e_f
        out_energy[2, i + 1] = e_v
    if n_ev > ev_time.shape[0]:
        status |= STATUS_EVENTS_TRUNCATED
    summary[S_E_INPUT] = e_in
    summary[S_E_FRICTION] = e_f
    summary[S_E_VISCOUS] = e_v
    summary[S_SLIP_TIME] = slip_time
    summary[S_N_EVENTS] = n_ev
    summary[S_STATUS] = status
    summary[S_N_SERIES] = n_series
    summary[S_N_LOCATED] = n_located


#: The piece helpers under public names, for the building on a multi-surface bearing
#: (:mod:`isolator.solver.building_multisurface_kernel`), which propagates the same augmented system.
krylov = _krylov
state_at = _state_at
poly = _poly
poly_root = _poly_root
quadratic_integral = _quadratic_integral
dot = _dot
matvec = _matvec
