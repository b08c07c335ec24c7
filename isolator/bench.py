r"""Speed against error: the exact solver against the usual numerical methods.

Every method answers the same question — the relative displacement ``X(t)`` of the
block (friction µs/µk, spring κ, dashpot c, per unit mass) under a ground
acceleration ``a_g(t)`` — through one interface::

    method(case, setting) -> MethodOutput

where ``case`` is a :class:`BenchCase` (a harmonic case of the paper, Eq. 2, or a
recorded accelerogram) and ``setting`` the method's knob (time step [s] or relative
tolerance [-]).  The output carries ``X`` and ``X'`` at the case's output times, the
peak (records) or amplitude A (harmonic), the residual displacement and the
slip-time ratio ζ.  :func:`run_bench` times every method (median of several runs in
one process) and measures its errors against the reference:

* **baselines** are compared with our exact solver;
* **our solver** is compared with the tightest event-located ``solve_ivp`` run
  (DOP853, rtol 1e-12), so its error column is an *upper bound* (the discrepancy
  between two independent solutions); for the harmonic cases the exact analytic
  steady state (:func:`isolator.solver.harmonic.harmonic_response`) is checked as well.

Methods
-------
``exact event-driven (ours)``
    :func:`isolator.solver.record.simulate_record` / the harmonic driver's
    period loop: closed-form slip segments and exactly located events (numba).
``implicit Euler, fixed step (paper's check)``
    Backward Euler with the set-valued Coulomb law solved exactly at each step
    (Moreau–Jean time stepping): stick when the trial velocity cannot overcome
    µs g h.  Numba loop.
``Newmark avg. accel. + elastic-plastic friction``
    Newmark γ = 1/2, β = 1/4 with friction as a stiff elastic–perfectly-plastic
    element (yield µs g from stick, µk g while sliding, elastic stick displacement
    ``u_y``), the way OpenSees-like codes model a flat or pendulum slider; the
    piecewise-linear residual is solved exactly (return mapping).  Numba loop.
``solve_ivp RK45|LSODA + events``
    Phase-by-phase integration: slip phases end at the terminal event V = 0, stick
    phases are skipped to the break-away time, found on the (linear or harmonic)
    forcing.  Pure SciPy/Python.
``solve_ivp RK45|LSODA, tanh friction``
    One integration of the regularised law µk g tanh(V/v_reg) (no events, no
    static friction); slip is counted where |V| > v_reg.

References
----------
M. Nicolas (2017), hal-01432172, Eq. 2 (harmonic case), Eqs. 3 (ζ) and 15 (α_SL).
"""

from __future__ import annotations

import math
import statistics
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import numpy as np
from numba import njit
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

STANDARD_GRAVITY_M_S2 = 9.80665  # [m/s²]
HARMONIC_PHASE = 0.5 * math.pi  #: φ of the paper, Eq. 2 [rad]
HARMONIC_SAMPLES_PER_PERIOD = 1000  #: output grid on the last forcing period
#: stick displacement of the Newmark elastic-plastic slider [m for records; A0 for harmonic]
ELASTIC_PLASTIC_YIELD_DISPLACEMENT = 1e-4
#: regularisation velocity of the tanh friction law [m/s for records; sqrt(g A0) for harmonic]
TANH_VELOCITY = 1e-3
ERROR_FLOOR = 1e-16  #: errors below this are reported as this (round-off)
OURS = "exact event-driven (ours)"


# ======================================================================================
# Cases
# ======================================================================================

@dataclass
class BenchCase:
    """One benchmark problem: a system and a ground motion, per unit mass (SI or Eq. 2 units).

    ``kind`` is ``"harmonic"`` (dimensionless, g = 1, a_g = ω² cos(ωt + π/2), from rest,
    compared on the last of ``n_periods`` forcing periods) or ``"record"`` (a sampled
    accelerogram [m/s²] taken as linear between samples, compared on every sample).
    """

    name: str
    kind: str
    mu_static: float
    mu_kinetic: float
    stiffness_per_mass: float  #: κ [1/s²] (k for harmonic cases)
    damping_per_mass: float  #: c [1/s] (η for harmonic cases)
    gravity: float  #: g [m/s²] (1 for harmonic cases)
    duration: float  #: [s] (dimensionless time for harmonic cases)
    output_time: np.ndarray = field(repr=False)  #: comparison times
    window_start: float = 0.0  #: start of the window where peak/A and ζ are measured
    acceleration_m_s2: np.ndarray | None = field(default=None, repr=False)
    dt_s: float | None = None
    alpha: float | None = None
    omega: float | None = None
    n_periods: int | None = None
    exact_zeta: float | None = None  #: analytic steady-state ζ (harmonic)
    exact_amplitude: float | None = None  #: analytic steady-state A (harmonic)

    def ground_acceleration(self, t) -> np.ndarray:
        """a_g at times ``t`` (first-order hold for records)."""
        t = np.asarray(t, dtype=float)
        if self.kind == "harmonic":
            return self.omega ** 2 * np.cos(self.omega * t + HARMONIC_PHASE)
        return np.interp(t, self.output_time, self.acceleration_m_s2)

    def ground_acceleration_at(self, t: float) -> float:
        """a_g at one time ``t`` (the fast path of the solve_ivp right-hand sides)."""
        if self.kind == "harmonic":
            return self.omega ** 2 * math.cos(self.omega * t + HARMONIC_PHASE)
        acc = self.acceleration_m_s2
        u = t / self.dt_s
        i = min(max(int(u), 0), acc.size - 2)
        frac = min(max(u - i, 0.0), 1.0)
        return float(acc[i] + frac * (acc[i + 1] - acc[i]))

    @property
    def static_friction(self) -> float:
        return self.mu_static * self.gravity

    @property
    def kinetic_friction(self) -> float:
        return self.mu_kinetic * self.gravity

    @property
    def window_length(self) -> float:
        return self.duration - self.window_start


