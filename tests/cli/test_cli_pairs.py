"""`isolator simulate` on a pair (and a vertical): model stated, 1-D limit, mismatches, histories."""

from __future__ import annotations

import csv
import json

import numpy as np
import pytest
from typer.testing import CliRunner

from isolator.cli import app

runner = CliRunner()
PAIR_KEYS = {"model", "model_reason", "peak_displacement_m", "residual_displacement_m", "residual_displacement_x_m",
             "residual_displacement_y_m", "peak_velocity_m_s", "n_events", "slip_time_s", "uplift_time_s",
             "energy_input_J_per_kg", "energy_friction_J_per_kg", "energy_viscous_J_per_kg",
             "energy_balance_error_J_per_kg", "solver_seconds", "schema_version", "record"}
PENDULUM = ["--mu-s", "0.05", "--radius-m", "2"]


def _json(args):
    result = runner.invoke(app, ["simulate", *args, "--json"])
    assert result.exit_code == 0, result.output
    return json.loads(result.stdout)


def _one_line_error(args):
    result = runner.invoke(app, ["simulate", *args])
    assert result.exit_code == 2, result.output
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    assert len(lines) == 1 and lines[0].startswith("error:"), result.stderr
    assert "Traceback" not in result.output
    return lines[0]


def test_v2_pair_and_all_state_the_model(records_dir):
    path = str(records_dir / "other" / "ce89486SampleInput.v2")
    pair = _json([path, "--component", "pair", *PENDULUM])
    assert PAIR_KEYS <= set(pair)
    assert pair["model"] == "2d" and "two horizontal components" in pair["model_reason"]
    components = pair["record"]["components"]
    assert components["x"]["component"] == "HN1 (180)" and components["y"]["component"] == "HN2 (90)"
    assert pair["residual_displacement_m"] == pytest.approx(np.hypot(pair["residual_displacement_x_m"],
                                                                     pair["residual_displacement_y_m"]), rel=1e-12)
    assert abs(pair["energy_balance_error_J_per_kg"]) <= 1e-9 * pair["energy_input_J_per_kg"]
    every = _json([path, "--component", "all", *PENDULUM])
    assert every["model"] == "2d+vertical" and "vertical" in every["model_reason"]
    single = _json([path, "--component", "180", *PENDULUM])
    assert single["model"] == "1d-exact" and "exact 1-D kernel" in single["model_reason"]
    assert single["residual_displacement_y_m"] == 0.0


def test_zero_second_component_equals_the_one_component_answer(records_dir, tmp_path):
    x = records_dir / "at2" / "IELC180.AT2"  # 4000 samples, dt 0.01 s
    zeros = tmp_path / "zeros.txt"
    np.savetxt(zeros, np.column_stack([0.01 * np.arange(4000), np.zeros(4000)]), fmt="%.2f", header="units: g")
    one = _json([str(x), *PENDULUM])
    two = _json([str(x), "--pair", str(zeros), *PENDULUM])
    assert one["model"] == "1d-exact" and two["model"] == "2d"
    for key in ("peak_displacement_m", "slip_time_s", "energy_input_J_per_kg", "energy_friction_J_per_kg"):
        assert two[key] == pytest.approx(one[key], rel=1e-9), key
    assert two["residual_displacement_x_m"] == pytest.approx(one["residual_displacement_m"], rel=1e-9)
    assert two["residual_displacement_y_m"] == 0.0


def test_lengths_differ_one_line_then_trim(records_dir):
    folder = records_dir / "pairs" / "superstitionhills1987_PTS"
    args = [str(folder / "RSN723_SUPER.B_B-PTS225.AT2"), "--pair", str(folder / "RSN723_SUPER.B_B-PTS315.AT2"),
            *PENDULUM]
    line = _one_line_error(args)
    assert "different lengths" in line and "2235" in line and "2231" in line and "--trim" in line
    trimmed = _json([*args, "--trim"])
    assert trimmed["record"]["npts"] == 2231
    assert trimmed["record"]["processing"][0]["step"] == "trim_to_common_window"


def test_time_steps_differ_one_line_then_resample(records_dir):
    coarse = records_dir / "pairs" / "landers1992_YER" / "RSN900_LANDERS_YER270.AT2"
    fine = records_dir / "pairs" / "duzce1999_DZC" / "RSN1605_DUZCE_DZC180.AT2"
    line = _one_line_error([str(coarse), "--pair", str(fine), *PENDULUM])
    assert "different time steps" in line and "--resample" in line
    assert "--resample" in _one_line_error([str(coarse), "--pair", str(fine), "--trim", *PENDULUM])
    joined = _json([str(coarse), "--pair", str(fine), "--resample", *PENDULUM])
    assert joined["record"]["processing"][0]["step"] == "common_time_grid" and joined["record"]["dt_s"] == 0.005


@pytest.mark.parametrize("options, words", [
    (["--mu-slow", "0.03"], "together"),
    (["--stiffness-per-mass", "3"], "not both"),
    (["--component", "pair"], "one component"),
    (["--radius-m", "0"], "--radius-m must be a finite number > 0"),
    (["--mu-slow", "0.09", "--mu-fast", "0.05", "--rate-s-per-m", "10"], "mu_slow"),
])
def test_option_mistakes_are_one_line(records_dir, options, words):
    line = _one_line_error([str(records_dir / "at2" / "IELC180.AT2"), *PENDULUM, *options])
    assert words in line


def test_out_csv_holds_both_components(records_dir, tmp_path):
    out = tmp_path / "histories.csv"
    path = str(records_dir / "other" / "ce89486SampleInput.v2")
    summary = _json([path, "--component", "all", *PENDULUM, "--out-csv", str(out)])
    with open(out) as stream:
        rows = list(csv.reader(stream))
    assert rows[0] == ["time_s", "ground_acceleration_x_m_s2", "ground_acceleration_y_m_s2",
                       "ground_acceleration_z_m_s2", "displacement_x_m", "displacement_y_m", "velocity_x_m_s",
                       "velocity_y_m_s", "absolute_acceleration_x_m_s2", "absolute_acceleration_y_m_s2"]
    table = np.array(rows[1:], dtype=float)
    assert table.shape == (summary["record"]["npts"], 10)
    resultant = np.hypot(table[:, 4], table[:, 5])
    assert resultant.max() <= summary["peak_displacement_m"] * (1 + 1e-12)  # the peak includes between samples
    assert np.hypot(*table[-1, 4:6]) == pytest.approx(summary["residual_displacement_m"], rel=1e-12)


def test_one_horizontal_with_its_vertical(records_dir):
    folder = records_dir / "pairs" / "iwatemiyagi2008_AOM017"
    result = _json([str(folder / "AOM0170806140843.NS"), "--vertical", str(folder / "AOM0170806140843.UD"),
                    "--mu-s", "0.01", "--radius-m", "2"])
    assert result["model"] == "2d+vertical" and "second horizontal component zero" in result["model_reason"]
    assert set(result["record"]["components"]) == {"x", "z"}
    assert result["residual_displacement_y_m"] == 0.0 and result["peak_displacement_m"] > 0
    line = _one_line_error([str(folder / "AOM0170806140843.NS"), "--vertical", str(folder / "AOM0170806140843.EW"),
                            *PENDULUM])
    assert "is not a vertical" in line
