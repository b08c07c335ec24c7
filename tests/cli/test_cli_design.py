"""`isolator design`: one-line mistakes (exit 2), the --json contract, the outputs, the recommended review, resume."""

from __future__ import annotations

import json

import pandas as pd
import pytest
from typer.testing import CliRunner

from isolator.cli import app
from tests.review.test_design_space import DESIGN, EXAMPLE, SHORT

runner = CliRunner()


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    folder = tmp_path_factory.mktemp("cli_design")
    body = ""
    for name, x, y, extra in SHORT:
        body += f'[[pair]]\nname = "{name}"\nx = "{EXAMPLE / name / x}"\ny = "{EXAMPLE / name / y}"\n{extra}\n'
    (folder / "suite.toml").write_text(body)
    (folder / "design.toml").write_text(DESIGN)
    (folder / "target.toml").write_text("S_MS = 0.75\nS_M1 = 0.45\nT_L = 8.0\n")
    return folder


def run(files, *extra):
    return runner.invoke(app, ["design", "--target", str(files / "target.toml"), "--suite", str(files / "suite.toml"),
                               "--isolator", str(files / "design.toml"), "--set", "n_pairs_min=3", "--jobs", "1",
                               *[str(a) for a in extra]])


def test_design_in_help():
    result = runner.invoke(app, ["--help"])
    assert result.exit_code == 0 and "design" in result.output
    result = runner.invoke(app, ["design", "--help"])
    assert result.exit_code == 0 and "--vary" in result.output and "--objective" in result.output


@pytest.mark.parametrize("extra, words", [
    (["--vary", "radius_m=1:4"], "--vary 'radius_m=1:4': expected radius_m=START:STOP:COUNT"),
    (["--vary", "radius=1:4:3"], "--vary 'radius=1:4:3': 'radius' is not a number of a design file"),
    (["--vary", "radius_m=1:4:0"], "--vary 'radius_m=1:4:0': COUNT must be >= 1"),
    (["--vary", "radius_m=2:3:2", "--vary", "radius_m=1,2"], "--vary 'radius_m' is varied twice"),
    (["--vary", "stiffness_N_per_m=1:4:2"], "--vary 'stiffness_N_per_m' cannot vary"),
    (["--vary", "radius_m=2:3:2", "--objective", "cheapest"], "--objective must be one of"),
    (["--vary", "radius_m=2:3:2", "--code", "nz"], "--code must be one of"),
    (["--vary", "radius_m=2:3:2", "-o", "chart.png"], "--output must end with .pdf"),
])
def test_mistakes_are_one_line_exit_2(files, tmp_path, extra, words):
    result = run(files, *extra, "-o", tmp_path / "d.pdf") if "-o" not in extra else run(files, *extra)
    assert result.exit_code == 2, result.output
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ") and words in lines[0], lines
    assert not (tmp_path / "d.pdf").exists()


def test_refuses_to_write_over_an_input(files):
    """An output beside the chart (here the recommended review) that is an input is refused before any work."""
    clash = files / "target.recommended.pdf"
    clash.write_text("S_MS = 0.75\nS_M1 = 0.45\nT_L = 8.0\n")
    result = runner.invoke(app, ["design", "--target", str(clash), "--suite", str(files / "suite.toml"),
                                 "--isolator", str(files / "design.toml"), "--vary", "radius_m=2:3:2",
                                 "-o", str(files / "target.pdf")])
    assert result.exit_code == 2 and "input" in result.stderr and len(result.stderr.strip().splitlines()) == 1
    assert clash.read_text().startswith("S_MS") and not (files / "target.pdf").exists()


def test_json_contract_outputs_and_resume(files, tmp_path):
    out_pdf = tmp_path / "reports" / "search.pdf"
    result = run(files, "--vary", "radius_m=2:4:2", "--vary", "mu_kinetic=0.04:0.08:2", "--objective",
                 "displacement", "-o", out_pdf, "--json")
    assert result.exit_code == 0, result.stderr
    out = json.loads(result.stdout)
    assert out["objective"] == "displacement" and len(out["candidates"]) == 4
    for c in out["candidates"]:
        assert {"radius_m", "mu_kinetic", "design_displacement_m", "design_total_displacement_m",
                "base_shear_coefficient", "passes", "first_failing_check", "error"} <= set(c)
    best = out["recommended"]
    passing = [c for c in out["candidates"] if c["passes"]]
    assert best is not None and best["passes"]
    assert best["design_total_displacement_m"] == min(c["design_total_displacement_m"] for c in passing)
    # the recommended design's full review is written beside the chart, with the numbers of its row
    review = json.loads((tmp_path / "reports" / "search.recommended.json").read_text())
    assert review["design_total_displacement_m"]["value"] == best["design_total_displacement_m"]
    assert review["design_base_shear_coefficient"]["value"] == best["base_shear_coefficient"]
    assert all(c["status"] != "fail" for c in review["checks"])
    assert (tmp_path / "reports" / "search.recommended.pdf").read_bytes()[:5] == b"%PDF-"
    # …and its design file, which the review read (its source)
    from isolator.design import Design

    recommended = Design.from_toml(tmp_path / "reports" / "search.recommended.toml")
    assert (recommended.radius_m, recommended.mu_kinetic) == (best["radius_m"], best["mu_kinetic"])
    assert review["design"]["source"] == str(tmp_path / "reports" / "search.recommended.toml")
    # its trace names the bytes of that file (written with the set, after the review: h185)
    import hashlib

    source = tmp_path / "reports" / "search.recommended.toml"
    assert review["inputs"][str(source)] == hashlib.sha256(source.read_bytes()).hexdigest()
    assert list(review["inputs"])[0] == str(source)
    assert out_pdf.read_bytes()[:5] == b"%PDF-"
    table = pd.read_csv(tmp_path / "reports" / "search.csv")
    assert list(table["radius_m"]) == [2.0, 2.0, 4.0, 4.0] and list(table["passes"]) == [c["passes"] for c in
                                                                                          out["candidates"]]
    parquet = pd.read_parquet(tmp_path / "reports" / "search.parquet")
    assert parquet["base_shear_coefficient"].tolist() == [c["base_shear_coefficient"] for c in out["candidates"]]
    assert json.loads((tmp_path / "reports" / "search.json").read_text())["candidates"] == out["candidates"]
    assert not list((tmp_path / "reports").glob("*.lock"))
    # a rerun reviews nothing again
    again = run(files, "--vary", "radius_m=2:4:2", "--vary", "mu_kinetic=0.04:0.08:2", "--objective",
                "displacement", "-o", out_pdf)
    assert again.exit_code == 0 and "resumed" in again.stdout and "4 candidates" in again.stdout
