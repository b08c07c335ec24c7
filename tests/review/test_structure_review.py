"""The review of a building (issue 22) and of double/triple friction pendulums (issue 23).

ELF inputs from the design's superstructure checked by hand; the response-history rows (17.6.4.2 shear,
17.6.4.4 drift, floor accelerations, 17.2.4.7 uplift, 17.2.4.6 stability) against an independent
aggregation of the analyses' own rows; the capacity rows of a bearing with rims against its
``ultimate_displacement_reached``.  Until the 2-D building and 2-D multi-surface models exist, the
review's analyses here run on the x component of each pair (the exact 1-D models; the worker is
patched to drop y — said in each test), so every number checked is a real model's.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from isolator.design import Design
from isolator.errors import ReviewError
from isolator.review import checks as C
from isolator.review import parameters as P
from isolator.review import worker
from isolator.review.codes import asce7_22
from isolator.review.run import elf_values, run_review, structure_inputs
from isolator.review.suite import load_suite
from isolator.review.target import two_period_target

ROOT = Path(__file__).resolve().parents[2]
G = 9.80665
BUILDING = ROOT / "data" / "example_building.toml"
TARGET = two_period_target(1.5, 0.9, 8.0)
#: Fenz & Constantinou's triple pendulum (docs/multisurface.md), capacities cut so that records reach the ultimate
FC_SURFACES = [{"radius_m": 2.1, "mu": 0.06, "displacement_capacity_m": 0.2},
               {"radius_m": 0.3, "mu": 0.02, "displacement_capacity_m": 0.05},
               {"radius_m": 0.3, "mu": 0.02, "displacement_capacity_m": 0.05},
               {"radius_m": 2.1, "mu": 0.10, "displacement_capacity_m": 0.2}]


def _triple(surfaces=FC_SURFACES, **extra) -> Design:
    return Design.from_mapping({"name": "tfp", "mass_kg": 1.0e6, "bearing": {"type": "triple", "surface": surfaces},
                                **extra})


def _x_component_only(monkeypatch):
    """The review's analyses on each pair's x component (the exact 1-D building / multi-surface models)."""
    real = worker.analyse_task
    monkeypatch.setattr(worker, "analyse_task", lambda task: real({**task, "ay": None, "az": None}))


def _suite_value(values, n_for_mean):
    """Independent of isolator.review.checks: mean of ≥ n, else the most unfavourable (max)."""
    values = np.asarray(values, dtype=float)
    return float(values.mean()) if values.size >= n_for_mean else float(values.max())


# ---- the ELF from the superstructure ---------------------------------------------------------------------------

def test_the_superstructure_fixes_ws_over_w_and_r_i():
    design = Design.from_toml(BUILDING)
    values, sources = P.from_design("asce7-22", P.resolve("asce7-22"), design)
    assert values["Ws_over_W"] == pytest.approx(7.4e6 / 9.3e6, rel=1e-15)
    assert values["R_I"] == 2.0  # 3 × 8 / 8 = 3, not above 2 (17.5.4.2)
    rows = {row["name"]: row for row in P.table("asce7-22", values, sources)}
    assert rows["Ws_over_W"]["source"].startswith("design: ") and "source" not in rows["f_disp"]
    with pytest.raises(ReviewError, match="fixed by the design's .superstructure.*do not override it"):
        P.from_design("asce7-22", values, design, {"Ws_over_W": 0.5})
    low_r = Design.from_mapping({**_building_mapping(), "superstructure": {**_building_mapping()["superstructure"],
                                                                            "response_modification_R": 2.0}})
    assert P.from_design("asce7-22", P.resolve("asce7-22"), low_r)[0]["R_I"] == 1.0  # 0.75 → not below 1
    rigid = Design.from_toml(ROOT / "data" / "example_review.toml")
    assert P.from_design("asce7-22", P.resolve("asce7-22"), rigid) == (P.resolve("asce7-22"), {})


def _building_mapping() -> dict:
    import tomllib

    return tomllib.loads(BUILDING.read_text())


def test_elf_with_the_superstructure_by_hand():
    """V_st = V_b (W_s/W)^(1 − 2.5 β_M), V_s = V_st/R_I, D'_M = D_M/√(1 + (T/T_M)²) with T from numpy's eigenvalues."""
    design = Design.from_toml(BUILDING)
    params, _ = P.from_design("asce7-22", P.resolve("asce7-22"), design)
    structure = structure_inputs(design)
    floors = design.superstructure.floors
    k = np.array([f.stiffness_x_N_per_m for f in floors])
    m = np.array([f.mass_kg for f in floors])
    stiffness = np.diag(k + np.append(k[1:], 0.0)) - np.diag(k[1:], 1) - np.diag(k[1:], -1)
    t_fixed = 2 * math.pi / math.sqrt(min(np.linalg.eigvals(stiffness / m[:, None]).real))
    assert structure["T_fixed_s"] == pytest.approx(t_fixed, rel=1e-12) and structure["T_fixed_s"] == pytest.approx(
        0.4907, abs=1e-4)
    elf = elf_values(design, design.mu_kinetic, TARGET, "asce7-22", params, structure["T_fixed_s"])
    ws = 7.4e6 / 9.3e6
    v_st = elf["V_b_over_W"] * ws ** (1 - 2.5 * elf["beta_M"])
    assert elf["V_st_over_W"] == pytest.approx(v_st, rel=1e-14) and elf["V_s_over_W"] == pytest.approx(v_st / 2.0)
    assert elf["D_M_prime_m"] == pytest.approx(elf["D_M_m"] / math.sqrt(1 + (t_fixed / elf["T_M_s"]) ** 2), rel=1e-12)
    assert elf["D_M_prime_m"] < elf["D_M_m"]


def test_torsion_factor_from_the_bearing_layout_by_hand():
    params = {"D_TM_floor": 1.0, "P_T_min": 1.0, "accidental_e": 0.05}
    design = Design.from_toml(BUILDING)
    from isolator.superstructure import review_inputs

    layout = review_inputs(design)
    x = np.tile([-16.0, -8.0, 0.0, 8.0, 16.0], 4)
    y = np.repeat([-12.0, -4.0, 4.0, 12.0], 5)
    b, d = 34.0, 26.0
    p_t = math.sqrt(np.mean(x * x + y * y)) / math.sqrt((b * b + d * d) / 12)  # Eq. 17.5-4
    by_hand = max(1 + (16.0 / p_t ** 2) * 12 * (0.5 + 0.05 * b) / (b * b + d * d),   # loading y: y = max |x|
                  1 + (12.0 / p_t ** 2) * 12 * (0.5 + 0.05 * d) / (b * b + d * d))   # loading x: y = max |y|
    out = asce7_22.torsion_factor(design.plan, params, layout)
    assert out["P_T"] == pytest.approx(p_t, rel=1e-14) and out["factor"] == pytest.approx(by_hand, rel=1e-14)
    assert not out["assumed"] and "the bearing layout" in out["basis"]
    given = asce7_22.torsion_factor({**design.plan, "P_T": 2.0, "y_m": 3.0}, params, layout)  # the plan's values win
    assert given["P_T"] == 2.0 and given["factor"] == pytest.approx(
        max(1 + (3.0 / 4.0) * 12 * (0.5 + 0.05 * p) / (b * b + d * d) for p in (b, d)), rel=1e-14)


def test_axial_capacity_key_is_all_or_none():
    from isolator.errors import DesignError

    mapping = _building_mapping()
    mapping["bearing_position"][3] = {k: v for k, v in mapping["bearing_position"][3].items()
                                      if k != "axial_capacity_N"}
    with pytest.raises(DesignError, match="bearing_position 4: missing key 'axial_capacity_N'"):
        Design.from_mapping(mapping, source="b.toml")
    mapping["bearing_position"][3]["axial_capacity_N"] = -1.0
    with pytest.raises(DesignError, match="bearing_position 4: key 'axial_capacity_N' must be > 0"):
        Design.from_mapping(mapping, source="b.toml")


# ---- the response-history rows of a building ---------------------------------------------------------------------

@pytest.fixture(scope="module")
def building_review(inputs):
    mp = pytest.MonkeyPatch()
    _x_component_only(mp)
    try:
        return run_review(Design.from_toml(BUILDING), TARGET, load_suite(inputs / "suite.toml"), jobs=1,
                          parameters={"n_for_mean": 3})
    finally:
        mp.undo()


def test_building_rows_equal_an_independent_aggregation_of_the_analyses(building_review):
    assert {a["model"] for b in building_review.analyses for a in building_review.analyses[b].values()} == {
        "1d-building"}
    _assert_building_rows(building_review, n_stories=5, n_bearings=20, ws=7.4e6 / 9.3e6, r_i=2.0, mu_static=0.06,
                          capacity_N=1.2e7)


def _assert_building_rows(r, *, n_stories, n_bearings, ws, r_i, mu_static, capacity_N):
    """Each building row against the analyses' own rows aggregated here (mean of ≥ n, else max; envelope)."""
    rows = {row["id"]: row for row in r.checks}
    n = r.parameters["n_for_mean"]
    bounds = list(r.analyses)
    per = {b: [a for a in r.analyses[b].values() if "error" not in a] for b in bounds}

    def suite(b, key, i=None):
        return _suite_value([a[key] if i is None else a[key][i] for a in per[b]], n)

    # 17.6.4.4: the largest story's suite drift ratio, envelope of the bounds
    drift = max(suite(b, "story_drift_ratio", i) for b in bounds for i in range(n_stories))
    assert rows["story_drift"]["value"] == pytest.approx(drift, rel=1e-14)
    assert rows["story_drift"]["status"] == ("pass" if drift <= 0.02 else "fail")
    assert rows["story_drift"]["limit"] == 0.02 and "[U]" in rows["story_drift"]["clause"]
    # 17.6.4.2: the suite's first-story shear × W_s/W ÷ R_I against max(0.6 V_s, the activation limit)
    shear = max(suite(b, "superstructure_shear_coefficient") for b in bounds) * ws / r_i
    v_s = max(r.elf[b]["V_s_over_W"] for b in ("lower", "upper"))
    v_act = max(r.bounds.lambda_max * mu_static, 1.5 * mu_static)  # 17.5.4.3(3): max(µs upper, 1.5 µs nominal)
    act = max(v_act * ws ** (1 - 2.5 * r.elf[b]["beta_M"]) for b in ("lower", "upper"))
    # 17.5.4.3(1): C_s of 12.8.1.1 at T_M with the superstructure's R, I_e = 1, S_DS = 1.0, S_D1 = 0.6 (2/3 of the
    # target's 1.5, 0.9), T_L = 8 s, times W_s/W; written out here, independent of asce7_22
    r_sup = r.design.superstructure.response_modification_R

    def c_s(t):
        return max(min(1.0 / r_sup, 0.6 / (t * r_sup) if t <= 8.0 else 0.6 * 8.0 / (t * t * r_sup)), 0.044)

    fixed = {b: c_s(r.elf[b]["T_M_s"]) * ws for b in ("lower", "upper")}
    b_fixed = min(fixed, key=lambda b: r.elf[b]["V_s_over_W"] / fixed[b])
    row = rows["V_s_fixed_base_limit"]
    assert row["limit"] == pytest.approx(fixed[b_fixed], rel=1e-14)
    assert row["value"] == pytest.approx(r.elf[b_fixed]["V_s_over_W"], rel=1e-14)
    assert row["status"] == ("pass" if row["value"] >= row["limit"] else "fail")
    assert f"R = {r_sup:g} (not R_I)" in row["note"] and "I_e = 1" in row["note"]
    limit = max(0.6 * v_s, act, max(fixed.values()))
    row = rows["superstructure_shear"]
    assert row["value"] == pytest.approx(shear, rel=1e-14) and row["limit"] == pytest.approx(limit, rel=1e-14)
    assert row["status"] == ("pass" if shear >= limit else "fail") and "17.6.4.2" in row["clause"]
    assert "17.5.4.3(1) fixed-base" in row["note"] and "17.5.4.3(3) activation" in row["note"]
    assert "17.5.4.3(2) not computed" in row["note"] and "17.5.4.3(1) not computed" not in row["note"]
    # 17.2.4.7: the least suite value of a bearing's minimum load; 17.2.4.6: the largest P_max / capacity — under
    # 2.3.6 (no vertical analysed: E_v = 0.2 S_MS D): each analysis's load shifted by (f − 1) × the gravity share,
    # f_min = 0.9 − 0.2 S_MS, f_max = 1.2 + 0.2 S_MS
    s_ms = r.target.parameters["S_MS"]
    share = r.design.bearing_layout.gravity_loads_N
    f_min, f_max = 0.9 - 0.2 * s_ms, 1.2 + 0.2 * s_ms
    least = min(-_suite_value([-(a["bearing_axial_load_min_N"][k] + (f_min - 1) * share[k]) for a in per[b]], n)
                for b in bounds for k in range(n_bearings))
    assert rows["uplift"]["value"] == pytest.approx(least, rel=1e-14)
    assert rows["uplift"]["status"] == ("pass" if least >= 0 else "fail")
    assert "no vertical analysed, so E_v is applied" in rows["uplift"]["note"]
    lifted = sum(1 for b in bounds for a in per[b]
                 if min(lo + (f_min - 1) * g for lo, g in zip(a["bearing_axial_load_min_N"], share, strict=True)) < 0)
    assert f"{lifted} analysis(es) lift a bearing" in rows["uplift"]["note"]
    ratio = max(_suite_value([a["bearing_axial_load_max_N"][k] + (f_max - 1) * share[k] for a in per[b]], n)
                for b in bounds for k in range(n_bearings)) / capacity_N
    assert rows["vertical_load_stability"]["value"] == pytest.approx(ratio, rel=1e-14)
    beyond = any(row["id"] == "record_capacity" and row["status"] == "fail" for row in r.checks)
    # a history with a bearing in tension: the linear statics does not release it, so no pass on its loads (h227)
    beyond = beyond or any(min(a["bearing_axial_load_min_N"]) < 0 for b in bounds for a in per[b])
    assert rows["vertical_load_stability"]["status"] == ("fail" if ratio > 1 else "not checked" if beyond else "pass")
    assert "17.2.4.6" in rows["vertical_load_stability"]["clause"]
    # floor accelerations: reported with their value, never a pass
    top = max(suite(b, "floor_peak_acceleration_m_s2", i) for b in bounds for i in range(n_stories))
    assert rows["floor_acceleration"]["status"] == "not checked"
    assert rows["floor_acceleration"]["value"] == pytest.approx(top, rel=1e-14)
    # 17.6.4.1 with D'_M of Eq. 17.6-1 (and the layout's torsion factor)
    prime = max(r.elf[b]["D_M_prime_m"] for b in ("lower", "upper")) * r.design_values["torsion"]["factor"]
    assert rows["D_TM_elf_floor"]["limit"] == pytest.approx(0.8 * prime, rel=1e-14)
    assert "Eq. 17.6-1" in rows["D_TM_elf_floor"]["clause"]
    out = r.to_dict()
    assert out["structure"]["Ws_over_W"] == pytest.approx(ws) and len(out["structure"]["story_drift_ratio"]) == n_stories
    assert next(p for p in out["parameters"] if p["name"] == "Ws_over_W")["source"].startswith("design: ")


