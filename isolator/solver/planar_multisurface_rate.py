"""Driver of the 2-D multi-surface model with velocity-dependent friction: model ``2d-multisurface+mu(v)``.

A double or triple friction pendulum whose surfaces follow µ_i(v) = µ_fast,i − (µ_fast,i − µ_slow,i)
exp(−a_i |v_i|) (``mu_slow``/``mu_fast``/``rate_s_per_m`` in ``[[bearing.surface]]``) under two horizontal
components: the series model of Fenz & Constantinou in the plane with coupled friction on every surface.
The equations, the method (Radau IIA collocation with events, the pieces of the 1-D model
:mod:`isolator.solver.multisurface_rate_kernel`) and its error are in
:mod:`isolator.solver.planar_multisurface_rate_kernel` and docs/multisurface.md.  The result is a
:class:`~isolator.solver.planar_multisurface.PlanarMultisurfaceResponse` (the keys of ``2d-multisurface``).

The rims: a surface reaching its rim is held there or slides along it (the rim's frictionless reaction normal to
it) and leaves it inward; every surface on its rim is the ultimate displacement, a plastic impact (the velocity
removed, its impulse and energy reported) as in 1-D (docs/multisurface.md, h131).  Every surface on its rim with the
rims apart is not the ultimate (h181): the kernel stops there and :func:`hand_over` integrates the slide along the
rims (:func:`isolator.solver.planar_rim_slide.close_along_rims`, Radau, the compiled force) to the rims' alignment,
where the ultimate's plastic impact takes the normal velocity e·Ẋ alone (h226).  Not modelled, each refused in one
line: what follows that slide (the slide on the rims' common circle after the impact, or the kernel restarted where
a rim's reaction turns inward or the mass rests; the line names the impact's impulse and energy), an impact at the
ultimate with a velocity along the rims, a slide along the rims from rest with no surface free inside its rim, a
vertical component, a superstructure.
"""

from __future__ import annotations

import math
import time

import numpy as np

from isolator.errors import DesignError, RecordInputError, SolverError
from isolator.solver import planar_multisurface_rate_kernel as _pr
from isolator.solver import planar_rim_slide
from isolator.solver.multisurface_rate import is_rate_dependent, rate_laws
from isolator.solver.multisurface_rate_kernel import LOCK_LEVELS
from isolator.solver.notice import note_if_slow
from isolator.solver.planar_multisurface import PlanarMultisurfaceResponse
from isolator.solver.record import record_timing
from isolator.units import STANDARD_GRAVITY

MODEL_NAME = "2d-multisurface+mu(v)"

#: Default step tolerance (as in 1-D): the largest difference of a step of h from two of h/2, as a fraction of
#: the running peak displacement and velocity (measured against the tests' reference: docs/multisurface.md).
DEFAULT_TOLERANCE = 1e-11

#: The largest part of the velocity along the rims (|Ẋ × ē|/|Ẋ|) that an impact at the ultimate may take away.
#: The kernel's plastic impact removes the whole velocity: exact for an arrival along the rims' common direction
#: (every 1-D motion, measured to rounding against ``1d-multisurface+mu(v)``), but a slide along the rims at the
#: ultimate is not modelled in the plane, so an arrival with more than this tangential part is refused rather than
#: answered with an unmodelled loss (the issue's 1e-9 of the peak).
IMPACT_TANGENTIAL_LIMIT = 1e-9

#: The largest sine of the angle between a surface's rim normal and the mass's direction X/|X| at an impact (the
#: kernel's ``S_IMPACT_SPREAD``).  The kernel takes the impact when every surface is on its rim; where the rims are
#: apart the mass is still inside its ultimate circle and would slide on along the rims, closing them into alignment
#: (the constant-µ model integrates that), so such an impact is refused too (h181: the off-axis probes and PTS's lower
#: bound reach it 2.2e-3 … 0.144 apart; a 1-D motion 1.9e-15).
IMPACT_SPREAD_LIMIT = _pr.ALIGNED_SPREAD