def harmonic_case(name: str, alpha: float, k: float, eta: float, mu_s: float, mu_k: float | None = None,
                  n_periods: int | None = None) -> BenchCase:
    """A harmonic case (Eq. 2) run from rest to its steady state plus two periods.

    Parameters
    ----------
    alpha, k, eta : float
        Reduced acceleration, stiffness and damping (Eq. 6) [-].
    mu_s, mu_k : float
        Friction coefficients [-].
    n_periods : int, optional
        Forcing periods simulated; by default two more than the exact solver needs
        to reach the periodic state, at least 4.
    """
    from isolator.solver.harmonic import harmonic_response

    mu_k = mu_s if mu_k is None else mu_k
    exact = harmonic_response(alpha, k, eta, mu_s, mu_k)
    if n_periods is None:
        n_periods = max(4, exact.periods_run + 2)
    omega = math.sqrt(alpha * mu_s)
    period = 2.0 * math.pi / omega
    start = (n_periods - 1) * period
    out = start + np.linspace(0.0, period, HARMONIC_SAMPLES_PER_PERIOD + 1)
    return BenchCase(name=name, kind="harmonic", mu_static=mu_s, mu_kinetic=mu_k, stiffness_per_mass=k,
                     damping_per_mass=eta, gravity=1.0, duration=n_periods * period, output_time=out,
                     window_start=start, alpha=alpha, omega=omega, n_periods=n_periods,
                     exact_zeta=exact.zeta, exact_amplitude=exact.amplitude)


def record_case(name: str, acceleration_m_s2, dt_s: float, *, mu_static: float, mu_kinetic: float | None = None,
                stiffness_per_mass: float = 0.0, damping_per_mass: float = 0.0,
                gravity_m_s2: float = STANDARD_GRAVITY_M_S2) -> BenchCase:
    """A recorded ground motion [m/s², dt_s in s] with an isolator (per unit mass)."""
    acc = np.ascontiguousarray(acceleration_m_s2, dtype=float)
    times = dt_s * np.arange(acc.size)
    return BenchCase(name=name, kind="record", mu_static=mu_static,
                     mu_kinetic=mu_static if mu_kinetic is None else mu_kinetic,
                     stiffness_per_mass=stiffness_per_mass, damping_per_mass=damping_per_mass,
                     gravity=gravity_m_s2, duration=float(times[-1]), output_time=times,
                     acceleration_m_s2=acc, dt_s=float(dt_s))


#: The friction-pendulum design of the record cases: R = 2 m (T = 2.84 s), µs = 0.06, µk = 0.05.
PENDULUM_RADIUS_M = 2.0
PENDULUM_MU_STATIC = 0.06
PENDULUM_MU_KINETIC = 0.05

#: Harmonic cases, one per configuration of the paper (Table 2): (name, α, k, η, µs, µk).
HARMONIC_CASES = [
    ("harmonic config 1 (friction)", 1.2, 0.0, 0.0, 0.25, 0.25),
    ("harmonic config 2 (+ dashpot)", 2.0, 0.0, 0.5, 0.25, 0.2),
    ("harmonic config 3 (+ spring)", 1.3, 0.1, 0.0, 0.25, 0.2),
    ("harmonic config 4a (complete)", 1.5, 1.0, 0.5, 0.25, 0.2),
]
#: Records of ../shared/records used by the full bench (the first one by --quick), with the
#: damping of an added viscous damper c = γ/M [1/s] (0.44 1/s: 10 % of critical at T = 2.84 s).
RECORD_FILES = [("at2/RSN1044_NORTHR_NWH360.AT2", 0.0), ("at2/IELC180.AT2", 0.0),
                ("at2/RSN779_LOMAP_LGP000.AT2", 0.44)]


def default_records_dir() -> Path:
    """``<repository>/../shared/records``."""
    return Path(__file__).resolve().parents[1].parent / "shared" / "records"


def bench_cases(quick: bool = False, records_dir: Path | None = None) -> list[BenchCase]:
    """The benchmark's cases: the harmonic configurations and the records found."""
    harmonic = HARMONIC_CASES[:1] + HARMONIC_CASES[3:] if quick else HARMONIC_CASES
    cases = [harmonic_case(*spec) for spec in harmonic]
    records_dir = default_records_dir() if records_dir is None else Path(records_dir)
    if records_dir.is_dir():
        from isolator.motion import read_ground_motion

        for rel, damping in RECORD_FILES[:1] if quick else RECORD_FILES:
            path = records_dir / rel
            if not path.is_file():
                continue
            motion = read_ground_motion(path)
            damper = f" + damper c={damping:g}/s" if damping else ""
            cases.append(record_case(
                f"record {path.stem} (FP R={PENDULUM_RADIUS_M:g} m{damper})", motion.acceleration_m_s2, motion.dt_s,
                mu_static=PENDULUM_MU_STATIC, mu_kinetic=PENDULUM_MU_KINETIC,
                stiffness_per_mass=STANDARD_GRAVITY_M_S2 / PENDULUM_RADIUS_M, damping_per_mass=damping))
    return cases


