"""The review's bearing rows: the capacity at the corner bearing and the factored vertical loads (issue 22 audit).

Hand numbers: the example building's torsion factor by Eq. 17.5-3 (REVIEW_RULES 1.9) from its TOML's plan and
layout, written out here; the 2.3.6 factors with S_MS = 1.5 g of the example target: 1.2 + 0.2 × 1.5 = 1.5 and
0.9 − 0.2 × 1.5 = 0.6 on the gravity share W/20 = 9.3e6 × 9.80665 / 20 N.
"""

from __future__ import annotations

import math

import pytest

from isolator.errors import ReviewError
from isolator.review import checks as C
from isolator.review.codes import asce7_22
from isolator.review.parameters import resolve

#: Eq. 17.5-3 for the example building, loading along y: y = 16 m (the farthest bearing along x),
#: e = 0.5 m + 0.05 × 34 m = 2.2 m, P_T = sqrt(mean(x² + y²)) / sqrt((b² + d²)/12) = sqrt(208) / sqrt(1832/12)
P_T = math.sqrt(208.0) / math.sqrt((34.0 ** 2 + 26.0 ** 2) / 12.0)
TORSION = 1.0 + 16.0 / P_T ** 2 * 12.0 * 2.2 / (34.0 ** 2 + 26.0 ** 2)
SHARE_N = 9.3e6 * 9.80665 / 20.0


def test_the_hand_torsion_factor_is_the_documented_one():
    assert round(TORSION, 3) == 1.169 and round(P_T, 3) == 1.167


def test_capacity_rows_read_the_corner_bearing():
    """A centre-of-mass displacement within the 1.4 m capacity fails when the factor takes its corner past it."""
    analyses = {"lower": {"Chuetsu-oki": {"peak_displacement_m": 1.32}, "Duzce": {"peak_displacement_m": 1.25}},
                "upper": {"Chuetsu-oki": {"peak_displacement_m": 1.336}, "PTS": {"peak_displacement_m": 1.19}}}
    assert [r["status"] for r in C.record_capacity(analyses, 1.4)] == ["pass"]  # the centre of mass: within
    rows = C.record_capacity(analyses, 1.4, torsion_factor=TORSION)
    # by hand: 1.32 × 1.169 = 1.543, 1.25 × 1.169 = 1.461, 1.336 × 1.169 = 1.562 > 1.4; 1.19 × 1.169 = 1.391 ≤ 1.4
    assert [(r["bound"], r["pair"]) for r in rows] == [("lower", "Chuetsu-oki"), ("lower", "Duzce"),
                                                        ("upper", "Chuetsu-oki")]
    for r, d in zip(rows, (1.32, 1.25, 1.336), strict=True):
        assert r["status"] == "fail" and r["value"] == pytest.approx(d * TORSION, rel=1e-15) and r["limit"] == 1.4
        assert r["centre_of_mass_m"] == d and r["torsion_factor"] == TORSION
        assert f"corner bearing {TORSION:.4g} × {d:.4g} m" in r["note"] and "centre of mass within it" in r["note"]
    assert [round(r["value"], 2) for r in rows] == [1.54, 1.46, 1.56]
    # below every corner: one pass row with the largest corner displacement, named
    (ok,) = C.record_capacity(analyses, 1.6, torsion_factor=TORSION)
    assert ok["status"] == "pass" and ok["value"] == pytest.approx(1.336 * TORSION, rel=1e-15)
    assert "at the corner bearing" in ok["note"] and "Chuetsu-oki, upper bound" in ok["note"]
    # a factor of 1 reads the centre of mass: the same verdicts and values as without
    same = C.record_capacity(analyses, 1.3, torsion_factor=1.0)
    assert [(r["pair"], r["value"], r["status"]) for r in same] == [
        (r["pair"], r["value"], r["status"]) for r in C.record_capacity(analyses, 1.3)]


