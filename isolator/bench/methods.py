"""The methods compared by the bench, behind one interface: ``method(case, setting) -> MethodOutput``.

:data:`METHODS` is the registry (name → :class:`Method`), in the spirit of
``scipy.integrate.solve_ivp``'s ``METHODS``.  "Ours" goes through the public solver
functions (:func:`isolator.solver.record.simulate_record` and
:func:`isolator.solver.harmonic.harmonic_transient`), never through private names.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from isolator.bench.base import HARMONIC_PHASE, BenchCase, MethodOutput
from isolator.solver.jit import njit

#: stick displacement of the Newmark elastic-plastic slider [m for records; A0 for harmonic]
ELASTIC_PLASTIC_YIELD_DISPLACEMENT = 1e-4
#: regularisation velocity of the tanh friction law [m/s for records; sqrt(g A0) for harmonic]
TANH_VELOCITY = 1e-3
OURS = "exact event-driven (ours)"


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
    """Our exact event-driven solver, through its public functions.

    Records: :func:`isolator.solver.record.simulate_record`; harmonic cases:
    :func:`isolator.solver.harmonic.harmonic_transient` (from rest, the last period sampled).
    """
    if case.kind == "record":
        from isolator.solver.record import simulate_record

        res = simulate_record(case.acceleration_m_s2, case.dt_s, mu_static=case.mu_static,
                              mu_kinetic=case.mu_kinetic, stiffness_per_mass=case.stiffness_per_mass,
                              damping_per_mass=case.damping_per_mass, gravity_m_s2=case.gravity)
        return MethodOutput(res.displacement_m, res.velocity_m_s, res.peak_displacement_m,
                            res.residual_displacement_m, res.slip_time_s / case.window_length, res.n_events)
    from isolator.solver.harmonic import harmonic_transient

    res = harmonic_transient(case.alpha, case.stiffness_per_mass, case.damping_per_mass, case.mu_static,
                             case.mu_kinetic, n_periods=case.n_periods, times=case.output_time, phase=HARMONIC_PHASE)
    return MethodOutput(res.x, res.xdot, res.amplitude, res.residual, res.slip_ratio, res.n_events)

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


@dataclass
class Method:
    """A method of the bench and its settings (steps in s for records, in Eq. 2 time for harmonic cases)."""

    name: str
    function: Callable[[BenchCase, object], MethodOutput]
    settings: list  #: records
    harmonic_settings: list
    setting_name: str  #: "dt", "rtol" or "-"
    quick_settings: list | None = None  #: records, with --quick (default: ``settings``)
    quick_harmonic_settings: list | None = None  #: harmonic cases, with --quick


_STEPS_RECORD = [1e-2, 3e-3, 1e-3, 3e-4, 1e-4]
_STEPS_RECORD_QUICK = [1e-2, 1e-3, 1e-4]
_STEPS_HARMONIC = [1e-1, 1e-2, 1e-3, 1e-4]
_STEPS_HARMONIC_QUICK = [1e-1, 1e-2, 1e-3]
_TOLS = [1e-3, 1e-5, 1e-7, 1e-9]
_TOLS_TANH = [1e-3, 1e-5, 1e-7]
_TOLS_QUICK = [1e-3, 1e-6]


def _method(name, function, settings, harmonic_settings, setting_name, quick, quick_harmonic) -> Method:
    return Method(name, function, settings, harmonic_settings, setting_name, quick, quick_harmonic)


#: The registry: every method of the bench by name, ours first.
METHODS: dict[str, Method] = {m.name: m for m in [
    _method(OURS, exact_solver, [None], [None], "-", [None], [None]),
    _method("implicit Euler fixed step (paper's check)", implicit_fixed_step, _STEPS_RECORD, _STEPS_HARMONIC, "dt",
            _STEPS_RECORD_QUICK, _STEPS_HARMONIC_QUICK),
    _method("Newmark avg. accel. + elastic-plastic friction", newmark_elastic_plastic, _STEPS_RECORD,
            _STEPS_HARMONIC, "dt", _STEPS_RECORD_QUICK, _STEPS_HARMONIC_QUICK),
    _method("solve_ivp RK45 + events", lambda case, tol: ivp_with_events(case, tol, "RK45"), _TOLS, _TOLS, "rtol",
            _TOLS_QUICK, _TOLS_QUICK),
    _method("solve_ivp LSODA + events", lambda case, tol: ivp_with_events(case, tol, "LSODA"), _TOLS, _TOLS,
            "rtol", _TOLS_QUICK, _TOLS_QUICK),
    _method("solve_ivp RK45, tanh friction", lambda case, tol: ivp_tanh(case, tol, "RK45"), _TOLS_TANH, _TOLS_TANH,
            "rtol", _TOLS_QUICK, _TOLS_QUICK),
    _method("solve_ivp LSODA, tanh friction", lambda case, tol: ivp_tanh(case, tol, "LSODA"), _TOLS_TANH,
            _TOLS_TANH, "rtol", _TOLS_QUICK, _TOLS_QUICK),
]}


def methods(quick: bool = False) -> list[Method]:
    """The methods of :data:`METHODS` with the settings of a full or a ``quick`` run, ours first."""
    if not quick:
        return list(METHODS.values())
    return [replace(m, settings=m.quick_settings or m.settings,
                    harmonic_settings=m.quick_harmonic_settings or m.harmonic_settings) for m in METHODS.values()]
