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
from _records import assert_one_line_exit_2
from typer.testing import CliRunner

from isolator.cli import app

ROOT = Path(__file__).resolve().parents[1]
BUILDING = ROOT / "data" / "example_building.toml"
RUNNER = CliRunner()


def _one_line_exit_2(args, *needles):
    return assert_one_line_exit_2(RUNNER.invoke(app, args), *needles)


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
    ("drift_limit_rha=none", ("--set", "'drift_limit_rha' needs a number (its default is 0.02), got 'none'")),
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


def _building(tmp_path, old: str, new: str) -> Path:
    text = BUILDING.read_text()
    assert old in text, old
    path = tmp_path / "b.toml"
    path.write_text(text.replace(old, new, 1))
    return path


#: (what is replaced in data/example_building.toml, by what, what the line must say)
BAD_DESIGNS = [
    ("damping_ratio = 0.05", "damping_ratio = 1.0", "'damping_ratio' must lie in [0, 1)"),
    ("damping_ratio = 0.05", 'damping_ratio = "0.05"', "'damping_ratio' must be a finite number"),
    ("damping_ratio = 0.05", "damping_ratio = nan", "'damping_ratio' must be a finite number"),
    ("response_modification_R = 8.0", "response_modification_R = 0.0", "'response_modification_R' must be > 0"),
    ("response_modification_R = 8.0", "response_modification_R = true", "'response_modification_R' must be a finite"),
    ("response_modification_R = 8.0", "response_modification_R = inf", "'response_modification_R' must be a finite"),
    ("mass_kg = 1.6e6", "mass_kg = -1.6e6", "floor 1 (from the bottom): key 'mass_kg' must be > 0"),
    ("mass_kg = 1.6e6", "mass_kg = 1.6e7", "the floors weigh"),
    ("story_height_m = 4.0", "story_height_m = 0", "floor 1 (from the bottom): key 'story_height_m' must be > 0"),
    ("stiffness_x_N_per_m = 3.4e9", 'stiffness_x_N_per_m = 3.4e9\nstiffness_y_N_per_m = "a"', "'stiffness_y_N_per_m'"),
    ("stiffness_x_N_per_m = 3.4e9", "stiffness_x_N_per_m = 3.4e9\ndamping = 3", "unknown key 'damping'"),
    ("x_m = -16\ny_m = -12", 'x_m = "a"\ny_m = -12', "bearing_position 1: key 'x_m' must be a finite number"),
    ("x_m = -16\ny_m = -12\n", "x_m = -16\n", "bearing_position 1: missing key 'y_m'"),
    ("x_m = -8\ny_m = -12", "x_m = -16\ny_m = -12", "bearing_position 2: at the same place as bearing_position 1"),
    ("axial_capacity_N = 1.2e7", "axial_capacity_N = 0", "bearing_position 1: key 'axial_capacity_N' must be > 0"),
    ("axial_capacity_N = 1.2e7", "axial_capacity_N = true", "'axial_capacity_N' must be a finite number"),
    ("axial_capacity_N = 1.2e7", "axial_capacity_N = 1.2e7\ngravity_load_N = -1", "'gravity_load_N' must be > 0"),
    # issue 22 third round: absurd magnitudes that passed the reading and broke (or fooled) the engine
    ("mass_kg = 1.6e6", "mass_kg = 1e-300", "floor 1 (from the bottom): key 'mass_kg' must lie in"),
    ("story_height_m = 4.0", "story_height_m = 1e300", "floor 1 (from the bottom): key 'story_height_m' must lie in"),
    ("x_m = -16\ny_m = -12", "x_m = 1e300\ny_m = -12", "bearing_position 1: key 'x_m' must lie in"),
]


@pytest.mark.parametrize(("old", "new", "needle"), BAD_DESIGNS, ids=[case[1][:40] for case in BAD_DESIGNS])
def test_bad_building_design_is_one_line_naming_file_and_key(tmp_path, old, new, needle):
    path = _building(tmp_path, old, new)
    _one_line_exit_2(["review", "--design", str(path), "--target", "example", "--suite",
                      str(tmp_path / "no_suite.toml"), "-o", str(tmp_path / "r.pdf")], str(path), needle)


@pytest.mark.parametrize(("setting", "needle"), [
    ("horizontal_only=maybe", "'horizontal_only' must be true or false"),
    ("drift_limit_rha=abc", "'drift_limit_rha' must be a number"),
    ("drift_limit_rha=0.2", "'drift_limit_rha' = 0.2 is outside (0, 0.1]"),
    ("importance_factor_Ie=2", "'importance_factor_Ie' = 2 is outside [1, 1.5]"),
    ("response_modification_R=4", "unknown review parameter 'response_modification_R'"),  # a design key
    ("Ws_over_W=0.5", "'Ws_over_W' is fixed by the design's [superstructure]"),
    ("R_I=1.5", "'R_I' is fixed by the design's [superstructure]"),
])
def test_review_set_of_the_building_parameters_is_refused_before_the_suite(tmp_path, setting, needle):
    """Each a line naming the parameter, exit 2, before the (missing) suite is read."""
    line = _one_line_exit_2(["review", "--design", str(BUILDING), "--target", "example", "--suite",
                             str(tmp_path / "no_suite.toml"), "-o", str(tmp_path / "r.pdf"), "--set", setting], needle)
    assert "no_suite" not in line


def test_building_with_one_component_suites_is_one_line(tmp_path):
    """A building reviewed on one horizontal component: the record files cannot form a pair, a SUITE.toml pair lacks
    its y — one line each, exit 2, nothing written."""
    record = ROOT / "isolator" / "data" / "suites" / "example" / "superstitionhills1987_PTS" / "RSN723_SUPER.B_B-PTS225.AT2"
    common = ["review", "--design", str(BUILDING), "--target", "example", "-o", str(tmp_path / "r.pdf"), "--no-cache"]
    _one_line_exit_2([*common, "--suite", str(record)], "cannot form a pair", "1 horizontal")
    (tmp_path / "one.toml").write_text(f'[[pair]]\nname = "a"\nx = "{record}"\n')
    _one_line_exit_2([*common, "--suite", str(tmp_path / "one.toml")], "pair 1: missing key 'y'")
    assert not (tmp_path / "r.pdf").exists()
