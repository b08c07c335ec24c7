"""2d-multisurface+mu(v) on real pairs against an independent reference of the equations (issue 23).

The reference is written from the model's equations alone (docs/multisurface.md, "Velocity-dependent friction"
and "Velocity-dependent friction in the plane"): massless sliders, one force r = F/W ∈ ℝ² through every surface,
back-forces b = diag(1/R̄) T⁻¹ u on each component, a sliding surface slips at u̇_k = φ_k(|r − b_k|) (r − b_k)/|r − b_k|
(φ_k the inverse of µ_k(v) = µ_fast − (µ_fast − µ_slow) e^(−a v)), a stuck one has |r − b_k| ≤ µ_slow,k, Σ u̇_k = Ẋ,
Ẍ = −g r − c Ẋ − a_g.  It shares nothing with the kernels but the bearing's matrices (``Bearing.elements``,
``Bearing.surface_matrix``): scipy's ``solve_ivp`` (Radau, rtol 1e-12, analytic Jacobian) on y = (Ẋ, u_1..u_n,
E_in, E_friction, E_viscous), the force per evaluation by a damped 2-D Newton on the inverse laws Σ_S Φ_k(r − b_k) = Ẋ
(the most saturated sliding surface's slip taken as the rest of Ẋ, the 1-D reference's device), the mode changes
(a surface starting, |r − b_k| rising to µ_slow,k; stopping, falling to it; the mass stopping, |Ẋ| falling to
``v_stop``) as solve_ivp's terminal events, interval by interval of the piecewise-linear record; at rest the exit of
−a_g/g from the intersection of the static discs in closed form (a quadratic per disc), the start from the nearest
point of that intersection with |Ẋ| = ``v_seed`` along the push.  Its own error is measured by its two tolerances
(rtol 1e-12 against 1e-11: 1.1e-13 of the peak; ``v_stop``/``v_seed`` 1e-10/1e-12 against 1e-9/1e-11: ≈ 2e-10 of the
peak on a window with six stops, nothing without stops): docs/multisurface.md, h152.

Not handled (the reference refuses, so a window must avoid them): a rim reached, two sliding surfaces both past
a·|u̇| = ``SATURATION_GUARD`` (the corner of two saturated circles: the inverse laws are not resolvable there).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import minimize

from isolator.bearing import parse_bearing
from isolator.errors import DesignError
from isolator.motion import read_ground_motion
from isolator.solver.planar_multisurface_rate import simulate_bearing_pair_rate

G = 9.80665
GEOMETRY = [(2.1, 0.4), (0.3, 0.05), (0.3, 0.05), (2.1, 0.4)]  # Fenz & Constantinou's TFP (R [m], d [m])
MU_SLOW = [0.03, 0.01, 0.01, 0.05]
MU_FAST = [0.06, 0.02, 0.02, 0.10]
SATURATION_GUARD = 20.0  # a·|u̇| of the second most saturated sliding surface the reference accepts


class OutsideReference(Exception):
    """The motion left the reference's domain (a rim, two saturated surfaces)."""


def rate_bearing(kind, geometry, mu_slow, mu_fast, rate):
    return parse_bearing({"type": kind, "surface": [
        {"radius_m": r, "mu_slow": s, "mu_fast": f, "rate_s_per_m": rate, "displacement_capacity_m": d}
        for (r, d), s, f in zip(geometry, mu_slow, mu_fast, strict=True)]}, DesignError)


