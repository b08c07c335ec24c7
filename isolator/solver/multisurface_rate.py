"""Driver of the 1-D multi-surface model with velocity-dependent friction: model ``1d-multisurface+mu(v)``.

A double or triple friction pendulum whose surfaces follow the single pendulum's law
µ_i(v) = µ_fast,i − (µ_fast,i − µ_slow,i) exp(−a_i |v_i|) (``mu_slow``/``mu_fast``/``rate_s_per_m``
in ``[[bearing.surface]]``), v_i the slide velocity on surface i, under one horizontal component.
The equations, the method (Radau IIA collocation with events) and its error are in
:mod:`isolator.solver.multisurface_rate_kernel` and docs/multisurface.md.  The result is a
:class:`~isolator.solver.multisurface.MultisurfaceResponse` (the keys of ``1d-multisurface``).
"""

from __future__ import annotations

import math
import time

import numpy as np

from isolator.errors import DesignError, RecordInputError, SolverError
from isolator.solver import multisurface_rate_kernel as _mr
from isolator.solver.base import SolverResult
from isolator.solver.multisurface import MultisurfaceResponse, response_fields
from isolator.solver.notice import note_if_slow
from isolator.solver.record import record_timing
from isolator.units import STANDARD_GRAVITY

MODEL_NAME = "1d-multisurface+mu(v)"

#: Default step tolerance: the largest difference of a step of h from two of h/2, as a fraction of the
#: running peak displacement and velocity.  Measured against the tests' independent reference: ≤ 1e-9
#: of the peak (docs/multisurface.md).
DEFAULT_TOLERANCE = 1e-11



def is_rate_dependent(bearing) -> bool:
    """True when a surface of the bearing has a genuine µ(v) law (µ_slow < µ_fast)."""
    return any(s.rate_s_per_m is not None and s.mu_slow < s.mu_fast for s in bearing.surfaces)


def scene_needs(scene) -> tuple[str, str] | None:
    """``(model, reason)`` for a double or triple bearing with µ(v) on its surfaces under one component; else None.

    It answers with a vertical too, so that such a scene is refused in one line (:func:`simulate_scene`)
    rather than run with constant friction by the 2-D model; two components go to ``2d-multisurface+mu(v)``
    (:mod:`isolator.solver.planar_multisurface_rate`).
    """
    bearing = getattr(scene.design, "bearing", None)
    if bearing is None or bearing.is_simple or scene.has_y or not is_rate_dependent(bearing):
        return None
    return MODEL_NAME, (f"a {bearing.kind} friction pendulum with velocity-dependent friction µ_i(v_i) on its "
                        "surfaces: the series model of Fenz & Constantinou as an index-1 DAE, Radau IIA "
                        "collocation with events (error controlled, not closed form)")


def simulate_scene(scene) -> SolverResult:
    """The 1-D response of the scene's µ(v) double or triple bearing (:func:`simulate_bearing_rate`).

    Raises
    ------
    RecordInputError
        Two horizontal components or a vertical.
    DesignError
        A superstructure.
    """
    kind = scene.design.bearing.kind
    if getattr(scene.design, "superstructure", None) is not None:
        raise DesignError(f"{scene.design.source}: a {kind} bearing with µ(v) under a [superstructure] is not "
                          f"modelled ({MODEL_NAME} carries a rigid mass)")
    if scene.has_y or scene.has_z:
        raise RecordInputError(f"a {kind} bearing with velocity-dependent friction is modelled for one horizontal "
                               f"component only ({MODEL_NAME}); under two components or a vertical give each "
                               "surface a constant 'mu'")
    return simulate_bearing_rate(scene.ax_m_s2, scene.dt_s, time_s=scene.time_s, bearing=scene.design.bearing,
                                 damping_per_mass=float(scene.isolator.get("damping_per_mass") or 0.0),
                                 gravity_m_s2=float(scene.isolator.get("gravity_m_s2") or STANDARD_GRAVITY))


def rate_laws(bearing, model: str = MODEL_NAME):
    """(µ_slow, µ_fast, rate) of every surface as arrays; ValueError naming the surface without a µ(v) law."""
    mu_s, mu_f, rate = [], [], []
    for i, s in enumerate(bearing.surfaces, start=1):
        if s.rate_s_per_m is None or not s.mu_slow < s.mu_fast:
            raise ValueError(f"surface {i}: {model} needs µ(v) with mu_slow < mu_fast on every surface "
                             "(a surface of constant friction in series with µ(v) ones is not modelled)")
        mu_s.append(s.mu_slow)
        mu_f.append(s.mu_fast)
        rate.append(s.rate_s_per_m)
    return np.array(mu_s), np.array(mu_f), np.array(rate)


