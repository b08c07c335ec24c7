r"""The building above the isolation plane: a linear shear building and the bearing layout.

A design may carry a superstructure (issue 22)::

    [superstructure]
    damping_ratio = 0.05                 # ζ in every fixed-base mode [-]

    [[superstructure.floor]]             # bottom to top
    mass_kg = 400000.0
    story_height_m = 4.0
    stiffness_x_N_per_m = 6.0e8
    stiffness_y_N_per_m = 5.0e8          # optional, default: stiffness_x_N_per_m

    [[bearing_position]]                 # optional, one per bearing
    x_m = -10.0                          # from the centre of mass [m]
    y_m = -8.0
    gravity_load_N = 2.0e6               # optional, default: equal shares of W

The design's ``mass_kg`` stays the total isolated mass M; the base slab is the rest,
``M − Σ m_i`` (> 0).  The superstructure is a shear building: floor i is a rigid
diaphragm of mass m_i joined to the floor below (the base slab for i = 1) by a story
spring k_i.  Damping is classical, ratio ζ in every fixed-base mode:

.. math::  C_s = M \Phi \,\mathrm{diag}(2\zeta\omega_j)\, \Phi^T M,
           \quad \Phi^T M \Phi = I,\quad K \Phi = M \Phi \,\mathrm{diag}(\omega_j^2)

acting on the floor displacements relative to the base slab.

Bearing axial loads come from rigid-slab statics (the slab stays plane, the bearings
have equal axial stiffness): each bearing's gravity share, times ``1 + a_z/g`` when a
vertical is given, plus the overturning moment of the floors' inertial forces at their
heights above the isolation plane, distributed linearly over the layout
(:meth:`BearingLayout.overturning_coefficients`).  Compression is positive; a negative
load is tension, i.e. uplift (ASCE 7-22 17.2.4.7).

References
----------
ASCE/SEI 7-22, Chapter 17: 17.2.4.7 (uplift), Eq. 17.5-3 (torsion factor, with y), Eq. 17.5-4 (P_T).
A. K. Chopra, *Dynamics of Structures*, classical damping from modal damping ratios (Sec. 11.4).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from isolator.errors import DesignError, key_hint, one_table_problem

#: keys of the ``[superstructure]`` table
SUPERSTRUCTURE_KEYS = {
    "damping_ratio": "classical damping ratio ζ in every fixed-base mode [-], 0 <= ζ < 1",
    "floor": "array of tables [[superstructure.floor]], bottom to top",
    "response_modification_R": "R of the seismic force-resisting system above the isolation (ASCE 7-22 Table "
                               "12.2-1) [-], 1 to 8, optional: the review's R_I = 3R/8 within [1, 2] (17.5.4.2)",
}
#: keys of one ``[[superstructure.floor]]`` entry
FLOOR_KEYS = {
    "mass_kg": "floor mass m_i [kg], > 0",
    "story_height_m": "height of the story below the floor h_i [m], > 0",
    "stiffness_x_N_per_m": "story shear stiffness along x k_x,i [N/m], > 0",
    "stiffness_y_N_per_m": "story shear stiffness along y k_y,i [N/m], > 0 (default: stiffness_x_N_per_m)",
}
#: keys of one ``[[bearing_position]]`` entry
BEARING_KEYS = {
    "x_m": "bearing position along x from the centre of mass [m]",
    "y_m": "bearing position along y from the centre of mass [m]",
    "gravity_load_N": "gravity load on the bearing [N], > 0 (default: equal shares of W = g × mass_kg)",
    "axial_capacity_N": "the bearing's vertical load capacity at the total maximum displacement [N], > 0, optional "
                        "(the review's stability row, ASCE 7-22 17.2.4.6)",
}
#: The bearings' gravity loads, when given, must add up to W within this fraction [-].
GRAVITY_SUM_TOLERANCE = 0.01
#: A floor's mass [kg]: the design's own mass range (isolator.design.MASS_RANGE_KG); a 1e-300 kg floor made the
#: modal eigensolver fail with a traceback (issue 22, third round).
FLOOR_MASS_RANGE_KG = (1e-3, 1e10)
#: A story's height [m]: a 1e300 m story made the overturning moments infinite and the bearing loads unknown.
STORY_HEIGHT_RANGE_M = (1e-3, 1e3)
#: A story's shear stiffness [N/m]: 1e-300 N/m cut the floors loose from the slab without a word (their
#: shear read 8e-18 W_s), 1e300 N/m asked the solver for 1e148 sub-steps per sample.
STORY_STIFFNESS_RANGE_N_PER_M = (1.0, 1e14)
#: R of the system above the isolation: ASCE 7-22 Table 12.2-1 lists 1 to 8 (its R_I = 3R/8 is then taken within
#: [1, 2], 17.5.4.2); 1e300 and 0.5 were read and clamped to an R_I without a word (session 24 sweep)
RESPONSE_MODIFICATION_RANGE = (1.0, 8.0)
#: Most floors of a [superstructure] (the tallest buildings have about 160 stories): the solve grows with the cube of
#: the floors (NWH360: 100 floors 18 s, 300 floors 79 s; 2000 floors ran past 120 s, session 10 sweep).
MAX_FLOORS = 200
#: A bearing's distance from the centre of mass along x or y [m] (a plan within 10 km).
BEARING_POSITION_MAX_M = 1e4
#: Most [[bearing_position]] entries of a design (the largest isolated buildings stand on about 1,500 bearings).
#: Read, 100,000 entries took 4.2 s and the building's `simulate` 16 s and 0.84 GB; with the bearings' old
#: pairwise check of their places, 30,000 took 40 s to read and 100,000 ran past 120 s (session 16 sweep).
MAX_BEARINGS = 10_000
#: ASCE 7-22 Eq. 12.8-7, T_a = C_t h_n^x, with Table 12.8-2's most flexible system (steel moment-resisting frames:
#: C_t = 0.0724, x = 0.8 with h_n in m) and Table 12.8-1's largest C_u = 1.4.  A fixed-base fundamental period above
#: FIXED_BASE_PERIOD_FACTOR × C_u T_a is a story stiffness in another unit, not a building: kN/m typed as N/m makes
#: the periods sqrt(1000) = 31.6 times longer (the example building's 0.49 s became 15.5 s and was read; session 24
#: sweep).  Computed periods of flexible frames reach about 2 C_u T_a; 4 C_u T_a leaves them room and still catches
#: one story of the example building in kN/m (its top story: T_1 = 5.9 s against 4 C_u T_a = 4.2 s).
PERIOD_CT, PERIOD_X, PERIOD_CU = 0.0724, 0.8, 1.4
FIXED_BASE_PERIOD_FACTOR = 4.0
#: A bearing's axial capacity [N]: the largest friction pendulums carry about 1e8 N (10,000 t); 1e9 N is ten times
#: that.  Below AXIAL_CAPACITY_MIN_SHARE of the bearing's own gravity load the capacity is another unit (kN typed as
#: N is 1/1000 of it), not a design: a failing design's capacity is a fraction of its load, not a thousandth
#: (1e-300 N and 1e300 N were read, session 24 sweep).
AXIAL_CAPACITY_MAX_N = 1e9
AXIAL_CAPACITY_MIN_SHARE = 0.1


@dataclass(frozen=True)
class Floor:
    """One floor of the shear building (SI units)."""

    mass_kg: float
    story_height_m: float  #: height of the story below this floor
    stiffness_x_N_per_m: float  #: story shear stiffness below this floor, along x
    stiffness_y_N_per_m: float


@dataclass(frozen=True)
class Superstructure:
    """A linear shear building with classical modal damping (floors bottom to top).

    Parameters
    ----------
    floors : tuple of Floor
        Bottom to top.
    damping_ratio : float
        ζ in every fixed-base mode [-].
    gravity_m_s2 : float
        Gravity for the weights [m/s²].
    """

    floors: tuple
    damping_ratio: float
    gravity_m_s2: float
    #: R of the lateral system above the isolation (ASCE 7-22 Table 12.2-1), if given (the review's R_I)
    response_modification_R: float | None = None

    @property
    def n_floors(self) -> int:
        return len(self.floors)

    @property
    def masses_kg(self) -> np.ndarray:
        """m_i, bottom to top [kg]."""
        return np.array([f.mass_kg for f in self.floors])

    @property
    def mass_kg(self) -> float:
        """Σ m_i [kg]."""
        return float(sum(f.mass_kg for f in self.floors))

    @property
    def weight_N(self) -> float:
        """W_s = g Σ m_i [N] (ASCE 7-22 17.5.4.3, the seismic weight above the isolation plane)."""
        return self.mass_kg * self.gravity_m_s2

    @property
    def story_heights_m(self) -> np.ndarray:
        """h_i, bottom to top [m]."""
        return np.array([f.story_height_m for f in self.floors])

    @property
    def floor_heights_m(self) -> np.ndarray:
        """Height of each floor above the isolation plane, H_i = Σ_{j≤i} h_j [m]."""
        return np.cumsum(self.story_heights_m)

    def story_stiffnesses(self, direction: str = "x") -> np.ndarray:
        """k_i along ``direction`` ("x" or "y"), bottom to top [N/m]."""
        if direction not in ("x", "y"):
            raise ValueError(f"direction must be 'x' or 'y', got {direction!r}")
        return np.array([f.stiffness_x_N_per_m if direction == "x" else f.stiffness_y_N_per_m for f in self.floors])

    def mass_matrix(self) -> np.ndarray:
        """M = diag(m_i) [kg]."""
        return np.diag(self.masses_kg)

    def stiffness_matrix(self, direction: str = "x") -> np.ndarray:
        """Shear-building K on the floor displacements relative to the base slab [N/m].

        Story i joins floor i − 1 (the slab for i = 1, fixed in these coordinates) to floor i.
        """
        k = self.story_stiffnesses(direction)
        n = k.size
        out = np.zeros((n, n))
        for i in range(n):
            out[i, i] += k[i]
            if i + 1 < n:
                out[i, i] += k[i + 1]
                out[i, i + 1] = out[i + 1, i] = -k[i + 1]
        return out

    def modes(self, direction: str = "x") -> tuple[np.ndarray, np.ndarray]:
        """Fixed-base circular frequencies ω_j [rad/s] (ascending) and mass-normalised modes Φ.

        Returns
        -------
        tuple
            ``(omega, phi)`` with ``phi.T @ M @ phi = I`` and ``K phi = M phi diag(ω²)``.
        """
        from scipy.linalg import eigh

        eigenvalues, phi = eigh(self.stiffness_matrix(direction), self.mass_matrix())
        return np.sqrt(np.maximum(eigenvalues, 0.0)), phi

    def fixed_base_periods_s(self, direction: str = "x") -> np.ndarray:
        """Fixed-base periods T_j = 2π/ω_j, longest first [s]."""
        omega, _ = self.modes(direction)
        return 2.0 * math.pi / omega

    def damping_matrix(self, direction: str = "x") -> np.ndarray:
        """C_s = M Φ diag(2ζω_j) Φᵀ M [N·s/m] (classical damping, ratio ζ in every fixed-base mode)."""
        omega, phi = self.modes(direction)
        m_phi = self.mass_matrix() @ phi
        return m_phi @ np.diag(2.0 * self.damping_ratio * omega) @ m_phi.T

    def as_dict(self) -> dict:
        """The superstructure's input and derived numbers (SI units)."""
        out = {"damping_ratio": self.damping_ratio, "mass_kg": self.mass_kg, "weight_N": self.weight_N,
               "response_modification_R": self.response_modification_R,
               "floors": [{"mass_kg": f.mass_kg, "story_height_m": f.story_height_m,
                           "stiffness_x_N_per_m": f.stiffness_x_N_per_m,
                           "stiffness_y_N_per_m": f.stiffness_y_N_per_m} for f in self.floors]}
        for direction in ("x", "y"):
            out[f"fixed_base_periods_{direction}_s"] = self.fixed_base_periods_s(direction).tolist()
        return out


