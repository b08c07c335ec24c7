r"""A linear shear building on the friction isolation plane under two horizontal components (2-D).

The model (issue 22, ``docs/building.md``).  The superstructure of
:class:`isolator.superstructure.Superstructure` responds independently along x and y (story
stiffnesses k_x,i and k_y,i, classical damping per direction); the two directions meet only in
the isolation plane, whose friction acts against the slab's sliding velocity **vector**:

.. math::

    M (\ddot u_d + \mathbf 1 (\ddot X_d + a_d)) + C_{s,d} \dot u_d + K_{s,d} u_d &= 0 \\
    m_b (\ddot X + a_g) &= S(u, \dot u) - K X - c \dot X - \mu_k N \,\dot X/|\dot X|

with X the slab's displacement relative to the ground (a plane vector), S the first story's
shear vector (spring and damper), K = W/R for a pendulum (or the design's spring), c the
optional dashpot and N = W = g × ``mass_kg``.  While stuck, the floors respond as the
fixed-base structure and the friction holds D = S − K X − m_b a_g while |D| ≤ µs N
(Euclidean norm); it breaks away at the first instant |D| = µs N; a stop (|Ẋ| → 0) sticks if
|D| ≤ µs N and restarts towards D otherwise.

The solution is propagated piece by piece by the Taylor series of the exact solution
(:mod:`isolator.solver.planar_building_kernel`): linear phases are exact to rounding, the
friction direction's series follows from the recurrences of a square root and a quotient,
and each piece is as long as its series reaches rounding.  Events and interior peaks are
roots of those polynomials; energies are exact integrals of them.

Outputs: the keys of the 1-D building (:class:`isolator.solver.building.BuildingResponse`),
resultants in the plane: ``story_drift_m`` and ``story_drift_ratio`` (peak over time of the
resultant drift per story), ``floor_peak_acceleration_m_s2`` (resultant, absolute),
``superstructure_shear_coefficient``, ``base_shear_coefficient`` and, with a bearing layout,
the bearings' axial loads from the overturning in both directions.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from isolator.errors import InvalidSystemError, RecordInputError
from isolator.solver import planar_building_kernel as _pk
from isolator.solver.base import SolverResult
from isolator.solver.building import (
    BuildingKeys,
    BuildingResponse,
    building_system,
    naming_design,
    van_loan,
)
from isolator.solver.record import building_substeps, sample_timing
from isolator.solver.system import System, check_friction_coefficient, check_friction_rate
from isolator.units import STANDARD_GRAVITY

#: The solver model's name in the registry.
MODEL_NAME = "2d-building"
MODEL_REASON = ("a superstructure above the isolation plane under two horizontal components: the 2-D building "
                "(friction coupled in the plane)")
DIRECTIONS = ("x", "y")
#: status bit: the state became non-finite (never seen; guarded so that it can never read as "ok")
STATUS_NON_FINITE = 8
#: Taylor orders of the series pieces the tests cover (12, 18, 30 give one answer to 1e-10;
#: tests/solver/test_planar_building_stops.py): the kernel's N_ORDER must lie here.
ORDER_RANGE = (8, 40)
#: The approach to a stop (and the departure from rest) by series in ln s (s the slab's speed; the kernel's APPROACH
#: phase, docs/building.md). Exact (the bench case agrees with the series in time to 3e-15) but not faster yet
#: (85.0 against 86.5 ms, 1 540 approach + 3 518 slide pieces against 4 962), so off by default.
STOP_APPROACH = False
#: Departures from rest at a break-away with µs = µk by the slow manifold's series from the break-away (the kernel's
#: ``_series_depart``, V = τ² W(τ)) instead of START's friction along D up to 1e-5 v_ref and stiff SLIDE pieces
#: (docs/building.md, Speed).
DEPARTURE_SERIES = True
#: Departures from rest with a finite acceleration, |D| > µk N at V = 0 (a break-away with µs > µk, a reversal at a
#: stop), by the same series written V = τ W(τ) (``_series_depart`` with lag 1) instead of START (with
#: DEPARTURE_SERIES only; docs/building.md, "Fewer pieces per slide").
LEAVE_SERIES = True
#: A slide's series piece slowing along its direction runs to e0·V = STOP_REACH r0 (the kernel's ``STOP_REACH``)
#: instead of to half its speed, its length held so that the series' tail keeps the halving's bound.
STOP_REACH_SERIES = True
#: ... and such a piece ends at the stop itself when the stop lies within it (e0·V = 0 located on the series, the
#: speed left there below FINISH's entry speed 1e-10 v_ref) instead of at STOP_REACH r0 and a FINISH piece
#: (with STOP_REACH_SERIES only; docs/building.md, "The stop in one piece").
STOP_PIECE = True
#: Truncation tolerance of the friction's polynomial in a fast sub-step, relative to µk N and |V| (the kernel's
#: law[10], default ``planar_building_kernel.FAST_TRUNC_EPS`` = 1e-12, the fraction its end check FAST_CHECK
#: accepts): 1e-16 is the previous rule, the pieces' own; 1e-12 lengthens the rungs near stops and departures, the
#: answers moving at rounding (docs/building.md, h114).
FAST_TRUNC_EPS = _pk.FAST_TRUNC_EPS
#: The range of FAST_TRUNC_EPS measured (docs/building.md, h172): from the pieces' own 1e-16 to 1e-2 the answer stays
#: within 6.3e-13 of the default's on the bench's PTS 0-20 s (the sub-steps' end check FAST_CHECK bounds it), but
#: above the default every looser value is slower (the end check refuses the longer rungs).  Outside it (or NaN,
#: or ≤ 0, which the kernel would silently replace by its default) :func:`simulate_planar_building` refuses.
FAST_TRUNC_EPS_RANGE = (1e-16, 1e-2)
#: The fast sub-steps' end check (the kernel's law[11], default ``planar_building_kernel.FAST_CHECK`` = 1e-12): the
#: friction at a sub-step's end from its polynomial and from V/|V| of the propagated state agree to this fraction of
#: µk N, or the sub-step is redone by series pieces.  It, not FAST_TRUNC_EPS, bounds the sub-steps' friction error.
#: With FAST_TRUNC_EPS at the same value the looser pair is a little faster (1e-8: 5-9 % less CPU on PTS, YER, DZC
#: 0-20 s, the bench's error against the independent reference 1.1e-11 -> 3.4e-11; docs/building.md, h184).
FAST_CHECK = _pk.FAST_CHECK
#: The range of FAST_CHECK measured (docs/building.md, h184): from 1e-14 (below it rounding of the check itself
#: refuses sub-steps) to 1e-6 (the sub-steps' friction error ~1e-6 µk N: the answers ~1e-8 of their scale).  Outside
#: it (or NaN) :func:`simulate_planar_building` refuses.
FAST_CHECK_RANGE = (1e-14, 1e-6)


@dataclass
class PlanarBuildingSystem:
    """The matrices of one building on its isolation plane, both directions (SI units)."""

    n_floors: int
    masses_kg: np.ndarray
    slab_mass_kg: float
    total_mass_kg: float
    floor_heights_m: np.ndarray
    story_heights_m: np.ndarray
    stiffness_matrices: tuple  #: K_s along x and y [N/m]
    damping_matrices: tuple  #: C_s along x and y [N·s/m]
    isolator_stiffness_N_per_m: float
    isolator_damping_Ns_per_m: float
    mu_static: float
    mu_kinetic: float
    gravity_m_s2: float
    a_mat: np.ndarray = field(repr=False)  #: [phase (stuck, sliding), direction, m, m]
    g_vec: np.ndarray = field(repr=False)
    p_vec: np.ndarray = field(repr=False)
    l_d: np.ndarray = field(repr=False)
    #: the largest |eigenvalue| of the stuck and sliding matrices [1/s]: a piece turns the fastest mode by
    #: at most THETA rad (the series' own truncation rule bounds its length too)
    fastest_rate_per_s: float = 0.0
    #: the 1-D building's systems along x and y (their augmented matrices and energy forms)
    directions: tuple = field(default=(), repr=False)
    #: the fast sub-steps' tables, by (sub-step length, watched rows), and the kernel's tables and watched rows by
    #: (sub-step length, bearing layout) (:func:`_run_tables`), reused by later runs of this system
    cache: dict = field(default_factory=dict, repr=False)

    @property
    def weight_N(self) -> float:
        return self.total_mass_kg * self.gravity_m_s2

    @property
    def superstructure_weight_N(self) -> float:
        return float(self.masses_kg.sum()) * self.gravity_m_s2


def planar_building_system(superstructure, *, total_mass_kg: float, stiffness_N_per_m: float, mu_static: float,
                           mu_kinetic: float | None = None, damping_Ns_per_m: float = 0.0,
                           gravity_m_s2: float = STANDARD_GRAVITY) -> PlanarBuildingSystem:
    """The 2-D system: the 1-D building's matrices (:func:`building_system`) along x and along y.

    Parameters are those of :func:`isolator.solver.building.building_system`.
    """
    per_direction = [building_system(superstructure, total_mass_kg=total_mass_kg, stiffness_N_per_m=stiffness_N_per_m,
                                     mu_static=mu_static, mu_kinetic=mu_kinetic, damping_Ns_per_m=damping_Ns_per_m,
                                     gravity_m_s2=gravity_m_s2, direction=d) for d in DIRECTIONS]
    first = per_direction[0]
    n = first.n_floors
    m = 2 * n + 2
    a_mat = np.zeros((2, 2, m, m))
    g_vec = np.zeros((2, 2, m))
    p_vec = np.zeros((2, m))
    l_d = np.zeros((2, m))
    shift = np.zeros((m, m))  # u' = u̇ (and x_b' = v_b sliding): the kernel writes these rows without products
    shift[2:2 + n, 2 + n:] = np.eye(n)
    for d, system in enumerate(per_direction):
        for phase in range(2):
            a_mat[phase, d] = system.a_modes[phase][:m, :m]
            g_vec[phase, d] = system.a_modes[phase][:m, system.AG]
            expected = shift.copy()
            expected[0, 1] = float(phase == 1)
            rows = [0, *range(2, 2 + n)]
            if not (np.array_equal(a_mat[phase, d][rows], expected[rows]) and not np.any(g_vec[phase, d][rows])):
                raise AssertionError("the building's matrices lost the structure the 2-D kernel relies on")
        # the friction force F_d along the sliding velocity: the 1-D friction column (f = s µk W)
        p_vec[d] = system.a_modes[1][:m, system.F]
        # the force on the slab other than friction, D = 1ᵀ(K_s u + C_s u̇) − K x_b − c v_b − m_b a_g
        l_d[d] = system.ell_hold[:m]
        l_d[d, 1] = -system.isolator_damping_Ns_per_m
    return PlanarBuildingSystem(
        n_floors=n, masses_kg=first.masses_kg, slab_mass_kg=first.slab_mass_kg, total_mass_kg=first.total_mass_kg,
        floor_heights_m=first.floor_heights_m, story_heights_m=first.story_heights_m,
        stiffness_matrices=tuple(s.stiffness_matrix for s in per_direction),
        damping_matrices=tuple(s.damping_matrix for s in per_direction),
        isolator_stiffness_N_per_m=first.isolator_stiffness_N_per_m,
        isolator_damping_Ns_per_m=first.isolator_damping_Ns_per_m, mu_static=first.mu_static,
        mu_kinetic=first.mu_kinetic, gravity_m_s2=first.gravity_m_s2, a_mat=a_mat, g_vec=g_vec, p_vec=p_vec, l_d=l_d,
        fastest_rate_per_s=max(float(np.max(np.abs(np.linalg.eigvals(a_mat[phase, d])))) for phase in range(2)
                               for d in range(2)), directions=tuple(per_direction))


def _augmented(system: PlanarBuildingSystem) -> np.ndarray:
    """Ã per phase and direction on w̃ = [z, a_g, ȧ_g, c_0 … c_K]: the 1-D building's augmented matrix
    (whose friction entry f is c_0) with the chain c_j' = (j + 1) c_{j+1} of the friction's polynomial."""
    m = 2 * system.n_floors + 2
    size = m + 3 + _pk.FAST_ORDER
    aug = np.zeros((2, 2, size, size))
    for d, one in enumerate(system.directions):
        for phase in range(2):
            aug[phase, d, :m + 3, :m + 3] = one.a_modes[phase]
            for j in range(_pk.FAST_ORDER):
                aug[phase, d, m + 2 + j, m + 3 + j] = j + 1.0
    return aug


def _fast_tables(system: PlanarBuildingSystem, h: float, watched: tuple) -> tuple:
    """The fast sub-steps' tables for the sub-step length h (see :func:`planar_building_kernel.building2d_kernel`):
    e^{Ãh}'s rows, the input rows, the viscous form, V's rows, Ã's and Ã²'s rows, the watched rows' powers, then the
    kernel's column-ordered copies of the first, of V's rows and of the watched rows' first two powers.

    e^{Ãh} and the Van Loan forms depend on (system, h) only and are kept in ``system.cache``; the
    watched quantities' rows ℓÃ^j/j! also on the watched rows (the bearing layout).
    """
    from scipy.linalg import expm

    m = 2 * system.n_floors + 2
    # e^{Ãh} and the forms do not depend on the friction (a review's bounds share them): keyed by the matrices
    key = ("propagators", h, *(a.tobytes() for one in system.directions for a in (one.a_modes, one.q_in,
                                                                                  one.q_vis)))
    if key in _PROPAGATORS:
        system.cache[key] = _PROPAGATORS[key]
    if key not in system.cache:
        aug = _augmented(system)
        size = aug.shape[-1]
        levels = _pk.FAST_LEVELS
        prop = np.empty((levels, 2, 2, m, size))
        p_in_rows = np.empty((levels, 2, 2, 2, size))
        p_vis = np.empty((levels, 2, 2, size, size))
        for d, one in enumerate(system.directions):
            q_in = np.zeros((size, size))
            q_vis = np.zeros((size, size))
            q_in[:m + 3, :m + 3] = one.q_in
            q_vis[:m + 3, :m + 3] = one.q_vis
            ell = _input_row(q_in, m)
            for phase in range(2):
                # on the chain scaled to each rung, ĉ_j = c_j h_l^j (the kernel's entries are then of one
                # size): the shortest rung by one exponential each, the longer ones by doubling,
                # e^{2Ãh} = (e^{Ãh})², P(2h) = P(h) + e^{Ãᵀh} P(h) e^{Ãh}, then rescaled ĉ_j → 2^j ĉ_j
                h_short = h / 2 ** (levels - 1)
                scale = np.ones(size)
                scale[m + 2:] = h_short ** np.arange(_pk.FAST_ORDER + 1)
                scaled = aug[phase, d] * scale[:, None] / scale[None, :]
                step = expm(scaled * h_short)
                rows_in = _power_rows(scaled, ell, h_short)
                form_vis = van_loan(scaled, q_vis, h_short)
                double = np.ones(size)
                double[m + 2:] = 2.0 ** np.arange(_pk.FAST_ORDER + 1)
                linear = aug[phase, d, :m + 2, :m + 2]
                for lev in range(levels - 1, -1, -1):
                    prop[lev, phase, d] = step[:m]
                    p_in_rows[lev, phase, d] = rows_in
                    p_vis[lev, phase, d] = form_vis
                    # the linear block [z, a_g, ȧ_g] on its own (its exponential is not widened by the chain's
                    # norm): the energy balance closes to ~1e-14 with it, ~1e-12 from the whole matrix
                    h_lev = h / 2 ** lev
                    prop[lev, phase, d, :, :m + 2] = expm(linear * h_lev)[:m]
                    p_in_rows[lev, phase, d, :, :m + 2] = _power_rows(linear, ell[:m + 2], h_lev)
                    p_vis[lev, phase, d, :m + 2, :m + 2] = van_loan(linear, q_vis[:m + 2, :m + 2], h_lev)
                    if lev > 0:
                        # ∫₀^{2h} = ∫₀^h + (∫₀^h, shifted by h) e^{Ãh}: R1 += R1 E, R2 += (R2 + h R1) E
                        rows_in = np.stack([rows_in[0] + rows_in[0] @ step,
                                            rows_in[1] + (rows_in[1] + h_lev * rows_in[0]) @ step]) / double[None, :]
                        form_vis = (form_vis + step.T @ form_vis @ step) / double[:, None] / double[None, :]
                        step = (step @ step) * double[:, None] / double[None, :]
        rate1 = np.ascontiguousarray(aug[:, :, :m, :m + 4])
        rate2 = np.ascontiguousarray(np.einsum("pdij,pdjk->pdik", aug[:, :, :m, :], aug[:, :, :, :m + 4]))
        v_rows = np.empty((2, _pk.FAST_ORDER + 1, size))
        for d in range(2):
            row = np.zeros(size)
            row[1] = 1.0
            for k in range(_pk.FAST_ORDER + 1):
                v_rows[d, k] = row
                row = row @ aug[1, d] / (k + 1)
        # symmetric to rounding; the kernel reads the upper triangle
        p_vis = 0.5 * (p_vis + np.swapaxes(p_vis, -1, -2))
        system.cache[key] = (aug, prop, p_in_rows, p_vis, v_rows, rate1, rate2, *_pk.by_columns(prop, v_rows))
        if len(_PROPAGATORS) >= _SYSTEMS_MAX:
            _PROPAGATORS.pop(next(iter(_PROPAGATORS)))
        _PROPAGATORS[key] = system.cache[key]
    aug, prop, p_in_rows, p_vis, v_rows, rate1, rate2, prop_t, v_t = system.cache[key]
    m1, m2, m3, sig1, sig2, sig3 = watched
    wkey = ("watched", h, *(a.tobytes() for a in watched))
    if wkey not in system.cache:
        size = aug.shape[-1]
        nk, nj = m1.shape[0], sig1.shape[0]
        mon = np.empty((2, nk, 2, _pk.FAST_POW, size))
        sig = np.empty((2, nj, 2, _pk.FAST_POW, size))
        for phase in range(2):
            for d in range(2):
                rate = aug[phase, d, :m]
                rows = np.zeros((nk + nj, size))
                rows[:nk, :m] = m1[:, d]
                rows[:nk] += m2[:, d] @ rate
                rows[:nk, m] += m3[:, d]
                rows[nk:, :m] = sig1[:, d]
                rows[nk:] += sig2[:, d] @ rate
                rows[nk:, m] += sig3[:, d]
                for j in range(_pk.FAST_POW):
                    mon[phase, :, d, j] = rows[:nk]
                    sig[phase, :, d, j] = rows[nk:]
                    rows = rows @ aug[phase, d] / (j + 1)
        if len(system.cache) > 16:
            system.cache.pop(next(iter(system.cache)))
        system.cache[wkey] = (mon, sig, _pk.end_rows(mon, sig, m))
    mon, sig, end = system.cache[wkey]
    return prop, p_in_rows, p_vis, v_rows, rate1, rate2, mon, sig, prop_t, v_t, end


def _layout_key(layout) -> tuple | None:
    """What the watched rows read of a bearing layout (positions and gravity loads), as a cache key (None: none)."""
    if layout is None:
        return None
    return tuple(np.asarray(v, dtype=np.float64).tobytes() for v in (layout.x_m, layout.y_m, layout.gravity_loads_N))


def _run_tables(system: PlanarBuildingSystem, layout, h: float | None) -> tuple:
    """(the watched rows of :func:`_watched`, the kernel's fast sub-step tables in its argument order) for the
    bearing layout and the sub-step length h (None: no fast sub-steps, tables of zeros), kept in ``system.cache``:
    they depend only on the system (the design), the layout and h, so a review's runs of one design build them once.
    """
    key = ("run", h, _layout_key(layout))
    if key not in system.cache:
        watched = _watched(system, layout)
        if h is not None:
            (prop, p_in_rows, p_vis, v_rows, rate1, rate2, mon, sig, prop_t, v_t,
             end) = _fast_tables(system, h, watched)
        else:
            m = 2 * system.n_floors + 2
            size = m + 3 + _pk.FAST_ORDER
            levels = _pk.FAST_LEVELS
            nk, nj = watched[0].shape[0], watched[3].shape[0]
            p_in_rows, p_vis = np.zeros((levels, 2, 2, 2, size)), np.zeros((levels, 2, 2, size, size))
            rate1 = rate2 = np.zeros((2, 2, m, m + 4))
            mon, sig = np.zeros((2, nk, 2, _pk.FAST_POW, size)), np.zeros((2, nj, 2, _pk.FAST_POW, size))
            prop_t, v_t = np.zeros((levels, 2, 2, size, m)), np.zeros((2, size, _pk.FAST_ORDER + 1))
            end = _pk.end_rows(mon, sig, m)
        if len(system.cache) > 16:
            system.cache.pop(next(iter(system.cache)))
        system.cache[key] = (watched, (prop_t, p_in_rows, p_vis, v_t, rate1, rate2, mon, sig, end))
    return system.cache[key]


def _input_row(q_in: np.ndarray, m: int) -> np.ndarray:
    """ℓ_p with w̃ᵀ Q_in w̃ = a_g (ℓ_p·w̃): the input power's form couples only a_g (entry m) with the state."""
    ell = 2.0 * q_in[m]
    rest = q_in.copy()
    rest[m] = 0.0
    rest[:, m] = 0.0
    if ell[m] != 0.0 or np.any(rest != 0.0) or not np.array_equal(q_in[:, m], q_in[m]):
        raise ValueError("the input power's form is not a_g times a row of the state")
    return ell


def _power_rows(a_mat: np.ndarray, ell: np.ndarray, h: float) -> np.ndarray:
    """[ℓ ∫₀^h e^{Aτ} dτ, ℓ ∫₀^h τ e^{Aτ} dτ] from one exponential of [[A, I, 0], [0, 0, I], [0, 0, 0]] h, whose
    blocks (1, 2) and (1, 3) are ∫₀^h e^{Aτ} dτ and ∫₀^h (h − τ) e^{Aτ} dτ (the input energy over a sub-step is
    a_g R1·w̃ + ȧ_g R2·w̃ with a_g, ȧ_g at its start)."""
    from scipy.linalg import expm

    s = a_mat.shape[0]
    block = np.zeros((3 * s, 3 * s))
    block[:s, :s] = a_mat
    block[:s, s:2 * s] = np.eye(s)
    block[s:2 * s, 2 * s:] = np.eye(s)
    e = expm(block * h)
    first = e[:s, s:2 * s]
    return np.stack([ell @ first, ell @ (h * first - e[:s, 2 * s:])])


def _watched(system: PlanarBuildingSystem, layout) -> tuple:
    """Rows of the watched quantities (resultants; signed overturning moments and bearing loads)."""
    n = system.n_floors
    m = 2 * n + 2
    nk = 2 * n + 4
    m1 = np.zeros((nk, 2, m))
    m2 = np.zeros((nk, 2, m))
    m3 = np.zeros((nk, 2))
    m_b = system.slab_mass_kg
    moment_rows = np.zeros(m)  # −Σ m_i H_i (ü_i + v̇_b) on ż, −Σ m_i H_i on a_d
    mh = system.masses_kg * system.floor_heights_m
    moment_rows[1] = -mh.sum()
    moment_rows[2 + n:] = -mh
    n_bearings = 0 if layout is None else layout.n_bearings
    nj = 2 + n_bearings
    sig1 = np.zeros((nj, 2, m))
    sig2 = np.zeros((nj, 2, m))
    sig3 = np.zeros((nj, 3))  # on a_x, a_y and the vertical a_z
    coefficients = None if layout is None else np.stack([layout.overturning_coefficients(d) for d in DIRECTIONS])
    for d in range(2):
        k_row = system.stiffness_matrices[d].sum(axis=0)
        c_row = system.damping_matrices[d].sum(axis=0)
        m1[0, d, 0] = 1.0
        m1[1, d, 1] = 1.0
        for i in range(n):
            m1[2 + i, d, 2 + i] = 1.0
            if i > 0:
                m1[2 + i, d, 1 + i] = -1.0
            m2[2 + n + i, d, 1] = 1.0
            m2[2 + n + i, d, 2 + n + i] = 1.0
            m3[2 + n + i, d] = 1.0
        for k in (2 + 2 * n, 3 + 2 * n):
            m1[k, d, 2:2 + n] = k_row
            m1[k, d, 2 + n:] = c_row
        m2[3 + 2 * n, d, 1] = -m_b
        m3[3 + 2 * n, d] = -m_b
        sig2[d, d] = moment_rows
        sig3[d, d] = -mh.sum()
        for j in range(n_bearings):
            sig2[2 + j, d] = coefficients[d, j] * moment_rows
            sig3[2 + j, d] = -coefficients[d, j] * mh.sum()
    if n_bearings:
        # the vertical's share of a bearing's load, P_k,g a_z/g (the floors and the slab move with the ground
        # vertically): zero without a vertical
        sig3[2:, 2] = np.asarray(layout.gravity_loads_N) / system.gravity_m_s2
    return m1, m2, m3, sig1, sig2, sig3


#: A sample whose x² + y² is within this fraction of the largest is a candidate for the largest hypot(x, y): the two
#: order the samples alike to a few ulp (x² + y² within 3 ulp of its exact value, hypot within 1), so the largest
#: hypot lies among the candidates (:func:`largest_resultant`)
RESULTANT_MARGIN = 1e-12
#: Below this x² + y² (squares near the subnormals, whose rounding is coarser) every sample is a candidate
RESULTANT_TINY = 1e-280


def largest_resultant(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """max over the last axis of hypot(x, y), per leading index — the same value as ``np.max(np.hypot(x, y),
    axis=-1)`` bit for bit, with hypot taken only at the candidates of :data:`RESULTANT_MARGIN` (hypot is ~10× the
    sum of squares; a record's resultant has one or two candidates).  Finite x and y (else: hypot throughout)."""
    with np.errstate(over="ignore", under="ignore"):
        squares = x * x + y * y
    top = np.max(squares, axis=-1, keepdims=True)
    if not np.all(np.isfinite(squares)):  # an overflowing square (|x| > 1e154) or a non-finite value
        return np.max(np.hypot(x, y), axis=-1)
    near = squares >= np.where(top < RESULTANT_TINY, 0.0, top * (1.0 - RESULTANT_MARGIN))
    return np.max(np.hypot(x, y, where=near, out=np.zeros(squares.shape)), axis=-1)


def sampled_floor(peaks, state, n: int):
    """The located peaks (slab displacement, slab velocity, story drifts: the kernel's order) held at or above the
    samples' own resultants: the largest value between samples can lie at a sample, where its series value may round
    below the sample's by an ulp or two (the bench case's slab peak by 2 ulp once the fast sub-steps' friction was cut at
    1e-12 µk N) — a peak under one of its own samples would be a contradiction, not a located value.

    ``state`` is the kernel's (samples, 2, m) history (x_b, v_b, the n floors' u, their u̇ per direction); a story's
    drift at a sample is u_i − u_{i−1} (u_0 = 0), as the response's floor displacements give it."""
    drift = np.empty((2, n, state.shape[0]))  # by direction and story, the samples contiguous
    for d in range(2):
        floors = state[:, d, 2:2 + n].T
        drift[d, 0] = floors[0] - 0.0
        np.subtract(floors[1:], floors[:-1], out=drift[d, 1:])
    out = peaks.copy()
    slab = largest_resultant(np.stack([state[:, 0, 0], state[:, 0, 1]]), np.stack([state[:, 1, 0], state[:, 1, 1]]))
    out[0] = max(out[0], float(slab[0]))
    out[1] = max(out[1], float(slab[1]))
    out[2:2 + n] = np.maximum(out[2:2 + n], largest_resultant(drift[0], drift[1]))
    return out


def _by_floor(state: np.ndarray, first: int, n: int) -> np.ndarray:
    """(samples, n, 2) of the state's columns first … first + n − 1 per direction (a contiguous copy)."""
    out = np.empty((state.shape[0], n, 2))
    out[:, :, 0] = state[:, 0, first:first + n]
    out[:, :, 1] = state[:, 1, first:first + n]
    return out


@dataclass(kw_only=True)
class PlanarBuildingResponse(BuildingKeys, SolverResult):
    """Response of the building on its isolation plane to a pair (SI units; energies per unit of the total mass).

    The histories of the slab are (N, 2); ``floor_displacement_m`` and ``floor_velocity_m_s`` are
    (N, floors, 2), relative to the slab; ``floor_absolute_acceleration_m_s2`` (N, floors, 2).
    Peaks are of the resultants in the plane, exact (located between samples).
    """

    EXTRA_SUMMARY_KEYS = BuildingResponse.EXTRA_SUMMARY_KEYS

    system: System
    building: PlanarBuildingSystem
    floor_displacement_m: np.ndarray
    floor_velocity_m_s: np.ndarray
    floor_absolute_acceleration_m_s2: np.ndarray
    superstructure_shear_N: np.ndarray  #: (N, 2) first story's spring + damper shear
    isolator_force_N: np.ndarray  #: (N, 2) spring + dashpot + friction on the slab
    overturning_moment_Nm: np.ndarray  #: (N, 2): Σ F_i H_i from the loading along x and along y
    event_displacement_m: np.ndarray  #: (events, 2)
    peak_resultants: np.ndarray = field(repr=False)
    signed_max: np.ndarray = field(repr=False)
    signed_min: np.ndarray = field(repr=False)
    energy_strain_final_J_per_kg: float = 0.0
    n_pieces: int = 0  #: series pieces
    n_fast_steps: int = 0  #: sub-steps by the exact propagators
    #: fast sub-steps refused (run as series pieces): the friction's series not at rounding, its end check, an
    #: event possible, V = 0
    n_fast_refused: tuple = ()
    #: series pieces by phase: stuck, start (leaving rest), slide, finish (the last of a stop), approach (in ln s)
    n_pieces_by_phase: tuple = ()
    #: slides whose slowing series piece ran to the stop itself (``STOP_PIECE``)
    n_stop_pieces: int = 0
    n_extrema_located: int = 0
    bearing_layout: object = None
    residual_displacement_x_m: float = 0.0
    residual_displacement_y_m: float = 0.0
    model: str = MODEL_NAME
    model_reason: str = MODEL_REASON
    #: the vertical ground acceleration analysed [m/s²] (None: none)
    vertical_acceleration_m_s2: np.ndarray | None = None
    uplift_time_s = 0.0  #: time with g + a_z ≤ 0 [s]: such a vertical is refused, so none
    n_uplifts = 0

    @property
    def configuration(self) -> str:
        """The paper's configuration of the equivalent single bearing (1 to 4)."""
        return self.system.configuration

    @property
    def story_drift_m(self) -> np.ndarray:
        """Peak resultant drift per story, bottom to top [m] (exact)."""
        n = self.building.n_floors
        return self.peak_resultants[2:2 + n].copy()

    @property
    def story_drift_ratio(self) -> np.ndarray:
        """Peak resultant drift / story height, bottom to top [-]."""
        return self.story_drift_m / self.building.story_heights_m

    @property
    def floor_peak_acceleration_m_s2(self) -> np.ndarray:
        """Peak resultant absolute acceleration per floor, bottom to top [m/s²] (exact)."""
        n = self.building.n_floors
        return self.peak_resultants[2 + n:2 + 2 * n].copy()

    @property
    def superstructure_shear_coefficient(self) -> float:
        """Peak resultant first-story shear (spring + damper) / W_s [-]."""
        n = self.building.n_floors
        return float(self.peak_resultants[2 + 2 * n]) / self.building.superstructure_weight_N

    @property
    def base_shear_coefficient(self) -> float:
        """Peak resultant isolator force (spring + dashpot + friction) / W [-]."""
        n = self.building.n_floors
        return float(self.peak_resultants[3 + 2 * n]) / self.building.weight_N

    @property
    def energy_balance_error_J(self) -> float:
        """input − (kinetic + strain + potential + friction + viscous) [J]."""
        return self.energy_balance_error_J_per_kg * self.building.total_mass_kg

    def bearing_loads(self) -> dict | None:
        """Axial loads of the bearings (:func:`isolator.superstructure.bearing_axial_loads`), extremes exact.

        The overturning from both directions and the vertical, P_k = P_k,g (1 + a_z/g) + ΔP_k,x M_x + ΔP_k,y M_y;
        the maximum and minimum of each bearing are located between samples; the uplift start and duration
        come from the samples (linear between them).
        """
        if self.bearing_layout is None:
            return None
        from isolator.superstructure import bearing_axial_loads

        az = self.vertical_acceleration_m_s2
        out = bearing_axial_loads(self.bearing_layout, self.overturning_moment_Nm[:, 0], self.time_s,
                                  moment_y_Nm=self.overturning_moment_Nm[:, 1],
                                  vertical_factor=None if az is None else 1.0 + az / self.building.gravity_m_s2)
        gravity = np.asarray(self.bearing_layout.gravity_loads_N)
        high = gravity + self.signed_max[2:]
        low = gravity + self.signed_min[2:]
        out["bearing_axial_load_max_N"] = high.tolist()
        out["bearing_axial_load_min_N"] = low.tolist()
        out["n_bearings_uplifted"] = int(np.sum(low < 0.0))
        return out



def scene_needs(scene) -> tuple[str, str] | None:
    """``(model, reason)`` when the scene's design has a superstructure and the scene more than one component,
    a vertical or µ(v) (the 2-D building carries N(t) and µ(v); the 1-D building does not)."""
    design = scene.design
    if design is None or getattr(design, "superstructure", None) is None:
        return None
    if not (scene.has_y or scene.has_z or scene.velocity_dependent):
        return None
    return MODEL_NAME, scene_reason(has_y=scene.has_y, has_z=scene.has_z,
                                    velocity_dependent=scene.velocity_dependent)


def scene_reason(*, has_y: bool, has_z: bool, velocity_dependent: bool) -> str:
    """The reason the registry prints for this model: the scene features that chose it.

    Parameters
    ----------
    has_y, has_z : bool
        The scene has a second horizontal component, a vertical one.
    velocity_dependent : bool
        The friction depends on the sliding speed (µ(v)).

    Returns
    -------
    str
        E.g. "a superstructure above the isolation plane under two horizontal components and a vertical
        (N = W (1 + a_z/g)): the 2-D building (friction coupled in the plane)".
    """
    features = ["two horizontal components" if has_y else "one horizontal component"]
    if has_z:
        features.append("a vertical (N = W (1 + a_z/g))")
    if velocity_dependent:
        features.append("velocity-dependent friction µ(v)")
    text = features[0] if len(features) == 1 else ", ".join(features[:-1]) + " and " + features[-1]
    # without a pair the 1-D building would have run had it carried the vertical / µ(v): say so
    why = "" if has_y else f" (the 1-D building does not carry {'them' if has_z and velocity_dependent else 'it'})"
    return (f"a superstructure above the isolation plane under {text}: the 2-D building "
            f"(friction coupled in the plane){why}")


def simulate_scene(scene) -> PlanarBuildingResponse:
    """The 2-D building's response to a scene (:func:`simulate_planar_building`; a missing a_y is zero, a
    vertical and µ(v) are carried)."""
    design = scene.design
    iso = {key: value for key, value in scene.isolator.items() if value is not None}
    g = float(iso.get("gravity_m_s2", design.gravity_m_s2))
    mass = design.mass_kg
    if iso.get("radius_m") is not None:
        stiffness = mass * g / float(iso["radius_m"])
    else:
        stiffness = mass * float(iso.get("stiffness_per_mass", 0.0))
    ax = np.asarray(scene.ax_m_s2, dtype=np.float64)
    ay = np.zeros_like(ax) if scene.ay_m_s2 is None else scene.ay_m_s2
    with naming_design(design):
        return simulate_planar_building(
            ax, ay, scene.dt_s, time_s=scene.time_s, superstructure=design.superstructure, total_mass_kg=mass,
            stiffness_N_per_m=stiffness, mu_static=float(iso["mu_static"]), mu_kinetic=iso.get("mu_kinetic"),
            damping_Ns_per_m=mass * float(iso.get("damping_per_mass", 0.0)), gravity_m_s2=g,
            bearing_layout=design.bearing_layout, az_m_s2=scene.az_m_s2, pendulum=iso.get("radius_m") is not None,
            mu_slow=iso.get("mu_slow"), mu_fast=iso.get("mu_fast"), rate_s_per_m=iso.get("rate_s_per_m"))


_READY = False
#: Systems built by :func:`simulate_planar_building`, by their parameters, with their propagators (a review
#: runs one system on many pairs)
_SYSTEMS: dict = {}
_SYSTEMS_MAX = 32
#: the fast sub-steps' propagators by (h, the matrices), shared by systems that differ only in friction
_PROPAGATORS: dict = {}


def _warm_up() -> None:
    # load (or compile) the kernel on a tiny problem so that solver_seconds measures solving
    global _READY
    if _READY:
        return
    from isolator.solver.notice import note_if_slow
    from isolator.superstructure import Floor, Superstructure

    with note_if_slow("compiling the 2-D building solver (its first use after installation takes a few seconds; "
                      "the machine code is cached for later runs)"):
        s = Superstructure(floors=(Floor(1.0, 1.0, 100.0, 100.0),), damping_ratio=0.05, gravity_m_s2=9.81)
        acc = np.array([0.0, 5.0, -5.0])
        system = planar_building_system(s, total_mass_kg=2.0, stiffness_N_per_m=10.0, mu_static=0.1)
        _run(system, acc, acc[::-1].copy(), _timing(system, acc, 0.01, None), None)
    _READY = True


def _check_component(name: str, values) -> np.ndarray:
    acc = np.ascontiguousarray(values, dtype=np.float64)
    if acc.ndim != 1 or acc.size < 2:
        raise RecordInputError(f"{name} must be one-dimensional with at least two samples")
    if not np.all(np.isfinite(acc)):
        raise RecordInputError(f"{name} holds NaN or infinite values")
    return acc


def simulate_planar_building(ax_m_s2, ay_m_s2, dt_s: float | None = None, *, time_s=None, superstructure,
                             total_mass_kg: float, stiffness_N_per_m: float, mu_static: float,
                             mu_kinetic: float | None = None, damping_Ns_per_m: float = 0.0,
                             gravity_m_s2: float = STANDARD_GRAVITY, bearing_layout=None, az_m_s2=None,
                             pendulum: bool = False, mu_slow: float | None = None, mu_fast: float | None = None,
                             rate_s_per_m: float | None = None) -> PlanarBuildingResponse:
    """Response of a shear building on a friction isolation plane to two horizontal components.

    Parameters
    ----------
    ax_m_s2, ay_m_s2 : array_like
        Ground acceleration along x and y [m/s²], linear between samples, one time base.
    dt_s : float, optional
        Sample interval [s] (or ``time_s``).
    time_s : array_like, optional
        Sample times [s]; unequal steps are solved interval by interval.
    superstructure : isolator.superstructure.Superstructure
    total_mass_kg, stiffness_N_per_m, mu_static, mu_kinetic, damping_Ns_per_m, gravity_m_s2
        As for :func:`isolator.solver.building.simulate_building`.
    bearing_layout : isolator.superstructure.BearingLayout, optional
        For the bearings' axial loads.
    az_m_s2 : array_like, optional
        Vertical ground acceleration [m/s²], up positive, linear between samples: the normal force is
        N(t) = W (1 + a_z/g) (the floors move rigidly with the slab vertically); the friction is µ N(t), the
        static limit µs N(t) and, with ``pendulum``, the restoring force N(t)/R X (its work ½∫(Ṅ/R)|X|² dt
        is in the input energy, as the 2-D rigid block counts it). g + a_z ≤ 0 (uplift) is refused.
    pendulum : bool
        The restoring stiffness is W/R of a friction pendulum (it follows N(t)); else a spring (it does not).
    mu_slow, mu_fast, rate_s_per_m : float, optional
        Velocity-dependent friction µ(v) = µ_fast − (µ_fast − µ_slow) e^{−a|V|}, a = rate_s_per_m [s/m]; all
        three or none, not with ``mu_kinetic``; µ_slow ≤ µ_fast and µ_slow ≤ µs.

    Returns
    -------
    PlanarBuildingResponse
    """
    parameters = dict(total_mass_kg=float(total_mass_kg), stiffness_N_per_m=float(stiffness_N_per_m),
                      mu_static=float(mu_static), mu_kinetic=None if mu_kinetic is None else float(mu_kinetic),
                      damping_Ns_per_m=float(damping_Ns_per_m), gravity_m_s2=float(gravity_m_s2))
    key = (superstructure, *sorted(parameters.items()))
    system = _SYSTEMS.get(key)
    if system is None:
        system = planar_building_system(superstructure, **parameters)
        if len(_SYSTEMS) >= _SYSTEMS_MAX:
            _SYSTEMS.pop(next(iter(_SYSTEMS)))
        _SYSTEMS[key] = system
    ax = _check_component("ax", ax_m_s2)
    ay = _check_component("ay", ay_m_s2)
    if ax.shape != ay.shape:
        raise RecordInputError(f"the two components differ in length ({ax.size} and {ay.size} samples)")
    if time_s is None and dt_s is None:
        raise TypeError("give dt_s or time_s")
    normal = _normal_force(ax.size, az_m_s2, pendulum, mu_static, mu_kinetic, mu_slow, mu_fast, rate_s_per_m,
                           float(gravity_m_s2))
    timing = _timing(system, ax, dt_s, time_s)  # refused before the kernel is loaded
    _warm_up()
    return _run(system, ax, ay, timing, bearing_layout, normal)


@dataclass(frozen=True)
class _Normal:
    """The vertical and µ(v) of a run: a_z [m/s²] (or None), whether the stiffness follows N, µ(v)'s law."""

    az: np.ndarray | None
    pendulum: bool
    mu_slow: float | None
    mu_fast: float | None
    rate_s_per_m: float = 0.0

    @property
    def varying(self) -> bool:
        """A vertical that is not zero, or µ(v) (a zero vertical runs today's constant-N code, bit for bit)."""
        return (self.az is not None and bool(np.any(self.az != 0.0))) or self.mu_fast is not None


def _normal_force(n, az_m_s2, pendulum, mu_static, mu_kinetic, mu_slow, mu_fast, rate_s_per_m, g) -> _Normal:
    """The vertical (checked: finite, the record's length, no uplift) and µ(v)'s law (checked as the 2-D rigid
    block checks it)."""
    law = (mu_slow, mu_fast, rate_s_per_m)
    given = [v is not None for v in law]
    if any(given) and not all(given):
        missing = [k for k, v in zip(("mu_slow", "mu_fast", "rate_s_per_m"), law, strict=True) if v is None]
        raise InvalidSystemError(f"velocity-dependent friction needs mu_slow, mu_fast and rate_s_per_m; "
                                 f"missing {', '.join(missing)}")
    slow = fast = None
    rate = 0.0
    if all(given):
        if mu_kinetic is not None:
            raise InvalidSystemError("give mu_kinetic or (mu_slow, mu_fast, rate_s_per_m), not both")
        slow = check_friction_coefficient("mu_slow", mu_slow)
        fast = check_friction_coefficient("mu_fast", mu_fast)
        rate = check_friction_rate(rate_s_per_m)
        if slow > fast:
            raise InvalidSystemError(f"mu_slow ({slow}) must not exceed mu_fast ({fast})")
        if slow > float(mu_static):
            raise InvalidSystemError(f"mu_slow ({slow}) must not exceed mu_static ({mu_static})")
    az = None
    if az_m_s2 is not None:
        az = _check_component("az", az_m_s2)
        if az.size != n:
            raise RecordInputError(f"the vertical has {az.size} samples, the horizontals {n}")
        lowest = int(np.argmin(az))
        if g + az[lowest] <= 0.0:
            raise InvalidSystemError(f"the vertical lifts the building off its isolators (g + a_z = "
                                     f"{g + az[lowest]:.4g} m/s² at sample {lowest}): uplift of a building is "
                                     "not modelled")
    return _Normal(az, bool(pendulum), slow, fast, rate)


def _timing(system: PlanarBuildingSystem, ax, dt_s, time_s) -> tuple:
    """(dt, relative times or None, t0, fast sub-steps per interval); refuses more than MAX_SUBSTEPS_PER_INTERVAL
    fast sub-steps (the fastest mode turns by at most THETA_FAST in one) in the longest interval
    (:func:`~isolator.solver.record.building_substeps`, the 1-D buildings' rule)."""
    if time_s is not None:
        times = np.asarray(time_s, dtype=np.float64)
        if times.shape != ax.shape:
            raise RecordInputError(f"time ({times.shape}) and acceleration ({ax.shape}) differ in length")
        dt, relative = sample_timing(times)
        t0 = float(times[0])
    else:
        dt = float(dt_s)
        if not (math.isfinite(dt) and dt > 0.0):
            raise RecordInputError(f"dt must be a finite number > 0, got {dt_s!r}")
        relative, t0 = None, 0.0
    rate = system.fastest_rate_per_s
    n_sub = building_substeps(dt, relative, _pk.THETA_FAST / rate if rate > 0 else math.inf,
                              f"the building's fastest rate {rate:.3g} 1/s")
    return dt, relative, t0, n_sub


def _check_settings() -> None:
    """The module's run-time settings, each of its kind and in its range, or a one-line ValueError (a text such as
    FAST_TRUNC_EPS = "1e-10" was a TypeError from the comparison; a text "no" as STOP_PIECE read as true)."""
    numbers = (("planar_building_kernel.N_ORDER", _pk.N_ORDER, ORDER_RANGE, "tested range", True),
               ("planar_building.FAST_TRUNC_EPS", FAST_TRUNC_EPS, FAST_TRUNC_EPS_RANGE, "measured range", False),
               ("planar_building.FAST_CHECK", FAST_CHECK, FAST_CHECK_RANGE, "measured range", False))
    for name, value, (low, high), why, whole in numbers:
        kinds = (int, np.integer) if whole else (int, float, np.integer, np.floating)
        if isinstance(value, (bool, np.bool_)) or not isinstance(value, kinds):
            raise ValueError(f"{name} = {value!r} is not {'a whole number' if whole else 'a number'} (a run-time "
                             f"setting in {low:g} … {high:g}, {why})")
        if not low <= value <= high:
            raise ValueError(f"{name} = {value!r} is outside {(low, high)} ({why})")
    for name in ("STOP_APPROACH", "DEPARTURE_SERIES", "LEAVE_SERIES", "STOP_REACH_SERIES", "STOP_PIECE"):
        value = globals()[name]
        if not isinstance(value, (bool, np.bool_)):
            raise ValueError(f"planar_building.{name} = {value!r} is not True or False (a run-time setting)")


def _run(system: PlanarBuildingSystem, ax, ay, timing: tuple, bearing_layout,
         normal: _Normal | None = None) -> PlanarBuildingResponse:
    """The kernel on a record; ``timing`` from :func:`_timing` (the public entry's: checked once)."""
    dt, relative, t0, n_sub = timing
    rate = system.fastest_rate_per_s
    _check_settings()
    h_max = _pk.THETA / rate if rate > 0 else math.inf
    n = system.n_floors
    m = 2 * n + 2
    weights = np.ones(m)
    weights[0] = weights[2:2 + n] = max(rate, 1e-300)
    weight = system.weight_N
    shortest = dt if relative is None else float(np.min(np.diff(relative)))
    v_ref = max(system.mu_static * system.gravity_m_s2, float(np.max(np.abs(ax))), float(np.max(np.abs(ay))),
                1e-12) * shortest
    # fast sub-steps (uniform records): the fastest mode turns by at most THETA_FAST in one
    # the exact propagators hold a constant A and a constant µ: with a vertical or µ(v) the kernel takes them
    # while stuck only (the floors' fixed-base system), sliding by series pieces
    n_fast = 0 if relative is not None else n_sub
    watched, tables = _run_tables(system, bearing_layout, dt / n_fast if n_fast > 0 else None)
    m1, m2, m3, sig1, sig2, sig3 = watched
    n_samples = ax.size
    nk, nj = m1.shape[0], sig1.shape[0]
    out_state = np.empty((n_samples, 2, m))
    out_mon = np.empty((n_samples, nk, 2))
    out_sig = np.empty((n_samples, nj))
    out_energy = np.zeros((3, n_samples))  # the kernel writes from sample 1 on; at sample 0 no work is done yet
    peak_sq = np.empty(nk)
    sig_max = np.empty(nj)
    sig_min = np.empty(nj)
    summary = np.zeros(_pk.SUMMARY_SIZE)
    c_floor = np.ascontiguousarray(np.stack(system.damping_matrices))
    kernel_times = np.empty(0) if relative is None else np.ascontiguousarray(relative)
    normal = normal or _Normal(None, False, None, None)
    g = system.gravity_m_s2
    k_vert = system.isolator_stiffness_N_per_m if normal.pendulum else 0.0
    mu_k_n = system.mu_kinetic * weight
    law = np.zeros(12)
    law[1] = g
    law[5] = 1.0 if STOP_APPROACH else 0.0
    law[6] = 1.0 if DEPARTURE_SERIES else 0.0
    law[7] = 1.0 if LEAVE_SERIES else 0.0
    law[8] = 1.0 if STOP_REACH_SERIES else 0.0
    law[9] = 1.0 if STOP_PIECE else 0.0
    law[10] = FAST_TRUNC_EPS
    law[11] = FAST_CHECK
    if normal.varying:
        law[0] = 1.0
        law[2] = k_vert
        if normal.mu_fast is not None:
            mu_k_n = normal.mu_fast * weight
            law[3] = (normal.mu_fast - normal.mu_slow) * weight
            law[4] = normal.rate_s_per_m
    az = np.zeros(ax.size) if normal.az is None else np.ascontiguousarray(normal.az)
    capacity = 64 + n_samples // 4
    while True:
        ev_time = np.empty(capacity)
        ev_kind = np.empty(capacity, dtype=np.int8)
        ev_x = np.empty((capacity, 2))
        start = time.perf_counter()
        _pk.building2d_kernel(ax, ay, az, law, dt, kernel_times, h_max, _pk.N_ORDER, system.a_mat, system.g_vec, system.p_vec, system.l_d,
                              weights, system.slab_mass_kg, system.total_mass_kg, system.masses_kg,
                              system.isolator_damping_Ns_per_m, c_floor, system.mu_static * weight,
                              mu_k_n, v_ref, m1, m2, m3, sig1, sig2, sig3, n_fast, *tables,
                              out_state, out_mon,
                              out_sig, out_energy, peak_sq, sig_max, sig_min, ev_time, ev_kind, ev_x, summary)
        elapsed = time.perf_counter() - start
        n_events = int(summary[_pk.S_N_EVENTS])
        if n_events <= capacity:
            break
        capacity = n_events + 16
    status = int(summary[_pk.S_STATUS])
    message = "ok"
    if status & _pk.STATUS_CHATTER:
        message = (f"chatter guard: more than {_pk.MAX_EVENTS_PER_INTERVAL} events in one sample interval; the "
                   "static friction held the slab to the end of that interval")
    elif status & _pk.STATUS_PIECES:
        message = (f"more than {_pk.MAX_PIECES_PER_INTERVAL} series pieces in one sample interval: that interval "
                   "was not finished")
    if not (np.all(np.isfinite(out_state)) and np.all(np.isfinite(out_energy))):
        # never reported as "ok": a non-finite state is a defect to report, not a result
        status |= STATUS_NON_FINITE
        message = "the 2-D building's state became non-finite (NaN or inf): no result"
    x_b = out_state[:, :, 0]
    v_b = out_state[:, :, 1]
    u = _by_floor(out_state, 2, n)
    ud = _by_floor(out_state, 2 + n, n)
    mass = system.total_mass_kg
    v_end, ud_end, u_end = v_b[-1], ud[-1], u[-1]
    kinetic = 0.5 * system.slab_mass_kg * float(v_end @ v_end) + 0.5 * float(
        system.masses_kg @ np.sum((v_end[None, :] + ud_end) ** 2, axis=1))
    strain = sum(0.5 * float(u_end[:, d] @ system.stiffness_matrices[d] @ u_end[:, d]) for d in range(2))
    # the restoring stiffness at the end (a pendulum's follows N = W (1 + a_z/g))
    k_end = system.isolator_stiffness_N_per_m + k_vert * float(az[-1]) / g
    potential = 0.5 * k_end * float(x_b[-1] @ x_b[-1])
    e_in, e_f, e_v = (float(summary[k]) for k in (_pk.S_E_INPUT, _pk.S_E_FRICTION, _pk.S_E_VISCOUS))
    peaks = sampled_floor(np.sqrt(peak_sq), out_state, n)
    force = out_mon[:, 3 + 2 * n, :]
    equivalent = System(mu_static=system.mu_static, mu_kinetic=system.mu_kinetic,
                        stiffness_per_mass=system.isolator_stiffness_N_per_m / mass,
                        damping_per_mass=system.isolator_damping_Ns_per_m / mass, gravity_m_s2=system.gravity_m_s2)
    return PlanarBuildingResponse(
        system=equivalent,
        building=system,
        time_s=t0 + (dt * np.arange(n_samples) if relative is None else relative),
        ground_acceleration_m_s2=np.column_stack([ax, ay]),
        displacement_m=x_b.copy(),
        velocity_m_s=v_b.copy(),
        absolute_acceleration_m_s2=force / mass,
        event_time_s=t0 + ev_time[:n_events],
        event_kind=ev_kind[:n_events],
        event_displacement_m=ev_x[:n_events].copy(),
        peak_displacement_m=float(peaks[0]),
        residual_displacement_m=float(math.hypot(*x_b[-1])),
        residual_displacement_x_m=float(x_b[-1, 0]),
        residual_displacement_y_m=float(x_b[-1, 1]),
        peak_velocity_m_s=float(peaks[1]),
        peak_transmitted_acceleration_m_s2=float(peaks[3 + 2 * n]) / mass,
        slip_time_s=float(summary[_pk.S_SLIP_TIME]),
        n_events=n_events,
        energy_input_J_per_kg=e_in / mass,
        energy_friction_J_per_kg=e_f / mass,
        energy_viscous_J_per_kg=e_v / mass,
        energy_kinetic_final_J_per_kg=kinetic / mass,
        energy_potential_final_J_per_kg=potential / mass,
        energy_strain_final_J_per_kg=strain / mass,
        energy_balance_error_J_per_kg=(e_in - (kinetic + strain + potential + e_f + e_v)) / mass,
        energy_history_J_per_kg=out_energy / mass,
        floor_displacement_m=u,
        floor_velocity_m_s=ud,
        floor_absolute_acceleration_m_s2=out_mon[:, 2 + n:2 + 2 * n, :].copy(),
        superstructure_shear_N=out_mon[:, 2 + 2 * n, :].copy(),
        isolator_force_N=force.copy(),
        overturning_moment_Nm=out_sig[:, :2].copy(),
        peak_resultants=peaks,
        signed_max=sig_max.copy(),
        signed_min=sig_min.copy(),
        status=status,
        message=message,
        solver_seconds=elapsed,
        n_pieces=int(summary[_pk.S_N_PIECES]),
        n_fast_steps=int(summary[_pk.S_N_FAST]),
        n_fast_refused=tuple(int(v) for v in summary[_pk.S_N_REFUSED:_pk.S_N_REFUSED + 4]),
        n_pieces_by_phase=tuple(int(v) for v in summary[_pk.S_N_PIECES_BY_MODE:_pk.S_N_PIECES_BY_MODE + _pk.N_PIECE_KINDS]),
        n_extrema_located=int(summary[_pk.S_N_LOCATED]),
        n_stop_pieces=int(summary[_pk.S_N_STOP_PIECES]),
        bearing_layout=bearing_layout,
        vertical_acceleration_m_s2=normal.az,
    )
