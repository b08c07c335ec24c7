"""The compiled planar (2-D) record loop: coupled friction, µ(v), n(t) = g + a_z, uplift.

Pure arrays in, arrays out (numba, cached on disk); the tuning constants and the pieces the loop
repeats are in :mod:`planar_control`, compiled into it.  The DOP853 steps of :mod:`planar_rk`
integrate the motion between events; the answer depends on the record only through its
piecewise-linear reading: no step crosses a sample nor an instant where n changes sign; stuck,
the first break-away is a root of a quadratic in local time (no stepping); a start runs in the
START form, a slide in the POLAR form, the approach to a stop in the LOG form down to V = 0 and
the last bit in closed form, then the stick test decides (stick, or a reversal); peaks of |X|,
|V| and |a| between step ends are located; every loop is bounded.  docs/planar.md, "Method".
"""

from __future__ import annotations

import math

import numpy as np

from isolator.solver.jit import njit
from isolator.solver.planar_control import (
    ENTER_LOG,
    KINK_STEP,
    LAG_MAX_RAD,
    LEAVE_LOG,
    POLAR_VELOCITY_TOL,
    R_FLOOR_FRACTION,
    STABLE_CARTESIAN,
    STABLE_POLAR,
    come_to_rest,
    enter_polar,
    leave_log,
    peak_in_step,
    stop_ahead,
    store_sample,
)
from isolator.solver.planar_dop853 import dop853_step
from isolator.solver.planar_events import (
    PH_APPROACH,
    PH_FLIGHT,
    PH_POLAR,
    PH_SLIDE,
    PH_START,
    PH_STUCK,
    acceleration_bound,
    acceleration_peak_rate,
    coast_to_rest,
    force_norm,
    force_scale,
    friction_force,
    ground_norm,
    hermite_crossing,
    holds_at,
    kappa_at,
    kappa_of,
    land,
    land_on,
    lift_off,
    locate_peak,
    mode_of,
    peak_value,
    phase_of_mode,
    rate_of_peak,
    record_event,
    rim_crossing,
    settled,
    start_lag,
    stuck_until,
    tangent_bound,
    transmitted,
    velocity,
)
from isolator.solver.planar_layout import (
    EV_BREAKAWAY,
    EV_LANDING,
    EV_UPLIFT,
    MAX_EVENTS_PER_INTERVAL,
    MAX_STEPS_PER_INTERVAL,
    RIM_SLACK,
    RM_HIT,
    RM_I,
    RM_RADIUS,
    RM_START,
    RM_TAU,
    RM_V1,
    RM_V2,
    RM_X1,
    RM_X2,
    RS_FRESH,
    RS_START,
    S_E_F,
    S_E_IN,
    S_E_V,
    S_N_EVENTS,
    S_N_REJECTED,
    S_N_STEPS,
    S_N_UPLIFTS,
    S_PEAK_A,
    S_PEAK_V,
    S_PEAK_X,
    S_SLIP_TIME,
    S_STATUS,
    S_STEPS_LIMITED,
    S_STEPS_LOG,
    S_STEPS_START,
    S_SUB_LAND,
    S_SUB_PEAK,
    S_UPLIFT_TIME,
    SC_R_MIN,
    SC_R_SWITCH,
    SC_R_SWITCH_LO,
    SC_V_FLOOR,
    SC_X_FLOOR,
    STATUS_CHATTER,
    STATUS_EVENTS_TRUNCATED,
    STATUS_STEP_LIMIT,
)
from isolator.solver.planar_rk import (
    CARTESIAN,
    LOG,
    NSTATE,
    POLAR,
    START,
    eighth_root,
    factor_of_root,
    norm,
    rhs,
    step_factor,
)


@njit(cache=True, _nrt=False)
def scan_record(ax, ay, nz):
    """One pass over a record before it is solved.

    Returns
    -------
    tuple
        ``(finite, pga², n_max, has_y)``: are a_x, a_y and n all finite, the largest
        a_x² + a_y² [m²/s⁴], the largest n = g + a_z [m/s²], and is any a_y ≠ 0.
    """
    finite = True
    pga2 = 0.0
    n_max = -np.inf
    has_y = False
    for i in range(ax.shape[0]):
        a1 = ax[i]
        a2 = ay[i]
        nn = nz[i]
        if not (math.isfinite(a1) and math.isfinite(a2) and math.isfinite(nn)):
            finite = False
        pga2 = max(pga2, a1 * a1 + a2 * a2)
        n_max = max(n_max, nn)
        if a2 != 0.0:
            has_y = True
    return finite, pga2, n_max, has_y


