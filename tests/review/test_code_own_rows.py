"""Each code's rows apply that code's rules (issue 22: "a review an engineer can sign").

* An EN 15129 / EN 1998-1 review cites no ASCE clause and applies no ASCE rule: the record-selection rows cite
  EN 1998-1 3.2.3.1, and each isolator's displacement is γ_x × δ_i × the centre of mass's, δ_i = 1 + e_tot y_i / r²
  (EN 1998-1 10.9.6 [U]) with no 1.15 floor (ASCE 7-22 Eq. 17.5-3's) — checked on a layout where the floor would
  bite (δ = 1.0625 < 1.15), the suite value aggregated here from the analyses' own peaks.
* The ASCE review's ``D_M_capacity`` reads the corner bearing, as ``record_capacity`` does (``capacity_at_corner``).
* The single-record report reads its capacity where the review does: the corner bearing with a [plan].
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from isolator.design import Design
from isolator.review.run import run_review
from isolator.review.suite import load_suite
from isolator.review.target import Target

#: EN 1998-1 type 1 spectrum, ground type C, a_g = 0.35 g
EN_TARGET = Target("en1998-elastic", {"a_g_g": 0.35, "S": 1.15, "T_B": 0.2, "T_C": 0.6, "T_D": 2.0}, name="EC8 C")
#: a 10 m × 10 m plan on 4 bearings at (±4, ±4) m, no actual eccentricity: r² = 32 m², e_tot = 0.05 × 10 = 0.5 m,
#: so δ = 1 + 0.5 × 4 / 32 = 1.0625 at every bearing — ASCE's Eq. 17.5-3 gives the same bracket and floors it at 1.15
SQUARE = {"name": "FPS on 4 bearings", "mass_kg": 1.0e6, "radius_m": 2.5, "mu_static": 0.06, "mu_kinetic": 0.05,
          "displacement_capacity_m": 0.5, "lambda_max": 1.3, "lambda_min": 0.8,
          "plan": {"b_m": 10.0, "d_m": 10.0, "eccentricity_m": 0.0},
          "bearing_position": [{"x_m": x, "y_m": y} for x in (-4.0, 4.0) for y in (-4.0, 4.0)]}
DELTA = 1.0 + 0.5 * 4.0 / 32.0


def _largest_suite_peak(review, n_for_mean: int) -> float:
    """The design displacement of the centre of mass, independently of isolator.review.checks: per bound the mean of
    ≥ n analyses, else the largest; the larger bound."""
    out = []
    for results in review.analyses.values():
        peaks = np.array([r["peak_displacement_m"] for r in results.values() if "error" not in r])
        out.append(peaks.mean() if peaks.size >= n_for_mean else peaks.max())
    return float(max(out))


@pytest.fixture(scope="module")
def en_square(inputs):
    return run_review(Design.from_mapping(SQUARE), EN_TARGET, load_suite(inputs / "suite.toml"), code="en15129",
                      jobs=1, nominal=False, cache_dir=inputs / "cache")


def test_en_rows_cite_en_clauses_and_apply_no_asce_floor(en_square):
    r = en_square
    rows = {row["id"]: row for row in r.checks}
    assert not [row["id"] for row in r.checks if "ASCE" in row["clause"]]  # no EN row on an ASCE authority
    assert rows["record_selection"]["clause"].startswith("EN 1998-1 3.2.3.1")
    assert rows["distinct_motions"]["clause"].startswith("EN 1998-1 3.2.3.1")
    torsion = r.to_dict()["torsion"]
    assert torsion["bearing_factors"] == pytest.approx([DELTA] * 4, rel=1e-14)
    assert torsion["factor"] == pytest.approx(DELTA, rel=1e-14)  # not 1.15: ASCE's floor is not an EN rule
    d = _largest_suite_peak(r, 7)
    row = rows["displacement_capacity"]
    assert row["value"] == pytest.approx(1.2 * DELTA * d, rel=1e-12)
    assert row["status"] == ("pass" if 1.2 * DELTA * d <= 0.5 else "fail")
    assert "10.9.6" in row["note"] and "4.3.2(1)" in row["note"] and "1.15" not in row["note"]
    assert rows["D_over_R"]["value"] == pytest.approx(1.2 * DELTA * d / 2.5, rel=1e-12)
    for cap_row in (c for c in r.checks if c["id"] == "record_capacity" and "pair" in c):
        assert cap_row["torsion_factor"] == pytest.approx(DELTA, rel=1e-14)
    # EN 1998-1 3.2.3.1.2(4): the mean zero-period ordinate (components' PGA, scaled) ≥ a_g S = 0.35 × 1.15 g
    pgas = [r.factors[p.name] * np.max(np.abs(a)) / 9.80665 for p in r.suite.pairs for a in (p.ax_m_s2, p.ay_m_s2)]
    zero = rows["suite_zero_period"]
    assert len(pgas) == 6 and zero["value"] == pytest.approx(np.mean(pgas), rel=1e-14)
    assert zero["limit"] == pytest.approx(0.35 * 1.15, rel=1e-14)
    assert zero["status"] == ("pass" if np.mean(pgas) >= 0.4025 else "fail")
    # the EN accidental eccentricity is printed as [U], ASCE's torsion parameters are not used at all
    printed = {p["name"]: p for p in r.to_dict()["parameters"]}
    assert printed["en_accidental_e"]["mark"] == "U" and printed["en_accidental_e"]["value"] == 0.05
    assert not {"accidental_e", "D_TM_floor", "P_T_min", "n_pairs_min"} & set(printed)


def test_en_accidental_eccentricity_is_a_parameter(inputs):
    """en_accidental_e = 0.1: e_tot = 1 m, δ = 1 + 1 × 4 / 32 = 1.125."""
    r = run_review(Design.from_mapping(SQUARE), EN_TARGET, load_suite(inputs / "suite.toml"), code="en15129",
                   jobs=1, nominal=False, cache_dir=inputs / "cache", parameters={"en_accidental_e": 0.1})
    assert r.to_dict()["torsion"]["factor"] == pytest.approx(1.125, rel=1e-14)


def test_en_without_a_plan_never_passes_the_displacement_row(inputs):
    """No [plan]: the torsion of EN 1998-1 10.3(2) cannot be computed, so the row cannot pass (a failure stands)."""
    design = Design.from_mapping({k: v for k, v in SQUARE.items() if k not in ("plan", "bearing_position")}
                                 | {"displacement_capacity_m": 5.0})
    r = run_review(design, EN_TARGET, load_suite(inputs / "suite.toml"),
                   code="en15129", jobs=1, nominal=False, cache_dir=inputs / "cache")
    rows = {row["id"]: row for row in r.checks}
    row = rows["displacement_capacity"]
    assert row["value"] == pytest.approx(1.2 * _largest_suite_peak(r, 7), rel=1e-12) and row["value"] < 5.0
    assert row["status"] == "not checked" and "needs the design's [plan]" in row["note"]
    capacity = [c for c in r.checks if c["id"] == "record_capacity"]
    assert [c["status"] for c in capacity] == ["not checked"]


def test_en_torsion_without_a_layout_by_hand():
    """From the plan alone: r² = P_T² (b² + d²)/12 (P_T given) or (b² + d²)/12, y given or half the dimension."""
    from isolator.review.codes import en15129

    plan = {"b_m": 40.0, "d_m": 25.0, "eccentricity_m": 0.5, "y_m": 20.0}
    r2 = (40.0 ** 2 + 25.0 ** 2) / 12.0
    out = en15129.torsion_factors(plan, 0.05)
    assert out["factor"] == pytest.approx(1 + (0.5 + 0.05 * 40.0) * 20.0 / r2, rel=1e-14) and out["assumed"]
    out = en15129.torsion_factors({**plan, "P_T": 1.2}, 0.05)
    assert out["factor"] == pytest.approx(1 + 2.5 * 20.0 / (1.44 * r2), rel=1e-14) and not out["assumed"]
    corner = en15129.torsion_factors({"b_m": 40.0, "d_m": 25.0}, 0.05)  # y = b/2 for loading y, d/2 for loading x
    assert corner["factor"] == pytest.approx(max(1 + 1.25 * 12.5 / r2, 1 + 2.0 * 20.0 / r2), rel=1e-14)
    assert en15129.torsion_factors(None, 0.05)["factor"] == 1.0


def test_asce_D_M_capacity_reads_the_corner_bearing(review, inputs):
    """The session review's design has no [plan]: the torsion factor is the 1.15 floor of Eq. 17.5-3, so the corner
    bearing's D_M is 1.15 × the centre of mass's; with capacity_at_corner false, the centre of mass's."""
    rows = {row["id"]: row for row in review.checks}
    d = _largest_suite_peak(review, 7)
    assert review.design_values["torsion"]["factor"] == 1.15
    assert rows["D_M_capacity"]["value"] == pytest.approx(1.15 * d, rel=1e-12)
    assert "corner bearing" in rows["D_M_capacity"]["note"]
    off = run_review(review.design, review.target, review.suite, jobs=1, cache_dir=inputs / "cache",
                     parameters={"capacity_at_corner": False})
    row = next(c for c in off.checks if c["id"] == "D_M_capacity")
    assert row["value"] == pytest.approx(d, rel=1e-12) and "centre of mass" in row["note"]