#: The slide along the rims handed over from the kernel (h226): Radau with the slide's Jacobian at this tolerance
#: (h221: on PTS its course converges at ≤ 1e-8 — the alignment within 5e-13 s and the friction within 1.9e-8 of
#: rtol 1e-10 — and not at 1e-6)
HAND_OVER_RTOL = 1e-8
#: ... and the saturated mode's gap (h221's default 1e-12 is ~3× above PTS's onset of the roots' swapping and below
#: the probe's, ~2e-11, where Radau's step then collapsed at the start, h226; 1e-10 gave PTS the same seven segments,
#: the alignment within 1e-12 s and the friction within 3e-8, h221)
HAND_OVER_GAP = 1e-10
#: ... and the bound on its force evaluations (PTS's slide to the alignment takes 3223, the probe's 1393; a slide in
#: the example review at 24.47 s had taken 77 000 in 30 s CPU, 12 ms of slide, with no event: refused by name, h226)
HAND_OVER_MAX_FORCES = 20_000


def hand_over(t_local, xdot, u, cap, bmat, smat, rbar, mu_s, mu_f, rate, g, c, times, ax, ay, energies,
              rtol=HAND_OVER_RTOL, saturated_gap=HAND_OVER_GAP) -> dict:
    """The kernel's state with every surface on its rim and the rims apart (``STATUS_ALL_RIMS``) carried on: the slide
    along the rims integrated (:func:`isolator.solver.planar_rim_slide.close_along_rims`, Radau with the compiled
    force, ``rtol``) to its first event, and at the rims' alignment the ultimate's plastic impact of the normal
    velocity e·Ẋ alone (issue 23: a rigid stop, its impulse reported; the velocity along the common circle kept).

    ``energies`` (input, friction, viscous, impact) of the kernel to ``t_local``.  Returns the closing's dict
    (:func:`~isolator.solver.planar_rim_slide.close_along_rims`) with ``impulse`` (e·Ẋ at the alignment, m/s per unit
    mass; 0 elsewhere), ``impact_energy`` (½(e·Ẋ)²), ``along`` (t·Ẋ after it), ``normal`` (e), ``start_t`` and
    ``total_balance``: input − (kinetic + potential + friction + viscous + impact) over the kernel's run and the
    hand-over together [J/kg], the kinetic energy after the impact.
    """
    u = np.asarray(u, dtype=float)
    rho = np.hypot(u[:, 0], u[:, 1])
    u = u * (cap / np.where(rho > 0.0, rho, 1.0))[:, None]  # on the circles (the kernel's to_rims, to rounding)
    root, counts = planar_rim_slide.compiled_root()
    out = planar_rim_slide.close_along_rims(t_local, np.asarray(xdot, dtype=float), u, bmat, smat, rbar, mu_s, mu_f,
                                            rate, g, c, times, ax, ay, float(times[-1]), rtol=rtol, method="Radau",
                                            root=root, saturated_gap=saturated_gap, max_forces=HAND_OVER_MAX_FORCES)
    xv = np.asarray(out["xdot"], dtype=float)
    x = np.sum(out["u"], axis=0)
    xn = math.hypot(x[0], x[1])
    normal = x / xn if xn > 0.0 else np.zeros(2)
    impulse = max(float(normal @ xv), 0.0) if out["reason"] == "aligned" else 0.0
    after = xv - impulse * normal
    e_in, e_f, e_v, e_imp = energies
    impact = 0.5 * impulse * impulse
    total_in = e_in + out["input"]
    total_balance = total_in - (0.5 * float(after @ after) + out["potential"][1] + e_f + out["friction"]
                                + e_v + out["viscous"] + e_imp + impact)
    out.update(impulse=impulse, impact_energy=impact, along=float(normal[0] * after[1] - normal[1] * after[0]),
               normal=normal, start_t=float(t_local), spread=planar_rim_slide.rim_spread(out["u"]), total_balance=total_balance, total_input=total_in,
               compiled_forces=counts["compiled"], numpy_forces=counts["numpy"])
    return out


def scene_needs(scene) -> tuple[str, str] | None:
    """``(model, reason)`` for a double or triple bearing with µ(v) surfaces under two components; else None.

    It answers with a vertical or a superstructure too, so that such a scene is refused in one line
    (:func:`simulate_scene`) rather than run with constant friction by another model.
    """
    bearing = getattr(scene.design, "bearing", None)
    if bearing is None or bearing.is_simple or not scene.has_y or not is_rate_dependent(bearing):
        return None
    return MODEL_NAME, (f"a {bearing.kind} friction pendulum with velocity-dependent friction µ_i(v_i) on its "
                        "surfaces under two horizontal components: the series model of Fenz & Constantinou in the "
                        "plane (coupled friction) as an index-1 DAE, Radau IIA collocation with events (error "
                        "controlled, not closed form; the rims held, slid along and left, the ultimate a plastic impact)")


