"""Record driver: the exact response to a sampled ground acceleration.

The record is taken as piecewise linear between its samples (first-order hold), the
only reading of a sampled signal under which "exact" has a meaning; the response to
that signal is then computed without discretisation error by
:func:`isolator.solver.kernel.record_kernel`.  The samples need not be evenly spaced
(digitised analogue records are not): a time column with unequal steps is the same
piecewise-linear signal, solved interval by interval.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from isolator.errors import InvalidSystemError, RecordInputError  # noqa: F401 - defined with the other typed errors
from isolator.solver import kernel as _kernel
from isolator.solver.base import SolverResult
from isolator.solver.notice import note_if_slow
from isolator.solver.system import System

#: The model this module is in the registry (:mod:`isolator.solver.models`), and why a scene needs it.
MODEL_NAME = "1d-exact"
MODEL_REASON = "one horizontal component, constant friction, no vertical: the exact 1-D kernel"


class AlongOneComponent:
    """What a response to one horizontal component says of the plane (the 1-D models: the block, the building, the
    multi-surface bearing): it moves along X only, so its residual is ``residual_displacement_x_m`` (signed), Y is
    zero, and it never lifts off."""

    uplift_time_s = 0.0  #: one horizontal component: no lift-off [s]
    n_uplifts = 0

    @property
    def residual_displacement_x_m(self) -> float:
        """Signed residual along the record [m]."""
        return self.residual_displacement_m

    @property
    def residual_displacement_y_m(self) -> float:
        """No motion across the record [m]."""
        return 0.0


@dataclass(kw_only=True)
class Response(AlongOneComponent, SolverResult):
    """Exact response of the block to one component (model ``1d-exact``; SI units).

    The fields of :class:`~isolator.solver.base.SolverResult` (histories of shape (N,),
    along the record), the isolator (``system``), the displacement at each event and the
    sub-steps per sample interval; along X only (:class:`AlongOneComponent`).
    """

    system: System
    event_displacement_m: np.ndarray
    substeps_per_interval: int = 1
    model: str = MODEL_NAME
    model_reason: str = MODEL_REASON

    @property
    def configuration(self) -> str:
        """The paper's configuration of the isolator (1 to 4)."""
        return self.system.configuration

    @property
    def sliding(self) -> np.ndarray:
        """True at the samples where the block slides relative to the ground."""
        return self.velocity_m_s != 0.0


#: Steps that differ from their mean by less than this fraction are one uniform step:
#: the sample times then move by < 1e-9 dt, far below any physical time scale.
UNIFORM_STEP_REL_TOLERANCE = 1e-9


def sample_clock(n: int, dt_s=None, time_s=None) -> tuple[float, np.ndarray]:
    """The first sample's time and the ``n`` sample times from it, from ``dt_s`` or ``time_s``.

    Parameters
    ----------
    n : int
        Number of samples.
    dt_s : float, optional
        Sample interval [s], finite and > 0 (times ``0, dt, 2 dt …``).
    time_s : array_like, optional
        Sample times [s] (``n`` of them, checked by :func:`sample_timing`); taken before ``dt_s``.

    Returns
    -------
    tuple
        ``(t0, times − t0)``.

    Raises
    ------
    RecordInputError
        Times of another length, not increasing, or a bad ``dt_s``.
    TypeError
        Neither given.
    """
    if time_s is not None:
        times = np.asarray(time_s, dtype=np.float64)
        if times.shape != (n,):
            raise RecordInputError(f"time ({times.shape}) and acceleration ({(n,)}) differ in length")
        sample_timing(times)
        t0 = float(times[0])
        return t0, times - t0
    if dt_s is not None:
        dt = float(dt_s)
        if not math.isfinite(dt) or dt <= 0.0:
            raise RecordInputError(f"dt must be a finite number > 0, got {dt_s!r}")
        return 0.0, dt * np.arange(n)
    raise TypeError("give dt_s or time_s")


