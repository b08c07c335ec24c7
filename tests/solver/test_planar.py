"""The planar (2-D) engine against independent truths (issue 10, "Consistency the tests must show").

Truths: the exact 1-D kernel (a pair with a zero component), rotation and mirror
invariance, the energy balance, the closed-form steady circular sliding, and an
independent reference (tests/planar_reference.py: scipy solve_ivp, DOP853 / Radau at
rtol 1e-12, stop events in Cartesian form) on real pairs and hard cases.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from isolator.motion import read_ground_motion
from isolator.solver.planar import simulate_pair
from isolator.solver.planar_kernel import scan_record
from isolator.solver.record import RecordInputError, simulate_record
from isolator.solver.system import InvalidSystemError
from tests.planar_reference import reference_pair

G = 9.80665


def synthetic_pair(n=800, dt=0.01, pga_g=0.4, seed=3):
    """Two pulse-like components with broadband noise: sticks, slips and turns."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) * dt
    env = np.exp(-((t - 0.4 * n * dt) / (0.25 * n * dt)) ** 2)
    ax = pga_g * G * np.sin(2 * np.pi * 0.8 * t) * env + 0.6 * rng.standard_normal(n) * env
    ay = 0.8 * pga_g * G * np.cos(2 * np.pi * 0.55 * t + 0.3) * env + 0.6 * rng.standard_normal(n) * env
    return t, ax, ay


SYSTEMS_1D = {
    "friction only": dict(mu_static=0.06),
    "model 2": dict(mu_static=0.08, mu_kinetic=0.056),
    "damper": dict(mu_static=0.10, mu_kinetic=0.07, damping_per_mass=2.0),
    "pendulum": dict(mu_static=0.06, radius_m=2.0),
    "under-damped spring": dict(mu_static=0.06, stiffness_per_mass=4.9, damping_per_mass=0.3),
}


def _rel(a, b):
    return abs(a - b) / max(abs(b), 1e-300)


@pytest.mark.parametrize("name", sorted(SYSTEMS_1D))
def test_zero_second_component_is_the_exact_1d_result(name):
    system = dict(SYSTEMS_1D[name])
    t, ax, _ = synthetic_pair()
    dt = t[1] - t[0]
    pair = simulate_pair(ax, np.zeros_like(ax), dt, **system)
    one_d = dict(system)
    if "radius_m" in one_d:
        one_d["stiffness_per_mass"] = G / one_d.pop("radius_m")
    exact = simulate_record(ax, dt, **one_d)
    assert pair.status == 0, pair.message
    assert exact.n_events > 4  # the record makes it stick and slip
    assert np.all(pair.displacement_m[:, 1] == 0.0) and np.all(pair.velocity_m_s[:, 1] == 0.0)
    scale = exact.peak_displacement_m
    assert _rel(pair.peak_displacement_m, scale) <= 1e-9
    assert abs(pair.residual_displacement_x_m - exact.residual_displacement_m) <= 1e-9 * scale
    assert np.max(np.abs(pair.displacement_m[:, 0] - exact.displacement_m)) <= 1e-9 * scale
    assert _rel(pair.peak_velocity_m_s, exact.peak_velocity_m_s) <= 1e-9
    assert pair.event_names == exact.event_names
    np.testing.assert_allclose(pair.event_time_s, exact.event_time_s, rtol=0, atol=1e-9)
    assert _rel(pair.slip_time_s, exact.slip_time_s) <= 1e-9
    assert _rel(pair.energy_friction_J_per_kg, exact.energy_friction_J_per_kg) <= 1e-9
    # the peak transmitted acceleration, located between samples (inside steps, at stick and
    # break-away instants) as the exact kernel locates it
    np.testing.assert_allclose(pair.absolute_acceleration_m_s2[:, 0], exact.absolute_acceleration_m_s2,
                               rtol=0, atol=1e-9 * exact.peak_transmitted_acceleration_m_s2)
    assert _rel(pair.peak_transmitted_acceleration_m_s2, exact.peak_transmitted_acceleration_m_s2) <= 1e-8


