r"""The rim of a single friction pendulum in the plane: the 2-D engine with a rigid stop at |X| = d.

A single pendulum with a ``displacement_capacity_m`` d (on the surface; the 1-D model's
convention, :func:`isolator.solver.multisurface.rim_of_single`: the rim is at d R_eff/R in the
bearing's displacement, = d for a surface without slider height) has a rim: the slider is
constrained to |X| ≤ d, a circle in the plane (issue 23).  Per unit mass, with
F = −κ(t) X − a_g(t) the non-dissipative force and n = g + a_z:

* **off the rim** the motion is the 2-D engine's (:mod:`isolator.solver.planar_kernel`), run
  with the rim on: it stops where |X| first reaches d, located inside the step;
* **impact**: reaching the rim with an outward radial velocity v_r = V·e_r > 0, a plastic
  impact removes it (V → V − v_r e_r); impulse per unit mass v_r, kinetic energy ½ v_r² lost
  (``impact_impulse_m_s`` sums them, as the 1-D model does);
* **on the rim, sliding** (tangential speed w ≠ 0, X = d e_r): the slider moves on the circle,
  w' = F·e_t − µ(|w|) n sgn w − c w, θ' = w/d, with the surface's friction µN, N = n per unit
  mass — the model of the 1-D rim: the rim's reaction λ e_r (inward) is frictionless, it does
  not add to the normal force of the friction.  λ = F·e_r + w²/d ≥ 0 holds it on the rim;
* **leaving the rim**: when λ falls to 0 the slider leaves along the tangent, sliding (the 2-D
  engine again);
* **at rest on the rim** (w = 0): held while F·e_r ≥ 0 and |F·e_t| ≤ µs n (the rim takes the
  radial part), or, F pointing inward, while |F| ≤ µs n (the ordinary stick); otherwise it slides
  along the rim (F·e_r ≥ 0, |F·e_t| > µs n, in the direction of F·e_t) or breaks away inward
  along F (the 2-D engine's START form).  With a piecewise-linear record F·e_r, F·e_t and µs n
  are linear in time and |F|² − (µs n)² quadratic: the instant the hold ends is a root, exact.

The slide on the rim is one degree of freedom, integrated sample interval by sample interval by a
compiled DOP853 (:mod:`isolator.solver.planar_rim_kernel`; rtol 1e-12, atol 1e-15 m, 1e-15 m/s), with
the stop (w = 0) and the lift-off (λ = 0) as terminal events located to the last bits of the time on
the integrator's own step; its |V| peaks are events too (w' = 0).  The
error of that integration is measured against an independent reference in
``tests/solver/test_planar_rim.py`` (docs/planar.md, "The rim").  The bearing transmits
M (V' + a_g): its ``peak_transmitted_acceleration_m_s2`` includes the rim's reaction (while held
on the rim it is |a_g|); inside a slide on the rim its peaks are events (A·A' = 0).

Not modelled (refused by a :class:`~isolator.errors.SolverError` naming the instant): the rim
while the bearing carries no load (n ≤ 0 on the rim: uplift).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from isolator.errors import InvalidSystemError, SolverError
from isolator.solver import planar as _planar
from isolator.solver import planar_kernel as _pk
from isolator.solver import planar_layout as _pl
from isolator.solver import planar_rim_kernel as _rk_rim
from isolator.solver import planar_rk as _rk

#: Event words of the 2-D engine with a rim.
RIM_EVENT_NAMES = _planar.PLANAR_EVENT_NAMES + ("rim impact", "rim leave")
assert RIM_EVENT_NAMES.index("rim impact") == _pl.EV_RIM_IMPACT
assert RIM_EVENT_NAMES.index("rim leave") == _pl.EV_RIM_LEAVE

#: Tolerances of the slide on the rim (DOP853): relative, and absolute on θ [rad], w [m/s], energies [J/kg]
RIM_RTOL = _rk_rim.RTOL
RIM_ATOL = _rk_rim.ATOL
#: Bound on the phases of one run (free → rim → free …): every rim contact is at least one event
MAX_RIM_CONTACTS_PER_SAMPLE = 50


@dataclass(kw_only=True)
class RimPairResponse(_planar.PairResponse):
    """Response of the 2-D engine with the rim of a single pendulum (model ``2d+rim``).

    The fields of :class:`~isolator.solver.planar.PairResponse`, and the rim's, under the names
    of the 1-D rim model (:class:`~isolator.solver.multisurface.MultisurfaceResponse`).  The
    balance ``input = kinetic + potential + friction + viscous + impact`` holds to
    ``energy_balance_error_J_per_kg``.
    """

    EXTRA_SUMMARY_KEYS = ("n_rim_contacts", "ultimate_displacement_reached", "ultimate_displacement_m",
                          "energy_impact_J_per_kg", "impact_impulse_m_s", "max_impact_velocity_m_s",
                          "rim_time_s")
    EVENT_NAMES = RIM_EVENT_NAMES

    energy_impact_J_per_kg: float  #: kinetic energy lost in the plastic impacts, Σ ½ v_r² [J/kg]
    n_rim_contacts: int  #: impacts on the rim (arrivals at |X| = d)
    ultimate_displacement_reached: bool  #: the rim was reached
    ultimate_displacement_m: float  #: the rim's radius in the bearing's displacement [m]
    ultimate_first_time_s: float | None  #: first arrival on the rim [s]
    impact_impulse_m_s: float  #: Σ v_r: impulse per unit mass [m/s] (M × it [N·s])
    max_impact_velocity_m_s: float  #: largest v_r [m/s]
    rim_time_s: float  #: time spent on the rim (held or sliding along it) [s]
    #: True when the registry's first run (``2d``, an unbounded plate) reached the capacity and the scene
    #: was run again here; :func:`isolator.solver.models.simulate` keeps this result's model and reason
    rerun: bool = False


def model_label(*, has_y: bool, has_z: bool, velocity_dependent: bool) -> str:
    """The model's name: the 2-D engine's (:func:`isolator.solver.planar.model_label`) + ``+rim``."""
    return _planar.model_label(has_y=has_y, has_z=has_z, velocity_dependent=velocity_dependent)[0] + "+rim"


class _Rim:
    """The rim's phases of one run (the kernel's arrays shared, written in place)."""

    def __init__(self, run, d, out_x, out_v, out_a, out_en, ev_t, ev_k, summary):
        self.run, self.d = run, d
        self.out_x, self.out_v, self.out_a, self.out_en = out_x, out_v, out_a, out_en
        self.ev_t, self.ev_k, self.summary = ev_t, ev_k, summary
        prm = run.prm
        self.pendulum = prm[_rk.P_PENDULUM] > 0.0
        self.inv_r, self.kappa, self.c = prm[_rk.P_INV_R], prm[_rk.P_KAPPA], prm[_rk.P_C]
        self.mu_s = prm[_rk.P_MU_S]
        self.rim_time = 0.0  #: on the rim, held or sliding [s]
        self.impulse = 0.0  #: Σ v_r [m/s]
        self.max_v = 0.0
        self.e_impact = 0.0  #: Σ ½ v_r² [J/kg]
        self.n_contacts = 0
        self.first_time = None
        self.params = np.zeros(_rk_rim.P_SIZE)  #: the compiled slide's parameters, one interval's forcing

    # -- the record inside interval i: a_g, n linear in local time ----------------------------------------------
    def forcing(self, i):
        t, ax, ay, nz = self.run.local_times, self.run.ax, self.run.ay, self.run.nz
        h = t[i + 1] - t[i]
        return (h, ax[i], (ax[i + 1] - ax[i]) / h, ay[i], (ay[i + 1] - ay[i]) / h, nz[i], (nz[i + 1] - nz[i]) / h)

    def mu(self, r):
        prm = self.run.prm
        if prm[_rk.P_VELDEP] > 0.0:
            return prm[_rk.P_MU_FAST] - (prm[_rk.P_MU_FAST] - prm[_rk.P_MU_SLOW]) * math.exp(-prm[_rk.P_RATE] * r)
        return prm[_rk.P_MU_K]

    def kappa_of(self, nn):
        return nn * self.inv_r if self.pendulum else self.kappa

    def event(self, i, tau, kind):
        n_ev = int(self.summary[_pl.S_N_EVENTS])
        if n_ev < self.ev_t.size:
            self.ev_t[n_ev] = self.run.local_times[i] + tau
            self.ev_k[n_ev] = kind
        self.summary[_pl.S_N_EVENTS] = n_ev + 1

    def peak_a(self, value):
        self.summary[_pl.S_PEAK_A] = max(self.summary[_pl.S_PEAK_A], value)

    def store(self, j, e, w, acc):
        d = self.d
        c, s = e
        self.out_x[j] = (d * c, d * s)
        self.out_v[j] = (-w * s, w * c)
        self.out_a[j] = acc
        self.out_en[:, j] = self.summary[[_pl.S_E_IN, _pl.S_E_F, _pl.S_E_V]]
        self.peak_a(math.hypot(acc[0], acc[1]))

    def check_contact(self, i, nn_lo, nn_hi):
        if not (nn_lo > 0.0 and nn_hi > 0.0):
            t = self.run.times[i]
            raise SolverError(f"the bearing carries no load (n = g + a_z ≤ 0) while on its rim near t = {t:.6g} s: "
                              "uplift on the rim is not modelled (the 2-D rim model needs n > 0 there)")

    # -- held at rest on the rim ----------------------------------------------------------------------------------
    def hold_ends(self, e, tau, frc):
        """First instant in [tau, h] at which rest on the rim at direction e ends, and how: (time, kind) with
        kind 'slide+' / 'slide-' (along the rim, sign of F·e_t) or 'inward'; (h, None) if it holds."""
        h, ax0, ax1, ay0, ay1, n0, n1 = frc
        d, mu_s = self.d, self.mu_s
        er = e
        et = (-e[1], e[0])

        def parts(s):
            nn = n0 + n1 * s
            a = (ax0 + ax1 * s, ay0 + ay1 * s)
            fr = -self.kappa_of(nn) * d - (a[0] * er[0] + a[1] * er[1])
            ft = -(a[0] * et[0] + a[1] * et[1])
            return fr, ft, mu_s * nn

        def held(s):
            fr, ft, cap = parts(s)
            return abs(ft) <= cap and (fr >= 0.0 or fr * fr + ft * ft <= cap * cap)

        # F·e_r, F·e_t, µs n are linear in s: their roots, and those of |F|² − (µs n)² (quadratic)
        fr0, ft0, cap0 = parts(0.0)
        fr1, ft1, cap1 = parts(1.0)
        dfr, dft, dcap = fr1 - fr0, ft1 - ft0, cap1 - cap0
        roots = []
        for p0, p1 in ((fr0, dfr), (ft0 - cap0, dft - dcap), (ft0 + cap0, dft + dcap)):
            if p1 != 0.0:
                roots.append(-p0 / p1)
        qa = dfr * dfr + dft * dft - dcap * dcap
        qb = 2.0 * (fr0 * dfr + ft0 * dft - cap0 * dcap)
        qc = fr0 * fr0 + ft0 * ft0 - cap0 * cap0
        if qa != 0.0:
            disc = qb * qb - 4.0 * qa * qc
            if disc >= 0.0:
                sq = math.sqrt(disc)
                q = -0.5 * (qb + math.copysign(sq, qb))
                if q != 0.0:
                    roots += [q / qa, qc / q]
        elif qb != 0.0:
            roots.append(-qc / qb)
        cuts = sorted({tau, h, *(r for r in roots if tau < r < h)})
        for lo, hi in zip(cuts[:-1], cuts[1:], strict=True):
            mid = 0.5 * (lo + hi)
            if not held(mid):
                fr, ft, _ = parts(mid)
                if fr >= 0.0:
                    return lo, ("slide+" if ft > 0.0 else "slide-")
                return lo, "inward"
        return h, None

    # -- one stay on the rim, from an arrival ----------------------------------------------------------------------
    def stay(self, i, tau, x1, x2, v1, v2):
        """From an arrival at (x1, x2) on the rim with velocity (v1, v2) in interval i at local time tau: the
        impact, then the rim's phases until the slider leaves it or the record ends.

        Returns
        -------
        tuple or None
            ``(i, tau, x1, x2, v1, v2, restart)`` to hand back to the 2-D engine, or None at the record's end.
        """
        d = self.d
        # the direction on the rim as a unit vector (an angle only while sliding along the rim): a collinear
        # record keeps e = (±1, 0) exactly, hence w = 0 and the 1-D answer
        e = (x1 / d, x2 / d)
        vr = v1 * e[0] + v2 * e[1]
        w = -v1 * e[1] + v2 * e[0]
        if vr > 0.0:
            self.impulse += vr
            self.max_v = max(self.max_v, vr)
            self.e_impact += 0.5 * vr * vr
        self.n_contacts += 1
        if self.first_time is None:
            self.first_time = float(self.run.times[i] + tau)
        self.event(i, tau, _pl.EV_RIM_IMPACT)
        n = self.run.ax.size
        guard = 0
        restart_kind = _pl.EV_BREAKAWAY  #: the event of the next start from rest on the rim
        while i < n - 1:
            frc = self.forcing(i)
            h = frc[0]
            self.check_contact(i, frc[5] + frc[6] * tau, frc[5] + frc[6] * h)
            while tau < h:
                guard += 1
                if guard > MAX_RIM_CONTACTS_PER_SAMPLE * n:
                    raise SolverError(f"rim guard: more than {MAX_RIM_CONTACTS_PER_SAMPLE} rim phases per sample "
                                      f"(near t = {self.run.times[i] + tau:.6g} s)")
                if w == 0.0:
                    t_end, how = self.hold_ends(e, tau, frc)
                    self.held(frc, tau, t_end)
                    self.rim_time += t_end - tau
                    tau = t_end
                    if how is None:
                        continue
                    self.event(i, tau, restart_kind)
                    restart_kind = _pl.EV_BREAKAWAY
                    if how == "inward":
                        return i, tau, d * e[0], d * e[1], 0.0, 0.0, _pl.RS_START
                    sign = 1.0 if how == "slide+" else -1.0
                else:
                    sign = 1.0 if w > 0.0 else -1.0
                    if self.reaction(frc, tau, e, w) < 0.0:  # it does not stay: leaves along the tangent
                        self.event(i, tau, _pl.EV_RIM_LEAVE)
                        return i, tau, d * e[0], d * e[1], -w * e[1], w * e[0], _pl.RS_SLIDE
                tau, theta, w, how = self.slide(i, frc, tau, math.atan2(e[1], e[0]), w, sign)
                e = (math.cos(theta), math.sin(theta))
                if how == "leave":
                    self.event(i, tau, _pl.EV_RIM_LEAVE)
                    return i, tau, d * e[0], d * e[1], -w * e[1], w * e[0], _pl.RS_SLIDE
                if how == "stop":  # a stick, or (the hold ends at once) a reversal, logged at its start
                    w = 0.0
                    t_hold, again = self.hold_ends(e, tau, frc)
                    if again is None or t_hold > tau:
                        self.event(i, tau, _pl.EV_STICK)
                    else:
                        restart_kind = _pl.EV_REVERSAL
            acc = self.acceleration(frc, h, e, w)
            self.store(i + 1, e, w, acc)
            i += 1
            tau = 0.0
        return None

    def held(self, frc, t0, t1):
        """At rest on the rim over [t0, t1]: the mass moves with the ground (|a| = |a_g|, linear: peaks at the
        ends) and the vertical motion works on the pendulum, ½ κ' d²."""
        h, ax0, ax1, ay0, ay1, n0, n1 = frc
        for s in (t0, t1):
            self.peak_a(math.hypot(ax0 + ax1 * s, ay0 + ay1 * s))
        if n1 != 0.0 and self.pendulum:
            self.summary[_pl.S_E_IN] += 0.5 * self.d * self.d * self.inv_r * n1 * (t1 - t0)

    def reaction(self, frc, s, e, w):
        """λ = F·e_r + w²/d [m/s²]: the rim's inward reaction needed to keep the slider on it (e = e_r)."""
        h, ax0, ax1, ay0, ay1, n0, n1 = frc
        nn = n0 + n1 * s
        fr = -self.kappa_of(nn) * self.d - ((ax0 + ax1 * s) * e[0] + (ay0 + ay1 * s) * e[1])
        return fr + w * w / self.d

    def acceleration(self, frc, s, e, w):
        """Absolute acceleration of the mass V' + a_g [m/s²] on the rim at e = e_r (w = 0: a_g)."""
        h, ax0, ax1, ay0, ay1, n0, n1 = frc
        a = np.array([ax0 + ax1 * s, ay0 + ay1 * s])
        if w == 0.0:
            return a
        c, sn = e
        nn = n0 + n1 * s
        ft = -(a[0] * -sn + a[1] * c)
        wdot = ft - self.mu(abs(w)) * nn * math.copysign(1.0, w) - self.c * w
        return a + wdot * np.array([-sn, c]) - (w * w / self.d) * np.array([c, sn])

    def slide(self, i, frc, tau, theta, w, sign):
        """Slide along the rim in the direction ``sign`` from (θ, w) at local time tau to the interval's end, a
        stop (w = 0) or the lift-off (λ = 0), compiled (:func:`isolator.solver.planar_rim_kernel.rim_slide`).
        Returns (tau, θ, w, 'end' | 'stop' | 'leave')."""
        h, ax0, ax1, ay0, ay1, n0, n1 = frc
        prm = self.run.prm
        p = self.params
        p[_rk_rim.P_AX0], p[_rk_rim.P_AX1], p[_rk_rim.P_AY0], p[_rk_rim.P_AY1] = ax0, ax1, ay0, ay1
        p[_rk_rim.P_N0], p[_rk_rim.P_N1], p[_rk_rim.P_SIGN] = n0, n1, sign
        p[_rk_rim.P_D], p[_rk_rim.P_C], p[_rk_rim.P_INV_R], p[_rk_rim.P_KAPPA] = self.d, self.c, self.inv_r, self.kappa
        p[_rk_rim.P_PENDULUM] = 1.0 if self.pendulum else 0.0
        p[_rk_rim.P_VELDEP], p[_rk_rim.P_MU_K] = prm[_rk.P_VELDEP], prm[_rk.P_MU_K]
        p[_rk_rim.P_MU_FAST], p[_rk_rim.P_MU_SLOW], p[_rk_rim.P_RATE] = (prm[_rk.P_MU_FAST], prm[_rk.P_MU_SLOW],
                                                                          prm[_rk.P_RATE])
        y = np.array([theta, w, *self.summary[[_pl.S_E_IN, _pl.S_E_F, _pl.S_E_V]]])
        peaks = self.summary[[_pl.S_PEAK_V, _pl.S_PEAK_A]]
        t_end, code = _rk_rim.rim_slide(p, float(tau), float(h), y, peaks)
        if code == _rk_rim.HOW_GUARD:
            raise SolverError(f"rim guard: more than {_rk_rim.MAX_STEPS} steps of the slide along the rim in one "
                              f"sample interval (near t = {self.run.times[i] + tau:.6g} s)")
        how = {_rk_rim.HOW_END: "end", _rk_rim.HOW_STOP: "stop", _rk_rim.HOW_LEAVE: "leave"}[code]
        self.summary[_pl.S_PEAK_V], self.summary[_pl.S_PEAK_A] = peaks
        self.summary[_pl.S_E_IN], self.summary[_pl.S_E_F], self.summary[_pl.S_E_V] = y[2], y[3], y[4]
        self.summary[_pl.S_SLIP_TIME] += t_end - tau
        self.rim_time += t_end - tau
        return t_end, float(y[0]), (0.0 if how == "stop" else float(y[1])), how


