r"""A linear shear building on a double or triple friction pendulum, 1-D: the exact response to a record.

The floors and the base slab are the 1-D building's (:mod:`isolator.solver.building`: modal
damping, the slab held while the force it needs stays inside what the bearing holds); the
isolation plane is Fenz & Constantinou's series bearing of the 1-D multi-surface model
(:mod:`isolator.solver.multisurface`: massless sliders, each surface stuck or sliding, the
rims, the ultimate displacement as a plastic impact with its impulse).  Along one direction,
with x_b the bearing's total displacement and u the floors' displacements relative to the slab,

.. math::

    M (\ddot u + \mathbf 1 (\ddot x_b + a_g)) + C_s \dot u + K_s u &= 0 \\
    m_b (\ddot x_b + a_g) &= \mathbf 1^T (K_s u + C_s \dot u) - c \dot x_b - F

with F the bearing's force, W = g M_total its normal force.  While the slab moves one way F is
the piecewise-linear force of one excursion of the series model (a spring W/Σ R̄ of the
sliding surfaces in series and a constant friction), so between events the system is linear
with a forcing linear in time and is propagated exactly
(:mod:`isolator.solver.building_multisurface_kernel`); the events (a surface starting or
reaching its rim, a stop, a stick, a reversal, a break-away, the ultimate) are located to
rounding.

Outputs: the 1-D building's (:class:`~isolator.solver.building.BuildingResponse`: story drifts,
floor accelerations, shears, bearing loads) and the bearing's (surface peaks, regimes, rim
contacts, the ultimate displacement and the impact impulse).
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass, field

import numpy as np

from isolator.errors import InvalidSystemError
from isolator.solver import building as _building
from isolator.solver import building_multisurface_kernel as _bmk
from isolator.solver import multisurface_kernel as _ms
from isolator.solver.building import BuildingResponse, building_system, van_loan
from isolator.solver.building_kernel import THETA
from isolator.solver.multisurface import response_fields, rim_of_single
from isolator.solver.multisurface_series import STATIC_FRICTION_REASON
from isolator.solver.record import building_substeps, record_timing
from isolator.solver.system import classify_configuration
from isolator.units import STANDARD_GRAVITY

MODEL_NAME = "1d-building-multisurface"

#: the bearing's keys a result adds to the building's
BEARING_KEYS = ("bearing_type", "surface_peak_displacement_m", "regimes", "n_rim_contacts",
                "ultimate_displacement_reached", "ultimate_displacement_m", "energy_impact_J_per_kg",
                "impact_impulse_m_s", "impact_impulse_N_s", "max_impact_velocity_m_s", "peak_force_per_weight")


@dataclass(kw_only=True)
class BearingFields:
    """The bearing's fields of a building on a double or triple friction pendulum (one component or a pair:
    :class:`BuildingMultisurfaceResponse`, ``planar_building_multisurface.PlanarBuildingMultisurfaceResponse``),
    and the properties read from them."""

    bearing: object
    force_per_weight: np.ndarray  #: the bearing's F/W at the samples (no dashpot; (N, 2) under a pair) [-]
    energy_impact_J_per_kg: float
    surface_peak_displacement_m: list
    regimes: dict
    n_rim_contacts: int
    ultimate_displacement_reached: bool
    ultimate_displacement_m: float
    ultimate_first_time_s: float | None
    impact_impulse_m_s: float  #: Σ |ΔV| of the slab at impacts (the speed lost) [m/s]
    impact_impulse_N_s: float  #: Σ m_b |ΔV| [N·s]
    max_impact_velocity_m_s: float
    peak_force_per_weight: float
    element_displacement_m: np.ndarray
    damping_per_mass: float = 0.0  #: the isolator's dashpot over the total mass [1/s]

    @property
    def bearing_type(self) -> str:
        return self.bearing.kind

    @property
    def configuration(self) -> str:
        """The paper's configuration at the stiffest regime (as for the rigid block on the same bearing)."""
        rbar = self.bearing.elements()[0]
        return classify_configuration(self.damping_per_mass, self.building.gravity_m_s2 / float(np.min(rbar)))