def test_d_tm_capacity_says_the_floor_it_used(building_review):
    """With a superstructure the 17.6.4.1 floor is f_disp × D'_TM (Eq. 17.6-1); D_TM_capacity said "0.8 D_TM ELF" and
    no number (h227: on c765efa the note lacks "D'_TM ELF (Eq. 17.6-1) = "). The floor by hand from the ELF values:
    0.8 × max over the bounds of D_M/√(1 + (T/T_M)²) × the torsion factor."""
    elf, torsion = building_review.elf, building_review.design_values["torsion"]["factor"]
    t = building_review.structure["T_fixed_s"]
    floor = 0.8 * max(elf[b]["D_M_m"] / math.sqrt(1.0 + (t / elf[b]["T_M_s"]) ** 2) * torsion for b in ("lower", "upper"))
    row = next(r for r in building_review.checks if r["id"] == "D_TM_capacity")
    assert f"0.8 D'_TM ELF (Eq. 17.6-1) = {floor:.4g} m" in row["note"]
    rha = building_review.design_values["envelope"]["D_M_rha_m"] * torsion
    assert f"= {rha:.4g} m, 0.8 D'_TM" in row["note"] and row["value"] == pytest.approx(max(rha, floor), rel=1e-12)


def test_rows_fail_when_the_numbers_say_so():
    """The check functions on hand-made numbers: tension is uplift, a load above the capacity fails, a drift above
    0.020 h fails, the larger of the 17.6.4.2 floor and the 17.5.4.3 limits governs."""
    assert C.uplift(0, 0, -1.0e5)["status"] == "fail" and C.uplift(0, 0, 1.0)["status"] == "pass"
    row = C.vertical_load_stability([4.0e6, 9.0e6, 5.0e6], [1.0e7, 8.0e6, 1.0e7])
    assert row["status"] == "fail" and row["value"] == pytest.approx(9.0 / 8.0) and "bearing 2" in row["note"]
    assert C.vertical_load_stability([4.0e6], None)["status"] == "not checked"
    assert C.story_drift(0.021, 0.02)["status"] == "fail" and C.story_drift(None, 0.02)["status"] == "not checked"
    row = C.superstructure_shear(0.2, 0.6, 0.2, limits={"wind": 0.15}, r_i=2.0)
    assert row["value"] == pytest.approx(0.1) and row["limit"] == pytest.approx(0.15) and row["status"] == "fail"
    assert "wind governs" in row["note"]
    assert C.superstructure_shear(0.2, 0.6, 0.3, r_i=2.0)["status"] == "pass"  # 0.15 ≥ 0.12
    assert C.superstructure_shear(0.2, 0.6)["status"] == "not checked"
    assert C.floor_acceleration(5.0)["status"] == "not checked"


