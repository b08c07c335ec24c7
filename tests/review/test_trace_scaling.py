"""The engineer's own factors ('given'), the 110 % rule of matched suites, input hashes and --verify."""

from __future__ import annotations

import json
import shutil

import pytest

from isolator.design import Design
from isolator.review.run import run_review
from isolator.review.suite import load_suite
from isolator.review.target import load_target
from isolator.review.trace import input_hashes, software
from isolator.review.verify import verify_review
from tests.review.conftest import EXAMPLE, SHORT


def _suite(folder, extra: str):
    body = ""
    for name, x, y, trim in SHORT:
        body += f'[[pair]]\nname = "{name}"\nx = "{EXAMPLE / name / x}"\ny = "{EXAMPLE / name / y}"\n{trim}\n{extra}\n'
    path = folder / "suite_given.toml"
    path.write_text(body)
    return path


@pytest.fixture(scope="module")
def given(inputs, review, tmp_path_factory):
    """The fixture review's common factor given back as the engineer's factor: scaling 'given', no cache."""
    folder = tmp_path_factory.mktemp("given")
    k = next(iter(review.factors.values()))
    path = _suite(folder, f"scale_factor = {k!r}")
    out = run_review(Design.from_toml(inputs / "design.toml"), load_target(inputs / "target.toml"), load_suite(path),
                     scaling="given", jobs=1)
    return folder, path, out


def test_given_factors_equal_to_common_reproduce_its_displacements(review, given):
    _, _, out = given
    a, b = review.to_dict(), out.to_dict()
    assert b["scale_factors"] == a["scale_factors"] and b["run"]["scaling_basis"] == "given"
    for bound in ("lower", "upper", "nominal"):
        for name, r in a["bounds"][bound]["pairs"].items():
            assert b["bounds"][bound]["pairs"][name]["peak_displacement_m"] == pytest.approx(
                r["peak_displacement_m"], rel=1e-12)
    rows = {r["id"]: r for r in b["checks"]}
    assert rows["suite_spectrum"]["value"] == pytest.approx(1.0, rel=1e-9) and "not rescaled" in rows["suite_spectrum"]["note"]


def test_given_needs_every_factor(inputs):
    from isolator.errors import ReviewError

    with pytest.raises(ReviewError, match="needs a scale_factor for every pair; pair 'landers1992_YER' has none"):
        run_review(Design.from_toml(inputs / "design.toml"), load_target(inputs / "target.toml"),
                   load_suite(inputs / "suite.toml"), scaling="given", jobs=1, nominal=False)


def test_matched_suite_is_not_rescaled_and_needs_110_percent(inputs, review, tmp_path):
    k = next(iter(review.factors.values()))
    path = _suite(tmp_path, f"matched = true\nscale_factor = {1.05 * k!r}")
    out = run_review(Design.from_toml(inputs / "design.toml"), load_target(inputs / "target.toml"), load_suite(path),
                     scaling="common", jobs=1, nominal=False, cache_dir=inputs / "cache").to_dict()
    rows = {r["id"]: r for r in out["checks"]}
    spectrum = rows["suite_spectrum"]
    # the common factor k puts the suite at exactly 1.00 × target; 1.05 k is 1.05, below the 110 % of 16.2.3.3
    assert spectrum["limit"] == pytest.approx(1.10) and spectrum["value"] == pytest.approx(1.05, rel=1e-9)
    assert spectrum["status"] == "fail" and out["run"]["scaling_basis"] == "matched"
    assert list(out["scale_factors"].values()) == pytest.approx([1.05 * k] * 3)
    assert any("not rescaled" in n for n in out["notes"])