class RateMultisurfaceResponse(MultisurfaceResponse):
    """:class:`~isolator.solver.multisurface.MultisurfaceResponse` of ``1d-multisurface+mu(v)``.

    Its event kinds (:data:`isolator.solver.multisurface_rate_kernel.EVENT_NAMES`): a rim reached by one
    surface is no impact here (the others take its velocity); only the ultimate displacement is.
    """

    EVENT_NAMES = _mr.EVENT_NAMES


_READY = False


def _warm_up() -> None:
    global _READY
    if _READY:
        return
    with note_if_slow("compiling the µ(v) multi-surface solver (its first use after installation takes a minute; "
                      "the machine code is cached for later runs)"):
        eye = np.eye(2)
        _run(np.array([0.0, 1.0, -1.0]), np.array([0.0, 0.01, 0.02]), STANDARD_GRAVITY, 0.0, eye, eye,
             np.array([0.03, 0.03]), np.array([0.06, 0.06]), np.array([20.0, 20.0]), np.array([0.1, 0.1]),
             1e-10, _mr.LOCK_LEVELS, True, 8)
    _READY = True


def _run(acc, times, g, c, bmat, smat, mu_s, mu_f, rate, cap, tol, lock_levels, simplified, capacity):
    n = acc.size
    ns = bmat.shape[0]
    out = {name: np.empty(n) for name in ("x", "v", "a", "r")}
    out_energy = np.empty((4, n))
    summary = np.zeros(_mr.SUMMARY_SIZE)
    surf_peak = np.zeros(ns)
    first = np.empty(4 ** ns)
    h_first = float(np.min(np.diff(times))) if n > 1 else 1.0
    while True:
        ev_time = np.empty(capacity)
        ev_kind = np.empty(capacity, dtype=np.int8)
        ev_x = np.empty(capacity)
        u = np.zeros(ns)
        surf_peak[:] = 0.0
        start = time.perf_counter()
        _mr.rate_kernel(acc, times, g, c, bmat, smat, mu_s, mu_f, rate, cap, tol, h_first, lock_levels, simplified,
                        out["x"], out["v"], out["a"], out["r"], out_energy, ev_time, ev_kind, ev_x,
                        summary, surf_peak, first, u)
        elapsed = time.perf_counter() - start
        n_ev = int(summary[_mr.S_N_EVENTS])
        if n_ev <= capacity:
            return out, out_energy, summary, surf_peak, first, u, ev_time[:n_ev], ev_kind[:n_ev], ev_x[:n_ev], elapsed
        capacity = n_ev + 16


