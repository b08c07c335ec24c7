"""run_review end to end on real pairs, its JSON contract, the cache, the PDF's page 1 and the CLI."""

from __future__ import annotations

import json
import re
import shutil

import numpy as np
import pytest
from typer.testing import CliRunner

from isolator.cli import app
from isolator.design import Design
from isolator.report.pdf import fmt
from isolator.review.suite import load_suite
from isolator.review.target import two_period_target
from tests.review.conftest import EXAMPLE, ROOT, SHORT


def test_contract_keys_and_suite_rules(review):
    out = review.to_dict()
    lo, hi = out["period_range_s"]
    assert lo == pytest.approx(0.75 * out["elf"]["upper"]["T_M_s"])
    assert hi == pytest.approx(1.25 * out["elf"]["lower"]["T_M_s"])
    assert out["min_ratio_required"] == 1.0 and out["suite_min_ratio"] >= 1.0 - 1e-12
    assert out["suite_min_ratio"] == pytest.approx(1.0, rel=1e-9)  # the common factor is the smallest that passes
    assert set(out["scale_factors"]) == {name for name, *_ in SHORT}
    for bound in ("lower", "upper"):
        assert set(out["elf"][bound]) >= {"D_M_m", "T_M_s", "beta_M", "B_M", "V_b_over_W"}
        pairs = out["bounds"][bound]["pairs"]
        for result in pairs.values():
            assert set(result) >= {"peak_displacement_m", "residual_displacement_m", "base_shear_coefficient"}
    assert out["bounds"]["upper"]["mu"] == pytest.approx(0.065) and out["bounds"]["lower"]["mu"] == pytest.approx(0.04)
    # three pairs (< 7): the design value is the maximum over the pairs of the governing bound
    d = out["design_displacement_m"]
    assert d["rule"] == "max" and d["n"] == 3
    governing = out["bounds"][d["governing_bound"]]["pairs"]
    assert d["value"] == max(r["peak_displacement_m"] for r in governing.values())
    assert d["value"] == max(max(r["peak_displacement_m"] for r in out["bounds"][b]["pairs"].values())
                             for b in ("lower", "upper"))
    ids = [c["id"] for c in out["checks"]]
    assert {"suite_size", "suite_spectrum", "D_M_capacity", "D_TM_capacity", "restoring_force", "D_over_R",
            "residual_displacement", "base_shear_elf_floor", "transmitted_over_pga", "uplift"} <= set(ids)
    for c in out["checks"]:
        assert set(c) >= {"id", "clause", "status", "value", "limit", "note"}
        assert c["status"] in ("pass", "fail", "not checked")
    size = next(c for c in out["checks"] if c["id"] == "suite_size")
    assert size["status"] == "fail" and size["value"] == 3 and size["limit"] == 7
    capacity = next(c for c in out["checks"] if c["id"] == "D_M_capacity")
    reached = any(r.get("ultimate_displacement_reached") for b in ("lower", "upper")
                  for r in out["bounds"][b]["pairs"].values())  # held at the rim (2d+rim): never a pass
    assert capacity["status"] == ("pass" if d["value"] <= 0.5 and not reached else "fail")
    json.dumps(out, allow_nan=False)


def test_scaled_spectrum_meets_the_target_on_the_grid(review):
    ratio = review.suite_ratio
    assert review.grid_s.size >= 300 and review.grid_s[0] == pytest.approx(review.period_range_s[0])
    assert np.min(ratio) >= 1.0 - 1e-12
    t_m = [review.elf[b]["T_M_s"] for b in ("lower", "upper")]
    assert all(np.any(np.isclose(review.grid_s, t)) for t in t_m)


def test_rerun_is_served_from_the_cache(inputs, review):
    from isolator.review.run import run_review

    again = run_review(Design.from_toml(inputs / "design.toml"), two_period_target(1.5, 0.9, 8.0),
                       load_suite(inputs / "suite.toml"), jobs=1, cache_dir=inputs / "cache")
    assert again.timing["analyses_cached"] == again.timing["analyses_total"] == 9
    assert again.to_dict()["design_displacement_m"] == review.to_dict()["design_displacement_m"]


