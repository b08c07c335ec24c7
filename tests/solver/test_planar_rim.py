"""The rim of a single friction pendulum in the plane (model ``2d+rim``, issue 23).

Truths: the 1-D rim model (``1d-multisurface`` with a single surface) for a pair whose second
component is zero; rotation invariance; an independent reference written here (:func:`rim_reference`:
scipy ``solve_ivp`` with events for the impact and for leaving the rim, the motion on the rim in
polar coordinates, sharing no code with ``isolator``) on a real pair scaled to hit the rim several
times; the energy balance input = kinetic + potential + friction + impact loss; and a run whose peak
stays below the capacity is the ``2d`` run, bit for bit.
"""

from __future__ import annotations

import math
from collections import Counter

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq, minimize_scalar

from isolator.errors import SolverError
from isolator.solver.planar import simulate_pair
from isolator.solver.planar_rim import simulate_pair_rim

G = 9.80665


# ---- the independent reference ------------------------------------------------------------------------------
def rim_reference(t, ax, ay, *, mu_s, mu_k, radius, d, rtol=1e-12, v_eps=1e-11, v_switch=1e-3):
    """Independent reference: a single pendulum (κ = g/R, constant µk, static µs) with a rim at |X| = d.

    scipy ``solve_ivp`` restarted at every sample, in the manner of ``isolator/bench/planar_reference.py``:

    * sliding off the rim, Cartesian (X, V): DOP853 at rtol 1e-12 for |V| ≥ v_switch, Radau below it
      (V/|V| is stiff near rest), with terminal events |X|² = d² (rising: the impact) and the stops; the
      last v_eps of a stop at constant deceleration; a start from rest at v_eps along F;
    * the impact: V → V − (V·e_r) e_r, impulse V·e_r per unit mass;
    * sliding on the rim, polar (θ, w): Radau at rtol 1e-12 with terminal events w = 0 and
      λ = F·e_r + w²/d = 0 (falling: it leaves along the tangent);
    * at rest, on or off the rim: the end of the hold is the first sign change on a 65-point grid,
      polished by brentq, of |F| − µs g off the rim, and on the rim of |F·e_t| − µs g where F·e_r ≥ 0,
      |F| − µs g where F·e_r < 0.

    Returns
    -------
    dict
        ``displacement_m``, ``velocity_m_s`` at the samples, ``impacts`` [(t, v_r)], ``energy_impact_J_per_kg``.
    """
    kap = G / radius
    t = np.asarray(t, float)
    out_x = np.zeros((t.size, 2))
    out_v = np.zeros((t.size, 2))
    X = np.zeros(2)
    V = np.zeros(2)
    mode = "stuck"  # stuck | slide | rim_slide | rim_held
    slow = True
    theta = 0.0
    w = 0.0
    impacts = []
    peak_a_rim = 0.0  # the largest |A| = |a_g + w' e_t − (w²/d) e_r| while sliding along the rim
    atol = 1e-16

    for i in range(t.size - 1):
        t0, t1 = t[i], t[i + 1]
        sx = (ax[i + 1] - ax[i]) / (t1 - t0)
        sy = (ay[i + 1] - ay[i]) / (t1 - t0)

        def acc(s, i=i, t0=t0, sx=sx, sy=sy):
            return np.array([ax[i] + sx * (s - t0), ay[i] + sy * (s - t0)])

        def force(s, x):
            return -kap * x - acc(s)

        def start(tb, x0, t1=t1):
            # the first v_eps along F from rest (X frozen, |F| − µk g linear in time)
            def excess(s):
                return np.linalg.norm(force(s, x0)) - mu_k * G
            delta = 1e-7 * (t1 - tb) if t1 > tb else 1e-9
            p = max(excess(tb), 0.0)
            q = (excess(tb + delta) - excess(tb)) / delta
            s = 2.0 * v_eps / (p + math.sqrt(p * p + 2.0 * q * v_eps)) if q > 0.0 else v_eps / p
            s = min(s, max(t1 - tb, 0.0))
            e = force(tb, x0) / np.linalg.norm(force(tb, x0))
            return x0 + e * (0.5 * p * s * s + q * s ** 3 / 6.0), v_eps * e, tb + s

        def first_failure(tt, held, t1=t1):
            grid = np.linspace(tt, t1, 65)
            vals = np.array([held(s) for s in grid])
            if vals[0] > 0.0:
                return tt
            pos = np.nonzero(vals > 0.0)[0]
            if pos.size == 0:
                return None
            j = pos[0]
            return brentq(held, grid[j - 1], grid[j], xtol=1e-15, rtol=1e-15)

        tt = t0
        guard = 0
        while tt < t1:
            guard += 1
            if guard > 2000:
                raise RuntimeError(f"rim reference: too many phases in interval {i}")
            if mode == "stuck":
                def q(s, X=X):
                    f = force(s, X)
                    return f @ f - (mu_s * G) ** 2
                tb = first_failure(tt, q)
                if tb is None:
                    break
                X, V, tt = start(tb, X)
                mode, slow = "slide", True
                continue
            if mode == "rim_held":
                er = np.array([math.cos(theta), math.sin(theta)])
                et = np.array([-er[1], er[0]])
                X = d * er

                def fails(s, er=er, et=et):
                    f = force(s, d * er)
                    fr, ft = f @ er, f @ et
                    if fr >= 0.0:
                        return abs(ft) - mu_s * G
                    return math.sqrt(fr * fr + ft * ft) - mu_s * G
                tb = first_failure(tt, fails)
                if tb is None:
                    break
                f = force(tb + 1e-12 * (t1 - t0), X)
                if f @ er >= 0.0:
                    mode, w, tt = "rim_slide", 0.0, tb
                    rim_sign = 1.0 if f @ et > 0.0 else -1.0
                else:
                    X, V, tt = start(tb, X)
                    mode, slow = "slide", True
                continue
            if mode == "rim_slide":
                sign = rim_sign

                def rhs_rim(s, y, sign=sign):
                    er = np.array([math.cos(y[0]), math.sin(y[0])])
                    et = np.array([-er[1], er[0]])
                    return [y[1] / d, force(s, d * er) @ et - sign * mu_k * G]

                def ev_stop(s, y, sign=sign):
                    return sign * y[1]
                ev_stop.terminal, ev_stop.direction = True, -1.0

                def ev_leave(s, y):
                    er = np.array([math.cos(y[0]), math.sin(y[0])])
                    return force(s, d * er) @ er + y[1] ** 2 / d
                ev_leave.terminal, ev_leave.direction = True, -1.0
                sol = solve_ivp(rhs_rim, (tt, t1), [theta, w], method="Radau", rtol=rtol, atol=1e-15,
                                events=(ev_stop, ev_leave), dense_output=True)

                def minus_a(s, sol=sol, rhs_rim=rhs_rim):
                    y = sol.sol(s)
                    er = np.array([math.cos(y[0]), math.sin(y[0])])
                    return -np.linalg.norm(acc(s) + rhs_rim(s, y)[1] * np.array([-er[1], er[0]]) - y[1] ** 2 / d * er)
                grid = np.linspace(sol.t[0], sol.t[-1], 201)
                vals = [minus_a(s) for s in grid]
                k = int(np.argmin(vals))
                best = minimize_scalar(minus_a, bounds=(grid[max(k - 1, 0)], grid[min(k + 1, 200)]), method="bounded",
                                       options={"xatol": 1e-13})
                peak_a_rim = max(peak_a_rim, -vals[k], -best.fun)
                theta, w = sol.y[0, -1], sol.y[1, -1]
                tt = sol.t[-1]
                er = np.array([math.cos(theta), math.sin(theta)])
                et = np.array([-er[1], er[0]])
                X, V = d * er, w * et
                if sol.status == 1 and sol.t_events[0].size:
                    mode, w = "rim_held", 0.0
                    V = np.zeros(2)
                elif sol.status == 1:
                    X = X * (1.0 - 1e-15)
                    mode, slow = "slide", math.hypot(*V) < v_switch
                continue
            # sliding off the rim
            def rhs(s, y):
                x, v = y[:2], y[2:]
                r = math.hypot(v[0], v[1])
                fr = mu_k * G / r if r > 0.0 else 0.0
                return np.concatenate([v, force(s, x) - fr * v])

            def ev_switch(s, y):
                return math.hypot(y[2], y[3]) - v_switch
            ev_switch.terminal = True
            ev_switch.direction = 1.0 if slow else -1.0

            def ev_stop(s, y):
                return math.hypot(y[2], y[3]) - v_eps
            ev_stop.terminal, ev_stop.direction = True, -1.0

            def ev_rim(s, y):
                return y[0] ** 2 + y[1] ** 2 - d * d
            ev_rim.terminal, ev_rim.direction = True, 1.0
            evs = [ev_switch, ev_rim] + ([ev_stop] if slow else [])
            sol = solve_ivp(rhs, (tt, t1), np.concatenate([X, V]), method="Radau" if slow else "DOP853",
                            rtol=rtol, atol=atol, events=evs)
            yend = sol.y[:, -1]
            X, V = yend[:2].copy(), yend[2:].copy()
            tt = sol.t[-1]
            if sol.status != 1:
                continue
            if sol.t_events[1].size:  # the impact
                er = X / np.linalg.norm(X)
                vr = V @ er
                impacts.append((tt, vr))
                et = np.array([-er[1], er[0]])
                theta = math.atan2(er[1], er[0])
                w = V @ et
                X = d * er
                if w == 0.0:
                    mode, V = "rim_held", np.zeros(2)
                elif force(tt, X) @ er + w * w / d < 0.0:
                    V = w * et
                    X = X * (1.0 - 1e-15)
                    mode, slow = "slide", abs(w) < v_switch
                else:
                    mode, rim_sign = "rim_slide", (1.0 if w > 0.0 else -1.0)
            elif slow and sol.t_events[2].size:  # the stop: the last v_eps at constant deceleration
                r = math.hypot(*V)
                rdot = V @ rhs(tt, yend)[2:] / r
                dt = min(r / max(-rdot, 1e-300), t1 - tt)
                X = X + 0.5 * dt * V
                tt = tt + dt
                V = np.zeros(2)
                if np.linalg.norm(force(tt, X)) <= mu_s * G:
                    mode = "stuck"
                else:
                    X, V, tt = start(tt, X)
                    slow = True
            else:
                slow = not slow
        out_x[i + 1] = X
        out_v[i + 1] = V if mode in ("slide", "rim_slide") else 0.0
    return {"displacement_m": out_x, "velocity_m_s": out_v, "impacts": impacts,
            "energy_impact_J_per_kg": sum(0.5 * v * v for _, v in impacts), "peak_a_rim_m_s2": peak_a_rim}


