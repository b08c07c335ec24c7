r"""A linear shear building on the friction isolation plane, 1-D: exact response to a record.

The model (issue 22, ``docs/building.md``).  Along one horizontal direction, with x_b the
base slab's displacement relative to the ground and u the floors' displacements relative to
the slab (M, K_s, C_s of :class:`isolator.superstructure.Superstructure`, m_b = M_total − Σ m_i):

.. math::

    M (\ddot u + \mathbf 1 (\ddot x_b + a_g)) + C_s \dot u + K_s u &= 0 \\
    m_b (\ddot x_b + a_g) &= \mathbf 1^T (K_s u + C_s \dot u) - K x_b - c \dot x_b - f

K = W/R for a pendulum (or the design's spring), c the optional dashpot, and f the friction
force with normal force W = g M_total: f = µk W sign(ẋ_b) while sliding; while the plane is
stuck (ẋ_b = 0, the floors respond as the fixed-base structure) the friction holds
D = −m_b a_g − K x_b + 1ᵀ(K_s u + C_s u̇) as long as |D| ≤ µs W.

Between events the system is linear with a forcing linear in time, so it is propagated
exactly (:mod:`isolator.solver.building_kernel`): precomputed matrix exponentials of the
augmented system for full sub-steps, the Taylor series of the same exact solution on its
Krylov vectors for partial pieces, events (stop, stick or reversal, break-away) and interior
peaks located as roots of those series to rounding.  Sub-steps are bounded by the fastest
rate of the system (‖Ã‖ h ≤ 0.75 after balancing), so stiff floors cost a few matrix-vector
products per sample, never accuracy.

Outputs (:meth:`BuildingResponse.summary`): the isolator's response as for the rigid block
(``peak_displacement_m`` … of the slab) and ``story_drift_m``, ``story_drift_ratio``,
``floor_peak_acceleration_m_s2``, ``superstructure_shear_coefficient`` (peak of
1ᵀ(K_s u + C_s u̇) over W_s), ``base_shear_coefficient`` (peak isolator force over W) and,
with a bearing layout, the bearings' axial loads.
"""

from __future__ import annotations

import math
import time
from contextlib import contextmanager
from dataclasses import dataclass, field

import numpy as np

from isolator.errors import InvalidSystemError
from isolator.solver import building_kernel as _bk
from isolator.solver.base import SolverResult
from isolator.solver.record import AlongOneComponent, building_substeps, record_timing
from isolator.solver.system import System
from isolator.units import STANDARD_GRAVITY

#: The solver model's name in the registry.
MODEL_NAME = "1d-building"
MODEL_REASON = "a superstructure above the isolation plane, one horizontal component: the exact 1-D building"


@dataclass
class BuildingSystem:
    """The matrices of one building on its isolation plane, for one direction (SI units)."""

    n_floors: int
    masses_kg: np.ndarray
    slab_mass_kg: float
    total_mass_kg: float
    floor_heights_m: np.ndarray
    story_heights_m: np.ndarray
    stiffness_matrix: np.ndarray  #: K_s [N/m]
    damping_matrix: np.ndarray  #: C_s [N·s/m]
    isolator_stiffness_N_per_m: float
    isolator_damping_Ns_per_m: float
    mu_static: float
    mu_kinetic: float
    gravity_m_s2: float
    a_modes: np.ndarray = field(repr=False)
    mon_modes: np.ndarray = field(repr=False)
    q_in: np.ndarray = field(repr=False)
    q_vis: np.ndarray = field(repr=False)
    ell_hold: np.ndarray = field(repr=False)
    fastest_rate_per_s: float = 0.0  #: ‖Ã‖₁ of the balanced matrices [1/s]
    #: propagators and Taylor rows computed for this system (per sub-step length), reused by later runs
    cache: dict = field(default_factory=dict, repr=False)

    @property
    def weight_N(self) -> float:
        return self.total_mass_kg * self.gravity_m_s2

    @property
    def max_step_s(self) -> float:
        """The longest sub-step, THETA over the fastest rate (‖Ã‖ h ≤ THETA) [s]; inf for a rate of 0."""
        return _bk.THETA / self.fastest_rate_per_s if self.fastest_rate_per_s > 0 else math.inf

    def substeps(self, timing) -> int:
        """Sub-steps per sample interval of a record (:class:`~isolator.solver.record.RecordTiming`); refuses
        more than MAX_SUBSTEPS_PER_INTERVAL (:func:`~isolator.solver.record.building_substeps`)."""
        return building_substeps(timing.dt_s, timing.relative_time_s, self.max_step_s,
                                 f"the building's fastest rate {self.fastest_rate_per_s:.3g} 1/s")

    @property
    def superstructure_weight_N(self) -> float:
        return float(self.masses_kg.sum()) * self.gravity_m_s2

    @property
    def size(self) -> int:
        return 2 * self.n_floors + 5

    # positions in the augmented state w
    XB, VB = 0, 1

    @property
    def AG(self) -> int:
        return 2 * self.n_floors + 2

    @property
    def BG(self) -> int:
        return 2 * self.n_floors + 3

    @property
    def F(self) -> int:
        return 2 * self.n_floors + 4