def simulate_scene(scene) -> PlanarMultisurfaceResponse:
    """The 2-D response of the scene's µ(v) double or triple bearing (:func:`simulate_bearing_pair_rate`).

    Raises
    ------
    RecordInputError
        A vertical component.
    DesignError
        A superstructure.
    """
    kind = scene.design.bearing.kind
    if getattr(scene.design, "superstructure", None) is not None:
        raise DesignError(f"{scene.design.source}: a {kind} bearing with µ(v) under a [superstructure] is not "
                          f"modelled ({MODEL_NAME} carries a rigid mass)")
    if scene.has_z:
        raise RecordInputError(f"a {kind} bearing with velocity-dependent friction under a vertical component is not "
                               f"modelled ({MODEL_NAME} takes the two horizontal components); give each surface a "
                               "constant 'mu' or leave the vertical out")
    return simulate_bearing_pair_rate(scene.ax_m_s2, scene.ay_m_s2, scene.dt_s, time_s=scene.time_s,
                                      bearing=scene.design.bearing,
                                      damping_per_mass=float(scene.isolator.get("damping_per_mass") or 0.0),
                                      gravity_m_s2=float(scene.isolator.get("gravity_m_s2") or STANDARD_GRAVITY))


class RatePlanarMultisurfaceResponse(PlanarMultisurfaceResponse):
    """:class:`~isolator.solver.planar_multisurface.PlanarMultisurfaceResponse` of ``2d-multisurface+mu(v)``
    (its event kinds: :data:`isolator.solver.planar_multisurface_rate_kernel.EVENT_NAMES`)."""

    EVENT_NAMES = _pr.EVENT_NAMES


_READY = False


def _warm_up() -> None:
    global _READY
    if _READY:
        return
    with note_if_slow("compiling the 2-D µ(v) multi-surface solver (its first use after installation takes a "
                      "minute or two; the machine code is cached for later runs)"):
        eye = np.eye(2)
        _run(np.array([0.0, 1.0, -1.0]), np.array([0.0, 0.5, 0.0]), np.array([0.0, 0.01, 0.02]),
             STANDARD_GRAVITY, 0.0, eye, eye, np.array([0.03, 0.03]), np.array([0.06, 0.06]), np.array([20.0, 20.0]),
             np.array([0.1, 0.1]), 1e-10, 8)
    _READY = True


def _run(ax, ay, times, g, c, bmat, smat, mu_s, mu_f, rate, cap, tol, capacity, levels=LOCK_LEVELS):
    n = ax.size
    ns = bmat.shape[0]
    out_x = np.empty((n, 2))
    out_v = np.empty((n, 2))
    out_a = np.empty((n, 2))
    out_en = np.empty((3, n))
    summary = np.zeros(_pr.SUMMARY_SIZE)
    surf_peak = np.zeros(ns)
    first = np.empty(1 << (2 * ns))  # index: sliding bits + 2^ns × rim bits
    h_first = float(np.min(np.diff(times))) if n > 1 else 1.0
    while True:  # once more with room for every event when the first run overflowed its list
        ev_t = np.empty(capacity)
        ev_k = np.empty(capacity, dtype=np.int8)
        u = np.zeros((ns, 2))
        surf_peak[:] = 0.0
        start = time.perf_counter()
        _pr.planar_rate_kernel(ax, ay, times, g, c, bmat, smat, mu_s, mu_f, rate, cap, tol, h_first,
                               out_x, out_v, out_a, out_en, ev_t, ev_k, summary, surf_peak, first, u, levels)
        elapsed = time.perf_counter() - start
        n_ev = int(summary[_pr.S_N_EVENTS])
        if n_ev <= capacity:
            return out_x, out_v, out_a, out_en, summary, surf_peak, first, u, ev_t[:n_ev], ev_k[:n_ev], elapsed
        capacity = n_ev + 16