# ---- the records -------------------------------------------------------------------------------------------
PTS = "superstitionhills1987_PTS"


def _pts(records_dir, start_s=None, end_s=None, scale=1.0):
    from isolator.motion import read_ground_motion

    folder = records_dir / "pairs" / PTS
    x = read_ground_motion(folder / "RSN723_SUPER.B_B-PTS225.AT2")
    y = read_ground_motion(folder / "RSN723_SUPER.B_B-PTS315.AT2")
    n = min(x.npts, y.npts)
    a = 0 if start_s is None else int(round(start_s / x.dt_s))
    b = n if end_s is None else int(round(end_s / x.dt_s))
    return scale * x.acceleration_m_s2[a:b], scale * y.acceleration_m_s2[a:b], x.dt_s


def _northridge_x3(records_dir):
    from isolator.motion import read_ground_motion

    motion = read_ground_motion(records_dir / "at2" / "RSN1044_NORTHR_NWH360.AT2")
    start = int(round(2.0 / motion.dt_s))
    return 3.0 * motion.acceleration_m_s2[start:start + int(round(12.0 / motion.dt_s))], motion.dt_s


PENDULUM = {"mu_static": 0.06, "radius_m": 2.0}


@pytest.fixture(scope="module")
def pts_segment(records_dir):
    """PTS 7–14 s × 2 on R = 2 m, µ = 0.06, rim at 0.4 m: four impacts, three slides along the rim and off it."""
    ax, ay, dt = _pts(records_dir, 7.0, 14.0, 2.0)
    return ax, ay, dt, simulate_pair_rim(ax, ay, dt, displacement_capacity_m=0.4, **PENDULUM)