def sample_timing(time_s) -> tuple[float, np.ndarray | None]:
    """Mean step and, for unequal steps, the sample times from the first one.

    Parameters
    ----------
    time_s : array_like
        Sample times [s], finite and strictly increasing.

    Returns
    -------
    tuple
        ``(dt, None)`` when every step equals the mean ``dt`` [s] to
        ``UNIFORM_STEP_REL_TOLERANCE``; ``(dt, time_s - time_s[0])`` otherwise.

    Raises
    ------
    RecordInputError
        Fewer than two samples, non-finite or non-increasing times.
    """
    times = np.asarray(time_s, dtype=np.float64)
    steps = np.diff(times)
    if steps.size == 0:
        raise RecordInputError("a record needs at least two samples")
    if not np.all(np.isfinite(times)) or np.any(steps <= 0.0):
        raise RecordInputError("time values must be finite and strictly increasing")
    dt = float((times[-1] - times[0]) / (times.size - 1))
    if np.max(np.abs(steps - dt)) <= UNIFORM_STEP_REL_TOLERANCE * dt:
        return dt, None
    return dt, np.ascontiguousarray(times - times[0])


#: The solver's range of a sample interval [s]: below, steps are rounding noise of a time column; above, a
#: sample interval is hours long, not a ground-motion record, and the exact kernel's sub-steps (bounded by
#: the oscillator's period) would be unbounded in number.
SOLVER_DT_RANGE_S = (1e-9, 1e4)
#: The solver's bound on |a| [m/s²] (about 1e5 g, far above any accelerogram: the readers refuse 50 g):
#: below it, displacements, velocities and energies (squares of them) stay finite in float64.
SOLVER_MAX_ABS_ACCELERATION_M_S2 = 1e6


@dataclass(frozen=True)
class RecordTiming:
    """A record the 1-D solvers can take: its samples and time base (:func:`record_timing`).

    Attributes
    ----------
    acceleration_m_s2 : numpy.ndarray
        The samples, float64, contiguous, shape (N,) [m/s²].
    dt_s : float
        The (mean) sample interval [s].
    relative_time_s : numpy.ndarray or None
        Sample times from the first one for unequal steps; None for a uniform record [s].
    t0_s : float
        Time of the first sample [s] (0 with ``dt_s``).
    """

    acceleration_m_s2: np.ndarray
    dt_s: float
    relative_time_s: np.ndarray | None
    t0_s: float


def record_timing(acceleration_m_s2, dt_s=None, time_s=None) -> RecordTiming:
    """Check a sampled record and its time base for the exact solvers (record, multi-surface, building).

    Parameters
    ----------
    acceleration_m_s2 : array_like
        Samples [m/s²]: real, one-dimensional, at least two, finite, |a| ≤
        :data:`SOLVER_MAX_ABS_ACCELERATION_M_S2`.
    dt_s : float, optional
        Sample interval [s] in :data:`SOLVER_DT_RANGE_S`.
    time_s : array_like, optional
        Sample times [s], finite and strictly increasing, one per sample.  With ``dt_s``
        too, ``dt_s`` must be their mean step (to ``UNIFORM_STEP_REL_TOLERANCE``).

    Returns
    -------
    RecordTiming

    Raises
    ------
    RecordInputError
        Samples that are not real numbers (complex, text), not 1-D, fewer than two,
        non-finite or beyond the bound; neither ``dt_s`` nor ``time_s``, or both and they
        disagree; a ``dt_s`` that is not a number or is out of range; times of another
        length, non-finite, not increasing, or steps out of range.
    """
    raw = np.asarray(acceleration_m_s2)
    if raw.dtype.kind not in "biuf":  # complex would be cast with a warning, text and objects not at all
        raise RecordInputError(f"acceleration must hold real numbers, got {raw.dtype}")
    acc = np.ascontiguousarray(raw, dtype=np.float64)
    if acc.ndim != 1:
        raise RecordInputError(f"acceleration must be one-dimensional, got shape {acc.shape}")
    if acc.size < 2:
        raise RecordInputError("a record needs at least two samples")
    if not np.all(np.isfinite(acc)):
        raise RecordInputError("acceleration holds NaN or infinite values")
    peak = float(np.max(np.abs(acc)))
    if peak > SOLVER_MAX_ABS_ACCELERATION_M_S2:
        raise RecordInputError(f"|acceleration| reaches {peak:g} m/s², above the solver's "
                               f"{SOLVER_MAX_ABS_ACCELERATION_M_S2:g} m/s² (about 1e5 g): not a ground acceleration")
    low, high = SOLVER_DT_RANGE_S
    given_dt = None
    if dt_s is not None:
        if isinstance(dt_s, bool) or not isinstance(dt_s, (int, float, np.integer, np.floating)):
            raise RecordInputError(f"dt must be a number of seconds, got {dt_s!r}")
        given_dt = float(dt_s)
        if not (math.isfinite(given_dt) and given_dt > 0.0):
            raise RecordInputError(f"dt must be a finite number > 0, got {dt_s!r}")
    if time_s is not None:
        times_raw = np.asarray(time_s)
        if times_raw.dtype.kind not in "biuf":
            raise RecordInputError(f"time must hold real numbers, got {times_raw.dtype}")
        times = np.asarray(times_raw, dtype=np.float64)
        if times.shape != acc.shape:
            raise RecordInputError(f"time ({times.shape}) and acceleration ({acc.shape}) differ in length")
        dt, relative = sample_timing(times)
        steps = np.diff(times)
        if float(np.min(steps)) < low or float(np.max(steps)) > high:
            raise RecordInputError(f"time steps from {float(np.min(steps)):g} to {float(np.max(steps)):g} s: "
                                   f"the solver takes steps in [{low:g}, {high:g}] s")
        if given_dt is not None and abs(given_dt - dt) > UNIFORM_STEP_REL_TOLERANCE * dt:
            raise RecordInputError(f"dt = {given_dt:g} s and time (mean step {dt:g} s) disagree: give one of them")
        return RecordTiming(acc, dt, relative, float(times[0]))
    if given_dt is None:
        raise RecordInputError("give dt_s or time_s")
    if not low <= given_dt <= high:
        raise RecordInputError(f"dt = {given_dt:g} s is outside the solver's range [{low:g}, {high:g}] s")
    return RecordTiming(acc, given_dt, None, 0.0)