#: monitored functionals: x_b, v_b, n drifts, n floor absolute accelerations, V_s, F_isolator, overturning moment
def _monitor_slices(n: int) -> dict:
    return {"x_b": 0, "v_b": 1, "drift": slice(2, 2 + n), "floor_acc": slice(2 + n, 2 + 2 * n),
            "shear": 2 + 2 * n, "isolator_force": 3 + 2 * n, "moment": 4 + 2 * n}


def building_system(superstructure, *, total_mass_kg: float, stiffness_N_per_m: float, mu_static: float,
                    mu_kinetic: float | None = None, damping_Ns_per_m: float = 0.0,
                    gravity_m_s2: float = STANDARD_GRAVITY, direction: str = "x") -> BuildingSystem:
    """Assemble the stuck and sliding system matrices of the building on its isolation plane.

    Parameters
    ----------
    superstructure : isolator.superstructure.Superstructure
    total_mass_kg : float
        The whole isolated mass (floors + slab) [kg].
    stiffness_N_per_m : float
        Isolator restoring stiffness K (W/R for a pendulum) [N/m].
    mu_static, mu_kinetic : float
        Friction coefficients [-], 0 ≤ µk ≤ µs (µk defaults to µs); µ = 0 is allowed here.
    damping_Ns_per_m : float
        Isolator dashpot [N·s/m].
    gravity_m_s2 : float
        [m/s²].
    direction : str
        "x" or "y": which story stiffnesses.
    """
    mu_kinetic = mu_static if mu_kinetic is None else mu_kinetic
    for name, value in (("mu_static", mu_static), ("mu_kinetic", mu_kinetic),
                        ("stiffness_N_per_m", stiffness_N_per_m), ("damping_Ns_per_m", damping_Ns_per_m)):
        if not (math.isfinite(value) and value >= 0.0):
            raise InvalidSystemError(f"{name} must be finite and >= 0, got {value!r}")
    if mu_kinetic > mu_static:
        raise InvalidSystemError(f"mu_kinetic ({mu_kinetic:g}) must not exceed mu_static ({mu_static:g})")
    masses = superstructure.masses_kg
    n = masses.size
    m_b = float(total_mass_kg) - float(masses.sum())
    if not m_b > 0.0:
        raise InvalidSystemError(f"the floors ({masses.sum():g} kg) must weigh less than the total mass "
                                 f"({total_mass_kg:g} kg): the base slab is the rest")
    k_s = superstructure.stiffness_matrix(direction)
    c_s = superstructure.damping_matrix(direction)
    k_row = k_s.sum(axis=0)  # 1ᵀ K_s: the story forces on the slab
    c_row = c_s.sum(axis=0)
    size = 2 * n + 5
    xb, vb, u, ud = 0, 1, slice(2, 2 + n), slice(2 + n, 2 + 2 * n)
    ag, bg, f = 2 * n + 2, 2 * n + 3, 2 * n + 4
    k_iso, c_iso = float(stiffness_N_per_m), float(damping_Ns_per_m)
    stiff_m = k_s / masses[:, None]  # M⁻¹ K_s
    damp_m = c_s / masses[:, None]

    stuck = np.zeros((size, size))
    stuck[u, ud] = np.eye(n)
    stuck[ud, u] = -stiff_m
    stuck[ud, ud] = -damp_m
    stuck[ud, ag] = -1.0
    stuck[ag, bg] = 1.0

    slide = np.zeros((size, size))
    slab = np.zeros(size)  # ẍ_b as a row: −a_g + (−K x_b − c v_b − f + 1ᵀ(K_s u + C_s u̇))/m_b
    slab[xb] = -k_iso / m_b
    slab[vb] = -c_iso / m_b
    slab[u] = k_row / m_b
    slab[ud] = c_row / m_b
    slab[f] = -1.0 / m_b
    slab[ag] = -1.0
    slide[xb, vb] = 1.0
    slide[vb] = slab
    slide[u, ud] = np.eye(n)
    slide[ud, u] = -stiff_m
    slide[ud, ud] = -damp_m
    slide[ud] -= slab[None, :] + np.eye(size)[ag][None, :]  # ü = … − (ẍ_b + a_g)
    slide[ag, bg] = 1.0

    hold = np.zeros(size)
    hold[ag] = -m_b
    hold[xb] = -k_iso
    hold[u] = k_row
    hold[ud] = c_row

    heights = superstructure.floor_heights_m
    n_mon = 2 * n + 5
    mon = np.zeros((2, n_mon, size))
    for mode, a_mat in enumerate((stuck, slide)):
        slab_abs = a_mat[vb] + np.eye(size)[ag]
        mon[mode, 0, xb] = 1.0
        mon[mode, 1, vb] = 1.0
        for i in range(n):
            mon[mode, 2 + i, 2 + i] = 1.0
            if i > 0:
                mon[mode, 2 + i, 1 + i] = -1.0
            mon[mode, 2 + n + i] = slab_abs + a_mat[2 + n + i]
        mon[mode, 2 + 2 * n, u] = k_row
        mon[mode, 2 + 2 * n, ud] = c_row
        mon[mode, 3 + 2 * n] = -m_b * slab_abs + mon[mode, 2 + 2 * n]
        mon[mode, 4 + 2 * n] = -(heights * masses) @ mon[mode, 2 + n:2 + 2 * n]

    q_in = np.zeros((size, size))
    q_in[ag, vb] = q_in[vb, ag] = -0.5 * float(total_mass_kg)
    q_in[ag, ud] = -0.5 * masses
    q_in[ud, ag] = -0.5 * masses
    q_vis = np.zeros((size, size))
    q_vis[vb, vb] = c_iso
    q_vis[ud, ud] = c_s

    from scipy.linalg import matrix_balance

    rate = 0.0
    for a_mat in (stuck, slide):
        balanced, _ = matrix_balance(a_mat, permute=False)
        rate = max(rate, float(np.abs(balanced).sum(axis=0).max()))
    return BuildingSystem(n_floors=n, masses_kg=masses, slab_mass_kg=m_b, total_mass_kg=float(total_mass_kg),
                          floor_heights_m=heights, story_heights_m=superstructure.story_heights_m,
                          stiffness_matrix=k_s, damping_matrix=c_s, isolator_stiffness_N_per_m=k_iso,
                          isolator_damping_Ns_per_m=c_iso, mu_static=float(mu_static),
                          mu_kinetic=float(mu_kinetic), gravity_m_s2=float(gravity_m_s2),
                          a_modes=np.ascontiguousarray(np.stack([stuck, slide])), mon_modes=mon, q_in=q_in,
                          q_vis=q_vis, ell_hold=hold, fastest_rate_per_s=rate)