@dataclass(frozen=True)
class BearingLayout:
    """Bearing positions from the centre of mass and their gravity loads (file order).

    Parameters
    ----------
    x_m, y_m : tuple of float
        Positions [m].
    gravity_loads_N : tuple of float
        Gravity load on each bearing [N].
    """

    x_m: tuple
    y_m: tuple
    gravity_loads_N: tuple
    #: each bearing's vertical load capacity at the total maximum displacement [N], if given (17.2.4.6)
    axial_capacities_N: tuple | None = None

    @property
    def n_bearings(self) -> int:
        return len(self.x_m)

    def overturning_coefficients(self, direction: str = "x") -> np.ndarray:
        r"""Axial load on each bearing per unit overturning moment from loading along ``direction`` [1/m].

        The additional loads ΔP_k = a + b x_k + c y_k (a rigid slab on bearings of equal axial
        stiffness stays plane) with ΣΔP = 0, the moment of the loads equal to the overturning
        moment M about the axis ⟂ ``direction`` (:math:`\sum \Delta P_k x_k = M` for loading
        along x), and no moment about the other axis.  A horizontal force F in +x at height H
        gives M = F H and compresses the bearings on the +x side.

        Returns
        -------
        numpy.ndarray
            ΔP_k / M [1/m] (compression positive).
        """
        x, y = np.asarray(self.x_m), np.asarray(self.y_m)
        matrix = np.array([[x.size, x.sum(), y.sum()], [x.sum(), x @ x, x @ y], [y.sum(), x @ y, y @ y]])
        rhs = np.array([0.0, 1.0, 0.0]) if direction == "x" else np.array([0.0, 0.0, 1.0])
        a, b, c = np.linalg.solve(matrix, rhs)
        return a + b * x + c * y

    def torsion_parameters(self, plan_b_m: float, plan_d_m: float) -> dict:
        r"""P_T of ASCE 7-22 Eq. 17.5-4 and the corner distances y from the layout.

        .. math::  P_T = \frac{1}{r_I}\sqrt{\frac{\sum (x_i^2 + y_i^2)}{N}},\quad r_I = \sqrt{(b^2 + d^2)/12}

        Parameters
        ----------
        plan_b_m, plan_d_m : float
            Plan dimensions [m] (a rectangular plan: r_I, the radius of gyration of the isolated mass).

        Returns
        -------
        dict
            ``P_T`` [-], ``r_I_m`` [m], ``y_for_loading_x_m`` (max |y|, the farthest bearing ⟂ to
            loading along x) and ``y_for_loading_y_m`` (max |x|) [m].
        """
        x, y = np.asarray(self.x_m), np.asarray(self.y_m)
        r_i = math.sqrt((plan_b_m ** 2 + plan_d_m ** 2) / 12.0)
        p_t = math.sqrt(float(np.mean(x * x + y * y))) / r_i
        return {"P_T": p_t, "r_I_m": r_i, "y_for_loading_x_m": float(np.max(np.abs(y))),
                "y_for_loading_y_m": float(np.max(np.abs(x)))}

    def as_dict(self) -> dict:
        return {"x_m": list(self.x_m), "y_m": list(self.y_m), "gravity_load_N": list(self.gravity_loads_N),
                "axial_capacity_N": None if self.axial_capacities_N is None else list(self.axial_capacities_N)}