#: Most sub-steps per sample interval of the building engines (1-D, 1-D on a multi-surface bearing, 2-D): a base
#: slab of 1e-5 of the floors asked for ~1e6 and ran for minutes (session 10); real buildings need tens.
MAX_SUBSTEPS_PER_INTERVAL = 5000


def building_substeps(dt_s: float, relative_time_s, step_s: float, what: str) -> int:
    """Sub-steps of at most ``step_s`` that fill the record's longest sample interval (the building engines' rule).

    The one rule of the three building drivers: the longest interval over the step their fastest rate allows
    (``THETA / rate``), at most :data:`MAX_SUBSTEPS_PER_INTERVAL`.  Called by each public entry before its kernel
    is loaded, so that a refused design waits for no compilation and prints no compile note before its line (the
    s10 hostile test's flake under load, session 14); the count is then passed to the driver's run.

    Parameters
    ----------
    dt_s : float
        The (mean) sample interval [s].
    relative_time_s : numpy.ndarray or None
        Sample times from the first one for unequal steps (:class:`RecordTiming`); None for a uniform record [s].
    step_s : float
        The longest sub-step the system allows [s], > 0 (``inf`` for a system that does not move).
    what : str
        The refusal's subject, e.g. ``"the building's fastest rate 3.4e+10 1/s"``.

    Returns
    -------
    int
        ``max(1, ceil(longest interval / step_s))``.

    Raises
    ------
    InvalidSystemError
        More than :data:`MAX_SUBSTEPS_PER_INTERVAL` (one line: the count, the interval, the cause).
    """
    longest = dt_s if relative_time_s is None else float(np.max(np.diff(relative_time_s)))
    ratio = longest / step_s if step_s > 0.0 else math.inf  # a step that vanishes (never: THETA / a finite rate)
    if not ratio <= MAX_SUBSTEPS_PER_INTERVAL:  # ceil(ratio) <= the bound exactly when ratio <= it (an integer)
        needed = math.ceil(ratio) if math.isfinite(ratio) else ratio
        raise InvalidSystemError(
            f"{what} needs {needed} sub-steps per sample interval of {longest:g} s (at most "
            f"{MAX_SUBSTEPS_PER_INTERVAL}): the base slab is too light for the first story's stiffness, or a story "
            "too stiff for its mass")
    return max(1, math.ceil(ratio))


_KERNEL_READY = False


