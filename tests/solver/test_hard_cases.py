"""Hard cases of the exact solver, each checked against the analytic solution or the
independent tight-tolerance reference (``tests/reference.py``, DOP853 with event
location), with a bound on our run time.

Harmonic cases use the paper's dimensionless Eq. 2 (g = 1, from rest, φ = π/2); their
trajectory is compared on the last simulated forcing period, where errors of the
transient have accumulated.  Record cases are per unit mass in SI units.
"""

from __future__ import annotations

import math
import time

import numpy as np
import pytest

from isolator import bench
from isolator.solver.harmonic import alpha_sl_friction_only, harmonic_response
from isolator.solver.record import simulate_record
from tests.reference import reference_harmonic, reference_record

G = 9.80665  # [m/s²]
#: bounded run time: a guard against hangs and runaway chatter, not a benchmark (timings are
#: measured by `isolator bench`); generous because the first call may compile and CI machines
#: are shared [s]
TIME_LIMIT_S = 60.0


def timed(function, *args, **kwargs):
    start = time.perf_counter()
    result = function(*args, **kwargs)
    return result, time.perf_counter() - start


def exact_vs_reference_harmonic(alpha, k, eta, mu_s, mu_k, n_periods=None, rtol=1e-8, atol=1e-12):
    """Last-period trajectory, A and ζ of the exact solver against the reference; returns both."""
    case = bench.harmonic_case("hard", alpha, k, eta, mu_s, mu_k, n_periods=n_periods)
    ours, seconds = timed(bench.exact_solver, case)
    assert seconds < TIME_LIMIT_S
    assert np.all(np.isfinite(ours.displacement)) and np.all(np.isfinite(ours.velocity))
    ref = reference_harmonic(alpha, k, eta, mu_s, mu_k, t_end=case.duration, t_out=case.output_time)
    scale = max(float(np.max(np.abs(ref["x"]))), 1e-300)
    np.testing.assert_allclose(ours.displacement, ref["x"], rtol=0, atol=rtol * scale + atol)
    return case, ours, ref


def exact_vs_reference_record(acc, dt, rtol=1e-8, **system):
    """Exact record response against the reference; returns (ours, reference)."""
    ours, seconds = timed(simulate_record, acc, dt, **system)
    assert seconds < TIME_LIMIT_S
    assert np.all(np.isfinite(ours.displacement_m)) and np.all(np.isfinite(ours.velocity_m_s))
    ref = reference_record(acc, dt, **system)
    scale = max(float(np.max(np.abs(ref["displacement_m"]))), 1e-300)
    np.testing.assert_allclose(ours.displacement_m, ref["displacement_m"], rtol=0, atol=rtol * scale)
    assert ours.slip_time_s == pytest.approx(ref["slip_time_s"], rel=1e-7, abs=1e-9)
    assert ours.peak_displacement_m == pytest.approx(ref["peak_displacement_m"], rel=1e-7, abs=1e-300)
    assert len(ours.event_time_s) == len(ref["events"])
    return ours, ref


def assert_energy_balance(response, rel=1e-7):
    scale = max(response.energy_input_J_per_kg, response.energy_friction_J_per_kg, 1e-300)
    assert abs(response.energy_balance_error_J_per_kg) <= rel * scale


def sine_record(duration_s=2.0, dt_s=0.01, amplitude_m_s2=4.0, frequency_hz=1.3):
    t = np.arange(0.0, duration_s, dt_s)
    return amplitude_m_s2 * np.sin(2 * np.pi * frequency_hz * t), dt_s


# --------------------------------------------------------------------------------------
# Critical damping: η² = 4k exactly and ± 1e-12 (the closed forms switch branch there)
# --------------------------------------------------------------------------------------

