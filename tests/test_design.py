"""Design files: every valid form, every invalid key with a message naming it."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from isolator.design import DESIGN_KEYS, Design, DesignError

DATA = Path(__file__).resolve().parents[1] / "data"
G = 9.80665
BASE = {"name": "t", "mass_kg": 1000.0, "radius_m": 2.0, "mu_static": 0.06}


def test_pendulum_quantities():
    d = Design.from_mapping(dict(BASE, mu_kinetic=0.05))
    assert d.stiffness_N_per_m == pytest.approx(1000.0 * G / 2.0)
    assert d.isolated_period_s == pytest.approx(2 * math.pi * math.sqrt(2.0 / G))
    assert d.mu_kinetic == 0.05 and d.damping_Ns_per_m == 0.0
    system = d.system()
    assert system.stiffness_per_mass == pytest.approx(G / 2.0)
    assert system.configuration == "3"


def test_mu_kinetic_defaults_to_mu_static_and_damping_ratio():
    d = Design.from_mapping(dict(BASE, damping_ratio=0.1))
    assert d.mu_kinetic == d.mu_static
    omega = math.sqrt(G / 2.0)
    assert d.damping_Ns_per_m == pytest.approx(2 * 0.1 * 1000.0 * omega)
    assert d.damping_ratio == pytest.approx(0.1)


def test_generic_stiffness_and_damper():
    d = Design.from_mapping({"name": "s", "mass_kg": 100.0, "stiffness_N_per_m": 400.0, "mu_static": 0.1,
                             "damping_Ns_per_m": 40.0})
    assert not d.is_pendulum and d.isolated_period_s == pytest.approx(2 * math.pi / 2.0)
    assert d.system().damping_per_mass == pytest.approx(0.4)


def test_effective_properties_hand_computed():
    d = Design.from_mapping(dict(BASE, mu_kinetic=0.05))  # W = 9806.65 N, K = 4903.325 N/m
    e = d.effective_properties(0.2)
    w = 1000.0 * G
    k_eff = w / 2.0 + 0.05 * w / 0.2
    assert e.effective_stiffness_N_per_m == pytest.approx(k_eff)
    assert e.effective_period_s == pytest.approx(2 * math.pi * math.sqrt(1000.0 / k_eff))
    # friction pendulum: beta = (2/pi) mu / (mu + D/R)
    assert e.effective_damping_ratio == pytest.approx(2 / math.pi * 0.05 / (0.05 + 0.2 / 2.0))
    assert e.design_force_N == pytest.approx(w / 2.0 * 0.2 + 0.05 * w)


@pytest.mark.parametrize("name", ["example_pendulum", "example_pendulum_damped", "example_flat_slider"])
def test_example_designs_are_valid(name):
    d = Design.from_toml(DATA / f"{name}.toml")
    assert d.name and d.mass_kg > 0


INVALID = [
    ({"radius": 2.0}, "radius_m", "unknown key 'radius'"),
    ({"mass": 1.0}, "mass_kg", "unknown key 'mass'"),
    ({"mu_kinetc": 0.05}, "mu_kinetic", "unknown key 'mu_kinetc'"),
    ({"colour": "red"}, None, "unknown key 'colour'"),
    ({"mass_kg": -1.0}, None, "'mass_kg' must be > 0"),
    ({"mass_kg": 0}, None, "'mass_kg' must be > 0"),
    ({"mass_kg": "heavy"}, None, "'mass_kg' must be a number"),
    ({"mass_kg": True}, None, "'mass_kg' must be a number"),
    ({"radius_m": -1.0}, None, "'radius_m' must be > 0, got -1"),
    ({"radius_m": 0.0}, None, "'radius_m' must be > 0"),
    ({"radius_m": float("inf")}, None, "'radius_m' must be finite"),
    ({"mu_static": 0.0}, None, "'mu_static' must be > 0"),
    ({"mu_static": 1.5}, None, "'mu_static' must be < 1"),
    ({"mu_kinetic": 0.07}, None, "'mu_kinetic' (0.07) must not exceed 'mu_static' (0.06)"),
    ({"mu_kinetic": -0.01}, None, "'mu_kinetic' must be >= 0"),
    ({"stiffness_N_per_m": 100.0}, None, "either 'radius_m'"),
    ({"damping_ratio": -0.1}, None, "'damping_ratio' must be >= 0"),
    ({"damping_Ns_per_m": -5.0}, None, "'damping_Ns_per_m' must be >= 0"),
    ({"damping_ratio": 0.1, "damping_Ns_per_m": 5.0}, None, "at most one of 'damping_Ns_per_m' and 'damping_ratio'"),
    ({"name": ""}, None, "'name' must be a non-empty text"),
    ({"name": 3}, None, "'name' must be a non-empty text"),
    ({"description": 3}, None, "'description' must be text"),
]


@pytest.mark.parametrize("change,suggestion,words", INVALID)
def test_invalid_key(change, suggestion, words):
    with pytest.raises(DesignError) as info:
        Design.from_mapping(dict(BASE, **change), source="design.toml")
    message = str(info.value)
    assert message.startswith("design.toml: ") and words in message and "\n" not in message
    if suggestion:
        assert f"did you mean '{suggestion}'" in message


@pytest.mark.parametrize("missing", ["name", "mass_kg", "mu_static", "radius_m"])
def test_missing_key(missing):
    mapping = dict(BASE)
    del mapping[missing]
    with pytest.raises(DesignError, match=f"missing key '{missing}'"):
        Design.from_mapping(mapping, source="design.toml")


def test_damping_ratio_needs_a_spring():
    with pytest.raises(DesignError, match="'damping_ratio' needs a restoring stiffness"):
        Design.from_mapping({"name": "f", "mass_kg": 1.0, "stiffness_N_per_m": 0.0, "mu_static": 0.1,
                             "damping_ratio": 0.1})


def test_every_key_is_documented():
    assert set(DESIGN_KEYS) == {"name", "description", "mass_kg", "radius_m", "stiffness_N_per_m", "mu_static",
                                "mu_kinetic", "damping_Ns_per_m", "damping_ratio", "mu_slow", "mu_fast",
                                "rate_s_per_m", "displacement_capacity_m", "lambda_max", "lambda_min", "mu_upper",
                                "mu_lower", "lambda_ae_max", "lambda_ae_min", "lambda_test_max", "lambda_test_min",
                                "lambda_spec_max", "lambda_spec_min", "plan",
                                "superstructure", "bearing_position", "bearing"}


REVIEW_INVALID = [
    ({"mu_slow": 0.02, "mu_fast": 0.05}, "missing 'rate_s_per_m'"),
    ({"mu_slow": 0.06, "mu_fast": 0.05, "rate_s_per_m": 20.0}, "'mu_slow' (0.06) must not exceed 'mu_fast'"),
    ({"mu_slow": -0.01, "mu_fast": 0.05, "rate_s_per_m": 20.0}, "'mu_slow' must be >= 0"),
    ({"mu_slow": 0.02, "mu_fast": 1.0, "rate_s_per_m": 20.0}, "'mu_fast' must be < 1"),
    ({"mu_slow": 0.02, "mu_fast": 0.05, "rate_s_per_m": 0.0}, "'rate_s_per_m' must be > 0"),
    ({"displacement_capacity_m": 0.0}, "'displacement_capacity_m' must be > 0"),
    ({"lambda_max": 1.2}, "missing key 'lambda_min'"),
    ({"lambda_max": 0.9, "lambda_min": 0.8}, "'lambda_max' must be >= 1"),
    ({"lambda_max": 1.3, "lambda_min": 1.1}, "'lambda_min' must be <= 1"),
    ({"lambda_max": 1.3, "lambda_min": 0.9, "mu_upper": 0.08, "mu_lower": 0.04}, "one way"),
    ({"mu_upper": 0.03, "mu_lower": 0.02}, "'mu_upper' (0.03) must be >= the nominal"),
    ({"plan": {"b_m": 30.0}}, "missing key 'plan.d_m'"),
    ({"plan": {"b_m": 30.0, "d_m": 20.0, "ecc": 1.0}}, "unknown key 'plan.ecc'"),
    ({"plan": {"b_m": -30.0, "d_m": 20.0}}, "'plan.b_m' must be > 0"),
]


@pytest.mark.parametrize("change,words", REVIEW_INVALID)
def test_review_keys_invalid(change, words):
    with pytest.raises(DesignError) as info:
        Design.from_mapping(dict(BASE, **change), source="design.toml")
    assert str(info.value).startswith("design.toml: ") and words in str(info.value)


def test_review_keys_valid_and_bounds_scale_every_mu():
    d = Design.from_mapping(dict(BASE, mu_kinetic=0.05, mu_slow=0.03, mu_fast=0.05, rate_s_per_m=20.0,
                                 displacement_capacity_m=0.5, lambda_max=1.3, lambda_min=0.8,
                                 plan={"b_m": 30.0, "d_m": 20.0, "y_m": 15.0}))
    assert d.velocity_dependent and d.displacement_capacity_m == 0.5 and d.plan["y_m"] == 15.0
    up = d.with_friction_factor(1.3, "upper bound")
    assert (up.mu_static, up.mu_kinetic, up.mu_slow, up.mu_fast) == pytest.approx((0.078, 0.065, 0.039, 0.065))
    assert up.name == "t (upper bound)" and up.radius_m == d.radius_m


def test_name_defaults_to_the_file_stem(tmp_path):
    path = tmp_path / "my_bearing.toml"
    path.write_text("mass_kg = 10\nradius_m = 1\nmu_static = 0.1\n")
    assert Design.from_toml(path).name == "my_bearing"


def test_toml_file_errors(tmp_path):
    with pytest.raises(DesignError, match="no such design file"):
        Design.from_toml(tmp_path / "absent.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text("name = \n")
    with pytest.raises(DesignError, match="not valid TOML"):
        Design.from_toml(bad)
    good = tmp_path / "good.toml"
    good.write_text('name = "x"\nmass_kg = 10\nradius_m = 1\nmu_static = 0.1\n')
    assert Design.from_toml(good).stiffness_N_per_m == pytest.approx(10 * G)


def test_design_file_that_is_not_a_regular_file_is_refused_at_once(tmp_path):
    import os
    import time

    fifo = tmp_path / "design.toml"
    os.mkfifo(fifo)
    start = time.perf_counter()
    with pytest.raises(DesignError, match=r"design.toml: is a FIFO \(named pipe\), not a regular file"):
        Design.from_toml(fifo)  # reading it would block forever
    assert time.perf_counter() - start < 1.0
    (tmp_path / "a.toml").symlink_to(tmp_path / "b.toml")
    (tmp_path / "b.toml").symlink_to(tmp_path / "a.toml")
    with pytest.raises(DesignError, match="a.toml: symbolic-link loop"):
        Design.from_toml(tmp_path / "a.toml")
    with pytest.raises(DesignError, match="is a folder"):
        Design.from_toml(tmp_path)