def bearing_axial_loads(layout: BearingLayout, moment_x_Nm, time_s, *, moment_y_Nm=None,
                        vertical_factor=None) -> dict:
    """Each bearing's axial load over time and its extremes, uplift time and duration.

    P_k(t) = P_k,g (1 + a_z/g) + ΔP_k,x M_x(t) + ΔP_k,y M_y(t) (compression positive).

    Parameters
    ----------
    layout : BearingLayout
    moment_x_Nm : array_like
        Overturning moment from the loading along x, Σ F_i H_i [N·m] at ``time_s``.
    time_s : array_like
        Sample times [s].
    moment_y_Nm : array_like, optional
        The same for loading along y [N·m].
    vertical_factor : array_like, optional
        1 + a_z/g at the samples [-] (the vertical's share of the gravity loads).

    Returns
    -------
    dict
        ``axial_load_N`` (bearings × samples), ``bearing_axial_load_max_N``,
        ``bearing_axial_load_min_N`` (lists, file order), ``uplift_start_s`` (first instant
        of tension, None if none), ``uplift_duration_s`` (time in tension; crossings between
        samples interpolated linearly) and ``n_bearings_uplifted``.
    """
    t = np.asarray(time_s, dtype=np.float64)
    gravity = np.asarray(layout.gravity_loads_N)[:, None] * (1.0 if vertical_factor is None
                                                             else np.asarray(vertical_factor)[None, :])
    loads = gravity + layout.overturning_coefficients("x")[:, None] * np.asarray(moment_x_Nm)[None, :]
    if moment_y_Nm is not None:
        loads = loads + layout.overturning_coefficients("y")[:, None] * np.asarray(moment_y_Nm)[None, :]
    starts, durations = [], []
    for row in loads:
        start, duration = tension_time(row, t)
        starts.append(start)
        durations.append(duration)
    return {"axial_load_N": loads, "bearing_axial_load_max_N": loads.max(axis=1).tolist(),
            "bearing_axial_load_min_N": loads.min(axis=1).tolist(), "uplift_start_s": starts,
            "uplift_duration_s": durations, "n_bearings_uplifted": int(sum(d is not None for d in starts))}