@pytest.mark.parametrize("offset", [0.0, 1e-12, -1e-12], ids=["exact", "plus", "minus"])
def test_critical_damping_harmonic(offset):
    k = 0.25
    eta = 1.0 if offset == 0.0 else math.sqrt(4 * k + offset)  # η² = 4k exactly for 0.25 and 1.0
    assert offset != 0.0 or eta * eta == 4 * k
    case, ours, _ = exact_vs_reference_harmonic(2.0, k, eta, 0.25, 0.2)
    exact = harmonic_response(2.0, k, eta, 0.25, 0.2)
    critical = harmonic_response(2.0, 0.25, 1.0, 0.25, 0.2)
    # the response is continuous across the branch switch
    assert exact.zeta == pytest.approx(critical.zeta, abs=1e-9)
    assert exact.amplitude == pytest.approx(critical.amplitude, rel=1e-9)
    assert ours.peak == pytest.approx(exact.amplitude, rel=1e-9)


@pytest.mark.parametrize("offset", [0.0, 1e-12, -1e-12], ids=["exact", "plus", "minus"])
def test_critical_damping_record(offset):
    acc, dt = sine_record()
    damping = 4.0 if offset == 0.0 else math.sqrt(16.0 + offset)  # c² = 4κ with κ = 4 1/s²
    ours, _ = exact_vs_reference_record(acc, dt, mu_static=0.06, mu_kinetic=0.05, stiffness_per_mass=4.0,
                                        damping_per_mass=damping)
    assert_energy_balance(ours)


# --------------------------------------------------------------------------------------
# Exact resonance: k = ω², η = 0 — linear growth at the paper's rate β (Eq. 26)
# --------------------------------------------------------------------------------------

@pytest.mark.parametrize("mu_k", [0.25, 0.2])
def test_exact_resonance_grows_at_paper_rate(mu_k):
    alpha, mu_s = 4.0, 0.25
    k = alpha * mu_s  # k = ω²: the spring is tuned to the forcing
    response, seconds = timed(harmonic_response, alpha, k, 0.0, mu_s, mu_k)
    assert seconds < TIME_LIMIT_S
    beta = (k - 4 * mu_k / math.pi) / (2 * math.sqrt(k))
    assert response.status == "resonant growth" and not response.steady
    assert response.growth_rate == pytest.approx(beta, rel=1e-6)
    # and the growing trajectory itself, from rest, against the reference
    exact_vs_reference_harmonic(alpha, k, 0.0, mu_s, mu_k, n_periods=6)


# --------------------------------------------------------------------------------------
# Vanishing dashpot and spring: η = 1e-9, k = 1e-12
# --------------------------------------------------------------------------------------

def test_tiny_damping_and_stiffness_harmonic():
    _, ours, _ = exact_vs_reference_harmonic(1.5, 1e-12, 1e-9, 0.25, 0.25)
    tiny = harmonic_response(1.5, 1e-12, 1e-9, 0.25, 0.25)
    friction_only = harmonic_response(1.5, 0.0, 0.0, 0.25, 0.25)
    assert tiny.configuration == "4a" or tiny.configuration.startswith("4")
    assert tiny.zeta == pytest.approx(friction_only.zeta, abs=1e-7)
    assert tiny.amplitude == pytest.approx(friction_only.amplitude, rel=1e-7)


def test_tiny_damping_and_stiffness_record():
    acc, dt = sine_record()
    ours, _ = exact_vs_reference_record(acc, dt, mu_static=0.06, mu_kinetic=0.05, stiffness_per_mass=1e-12,
                                        damping_per_mass=1e-9)
    bare = simulate_record(acc, dt, mu_static=0.06, mu_kinetic=0.05)
    np.testing.assert_allclose(ours.displacement_m, bare.displacement_m, rtol=0, atol=1e-8)
    assert_energy_balance(ours)


# --------------------------------------------------------------------------------------
# At the regime thresholds: α = 1 + 1e-9 (barely slides) and α = α_SL exactly
# --------------------------------------------------------------------------------------