def van_loan(a_mat: np.ndarray, q_mat: np.ndarray, h: float) -> np.ndarray:
    """∫₀ʰ e^{Aᵀτ} Q e^{Aτ} dτ by one matrix exponential (C. Van Loan, IEEE TAC 23, 1978)."""
    from scipy.linalg import expm

    n = a_mat.shape[0]
    block = np.zeros((2 * n, 2 * n))
    block[:n, :n] = -a_mat.T
    block[:n, n:] = q_mat
    block[n:, n:] = a_mat
    big = expm(block * h)
    return big[n:, n:].T @ big[:n, n:]


class BuildingKeys:
    """The keys a building result derives from its ``bearing_loads()`` and its per-story arrays, shared by the
    1-D (:class:`BuildingResponse`) and 2-D (``planar_building.PlanarBuildingResponse``) building results."""

    @property
    def bearing_axial_load_max_N(self) -> list | None:
        loads = self.bearing_loads()
        return None if loads is None else loads["bearing_axial_load_max_N"]

    @property
    def bearing_axial_load_min_N(self) -> list | None:
        loads = self.bearing_loads()
        return None if loads is None else loads["bearing_axial_load_min_N"]

    @property
    def n_bearings_uplifted(self) -> int | None:
        loads = self.bearing_loads()
        return None if loads is None else loads["n_bearings_uplifted"]

    def summary(self) -> dict:
        """:meth:`SolverResult.summary`, the per-story and per-floor arrays as lists."""
        out = super().summary()
        for key in ("story_drift_m", "story_drift_ratio", "floor_peak_acceleration_m_s2"):
            out[key] = [float(v) for v in out[key]]
        return out