def _warm_up_kernel() -> None:
    # The first call of a numba function loads its machine code from the on-disk
    # cache (or compiles it); do that on a two-sample record so that
    # ``solver_seconds`` measures solving, not loading.
    global _KERNEL_READY
    if _KERNEL_READY:
        return
    with note_if_slow("compiling the 1-D solver (its first use after installation takes a few seconds; "
                      "the machine code is cached for later runs)"):
        basis, gram = _kernel.full_step_coefficients(0.01, 0.1, 1.0)
        two = np.zeros(2)
        _kernel.record_kernel(np.array([0.0, 1.0]), 0.01, 1, 0.1, 1.0, 0.5, 0.5, basis, gram, two.copy(),
                              two.copy(), two.copy(), np.empty((3, 2)), np.empty(4), np.empty(4, dtype=np.int8),
                              np.empty(4), np.zeros(_kernel.SUMMARY_SIZE), np.empty(0), math.inf)
    _KERNEL_READY = True


def simulate_record(acceleration_m_s2, dt_s: float | None = None, *, time_s=None,
                    system: System | None = None, mu_static: float | None = None,
                    mu_kinetic: float | None = None, stiffness_per_mass: float = 0.0,
                    damping_per_mass: float = 0.0, gravity_m_s2: float | None = None) -> Response:
    """Exact response of a friction–spring–dashpot block to a sampled ground acceleration.

    Parameters
    ----------
    acceleration_m_s2 : array_like
        Ground acceleration samples [m/s²], taken as linear between samples.
    dt_s : float, optional
        Sample interval [s]; give either this or ``time_s``.
    time_s : array_like, optional
        Sample times [s], strictly increasing; unequal steps are solved exactly
        (each interval its own ramp), equal ones on the uniform fast path.
    system : System, optional
        The isolator; or give ``mu_static`` etc. as keywords.
    mu_static, mu_kinetic : float
        Static and kinetic friction coefficients [-] (µk defaults to µs).
    stiffness_per_mass : float
        K/M [1/s²] (g/R for a friction pendulum of radius R).
    damping_per_mass : float
        γ/M [1/s].
    gravity_m_s2 : float, optional
        Acceleration of gravity [m/s²], standard gravity by default.

    Returns
    -------
    Response
        Sampled displacement, velocity and absolute acceleration, the exact event list,
        peaks (exact, including between samples), slip time and energies.

    Raises
    ------
    RecordInputError
        A record the solver cannot take (:func:`record_timing`: complex or non-finite
        samples, |a| beyond the solver's bound, ``dt_s`` out of range or disagreeing with
        ``time_s`` …).
    InvalidSystemError
        Neither a ``system`` nor ``mu_static``; parameters outside their domain.
    """
    if system is None:
        if mu_static is None:
            raise InvalidSystemError("give a System or mu_static")
        kwargs = {} if gravity_m_s2 is None else {"gravity_m_s2": gravity_m_s2}
        system = System(mu_static=mu_static, mu_kinetic=mu_kinetic,
                        stiffness_per_mass=stiffness_per_mass, damping_per_mass=damping_per_mass, **kwargs)
    timing = record_timing(acceleration_m_s2, dt_s, time_s)
    acc, dt, relative_times, t0 = timing.acceleration_m_s2, timing.dt_s, timing.relative_time_s, timing.t0_s

    c = system.damping_per_mass
    kappa = system.stiffness_per_mass
    if relative_times is None:
        n_sub = _kernel.substeps_per_interval(dt, c, kappa)
        basis, gram = _kernel.full_step_coefficients(dt / n_sub, c, kappa)
        kernel_times = np.empty(0)
    else:  # per-interval pieces; the full-step constants are unused
        n_sub = max(1, math.ceil(float(np.max(np.diff(relative_times))) / _kernel.max_piece_s(c, kappa)))
        basis, gram = np.zeros(5), np.zeros((3, 3))
        kernel_times = relative_times
    n = acc.size
    out_x = np.empty(n)
    out_v = np.empty(n)
    out_a = np.empty(n)
    out_energy = np.empty((3, n))
    summary = np.zeros(_kernel.SUMMARY_SIZE)
    capacity = 64 + n // 4
    _warm_up_kernel()
    while True:
        ev_time = np.empty(capacity)
        ev_kind = np.empty(capacity, dtype=np.int8)
        ev_x = np.empty(capacity)
        start = time.perf_counter()
        _kernel.record_kernel(acc, dt, n_sub, c, kappa, system.static_friction_m_s2,
                              system.kinetic_friction_m_s2, basis, gram, out_x, out_v, out_a, out_energy,
                              ev_time, ev_kind, ev_x, summary, kernel_times, _kernel.max_piece_s(c, kappa))
        elapsed = time.perf_counter() - start
        n_events = int(summary[_kernel.SUMMARY_N_EVENTS])
        if n_events <= capacity:
            break
        capacity = n_events + 16  # rare: rerun with room for every event
    status = int(summary[_kernel.SUMMARY_STATUS])
    message = "ok"
    if status & _kernel.STATUS_CHATTER:
        message = (f"chatter guard: more than {_kernel.MAX_EVENTS_PER_INTERVAL} events in one sample "
                   "interval; the static friction held the block to the end of that interval")
    e_in = summary[_kernel.SUMMARY_ENERGY_INPUT]
    e_f = summary[_kernel.SUMMARY_ENERGY_FRICTION]
    e_v = summary[_kernel.SUMMARY_ENERGY_VISCOUS]
    e_kin = 0.5 * out_v[-1] ** 2
    e_pot = 0.5 * kappa * out_x[-1] ** 2
    return Response(
        system=system,
        time_s=t0 + (dt * np.arange(n) if relative_times is None else relative_times),
        ground_acceleration_m_s2=acc,
        displacement_m=out_x,
        velocity_m_s=out_v,
        absolute_acceleration_m_s2=out_a,
        event_time_s=t0 + ev_time[:n_events],
        event_kind=ev_kind[:n_events],
        event_displacement_m=ev_x[:n_events],
        peak_displacement_m=float(summary[_kernel.SUMMARY_PEAK_DISPLACEMENT]),
        residual_displacement_m=float(out_x[-1]),
        peak_velocity_m_s=float(summary[_kernel.SUMMARY_PEAK_VELOCITY]),
        peak_transmitted_acceleration_m_s2=float(summary[_kernel.SUMMARY_PEAK_ABS_ACCELERATION]),
        slip_time_s=float(summary[_kernel.SUMMARY_SLIP_TIME]),
        n_events=n_events,
        energy_input_J_per_kg=float(e_in),
        energy_friction_J_per_kg=float(e_f),
        energy_viscous_J_per_kg=float(e_v),
        energy_kinetic_final_J_per_kg=float(e_kin),
        energy_potential_final_J_per_kg=float(e_pot),
        energy_balance_error_J_per_kg=float(e_in - (e_kin + e_pot + e_f + e_v)),
        energy_history_J_per_kg=out_energy,
        status=status,
        message=message,
        solver_seconds=elapsed,
        substeps_per_interval=n_sub,
    )


