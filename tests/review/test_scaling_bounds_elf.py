"""Scale factors, λ combination, B_M, the D_M fixed point and D_TM against hand calculations."""

from __future__ import annotations

import math

import numpy as np
import pytest

from isolator.design import Design
from isolator.review.bounds import combine_lambda, friction_bounds
from isolator.review.codes import asce7_22
from isolator.review.scaling import period_grid, scale_factors, suite_mean
from isolator.review.target import two_period_target

G = 9.80665


def test_common_and_fit_factors_by_hand():
    periods = np.geomspace(1.0, 4.0, 50)
    target = 0.9 / periods
    half, full = 0.5 * target, 1.0 * target
    # common: the mean is 0.75 target, so k = 1/0.75 (or 0.9/0.75 for a 90 % floor)
    assert scale_factors([half, full], target, method="common") == pytest.approx([4 / 3, 4 / 3], rel=1e-9)
    assert scale_factors([half, full], target, method="common", min_ratio=0.9) == pytest.approx([1.2, 1.2], rel=1e-9)
    # fit: shape factors 2 and 1 bring both onto the target, so k = 1
    assert scale_factors([half, full], target, method="fit") == pytest.approx([2.0, 1.0], rel=1e-9)
    # a tilted spectrum: f = exp(mean ln(target/S)), then the worst period sets k
    tilted = target * (periods / 2.0) ** 0.5
    f = math.exp(np.mean(-0.5 * np.log(periods / 2.0)))
    k = np.max(target / (f * tilted))
    assert scale_factors([tilted], target, method="fit")[0] == pytest.approx(k * f, rel=1e-9)
    # the scaled average meets the floor, with equality at its worst period
    factors = scale_factors([half, tilted], target, method="common")
    ratio = suite_mean([half, tilted], factors) / target
    assert ratio.min() == pytest.approx(1.0, rel=1e-9) and ratio.min() >= 1.0


def test_component_spectra_average_both_components():
    periods = np.geomspace(1.0, 2.0, 5)
    target = np.ones(5)
    spectra = np.array([[[0.5] * 5, [1.5] * 5]])  # one pair, two components: mean 1.0
    assert scale_factors(spectra, target)[0] == pytest.approx(1.0, rel=1e-9)
    assert periods.size == 5


def test_period_grid_has_the_ends_and_the_T_M_values():
    base, grid = period_grid(2.0, 4.0, 300, (2.5, 3.3, 9.0))
    assert base.size == 300 and base[0] == 2.0 and base[-1] == pytest.approx(4.0)
    assert 2.5 in grid and 3.3 in grid and 9.0 not in grid and grid.size == 302


def test_lambda_combination_asce_and_en():
    # ASCE 7-22 Eqs. 17.2-1/-2 with f_ae = 0.75
    assert combine_lambda(1.1, 1.2, 1.15, side="max") == pytest.approx((1 + 0.75 * 0.1) * 1.2 * 1.15)
    assert combine_lambda(0.9, 0.9, 0.85, side="min") == pytest.approx((1 - 0.75 * 0.1) * 0.9 * 0.85)
    # EN 15129: the plain product
    assert combine_lambda(1.1, 1.2, 1.15, side="max", code="en15129") == pytest.approx(1.1 * 1.2 * 1.15)
    design = Design.from_mapping({"name": "b", "mass_kg": 1.0, "radius_m": 2.0, "mu_static": 0.06,
                                  "mu_kinetic": 0.05, "lambda_ae_max": 1.1, "lambda_ae_min": 0.9,
                                  "lambda_test_max": 1.2, "lambda_test_min": 0.9, "lambda_spec_max": 1.15,
                                  "lambda_spec_min": 0.85})
    b = friction_bounds(design)
    assert b.mu_upper == pytest.approx(0.05 * 1.075 * 1.2 * 1.15)
    assert b.mu_lower == pytest.approx(0.05 * 0.925 * 0.9 * 0.85)
    explicit = Design.from_mapping({"name": "b", "mass_kg": 1.0, "radius_m": 2.0, "mu_static": 0.06,
                                    "mu_kinetic": 0.05, "mu_upper": 0.07, "mu_lower": 0.04})
    e = friction_bounds(explicit)
    assert (e.lambda_max, e.lambda_min) == pytest.approx((1.4, 0.8))


@pytest.mark.parametrize("beta,expected", [(0.0, 0.8), (0.02, 0.8), (0.035, 0.9), (0.075, 1.1), (0.15, 1.35),
                                           (0.25, 1.6), (0.45, 1.95), (0.5, 2.0), (0.8, 2.0)])
def test_B_M_table_interpolation(beta, expected):
    assert asce7_22.damping_coefficient(beta) == pytest.approx(expected)