def test_pdf_checks_pages_numbers_equal_the_json_and_read_well(review, tmp_path):
    """The checks pages hold every row's id, value and limit as in the JSON; the inputs are echoed; no text run
    below 7 pt (tick-label exponents aside); no internal references; every page carries the version and the
    inputs digest; the paper's measures are an appendix."""
    from pypdf import PdfReader

    from isolator.report.review_pages import inputs_digest, write_review_pdf

    out = write_review_pdf(review, tmp_path / "r.pdf", command="isolator review …")
    saved = json.loads((tmp_path / "r.json").read_text())
    assert saved["checks"] == out["checks"]
    reader = PdfReader(tmp_path / "r.pdf")
    assert len(reader.pages) == saved["pdf_pages"] >= 6
    texts = [page.extract_text() for page in reader.pages]
    checks = " ".join(t for t in texts if "Design review: summary and checks" in t)
    for c in saved["checks"]:
        assert c["id"] in checks and fmt(c["value"]) in checks and fmt(c["limit"]) in checks
    assert fmt(saved["design_displacement_m"]["value"]) in checks
    assert fmt(saved["suite_min_ratio"]) in checks and fmt(saved["D_TM_m"]) in checks
    flat = " ".join(checks.split())
    assert "if nothing cut it short" in flat  # the design's name in full (wrapped), never cut
    for echo in ("W = 9807 kN", "R = 2.5 m", "µs = 0.06, µk = 0.05", "capacity", "S_MS = 1.5 g", "[U]"):
        assert echo in flat, echo
    digest = inputs_digest(saved["inputs"])[:16]
    for text in texts:
        assert f"isolator {saved['software']['version']}" in text and digest in " ".join(text.split())
        assert "(issue" not in text
    assert "Appendix A" in texts[-1]
    pairs_text = " ".join(t for t in texts if "Analyses per pair and bound" in t)
    failing = [row for row in saved["checks"] if row["id"] == "record_capacity" and row["status"] == "fail"]
    for row in failing:  # exactly the failing record_capacity rows are starred, those failing at the corner only too
        assert f"{fmt(row.get('centre_of_mass_m', row['value']))} *" in pairs_text
    assert len(re.findall(r"[0-9] \*", pairs_text)) == len(failing)
    sizes = []
    for page in reader.pages:
        page.extract_text(visitor_text=lambda text, cm, tm, font, size: sizes.append((size * abs(tm[0] or 1), text)))
    small = [(size, text) for size, text in sizes if len(text.strip()) >= 3 and size < 7.0 - 1e-9]
    assert not small, small[:5]


def _cli(*args):
    return CliRunner().invoke(app, ["review", *[str(a) for a in args]])


def test_cli_review_json(inputs, tmp_path):
    result = _cli("--design", inputs / "design.toml", "--target", inputs / "target.toml", "--suite",
                  inputs / "suite.toml", "-o", tmp_path / "r.pdf", "--json", "--jobs", "1", "--scaling", "fit")
    assert result.exit_code == 0, result.output
    out = json.loads(result.stdout)
    assert out["scaling"] == "fit" and len(set(np.round(list(out["scale_factors"].values()), 9))) == 3
    assert (tmp_path / "r.pdf").is_file() and (tmp_path / "r.json").is_file()


@pytest.mark.parametrize("change, words", [
    (["--code", "aashto"], "--code must be one of"),
    (["--scaling", "best"], "--scaling must be one of"),
    (["--set", "min_ratio=abc"], "must be a number"),
    (["--set", "colour=red"], "unknown review parameter 'colour'"),
    (["-o", "r.png"], "must end with .pdf"),
    (["--target", "absent.toml"], "no such target file"),
])
def test_cli_mistakes_are_one_line_exit_2(inputs, change, words):
    args = {"--design": inputs / "design.toml", "--target": inputs / "target.toml", "--suite": inputs / "suite.toml",
            "-o": inputs / "out.pdf"}
    extra = []
    for i in range(0, len(change), 2):
        if change[i] in args:
            args[change[i]] = change[i + 1]
        else:
            extra += change[i:i + 2]
    flat = [item for pair in args.items() for item in pair] + extra
    result = _cli(*flat)
    assert result.exit_code == 2 and words in result.output and "Traceback" not in result.output
    assert len(result.output.strip().splitlines()) == 1