def test_barely_slides_friction_only():
    response, seconds = timed(harmonic_response, 1.0 + 1e-9, 0.0, 0.0, 0.25, 0.25)
    assert seconds < TIME_LIMIT_S
    assert response.regime == "SS"
    assert 0.0 < response.zeta < 1e-3  # slips for a sliver of each period
    assert 0.0 < response.amplitude < 1e-12
    case = bench.harmonic_case("barely", 1.0 + 1e-9, 0.0, 0.0, 0.25, 0.25)
    ref = reference_harmonic(1.0 + 1e-9, 0.0, 0.0, 0.25, 0.25, t_end=case.duration, t_out=case.output_time)
    ours = bench.exact_solver(case)
    assert ours.peak == pytest.approx(0.5 * (ref["x"].max() - ref["x"].min()), rel=1e-4)
    np.testing.assert_allclose(ours.displacement, ref["x"], rtol=0, atol=1e-21)


def test_barely_slides_complete_model():
    # with spring and dashpot the tiny first slip grows into a finite stick-slip cycle
    _, ours, _ = exact_vs_reference_harmonic(1.0 + 1e-9, 1.0, 0.5, 0.25, 0.2)
    response = harmonic_response(1.0 + 1e-9, 1.0, 0.5, 0.25, 0.2)
    assert response.regime == "SS" and response.steady
    assert ours.peak == pytest.approx(response.amplitude, rel=1e-9)
    assert ours.slip_ratio == pytest.approx(response.zeta, abs=1e-9)
    assert harmonic_response(1.0, 1.0, 0.5, 0.25, 0.2).regime == "ST"


@pytest.mark.parametrize("mu_k", [0.25, 0.15])
def test_alpha_exactly_at_alpha_sl(mu_k):
    mu_s = 0.25
    alpha_sl = alpha_sl_friction_only(mu_s, mu_k)  # Eq. 15
    assert alpha_sl == pytest.approx(math.sqrt(1 + math.pi ** 2 / 4 * (mu_k / mu_s) ** 2), rel=1e-15)
    at, seconds = timed(harmonic_response, alpha_sl, 0.0, 0.0, mu_s, mu_k)
    assert seconds < TIME_LIMIT_S
    assert at.regime in ("SS", "SL") and at.zeta > 1 - 1e-9  # ζ → 1 continuously
    assert harmonic_response(alpha_sl * (1 + 1e-7), 0.0, 0.0, mu_s, mu_k).regime == "SL"
    below = harmonic_response(alpha_sl * (1 - 1e-4), 0.0, 0.0, mu_s, mu_k)
    assert below.regime == "SS" and 0.99 < below.zeta < 1.0
    exact_vs_reference_harmonic(alpha_sl, 0.0, 0.0, mu_s, mu_k, n_periods=4)


def test_alpha_sl_reference_value():
    # ζ(α = 1.2, µs = µk = 0.25, k = η = 0) ≈ 0.566 (the paper's configuration-1 example)
    assert harmonic_response(1.2, 0.0, 0.0, 0.25, 0.25).zeta == pytest.approx(0.566, abs=5e-4)


# --------------------------------------------------------------------------------------
# Violent forcing: α = 1e3
# --------------------------------------------------------------------------------------

def test_alpha_1e3_friction_only():
    response, seconds = timed(harmonic_response, 1e3, 0.0, 0.0, 0.25, 0.25)
    assert seconds < TIME_LIMIT_S
    assert response.regime == "SL" and response.zeta == 1.0
    assert response.amplitude == pytest.approx(1.0, abs=1e-2)  # the block hardly follows: x ≈ -ground
    exact_vs_reference_harmonic(1e3, 0.0, 0.0, 0.25, 0.25, n_periods=5)


def test_alpha_1e3_complete_model():
    response, seconds = timed(harmonic_response, 1e3, 1.0, 0.5, 0.25, 0.2)
    assert seconds < TIME_LIMIT_S
    assert response.regime == "SL" and response.steady
    assert response.amplitude == pytest.approx(1.0, abs=1e-2)
    assert abs(response.energy_balance_residual) < 1e-8 * abs(response.work_input)
    exact_vs_reference_harmonic(1e3, 1.0, 0.5, 0.25, 0.2, n_periods=5)


# --------------------------------------------------------------------------------------
# µk = 0.7 µs: long stick-slip chatter
# --------------------------------------------------------------------------------------

