"""The review and report of a building under hostile use (issue 22, third round): bad ``[superstructure]``,
``[[bearing_position]]`` and ``axial_capacity_N`` values, ``--set`` of the building's parameters with wrong types,
a building with a one-component suite, a bad ``--scheduler`` — each one line on stderr naming the file or flag and
exit 2, or a correct run.

The refusals come before any analysis, so each case costs a design read (the suite is a small synthetic one,
written here).
"""

from __future__ import annotations

from pathlib import Path

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
