"""The restoring-force rule on both sides of D = 0.05 R, the ≥ 7 mean rule, status logic."""

from __future__ import annotations

import math

import pytest

from isolator.design import Design
from isolator.review import checks as C
from isolator.review.codes import asce7_22, en15129


@pytest.mark.parametrize("radius", [1.5, 3.0])
def test_restoring_force_both_sides_of_five_percent_of_R(radius):
    design = Design.from_mapping({"name": "r", "mass_kg": 5.0e5, "radius_m": radius, "mu_static": 0.05})
    for d, status in ((0.05 * radius * 1.001, "pass"), (0.05 * radius * 0.999, "fail")):
        ratio = asce7_22.restoring_force_ratio(design, d)
        assert ratio == pytest.approx(d / (2 * radius))  # F(D) − F(D/2) = W D/(2R)
        row = C.restoring_force(ratio, 0.025, displacement_m=d, radius_m=radius)
        assert row["status"] == status and row["clause"] == "ASCE 7-22 17.2.4.4"


def test_suite_value_mean_of_seven_else_max():
    seven = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7]
    assert C.suite_value(seven) == {"value": pytest.approx(0.4), "rule": "mean", "n": 7}
    assert C.suite_value(seven[:6]) == {"value": 0.6, "rule": "max", "n": 6}
    assert C.suite_value(seven[:6], n_for_mean=3)["rule"] == "mean"
    assert C.suite_value([float("nan")] + seven)["n"] == 7  # failed analyses do not count


def test_status_logic_and_missing_limits():
    assert C.at_most("a", "c", 1.0, 2.0)["status"] == "pass"
    assert C.at_most("a", "c", 3.0, 2.0)["status"] == "fail"
    assert C.at_most("a", "c", 3.0, None)["status"] == "not checked"
    assert C.at_least("a", "c", 3.0, 2.0)["status"] == "pass"
    band = C.usable_band([("p1", 0.08), ("p2", None)], range_hi_s=4.0)
    # one corner unknown: not checked for that pair, and the row says how many (never a pass on half the suite)
    assert band["status"] == "not checked" and band["value"] == pytest.approx(10.0) and "p2" in band["note"]
    assert "1 of 2 pair(s)" in band["note"]
    assert C.usable_band([("p1", 0.08), ("p2", 0.05)], range_hi_s=4.0)["status"] == "pass"
    assert C.usable_band([("p1", 0.3), ("p2", None)], range_hi_s=4.0)["status"] == "fail"  # a known one falls short
    assert C.usable_band([("p1", 0.3)], range_hi_s=4.0)["status"] == "fail"  # 1/(1.25 × 0.3) = 2.7 s
    assert C.usable_band([("p1", None)], range_hi_s=4.0)["status"] == "not checked"


def test_en15129_restoring_capability_is_d_over_mu_R():
    design = Design.from_mapping({"name": "r", "mass_kg": 1.0, "radius_m": 2.0, "mu_static": 0.06})
    assert en15129.static_residual_m(design, 0.05) == pytest.approx(0.1)
    assert en15129.restoring_capability_ratio(design, 0.05, 0.3) == pytest.approx(3.0)


def test_single_record_checks_and_the_labelled_measure():
    """One record: capacity, D/R, restoring force, transmitted/PGA, scale factor, usable band; no AMPLIFIES."""
    import numpy as np

    from isolator.analysis import analyse, verdicts
    from isolator.motion import GroundMotion
    from isolator.review.record_checks import with_record_checks

    t = np.arange(0, 20, 0.01)
    motion = GroundMotion.from_array(3.0 * np.sin(2 * np.pi * 0.5 * t) * np.exp(-0.1 * t), 0.01).scaled(2.0)
    design = Design.from_mapping({"name": "x" * 120, "mass_kg": 1.0e5, "radius_m": 2.0, "mu_static": 0.05,
                                  "displacement_capacity_m": 3.0})  # not reached (at the rim: test_multisurface)
    a = with_record_checks(analyse(design, motion))  # the caller adds the one-record checks
    rows = {row["id"]: row for row in a.to_dict()["checks"]}
    d = a.engineering["peak_displacement_m"]
    assert rows["displacement_capacity"]["status"] == ("pass" if d <= 3.0 else "fail")
    assert rows["D_over_R"]["value"] == pytest.approx(d / 2.0)
    assert rows["restoring_force"]["status"] == ("pass" if d >= 0.1 else "fail")
    assert rows["scale_factor"]["value"] == pytest.approx(2.0) and rows["scale_factor"]["status"] == "pass"
    assert rows["usable_band"]["status"] == "not checked"  # an array states no filter corner
    text = " ".join(verdicts(a))
    assert "AMPLIFIES" not in text and "A0 = PGV²/PGA" in text and "Paper's measure A" in text


@pytest.mark.parametrize("beta,divisor", [(0.05, 1.0), (0.15, math.sqrt(2.0)), (0.5, 1 / 0.55)])
def test_en_damping_correction(beta, divisor):
    assert en15129.damping_divisor(beta) == pytest.approx(divisor)


def test_parameters_resolve_with_marks_and_the_090_reading():
    from isolator.errors import ReviewError
    from isolator.review.parameters import PARAMETERS, resolve, table

    asce = resolve("asce7-22")
    assert asce["min_ratio"] == 1.0 and asce["mean_ratio_min"] is None and "gamma_x" not in asce
    relaxed = resolve("asce7-22", {"min_ratio": "0.9"})
    assert relaxed["min_ratio"] == 0.9 and relaxed["mean_ratio_min"] == 1.0  # REVIEW_RULES 1.5
    assert resolve("en15129", {"n_for_mean": "3"})["n_for_mean"] == 3
    assert resolve("asce7-22", {"abrupt_hysteresis": "true"})["abrupt_hysteresis"] is True
    for bad in ({"n_for_mean": "2.5"}, {"D_M_form": "X"}, {"nonsense": 1}, {"f_ae": "-1"}):
        with pytest.raises(ReviewError):
            resolve("asce7-22", bad)
    rows = table("asce7-22", asce)
    assert all(row["mark"] for row in rows) and {row["name"] for row in rows} <= set(PARAMETERS)
    assert next(r for r in rows if r["name"] == "range_lo_factor")["mark"] == "U"