@dataclass(kw_only=True)
class BuildingResponse(BuildingKeys, AlongOneComponent, SolverResult):
    """Exact response of the building on its isolation plane to one record (model ``1d-building``, SI units).

    The fields of :class:`~isolator.solver.base.SolverResult` describe the isolator (the slab
    relative to the ground, energies per unit of the total mass); ``absolute_acceleration_m_s2``
    is the isolator force over the total mass (the rigid block's transmitted acceleration).
    ``system`` is the equivalent single bearing (per unit of the total mass), ``building`` the
    building's matrices.  Histories are at the samples; peaks are exact (located between samples).
    """

    EXTRA_SUMMARY_KEYS = ("energy_strain_final_J_per_kg", "story_drift_m", "story_drift_ratio",
                          "floor_peak_acceleration_m_s2", "superstructure_shear_coefficient",
                          "base_shear_coefficient", "bearing_axial_load_max_N", "bearing_axial_load_min_N",
                          "n_bearings_uplifted")

    system: System
    building: BuildingSystem
    floor_displacement_m: np.ndarray  #: (samples × floors) relative to the slab
    floor_velocity_m_s: np.ndarray
    floor_absolute_acceleration_m_s2: np.ndarray  #: (samples × floors)
    superstructure_shear_N: np.ndarray  #: 1ᵀ(K_s u + C_s u̇) at the samples
    isolator_force_N: np.ndarray  #: spring + dashpot + friction on the slab
    overturning_moment_Nm: np.ndarray  #: Σ F_i H_i, F_i = −m_i a_i (compresses the +x bearings)
    event_displacement_m: np.ndarray
    peak_max: np.ndarray = field(repr=False)
    peak_min: np.ndarray = field(repr=False)
    energy_strain_final_J_per_kg: float = 0.0
    substeps_per_interval: int = 1
    #: pieces evaluated by their Taylor series and interior extrema located (the work beyond e^{Ãh} products)
    n_series_pieces: int = 0
    n_extrema_located: int = 0
    bearing_layout: object = None
    model: str = MODEL_NAME
    model_reason: str = MODEL_REASON

    def _peak(self, key) -> np.ndarray:
        sl = _monitor_slices(self.building.n_floors)[key]
        return np.maximum(self.peak_max[sl], -self.peak_min[sl])

    @property
    def configuration(self) -> str:
        """The paper's configuration of the equivalent single bearing (1 to 4)."""
        return self.system.configuration

    @property
    def story_drift_m(self) -> np.ndarray:
        """Peak |u_i − u_{i−1}| per story, bottom to top [m] (exact)."""
        return self._peak("drift")

    @property
    def story_drift_ratio(self) -> np.ndarray:
        """Peak drift / story height, bottom to top [-]."""
        return self.story_drift_m / self.building.story_heights_m

    @property
    def floor_peak_acceleration_m_s2(self) -> np.ndarray:
        """Peak absolute acceleration per floor, bottom to top [m/s²] (exact)."""
        return self._peak("floor_acc")

    @property
    def superstructure_shear_coefficient(self) -> float:
        """Peak first-story shear (spring + damper, = Σ floor inertia forces) / W_s [-]."""
        return float(self._peak("shear")) / self.building.superstructure_weight_N

    @property
    def base_shear_coefficient(self) -> float:
        """Peak isolator force (spring + dashpot + friction) / W [-]."""
        return float(self._peak("isolator_force")) / self.building.weight_N

    @property
    def overturning_moment_extremes_Nm(self) -> tuple[float, float]:
        """(max, min) of the overturning moment over time [N·m] (exact)."""
        k = _monitor_slices(self.building.n_floors)["moment"]
        return float(self.peak_max[k]), float(self.peak_min[k])

    @property
    def energy_balance_error_J(self) -> float:
        """input − (kinetic + strain + potential + friction + viscous) [J]."""
        return self.energy_balance_error_J_per_kg * self.building.total_mass_kg

    def bearing_loads(self) -> dict | None:
        """Axial loads of the bearings (:func:`isolator.superstructure.bearing_axial_loads`), extremes exact.

        The maximum and minimum of each bearing come from the exact extremes of the overturning
        moment; the uplift start and duration from the samples (linear between them).
        """
        if self.bearing_layout is None:
            return None
        from isolator.superstructure import bearing_axial_loads

        out = bearing_axial_loads(self.bearing_layout, self.overturning_moment_Nm, self.time_s)
        coeff = self.bearing_layout.overturning_coefficients("x")
        gravity = np.asarray(self.bearing_layout.gravity_loads_N)
        m_max, m_min = self.overturning_moment_extremes_Nm
        out["bearing_axial_load_max_N"] = (gravity + np.maximum(coeff * m_max, coeff * m_min)).tolist()
        low = gravity + np.minimum(coeff * m_max, coeff * m_min)
        out["bearing_axial_load_min_N"] = low.tolist()
        out["n_bearings_uplifted"] = int(np.sum(low < 0.0))
        return out