@pytest.mark.parametrize("mu", [0.05, 0.1])
def test_zero_second_component_on_a_real_record_is_the_exact_1d_result(records_dir, mu):
    """A real record (IELC180) whose slides end outside the LOG form too: every stop must be
    finished to rest (not cut r_min/|ṙ| short), so the slip time agrees as well as the peaks."""
    motion = read_ground_motion(records_dir / "at2" / "IELC180.AT2")
    a = motion.acceleration_m_s2
    exact = simulate_record(a, motion.dt_s, mu_static=mu, stiffness_per_mass=G / 2.0)
    pair = simulate_pair(a, np.zeros_like(a), motion.dt_s, mu_static=mu, radius_m=2.0)
    assert exact.n_events > 20
    for key in ("peak_displacement_m", "slip_time_s", "energy_input_J_per_kg", "energy_friction_J_per_kg",
                "peak_velocity_m_s", "peak_transmitted_acceleration_m_s2"):
        assert _rel(getattr(pair, key), getattr(exact, key)) <= 1e-9, key
    assert abs(pair.residual_displacement_x_m - exact.residual_displacement_m) <= 1e-9 * exact.peak_displacement_m


@pytest.mark.parametrize("angle", [0.3, 2.0, -1.1])
def test_rotating_the_ground_motion_rotates_the_trajectory(angle):
    t, ax, ay = synthetic_pair()
    dt = t[1] - t[0]
    system = dict(mu_static=0.06, mu_kinetic=0.05, radius_m=2.5, damping_per_mass=0.2)
    base = simulate_pair(ax, ay, dt, **system)
    c, s = math.cos(angle), math.sin(angle)
    rot = simulate_pair(c * ax - s * ay, s * ax + c * ay, dt, **system)
    expected = np.column_stack((c * base.displacement_m[:, 0] - s * base.displacement_m[:, 1],
                                s * base.displacement_m[:, 0] + c * base.displacement_m[:, 1]))
    scale = base.peak_displacement_m
    assert base.n_events >= 4
    assert np.max(np.abs(rot.displacement_m - expected)) <= 1e-9 * scale
    assert _rel(rot.peak_displacement_m, base.peak_displacement_m) <= 1e-9
    assert _rel(rot.residual_displacement_m, base.residual_displacement_m) <= 1e-9
    assert rot.event_names == base.event_names


def test_mirror_symmetry():
    t, ax, ay = synthetic_pair(seed=5)
    dt = t[1] - t[0]
    base = simulate_pair(ax, ay, dt, mu_static=0.07, radius_m=2.0)
    mirror = simulate_pair(ax, -ay, dt, mu_static=0.07, radius_m=2.0)
    # the y-mirror is exact in floating point (every operation is sign-symmetric)
    np.testing.assert_array_equal(mirror.displacement_m[:, 0], base.displacement_m[:, 0])
    np.testing.assert_array_equal(mirror.displacement_m[:, 1], -base.displacement_m[:, 1])
    swapped = simulate_pair(ay, ax, dt, mu_static=0.07, radius_m=2.0)  # mirror about x = y
    scale = base.peak_displacement_m
    assert np.max(np.abs(swapped.displacement_m[:, ::-1] - base.displacement_m)) <= 1e-9 * scale


ENERGY_CASES = {
    "coulomb pendulum": dict(mu_static=0.06, radius_m=2.0),
    "spring + damper, model 2": dict(mu_static=0.08, mu_kinetic=0.06, stiffness_per_mass=3.0, damping_per_mass=0.5),
    "mu(v)": dict(mu_static=0.08, mu_slow=0.04, mu_fast=0.11, rate_s_per_m=25.0, radius_m=2.0),
    "vertical n(t)": dict(mu_static=0.06, radius_m=2.0, vertical_g=0.5),
    "vertical with uplift and mu(v)": dict(mu_static=0.08, mu_slow=0.05, mu_fast=0.1, rate_s_per_m=20.0,
                                           radius_m=1.5, vertical_g=1.4),
}


@pytest.mark.parametrize("name", sorted(ENERGY_CASES))
def test_energy_balance(name):
    system = dict(ENERGY_CASES[name])
    t, ax, ay = synthetic_pair(seed=7)
    dt = t[1] - t[0]
    vertical_g = system.pop("vertical_g", None)
    az = None
    if vertical_g is not None:
        az = vertical_g * G * np.sin(2 * np.pi * 2.7 * t) * np.exp(-((t - 3.0) / 2.0) ** 2)
    r = simulate_pair(ax, ay, dt, az_m_s2=az, **system)
    assert r.status == 0, r.message
    assert r.energy_friction_J_per_kg > 0.1 * r.energy_input_J_per_kg
    assert abs(r.energy_balance_error_J_per_kg) <= 1e-9 * r.energy_input_J_per_kg
    history = r.energy_history_J_per_kg
    assert np.all(np.diff(history[1]) >= -1e-15) and np.all(np.diff(history[2]) >= -1e-15)
    if vertical_g is not None and vertical_g > 1.0:
        assert r.n_uplifts > 0 and r.uplift_time_s > 0.0
        assert "uplift" in r.event_names and "landing" in r.event_names


