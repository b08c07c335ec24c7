"""The EN 15129 / EN 1998-1 review of a building (REVIEW_RULES §2): γ_x on each bearing's displacement with torsion,
the suite rule (mean of ≥ n_for_mean, else the most unfavourable), and the building's rows reported where the rules
give no EN limit — never a pass without a computed check.

Per-bearing torsion factors by hand on the bundled 20-bearing layout; the rows of a review on three real pairs
through the 2-D building against an aggregation of the analyses' own rows written here.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from isolator.design import Design
from isolator.review.codes import asce7_22, en15129
from isolator.review.run import run_review
from isolator.review.suite import load_suite
from isolator.review.target import Target

ROOT = Path(__file__).resolve().parents[2]
BUILDING = ROOT / "data" / "example_building.toml"
#: EN 1998-1 type 1 spectrum, ground type C (S = 1.15, T_B = 0.2, T_C = 0.6, T_D = 2.0 s), a_g = 0.35 g
EN_TARGET = Target("en1998-elastic", {"a_g_g": 0.35, "S": 1.15, "T_B": 0.2, "T_C": 0.6, "T_D": 2.0}, name="EC8 C")
#: 2 stories on 4 bearings at (±4, ±2.5) m of a 10 m × 10 m plan with 0.3 m eccentricity (P_T by hand below)
EN_BUILDING = {
    "name": "2-story building, 4 bearings (EN)", "mass_kg": 3.0e6, "radius_m": 2.5, "mu_static": 0.06,
    "mu_kinetic": 0.05, "displacement_capacity_m": 2.0, "lambda_max": 1.2, "lambda_min": 0.85,
    "plan": {"b_m": 10.0, "d_m": 10.0, "eccentricity_m": 0.3},
    "superstructure": {"damping_ratio": 0.05, "response_modification_R": 4.0, "floor": [
        {"mass_kg": 1.2e6, "story_height_m": 6.0, "stiffness_x_N_per_m": 1.0e9, "stiffness_y_N_per_m": 8.0e8},
        {"mass_kg": 1.0e6, "story_height_m": 6.0, "stiffness_x_N_per_m": 6.0e8}]},
    "bearing_position": [{"x_m": x, "y_m": y, "axial_capacity_N": 1.2e7} for x in (-4.0, 4.0) for y in (-2.5, 2.5)]}


def test_each_bearing_torsion_factor_by_hand():
    """EN 1998-1 10.9.6's δ_i = 1 + e_tot y_i / r² at each bearing of the 8 m grid of data/example_building.toml
    (b = 34, d = 26 m, e = 0.5 m actual + 5 %): loading x uses |y_i| and e_x = 0.5 + 0.05 × 26 = 1.8 m; loading y
    |x_i| and e_y = 0.5 + 0.05 × 34 = 2.2 m; r² = mean(x² + y²).  No floor (ASCE 7's 1.15 is not an EN rule)."""
    design = Design.from_toml(BUILDING)
    x = np.tile([-16.0, -8.0, 0.0, 8.0, 16.0], 4)
    y = np.repeat([-12.0, -4.0, 4.0, 12.0], 5)
    r2 = float(np.mean(x * x + y * y))
    layout = design.bearing_layout
    torsion = en15129.torsion_factors(design.plan, 0.05, layout.x_m, layout.y_m)
    factors = torsion["bearing_factors"]
    # the centre bearing of the second row, (0, -4): max(1 + 1.8 × 4 / r², 1 + 0) — loading x governs
    middle = list(zip(layout.x_m, layout.y_m, strict=True)).index((0.0, -4.0))
    assert factors[middle] == pytest.approx(1 + 1.8 * 4.0 / r2, rel=1e-14)
    # a corner (16, 12): max(1 + 1.8 × 12 / r², 1 + 2.2 × 16 / r²) — loading y governs
    corner = list(zip(layout.x_m, layout.y_m, strict=True)).index((16.0, 12.0))
    assert factors[corner] == pytest.approx(1 + 2.2 * 16.0 / r2, rel=1e-14)
    assert max(factors) == factors[corner] == torsion["factor"] and min(factors) == factors[middle]
    assert torsion["r_m"] == pytest.approx(math.sqrt(r2), rel=1e-15) and "10.9.6" in torsion["basis"]
    # ASCE's Eq. 17.5-3 bracket with the layout's P_T is the same number (1/(P_T² r_I²) = 1/r²), before its floor
    s = 34.0 ** 2 + 26.0 ** 2
    p_t = math.sqrt(r2) / math.sqrt(s / 12.0)
    assert asce7_22.torsion_amplification(16.0, 2.2, p_t, 34.0, 26.0) == pytest.approx(factors[corner], rel=1e-14)


def _suite_value(values, n_for_mean):
    """Independent of isolator.review.checks: mean of ≥ n, else the most unfavourable (max)."""
    values = np.asarray(values, dtype=float)
    return float(values.mean()) if values.size >= n_for_mean else float(values.max())


@pytest.fixture(scope="module")
def en_building_reviews(inputs, tmp_path_factory):
    """The review with n_for_mean 3 (the mean of the 3 pairs) and 4 (the most unfavourable), one analysis cache."""
    cache = tmp_path_factory.mktemp("en_building") / "cache"
    return {n: run_review(Design.from_mapping(EN_BUILDING), EN_TARGET, load_suite(inputs / "suite.toml"),
                          code="en15129", jobs=1, nominal=False, parameters={"n_for_mean": n}, cache_dir=cache)
            for n in (3, 4)}


@pytest.mark.parametrize("n_for_mean", [3, 4])
def test_en_building_rows_on_real_pairs(en_building_reviews, n_for_mean):
    """3 pairs through the 2-D building at both bounds; n_for_mean 3: the mean of 3; 4: the most unfavourable."""
    r = en_building_reviews[n_for_mean]
    checks = r.checks
    assert {a["model"] for b in r.analyses for a in r.analyses[b].values()} == {"2d-building"}
    rows = {row["id"]: row for row in checks}
    per = {b: [a for a in r.analyses[b].values() if "error" not in a] for b in r.analyses}

    def suite(b, key, i=None):
        return _suite_value([a[key] if i is None else a[key][i] for a in per[b]], n_for_mean)

    # EN 1998-1 10.3(2): γ_x × each bearing's displacement with torsion; P_T = √(4² + 2.5²)/√(200/12) = 1.1557;
    # loading x: |y| = 2.5, e = 0.3 + 0.5 = 0.8; loading y: |x| = 4, e = 0.8: f = 1 + 4/P_T² · 12 · 0.8/200 (all four)
    p_t = math.sqrt(16.0 + 6.25) / math.sqrt(200.0 / 12.0)
    f = 1 + 4.0 / p_t ** 2 * 12 * 0.8 / 200.0
    d = max(suite(b, "peak_displacement_m") for b in per)
    row = rows["displacement_capacity"]
    assert row["value"] == pytest.approx(1.2 * f * d, rel=1e-13) and row["limit"] == 2.0
    assert row["status"] == ("pass" if 1.2 * f * d <= 2.0 else "fail") and "10.3(2)" in row["clause"]
    assert "bearing 1 at (-4, -2.5) m governs" in row["note"] and "4.3.3.4.3(3)" in row["note"]
    rule = "mean" if n_for_mean <= 3 else "max"
    assert f"{rule} of 3 pairs" in row["note"] and f"{rule} of 3 analyses" in rows["story_drift"]["note"]
    # drift, shear, floor acceleration: reported with their values, no EN limit in the rules
    drift = max(suite(b, "story_drift_ratio", i) for b in per for i in range(2))
    shear = max(suite(b, "superstructure_shear_coefficient") for b in per) * 2.2 / 3.0
    top = max(suite(b, "floor_peak_acceleration_m_s2", i) for b in per for i in range(2))
    for id_, value in (("story_drift", drift), ("superstructure_shear", shear), ("floor_acceleration", top)):
        assert rows[id_]["status"] == "not checked" and rows[id_]["limit"] is None, id_
        assert rows[id_]["value"] == pytest.approx(value, rel=1e-13), id_
        assert "no EN limit in the rules" in rows[id_]["note"] and "EN 1998-1 4.3.3.4.3(3)" in rows[id_]["clause"]
    # the bearings: their axial capacity as given, and no tension in a slider
    ratio = max(suite(b, "bearing_axial_load_max_N", k) for b in per for k in range(4)) / 1.2e7
    stability = rows["vertical_load_stability"]
    assert stability["value"] == pytest.approx(ratio, rel=1e-13) and stability["clause"].startswith("EN 15129")
    beyond = any(row["id"] == "record_capacity" and row["status"] == "fail" for row in checks)
    # a history with a bearing in tension: the linear statics does not release it, so no pass on its loads (h227)
    beyond = beyond or any(min(a["bearing_axial_load_min_N"]) < 0 for b in per for a in per[b])
    assert stability["status"] == ("fail" if ratio > 1 else "not checked" if beyond else "pass")
    assert "2.3.6" not in stability["note"]
    least = min(-_suite_value([-a["bearing_axial_load_min_N"][k] for a in per[b]], n_for_mean) for b in per
                for k in range(4))
    assert rows["uplift"]["value"] == pytest.approx(least, rel=1e-13) and "ASCE" not in rows["uplift"]["clause"]
    building = ("displacement_capacity", "record_capacity", "story_drift", "superstructure_shear", "floor_acceleration",
                "vertical_load_stability", "uplift")
    assert not any("ASCE" in rows[id_]["clause"] for id_ in building)  # the EN building rows cite no ASCE clause
    assert r.to_dict()["torsion"]["bearing_factors"] == pytest.approx([f] * 4, rel=1e-14)
    # EN 1998-1 10.3(2) on each analysis as on the suite value: γ_x 1.2 × δ f × the analysis's own peak ≤ 2.0 m
    each = {(b, name): 1.2 * f * a["peak_displacement_m"] for b in r.analyses for name, a in r.analyses[b].items()
            if "error" not in a}
    capacity = [c for c in checks if c["id"] == "record_capacity"]
    beyond = {k for k, v in each.items() if v > 2.0}
    if beyond:
        assert {(c["bound"], c["pair"]) for c in capacity} == beyond
        assert all(c["value"] == pytest.approx(each[c["bound"], c["pair"]], rel=1e-14) for c in capacity)
    else:
        assert len(capacity) == 1 and capacity[0]["value"] == pytest.approx(max(each.values()), rel=1e-14)
        assert capacity[0]["status"] in ("pass", "not checked") and "γ_x" in capacity[0]["note"]
    # EN 1998-2 7.7.1(2) / EN 15129: d_cd = the bound's centre-of-mass suite value (the stiffness centre; no γ_x,
    # no δ_i: they enlarge the capacity requirement, not this check), d_r = µ_b R with µ_b = λ_b × 0.05; the
    # smaller ratio of the two bounds against δ = 0.5
    mu = {"lower": 0.85 * 0.05, "upper": 1.2 * 0.05}
    ratio = min(suite(b, "peak_displacement_m") / (mu[b] * 2.5) for b in per)
    restoring = rows["restoring_capability"]
    assert restoring["value"] == pytest.approx(ratio, rel=1e-13) and restoring["limit"] == 0.5
    assert restoring["status"] == ("pass" if ratio >= 0.5 else "fail") and "without γ_x" in restoring["note"]
