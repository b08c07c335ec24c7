"""The compiled record loop of a multi-surface bearing: exact 1-D response, rims included.

Pure arrays in, arrays out (numba, cached on disk).  The bearing is the series model of
:mod:`isolator.solver.multisurface_series`; the mass obeys, per unit mass,

    X'' + c X' + F(X)/M = −a_g(t),

where, while the mass moves one way, F/M = κ_k X + b_k on regime k of the excursion
(κ_k = g / Σ R̄ of the sliding elements).  So between events the motion is the closed
form of :mod:`isolator.solver.segments` (the single pendulum's), and the events are:

* **stop** (V = 0) — the same decisive test and bracketed root as the single pendulum
  (:func:`isolator.solver.events.find_stop`; pieces are at most π/(2 ω_d) of the
  *stiffest* regime, so the velocity is unimodal on every piece);
* **regime change** — X reaches the next breakpoint of the excursion.  X is monotone
  between stops, so the crossing is the single root of X(τ) − x_k on a bracket,
  found by a safeguarded Newton iteration (:func:`displacement_root`);
* **rim reached** — the next regime is rigid but not the last (an *intermediate* rim: the
  elements that slid are on their rims before the force reaches the next element's
  friction level, e.g. a double with µ2 > µ1 + d1*/R̄1).  The sliders are massless, so
  the element on its rim cannot move outward while the next one is rigid–plastic: it
  takes any slide rate at its friction level.  The force through the bearing therefore
  jumps to the next regime's level (a finite force, so no impulse) and the mass goes on
  with its velocity continuous; only the friction work changes rate.  The rigid regime
  is passed at once (both regimes start at the same x);
* **ultimate** — the last regime is rigid (every element on its rim): a plastic impact,
  V → 0, the impulse per unit mass |V| and the energy ½V² reported; the bearing then
  holds any outward force;
* **stick / break-away** — the stuck bearing holds F/W in the window of
  :func:`isolator.solver.multisurface_series.stick_window` (static friction); with a
  piecewise-linear record the break-away is linear in time, hence exact.  A single
  element with µs > µk then slides at µk (the force drops, as in
  :mod:`isolator.solver.kernel`).

Energies per unit mass: input −∫a_g V dt and the bearing's friction work
g Σ µ_i |Δū_i| in closed form, the stored energy g Σ ū_i²/(2R̄_i), viscous c∫V² by
Gauss–Legendre on the exact velocity, and the impacts' ½V².
"""

from __future__ import annotations

import math

import numpy as np

from isolator.solver.events import BREAKAWAY, REVERSAL, STICK, find_stop, record_event, secant_guess, segment_root
from isolator.solver.jit import njit
from isolator.solver.kernel import velocity_peak, viscous_integral
from isolator.solver.multisurface_series import excursion, settle, stick_window
from isolator.solver.segments import ramp_basis, segment_state

REGIME = 3  #: the sliding set changed (an element started or reached its rim)
RIM_REACHED = 4  #: an intermediate rigid regime passed: the force jumps to the next element's level, V continuous
ULTIMATE = 5  #: plastic impact at the ultimate displacement (every slider on its rim)
EVENT_NAMES = ("breakaway", "stick", "reversal", "regime", "rim reached", "ultimate")

MAX_EVENTS_PER_INTERVAL = 1000  #: chatter guard, as for the single pendulum

STATUS_OK = 0
STATUS_CHATTER = 1
STATUS_EVENTS_TRUNCATED = 2

# layout of the summary vector
S_PEAK_X = 0
S_PEAK_V = 1
S_PEAK_A = 2
S_SLIP_TIME = 3
S_E_INPUT = 4
S_E_FRICTION = 5
S_E_VISCOUS = 6
S_E_IMPACT = 7
S_N_EVENTS = 8
S_STATUS = 9
S_N_RIM_CONTACTS = 10
S_N_ULTIMATE = 11
S_IMPULSE = 12  #: Σ |V| at impacts [m/s] (impulse per unit mass)
S_MAX_IMPACT_V = 13  #: largest |V| at an impact [m/s]
S_FIRST_ULTIMATE_T = 14  #: time of the first impact at the ultimate displacement [s] (-1: none)
S_PEAK_R = 15  #: largest |F/W| of the bearing [-]
SUMMARY_SIZE = 16