def simulate_pair_rim(ax_m_s2, ay_m_s2, dt_s=None, *, displacement_capacity_m, time_s=None, az_m_s2=None,
                      **isolator) -> RimPairResponse:
    """Response of a single friction pendulum with a rim at |X| = d to two horizontal components (and a vertical).

    Parameters
    ----------
    ax_m_s2, ay_m_s2, dt_s, time_s, az_m_s2, **isolator
        As :func:`isolator.solver.planar.simulate_pair` (a restoring stiffness is needed: a radius or a spring).
    displacement_capacity_m : float
        The rim's radius d in the bearing's displacement [m] (the 1-D rim's d* = d R_eff/R).

    Returns
    -------
    RimPairResponse

    Raises
    ------
    InvalidSystemError
        A bad parameter, or no restoring stiffness (a flat slider has no pendulum, hence no rim here).
    SolverError
        Uplift on the rim (n ≤ 0 there), or a guard.
    """
    d = float(displacement_capacity_m)
    if not (math.isfinite(d) and d > 0.0):
        raise InvalidSystemError(f"displacement_capacity_m must be a finite number > 0, got "
                                         f"{displacement_capacity_m!r}")
    run = _planar.prepare_pair(ax_m_s2, ay_m_s2, dt_s, time_s=time_s, az_m_s2=az_m_s2, **isolator)
    if not (run.prm[_rk.P_PENDULUM] > 0.0 or run.prm[_rk.P_KAPPA] > 0.0):
        raise InvalidSystemError("the rim is modelled for a pendulum (radius_m or stiffness_per_mass > 0)")
    n = run.ax.size
    capacity = 64 + n // 4
    for _ in range(4):  # the event arrays: rerun once with room for every event
        out_x, out_v, out_a = np.empty((n, 2)), np.empty((n, 2)), np.empty((n, 2))
        out_en = np.empty((3, n))
        summary = np.zeros(_pl.S_SIZE)
        ev_t = np.empty(capacity)
        ev_k = np.empty(capacity, dtype=np.int8)
        rim = _Rim(run, d, out_x, out_v, out_a, out_en, ev_t, ev_k, summary)
        state = np.zeros(_pl.RM_SIZE)
        state[_pl.RM_RADIUS] = d
        state[_pl.RM_START] = _pl.RS_FRESH
        start = time.perf_counter()
        for _phase in range(MAX_RIM_CONTACTS_PER_SAMPLE * n + 2):
            _pk.planar_kernel(run.local_times, run.ax, run.ay, run.nz, run.prm, run.scales, run.rtol, run.refresh,
                              out_x, out_v, out_a, out_en, ev_t, ev_k, summary, state)
            if int(summary[_pl.S_STATUS]) & _pl.STATUS_STEP_LIMIT or state[_pl.RM_HIT] == 0.0:
                break
            back = rim.stay(int(state[_pl.RM_I]), float(state[_pl.RM_TAU]), *state[_pl.RM_X1:_pl.RM_V2 + 1])
            if back is None:
                break
            (i, tau, x1, x2, v1, v2, how) = back
            state[_pl.RM_I], state[_pl.RM_TAU], state[_pl.RM_START] = i, tau, how
            state[_pl.RM_X1], state[_pl.RM_X2], state[_pl.RM_V1], state[_pl.RM_V2] = x1, x2, v1, v2
        else:  # pragma: no cover - bounded by the rim guard inside
            raise SolverError("rim guard: too many rim contacts")
        elapsed = time.perf_counter() - start
        if int(summary[_pl.S_N_EVENTS]) <= capacity:
            break
        capacity = int(summary[_pl.S_N_EVENTS]) + 16
    result = _planar.pair_response(
        run, out_x, out_v, out_a, out_en, ev_t, ev_k, summary, elapsed, response_class=RimPairResponse,
        energy_impact_J_per_kg=rim.e_impact, n_rim_contacts=rim.n_contacts,
        ultimate_displacement_reached=rim.n_contacts > 0, ultimate_displacement_m=d,
        ultimate_first_time_s=rim.first_time, impact_impulse_m_s=rim.impulse, max_impact_velocity_m_s=rim.max_v,
        rim_time_s=rim.rim_time)
    result.energy_balance_error_J_per_kg -= rim.e_impact
    result.model = model_label(has_y=run.has_y, has_z=run.az is not None, velocity_dependent=run.velocity_dependent)
    result.model_reason = (f"a single pendulum with a displacement capacity of {d:.4g} m in the plane: the 2-D engine "
                           "with the rim (plastic impact at |X| = d, sliding along the rim)")
    return result


