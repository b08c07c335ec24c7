"""Session 25, read as the signer (h227): every printed input traceable to what the design gave.

Each test fails on c765efa (the base of the session); how is said in its docstring.
"""

from __future__ import annotations

import math

import pytest

from isolator.review import parameters as P
from isolator.review.codes import asce7_22


def test_a_layout_p_t_below_the_floor_is_printed_as_the_floor_not_as_the_layout_s():
    """20 bearings within ±4 × ±3 m under a 34 × 26 m plan: Eq. 17.5-4 gives P_T = √(Σ(x² + y²)/N) / r_I =
    √(mean x² + mean y²) / √((34² + 26²)/12) = 0.2918 (by hand below); the floor P_T_min = 1 is what Eq. 17.5-3
    used.  On c765efa the basis said "P_T = 1 (the bearing layout)" — a P_T no layout gave — and the JSON had no
    raw value (KeyError 'P_T_raw')."""
    xs = [-4.0, -2.0, 0.0, 2.0, 4.0]
    ys = [-3.0, -1.0, 1.0, 3.0]
    mean_sq = sum(x * x for x in xs) / 5 + sum(y * y for y in ys) / 4
    p_t = math.sqrt(mean_sq) / math.sqrt((34.0 ** 2 + 26.0 ** 2) / 12.0)
    assert p_t == pytest.approx(0.29181, abs=1e-5)
    layout = {"P_T": p_t, "y_for_loading_x_m": 3.0, "y_for_loading_y_m": 4.0}
    params = P.resolve("asce7-22", {})
    t = asce7_22.torsion_factor({"b_m": 34.0, "d_m": 26.0, "eccentricity_m": 0.5}, params, layout)
    assert t["P_T"] == 1.0 and t["P_T_raw"] == pytest.approx(p_t, rel=1e-15)
    assert "P_T = 1 (P_T_min; the bearing layout: 0.2918)" in t["basis"]
    assert "P_T = 1 (the bearing layout)" not in t["basis"]
    # the bracket by hand with P_T = 1: along y, e = 0.5 + 0.05 × 34 = 2.2 m, y = 4 m; the 1.15 floor governs
    raw = 1.0 + 4.0 * 12.0 * 2.2 / (34.0 ** 2 + 26.0 ** 2)
    assert t["raw_factor"] == pytest.approx(raw, rel=1e-15) and t["factor"] == 1.15
    # a P_T at or above the floor is said as before
    above = asce7_22.torsion_factor({"b_m": 34.0, "d_m": 26.0}, params, {**layout, "P_T": 1.167})
    assert "P_T = 1.167 (the bearing layout)" in above["basis"]


def test_the_summary_plan_line_says_when_the_floor_replaced_the_design_s_p_t():
    """The PDF's Plan line printed "P_T = 1" alone; now it says the floor and the layout's value (on c765efa
    ``p_t_floor_said`` does not exist: ImportError)."""
    from isolator.report.review_pages import p_t_floor_said

    assert p_t_floor_said({"P_T": 1.0, "P_T_raw": 0.2918}) == " (the floor P_T_min; 0.2918 from the design)"
    assert p_t_floor_said({"P_T": 1.167, "P_T_raw": 1.167}) == ""
    assert p_t_floor_said({"P_T": 1.15}) == ""  # a JSON written before the raw value was kept