def tension_time(load_N: np.ndarray, time_s: np.ndarray) -> tuple[float | None, float]:
    """First instant and total duration of a negative load, linear between samples [s]."""
    negative = load_N < 0.0
    if not negative.any():
        return None, 0.0
    duration = 0.0
    first = None
    for i in range(load_N.size - 1):
        a, b = load_N[i], load_N[i + 1]
        dt = time_s[i + 1] - time_s[i]
        if a < 0.0 and b < 0.0:
            part, begin = dt, time_s[i]
        elif a < 0.0 <= b:
            part, begin = dt * a / (a - b), time_s[i]
        elif b < 0.0 <= a:
            part = dt * b / (b - a)
            begin = time_s[i + 1] - part
        else:
            continue
        duration += part
        if first is None:
            first = float(begin)
    if first is None:  # only the last sample is negative
        first = float(time_s[-1])
    return first, duration


# ---- parsing ----------------------------------------------------------------------------------


def _number(table: dict, key: str, where: str, keys: dict, *, positive: bool = True, required: bool = True,
            within: tuple | None = None, what: str = ""):
    if key not in table:
        if required:
            raise DesignError(f"{where}: missing key '{key}' ({keys[key]})")
        return None
    value = table[key]
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise DesignError(f"{where}: key '{key}' must be a finite number, got {value!r}")
    if positive and not value > 0:
        raise DesignError(f"{where}: key '{key}' must be > 0, got {value:g}")
    if within is not None and not within[0] <= value <= within[1]:
        raise DesignError(f"{where}: key '{key}' must lie in [{within[0]:g}, {within[1]:g}]{what}, got {value:g}")
    return float(value)