# ======================================================================================
# Method outputs and their summary
# ======================================================================================

@dataclass
class MethodOutput:
    """What every method returns (units of the case)."""

    displacement: np.ndarray  #: X at ``case.output_time``
    velocity: np.ndarray  #: X' at ``case.output_time``
    peak: float  #: records: max |X|; harmonic: A = half peak-to-peak on the last period
    residual: float  #: X at the end of the run
    slip_ratio: float  #: slip time / window length (ζ, Eq. 3)
    n_events: int = -1  #: break-aways + stops, when the method knows them


def _window_peak(case: BenchCase, x_window: np.ndarray) -> float:
    if case.kind == "harmonic":
        return 0.5 * float(np.max(x_window) - np.min(x_window))
    return float(np.max(np.abs(x_window)))


def _from_grid(case: BenchCase, t_grid, x_grid, v_grid, slipping) -> MethodOutput:
    """Summarise a fixed-step solution (values at every step, slip flag per step)."""
    x_out = np.interp(case.output_time, t_grid, x_grid)
    v_out = np.interp(case.output_time, t_grid, v_grid)
    inside = t_grid >= case.window_start - 1e-12 * case.duration
    h = t_grid[1] - t_grid[0]
    slip = float(np.count_nonzero(slipping[1:] & inside[1:])) * h / case.window_length
    return MethodOutput(x_out, v_out, _window_peak(case, x_grid[inside]), float(x_grid[-1]), min(slip, 1.0))


def _step_grid(case: BenchCase, step: float):
    n_steps = max(1, int(math.ceil(case.duration / step - 1e-9)))
    t_grid = np.linspace(0.0, case.duration, n_steps + 1)
    return t_grid, case.ground_acceleration(t_grid), case.duration / n_steps


# ======================================================================================
# Ours
# ======================================================================================

def exact_solver(case: BenchCase, setting=None) -> MethodOutput:
    """Our exact event-driven solver (the record kernel, or the harmonic period loop)."""
    if case.kind == "record":
        from isolator.solver.record import simulate_record

        res = simulate_record(case.acceleration_m_s2, case.dt_s, mu_static=case.mu_static,
                              mu_kinetic=case.mu_kinetic, stiffness_per_mass=case.stiffness_per_mass,
                              damping_per_mass=case.damping_per_mass, gravity_m_s2=case.gravity)
        return MethodOutput(res.displacement_m, res.velocity_m_s, res.peak_displacement_m,
                            res.residual_displacement_m, res.slip_time_s / case.window_length, res.n_events)
    from isolator.solver import harmonic as hm

    k, eta, mu_s, mu_k, omega = (case.stiffness_per_mass, case.damping_per_mass, case.mu_static,
                                 case.mu_kinetic, case.omega)
    period = 2.0 * math.pi / omega
    shortest = period
    d2 = 0.25 * eta * eta - k
    if d2 < 0.0:
        shortest = min(shortest, 2.0 * math.pi / math.sqrt(-d2))
    if eta > 0.0:
        shortest = min(shortest, 2.0 * math.pi / eta)
    piece_max = shortest / hm.PIECES_PER_PERIOD
    state = np.zeros(hm._STATE_SIZE)
    state[2] = 1.0  # at rest, stuck
    metrics = np.zeros(hm._METRICS_SIZE)
    empty = np.zeros(0)
    empty_kind = np.zeros(0, dtype=np.int8)
    if case.n_periods > 1:
        hm._advance_periods(case.n_periods - 1, state, omega, k, eta, mu_s, mu_k, HARMONIC_PHASE, piece_max,
                            False, empty, empty_kind, empty, empty, empty, empty, metrics)
    # times from the start of the last period; rounding must not push the last one past it
    t_out = np.clip(case.output_time - case.window_start, 0.0, period)
    x_out = np.empty_like(t_out)
    v_out = np.empty_like(t_out)
    capacity = 256
    ev_time = np.empty(capacity)
    ev_kind = np.empty(capacity, dtype=np.int8)
    ev_x = np.empty(capacity)
    n_ev = hm._advance_periods(1, state, omega, k, eta, mu_s, mu_k, HARMONIC_PHASE, piece_max, True,
                               ev_time, ev_kind, ev_x, t_out, x_out, v_out, metrics)
    amplitude = 0.5 * (metrics[hm.M_XMAX] - metrics[hm.M_XMIN])
    return MethodOutput(x_out, v_out, float(amplitude), float(state[0]), float(metrics[hm.M_SLIP] / period), n_ev)


# ======================================================================================
# Fixed-step baselines (numba, so that algorithms and not interpreters are compared)
# ======================================================================================

