"""Property-based tests of the exact solver over random systems and random records.

* energy balance: input = kinetic + potential + friction + viscous (records) and
  ∆e_f + ∆e_v + ∆w_i = 0 per period (harmonic, Eq. 8);
* mirror symmetry: the ground motion -a_g gives exactly -X (records), and the phase
  φ + π gives the same A and ζ (harmonic);
* agreement with the independent reference integrator (``tests/reference.py``).

``max_examples`` is kept modest and ``deadline`` off so that the suite stays fast on a
shared 2-core machine.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from isolator.solver.harmonic import harmonic_response
from isolator.solver.record import simulate_record
from tests.reference import reference_record

G = 9.80665  # [m/s²]
FAST = settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
WITH_REFERENCE = settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@st.composite
def systems(draw):
    """A random isolator per unit mass: µs, µk ≤ µs, κ [1/s²] and c [1/s], zeros included."""
    mu_s = draw(st.floats(0.02, 0.4))
    mu_k = mu_s * draw(st.sampled_from([1.0, 0.7]) | st.floats(0.0, 1.0))
    stiffness = draw(st.sampled_from([0.0]) | st.floats(0.05, 200.0))
    damping = draw(st.sampled_from([0.0]) | st.floats(0.01, 50.0))
    if draw(st.booleans()) and stiffness > 0.0:
        damping = 2.0 * math.sqrt(stiffness)  # critical damping, exactly as computed
    return dict(mu_static=mu_s, mu_kinetic=mu_k, stiffness_per_mass=stiffness, damping_per_mass=damping)


@st.composite
def records(draw, max_samples=400, smooth=False):
    """A random record [m/s²] starting from zero: smoothed noise, pulses or a sine; and its dt [s].

    ``smooth`` keeps to sines: the reference integrator steps over pairs of stops that a
    rough record packs into one of its steps (see test_record_agrees_with_fine_implicit_euler).
    """
    n = draw(st.integers(20, max_samples))
    dt = draw(st.sampled_from([0.001, 0.005, 0.01, 0.02]))
    seed = draw(st.integers(0, 2 ** 32 - 1))
    rng = np.random.default_rng(seed)
    shape = draw(st.sampled_from(["sine"] if smooth else ["noise", "pulses", "sine"]))
    if shape == "noise":
        width = draw(st.integers(8, 20) if smooth else st.integers(1, 10))
        acc = np.convolve(rng.standard_normal(n), np.ones(width) / width, mode="same")
    elif shape == "pulses":
        acc = np.where(rng.random(n) < 0.05, rng.standard_normal(n) * 5.0, 0.0)
    else:
        acc = np.sin(2 * np.pi * rng.uniform(0.2, 5.0) * dt * np.arange(n))
    peak_g = draw(st.floats(0.01, 2.0))
    scale = np.max(np.abs(acc))
    acc = acc * (peak_g * G / scale) if scale > 0 else acc
    acc[0] = 0.0  # a record starts at rest (see test_hard_cases::test_breakaway_at_time_zero_by_a_jump)
    return acc, dt


def energy_scale(response) -> float:
    """The largest energy term [J/kg] (the balance is checked relative to it)."""
    return max(response.energy_input_J_per_kg, response.energy_friction_J_per_kg, response.energy_viscous_J_per_kg,
               response.energy_kinetic_final_J_per_kg, response.energy_potential_final_J_per_kg)


def well_conditioned(ours, acc, dt, system) -> bool:
    """False where the net force at a stop, or at a sample, is within rounding of µs g:
    there stick and slip are equally right (with µk < µs an exceedance of one ulp at one
    instant starts a finite slide), and two correct solvers may part ways.  (At a
    break-away the force is µs g by definition: only stops count among the events.)"""
    stops = ours.event_kind != 0
    force = np.concatenate([
        system["stiffness_per_mass"] * ours.event_displacement_m[stops]
        + np.interp(ours.event_time_s[stops], dt * np.arange(acc.size), acc),
        system["stiffness_per_mass"] * ours.displacement_m + acc])
    threshold = system["mu_static"] * G
    return bool(np.all(np.abs(np.abs(force) - threshold) > 1e-9 * threshold))


@FAST
@given(system=systems(), record=records())
def test_record_energy_balance(system, record):
    acc, dt = record
    response = simulate_record(acc, dt, **system)
    assert np.all(np.isfinite(response.displacement_m)) and np.all(np.isfinite(response.velocity_m_s))
    # rounding floor: (max|a_g| × duration)² is the record's natural energy scale [J/kg]
    floor = 1e-13 * (float(np.max(np.abs(acc))) * dt * acc.size) ** 2
    assert abs(response.energy_balance_error_J_per_kg) <= 1e-7 * energy_scale(response) + floor
    assert response.energy_friction_J_per_kg >= 0.0 and response.energy_viscous_J_per_kg >= 0.0
    assert 0.0 <= response.slip_time_s <= dt * (acc.size - 1) * (1 + 1e-12)
    assert response.peak_displacement_m >= np.max(np.abs(response.displacement_m))


@FAST
@given(system=systems(), record=records())
def test_record_mirror_symmetry(system, record):
    acc, dt = record
    forward = simulate_record(acc, dt, **system)
    mirrored = simulate_record(-acc, dt, **system)
    scale = max(forward.peak_displacement_m, 1e-300)
    np.testing.assert_allclose(mirrored.displacement_m, -forward.displacement_m, rtol=0, atol=1e-12 * scale)
    np.testing.assert_array_equal(mirrored.event_kind, forward.event_kind)
    assert mirrored.slip_time_s == pytest.approx(forward.slip_time_s, rel=1e-12, abs=1e-15)
    assert mirrored.peak_displacement_m == pytest.approx(forward.peak_displacement_m, rel=1e-12, abs=1e-300)


@WITH_REFERENCE
@given(system=systems(), record=records(max_samples=120, smooth=True))
def test_record_agrees_with_reference(system, record):
    # near-free sliding (µk < 0.1 µs) is left out: the reference then steps over pairs of
    # stops (test_hard_cases::test_reference_free_sliding); the implicit-Euler check covers it
    assume(system["mu_kinetic"] >= 0.1 * system["mu_static"])
    acc, dt = record
    ours = simulate_record(acc, dt, **system)
    assume(well_conditioned(ours, acc, dt, system))
    ref = reference_record(acc, dt, **system)
    # rounding floor: a grazing touch of µs g may move the reference by ~1e-50 m
    floor = 1e-12 * float(np.max(np.abs(acc))) * (dt * acc.size) ** 2
    scale = float(np.max(np.abs(ref["displacement_m"])))
    np.testing.assert_allclose(ours.displacement_m, ref["displacement_m"], rtol=0, atol=1e-7 * scale + floor)
    assert ours.slip_time_s == pytest.approx(ref["slip_time_s"], rel=1e-6, abs=1e-9)
    assert ours.peak_displacement_m == pytest.approx(ref["peak_displacement_m"], rel=1e-6, abs=floor)


@FAST
@given(system=systems(), record=records(max_samples=60))
def test_record_agrees_with_fine_implicit_euler(system, record):
    """Rough records too, against a first-order scheme that cannot miss a stop: implicit
    Euler (Moreau–Jean, isolator.bench) with 10 000 steps per sample interval.  It catches
    missed or spurious events (errors of several per cent), not the last digits."""
    from isolator import bench

    acc, dt = record
    ours = simulate_record(acc, dt, **system)
    assume(well_conditioned(ours, acc, dt, system))
    case = bench.record_case("property", acc, dt, **system)
    fine = bench.implicit_fixed_step(case, dt / 10000)
    floor = 1e-9 * float(np.max(np.abs(acc))) * (dt * acc.size) ** 2  # a touch of µs g near the end
    scale = float(np.max(np.abs(ours.displacement_m)))
    # First order: a slide of a few sample intervals is resolved to ~1e-3 of itself.  Near
    # a stop a finite step can still take a wrong turn (stick for reverse) that only the
    # last samples see, so a missed or spurious event of ours must show on more than 10 %
    # of the samples to fail.
    wrong = np.abs(fine.displacement - ours.displacement_m) > 1e-2 * scale + floor
    assert np.mean(wrong) <= 0.1, np.flatnonzero(wrong)


@st.composite
def harmonic_points(draw):
    """A random point (α, k, η, µs, µk) of the paper's parameter space, away from exact resonance."""
    alpha = draw(st.floats(1.0001, 5.0))
    mu_s = draw(st.floats(0.05, 0.5))
    mu_k = mu_s * draw(st.sampled_from([1.0, 0.7]) | st.floats(0.1, 1.0))
    k = draw(st.sampled_from([0.0]) | st.floats(0.01, 5.0))
    eta = draw(st.sampled_from([0.0]) | st.floats(0.05, 3.0))
    if eta == 0.0 and k > 0.0:
        eta = 0.1  # an undamped spring may be resonant: covered by test_hard_cases
    return alpha, k, eta, mu_s, mu_k


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(point=harmonic_points())
def test_harmonic_energy_balance_and_mirror_symmetry(point):
    alpha, k, eta, mu_s, mu_k = point
    response = harmonic_response(alpha, k, eta, mu_s, mu_k, samples_per_period=4)
    assert math.isfinite(response.amplitude) and 0.0 <= response.zeta <= 1.0
    if response.steady:
        scale = max(abs(response.work_input), response.energy_friction, 1e-30)
        assert abs(response.energy_balance_residual) <= 1e-7 * scale  # Eq. 8
        mirrored = harmonic_response(alpha, k, eta, mu_s, mu_k, phase=1.5 * math.pi, samples_per_period=4)
        if mirrored.steady:
            assert mirrored.zeta == pytest.approx(response.zeta, abs=1e-7)
            assert mirrored.amplitude == pytest.approx(response.amplitude, rel=1e-7, abs=1e-12)