class PlanarRateReference:
    """The µ(v) series model in the plane integrated by scipy (Radau), events by solve_ivp."""

    def __init__(self, bearing, c=0.0, g=G, rtol=1e-12, v_stop=1e-10, v_seed=1e-12):
        rbar, _, _ = bearing.elements()
        smat = np.linalg.inv(bearing.surface_matrix())
        self.rbar = rbar
        self.smat = smat
        self.bmat = smat / rbar[:, None]
        self.B = self.bmat.tolist()
        self.n = len(bearing.surfaces)
        self.ms = [s.mu_slow for s in bearing.surfaces]
        self.mf = [s.mu_fast for s in bearing.surfaces]
        self.a = [s.rate_s_per_m for s in bearing.surfaces]
        self.cap = [float(d) for d in bearing.effective_capacities_m]
        self.c, self.g = float(c), float(g)
        self.rtol, self.v_stop, self.v_seed = rtol, v_stop, v_seed
        self.memo = (None, None)
        self.warm = {}
        self.h = 1e-4
        self.max_second_saturation = 0.0
        self.n_stage_failures = 0
        self.n_fallback = 0
        self.recent = []
        self.modes = set()
        self.n_events = {"start": 0, "stop": 0, "mass stop": 0, "start from rest": 0}

    # ---- the laws ----
    def phi(self, k, s):
        """Slip speed of surface k at friction |r − b_k| = s (continued below µ_slow: negative)."""
        return -math.log1p(-(s - self.ms[k]) / (self.mf[k] - self.ms[k])) / self.a[k]

    def mu(self, k, v):
        return self.mf[k] - (self.mf[k] - self.ms[k]) * math.exp(-self.a[k] * v)

    def back(self, u):
        """b_k = Σ_q B_kq u_q on each component; u a flat sequence (u_1x, u_1y, …); a list of (x, y)."""
        return (self.bmat @ np.asarray(u, dtype=float).reshape(self.n, 2)).tolist()

    def _residual(self, r, V, b, S):
        """(Ψ(r), F(r) = ∇Ψ, its Jacobian (2 × 2, symmetric)) of Ψ(r) = Σ_S Ψ_k(|r − b_k|) − V·r, Ψ_k' = φ_k;
        None outside the domain |r − b_k| < µ_fast,k.  Ψ_k(s) = (Δ/a)(z ln z − z + 1), z = (µ_fast − s)/Δ."""
        fx = -V[0]
        fy = -V[1]
        psi = -(V[0] * r[0] + V[1] * r[1])
        jxx = jxy = jyy = 0.0
        for k in S:
            dx, dy = r[0] - b[k][0], r[1] - b[k][1]
            s = math.hypot(dx, dy)
            if not 0.0 < s < self.mf[k]:
                return None
            delta = self.mf[k] - self.ms[k]
            z = (self.mf[k] - s) / delta
            p = -math.log(z) / self.a[k]
            psi += delta / self.a[k] * (z * math.log(z) - z + 1.0)
            ex, ey = dx / s, dy / s
            fx += p * ex
            fy += p * ey
            dp = 1.0 / (self.a[k] * (self.mf[k] - s))
            t = max(p / s, 0.0)  # below µ_slow (a stop's continuation) the tangential term is left out
            jxx += dp * ex * ex + t * (1.0 - ex * ex)
            jxy += (dp - t) * ex * ey
            jyy += dp * ey * ey + t * (1.0 - ey * ey)
        return psi, fx, fy, jxx, jxy, jyy

    def _feasible(self, b, S):
        """A point inside every disc |r − b_k| < µ_fast,k of S (alternating projections on shrunk discs)."""
        for shrink in (0.5, 0.9, 0.999):
            r = (sum(b[k][0] for k in S) / len(S), sum(b[k][1] for k in S) / len(S))
            for _ in range(200):
                worst, kk = max((math.hypot(r[0] - b[k][0], r[1] - b[k][1]) / (self.ms[k] + shrink * (
                    self.mf[k] - self.ms[k])), k) for k in S)
                if worst <= 1.0:
                    return r
                rad = self.ms[kk] + shrink * (self.mf[kk] - self.ms[kk])
                r = (b[kk][0] + (r[0] - b[kk][0]) / worst * (1 - 1e-12) * rad / rad,
                     b[kk][1] + (r[1] - b[kk][1]) / worst * (1 - 1e-12) * rad / rad)
        return None

    def _newton(self, r, V, b, S):
        """Damped Newton on ∇Ψ = 0 (Ψ convex where the surfaces slide): a trial is kept when Ψ or |∇Ψ| falls."""
        out = self._residual(r, V, b, S)
        if out is None:
            return None
        for _ in range(200):
            psi, fx, fy, jxx, jxy, jyy = out
            det = jxx * jyy - jxy * jxy
            if not (det > 0.0 and math.isfinite(det)):
                return None
            dx = -(jyy * fx - jxy * fy) / det
            dy = -(jxx * fy - jxy * fx) / det
            norm = math.hypot(fx, fy)
            step = math.hypot(dx, dy)
            if step <= 1e-11 * (1.0 + math.hypot(*r)):  # quadratic convergence: what is left is ~ step²
                trial = (r[0] + dx, r[1] + dy)
                return trial if self._residual(trial, V, b, S) is not None else r
            lam = 1.0
            for _ in range(80):
                trial = (r[0] + lam * dx, r[1] + lam * dy)
                new = self._residual(trial, V, b, S)
                if new is not None and (new[0] < psi or math.hypot(new[1], new[2]) < norm):
                    break
                lam *= 0.5
            else:
                # no decrease: at the rounding of r (a Newton step of a few ulp) that is the root
                return r if step <= 1e-14 * (1.0 + math.hypot(*r)) else None
            r, out = trial, new
            if lam == 1.0 and step <= 4e-16 * (1.0 + math.hypot(*r)):
                return r
            if math.hypot(new[1], new[2]) == 0.0:
                return r
        return None

    def _fallback(self, starts, V, b, S):
        """Fallback: Nelder–Mead on the convex Ψ (+inf off the domain) from each start, polished by Newton."""
        def psi(r):
            out = self._residual((r[0], r[1]), V, b, S)
            return math.inf if out is None else out[0]

        for r0 in starts:
            if r0 is None or not math.isfinite(psi(r0)):
                continue
            sol = minimize(psi, list(r0), method="Nelder-Mead",
                           options={"xatol": 1e-14, "fatol": 1e-22, "maxiter": 4000, "maxfev": 8000,
                                    "initial_simplex": [list(r0), [r0[0] + 1e-3, r0[1]], [r0[0], r0[1] + 1e-3]]})
            r = self._newton((float(sol.x[0]), float(sol.x[1])), V, b, S)
            if r is not None:
                self.n_fallback += 1
                return r
        raise OutsideReference(f"no force found: V {V}, mode {S}")

    def force(self, V, u, S):
        """(r, slips [(x, y)] per surface, f = r − b per surface) in mode S (the sliding surfaces)."""
        key = (tuple(V), tuple(u), S)
        if self.memo[0] == key:
            return self.memo[1]
        b = self.back(u)
        if S:
            starts = self.recent[::-1]  # the last roots: r is continuous in time, across events too
            if S in self.warm:
                starts.append(self.warm[S])
            speed = math.hypot(*V)
            if speed > 0.0:
                ex, ey = V[0] / speed, V[1] / speed
                for k in S:
                    m = self.mu(k, speed / len(S))
                    starts.append((b[k][0] + m * ex, b[k][1] + m * ey))
                m = [self.mu(k, speed / len(S)) for k in S]
                starts.append((sum(b[k][0] for k in S) / len(S) + sum(m) / len(S) * ex,
                               sum(b[k][1] for k in S) / len(S) + sum(m) / len(S) * ey))
            starts.append(self._feasible(b, S))
            for r0 in starts:
                r = None if r0 is None else self._newton(r0, V, b, S)
                if r is not None:
                    break
            else:
                r = self._fallback(starts, V, b, S)
            self.warm[S] = r
            self.recent = (self.recent + [r])[-6:]
        else:
            r = (0.0, 0.0)
        f = [(r[0] - b[k][0], r[1] - b[k][1]) for k in range(self.n)]
        slips = [(0.0, 0.0)] * self.n
        gaps = []
        for k in S:
            s = math.hypot(*f[k])
            p = self.phi(k, s)
            slips[k] = (p * f[k][0] / s, p * f[k][1] / s)
            gaps.append(((self.mf[k] - s) / (self.mf[k] - self.ms[k]), k))
        if len(S) > 1:  # the most saturated surface: the rest of Ẋ (its inverse law is the least resolvable)
            gaps.sort()
            kk = gaps[0][1]
            sx = V[0] - sum(slips[j][0] for j in S if j != kk)
            sy = V[1] - sum(slips[j][1] for j in S if j != kk)
            slips[kk] = (sx, sy)
            second = -math.log(gaps[1][0])  # a·|u̇| of the second most saturated surface
            if second > SATURATION_GUARD:
                raise OutsideReference(f"two surfaces saturated together (a·|u̇| {second:.1f} on the second)")
            self.max_second_saturation = max(self.max_second_saturation, second)
        out = (r, slips, f)
        self.memo = (key, out)
        return out

    # ---- the ODE ----
    def rhs(self, t, y, S, a0, slope):
        n = self.n
        V = (y[0], y[1])
        u = tuple(y[2:2 + 2 * n])
        try:
            r, slips, f = self.force(V, u, S)
        except OutsideReference:  # a collocation iterate off the domain: NaN makes Radau's Newton fail, h halves
            self.n_stage_failures += 1
            return np.full(2 + 2 * n + 3, np.nan)
        agx = a0[0] + slope[0] * t
        agy = a0[1] + slope[1] * t
        dy = np.empty(2 + 2 * n + 3)
        dy[0] = -self.g * r[0] - self.c * V[0] - agx
        dy[1] = -self.g * r[1] - self.c * V[1] - agy
        for k in range(n):
            dy[2 + 2 * k] = slips[k][0]
            dy[3 + 2 * k] = slips[k][1]
        elements = self.smat @ np.asarray(slips)  # ū̇ = T⁻¹ u̇: friction power g Σ_i (r − b_i)·ū̇_i
        fr = np.asarray(f)
        power = float(np.sum(fr * elements))
        dy[2 + 2 * n] = -(agx * V[0] + agy * V[1])
        dy[3 + 2 * n] = self.g * power
        dy[4 + 2 * n] = self.c * (V[0] ** 2 + V[1] ** 2)
        return dy

    def jac(self, t, y, S, a0, slope):
        """∂ẏ/∂y by the implicit-function theorem on Σ_S Φ_k(r − b_k) = Ẋ (energy rows but the input's: 0)."""
        n = self.n
        m = 2 + 2 * n + 3
        J = np.zeros((m, m))
        V = (y[0], y[1])
        u = tuple(y[2:2 + 2 * n])
        try:
            r, slips, f = self.force(V, u, S)
        except OutsideReference:
            return np.full((m, m), np.nan)
        J[0, 0] = J[1, 1] = -self.c
        J[2 + 2 * n, 0] = -(a0[0] + slope[0] * t)
        J[2 + 2 * n, 1] = -(a0[1] + slope[1] * t)
        if not S:
            return J
        D = {}
        for k in S:
            s = math.hypot(*f[k])
            e = np.array(f[k]) / s
            p = self.phi(k, s)
            dp = 1.0 / (self.a[k] * (self.mf[k] - s))
            D[k] = dp * np.outer(e, e) + (p / s) * (np.eye(2) - np.outer(e, e))
        M = sum(D.values())
        Minv = np.linalg.inv(M)
        dr = np.zeros((2, 2 + 2 * n))  # ∂r/∂(V, u)
        dr[:, 0:2] = Minv
        for q in range(n):
            acc = sum(self.B[k][q] * D[k] for k in S)
            dr[:, 2 + 2 * q:4 + 2 * q] = Minv @ acc
        J[0:2, 0:2 + 2 * n] += -self.g * dr
        rows = {}
        for k in S:
            db = np.zeros((2, 2 + 2 * n))
            for q in range(n):
                db[:, 2 + 2 * q:4 + 2 * q] = self.B[k][q] * np.eye(2)
            rows[k] = D[k] @ (dr - db)
        if len(S) > 1:
            kk = min(S, key=lambda k: (self.mf[k] - math.hypot(*f[k])) / (self.mf[k] - self.ms[k]))
            rest = np.zeros((2, 2 + 2 * n))
            rest[:, 0:2] = np.eye(2)
            rows[kk] = rest - sum(rows[j] for j in S if j != kk)
        for k in S:
            J[2 + 2 * k:4 + 2 * k, 0:2 + 2 * n] = rows[k]
        return J

    # ---- rest ----
    def discs(self, u):
        return self.back(u)

    def inside_all(self, p, b, slack=0.0):
        return all(math.hypot(p[0] - b[k][0], p[1] - b[k][1]) <= self.ms[k] + slack for k in range(self.n))

    def exit_time(self, p0, p1, b, t_from, t_to):
        """First τ in (t_from, t_to] where p0 + p1 τ leaves a static disc (it is inside all at t_from), or None."""
        best = None
        for k in range(self.n):
            qx, qy = p0[0] - b[k][0], p0[1] - b[k][1]
            A = p1[0] ** 2 + p1[1] ** 2
            Bq = 2.0 * (qx * p1[0] + qy * p1[1])
            C = qx * qx + qy * qy - self.ms[k] ** 2
            if A == 0.0:
                continue
            disc = Bq * Bq - 4.0 * A * C
            if disc < 0.0:
                continue
            root = math.sqrt(disc)
            # the larger root (leaving), in a stable form
            tau = (-Bq + root) / (2.0 * A) if Bq <= 0.0 else (2.0 * C) / (-Bq - root)
            if tau > t_from and tau <= t_to and (best is None or tau < best):
                best = tau
        return best

    def projection(self, p, b):
        """The nearest point of the intersection of the static discs to p (outside it) and the discs on it."""
        cands = []
        for k in range(self.n):
            dx, dy = p[0] - b[k][0], p[1] - b[k][1]
            s = math.hypot(dx, dy)
            if s > 0.0:
                q = (b[k][0] + self.ms[k] * dx / s, b[k][1] + self.ms[k] * dy / s)
                if self.inside_all(q, b, 1e-14):
                    cands.append(q)
            for j in range(k + 1, self.n):
                cx, cy = b[j][0] - b[k][0], b[j][1] - b[k][1]
                d = math.hypot(cx, cy)
                if d == 0.0 or d > self.ms[k] + self.ms[j] or d < abs(self.ms[k] - self.ms[j]):
                    continue
                along = (self.ms[k] ** 2 - self.ms[j] ** 2 + d * d) / (2.0 * d)
                h = math.sqrt(max(self.ms[k] ** 2 - along * along, 0.0))
                for sgn in (1.0, -1.0):
                    q = (b[k][0] + (along * cx - sgn * h * cy) / d, b[k][1] + (along * cy + sgn * h * cx) / d)
                    if self.inside_all(q, b, 1e-14):
                        cands.append(q)
        q = min(cands, key=lambda c: math.hypot(p[0] - c[0], p[1] - c[1]))
        S = tuple(k for k in range(self.n) if math.hypot(q[0] - b[k][0], q[1] - b[k][1]) >= self.ms[k] - 1e-13)
        return q, S

    def start_from_rest(self, y, p):
        """Mode and seeded velocity of a start from rest with the push p = −a_g/g outside the static discs."""
        u = tuple(y[2:2 + 2 * self.n])
        b = self.back(u)
        q, S = self.projection(p, b)
        dx, dy = p[0] - q[0], p[1] - q[1]
        d = math.hypot(dx, dy)
        if d <= 1e-14:  # at the exit instant: along the outward normals
            dx = sum((q[0] - b[k][0]) / self.ms[k] for k in S)
            dy = sum((q[1] - b[k][1]) / self.ms[k] for k in S)
            d = math.hypot(dx, dy)
        y[0], y[1] = self.v_seed * dx / d, self.v_seed * dy / d
        y[3 + 2 * self.n] -= 0.5 * self.v_seed ** 2  # the seed's kinetic energy, booked against friction
        self.warm[S] = q
        self.recent = [q]
        self.n_events["start from rest"] += 1
        return S

    def mode_of_state(self, y):
        """The sliding set of a moving state: the one S whose force leaves S outside and the rest inside their discs."""
        V = (y[0], y[1])
        u = tuple(y[2:2 + 2 * self.n])
        best = None
        for mask in range(1, 1 << self.n):
            S = tuple(k for k in range(self.n) if mask >> k & 1)
            try:
                r, slips, f = self.force(V, u, S)
            except OutsideReference:
                continue
            excess = [math.hypot(*f[k]) - self.ms[k] for k in range(self.n)]
            worst = max([-excess[k] for k in S] + [excess[k] for k in range(self.n) if k not in S])
            if best is None or worst < best[0]:
                best = (worst, S)
        if best is None or best[0] > 1e-9:
            raise OutsideReference(f"no consistent sliding set at the window's start ({best})")
        return best[1]

    # ---- events ----
    def events(self, S, t_start):
        n = self.n
        out = []

        def make(kind, k, fn):
            def event(t, y, S_, a0, slope):
                value = fn(y)
                return abs(value) + 1e-300 if t == t_start and abs(value) <= 1e-12 else value
            event.terminal = True
            event.direction = -1
            event.which = (kind, k)
            return event

        def excess(y, k):
            r, slips, f = self.force((y[0], y[1]), tuple(y[2:2 + 2 * n]), S)
            return math.hypot(*f[k]) - self.ms[k]

        for k in range(n):
            if k in S:
                out.append(make("stop", k, lambda y, k=k: excess(y, k)))
                out.append(make("rim", k, lambda y, k=k: self.cap[k] - math.hypot(y[2 + 2 * k], y[3 + 2 * k])))
            else:
                out.append(make("start", k, lambda y, k=k: -excess(y, k)))
        out.append(make("mass stop", -1, lambda y: math.hypot(y[0], y[1]) - self.v_stop))
        return out

    # ---- the run ----
    def run(self, ax, ay, dt, y0=None):
        """Displacement and velocity at the samples [(n, 2)], energies (E_in, E_f, E_v) at the samples."""
        n = self.n
        y = np.zeros(2 + 2 * n + 3) if y0 is None else np.array(y0, dtype=float)
        moving = math.hypot(y[0], y[1]) > 0.0
        S = self.mode_of_state(y) if moving else ()
        xs = [self.position(y)]
        vs = [(y[0], y[1])]
        en = [tuple(y[2 + 2 * n:])]
        self.progress = (xs, vs, en)
        for j in range(ax.size - 1):
            a0 = (ax[j], ay[j])
            slope = ((ax[j + 1] - ax[j]) / dt, (ay[j + 1] - ay[j]) / dt)
            t = 0.0
            for _ in range(1000):
                if t >= dt:
                    break
                if not moving:
                    b = self.back(tuple(y[2:2 + 2 * n]))
                    p0 = (-a0[0] / self.g, -a0[1] / self.g)
                    p1 = (-slope[0] / self.g, -slope[1] / self.g)
                    p = (p0[0] + p1[0] * t, p0[1] + p1[1] * t)
                    if self.inside_all(p, b):
                        te = self.exit_time(p0, p1, b, t, dt)
                        if te is None:
                            break
                        t = te
                        p = (p0[0] + p1[0] * t, p0[1] + p1[1] * t)
                    S = self.start_from_rest(y, p)
                    moving = True
                self.modes.add(S)
                events = self.events(S, t)
                try:
                    sol = solve_ivp(self.rhs, (t, dt), y, method="Radau", rtol=self.rtol, atol=self._atol(),
                                    jac=self.jac, args=(S, a0, slope), events=events, first_step=min(self.h, dt - t))
                except ValueError as exc:  # a Jacobian at a state without a force (NaN)
                    raise OutsideReference(f"{exc} in mode {S} in the interval from {j * dt} s") from exc
                if sol.status == -1:
                    raise OutsideReference(f"solve_ivp: {sol.message} at {j * dt + t} s")
                if sol.t.size > 1:
                    self.h = max(float(np.min(np.diff(sol.t))), 1e-10)
                y = sol.y[:, -1].copy()
                if sol.status == 0:
                    break
                fired = [i for i, te in enumerate(sol.t_events) if te.size]
                t = float(sol.t[-1])
                kind, k = events[fired[-1]].which
                self.n_events[kind] = self.n_events.get(kind, 0) + 1
                if kind == "rim":
                    raise OutsideReference(f"surface {k + 1} reaches its rim at {j * dt + t} s")
                if kind == "mass stop" or (kind == "stop" and len(S) == 1):
                    # the coast left (|Ẋ| ≤ v_stop) is not integrated: its kinetic energy booked as friction
                    y[3 + 2 * n] += 0.5 * (y[0] ** 2 + y[1] ** 2)
                    y[0] = y[1] = 0.0
                    S = ()
                    moving = False
                elif kind == "stop":
                    S = tuple(i for i in S if i != k)
                else:
                    S = tuple(sorted(S + (k,)))
            else:
                raise OutsideReference(f"1000 phases in the interval at {j * dt} s")
            xs.append(self.position(y))
            vs.append((y[0], y[1]))
            en.append(tuple(y[2 + 2 * n:]))
        self.y_end = y
        return np.array(xs), np.array(vs), np.array(en)

    def balance(self, y0, y1):
        """E_in − ΔE_kin − ΔE_pot − E_friction − E_viscous between two states [J/kg], and E_in."""
        n = self.n
        kin = 0.5 * (y1[0] ** 2 + y1[1] ** 2 - y0[0] ** 2 - y0[1] ** 2)
        pot = self.potential(y1[2:2 + 2 * n]) - self.potential(y0[2:2 + 2 * n])
        e_in, e_f, e_v = (y1[2 + 2 * n + i] - y0[2 + 2 * n + i] for i in range(3))
        return e_in - kin - pot - e_f - e_v, e_in

    def _atol(self):
        n = self.n
        return np.concatenate(([1e-15] * 2, [1e-16] * (2 * n), [1e-15] * 3))

    def position(self, y):
        n = self.n
        return (float(sum(y[2 + 2 * k] for k in range(n))), float(sum(y[3 + 2 * k] for k in range(n))))

    def potential(self, u):
        """g Σ ū_i²/(2R̄_i), ū = T⁻¹ u (u as (n, 2))."""
        elements = self.smat @ np.asarray(u).reshape(self.n, 2)
        return float(self.g * np.sum(np.sum(elements ** 2, axis=1) / (2.0 * self.rbar)))