# ---- truths ------------------------------------------------------------------------------------------------
def test_a_zero_second_component_is_the_1d_rim_model(records_dir):
    """Northridge NWH360 (2–14 s) × 3, R = 2 m, µs/µk = 0.08/0.05, capacity 0.6 m: the 1-D rim (1d-multisurface)."""
    from isolator.bearing import Bearing, Surface
    from isolator.solver.multisurface import simulate_bearing

    acc, dt = _northridge_x3(records_dir)
    one = simulate_bearing(acc, dt, bearing=Bearing(kind="single", surfaces=(Surface(
        radius_m=2.0, height_m=0.0, mu_kinetic=0.05, mu_static=0.08, displacement_capacity_m=0.6),)))
    two = simulate_pair_rim(acc, np.zeros_like(acc), dt, displacement_capacity_m=0.6, mu_static=0.08,
                            mu_kinetic=0.05, radius_m=2.0)
    assert one.n_rim_contacts == two.n_rim_contacts == 4
    assert two.model == "2d+rim" and two.ultimate_displacement_reached and two.peak_displacement_m == 0.6
    assert np.all(two.displacement_m[:, 1] == 0.0) and np.all(two.velocity_m_s[:, 1] == 0.0)
    assert np.max(np.abs(two.displacement_m[:, 0] - one.displacement_m)) <= 1e-9 * 0.6  # 2.7e-11 m measured
    assert np.max(np.abs(two.velocity_m_s[:, 0] - one.velocity_m_s)) <= 1e-9 * one.peak_velocity_m_s
    for key in ("impact_impulse_m_s", "max_impact_velocity_m_s", "energy_impact_J_per_kg",
                "peak_transmitted_acceleration_m_s2", "peak_velocity_m_s", "energy_input_J_per_kg"):
        assert getattr(two, key) == pytest.approx(getattr(one, key), rel=1e-9), key
    # the same events: impacts where the 1-D model reaches its ultimate, the stops and starts between
    ones = [k for k in one.event_names if k != "regime"]
    assert [k.replace("rim impact", "ultimate") for k in two.event_names] == ones
    held = np.abs(two.displacement_m[:, 0]) == 0.6  # held on the rim: the mass moves with the ground
    assert np.count_nonzero(held) > 5
    np.testing.assert_allclose(two.absolute_acceleration_m_s2[held, 0], acc[held], rtol=1e-15, atol=0)


