"""Independent high-accuracy reference integrator for the rigid block on a
moving ground with Coulomb friction, a linear spring and a linear dashpot
(M. Nicolas 2017).  Used ONLY by the test-suite to check the closed-form
event-driven solver; it shares no code with ``isolator``.

Model (per unit mass, X = displacement relative to the ground, V = X'):

* sliding, s = sign(V):   X'' = -mu_k g s - kappa X - c V - a_g(t)
* stuck (V = 0):          stays stuck while |kappa X + a_g(t)| <= mu_s g;
                          break-away when |F| > mu_s g, new s = -sign(F),
                          with F = kappa X + a_g(t)
* stop (V -> 0 at t*):    F = kappa X + a_g(t*); sticks if |F| <= mu_s g,
                          otherwise reverses at once with s = -sign(F).

Method: scipy ``solve_ivp`` (DOP853, dense output) integrated phase by phase.
Slip phases end with a terminal event ``s*V = 0`` (direction -1, so only a
crossing from the sliding side triggers; scipy locates the root with brentq
on the dense output to xtol = 4*eps).  Stick phases are not integrated: the
break-away instant is solved in closed form (linear in t inside a sample
interval for a first-order-hold record, arccos for harmonic forcing) and
polished with brentq.  For records, integration is restarted at every sample
boundary so that no step straddles a kink of the forcing.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

__all__ = [
    "reference_record",
    "reference_harmonic",
    "ReferenceError",
    "energy_balance",
    "evaluate_segments",
]

G_STANDARD = 9.80665
MAX_EVENTS_PER_INTERVAL = 200


class ReferenceError(RuntimeError):
    """Raised on stick/slip chatter or integration failure."""


@dataclass
class Segment:
    """One phase of motion on [t0, t1].

    kind == 0: stuck at displacement ``x`` (V = 0).
    kind == +1/-1: sliding in that direction; ``sol`` is the dense output
    (OdeSolution) of y = [X, V]; ``accel`` is the ground acceleration
    function valid on the segment.
    """

    t0: float
    t1: float
    kind: int
    x: float = 0.0
    sol: object = None
    accel: Callable[[np.ndarray], np.ndarray] | None = None

    def state(self, t):
        t = np.asarray(t, dtype=float)
        if self.kind == 0:
            return np.full_like(t, self.x), np.zeros_like(t)
        y = self.sol(t)
        return y[0], y[1]


class _Core:
    """Event-driven phase-by-phase integrator (shared by record/harmonic)."""

    def __init__(self, *, mu_s, mu_k, kappa, c, g, rtol, atol, max_step):
        if mu_k is None:
            mu_k = mu_s
        if mu_s < 0 or mu_k < 0 or mu_k > mu_s * (1 + 1e-15):
            raise ValueError("need 0 <= mu_kinetic <= mu_static")
        if kappa < 0 or c < 0:
            raise ValueError("stiffness and damping must be >= 0")
        self.mu_s, self.mu_k = float(mu_s), float(mu_k)
        self.kappa, self.c, self.g = float(kappa), float(c), float(g)
        self.fs = self.mu_s * self.g  # static friction threshold (per mass)
        self.fk = self.mu_k * self.g  # kinetic friction (per mass)
        self.rtol, self.atol, self.max_step = rtol, atol, max_step
        self.events: list[tuple[float, str]] = []
        self.segments: list[Segment] = []
        self.slip_time = 0.0
        self.peak = 0.0
        # state
        self.t = 0.0
        self.X = 0.0
        self.V = 0.0
        self.mode = 0  # 0 stuck, +1/-1 sliding direction

    # ------------------------------------------------------------------
    def _rhs(self, accel):
        """Right-hand side for the current slip direction.  For a record the
        forcing is linear, a0 + slope*(t - ti) (accel.lin), and the constant
        part is combined with the friction first so that net accelerations
        that are tiny compared with mu g are not lost to cancellation."""
        s = self.mode
        kappa, c = self.kappa, self.c
        lin = getattr(accel, "lin", None)
        if lin is not None:
            a0, slope, ti = lin
            base = -self.fk * s - a0

            def rhs(t, y):
                return np.array([y[1], (base - slope * (t - ti))
                                 - kappa * y[0] - c * y[1]])
        else:
            fk = self.fk

            def rhs(t, y):
                return np.array([y[1], -fk * s - kappa * y[0] - c * y[1] - accel(t)])
        return rhs

    def _slide(self, accel, t_end, fresh):
        """Integrate a slip phase from the current state up to t_end or to
        the first stop.  Returns True if a stop occurred (state at stop)."""
        s = self.mode
        rhs = self._rhs(accel)

        def stop(t, y):
            return s * y[1]

        stop.terminal = True
        stop.direction = -1

        t0 = self.t
        y0 = [self.X, self.V]
        sol = solve_ivp(
            rhs, (t0, t_end), y0, method="DOP853", dense_output=True,
            events=stop, rtol=self.rtol, atol=self.atol, max_step=self.max_step,
        )
        if sol.status < 0:
            raise ReferenceError(f"solve_ivp failed: {sol.message}")
        stopped = sol.status == 1 and len(sol.t_events[0]) > 0
        if stopped:
            t1 = float(sol.t_events[0][0])
            X1 = float(sol.y_events[0][0][0])
            V1 = 0.0
        else:
            t1 = float(sol.t[-1])
            X1 = float(sol.y[0, -1])
            V1 = float(sol.y[1, -1])
        if t1 > t0:
            self.segments.append(Segment(t0, t1, s, sol=sol.sol, accel=accel))
            self.slip_time += t1 - t0
        self.t, self.X, self.V = t1, X1, V1
        self.peak = max(self.peak, abs(X1))
        return stopped

    def _at_stop(self, accel, kind_if_reverse="reverse"):
        """Apply the stop rule at the current time (V = 0).

        Returns the new mode and the event kind (None if the 'stop' was
        spurious, i.e. the force keeps pushing in the same direction)."""
        F = self.kappa * self.X + accel(self.t)
        if abs(F) <= self.fs:
            return 0, "stick"
        new_s = -1 if F > 0 else 1
        if new_s == self.mode:
            return new_s, None
        return new_s, kind_if_reverse

    def run_interval(self, accel, t_end, stick_break):
        """Advance the state from self.t to t_end.

        accel(t): ground acceleration (smooth on the interval).
        stick_break(t0, t1, X): first time in [t0, t1] where
        |kappa X + accel(t)| > mu_s g (strictly after, or at t0 if it already
        exceeds / is leaving the admissible set), else None.
        """
        n_ev = 0
        n_nudge = 0
        t_ivl = self.t
        fresh = False
        while self.t < t_end:
            if n_ev > MAX_EVENTS_PER_INTERVAL:
                raise ReferenceError(
                    f"more than {MAX_EVENTS_PER_INTERVAL} events in interval "
                    f"ending at t={t_end} (stick/slip chatter)")
            if self.mode == 0:
                tb = stick_break(self.t, t_end, self.X)
                if tb is None:
                    self.segments.append(Segment(self.t, t_end, 0, x=self.X))
                    self.t = t_end
                    break
                tb = min(max(tb, self.t), t_end)
                if tb > self.t:
                    self.segments.append(Segment(self.t, tb, 0, x=self.X))
                self.t = tb
                F = self.kappa * self.X + accel(tb)
                self.mode = -1 if F > 0 else 1
                self.V = 0.0
                self.events.append((float(tb), "breakaway"))
                n_ev += 1
                fresh = True
                if tb >= t_end:
                    break
                continue
            # sliding
            if not fresh and self.mode * self.V <= 0.0:
                # velocity already at (or numerically past) zero at an
                # interval start: a stop exactly at the boundary.
                self.V = 0.0
                new_mode, kind = self._at_stop(accel)
                if kind is not None:
                    self.events.append((float(self.t), kind))
                    n_ev += 1
                    self.mode = new_mode
                    fresh = True
                    continue
                fresh = True
            t_start = self.t
            stopped = self._slide(accel, t_end, fresh)
            if not stopped:
                break
            new_mode, kind = self._at_stop(accel)
            spurious = kind is None or (
                fresh and self.t - t_start <= 1e-12 * (t_end - t_ivl))
            if spurious:
                # A zero of s*V right after a start from rest cannot be a
                # genuine stop: at a start the net force points along s
                # (|F| >= mu_s g >= mu_k g, growing outward).  It occurs only
                # when the net acceleration is at rounding level (break-away
                # exactly at threshold with mu_s == mu_k).  Keep sliding in
                # the same direction through a short event-free nudge whose
                # length doubles while the situation persists.
                n_nudge += 1
                if n_nudge > 60:
                    raise ReferenceError(f"cannot leave rest at t={self.t}")
                h = min(t_end - self.t,
                        1e-9 * (t_end - t_ivl) * 2.0 ** (n_nudge - 1))
                self._nudge(accel, self.t + h)
                fresh = True
                continue
            n_nudge = 0
            n_ev += 1
            self.events.append((float(self.t), kind))
            self.mode = new_mode
            self.V = 0.0
            fresh = True

    def _nudge(self, accel, t_end):
        s = self.mode
        rhs = self._rhs(accel)

        t0 = self.t
        sol = solve_ivp(rhs, (t0, t_end), [self.X, self.V], method="DOP853",
                        dense_output=True, rtol=self.rtol, atol=self.atol)
        self.segments.append(Segment(t0, t_end, s, sol=sol.sol, accel=accel))
        self.slip_time += t_end - t0
        self.t, self.X, self.V = t_end, float(sol.y[0, -1]), float(sol.y[1, -1])


# ----------------------------------------------------------------------
def evaluate_segments(segments, t):
    """Displacement and velocity at times ``t`` from a list of segments."""
    t = np.atleast_1d(np.asarray(t, dtype=float))
    x = np.empty_like(t)
    v = np.empty_like(t)
    t1s = np.array([sg.t1 for sg in segments])
    idx = np.searchsorted(t1s, t, side="left")
    idx = np.clip(idx, 0, len(segments) - 1)
    for k in np.unique(idx):
        m = idx == k
        x[m], v[m] = segments[k].state(t[m])
    return x, v


def energy_balance(result, n_gauss=12):
    """Energy terms (per unit mass) integrated from the dense output with
    Gauss-Legendre quadrature on every solver step.

    Returns dict with input_work = -int a_g V dt, kinetic, potential,
    friction = mu_k g int |V| dt, viscous = c int V^2 dt.
    """
    p = result["params"]
    nodes, weights = np.polynomial.legendre.leggauss(n_gauss)
    w_in = fric = visc = 0.0
    for sg in result["segments"]:
        if sg.kind == 0 or sg.t1 <= sg.t0:
            continue
        ts = np.asarray(sg.sol.ts)
        ts = ts[(ts > sg.t0) & (ts < sg.t1)]
        edges = np.concatenate(([sg.t0], ts, [sg.t1]))
        a, b = edges[:-1], edges[1:]
        half = 0.5 * (b - a)
        tq = (0.5 * (a + b))[:, None] + half[:, None] * nodes[None, :]
        wq = half[:, None] * weights[None, :]
        tq, wq = tq.ravel(), wq.ravel()
        y = sg.sol(tq)
        V = y[1]
        ag = np.asarray(sg.accel(tq), dtype=float)
        w_in += -np.sum(wq * ag * V)
        fric += np.sum(wq * np.abs(V))
        visc += np.sum(wq * V * V)
    return {
        "input_work": w_in,
        "kinetic": 0.5 * result["_final_V"] ** 2,
        "potential": 0.5 * p["kappa"] * result["_final_X"] ** 2,
        "friction": p["mu_k"] * p["g"] * fric,
        "viscous": p["c"] * visc,
    }


# ----------------------------------------------------------------------
def reference_record(acceleration_m_s2, dt_s, *, mu_static, mu_kinetic=None,
                     stiffness_per_mass=0.0, damping_per_mass=0.0,
                     gravity_m_s2=G_STANDARD, rtol=1e-12, atol=1e-13, time_s=None,
                     max_step_s=np.inf):
    """Reference response to a sampled ground-acceleration record
    (first-order hold between samples).  ``time_s`` (then ``dt_s`` is ignored)
    gives sample times that need not be evenly spaced; ``max_step_s`` caps the
    integrator's step (a long step can hide a velocity zero and its return).

    Returns dict with keys time_s, displacement_m, velocity_m_s, events
    [(time_s, kind)], slip_time_s, peak_displacement_m,
    residual_displacement_m (plus 'segments', 'params' for diagnostics).
    """
    a = np.asarray(acceleration_m_s2, dtype=float).ravel()
    if a.size < 1:
        raise ValueError("empty record")
    if not np.all(np.isfinite(a)):
        raise ValueError("non-finite acceleration")
    n = a.size
    if time_s is None:
        dt = float(dt_s)
        if not dt > 0:
            raise ValueError("dt must be > 0")
        times = np.arange(n) * dt
    else:
        times = np.asarray(time_s, dtype=float) - float(time_s[0])
        if times.shape != a.shape or np.any(np.diff(times) <= 0):
            raise ValueError("time_s must increase and match the acceleration")
    core = _Core(mu_s=mu_static, mu_k=mu_kinetic, kappa=stiffness_per_mass,
                 c=damping_per_mass, g=gravity_m_s2, rtol=rtol, atol=atol,
                 max_step=max_step_s)
    fs = core.fs
    kappa = core.kappa
    X = np.zeros(n)
    V = np.zeros(n)

    # break-away check at t = 0 (state X = 0, stuck)
    if n == 1:
        if abs(a[0]) > fs:
            core.events.append((0.0, "breakaway"))
    for i in range(n - 1):
        ti, ti1 = times[i], times[i + 1]
        a0, a1 = a[i], a[i + 1]
        slope = (a1 - a0) / (ti1 - ti)

        def accel(t, ti=ti, a0=a0, slope=slope):
            return a0 + slope * (t - ti)

        accel.lin = (a0, slope, ti)

        def stick_break(t0, t1, Xs, ti=ti, a0=a0, slope=slope):
            # F(t) = kappa*Xs + a0 + slope*(t - ti), linear in t
            F0 = kappa * Xs + a0 + slope * (t0 - ti)
            if abs(F0) > fs:
                return t0  # already beyond the threshold
            cands = []
            if slope > 0:
                cands.append((fs - F0) / slope)
            elif slope < 0:
                cands.append((-fs - F0) / slope)
            best = None
            for tau in cands:
                tau = max(tau, 0.0)
                tb = t0 + tau
                if tb <= t1:
                    # exact root of F = +/- fs; is it strictly exceeded right
                    # after?  (slope is nonzero and outward by construction)
                    best = tb if best is None else min(best, tb)
            if best is not None and best >= t1:
                # reaching the threshold exactly at the interval end: the
                # next interval decides whether it is exceeded.
                return None
            return best

        core.run_interval(accel, ti1, stick_break)
        core.t = ti1  # exact sample time
        X[i + 1] = core.X
        V[i + 1] = core.V if core.mode != 0 else 0.0
        core.peak = max(core.peak, abs(core.X))

    return {
        "time_s": times,
        "displacement_m": X,
        "velocity_m_s": V,
        "events": list(core.events),
        "slip_time_s": core.slip_time,
        "peak_displacement_m": core.peak,
        "residual_displacement_m": float(X[-1]),
        "segments": core.segments,
        "params": {"mu_s": core.mu_s, "mu_k": core.mu_k, "kappa": core.kappa,
                   "c": core.c, "g": core.g},
        "_final_X": float(X[-1]),
        "_final_V": float(V[-1]),
    }


def reference_harmonic(alpha, k, eta, mu_s, mu_k=None, *, t_end, t_out=None,
                       phi=math.pi / 2, rtol=1e-12, atol=1e-13):
    """Reference solution of the paper's dimensionless Eq. (2):
    x'' + mu(x') sign(x') + k x + eta x' + w^2 cos(w t + phi) = 0,
    w = sqrt(alpha mu_s), stick while |k x + w^2 cos(w t + phi)| <= mu_s.

    Returns dict with t, x, xdot (at t_out; default 2001 points on
    [0, t_end]), events [(t, kind)], slip_time, plus 'segments'/'params'.
    """
    if mu_k is None:
        mu_k = mu_s
    w = math.sqrt(alpha * mu_s)
    w2 = w * w
    if t_out is None:
        t_out = np.linspace(0.0, t_end, 2001)
    t_out = np.asarray(t_out, dtype=float)
    period = 2 * math.pi / w if w > 0 else np.inf
    core = _Core(mu_s=mu_s, mu_k=mu_k, kappa=k, c=eta, g=1.0, rtol=rtol,
                 atol=atol, max_step=period / 64)
    fs = core.fs

    def accel(t):
        return w2 * np.cos(w * t + phi)

    def F(t, xs):
        return k * xs + w2 * math.cos(w * t + phi)

    def stick_break(t0, t1, xs):
        if w2 == 0.0:
            return t0 if abs(k * xs) > fs else None
        C = k * xs
        F0 = F(t0, xs)
        dF0 = -w2 * w * math.sin(w * t0 + phi)
        if F0 > fs or F0 < -fs:
            return t0
        if (F0 >= fs and dF0 > 0) or (F0 <= -fs and dF0 < 0):
            return t0
        th0 = w * t0 + phi
        cands = []
        # cos(th) > c1  <=>  th mod 2pi in (-b1, b1); entry at -b1
        c1 = (fs - C) / w2
        if c1 < 1.0:
            b1 = math.acos(max(c1, -1.0))
            # smallest entry point >= th0 (a rounding-level tolerance keeps
            # an entry that coincides with th0 instead of skipping a period)
            th = -b1 + 2 * math.pi * math.ceil((th0 + b1) / (2 * math.pi) - 1e-12)
            cands.append((th, +1))
        # cos(th) < c2  <=>  th mod 2pi in (b2, 2pi - b2); entry at b2
        c2 = (-fs - C) / w2
        if c2 > -1.0:
            b2 = math.acos(min(c2, 1.0))
            th = b2 + 2 * math.pi * math.ceil((th0 - b2) / (2 * math.pi) - 1e-12)
            cands.append((th, -1))
        if not cands:
            return None
        th, sgn = min(cands)
        tb = (th - phi) / w
        # polish with brentq on g(t) = sgn*F - fs on a small bracket
        h = 1e-6 * period
        lo, hi = max(t0, tb - h), tb + h
        gfun = lambda t: sgn * F(t, xs) - fs  # noqa: E731
        try:
            if gfun(lo) < 0 < gfun(hi):
                tb = brentq(gfun, lo, hi, xtol=1e-15, rtol=4 * np.finfo(float).eps)
        except ValueError:
            pass
        if tb > t1:
            return None
        return max(tb, t0)

    core.run_interval(accel, float(t_end), stick_break)
    x, v = evaluate_segments(core.segments, t_out)
    fX, fV = evaluate_segments(core.segments, [t_end])
    return {
        "t": t_out,
        "x": x,
        "xdot": v,
        "events": list(core.events),
        "slip_time": core.slip_time,
        "segments": core.segments,
        "params": {"mu_s": core.mu_s, "mu_k": core.mu_k, "kappa": core.kappa,
                   "c": core.c, "g": 1.0},
        "_final_X": float(fX[0]),
        "_final_V": float(fV[0]),
    }