@dataclass(kw_only=True)
class BuildingMultisurfaceResponse(BearingFields, BuildingResponse):
    """Exact response of a shear building on a double or triple friction pendulum (``1d-building-multisurface``).

    The fields of :class:`~isolator.solver.building.BuildingResponse` and the bearing's own (as in
    :class:`~isolator.solver.multisurface.MultisurfaceResponse`).  The balance
    ``input = kinetic + strain + stored + friction + viscous + impact`` holds to
    ``energy_balance_error_J_per_kg``; the stored energy of the bearing is W Σ ū_i²/(2R̄_i)
    (``energy_potential_final_J_per_kg``), ``energy_impact_J_per_kg`` the slab's ½ m_b v_b² lost at
    plastic impacts on the ultimate displacement, ``impact_impulse_N_s`` their Σ m_b |v_b|.
    """

    EXTRA_SUMMARY_KEYS = BuildingResponse.EXTRA_SUMMARY_KEYS + BEARING_KEYS
    EVENT_NAMES = _bmk.EVENT_NAMES

    model: str = MODEL_NAME
    model_reason: str = ""
    #: True when the registry's first run (``1d-building``, an unbounded plate) reached the single pendulum's
    #: capacity and the scene was run again here with its rim; :func:`isolator.solver.models.simulate` keeps
    #: this result's model and reason
    rerun: bool = False


def _refusal(scene) -> str | None:
    """One line naming what is not modelled for a building on this bearing, or None."""
    bearing = scene.design.bearing
    if scene.has_y:
        return f"a {bearing.kind} bearing under a [superstructure] is modelled for one horizontal component only"
    if scene.has_z:
        return f"a {bearing.kind} bearing under a [superstructure] with a vertical component is not modelled"
    if scene.velocity_dependent or any(s.rate_s_per_m is not None and s.mu_slow < s.mu_fast
                                       for s in bearing.surfaces):
        return f"µ(v) on a {bearing.kind} bearing under a [superstructure] is not modelled (constant µ per surface)"
    return None


#: The model a building on a single pendulum with a capacity runs first (the exact 1-D building).
RIM_FIRST_MODEL = _building.MODEL_NAME


def single_with_rim(scene):
    """The single pendulum with its rim under a building that a one-component scene describes, or None.

    A design with a ``[superstructure]``, a ``displacement_capacity_m`` and one surface, a restoring
    stiffness, one horizontal component with constant friction (what ``1d-building`` runs): the
    surface of :func:`isolator.solver.multisurface.rim_of_single` (its radius and friction from the
    isolator keywords, or the ``[bearing]`` single; the rim at d* = d R_eff/R).

    Returns
    -------
    isolator.bearing.Bearing or None
    """
    design = scene.design
    if getattr(design, "superstructure", None) is None or getattr(design, "displacement_capacity_m", None) is None:
        return None
    return rim_of_single(dataclasses.replace(scene, design=_WithoutFloors(design)))


class _WithoutFloors:
    """A design seen without its superstructure (what :func:`isolator.solver.multisurface.rim_of_single` reads)."""

    superstructure = None

    def __init__(self, design):
        self._design = design

    def __getattr__(self, name):
        return getattr(self._design, name)


def rerun_past_capacity(scene, single, free_run, rim_run, first_model: str, how: str):
    """A building on a single pendulum run on its unbounded plate (``free_run(scene)``) and, when its peak reaches
    the capacity, again with the rim (``rim_run(scene, single)``; ``rerun`` true, ``model_reason`` naming
    ``first_model``'s peak and ``how`` the rim model runs)."""
    free = free_run(scene)
    capacity = single.ultimate_displacement_m
    if free.peak_displacement_m < capacity:
        return free
    rimmed = rim_run(scene, single)
    rimmed.rerun = True
    rimmed.model_reason = (f"a building on a single pendulum that reached its displacement capacity "
                           f"{capacity:.4g} m: on {first_model} (an unbounded plate) its peak was "
                           f"{free.peak_displacement_m:.4g} m, so the run was redone with the rim ({how}); chosen on "
                           "that result")
    return rimmed