def test_rotation_turns_the_answer(pts_segment):
    ax, ay, dt, res = pts_segment
    phi = 0.7
    c, s = math.cos(phi), math.sin(phi)
    turned = simulate_pair_rim(c * ax - s * ay, s * ax + c * ay, dt, displacement_capacity_m=0.4, **PENDULUM)
    rot = np.array([[c, -s], [s, c]])
    assert np.max(np.abs(turned.displacement_m - res.displacement_m @ rot.T)) <= 1e-9 * 0.4
    assert np.max(np.abs(turned.velocity_m_s - res.velocity_m_s @ rot.T)) <= 1e-9 * res.peak_velocity_m_s
    assert turned.n_rim_contacts == res.n_rim_contacts
    assert turned.impact_impulse_m_s == pytest.approx(res.impact_impulse_m_s, rel=1e-9)
    assert turned.energy_impact_J_per_kg == pytest.approx(res.energy_impact_J_per_kg, rel=1e-9)


def test_the_independent_reference_on_a_real_pair(pts_segment):
    """4.0e-11 of the capacity measured (X), 8e-12 on the impulse; the reference takes ~3 s."""
    ax, ay, dt, res = pts_segment
    events = Counter(res.event_names)
    assert events["rim impact"] == 4 and events["rim leave"] >= 2  # hits several times and slides along the rim
    assert res.rim_time_s > 0.1
    ref = rim_reference(dt * np.arange(ax.size), ax, ay, mu_s=0.06, mu_k=0.06, radius=2.0, d=0.4)
    assert np.max(np.abs(res.displacement_m - ref["displacement_m"])) <= 1e-9 * 0.4
    assert np.max(np.abs(res.velocity_m_s - ref["velocity_m_s"])) <= 1e-9 * res.peak_velocity_m_s * 10
    assert len(ref["impacts"]) == res.n_rim_contacts
    assert res.impact_impulse_m_s == pytest.approx(sum(v for _, v in ref["impacts"]), rel=1e-9)
    assert res.energy_impact_J_per_kg == pytest.approx(ref["energy_impact_J_per_kg"], rel=1e-9)
    times = [t for t, k in zip(res.event_time_s, res.event_names, strict=True) if k == "rim impact"]
    np.testing.assert_allclose(times, [t for t, _ in ref["impacts"]], rtol=0, atol=1e-9)
    assert np.max(np.hypot(*res.displacement_m.T)) <= 0.4 * (1 + 1e-15)