@njit(cache=True)
def _implicit_euler_kernel(acc, h, c, kappa, fs, fk, x, v, slipping):  # pragma: no cover - numba
    # Backward Euler on X' = V, V' = -κX - cV - a_g - f, f ∈ fk Sign(V) (fs from rest):
    # (1 + hc + h²κ) V₊ = r - h f with r = V - h(κX + a₊); the set-valued law is solved
    # exactly, so a stuck block has V = 0 to the bit.
    denom = 1.0 + h * c + h * h * kappa
    x[0] = 0.0
    v[0] = 0.0
    slipping[0] = False
    for n in range(acc.shape[0] - 1):
        r = v[n] - h * (kappa * x[n] + acc[n + 1])
        vn = 0.0
        if v[n] != 0.0 and r * v[n] > 0.0 and abs(r) > h * fk:
            vn = (r - h * fk * math.copysign(1.0, r)) / denom  # keeps sliding
        elif abs(r) > h * fs:
            vn = (r - h * fk * math.copysign(1.0, r)) / denom  # starts or reverses
        v[n + 1] = vn
        x[n + 1] = x[n] + h * vn
        slipping[n + 1] = vn != 0.0


def implicit_fixed_step(case: BenchCase, step: float) -> MethodOutput:
    """Implicit (backward Euler, Moreau–Jean) fixed-step scheme; ``step`` in case time units."""
    t_grid, acc, h = _step_grid(case, step)
    x = np.empty_like(t_grid)
    v = np.empty_like(t_grid)
    slipping = np.empty(t_grid.size, dtype=np.bool_)
    _implicit_euler_kernel(acc, h, case.damping_per_mass, case.stiffness_per_mass, case.static_friction,
                           case.kinetic_friction, x, v, slipping)
    return _from_grid(case, t_grid, x, v, slipping)


@njit(cache=True)
def _newmark_kernel(acc, h, c, kappa, fs, fk, k_elastic, x, v, slipping):  # pragma: no cover - numba
    # Newmark average acceleration; friction z is elastic (stiffness k_elastic) up to the
    # yield force fs (from stick) or fk (while sliding), then perfectly plastic at fk.
    # The residual is piecewise linear in X₊, so the return mapping is solved exactly.
    k_dyn = 4.0 / (h * h) + 2.0 * c / h + kappa
    x[0] = 0.0
    v[0] = 0.0
    a_rel = -acc[0]
    z = 0.0
    plastic = False
    slipping[0] = False
    for n in range(acc.shape[0] - 1):
        # equilibrium at n+1: A + cV + κX + z = -a_g, with A, V linear in X₊
        b = (-acc[n + 1] + (4.0 / (h * h)) * (x[n] + h * v[n]) + a_rel
             + c * ((2.0 / h) * x[n] + v[n]))
        limit = fk if plastic else fs
        x_new = (b - z + k_elastic * x[n]) / (k_dyn + k_elastic)
        z_new = z + k_elastic * (x_new - x[n])
        plastic = False
        if abs(z_new) > limit:
            sign = math.copysign(1.0, z_new)
            x_new = (b - sign * fk) / k_dyn
            z_new = sign * fk
            plastic = True
        a_new = (4.0 / (h * h)) * (x_new - x[n] - h * v[n]) - a_rel
        v_new = v[n] + 0.5 * h * (a_rel + a_new)
        x[n + 1] = x_new
        v[n + 1] = v_new
        a_rel = a_new
        z = z_new
        slipping[n + 1] = plastic


def newmark_elastic_plastic(case: BenchCase, step: float) -> MethodOutput:
    """Newmark average acceleration with an elastic–plastic friction element; ``step`` in case time units."""
    t_grid, acc, h = _step_grid(case, step)
    x = np.empty_like(t_grid)
    v = np.empty_like(t_grid)
    slipping = np.empty(t_grid.size, dtype=np.bool_)
    k_elastic = case.static_friction / ELASTIC_PLASTIC_YIELD_DISPLACEMENT
    _newmark_kernel(acc, h, case.damping_per_mass, case.stiffness_per_mass, case.static_friction,
                    case.kinetic_friction, k_elastic, x, v, slipping)
    return _from_grid(case, t_grid, x, v, slipping)


# ======================================================================================
# solve_ivp baselines (pure SciPy)
# ======================================================================================

def _breakaway_time(case: BenchCase, t_from: float, x_stuck: float) -> float | None:
    """First time after ``t_from`` where |κ X + a_g| > µs g, or None."""
    kappa, fs = case.stiffness_per_mass, case.static_friction
    if case.kind == "record":
        dt = case.dt_s
        acc = case.acceleration_m_s2
        i0 = min(int(t_from / dt), acc.size - 2)
        f0 = kappa * x_stuck + (case.ground_acceleration_at(t_from))
        if abs(f0) > fs:
            return t_from
        force = kappa * x_stuck + acc[i0 + 1:]
        over = np.flatnonzero(np.abs(force) > fs)
        if over.size == 0:
            return None
        j = i0 + 1 + int(over[0])  # first sample beyond the threshold
        ta = max(t_from, (j - 1) * dt)
        fa = kappa * x_stuck + (case.ground_acceleration_at(ta))
        fb = force[over[0]]
        target = math.copysign(fs, fb)
        frac = (target - fa) / (fb - fa) if fb != fa else 1.0
        return ta + min(max(frac, 0.0), 1.0) * (j * dt - ta)
    # harmonic: scan a grid of 1/256 period, then bracket the crossing
    period = 2.0 * math.pi / case.omega
    step = period / 256.0

    def excess(t):
        return abs(kappa * x_stuck + (case.ground_acceleration_at(t))) - fs

    if excess(t_from) > 0.0:
        return t_from
    t = t_from
    while t < case.duration:
        t_next = min(t + step, case.duration)
        if excess(t_next) > 0.0:
            return brentq(excess, t, t_next, xtol=1e-14, rtol=4 * np.finfo(float).eps)
        t = t_next
    return None