def scene_needs(scene) -> tuple[str, str] | None:
    """``(model, reason)`` for a design with a ``[superstructure]`` on a double or triple bearing under one
    component with constant friction; else None (a pair, a vertical, µ(v): the models above and below refuse
    them in one line).

    A building on a single pendulum with a capacity under one component (:func:`single_with_rim`):
    ``1d-building`` first, **and the choice depends on its result** — when its peak reaches the
    capacity the scene is run again here with the rim (:func:`simulate_scene`).
    """
    design = scene.design
    bearing = getattr(design, "bearing", None)
    if getattr(design, "superstructure", None) is None:
        return None
    if bearing is None or bearing.is_simple:  # a single pendulum: with a capacity, its rim when the peak reaches it
        single = single_with_rim(scene)
        return None if single is None else (RIM_FIRST_MODEL, _building.MODEL_REASON + (
            f"; a displacement capacity of {single.ultimate_displacement_m:.4g} m: if the peak reaches it, the run "
            f"is redone with the rim ({MODEL_NAME}), a choice made on the result"))
    if _refusal(scene) is not None:
        return None
    floors = len(design.superstructure.floors)
    return MODEL_NAME, (f"a {floors}-story superstructure on a {bearing.kind} friction pendulum "
                        f"({len(bearing.surfaces)} surfaces), one horizontal component: the exact 1-D building on "
                        "Fenz & Constantinou's series model with rims (linear between events)")


def simulate_scene(scene) -> BuildingResponse:
    """The exact 1-D response of the scene's building on its multi-surface bearing.

    A building on a single pendulum with a capacity (:func:`single_with_rim`) runs on the 1-D
    building (:func:`isolator.solver.building.simulate_scene`); if its peak reaches the capacity,
    the plate it ran on does not exist there, and the scene is run again here with the single
    surface and its rim (plastic impact at the capacity, the impulse reported): that result has
    ``rerun`` true and its own ``model``/``model_reason``, which the registry keeps.

    Raises
    ------
    InvalidSystemError
        Two horizontal components, a vertical or µ(v) (not modelled under a superstructure).
    """
    design = scene.design
    if design.bearing is None or design.bearing.is_simple:
        single = single_with_rim(scene)
        if single is None:
            raise LookupError("this model takes a building on a single pendulum only with a capacity (scene_needs)")
        return rerun_past_capacity(scene, single, _building.simulate_scene, _simulate_on, RIM_FIRST_MODEL,
                                   "the exact 1-D building on the series model, plastic impact at the capacity")
    why = _refusal(scene)
    if why is not None:
        raise InvalidSystemError(f"{design.source}: {why}")
    return _simulate_on(scene, design.bearing)


def _simulate_on(scene, bearing) -> BuildingMultisurfaceResponse:
    design = scene.design
    iso = {key: value for key, value in scene.isolator.items() if value is not None}
    g = float(iso.get("gravity_m_s2", design.gravity_m_s2))
    mass = design.mass_kg
    with _building.naming_design(design):
        return simulate_building_bearing(scene.ax_m_s2, scene.dt_s, time_s=scene.time_s,
                                         superstructure=design.superstructure, bearing=bearing, total_mass_kg=mass,
                                         damping_Ns_per_m=mass * float(iso.get("damping_per_mass", 0.0)),
                                         gravity_m_s2=g, bearing_layout=design.bearing_layout)


@dataclass
class _Matrices:
    base: object  #: the 1-D building with no isolator spring (its stuck and sliding matrices, watched rows)
    da: np.ndarray  #: d Ã_slide / dK
    dmon: np.ndarray  #: d(watched rows, sliding) / dK
    h_max: float
    modes: list  #: Ã per mode: 0 stuck, 1 + mask sliding on that set (W/ΣR̄ in series); None for mask 0
    cache: dict = field(default_factory=dict)  #: full sub-step propagators by their length

    def substeps(self, timing) -> int:
        """Sub-steps per sample interval of a record (:class:`~isolator.solver.record.RecordTiming`); refuses
        more than MAX_SUBSTEPS_PER_INTERVAL (:func:`~isolator.solver.record.building_substeps`)."""
        return building_substeps(timing.dt_s, timing.relative_time_s, self.h_max, "the building on its bearing")

    def full_steps(self, h: float) -> tuple:
        """(e^{Ãh}, ∫e^{Ãᵀτ}Q_in e^{Ãτ}, ∫e^{Ãᵀτ}Q_vis e^{Ãτ}) per mode, for full sub-steps of length h."""
        if h not in self.cache:
            from scipy.linalg import expm

            size = self.base.size
            out = np.zeros((3, len(self.modes), size, size))
            for mode, a_mat in enumerate(self.modes):
                if a_mat is not None:
                    out[0, mode] = expm(a_mat * h)
                    out[1, mode] = van_loan(a_mat, self.base.q_in, h)
                    out[2, mode] = van_loan(a_mat, self.base.q_vis, h)
            self.cache[h] = tuple(np.ascontiguousarray(x) for x in out)
        return self.cache[h]


