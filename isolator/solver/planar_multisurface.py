"""Driver of the 2-D multi-surface model: a mass on a double or triple friction pendulum in the plane.

Model ``2d-multisurface``: the series model of Fenz & Constantinou (the elements of
:meth:`isolator.bearing.Bearing.elements`, the same R̄_i, µ_i and rims as the 1-D model
``1d-multisurface``) with every element a rigid–plastic element with linear hardening in the
horizontal plane, coupled through the one force vector the massless sliders carry; the
method is in :mod:`isolator.solver.planar_multisurface_kernel` and docs/multisurface.md.

The rims: a slider reaching its rim stays on the circle |ū_i| = c̄_i (it slides along it or
leaves it inward; the force transfers to the other surfaces), and with every slider on its rim
the bearing is at its ultimate displacement (plastic impact).  The event-driven kernel has no
rim: where it reaches one, ``auto`` hands the record to the implicit steps, which have the rims
(:mod:`isolator.solver.planar_multisurface_stepper`).

A vertical component (model ``2d-multisurface+vertical``): every surface carries the same normal force
N = M n, n = g + a_z (massless sliders), so in units of the normal force the series model is unchanged
and only the mass's equation takes n(t): X'' = −n r − cV − a_g (docs/multisurface.md, "The vertical").
Not modelled here, each refused in one line: the bearing lifting off (n ≤ 0), a superstructure.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from isolator.errors import DesignError, InvalidSystemError, RecordInputError, SolverError
from isolator.solver import planar_multisurface_kernel as _pm
from isolator.solver import planar_multisurface_stepper as _ps
from isolator.solver.base import SolverResult
from isolator.solver.notice import note_if_slow
from isolator.solver.planar import R_MIN_FACTOR
from isolator.solver.record import sample_clock
from isolator.solver.system import classify_configuration
from isolator.units import STANDARD_GRAVITY

MODEL_NAME = "2d-multisurface"
#: START → Cartesian hand-over speed of the event kernel, as a fraction of the speed scale: with the planar engine's
#: 1e-3 the hand-over after a break-away erred by up to 1.6e-6 of the peak (Loma Prieta APEEL2 from 26.05 s, balance
#: open by 9.1e-10; YER, ABY, WLT, 89146 2.7e-9 to 4.4e-8); at 1e-4 APEEL2 is within 2.9e-8 of the implicit steps
#: (their own error), balance 9.4e-13; at 1e-5 Hector Mine ABY's 1.1e-9 and Iwate AOM017's 1.5e-10 from the converged
#: kernel (both speeds at 1e-7, rtol 1e-13) fall to 1.1e-10 and 7.5e-13, the other pairs' unchanged
#: (docs/multisurface.md, "The START form's hand-over" and "ABY's 33.0089 s: the START form re-entered")
R_SWITCH_MULTI_FACTOR = 1e-5
#: the event kernel's lowest speed of a form, as a fraction of the speed scale (its ``SC_R_SWITCH_LO``): below half
#: of it a one-group slide that is not decelerating goes on in the START form (its direction slaved to F, not the
#: velocity's own: an approximation), and a corner hands over to one group (another).  At the
#: planar engine's R_SWITCH_LO_FACTOR (1e-4) Hector Mine ABY re-entered the START form at 6e-8 m/s just after the
#: leave at 33.0089 s and went on 4.5e-8 of the peak from solve_ivp on that one-group pendulum; at 1e-6 to 1e-10
#: the 10 finishing pairs give the same answers at the same cost, ABY within 1.1e-12 of solve_ivp there
R_SWITCH_MULTI_LO_FACTOR = 1e-6
#: relative tolerance of the DOP853 steps (the planar engine's default)
DEFAULT_RTOL = 1e-11
#: the relative tolerances accepted (h171, docs/bench.md "The 2-D TFP's work-precision curve"): below 1e-13 the steps
#: chase round-off; at 1e-9 the pairs the kernel finishes (PTS, DZC, CHY028, ABY, AOM017 measured) erred by 5.8e-10 to
#: 1.3e-8 of the peak from the kernel at 1e-13, but Landers YER stopped at 39.8 s where only a reduction went on and
#: "auto" ran the implicit steps (0.002 against 0.1 M samples/s; at 1e-10 all 10 such pairs stayed on the kernel).
#: Looser, the kernel's own answer breaks: method "events" erred by 5.2e-2 on CHY028 at 1e-7, 0.25 on ABY at 1e-6,
#: and divided by zero on PTS at 1e-5 ("auto" caught the first two through EVENTS_BALANCE_TOL, at 50-75x the cost)
RTOL_RANGE = (1e-13, 1e-9)
#: two friction coefficients closer than this (relative) make one group: equal circles slide together
MU_TIE = 1e-12
#: relative tolerance of the implicit steps' local error estimate (the method where the events cannot be
#: resolved; measured error on the real pairs in docs/multisurface.md)
DEFAULT_STEP_TOL = 1e-7
#: the event-driven kernel is exact between events (its energy balance closes to ~1e-12 of the input on its
#: checks); a larger imbalance means its reduction of nearly tangent circles (groups sliding on as one along a
#: fixed direction) did not hold, and "auto" runs the implicit steps instead (Landers YER: 1.2e-4, its
#: history 36 % off the converged steps from 15 s on).  So does any such reduction on a record that is not
#: collinear, balance closed or not (Loma Prieta APEEL2: 7e-10, and 29 % off from 4.5 s on)
EVENTS_BALANCE_TOL = 1e-8
#: with a rim contact, the implicit steps' energy balance (impacts counted) closes to ~1e-7 of the input where they
#: resolve the impacts (docs/multisurface.md); more open than this, an impact was not resolved and the run is refused
RIM_BALANCE_TOL = 1e-5
#: the methods of ``simulate_bearing_pair``: events (exact between events), steps (implicit steps, every
#: record), auto (events, and the implicit steps when the event-driven kernel cannot finish)
METHODS = ("auto", "events", "steps")


@dataclass(kw_only=True)
class PlanarMultisurfaceResponse(SolverResult):
    """Response of a mass on a double or triple friction pendulum to two components (model ``2d-multisurface``).

    The fields of :class:`~isolator.solver.base.SolverResult` with (N, 2) histories, and the
    bearing's keys of the 1-D model (:class:`isolator.solver.multisurface.MultisurfaceResponse`):
    ``surface_peak_displacement_m`` (peak |u_i| on each real surface, on the surface, taken at
    the integration steps' ends and the events), ``regimes`` (first time each set of sliding
    surfaces was entered, named as in 1-D: regimes IV and V with their elements on the rims),
    ``n_rim_contacts`` (elements reaching their rims), ``ultimate_displacement_reached`` (every
    element on its rim at some instant), the plastic impacts there (``impact_impulse_m_s`` Σ velocity
    lost, ``max_impact_velocity_m_s``, ``energy_impact_J_per_kg`` the kinetic energy they took,
    counted in the energy balance), ``peak_force_per_weight`` (the surfaces' force: at the
    ultimate the rims' reaction is left out, as in 1-D).
    """

    EXTRA_SUMMARY_KEYS = ("bearing_type", "surface_peak_displacement_m", "regimes", "n_rim_contacts",
                          "ultimate_displacement_reached", "ultimate_displacement_m", "energy_impact_J_per_kg",
                          "impact_impulse_m_s", "max_impact_velocity_m_s", "peak_force_per_weight")
    EVENT_NAMES = _pm.EVENT_NAMES

    bearing: object
    residual_displacement_x_m: float
    residual_displacement_y_m: float
    surface_peak_displacement_m: list
    regimes: dict
    element_displacement_m: np.ndarray  #: final state of the series elements, (n_elements, 2) [m]
    ultimate_displacement_m: float
    peak_force_per_weight: float
    n_steps: int = 0
    #: the implicit steps (planar_multisurface_stepper) accepted at the shortest length with their error estimate above
    #: the tolerance: not zero, the history's error is not held to ``step_tol`` there (0 from the event-driven kernel)
    n_steps_at_floor: int = 0
    n_rim_contacts: int = 0
    ultimate_displacement_reached: bool = False
    n_impacts: int = 0  #: plastic impacts at the ultimate displacement
    energy_impact_J_per_kg: float = 0.0
    impact_impulse_m_s: float = 0.0
    max_impact_velocity_m_s: float = 0.0
    damping_per_mass: float = 0.0
    gravity_m_s2: float = STANDARD_GRAVITY
    uplift_time_s = 0.0
    n_uplifts = 0
    model: str = MODEL_NAME
    model_reason: str = "a multi-surface bearing under two horizontal components: the 2-D series model"

    @property
    def bearing_type(self) -> str:
        return self.bearing.kind

    @property
    def configuration(self) -> str:
        rbar = self.bearing.elements()[0]
        return classify_configuration(self.damping_per_mass, self.gravity_m_s2 / float(np.min(rbar)))


def scene_needs(scene) -> tuple[str, str] | None:
    """``(model, reason)`` for a double or triple bearing under two components (or a vertical); else None."""
    bearing = getattr(scene.design, "bearing", None)
    if bearing is None or bearing.is_simple or not (scene.has_y or scene.has_z):
        return None
    name = MODEL_NAME + ("+vertical" if scene.has_z else "")
    return name, (f"a {bearing.kind} friction pendulum ({len(bearing.surfaces)} surfaces) under "
                  + ("two horizontal components" + (" and a vertical" if scene.has_z else "") if scene.has_y
                     else "a vertical component")
                  + ": the series model of Fenz & Constantinou in the plane (coupled friction on every surface)")


def simulate_scene(scene) -> PlanarMultisurfaceResponse:
    """The 2-D response of the scene's multi-surface bearing (:func:`simulate_bearing_pair`), its vertical too.

    Raises
    ------
    SolverError
        The vertical lifts the bearing off (n = g + a_z ≤ 0).
    DesignError
        A superstructure on a double or triple bearing.
    """
    kind = scene.design.bearing.kind
    if getattr(scene.design, "superstructure", None) is not None:
        raise DesignError(f"{scene.design.source}: a {kind} bearing under a [superstructure] is not modelled "
                          "(2d-multisurface carries a rigid mass)")
    ax = np.asarray(scene.ax_m_s2, dtype=np.float64)
    ay = np.zeros_like(ax) if scene.ay_m_s2 is None else scene.ay_m_s2
    return simulate_bearing_pair(ax, ay, scene.dt_s, time_s=scene.time_s, bearing=scene.design.bearing,
                                 az_m_s2=scene.az_m_s2 if scene.has_z else None,
                                 damping_per_mass=float(scene.isolator.get("damping_per_mass") or 0.0),
                                 gravity_m_s2=float(scene.isolator.get("gravity_m_s2") or STANDARD_GRAVITY),
                                 rtol=DEFAULT_RTOL if scene.isolator.get("rtol") is None else scene.isolator["rtol"])


def tolerance(rtol) -> float:
    """``rtol`` as a float in :data:`RTOL_RANGE` (the event kernel's relative tolerance).

    Raises
    ------
    InvalidSystemError
        Not a number, or outside :data:`RTOL_RANGE` (one line).
    """
    if isinstance(rtol, bool):
        raise InvalidSystemError(f"rtol must be a number, got {rtol!r}")
    try:
        value = float(rtol)
    except (TypeError, ValueError):
        raise InvalidSystemError(f"rtol must be a number, got {rtol!r}") from None
    low, high = RTOL_RANGE
    where = f"rtol = {rtol!r} is outside [{low:g}, {high:g}], 2d-multisurface's event kernel's range"
    if value < low:  # 1e-14 was told "looser, its answer breaks" (session 19 sweep): it is tighter
        raise InvalidSystemError(f"{where}: tighter than {low:g}, where the kernel's error has reached its floor "
                                 "(7e-11 to 5e-10 of the peak on real pairs from rtol 1e-11 on, docs/bench.md): a "
                                 "tighter rtol buys steps, not accuracy")
    if value > high:
        raise InvalidSystemError(f"{where}: looser than {high:g}, the kernel's answer breaks on real pairs (5e-2 of "
                                 "the peak on CHY028 at 1e-7, docs/bench.md)")
    if not low <= value <= high:  # NaN
        raise InvalidSystemError(f"{where}: not a number")
    return value


def normal_per_mass(az, g: float, t0: float, local, subject: str) -> np.ndarray:
    """n = g + a_z at the samples [m/s²] (g without a vertical), linear between them: the normal force per unit of
    the isolated mass that every surface carries.

    Raises
    ------
    SolverError
        n ≤ 0 at a sample (``subject`` lifts off): massless sliders under no normal force have no position, so the
        lift-off is not modelled for a double or triple bearing.
    """
    nz = np.full(local.size, g) if az is None else g + az
    if az is not None and not np.all(nz > 0.0):
        up = int(np.flatnonzero(~(nz > 0.0))[0])
        raise SolverError(f"{subject} lifts off at t = {t0 + float(local[up]):.6g} s (n = g + a_z = {float(nz[up]):.3g} "
                          "m/s² ≤ 0): not modelled for a double or triple bearing")
    return nz


def speed_scales(ax, ay, local, nz, rb, mu, c: float) -> tuple[float, float]:
    """``(t_scale [s], vref [m/s])`` as the planar engine builds them (docs/planar.md), for the stiffest group: the
    sample interval, the fastest pendulum (at the largest n = g + a_z) and 1/c bound the time; the largest friction
    force per mass or the PGA over it gives the speed."""
    pga = float(np.max(np.hypot(ax, ay)))
    n_max = float(np.max(nz))
    t_scale = min(float(np.median(np.diff(local))), 1.0 / math.sqrt(n_max / float(np.min(rb))))
    if c > 0.0:
        t_scale = min(t_scale, 1.0 / c)
    return t_scale, max(float(np.max(mu)) * n_max, pga, 1e-12) * t_scale


def element_groups(bearing, split_rims: bool = False):
    """The series elements gathered into groups of equal friction (equal circles: they slide together).

    With ``split_rims`` (the implicit steps, which take the rims) elements of equal friction stay apart
    when their rims are not at the same fraction of R̄ (one would reach its rim while the other slides on).

    Returns
    -------
    tuple of numpy.ndarray
        ``(rbar_group [m], mu_group [-], rim_group [m], members)``: per group the summed R̄, the
        friction, the rim on |ū_group| (the nearest of its elements' rims, ū_i = R̄_i ū_group / R̄_group);
        ``members[i] = (group of element i, R̄_i)``.
    """
    rbar, mu, rim = bearing.elements()
    groups: list[list[int]] = []
    for i, m in enumerate(mu):
        for g in groups:
            same_rim = abs(rim[i] / rbar[i] - rim[g[0]] / rbar[g[0]]) <= MU_TIE * rim[i] / rbar[i]
            if abs(mu[g[0]] - m) <= MU_TIE * max(m, mu[g[0]]) and (same_rim or not split_rims):
                g.append(i)
                break
        else:
            groups.append([i])
    rb = np.array([sum(rbar[i] for i in g) for g in groups])
    mg = np.array([mu[g[0]] for g in groups])
    rg = np.array([min(rim[i] * rb[k] / rbar[i] for i in g) for k, g in enumerate(groups)])
    members = np.empty((rbar.size, 2))
    for k, g in enumerate(groups):
        for i in g:
            members[i] = (k, rbar[i])
    return rb, mg, rg, members


_READY = False


def _warm_up() -> None:
    global _READY
    if _READY:
        return
    with note_if_slow("compiling the 2-D multi-surface solver (its first use after installation takes a minute or "
                      "so; the machine code is cached for later runs)"):
        _run(np.array([0.0, 0.01, 0.02]), np.array([0.0, 1.0, -1.0]), np.array([0.0, 0.5, 0.0]),
             np.full(3, STANDARD_GRAVITY), np.array([1.0, 2.0]), np.array([0.02, 0.05]), np.array([1.0, 1.0]),
             np.array([[0.0, 1.0], [1.0, 2.0]]), np.eye(2), 0.0, np.array([1e-8, 1e-6, 1e-9, 1e-6, 1e-7]),
             DEFAULT_RTOL, 8)
    _READY = True


def _run(t, ax, ay, nz, rb, mu, rim, members, tmat, c, scales, rtol, capacity):
    # the event kernel's outputs, and its work counters (planar_multisurface_kernel.ST_*) last
    stats = np.zeros(_pm.ST_SIZE, dtype=np.int64)

    def kernel(out_x, out_v, out_a, out_en, ev_t, ev_k, summary, surf_peak, first, ub):
        stats[:] = 0
        _pm.planar_multisurface_kernel(t, ax, ay, nz, rb, mu, rim, members, tmat, c, scales, rtol, out_x, out_v,
                                       out_a, out_en, ev_t, ev_k, summary, surf_peak, first, ub, stats)
    return (*_with_event_room(kernel, t.size, rb.size, members.shape[0], tmat.shape[0], capacity), stats)


def _with_event_room(kernel, n, n_groups, n_members, n_surfaces, capacity):
    # the output buffers of either compiled loop (the event kernel, the implicit steps), and one more run with
    # room for every event when the first overflowed its event list
    out_x = np.empty((n, 2))
    out_v = np.empty((n, 2))
    out_a = np.empty((n, 2))
    out_en = np.empty((3, n))
    summary = np.zeros(max(_pm.S_SIZE, _ps.S_SIZE_STEPS))
    surf_peak = np.zeros(n_surfaces)
    # first time of each state: sliding elements, and (the steps) the elements on their rims above them
    first = np.empty(1 << (2 * n_members))
    while True:
        ev_t = np.empty(capacity)
        ev_k = np.empty(capacity, dtype=np.int8)
        ub = np.zeros((n_groups, 2))
        surf_peak[:] = 0.0
        # the event kernel writes no rim slots: never reached unless the steps say when (zero would read as t = 0 s)
        summary[_ps.S_FIRST_ULT] = -1.0
        start = time.perf_counter()
        kernel(out_x, out_v, out_a, out_en, ev_t, ev_k, summary, surf_peak, first, ub)
        elapsed = time.perf_counter() - start
        n_ev = int(summary[_pm.S_N_EVENTS])
        if n_ev <= capacity:
            return out_x, out_v, out_a, out_en, summary, surf_peak, first, ub, ev_t[:n_ev], ev_k[:n_ev], elapsed
        capacity = n_ev + 16


_STOPPED = _pm.STATUS_STEP_LIMIT | _pm.STATUS_SINGULAR | _pm.STATUS_CHATTER | _pm.STATUS_REDUCED | _pm.STATUS_STIFF
_STEPS_READY = False


def _refuse_rim(status, fail_t, bearing):
    # the event-driven kernel stops where a slider reaches its rim (it has no rim): asked for alone, it refuses
    if status & _pm.STATUS_RIM:
        raise SolverError(f"the {bearing.kind} bearing reaches a rim at t = {fail_t:.6g} s: the event-driven kernel "
                          "of 2d-multisurface has no rim (method 'steps' or 'auto' takes the rims)")


def _collinear(ax, ay):
    # both components along one line (a rotated 1-D record): the kernel's groups sliding as one along a fixed
    # direction are then exact
    cross = np.abs(ax[1:] * ay[:-1] - ay[1:] * ax[:-1])
    scale = np.hypot(ax, ay)
    return bool(np.all(cross <= 1e-12 * scale[1:] * scale[:-1]))


def _imbalance(summary, out_v, ub, rb, g):
    # |input − (kinetic + stored + friction + viscous)| / input of a finished run (g: n at its end)
    e_in = float(summary[_pm.S_E_IN])
    if not e_in > 0.0:
        return 0.0
    e_kin = 0.5 * float(out_v[-1, 0] ** 2 + out_v[-1, 1] ** 2)
    e_pot = float(g * np.sum(np.sum(ub * ub, axis=1) / (2.0 * rb)))
    return abs(e_in - e_kin - e_pot - float(summary[_pm.S_E_F]) - float(summary[_pm.S_E_V])) / e_in


def _run_steps(t, ax, ay, nz, rb, mu, rim, members, tmat, c, tol, scales, capacity):
    # the implicit steps (planar_multisurface_stepper): the same outputs as _run
    global _STEPS_READY
    if not _STEPS_READY:
        with note_if_slow("compiling the 2-D multi-surface implicit steps (first use after installation only)"):
            _run_steps_once(np.array([0.0, 0.01, 0.02]), np.array([0.0, 1.0, -1.0]), np.array([0.0, 0.5, 0.0]),
                            np.full(3, STANDARD_GRAVITY), np.array([1.0, 2.0]), np.array([0.02, 0.05]), np.array([1.0, 1.0]),
                            np.array([[0.0, 1.0], [1.0, 2.0]]), np.eye(2), 0.0, 1e-6, scales, 8)
        _STEPS_READY = True
    return _run_steps_once(t, ax, ay, nz, rb, mu, rim, members, tmat, c, tol, scales, capacity)


def _run_steps_once(t, ax, ay, nz, rb, mu, rim, members, tmat, c, tol, scales, capacity):
    floors = np.array([scales[_pm.SC_X_FLOOR], scales[_pm.SC_V_FLOOR]])

    def kernel(out_x, out_v, out_a, out_en, ev_t, ev_k, summary, surf_peak, first, ub):
        _ps.planar_multisurface_stepper(t, ax, ay, nz, rb, mu, rim, members, tmat, c, tol, floors, out_x, out_v,
                                        out_a, out_en, ev_t, ev_k, summary, surf_peak, first, ub)
    return _with_event_room(kernel, t.size, rb.size, members.shape[0], tmat.shape[0], capacity)


def _samples(name, values, size=None):
    a = np.ascontiguousarray(values, dtype=np.float64)
    if a.ndim != 1 or a.size < 2:
        raise RecordInputError(f"{name}: a record needs at least two samples in one dimension")
    if size is not None and a.size != size:
        raise RecordInputError(f"{name}: {a.size} samples, the first component has {size}")
    if not np.all(np.isfinite(a)):
        raise RecordInputError(f"{name}: acceleration holds NaN or infinite values")
    return a


def simulate_bearing_pair(ax_m_s2, ay_m_s2, dt_s: float | None = None, *, bearing, time_s=None, az_m_s2=None,
                          damping_per_mass: float = 0.0, gravity_m_s2: float = STANDARD_GRAVITY,
                          rtol: float = DEFAULT_RTOL, method: str = "auto",
                          step_tol: float = DEFAULT_STEP_TOL) -> PlanarMultisurfaceResponse:
    """Response of a mass on a multi-surface friction pendulum to two horizontal components.

    Parameters
    ----------
    ax_m_s2, ay_m_s2 : array_like
        Ground acceleration along x and y [m/s²], linear between samples.
    dt_s : float, optional
        Sample interval [s] (or give ``time_s``).
    bearing : isolator.bearing.Bearing
        The bearing (kinetic friction per surface).
    time_s : array_like, optional
        Sample times [s], strictly increasing.
    az_m_s2 : array_like, optional
        Vertical ground acceleration [m/s²], up positive, linear between samples: the normal force of
        every surface is M (g + a_z) (model ``2d-multisurface+vertical``).
    damping_per_mass : float
        Supplemental linear damper γ/M [1/s] (isotropic in the plane).
    gravity_m_s2 : float
        g [m/s²].
    rtol : float
        Relative tolerance of the event kernel's non-exact steps (DOP853 and the corner steps), in
        :data:`RTOL_RANGE`; the scene's ``rtol`` key in the registry.  Measured on six real pairs: the
        history within ~rtol of the peak from the kernel at 1e-13 (docs/bench.md).
    method : {"auto", "events", "steps"}
        ``"events"``: the event-driven kernel (exact between events; stops with a SolverError where
        the sliding set cannot be resolved: three friction circles meeting at small angles, a corner
        closing towards tangency in a curved motion); ``"steps"``: implicit steps on the smooth
        formulation (:mod:`isolator.solver.planar_multisurface_stepper`, every geometry, local error
        controlled by ``step_tol``); ``"auto"``: events, and the steps for the whole record when the
        event-driven kernel cannot finish (``model_reason`` says which ran, and why).
    step_tol : float
        Relative tolerance of the implicit steps' local error estimate (of the peak displacement and
        velocity).

    Returns
    -------
    PlanarMultisurfaceResponse

    Raises
    ------
    SolverError
        ``method="events"`` and a slider reached its rim (the event-driven kernel has none), or a
        step guard tripped (``method="events"``: the event-driven kernel could not finish), or its
        energy balance is open by more than :data:`EVENTS_BALANCE_TOL` of the input (``method="events"``:
        the answer is not trusted; "auto" runs the implicit steps there), or the
        vertical lifts the bearing off (n = g + a_z ≤ 0 at a sample: not modelled).
    """
    if method not in METHODS:
        raise ValueError(f"method must be one of {METHODS}, got {method!r}")
    if not (math.isfinite(step_tol) and 1e-12 <= step_tol <= 1e-2):
        raise ValueError(f"step_tol must be in [1e-12, 1e-2], got {step_tol!r}")
    rtol = tolerance(rtol)
    ax = _samples("ax_m_s2", ax_m_s2)
    ay = _samples("ay_m_s2", ay_m_s2, ax.size)
    t0, local = sample_clock(ax.size, dt_s, time_s)
    c = float(damping_per_mass)
    g = float(gravity_m_s2)
    if not (c >= 0.0 and math.isfinite(c) and g > 0.0 and math.isfinite(g)):
        raise ValueError("damping_per_mass must be >= 0 and gravity_m_s2 > 0, both finite")
    az = None if az_m_s2 is None else _samples("az_m_s2", az_m_s2, ax.size)
    nz = normal_per_mass(az, g, t0, local, f"the {bearing.kind} bearing")
    rb, mu, rim, members = element_groups(bearing)
    tmat = bearing.surface_matrix()
    t_scale, vref = speed_scales(ax, ay, local, nz, rb, mu, c)
    scales = np.array([R_MIN_FACTOR * vref, R_SWITCH_MULTI_FACTOR * vref, 1e-3 * vref * t_scale, 1e-3 * vref,
                       R_SWITCH_MULTI_LO_FACTOR * vref])
    reason = f"a {bearing.kind} bearing: the series model in the plane, "
    how = "exact between events (event-driven kernel)"
    if method != "steps":
        _warm_up()
        collinear = _collinear(ax, ay)
        if method == "auto" and not collinear:
            # "auto" discards a run that goes through a reduction on a record that is not collinear: the kernel stops
            # at the first one, or where a closing corner makes its steps stiff (which ends in one; CBGS: 2.6 s of a
            # 3.9 s answer at load 9 were such a run)
            scales = np.append(scales, 1.0)
        out_x, out_v, out_a, out_en, summary, surf_peak, first, ub, ev_t, ev_k, elapsed, stats = _run(
            local, ax, ay, nz, rb, mu, rim, members, tmat, c, scales, float(rtol), 64 + ax.size // 4)
        if stats[_pm.ST_RADAU_MAIN] + stats[_pm.ST_DOP_MAIN]:
            refused = int(stats[_pm.ST_REF_NEWTON] + stats[_pm.ST_REF_ERROR])
            how += (f"; corner steps: {int(stats[_pm.ST_RADAU_MAIN])} implicit (Radau IIA; {refused} refused, "
                    f"{int(stats[_pm.ST_REF_NEWTON])} of them by Newton; {int(stats[_pm.ST_NEWTON])} Newton "
                    f"iterations), {int(stats[_pm.ST_DOP_MAIN])} explicit (DOP853)")
        status = int(summary[_pm.S_STATUS])
        fail_t = t0 + float(summary[_pm.S_FAIL_T])
        if method == "events":
            _refuse_rim(status, fail_t, bearing)
        imbalance = 0.0 if status & (_STOPPED | _pm.STATUS_RIM) else _imbalance(summary, out_v, ub, rb, nz[-1])
        merged = 0 if status & (_STOPPED | _pm.STATUS_RIM) or collinear else int(summary[_pm.S_N_MERGED])
        if status & _pm.STATUS_RIM:
            # the kernel has no rim: the steps take the record from the start, rims included
            status |= _pm.STATUS_SINGULAR
            how = (f"implicit steps, local error tolerance {step_tol:g} (the event-driven kernel reached a rim at "
                   f"t = {fail_t:.6g} s; the steps take the rims: a slider on its rim slides along it or leaves it "
                   "inward, plastic impact at the ultimate displacement)")
        elif method == "auto" and (imbalance > EVENTS_BALANCE_TOL or merged):
            status |= _pm.STATUS_SINGULAR
            how = (f"implicit steps, local error tolerance {step_tol:g} (the event-driven kernel finished, but "
                   + (f"with an energy imbalance of {imbalance:.1e} of the input" if imbalance > EVENTS_BALANCE_TOL
                      else f"through {merged} reductions exact only for a collinear record")
                   + ": groups of nearly tangent circles slid as one along a fixed direction, or a slow corner was "
                   "left to one group)")
        elif method == "events" and imbalance > EVENTS_BALANCE_TOL:
            # the balance "auto" reads, read here too: the kernel finished with an answer it cannot stand behind (ABY at
            # rtol 1e-6: 0.25 of the peak off the kernel at 1e-13, balance open by 5.5e-3, returned without a word
            # before h186)
            raise SolverError(f"the 2-D multi-surface event-driven kernel finished with its energy balance open by "
                              f"{imbalance:.1e} of the input (limit EVENTS_BALANCE_TOL = {EVENTS_BALANCE_TOL:g}): its "
                              "answer is not trusted (method 'auto' runs the implicit steps there)")
        elif status & _STOPPED:
            if method == "events":
                raise SolverError(f"the 2-D multi-surface solver could not finish at t = {fail_t:.6g} s "
                                  f"(status {status}: step guard, event guard or singular compliance)")
            how = (f"implicit steps, local error tolerance {step_tol:g} (the event-driven kernel stopped at "
                   f"t = {fail_t:.6g} s, " + (
                       "where it would go on only through a reduction exact only for a collinear record: groups of "
                       "nearly tangent circles sliding as one along a fixed direction, or a slow corner left to one "
                       "group)" if status & _pm.STATUS_REDUCED else
                       "where a corner of two circles closing towards tangency made its steps stiff: more "
                       f"than {_pm.MAX_STIFF_STEPS_PER_INTERVAL} in one sample interval)" if status & _pm.STATUS_STIFF else
                       f"status {status}: the sliding set changes faster than its events resolve)"))
    n_floor = 0
    if method == "steps" or status & _STOPPED:
        events_seconds = 0.0
        if method == "steps":
            how = f"implicit steps, local error tolerance {step_tol:g} (asked for)"
        else:
            events_seconds = elapsed
        # groups of equal friction whose rims differ part where the first reaches its rim
        rb, mu, rim, members = element_groups(bearing, split_rims=True)
        out_x, out_v, out_a, out_en, summary, surf_peak, first, ub, ev_t, ev_k, elapsed = _run_steps(
            local, ax, ay, nz, rb, mu, rim, members, tmat, c, step_tol, scales, 64 + ax.size // 4)
        elapsed += events_seconds
        status = int(summary[_pm.S_STATUS])
        n_floor = int(summary[_pm.S_STEPS_MULTI])
        fail_t = t0 + float(summary[_pm.S_FAIL_T])
        if status & _pm.STATUS_RIM:
            raise SolverError(f"the 2-D multi-surface implicit steps left a rim at t = {fail_t:.6g} s (a guard)")
        if status & _ps.STATUS_WORK:
            on_rims = int(summary[_ps.S_FAIL_RIMS])
            raise SolverError(
                f"the 2-D multi-surface implicit steps needed more than {_ps.work_bound(step_tol):.0f} force "
                f"evaluations in one sample interval at t = {fail_t:.6g} s ({on_rims} of {rb.size} slider groups on "
                "their rims" + (": the bearing at its ultimate displacement, not resolved there" if on_rims == rb.size
                                else "") + "); the run stops there")
        if status & _ps.STATUS_UNSOLVED:
            on_rims = int(summary[_ps.S_FAIL_RIMS])
            raise SolverError(f"the 2-D multi-surface implicit steps found no force at t = {fail_t:.6g} s (Newton did "
                              f"not converge; {on_rims} of {rb.size} slider groups on their rims: not resolved; the "
                              "run stops there)")
        if status & _STOPPED:
            raise SolverError(f"the 2-D multi-surface implicit steps could not finish at t = {fail_t:.6g} s "
                              f"(status {status}: more than {_ps.MAX_STEPS_PER_INTERVAL} steps in one sample interval)")
    elements = np.array([members[i, 1] / rb[int(members[i, 0])] * ub[int(members[i, 0])]
                         for i in range(members.shape[0])])
    regimes: dict = {}
    n_masks = 1 << members.shape[0]
    for code in np.flatnonzero(first >= 0.0):
        name = bearing.regime_name(int(code) % n_masks, int(code) // n_masks)
        if name and (name not in regimes or first[code] + t0 < regimes[name]):
            regimes[name] = float(first[code] + t0)
    regimes = dict(sorted(regimes.items(), key=lambda item: item[1]))
    on_surface = [float(p) * s.radius_m / s.effective_radius_m for p, s in zip(surf_peak, bearing.surfaces,
                                                                                 strict=True)]
    e_in, e_f, e_v = (float(summary[k]) for k in (_pm.S_E_IN, _pm.S_E_F, _pm.S_E_V))
    e_kin = 0.5 * float(out_v[-1, 0] ** 2 + out_v[-1, 1] ** 2)
    # the stored energy n Σ|ū_k|²/(2R̄_k) at the end (n = g without a vertical)
    e_pot = float(nz[-1] * np.sum(np.sum(ub * ub, axis=1) / (2.0 * rb)))
    peak_a = float(summary[_pm.S_PEAK_A])
    balance = e_in - (e_kin + e_pot + e_f + e_v + float(summary[_ps.S_E_IMP]))
    if summary[_ps.S_N_RIM_CONTACTS] > 0 and abs(balance) > RIM_BALANCE_TOL * e_in:
        raise SolverError(f"the 2-D multi-surface implicit steps reached the rims with the energy balance open by "
                          f"{abs(balance) / e_in:.1e} of the input (limit {RIM_BALANCE_TOL:g}; "
                          f"{int(summary[_ps.S_N_RIM_CONTACTS])} rim contacts: the steps did not resolve the motion on "
                          "the rims); not answered")
    # the rims (the steps' slots; the event-driven kernel finishes only without a rim contact: zeros there)
    e_imp = float(summary[_ps.S_E_IMP])
    if summary[_ps.S_PEAK_R] > 0.0:
        peak_r = float(summary[_ps.S_PEAK_R])
    elif az is not None:
        # per unit of the normal force M n(t), at the samples
        peak_r = float(np.max(np.hypot(*(out_a.T + c * out_v.T)) / nz))
    else:
        peak_r = peak_a / g if c == 0.0 else float(np.max(np.hypot(*(out_a.T + c * out_v.T)))) / g
    return PlanarMultisurfaceResponse(
        bearing=bearing,
        time_s=t0 + local,
        ground_acceleration_m_s2=np.column_stack((ax, ay)),
        displacement_m=out_x, velocity_m_s=out_v, absolute_acceleration_m_s2=out_a,
        event_time_s=t0 + ev_t, event_kind=ev_k,
        peak_displacement_m=float(summary[_pm.S_PEAK_X]),
        residual_displacement_m=float(math.hypot(out_x[-1, 0], out_x[-1, 1])),
        residual_displacement_x_m=float(out_x[-1, 0]),
        residual_displacement_y_m=float(out_x[-1, 1]),
        peak_velocity_m_s=float(summary[_pm.S_PEAK_V]),
        peak_transmitted_acceleration_m_s2=peak_a,
        slip_time_s=float(summary[_pm.S_SLIP_TIME]),
        n_events=int(summary[_pm.S_N_EVENTS]),
        energy_input_J_per_kg=e_in, energy_friction_J_per_kg=e_f, energy_viscous_J_per_kg=e_v,
        energy_kinetic_final_J_per_kg=e_kin, energy_potential_final_J_per_kg=e_pot,
        energy_balance_error_J_per_kg=e_in - (e_kin + e_pot + e_f + e_v + e_imp),
        energy_impact_J_per_kg=e_imp,
        n_rim_contacts=int(summary[_ps.S_N_RIM_CONTACTS]),
        ultimate_displacement_reached=bool(summary[_ps.S_FIRST_ULT] >= 0.0),
        impact_impulse_m_s=float(summary[_ps.S_IMPULSE]),
        max_impact_velocity_m_s=float(summary[_ps.S_MAX_IMPACT_V]),
        n_impacts=int(summary[_ps.S_N_ULTIMATE]),
        energy_history_J_per_kg=out_en,
        surface_peak_displacement_m=on_surface,
        regimes=regimes,
        element_displacement_m=elements,
        ultimate_displacement_m=bearing.ultimate_displacement_m,
        peak_force_per_weight=peak_r,
        n_steps=int(summary[_pm.S_N_STEPS]),
        n_steps_at_floor=n_floor,
        status=status, message="ok", solver_seconds=elapsed,
        damping_per_mass=c, gravity_m_s2=g,
        model=MODEL_NAME + ("+vertical" if az is not None else ""),
        model_reason=reason + ("n = g + a_z (the vertical), " if az is not None else "") + how,
    )


__all__ = ["MODEL_NAME", "RTOL_RANGE", "PlanarMultisurfaceResponse", "element_groups", "scene_needs", "simulate_bearing_pair",
           "simulate_scene",
           "tolerance"]