def _ivp_events(case: BenchCase, method: str, rtol: float, atol_scale: float = 1e-3):
    """Event-driven solve_ivp: returns the dense pieces [(t0, t1, sol or x_stuck)], events, slip intervals."""
    kappa, c, fs, fk = case.stiffness_per_mass, case.damping_per_mass, case.static_friction, case.kinetic_friction
    atol = rtol * atol_scale
    t, x, mode = 0.0, 0.0, 0
    pieces = []
    n_events = 0
    while t < case.duration:
        if mode == 0:
            tb = _breakaway_time(case, t, x)
            if tb is None or tb >= case.duration:
                pieces.append((t, case.duration, x))
                break
            if tb > t:
                pieces.append((t, tb, x))
            force = kappa * x + (case.ground_acceleration_at(tb))
            mode = -1 if force > 0.0 else 1
            t = tb
            n_events += 1
            v = 0.0
        s = mode

        def rhs(tt, y, s=s):
            return [y[1], -fk * s - kappa * y[0] - c * y[1] - (case.ground_acceleration_at(tt))]

        def stop(tt, y, s=s):
            return s * y[1]

        stop.terminal = True
        stop.direction = -1
        t_start = t
        sol = solve_ivp(rhs, (t, case.duration), [x, v], method=method, rtol=rtol, atol=atol,
                        dense_output=True, events=stop)
        if sol.status < 0:
            raise RuntimeError(f"solve_ivp {method}: {sol.message}")
        if sol.status == 1 and sol.t_events[0].size:
            t1 = float(sol.t_events[0][0])
            x1 = float(sol.y_events[0][0][0])
            if t1 <= t_start + 1e-12 * case.duration:
                # a touch of V = 0 at the start from rest: slide a little without the event
                h = 1e-9 * case.duration
                nudge = solve_ivp(rhs, (t, t + h), [x, v], method=method, rtol=rtol, atol=atol, dense_output=True)
                pieces.append((t, t + h, nudge.sol))
                t, x, v = t + h, float(nudge.y[0, -1]), float(nudge.y[1, -1])
                continue
            pieces.append((t_start, t1, sol.sol))
            t, x, v = t1, x1, 0.0
            n_events += 1
            force = kappa * x + (case.ground_acceleration_at(t))
            mode = 0 if abs(force) <= fs else (-1 if force > 0.0 else 1)
        else:
            pieces.append((t_start, case.duration, sol.sol))
            t = case.duration
            x = float(sol.y[0, -1])
    return pieces, n_events


def _evaluate_pieces(case: BenchCase, pieces):
    starts = np.array([p[0] for p in pieces])
    x_out = np.empty_like(case.output_time)
    v_out = np.zeros_like(case.output_time)
    idx = np.clip(np.searchsorted(starts, case.output_time, side="right") - 1, 0, len(pieces) - 1)
    for i in np.unique(idx):
        mask = idx == i
        body = pieces[i][2]
        if isinstance(body, float):
            x_out[mask] = body
        else:
            y = body(np.clip(case.output_time[mask], pieces[i][0], pieces[i][1]))
            x_out[mask], v_out[mask] = y[0], y[1]
    ends = []  # displacements where pieces end (stops are the extrema)
    slip = 0.0
    for t0, t1, body in pieces:
        if t1 >= case.window_start:
            if isinstance(body, float):
                ends.append(body)
            else:
                ends.append(float(body(t1)[0]))
                slip += t1 - max(t0, case.window_start)
    last = pieces[-1]
    residual = last[2] if isinstance(last[2], float) else float(last[2](last[1])[0])
    peak = _window_peak(case, np.concatenate([x_out[case.output_time >= case.window_start], ends]))
    return x_out, v_out, peak, residual, slip / case.window_length


def ivp_with_events(case: BenchCase, rtol: float, method: str = "RK45") -> MethodOutput:
    """``scipy.integrate.solve_ivp`` phase by phase with event location at every stop."""
    pieces, n_events = _ivp_events(case, method, rtol)
    x, v, peak, residual, slip = _evaluate_pieces(case, pieces)
    return MethodOutput(x, v, peak, residual, slip, n_events)


def ivp_tanh(case: BenchCase, rtol: float, method: str = "RK45") -> MethodOutput:
    """``solve_ivp`` on the regularised law µk g tanh(V/v_reg), no events."""
    kappa, c, fk = case.stiffness_per_mass, case.damping_per_mass, case.kinetic_friction
    v_reg = TANH_VELOCITY

    def rhs(t, y):
        return [y[1], -fk * math.tanh(y[1] / v_reg) - kappa * y[0] - c * y[1] - (case.ground_acceleration_at(t))]

    t_eval = np.unique(np.concatenate([case.output_time, [case.duration]]))
    sol = solve_ivp(rhs, (0.0, case.duration), [0.0, 0.0], method=method, rtol=rtol, atol=rtol * 1e-3,
                    t_eval=t_eval)
    if sol.status < 0:
        raise RuntimeError(f"solve_ivp {method}: {sol.message}")
    x_out = np.interp(case.output_time, sol.t, sol.y[0])
    v_out = np.interp(case.output_time, sol.t, sol.y[1])
    inside = case.output_time >= case.window_start
    slip = float(np.mean(np.abs(v_out[inside]) > v_reg))
    return MethodOutput(x_out, v_out, _window_peak(case, x_out[inside]), float(sol.y[0, -1]), slip)