def scene_needs(scene) -> tuple[str, str] | None:
    """``(model, reason)`` when the scene's design has a superstructure and one horizontal component; else None.

    A pair, a vertical or µ(v) with a superstructure goes to the 2-D building
    (:mod:`isolator.solver.planar_building`, registered above this model), never to the rigid block.
    """
    design = scene.design
    if design is None or getattr(design, "superstructure", None) is None:
        return None
    if scene.has_y or scene.has_z or scene.velocity_dependent:
        return None
    return MODEL_NAME, MODEL_REASON


def simulate_scene(scene) -> BuildingResponse:
    """The exact 1-D building response to a scene (:func:`simulate_building`).

    The isolator keywords of the scene (µs, µk, ``radius_m`` or ``stiffness_per_mass``,
    ``damping_per_mass``, ``gravity_m_s2``: per unit of the total mass) scale by the design's
    ``mass_kg``; the floors and the bearing layout come from the design.

    Raises
    ------
    InvalidSystemError
        A second horizontal component, a vertical or µ(v): those scenes are the 2-D building's.
    """
    design = scene.design
    if scene.has_y or scene.has_z or scene.velocity_dependent:
        raise InvalidSystemError(f"{design.source}: the 1-D building takes one horizontal component with constant "
                                 "friction; this scene is the 2-D building's (model '2d-building')")
    iso = {key: value for key, value in scene.isolator.items() if value is not None}
    g = float(iso.get("gravity_m_s2", design.gravity_m_s2))
    mass = design.mass_kg
    if iso.get("radius_m") is not None:
        stiffness = mass * g / float(iso["radius_m"])
    else:
        stiffness = mass * float(iso.get("stiffness_per_mass", 0.0))
    with naming_design(design):
        return simulate_building(scene.ax_m_s2, scene.dt_s, time_s=scene.time_s,
                                 superstructure=design.superstructure, total_mass_kg=mass,
                                 stiffness_N_per_m=stiffness, mu_static=float(iso["mu_static"]),
                                 mu_kinetic=iso.get("mu_kinetic"),
                                 damping_Ns_per_m=mass * float(iso.get("damping_per_mass", 0.0)), gravity_m_s2=g,
                                 bearing_layout=design.bearing_layout)


