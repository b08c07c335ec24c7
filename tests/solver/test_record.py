"""The exact record solver against an independent reference, invariances and energy.

The reference is tests/reference.py: scipy solve_ivp (DOP853, rtol 1e-12) with event
location, restarted at every sample, written without looking at the solver.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from isolator.solver.events import BREAKAWAY, REVERSAL, STICK
from isolator.solver.harmonic import harmonic_response
from isolator.solver.record import RecordInputError, simulate_record
from isolator.solver.system import InvalidSystemError, System
from tests.reference import reference_record

G = 9.80665
CRITICAL = 2.0 * math.sqrt(4.9)


def synthetic_record(n=1500, dt=0.01, pga_g=0.4, seed=1):
    """A pulse-like record with broadband noise: sticks, slips and reversals."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) * dt
    envelope = np.exp(-((t - 0.4 * n * dt) / (0.27 * n * dt)) ** 2)
    acc = pga_g * G * np.sin(2 * np.pi * 0.8 * t) * envelope + 0.5 * rng.standard_normal(n) * envelope
    return acc, dt


SYSTEMS = {
    "1 friction only": dict(mu_static=0.06),
    "1 model 2": dict(mu_static=0.06, mu_kinetic=0.042),
    "2 damper": dict(mu_static=0.10, mu_kinetic=0.07, damping_per_mass=2.0),
    "3 pendulum": dict(mu_static=0.06, stiffness_per_mass=4.9),
    "3 pendulum model 2": dict(mu_static=0.06, mu_kinetic=0.042, stiffness_per_mass=4.9),
    "4a under-damped": dict(mu_static=0.06, stiffness_per_mass=4.9, damping_per_mass=0.3),
    "4b critical": dict(mu_static=0.05, stiffness_per_mass=4.9, damping_per_mass=CRITICAL),
    "4b critical + 1e-12": dict(mu_static=0.05, stiffness_per_mass=4.9, damping_per_mass=CRITICAL * (1 + 1e-12)),
    "4c over-damped": dict(mu_static=0.05, stiffness_per_mass=4.9, damping_per_mass=20.0),
    "vanishing k and eta": dict(mu_static=0.06, stiffness_per_mass=1e-12, damping_per_mass=1e-9),
}


@pytest.mark.parametrize("name", list(SYSTEMS))
def test_agrees_with_independent_reference(name):
    acc, dt = synthetic_record()
    params = SYSTEMS[name]
    ours = simulate_record(acc, dt, **params)
    ref = reference_record(acc, dt, **params)
    scale = max(ours.peak_displacement_m, 1e-3)
    assert np.max(np.abs(ours.displacement_m - ref["displacement_m"])) <= 1e-9 * scale
    assert np.max(np.abs(ours.velocity_m_s - ref["velocity_m_s"])) <= 1e-9 * max(ours.peak_velocity_m_s, 1e-3)
    assert ours.n_events == len(ref["events"])
    ref_times = np.array([t for t, _ in ref["events"]])
    assert np.max(np.abs(ours.event_time_s - ref_times)) <= 1e-9
    assert ours.slip_time_s == pytest.approx(ref["slip_time_s"], abs=1e-9)
    assert ours.peak_displacement_m == pytest.approx(ref["peak_displacement_m"], rel=1e-9)
    assert ours.status == 0


def test_real_record_agrees_with_reference(records_dir):
    from isolator.motion import read_ground_motion

    motion = read_ground_motion(records_dir / "at2" / "RSN1044_NORTHR_NWH360.AT2")
    design = dict(mu_static=0.06, stiffness_per_mass=G / 2.0, damping_per_mass=0.3)
    ours = simulate_record(motion.acceleration_m_s2, motion.dt_s, **design)
    ref = reference_record(motion.acceleration_m_s2, motion.dt_s, **design)
    assert np.max(np.abs(ours.displacement_m - ref["displacement_m"])) <= 1e-9 * ours.peak_displacement_m
    assert ours.n_events == len(ref["events"])
    assert ours.residual_displacement_m == pytest.approx(ref["residual_displacement_m"], abs=1e-10)


def test_energy_balance_on_every_real_record(records_dir):
    from isolator.motion import read_ground_motion

    for path in sorted((records_dir / "at2").iterdir()):
        motion = read_ground_motion(path)
        for damping in (0.0, 0.6):
            r = simulate_record(motion.acceleration_m_s2, motion.dt_s, mu_static=0.05, mu_kinetic=0.04,
                                stiffness_per_mass=G / 2.5, damping_per_mass=damping)
            assert r.energy_input_J_per_kg > 0.0
            assert abs(r.energy_balance_error_J_per_kg) <= 1e-10 * r.energy_input_J_per_kg, path.name