def simulate_bearing_rate(acceleration_m_s2, dt_s: float | None = None, *, bearing, time_s=None,
                          damping_per_mass: float = 0.0, gravity_m_s2: float = STANDARD_GRAVITY,
                          tolerance: float = DEFAULT_TOLERANCE,
                          saturation_levels: tuple[float, float] | None = None,
                          simplified_newton: bool = True) -> RateMultisurfaceResponse:
    """1-D response of a mass on a double or triple friction pendulum with µ(v) on every surface.

    Parameters
    ----------
    acceleration_m_s2 : array_like
        Ground acceleration [m/s²], linear between samples.
    dt_s : float, optional
        Sample interval [s] (or give ``time_s``).
    bearing : isolator.bearing.Bearing
        Every surface with ``mu_slow < mu_fast`` and ``rate_s_per_m`` (µ increasing with speed).
    time_s : array_like, optional
        Sample times [s], strictly increasing.
    damping_per_mass : float
        Supplemental linear damper γ/M [1/s].
    gravity_m_s2 : float
        g [m/s²].
    tolerance : float
        Step tolerance: largest difference of a collocation step from its two halves, as a
        fraction of the running peak displacement (≥ 1e-4 m) and velocity (≥ 1e-3 m/s) [-].
    saturation_levels : (float, float), optional
        Levels of a_i |v_i| at which a sliding surface joins and leaves the set of surfaces saturated together,
        whose velocity is shared so that their back-forces move together (the slow manifold; friction within
        (µ_fast − µ_slow) e^(−leave) of µ_fast, docs/multisurface.md) [-].  Default
        :data:`isolator.solver.multisurface_rate_kernel.LOCK_LEVELS` (28, 26); ``(inf, inf)``: only where a
        surface's slide law cannot be inverted at all (the kernel before the set; it stops where two surfaces
        saturate beyond a·v ≈ 30, NWH360 ×3 at 4.92 s).
    simplified_newton : bool
        The collocation's Newton iteration with one Jacobian per step, factored once for h and once for h/2
        (full Newton, a Jacobian per stage and iteration, where it does not contract); False: full Newton
        throughout (the kernel before; both end at their rounding floor, docs/multisurface.md).

    Returns
    -------
    RateMultisurfaceResponse
        ``model`` ``1d-multisurface+mu(v)``; ``force_per_weight`` is F/W at the samples.
    """
    timing = record_timing(acceleration_m_s2, dt_s, time_s)
    acc, dt, relative, t0 = timing.acceleration_m_s2, timing.dt_s, timing.relative_time_s, timing.t0_s
    c = float(damping_per_mass)
    g = float(gravity_m_s2)
    if not (c >= 0.0 and math.isfinite(c) and g > 0.0 and math.isfinite(g)):
        raise ValueError("damping_per_mass must be >= 0 and gravity_m_s2 > 0, both finite")
    if not (0.0 < tolerance < 1e-3):
        raise ValueError(f"tolerance must be in (0, 1e-3), got {tolerance!r}")
    levels = np.array(_mr.LOCK_LEVELS if saturation_levels is None else saturation_levels, dtype=np.float64)
    if not (levels.shape == (2,) and levels[0] >= levels[1] > 0.0):
        raise ValueError(f"saturation_levels must be (join, leave) with join >= leave > 0, got {saturation_levels!r}")
    if bearing.is_simple:
        raise ValueError("a single surface with µ(v) runs on the 2-D engine (2d+mu(v)), not here")
    mu_s, mu_f, rate = rate_laws(bearing)
    rbar, _, _ = bearing.elements()
    tmat = bearing.surface_matrix()
    smat = np.linalg.inv(tmat)
    bmat = smat / rbar[:, None]  # b = diag(1/R̄) T⁻¹ u
    cap = bearing.effective_capacities_m.astype(np.float64)
    times = dt * np.arange(acc.size) if relative is None else np.ascontiguousarray(relative, dtype=np.float64)
    _warm_up()
    out, energy, summary, surf_peak, first, u, ev_t, ev_k, ev_x, elapsed = _run(
        acc, times, g, c, bmat, smat, mu_s, mu_f, rate, cap, float(tolerance), levels,
        bool(simplified_newton), 64 + acc.size // 4)
    status = int(summary[_mr.S_STATUS])
    message = "ok"
    if status & _mr.STATUS_STEP_FAILED:
        raise SolverError(f"{MODEL_NAME}: the step size fell below 1e-13 of the sample interval at "
                           f"t = {t0 + summary[_mr.S_FAIL_T]:.6g} s")
    over = [i + 1 for i, (p, d) in enumerate(zip(surf_peak, bearing.effective_capacities_m, strict=True))
            if p > d * (1.0 + 1e-9)]
    if over:  # never an answer past a rim (docs/multisurface.md, known defect of the rim events)
        raise SolverError(f"{MODEL_NAME}: surface {over[0]} passed its rim (the rim events of the µ(v) model are "
                          "not reliable yet); no answer is given")
    if status & _mr.STATUS_CHATTER:
        message = (f"chatter guard: more than {_mr.MAX_EVENTS_PER_INTERVAL} events in one sample interval; the "
                   "bearing was held to the end of that interval")
    ubar = smat @ u
    n_steps = int(summary[_mr.S_N_STEPS])
    return RateMultisurfaceResponse(
        time_s=t0 + times, ground_acceleration_m_s2=acc,
        **response_fields(bearing, summary, out, energy, surf_peak, first, ubar, rbar, g, t0, ev_t, ev_k, ev_x),
        status=status, message=message, solver_seconds=elapsed, substeps_per_interval=max(1, n_steps // max(1, acc.size - 1)),
        damping_per_mass=c, gravity_m_s2=g, model=MODEL_NAME,
        model_reason=(f"a {bearing.kind} bearing with µ(v) on its surfaces: Radau IIA collocation with events, "
                      f"step tolerance {tolerance:g} of the peaks ({n_steps} steps, "
                      f"{int(summary[_mr.S_N_NEWTON])} Newton iterations)"),
    )


__all__ = ["MODEL_NAME", "DEFAULT_TOLERANCE", "is_rate_dependent", "rate_laws", "scene_needs",
           "simulate_scene", "simulate_bearing_rate"]