def test_a_pair_the_engine_refuses_stops_the_review_in_one_line(inputs, monkeypatch):
    def refuse(task):
        return {"error": "InvalidSystemError: b.toml: a design with a [superstructure] is analysed under one "
                         "horizontal component"}

    monkeypatch.setattr(worker, "analyse_task", refuse)
    with pytest.raises(ReviewError) as err:
        run_review(Design.from_toml(BUILDING), TARGET, load_suite(inputs / "suite.toml"), jobs=1)
    text = str(err.value)
    # the design file and the pair's files are named (session 14), then the engine's own words
    assert "\n" not in text and f"engine refuses {BUILDING} under " in text and "(pair 'landers1992_YER', " in text
    assert "[superstructure]" in text


def test_cli_review_of_a_building_with_mu_v_runs_on_the_2d_building(inputs, tmp_path):
    """A building with µ(v): the 2-D building carries velocity-dependent friction (c679ac0); every analysis ran on
    it, never on the rigid block's µ(v) engine, and the review's JSON says so."""
    import json

    from typer.testing import CliRunner

    from isolator.cli import app

    text = BUILDING.read_text().replace("mu_static = 0.06\nmu_kinetic = 0.05\n",
                                        "mu_static = 0.03\nmu_slow = 0.03\nmu_fast = 0.06\nrate_s_per_m = 20.0\n")
    assert "rate_s_per_m" in text
    (tmp_path / "b.toml").write_text(text)
    result = CliRunner().invoke(app, ["review", "--design", str(tmp_path / "b.toml"), "--target",
                                      str(inputs / "target.toml"), "--suite", str(inputs / "suite.toml"), "-o",
                                      str(tmp_path / "r.pdf"), "--jobs", "1", "--no-cache"])
    assert result.exit_code == 0, result.output
    saved = json.loads((tmp_path / "r.json").read_text())
    models = {a["model"] for bound in saved["bounds"].values() for a in bound["pairs"].values()}
    assert models == {"2d-building"} and all(bound["models"] == ["2d-building"] for bound in saved["bounds"].values())


