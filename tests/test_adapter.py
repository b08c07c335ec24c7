"""Adapter: the mapping of a design and a motion onto (α, k, η), on hand-computed cases."""

from __future__ import annotations

import math

import numpy as np
import pytest

from isolator.adapter import adapt, dimensionless_point, engineering_quantities
from isolator.design import Design
from isolator.motion import GroundMotion

G = 9.80665


def test_pendulum_point_by_hand():
    # PGA 0.3 g, PGV 0.5 m/s: A0 = 0.25/(0.3 g) = 0.084976 m; α = 0.3 g/(0.06 g) = 5; k = A0/R
    d = Design.from_mapping({"name": "p", "mass_kg": 2.0e5, "radius_m": 2.0, "mu_static": 0.06, "mu_kinetic": 0.05})
    p = dimensionless_point(d, 0.3 * G, 0.5)
    a0 = 0.25 / (0.3 * G)
    assert p.a0_m == pytest.approx(a0)
    assert p.alpha == pytest.approx(5.0)
    assert p.k == pytest.approx(a0 / 2.0)
    assert p.eta == 0.0
    assert p.omega_rad_s == pytest.approx(0.3 * G / 0.5)
    assert (p.mu_s, p.mu_k) == (0.06, 0.05)


def test_generic_point_by_hand():
    # M = 100 kg, K = 1000 N/m, γ = 200 N s/m; PGA 2 m/s², PGV 0.4 m/s → A0 = 0.08 m
    d = Design.from_mapping({"name": "s", "mass_kg": 100.0, "stiffness_N_per_m": 1000.0, "mu_static": 0.1,
                             "damping_Ns_per_m": 200.0})
    p = dimensionless_point(d, 2.0, 0.4)
    assert p.alpha == pytest.approx(2.0 / (0.1 * G))
    assert p.k == pytest.approx(1000.0 * 0.08 / (100.0 * G))
    assert p.eta == pytest.approx(2.0 * math.sqrt(0.08 / G))


def test_sampled_cosine_gives_its_own_point():
    a0, omega = 0.05, 4.0
    dt = 2 * math.pi / omega / 400
    t = np.arange(40 * 400 + 1) * dt
    motion = GroundMotion.from_array(a0 * omega ** 2 * np.cos(omega * t), dt)
    d = Design.from_mapping({"name": "p", "mass_kg": 1.0, "radius_m": 1.0, "mu_static": 0.1})
    adaptation = adapt(d, motion)
    assert adaptation.point.a0_m == pytest.approx(a0, rel=1e-4)
    assert adaptation.point.k == pytest.approx(a0 / 1.0, rel=1e-4)
    assert adaptation.point.alpha == pytest.approx(a0 * omega ** 2 / (0.1 * G))
    assert adaptation.system.stiffness_per_mass == pytest.approx(G)


def test_engineering_quantities():
    from types import SimpleNamespace

    d = Design.from_mapping({"name": "p", "mass_kg": 1000.0, "radius_m": 2.0, "mu_static": 0.05})
    response = SimpleNamespace(peak_displacement_m=0.1, residual_displacement_m=0.01,
                               peak_transmitted_acceleration_m_s2=1.0)
    q = engineering_quantities(d, response)
    assert q["peak_transmitted_force_N"] == pytest.approx(1000.0)
    assert q["base_shear_coefficient"] == pytest.approx(1.0 / G)
    assert q["effective_stiffness_N_per_m"] == pytest.approx(1000 * G / 2 + 0.05 * 1000 * G / 0.1)
    assert q["isolated_period_s"] == pytest.approx(2 * math.pi * math.sqrt(2.0 / G))


def test_zero_pgv_is_an_error():
    d = Design.from_mapping({"name": "p", "mass_kg": 1.0, "radius_m": 1.0, "mu_static": 0.1})
    with pytest.raises(ValueError):
        dimensionless_point(d, 0.0, 1.0)