PAIRS = {
    "ABY": ("hectormine1999_ABY", "RSN1762_HECTOR_ABY090.AT2", "RSN1762_HECTOR_ABY360.AT2"),
    "PTS": ("superstitionhills1987_PTS", "RSN723_SUPER.B_B-PTS225.AT2", "RSN723_SUPER.B_B-PTS315.AT2"),
    "DZC": ("duzce1999_DZC", "RSN1605_DUZCE_DZC180.AT2", "RSN1605_DUZCE_DZC270.AT2"),
    "CHY028": ("chichi1999_CHY028", "RSN1197_CHICHI_CHY028-N.AT2", "RSN1197_CHICHI_CHY028-E.AT2"),
    "CBGS": ("christchurch2011_CBGS", "RSN8063_CCHURCH_CBGSN89W.AT2", "RSN8063_CCHURCH_CBGSS01W.AT2"),
    "YER": ("landers1992_YER", "RSN900_LANDERS_YER270.AT2", "RSN900_LANDERS_YER360.AT2"),
    "65025": ("chuetsuoki2007_65025", "RSN4856_CHUETSU_65025EW.AT2", "RSN4856_CHUETSU_65025NS.AT2"),
}


def read_pair(name, scale=1.0, records=None):
    folder, fx, fy = PAIRS[name]
    records = Path(__file__).resolve().parents[2].parent / "shared" / "records" if records is None else records
    mx, my = (read_ground_motion(records / "pairs" / folder / f) for f in (fx, fy))
    n = min(mx.npts, my.npts)
    return scale * mx.acceleration_m_s2[:n], scale * my.acceleration_m_s2[:n], mx.dt_s


