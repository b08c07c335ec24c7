"""Rows that hang on an unverified reading say so where the signer reads them (h175): 17.5.4.3(3)'s activation
force max(upper, 1.5 × nominal) [U], the record-strength floor on the breakaway, the design chart's caption."""

from __future__ import annotations

import pytest

from isolator.review import parameters as P
from isolator.review.codes import asce7_22

ELF = {"lower": {"T_M_s": 3.6, "beta_M": 0.15, "V_s_over_W": 0.2},
       "upper": {"T_M_s": 3.3, "beta_M": 0.2, "V_s_over_W": None}}


def _row(v_s: float, parameters: dict | None = None, upper: float = 0.089, nominal: float = 0.06) -> dict:
    elf = {"lower": {**ELF["lower"], "V_s_over_W": v_s}}
    params = P.resolve("asce7-22", {"Ws_over_W": 0.8, **(parameters or {})})
    return next(r for r in asce7_22.requirement_rows(elf, params, mu_static_lower=0.0459, mu_static_upper=upper,
                                                     mu_static_nominal=nominal) if r["id"] == "V_s_activation_limit")


def test_the_activation_row_prints_its_reading_margin_and_the_other_verdict():
    """The example building's case: upper µs 0.089 < 1.5 × 0.06 = 0.09, so the [U] factor decides the limit. Limit by
    hand: V_st = V_b (W_s/W)^(1 − 2.5 β); between the two readings' limits the row fails as printed and the note says
    it passes with the upper bound alone."""
    scale = 0.8 ** (1.0 - 2.5 * 0.15)
    limit, other = 0.09 * scale, 0.089 * scale
    between = 0.5 * (limit + other)
    row = _row(between)
    assert row["limit"] == pytest.approx(limit, rel=1e-14) and row["status"] == "fail"
    note = row["note"]
    assert "upper 0.089, 1.5 × nominal 0.06 = 0.09: the 1.5 × nominal reading governs" in note
    assert "activation_nominal_factor 1.5 [U]" in note
    assert f"margin {100 * (between / limit - 1):+.3g} %" in note
    assert f"with the upper bound alone (the other reading) the limit is {other:.4g}: pass, margin " \
           f"{100 * (between / other - 1):+.3g} %" in note
    # a narrow pass says its margin (the example building passed by +0.02 %)
    assert "margin +0.02 %" in _row(limit * 1.0002)["note"] and _row(limit * 1.0002)["status"] == "pass"


def test_the_activation_factor_is_a_parameter_printed_with_its_default():
    """1.5 was hard-coded ([U] in REVIEW_RULES 1.9): now `--set activation_nominal_factor=1.0` reads the upper bound
    alone (limit 0.089 × the scale, not 0.09 ×), and its row in the parameter table shows the default and mark."""
    scale = 0.8 ** (1.0 - 2.5 * 0.15)
    row = _row(0.2, {"activation_nominal_factor": 1.0})
    assert row["limit"] == pytest.approx(0.089 * scale, rel=1e-14)
    assert "the upper bound governs" in row["note"] and "other reading" not in row["note"]
    entry = next(t for t in P.table("asce7-22", P.resolve("asce7-22")) if t["name"] == "activation_nominal_factor")
    assert entry["value"] == 1.5 and entry["mark"] == "U"
    with pytest.raises(Exception, match="activation_nominal_factor"):
        P.resolve("asce7-22", {"activation_nominal_factor": 0.5})


def test_record_strength_floor_is_the_lower_bounds_breakaway_us(review):
    """A record moves a single pendulum once it passes µs (the breakaway), not µk: the floor is
    weak_pga_fraction × λ_min × µs = 0.1 × 0.8 × 0.06 = 0.0048 g (it was 0.1 × 0.8 × µk 0.05 = 0.004)."""
    row = next(r for r in review.checks if r["id"] == "record_strength")
    assert row["limit"] == pytest.approx(0.1 * 0.8 * 0.06, rel=1e-14)
    assert "the lower bound's breakaway µs (λ_min × µs) 0.048" in row["note"]


def _chart_data(**extra) -> dict:
    return {"fixed": {}, "paper_regimes": [], "paper_map": None, "isolated": "a rigid block on one surface", **extra}


def test_the_design_chart_caption_describes_what_is_drawn():
    """The caption described the paper's harmonic map on every chart; it is drawn only for a rigid block on one
    surface (`paper_map`)."""
    from isolator.report.design_chart import chart_caption

    drawn = chart_caption(_chart_data(paper_map={"map": object()}))
    assert "Behind the points, the paper's harmonic regime map" in drawn and "No regime map" not in drawn
    for isolated, regimes in (("a triple pendulum", ["III"]), ("a building on one surface", []),
                              ("a building on a double pendulum", ["1+2"])):
        text = chart_caption(_chart_data(isolated=isolated, paper_regimes=regimes))
        assert f"No regime map is drawn: the paper's map is a rigid block's on one surface, and these candidates " \
               f"are {isolated}" in text
        assert "harmonic regime map" not in text and "classifies" not in text
        assert ("on the backbone regime its motions reached" in text) is bool(regimes)