def _circular_steady_radius(amplitude, omega, mu, n, kappa, c):
    # radial: A cos φ = ρ(ω² − κ); tangential: A sin φ = µn + cρω  (relative orbit of radius ρ)
    d = (omega ** 2 - kappa) ** 2 + (c * omega) ** 2
    b = mu * n * c * omega
    return (-b + math.sqrt(b * b - d * ((mu * n) ** 2 - amplitude ** 2))) / d


def test_circular_ground_motion_converges_to_steady_circular_sliding():
    amplitude, omega, mu, radius, c = 0.3 * G, 2 * math.pi, 0.05, 2.0, 2.0
    rho = _circular_steady_radius(amplitude, omega, mu, G, G / radius, c)
    errors = []
    for dt in (2e-3, 1e-3):
        t = np.arange(0.0, 25.0, dt)
        r = simulate_pair(amplitude * np.cos(omega * t), amplitude * np.sin(omega * t), dt, mu_static=mu,
                          radius_m=radius, damping_per_mass=c)
        last = t > 20.0
        orbit = np.hypot(r.displacement_m[last, 0], r.displacement_m[last, 1])
        speed = np.hypot(r.velocity_m_s[last, 0], r.velocity_m_s[last, 1])
        errors.append(max(np.max(np.abs(orbit - rho)) / rho, np.max(np.abs(speed - rho * omega)) / (rho * omega)))
    # the piecewise-linear reading of the circle differs by O((ω dt)²): second-order convergence
    assert errors[1] < 1e-5
    assert errors[1] < errors[0] / 3.0


def _compare(ref, r, tol):
    scale = ref.peak_displacement_m
    assert _rel(r.peak_displacement_m, ref.peak_displacement_m) <= tol
    assert abs(r.residual_displacement_m - ref.residual_displacement_m) <= tol * scale
    assert _rel(r.peak_velocity_m_s, ref.peak_velocity_m_s) <= tol
    # the history within 10 tol: a break-away where |κX + a_g| grazes µs n is ill-conditioned
    # (its instant moves by ~1e-6 s for a 1e-12 change of X), a local, transient difference
    assert np.max(np.abs(r.displacement_m - ref.displacement_m)) <= 10 * tol * scale


def _pair_from(records_dir, folder, names, n_max=None):
    motions = [read_ground_motion(records_dir / "pairs" / folder / name) for name in names]
    n = min(m.npts for m in motions)
    if n_max:
        n = min(n, n_max)
    return motions[0].dt_s, [m.acceleration_m_s2[:n] for m in motions]


@pytest.mark.slow
def test_real_pair_against_the_reference(records_dir):
    dt, (ax, ay) = _pair_from(records_dir, "superstitionhills1987_PTS",
                              ["RSN723_SUPER.B_B-PTS225.AT2", "RSN723_SUPER.B_B-PTS315.AT2"], n_max=1000)
    t = dt * np.arange(ax.size)
    r = simulate_pair(ax, ay, dt, mu_static=0.06, radius_m=2.0)
    ref = reference_pair(t, ax, ay, mu_s=0.06, radius=2.0)
    # 10 s: the strong part, 13 stick-slip events (3.1–9.3 s); the 6 s after it is one long slide
    assert r.status == 0 and ref.n_stops > 5
    _compare(ref, r, 1e-9)


@pytest.mark.slow
def test_real_pair_with_vertical_against_the_reference(records_dir):
    dt, (ax, ay, az) = _pair_from(records_dir, "lomaprieta1989_APEEL2",
                                  ["np01002p_4225a_a.smc", "np01002p_4225c_a.smc", "np01002p_4225b_a.smc"],
                                  n_max=3000)
    t = dt * np.arange(ax.size)
    system = dict(mu_static=0.05, mu_kinetic=0.04, radius_m=1.5)
    r = simulate_pair(ax, ay, dt, az_m_s2=az, **system)
    ref = reference_pair(t, ax, ay, az, mu_s=0.05, mu_k=0.04, radius=1.5)
    assert r.status == 0 and r.model == "2d+vertical"
    _compare(ref, r, 1e-9)
    flat = simulate_pair(ax, ay, dt, **system)
    assert flat.peak_displacement_m != r.peak_displacement_m  # the vertical matters