@pytest.mark.parametrize("name", ["1 model 2", "4a under-damped", "4c over-damped"])
def test_mirrored_record_gives_mirrored_response(name):
    acc, dt = synthetic_record(seed=3)
    up = simulate_record(acc, dt, **SYSTEMS[name])
    down = simulate_record(-acc, dt, **SYSTEMS[name])
    assert np.allclose(down.displacement_m, -up.displacement_m, rtol=0, atol=1e-13)
    assert np.allclose(down.velocity_m_s, -up.velocity_m_s, rtol=0, atol=1e-13)
    assert np.array_equal(down.event_kind, up.event_kind)
    assert down.peak_displacement_m == pytest.approx(up.peak_displacement_m, rel=1e-12)


@pytest.mark.parametrize("name", ["3 pendulum", "4a under-damped"])
def test_doubling_the_sampling_of_a_linear_record_changes_nothing(name):
    acc, dt = synthetic_record(n=800, seed=5)
    fine = np.empty(2 * acc.size - 1)
    fine[0::2] = acc
    fine[1::2] = 0.5 * (acc[:-1] + acc[1:])  # the same piecewise-linear signal
    coarse_r = simulate_record(acc, dt, **SYSTEMS[name])
    fine_r = simulate_record(fine, dt / 2, **SYSTEMS[name])
    assert np.max(np.abs(fine_r.displacement_m[0::2] - coarse_r.displacement_m)) <= 1e-12
    assert fine_r.n_events == coarse_r.n_events
    assert np.max(np.abs(fine_r.event_time_s - coarse_r.event_time_s)) <= 1e-10
    assert fine_r.energy_input_J_per_kg == pytest.approx(coarse_r.energy_input_J_per_kg, rel=1e-11)


def test_sampled_sine_converges_to_the_harmonic_solver():
    """A sampled harmonic record reproduces the paper's closed-form response, at O(dt²)."""
    alpha, k, eta, mu_s = 2.0, 0.5, 0.3, 0.25
    exact = harmonic_response(alpha, k, eta, mu_s)
    omega = exact.omega
    period = 2 * math.pi / omega
    n_periods = 30
    errors = []
    for per_period in (50, 100, 200):
        dt = period / per_period
        t = np.arange(n_periods * per_period + 1) * dt
        acc = omega ** 2 * np.cos(omega * t + math.pi / 2)  # Eq. 2 with g = 1 (dimensionless)
        r = simulate_record(acc, dt, mu_static=mu_s, stiffness_per_mass=k, damping_per_mass=eta, gravity_m_s2=1.0)
        last = r.displacement_m[-per_period - 1:]
        truth = np.interp(np.linspace(0, period, per_period + 1), exact.cycle_time, exact.cycle_x)
        errors.append(np.max(np.abs(last - truth)))
    assert errors[2] < 1e-3 * exact.amplitude
    # first-order hold: the error falls like dt² (a factor ~4 per halving)
    assert errors[0] / errors[1] > 3.0 and errors[1] / errors[2] > 3.0


def test_no_motion_below_the_static_threshold():
    acc, dt = synthetic_record(pga_g=0.05)
    acc = acc * (0.0999 * G / np.max(np.abs(acc)))
    r = simulate_record(acc, dt, mu_static=0.1)
    assert r.n_events == 0 and r.peak_displacement_m == 0.0 and r.slip_time_s == 0.0
    assert np.array_equal(r.absolute_acceleration_m_s2, acc)  # the mass moves with the ground


def test_events_obey_the_friction_law():
    acc, dt = synthetic_record(seed=7)
    system = System(mu_static=0.06, mu_kinetic=0.042, stiffness_per_mass=4.9, damping_per_mass=0.3)
    r = simulate_record(acc, dt, system=system)
    a_at = np.interp(r.event_time_s, r.time_s, acc)
    force = system.stiffness_per_mass * r.event_displacement_m + a_at
    limit = system.static_friction_m_s2
    stick = r.event_kind == STICK
    assert np.all(np.abs(force[stick]) <= limit * (1 + 1e-12))
    assert np.all(np.abs(force[r.event_kind == REVERSAL]) > limit)
    assert np.allclose(np.abs(force[r.event_kind == BREAKAWAY]), limit, rtol=1e-9)
    assert np.all(np.diff(r.event_time_s) >= 0.0)


def test_long_chatter_terminates():
    # model 2 friction on a long noisy record at the edge of the static threshold
    rng = np.random.default_rng(11)
    acc = 0.06 * G * (1.0 + 0.2 * rng.standard_normal(200_000)) * np.sign(np.sin(np.arange(200_000) * 0.05))
    r = simulate_record(acc, 0.005, mu_static=0.06, mu_kinetic=0.042, stiffness_per_mass=4.9)
    assert r.status == 0 and np.all(np.isfinite(r.displacement_m)) and r.n_events > 1000
    assert abs(r.energy_balance_error_J_per_kg) <= 1e-9 * r.energy_input_J_per_kg