# ---- double and triple friction pendulums ------------------------------------------------------------------------

def test_triple_pendulum_elf_is_the_loop_fixed_point():
    """D_M = g S_a(T_M) T_M²/(4π² B(β_M)) with T_M, β_M of the bearing's own loop at D_M, by hand."""
    design = _triple()
    elf = asce7_22.elf_displacement(design, design.mu_kinetic, TARGET)
    d = elf["D_M_m"]
    loop = design.bearing.loop_properties(d, design.weight_N, G)
    image = G * float(TARGET.sa_g(loop.effective_period_s)[0]) * loop.effective_period_s ** 2 / (
        4 * math.pi ** 2 * asce7_22.damping_coefficient(loop.effective_damping_ratio))
    assert image == pytest.approx(d, rel=1e-10)
    assert elf["T_M_s"] == pytest.approx(loop.effective_period_s, rel=1e-14)
    assert elf["beta_M"] == pytest.approx(loop.effective_damping_ratio, rel=1e-14)
    assert any(f"regime {loop.regime}" in note for note in elf["notes"])
    strong = asce7_22.elf_displacement(design, design.mu_kinetic, two_period_target(3.0, 3.0, 8.0))
    assert strong["beyond_ultimate"] and math.isnan(strong["D_M_m"]) and "ultimate" in strong["notes"][0]