def test_a_rim_held_analysis_fails_at_its_corner_too():
    """The rim holds the centre of mass at the capacity: its corner reads factor × capacity, a fail with the reason,
    never a contradiction (a pass beside the rim's fail)."""
    analyses = {"upper": {"a": {"peak_displacement_m": 1.0, "ultimate_displacement_reached": True,
                                "impact_impulse_m_s": 0.01},
                          "b": {"peak_displacement_m": 0.8}}}
    rows = C.record_capacity(analyses, 1.0, mass_kg=2.0e6, torsion_factor=1.15)
    assert [(r["pair"], r["status"]) for r in rows] == [("a", "fail")]  # b: 0.92 m at its corner, within
    (a,) = rows
    assert a["value"] == pytest.approx(1.15) and a["centre_of_mass_m"] == 1.0
    assert "REACHED" in a["note"] and "2e+04 N·s" in a["note"]
    assert "held at the rim" in a["note"] and "corner bearing 1.15 × 1 m = 1.15 m exceeds the capacity" in a["note"]
    # b past the capacity at its corner only when the factor says so: 0.8 × 1.3 = 1.04 > 1
    rows = C.record_capacity(analyses, 1.0, torsion_factor=1.3)
    assert [(r["pair"], r["status"]) for r in rows] == [("a", "fail"), ("b", "fail")]


def test_capacity_at_corner_is_a_printed_parameter():
    p = resolve("asce7-22")
    assert p["capacity_at_corner"] is True and resolve("en15129")["capacity_at_corner"] is True
    assert resolve("asce7-22", {"capacity_at_corner": "false"})["capacity_at_corner"] is False
    with pytest.raises(ReviewError, match="capacity_at_corner"):
        resolve("asce7-22", {"capacity_at_corner": "sometimes"})


def test_vertical_load_factors_by_hand():
    """17.2.4.6 / 2.3.6 with S_MS = 1.5 g: (1.2 + 0.2 × 1.5, 0.9 − 0.2 × 1.5) = (1.5, 0.6); with the vertical
    analysed the dead-load factors alone (1.2, 0.9): E_v is in the loads already."""
    p = resolve("asce7-22")
    assert (p["dead_load_factor_max"], p["dead_load_factor_min"], p["vertical_Ev_coefficient"]) == (1.2, 0.9, 0.2)
    assert asce7_22.vertical_load_factors(1.5, p, vertical_analysed=False) == pytest.approx((1.5, 0.6), rel=1e-15)
    assert asce7_22.vertical_load_factors(1.5, p, vertical_analysed=True) == (1.2, 0.9)
    q = resolve("asce7-22", {"dead_load_factor_max": 1.4, "dead_load_factor_min": 0.8, "vertical_Ev_coefficient": 0})
    assert asce7_22.vertical_load_factors(1.5, q, vertical_analysed=False) == (1.4, 0.8)
    for name, bad in (("dead_load_factor_max", 0.9), ("dead_load_factor_min", 1.1), ("vertical_Ev_coefficient", 2)):
        with pytest.raises(ReviewError, match=name):
            resolve("asce7-22", {name: bad})


def test_the_audits_factored_figures_by_hand():
    """The audit's figures from the documented unfactored loads of the example review (bearing 5: P_max 6.20 MN of
    a 12 MN capacity; bearing 16's least load 2.93 MN): E_h = P − W/20 is unchanged, the share is factored."""
    p_max, p_min = 6.20e6, 2.93e6
    f_max, f_min = asce7_22.vertical_load_factors(1.5, resolve("asce7-22"), vertical_analysed=False)
    stability = (p_max + (f_max - 1.0) * SHARE_N) / 1.2e7
    least = p_min + (f_min - 1.0) * SHARE_N
    # the documented loads are rounded to 0.005 MN (± 4e-4 of the ratio, ± 5e3 N of the load): the audit's 0.706
    # and 1.10 MN (from the unrounded loads) within that and their own last digit
    assert stability == pytest.approx(0.706, abs=1e-3) and least == pytest.approx(1.10e6, abs=1.1e4)
    row = C.vertical_load_stability([stability * 1.2e7], [1.2e7], basis="factored (2.3.6 [U]): …")
    assert row["status"] == "pass" and "unfactored" not in row["note"] and "factored (2.3.6" in row["note"]
    row = C.uplift(0, 0, least, basis="factored (2.3.6 [U]): …")
    assert row["status"] == "pass" and row["value"] == least and "unfactored" not in row["note"]
    assert "not applied [U]" in C.uplift(0, 0, least)["note"]  # without a basis: said unfactored