@contextmanager
def naming_design(design):
    """An :class:`InvalidSystemError` of the building solvers run inside, prefixed with the design file: the
    solvers see numbers, not files, and a refusal of the design's numbers (a base slab too light for its first
    story, a friction law) must name the design (the building models' ``simulate_scene``)."""
    try:
        yield
    except InvalidSystemError as err:
        raise InvalidSystemError(f"{design.source}: {err}") from None


_READY = False


def _warm_up() -> None:
    # load (or compile) the kernel on a tiny problem so that solver_seconds measures solving
    global _READY
    if _READY:
        return
    from isolator.solver.notice import note_if_slow
    from isolator.superstructure import Floor, Superstructure

    with note_if_slow("compiling the building solver (its first use after installation takes a few seconds; "
                      "the machine code is cached for later runs)"):
        s = Superstructure(floors=(Floor(1.0, 1.0, 100.0, 100.0),), damping_ratio=0.05, gravity_m_s2=9.81)
        for times in (None, [0.0, 0.01, 0.03]):
            acc = np.array([0.0, 5.0, -5.0])
            system = building_system(s, total_mass_kg=2.0, stiffness_N_per_m=10.0, mu_static=0.1)
            timing = record_timing(acc, None if times else 0.01, times)
            _run(system, timing, system.substeps(timing), None)
    _READY = True


def simulate_building(acceleration_m_s2, dt_s: float | None = None, *, time_s=None, superstructure,
                      total_mass_kg: float, stiffness_N_per_m: float, mu_static: float,
                      mu_kinetic: float | None = None, damping_Ns_per_m: float = 0.0,
                      gravity_m_s2: float = STANDARD_GRAVITY, direction: str = "x",
                      bearing_layout=None) -> BuildingResponse:
    """Exact response of a shear building on a friction isolation plane to one horizontal record.

    Parameters
    ----------
    acceleration_m_s2 : array_like
        Ground acceleration [m/s²], linear between samples.
    dt_s : float, optional
        Sample interval [s] (or ``time_s``).
    time_s : array_like, optional
        Sample times [s]; unequal steps are solved exactly, interval by interval.
    superstructure : isolator.superstructure.Superstructure
    total_mass_kg, stiffness_N_per_m, mu_static, mu_kinetic, damping_Ns_per_m, gravity_m_s2, direction
        See :func:`building_system`.
    bearing_layout : isolator.superstructure.BearingLayout, optional
        For the bearings' axial loads.

    Returns
    -------
    BuildingResponse
    """
    system = _system_for(superstructure, total_mass_kg=float(total_mass_kg), stiffness_N_per_m=float(stiffness_N_per_m),
                         mu_static=float(mu_static), mu_kinetic=None if mu_kinetic is None else float(mu_kinetic),
                         damping_Ns_per_m=float(damping_Ns_per_m), gravity_m_s2=float(gravity_m_s2),
                         direction=direction)
    timing = record_timing(acceleration_m_s2, dt_s, time_s)
    n_sub = system.substeps(timing)  # refused before the kernel is loaded
    _warm_up()
    return _run(system, timing, n_sub, bearing_layout)


def simulate_design_building(design, acceleration_m_s2, dt_s: float | None = None, *, time_s=None,
                             direction: str = "x") -> BuildingResponse:
    """:func:`simulate_building` for a :class:`isolator.design.Design` with a superstructure."""
    if design.superstructure is None:
        raise InvalidSystemError(f"{design.source}: the design has no [superstructure]")
    return simulate_building(acceleration_m_s2, dt_s, time_s=time_s, superstructure=design.superstructure,
                             total_mass_kg=design.mass_kg, stiffness_N_per_m=design.stiffness_N_per_m,
                             mu_static=design.mu_static, mu_kinetic=design.mu_kinetic,
                             damping_Ns_per_m=design.damping_Ns_per_m, gravity_m_s2=design.gravity_m_s2,
                             direction=direction, bearing_layout=design.bearing_layout)