def test_triple_pendulum_forces_by_hand():
    """Fenz & Constantinou's bearing (uncut capacities): regime III slope W/4.2 m, breakaway 0.02 W, activation 0.10 W."""
    design = _triple([{**s, "displacement_capacity_m": c} for s, c in zip(FC_SURFACES, (0.4, 0.05, 0.05, 0.4),
                                                                          strict=True)])
    assert asce7_22.restoring_force_ratio(design, 0.5) == pytest.approx(0.25 / 4.2, rel=1e-12)  # both in regime III
    assert asce7_22.breakaway_force_per_weight(design) == pytest.approx(0.02, rel=1e-12)
    assert asce7_22.activation_force_per_weight(design) == pytest.approx(0.10, rel=1e-12)
    assert math.isnan(asce7_22.restoring_force_ratio(design, 0.95))  # beyond the ultimate 0.9 m
    upper = design.with_friction_factor(1.3, "upper bound")  # λ on every µ_i
    np.testing.assert_allclose(upper.bearing.mu_kinetic, 1.3 * design.bearing.mu_kinetic, rtol=1e-15)


def test_capacity_rows_never_pass_a_bearing_at_its_ultimate():
    analyses = {"lower": {"a": {"peak_displacement_m": 0.5, "ultimate_displacement_reached": True,
                                "impact_impulse_m_s": 0.2},
                          "b": {"peak_displacement_m": 0.3, "ultimate_displacement_reached": False}}}
    rows = C.record_capacity(analyses, 0.5, mass_kg=1.0e6)
    assert [r["status"] for r in rows] == ["fail"] and rows[0]["pair"] == "a" and "2e+05 N·s" in rows[0]["note"]
    mean = C.at_most("D_M_capacity", "c", 0.4, 0.5, "mean")
    assert mean["status"] == "pass"
    assert C.never_pass_at_ultimate(mean, C.ultimate_reached(analyses))["status"] == "fail"
    assert C.never_pass_at_ultimate(mean, [])["status"] == "pass"