# ---------------------------------------------------------------------------------------
# the registry's entry points (isolator.solver.models)
# ---------------------------------------------------------------------------------------
MODEL_NAME = "2d+rim"


def rim_radius(scene) -> float | None:
    """The rim's radius [m] of a scene the 2-D engine takes with a single pendulum that has a capacity, or None.

    A design with a ``displacement_capacity_m``, one surface (no ``[bearing]``, or ``type = "single"``
    with a capacity: the rim at d* = d R_eff/R, as the 1-D rim model), a restoring stiffness > 0 (a
    radius or a spring) and no superstructure.
    """
    design = scene.design
    capacity = getattr(design, "displacement_capacity_m", None)
    if capacity is None or getattr(design, "superstructure", None) is not None:
        return None
    bearing = getattr(design, "bearing", None)
    if bearing is not None:
        return float(bearing.ultimate_displacement_m) if bearing.is_simple and bearing.has_rims else None
    iso = scene.isolator
    if iso.get("radius_m") is None and not (iso.get("stiffness_per_mass") or 0.0) > 0.0:
        return None  # a flat slider without restoring force: no pendulum, no rim modelled
    return float(capacity)


def scene_needs(scene) -> tuple[str, str] | None:
    """``(model, reason)`` for a single pendulum with a capacity that needs the 2-D engine; else None.

    It runs on ``2d`` first (an unbounded plate), **and the choice depends on its result**: when its
    peak reaches the capacity, the scene is run again with the rim (:func:`simulate_scene`), and that
    result says so (``model`` ``2d+rim``, ``rerun`` true), as the 1-D rim does.  The registry asks this
    after the models of one component, so a scene here needs the 2-D engine (a pair, a vertical or µ(v)).
    """
    d = rim_radius(scene)
    if d is None:
        return None
    name, reason = _planar.scene_needs(scene)
    return name, (f"{reason}; a displacement capacity of {d:.4g} m: if the peak reaches it, the run is redone "
                  f"with the rim ({MODEL_NAME}), a choice made on the result")


def simulate_scene(scene) -> _planar.PairResponse:
    """The 2-D engine's response (:func:`isolator.solver.planar.simulate_scene`); rerun with the rim when its
    peak reaches the capacity (:func:`simulate_pair_rim`, ``rerun`` true, its own ``model``/``model_reason``)."""
    d = rim_radius(scene)
    free = _planar.simulate_scene(scene)
    if d is None or free.peak_displacement_m < d:
        return free
    ax = np.asarray(scene.ax_m_s2, dtype=np.float64)
    ay = np.zeros_like(ax) if scene.ay_m_s2 is None else scene.ay_m_s2
    rimmed = simulate_pair_rim(ax, ay, scene.dt_s, time_s=scene.time_s, az_m_s2=scene.az_m_s2,
                               displacement_capacity_m=d, **scene.isolator)
    rimmed.rerun = True
    rimmed.model_reason = (f"a single pendulum that reached its displacement capacity {d:.4g} m: on {free.model} "
                           f"(an unbounded plate) its peak was {free.peak_displacement_m:.4g} m, so the run was redone "
                           "with the rim (plastic impact at |X| = d, sliding along the rim); chosen on that result")
    return rimmed
