"""ASCE 7-22 17.5.4.3(1): the superstructure's V_s ≥ the fixed-base ELF force of W_s at T_M (C_s of 12.8.1.1).

Every number is worked by hand in the comments (S_DS, S_D1 in g, T in s); the review-level check on a real
building is in ``test_structure_review.py`` (``_assert_building_rows``).
"""

from __future__ import annotations

import pytest

from isolator.errors import ReviewError
from isolator.review import checks as C
from isolator.review.codes import asce7_22
from isolator.review.parameters import resolve, table
from isolator.review.target import Target, design_values, two_period_target


@pytest.mark.parametrize(("s_ds", "s_d1", "t_l", "t", "r", "i_e", "c_s", "equation"), [
    # T = 3 s, R = 8: 12.8-2 1.0/8 = 0.125; 12.8-3 0.6/(3 × 8) = 0.025; the minimum 0.044 × 1.0 × 1 governs
    (1.0, 0.6, 8.0, 3.0, 8.0, 1.0, 0.044, "12.8-5 (0.044 S_DS I_e)"),
    # T = 2 s, R = 4, I_e = 1.5: R/I_e = 8/3; 12.8-2 0.375; 12.8-3 0.6/(2 × 8/3) = 0.1125 > 0.044 × 1.5 = 0.066
    (1.0, 0.6, 8.0, 2.0, 4.0, 1.5, 0.1125, "12.8-3"),
    # T = 5 s > T_L = 4 s, R = 1: 12.8-4 0.6 × 4/25 = 0.096 (12.8-3 would give 0.12)
    (1.0, 0.6, 4.0, 5.0, 1.0, 1.0, 0.096, "12.8-4"),
    # T = 0.3 s, R = 8: 12.8-2 0.125 < 12.8-3 0.6/(0.3 × 8) = 0.25: the plateau governs
    (1.0, 0.6, 8.0, 0.3, 8.0, 1.0, 0.125, "12.8-2"),
    # S_DS = 0.2: 0.044 × 0.2 = 0.0088 < 0.01; 12.8-3 0.1/(3 × 8) = 0.00417: the absolute floor 0.01 governs
    (0.2, 0.1, 8.0, 3.0, 8.0, 1.0, 0.01, "12.8-5 (0.01)"),
])
def test_fixed_base_seismic_coefficient_by_hand(s_ds, s_d1, t_l, t, r, i_e, c_s, equation):
    out = asce7_22.fixed_base_seismic_coefficient(s_ds, s_d1, t_l, t, r, i_e)
    assert out["C_s"] == pytest.approx(c_s, rel=1e-14) and out["equation"] == equation


def test_fixed_base_coefficient_refuses_a_vanishing_period_or_r():
    for bad in ({"period_s": 0.0}, {"r": 0.0}, {"i_e": 0.0}):
        kwargs = {"s_ds": 1.0, "s_d1": 0.6, "t_l": 8.0, "period_s": 3.0, "r": 8.0, "i_e": 1.0, **bad}
        with pytest.raises(ValueError):
            asce7_22.fixed_base_seismic_coefficient(**kwargs)


def test_design_values_of_the_target():
    # MCE_R S_MS = 1.5, S_M1 = 0.9: S_DS = 1.0, S_D1 = 0.6 (11.4.5)
    mce = design_values(two_period_target(1.5, 0.9, 8.0))
    assert mce["S_DS"] == pytest.approx(1.0, rel=1e-15) and mce["S_D1"] == pytest.approx(0.6, rel=1e-15)
    assert mce["T_L"] == 8.0 and "2/3" in mce["basis"]
    given = Target("asce7-two-period", {"S_MS": 1.5 * 0.7, "S_M1": 1.5 * 0.35, "T_L": 6.0,
                                        "from_design_values": {"S_DS": 0.7, "S_D1": 0.35}})
    assert design_values(given)["S_DS"] == 0.7 and design_values(given)["S_D1"] == 0.35  # as given, exactly
    assert design_values(Target("en1998-elastic", {"a_g_g": 0.3, "S": 1.2, "T_B": 0.15, "T_C": 0.5,
                                                   "T_D": 2.0})) is None


ELF = {"lower": {"T_M_s": 3.2, "beta_M": 0.2, "V_s_over_W": 0.05},
       "upper": {"T_M_s": 2.0, "beta_M": 0.25, "V_s_over_W": 0.06}}
KWARGS = {"mu_static_lower": 0.04, "mu_static_upper": 0.078, "mu_static_nominal": 0.06}


def _rows(params, fixed_base):
    return {r["id"]: r for r in asce7_22.requirement_rows(ELF, params, fixed_base=fixed_base, **KWARGS)}


