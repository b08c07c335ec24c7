"""Design search: every row is the review of its design, the recommendation, the chart's data, resume."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from isolator.design import Design
from isolator.errors import ReviewError
from isolator.review.design_grid import candidate_mappings, parse_vary, recommend
from isolator.review.design_outputs import chart_data
from isolator.review.design_space import search
from isolator.review.design_workers import SpectraMemo
from isolator.review.spectra import pair_spectra
from isolator.review.suite import load_suite
from isolator.review.target import two_period_target

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "isolator" / "data" / "suites" / "example"
# the three shortest pairs of the bundled suite (2 200 – 3 000 samples): a short suite keeps the test fast
SHORT = [("landers1992_YER", "RSN900_LANDERS_YER270.AT2", "RSN900_LANDERS_YER360.AT2", ""),
         ("hectormine1999_ABY", "RSN1762_HECTOR_ABY090.AT2", "RSN1762_HECTOR_ABY360.AT2", ""),
         ("superstitionhills1987_PTS", "RSN723_SUPER.B_B-PTS225.AT2", "RSN723_SUPER.B_B-PTS315.AT2", "trim = true")]
DESIGN = """name = "FPS under search"
mass_kg = 1.0e6
radius_m = 2.5
mu_static = 0.07
mu_kinetic = 0.06
displacement_capacity_m = 1.0
lambda_max = 1.3
lambda_min = 0.8
"""
PARAMETERS = {"n_pairs_min": 3}  # three pairs: the suite-size rule is met, so the other checks decide
VARY = ["radius_m=2:4:2", "mu_kinetic=0.04:0.08:2"]
TARGET = two_period_target(0.75, 0.45, 8.0)
NUMBERS = ("design_displacement_m", "design_total_displacement_m", "base_shear_coefficient")


@pytest.fixture(scope="module")
def inputs(tmp_path_factory):
    folder = tmp_path_factory.mktemp("design")
    body = ""
    for name, x, y, extra in SHORT:
        body += f'[[pair]]\nname = "{name}"\nx = "{EXAMPLE / name / x}"\ny = "{EXAMPLE / name / y}"\n{extra}\n'
    (folder / "suite.toml").write_text(body)
    (folder / "design.toml").write_text(DESIGN)
    return folder


@pytest.fixture(scope="module")
def suite(inputs):
    return load_suite(inputs / "suite.toml")


@pytest.fixture(scope="module")
def result(inputs, suite):
    return search(inputs / "design.toml", TARGET, suite, VARY, parameters=PARAMETERS, jobs=1,
                  store_dir=inputs / "store")


def _design_file(folder: Path, radius_m: float, mu_kinetic: float, capacity: float = 1.0) -> Path:
    """The candidate written as its own design file, µs = µk × 7/6 (the file's ratio) by hand."""
    path = folder / f"candidate_{radius_m}_{mu_kinetic}_{capacity}.toml"
    path.write_text(DESIGN.replace("radius_m = 2.5", f"radius_m = {radius_m!r}")
                    .replace("mu_kinetic = 0.06", f"mu_kinetic = {mu_kinetic!r}")
                    .replace("mu_static = 0.07", f"mu_static = {mu_kinetic * 0.07 / 0.06!r}")
                    .replace("displacement_capacity_m = 1.0", f"displacement_capacity_m = {capacity!r}"))
    return path


def test_each_row_is_the_review_of_its_design(inputs, suite, result):
    """Same numbers, same statuses as run_review of the design written out by hand (no shared memo, no cache)."""
    from isolator.review.run import run_review

    assert [(r["radius_m"], r["mu_kinetic"]) for r in result.rows] == [(2.0, 0.04), (2.0, 0.08), (4.0, 0.04),
                                                                      (4.0, 0.08)]
    statuses = set()
    for row in result.rows:
        assert row["error"] is None
        design = Design.from_toml(_design_file(inputs, row["radius_m"], row["mu_kinetic"]))
        assert row["mu_static"] == pytest.approx(design.mu_static, rel=1e-15)
        review = run_review(design, TARGET, suite, jobs=1, parameters=PARAMETERS).to_dict()
        assert row["design_displacement_m"] == review["design_displacement_m"]["value"]
        assert row["design_total_displacement_m"] == review["design_total_displacement_m"]["value"]
        assert row["base_shear_coefficient"] == review["design_base_shear_coefficient"]["value"]
        assert row["governing_bound"] == review["design_displacement_m"]["governing_bound"]
        assert row["period_range_lo_s"] == review["period_range_s"][0]
        assert row["scale_factor_max"] == max(review["scale_factors"].values())
        for check in review["checks"]:
            statuses.add(check["status"])
            rows_of_check = {c["status"] for c in review["checks"] if c["id"] == check["id"]}
            # a check with a row per analysis is failed by any of them
            expected = ("fail" if "fail" in rows_of_check else "pass" if "pass" in rows_of_check
                        else "not checked")
            assert row[f"check_{check['id']}"] == expected, check["id"]
        failing = [c["id"] for c in review["checks"] if c["status"] == "fail"]
        assert row["passes"] is (not failing)
        assert row["first_failing_check"] == (failing[0] if failing else None)
    # the grid is not trivial: some candidates fail, some pass
    assert {r["passes"] for r in result.rows} == {True, False} and "fail" in statuses


def test_recommended_passes_and_nothing_passing_beats_it(result):
    best = result.recommended()
    assert best is not None and best["passes"] and best["error"] is None
    assert all(best[f] == "pass" for f in best if f.startswith("check_") and best[f] != "not checked")
    for row in result.rows:
        if row["passes"]:
            assert row["base_shear_coefficient"] >= best["base_shear_coefficient"]
    by_displacement = result.recommended("displacement")
    assert all(r["design_total_displacement_m"] >= by_displacement["design_total_displacement_m"]
               for r in result.rows if r["passes"])


def test_recommend_by_hand():
    rows = [{"candidate": 0, "passes": True, "error": None, "base_shear_coefficient": 0.2,
             "design_total_displacement_m": 0.5},
            {"candidate": 1, "passes": False, "error": None, "base_shear_coefficient": 0.1,
             "design_total_displacement_m": 0.4},  # better but failing
            {"candidate": 2, "passes": True, "error": None, "base_shear_coefficient": 0.2,
             "design_total_displacement_m": 0.45},  # ties on V_b/W, smaller displacement: wins
            {"candidate": 3, "passes": False, "error": "no period range"}]
    assert recommend(rows, "base_shear")["candidate"] == 2
    assert recommend(rows[1:2], "base_shear") is None
    with pytest.raises(ReviewError) as err:
        recommend(rows, "cheapest")
    assert err.value.parameter == "objective"


def test_contract_json(result):
    out = result.to_dict()
    assert out["objective"] == "base_shear" and len(out["candidates"]) == 4
    for c in out["candidates"]:
        assert {"radius_m", "mu_kinetic", "design_displacement_m", "design_total_displacement_m",
                "base_shear_coefficient", "passes", "first_failing_check", "error"} <= set(c)
    assert out["recommended"]["base_shear_coefficient"] == result.recommended()["base_shear_coefficient"]


def test_chart_failing_region_matches_the_table(result):
    data = chart_data(result)
    assert data["x_key"] == "radius_m" and data["y_key"] == "mu_kinetic"
    for row in result.rows:
        i = list(data["y"]).index(row["mu_kinetic"])
        j = list(data["x"]).index(row["radius_m"])
        assert data["candidate"][i, j] == row["candidate"]
        assert data["state"][i, j] == ("pass" if row["passes"] else row["first_failing_check"])
        assert data["passes"][i, j] == row["passes"]
        assert data["design_total_displacement_m"][i, j] == row["design_total_displacement_m"]
        assert data["base_shear_coefficient"][i, j] == row["base_shear_coefficient"]
    best = result.recommended()
    assert data["recommended"] == (best["radius_m"], best["mu_kinetic"])


def test_capacity_only_candidates_are_analysed_each_and_the_chart_slices(inputs, suite):
    """Candidates differing only in the capacity no longer share analyses: a pendulum whose motion reaches its
    capacity is run again with its rim (2d+rim), so the capacity changes the analysis; the checks differ."""
    res = search(inputs / "design.toml", TARGET, suite, ["radius_m=3,4", "mu_kinetic=0.06",
                                                         "displacement_capacity_m=0.3,2.0"],
                 parameters=PARAMETERS, jobs=1)
    small, large = res.rows[0], res.rows[1]
    assert (small["displacement_capacity_m"], large["displacement_capacity_m"]) == (0.3, 2.0)
    assert small["analyses_cached"] == 0 and large["analyses_cached"] == 0  # nothing shared across capacities
    assert small["design_displacement_m"] <= 0.3 * (1 + 1e-12) < large["design_displacement_m"]  # held on the rim
    assert small["check_D_M_capacity"] == "fail" and large["check_D_M_capacity"] == "pass"
    data = chart_data(res)  # three keys: the slice through the recommended candidate's capacity
    assert set(data["fixed"]) == {"displacement_capacity_m"}
    for row in res.rows:
        if row["displacement_capacity_m"] == data["fixed"]["displacement_capacity_m"]:
            j = list(data["x"]).index(row["radius_m"])
            assert data["candidate"][0, j] == row["candidate"]


def test_a_candidate_that_cannot_be_reviewed_is_a_row(inputs, suite):
    # µk = 0.9 gives µs = 1.05 ≥ 1: no valid design; the other candidate is reviewed
    res = search(inputs / "design.toml", TARGET, suite, ["mu_kinetic=0.06,0.9"], parameters=PARAMETERS, jobs=1)
    bad = res.rows[1]
    assert bad["error"] and "mu_static" in bad["error"] and bad["passes"] is False
    assert res.rows[0]["error"] is None
    data = chart_data(res)
    assert data["state"][0, 1] == "not analysed"


def test_resume_skips_done_candidates(inputs, suite, result, monkeypatch):
    import isolator.review.run as run

    def refuse(*args, **kwargs):
        raise AssertionError("a finished candidate was reviewed again")

    monkeypatch.setattr(run, "run_review", refuse)
    again = search(inputs / "design.toml", TARGET, suite, VARY, parameters=PARAMETERS, jobs=1,
                   store_dir=inputs / "store")
    assert again.n_resumed == 4
    assert [r["base_shear_coefficient"] for r in again.rows] == [r["base_shear_coefficient"] for r in result.rows]
    # a changed parameter is another search: nothing is resumed, so the refusing review is reached
    with pytest.raises(AssertionError, match="reviewed again"):
        search(inputs / "design.toml", TARGET, suite, VARY, parameters={**PARAMETERS, "min_ratio": 0.9}, jobs=1,
               store_dir=inputs / "store")


def test_parse_vary():
    assert parse_vary("radius_m=1.5:4.5:13") == ("radius_m", list(np.linspace(1.5, 4.5, 13)))
    assert parse_vary("mu_kinetic = 0.04,0.06") == ("mu_kinetic", [0.04, 0.06])
    for bad, words in (("radius_m=1:2", "START:STOP:COUNT"), ("radius=1:2:3", "did you mean 'radius_m'"),
                       ("radius_m=1:2:0", "COUNT must be >= 1"), ("radius_m=1:2:1", "COUNT = 1"),
                       ("radius_m=a:2:3", "numbers"), ("radius_m=1:nan:3", "finite"), ("radius_m", "KEY="),
                       ("radius_m=1,1", "repeated"), ("name=1:2:3", "not a number")):
        with pytest.raises(ReviewError, match=words) as err:
            parse_vary(bad)
        assert err.value.parameter == "vary"


def test_friction_follows_mu_kinetic_by_the_design_ratio():
    base = {"name": "d", "mass_kg": 1.0, "radius_m": 2.0, "mu_static": 0.08, "mu_kinetic": 0.04,
            "mu_upper": 0.05, "mu_lower": 0.03}
    (m,) = candidate_mappings(base, 0.04, [("mu_kinetic", [0.06])])
    assert (m["mu_static"], m["mu_upper"], m["mu_lower"]) == pytest.approx((0.12, 0.075, 0.045), rel=1e-15)
    (m,) = candidate_mappings(base, 0.04, [("mu_kinetic", [0.06]), ("mu_static", [0.07])])
    assert m["mu_static"] == 0.07  # varied itself: not a follower
    with pytest.raises(ReviewError, match="varied twice"):
        candidate_mappings(base, 0.04, [("radius_m", [1.0]), ("radius_m", [2.0])])
    with pytest.raises(ReviewError, match="gives 'radius_m'"):
        candidate_mappings(base, 0.04, [("stiffness_N_per_m", [1.0])])


def test_spectra_memo_is_bit_identical(suite):
    pair = suite.pairs[0]
    memo = SpectraMemo(keep_s=[1.0])
    periods = np.geomspace(0.05, 6.0, 37)
    first = memo(pair, periods[::2])
    both = memo(pair, periods[::-1])  # half from the memo, half new, in another order
    fresh = pair_spectra(pair.ax_m_s2, pair.ay_m_s2, pair.dt_s, periods[::-1])
    for key in fresh:
        assert np.array_equal(both[key], fresh[key])
        assert np.array_equal(first[key], both[key][::-1][::2])
    assert memo.computed == 37
    memo.forget()
    assert not memo.values
    assert math.isfinite(memo.seconds)


def test_local_processes_give_the_same_rows(inputs, suite, result):
    parallel = search(inputs / "design.toml", TARGET, suite, VARY, parameters=PARAMETERS, jobs=2)
    for a, b in zip(parallel.rows, result.rows, strict=True):
        assert a["candidate"] == b["candidate"]
        assert all(a[k] == b[k] for k in (*NUMBERS, "passes", "first_failing_check", "error"))


def test_design_toml_round_trips(tmp_path):
    from dataclasses import asdict

    from isolator.review.design_outputs import design_toml

    mapping = {"name": 'FPS "R" [radius_m=2.5]', "mass_kg": 2.0e6, "radius_m": 2.5, "mu_static": 0.07 / 0.06 * 0.05,
               "mu_kinetic": 0.05, "displacement_capacity_m": 1.0, "lambda_ae_max": 1.1, "lambda_ae_min": 1.0,
               "lambda_test_max": 1.2, "lambda_test_min": 0.9, "lambda_spec_max": 1.15, "lambda_spec_min": 0.85,
               "plan": {"b_m": 40.0, "d_m": 25.0, "eccentricity_m": 0.5, "y_m": 20}}
    path = tmp_path / "d.toml"
    path.write_text(design_toml(mapping, "two\nlines"))
    read, direct = asdict(Design.from_toml(path)), asdict(Design.from_mapping(mapping))
    read.pop("source"), direct.pop("source")
    assert read == direct
    # arrays of tables, nested (a building's floors) and at the top (bearing positions), and lists
    import tomllib

    nested = {"name": "b", "superstructure": {"damping_ratio": 0.05, "floor": [
        {"mass_kg": 1e5, "story_height_m": 3.5}, {"mass_kg": 9e4, "story_height_m": 3.0}]},
        "bearing_position": [{"x_m": -5.0, "y_m": 1.0}, {"x_m": 5.0, "y_m": 1.0}], "weird key": [1, 2.5]}
    assert tomllib.loads(design_toml(nested)) == nested
