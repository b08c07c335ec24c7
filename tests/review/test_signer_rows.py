"""The review of a building on a TFP read as its signer would (session 16): rows that must not pass, and what the
pages must say.

* An analysis that reached the bearing's ultimate displacement (every slider on its rim, or a single pendulum held at
  its rim) continues after a plastic impact of the slab (or the mass) on the rims: its forces, drifts, bearing loads
  and accelerations are that idealisation's, and its displacement is held at the rim.  Measured on
  /tmp/coord/building_on_tfp.toml over the example suite (docs/review.md, session 16): 7 of 24 analyses reached the
  ultimate; the suite V/W of the lower bound was 1.07 (the five analyses below the ultimate 0.09–0.22) and
  ``base_shear_elf_floor`` and ``superstructure_shear`` passed on it.  Such rows now say ``not checked``.
* An inner surface of a triple past its own rim (the planar model's limit) is said and takes the capacity pass away;
  a surface on its rim reads its rim's D/R (not a fail by rounding).
* What the analyses ran with is on the JSON and the pages: every µ_i of each bound, each model and its reason, the
  implicit steps' tolerance; the forces of a double/triple named for what they are (the record-strength floor on the
  bearing's breakaway, the activation force a printed [U] parameter).
"""

from __future__ import annotations

import numpy as np
import pytest

from isolator.design import Design
from isolator.review import checks as C
from isolator.review import worker
from isolator.review.assess import PAST_ULTIMATE, no_pass_past_ultimate
from isolator.review.run import run_review
from isolator.review.suite import load_suite
from isolator.review.target import two_period_target

#: a capacity so large that every analysis passes it: what would pass is what the ultimate must take away
DESIGN = {"name": "signer", "mass_kg": 1.0e6, "radius_m": 2.5, "mu_static": 0.06, "mu_kinetic": 0.05,
          "displacement_capacity_m": 5.0, "lambda_max": 1.3, "lambda_min": 0.8}


def _review_with_one_analysis_at_the_ultimate(inputs, tmp_path, monkeypatch):
    suite = load_suite(inputs / "suite.toml")
    aby = next(p.ax_m_s2 for p in suite.pairs if p.name == "hectormine1999_ABY")
    real = worker.analyse_task

    def analyse(task):  # the ABY analyses say they reached the ultimate (as a rim-held analysis says it)
        result = real(task)
        if task["ax"].shape == aby.shape and np.array_equal(task["ax"], aby):
            return {**result, "ultimate_displacement_reached": True, "impact_impulse_m_s": 0.25,
                    "model": "2d-multisurface"}  # the rows read each analysis's own model: the implicit steps' one
        return result

    monkeypatch.setattr(worker, "analyse_task", analyse)
    return run_review(Design.from_mapping(DESIGN), two_period_target(1.5, 0.9, 8.0), suite, jobs=1, nominal=False,
                      cache_dir=tmp_path / "c")


def test_no_row_passes_on_analyses_past_the_ultimate(inputs, tmp_path, monkeypatch):
    r = _review_with_one_analysis_at_the_ultimate(inputs, tmp_path, monkeypatch)
    rows = {row["id"]: row for row in r.checks}
    # the ELF floor of the isolation system's shear passed on these numbers before (0.9 V_b/W is far below them)
    floor = rows["base_shear_elf_floor"]
    assert floor["value"] >= floor["limit"], "the test needs a row that would pass"
    assert floor["status"] == "not checked"
    assert "reached the bearing's ultimate displacement (hectormine1999_ABY (lower)" in floor["note"]
    assert "would pass" in floor["note"]
    assert not [row["id"] for row in r.checks if row["id"] in PAST_ULTIMATE and row["status"] == "pass"]
    # the capacity rows fail (held at the rim: the suite value understates the demand), the floor on D stands
    assert rows["D_M_capacity"]["status"] == rows["D_TM_capacity"]["status"] == "fail"
    assert rows["D_TM_elf_floor"]["status"] == "pass"
    # the model's limit is said on the rows whose value is a peak of the analyses, with the tolerance they ran at
    said = "model 2d-multisurface: implicit steps at step_tol 1e-07 (relative local error; not exact"
    assert said in floor["note"] and said in rows["transmitted_over_pga"]["note"]
    assert said not in rows["suite_spectrum"]["note"] and "sampled peak" not in floor["note"]  # no building here
    # rows from the spectra, the selection and the ELF are not touched
    assert rows["suite_spectrum"]["status"] == "pass" and rows["V_s_activation_limit"]["status"] == "pass"