def window(bearing, ax, ay, dt, t0, t1, tolerance=None, **ref_keywords):
    """The model on the record to t1 and the reference from the model's state at t0 (a truncated run of the model:
    it is causal): the model's run to t1, the reference's X, Ẋ and energies on [t0, t1], the reference, the samples
    k0 and k1, and the reference's state at t0."""
    k0, k1 = int(round(t0 / dt)), int(round(t1 / dt))
    options = {} if tolerance is None else {"tolerance": tolerance}
    full = simulate_bearing_pair_rate(ax[:k1 + 1], ay[:k1 + 1], dt, bearing=bearing, **options)
    ref = PlanarRateReference(bearing, **ref_keywords)
    n = ref.n
    y0 = np.zeros(2 + 2 * n + 3)
    if k0 > 0:
        head = simulate_bearing_pair_rate(ax[:k0 + 1], ay[:k0 + 1], dt, bearing=bearing, **options)
        assert np.array_equal(head.displacement_m, full.displacement_m[:k0 + 1])  # causal: the same steps
        u0 = bearing.surface_matrix() @ head.element_displacement_m  # u = T ū, (n, 2)
        y0[0:2] = head.velocity_m_s[-1]
        y0[2:2 + 2 * n] = u0.ravel()
    x, v, en = ref.run(ax[k0:k1 + 1], ay[k0:k1 + 1], dt, y0)
    return full, x, v, en, ref, k0, k1, y0