def test_fixed_base_row_by_hand():
    """W_s/W = 0.8, R = 4, I_e = 1.25 (R/I_e = 3.2), S_DS = 1.0, S_D1 = 0.6, T_L = 8:
    lower T_M = 3.2: 0.6/(3.2 × 3.2) = 0.05859 > 0.044 × 1.25 = 0.055 → C_s W_s/W = 0.046875; V_s 0.05, margin 1.0667
    upper T_M = 2.0: 0.6/(2.0 × 3.2) = 0.09375 → C_s W_s/W = 0.075; V_s 0.06 < 0.075: fails, margin 0.8 (smaller)."""
    params = resolve("asce7-22", {"importance_factor_Ie": 1.25, "Ws_over_W": 0.8})
    fixed = asce7_22.fixed_base_limits(ELF, design_values(two_period_target(1.5, 0.9, 8.0)), 4.0, params)
    assert fixed["per_bound"]["lower"]["V_over_W"] == pytest.approx(0.046875, rel=1e-14)
    assert fixed["per_bound"]["upper"]["V_over_W"] == pytest.approx(0.075, rel=1e-14)
    row = _rows(params, fixed)["V_s_fixed_base_limit"]
    assert row["status"] == "fail" and row["value"] == 0.06 and row["limit"] == pytest.approx(0.075, rel=1e-14)
    assert "upper bound" in row["note"] and "Eq. 12.8-3 governs" in row["note"] and "I_e = 1.25" in row["note"]
    assert "12.8-6" in row["note"]  # the S_1 minimum it cannot apply is said
    # R = 5, I_e = 1 (default): upper 0.6/(2 × 5) = 0.06 → × 0.8 = 0.048 ≤ V_s 0.06, margin 1.25; lower
    # 0.6/(3.2 × 5) = 0.0375 < 0.044 → 0.044 × 0.8 = 0.0352, margin 0.05/0.0352 = 1.42: the upper bound shown, passes
    plain = resolve("asce7-22", {"Ws_over_W": 0.8})
    fixed = asce7_22.fixed_base_limits(ELF, design_values(two_period_target(1.5, 0.9, 8.0)), 5.0, plain)
    assert fixed["per_bound"]["lower"]["V_over_W"] == pytest.approx(0.0352, rel=1e-14)
    assert fixed["per_bound"]["lower"]["equation"] == "12.8-5 (0.044 S_DS I_e)"
    row = _rows(plain, fixed)["V_s_fixed_base_limit"]
    assert row["limit"] == pytest.approx(0.048, rel=1e-14) and row["status"] == "pass" and "upper" in row["note"]


def test_fixed_base_row_not_checked_says_why():
    params = resolve("asce7-22")
    no_r = asce7_22.fixed_base_limits(ELF, design_values(two_period_target(1.5, 0.9, 8.0)), None, params)
    row = _rows(params, no_r)["V_s_fixed_base_limit"]
    assert row["status"] == "not checked" and "response_modification_R" in row["note"]
    table_target = Target("table", {"spectrum_csv": "t.csv"})
    row = _rows(params, asce7_22.fixed_base_limits(ELF, design_values(table_target), 4.0, params))[
        "V_s_fixed_base_limit"]
    assert row["status"] == "not checked" and "two-period target" in row["note"]
    assert _rows(params, None)["V_s_fixed_base_limit"]["status"] == "not checked"


def test_the_fixed_base_limit_joins_the_superstructure_shear_row():
    """The 17.6.4.2 row's limit is the largest of 0.6 V_s and every 17.5.4.3 limit computed, each stated."""
    row = C.superstructure_shear(0.05, 0.6, 0.2, r_i=2.0, limits={"17.5.4.3(1) fixed-base = 0.075": 0.075,
                                                                    "17.5.4.3(3) activation = 0.07": 0.07})
    # value 0.2/2 = 0.1 ≥ max(0.03, 0.075, 0.07)
    assert row["limit"] == pytest.approx(0.075) and row["status"] == "pass" and row["value"] == pytest.approx(0.1)
    assert "0.6 × ELF V_s/W = 0.6 × 0.05 = 0.03" in row["note"] and "activation = 0.07" in row["note"]
    assert row["note"].endswith("17.5.4.3(1) fixed-base = 0.075 governs")


def test_importance_factor_is_a_printed_parameter_with_a_range():
    values = resolve("asce7-22")
    assert values["importance_factor_Ie"] == 1.0
    entry = next(r for r in table("asce7-22", values) if r["name"] == "importance_factor_Ie")
    assert entry["mark"] == "U" and "17.5.4.3(1)" in entry["rule"]
    for bad in ("0.9", "1.6", "abc"):
        with pytest.raises(ReviewError, match="importance_factor_Ie"):
            resolve("asce7-22", {"importance_factor_Ie": bad})
    assert "importance_factor_Ie" not in resolve("en15129")
