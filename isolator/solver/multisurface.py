"""Driver of the 1-D multi-surface model: a mass on a single, double or triple friction pendulum.

The record is piecewise linear between its samples, as for the single pendulum
(:mod:`isolator.solver.record`); the response to it is exact between events and the
events are located to rounding (:mod:`isolator.solver.multisurface_kernel`).  The
bearing is :class:`isolator.bearing.Bearing` (series model, rims, ultimate displacement).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from isolator.errors import DesignError, RecordInputError
from isolator.solver import multisurface_kernel as _ms
from isolator.solver import record as _record
from isolator.solver.base import SolverResult
from isolator.solver.kernel import max_piece_s, substeps_per_interval
from isolator.solver.multisurface_series import STATIC_FRICTION_REASON
from isolator.solver.notice import note_if_slow
from isolator.solver.record import AlongOneComponent, record_timing
from isolator.solver.system import classify_configuration
from isolator.units import STANDARD_GRAVITY

MODEL_NAME = "1d-multisurface"


@dataclass(kw_only=True)
class MultisurfaceResponse(AlongOneComponent, SolverResult):
    """Exact response of a mass on a multi-surface bearing to one component (model ``1d-multisurface``).

    The fields of :class:`~isolator.solver.base.SolverResult` (SI units, energies per unit
    mass) and the bearing's own.  The balance
    ``input = kinetic + stored + friction + viscous + impact`` holds to
    ``energy_balance_error_J_per_kg``; ``energy_impact_J_per_kg`` is the kinetic energy lost
    in plastic impacts on rims; ``energy_potential_final_J_per_kg`` is the energy stored in
    the bearing, g Σ ū_i²/(2 R̄_i).
    """

    EXTRA_SUMMARY_KEYS = ("bearing_type", "surface_peak_displacement_m", "regimes", "n_rim_contacts",
                          "ultimate_displacement_reached", "ultimate_displacement_m", "energy_impact_J_per_kg",
                          "impact_impulse_m_s", "max_impact_velocity_m_s", "peak_force_per_weight")
    EVENT_NAMES = _ms.EVENT_NAMES

    bearing: object
    force_per_weight: np.ndarray  #: the bearing's F/W at the samples [-]
    event_displacement_m: np.ndarray
    energy_impact_J_per_kg: float
    surface_peak_displacement_m: list  #: per surface in file order, on the surface (d, not d*) [m]
    regimes: dict  #: first time [s] each regime was entered (I–V for a triple; sliding surfaces otherwise)
    n_rim_contacts: int
    ultimate_displacement_reached: bool
    ultimate_displacement_m: float
    ultimate_first_time_s: float | None
    impact_impulse_m_s: float  #: Σ |V| lost at impacts: impulse per unit mass [m/s]
    max_impact_velocity_m_s: float
    peak_force_per_weight: float  #: largest |F/W| of the bearing [-]
    element_displacement_m: np.ndarray  #: final state of the series elements [m]
    #: True when the registry's first model (``1d-exact``, a single pendulum) reached the
    #: capacity and the scene was run again here; :func:`isolator.solver.models.simulate`
    #: then keeps this result's ``model`` and ``model_reason``
    rerun: bool = False
    substeps_per_interval: int = 1
    damping_per_mass: float = 0.0
    gravity_m_s2: float = STANDARD_GRAVITY
    model: str = MODEL_NAME
    model_reason: str = "a multi-surface bearing: the exact 1-D series model with rims"

    @property
    def bearing_type(self) -> str:
        return self.bearing.kind

    @property
    def configuration(self) -> str:
        """The paper's configuration (friction + spring = 3, + damper = 4a/b/c at the stiffest regime)."""
        rbar = self.bearing.elements()[0]
        return classify_configuration(self.damping_per_mass, self.gravity_m_s2 / float(np.min(rbar)))

    @property
    def sliding(self) -> np.ndarray:
        """True at the samples where the mass slides on the bearing."""
        return self.velocity_m_s != 0.0