TFP = rate_bearing("triple", GEOMETRY, MU_SLOW, MU_FAST, 20.0)
DOUBLE = rate_bearing("double", [(2.1, 0.4), (1.5, 0.4)], [0.03, 0.05], [0.06, 0.09], 20.0)


def compare(bearing, name, t0, t1, records, tolerance=None):
    """Run one window; print and return (distance / peak, the model, the reference's pieces)."""
    ax, ay, dt = read_pair(name, 1.0, records)
    full, x, v, en, ref, k0, k1, y0 = window(bearing, ax, ay, dt, t0, t1, tolerance)
    peak = float(np.max(np.hypot(*full.displacement_m.T)))
    dist = float(np.max(np.hypot(*(x - full.displacement_m[k0:k1 + 1]).T))) / peak
    print(f"{name} [{t0}, {t1}] s step_tol {tolerance}: |X − X_ref| ≤ {dist:.3g} of the peak {peak:.4f} m; modes "
          f"{sorted(ref.modes)}; events {ref.n_events}; a·|u̇| of the second saturated ≤ {ref.max_second_saturation:.1f}")
    return dist, full, (x, v, en, ref, k0, k1, ax, ay, dt, y0)


def energies(full, en, k0, k1):
    """(the model's E_in and E_friction over the window, the reference's)."""
    hist = full.energy_history_J_per_kg
    return (hist[0, k1] - hist[0, k0], hist[1, k1] - hist[1, k0]), (en[-1, 0] - en[0, 0], en[-1, 1] - en[0, 1])