def test_the_en_suite_capacity_row_fails_past_the_ultimate_and_a_failure_stands():
    en_row = C.at_most("displacement_capacity", "EN 1998-1 10.3(2) / EN 15129", 0.4, 1.0, "suite value", "m")
    drift = C.story_drift(0.03, 0.02, "story 2")
    drift_pass = C.story_drift(0.01, 0.02, "story 2")
    out = {row["id"] + row["status"]: row for row in no_pass_past_ultimate([en_row, drift, drift_pass], ["PTS (lower)"])}
    assert set(out) == {"displacement_capacityfail", "story_driftfail", "story_driftnot checked"}
    assert "PTS (lower)" in out["displacement_capacityfail"]["note"]
    assert out["story_driftfail"]["note"] == "story 2"  # a failure stands as it was
    assert no_pass_past_ultimate([en_row, drift_pass], []) == [en_row, drift_pass]


def test_a_surface_past_its_own_rim_is_said_and_takes_the_pass_away():
    """Measured in the building-on-TFP review: surface 3 (inner, d = 0.05 m) peaked at 0.05487 m in Chuetsu-oki
    65025 (upper), while the outer surfaces sat on their rims at 0.4000000000000002 m (rounding: not said)."""
    capacities = [0.4, 0.05, 0.05, 0.4]
    analyses = {"upper": {"65025": {"peak_displacement_m": 0.9,
                                    "surface_peak_displacement_m": [0.4000000000000002, 0.05309, 0.05487, 0.4]},
                          "YER": {"peak_displacement_m": 0.24,
                                  "surface_peak_displacement_m": [0.155, 0.0244, 0.0409, 0.0247]},
                          "broken": {"error": "RuntimeError: x"}}}
    passed = C.surface_rims_passed(analyses, capacities)
    assert passed == ["65025 (upper): surface 2 0.05309 m > its 0.05 m, surface 3 0.05487 m > its 0.05 m"]
    assert C.surface_rims_passed(analyses, None) == []
    ok = C.record_capacity(analyses, 0.9)  # 0.9 m is not past 0.9 m: one pass row
    assert [row["status"] for row in ok] == ["pass"]
    d_over_r = C.at_most("D_over_R", "small-angle pendulum (practice)", 0.19, 0.25, "largest", "-")
    out = C.within_surface_rims(ok + [d_over_r], passed)
    assert out[0]["status"] == "not checked" and "surface 3 0.05487 m > its 0.05 m" in out[0]["note"]
    assert out[1]["status"] == "pass" and "docs/multisurface.md" in out[1]["note"]
    failing = C.check("record_capacity", "c", C.FAIL, 1.0, 0.9, "65025, upper bound", "m")
    assert C.within_surface_rims([failing], passed)[0]["status"] == "fail"
    assert C.within_surface_rims(ok, []) == ok


def test_every_surface_friction_of_each_bound_is_in_the_json_and_on_the_page():
    """λ on every µ_i (ASCE 7-22 17.2.8.4): the JSON and the pages gave only the equivalent single pendulum's µ of a
    bound (0.05464 / 0.106 for the building on the TFP), never the µ_i its analyses and ELF ran with."""
    from types import SimpleNamespace

    from isolator.report.review_pages import bound_friction
    from isolator.review.bounds import friction_bounds
    from isolator.review.run import Review

    mu = [0.06, 0.02, 0.02, 0.10]
    design = Design.from_mapping({"name": "tfp", "mass_kg": 1.0e6, "lambda_ae_max": 1.1, "lambda_ae_min": 1.0,
                                  "lambda_test_max": 1.2, "lambda_test_min": 0.9, "lambda_spec_max": 1.15,
                                  "lambda_spec_min": 0.85, "bearing": {"type": "triple", "surface": [
                                      {"radius_m": r, "mu": m, "displacement_capacity_m": d}
                                      for r, m, d in zip((2.1, 0.3, 0.3, 2.1), mu, (0.4, 0.05, 0.05, 0.4), strict=True)]}})
    lam = {"upper": (1 + 0.75 * 0.1) * 1.2 * 1.15, "lower": 0.9 * 0.85, "nominal": 1.0}  # Eqs. 17.2-1 / 17.2-2
    review = SimpleNamespace(design=design, bounds=friction_bounds(design))
    r = {"bounds": {}}
    for bound, factor in lam.items():
        out = Review.surface_friction(review, bound)
        assert out["lambda"] == pytest.approx(factor, rel=1e-15)
        assert np.allclose(out["surface_mu"], [factor * m for m in mu], rtol=1e-15, atol=0)
        r["bounds"][bound] = out
    assert bound_friction(r, "upper") == "µ_i 0.08901/0.02967/0.02967/0.1484"
    assert bound_friction({"bounds": {"lower": {"mu": 0.04}}}, "lower") == "µ = 0.04"
    single = SimpleNamespace(design=Design.from_mapping(DESIGN), bounds=friction_bounds(Design.from_mapping(DESIGN)))
    assert Review.surface_friction(single, "upper") == {}