def _hard_case(name):
    n, dt = 500, 0.01
    t = np.arange(n) * dt
    env = np.sin(np.pi * t / t[-1]) ** 2
    system = dict(mu_static=0.06, radius_m=2.0)
    az = None
    if name == "turning near zero velocity":
        # nearly collinear motion: the velocity passes close to zero while it turns
        ax = 0.3 * G * np.sin(2 * np.pi * 1.2 * t) * env
        ay = 0.004 * G * np.cos(2 * np.pi * 1.2 * t) * env
    elif name == "mu_s just above the PGA":
        ax = 0.3 * G * np.sin(2 * np.pi * 1.1 * t) * env
        ay = 0.2 * G * np.cos(2 * np.pi * 0.7 * t) * env
        pga = np.max(np.hypot(ax, ay))
        system = dict(mu_static=pga / G * (1 - 1e-3), mu_kinetic=pga / G * 0.9, radius_m=2.0)
    elif name == "chatter":
        # a stick–slip cycle in every period of a 25 Hz forcing that only just beats µs
        t = t[:40]  # 0.4 s, 10 cycles (the reference needs ~0.2 s per stop at rest, more at load): each one alike
        ax = 0.045 * G + 0.03 * G * np.sin(2 * np.pi * 25 * t)
        ay = 0.01 * G * np.cos(2 * np.pi * 25 * t)
        system = dict(mu_static=0.07, mu_kinetic=0.05, stiffness_per_mass=1.0)
    elif name == "uplift":
        ax = 0.3 * G * np.sin(2 * np.pi * 0.9 * t) * env
        ay = 0.25 * G * np.cos(2 * np.pi * 0.6 * t) * env
        az = 1.3 * G * np.sin(2 * np.pi * 3.1 * t) * env
    elif name == "mu_fast >> mu_slow":
        ax = 0.4 * G * np.sin(2 * np.pi * 0.9 * t) * env
        ay = 0.3 * G * np.cos(2 * np.pi * 0.6 * t) * env
        system = dict(mu_static=0.03, mu_slow=0.02, mu_fast=0.2, rate_s_per_m=40.0, radius_m=2.0)
    elif name == "starts above mu_s n":
        ax = 0.2 * G + 0.1 * G * np.sin(2 * np.pi * 0.9 * t)
        ay = -0.1 * G * np.cos(2 * np.pi * 0.6 * t)
    else:
        raise KeyError(name)
    return t, ax, ay, az, system


HARD = ["turning near zero velocity", "mu_s just above the PGA", "chatter", "uplift", "mu_fast >> mu_slow",
        "starts above mu_s n"]


@pytest.mark.parametrize("name", HARD)
def test_hard_cases_against_the_reference(name):
    t, ax, ay, az, system = _hard_case(name)
    r = simulate_pair(ax, ay, time_s=t, az_m_s2=az, **system)
    assert r.status == 0, r.message
    ref = reference_pair(t, ax, ay, az, mu_s=system["mu_static"], mu_k=system.get("mu_kinetic"),
                         radius=system.get("radius_m"), kappa=system.get("stiffness_per_mass", 0.0),
                         mu_slow=system.get("mu_slow"), mu_fast=system.get("mu_fast"),
                         rate=system.get("rate_s_per_m"))
    if ref.peak_displacement_m == 0.0:
        assert r.peak_displacement_m == 0.0 and r.n_events == 0
        return
    _compare(ref, r, 1e-9)
    if name == "uplift":
        assert r.n_uplifts > 0 and r.model == "2d+vertical"
    if name == "chatter":
        assert r.n_events >= 20  # a break-away and a stop in each of the 10 periods
    if name == "starts above mu_s n":
        assert r.event_time_s[0] == 0.0 and r.event_names[0] == "breakaway"


def test_below_static_friction_nothing_moves():
    t, ax, ay = synthetic_pair(pga_g=0.05)
    pga = float(np.max(np.hypot(ax, ay)))
    r = simulate_pair(ax, ay, time_s=t, mu_static=pga / G * (1 + 1e-9), radius_m=2.0)
    assert r.peak_displacement_m == 0.0 and r.n_events == 0 and r.slip_time_s == 0.0
    np.testing.assert_array_equal(r.absolute_acceleration_m_s2, np.column_stack((ax, ay)))