def rim_of_single(scene):
    """The single pendulum with its rim that a one-component scene describes, or None.

    A design with a ``displacement_capacity_m`` and one surface (no ``[bearing]``, or
    ``type = "single"``), a restoring stiffness > 0, constant friction, one horizontal
    component, no vertical and no superstructure.  Its friction, radius (R = g/κ for a
    spring), damping and gravity are the scene's isolator keywords (what ``1d-exact`` runs);
    a ``[bearing]`` single gives its own surface (R, h, d: the rim at d* = d R_eff/R).

    Returns
    -------
    isolator.bearing.Bearing or None
    """
    # the design layer's class, imported here: isolator.bearing imports the solver package's series functions
    from isolator.bearing import Bearing, Surface

    design = scene.design
    capacity = getattr(design, "displacement_capacity_m", None)
    if (capacity is None or scene.has_y or scene.has_z or scene.velocity_dependent
            or getattr(design, "superstructure", None) is not None):
        return None
    bearing = getattr(design, "bearing", None)
    if bearing is not None:
        return bearing if bearing.is_simple and bearing.has_rims else None
    iso = scene.isolator
    g = float(iso.get("gravity_m_s2") or STANDARD_GRAVITY)
    radius = iso.get("radius_m")
    if radius is None:
        kappa = iso.get("stiffness_per_mass")
        if not kappa or not kappa > 0.0:
            return None  # a flat slider without restoring force: no pendulum, no rim modelled
        radius = g / float(kappa)
    mu_s = float(iso["mu_static"])
    mu_k = float(iso.get("mu_kinetic") if iso.get("mu_kinetic") is not None else mu_s)
    return Bearing(kind="single", surfaces=(Surface(radius_m=float(radius), height_m=0.0, mu_kinetic=mu_k,
                                                    mu_static=mu_s, displacement_capacity_m=float(capacity)),))


def scene_needs(scene) -> tuple[str, str] | None:
    """``(model, reason)`` for a double or triple bearing, or a single pendulum with a capacity; else None.

    A double or triple bearing: ``1d-multisurface``.  Under two components or a vertical it
    is the 2-D model's (:mod:`isolator.solver.planar_multisurface`).

    A single pendulum with a displacement capacity under one component
    (:func:`rim_of_single`): ``1d-exact``, today's kernel, **and the choice depends on its
    result** — when its peak reaches the capacity the scene is run again on
    ``1d-multisurface`` with the rim, and that result says so (``model``,
    ``model_reason``).  Any other single surface: None (today's kernels).
    """
    bearing = getattr(scene.design, "bearing", None)
    if bearing is None or bearing.is_simple:
        single = rim_of_single(scene)
        if single is None:
            return None
        return RIM_FIRST_MODEL, (f"{_record.MODEL_REASON}; a displacement capacity of "
                                 f"{single.ultimate_displacement_m:.4g} m: if the peak reaches it, the run is redone "
                                 f"with the rim ({MODEL_NAME}), a choice made on the result")
    if scene.has_y or scene.has_z:
        return None  # the 2-D model's (isolator.solver.planar_multisurface)
    n = len(bearing.surfaces)
    return MODEL_NAME, (f"a {bearing.kind} friction pendulum ({n} surfaces): the exact 1-D series model of "
                        "Fenz & Constantinou with rims (closed forms between events)")


#: The model a single pendulum with a capacity runs first (today's exact 1-D kernel).
RIM_FIRST_MODEL = _record.MODEL_NAME