def test_the_implicit_step_limit_names_the_models_and_the_sampled_base_shear():
    from isolator.solver.planar_multisurface import DEFAULT_STEP_TOL

    assert DEFAULT_STEP_TOL == 1e-7  # the sentence below quotes it
    analyses = {"lower": {"a": {"model": "2d-building-multisurface+vertical"}, "b": {"model": "2d-building"},
                          "c": {"error": "x", "model": "2d-multisurface"}}}
    said = C.implicit_step_limit(analyses)
    assert said.startswith("model 2d-building-multisurface+vertical: implicit steps at step_tol 1e-07")
    assert "the base shear while the slab slides is the peak of each step's parabola" in said
    assert C.implicit_step_limit({"lower": {"a": {"model": "2d"}, "b": {"model": "2d+rim"}}}) == ""


def test_the_pages_name_each_model_with_its_analyses_and_reason():
    from isolator.report.review_pages import models_text

    row = {"model": "2d-building-multisurface", "model_reason": "the 2-D series model with rims by implicit steps"}
    vertical = {"model": "2d-building-multisurface+vertical", "model_reason": "… and its vertical"}
    r = {"scale_factors": {"PTS": 1.5, "YER": 1.5, "APEEL2": 1.5},
         "bounds": {b: {"pairs": {"PTS": row, "YER": row, "APEEL2": vertical}} for b in ("lower", "upper")}}
    assert models_text(r) == ("2d-building-multisurface (4 analyses): the 2-D series model with rims by implicit "
                              "steps; 2d-building-multisurface+vertical (2 analyses: #3 lower, #3 upper): … and its "
                              "vertical")


def test_a_double_or_triple_says_what_its_activation_and_breakaway_forces_are():
    from isolator.review.codes import asce7_22

    elf = {b: {"T_M_s": 3.0, "beta_M": 0.2, "V_s_over_W": 0.2} for b in ("lower", "upper")}
    params = {"wind_shear_over_W": None, "Ws_over_W": 1.0, "abrupt_hysteresis": False, "drift_limit_rha": 0.02}
    for multi, said in ((True, "backbone's force at the start of the regime of the largest compliance"),
                        (False, "max(µs upper, 1.5 µs nominal)")):
        rows = {row["id"]: row for row in asce7_22.requirement_rows(
            elf, params, mu_static_lower=0.0153, mu_static_upper=0.148, mu_static_nominal=0.1, multisurface=multi)}
        assert said in rows["V_s_activation_limit"]["note"]
        assert ("smallest µ_i" in rows["wind_restraint"]["note"]) is multi


def _double(capacity_m: float = 0.5) -> Design:
    return Design.from_mapping({"name": "double", "mass_kg": 1.0e6, "bearing": {"type": "double", "surface": [
        {"radius_m": 2.0, "mu": 0.04, "displacement_capacity_m": capacity_m},
        {"radius_m": 2.5, "mu": 0.07, "displacement_capacity_m": capacity_m}]}})