def test_triple_pendulum_review_reads_the_rims(inputs, monkeypatch):
    _x_component_only(monkeypatch)
    design = _triple(lambda_max=1.2, lambda_min=0.85)
    r = run_review(design, TARGET, load_suite(inputs / "suite.toml"), jobs=1, parameters={"n_for_mean": 3})
    assert {a["model"] for b in r.analyses for a in r.analyses[b].values()} == {"1d-multisurface"}
    reached = [(b, name) for b in r.analyses for name, a in r.analyses[b].items() if a["ultimate_displacement_reached"]]
    assert reached  # the cut capacities are reached by Superstition Hills
    rows = [row for row in r.checks if row["id"] == "record_capacity"]
    assert {(row["bound"], row["pair"]) for row in rows} == set(reached)
    assert all(row["status"] == "fail" and row["centre_of_mass_m"] <= 0.5 + 1e-12 for row in rows)  # at the rim
    # capacity_at_corner: the value is the corner bearing's, the torsion factor × the held centre of mass
    assert all(row["value"] == row["torsion_factor"] * row["centre_of_mass_m"] for row in rows)
    by_id = {row["id"]: row for row in r.checks}
    assert by_id["D_M_capacity"]["status"] == by_id["D_TM_capacity"]["status"] == "fail"
    assert by_id["D_M_capacity"]["limit"] == pytest.approx(design.bearing.ultimate_displacement_m)
    assert "ultimate" in by_id["D_M_capacity"]["note"]
    # ELF per bound from each bound's loop: λ scales every µ_i
    upper = design.with_friction_factor(r.bounds.lambda_max, "upper")
    assert r.elf["upper"]["T_M_s"] == pytest.approx(upper.effective_properties(r.elf["upper"]["D_M_m"])
                                                    .effective_period_s, rel=1e-14)
    assert by_id["D_over_R"]["value"] == pytest.approx(max(
        max(d / s["radius_m"] for d, s in zip(a["surface_peak_displacement_m"], FC_SURFACES, strict=True))
        for b in r.analyses for a in r.analyses[b].values()), rel=1e-14)