def _matrices(superstructure, bearing, total_mass_kg, damping_Ns_per_m, gravity_m_s2) -> _Matrices:
    from scipy.linalg import matrix_balance

    def build(stiffness):
        return building_system(superstructure, total_mass_kg=total_mass_kg, stiffness_N_per_m=stiffness,
                               mu_static=0.0, damping_Ns_per_m=damping_Ns_per_m, gravity_m_s2=gravity_m_s2)

    base, unit = build(0.0), build(1.0)
    da = unit.a_modes[1] - base.a_modes[1]
    dmon = unit.mon_modes[1] - base.mon_modes[1]
    weight = base.weight_N
    rbar = bearing.elements()[0]
    modes = [base.a_modes[0], None]
    for mask in range(1, 1 << rbar.size):  # every sliding set's spring W/ΣR̄
        rsum = sum(float(rbar[i]) for i in range(rbar.size) if mask >> i & 1)
        modes.append(base.a_modes[1] + weight / rsum * da)
    rate = 0.0
    for a_mat in modes:
        if a_mat is not None:
            balanced, _ = matrix_balance(a_mat, permute=False)
            rate = max(rate, float(np.abs(balanced).sum(axis=0).max()))
    return _Matrices(base=base, da=da, dmon=dmon, h_max=THETA / rate if rate > 0.0 else math.inf, modes=modes)


#: The matrices (and full sub-steps' propagators) of the buildings run, by their parameters (a review runs one
#: design on many records).
_MATRICES: dict = {}

_READY = False


def _warm_up() -> None:
    global _READY
    if _READY:
        return
    from isolator.bearing import Bearing, Surface
    from isolator.solver.notice import note_if_slow
    from isolator.superstructure import Floor, Superstructure

    with note_if_slow("compiling the solver of a building on a multi-surface bearing (its first use after "
                      "installation takes a few seconds; the machine code is cached for later runs)"):
        s = Superstructure(floors=(Floor(1.0, 1.0, 100.0, 100.0),), damping_ratio=0.05, gravity_m_s2=9.81)
        b = Bearing(kind="double", surfaces=tuple(Surface(radius_m=1.0, height_m=0.0, mu_kinetic=0.05,
                                                          mu_static=0.05, displacement_capacity_m=0.01)
                                                  for _ in range(2)))
        mats, timing = _matrices(s, b, 2.0, 0.0, 9.81), record_timing(np.array([0.0, 5.0, -5.0]), 0.01, None)
        _run(mats, b, timing, mats.substeps(timing))
    _READY = True