def _one_record(design, *, pair=False):
    from isolator.analysis import analyse
    from isolator.motion import GroundMotion
    from isolator.motion.pair import MotionPair
    from isolator.review.record_checks import with_record_checks

    t = np.arange(0, 20, 0.01)
    motion = GroundMotion.from_array(3.0 * np.sin(2 * np.pi * 0.5 * t) * np.exp(-0.1 * t), 0.01)
    if pair:  # a planar analysis: its verdicts carry the capacity sentence
        motion = MotionPair(motion, GroundMotion.from_array(0.5 * motion.acceleration_m_s2, 0.01))
    return with_record_checks(analyse(design, motion))


def test_single_record_capacity_reads_the_corner_bearing_as_the_review():
    """With [plan] and [[bearing_position]]: P_T = √32/√(200/12) (Eq. 17.5-4), y = 4 m (the farthest bearing),
    e = 1 + 0.05 × 10 = 1.5 m: D_TM/D_M = 1 + 4/P_T² × 12 × 1.5/200 = 1.1875, the review's factor; no plan: the
    centre of mass, said."""
    design = Design.from_mapping(SQUARE | {"plan": {"b_m": 10.0, "d_m": 10.0, "eccentricity_m": 1.0},
                                           "displacement_capacity_m": 3.0})  # the rim is not reached
    p_t = math.sqrt(32.0) / math.sqrt(200.0 / 12.0)
    factor = 1 + 4.0 / p_t ** 2 * 12 * (1.0 + 0.5) / 200.0
    a = _one_record(design)
    d = a.engineering["peak_displacement_m"]
    row = next(c for c in a.to_dict()["checks"] if c["id"] == "displacement_capacity")
    assert row["value"] == pytest.approx(factor * d, rel=1e-13) and row["centre_of_mass_m"] == d
    assert row["torsion_factor"] == pytest.approx(factor, rel=1e-13) and "corner bearing" in row["note"]
    assert row["status"] == ("pass" if factor * d <= 3.0 else "fail")
    bare = _one_record(Design.from_mapping({k: v for k, v in SQUARE.items() if k not in ("plan", "bearing_position")}))
    row = next(c for c in bare.to_dict()["checks"] if c["id"] == "displacement_capacity")
    assert row["value"] == bare.engineering["peak_displacement_m"] and "centre of mass" in row["note"]
    assert row["torsion_factor"] is None


def test_planar_verdict_names_the_centre_of_mass():
    """A pair (the planar model, no one-record rows): the capacity sentence says its demand is the centre of mass's
    peak, with the plan or without, and where the bearings' demand is."""
    for design in (Design.from_mapping(SQUARE | {"displacement_capacity_m": 3.0}),
                   Design.from_mapping({k: v for k, v in SQUARE.items() if k not in ("plan", "bearing_position")}
                                       | {"displacement_capacity_m": 3.0})):
        a = _one_record(design, pair=True)
        d = a.response.peak_displacement_m
        (said,) = [v for v in a.to_dict()["verdicts"] if "the displacement capacity" in v]
        assert said.startswith(f"Peak resultant displacement of the centre of mass {d:.4g} m within the "
                               f"displacement capacity 3 m (ratio {d / 3.0:.3g}") and "record_capacity row" in said