def _unknown(table: dict, keys: dict, where: str) -> None:
    for key in table:
        if key not in keys:
            raise DesignError(f"{where}: unknown key '{key}'{key_hint(key, keys)}")


def parse_superstructure(table, total_mass_kg: float, gravity_m_s2: float, source: str = "<design>"):
    """The ``[superstructure]`` table of a design, validated.

    Parameters
    ----------
    table : dict or None
        The table as read from TOML.
    total_mass_kg : float
        The design's ``mass_kg`` (the whole isolated mass) [kg].
    gravity_m_s2 : float
        [m/s²].
    source : str
        The file, for messages.

    Returns
    -------
    Superstructure or None

    Raises
    ------
    DesignError
        One line naming the file, the floor (numbered from 1 at the bottom) and the key.
    """
    if table is None:
        return None
    where = f"{source}: [superstructure]"
    if not isinstance(table, dict):
        raise DesignError(f"{where} must be a table with damping_ratio and [[superstructure.floor]] entries")
    _unknown(table, SUPERSTRUCTURE_KEYS, where)
    zeta = _number(table, "damping_ratio", where, SUPERSTRUCTURE_KEYS, positive=False)
    if not 0.0 <= zeta < 1.0:
        raise DesignError(f"{where}: key 'damping_ratio' must lie in [0, 1), got {zeta:g}")
    entries = table.get("floor")
    wrong = next((i for i, e in enumerate(entries, start=1) if not isinstance(e, dict)), None) \
        if isinstance(entries, list) else None
    if wrong is not None:  # floor = [1, 2] was told "needs at least one entry" (session 20 sweep)
        raise DesignError(f"{where}: key 'floor': entry {wrong} is {repr(entries[wrong - 1])[:60]}, not a table of "
                          "keys (each [[superstructure.floor]] holds mass_kg, story_height_m, stiffness_x_N_per_m)")
    if (problem := one_table_problem(entries, "superstructure.floor")) is not None:
        raise DesignError(f"{where}: {problem}, bottom to top")
    if not isinstance(entries, list) or not entries:
        raise DesignError(f"{where}: needs at least one [[superstructure.floor]] entry (mass_kg, story_height_m, "
                          "stiffness_x_N_per_m)")
    if len(entries) > MAX_FLOORS:
        raise DesignError(f"{where}: {len(entries)} [[superstructure.floor]] entries, more than {MAX_FLOORS} (the "
                          "tallest buildings have about 160 stories)")
    floors = []
    for number, entry in enumerate(entries, start=1):
        here = f"{source}: superstructure floor {number} (from the bottom)"
        _unknown(entry, FLOOR_KEYS, here)
        story = {"within": STORY_STIFFNESS_RANGE_N_PER_M, "what": " N/m, a story's shear stiffness"}
        kx = _number(entry, "stiffness_x_N_per_m", here, FLOOR_KEYS, **story)
        ky = _number(entry, "stiffness_y_N_per_m", here, FLOOR_KEYS, required=False, **story)
        floors.append(Floor(mass_kg=_number(entry, "mass_kg", here, FLOOR_KEYS, within=FLOOR_MASS_RANGE_KG,
                                            what=" kg, the design's mass range"),
                            story_height_m=_number(entry, "story_height_m", here, FLOOR_KEYS,
                                                   within=STORY_HEIGHT_RANGE_M, what=" m, a story's height"),
                            stiffness_x_N_per_m=kx, stiffness_y_N_per_m=kx if ky is None else ky))
    floors_mass = sum(f.mass_kg for f in floors)
    if not floors_mass < total_mass_kg:
        raise DesignError(f"{where}: the floors weigh {floors_mass:g} kg, not less than the design's mass_kg = "
                          f"{total_mass_kg:g} kg (the total isolated mass: the base slab is the rest)")
    r = _number(table, "response_modification_R", where, SUPERSTRUCTURE_KEYS, required=False,
                within=RESPONSE_MODIFICATION_RANGE, what=", ASCE 7-22 Table 12.2-1's R of a system")
    building = Superstructure(floors=tuple(floors), damping_ratio=zeta, gravity_m_s2=float(gravity_m_s2),
                              response_modification_R=r)
    _refuse_unit_slip_in_stiffness(building, where)
    return building