def simulate_building_bearing(acceleration_m_s2, dt_s: float | None = None, *, time_s=None, superstructure,
                              bearing, total_mass_kg: float, damping_Ns_per_m: float = 0.0,
                              gravity_m_s2: float = STANDARD_GRAVITY,
                              bearing_layout=None) -> BuildingMultisurfaceResponse:
    """Exact response of a shear building on a single, double or triple friction pendulum to one record.

    Parameters
    ----------
    acceleration_m_s2 : array_like
        Ground acceleration [m/s²], linear between samples.
    dt_s : float, optional
        Sample interval [s] (or ``time_s``).
    time_s : array_like, optional
        Sample times [s].
    superstructure : isolator.superstructure.Superstructure
    bearing : isolator.bearing.Bearing
        Constant friction per surface (kinetic; static above kinetic on a double or triple is
        refused by the design, as for the rigid block).
    total_mass_kg : float
        The whole isolated mass (floors + slab) [kg]; W = g × it is the bearing's normal force.
    damping_Ns_per_m : float
        The isolator's dashpot [N·s/m].
    gravity_m_s2 : float
    bearing_layout : isolator.superstructure.BearingLayout, optional
        For the bearings' axial loads.
    """
    rbar, mu, _ = bearing.elements()
    if any(s.rate_s_per_m is not None and s.mu_slow < s.mu_fast for s in bearing.surfaces):
        raise ValueError("velocity-dependent friction is not part of the exact 1-D building on a multi-surface "
                         "bearing (constant friction per surface)")
    if rbar.size > 1 and np.any(bearing.mu_static != mu):
        raise ValueError(f"static friction above kinetic on the bearing is not modelled: {STATIC_FRICTION_REASON}")
    key = (superstructure, bearing, float(total_mass_kg), float(damping_Ns_per_m), float(gravity_m_s2))
    mats = _MATRICES.get(key)
    if mats is None:
        mats = _matrices(*key)
        if len(_MATRICES) >= 16:
            _MATRICES.pop(next(iter(_MATRICES)))
        _MATRICES[key] = mats
    timing = record_timing(acceleration_m_s2, dt_s, time_s)
    n_sub = mats.substeps(timing)  # refused before the kernel is loaded
    _warm_up()
    return _run(mats, bearing, timing, n_sub, bearing_layout)