#: Windows (regimes I–III of the tests' TFP, a double with stops): the largest |X − X_ref| / peak measured at the
#: default step_tol (docs/multisurface.md, h152) and the bound asserted (about 8–10× the measured; where the mass
#: stops the reference's own error grows with its v_stop and v_seed: ≈ 2e-10 of the peak on the double's 1–3 s).
WINDOWS = [
    pytest.param(TFP, "PTS", 3.0, 3.6, 2e-11, id="TFP-PTS-3.0-3.6s-regimes-II-III"),  # measured 2.4e-12
    pytest.param(TFP, "DZC", 2.5, 3.0, 2e-12, id="TFP-DZC-2.5-3.0s-regime-III"),      # measured 2.1e-13
    pytest.param(DOUBLE, "DZC", 2.0, 3.0, 5e-11, id="double-DZC-2-3s-stops"),         # measured 4.9e-12
    # surface 3, just started, stops at 55.153814849 s inside the first step it takes (h162): with a just-started
    # surface's stop slot switched off for that step the stop was taken at the step's end, 55.15473 s at step_tol
    # 1e-11 (55.15443 at 1e-12), 2.6e-7 of the peak from the reference; located now: 7.5e-13
    pytest.param(TFP, "CHY028", 55.1, 55.3, 1e-11, id="TFP-CHY028-55.1-55.3s-a-stop-in-a-first-step"),
]