@pytest.mark.parametrize("bad, message", [
    (dict(acceleration_m_s2=[0.0]), "at least two samples"),
    (dict(acceleration_m_s2=[0.0, float("nan")]), "NaN"),
    (dict(acceleration_m_s2=[0.0, 1.0], dt_s=0.0), "dt"),
    (dict(acceleration_m_s2=[0.0, 1.0], time_s=[0.0, 0.0]), "increasing"),
])
def test_bad_input_is_refused_with_a_reason(bad, message):
    kwargs = {"dt_s": 0.01, **bad}
    with pytest.raises(RecordInputError, match=message):
        simulate_record(mu_static=0.1, **kwargs)


@pytest.mark.parametrize("params, key", [
    (dict(mu_static=-0.1), "mu_static"), (dict(mu_static=0.1, mu_kinetic=0.2), "mu_kinetic"),
    (dict(mu_static=0.1, stiffness_per_mass=float("inf")), "stiffness_per_mass"),
    (dict(mu_static=0.1, damping_per_mass=-1.0), "damping_per_mass"),
    (dict(mu_static=0.1, gravity_m_s2=0.0), "gravity"),
])
def test_invalid_system_names_the_parameter(params, key):
    with pytest.raises(InvalidSystemError, match=key):
        System(**params)


@pytest.mark.parametrize("damping, stiffness, config", [
    (0.0, 0.0, "1"), (0.5, 0.0, "2"), (0.0, 2.0, "3"), (1.0, 2.0, "4a"), (2.0, 1.0, "4b"), (3.0, 1.0, "4c")])
def test_configuration(damping, stiffness, config):
    assert System(mu_static=0.1, damping_per_mass=damping, stiffness_per_mass=stiffness).configuration == config


@pytest.mark.parametrize("params", [
    dict(mu_static=0.06, stiffness_per_mass=1e6),  # period 6 ms, below dt: sub-steps
    dict(mu_static=0.06, stiffness_per_mass=1e6, damping_per_mass=50.0),
    dict(mu_static=0.06, stiffness_per_mass=4.9, damping_per_mass=1e4),  # exponent 100 per sample
])
def test_stiff_and_heavily_damped_systems(params):
    acc, dt = synthetic_record(n=400)
    ours = simulate_record(acc, dt, **params)
    # the displacements are micrometres here: the reference needs an absolute tolerance to match
    ref = reference_record(acc, dt, rtol=1e-13, atol=1e-17, **params)
    assert np.max(np.abs(ours.displacement_m - ref["displacement_m"])) <= 1e-9 * ours.peak_displacement_m
    assert abs(ours.energy_balance_error_J_per_kg) <= 1e-12 * ours.energy_input_J_per_kg
    # a grazing touch (V tangent to zero) may be counted as a stop here and not by the reference,
    # so events are compared through the trajectory, not their number


def test_energy_history_balances_at_every_sample():
    acc, dt = synthetic_record(seed=13)
    params = SYSTEMS["4a under-damped"]
    r = simulate_record(acc, dt, **params)
    e_in, e_f, e_v = r.energy_history_J_per_kg
    stored = 0.5 * r.velocity_m_s ** 2 + 0.5 * params["stiffness_per_mass"] * r.displacement_m ** 2
    assert np.max(np.abs(e_in - e_f - e_v - stored)) <= 1e-12 * r.energy_input_J_per_kg
    assert np.all(np.diff(e_f) >= 0.0) and np.all(np.diff(e_v) >= -1e-18)
    assert e_in[-1] == r.energy_input_J_per_kg and e_f[-1] == r.energy_friction_J_per_kg


def test_a_record_that_starts_beyond_the_static_window_slides_from_t_0():
    """A record whose first sample already exceeds µs g, and whose second is back inside the window, slides from
    t = 0 (before, the first interval was taken as stuck because only its end was tested).  Closed form, no spring:
    a_g = 3 − 25 t on [0, 0.1] s, then 0.5 m/s² (< µ g); sliding backwards, x'' = −a_g + µ g."""
    mu, dt = 0.1, 0.1
    r = simulate_record(np.array([3.0, 0.5, 0.5, 0.5]), dt_s=dt, mu_static=mu, mu_kinetic=mu)
    mg = mu * G
    v1 = -(3.0 * dt - 12.5 * dt**2) + mg * dt  # at the end of the first interval
    x1 = -(1.5 * dt**2 - 12.5 / 3.0 * dt**3) + 0.5 * mg * dt**2
    decel = -0.5 + mg  # x'' in the second interval (V < 0, so friction pushes +)
    t_stop = dt - v1 / decel
    x_end = x1 - v1**2 / (2.0 * decel)
    assert r.displacement_m[1] == pytest.approx(x1, rel=1e-12)
    assert r.velocity_m_s[1] == pytest.approx(v1, rel=1e-12)
    assert r.displacement_m[3] == pytest.approx(x_end, rel=1e-12) and r.velocity_m_s[3] == 0.0
    assert r.event_names[:2] == ["breakaway", "stick"]
    assert r.event_time_s[0] == 0.0 and r.event_time_s[1] == pytest.approx(t_stop, abs=1e-15)