def test_D_M_fixed_point_against_a_hand_iteration():
    """FPS R = 2.5 m, µ = 0.05 under S_M1 = 0.9 g: successive substitution written out by hand."""
    design = Design.from_mapping({"name": "h", "mass_kg": 1000.0, "radius_m": 2.5, "mu_static": 0.05})
    target = two_period_target(1.5, 0.9, 8.0)
    table = [(0.02, 0.8), (0.05, 1.0), (0.10, 1.2), (0.20, 1.5), (0.30, 1.7), (0.40, 1.9), (0.50, 2.0)]

    def b_m(beta):
        for (b0, v0), (b1, v1) in zip(table, table[1:], strict=False):
            if b0 <= beta <= b1:
                return v0 + (v1 - v0) * (beta - b0) / (b1 - b0)
        return 0.8 if beta < 0.02 else 2.0

    d = 0.5
    for _ in range(200):
        t = 2 * math.pi / math.sqrt(G / 2.5 + 0.05 * G / d)   # T_M = 2π sqrt(W/(k_M g)), k_M = W/R + µW/D
        beta = 2 * 0.05 / (math.pi * (0.05 + d / 2.5))         # β = 2µ/(π(µ + D/R))
        d = G * 0.9 * t / (4 * math.pi ** 2 * b_m(beta))      # T_S ≤ T ≤ T_L: S_a T² = S_M1 T
    elf = asce7_22.elf_displacement(design, 0.05, target)
    assert elf["D_M_m"] == pytest.approx(d, rel=1e-9)
    assert elf["T_M_s"] == pytest.approx(t, rel=1e-9) and elf["beta_M"] == pytest.approx(beta, rel=1e-9)
    assert elf["V_b_over_W"] == pytest.approx(d / 2.5 + 0.05, rel=1e-9)
    assert asce7_22.elf_displacement(design, 0.05, target, form="SM1")["D_M_m"] == pytest.approx(d, rel=1e-9)


def test_no_sliding_when_friction_exceeds_the_demand():
    design = Design.from_mapping({"name": "h", "mass_kg": 1000.0, "radius_m": 2.5, "mu_static": 0.5})
    elf = asce7_22.elf_displacement(design, 0.5, two_period_target(0.2, 0.1, 8.0))
    assert elf["D_M_m"] == 0.0 and "no sliding" in elf["notes"][0]


def test_D_TM_by_hand():
    params = {"D_TM_floor": 1.15, "P_T_min": 1.0, "accidental_e": 0.05}
    plan = {"b_m": 40.0, "d_m": 25.0, "eccentricity_m": 0.5, "y_m": 20.0}
    by_hand = max(1 + 20.0 * 12 * (0.5 + 0.05 * p) / (40.0 ** 2 + 25.0 ** 2) for p in (40.0, 25.0))
    assert asce7_22.torsion_factor(plan, params)["factor"] == pytest.approx(by_hand)
    assert asce7_22.torsion_factor(None, params)["factor"] == 1.15
    small = {"b_m": 40.0, "d_m": 25.0, "y_m": 1.0, "P_T": 1.3}
    assert asce7_22.torsion_factor(small, params)["factor"] == 1.15  # the floor governs


def test_factors_of_a_pair_and_its_double_on_real_records():
    """Pair B = 2 × pair A: RotD100_B = 2 RotD100_A, so 'fit' gives SF_A = 2 SF_B and 'common' k = max(T/S_A)/1.5."""
    from pathlib import Path

    from isolator.motion import read_ground_motion
    from isolator.review.spectra import pair_spectra

    folder = Path(__file__).resolve().parents[2] / "isolator" / "data" / "suites" / "example" / "landers1992_YER"
    x = read_ground_motion(folder / "RSN900_LANDERS_YER270.AT2")
    y = read_ground_motion(folder / "RSN900_LANDERS_YER360.AT2")
    _, grid = period_grid(2.0, 4.0, 200)
    a = pair_spectra(x.acceleration_m_s2, y.acceleration_m_s2, x.dt_s, grid)["rotd100_m_s2"] / G
    b = pair_spectra(2 * x.acceleration_m_s2, 2 * y.acceleration_m_s2, x.dt_s, grid)["rotd100_m_s2"] / G
    np.testing.assert_allclose(b, 2 * a, rtol=1e-12)
    target = two_period_target(1.5, 0.9, 8.0).sa_g(grid)
    fit = scale_factors([a, b], target, method="fit")
    assert fit[0] == pytest.approx(2 * fit[1], rel=1e-12)
    common = scale_factors([a, b], target, method="common")
    assert common[0] == pytest.approx(np.max(target / a) / 1.5, rel=1e-9)