def test_hashes_change_when_a_record_changes(inputs, tmp_path):
    name, x, y, trim = SHORT[0]
    for f in (x, y):
        shutil.copy(EXAMPLE / name / f, tmp_path / f)
    path = tmp_path / "s.toml"
    path.write_text(f'[[pair]]\nx = "{x}"\ny = "{y}"\n{trim}\n')
    design, target = Design.from_toml(inputs / "design.toml"), load_target(inputs / "target.toml")
    before = input_hashes(design, target, load_suite(path))
    assert set(before) == {str(inputs / "design.toml"), str(inputs / "target.toml"), str(path),
                           str(tmp_path / x), str(tmp_path / y)}
    text = (tmp_path / y).read_text().splitlines()
    text[5] = text[5].replace("E-", "E+", 1)[:-1] + text[5][-1]  # one sample changed
    (tmp_path / y).write_text("\n".join(text) + "\n")
    after = input_hashes(design, target, load_suite(path))
    assert [p for p in before if before[p] != after[p]] == [str(tmp_path / y)]
    assert software()["version"] and set(software()) == {"name", "version", "commit", "dirty"}


def test_verify_reproduces_and_fails_on_an_edited_json_or_a_changed_input(given, tmp_path):
    folder, path, out = given
    saved = out.to_dict()
    good = tmp_path / "review.json"
    good.write_text(json.dumps(saved))
    result = verify_review(good, jobs=1)
    assert result["ok"] and not result["differences"] and not result["changed_inputs"]
    edited = json.loads(json.dumps(saved))
    row = next(r for r in edited["checks"] if r["id"] == "D_M_capacity")
    row["value"] *= 0.9
    bad = tmp_path / "edited.json"
    bad.write_text(json.dumps(edited))
    result = verify_review(bad, jobs=1)
    assert not result["ok"] and any("check D_M_capacity value" in d for d in result["differences"])
    original = path.read_text()
    try:
        path.write_text(original + "\n# edited\n")
        result = verify_review(good, jobs=1)
    finally:
        path.write_text(original)
    assert not result["ok"] and result["changed_inputs"] == [f"{path} (sha256 differs)"]


def test_cli_verify_exit_codes(given, tmp_path):
    from typer.testing import CliRunner

    from isolator.cli import app

    _, _, out = given
    saved = out.to_dict()
    good = tmp_path / "ok.json"
    good.write_text(json.dumps(saved))
    result = CliRunner().invoke(app, ["review", "--verify", str(good), "--jobs", "1"])
    assert result.exit_code == 0 and "same numbers" in result.output, result.output
    saved["scale_factors"] = {name: 2 * f for name, f in saved["scale_factors"].items()}
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(saved))
    result = CliRunner().invoke(app, ["review", "--verify", str(bad), "--jobs", "1"])
    assert result.exit_code == 1 and "differs  scale factor" in result.output and "NOT reproduced" in result.output
    result = CliRunner().invoke(app, ["review", "--verify", str(tmp_path / "absent.json")])
    assert result.exit_code == 2 and "cannot read the review JSON" in result.output
    assert len(result.output.strip().splitlines()) == 1
    result = CliRunner().invoke(app, ["review", "--target", "example", "--suite", "example"])
    assert result.exit_code == 2 and "missing option --design" in result.output


def test_default_scaling_follows_the_suite(given, inputs, tmp_path):
    from typer.testing import CliRunner

    from isolator.cli import app
    from isolator.review.scaling import default_scaling

    assert default_scaling(["a", "b"], [1.2, 0.9]) == "given"
    assert default_scaling(["a", "b"], [None, None]) == "common"
    with pytest.raises(ValueError, match="pair 'b' gives no scale_factor while other pairs do"):
        default_scaling(["a", "b"], [1.2, None])
    _, path, out = given
    result = CliRunner().invoke(app, ["review", "--design", str(inputs / "design.toml"), "--target",
                                      str(inputs / "target.toml"), "--suite", str(path), "-o", str(tmp_path / "r.pdf"),
                                      "--json", "--jobs", "1"])
    assert result.exit_code == 0, result.output
    cli = json.loads(result.stdout)
    assert cli["run"]["scaling_basis"] == "given" and cli["scale_factors"] == out.to_dict()["scale_factors"]