@njit(cache=True)
def displacement_root(sign, t_hi, x0, v0, p, q, c, kappa, target, guess):
    """The instant in (0, t_hi] where X(τ) reaches ``target``, X monotone (direction ``sign``) on [0, t_hi].

    Safeguarded Newton (derivative V) inside a bracket that always holds the root.
    """
    a = 0.0
    b = t_hi
    t = guess if 0.0 < guess < t_hi else 0.5 * t_hi
    for _ in range(200):
        x, v, _, _ = segment_state(t, x0, v0, p, q, 0.0, 0.0, c, kappa, 0.0)
        f = sign * (x - target)
        if f == 0.0:
            return t
        if f < 0.0:
            a = t
        else:
            b = t
        if b - a <= 4e-16 * b:
            return b
        df = sign * v
        t_new = t - f / df if df > 0.0 else 0.5 * (a + b)
        if not (a < t_new < b):
            t_new = 0.5 * (a + b)
        elif abs(t_new - t) <= 2e-16 * t:
            return t_new
        t = t_new
    return b


@njit(cache=True)
def _surface_peaks(u, tmat, surf_peak):
    for j in range(tmat.shape[0]):
        total = 0.0
        for i in range(u.shape[0]):
            total += tmat[j, i] * u[i]
        if abs(total) > surf_peak[j]:
            surf_peak[j] = abs(total)


@njit(cache=True)
def _regime_setup(k, reg_x, reg_r, reg_rsum, reg_mask, rbar, mu, g):
    # κ_k, b_k (F/M = κ X + b) and g µ_eff (friction force per unit of |ΔX|) of regime k
    rsum = reg_rsum[k]
    kappa = g / rsum
    b = g * reg_r[k] - kappa * reg_x[k]
    mu_eff = 0.0
    for i in range(rbar.shape[0]):
        if reg_mask[k] >> i & 1:
            mu_eff += mu[i] * rbar[i]
    return kappa, b, g * mu_eff / rsum


@njit(cache=True)
def _enter_excursion(s, u, rbar, mu, rim, x, reg_x, reg_r, reg_rsum, reg_mask, g, state_first_time, t):
    # the regimes of a new excursion in direction s, the elements already on their rim that way,
    # and regime 0's κ, b, g µ_eff (zeros when it is rigid); marks the state's first time
    n_reg = excursion(s, u, rbar, mu, rim, x, reg_x, reg_r, reg_rsum, reg_mask)
    rim_before = 0
    for e in range(u.shape[0]):
        if s * u[e] >= rim[e]:
            rim_before |= 1 << e
    kappa = 0.0
    bk = 0.0
    fric = 0.0
    if reg_rsum[0] > 0.0:
        kappa, bk, fric = _regime_setup(np.int64(0), reg_x, reg_r, reg_rsum, reg_mask, rbar, mu, g)
        code = reg_mask[0] + (1 << u.shape[0]) * rim_before
        if state_first_time[code] < 0.0:
            state_first_time[code] = t
    return n_reg, rim_before, kappa, bk, fric