# ======================================================================================
# The benchmark
# ======================================================================================

@dataclass
class Method:
    name: str
    function: Callable[[BenchCase, object], MethodOutput]
    settings: list  #: records
    harmonic_settings: list
    setting_name: str  #: "dt" or "rtol"


def methods(quick: bool = False) -> list[Method]:
    """The methods and their settings (steps in s for records, in Eq. 2 time for harmonic cases)."""
    steps_rec = [1e-2, 1e-3, 1e-4] if quick else [1e-2, 3e-3, 1e-3, 3e-4, 1e-4]
    steps_harm = [1e-1, 1e-2, 1e-3] if quick else [1e-1, 1e-2, 1e-3, 1e-4]
    tols = [1e-3, 1e-6] if quick else [1e-3, 1e-5, 1e-7, 1e-9]
    tols_tanh = [1e-3, 1e-6] if quick else [1e-3, 1e-5, 1e-7]
    return [
        Method(OURS, exact_solver, [None], [None], "-"),
        Method("implicit Euler fixed step (paper's check)", implicit_fixed_step, steps_rec, steps_harm, "dt"),
        Method("Newmark avg. accel. + elastic-plastic friction", newmark_elastic_plastic, steps_rec, steps_harm,
               "dt"),
        Method("solve_ivp RK45 + events", lambda case, tol: ivp_with_events(case, tol, "RK45"), tols, tols, "rtol"),
        Method("solve_ivp LSODA + events", lambda case, tol: ivp_with_events(case, tol, "LSODA"), tols, tols,
               "rtol"),
        Method("solve_ivp RK45, tanh friction", lambda case, tol: ivp_tanh(case, tol, "RK45"), tols_tanh, tols_tanh,
               "rtol"),
        Method("solve_ivp LSODA, tanh friction", lambda case, tol: ivp_tanh(case, tol, "LSODA"), tols_tanh,
               tols_tanh, "rtol"),
    ]


CROSS_CHECK = ("solve_ivp DOP853 + events (tightest)", 1e-12)


def errors(case: BenchCase, out: MethodOutput, ref: MethodOutput) -> dict:
    """Errors of ``out`` against ``ref``: peak (relative), residual [m], ζ, trajectory (relative to the peak)."""
    scale = max(float(np.max(np.abs(ref.displacement))), ERROR_FLOOR)
    traj = float(np.max(np.abs(out.displacement - ref.displacement))) / scale
    peak = abs(out.peak - ref.peak) / max(abs(ref.peak), ERROR_FLOOR)
    return {
        "error_peak_rel": max(peak, ERROR_FLOOR),
        "error_residual_abs": max(abs(out.residual - ref.residual), ERROR_FLOOR),
        "error_zeta": max(abs(out.slip_ratio - ref.slip_ratio), ERROR_FLOOR),
        "error_trajectory": max(traj, ERROR_FLOOR) if np.all(np.isfinite(out.displacement)) else math.inf,
    }


def time_method(function, case, setting, repeats: int, budget_s: float = 2.0, min_total_s: float = 0.2,
                max_runs: int = 50):
    """Median wall time [s] of at least ``repeats`` runs, more (up to ``max_runs``) while the
    total stays under ``min_total_s``; a single run if the first takes more than ``budget_s``."""
    times = []
    out = None
    while True:
        start = time.perf_counter()
        out = function(case, setting)
        times.append(time.perf_counter() - start)
        if times[0] > budget_s or len(times) >= max_runs:
            break
        if len(times) >= max(1, repeats) and sum(times) >= min_total_s:
            break
    return statistics.median(times), out


def warm_up() -> None:
    """Compile or load every numba function once, so that timings measure solving."""
    case = harmonic_case("warm-up", 1.5, 1.0, 0.5, 0.25, 0.2, n_periods=1)
    exact_solver(case)
    implicit_fixed_step(case, 0.5)
    newmark_elastic_plastic(case, 0.5)
    rec = record_case("warm-up", np.sin(np.arange(50) * 0.3), 0.01, mu_static=0.05, stiffness_per_mass=4.9)
    exact_solver(rec)