def test_energy_balance_with_impacts(pts_segment, records_dir):
    ax, ay, dt, res = pts_segment
    assert res.energy_impact_J_per_kg > 0.2 * res.energy_input_J_per_kg  # the impacts matter
    assert abs(res.energy_balance_error_J_per_kg) <= 1e-9 * res.energy_input_J_per_kg
    # the whole pair × 2, with a damper: energy into the damper too
    ax, ay, dt = _pts(records_dir, scale=2.0)
    full = simulate_pair_rim(ax, ay, dt, displacement_capacity_m=0.4, damping_per_mass=0.3, **PENDULUM)
    assert full.n_rim_contacts >= 3 and full.energy_viscous_J_per_kg > 0.0
    assert abs(full.energy_balance_error_J_per_kg) <= 1e-9 * full.energy_input_J_per_kg


def test_vertical_and_mu_of_v_on_the_rim(records_dir):
    """n(t) = g + a_z (a synthetic vertical that keeps n > 0) and µ(v): the rim holds, the balance closes."""
    ax, ay, dt = _pts(records_dir, 7.0, 14.0, 2.0)
    t = dt * np.arange(ax.size)
    az = 2.0 * np.sin(2 * np.pi * 3.0 * t)
    res = simulate_pair_rim(ax, ay, dt, az_m_s2=az, displacement_capacity_m=0.4, mu_static=0.08, mu_slow=0.05,
                            mu_fast=0.1, rate_s_per_m=20.0, radius_m=2.0)
    assert res.model == "2d+vertical+mu(v)+rim" and res.n_rim_contacts >= 2
    assert np.max(np.hypot(*res.displacement_m.T)) <= 0.4 * (1 + 1e-15)
    assert abs(res.energy_balance_error_J_per_kg) <= 1e-9 * res.energy_input_J_per_kg


def test_uplift_on_the_rim_is_refused_in_one_line():
    dt = 0.01
    t = dt * np.arange(400)
    ax = np.where(t < 1.0, 6.0, 0.0)  # pushes the slider onto the rim and holds it there
    az = np.where(t > 2.0, -15.0, 0.0)  # then the bearing lifts off
    with pytest.raises(SolverError, match=r"uplift on the rim is not modelled"):
        simulate_pair_rim(ax, np.zeros_like(ax), dt, az_m_s2=az, displacement_capacity_m=0.1, **PENDULUM)


def test_the_transmitted_acceleration_peaks_inside_a_slide_along_the_rim():
    """A push onto the rim (−4 m/s² along x) and a sideways shake at 0.25 s samples: the slider slides along the
    rim and back; |A| = |a_g + w' e_t − (w²/d) e_r| peaks between samples, above every |a_g| (5 m/s²).  The
    reference scans each of its slides on the rim (dense output, then a bounded search): 1.7e-14 apart measured."""
    dt = 0.25
    ax = np.array([0.0, -4, -4, -4, -4, -4, -4, 0, 0])
    ay = np.array([0.0, 0, 0, 3, -3, 3, 0, 0, 0])
    res = simulate_pair_rim(ax, ay, dt, displacement_capacity_m=0.1, mu_static=0.05, radius_m=2.0)
    ref = rim_reference(dt * np.arange(ax.size), ax, ay, mu_s=0.05, mu_k=0.05, radius=2.0, d=0.1)
    assert res.n_rim_contacts == 1 and res.event_names.count("reversal") == 2 and res.rim_time_s > 1.0
    assert np.max(np.abs(res.displacement_m - ref["displacement_m"])) <= 1e-9 * 0.1
    assert ref["peak_a_rim_m_s2"] > 1.2 * np.max(np.hypot(ax, ay))  # the rim's reaction: above the ground's
    assert res.peak_transmitted_acceleration_m_s2 == pytest.approx(ref["peak_a_rim_m_s2"], rel=1e-9)
    assert np.max(np.hypot(*res.absolute_acceleration_m_s2.T)) < 0.99 * res.peak_transmitted_acceleration_m_s2


# ---- the registry ------------------------------------------------------------------------------------------
def _design(capacity_m, **extra):
    from isolator.design import Design

    return Design.from_mapping({"name": "FPS", "mass_kg": 1.0e5, "radius_m": 2.0, "mu_static": 0.06,
                                "displacement_capacity_m": capacity_m, **extra}, source="fps.toml")


