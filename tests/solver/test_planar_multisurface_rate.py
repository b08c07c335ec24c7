"""Double and triple pendulums with µ(v) surfaces in the plane (2d-multisurface+mu(v)) against independent truths.

Truths: the 1-D µ(v) model ``1d-multisurface+mu(v)`` (a pair whose second component is zero, and that record
along another azimuth), the single-surface engine ``2d+mu(v)`` (an equal double: each surface slides at V/2, so
it is one pendulum of radius 2R̄ with the rate a/2), rotation and mirror invariance, the energy balance, the
constant-µ model (µ_slow = µ_fast runs ``2d-multisurface``), and a reference written from the equations alone
(:class:`PlanarRateReference`: scipy's Radau on the physical state, the force the minimiser of the convex dual
Σ Ψ_i(|r − b_i|) − Ẋ·r by damped Newton, the kinks of the slide laws and the mass's stops as solve_ivp events).
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from isolator.bearing import parse_bearing
from isolator.errors import DesignError, RecordInputError, SolverError
from isolator.solver.multisurface_rate import simulate_bearing_rate
from isolator.solver.planar import simulate_pair
from isolator.solver.planar_multisurface_rate import simulate_bearing_pair_rate

G = 9.80665
GEOMETRY = [(2.1, 0.4), (0.3, 0.05), (0.3, 0.05), (2.1, 0.4)]  # Fenz & Constantinou's TFP (R [m], d [m])
MU_SLOW = [0.03, 0.01, 0.01, 0.05]
MU_FAST = [0.06, 0.02, 0.02, 0.10]
PTS = ("superstitionhills1987_PTS", "RSN723_SUPER.B_B-PTS225.AT2", "RSN723_SUPER.B_B-PTS315.AT2")


def rate_bearing(kind, geometry, mu_slow, mu_fast, rate):
    return parse_bearing({"type": kind, "surface": [
        {"radius_m": r, "mu_slow": s, "mu_fast": f, "rate_s_per_m": rate, "displacement_capacity_m": d}
        for (r, d), s, f in zip(geometry, mu_slow, mu_fast, strict=True)]}, DesignError)


TFP = rate_bearing("triple", GEOMETRY, MU_SLOW, MU_FAST, 20.0)


def pulse_pair(ax_g=0.2, ay_g=0.15, dt=0.01, duration=4.0, until=2.0):
    t = np.arange(0.0, duration, dt)
    on = t < until
    return ax_g * G * np.sin(2 * np.pi * t / 2.0) * on, ay_g * G * np.cos(2 * np.pi * t / 1.7) * on, dt


def rotate(a, b, theta):
    c, s = np.cos(theta), np.sin(theta)
    return c * a - s * b, s * a + c * b


def read_pair(records_dir, seconds):
    from isolator.motion import read_ground_motion

    folder, fx, fy = PTS
    mx, my = (read_ground_motion(records_dir / "pairs" / folder / name) for name in (fx, fy))
    n = min(mx.npts, my.npts, int(round(seconds / mx.dt_s)) + 1)
    return mx.acceleration_m_s2[:n], my.acceleration_m_s2[:n], mx.dt_s


class PlanarRateReference:
    """The µ(v) series model in the plane integrated by scipy (Radau, rtol 1e-12), interval by interval.

    State (Ẋ, u_1..u_n) ∈ ℝ^(2+2n); the force r is the minimiser of Σ_i Ψ_i(|r − b_i|) − Ẋ·r with
    Ψ_i(ρ) = ∫_{µ_slow}^ρ φ_i (0 inside the static disc, +inf past µ_fast), whose gradient condition is
    Σ_i φ_i(|r − b_i|) (r − b_i)/|r − b_i| = Ẋ with the physical laws (no continuation, no pivot: not the
    kernel's formulation); damped Newton on that convex function.  A surface's kink |r − b_i| = µ_slow,i is a
    terminal event (the integration restarts there); the mass is put at rest when its speed falls to 1e-8 m/s
    and leaves rest by the exit of −a_g/g from the intersection of the static discs (brentq), its first 1e-4 s
    taken as a series along the exit direction.
    """

    def __init__(self, b, g=G):
        rbar, _, _ = b.elements()
        smat = np.linalg.inv(b.surface_matrix())
        self.bmat = smat / rbar[:, None]
        self.ms = np.array([s.mu_slow for s in b.surfaces])
        self.mf = np.array([s.mu_fast for s in b.surfaces])
        self.a = np.array([s.rate_s_per_m for s in b.surfaces])
        self.n = len(b.surfaces)
        self.g = g
        self.r = np.zeros(2)

    def back(self, u):
        return self.bmat @ u.reshape(self.n, 2)

    def _objective(self, r, v, bf):
        total = -float(v @ r)
        for i in range(self.n):
            rho = math.hypot(*(r - bf[i]))
            if rho >= self.mf[i]:
                return math.inf
            if rho > self.ms[i]:
                d = self.mf[i] - self.ms[i]
                w = self.mf[i] - rho
                total += ((rho - self.ms[i]) * math.log(d) - (d * math.log(d) - d - w * math.log(w) + w)) / self.a[i]
        return total

    def _gradient(self, r, v, bf):
        grad = -v.copy()
        hess = np.zeros((2, 2))
        for i in range(self.n):
            f = r - bf[i]
            rho = math.hypot(*f)
            if rho > self.ms[i]:
                e = f / rho
                phi = math.log((self.mf[i] - self.ms[i]) / (self.mf[i] - rho)) / self.a[i]
                dphi = 1.0 / (self.a[i] * (self.mf[i] - rho))
                grad += phi * e
                hess += dphi * np.outer(e, e) + phi / rho * (np.eye(2) - np.outer(e, e))
        return grad, hess

    def force(self, v, u):
        bf = self.back(u)
        r = self.r.copy()
        if not math.isfinite(self._objective(r, v, bf)):
            r = bf[int(np.argmax(self.ms))].copy()
        value = self._objective(r, v, bf)
        for _ in range(200):
            grad, hess = self._gradient(r, v, bf)
            reg = 1e-14 * (np.trace(hess) + 1e-300)
            step = np.linalg.solve(hess + reg * np.eye(2) if np.linalg.det(hess) > 0 else np.eye(2) + hess, grad)
            lam = 1.0
            while lam > 1e-12:
                trial = r - lam * step
                new = self._objective(trial, v, bf)
                if new <= value:
                    break
                lam *= 0.5
            r, value = trial, new
            if lam * math.hypot(*step) <= 1e-17:
                break
        self.r = r
        return r, bf

    def rates(self, r, bf):
        out = np.zeros((self.n, 2))
        for i in range(self.n):
            f = r - bf[i]
            rho = math.hypot(*f)
            if rho > self.ms[i]:
                out[i] = math.log((self.mf[i] - self.ms[i]) / (self.mf[i] - rho)) / self.a[i] * f / rho
        return out

    def rhs(self, t, y, ag):
        r, bf = self.force(y[:2], y[2:])
        return np.concatenate((-self.g * r - ag(t), self.rates(r, bf).ravel()))

    def run(self, ax, ay, dt, until=None):
        n_samples = ax.size
        times = dt * np.arange(n_samples)
        t_end = times[-1] if until is None else until
        y = np.zeros(2 + 2 * self.n)
        out = np.full((n_samples, 2), np.nan)
        out[0] = 0.0

        def ag(t):
            return np.array([np.interp(t, times, ax), np.interp(t, times, ay)])

        def need(t):
            return -ag(t) / self.g

        t = 0.0
        rest = True
        k = 1
        segments = 0
        while t < t_end - 1e-12:
            if rest:
                bf = self.back(y[2:])

                def outside(s, bf=bf):
                    return max(math.hypot(*(need(s) - bf[i])) - self.ms[i] for i in range(self.n))

                grid = times[(times > t) & (times <= t_end)]
                start = None
                prev = t
                for s in grid:
                    if outside(s) > 0.0:
                        start = brentq(outside, prev, s, xtol=1e-15, rtol=1e-15) if outside(prev) < 0.0 else prev
                        break
                    prev = s
                while k < n_samples and (start is None or times[k] <= start) and times[k] <= t_end:
                    out[k] = y[2::2].sum(), y[3::2].sum()
                    k += 1
                if start is None:
                    break
                # the first 1e-4 s from rest: along the exit direction e, speed ½ g (d|r_need − b_k|/dt) τ²
                over = [math.hypot(*(need(start) - bf[i])) - self.ms[i] for i in range(self.n)]
                movers = [i for i in range(self.n) if over[i] >= max(over) - 1e-13]
                e = (need(start) - bf[movers[0]]) / math.hypot(*(need(start) - bf[movers[0]]))
                tau = 1e-4
                rate = float((need(start + tau) - need(start)) @ e) / tau
                y[:2] = 0.5 * self.g * rate * tau ** 2 * e
                for i in movers:
                    y[2 + 2 * i:4 + 2 * i] += self.g * rate * tau ** 3 / 6.0 * e / len(movers)
                self.r = bf[movers[0]] + self.ms[movers[0]] * e
                t = start + tau
                rest = False
                continue

            def kink(i):
                def event(s, yy, *_):
                    r, bf = self.force(yy[:2], yy[2:])
                    return math.hypot(*(r - bf[i])) - self.ms[i]
                event.terminal = True
                return event

            kinks = [kink(i) for i in range(self.n)]
            values = [ev(t, y) for ev in kinks]
            signs = [0.0 if abs(v) < 1e-11 else np.sign(v) for v in values]  # at a kink now: not armed

            def armed(i, signs, kinks):
                def event(tt, yy, *_):
                    return signs[i] * kinks[i](tt, yy) if signs[i] != 0 else 1.0
                event.terminal = True
                event.direction = -1
                return event

            def stop(s, yy, *_):
                return math.hypot(yy[0], yy[1]) - 1e-8
            stop.terminal = True
            stop.direction = -1
            sol = solve_ivp(self.rhs, (t, t_end), y, method="Radau", rtol=1e-12, atol=1e-14, dense_output=True,
                            events=[armed(i, signs, kinks) for i in range(self.n)] + [stop], args=(ag,), first_step=1e-6)
            t_new = sol.t[-1]
            while k < n_samples and times[k] <= t_new:
                z = sol.sol(times[k])
                out[k] = z[2::2].sum(), z[3::2].sum()
                k += 1
            y = sol.y[:, -1].copy()
            if sol.status == 1 and sol.t_events[-1].size:
                y[:2] = 0.0
                rest = True
            t = t_new
            segments += 1
            assert segments < 10000, "the reference did not get through"
        return out


def test_zero_second_component_is_the_1d_model():
    """The 1-D model's TFP pulse (regimes I–III) as a pair with ay = 0, and along two other azimuths."""
    t = np.arange(0.0, 1.0, 0.02)
    acc = 0.25 * G * np.sin(2 * np.pi * t / 2.0)
    one = simulate_bearing_rate(acc, 0.02, bearing=TFP)
    two = simulate_bearing_pair_rate(acc, np.zeros_like(acc), 0.02, bearing=TFP)
    peak = one.peak_displacement_m
    print("zero component:", two.model_reason, np.max(np.abs(two.displacement_m[:, 0] - one.displacement_m)) / peak)
    assert list(one.regimes) == ["I", "II", "III"] and list(two.regimes) == list(one.regimes)
    assert np.max(np.abs(two.displacement_m[:, 0] - one.displacement_m)) <= 1e-9 * peak
    assert np.all(two.displacement_m[:, 1] == 0.0)
    assert abs(two.peak_displacement_m - peak) <= 1e-9 * peak
    for name in one.regimes:
        assert abs(two.regimes[name] - one.regimes[name]) <= 1e-9
    np.testing.assert_allclose(two.surface_peak_displacement_m, one.surface_peak_displacement_m, rtol=0, atol=1e-9 * peak)
    assert abs(two.energy_balance_error_J_per_kg) <= 1e-9 * two.energy_input_J_per_kg
    assert abs(two.energy_input_J_per_kg - one.energy_input_J_per_kg) <= 1e-9 * one.energy_input_J_per_kg
    theta = np.radians(35.0)
    rot = simulate_bearing_pair_rate(np.cos(theta) * acc, np.sin(theta) * acc, 0.02, bearing=TFP)
    along = rot.displacement_m[:, 0] * np.cos(theta) + rot.displacement_m[:, 1] * np.sin(theta)
    assert np.max(np.abs(along - one.displacement_m)) <= 1e-9 * peak


def test_rotation_mirror_and_energy_in_the_plane():
    ax, ay, dt = pulse_pair()
    res = simulate_bearing_pair_rate(ax, ay, dt, bearing=TFP)
    peak = res.peak_displacement_m
    print("pulse pair:", res.model_reason, res.regimes, "balance", res.energy_balance_error_J_per_kg)
    assert set(res.regimes) >= {"I", "II", "III"}
    assert abs(res.energy_balance_error_J_per_kg) <= 1e-9 * res.energy_input_J_per_kg
    theta = 0.7
    rot = simulate_bearing_pair_rate(*rotate(ax, ay, theta), dt, bearing=TFP)
    x = np.column_stack(rotate(res.displacement_m[:, 0], res.displacement_m[:, 1], theta))
    assert np.max(np.abs(x - rot.displacement_m)) <= 1e-9 * peak
    mir = simulate_bearing_pair_rate(ax, -ay, dt, bearing=TFP)
    assert np.max(np.abs(mir.displacement_m[:, 1] + res.displacement_m[:, 1])) <= 1e-9 * peak
    assert np.max(np.abs(mir.displacement_m[:, 0] - res.displacement_m[:, 0])) <= 1e-9 * peak


def test_equal_double_is_the_single_pendulum_of_summed_radius_and_half_rate():
    """Equal surfaces (R̄, µ_slow, µ_fast, a) share the velocity: each slides at V/2 with the one force, so
    r = u/R̄ + µ(|V|/2) V̂ = X/(2R̄) + (µ_fast − Δµ e^(−(a/2)|V|)) V̂: the single pendulum of radius 2R̄ and rate
    a/2 (break-away at µ_slow), run by the planar engine (another integrator, its own events)."""
    dbl = rate_bearing("double", [(1.5, 1.5), (1.5, 1.5)], [0.04, 0.04], [0.08, 0.08], 10.0)
    rbar, _, _ = dbl.elements()
    ax, ay, dt = pulse_pair(0.3, 0.25)
    res = simulate_bearing_pair_rate(ax, ay, dt, bearing=dbl)
    ref = simulate_pair(ax, ay, dt, mu_static=0.04, radius_m=float(rbar.sum()), mu_slow=0.04, mu_fast=0.08,
                        rate_s_per_m=5.0)
    peak = ref.peak_displacement_m
    dist = np.max(np.hypot(*(res.displacement_m - ref.displacement_m).T)) / peak
    print("equal double vs 2d+mu(v):", dist, "peak", peak)
    assert dist <= 1e-9
    assert abs(res.energy_balance_error_J_per_kg) <= 1e-9 * res.energy_input_J_per_kg


def test_a_constant_law_runs_the_constant_model_and_the_registry_says_which():
    from isolator.adapter import motion_keywords
    from isolator.design import Design
    from isolator.solver.models import Scene, select_model, simulate
    from isolator.solver.planar_multisurface import simulate_bearing_pair

    def design(mu_fast):
        return Design.from_mapping({"name": "TFP", "mass_kg": 1.0e5, "bearing": {"type": "triple", "surface": [
            {"radius_m": r, "mu_slow": s, "mu_fast": s if mu_fast is None else f, "rate_s_per_m": 20.0,
             "displacement_capacity_m": d} for (r, d), s, f in zip(GEOMETRY, MU_SLOW, MU_FAST, strict=True)]}},
            source="tfp_muv.toml")

    ax, ay, dt = pulse_pair(duration=3.0)
    rate = design(True)
    pair = Scene(ax_m_s2=ax, ay_m_s2=ay, dt_s=dt, isolator=motion_keywords(rate), design=rate)
    assert select_model(pair)[0] == "2d-multisurface+mu(v)"
    one = Scene(ax_m_s2=ax, dt_s=dt, isolator=motion_keywords(rate), design=rate)
    assert select_model(one)[0] == "1d-multisurface+mu(v)"  # one component keeps the 1-D model
    vertical = Scene(ax_m_s2=ax, ay_m_s2=ay, az_m_s2=0.1 * ax, dt_s=dt, isolator=motion_keywords(rate), design=rate)
    with pytest.raises(RecordInputError, match="vertical component is not modelled"):
        simulate(vertical)
    flat = design(None)  # µ_slow = µ_fast: constant friction, the constant-µ model
    scene = Scene(ax_m_s2=ax, ay_m_s2=ay, dt_s=dt, isolator=motion_keywords(flat), design=flat)
    res = simulate(scene)
    assert res.model == "2d-multisurface"
    constant = parse_bearing({"type": "triple", "surface": [
        {"radius_m": r, "mu": s, "displacement_capacity_m": d} for (r, d), s in zip(GEOMETRY, MU_SLOW, strict=True)]},
        DesignError)
    direct = simulate_bearing_pair(ax, ay, dt, bearing=constant)
    np.testing.assert_array_equal(res.displacement_m, direct.displacement_m)


def test_a_rim_is_refused_in_one_line_with_its_time_and_surface(records_dir):
    """Chuetsu-oki 65025 drives surface 1 to its rim (25.76 s; the constant-µ event kernel's first rim: 25.74 s)."""
    from isolator.motion import read_ground_motion

    folder = records_dir / "pairs" / "chuetsuoki2007_65025"
    mx, my = (read_ground_motion(folder / name) for name in ("RSN4856_CHUETSU_65025EW.AT2",
                                                              "RSN4856_CHUETSU_65025NS.AT2"))
    n = min(mx.npts, my.npts)
    with pytest.raises(SolverError, match=r"surface 1 of the triple bearing reaches its rim at t = 25\.7\d* s; the "
                                          r"rims of the µ\(v\) model in the plane are not modelled") as info:
        simulate_bearing_pair_rate(mx.acceleration_m_s2[:n], my.acceleration_m_s2[:n], mx.dt_s, bearing=TFP)
    assert "\n" not in str(info.value)


def test_real_pair_against_the_reference(records_dir):
    """Superstition Hills PTS, 0–1.6 s: two break-aways of the equal inner surfaces, a stop between, then regimes I–II."""
    ax, ay, dt = read_pair(records_dir, 1.6)
    res = simulate_bearing_pair_rate(ax, ay, dt, bearing=TFP)
    ref = PlanarRateReference(TFP).run(ax, ay, dt)
    peak = res.peak_displacement_m
    dist = np.max(np.hypot(*(res.displacement_m - ref).T)) / peak
    print("PTS 0-1.6 s vs reference:", dist, "peak", peak, res.regimes, "events", res.n_events)
    assert res.n_events >= 3 and "I" in res.regimes
    assert dist <= 1e-9


def test_real_pair_energy_balance(records_dir):
    ax, ay, dt = read_pair(records_dir, 1e9)
    res = simulate_bearing_pair_rate(ax, ay, dt, bearing=TFP)
    print("PTS whole:", res.model_reason, res.regimes, "balance", res.energy_balance_error_J_per_kg, "of",
          res.energy_input_J_per_kg)
    assert list(res.regimes) == ["I", "II", "III"]
    assert abs(res.energy_balance_error_J_per_kg) <= 1e-9 * res.energy_input_J_per_kg
    hist = res.energy_history_J_per_kg
    assert np.all(np.diff(hist[1]) >= -1e-12 * res.energy_input_J_per_kg)  # friction work never decreases


#: the µ(v) TFP of these tests as a design file, with the review's bounds and plan
TFP_MUV_TOML = """name = "TFP with mu(v) (review)"
mass_kg = 2.0e6
lambda_max = 1.2
lambda_min = 0.9
[plan]
b_m = 40.0
d_m = 25.0
eccentricity_m = 0.5
y_m = 20.0
[bearing]
type = "triple"
surface = [
  {radius_m = 2.1, mu_slow = 0.03, mu_fast = 0.06, rate_s_per_m = 20.0, displacement_capacity_m = 0.4},
  {radius_m = 0.3, mu_slow = 0.01, mu_fast = 0.02, rate_s_per_m = 20.0, displacement_capacity_m = 0.05},
  {radius_m = 0.3, mu_slow = 0.01, mu_fast = 0.02, rate_s_per_m = 20.0, displacement_capacity_m = 0.05},
  {radius_m = 2.1, mu_slow = 0.05, mu_fast = 0.10, rate_s_per_m = 20.0, displacement_capacity_m = 0.4},
]
"""


def test_cli_simulate_json_on_a_pair(tmp_path, records_dir):
    design = tmp_path / "tfp_muv.toml"
    design.write_text(TFP_MUV_TOML)
    folder = records_dir / "pairs" / PTS[0]
    exe = str(Path(sys.executable).with_name("isolator"))
    run = subprocess.run([exe, "simulate", str(folder / PTS[1]), "--pair", str(folder / PTS[2]), "--design",
                          str(design), "--trim", "--json"], capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr
    out = json.dumps(json.loads(run.stdout))
    assert "2d-multisurface+mu(v)" in out and "Radau IIA" in out and "regimes" in out