def test_kinetic_07_static_long_chatter_record():
    mu_s = 0.1
    mu_k = 0.7 * mu_s
    dt = 0.002
    t = np.arange(0.0, 20.0, dt)
    acc = 1.05 * mu_s * G * np.sin(2 * np.pi * 5.0 * t)  # just above the static threshold, 100 cycles
    system = dict(mu_static=mu_s, mu_kinetic=mu_k, stiffness_per_mass=2.0, damping_per_mass=0.1)
    full, seconds = timed(simulate_record, acc, dt, **system)
    assert seconds < TIME_LIMIT_S
    assert full.n_events > 300 and full.status == 0
    assert np.all(np.isfinite(full.displacement_m))
    assert_energy_balance(full)
    # a 2 s window (20 cycles of break-away, stick, break-away …) against the reference
    window = exact_vs_reference_record(acc[:1000], dt, **system)[0]
    assert window.n_events > 30


def test_kinetic_07_static_chatter_harmonic():
    _, ours, ref = exact_vs_reference_harmonic(1.05, 0.5, 0.1, 0.3, 0.21)
    assert ours.slip_ratio < 1.0 and len(ref["events"]) > 40


# --------------------------------------------------------------------------------------
# Long, spiky, empty and threshold records
# --------------------------------------------------------------------------------------

def test_one_khz_ten_minute_record():
    rng = np.random.default_rng(7)
    n = 600_000  # 10 minutes at 1 kHz
    acc = np.convolve(rng.standard_normal(n), np.ones(50) / 50, mode="same")
    acc *= 0.3 * G / np.max(np.abs(acc))
    acc[:1000] *= np.linspace(0.0, 1.0, 1000)  # starts from rest (see test_breakaway_at_time_zero…)
    system = dict(mu_static=0.06, mu_kinetic=0.05, stiffness_per_mass=G / 2.0, damping_per_mass=0.2)
    response, seconds = timed(simulate_record, acc, 1e-3, **system)
    assert seconds < TIME_LIMIT_S
    assert response.status == 0 and response.n_events > 1000
    assert np.all(np.isfinite(response.displacement_m)) and np.all(np.isfinite(response.velocity_m_s))
    assert response.peak_displacement_m >= np.max(np.abs(response.displacement_m))
    assert_energy_balance(response, rel=1e-9)
    # the first 3 s against the reference
    window, _ = exact_vs_reference_record(acc[:3000], 1e-3, **system)
    np.testing.assert_array_equal(window.displacement_m, response.displacement_m[:3000])


def test_single_huge_spike():
    acc = np.zeros(500)
    acc[100] = 50 * G  # one sample of 50 g
    ours, _ = exact_vs_reference_record(acc, 0.01, mu_static=0.06, mu_kinetic=0.05, stiffness_per_mass=G / 2.0)
    assert ours.peak_displacement_m > 1.0
    assert_energy_balance(ours)


def test_zero_record():
    response = simulate_record(np.zeros(10_000), 0.01, mu_static=0.06, mu_kinetic=0.05, stiffness_per_mass=4.9,
                               damping_per_mass=0.3)
    assert response.n_events == 0 and response.slip_time_s == 0.0
    assert not np.any(response.displacement_m) and not np.any(response.velocity_m_s)
    assert response.peak_displacement_m == 0.0 and response.energy_input_J_per_kg == 0.0


@pytest.mark.parametrize("mu_k, stiffness", [(0.05, 0.0), (0.05, 4.9), (0.06, 0.0)], ids=["muk<mus", "spring", "muk=mus"])
def test_record_at_static_threshold_for_many_samples(mu_k, stiffness):
    mu_s = 0.06
    plateau = mu_s * G  # |a_g| = µs g exactly: stuck, by the stick rule |κX + a_g| <= µs g
    acc = np.concatenate([np.linspace(0.0, plateau, 50), np.full(1000, plateau), np.linspace(plateau, 0.0, 50)])
    acc = np.concatenate([acc, -acc])
    response = simulate_record(acc, 0.01, mu_static=mu_s, mu_kinetic=mu_k, stiffness_per_mass=stiffness)
    assert response.n_events == 0 and response.slip_time_s == 0.0
    assert not np.any(response.displacement_m)
    # one sample a hair above the plateau: it breaks away there, as the reference says
    touched = acc.copy()
    touched[500] = plateau * (1 + 1e-9)
    ours, _ = exact_vs_reference_record(touched, 0.01, mu_static=mu_s, mu_kinetic=mu_k, stiffness_per_mass=stiffness)
    assert ours.n_events >= 1 and ours.event_time_s[0] == pytest.approx(4.99, abs=0.0101)