def _refuse_unit_slip_in_stiffness(building: Superstructure, where: str) -> None:
    """A fixed-base fundamental period beyond any building's (:data:`FIXED_BASE_PERIOD_FACTOR` × C_u T_a) is refused,
    naming the story whose own period 2π √(Σ m above / k_i) is the longest: its stiffness is the likeliest slip."""
    height_m = float(np.sum(building.story_heights_m))
    bound_s = FIXED_BASE_PERIOD_FACTOR * PERIOD_CU * PERIOD_CT * height_m ** PERIOD_X
    masses_above = np.cumsum(building.masses_kg[::-1])[::-1]
    for direction in ("x", "y"):
        period_s = float(building.fixed_base_periods_s(direction)[0])
        if period_s > bound_s:
            story_periods = 2 * math.pi * np.sqrt(masses_above / building.story_stiffnesses(direction))
            softest = int(np.argmax(story_periods))
            key = f"stiffness_{direction}_N_per_m"
            raise DesignError(
                f"{where}: the fixed-base period along {direction} is {period_s:.3g} s, longer than any building of "
                f"h_n = {height_m:g} m (above {FIXED_BASE_PERIOD_FACTOR:g} C_u T_a = {bound_s:.3g} s; ASCE 7-22 Eq. "
                f"12.8-7, T_a = {PERIOD_CT} h_n^{PERIOD_X} of a steel moment frame, C_u = {PERIOD_CU}): a story "
                f"stiffness in kN/m? ({key} is in N/m; floor {softest + 1} from the bottom has "
                f"{building.story_stiffnesses(direction)[softest]:g} N/m)")