def test_horizontal_only_drops_the_verticals_said_and_keyed(tmp_path):
    """Loma Prieta APEEL2 (x, y, z) on the rigid block: '2d+vertical' by default, '2d' with horizontal_only, a note,
    and a cache key of its own (a cached vertical analysis is never reused for the horizontal one)."""
    from tests.review.conftest import EXAMPLE

    folder = EXAMPLE / "lomaprieta1989_APEEL2"
    (tmp_path / "suite.toml").write_text(
        f'[[pair]]\nname = "apeel2"\nx = "{folder / "np01002p_4225a_a.smc"}"\ny = "{folder / "np01002p_4225c_a.smc"}"\n'
        f'z = "{folder / "np01002p_4225b_a.smc"}"\ntrim = true\n')
    suite = load_suite(tmp_path / "suite.toml")
    design = Design.from_mapping({"name": "fps", "mass_kg": 1.0e6, "radius_m": 2.5, "mu_static": 0.06})
    cache = tmp_path / "cache"
    both = run_review(design, TARGET, suite, jobs=1, nominal=False, cache_dir=cache)
    flat = run_review(design, TARGET, suite, jobs=1, nominal=False, cache_dir=cache,
                      parameters={"horizontal_only": "true"})
    assert {a["model"] for b in both.analyses for a in both.analyses[b].values()} == {"2d+vertical"}
    assert {a["model"] for b in flat.analyses for a in flat.analyses[b].values()} == {"2d"}
    assert flat.timing["analyses_cached"] == 0 and any("horizontal_only" in n for n in flat.notes)
    uplift = {row["id"]: row for row in flat.checks}["uplift"]
    assert "the verticals of 1 pair(s) not analysed (horizontal_only)" in uplift["note"]  # the suite has one


# ---- end to end on real pairs, through the models the registry runs -------------------------------------------

def _registry_has(model: str) -> bool:
    from isolator.solver.models import MODELS

    return model in MODELS


SMALL_BUILDING = {
    "name": "2-story building, 4 bearings", "mass_kg": 3.0e6, "radius_m": 2.5, "mu_static": 0.06, "mu_kinetic": 0.05,
    "displacement_capacity_m": 2.0, "lambda_max": 1.2, "lambda_min": 0.85, "plan": {"b_m": 10.0, "d_m": 10.0},
    "superstructure": {"damping_ratio": 0.05, "response_modification_R": 4.0, "floor": [
        {"mass_kg": 1.2e6, "story_height_m": 6.0, "stiffness_x_N_per_m": 1.0e9, "stiffness_y_N_per_m": 8.0e8},
        {"mass_kg": 1.0e6, "story_height_m": 6.0, "stiffness_x_N_per_m": 6.0e8}]},
    "bearing_position": [{"x_m": x, "y_m": y, "axial_capacity_N": 1.2e7} for x in (-2.5, 2.5) for y in (-2.5, 2.5)]}


@pytest.mark.skipif(not _registry_has("2d-building"), reason="the 2-D building is not in the model registry")
def test_building_review_on_real_pairs(inputs):
    """Three real pairs through the 2-D building: every row against the analyses' own rows."""
    design = Design.from_mapping(SMALL_BUILDING)
    r = run_review(design, TARGET, load_suite(inputs / "suite.toml"), jobs=1, nominal=False,
                   parameters={"n_for_mean": 3})
    assert {a["model"] for b in r.analyses for a in r.analyses[b].values()} == {"2d-building"}
    _assert_building_rows(r, n_stories=2, n_bearings=4, ws=2.2 / 3.0, r_i=1.5, mu_static=0.06, capacity_N=1.2e7)
    assert np.asarray(next(iter(r.analyses["lower"].values()))["orbit_m"]).shape[1] == 2  # a planar orbit