def test_a_surface_on_its_rim_reads_its_rims_d_over_r_not_a_rounding_fail():
    """/tmp/h155/double.toml over the example suite: surface 1 (R 2 m, d 0.5 m) held on its rim peaked at
    0.5000000000000001 m, and D_over_R said 0.25000000000000006 against 0.25: 'fail'."""
    from types import SimpleNamespace

    from isolator.review.assess import surface_d_over_r

    held = {"lower": {"DZC": {"surface_peak_displacement_m": [0.5000000000000001, 0.5000000000000001]}}}
    row = surface_d_over_r(SimpleNamespace(design=_double(), analyses=held), 0.25)
    assert row["value"] == 0.25 and row["status"] == "pass"
    past = {"lower": {"DZC": {"surface_peak_displacement_m": [0.5 * (1 + 1e-6), 0.1]}}}  # past it: said as it is
    row = surface_d_over_r(SimpleNamespace(design=_double(), analyses=past), 0.25)
    assert row["value"] == 0.5 * (1 + 1e-6) / 2.0 and row["status"] == "fail"


def test_a_triple_review_shows_what_its_analyses_ran_with(inputs, tmp_path):
    """A TFP over three short real pairs, the JSON and the PDF read as the signer reads them: every µ_i of each bound
    (λ given: 0.8 / 1.3), the record-strength floor on the bearing's breakaway (its smallest µ_i, not the equivalent
    single pendulum's µ that no analysis ran), the activation and breakaway forces named, each model with its reason,
    the implicit steps' tolerance on the rows whose values are the analyses' peaks."""
    import pypdf

    from isolator.report.review_pages import write_review_pdf

    mu = (0.06, 0.02, 0.02, 0.10)
    design = Design.from_mapping({"name": "tfp", "mass_kg": 1.0e6, "lambda_max": 1.3, "lambda_min": 0.8,
                                  "bearing": {"type": "triple", "surface": [
                                      {"radius_m": r, "mu": m, "displacement_capacity_m": d} for r, m, d in
                                      zip((2.1, 0.3, 0.3, 2.1), mu, (0.8, 0.05, 0.05, 0.8), strict=True)]}})
    review = run_review(design, two_period_target(1.5, 0.9, 8.0), load_suite(inputs / "suite.toml"), jobs=1,
                        nominal=False)
    r = write_review_pdf(review, tmp_path / "tfp.pdf")
    for bound, lam in (("lower", 0.8), ("upper", 1.3)):
        assert r["bounds"][bound]["lambda"] == lam
        assert np.allclose(r["bounds"][bound]["surface_mu"], [lam * m for m in mu], rtol=1e-15, atol=0)
        assert {a["model"] for a in r["bounds"][bound]["pairs"].values()} == {"2d-multisurface"}
    rows = {row["id"]: row for row in r["checks"]}
    assert rows["record_strength"]["limit"] == pytest.approx(0.1 * 0.8 * 0.02, rel=1e-14)  # not 0.1 × 0.8 × 0.0714
    assert "breakaway force / W (the bearing at rest: its smallest µ_i)" in rows["record_strength"]["note"]
    assert "backbone's force at the start of the regime" in rows["V_s_activation_limit"]["note"]
    assert "regime III of the triple (both outer surfaces slide)" in rows["V_s_activation_limit"]["note"]
    assert rows["wind_restraint"]["limit"] == pytest.approx(0.8 * 0.02, rel=1e-14)
    assert "smallest µ_i" in rows["wind_restraint"]["note"]
    assert "implicit steps at step_tol 1e-07" in rows["base_shear_elf_floor"]["note"]
    text = " ".join(" ".join(page.extract_text().split()) for page in pypdf.PdfReader(tmp_path / "tfp.pdf").pages)
    assert "lower µ_i 0.048/0.016/0.016/0.08 (λ 0.8)" in text and "upper µ_i 0.078/0.026/0.026/0.13 (λ 1.3)" in text
    assert "ELF lower bound (µ_i 0.048/0.016/0.016/0.08)" in text
    assert "Engine (the model each analysis ran, and why): 2d-multisurface (6 analyses): a triple" in text