def parse_bearing_layout(entries, weight_N: float, source: str = "<design>"):
    """The ``[[bearing_position]]`` entries of a design, validated.

    Parameters
    ----------
    entries : list of dict or None
    weight_N : float
        W = g × the design's mass_kg [N]: shared equally when no gravity_load_N is given.
    source : str
        The file, for messages.

    Returns
    -------
    BearingLayout or None

    Raises
    ------
    DesignError
        One line naming the file, the bearing (numbered from 1 in file order) and the key.
    """
    if entries is None:
        return None
    where = f"{source}: [[bearing_position]]"
    if not isinstance(entries, list) or not all(isinstance(e, dict) for e in entries):
        raise DesignError(f"{where} must be an array of tables with x_m, y_m (and gravity_load_N)")
    if len(entries) > MAX_BEARINGS:
        raise DesignError(f"{where}: {len(entries)} entries, more than {MAX_BEARINGS:,} (the largest isolated "
                          "buildings stand on about 1,500 bearings)")
    if not entries:  # `bearing_position = []` divided W by no bearings (ZeroDivisionError; session 24 sweep)
        raise DesignError(f"{where}: the array is empty; give at least three bearings, not on one line, for the "
                          "rigid-slab statics (or no bearing_position key for a design without a layout)")
    xs, ys, loads, capacities = [], [], [], []
    places: dict = {}  # (x, y) -> the first bearing there: one look-up each (a scan of the others was quadratic:
    # 30,000 bearings read in 40 s, 100,000 past 120 s; session 16 sweep)
    for number, entry in enumerate(entries, start=1):
        here = f"{source}: bearing_position {number}"
        _unknown(entry, BEARING_KEYS, here)
        plan = (-BEARING_POSITION_MAX_M, BEARING_POSITION_MAX_M), " m from the centre of mass"
        xs.append(_number(entry, "x_m", here, BEARING_KEYS, positive=False, within=plan[0], what=plan[1]))
        ys.append(_number(entry, "y_m", here, BEARING_KEYS, positive=False, within=plan[0], what=plan[1]))
        loads.append(_number(entry, "gravity_load_N", here, BEARING_KEYS, required=False))
        capacities.append(_number(entry, "axial_capacity_N", here, BEARING_KEYS, required=False))
        if capacities[-1] is not None and capacities[-1] > AXIAL_CAPACITY_MAX_N:
            raise DesignError(f"{here}: key 'axial_capacity_N' = {capacities[-1]:g} N is above {AXIAL_CAPACITY_MAX_N:g} "
                              "N, ten times the largest friction pendulums' (about 1e8 N)")
        first = places.setdefault((xs[-1], ys[-1]), number)
        if first != number:
            raise DesignError(f"{here}: at the same place as bearing_position {first} ({xs[-1]:g}, {ys[-1]:g}) m")
    given = [load is not None for load in loads]
    if any(given) and not all(given):
        missing = given.index(False) + 1
        raise DesignError(f"{source}: bearing_position {missing}: missing key 'gravity_load_N' (give it for every "
                          "bearing or for none: none means equal shares of W)")
    if not any(given):
        loads = [weight_N / len(xs)] * len(xs)
    elif abs(sum(loads) - weight_N) > GRAVITY_SUM_TOLERANCE * weight_N:
        raise DesignError(f"{where}: the gravity loads add up to {sum(loads):.6g} N, not W = g × mass_kg = "
                          f"{weight_N:.6g} N (within {GRAVITY_SUM_TOLERANCE:.0%})")
    x, y = np.array(xs), np.array(ys)
    # a rigid slab needs three bearings not on one line: otherwise the statics has no unique answer
    spread = np.linalg.matrix_rank(np.column_stack([np.ones_like(x), x, y]), tol=1e-9 * max(1.0, np.abs(x).max(),
                                                                                             np.abs(y).max()))
    if len(xs) < 3 or spread < 3:
        raise DesignError(f"{where}: the {len(xs)} bearing(s) do not span the plan (at least three, not on one "
                          "line, for the rigid-slab statics)")
    if any(c is not None for c in capacities) and not all(c is not None for c in capacities):
        missing = [c is not None for c in capacities].index(False) + 1
        raise DesignError(f"{source}: bearing_position {missing}: missing key 'axial_capacity_N' (give it for every "
                          "bearing or for none)")
    for number, (capacity, load) in enumerate(zip(capacities, loads, strict=True), start=1):
        if capacity is not None and capacity < AXIAL_CAPACITY_MIN_SHARE * load:
            raise DesignError(f"{source}: bearing_position {number}: key 'axial_capacity_N' = {capacity:g} N is below "
                              f"{AXIAL_CAPACITY_MIN_SHARE:g} of the bearing's gravity load ({load:.4g} N): a capacity "
                              "in kN? (axial_capacity_N is in N)")
    return BearingLayout(x_m=tuple(xs), y_m=tuple(ys), gravity_loads_N=tuple(float(v) for v in loads),
                         axial_capacities_N=tuple(capacities) if capacities and capacities[0] is not None else None)