def test_the_registry_reruns_a_pair_past_the_capacity_with_the_rim(records_dir):
    from isolator.adapter import motion_keywords
    from isolator.solver.models import Scene, select_model, simulate

    ax, ay, dt = _pts(records_dir, scale=2.0)
    design = _design(0.4)
    scene = Scene(ax_m_s2=ax, ay_m_s2=ay, dt_s=dt, isolator=motion_keywords(design), design=design)
    name, reason = select_model(scene)
    assert name == "2d" and "a displacement capacity of 0.4 m: if the peak reaches it, the run is redone" in reason
    res = simulate(scene)
    free = simulate_pair(ax, ay, dt, **motion_keywords(design))
    assert free.peak_displacement_m > 0.6  # an unbounded plate
    assert res.model == "2d+rim" and res.rerun and res.ultimate_displacement_reached
    assert f"on 2d (an unbounded plate) its peak was {free.peak_displacement_m:.4g} m" in res.model_reason
    assert res.peak_displacement_m == pytest.approx(0.4, rel=1e-15)
    summary = res.summary()
    assert summary["n_rim_contacts"] == res.n_rim_contacts >= 3 and summary["impact_impulse_m_s"] > 0.0
    # up to the first impact it is the 2d run, bit for bit (the same kernel, the rim not yet reached)
    before = res.time_s < res.ultimate_first_time_s
    assert np.count_nonzero(before) > 100
    np.testing.assert_array_equal(res.displacement_m[before], free.displacement_m[before])


def test_a_pair_below_the_capacity_is_todays_2d_run_bit_for_bit(records_dir):
    from isolator.adapter import motion_keywords
    from isolator.solver.models import Scene, simulate

    ax, ay, dt = _pts(records_dir)
    design = _design(2.0)
    res = simulate(Scene(ax_m_s2=ax, ay_m_s2=ay, dt_s=dt, isolator=motion_keywords(design), design=design))
    free = simulate_pair(ax, ay, dt, **motion_keywords(design))
    assert res.model == "2d" and "2 m" in res.model_reason and not getattr(res, "rerun", False)
    for key in ("displacement_m", "velocity_m_s", "absolute_acceleration_m_s2", "energy_history_J_per_kg",
                "event_time_s"):
        np.testing.assert_array_equal(getattr(res, key), getattr(free, key))
    assert res.peak_displacement_m == free.peak_displacement_m == pytest.approx(0.8135803309086524, rel=1e-13)


# ---- the review ------------------------------------------------------------------------------------------------
def test_a_review_whose_suite_reaches_the_capacity_shows_the_rim_and_fails_the_capacity(tmp_path):
    """Three short real pairs of the bundled suite on R = 2.5 m, µk = 0.05, capacity 0.25 m: analyses at the upper
    bound reach the rim (2d+rim), and the capacity rows fail with the impulse stated."""
    from isolator.design import Design
    from isolator.review.run import run_review
    from isolator.review.suite import load_suite
    from isolator.review.target import two_period_target
    from tests.review.conftest import DESIGN, EXAMPLE, SHORT

    body = "".join(f'[[pair]]\nname = "{name}"\nx = "{EXAMPLE / name / x}"\ny = "{EXAMPLE / name / y}"\n{extra}\n'
                   for name, x, y, extra in SHORT)
    (tmp_path / "suite.toml").write_text(body)
    (tmp_path / "design.toml").write_text(DESIGN.replace("displacement_capacity_m = 0.5",
                                                         "displacement_capacity_m = 0.25"))
    design = Design.from_toml(tmp_path / "design.toml")
    out = run_review(design, two_period_target(1.5, 0.9, 8.0), load_suite(tmp_path / "suite.toml"), jobs=1,
                     cache_dir=tmp_path / "cache").to_dict()
    upper = out["bounds"]["upper"]["pairs"]
    rimmed = {name: r for name, r in upper.items() if r.get("ultimate_displacement_reached")}
    assert rimmed, {name: r["peak_displacement_m"] for name, r in upper.items()}
    for r in rimmed.values():
        assert r["model"] == "2d+rim" and r["n_rim_contacts"] >= 1 and r["impact_impulse_m_s"] > 0.0
        assert r["peak_displacement_m"] == pytest.approx(0.25, rel=1e-12)
    rows = [c for c in out["checks"] if c["id"] == "record_capacity" and c.get("bound") == "upper"]
    assert {c["pair"] for c in rows} >= set(rimmed)
    for c in rows:
        if c["pair"] in rimmed:
            impulse = design.mass_kg * upper[c["pair"]]["impact_impulse_m_s"]
            assert c["status"] == "fail" and f"impulse {impulse:.4g} N·s" in c["note"], c["note"]
    assert next(c for c in out["checks"] if c["id"] == "D_M_capacity")["status"] == "fail"