def _taylor_rows(system: BuildingSystem) -> tuple:
    """ℓÃ for the slopes and ℓÃ^j for the Taylor coefficients of the watched quantities, the hold force and v_b."""
    size = system.size
    mon = system.mon_modes
    mon_d = np.ascontiguousarray(np.stack([mon[k] @ system.a_modes[k] for k in range(2)]))
    hold_d = system.ell_hold @ system.a_modes[0]
    n_pow = _bk.N_TAYLOR + 2
    mon_pow = np.empty((2, n_pow, mon.shape[1], size))
    vb_pow = np.empty((2, n_pow, size))
    hold_pow = np.empty((n_pow, size))
    for mode in range(2):
        rows = np.vstack([mon[mode], np.eye(size)[1], system.ell_hold])
        for j in range(n_pow):
            mon_pow[mode, j] = rows[:-2]
            vb_pow[mode, j] = rows[-2]
            if mode == 0:
                hold_pow[j] = rows[-1]
            rows = rows @ system.a_modes[mode]
    return mon_d, hold_d, mon_pow, vb_pow, hold_pow


#: Systems built by :func:`simulate_building`, by their parameters (a review runs one system on many records).
_SYSTEMS: dict = {}
_SYSTEMS_MAX = 64


def _system_for(superstructure, **parameters) -> BuildingSystem:
    key = (superstructure, *sorted(parameters.items()))
    system = _SYSTEMS.get(key)
    if system is None:
        system = building_system(superstructure, **parameters)
        if len(_SYSTEMS) >= _SYSTEMS_MAX:
            _SYSTEMS.pop(next(iter(_SYSTEMS)))
        _SYSTEMS[key] = system
    return system