def run_bench(quick: bool = False, records_dir: Path | None = None, repeats: int | None = None,
              cases: list[BenchCase] | None = None, progress: Callable[[str], None] | None = None):
    """Run every method on every case.

    Returns
    -------
    rows : list of dict
        One row per (method, case, setting) with keys ``method``, ``case``, ``setting``,
        ``seconds`` (median wall time [s]), ``error_peak_rel`` [-], ``error_residual_abs``
        [m, or A0 for harmonic cases], ``error_zeta`` [-] and ``error_trajectory`` [-,
        max |X - X_ref| / max |X_ref|].
    pareto : list of dict
        Per case, where our solver stands against the baselines (see :func:`pareto_summary`).
    """
    repeats = (3 if quick else 5) if repeats is None else repeats
    cases = bench_cases(quick, records_dir) if cases is None else cases
    warm_up()
    rows = []
    for case in cases:
        seconds, ours = time_method(exact_solver, case, None, repeats)
        cross_name, cross_tol = CROSS_CHECK
        cross_seconds, cross = time_method(lambda c, tol: ivp_with_events(c, tol, "DOP853"), case, cross_tol, 1)
        row = {"method": OURS, "case": case.name, "setting": "-", "seconds": seconds, **errors(case, ours, cross),
               "n_events": ours.n_events}
        if case.kind == "harmonic":
            row["error_zeta_analytic"] = max(abs(ours.slip_ratio - case.exact_zeta), ERROR_FLOOR)
            row["error_amplitude_analytic_rel"] = max(abs(ours.peak - case.exact_amplitude) / case.exact_amplitude,
                                                      ERROR_FLOOR)
        rows.append(row)
        rows.append({"method": cross_name, "case": case.name, "setting": cross_tol, "seconds": cross_seconds,
                     **errors(case, cross, ours), "n_events": cross.n_events})
        if progress:
            progress(f"{case.name}: ours {seconds * 1e3:.3g} ms, cross-check {cross_seconds:.3g} s")
        for method in methods(quick)[1:]:
            settings = method.harmonic_settings if case.kind == "harmonic" else method.settings
            for setting in settings:
                seconds, out = time_method(method.function, case, setting, repeats)
                rows.append({"method": method.name, "case": case.name, "setting": setting, "seconds": seconds,
                             **errors(case, out, ours), "n_events": out.n_events})
                if progress:
                    progress(f"  {method.name} {method.setting_name}={setting}: {seconds:.3g} s, "
                             f"trajectory error {rows[-1]['error_trajectory']:.2e}")
    pareto = pareto_summary(rows)
    for row in rows:  # the ratios ride along on our rows too
        if row["method"] == OURS:
            by_case = pareto_by_case(pareto)[row["case"]]
            row.update({k: v for k, v in by_case.items() if k.startswith(("speedup", "accuracy"))})
    return rows, pareto


def pareto_by_case(pareto):
    return {p["case"]: p for p in pareto}


#: the engineering accuracy at which speed-ups are also quoted (trajectory error)
ENGINEERING_ERROR = 1e-3


def pareto_summary(rows: list[dict], error_key: str = "error_trajectory") -> list[dict]:
    """Per case: is ours on the Pareto front, and by how much.

    ``speedup_at_equal_error``: time of the fastest baseline whose error is at most
    ours, divided by ours (``None``: no baseline reaches our error).
    ``speedup_at_1e-3``: the same at the engineering accuracy 1e-3.
    ``accuracy_gain_at_equal_time``: error of the most accurate baseline that runs at
    most as long as ours, divided by ours (``None``: no baseline is as fast).
    ``accuracy_gain_vs_fastest``: error of the fastest baseline over ours, with
    ``fastest_time_ratio`` its time over ours.  The DOP853 cross-check is left out of
    the baselines (its error and ours are the same number, their discrepancy);
    ``cross_check_time_ratio`` is its time over ours.
    """
    summary = []
    for case in dict.fromkeys(r["case"] for r in rows):
        ours = next(r for r in rows if r["case"] == case and r["method"] == OURS)
        # the cross-check is not a baseline: its error and ours are the same discrepancy
        base = [r for r in rows if r["case"] == case and r["method"] not in (OURS, CROSS_CHECK[0])
                and math.isfinite(r[error_key])]
        cross = [r for r in rows if r["case"] == case and r["method"] == CROSS_CHECK[0]]
        t0, e0 = ours["seconds"], ours[error_key]
        reach = [r for r in base if r[error_key] <= e0]
        reach_eng = [r for r in base if r[error_key] <= ENGINEERING_ERROR]
        as_fast = [r for r in base if r["seconds"] <= t0]
        fastest = min(base, key=lambda r: r["seconds"])
        most_accurate = min(base, key=lambda r: r[error_key])
        dominated = any(r["seconds"] <= t0 and r[error_key] <= e0 for r in base)

        def label(r):
            return f"{r['method']} @ {r['setting']}"

        summary.append({
            "case": case,
            "seconds": t0,
            "error": e0,
            "on_pareto_front": not dominated,
            "speedup_at_equal_error": min(r["seconds"] for r in reach) / t0 if reach else None,
            "speedup_at_1e-3": (min(r["seconds"] for r in reach_eng) / t0) if reach_eng else None,
            "speedup_at_1e-3_vs": label(min(reach_eng, key=lambda r: r["seconds"])) if reach_eng else "none reaches it",
            "accuracy_gain_at_equal_time": (min(r[error_key] for r in as_fast) / e0) if as_fast else None,
            "accuracy_gain_vs_fastest": fastest[error_key] / e0,
            "fastest_baseline": label(fastest),
            "fastest_time_ratio": fastest["seconds"] / t0,
            "most_accurate_baseline": label(most_accurate),
            "most_accurate_error": most_accurate[error_key],
            "most_accurate_time_ratio": most_accurate["seconds"] / t0,
            "cross_check_time_ratio": cross[0]["seconds"] / t0 if cross else None,
        })
    return summary


# ======================================================================================
# Output: table, CSV, plot
# ======================================================================================

ROW_KEYS = ["method", "case", "setting", "seconds", "error_peak_rel", "error_residual_abs", "error_zeta",
            "error_trajectory"]


