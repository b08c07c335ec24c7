"""The review and report of a building under hostile use (issue 22, third round): bad ``[superstructure]``,
``[[bearing_position]]`` and ``axial_capacity_N`` values, ``--set`` of the building's parameters with wrong types,
a building with a one-component suite, a bad ``--scheduler`` — each one line on stderr naming the file or flag and
exit 2, or a correct run.

The refusals come before any analysis, so each case costs a design read (the suite is a small synthetic one,
written here).
"""

from __future__ import annotations

from pathlib import Path

import pytest
from typer.testing import CliRunner

from isolator.cli import app

ROOT = Path(__file__).resolve().parents[1]
BUILDING = ROOT / "data" / "example_building.toml"
RUNNER = CliRunner()


def _one_line_exit_2(args, *needles):
    result = RUNNER.invoke(app, args)
    lines = [line for line in result.output.splitlines() if line.strip()]
    assert result.exit_code == 2, result.output
    assert len(lines) == 1 and "Traceback" not in result.output, result.output
    for needle in needles:
        assert needle in lines[0], (needle, lines[0])
    return lines[0]


def test_review_refuses_a_bad_scheduler_before_reading_the_suite(tmp_path):
    """The suite named does not exist: the line is about --scheduler, so nothing was read first (as batch does)."""
    line = _one_line_exit_2(["review", "--design", str(BUILDING), "--target", "example", "--suite",
                             str(tmp_path / "no_such_suite.toml"), "-o", str(tmp_path / "r.pdf"),
                             "--scheduler", "bogus"], "scheduler address 'bogus'", "--scheduler")
    assert "no_such_suite" not in line
    assert not (tmp_path / "r.pdf").exists()


@pytest.mark.parametrize(("setting", "needles"), [
    ("bogus=1", ("--set", "'bogus' is not a parameter of the report")),
    ("n_pairs_min=3", ("--set", "'n_pairs_min' is not a parameter of the report")),  # a review's, not the report's
    ("drift_limit_rha=abc", ("--set", "'drift_limit_rha' must be a number")),
    ("drift_limit_rha=none", ("--set", "'drift_limit_rha' must be a number for the report")),
    ("drift_limit_rha=0.5", ("--set", "outside (0, 0.1]")),
    ("drift_limit_rha=-0.01", ("--set", "finite number ≥ 0")),
    ("drift_limit_rha=nan", ("--set", "finite number ≥ 0")),
    ("drift_limit_rha", ("--set drift_limit_rha: expected NAME=VALUE",)),
    ("sf_flag_low=2", ("--set", "outside (0, 1]")),
])
def test_report_set_refuses_in_one_line_before_reading(tmp_path, setting, needles):
    """A bad ``report --set``: one line naming the flag, exit 2, before the (missing) record is read."""
    line = _one_line_exit_2(["report", str(tmp_path / "missing.AT2"), "-d", str(BUILDING), "-o",
                             str(tmp_path / "r.pdf"), "--set", setting], *needles)
    assert "missing.AT2" not in line and not (tmp_path / "r.json").exists()
