"""Independent reference for the planar (2-D) friction block: the truth of the bench's 2-D cases.

The tests import it too (``tests/planar_reference.py``); it shares no code with the rest of
``isolator``.  Its own error, measured
against the exact 1-D kernel on a collinear record, is ~1e-14 of the peak
(docs/planar.md).

Model (per unit mass, X relative to the ground):

* sliding:  X'' = -mu(|V|) n(t) V/|V| - kappa(t) X - c V - a_g(t),  n = g + a_z,
  kappa = n/R (pendulum) or K/M;  no friction and (pendulum) no kappa where n <= 0;
* stuck:    V = 0 while |kappa X + a_g| <= mu_s n;
* stop:     stick if that holds, otherwise restart from rest along -(kappa X + a_g).

Method: scipy ``solve_ivp`` restarted at every sample (no step straddles a kink),
in Cartesian form (X, V) only:

* fast sliding (|V| >= ``v_switch``): DOP853 at rtol 1e-12 with a terminal event at
  |V| = v_switch (falling) and non-terminal events X.V = 0 / V.A = 0 for the peaks;
* slow sliding (|V| < v_switch, where V/|V| makes the equations stiff): Radau
  (implicit, L-stable) at rtol 1e-12 with terminal events |V| = v_switch (rising) and
  |V| = v_eps (falling: the stop; the last v_eps is finished at constant deceleration,
  an error ~ v_eps^2 / (2 |d|V|/dt|) in X);
* a start from rest begins at |V| = v_eps along the net force, reached after the time
  that the net force |F| - mu n (frozen X, linear in time) needs to give that speed;
* break-away: the first sign change of |kappa X + a_g|^2 - (mu_s n)^2 on a 65-point
  grid of the stuck stretch, polished by brentq.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

G = 9.80665


@dataclass
class PlanarReference:
    time_s: np.ndarray
    displacement_m: np.ndarray
    velocity_m_s: np.ndarray
    peak_displacement_m: float
    peak_velocity_m_s: float
    n_stops: int
    n_breakaways: int
    events: list = field(default_factory=list)

    @property
    def residual_displacement_m(self) -> float:
        return float(np.hypot(*self.displacement_m[-1]))


def reference_pair(t, ax, ay, az=None, *, mu_s, mu_k=None, kappa=0.0, radius=None, c=0.0, g=G,
                   mu_slow=None, mu_fast=None, rate=None, rtol=1e-12, v_eps=1e-11, v_switch=1e-3):
    t = np.asarray(t, float)
    ax = np.asarray(ax, float)
    ay = np.asarray(ay, float)
    nz = g + (np.zeros_like(ax) if az is None else np.asarray(az, float))
    mu_k = mu_s if mu_k is None else mu_k

    def mu(r):
        if mu_slow is None:
            return mu_k
        return mu_fast - (mu_fast - mu_slow) * math.exp(-rate * r)

    def start_from_rest(tb, x0, kap, acc, normal, t_end):
        # the first v_eps of speed along the net force F: r' = |F| - mu(0) n =: p + q s
        # (X frozen), solved for the time s at which r = v_eps; X moves by the integral of r
        def excess(s):
            force = -(kap(s) * x0 + acc(s))
            return np.linalg.norm(force) - mu(0.0) * normal(s)
        delta = 1e-7 * (t_end - tb) if t_end > tb else 1e-9
        p = max(excess(tb), 0.0)
        q = (excess(tb + delta) - excess(tb)) / delta
        if q > 0.0:
            s = 2.0 * v_eps / (p + math.sqrt(p * p + 2.0 * q * v_eps))
        else:
            s = v_eps / p
        s = min(s, max(t_end - tb, 0.0))
        force = -(kap(tb) * x0 + acc(tb))
        direction = force / np.linalg.norm(force)
        return x0 + direction * (0.5 * p * s * s + q * s ** 3 / 6.0), v_eps * direction, tb + s

    X = np.zeros(2)
    V = np.zeros(2)
    stuck = True
    slow_form = None  # slow (Radau) or fast (DOP853) form of the sliding equations
    peak_x = 0.0
    peak_v = 0.0
    n_stops = 0
    n_break = 0
    events = []
    out_x = np.zeros((t.size, 2))
    out_v = np.zeros((t.size, 2))
    atol = 1e-16

    for i in range(t.size - 1):
        t0, t1 = t[i], t[i + 1]
        h = t1 - t0
        sx = (ax[i + 1] - ax[i]) / h
        sy = (ay[i + 1] - ay[i]) / h
        sn = (nz[i + 1] - nz[i]) / h

        def acc(tt, i=i, t0=t0, sx=sx, sy=sy):
            return np.array([ax[i] + sx * (tt - t0), ay[i] + sy * (tt - t0)])

        def normal(tt, i=i, t0=t0, sn=sn):
            return nz[i] + sn * (tt - t0)

        # split the interval where n changes sign (contact / flight)
        cuts = [t0]
        if nz[i] * nz[i + 1] < 0.0:
            cuts.append(t0 + nz[i] / (nz[i] - nz[i + 1]) * h)
        cuts.append(t1)
        for a, b in zip(cuts[:-1], cuts[1:], strict=False):
            contact = normal(0.5 * (a + b)) > 0.0

            def kap(tt, contact=contact):
                if radius is None:
                    return kappa
                return normal(tt) / radius if contact else 0.0

            def rhs(tt, y, contact=contact):
                x, v = y[:2], y[2:]
                r = math.hypot(v[0], v[1])
                fr = mu(r) * normal(tt) if (contact and r > 0.0) else 0.0
                e = v / r if r > 0.0 else np.zeros(2)
                return np.concatenate([v, -fr * e - kap(tt) * x - c * v - acc(tt)])

            tt = a
            if not contact and stuck:
                stuck = False  # lift-off: free flight from rest
            guard = 0
            while tt < b:
                guard += 1
                if guard > 2000:
                    raise RuntimeError(f"reference: too many phases in interval {i}")
                if stuck:
                    def q(s, X=X):
                        gv = kap(s) * X + acc(s)
                        return gv @ gv - (mu_s * normal(s)) ** 2
                    grid = np.linspace(tt, b, 65)
                    vals = np.array([q(s) for s in grid])
                    if vals[0] > 0.0:
                        tb = tt
                    else:
                        pos = np.nonzero(vals > 0.0)[0]
                        if pos.size == 0:
                            tt = b
                            break
                        j = pos[0]
                        tb = brentq(q, grid[j - 1], grid[j], xtol=1e-15, rtol=1e-15)
                    X, V, tb = start_from_rest(tb, X, kap, acc, normal, b)
                    stuck = False
                    slow_form = True
                    n_break += 1
                    events.append((tb, "breakaway"))
                    tt = tb
                    continue
                if slow_form is None:
                    slow_form = math.hypot(*V) < v_switch
                slow = contact and slow_form
                y0 = np.concatenate([X, V])
                evs = []
                if contact:
                    def ev_switch(s, y):
                        return math.hypot(y[2], y[3]) - v_switch
                    ev_switch.terminal = True
                    ev_switch.direction = 1.0 if slow else -1.0
                    evs.append(ev_switch)
                    if slow:
                        def ev_stop(s, y):
                            return math.hypot(y[2], y[3]) - v_eps
                        ev_stop.terminal = True
                        ev_stop.direction = -1.0
                        evs.append(ev_stop)

                def ev_peak_x(s, y):
                    return y[0] * y[2] + y[1] * y[3]
                ev_peak_x.direction = -1.0

                def ev_peak_v(s, y):
                    return y[2:] @ rhs(s, y)[2:]
                ev_peak_v.direction = -1.0
                evs += [ev_peak_x, ev_peak_v]
                sol = solve_ivp(rhs, (tt, b), y0, method="Radau" if slow else "DOP853", rtol=rtol,
                                atol=atol, events=evs, dense_output=False)
                if sol.status < 0:
                    raise RuntimeError(f"reference: solve_ivp failed: {sol.message}")
                for yv in sol.y.T:
                    peak_x = max(peak_x, math.hypot(yv[0], yv[1]))
                    peak_v = max(peak_v, math.hypot(yv[2], yv[3]))
                for ye in sol.y_events[-2]:
                    peak_x = max(peak_x, math.hypot(ye[0], ye[1]))
                for ye in sol.y_events[-1]:
                    peak_v = max(peak_v, math.hypot(ye[2], ye[3]))
                yend = sol.y[:, -1]
                X, V = yend[:2].copy(), yend[2:].copy()
                tt = sol.t[-1]
                if sol.status == 1 and contact and slow and len(sol.t_events[1]):
                    # the stop: finish the last v_eps at constant deceleration
                    r = math.hypot(*V)
                    rdot = V @ rhs(tt, yend)[2:] / r
                    dt = min(r / max(-rdot, 1e-300), b - tt)
                    X = X + 0.5 * dt * V
                    tt = tt + dt
                    V = np.zeros(2)
                    peak_x = max(peak_x, math.hypot(*X))
                    n_stops += 1
                    force = -(kap(tt) * X + acc(tt))
                    if np.linalg.norm(force) <= mu_s * normal(tt):
                        stuck = True
                        events.append((tt, "stick"))
                    else:
                        X, V, tt = start_from_rest(tt, X, kap, acc, normal, b)
                        slow_form = True
                        events.append((tt, "reversal"))
                elif sol.status == 1:
                    tt = sol.t[-1]  # switched between slow and fast form
                    slow_form = not slow_form
                else:
                    tt = b
            if contact is False and b < t1:
                # landing: from rest it is a stick test
                if not np.any(V):
                    stuck = True
        out_x[i + 1] = X
        out_v[i + 1] = 0.0 if stuck else V
    return PlanarReference(time_s=t, displacement_m=out_x, velocity_m_s=out_v, peak_displacement_m=peak_x,
                           peak_velocity_m_s=peak_v, n_stops=n_stops, n_breakaways=n_break, events=events)