def simulate_scene(scene) -> SolverResult:
    """The exact 1-D response of the scene's multi-surface bearing (:func:`simulate_bearing`).

    A single pendulum with a capacity (:func:`rim_of_single`) runs on today's kernel
    (:func:`isolator.solver.record.simulate_scene`); if its peak reaches the capacity,
    the plate it ran on does not exist there, and the scene is run again on the rim model
    (:func:`simulate_bearing`, equal to today's kernel up to the first rim contact).  That
    result has ``rerun`` true and its own ``model``/``model_reason``, which the registry
    keeps.

    Raises
    ------
    RecordInputError
        Two horizontal components or a vertical (not modelled for a double or triple bearing).
    DesignError
        A superstructure on a double or triple bearing (not modelled).
    """
    damping = float(scene.isolator.get("damping_per_mass") or 0.0)
    gravity = float(scene.isolator.get("gravity_m_s2") or STANDARD_GRAVITY)
    bearing = getattr(scene.design, "bearing", None)
    if bearing is None or bearing.is_simple:
        single = rim_of_single(scene)
        if single is None:  # pragma: no cover - scene_needs answers only for these scenes
            raise LookupError("the multi-surface model takes no such scene")
        free = _record.simulate_scene(scene)
        capacity = single.ultimate_displacement_m
        if free.peak_displacement_m < capacity:
            return free
        rimmed = simulate_bearing(scene.ax_m_s2, scene.dt_s, time_s=scene.time_s, bearing=single,
                                  damping_per_mass=damping, gravity_m_s2=gravity)
        rimmed.rerun = True
        rimmed.model = MODEL_NAME
        rimmed.model_reason = (f"a single pendulum that reached its displacement capacity {capacity:.4g} m: on "
                               f"{RIM_FIRST_MODEL} (an unbounded plate) its peak was "
                               f"{free.peak_displacement_m:.4g} m, so the run was redone with the rim "
                               "(the exact 1-D series model, plastic impact at the capacity); chosen on that result")
        return rimmed
    if getattr(scene.design, "superstructure", None) is not None:
        raise DesignError(f"{scene.design.source}: a {scene.design.bearing.kind} bearing under a [superstructure] is "
                          "not modelled (1d-multisurface carries a rigid mass; the registry runs it on 1d-building-multisurface)")
    if scene.has_y or scene.has_z:
        raise RecordInputError(f"a {scene.design.bearing.kind} bearing is modelled for one horizontal component "
                               "only (1d-multisurface); the 2-D model is 2d-multisurface")
    return simulate_bearing(scene.ax_m_s2, scene.dt_s, time_s=scene.time_s, bearing=scene.design.bearing,
                            damping_per_mass=damping, gravity_m_s2=gravity)