def test_building_with_a_vertical_is_analysed_by_the_2d_building(tmp_path):
    """Loma Prieta APEEL2 with its vertical: the 2-D building carries N(t) = W (1 + a_z/g) (it was refused)."""
    folder = Path(__file__).resolve().parents[2] / "isolator" / "data" / "suites" / "example" / "lomaprieta1989_APEEL2"
    (tmp_path / "suite.toml").write_text(
        f'[[pair]]\nname = "apeel2"\nx = "{folder / "np01002p_4225a_a.smc"}"\ny = "{folder / "np01002p_4225c_a.smc"}"\n'
        f'z = "{folder / "np01002p_4225b_a.smc"}"\ntrim = true\n')
    r = run_review(Design.from_mapping(SMALL_BUILDING), TARGET, load_suite(tmp_path / "suite.toml"), jobs=1,
                   nominal=False, parameters={"n_for_mean": 1})
    analyses = [a for b in r.analyses for a in r.analyses[b].values()]
    assert {a["model"] for a in analyses} == {"2d-building"} and all("error" not in a for a in analyses)
    uplift = next(row for row in r.checks if row["id"] == "uplift")
    assert "not analysed (horizontal_only)" not in uplift["note"]


@pytest.mark.skipif(not _registry_has("2d-multisurface"), reason="the 2-D multi-surface model is not in the registry")
@pytest.mark.parametrize("capacities", [(0.4, 0.05, 0.05, 0.4), (0.2, 0.05, 0.05, 0.2)], ids=["uncut", "cut"])
def test_triple_pendulum_review_on_real_pairs(inputs, capacities):
    """Fenz & Constantinou's bearing through the 2-D multi-surface model on three real pairs: every analysis runs on it
    and the rows read its keys.  Superstition Hills PTS reaches the ultimate at both bounds with either capacities.
    The cut bearing (0.2/0.05/0.05/0.2 m) stopped on PTS at its misaligned ultimate (12.72 s, the work bound) until
    the mass carried on one group's rim took that group on its half disc (planar_multisurface_stepper.half_discs):
    it is answered now (PTS: 12 / 9 rim contacts, impulse 5.10 / 4.80 m/s at the lower / upper bound)."""
    surfaces = [{**s, "displacement_capacity_m": c} for s, c in zip(FC_SURFACES, capacities, strict=True)]
    design = _triple(surfaces, lambda_max=1.2, lambda_min=0.85)
    r = run_review(design, TARGET, load_suite(inputs / "suite.toml"), jobs=1, nominal=False,
                   parameters={"n_for_mean": 3})
    assert all(r.analyses[b]["superstitionhills1987_PTS"]["ultimate_displacement_reached"] for b in r.analyses)
    assert {a["model"] for b in r.analyses for a in r.analyses[b].values()} == {"2d-multisurface"}
    rows = {row["id"]: row for row in r.checks}
    peaks = [a["peak_displacement_m"] for b in r.analyses for a in r.analyses[b].values()]
    capacity_rows = [row for row in r.checks if row["id"] == "record_capacity"]
    factor = r.design_values["torsion"]["factor"]  # capacity_at_corner: each analysis's corner bearing
    past = [a for b in r.analyses for a in r.analyses[b].values()
            if a["ultimate_displacement_reached"] or factor * a["peak_displacement_m"] > rows["D_M_capacity"]["limit"]]
    assert len([row for row in capacity_rows if row["status"] == "fail"]) == len(past)
    if not past:
        assert capacity_rows[0]["value"] == pytest.approx(factor * max(peaks))
    assert rows["D_M_capacity"]["limit"] == pytest.approx(sum(capacities), rel=1e-12)  # heights 0: d* = d
    assert rows["D_over_R"]["value"] == pytest.approx(max(
        max(d / s["radius_m"] for d, s in zip(a["surface_peak_displacement_m"], surfaces, strict=True))
        for b in r.analyses for a in r.analyses[b].values()), rel=1e-14)