def _run(mats: _Matrices, bearing, timing, n_sub: int, bearing_layout=None) -> BuildingMultisurfaceResponse:
    """The kernel on a checked record; ``n_sub`` from :meth:`_Matrices.substeps` (the public entry's)."""
    acc, dt, relative, t0 = timing.acceleration_m_s2, timing.dt_s, timing.relative_time_s, timing.t0_s
    system = mats.base
    rbar, mu, rim = bearing.elements()
    # static friction above kinetic on a single surface only (simulate_building_bearing refuses it on more)
    mu_static = np.ascontiguousarray(bearing.mu_static, dtype=np.float64) if rbar.size == 1 else mu
    tmat = bearing.surface_matrix()
    n, size, nf = acc.size, system.size, system.n_floors
    mon0 = np.ascontiguousarray(system.mon_modes[1])
    n_mon = mon0.shape[0]
    out_state, out_mon = np.empty((n, size)), np.empty((n, n_mon))
    out_r, out_energy = np.empty(n), np.empty((4, n))
    peak_max, peak_min = np.empty(n_mon), np.empty(n_mon)
    summary = np.zeros(_bmk.SUMMARY_SIZE)
    surf_peak = np.zeros(tmat.shape[0])
    first = np.empty(4 ** rbar.size)
    if relative is None:
        kernel_times = np.empty(0)
        phi, p_in, p_vis = mats.full_steps(dt / n_sub)
    else:
        kernel_times = np.ascontiguousarray(relative)
        phi = p_in = p_vis = np.zeros((1, size, size))
    capacity = 64 + n // 4
    while True:
        ev_time, ev_kind, ev_x = np.empty(capacity), np.empty(capacity, dtype=np.int8), np.empty(capacity)
        u = np.zeros(rbar.size)
        surf_peak[:] = 0.0
        start = time.perf_counter()
        _bmk.building_multisurface_kernel(
            acc, dt, kernel_times, mats.h_max, np.ascontiguousarray(system.a_modes[0]),
            np.ascontiguousarray(system.a_modes[1]), mats.da, phi, p_in, p_vis, np.ascontiguousarray(system.mon_modes[0]),
            mon0,
            mats.dmon, system.q_in, system.q_vis, system.ell_hold, system.weight_N, system.slab_mass_kg, nf, rbar,
            mu, mu_static, rim, tmat, system.AG, system.BG, system.F, out_state, out_mon, out_r, out_energy, peak_max,
            peak_min, ev_time, ev_kind, ev_x, summary, surf_peak, first, u)
        elapsed = time.perf_counter() - start
        n_events = int(summary[_bmk.S_N_EVENTS])
        if n_events <= capacity:
            break
        capacity = n_events + 16
    status = int(summary[_bmk.S_STATUS])
    message = "ok"
    if status & _bmk.STATUS_CHATTER:
        message = (f"chatter guard: more than {_bmk.MAX_EVENTS_PER_INTERVAL} events in one sample interval; the "
                   "bearing was held to the end of that interval")
    mass, weight, g = system.total_mass_kg, system.weight_N, system.gravity_m_s2
    x_b, v_b = out_state[:, 0], out_state[:, 1]
    u_last, ud_last = out_state[-1, 2:2 + nf], out_state[-1, 2 + nf:2 + 2 * nf]
    kinetic = 0.5 * system.slab_mass_kg * v_b[-1] ** 2 + 0.5 * float(system.masses_kg @ (v_b[-1] + ud_last) ** 2)
    strain = float(0.5 * u_last @ system.stiffness_matrix @ u_last)
    stored = float(weight * np.sum(u * u / (2.0 * rbar)))
    e_in, e_f, e_v, e_imp = (float(summary[k]) for k in (_bmk.S_E_INPUT, _bmk.S_E_FRICTION, _bmk.S_E_VISCOUS,
                                                         _bmk.S_E_IMPACT))
    # the bearing's own fields, read as the rigid block's model reads them
    ms_summary = np.zeros(_ms.SUMMARY_SIZE)
    for ours, theirs in ((_bmk.S_PEAK_R, _ms.S_PEAK_R), (_bmk.S_N_RIM_CONTACTS, _ms.S_N_RIM_CONTACTS),
                         (_bmk.S_N_ULTIMATE, _ms.S_N_ULTIMATE), (_bmk.S_IMPULSE, _ms.S_IMPULSE),
                         (_bmk.S_MAX_IMPACT_V, _ms.S_MAX_IMPACT_V), (_bmk.S_FIRST_ULTIMATE_T, _ms.S_FIRST_ULTIMATE_T)):
        ms_summary[theirs] = summary[ours]
    fields = response_fields(bearing, ms_summary, {"x": x_b, "v": v_b, "a": x_b, "r": out_r}, None, surf_peak,
                             first, u, rbar, g, t0, ev_time[:0], ev_kind[:0], ev_x[:0])
    bearing_fields = {key: fields[key] for key in (
        "surface_peak_displacement_m", "regimes", "n_rim_contacts", "ultimate_displacement_reached",
        "ultimate_displacement_m", "ultimate_first_time_s", "impact_impulse_m_s", "max_impact_velocity_m_s",
        "peak_force_per_weight", "element_displacement_m")}
    sl = {"x_b": 0, "v_b": 1, "force": 3 + 2 * nf}
    peak_force = float(max(peak_max[sl["force"]], -peak_min[sl["force"]]))
    return BuildingMultisurfaceResponse(
        # no equivalent single bearing: the paper's measures (which read ``system``) do not describe this one
        system=None, building=system, bearing=bearing, damping_per_mass=system.isolator_damping_Ns_per_m / mass,
        time_s=t0 + (dt * np.arange(n) if relative is None else relative),
        ground_acceleration_m_s2=acc,
        displacement_m=x_b.copy(), velocity_m_s=v_b.copy(),
        absolute_acceleration_m_s2=out_mon[:, sl["force"]] / mass,
        force_per_weight=out_r,
        event_time_s=t0 + ev_time[:n_events], event_kind=ev_kind[:n_events], event_displacement_m=ev_x[:n_events],
        peak_displacement_m=float(max(peak_max[0], -peak_min[0])),
        residual_displacement_m=float(x_b[-1]),
        peak_velocity_m_s=float(max(peak_max[1], -peak_min[1])),
        peak_transmitted_acceleration_m_s2=peak_force / mass,
        slip_time_s=float(summary[_bmk.S_SLIP_TIME]),
        n_events=n_events,
        energy_input_J_per_kg=e_in / mass, energy_friction_J_per_kg=e_f / mass,
        energy_viscous_J_per_kg=e_v / mass, energy_impact_J_per_kg=e_imp / mass,
        energy_kinetic_final_J_per_kg=kinetic / mass, energy_potential_final_J_per_kg=stored / mass,
        energy_strain_final_J_per_kg=strain / mass,
        energy_balance_error_J_per_kg=(e_in - (kinetic + strain + stored + e_f + e_v + e_imp)) / mass,
        energy_history_J_per_kg=out_energy / mass,
        floor_displacement_m=out_state[:, 2:2 + nf].copy(), floor_velocity_m_s=out_state[:, 2 + nf:2 + 2 * nf].copy(),
        floor_absolute_acceleration_m_s2=out_mon[:, 2 + nf:2 + 2 * nf].copy(),
        superstructure_shear_N=out_mon[:, 2 + 2 * nf].copy(), isolator_force_N=out_mon[:, sl["force"]].copy(),
        overturning_moment_Nm=out_mon[:, 4 + 2 * nf].copy(),
        peak_max=peak_max, peak_min=peak_min,
        status=status, message=message, solver_seconds=elapsed, substeps_per_interval=n_sub,
        n_series_pieces=int(summary[_bmk.S_N_PIECES]),
        bearing_layout=bearing_layout,
        impact_impulse_N_s=system.slab_mass_kg * bearing_fields["impact_impulse_m_s"],
        model_reason=f"a shear building on a {bearing.kind} bearing: the exact 1-D building on the series model",
        **bearing_fields,
    )