# --------------------------------------------------------------------------------------
# Stiff and heavily damped systems
# --------------------------------------------------------------------------------------

def test_very_stiff_spring_period_far_below_dt():
    acc, _ = sine_record(dt_s=0.02)
    stiffness = 1e6  # natural period 6.3 ms, a third of the sample interval
    ours, _ = exact_vs_reference_record(acc, 0.02, mu_static=0.06, mu_kinetic=0.05, stiffness_per_mass=stiffness)
    assert ours.substeps_per_interval > 1
    assert_energy_balance(ours)


@pytest.mark.parametrize("stiffness", [1e8, 1e10])
def test_extremely_stiff_spring_is_finite_and_balanced(stiffness):
    acc, _ = sine_record(dt_s=0.02)
    response, seconds = timed(simulate_record, acc, 0.02, mu_static=0.06, mu_kinetic=0.05,
                              stiffness_per_mass=stiffness)
    assert seconds < TIME_LIMIT_S
    assert np.all(np.isfinite(response.displacement_m))
    # the spring carries the load: |X| ≲ (max|a_g| + µs g) / κ
    assert response.peak_displacement_m <= (np.max(np.abs(acc)) + 0.06 * G) / stiffness
    assert_energy_balance(response)


def test_heavy_damping_fast_exponent():
    acc, dt = sine_record()
    ours, _ = exact_vs_reference_record(acc, dt, mu_static=0.06, mu_kinetic=0.05, stiffness_per_mass=4.9,
                                        damping_per_mass=1e4)
    assert_energy_balance(ours, rel=1e-6)


@pytest.mark.parametrize("damping", [1e8, 1e12])
def test_extreme_damping_is_finite_and_balanced(damping):
    acc, dt = sine_record()
    response, seconds = timed(simulate_record, acc, dt, mu_static=0.06, mu_kinetic=0.05, stiffness_per_mass=4.9,
                              damping_per_mass=damping)
    assert seconds < TIME_LIMIT_S
    assert np.all(np.isfinite(response.displacement_m))
    # the dashpot locks the block to the ground: |X| ≲ ∫|a_g| dt / c
    assert response.peak_displacement_m <= np.sum(np.abs(acc)) * dt / damping
    assert_energy_balance(response, rel=1e-6)


def test_large_k_and_large_eta_harmonic():
    # k = 1e4: the spring period is 1/140 of the forcing period; η = 1e3: exponent -η t
    stiff, seconds_stiff = timed(harmonic_response, 2.0, 1e4, 0.0, 0.25, 0.2)
    damped, seconds_damped = timed(harmonic_response, 2.0, 0.0, 1e3, 0.25, 0.2)
    assert seconds_stiff < TIME_LIMIT_S and seconds_damped < TIME_LIMIT_S
    for response in (stiff, damped):
        assert response.steady and math.isfinite(response.amplitude) and 0.0 <= response.zeta <= 1.0
        assert abs(response.energy_balance_residual) < 1e-6 * abs(response.work_input)
    assert stiff.amplitude < 1e-4 and damped.amplitude < 1e-3
    _, ours, _ = exact_vs_reference_harmonic(2.0, 0.0, 1e3, 0.25, 0.2, n_periods=2)
    assert ours.peak == pytest.approx(damped.amplitude, rel=1e-6)


# --------------------------------------------------------------------------------------
# Found while building the hard cases: a solver problem, kept as an expected failure
# --------------------------------------------------------------------------------------

