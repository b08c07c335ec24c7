r"""A linear shear building on a double or triple friction pendulum under a pair (model ``2d-building-multisurface``).

The floors and the base slab are the 2-D building's (:mod:`isolator.solver.planar_building`: a shear building per
direction, classical modal damping, the same matrices); the isolation plane is the 2-D series model of Fenz &
Constantinou with its rims and ultimate displacement (:mod:`isolator.solver.planar_multisurface`, the implicit
steps of :mod:`isolator.solver.planar_multisurface_stepper`).  One backward-Euler step of the slab on the bearing
carries the floors exactly: over the step the slab's acceleration is constant, the floors' modes are propagated in
closed form, and their reaction enters the step as an effective slab mass and a modified mean acceleration
(:mod:`isolator.solver.planar_building_multisurface_kernel`).  The local error is controlled on the slab and on the
floors (``HISTORY_SHARE`` of the relative tolerance ``step_tol``, the floors on ``FLOOR_SCALE`` of the slab's peaks);
the error is measured in docs/building.md.

A vertical component (model ``2d-building-multisurface+vertical``): every surface carries N = M n(t), n = g + a_z
(the floors and the slab move with the ground vertically; the floors are horizontal shear springs the vertical does
not load), each implicit step takes n at its mean and books the vertical's work as the rigid block's steps
(docs/multisurface.md, "The vertical"); the bearings' axial loads take its share P_k,g a_z/g as the 2-D building's.

Not modelled, each refused in one line: the bearing lifting off (n ≤ 0), µ(v), a damping ratio ≥ 1 (or differing between
modes), static friction above kinetic on a double or triple (a single surface's µs is modelled: held at rest inside µs, sliding at µk).

Outputs: the 2-D building's keys (:class:`~isolator.solver.planar_building.PlanarBuildingResponse`: resultant story
drifts, floor accelerations, the first story's shear, the overturning moments and bearing loads — their extremes
located inside the steps; the base shear while sliding the peak of each step's parabola through its start, half
and end) and the bearing's
(:class:`~isolator.solver.building_multisurface.BuildingMultisurfaceResponse`'s: surface peaks, regimes, rim
contacts, the ultimate and its impulse).
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass

import numpy as np

from isolator.errors import DesignError, InvalidSystemError, RecordInputError, SolverError
from isolator.solver import multisurface_kernel as _ms
from isolator.solver import planar_building
from isolator.solver import planar_building_multisurface_kernel as _bk
from isolator.solver import planar_multisurface_kernel as _pm
from isolator.solver import planar_multisurface_stepper as _ps
from isolator.solver.building import naming_design
from isolator.solver.building_multisurface import BEARING_KEYS, BearingFields, rerun_past_capacity, single_with_rim
from isolator.solver.multisurface import response_fields
from isolator.solver.multisurface_series import STATIC_FRICTION_REASON
from isolator.solver.notice import note_if_slow
from isolator.solver.planar_building import PlanarBuildingResponse, planar_building_system
from isolator.solver.planar_multisurface import (
    DEFAULT_STEP_TOL,
    RIM_BALANCE_TOL,
    element_groups,
    normal_per_mass,
    speed_scales,
)
from isolator.solver.record import sample_clock
from isolator.units import STANDARD_GRAVITY

MODEL_NAME = "2d-building-multisurface"
#: The model a building on a single pendulum with a capacity runs first under a pair (the 2-D building).
RIM_FIRST_MODEL = planar_building.MODEL_NAME
#: the floors' error norm's floors, as multiples of the slab's (their modal displacement's and velocity's error scaled
#: on this share of the slab's peaks).  The floors' relative motion is ~1/100 of the slab's, and it inherits the slab's
#: velocity error at an impact at the ultimate (the floors keep their absolute velocities) and passes it back through
#: the stories' stiffness once the slab leaves the ultimate: on the slab's full scale (1.0) Kobe KJM ×1.6 on the small
#: TFP erred by 4.0e-9 of the peak at step_tol 1e-9 (docs/building.md, "The history to step_tol")
FLOOR_SCALE = 0.3
#: the share of ``step_tol`` the steps' local error is held to: the local error of the two halves bounds each step, the
#: accepted state is their Richardson combination, and its global error is ∝ step_tol with a constant of the case's
#: (1.1 on Kobe before its impact, 1.4 on NWH360 on the double; docs/building.md, "The history to step_tol")
HISTORY_SHARE = 0.5


@dataclass(kw_only=True)
class PlanarBuildingMultisurfaceResponse(BearingFields, PlanarBuildingResponse):
    """Response of a shear building on a double or triple friction pendulum to a pair (``2d-building-multisurface``).

    The fields of :class:`~isolator.solver.planar_building.PlanarBuildingResponse` (the floors' peaks and the signed
    rows' extremes located inside the implicit steps, the base shear at their ends and watch points) and the
    bearing's, as in
    :class:`~isolator.solver.building_multisurface.BuildingMultisurfaceResponse`.  The balance ``input = kinetic +
    strain + stored + friction + viscous + impact`` holds to ``energy_balance_error_J_per_kg`` (the steps' own
    numerical dissipation, measured in docs/building.md).
    """

    EXTRA_SUMMARY_KEYS = PlanarBuildingResponse.EXTRA_SUMMARY_KEYS + BEARING_KEYS

    n_steps: int = 0
    #: the steps accepted at the kernel's shortest length (H_MIN_FRACTION of the sample interval) with their error
    #: estimate above the tolerance: not zero, the history's error is not held to ``step_tol`` there
    n_steps_at_floor: int = 0
    step_tol: float = DEFAULT_STEP_TOL
    model: str = MODEL_NAME
    model_reason: str = ""
    #: True when the registry's first run (``2d-building``, an unbounded plate) reached the single pendulum's
    #: capacity and the scene was run again here with its rim
    rerun: bool = False


def single_with_rim_in_plane(scene):
    """The single pendulum with its rim under a building that a pair describes, or None.

    A design with a ``[superstructure]``, a ``displacement_capacity_m`` and one surface, a restoring stiffness, two
    horizontal components, constant friction and no vertical (what ``2d-building`` runs and this model can run
    again with the rim): :func:`isolator.solver.building_multisurface.single_with_rim` of the scene seen along one
    component (the surface does not depend on the record)."""
    if not scene.has_y or scene.has_z or scene.velocity_dependent:
        return None
    return single_with_rim(dataclasses.replace(scene, ay_m_s2=None))


def isotropic(superstructure) -> bool:
    """The floors' stiffness (and so their damping) is the same along x and y (the steps' closed isotropic form;
    else Ψ's diagonal metric)."""
    return bool(np.array_equal(superstructure.stiffness_matrix("x"), superstructure.stiffness_matrix("y")))


def scene_needs(scene) -> tuple[str, str] | None:
    """``(model, reason)`` for a design with a ``[superstructure]`` on a double or triple bearing under a pair.

    A building on a single pendulum with a capacity under a pair (:func:`single_with_rim_in_plane`):
    ``2d-building`` first, **and the choice depends on its result** — when its peak reaches the capacity the scene
    is run again here with the rim (:func:`simulate_scene`)."""
    design = scene.design
    bearing = getattr(design, "bearing", None)
    if getattr(design, "superstructure", None) is None or not scene.has_y:
        return None
    if bearing is None or bearing.is_simple:
        single = single_with_rim_in_plane(scene)
        if single is None:
            return None
        return RIM_FIRST_MODEL, planar_building.scene_reason(has_y=True, has_z=False, velocity_dependent=False) + (
            f"; a displacement capacity of {single.ultimate_displacement_m:.4g} m: if the peak reaches it, the run is "
            f"redone with the rim ({MODEL_NAME}), a choice made on the result")
    floors = getattr(design.superstructure, "floors", None)
    if floors is None:
        return None  # not a superstructure this model reads (2d-multisurface refuses it in one line)
    vertical = " and a vertical (n = g + a_z on every surface)" if scene.has_z else ""
    return MODEL_NAME + ("+vertical" if scene.has_z else ""), (
        f"a {len(floors)}-story superstructure on a {bearing.kind} friction pendulum ({len(bearing.surfaces)} "
        f"surfaces) under two horizontal components{vertical}: the 2-D series model with rims by implicit steps, the "
        "floors propagated exactly within each step (µ(v) is refused)")


def _refusal(scene) -> str | None:
    """One line naming what this model does not take for the scene, or None."""
    kind = scene.design.bearing.kind
    if scene.velocity_dependent or any(s.rate_s_per_m is not None and s.mu_slow < s.mu_fast
                                       for s in scene.design.bearing.surfaces):
        return f"µ(v) on a {kind} bearing under a [superstructure] is not modelled (constant µ per surface)"
    return None


def simulate_scene(scene) -> PlanarBuildingMultisurfaceResponse:
    """The 2-D response of the scene's building on its multi-surface bearing (:func:`simulate_building_bearing_pair`).

    Raises
    ------
    DesignError
        µ(v) (not modelled).
    SolverError
        The vertical lifts the bearing off (n = g + a_z ≤ 0).
    InvalidSystemError
        Floors whose damping ratio differs between modes or is ≥ 1.
    """
    design = scene.design
    if design.bearing is None or design.bearing.is_simple:
        single = single_with_rim_in_plane(scene)
        if single is None:
            raise LookupError("this model takes a building on a single pendulum only with a capacity (scene_needs)")
        return rerun_past_capacity(scene, single, planar_building.simulate_scene, simulate_on, RIM_FIRST_MODEL,
                                   f"{MODEL_NAME} under the pair: implicit steps, plastic impact at the capacity, "
                                   "sliding along the rim; static friction at rest, kinetic sliding")
    why = _refusal(scene)
    if why is not None:
        raise DesignError(f"{design.source}: {why}")
    return simulate_on(scene, design.bearing)


def simulate_on(scene, bearing, step_tol: float = DEFAULT_STEP_TOL) -> PlanarBuildingMultisurfaceResponse:
    """The scene's building (its floors, mass, damping, layout) on ``bearing``, under its pair."""
    design = scene.design
    iso = {key: value for key, value in scene.isolator.items() if value is not None}
    g = float(iso.get("gravity_m_s2", design.gravity_m_s2))
    mass = design.mass_kg
    ax = np.asarray(scene.ax_m_s2, dtype=np.float64)
    ay = np.zeros_like(ax) if scene.ay_m_s2 is None else scene.ay_m_s2
    with naming_design(design):
        return simulate_building_bearing_pair(
            ax, ay, scene.dt_s, time_s=scene.time_s, superstructure=design.superstructure, bearing=bearing,
            total_mass_kg=mass, damping_Ns_per_m=mass * float(iso.get("damping_per_mass", 0.0)), gravity_m_s2=g,
            bearing_layout=design.bearing_layout, step_tol=step_tol, az_m_s2=scene.az_m_s2 if scene.has_z else None)


def static_friction(bearing, mu):
    """The groups' static friction: a single surface's ``mu_static`` (at least its kinetic), else ``mu`` itself.

    Raises
    ------
    ValueError
        Static friction above kinetic on a double or triple (not modelled, as in ``1d-building-multisurface``).
    """
    mu_static = np.asarray(bearing.mu_static, dtype=np.float64)
    if len(bearing.surfaces) > 1:
        if np.any(mu_static != np.asarray(bearing.mu_kinetic, dtype=np.float64)):
            raise ValueError(f"static friction above kinetic on the bearing is not modelled: {STATIC_FRICTION_REASON}")
        return mu.copy()
    return np.maximum(np.full(mu.size, float(mu_static[0])), mu)


def modal_rows(building, bearing_layout):
    """The floors' modes and watched rows of a 2-D building system (:func:`planar_building_system`), per direction.

    Returns
    -------
    tuple
        ``(ω [rad/s] (2, n), ζ, Γ̃ = φᵀ M_s 1/√M (2, n), lin, sig)``: ``lin[d]`` (2n + 1, 2n) maps direction d's
        modal state (q̃, q̃') to its drifts, floors' absolute accelerations and first story's shear [N];
        ``sig`` (2 + bearings, 2, 2n) maps both directions' states to the overturning moments about the two
        axes [N·m] and the bearings' axial load changes [N] (as the 2-D building's signed rows).

    Raises
    ------
    InvalidSystemError
        A damping ratio that differs between modes or is ≥ 1.
    """
    from scipy.linalg import eigh

    masses = building.masses_kg
    n = masses.size
    root = math.sqrt(building.total_mass_kg)
    n_bearings = 0 if bearing_layout is None else bearing_layout.n_bearings
    om = np.zeros((2, n))
    gam = np.zeros((2, n))
    lin = np.zeros((2, 2 * n + 1, 2 * n))
    sig = np.zeros((2 + n_bearings, 2, 2 * n))
    zeta = 0.0
    accel = -np.diag(1.0 / masses)
    for d, direction in enumerate(("x", "y")):
        k_d = building.stiffness_matrices[d]
        c_d = building.damping_matrices[d]
        eigenvalues, phi = eigh(k_d, np.diag(masses))
        om[d] = np.sqrt(np.maximum(eigenvalues, 0.0))
        # ζ of the classical damping: C = M Φ diag(2ζω) Φᵀ M
        zetas = np.diag(phi.T @ c_d @ phi) / (2.0 * om[d])
        if d == 0:
            zeta = float(zetas[0])
        if not (np.allclose(zetas, zeta, rtol=1e-9, atol=0.0) and 0.0 <= zeta < 1.0 and np.all(om[d] > 0.0)):
            raise InvalidSystemError(f"{MODEL_NAME} takes floors with one damping ratio below 1 in every mode (both "
                                     "directions)")
        gam[d] = phi.T @ masses / root
        shape = phi * root  # u = shape q̃
        for i in range(n):
            lin[d, i, :n] = shape[i] - (shape[i - 1] if i > 0 else 0.0)
        lin[d, n:2 * n, :n] = accel @ k_d @ shape
        lin[d, n:2 * n, n:] = accel @ c_d @ shape
        lin[d, 2 * n, :n] = k_d.sum(axis=0) @ shape
        lin[d, 2 * n, n:] = c_d.sum(axis=0) @ shape
        # Σ H_i (K u + C u̇)_i = −Σ m_i H_i (floor i's absolute acceleration): the overturning moment of one direction
        moment = np.concatenate([building.floor_heights_m @ k_d @ shape, building.floor_heights_m @ c_d @ shape])
        sig[d, d] = moment
        if n_bearings:
            coefficients = bearing_layout.overturning_coefficients(direction)
            for j in range(n_bearings):
                sig[2 + j, d] = coefficients[j] * moment
    return om, zeta, gam, lin, sig


_READY = False


def _warm_up() -> None:
    global _READY
    if _READY:
        return
    from isolator.bearing import Bearing, Surface
    from isolator.superstructure import Floor, Superstructure

    with note_if_slow("compiling the solver of a building on a multi-surface bearing under a pair (its first use "
                      "after installation takes a minute or so; the machine code is cached for later runs)"):
        s = Superstructure(floors=(Floor(1.0, 1.0, 100.0, 100.0),), damping_ratio=0.05, gravity_m_s2=9.81)
        b = Bearing(kind="double", surfaces=tuple(Surface(radius_m=1.0, height_m=0.0, mu_kinetic=mu, mu_static=mu,
                                                          displacement_capacity_m=0.01) for mu in (0.03, 0.05)))
        _READY = True
        simulate_building_bearing_pair(np.array([0.0, 5.0, -5.0]), np.array([0.0, 2.0, 1.0]), 0.01,
                                       superstructure=s, bearing=b, total_mass_kg=2.0)


def simulate_building_bearing_pair(ax_m_s2, ay_m_s2, dt_s: float | None = None, *, time_s=None, superstructure,
                                   bearing, total_mass_kg: float, damping_Ns_per_m: float = 0.0,
                                   gravity_m_s2: float = STANDARD_GRAVITY, bearing_layout=None,
                                   step_tol: float = DEFAULT_STEP_TOL, az_m_s2=None) -> PlanarBuildingMultisurfaceResponse:
    """Response of a shear building on a multi-surface friction pendulum to two horizontal components.

    Parameters
    ----------
    ax_m_s2, ay_m_s2 : array_like
        Ground acceleration along x and y [m/s²], linear between samples.
    dt_s : float, optional
        Sample interval [s] (or ``time_s``).
    superstructure : isolator.superstructure.Superstructure
    bearing : isolator.bearing.Bearing
        A double or triple (or a single with its rim) bearing; its surfaces' kinetic friction, and on a single
        surface its static friction (held at rest while the force the slab needs is inside µs, sliding at µk).
    total_mass_kg, damping_Ns_per_m, gravity_m_s2
        As for :func:`isolator.solver.planar_building.simulate_planar_building`.
    bearing_layout : isolator.superstructure.BearingLayout, optional
        For the bearings' axial loads.
    step_tol : float
        Relative tolerance of the history: the implicit steps' local error is held to ``HISTORY_SHARE`` of it (of
        the peak displacement and velocity of the slab, and ``FLOOR_SCALE`` of them for the floors' modes); on the
        measured cases the history is within step_tol of the peak at 1e-9 (docs/building.md).
    az_m_s2 : array_like, optional
        Vertical ground acceleration [m/s²] (up positive), linear between samples: every surface carries
        N = M (g + a_z) (model ``2d-building-multisurface+vertical``); the bearings' loads take P_k,g a_z/g.

    Returns
    -------
    PlanarBuildingMultisurfaceResponse

    Raises
    ------
    SolverError
        The steps could not finish (their guards: a work bound per sample interval, Newton's failure at the
        misaligned ultimate, an energy balance open by more than ``RIM_BALANCE_TOL`` with rims reached); the
        vertical lifts the bearing off (n = g + a_z ≤ 0 at a sample: not modelled).
    """
    _warm_up()
    if not (math.isfinite(step_tol) and 1e-12 <= step_tol <= 1e-2):
        raise ValueError(f"step_tol must be in [1e-12, 1e-2], got {step_tol!r}")
    ax = np.ascontiguousarray(ax_m_s2, dtype=np.float64)
    ay = np.ascontiguousarray(ay_m_s2, dtype=np.float64)
    if ax.ndim != 1 or ax.size < 2 or ax.shape != ay.shape:
        raise RecordInputError("a pair needs two components of the same length (at least two samples)")
    if not (np.all(np.isfinite(ax)) and np.all(np.isfinite(ay))):
        raise RecordInputError("acceleration holds NaN or infinite values")
    t0, local = sample_clock(ax.size, dt_s, time_s)
    mass = float(total_mass_kg)
    g = float(gravity_m_s2)
    az = None
    if az_m_s2 is not None:
        az = np.ascontiguousarray(az_m_s2, dtype=np.float64)
        if az.shape != ax.shape or not np.all(np.isfinite(az)):
            raise RecordInputError(f"the vertical needs {ax.size} finite samples (the horizontals'), got {az.size}")
    nz = normal_per_mass(az, g, t0, local, f"the {bearing.kind} bearing under the building")
    building = planar_building_system(superstructure, total_mass_kg=mass, stiffness_N_per_m=0.0, mu_static=0.0,
                                      damping_Ns_per_m=float(damping_Ns_per_m), gravity_m_s2=g)
    om, zeta, gam, lin, sig = modal_rows(building, bearing_layout)
    c = float(damping_Ns_per_m) / mass
    rb, mu, rim, members = element_groups(bearing, split_rims=True)
    mu_s = static_friction(bearing, mu)
    tmat = bearing.surface_matrix()
    # the error norm's floors as the rigid block's steps build them (planar_multisurface), for the stiffest group
    t_scale, vref = speed_scales(ax, ay, local, nz, rb, mu, c)
    scales = np.array([1e-3 * vref * t_scale, 1e-3 * vref, 1e-3 * vref * t_scale, 1e-3 * vref, FLOOR_SCALE])
    n = ax.size
    ny = _ps.carry_slot(rb.size) + 1 + 4 * om.shape[1]
    out_y = np.empty((n, ny))
    out_r = np.empty((n, 2))
    peaks = np.zeros(lin.shape[1] + 3)
    sig_max = np.zeros(sig.shape[0])
    sig_min = np.zeros(sig.shape[0])
    summary = np.zeros(_ps.S_SIZE_STEPS)
    surf_peak = np.zeros(tmat.shape[0])
    first = np.empty(1 << (2 * members.shape[0]))
    ub = np.zeros((rb.size, 2))
    start = time.perf_counter()
    # the vertical's share of the signed rows: a bearing's P_k,g a_z/g (the 2-D building's), none for the moments
    sig_z = np.zeros(sig.shape[0])
    if bearing_layout is not None:
        sig_z[2:] = np.asarray(bearing_layout.gravity_loads_N) / building.gravity_m_s2
    tol = float(step_tol) * HISTORY_SHARE
    _bk.planar_building_multisurface_kernel(local, ax, ay, nz, c, rb, mu, rim, members, tmat, om, zeta, gam, lin, sig,
                                            tol, scales, out_y, out_r, peaks, sig_max, sig_min, summary,
                                            surf_peak, first, ub, mu_s, np.zeros(ax.size) if az is None else az, sig_z)
    elapsed = time.perf_counter() - start
    status = int(summary[_pm.S_STATUS])
    fail_t = t0 + float(summary[_pm.S_FAIL_T])
    on_rims = int(summary[_ps.S_FAIL_RIMS])
    if status & _ps.STATUS_WORK:
        raise SolverError(f"the implicit steps of {MODEL_NAME} needed more than {_ps.work_bound(tol):.0f} force "
                          f"evaluations in one sample interval at t = {fail_t:.6g} s ({on_rims} of {rb.size} slider "
                          "groups on their rims); the run stops there")
    if status & _ps.STATUS_UNSOLVED:
        raise SolverError(f"the implicit steps of {MODEL_NAME} found no force at t = {fail_t:.6g} s (Newton did not "
                          f"converge; {on_rims} of {rb.size} slider groups on their rims: not resolved)")
    if status:
        raise SolverError(f"the implicit steps of {MODEL_NAME} could not finish at t = {fail_t:.6g} s (status "
                          f"{status}: a rim guard or more than {_ps.MAX_STEPS_PER_INTERVAL} steps in one interval)")
    nm = om.shape[1]
    f0 = _ps.carry_slot(rb.size) + 1
    x_b = out_y[:, _ps.Y_X:_ps.Y_X + 2].copy()
    v_b = out_y[:, _ps.Y_V:_ps.Y_V + 2].copy()
    modal = [out_y[:, f0 + 2 * nm * d:f0 + 2 * nm * (d + 1)] for d in range(2)]  # (q̃, q̃') per direction
    shapes = [np.cumsum(lin[d, :nm, :nm], axis=0) for d in range(2)]  # the drifts' rows summed: u = shape q̃
    u = np.stack([modal[d][:, :nm] @ shapes[d].T for d in range(2)], axis=2)
    ud = np.stack([modal[d][:, nm:] @ shapes[d].T for d in range(2)], axis=2)
    rows = np.stack([modal[d] @ lin[d].T for d in range(2)], axis=2)  # (N, 2n + 1, 2)
    moments = np.stack([modal[d] @ sig[d, d] for d in range(2)], axis=1)
    final = out_y[-1]
    n_end = float(nz[-1])  # n at the end: the bearing's stored energy n Σ|ū|²/(2R̄)
    e_total = float(_bk.total_energy(final, n_end, rb, om, gam))
    elements = np.array([members[i, 1] / rb[int(members[i, 0])] * ub[int(members[i, 0])]
                         for i in range(members.shape[0])])
    rbar = np.array([members[i, 1] for i in range(members.shape[0])])
    stored = float(n_end * np.sum(np.sum(elements * elements, axis=1) / (2.0 * rbar)))
    kinetic = 0.5 * float(v_b[-1] @ v_b[-1]) + sum(
        float(v_b[-1, d] * (gam[d] @ modal[d][-1, nm:]) + 0.5 * modal[d][-1, nm:] @ modal[d][-1, nm:]) for d in range(2))
    strain = e_total - stored - kinetic
    e_in, e_f, e_v, e_imp = (float(summary[k]) for k in (_pm.S_E_IN, _pm.S_E_F, _pm.S_E_V, _ps.S_E_IMP))
    balance = e_in - (e_total + e_f + e_v + e_imp)
    if summary[_ps.S_N_RIM_CONTACTS] > 0 and e_in > 0.0 and abs(balance) > RIM_BALANCE_TOL * e_in:
        raise SolverError(f"the implicit steps of {MODEL_NAME} reached the rims with the energy balance open by "
                          f"{abs(balance) / e_in:.1e} of the input (limit {RIM_BALANCE_TOL:g}); not answered")
    # the bearing's fields, read as the 1-D models read them (magnitudes for the 1-D reader; the vectors kept)
    ms_summary = np.zeros(_ms.SUMMARY_SIZE)
    for ours, theirs in ((_ps.S_PEAK_R, _ms.S_PEAK_R), (_ps.S_N_RIM_CONTACTS, _ms.S_N_RIM_CONTACTS),
                         (_ps.S_N_ULTIMATE, _ms.S_N_ULTIMATE), (_ps.S_IMPULSE, _ms.S_IMPULSE),
                         (_ps.S_MAX_IMPACT_V, _ms.S_MAX_IMPACT_V), (_ps.S_FIRST_ULT, _ms.S_FIRST_ULTIMATE_T)):
        ms_summary[theirs] = summary[ours]
    size = np.hypot(x_b[:, 0], x_b[:, 1])
    fields = response_fields(bearing, ms_summary, {"x": size, "v": size, "a": size, "r": size}, None, surf_peak,
                             first, np.hypot(elements[:, 0], elements[:, 1]), rbar, n_end, t0, np.empty(0),
                             np.empty(0, dtype=np.int8), np.empty(0))
    bearing_fields = {key: fields[key] for key in (
        "surface_peak_displacement_m", "regimes", "n_rim_contacts", "ultimate_displacement_reached",
        "ultimate_displacement_m", "ultimate_first_time_s", "impact_impulse_m_s", "max_impact_velocity_m_s",
        "peak_force_per_weight")}
    n_floors = nm
    force = nz[:, None] * out_r + c * v_b
    peak_resultants = np.zeros(2 * n_floors + 4)
    peak_resultants[:2 * n_floors + 3] = peaks[:2 * n_floors + 3]
    peak_resultants[3 + 2 * n_floors] = peaks[-1] * mass
    return PlanarBuildingMultisurfaceResponse(
        system=None, building=building, bearing=bearing, damping_per_mass=c,
        time_s=t0 + local, ground_acceleration_m_s2=np.column_stack((ax, ay)),
        displacement_m=x_b, velocity_m_s=v_b, absolute_acceleration_m_s2=force,
        force_per_weight=out_r.copy(),
        event_time_s=np.empty(0), event_kind=np.empty(0, dtype=np.int8), event_displacement_m=np.empty((0, 2)),
        peak_displacement_m=float(peaks[0]), residual_displacement_m=float(size[-1]),
        residual_displacement_x_m=float(x_b[-1, 0]), residual_displacement_y_m=float(x_b[-1, 1]),
        peak_velocity_m_s=float(peaks[1]), peak_transmitted_acceleration_m_s2=float(peaks[-1]),
        slip_time_s=float(summary[_pm.S_SLIP_TIME]), n_events=0,
        energy_input_J_per_kg=e_in, energy_friction_J_per_kg=e_f, energy_viscous_J_per_kg=e_v,
        energy_impact_J_per_kg=e_imp, energy_kinetic_final_J_per_kg=kinetic, energy_potential_final_J_per_kg=stored,
        energy_strain_final_J_per_kg=strain, energy_balance_error_J_per_kg=balance,
        energy_history_J_per_kg=np.stack([out_y[:, _ps.Y_EIN], out_y[:, _ps.Y_EF], out_y[:, _ps.Y_EV]]),
        floor_displacement_m=u, floor_velocity_m_s=ud,
        floor_absolute_acceleration_m_s2=rows[:, n_floors:2 * n_floors, :].copy(),
        superstructure_shear_N=rows[:, 2 * n_floors, :].copy(), isolator_force_N=force * mass,
        overturning_moment_Nm=moments, peak_resultants=peak_resultants,
        signed_max=sig_max.copy(), signed_min=sig_min.copy(),
        status=status, message="ok", solver_seconds=elapsed, bearing_layout=bearing_layout,
        n_steps=int(summary[_pm.S_N_STEPS]), n_steps_at_floor=int(summary[_pm.S_STEPS_MULTI]), step_tol=float(step_tol),
        impact_impulse_N_s=building.slab_mass_kg * bearing_fields["impact_impulse_m_s"],
        element_displacement_m=elements,
        model=MODEL_NAME + ("+vertical" if az is not None else ""), vertical_acceleration_m_s2=az,
        model_reason=(f"a shear building on a {bearing.kind} bearing under a pair"
                      + (" and a vertical (n = g + a_z)" if az is not None else "")
                      + f": implicit steps, history tolerance {step_tol:g} (local error {tol:g}), the floors exact "
                        "within each step"),
        **bearing_fields,
    )


__all__ = ["MODEL_NAME", "PlanarBuildingMultisurfaceResponse", "modal_rows", "scene_needs",
           "simulate_building_bearing_pair", "simulate_on", "simulate_scene", "isotropic", "single_with_rim_in_plane"]