#: the keys a building run without a rim adds when its design gives a capacity (:func:`say_if_capacity_passed`)
UNBOUNDED_KEYS = ("ultimate_displacement_reached", "ultimate_displacement_m", "ultimate_first_time_s", "rim_modelled")


def say_if_capacity_passed(scene, result) -> None:
    """Say it when a building's bearing, run without a rim, reached its displacement capacity (in place).

    The 2-D building (``2d-building``) has no rim: past the capacity it runs on as if the concave plate
    were unbounded (under a pair alone the registry runs it again with the rim,
    :mod:`isolator.solver.planar_building_multisurface`; with a vertical or µ(v) this notice stays).  For a design with a ``[superstructure]`` and a ``displacement_capacity_m`` whose
    result carries no rim of its own (no ``ultimate_displacement_reached`` field), the result gains
    :data:`UNBOUNDED_KEYS` in its summary — ``ultimate_displacement_reached`` (peak ≥ the capacity d* =
    d R_eff/R), the capacity, ``ultimate_first_time_s``, the first sample with |X| ≥ d* (the crossing
    lies in the sample interval before it; the sample after the largest when no sample passes d*), and
    ``rim_modelled`` false (the capacity rows then read the peak beyond d*, not a slab held at a rim) —
    and, when reached, a notice in ``solver_status`` (as the chatter guard says itself): the response
    after that time is that of an unbounded plate, not modelled.  ``simulate``, ``report``, ``batch``
    and ``review`` show ``solver_status``; the review's capacity rows fail on the peak and name the notice.
    """
    design = scene.design
    capacity = getattr(design, "displacement_capacity_m", None)
    if (capacity is None or getattr(design, "superstructure", None) is None
            or hasattr(result, "ultimate_displacement_reached")):
        return
    bearing = getattr(design, "bearing", None)
    d = float(capacity) if bearing is None else float(bearing.ultimate_displacement_m)
    if not math.isfinite(d):
        return
    x = np.asarray(result.displacement_m, dtype=np.float64)
    size = np.hypot(x[:, 0], x[:, 1]) if x.ndim == 2 else np.abs(x)
    reached = bool(result.peak_displacement_m >= d)
    first = None
    if reached:
        past = np.flatnonzero(size >= d)
        k = int(past[0]) if past.size else min(int(np.argmax(size)) + 1, size.size - 1)
        first = float(result.time_s[k])
    result.ultimate_displacement_reached = reached
    result.ultimate_displacement_m = d
    result.ultimate_first_time_s = first
    result.rim_modelled = False  # the review's capacity rows read a peak past d*, not a slab held at a rim
    result.EXTRA_SUMMARY_KEYS = tuple(result.EXTRA_SUMMARY_KEYS) + UNBOUNDED_KEYS
    if reached:
        notice = (f"the bearing reached its displacement capacity {d:.4g} m by t = {first:.4g} s (peak "
                  f"{result.peak_displacement_m:.4g} m): {result.model or 'this model'} has no rim, so the response "
                  "after that time is that of an unbounded plate, not modelled")
        result.message = notice if result.message == "ok" else f"{result.message}; {notice}"


__all__ = ["MODEL_NAME", "UNBOUNDED_KEYS", "BuildingMultisurfaceResponse", "rerun_past_capacity", "say_if_capacity_passed",
           "scene_needs", "simulate_building_bearing", "simulate_scene", "single_with_rim"]