@pytest.mark.parametrize(("bearing", "name", "t0", "t1", "bound"), WINDOWS)
def test_real_pair_window_against_the_reference(bearing, name, t0, t1, bound, records_dir):
    dist, full, (x, v, en, ref, k0, k1, ax, ay, dt, y0) = compare(bearing, name, t0, t1, records_dir)
    assert dist <= bound
    (m_in, m_f), (r_in, r_f) = energies(full, en, k0, k1)
    print(f"  E_in over the window: model {m_in:.15g}, reference {r_in:.15g}; E_friction {m_f:.15g} / {r_f:.15g}")
    assert abs(m_in - r_in) <= 1e-9 * abs(r_in)
    assert abs(m_f - r_f) <= 1e-9 * abs(r_f)
    miss, e_in = ref.balance(y0, ref.y_end)  # the reference's own balance over the window
    print(f"  the reference's balance: {miss:.3g} J/kg of {e_in:.4g}")
    assert abs(miss) <= 1e-10 * abs(e_in)
    if name == "PTS":  # the bound is not one that cannot fail: µ_fast of surface 1 moved by 1e-6
        moved = rate_bearing("triple", GEOMETRY, MU_SLOW, [MU_FAST[0] + 1e-6] + MU_FAST[1:], 20.0)
        other = simulate_bearing_pair_rate(ax[:k1 + 1], ay[:k1 + 1], dt, bearing=moved)
        peak = float(np.max(np.hypot(*full.displacement_m.T)))
        off = float(np.max(np.hypot(*(x - other.displacement_m[k0:k1 + 1]).T))) / peak
        print(f"  µ_fast,1 + 1e-6: {off:.3g} of the peak from the reference")
        assert off > 10 * bound


@pytest.mark.parametrize("tolerance", [None, 1e-12], ids=lambda value: f"step_tol-{value}")
def test_a_surface_stopping_at_speed_on_pts(tolerance, records_dir):
    """PTS ×1, 11.10–11.30 s (the TFP in regime III at 0.45 m/s, surface 2 stopping at 11.1837 s).  Found by this
    reference (h152): at the default step_tol the kernel restarted surface 2 at the instant it stopped (its start
    slot −9.7e-17 from the force's rounding, taken as a start already past) and let it slip 3.05e-6 m for a step,
    3.2e-6 of the peak; the just-stopped surface's start slot is now armed only from 0 (h157)."""
    dist, full, (x, v, en, ref, k0, k1, ax, ay, dt, y0) = compare(TFP, "PTS", 11.1, 11.3, records_dir, tolerance)
    sel = (full.event_time_s > 11.1) & (full.event_time_s <= 11.3)
    print("  the model's events:", np.round(full.event_time_s[sel], 9).tolist())
    assert ref.n_events["stop"] >= 1
    assert np.sum(np.diff(full.event_time_s[sel]) == 0.0) == 0  # no second event at the stop's instant
    assert dist <= 1e-10
