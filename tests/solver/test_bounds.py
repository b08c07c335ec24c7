"""Absurd numbers end in one typed error naming the quantity, quickly; the limits themselves still solve."""

from __future__ import annotations

import math
import time

import numpy as np
import pytest

from isolator.adapter import dimensionless_point
from isolator.design import Design, DesignError
from isolator.solver.harmonic import MAX_DIMENSIONLESS, harmonic_response
from isolator.solver.linear import MAX_SUBSTEPS_PER_SAMPLE, linear_peak_displacement
from isolator.solver.record import RecordInputError, simulate_record
from isolator.solver.system import MAX_DAMPING_PER_MASS, MAX_STIFFNESS_PER_MASS, InvalidSystemError, System
from isolator.solver.thresholds import MAX_THRESHOLD_GRID, harmonic_thresholds


@pytest.mark.parametrize("key, value, words", [
    ("stiffness_per_mass", 1e300, r"stiffness_per_mass = 1e\+300 exceeds"),
    ("damping_per_mass", 1e300, r"damping_per_mass = 1e\+300 exceeds"),
    ("stiffness_per_mass", MAX_STIFFNESS_PER_MASS * 1.0001, "stiffness_per_mass"),
])
def test_system_refuses_rates_beyond_the_limits(key, value, words):
    with pytest.raises(InvalidSystemError, match=words):
        System(mu_static=0.1, **{key: value})


def test_system_at_the_limits_still_solves_exactly():
    # at the largest K/M and γ/M the solver still answers, quickly: a sine below µs g never
    # breaks the block away (|a_g| ≤ µs g), whatever the spring and damper
    t = np.arange(2001) * 0.01
    acc = 0.5 * np.sin(2 * np.pi * t)
    start = time.perf_counter()
    response = simulate_record(acc, 0.01, system=System(mu_static=0.1, stiffness_per_mass=MAX_STIFFNESS_PER_MASS,
                                                        damping_per_mass=MAX_DAMPING_PER_MASS))
    assert time.perf_counter() - start < 20
    assert response.peak_displacement_m == 0.0 and response.n_events == 0  # 0.5 < µs g = 0.98: stuck


def test_design_blames_its_own_key():
    base = {"name": "x", "mass_kg": 1000.0, "mu_static": 0.1}
    with pytest.raises(DesignError, match=r"key 'radius_m' = 1e-300 m gives K/M"):
        Design.from_mapping({**base, "radius_m": 1e-300}, source="d.toml")
    with pytest.raises(DesignError, match=r"key 'stiffness_N_per_m'"):
        Design.from_mapping({**base, "stiffness_N_per_m": 1e300}, source="d.toml")
    with pytest.raises(DesignError, match=r"key 'damping_Ns_per_m' gives"):
        Design.from_mapping({**base, "radius_m": 1.0, "damping_Ns_per_m": 1e300}, source="d.toml")
    with pytest.raises(DesignError, match=r"key 'mass_kg' must lie in"):
        Design.from_mapping({**base, "mass_kg": 1e-320, "radius_m": 1.0}, source="d.toml")
    # a real pendulum is accepted and its K/M is g/R
    assert Design.from_mapping({**base, "radius_m": 2.0}).stiffness_per_mass == pytest.approx(9.80665 / 2)


def test_vanishing_motion_is_the_records_fault():
    design = Design.from_mapping({"name": "x", "mass_kg": 1000.0, "mu_static": 0.1, "radius_m": 2.0})
    with pytest.raises(RecordInputError, match="no ground motion"):
        dimensionless_point(design, 0.0, 0.0)
    with pytest.raises(RecordInputError, match="PGV²/PGA = 0 m"):
        dimensionless_point(design, 1e-300, 1e-301)  # PGV² underflows: was a ZeroDivisionError later


@pytest.mark.parametrize("kwargs, words", [
    ({"alpha": 2.0, "k": 1e300, "eta": 0.0}, r"k = 1e\+300 exceeds"),
    ({"alpha": 2.0, "k": 1.0, "eta": 1e300}, r"eta = 1e\+300 exceeds"),
    ({"alpha": 1e300, "k": 0.0, "eta": 0.0}, r"alpha = 1e\+300 exceeds"),
])
def test_harmonic_refuses_absurd_points_at_once(kwargs, words):
    start = time.perf_counter()
    with pytest.raises(InvalidSystemError, match=words):
        harmonic_response(mu_s=0.25, **kwargs)
    assert time.perf_counter() - start < 1.0


def test_harmonic_at_the_limit_solves_and_is_stuck_below_alpha_one():
    # α < 1: the ground acceleration never exceeds µs g, so the block sticks (Eq. 6)
    assert harmonic_response(0.5, MAX_DIMENSIONLESS, 0.0, 0.25).regime == "ST"


def test_threshold_scan_bounds():
    with pytest.raises(InvalidSystemError, match="4 to 20000 points"):
        harmonic_thresholds(0.0, 0.0, 0.25, n_grid=10_000_000)
    with pytest.raises(InvalidSystemError, match="alpha_max = 1e\\+300 exceeds"):
        harmonic_thresholds(0.0, 0.0, 0.25, alpha_max=1e300)
    assert MAX_THRESHOLD_GRID == 20_000


def test_spectrum_refuses_a_time_step_no_accelerogram_has():
    acc = np.sin(np.arange(2000) * 0.3)
    start = time.perf_counter()
    with pytest.raises(RecordInputError, match="time step 100 s is 5000 times the spectral period 0.02 s"):
        linear_peak_displacement(acc, 100.0, 0.02, 0.05)
    assert time.perf_counter() - start < 1.0
    # at the limit (25 periods per sample) the peak is still exact: a static load
    # a = const gives X → a/ω² at most 2 a/ω² (undamped overshoot)
    dt = 25 * 0.02
    assert math.ceil(dt / (0.25 * 0.02)) == MAX_SUBSTEPS_PER_SAMPLE
    peak = linear_peak_displacement(np.ones(50), dt, 0.02, 0.0)
    assert peak == pytest.approx(2.0 / (2 * math.pi / 0.02) ** 2, rel=1e-9)