def _run(system: BuildingSystem, timing, n_sub: int, bearing_layout) -> BuildingResponse:
    """The kernel on a checked record; ``n_sub`` from :meth:`BuildingSystem.substeps` (the public entry's)."""
    from scipy.linalg import expm

    acc, dt, relative, t0 = timing.acceleration_m_s2, timing.dt_s, timing.relative_time_s, timing.t0_s
    h_max = system.max_step_s
    size = system.size
    if relative is None:
        h = dt / n_sub
        if h not in system.cache:
            system.cache[h] = (np.stack([expm(a * h) for a in system.a_modes]),
                               np.stack([van_loan(a, system.q_in, h) for a in system.a_modes]),
                               np.stack([van_loan(a, system.q_vis, h) for a in system.a_modes]))
        phi, p_in, p_vis = system.cache[h]
        kernel_times = np.empty(0)
    else:
        phi = p_in = p_vis = np.zeros((2, size, size))
        kernel_times = np.ascontiguousarray(relative)
    if "rows" not in system.cache:
        system.cache["rows"] = _taylor_rows(system)
    mon = system.mon_modes
    mon_d, hold_d, mon_pow, vb_pow, hold_pow = system.cache["rows"]
    n = acc.size
    n_mon = mon.shape[1]
    out_state = np.empty((n, size))
    out_mon = np.empty((n, n_mon))
    out_energy = np.empty((3, n))
    peak_max = np.empty(n_mon)
    peak_min = np.empty(n_mon)
    summary = np.zeros(_bk.SUMMARY_SIZE)
    weight = system.weight_N
    capacity = 64 + n // 4
    while True:
        ev_time = np.empty(capacity)
        ev_kind = np.empty(capacity, dtype=np.int8)
        ev_x = np.empty(capacity)
        start = time.perf_counter()
        _bk.building_kernel(acc, dt, n_sub, kernel_times, h_max, system.a_modes, phi, p_in, p_vis, system.q_in,
                            system.q_vis, mon, mon_d, mon_pow, system.ell_hold, hold_d, hold_pow, vb_pow,
                            system.mu_static * weight,
                            system.mu_kinetic * weight, 0, 1, system.AG, system.BG, system.F, out_state, out_mon,
                            out_energy, peak_max, peak_min, ev_time, ev_kind, ev_x, summary)
        elapsed = time.perf_counter() - start
        n_events = int(summary[_bk.S_N_EVENTS])
        if n_events <= capacity:
            break
        capacity = n_events + 16
    status = int(summary[_bk.S_STATUS])
    message = "ok"
    if status & _bk.STATUS_CHATTER:
        message = (f"chatter guard: more than {_bk.MAX_EVENTS_PER_INTERVAL} events in one sample interval; the "
                   "static friction held the slab to the end of that interval")
    nf = system.n_floors
    sl = _monitor_slices(nf)
    x_b, v_b = out_state[:, 0], out_state[:, 1]
    u_last, ud_last = out_state[-1, 2:2 + nf], out_state[-1, 2 + nf:2 + 2 * nf]
    kinetic = 0.5 * system.slab_mass_kg * v_b[-1] ** 2 + 0.5 * float(system.masses_kg @ (v_b[-1] + ud_last) ** 2)
    mass = system.total_mass_kg
    e_in, e_f, e_v = (float(summary[k]) for k in (_bk.S_E_INPUT, _bk.S_E_FRICTION, _bk.S_E_VISCOUS))
    strain = float(0.5 * u_last @ system.stiffness_matrix @ u_last)
    potential = float(0.5 * system.isolator_stiffness_N_per_m * x_b[-1] ** 2)
    force = out_mon[:, sl["isolator_force"]]
    peak_force = float(max(peak_max[sl["isolator_force"]], -peak_min[sl["isolator_force"]]))
    equivalent = System(mu_static=system.mu_static, mu_kinetic=system.mu_kinetic,
                        stiffness_per_mass=system.isolator_stiffness_N_per_m / mass,
                        damping_per_mass=system.isolator_damping_Ns_per_m / mass, gravity_m_s2=system.gravity_m_s2)
    return BuildingResponse(
        system=equivalent,
        building=system,
        time_s=t0 + (dt * np.arange(n) if relative is None else relative),
        ground_acceleration_m_s2=acc,
        displacement_m=x_b.copy(),
        velocity_m_s=v_b.copy(),
        absolute_acceleration_m_s2=force / mass,
        event_time_s=t0 + ev_time[:n_events],
        event_kind=ev_kind[:n_events],
        event_displacement_m=ev_x[:n_events],
        peak_displacement_m=float(max(peak_max[sl["x_b"]], -peak_min[sl["x_b"]])),
        residual_displacement_m=float(x_b[-1]),
        peak_velocity_m_s=float(max(peak_max[sl["v_b"]], -peak_min[sl["v_b"]])),
        peak_transmitted_acceleration_m_s2=peak_force / mass,
        slip_time_s=float(summary[_bk.S_SLIP_TIME]),
        n_events=n_events,
        energy_input_J_per_kg=e_in / mass,
        energy_friction_J_per_kg=e_f / mass,
        energy_viscous_J_per_kg=e_v / mass,
        energy_kinetic_final_J_per_kg=float(kinetic) / mass,
        energy_potential_final_J_per_kg=potential / mass,
        energy_strain_final_J_per_kg=strain / mass,
        energy_balance_error_J_per_kg=(e_in - (float(kinetic) + strain + potential + e_f + e_v)) / mass,
        energy_history_J_per_kg=out_energy / mass,
        floor_displacement_m=out_state[:, 2:2 + nf].copy(),
        floor_velocity_m_s=out_state[:, 2 + nf:2 + 2 * nf].copy(),
        floor_absolute_acceleration_m_s2=out_mon[:, sl["floor_acc"]].copy(),
        superstructure_shear_N=out_mon[:, sl["shear"]].copy(),
        isolator_force_N=force.copy(),
        overturning_moment_Nm=out_mon[:, sl["moment"]].copy(),
        peak_max=peak_max,
        peak_min=peak_min,
        status=status,
        message=message,
        solver_seconds=elapsed,
        substeps_per_interval=n_sub,
        n_series_pieces=int(summary[_bk.S_N_SERIES]),
        n_extrema_located=int(summary[_bk.S_N_LOCATED]),
        bearing_layout=bearing_layout,
    )