def test_cli_bad_target_key_and_duplicate_suite(inputs, tmp_path):
    target = tmp_path / "t.toml"
    target.write_text("S_MS = 1.5\nS_M1 = 0.9\n")
    result = _cli("--design", inputs / "design.toml", "--target", target, "--suite", inputs / "suite.toml")
    assert result.exit_code == 2 and "missing key 'T_L'" in result.output
    name, x, _, _ = SHORT[0]
    shutil.copy(EXAMPLE / name / x, tmp_path / "again.AT2")
    suite = tmp_path / "dup.toml"
    suite.write_text(f'[[pair]]\nx = "{EXAMPLE / name / x}"\ny = "again.AT2"\n')
    result = _cli("--design", inputs / "design.toml", "--target", inputs / "target.toml", "--suite", suite)
    assert result.exit_code == 2 and "same samples" in result.output and "again.AT2" in result.output


def test_velocity_dependent_friction_and_en15129(inputs):
    from isolator.review.run import run_review

    text = (inputs / "design.toml").read_text() + "mu_slow = 0.03\nmu_fast = 0.05\nrate_s_per_m = 25.0\n"
    design = Design.from_mapping(__import__("tomllib").loads(text), source="v.toml")
    suite = load_suite(inputs / "suite.toml")
    out = run_review(design, two_period_target(1.5, 0.9, 8.0), suite, jobs=1, nominal=False,
                     code="en15129").to_dict()
    models = {r["model"] for b in ("lower", "upper") for r in out["bounds"][b]["pairs"].values()}
    assert models <= {"2d+mu(v)", "2d+mu(v)+rim"} and "2d+mu(v)" in models  # +rim: held at its 0.5 m capacity
    assert out["elf"]["upper"]["mu"] == pytest.approx(0.05 * 1.3)  # ELF at µ_fast of the bound
    assert out["property_bounds"]["lambda_max"] == 1.3  # lambda_max given: no combination
    ids = {c["id"] for c in out["checks"]}
    assert {"displacement_capacity", "restoring_capability"} <= ids and "restoring_force" not in ids
    lo, hi = out["period_range_s"]
    assert lo == pytest.approx(0.2 * out["elf"]["upper"]["T_M_s"]) and hi == pytest.approx(2.0 * out["elf"]["lower"]["T_M_s"])


def test_bundled_example_uses_the_mean_of_eight_pairs():
    """The shipped example: 8 pairs (≥ 7) → the suite value is the mean; the Düzce header corner is the only one
    known, so the usable band is not checked for 7 pairs; the APEEL2 vertical is counted, not called uplift;
    every clause is named."""
    from isolator.review.examples import resolve_example
    from isolator.review.run import run_review
    from isolator.review.target import load_target

    out = run_review(Design.from_toml(ROOT / "data" / "example_review.toml"),
                     load_target(resolve_example("target", "example")), load_suite(resolve_example("suite", "example")),
                     jobs=1, nominal=False).to_dict()
    d = out["design_displacement_m"]
    assert d["rule"] == "mean" and d["n"] == 8
    pairs = out["bounds"][d["governing_bound"]]["pairs"]
    assert d["value"] == pytest.approx(np.mean([r["peak_displacement_m"] for r in pairs.values()]), rel=1e-12)
    rows = {c["id"]: c for c in out["checks"]}
    assert rows["usable_band"]["value"] == pytest.approx(1 / (1.25 * 0.08))
    # the vertical-only count is shown as what it is; uplift itself needs bearing axial loads
    assert rows["uplift"]["status"] == "not checked" and rows["uplift"]["value"] is None
    assert "1 pair(s) with a vertical" in rows["uplift"]["note"] and "axial loads" in rows["uplift"]["note"]
    assert rows["usable_band"]["status"] == "not checked" and "7 of 8 pair(s)" in rows["usable_band"]["note"]
    assert all(c["clause"] for c in out["checks"])
    # 2d+rim where a pair reaches the 1.0 m capacity (issue 23: held there by the rim)
    assert {r["model"].removesuffix("+rim") for r in pairs.values()} == {"2d", "2d+vertical"}