# ---------------------------------------------------------------------------------------
# the registry's entry points (isolator.solver.models)
# ---------------------------------------------------------------------------------------
def scene_needs(scene) -> tuple[str, str] | None:
    """``(model, reason)`` when a scene is one component under constant friction and no vertical; else None.

    Parameters
    ----------
    scene : isolator.solver.base.Scene
    """
    if scene.has_y or scene.has_z or scene.velocity_dependent:
        return None
    return MODEL_NAME, MODEL_REASON


def simulate_scene(scene) -> Response:
    """The exact 1-D response to a scene (:func:`simulate_record`; a pendulum's radius gives K/M = g/R).

    Parameters
    ----------
    scene : isolator.solver.base.Scene
        One component; the isolator keywords of :func:`isolator.solver.planar.simulate_pair`
        (``rtol`` is not used: the kernel is exact).

    Raises
    ------
    InvalidSystemError
        An invalid isolator (a radius ≤ 0, a radius and a stiffness together, …).
    RecordInputError
        A record the kernel cannot take.
    """
    kwargs = {key: value for key, value in scene.isolator.items() if value is not None}
    kwargs.pop("rtol", None)
    radius = kwargs.pop("radius_m", None)
    if radius is not None:
        if kwargs.get("stiffness_per_mass"):
            raise InvalidSystemError("give radius_m (friction pendulum) or stiffness_per_mass, not both")
        try:
            radius = float(radius)
        except (TypeError, ValueError):
            raise InvalidSystemError(f"radius_m must be a number, got {radius!r}") from None
        if not math.isfinite(radius) or radius <= 0.0:
            raise InvalidSystemError(f"radius_m must be a finite number > 0, got {radius!r}")
        system = System(**{**kwargs, "stiffness_per_mass": 0.0})  # validates µ, c and g first
        kwargs["stiffness_per_mass"] = system.gravity_m_s2 / radius
    return simulate_record(scene.ax_m_s2, scene.dt_s, time_s=scene.time_s, **kwargs)
