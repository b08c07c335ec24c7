"""The single-record report reads its displacement capacity where the review does (issue 22).

With a design ``[plan]`` (and ``capacity_at_corner``, default): the corner bearing, the centre-of-mass peak × D_TM/D_M
of ASCE 7-22 Eq. 17.5-3, computed here by hand; without one, the centre of mass, and the report says which.
"""

from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

from isolator.cli import app

DESIGN = """name = "FP R2"
mass_kg = 1000.0
radius_m = 2.0
mu_static = 0.05
displacement_capacity_m = 0.05
"""
PLAN = """
[plan]
b_m = 40.0
d_m = 25.0
eccentricity_m = 0.5
y_m = 20.0
"""
#: Eq. 17.5-3 with P_T = 1 (not given: the most conservative), y = 20 m: loading along y (e = 0.5 + 0.05 × 40 m)
#: governs over loading along x (e = 0.5 + 0.05 × 25 m)
FACTOR = max(1 + 20.0 * 12 * (0.5 + 0.05 * 40.0) / (40.0 ** 2 + 25.0 ** 2),
             1 + 20.0 * 12 * (0.5 + 0.05 * 25.0) / (40.0 ** 2 + 25.0 ** 2))


def _pair_report(v2, tmp_path, text):
    design = tmp_path / "fp.toml"
    design.write_text(text)
    out = tmp_path / "pair.pdf"
    result = CliRunner().invoke(app, ["report", str(v2), "--component", "all", "-d", str(design), "-o", str(out)])
    assert result.exit_code == 0, result.output
    return json.loads(out.with_suffix(".json").read_text()), out


@pytest.mark.parametrize("plan", [True, False])
def test_pair_report_reads_the_capacity_where_the_review_does(records_dir, tmp_path, plan):
    numbers, out = _pair_report(records_dir / "other" / "ce89486SampleInput.v2", tmp_path, DESIGN + (PLAN if plan else ""))
    reading = numbers["capacity_reading"]
    factor = FACTOR if plan else 1.0
    assert reading["at_corner"] is plan and reading["factor"] == pytest.approx(factor, rel=1e-14)
    assert reading["demand_ratio"] == pytest.approx(factor * numbers["displacement_demand_ratio"], rel=1e-14)
    assert reading["displacement_m"] == pytest.approx(factor * numbers["peak_displacement_m"], rel=1e-14)
    pypdf = pytest.importorskip("pypdf")
    first = " ".join(pypdf.PdfReader(str(out)).pages[0].extract_text().split())
    assert ("demand / capacity (corner)" in first) is plan and ("(centre of mass)" in first) is not plan