def test_non_uniform_sampling_is_the_piecewise_linear_signal():
    t, ax, ay = synthetic_pair(n=500)
    system = dict(mu_static=0.06, mu_kinetic=0.05, radius_m=2.0)
    uniform = simulate_pair(ax, ay, time_s=t, **system)
    # insert collinear points (the same piecewise-linear signal on a non-uniform grid)
    rng = np.random.default_rng(11)
    frac = rng.uniform(0.05, 0.95, t.size - 1)
    keep = rng.uniform(size=t.size - 1) < 0.5
    t_mid = t[:-1] + frac * np.diff(t)
    t2 = np.sort(np.concatenate((t, t_mid[keep])))
    ax2, ay2 = np.interp(t2, t, ax), np.interp(t2, t, ay)
    fine = simulate_pair(ax2, ay2, time_s=t2, **system)
    original = np.isin(t2, t)
    scale = uniform.peak_displacement_m
    assert np.max(np.abs(fine.displacement_m[original] - uniform.displacement_m)) <= 1e-9 * scale
    assert _rel(fine.peak_displacement_m, uniform.peak_displacement_m) <= 1e-9
    # and a genuinely non-uniform record against the reference
    ref = reference_pair(t2, ax2 * (1 + 0.3 * np.sin(t2)), ay2, mu_s=0.06, mu_k=0.05, radius=2.0)
    r = simulate_pair(ax2 * (1 + 0.3 * np.sin(t2)), ay2, time_s=t2, **system)
    _compare(ref, r, 1e-9)


@pytest.mark.parametrize("kwargs, word", [
    (dict(mu_static=-0.1), "mu_static"),
    (dict(mu_static=0.05, mu_kinetic=0.06), "mu_kinetic"),
    (dict(mu_static=0.05, mu_slow=0.03, mu_fast=0.06), "rate_s_per_m"),
    (dict(mu_static=0.05, mu_slow=0.07, mu_fast=0.06, rate_s_per_m=1.0), "mu_slow"),
    (dict(mu_static=0.05, mu_slow=0.06, mu_fast=0.08, rate_s_per_m=1.0), "mu_static"),
    (dict(mu_static=0.05, mu_kinetic=0.04, mu_slow=0.03, mu_fast=0.06, rate_s_per_m=1.0), "mu_kinetic"),
    (dict(mu_static=0.05, radius_m=0.0), "radius_m"),
    (dict(mu_static=0.05, radius_m=2.0, stiffness_per_mass=1.0), "radius_m"),
    (dict(mu_static=0.05, damping_per_mass=float("nan")), "damping_per_mass"),
    (dict(mu_static=0.05, rate_s_per_m=float("inf"), mu_slow=0.01, mu_fast=0.02), "rate_s_per_m"),
])
def test_invalid_parameters_raise_a_typed_error_naming_the_parameter(kwargs, word):
    with pytest.raises(InvalidSystemError, match=word):
        simulate_pair(np.zeros(3), np.zeros(3), 0.01, **kwargs)
    assert issubclass(InvalidSystemError, ValueError)


def test_invalid_records_raise_record_errors():
    with pytest.raises(RecordInputError, match="ay_m_s2"):
        simulate_pair(np.zeros(5), np.zeros(4), 0.01, mu_static=0.05)
    with pytest.raises(RecordInputError, match="az_m_s2"):
        simulate_pair(np.zeros(5), np.zeros(5), 0.01, az_m_s2=np.full(5, np.nan), mu_static=0.05)
    with pytest.raises(RecordInputError, match="increasing"):
        simulate_pair(np.zeros(3), np.zeros(3), time_s=[0.0, 0.02, 0.01], mu_static=0.05)


@pytest.mark.parametrize("bad", ["ax_m_s2", "ay_m_s2", "az_m_s2"])
@pytest.mark.parametrize("value", [np.nan, np.inf, -np.inf])
def test_a_non_finite_sample_is_named_by_its_component(bad, value):
    # one pass over the record finds it (scan_record); the error names the array that holds it
    arrays = {name: np.zeros(6) for name in ("ax_m_s2", "ay_m_s2", "az_m_s2")}
    arrays[bad][4] = value
    with pytest.raises(RecordInputError, match=f"{bad} holds NaN or infinite values"):
        simulate_pair(arrays["ax_m_s2"], arrays["ay_m_s2"], 0.01, az_m_s2=arrays["az_m_s2"], mu_static=0.05)