def review_inputs(design) -> dict:
    """The code-review inputs a design's superstructure and bearing layout fix, instead of assumed values.

    For the review (ASCE 7-22 Chapter 17) to call: each value with its clause and basis, and only
    those the design determines (an empty dict for a rigid block without a layout).

    Parameters
    ----------
    design : isolator.design.Design

    Returns
    -------
    dict
        ``Ws_over_W`` (17.5.4.2, Eq. 17.5-8: W_s = g Σ m_i over W = g × mass_kg) [-];
        ``T_fixed_s`` (the fixed-base fundamental period along x and y, for D'_M of Eq. 17.6-1) [s];
        ``P_T`` (Eq. 17.5-4) and ``y_for_loading_x_m`` / ``y_for_loading_y_m`` (the corner distances of
        Eq. 17.5-3) when the design has ``[[bearing_position]]`` and a ``[plan]``, with ``rigidity_centre_m``
        (x, y) [m] from the centre of mass (pendulum bearings: the load-weighted centroid, their stiffness being
        proportional to their load; springs: the plain centroid); ``basis``: one sentence per value.
    """
    out: dict = {}
    basis = []
    s = design.superstructure
    if s is not None:
        out["Ws_over_W"] = s.mass_kg / design.mass_kg
        out["T_fixed_s"] = {d: float(s.fixed_base_periods_s(d)[0]) for d in ("x", "y")}
        basis.append(f"W_s/W = {out['Ws_over_W']:.4g} from the {s.n_floors} floors (17.5.4.2)")
        basis.append(f"fixed-base T = {out['T_fixed_s']['x']:.4g} s (x), {out['T_fixed_s']['y']:.4g} s (y), "
                     "from the story stiffnesses (Eq. 17.6-1)")
    layout, plan = design.bearing_layout, design.plan
    if layout is not None and plan is not None:
        torsion = layout.torsion_parameters(plan["b_m"], plan["d_m"])
        out.update({key: torsion[key] for key in ("P_T", "y_for_loading_x_m", "y_for_loading_y_m")})
        # the centre of rigidity: a pendulum bearing's stiffness is its load / R (its friction's µ × load / D), so
        # the load-weighted centroid; a flat slider on springs of one stiffness each: the plain centroid
        bearing = getattr(design, "bearing", None)
        weights = np.asarray(layout.gravity_loads_N, dtype=float) if design.is_pendulum or (
            bearing is not None and not bearing.is_simple) else np.ones(layout.n_bearings)
        total = float(np.sum(weights))
        if total > 0:
            out["rigidity_centre_m"] = (float(np.dot(weights, layout.x_m)) / total,
                                        float(np.dot(weights, layout.y_m)) / total)
        basis.append(f"P_T = {torsion['P_T']:.4g} from the {layout.n_bearings} bearings (Eq. 17.5-4), corner "
                     f"y = {torsion['y_for_loading_x_m']:g} / {torsion['y_for_loading_y_m']:g} m (Eq. 17.5-3)")
    if out:
        out["basis"] = basis
    return out