@pytest.mark.parametrize("alpha", [5.6, 5.8])
def test_subharmonic_cycle_dense_output_closes(alpha):
    response = harmonic_response(alpha, 3.5, 0.0, 0.25, 0.25)
    assert response.cycle_periods == 2
    # the steady cycle is periodic: its last sample is its first
    assert response.cycle_x[-1] == pytest.approx(response.cycle_x[0], abs=1e-6)
    assert response.cycle_xdot[-1] == pytest.approx(response.cycle_xdot[0], abs=1e-6)


@pytest.mark.parametrize("mu_k", [0.05, 0.06])
def test_breakaway_at_time_zero_by_a_jump(mu_k):
    acc = np.full(3, -1.0)  # [m/s²], beyond µs g = 0.588 m/s² from the first sample
    response = simulate_record(acc, 0.001, mu_static=0.06, mu_kinetic=mu_k)
    t = np.array([0.0, 0.001, 0.002])
    exact = 0.5 * (1.0 - mu_k * G) * t ** 2  # slides forwards at X'' = |a_g| - µk g
    np.testing.assert_allclose(response.displacement_m, exact, rtol=1e-9, atol=1e-20)
    assert abs(response.energy_balance_error_J_per_kg) < 1e-12


# µk = 0: free sliding between a break-away and the next stop.  V = -∫ a_g dt returns to
# zero at t = 3.4271 ms and (were the block not held by µs g there) again at 3.7530 ms:
# a step-based integrator with event location steps over the pair and misses the stick
# (both tests/reference.py and the solve_ivp methods of isolator.bench do).
FREE_SLIDING_RECORD = np.array([
    0.0, 6.18292357, 2.48663835, -9.80665, 6.81307512, 3.35910287, -4.04073455, 4.37308846, 2.7435169,
    2.21343548, 0.21388591, 4.11417961, -5.54203844, -1.22594634, -3.62809279, 4.50649781, 0.2989208,
    -2.20082499, -5.88409628, -1.93544894])  # [m/s²], dt = 1 ms


def test_free_sliding_mu_k_zero():
    from scipy.optimize import brentq

    system = dict(mu_static=0.375, mu_kinetic=0.0)
    dt = 0.001
    ours = simulate_record(FREE_SLIDING_RECORD, dt, **system)
    assert list(ours.event_names) == ["breakaway", "stick", "breakaway"]
    sample_times = dt * np.arange(FREE_SLIDING_RECORD.size)
    t_break = ours.event_time_s[0]
    assert np.interp(t_break, sample_times, FREE_SLIDING_RECORD) == pytest.approx(0.375 * G, rel=1e-12)

    def velocity(t):  # exact for a piecewise-linear record: V = -∫ a_g from the break-away
        nodes = np.concatenate(([t_break], sample_times[(sample_times > t_break) & (sample_times < t)], [t]))
        values = np.interp(nodes, sample_times, FREE_SLIDING_RECORD)
        return -float(np.sum(0.5 * (values[1:] + values[:-1]) * np.diff(nodes)))

    t_stop = brentq(velocity, 0.0034, 0.0035, xtol=1e-15)
    assert ours.event_time_s[1] == pytest.approx(t_stop, abs=1e-12)
    assert abs(np.interp(t_stop, sample_times, FREE_SLIDING_RECORD)) < 0.375 * G  # so it sticks
    assert_energy_balance(ours)


@pytest.mark.xfail(strict=True, reason="tests/reference.py steps over the pair of zeros of V and misses the "
                   "stick at t = 3.427 ms when µk = 0 (a limitation of the reference, not a solver problem; it also "
                   "misses stops on rough records, so the property tests compare with it on sine records with "
                   "µk >= 0.1 µs only)")
def test_reference_free_sliding():
    system = dict(mu_static=0.375, mu_kinetic=0.0)
    ours = simulate_record(FREE_SLIDING_RECORD, 0.001, **system)
    ref = reference_record(FREE_SLIDING_RECORD, 0.001, **system)
    assert len(ref["events"]) == ours.n_events
