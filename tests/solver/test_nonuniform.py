"""Non-uniform sampling: a time column with unequal steps is the same piecewise-linear record.

Two independent truths: (1) inserting samples on the straight line between two samples
does not change the signal, so the response at the original samples must not change;
(2) the reference integrator of tests/reference.py (solve_ivp restarted at every sample,
each interval its own slope) on a genuinely non-uniform record.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from isolator.solver.record import simulate_record
from tests.reference import reference_record

G = 9.80665

SYSTEMS = {
    "friction only": dict(mu_static=0.06),
    "pendulum model 2": dict(mu_static=0.06, mu_kinetic=0.042, stiffness_per_mass=4.9),
    "damped pendulum": dict(mu_static=0.06, stiffness_per_mass=4.9, damping_per_mass=0.9),
    # stiff enough that a 0.01 s interval is split into sub-steps (ω_d dt > π/2)
    "stiff": dict(mu_static=0.05, stiffness_per_mass=4.0e4, damping_per_mass=20.0),
}


def synthetic_record(n=1200, dt=0.01, pga_g=0.4, seed=3):
    rng = np.random.default_rng(seed)
    t = np.arange(n) * dt
    envelope = np.exp(-((t - 0.4 * n * dt) / (0.27 * n * dt)) ** 2)
    return pga_g * G * np.sin(2 * np.pi * 0.8 * t) * envelope + 0.5 * rng.standard_normal(n) * envelope, dt


def with_collinear_samples(acc, dt, seed=0):
    """The same signal with 0–3 extra samples on the line inside each interval; index of the originals."""
    rng = np.random.default_rng(seed)
    times, values, original = [], [], []
    for i in range(acc.size - 1):
        original.append(len(times))
        times.append(i * dt)
        values.append(acc[i])
        for u in np.sort(rng.uniform(0.05, 0.95, rng.integers(0, 4))):
            times.append((i + u) * dt)
            values.append(acc[i] + u * (acc[i + 1] - acc[i]))
    original.append(len(times))
    times.append((acc.size - 1) * dt)
    values.append(acc[-1])
    return np.array(values), np.array(times), np.array(original)


@pytest.mark.parametrize("name", list(SYSTEMS))
def test_collinear_samples_change_nothing(name):
    acc, dt = synthetic_record()
    uniform = simulate_record(acc, dt, **SYSTEMS[name])
    values, times, original = with_collinear_samples(acc, dt)
    assert np.ptp(np.diff(times)) > 0.5 * dt  # truly non-uniform
    dense = simulate_record(values, time_s=times, **SYSTEMS[name])
    scale = uniform.peak_displacement_m
    assert uniform.n_events > 10
    np.testing.assert_allclose(dense.time_s, times, rtol=0, atol=0)
    np.testing.assert_allclose(dense.displacement_m[original], uniform.displacement_m, rtol=0, atol=1e-12 * scale)
    np.testing.assert_allclose(dense.velocity_m_s[original], uniform.velocity_m_s, rtol=0,
                               atol=1e-12 * uniform.peak_velocity_m_s)
    assert dense.n_events == uniform.n_events
    np.testing.assert_allclose(dense.event_time_s, uniform.event_time_s, rtol=0, atol=1e-12 * acc.size * dt)
    for key in ("peak_displacement_m", "residual_displacement_m", "peak_velocity_m_s", "slip_time_s",
                "peak_transmitted_acceleration_m_s2", "energy_input_J_per_kg", "energy_friction_J_per_kg",
                "energy_viscous_J_per_kg"):
        ours, theirs = getattr(dense, key), getattr(uniform, key)
        assert ours == pytest.approx(theirs, rel=1e-12, abs=1e-12 * max(abs(theirs), scale)), key
    scale_e = max(dense.energy_input_J_per_kg, 1e-300)
    assert abs(dense.energy_balance_error_J_per_kg) <= 1e-10 * scale_e


def decimated_real_record(records_dir, n_keep=700, seed=5):
    """A real record made non-uniform: samples dropped at random (steps of 1 to 4 dt)."""
    from isolator.motion import read_ground_motion

    motion = read_ground_motion(records_dir / "at2" / "RSN1044_NORTHR_NWH360.AT2")
    rng = np.random.default_rng(seed)
    index = np.concatenate([[0], np.cumsum(rng.integers(1, 5, n_keep - 1))])
    index = index[index < motion.npts]
    return motion.acceleration_m_s2[index], motion.time_s[index]


@pytest.mark.parametrize("name", ["friction only", "pendulum model 2", "damped pendulum"])
def test_non_uniform_real_record_against_reference(records_dir, name):
    acc, times = decimated_real_record(records_dir)
    system = SYSTEMS[name]
    ours = simulate_record(acc, time_s=times, **system)
    ref = reference_record(acc, None, time_s=times, max_step_s=0.005, **system)
    scale = float(np.max(np.abs(ref["displacement_m"])))
    assert scale > 0.01 and ours.n_events > 10
    np.testing.assert_allclose(ours.displacement_m, ref["displacement_m"], rtol=0, atol=1e-8 * scale)
    assert ours.slip_time_s == pytest.approx(ref["slip_time_s"], rel=1e-7)
    assert ours.peak_displacement_m == pytest.approx(ref["peak_displacement_m"], rel=1e-7)
    assert ours.n_events == len(ref["events"])
    assert abs(ours.energy_balance_error_J_per_kg) <= 1e-9 * ours.energy_input_J_per_kg


def test_start_time_is_kept_and_steps_equal_to_rounding_take_the_uniform_path():
    acc, dt = synthetic_record(n=300)
    times = 12.5 + dt * np.arange(acc.size)  # equal steps up to the rounding of 12.5 + k dt
    shifted = simulate_record(acc, time_s=times, mu_static=0.06, stiffness_per_mass=4.9)
    plain = simulate_record(acc, dt, mu_static=0.06, stiffness_per_mass=4.9)
    assert shifted.time_s[0] == 12.5
    assert shifted.event_time_s[0] == pytest.approx(plain.event_time_s[0] + 12.5, abs=1e-9)
    assert math.isclose(shifted.peak_displacement_m, plain.peak_displacement_m, rel_tol=1e-9)


@pytest.mark.parametrize("name", list(SYSTEMS))
def test_non_uniform_record_equals_its_uniform_refinement(records_dir, name):
    # the decimated record's times lie on the original 0.02 s grid: its linear
    # interpolation onto that grid is the same signal, solved on the uniform path
    acc, times = decimated_real_record(records_dir)
    grid = 0.02 * np.arange(int(round(times[-1] / 0.02)) + 1)
    refined = simulate_record(np.interp(grid, times, acc), 0.02, **SYSTEMS[name])
    ours = simulate_record(acc, time_s=times, **SYSTEMS[name])
    index = np.round(times / 0.02).astype(int)
    np.testing.assert_allclose(ours.displacement_m, refined.displacement_m[index], rtol=0,
                               atol=1e-12 * refined.peak_displacement_m)
    assert ours.n_events == refined.n_events
    assert ours.peak_displacement_m == pytest.approx(refined.peak_displacement_m, rel=1e-12)


def test_linear_spectrum_of_collinear_samples_is_unchanged():
    from isolator.solver.linear import pseudo_acceleration_spectrum

    acc, dt = synthetic_record(n=800)
    values, times, _ = with_collinear_samples(acc, dt, seed=2)
    periods = np.array([0.02, 0.1, 0.5, 2.0])
    uniform = pseudo_acceleration_spectrum(acc, dt, periods)
    dense = pseudo_acceleration_spectrum(values, float(np.mean(np.diff(times))), periods, time_s=times)
    np.testing.assert_allclose(dense, uniform, rtol=1e-12)


def test_simulate_motion_keeps_a_non_uniform_single_component_on_the_exact_kernel():
    from isolator.solver.models import simulate_motion

    acc, dt = synthetic_record(n=400)
    values, times, original = with_collinear_samples(acc, dt, seed=7)
    result = simulate_motion(values, time_s=times, mu_static=0.06, radius_m=2.0)
    assert result.model == "1d-exact"
    reference = simulate_record(acc, dt, mu_static=0.06, stiffness_per_mass=G / 2.0)
    np.testing.assert_allclose(result.displacement_m[original], reference.displacement_m, rtol=0,
                               atol=1e-12 * reference.peak_displacement_m)