def rows_to_csv(rows: list[dict]) -> str:
    """The rows as CSV text (ROW_KEYS columns, then n_events)."""
    lines = [",".join(ROW_KEYS + ["n_events"])]
    for r in rows:
        cells = []
        for key in ROW_KEYS + ["n_events"]:
            value = r.get(key, "")
            cells.append(f'"{value}"' if isinstance(value, str) and "," in value else
                         (f"{value:.6g}" if isinstance(value, float) else str(value)))
        lines.append(",".join(cells))
    return "\n".join(lines) + "\n"


def pareto_to_csv(pareto: list[dict]) -> str:
    keys = list(pareto[0].keys()) if pareto else []
    lines = [",".join(keys)]
    for p in pareto:
        cells = []
        for k in keys:
            v = p[k]
            cells.append(f"{v:.4g}" if isinstance(v, float) else (f'"{v}"' if isinstance(v, str) and "," in v
                                                                   else str(v)))
        lines.append(",".join(cells))
    return "\n".join(lines) + "\n"


def _ratio(value, fmt=".3g"):
    return "—" if value is None else f"{value:{fmt}}×"


def _speed_words(time_ratio: float) -> str:
    return f"{time_ratio:.3g}× slower" if time_ratio >= 1.0 else f"{1.0 / time_ratio:.3g}× faster"


def pareto_markdown(pareto: list[dict]) -> str:
    """The Pareto headline as a Markdown table."""
    lines = ["| case | ours: time | ours: error | on front | speed-up at equal error | speed-up at error 1e-3 "
             "| accuracy gain at equal time | fastest baseline: time, error gain | most accurate baseline |",
             "|---|---|---|---|---|---|---|---|---|"]
    for p in pareto:
        eq_err = _ratio(p["speedup_at_equal_error"]) if p["speedup_at_equal_error"] else "none reaches it"
        if p["speedup_at_equal_error"] is None and p.get("cross_check_time_ratio"):
            eq_err += f" (DOP853 rtol 1e-12 cross-check: {p['cross_check_time_ratio']:.3g}× slower)"
        eq_time = _ratio(p["accuracy_gain_at_equal_time"]) if p["accuracy_gain_at_equal_time"] else "none as fast"
        eng = (f"{p['speedup_at_1e-3']:.3g}× ({p['speedup_at_1e-3_vs']})" if p["speedup_at_1e-3"] else
               "none reaches it")
        lines.append(
            f"| {p['case']} | {p['seconds'] * 1e3:.3g} ms | {p['error']:.1e} | {'yes' if p['on_pareto_front'] else 'NO'} "
            f"| {eq_err} | {eng} | {eq_time} | {_speed_words(p['fastest_time_ratio'])}, "
            f"{p['accuracy_gain_vs_fastest']:.2g}× less accurate ({p['fastest_baseline']}) | "
            f"{p['most_accurate_baseline']}: error {p['most_accurate_error']:.1e}, "
            f"{_speed_words(p['most_accurate_time_ratio'])} |")
    return "\n".join(lines) + "\n"


def rows_markdown(rows: list[dict]) -> str:
    """All rows as a Markdown table."""
    lines = ["| case | method | setting | time [ms] | peak (rel) | residual (abs) | ζ | trajectory (rel) |",
             "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        setting = r["setting"] if isinstance(r["setting"], str) else f"{r['setting']:g}"
        lines.append(f"| {r['case']} | {r['method']} | {setting} | {r['seconds'] * 1e3:.3g} | "
                     f"{r['error_peak_rel']:.1e} | {r['error_residual_abs']:.1e} | {r['error_zeta']:.1e} | "
                     f"{r['error_trajectory']:.1e} |")
    return "\n".join(lines) + "\n"


def plot(rows: list[dict], path: Path, error_key: str = "error_trajectory") -> None:
    """Log error against log time, one curve per method, one panel per case."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    cases = list(dict.fromkeys(r["case"] for r in rows))
    names = list(dict.fromkeys(r["method"] for r in rows))
    n_col = 2 if len(cases) > 1 else 1
    n_row = int(math.ceil(len(cases) / n_col))
    fig, axes = plt.subplots(n_row, n_col, figsize=(6.0 * n_col, 4.2 * n_row), squeeze=False)
    markers = "o^svDPX*"
    for ax, case in zip(axes.ravel(), cases):
        for i, name in enumerate(names):
            # in the order of the settings (coarse to fine), so each curve is the method's own path
            pts = [(r["seconds"], r[error_key]) for r in rows if r["case"] == case and r["method"] == name]
            if not pts:
                continue
            t, e = zip(*pts)
            style = dict(marker=markers[i % len(markers)], label=name)
            if name == OURS:
                style.update(color="k", markersize=11, zorder=5)
            ax.loglog(t, e, "-" if len(t) > 1 else "", **style)
        ax.set_title(case, fontsize=9)
        ax.set_xlabel("wall time [s] (median)")
        ax.set_ylabel("max trajectory error / peak [-]")
        ax.grid(True, which="major", alpha=0.3)
    for ax in axes.ravel()[len(cases):]:
        ax.axis("off")
    handles, labels = axes.ravel()[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=3, fontsize=8, frameon=False)
    fig.tight_layout(rect=(0, 0.08 if n_row > 1 else 0.15, 1, 1))
    fig.savefig(path, dpi=110)
    plt.close(fig)