@njit(cache=True)
def planar_kernel(t, ax, ay, nz, prm, scales, rtol, refresh, out_x, out_v, out_a, out_en, ev_t, ev_k,
                  summary, rim):
    """Response of the planar friction block to a piecewise-linear record.

    Parameters
    ----------
    t : float64[n]
        Sample times [s], strictly increasing (not necessarily uniform).
    ax, ay : float64[n]
        Ground acceleration samples [m/s²].
    nz : float64[n]
        Normal acceleration n = g + a_z at the samples [m/s²].
    prm : float64[P_SIZE]
        System (see :mod:`planar_rk`).
    scales : float64[SC_SIZE]
        Speed and tolerance scales (see the SC_* constants).
    rtol : float
        Relative tolerance of the DOP853 steps [-].
    refresh : bool
        Re-evaluate the derivative at each sample (needed when κ' jumps there).
    out_x, out_v, out_a : float64[n, 2]
        Filled with X [m], V [m/s] and the absolute acceleration of the mass [m/s²].
    out_en : float64[3, n]
        Cumulative input, friction and viscous energy per unit mass [J/kg].
    ev_t, ev_k : arrays
        Event times [s] and kinds, while room lasts.
    summary : float64[S_SIZE]
        Peaks, times, energies, counts and status (read as the starting values on a restart).
    rim : float64[RM_SIZE]
        The rim (:mod:`planar_layout`, ``RM_*``): its radius d (inf: none), and a restart — in
        interval ``RM_I`` at local time ``RM_TAU`` from X and either rest (START form) or a velocity
        V — after the rim's own phase (:mod:`isolator.solver.planar_rim`).  With a finite d the run
        stops where |X| first reaches d (located inside the step, :func:`rim_crossing`) and
        returns that instant, X and V there, with ``RM_HIT`` = 1; the samples after it are not
        written.
    """
    n = t.shape[0]
    y = np.zeros(NSTATE)
    f = np.zeros(NSTATE)
    ynew = np.zeros(NSTATE)
    fnew = np.zeros(NSTATE)
    yb = np.zeros(NSTATE)
    fb = np.zeros(NSTATE)
    atol = np.full(NSTATE, np.inf)
    frc = np.zeros(7)
    work = np.zeros(2)
    phase = np.int64(PH_STUCK)
    x = 0.0
    h_sugg = -1.0
    ds_sugg = -0.5
    r_min = scales[SC_R_MIN]
    r_switch = scales[SC_R_SWITCH]
    r_switch_lo = scales[SC_R_SWITCH_LO]
    r_floor = r_min * R_FLOOR_FRACTION  #: the finish of a stop outside the LOG form, and of an unsettled one
    s_end = math.log(r_min)
    s_floor = math.log(r_floor)
    s_stop = s_end  #: where the current approach to a stop hands over to the closed-form finish
    peak_x = 0.0
    peak_v = 0.0
    peak_a = norm(ax[0], ay[0])
    slip = 0.0
    upt = 0.0
    n_up = 0
    n_ev = 0
    status = 0
    n_steps = 0
    n_rej = 0
    n_start = 0
    n_log = 0
    n_lim = 0
    just_rejected = False
    acc_i = -1  #: sample interval and local time of (a_end, g_end), the transmitted acceleration
    acc_tau = -1.0
    a_end = 0.0
    g_end = 0.0
    h_prev = -1.0  #: the last accepted step that did not end on a sample [s]
    root_prev = 1.0  #: err^(1/8) of that step
    prev_mode = -1
    same_state = False  #: the state has not moved since the last transmitted-acceleration check
    polar_ok = True
    failed_at = -1
    d_rim = rim[RM_RADIUS]
    rim_on = d_rim < np.inf
    d2 = d_rim * d_rim
    d_detect = d_rim * (1.0 + RIM_SLACK)
    restart = int(rim[RM_START])
    rim[RM_HIT] = 0.0
    ys = np.zeros(NSTATE)  #: the start of the last step, kept while a rim is on (its crossing is located on it)
    fs = np.zeros(NSTATE)
    xs = 0.0
    ts = 0.0
    step_h = -1.0
    step_mode = np.int64(CARTESIAN)
    pxs = 0.0
    pvs = 0.0
    pas = 0.0
    slips = 0.0
    upts = 0.0
    at_rim = False
    i0 = 0
    if restart == RS_FRESH:
        store_sample(0, 0.0, 0.0, ax[0], ay[0], y, out_x, out_v, out_a, out_en)  # at rest, y = 0
    else:  # go on from the rim's phase: its state, energies, peaks and counts
        i0 = int(rim[RM_I])
        y[0] = rim[RM_X1]
        y[1] = rim[RM_X2]
        y[4] = summary[S_E_IN]
        y[5] = summary[S_E_F]
        y[6] = summary[S_E_V]
        peak_x = summary[S_PEAK_X]
        peak_v = summary[S_PEAK_V]
        peak_a = summary[S_PEAK_A]
        slip = summary[S_SLIP_TIME]
        upt = summary[S_UPLIFT_TIME]
        n_up = int(summary[S_N_UPLIFTS])
        n_ev = int(summary[S_N_EVENTS])
        status = int(summary[S_STATUS])
        n_steps = int(summary[S_N_STEPS])
        n_rej = int(summary[S_N_REJECTED])
        n_start = int(summary[S_STEPS_START])
        n_log = int(summary[S_STEPS_LOG])
        n_lim = int(summary[S_STEPS_LIMITED])
        work[0] = summary[S_SUB_LAND]
        work[1] = summary[S_SUB_PEAK]
        phase = np.int64(PH_START if restart == RS_START else PH_SLIDE)
    for i in range(i0, n - 1):
        restart_here = restart != RS_FRESH and i == i0
        if phase == PH_STUCK and holds_at(y[0], y[1], ax[i], ay[i], nz[i], prm) and holds_at(
                y[0], y[1], ax[i + 1], ay[i + 1], nz[i + 1], prm):
            # stuck at both ends of the interval, so throughout (holds_at): the sample in closed form
            if nz[i + 1] != nz[i]:  # κ = n/R changes: the work ½κ'|X|² of the vertical motion
                y[4] += 0.5 * (y[0] * y[0] + y[1] * y[1]) * (
                    kappa_of(nz[i + 1], prm) - kappa_of(nz[i], prm))
            store_sample(i + 1, 0.0, 0.0, ax[i + 1], ay[i + 1], y, out_x, out_v, out_a, out_en)
            peak_a = max(peak_a, norm(ax[i + 1], ay[i + 1]))
            continue
        hi = t[i + 1] - t[i]
        t0 = t[i]
        inv_hi = 1.0 / hi
        frc[0] = ax[i]
        frc[1] = (ax[i + 1] - ax[i]) * inv_hi
        frc[2] = ay[i]
        frc[3] = (ay[i + 1] - ay[i]) * inv_hi
        frc[4] = nz[i]
        frc[5] = (nz[i + 1] - nz[i]) * inv_hi
        frc[6] = 0.0 if phase == PH_FLIGHT else 1.0
        tau = 0.0
        if phase == PH_APPROACH:
            y[7] = 0.0
        elif phase != PH_STUCK:
            x = 0.0
        if refresh and phase != PH_STUCK and not restart_here:
            rhs(mode_of(phase), x, y, prm, frc, f)
        if restart_here:
            tau = rim[RM_TAU]
            x = tau
            y[7] = 0.0
            if restart == RS_START:  # a break-away from rest on the rim, inward
                y[2] = 0.0
                y[3] = 0.0
                rhs(np.int64(START), tau, y, prm, frc, f)
                h_sugg = 0.01 * hi
            else:  # leaving the rim along its tangent
                y[2] = rim[RM_V1]
                y[3] = rim[RM_V2]
                rhs(np.int64(CARTESIAN), tau, y, prm, frc, f)
        tz = hi
        if (nz[i] > 0.0 > nz[i + 1]) or (nz[i] < 0.0 < nz[i + 1]):
            tz = nz[i] / (nz[i] - nz[i + 1]) * hi
        crossed = tz >= hi or (restart_here and tz <= tau)
        nplus = nz[i] if nz[i] != 0.0 else nz[i + 1]
        # contact state just after the sample
        if restart_here:
            pass  # the rim's phase ended in contact (n > 0): the phase is set above
        elif phase == PH_FLIGHT and nplus > 0.0:
            n_ev = record_event(ev_t, ev_k, n_ev, t0, np.int64(EV_LANDING))
            phase = land(0.0, y, prm, frc, f)
            if phase == PH_START:
                n_ev = record_event(ev_t, ev_k, n_ev, t0, np.int64(EV_BREAKAWAY))
                h_sugg = 0.01 * hi
        elif phase != PH_FLIGHT and nplus <= 0.0:
            phase = lift_off(phase, x, 0.0, y, prm, frc, f)
            x = 0.0
            n_up += 1
            n_ev = record_event(ev_t, ev_k, n_ev, t0, np.int64(EV_UPLIFT))
        atol[0] = rtol * max(peak_x, scales[SC_X_FLOOR])
        atol[1] = atol[0]
        # the energies are error-controlled too (the balance is a check of the integration)
        atol[4] = rtol * max(abs(y[4]) + y[5] + y[6], scales[SC_V_FLOOR] ** 2)
        atol[5] = atol[4]
        atol[6] = atol[4]
        events_here = 0
        if phase == PH_POLAR and h_sugg > 0.0:
            h_sugg *= KINK_STEP
        steps_here = 0
        while True:
            if rim_on and step_h > 0.0:
                if norm(y[0], y[1]) > d_detect or peak_x > d_detect:
                    # the last step reached the rim: its instant, state and velocity there
                    theta = rim_crossing(step_mode, xs, ys, fs, step_h, d2, prm, frc, yb, fb, atol, rtol, work)
                    if theta < 0.0:
                        # not inside the step's own motion: the closed-form finish of a stop after it (a
                        # displacement ~r_min²/|ṙ|, far below the tolerance) ended beyond d
                        for k in range(NSTATE):
                            yb[k] = y[k]
                        tau_hit = tau
                        v1, v2 = velocity(phase, x, tau, y, prm, frc)
                        a1, a2 = transmitted(phase, x, tau, y, prm, frc)
                    else:
                        sp_ph = phase_of_mode(step_mode)
                        x_hit = xs + theta * step_h
                        tau_hit = yb[7] if step_mode == LOG else x_hit
                        v1, v2 = velocity(sp_ph, x_hit, tau_hit, yb, prm, frc)
                        a1, a2 = transmitted(sp_ph, x_hit, tau_hit, yb, prm, frc)
                        if step_mode != START and theta > 0.0:
                            # |V| and |a| may peak inside the part of the step before the impact
                            pvs = peak_in_step(pvs, np.int64(1), step_mode, xs, ys, fs, theta * step_h,
                                               peak_value(np.int64(1), step_mode, ys),
                                               rate_of_peak(np.int64(1), step_mode, ys, fs),
                                               peak_value(np.int64(1), step_mode, yb),
                                               rate_of_peak(np.int64(1), step_mode, yb, fb),
                                               tau_hit - ts, prm, frc, ynew, fnew, atol, rtol, work)
                            a_lo, g0 = acceleration_peak_rate(step_mode, xs, ys, fs, prm, frc)
                            a_hi, g1 = acceleration_peak_rate(step_mode, x_hit, yb, fb, prm, frc)
                            pas = peak_in_step(pas, np.int64(2), step_mode, xs, ys, fs, theta * step_h, a_lo, g0, a_hi,
                                               g1, tau_hit - ts, prm, frc, ynew, fnew, atol, rtol, work)
                    scale = d_rim / norm(yb[0], yb[1])  # on the circle (the crossing is located to rounding)
                    rim[RM_X1] = yb[0] * scale
                    rim[RM_X2] = yb[1] * scale
                    rim[RM_V1] = v1
                    rim[RM_V2] = v2
                    rim[RM_I] = i
                    rim[RM_TAU] = tau_hit
                    rim[RM_HIT] = 1.0
                    y[4] = yb[4]
                    y[5] = yb[5]
                    y[6] = yb[6]
                    peak_x = max(pxs, d_rim)
                    peak_v = max(pvs, norm(v1, v2))
                    peak_a = max(pas, norm(a1, a2))
                    if tau_hit >= ts:
                        slip = slips + (tau_hit - ts)
                        if step_mode == CARTESIAN and frc[6] == 0.0:
                            upt = upts + (tau_hit - ts)
                    at_rim = True
                    break
                step_h = -1.0
            if not tau < hi:
                break
            steps_here += 1
            if steps_here > MAX_STEPS_PER_INTERVAL:
                status |= STATUS_STEP_LIMIT
                failed_at = i
                break
            # every path through the loop (including each `continue`) comes back here
            if phase != PH_STUCK and not same_state:
                if phase == PH_SLIDE or phase == PH_FLIGHT:  # V' + a_g, from the derivative at hand
                    a1 = f[2] + frc[0] + frc[1] * tau
                    a2 = f[3] + frc[2] + frc[3] * tau
                elif phase == PH_POLAR:  # V' = r' e + r e'
                    a1 = f[7] * y[2] + y[7] * f[2] + frc[0] + frc[1] * tau
                    a2 = f[7] * y[3] + y[7] * f[3] + frc[2] + frc[3] * tau
                else:
                    a1, a2 = transmitted(phase, x, tau, y, prm, frc)
                peak_a = max(peak_a, norm(a1, a2))
            same_state = False
            if events_here > MAX_EVENTS_PER_INTERVAL:
                # chatter guard: let the static friction hold the block to the end of the interval
                status |= STATUS_CHATTER
                phase = np.int64(PH_STUCK)
                y[2] = 0.0
                y[3] = 0.0
                break
            if not crossed and tau >= tz:
                crossed = True
                if phase == PH_FLIGHT:
                    n_ev = record_event(ev_t, ev_k, n_ev, t0 + tau, np.int64(EV_LANDING))
                    events_here += 1
                    phase = land(tau, y, prm, frc, f)
                    if phase == PH_START:
                        n_ev = record_event(ev_t, ev_k, n_ev, t0 + tau, np.int64(EV_BREAKAWAY))
                        h_sugg = 0.01 * hi
                else:
                    phase = lift_off(phase, x, tau, y, prm, frc, f)
                    n_up += 1
                    n_ev = record_event(ev_t, ev_k, n_ev, t0 + tau, np.int64(EV_UPLIFT))
                    events_here += 1
                x = tau
            target = tz if tau < tz else hi
            if phase == PH_STUCK:
                u, up = stuck_until(y[0], y[1], tau, target - tau, prm, frc)
                tau_new = target if u < 0.0 else min(tau + u, target)
                # stuck, the transmitted acceleration is a_g, linear: its largest value is at an end (this
                # counts it at every stick and break-away; a stick on a sample end is counted with the sample)
                peak_a = max(peak_a, ground_norm(tau, frc), ground_norm(tau_new, frc))
                if frc[5] != 0.0:  # κ changes with n(t): the work ½κ'|X|² of the vertical motion
                    y[4] += 0.5 * (y[0] * y[0] + y[1] * y[1]) * (kappa_at(tau_new, prm, frc) - kappa_at(tau, prm, frc))
                tau = tau_new
                if u >= 0.0 and not up:
                    phase = np.int64(PH_START)
                    y[2] = 0.0
                    y[3] = 0.0
                    rhs(np.int64(START), tau, y, prm, frc, f)
                    n_ev = record_event(ev_t, ev_k, n_ev, t0 + tau, np.int64(EV_BREAKAWAY))
                    events_here += 1
                    h_sugg = 0.01 * hi
                    a1, a2 = transmitted(phase, x, tau, y, prm, frc)
                    peak_a = max(peak_a, norm(a1, a2))
            elif phase == PH_APPROACH:
                r = math.exp(x)
                rdot = r / f[7]
                fscale = force_scale(y[7], y, r, prm, frc)
                if x <= s_stop and s_stop > s_floor and not settled(y[7], y, f, prm, frc):
                    s_stop = s_floor  # the direction still turns: on to the old, deeper finish
                if x <= s_stop or rdot > -LEAVE_LOG * fscale:
                    if x > s_stop:
                        # the speed no longer falls fast: back to Cartesian form (a turn, not a stop)
                        x = leave_log(tau, y, r, prm, frc, f)
                        phase = np.int64(PH_SLIDE)
                        h_sugg = r / max(fscale, 1e-300)
                        continue
                else:
                    ds = max(ds_sugg, s_stop - x)
                    # the stop instant is error-controlled too, to what the POLAR form holds the speed to over
                    # the deceleration: it is no more precise than that speed before it (docs/dev-notes.md)
                    speed_tol = POLAR_VELOCITY_TOL * rtol * max(peak_v, scales[SC_V_FLOOR])
                    atol[7] = max(rtol * hi, speed_tol / max(-rdot, 1e-300))
                    if rim_on:
                        ys[:] = y
                        fs[:] = f
                        xs = x
                        ts = y[7]
                        pxs = peak_x
                        pvs = peak_v
                        pas = peak_a
                        slips = slip
                        upts = upt
                    ok, err = dop853_step(np.int64(LOG), x, y, f, ds, prm, frc, ynew, fnew, atol, rtol)
                    n_steps += 1
                    n_log += 1
                    if not ok or err > 1.0:
                        n_rej += 1
                        ds_sugg = ds * (0.25 if not ok else step_factor(err))
                        just_rejected = True
                        same_state = True  # a rejected step leaves the state as it was
                        if abs(ds_sugg) < 1e-9:
                            x = leave_log(tau, y, r, prm, frc, f)
                            phase = np.int64(PH_SLIDE)
                            h_sugg = r / max(fscale, 1e-300)
                        continue
                    hit = False
                    if ynew[7] >= target:
                        theta = land_on(np.int64(LOG), x, y, f, ds, np.int64(7), target, ynew[7], fnew[7], prm, frc, yb,
                                        fb, atol, rtol, work)
                        ynew[:] = yb
                        fnew[:] = fb
                        ds *= theta
                        ynew[7] = target
                        hit = True
                    if rim_on:
                        step_mode = np.int64(LOG)
                        step_h = ds
                    a_lo, g0 = acceleration_peak_rate(np.int64(LOG), x, y, f, prm, frc)
                    a_hi, g1 = acceleration_peak_rate(np.int64(LOG), x + ds, ynew, fnew, prm, frc)
                    peak_a = peak_in_step(peak_a, np.int64(2), np.int64(LOG), x, y, f, ds, a_lo, g0, a_hi, g1,
                                          ynew[7] - y[7], prm, frc, yb, fb, atol, rtol, work)
                    peak_x = peak_in_step(peak_x, np.int64(0), np.int64(LOG), x, y, f, ds, norm(y[0], y[1]),
                                          rate_of_peak(np.int64(0), np.int64(LOG), y, f), norm(ynew[0], ynew[1]),
                                          rate_of_peak(np.int64(0), np.int64(LOG), ynew, fnew), ynew[7] - y[7],
                                          prm, frc, yb, fb, atol, rtol, work)
                    slip += ynew[7] - y[7]
                    x += ds
                    y[:] = ynew
                    f[:] = fnew
                    tau = y[7]
                    peak_x = max(peak_x, norm(y[0], y[1]))
                    if not hit:
                        # no growth right after a rejection (Hairer & Wanner's facmax = 1)
                        ds_sugg = ds * (min(1.0, step_factor(err)) if just_rejected else step_factor(err))
                    just_rejected = False
                    if hit or x > s_stop:
                        continue
                    if s_stop > s_floor and not settled(y[7], y, f, prm, frc):
                        s_stop = s_floor  # the direction still turns: on to the old, deeper finish
                        continue
                # the stop: the last speed r_min in closed form (the speed quadratic in time)
                r = math.exp(x)
                dtt = coast_to_rest(tau, y, r, r / f[7], target, prm, frc)
                tau += dtt
                slip += dtt
                peak_x = max(peak_x, norm(y[0], y[1]))
                phase, n_ev = come_to_rest(tau, t0 + tau, y, prm, frc, f, ev_t, ev_k, n_ev)
                x = tau
                events_here += 1
                h_sugg = 0.01 * hi
            else:
                mode = START if phase == PH_START else (POLAR if phase == PH_POLAR else CARTESIAN)
                if phase == PH_POLAR:
                    r = y[7]
                    fm = force_norm(tau, y, prm, frc)
                    fscale = fm + friction_force(tau, r, prm, frc)
                    rdot = f[7]
                    h_try = h_sugg if h_sugg > 0.0 else target - tau
                    if (r <= r_floor and rdot <= 0.0) or stop_ahead(r, rdot, fscale, h_try):
                        # a stop, or the approach to one: the Cartesian branch takes over (and, until it has
                        # taken a step, does not hand back: rounding must not ping-pong)
                        polar_ok = False
                        y[2] *= r
                        y[3] *= r
                        y[7] = 0.0
                        phase = np.int64(PH_SLIDE)
                        rhs(np.int64(CARTESIAN), tau, y, prm, frc, f)
                        continue
                if phase == PH_SLIDE:
                    r = norm(y[2], y[3])
                    fm = force_norm(tau, y, prm, frc)
                    fscale = fm + friction_force(tau, r, prm, frc)
                    rdot = (y[2] * f[2] + y[3] * f[3]) / r if r > 0.0 else 0.0
                    if r <= r_floor and rdot <= 0.0:
                        if r > 0.0:
                            # the last speed in closed form, as at the end of the LOG form (a slide can get
                            # here when the approach to the stop was never predicted a step ahead)
                            y[2] /= r
                            y[3] /= r
                            dtt = coast_to_rest(tau, y, r, rdot, target, prm, frc)
                            tau += dtt
                            slip += dtt
                            peak_x = max(peak_x, norm(y[0], y[1]))
                        phase, n_ev = come_to_rest(tau, t0 + tau, y, prm, frc, f, ev_t, ev_k, n_ev)
                        x = tau
                        events_here += 1
                        h_sugg = 0.01 * hi
                        if events_here > MAX_EVENTS_PER_INTERVAL:
                            status |= STATUS_CHATTER
                            phase = np.int64(PH_STUCK)
                            break
                        continue
                    if r < 0.5 * r_switch_lo and not rdot < -ENTER_LOG * fscale:
                        # too slow for the Cartesian form (the direction is stiff): slaved-direction form
                        # (a slide that decelerates goes on to the LOG form below, which locates its stop)
                        y[2] = r
                        y[3] = 0.0
                        phase = np.int64(PH_START)
                        rhs(np.int64(START), tau, y, prm, frc, f)
                        continue
                    h_try = h_sugg if h_sugg > 0.0 else target - tau
                    if stop_ahead(r, rdot, fscale, h_try):
                        y[2] /= r
                        y[3] /= r
                        y[7] = tau
                        x = math.log(r)
                        if rhs(np.int64(LOG), x, y, prm, frc, f):
                            phase = np.int64(PH_APPROACH)
                            s_stop = s_end
                            ds_sugg = -0.5
                            continue
                        y[2] *= r
                        y[3] *= r
                        x = tau
                        rhs(np.int64(CARTESIAN), tau, y, prm, frc, f)
                    elif polar_ok:
                        enter_polar(tau, y, y[2], y[3], r, prm, frc, f)
                        phase = np.int64(PH_POLAR)
                        continue
                hmax = target - tau
                h = hmax if (h_sugg <= 0.0 or h_sugg >= hmax) else h_sugg
                if phase == PH_SLIDE:
                    # slow sliding: the direction relaxes at the rate ~ µn/|V|; DOP853 is
                    # stable for h·rate up to ≈ 6, so stay inside rather than be rejected
                    h_stable = STABLE_CARTESIAN * r / max(fscale, 1e-300)
                    if h_stable < h:
                        h = h_stable
                        n_lim += 1
                elif phase == PH_POLAR:
                    h_stable = STABLE_POLAR * y[7] / max(fm, 1e-300)
                    if h_stable < h:
                        h = h_stable
                        n_lim += 1
                atol[2] = rtol * max(peak_v, scales[SC_V_FLOOR])
                atol[7] = np.inf
                atol[3] = atol[2] if mode == CARTESIAN else np.inf
                if mode == POLAR:
                    atol[2] *= POLAR_VELOCITY_TOL
                    atol[7] = atol[2]
                    atol[2] /= y[7]
                    atol[3] = atol[2]
                if rim_on:
                    ys[:] = y
                    fs[:] = f
                    xs = tau
                    ts = tau
                    pxs = peak_x
                    pvs = peak_v
                    pas = peak_a
                    slips = slip
                    upts = upt
                ok, err = dop853_step(mode, tau, y, f, h, prm, frc, ynew, fnew, atol, rtol)
                n_steps += 1
                if mode == START:
                    n_start += 1
                if not ok or err > 1.0:
                    n_rej += 1
                    h_sugg = h * (0.25 if not ok else step_factor(err))
                    just_rejected = True
                    same_state = True
                    continue
                if mode == START and ynew[2] < 0.0 and fnew[2] < 0.0:
                    # it stops again inside the step
                    theta = land_on(np.int64(START), tau, y, f, h, np.int64(2), 0.0, ynew[2], fnew[2], prm, frc, yb, fb,
                                    atol, rtol, work)
                    if rim_on:
                        step_mode = np.int64(START)
                        step_h = theta * h
                    y[:] = yb
                    slip += theta * h
                    tau = tau + theta * h if theta < 1.0 else target
                    peak_x = max(peak_x, norm(y[0], y[1]))
                    phase, n_ev = come_to_rest(tau, t0 + tau, y, prm, frc, f, ev_t, ev_k, n_ev)
                    x = tau
                    events_here += 1
                    h_sugg = 0.01 * hi
                    if events_here > MAX_EVENTS_PER_INTERVAL:
                        status |= STATUS_CHATTER
                        phase = np.int64(PH_STUCK)
                        break
                    continue
                if mode == START and ynew[2] > 1.5 * r_switch and y[2] < r_switch:
                    # the slaved direction is accurate only up to r_switch (a step ending below 1.5 r_switch is
                    # accepted as it is): end this one inside that band, where the cubic Hermite interpolant of
                    # the speed reaches 1.2 r_switch (one sub-step), or else on r_switch itself (secant)
                    theta = hermite_crossing(y[2], h * f[2], ynew[2], h * fnew[2], 1.2 * r_switch)
                    ok, _ = dop853_step(np.int64(START), tau, y, f, theta * h, prm, frc, yb, fb, atol, rtol)
                    work[0] += 1
                    if not (ok and r_switch <= yb[2] <= 1.5 * r_switch):
                        theta = land_on(np.int64(START), tau, y, f, h, np.int64(2), r_switch, ynew[2], fnew[2], prm,
                                        frc, yb, fb, atol, rtol, work)
                    ynew[:] = yb
                    fnew[:] = fb
                    h *= theta
                if rim_on:
                    step_mode = mode
                    step_h = h
                # |X| and |V| may peak inside the step where the rates of their squares go from + to −
                # the peak brackets of :func:`peak_in_step`, written out here: in the helper's form this hot
                # path compiled 2-6 % slower (least of 61 calls, interleaved; docs/dev-notes.md)
                turns = 0  #: bit 1: |X| may peak inside the step, bit 2: |V| may
                for which in range(2):
                    g0 = rate_of_peak(which, mode, y, f)
                    g1 = rate_of_peak(which, mode, ynew, fnew)
                    if g0 > 0.0 >= g1:
                        turns |= 1 << which
                        v0 = peak_value(which, mode, y)
                        v1 = peak_value(which, mode, ynew)
                        if tangent_bound(v0, g0, v1, g1, h) > (peak_x if which == 0 else peak_v):
                            best = locate_peak(which, mode, tau, y, f, h, v0, g0, v1, g1, h, prm, frc, yb, fb, atol,
                                               rtol, work)
                            if which == 0:
                                peak_x = max(peak_x, best)
                            else:
                                peak_v = max(peak_v, best)
                if mode != START:
                    # |a| ≤ µ n + κ|X| + c|V| over the step (|X| and |V| at most their values at the ends, or the
                    # running peaks where they may peak inside): not above the peak so far, nothing to locate
                    x_top = peak_x if turns & 1 else max(norm(y[0], y[1]), norm(ynew[0], ynew[1]))
                    v_top = peak_v if turns & 2 else max(peak_value(np.int64(1), mode, y),
                                                           peak_value(np.int64(1), mode, ynew))
                    if acceleration_bound(frc[4] + frc[5] * tau, frc[4] + frc[5] * (tau + h), x_top, v_top,
                                          prm) <= peak_a:
                        acc_i = -1  # the end's value is not computed (the next step computes its start)
                    else:
                        # the transmitted acceleration between the step's ends (its rate from (y, f), no extra
                        # evaluation; the value at the start is the previous step's end when it is the same point)
                        if acc_i == i and acc_tau == tau:
                            a_lo, g0 = a_end, g_end
                        else:
                            a_lo, g0 = acceleration_peak_rate(mode, tau, y, f, prm, frc)
                        a_end, g_end = acceleration_peak_rate(mode, tau + h, ynew, fnew, prm, frc)
                        acc_i = i
                        acc_tau = target if h == hmax else tau + h
                        if g0 > 0.0 >= g_end and tangent_bound(a_lo, g0, a_end, g_end, h) > peak_a:
                            peak_a = max(peak_a, locate_peak(np.int64(2), mode, tau, y, f, h, a_lo, g0, a_end, g_end, h,
                                                             prm, frc, yb, fb, atol, rtol, work))
                tau = target if h == hmax else tau + h
                y[:] = ynew
                f[:] = fnew
                slip += h
                if phase == PH_FLIGHT:
                    upt += h
                root = eighth_root(max(err, 1e-10))
                fac = factor_of_root(root)
                if h_prev > 0.0 and h != hmax and mode == prev_mode:
                    # Gustafsson's predictive factor (as in Hairer's RADAU5: the smaller of the two)
                    fac = max(min(fac, 0.9 * (h / h_prev) * root_prev / (root * root)), 0.2)
                if just_rejected:
                    fac = min(1.0, fac)
                h_sugg = h * fac
                if h != hmax:
                    h_prev = h
                    root_prev = root
                    prev_mode = mode
                else:
                    h_prev = -1.0
                just_rejected = False
                peak_x = max(peak_x, norm(y[0], y[1]))
                peak_v = max(peak_v, peak_value(np.int64(1), mode, y))
                x = tau
                polar_ok = True
                if phase == PH_START and (y[2] >= r_switch or (
                        y[2] >= r_switch_lo and start_lag(tau, y, prm, frc) > LAG_MAX_RAD)):
                    v1, v2 = velocity(np.int64(PH_START), x, tau, y, prm, frc)
                    enter_polar(tau, y, v1, v2, y[2], prm, frc, f)
                    phase = np.int64(PH_POLAR)
        if failed_at >= 0 or at_rim:
            break
        v1, v2 = velocity(phase, x, hi, y, prm, frc)
        if phase == PH_STUCK:
            a1, a2 = ax[i + 1], ay[i + 1]
        else:
            a1, a2 = transmitted(phase, x, hi, y, prm, frc)
        store_sample(i + 1, v1, v2, a1, a2, y, out_x, out_v, out_a, out_en)
        peak_a = max(peak_a, norm(a1, a2))
    if failed_at >= 0:
        for j in range(failed_at + 1, n):
            out_x[j, 0] = np.nan
            out_x[j, 1] = np.nan
            out_v[j, 0] = np.nan
            out_v[j, 1] = np.nan
            out_a[j, 0] = np.nan
            out_a[j, 1] = np.nan
            out_en[0, j] = np.nan
            out_en[1, j] = np.nan
            out_en[2, j] = np.nan
    if n_ev > ev_t.shape[0]:
        status |= STATUS_EVENTS_TRUNCATED
    summary[S_PEAK_X] = peak_x
    summary[S_PEAK_V] = peak_v
    summary[S_PEAK_A] = peak_a
    summary[S_SLIP_TIME] = slip
    summary[S_UPLIFT_TIME] = upt
    summary[S_N_UPLIFTS] = n_up
    summary[S_E_IN] = y[4]
    summary[S_E_F] = y[5]
    summary[S_E_V] = y[6]
    summary[S_N_EVENTS] = n_ev
    summary[S_STATUS] = status
    summary[S_N_STEPS] = n_steps
    summary[S_N_REJECTED] = n_rej
    summary[S_STEPS_START] = n_start
    summary[S_STEPS_LOG] = n_log
    summary[S_STEPS_LIMITED] = n_lim
    summary[S_SUB_LAND] = work[0]
    summary[S_SUB_PEAK] = work[1]