def test_the_activation_reading_of_a_double_or_triple_is_a_printed_parameter():
    """17.5.4.3(3) for a TFP: the review's default reads 'fully activate' as the start of regime III (µ4: V_b 0.15 W on
    the building on the TFP, whose V_s_activation_limit then fails 0.0803 against 0.1322); REVIEW_RULES 1.9 names the
    breakaway friction for sliders (µ2: 0.03 W).  Unverified, so a parameter with its mark, printed, either way."""
    from isolator.errors import ReviewError
    from isolator.review import parameters as P
    from isolator.review.codes import asce7_22

    mu = (0.06, 0.02, 0.02, 0.10)
    triple = Design.from_mapping({"name": "tfp", "mass_kg": 1.0e6, "bearing": {"type": "triple", "surface": [
        {"radius_m": r, "mu": m, "displacement_capacity_m": d}
        for r, m, d in zip((2.1, 0.3, 0.3, 2.1), mu, (0.4, 0.05, 0.05, 0.4), strict=True)]}})
    assert asce7_22.activation_force_per_weight(triple) == pytest.approx(0.10, rel=1e-15)  # regime III starts at µ4
    assert asce7_22.activation_force_per_weight(triple, "breakaway") == pytest.approx(0.02, rel=1e-15)  # µ2
    single = Design.from_mapping(DESIGN)
    assert asce7_22.activation_force_per_weight(single, "breakaway") == single.mu_static == 0.06
    table = {row["name"]: row for row in P.table("asce7-22", P.resolve("asce7-22", {}))}
    assert table["multisurface_activation"]["value"] == "outer" and table["multisurface_activation"]["mark"] == "U"
    assert P.resolve("asce7-22", {"multisurface_activation": "breakaway"})["multisurface_activation"] == "breakaway"
    with pytest.raises(ReviewError, match="multisurface_activation"):
        P.resolve("asce7-22", {"multisurface_activation": "regime III"})
    elf = {b: {"T_M_s": 3.0, "beta_M": 0.2, "V_s_over_W": 0.2} for b in ("lower", "upper")}
    params = {"wind_shear_over_W": None, "Ws_over_W": 1.0, "abrupt_hysteresis": False, "drift_limit_rha": 0.02}
    row = next(row for row in asce7_22.requirement_rows(
        elf, params, mu_static_lower=0.0153, mu_static_upper=0.02967, mu_static_nominal=0.02, multisurface=True,
        activation_mode="breakaway") if row["id"] == "V_s_activation_limit")
    assert row["limit"] == pytest.approx(0.03, rel=1e-15) and "multisurface_activation 'breakaway'" in row["note"]


def test_a_text_parameter_set_away_from_its_default_is_printed_not_a_traceback(inputs, tmp_path):
    """`isolator review … --set multisurface_activation=breakaway` (or `--set D_M_form=SM1`) raised ValueError in the
    PDF's parameter table (fmt of the default 'outer' / 'SaM'); now printed with its default."""
    import pypdf

    from isolator.report.review_pages import write_review_pdf

    review = run_review(Design.from_mapping(DESIGN), two_period_target(1.5, 0.9, 8.0),
                        load_suite(inputs / "suite.toml"), jobs=1, nominal=False,
                        parameters={"D_M_form": "SM1", "multisurface_activation": "breakaway"})
    write_review_pdf(review, tmp_path / "r.pdf")
    text = " ".join(" ".join(page.extract_text().split()) for page in pypdf.PdfReader(tmp_path / "r.pdf").pages)
    assert "D_M_form = SM1 (default SaM) [U]" in text
    assert "multisurface_activation = breakaway (default outer) [U]" in text


def test_the_pairs_page_marks_the_force_of_an_analysis_past_the_ultimate(inputs, tmp_path, monkeypatch):
    """Page 'Analyses per pair and bound' printed V/W 4.315 for Chuetsu-oki 65025 (lower) on the building on the TFP
    with nothing to say that it is the force of an impact on the rims."""
    import pypdf

    from isolator.report.review_pages import write_review_pdf

    review = _review_with_one_analysis_at_the_ultimate(inputs, tmp_path, monkeypatch)
    write_review_pdf(review, tmp_path / "r.pdf")
    text = " ".join(" ".join(page.extract_text().split()) for page in pypdf.PdfReader(tmp_path / "r.pdf").pages)
    vw = review.analyses["lower"]["hectormine1999_ABY"]["base_shear_coefficient"]
    from isolator.report.layout import fmt

    assert f"{fmt(vw)} †" in text
    assert "† the analysis reached the bearing's ultimate displacement (2 analyses)" in text
    assert "6 run, 0 failed; 2 reached the bearing's ultimate displacement (#2 lower, #2 upper)" in text