def _refuse_after_hand_over(summary, xdot, u, cap, bmat, smat, rbar, mu_s, mu_f, rate, g, c, local, ax, ay, t0, kind):
    """The kernel stopped with every surface on its rim and the rims apart: the slide along the rims carried on to
    its first event (:func:`hand_over`); what follows is not modelled yet, so the run ends in one line naming it."""
    t1 = float(summary[_pr.S_FAIL_T])
    energies = tuple(float(summary[k]) for k in (_pr.S_E_IN, _pr.S_E_F, _pr.S_E_V, _pr.S_E_IMPACT))
    reached = (f"{MODEL_NAME}: every surface of the {kind} bearing reached its rim at t = {t0 + t1:.6g} s with the "
               f"rims {float(summary[_pr.S_RIMS_SPREAD]):.3g} apart (sine)")
    try:
        out = hand_over(t1, xdot, u, cap, bmat, smat, rbar, mu_s, mu_f, rate, g, c, local, ax, ay, energies)
    except SolverError as exc:
        raise SolverError(f"{reached}: the slide along the rims from there stopped: {exc}; no answer is given") from None
    head = (f"{reached}: the slide along the rims integrated from there "
            f"(Radau, rtol {HAND_OVER_RTOL:g}; energy balance {out['total_balance']:.2g} of {out['total_input']:.3g} "
            "J/kg input over the run)")
    if out["reason"] == "aligned":
        raise SolverError(f"{head} reaches the rims' alignment at t = {t0 + out['t']:.9g} s (1 − |X|/Σd* = "
                          f"{out['gap']:.2g}, the rims {out['spread']:.2g} apart), the ultimate "
                          f"displacement: a plastic impact of {out['impulse']:.4g} m/s into the rims (impulse "
                          f"{out['impulse']:.4g} m/s per unit mass, {out['impact_energy']:.3g} J/kg taken); the slide "
                          f"on the rims' common circle after it ({abs(out['along']):.3g} m/s along it) is not modelled "
                          "for µ(v) in the plane; no answer is given")
    what = {"leaves": "a surface's rim reaction turns inward (it leaves its rim)", "rest": "the mass comes to rest",
            "end": "the record ends"}[out["reason"]]
    raise SolverError(f"{head} ends at t = {t0 + out['t']:.9g} s where {what}: the run on from there (the kernel "
                      "restarted from that state) is not modelled for µ(v) in the plane; no answer is given")