def test_per_pair_results_are_the_rows_of_the_one_analysis(review):
    """The review's worker keeps no pipeline of its own: each per-pair result is ``analyse(design, pair).row()``
    (the batch's and ``simulate --json``'s names), recomputed here from the suite's arrays scaled by hand."""
    from isolator.analysis import ROW_ENGINEERING_KEYS, ROW_KEYS, analyse
    from isolator.motion import GroundMotion, MotionPair

    out = review.to_dict()
    for bound in ("lower", "upper"):
        for result in out["bounds"][bound]["pairs"].values():
            assert set(ROW_KEYS) | set(ROW_ENGINEERING_KEYS) <= set(result)
            assert result["model"] in ("2d", "2d+rim") and result["harmonic_status"] == "not applicable"
            assert result["amplitude_record"] is None and 0.0 <= result["zeta_record"] <= 1.0
        # the response-history design value and the ELF value have distinct names
        values = out["bounds"][bound]
        assert values["D_M_rha_m"] == max(r["peak_displacement_m"] for r in values["pairs"].values())  # n < 7: max
        assert "D_M_m" not in values and out["elf"][bound]["D_M_m"] > 0
    pair = review.suite.pairs[0]
    f = review.factors[pair.name]
    design = review.design.with_friction_factor(review.bounds.lambda_max, "upper bound")
    motion = MotionPair(GroundMotion.from_array(f * pair.ax_m_s2, dt_s=pair.dt_s),
                        GroundMotion.from_array(f * pair.ay_m_s2, dt_s=pair.dt_s))
    row = analyse(design, motion, harmonic=False).row()
    got = out["bounds"]["upper"]["pairs"][pair.name]
    for key in ("peak_displacement_m", "residual_displacement_m", "alpha", "k", "eta", "zeta_record",
                "peak_displacement_over_a0", "transmitted_over_pga", "base_shear_coefficient", "slip_time_s"):
        assert got[key] == pytest.approx(row[key], rel=1e-12), key
    # the resultant PGA by hand, and the paper's α from it
    pga = f * float(np.max(np.hypot(pair.ax_m_s2, pair.ay_m_s2)))
    assert got["pga_m_s2"] == pytest.approx(pga, rel=1e-12)
    assert got["alpha"] == pytest.approx(pga / (design.mu_static * design.gravity_m_s2), rel=1e-12)
    assert got["transmitted_over_pga"] == pytest.approx(got["peak_transmitted_acceleration_m_s2"] / pga, rel=1e-12)


def test_cli_review_says_which_analyses_failed(inputs, tmp_path, monkeypatch):
    """An analysis that fails is named on the console (pair, bound, error) and counted apart from the records read:
    "8 read, 0 failed" alone hid three failed analyses of a TFP review (APEEL2's vertical)."""
    from isolator.review import worker

    original, calls = worker.analyse_task, []

    def first_fails(task):  # tasks run largest first, in this process with --jobs 1: the first one fails
        calls.append(task["key"])
        return {"error": "RecordInputError: injected"} if len(calls) == 1 else original(task)

    monkeypatch.setattr(worker, "analyse_task", first_fails)
    result = _cli("--design", inputs / "design.toml", "--target", inputs / "target.toml", "--suite",
                  inputs / "suite.toml", "-o", tmp_path / "r.pdf", "--jobs", "1", "--no-cache")
    assert result.exit_code == 0, result.output
    lines = result.stdout.splitlines()
    out = json.loads((tmp_path / "r.json").read_text())
    n_run = sum(len(b["pairs"]) for b in out["bounds"].values())
    assert n_run == len(calls) >= 3
    assert lines[1].startswith("pairs    3 read, 0 failed to read;"), lines[1]
    assert lines[2] == f"analyses {n_run} run, 1 failed (the rows needing them say not checked)", lines[2]
    failed = [line for line in lines if line.startswith("failed   ")]
    assert len(failed) == 1 and failed[0].endswith("): RecordInputError: injected"), failed
    name, bound = failed[0][len("failed   "):].split(" (")[0], failed[0].split(" (")[1].split(")")[0]
    assert out["bounds"][bound]["pairs"][name] == {"error": "RecordInputError: injected",
                                                   "scale_factor": out["scale_factors"][name]}