def response_fields(bearing, summary, out, energy, surf_peak, first, elements, rbar, g, t0, ev_t, ev_k, ev_x) -> dict:
    """The fields of a :class:`MultisurfaceResponse` read from a 1-D multi-surface kernel's outputs.

    The kernels of ``1d-multisurface`` and ``1d-multisurface+mu(v)`` share the summary layout of
    :mod:`isolator.solver.multisurface_kernel` (``S_PEAK_X`` … ``S_PEAK_R``), the output arrays ``out`` (x, v, a, r),
    the per-surface peaks, the first time of each sliding set (``first``) and the elements' final displacements
    ``elements`` [m] (series elements, radii ``rbar`` [m]); ``t0`` [s] is the record's start.
    """
    e_kin = 0.5 * float(out["v"][-1]) ** 2
    e_pot = float(g * np.sum(elements * elements / (2.0 * rbar)))
    e_in, e_f, e_v, e_imp = (float(summary[k]) for k in (_ms.S_E_INPUT, _ms.S_E_FRICTION, _ms.S_E_VISCOUS,
                                                         _ms.S_E_IMPACT))
    ne = rbar.size
    regimes: dict = {}
    for code in np.flatnonzero(first >= 0.0):
        name = bearing.regime_name(int(code) % (1 << ne), int(code) // (1 << ne))
        if name and (name not in regimes or first[code] + t0 < regimes[name]):
            regimes[name] = float(first[code] + t0)
    regimes = dict(sorted(regimes.items(), key=lambda item: item[1]))
    on_surface = [float(p) * s.radius_m / s.effective_radius_m for p, s in zip(surf_peak, bearing.surfaces,
                                                                                 strict=True)]
    first_ult = float(summary[_ms.S_FIRST_ULTIMATE_T])
    return dict(
        bearing=bearing, peak_force_per_weight=float(summary[_ms.S_PEAK_R]),
        displacement_m=out["x"], velocity_m_s=out["v"], absolute_acceleration_m_s2=out["a"],
        force_per_weight=out["r"],
        event_time_s=t0 + ev_t, event_kind=ev_k, event_displacement_m=ev_x,
        peak_displacement_m=float(summary[_ms.S_PEAK_X]),
        residual_displacement_m=float(out["x"][-1]),
        peak_velocity_m_s=float(summary[_ms.S_PEAK_V]),
        peak_transmitted_acceleration_m_s2=float(summary[_ms.S_PEAK_A]),
        slip_time_s=float(summary[_ms.S_SLIP_TIME]),
        n_events=int(summary[_ms.S_N_EVENTS]),
        energy_input_J_per_kg=e_in, energy_friction_J_per_kg=e_f, energy_viscous_J_per_kg=e_v,
        energy_impact_J_per_kg=e_imp, energy_kinetic_final_J_per_kg=e_kin, energy_potential_final_J_per_kg=e_pot,
        energy_balance_error_J_per_kg=e_in - (e_kin + e_pot + e_f + e_v + e_imp),
        energy_history_J_per_kg=energy,
        surface_peak_displacement_m=on_surface,
        regimes=regimes,
        n_rim_contacts=int(summary[_ms.S_N_RIM_CONTACTS]),
        ultimate_displacement_reached=bool(summary[_ms.S_N_ULTIMATE] > 0),
        ultimate_displacement_m=bearing.ultimate_displacement_m,
        ultimate_first_time_s=None if first_ult < 0.0 else t0 + first_ult,
        impact_impulse_m_s=float(summary[_ms.S_IMPULSE]),
        max_impact_velocity_m_s=float(summary[_ms.S_MAX_IMPACT_V]),
        element_displacement_m=elements,
    )


_READY = False


def _warm_up() -> None:
    global _READY
    if _READY:
        return
    with note_if_slow("compiling the multi-surface solver (its first use after installation takes a few "
                      "seconds; the machine code is cached for later runs)"):
        _run(np.array([0.0, 1.0, -1.0]), 0.01, np.empty(0), 1, math.inf, 0.0, STANDARD_GRAVITY,
             np.array([1.0, 2.0]), np.array([0.05, 0.05]), np.array([0.05, 0.05]), np.array([0.1, 0.1]),
             np.eye(2), 8)
    _READY = True


def _run(acc, dt, times, n_sub, max_piece, c, g, rbar, mu, mu_static, rim, tmat, capacity):
    n = acc.size
    ne = rbar.size
    out = {name: np.empty(n) for name in ("x", "v", "a", "r")}
    out_energy = np.empty((4, n))
    summary = np.zeros(_ms.SUMMARY_SIZE)
    surf_peak = np.zeros(tmat.shape[0])
    first = np.empty(4 ** ne)
    while True:
        ev_time = np.empty(capacity)
        ev_kind = np.empty(capacity, dtype=np.int8)
        ev_x = np.empty(capacity)
        u = np.zeros(ne)
        surf_peak[:] = 0.0
        start = time.perf_counter()
        _ms.multisurface_kernel(acc, dt, times, n_sub, max_piece, c, g, rbar, mu, mu_static, rim, tmat,
                                out["x"], out["v"], out["a"], out["r"], out_energy, ev_time, ev_kind, ev_x,
                                summary, surf_peak, first, u)
        elapsed = time.perf_counter() - start
        n_ev = int(summary[_ms.S_N_EVENTS])
        if n_ev <= capacity:
            return out, out_energy, summary, surf_peak, first, u, ev_time[:n_ev], ev_kind[:n_ev], ev_x[:n_ev], elapsed
        capacity = n_ev + 16


def simulate_bearing(acceleration_m_s2, dt_s: float | None = None, *, bearing, time_s=None,
                     damping_per_mass: float = 0.0, gravity_m_s2: float = STANDARD_GRAVITY) -> MultisurfaceResponse:
    """Exact 1-D response of a mass on a multi-surface friction pendulum to a sampled record.

    Parameters
    ----------
    acceleration_m_s2 : array_like
        Ground acceleration [m/s²], linear between samples.
    dt_s : float, optional
        Sample interval [s] (or give ``time_s``).
    bearing : isolator.bearing.Bearing
        The bearing (kinetic friction per surface; static friction above kinetic on a
        single surface only; µ(v) is :mod:`isolator.solver.multisurface_rate`'s, except µ_slow =
        µ_fast, a constant law run here).
    time_s : array_like, optional
        Sample times [s], strictly increasing.
    damping_per_mass : float
        Supplemental linear damper γ/M [1/s].
    gravity_m_s2 : float
        g [m/s²] (the weight, hence the pendulum's stiffness and the friction force).

    Returns
    -------
    MultisurfaceResponse
    """
    timing = record_timing(acceleration_m_s2, dt_s, time_s)
    acc, dt, relative, t0 = timing.acceleration_m_s2, timing.dt_s, timing.relative_time_s, timing.t0_s
    c = float(damping_per_mass)
    g = float(gravity_m_s2)
    if not (c >= 0.0 and math.isfinite(c) and g > 0.0 and math.isfinite(g)):
        raise ValueError("damping_per_mass must be >= 0 and gravity_m_s2 > 0, both finite")
    rbar, mu, rim = bearing.elements()
    if any(surface.rate_s_per_m is not None and surface.mu_slow < surface.mu_fast for surface in bearing.surfaces):
        # µ_slow = µ_fast is a constant law (µ = µ_fast), which the closed forms take
        raise ValueError("velocity-dependent friction is not part of the exact 1-D multi-surface model (closed forms "
                         "need constant friction per surface): it is 1d-multisurface+mu(v) "
                         "(isolator.solver.multisurface_rate)")
    if rbar.size > 1 and np.any(bearing.mu_static != mu):
        raise ValueError(f"static friction above kinetic on a {bearing.kind} bearing is not modelled: "
                         f"{STATIC_FRICTION_REASON}")
    tmat = bearing.surface_matrix()
    kappa_max = g / float(np.min(rbar))  # the stiffest regime: one element of the smallest radius
    max_piece = max_piece_s(c, kappa_max)
    if relative is None:
        n_sub = substeps_per_interval(dt, c, kappa_max)
        kernel_times = np.empty(0)
    else:
        n_sub = 1
        kernel_times = relative
    _warm_up()
    out, energy, summary, surf_peak, first, u, ev_t, ev_k, ev_x, elapsed = _run(
        acc, dt, kernel_times, n_sub, max_piece, c, g, rbar, mu, bearing.mu_static, rim, tmat, 64 + acc.size // 4)
    status = int(summary[_ms.S_STATUS])
    message = "ok"
    if status & _ms.STATUS_CHATTER:
        message = (f"chatter guard: more than {_ms.MAX_EVENTS_PER_INTERVAL} events in one sample interval; the "
                   "bearing was held to the end of that interval")
    return MultisurfaceResponse(
        time_s=t0 + (dt * np.arange(acc.size) if relative is None else relative),
        ground_acceleration_m_s2=acc,
        **response_fields(bearing, summary, out, energy, surf_peak, first, u, rbar, g, t0, ev_t, ev_k, ev_x),
        status=status, message=message, solver_seconds=elapsed, substeps_per_interval=n_sub,
        damping_per_mass=c, gravity_m_s2=g, model=MODEL_NAME,
        model_reason=f"a {bearing.kind} bearing: the exact 1-D series model with rims",
    )