@njit(cache=True)
def multisurface_kernel(acc, dt, times, n_sub, max_piece, c, g, rbar, mu, mu_static, rim, tmat,
                        out_x, out_v, out_a, out_r, out_energy, ev_time, ev_kind, ev_x,
                        summary, surf_peak, state_first_time, u):
    """Exact response of a mass on a multi-surface bearing to a sampled record.

    Parameters
    ----------
    acc : float64[n]
        Ground acceleration [m/s²], linear between samples.
    dt : float
        Sample interval [s] of a uniform record (``times`` empty).
    times : float64[n] or float64[0]
        Sample times from the first [s] of a non-uniform record.
    n_sub : int
        Sub-steps per interval of a uniform record (pieces ≤ ``max_piece``).
    max_piece : float
        Longest piece [s]: π/(2 ω_d) of the stiffest regime.
    c, g : float
        Damping per unit mass [1/s] and gravity [m/s²].
    rbar, mu, rim : float64[ne]
        The series elements (radius [m], kinetic friction [-], rim [m]).
    mu_static : float64[ne]
        Static friction [-] (>= ``mu``): the stuck bearing's window.  Above ``mu`` only for
        one element (a single pendulum): the force then drops from the static to the
        kinetic level at the break-away, as in :mod:`isolator.solver.kernel`; in a series
        of massless sliders such a drop would stop the others (the caller refuses it).
    tmat : float64[ns, ne]
        Displacement on each real surface from the elements' [-].
    out_x, out_v, out_a, out_r : float64[n]
        Filled: displacement [m], velocity [m/s], absolute acceleration of the mass
        [m/s²] and the bearing's force F/W [-] at the samples.
    out_energy : float64[4, n]
        Filled: cumulative input, friction, viscous and impact energy [J/kg].
    ev_time, ev_kind, ev_x : arrays
        Filled with the events while room lasts.
    summary : float64[SUMMARY_SIZE]
        Filled with peaks, energies, counts and status.
    surf_peak : float64[ns]
        Filled with the peak |displacement| on each real surface (effective geometry) [m].
    state_first_time : float64[4**ne]
        Filled with the first time [s] each (sliding set, rims) state was entered (-1: never);
        index = sliding mask + 2**ne × rim mask.
    u : float64[ne]
        In: the elements' initial displacements (zeros); out: their final ones [m].
    """
    n = acc.shape[0]
    ne = rbar.shape[0]
    uniform = times.shape[0] == 0
    size = 2 * ne + 1
    reg_x = np.empty(size)
    reg_r = np.empty(size)
    reg_rsum = np.empty(size)
    reg_mask = np.zeros(size, dtype=np.int64)
    n_reg = 0
    k = 0
    rim_before = 0  # elements on their rim in the direction of motion at regime k
    # full sub-step basis per sliding set (uniform records)
    n_masks = 1 << ne
    basis_cache = np.zeros((n_masks, 5))
    basis_ok = np.zeros(n_masks, dtype=np.bool_)
    h_full = dt / n_sub if uniform else 0.0
    kappa = 0.0
    bk = 0.0
    fric = 0.0
    x = 0.0
    v = 0.0
    for i in range(ne):
        x += u[i]
    stuck = True
    s = 0.0
    from_rest = False
    exact_start = False
    n_ev = 0
    status = 0
    peak_x = abs(x)
    peak_v = 0.0
    peak_a = abs(acc[0])
    peak_r = 0.0
    slip_time = 0.0
    e_in = 0.0
    e_f = 0.0
    e_v = 0.0
    e_imp = 0.0
    n_rim = 0
    n_ult = 0
    impulse = 0.0
    max_imp_v = 0.0
    first_ult = -1.0
    r_lo, r_hi = stick_window(u, rbar, mu_static, rim)
    # at a break-away the net force on the mass is exactly zero unless the friction drops there
    exact_breakaway = True
    for e in range(ne):
        if mu_static[e] != mu[e]:
            exact_breakaway = False
    for j in range(state_first_time.shape[0]):
        state_first_time[j] = -1.0
    out_x[0] = x
    out_v[0] = 0.0
    out_a[0] = acc[0]
    out_r[0] = -acc[0] / g
    for row in range(4):
        out_energy[row, 0] = 0.0
    i = 0
    while i < n - 1:
        if stuck:
            f_lo = g * r_lo
            f_hi = g * r_hi
            # both ends inside the window (the start too: a record whose first sample is beyond it
            # slides from t = 0, it must not be skipped)
            while i < n - 1 and f_lo <= -acc[i] <= f_hi and f_lo <= -acc[i + 1] <= f_hi:
                i += 1
                out_x[i] = x
                out_v[i] = 0.0
                out_a[i] = acc[i]
                out_r[i] = -acc[i] / g
                out_energy[0, i] = e_in
                out_energy[1, i] = e_f
                out_energy[2, i] = e_v
                out_energy[3, i] = e_imp
                if abs(acc[i]) > peak_a:
                    peak_a = abs(acc[i])
            if i >= n - 1:
                break
        a0 = acc[i]
        if uniform:
            dt_i = dt
            n_sub_i = n_sub
            h = h_full
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
                    # break-away: the force the mass needs, −a_g, leaves [g r_lo, g r_hi] (linear in τ)
                    need_end = -(a_sub + b * h)
                    need_now = -(a_sub + b * tau)
                    f_lo = g * r_lo
                    f_hi = g * r_hi
                    if f_lo <= need_now <= f_hi:
                        if f_lo <= need_end <= f_hi:
                            break  # stuck to the end of the sub-step (linear in between)
                        s = 1.0 if need_end > f_hi else -1.0
                        level = f_hi if s > 0.0 else f_lo
                        tb = (level + a_sub) / (-b) if b != 0.0 else tau
                        tb = min(max(tb, tau), h)
                        exact_start = exact_breakaway
                    else:
                        # already beyond the window (a record that starts there, or the force
                        # after an impact): a jump, not a crossing
                        s = 1.0 if need_now > f_hi else -1.0
                        tb = tau
                        exact_start = False
                    tau = tb
                    stuck = False
                    from_rest = True
                    n_ev = record_event(ev_time, ev_kind, ev_x, n_ev, t_sub + tb, np.int64(BREAKAWAY), x)
                    n_reg, rim_before, kappa, bk, fric = _enter_excursion(
                        s, u, rbar, mu, rim, x, reg_x, reg_r, reg_rsum, reg_mask, g, state_first_time, t_sub + tb)
                    k = 0
                    peak_a = max(peak_a, abs(a_sub + b * tb))
                    if tau >= h:
                        break
                if reg_rsum[k] == 0.0 and k < n_reg - 1 and v != 0.0:
                    # an intermediate rim while moving: the next element takes the motion at its friction
                    # level, a finite force, so V is continuous (no impulse); the force jumps there
                    k += 1
                    kappa, bk, fric = _regime_setup(k, reg_x, reg_r, reg_rsum, reg_mask, rbar, mu, g)
                    code = reg_mask[k] + n_masks * rim_before
                    if state_first_time[code] < 0.0:
                        state_first_time[code] = t_sub + tau
                    peak_r = max(peak_r, abs(reg_r[k]))
                    peak_a = max(peak_a, abs(g * reg_r[k] + c * v))
                    n_ev = record_event(ev_time, ev_kind, ev_x, n_ev, t_sub + tau, np.int64(RIM_REACHED), x)
                    continue
                if reg_rsum[k] == 0.0:
                    # entering a rigid regime at rest (it holds the force: stuck), or the ultimate
                    # displacement while moving: plastic impact
                    if v != 0.0:
                        impulse += abs(v)
                        if abs(v) > max_imp_v:
                            max_imp_v = abs(v)
                        e_imp += 0.5 * v * v
                    v = 0.0
                    r_end = reg_r[k]
                    settle(s, u, rbar, mu, rim, r_end)
                    if abs(r_end) > peak_r:
                        peak_r = abs(r_end)
                    ultimate = k == n_reg - 1
                    kind = ULTIMATE if ultimate else STICK
                    if ultimate:
                        n_ult += 1
                        if first_ult < 0.0:
                            first_ult = t_sub + tau
                    n_ev = record_event(ev_time, ev_kind, ev_x, n_ev, t_sub + tau, kind, x)
                    _surface_peaks(u, tmat, surf_peak)
                    r_lo, r_hi = stick_window(u, rbar, mu_static, rim)
                    stuck = True
                    events_here += 1
                    if events_here > MAX_EVENTS_PER_INTERVAL:
                        status |= STATUS_CHATTER
                        r_lo = -math.inf
                        r_hi = math.inf
                        break
                    continue
                # ---- sliding in direction s, regime k, from local time tau ----
                rem = h - tau
                a_start = a_sub + b * tau
                if exact_start:
                    p = kappa * x  # at a break-away the net force is exactly zero
                else:
                    p = -(a_start + bk)
                mask = reg_mask[k]
                if uniform and tau == 0.0 and not exact_start:
                    if not basis_ok[mask]:
                        e0_, e1_, h1_, h2_, h3_ = ramp_basis(h_full, c, kappa)
                        basis_cache[mask, 0] = e0_
                        basis_cache[mask, 1] = e1_
                        basis_cache[mask, 2] = h1_
                        basis_cache[mask, 3] = h2_
                        basis_cache[mask, 4] = h3_
                        basis_ok[mask] = True
                    e0 = basis_cache[mask, 0]
                    e1 = basis_cache[mask, 1]
                    h1 = basis_cache[mask, 2]
                    h2 = basis_cache[mask, 3]
                    h3 = basis_cache[mask, 4]
                else:
                    e0, e1, h1, h2, h3 = ramp_basis(rem, c, kappa)
                m = -0.5 * c
                x1 = e0 * x + e1 * (v - m * x) + p * h1 + q * h2
                v1 = e0 * v + e1 * (m * v - kappa * x + p) + q * h1
                acc0 = p - kappa * x - c * v
                acc1 = p + q * rem - kappa * x1 - c * v1
                t_stop, t_ext, v_ext = find_stop(s, from_rest, rem, x, v, v1, acc0, acc1, p, q,
                                                 0.0, 0.0, c, kappa, 0.0)
                if t_ext >= 0.0 and abs(v_ext) > peak_v:
                    peak_v = abs(v_ext)
                # does X reach the next breakpoint before the stop / the end of the piece?
                t_cross = -1.0
                # the basis at the stop, computed once (used for the crossing test and the stop)
                e0s = e1s = h1s = h2s = h3s = 0.0
                if t_stop >= 0.0:
                    e0s, e1s, h1s, h2s, h3s = ramp_basis(t_stop, c, kappa)
                if k + 1 < n_reg:
                    x_next = reg_x[k + 1]
                    if s * (x_next - x) <= 0.0:
                        t_cross = 0.0
                    else:
                        x_h = x1
                        t_h = rem
                        if t_stop >= 0.0:
                            t_h = t_stop
                            x_h = e0s * x + e1s * (v - m * x) + p * h1s + q * h2s
                        if s * (x_h - x_next) > 0.0 or (t_stop < 0.0 and s * (x_h - x_next) == 0.0):
                            t_cross = displacement_root(s, t_h, x, v, p, q, c, kappa, x_next,
                                                        secant_guess(0.0, t_h, x - x_next, x_h - x_next))
                if t_cross < 0.0 and t_stop < 0.0:
                    # slides through to the end of the piece
                    int_x = e1 * x + h1 * (v - 2.0 * m * x) + p * h2 + q * h3
                    e_in -= a_start * (x1 - x) + b * (rem * x1 - int_x)
                    e_f += fric * abs(x1 - x)
                    if c > 0.0:
                        e_v += c * viscous_integral(rem, x, v, p, q, c, kappa)
                        d0 = kappa * v + c * acc0
                        d1 = kappa * v1 + c * acc1
                        a_ends = max(abs(kappa * x + bk + c * v), abs(kappa * x1 + bk + c * v1))
                        if d0 * d1 < 0.0 and a_ends + 2.0 * rem * max(abs(d0), abs(d1)) > peak_a:
                            sg = 1.0 if d0 > 0.0 else -1.0
                            t_e = segment_root(np.int64(2), sg, 0.0, rem, x, v, p, q, 0.0, 0.0, c, kappa, 0.0,
                                               secant_guess(0.0, rem, d0, d1))
                            x_e, v_e, _, _ = segment_state(t_e, x, v, p, q, 0.0, 0.0, c, kappa, 0.0)
                            peak_a = max(peak_a, abs(kappa * x_e + bk + c * v_e))
                    slip_time += rem
                    if t_ext < 0.0:
                        peak_v = velocity_peak(peak_v, rem, x, v, v1, acc0, acc1, p, q, c, kappa)
                    x = x1
                    v = v1
                    tau = h
                    from_rest = False
                    exact_start = False
                    peak_x = max(peak_x, abs(x))
                    peak_v = max(peak_v, abs(v))
                    peak_a = max(peak_a, abs(kappa * x + bk + c * v))
                    break
                # an event inside the piece: the crossing of a breakpoint or a stop, whichever first
                crossing = t_cross >= 0.0
                t_ev = t_cross if crossing else t_stop
                if t_ev > 0.0:
                    if crossing:
                        e0s, e1s, h1s, h2s, h3s = ramp_basis(t_ev, c, kappa)
                    x_s = e0s * x + e1s * (v - m * x) + p * h1s + q * h2s
                    v_s = e0s * v + e1s * (m * v - kappa * x + p) + q * h1s
                    acc_s = p + q * t_ev - kappa * x_s - c * v_s
                    if crossing:
                        x_s = reg_x[k + 1]  # the breakpoint itself (the root is exact to rounding)
                    else:
                        v_s = 0.0
                    int_x = e1s * x + h1s * (v - 2.0 * m * x) + p * h2s + q * h3s
                    e_in -= a_start * (x_s - x) + b * (t_ev * x_s - int_x)
                    e_f += fric * abs(x_s - x)
                    if c > 0.0:
                        e_v += c * viscous_integral(t_ev, x, v, p, q, c, kappa)
                    if t_ext < 0.0 or t_ext > t_ev:
                        peak_v = velocity_peak(peak_v, t_ev, x, v, v_s, acc0, acc_s, p, q, c, kappa)
                    slip_time += t_ev
                    tau += t_ev
                    x = x_s
                    v = v_s
                    peak_x = max(peak_x, abs(x))
                    peak_v = max(peak_v, abs(v))
                    peak_a = max(peak_a, abs(kappa * x + bk + c * v))
                from_rest = False
                exact_start = False
                if crossing:
                    # the sliding set changes at the breakpoint
                    left = reg_mask[k] & ~reg_mask[k + 1]
                    while left:
                        n_rim += left & 1
                        left >>= 1
                    rim_before |= reg_mask[k] & ~reg_mask[k + 1]
                    k += 1
                    n_ev = record_event(ev_time, ev_kind, ev_x, n_ev, t_sub + tau, np.int64(REGIME), x)
                    if reg_rsum[k] > 0.0:
                        kappa, bk, fric = _regime_setup(k, reg_x, reg_r, reg_rsum, reg_mask, rbar, mu, g)
                        code = reg_mask[k] + n_masks * rim_before
                        if state_first_time[code] < 0.0:
                            state_first_time[code] = t_sub + tau
                    peak_r = max(peak_r, abs(reg_r[k]))
                    events_here += 1
                    if events_here > MAX_EVENTS_PER_INTERVAL:
                        # chatter guard: hold the bearing to the end of the interval
                        status |= STATUS_CHATTER
                        settle(s, u, rbar, mu, rim, reg_r[k])
                        stuck = True
                        v = 0.0
                        r_lo = -math.inf
                        r_hi = math.inf
                        break
                    continue
                # ---- the mass stops: settle the elements, then stick or reverse ----
                r_end = reg_r[k] + (x - reg_x[k]) / reg_rsum[k]
                peak_r = max(peak_r, abs(r_end))
                settle(s, u, rbar, mu, rim, r_end)
                _surface_peaks(u, tmat, surf_peak)
                r_lo, r_hi = stick_window(u, rbar, mu_static, rim)
                need = -(a_sub + b * tau)
                if g * r_lo <= need <= g * r_hi:
                    stuck = True
                    kind = STICK
                    peak_a = max(peak_a, abs(need))
                else:
                    s = 1.0 if need > g * r_hi else -1.0
                    kind = REVERSAL
                    from_rest = True
                    n_reg, rim_before, kappa, bk, fric = _enter_excursion(
                        s, u, rbar, mu, rim, x, reg_x, reg_r, reg_rsum, reg_mask, g, state_first_time, t_sub + tau)
                    k = 0
                    peak_a = max(peak_a, abs(g * reg_r[0]))
                n_ev = record_event(ev_time, ev_kind, ev_x, n_ev, t_sub + tau, kind, x)
                events_here += 1
                if events_here > MAX_EVENTS_PER_INTERVAL:
                    status |= STATUS_CHATTER
                    if not stuck:
                        # let the bearing hold to the end of the interval (state already settled)
                        stuck = True
                        r_lo = -math.inf
                        r_hi = math.inf
                    break
            if events_here > MAX_EVENTS_PER_INTERVAL:
                break
        if status & STATUS_CHATTER and stuck and r_lo == -math.inf:
            r_lo, r_hi = stick_window(u, rbar, mu_static, rim)
        i += 1
        out_x[i] = x
        out_v[i] = v
        out_energy[0, i] = e_in
        out_energy[1, i] = e_f
        out_energy[2, i] = e_v
        out_energy[3, i] = e_imp
        if stuck:
            out_a[i] = acc[i]
            out_r[i] = -acc[i] / g
        else:
            out_r[i] = (kappa * x + bk) / g
            out_a[i] = -(kappa * x + bk + c * v)
            peak_r = max(peak_r, abs(out_r[i]))
        peak_a = max(peak_a, abs(out_a[i]))
    if not stuck and n_reg > 0 and reg_rsum[k] > 0.0:
        # the record ends mid-excursion: the elements' state at the current force
        settle(s, u, rbar, mu, rim, reg_r[k] + (x - reg_x[k]) / reg_rsum[k])
    _surface_peaks(u, tmat, surf_peak)
    if n_ev > ev_time.shape[0]:
        status |= STATUS_EVENTS_TRUNCATED
    summary[S_PEAK_X] = peak_x
    summary[S_PEAK_V] = peak_v
    summary[S_PEAK_A] = peak_a
    summary[S_SLIP_TIME] = slip_time
    summary[S_E_INPUT] = e_in
    summary[S_E_FRICTION] = e_f
    summary[S_E_VISCOUS] = e_v
    summary[S_E_IMPACT] = e_imp
    summary[S_N_EVENTS] = n_ev
    summary[S_STATUS] = status
    summary[S_N_RIM_CONTACTS] = n_rim
    summary[S_N_ULTIMATE] = n_ult
    summary[S_IMPULSE] = impulse
    summary[S_MAX_IMPACT_V] = max_imp_v
    summary[S_FIRST_ULTIMATE_T] = first_ult
    summary[S_PEAK_R] = peak_r


__all__ = ["multisurface_kernel", "EVENT_NAMES", "SUMMARY_SIZE"]