def test_the_record_scan_gives_the_pga_the_largest_normal_force_and_whether_a_y_moves():
    ax = np.array([0.0, 3.0, -1.0, 0.5])
    ay = np.array([0.0, 0.0, -4.0, 0.0])
    nz = np.array([9.0, 10.5, 8.0, 9.5])
    assert scan_record(ax, ay, nz) == (True, 17.0, 10.5, True)
    assert scan_record(ax, np.zeros(4), nz)[3] is False
    assert scan_record(ax, ay, np.array([9.0, np.nan, 8.0, 9.5]))[0] is False


def test_frequent_uplift_keeps_the_energy_balance_and_pairs_uplifts_with_landings():
    # n = g + a_z crosses zero hundreds of times, also inside approach-to-stop steps
    rng = np.random.default_rng(0)
    n = 2000
    ax, ay, az = rng.standard_normal(n), rng.standard_normal(n), 15.0 * rng.standard_normal(n)
    r = simulate_pair(ax, ay, 0.01, az_m_s2=az, mu_static=0.05, radius_m=2.0)
    assert r.status == 0 and r.n_uplifts > 100
    assert abs(r.energy_balance_error_J_per_kg) <= 1e-9 * r.energy_input_J_per_kg
    names = r.event_names
    assert names.count("uplift") == r.n_uplifts
    assert abs(names.count("landing") - names.count("uplift")) <= 1
    # every uplift instant is where n = 0 on the piecewise-linear vertical record
    nz = G + az
    for time in r.event_time_s[np.array(names) == "uplift"][:50]:
        i = min(int(time / 0.01), n - 2)
        frac = time / 0.01 - i
        assert abs(nz[i] + frac * (nz[i + 1] - nz[i])) <= 1e-9 * G


def test_stiff_coarsely_sampled_spring_converges():
    # ω dt = 10 and ~1 000 stick–slip events: the slow-speed hand-over scales with 1/ω, not dt
    rng = np.random.default_rng(0)
    rng.standard_normal(8000)
    ax, ay = 5.0 * rng.standard_normal(2000), 5.0 * rng.standard_normal(2000)
    system = dict(mu_static=0.05, stiffness_per_mass=1e6, damping_per_mass=10.0)
    loose = simulate_pair(ax, ay, 0.01, **system)
    tight = simulate_pair(ax, ay, 0.01, rtol=1e-14, **system)
    assert loose.status == 0 and loose.n_events > 100
    assert _rel(loose.peak_displacement_m, tight.peak_displacement_m) <= 1e-8
    assert abs(loose.residual_displacement_m - tight.residual_displacement_m) <= 1e-8 * tight.peak_displacement_m


def test_slaved_direction_lag_matches_a_steadily_turning_force():
    # independent truth: the Cartesian motion V' = F(t) − fr V/|V| from rest under a force of
    # constant magnitude turning at ω (solve_ivp Radau, tight); the START form's slaved direction
    # must trail F by the same angle.  The first-order lag ω r/|F| is 50 % off here (r grows).
    from scipy.integrate import solve_ivp

    from isolator.solver.planar_rk import start_direction

    phi, fr, omega = 1.0, 0.5, 2.0

    def rhs(t, v):
        r = math.hypot(v[0], v[1])
        return [phi * math.cos(omega * t) - fr * v[0] / r, phi * math.sin(omega * t) - fr * v[1] / r]

    t0 = 1e-6
    for t1, tol in ((0.002, 1e-6), (0.01, 2e-5)):
        v = solve_ivp(rhs, (t0, t1), [(phi - fr) * t0, 0.0], method="Radau", rtol=1e-12, atol=1e-18).y[:, -1]
        r = math.hypot(v[0], v[1])
        fx, fy = phi * math.cos(omega * t1), phi * math.sin(omega * t1)
        true_lag = math.atan2(fx * v[1] - fy * v[0], fx * v[0] + fy * v[1])
        # frc: a_g = −F linear in time with a_g' = −F'
        frc = np.array([-fx, omega * fy, -fy, -omega * fx, G, 0.0, 1.0])
        e1, e2 = start_direction(r, 0.0, 0.0, fx, fy, 0.0, 0.0, frc, fr, 0.0)
        lag = math.atan2(fx * e2 - fy * e1, fx * e1 + fy * e2)
        assert true_lag < 0.0
        assert abs(lag - true_lag) <= tol * abs(true_lag)
        assert abs(-omega * r / phi - true_lag) > 0.4 * abs(true_lag)  # the first-order lag would fail