def simulate_bearing_pair_rate(ax_m_s2, ay_m_s2, dt_s: float | None = None, *, bearing, time_s=None,
                               damping_per_mass: float = 0.0, gravity_m_s2: float = STANDARD_GRAVITY,
                               tolerance: float = DEFAULT_TOLERANCE,
                               saturation_levels=None) -> RatePlanarMultisurfaceResponse:
    """Response of a mass on a double or triple friction pendulum with µ(v) surfaces to two components.

    Parameters
    ----------
    ax_m_s2, ay_m_s2 : array_like
        Ground acceleration along x and y [m/s²], linear between samples.
    dt_s : float, optional
        Sample interval [s] (or give ``time_s``).
    bearing : isolator.bearing.Bearing
        Every surface with ``mu_slow < mu_fast`` and ``rate_s_per_m``.
    time_s : array_like, optional
        Sample times [s], strictly increasing.
    damping_per_mass : float
        Supplemental linear damper γ/M [1/s] (isotropic in the plane).
    gravity_m_s2 : float
        g [m/s²].
    tolerance : float
        Step tolerance: largest difference of a collocation step from its two halves, as a fraction of the
        running peak displacement (≥ 1e-4 m) and speed (≥ 1e-3 m/s) [-].
    saturation_levels : (float, float), optional
        (join, leave) levels of a_i |u̇_i| of the saturated set (default
        :data:`isolator.solver.multisurface_rate_kernel.LOCK_LEVELS`, (28, 26); ``(inf, inf)``: no set).

    Returns
    -------
    RatePlanarMultisurfaceResponse
        ``model`` ``2d-multisurface+mu(v)``.

    Raises
    ------
    SolverError
        An impact at the ultimate taking a velocity along the rims (more than IMPACT_TANGENTIAL_LIMIT; named first,
        before a stop it causes); every surface on its rim with the rims apart, after the slide along the rims
        (:func:`hand_over`) to its first event — the alignment's impact (named with its impulse and energy), a rim
        left inward, rest or the record's end: what follows is not modelled; a slide along the rims alone from rest (not modelled: the
        time and a surface are named), more than
        MAX_STEPS_PER_INTERVAL steps in one sample interval, or the step size fell below 1e-13 of the sample
        interval.
    """
    timing = record_timing(ax_m_s2, dt_s, time_s)
    ax, dt, relative, t0 = timing.acceleration_m_s2, timing.dt_s, timing.relative_time_s, timing.t0_s
    ay = record_timing(ay_m_s2, dt_s, time_s).acceleration_m_s2
    if ay.size != ax.size:
        raise RecordInputError(f"ay_m_s2: {ay.size} samples, the first component has {ax.size}")
    local = dt * np.arange(ax.size) if relative is None else relative
    c = float(damping_per_mass)
    g = float(gravity_m_s2)
    if not (c >= 0.0 and math.isfinite(c) and g > 0.0 and math.isfinite(g)):
        raise ValueError("damping_per_mass must be >= 0 and gravity_m_s2 > 0, both finite")
    if not (0.0 < tolerance < 1e-3):
        raise ValueError(f"tolerance must be in (0, 1e-3), got {tolerance!r}")
    if bearing.is_simple:
        raise ValueError("a single surface with µ(v) runs on the 2-D engine (2d+mu(v)), not here")
    mu_s, mu_f, rate = rate_laws(bearing, MODEL_NAME)
    rbar, _, _ = bearing.elements()
    smat = np.linalg.inv(bearing.surface_matrix())
    bmat = smat / rbar[:, None]  # b = diag(1/R̄) T⁻¹ u, on each component
    cap = bearing.effective_capacities_m.astype(np.float64)
    _warm_up()
    out_x, out_v, out_a, out_en, summary, surf_peak, first, u, ev_t, ev_k, elapsed = _run(
        ax, ay, np.ascontiguousarray(local, dtype=np.float64), g, c, bmat, smat, mu_s, mu_f, rate, cap,
        float(tolerance), 64 + ax.size // 4,
        LOCK_LEVELS if saturation_levels is None else np.asarray(saturation_levels, dtype=np.float64))
    status = int(summary[_pr.S_STATUS])
    fail_t = t0 + float(summary[_pr.S_FAIL_T])
    if status & _pr.STATUS_ALL_RIMS:
        _refuse_after_hand_over(summary, out_v[-1], u, cap, bmat, smat, rbar, mu_s, mu_f, rate, g, c,
                                np.ascontiguousarray(local, dtype=np.float64), ax, ay, t0, bearing.kind)
    tangential = float(summary[_pr.S_IMPACT_TANGENTIAL])
    spread = float(summary[_pr.S_IMPACT_SPREAD])
    if tangential > IMPACT_TANGENTIAL_LIMIT or spread > IMPACT_SPREAD_LIMIT:
        # before the status checks: a stop after such an impact (a start from rest along the rims) is its consequence
        raise SolverError(f"{MODEL_NAME}: the ultimate displacement was reached (first at t = "
                          f"{t0 + float(summary[_pr.S_FIRST_ULT]):.6g} s) with {tangential:.3g} of the velocity along "
                          f"the rims and the rims {spread:.3g} apart (sine; the mass "
                          f"{float(summary[_pr.S_IMPACT_GAP]) * float(np.sum(cap)):.3g} m inside the ultimate circle): "
                          "the closing into alignment and the slide along the rims at the ultimate are not modelled "
                          "for µ(v) in the plane (the impact would take that velocity away); no answer is given")
    if status & _pr.STATUS_RIM:
        raise SolverError(f"{MODEL_NAME}: at t = {fail_t:.6g} s the mass at rest is pushed along the rims with no "
                          f"surface of the {bearing.kind} bearing free to slide inside its rim (surface "
                          f"{int(summary[_pr.S_RIM_SURFACE]) + 1} on its rim): a slide along the rims alone is not "
                          "modelled; no answer is given")
    if status & _pr.STATUS_WORK:
        raise SolverError(f"{MODEL_NAME}: more than {_pr.MAX_STEPS_PER_INTERVAL} collocation steps in one sample "
                          f"interval at t = {fail_t:.6g} s (not resolved: two surfaces saturated together, or a stop "
                          "approached without end); no answer is given")
    if status & _pr.STATUS_STEP_FAILED:
        raise SolverError(f"{MODEL_NAME}: the step size fell below 1e-13 of the sample interval at t = {fail_t:.6g} s "
                          "(the force through the sliders was not found: two surfaces saturated together, or a "
                          "stop not resolved); no answer is given")
    message = "ok"
    if status & _pr.STATUS_CHATTER:
        message = (f"chatter guard: more than {_pr.MAX_EVENTS_PER_INTERVAL} events in one sample interval; the "
                   "bearing was held to the end of that interval")
    elements = smat @ u  # ū = T⁻¹ u, (n, 2)
    regimes: dict = {}
    n_surf = len(bearing.surfaces)
    for code in np.flatnonzero(first >= 0.0):
        name = bearing.regime_name(int(code) % (1 << n_surf), int(code) >> n_surf)
        if name and (name not in regimes or first[code] + t0 < regimes[name]):
            regimes[name] = float(first[code] + t0)
    regimes = dict(sorted(regimes.items(), key=lambda item: item[1]))
    on_surface = [float(p) * s.radius_m / s.effective_radius_m for p, s in zip(surf_peak, bearing.surfaces,
                                                                                 strict=True)]
    e_in, e_f, e_v, e_imp = (float(summary[k]) for k in (_pr.S_E_IN, _pr.S_E_F, _pr.S_E_V, _pr.S_E_IMPACT))
    e_kin = 0.5 * float(out_v[-1, 0] ** 2 + out_v[-1, 1] ** 2)
    e_pot = float(g * np.sum(np.sum(elements * elements, axis=1) / (2.0 * rbar)))
    n_steps = int(summary[_pr.S_N_STEPS])
    return RatePlanarMultisurfaceResponse(
        bearing=bearing,
        time_s=t0 + local,
        ground_acceleration_m_s2=np.column_stack((ax, ay)),
        displacement_m=out_x, velocity_m_s=out_v, absolute_acceleration_m_s2=out_a,
        event_time_s=t0 + ev_t, event_kind=ev_k,
        peak_displacement_m=float(summary[_pr.S_PEAK_X]),
        residual_displacement_m=float(math.hypot(out_x[-1, 0], out_x[-1, 1])),
        residual_displacement_x_m=float(out_x[-1, 0]),
        residual_displacement_y_m=float(out_x[-1, 1]),
        peak_velocity_m_s=float(summary[_pr.S_PEAK_V]),
        peak_transmitted_acceleration_m_s2=float(summary[_pr.S_PEAK_A]),
        slip_time_s=float(summary[_pr.S_SLIP_TIME]),
        n_events=int(summary[_pr.S_N_EVENTS]),
        energy_input_J_per_kg=e_in, energy_friction_J_per_kg=e_f, energy_viscous_J_per_kg=e_v,
        energy_kinetic_final_J_per_kg=e_kin, energy_potential_final_J_per_kg=e_pot,
        energy_balance_error_J_per_kg=e_in - (e_kin + e_pot + e_f + e_v + e_imp),
        energy_impact_J_per_kg=e_imp,
        n_rim_contacts=int(summary[_pr.S_N_RIM]),
        ultimate_displacement_reached=bool(summary[_pr.S_FIRST_ULT] >= 0.0),
        impact_impulse_m_s=float(summary[_pr.S_IMPULSE]),
        max_impact_velocity_m_s=float(summary[_pr.S_MAX_IMPACT_V]),
        n_impacts=int(summary[_pr.S_N_ULT]),
        energy_history_J_per_kg=out_en,
        surface_peak_displacement_m=on_surface,
        regimes=regimes,
        element_displacement_m=elements,
        ultimate_displacement_m=bearing.ultimate_displacement_m,
        peak_force_per_weight=float(summary[_pr.S_PEAK_R]),
        n_steps=n_steps,
        status=status, message=message, solver_seconds=elapsed,
        damping_per_mass=c, gravity_m_s2=g,
        model=MODEL_NAME,
        model_reason=(f"a {bearing.kind} bearing with µ(v) on its surfaces in the plane: Radau IIA collocation with "
                      f"events, step tolerance {tolerance:g} of the peaks ({n_steps} steps, "
                      f"{int(summary[_pr.S_N_NEWTON])} Newton iterations); rims held, slid along and left, the ultimate a "
                      "plastic impact"),
    )


__all__ = ["MODEL_NAME", "DEFAULT_TOLERANCE", "RatePlanarMultisurfaceResponse", "scene_needs", "simulate_scene",
           "simulate_bearing_pair_rate"]
