"""The solver commands: harmonic, threshold, simulate — JSON contracts and user errors."""

from __future__ import annotations

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from isolator.cli import app

runner = CliRunner()

HARMONIC_KEYS = {"regime", "zeta", "amplitude", "xdot_rms", "energy_friction", "energy_viscous", "work_input",
                 "rho_ev", "rho_vf", "rho_ef", "steady", "growth_rate"}
SIMULATE_KEYS = {"peak_displacement_m", "residual_displacement_m", "peak_velocity_m_s",
                 "peak_transmitted_acceleration_m_s2", "slip_time_s", "n_events", "energy_input_J_per_kg",
                 "energy_friction_J_per_kg", "energy_viscous_J_per_kg", "energy_balance_error_J_per_kg",
                 "solver_seconds"}


def _one_line_error(result):
    assert result.exit_code == 2
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    assert len(lines) == 1 and lines[0].startswith("error:")
    assert "Traceback" not in result.output
    return lines[0]


def test_harmonic_json_contract():
    result = runner.invoke(app, ["harmonic", "--alpha", "1.2", "--k", "0", "--eta", "0", "--mu-s", "0.25", "--json"])
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    assert HARMONIC_KEYS <= data.keys()
    assert data["regime"] == "SS" and data["steady"] is True and data["growth_rate"] is None
    assert data["zeta"] == pytest.approx(0.566, abs=1e-3)


def test_harmonic_resonance_reports_growth():
    result = runner.invoke(app, ["harmonic", "--alpha", "4", "--k", "1", "--eta", "0", "--mu-s", "0.25", "--json"])
    data = json.loads(result.stdout)
    assert data["steady"] is False and data["growth_rate"] > 0 and data["rho_ev"] is None


def test_harmonic_table_names_the_regime():
    result = runner.invoke(app, ["harmonic", "--alpha", "2", "--mu-s", "0.25"])
    assert result.exit_code == 0 and "permanent slip" in result.stdout


def test_threshold_json_contract():
    result = runner.invoke(app, ["threshold", "--k", "0", "--eta", "0", "--mu-s", "0.25", "--alpha-max", "3",
                                 "--grid", "20", "--json"])
    data = json.loads(result.stdout)
    assert {"alpha_ss", "alpha_sl", "transitions"} <= data.keys()
    assert data["alpha_ss"] == 1.0 and data["alpha_sl"] == pytest.approx(1.8620958893, rel=1e-8)
    assert [(t["from"], t["to"]) for t in data["transitions"]] == [("ST", "SS"), ("SS", "SL")]


@pytest.fixture
def two_column_record(tmp_path):
    t = np.arange(0, 20, 0.01)
    acc_g = 0.3 * np.sin(2 * np.pi * 0.7 * t) * np.exp(-((t - 8) / 4) ** 2)
    path = tmp_path / "record.csv"
    np.savetxt(path, np.column_stack([t, acc_g]), delimiter=",", header="time_s,acc_g")
    return path


def test_simulate_json_contract_and_units(two_column_record, tmp_path):
    out_csv = tmp_path / "out" / "history.csv"
    args = ["simulate", str(two_column_record), "--units", "g", "--mu-s", "0.06", "--stiffness-per-mass", "4.9",
            "--damping-per-mass", "0.3", "--json", "--out-csv", str(out_csv)]
    result = runner.invoke(app, args)
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    assert SIMULATE_KEYS <= data.keys()
    assert data["peak_displacement_m"] > 0 and data["n_events"] > 0
    assert abs(data["energy_balance_error_J_per_kg"]) < 1e-9 * data["energy_input_J_per_kg"]
    history = np.loadtxt(out_csv, delimiter=",", skiprows=1)
    assert history.shape == (2000, 5)
    assert np.max(np.abs(history[:, 2])) == pytest.approx(data["peak_displacement_m"], rel=0.05)
    # the same record in gal gives the same answer: units are applied, not guessed
    gal = tmp_path / "record_gal.csv"
    raw = np.loadtxt(two_column_record, delimiter=",", skiprows=1)
    np.savetxt(gal, np.column_stack([raw[:, 0], raw[:, 1] * 980.665]), delimiter=",")
    again = json.loads(runner.invoke(app, args[:1] + [str(gal), "--units", "gal"] + args[4:-2]).stdout)
    assert again["peak_displacement_m"] == pytest.approx(data["peak_displacement_m"], rel=1e-12)


def test_simulate_without_units_is_refused(two_column_record):
    result = runner.invoke(app, ["simulate", str(two_column_record), "--mu-s", "0.06"])
    assert "units" in _one_line_error(result)


@pytest.mark.parametrize("args, word", [
    (["harmonic", "--alpha", "2", "--mu-s", "0.25", "--mu-k", "0.5"], "mu_k"),
    (["harmonic", "--alpha", "-2", "--mu-s", "0.25"], "alpha"),
    (["threshold", "--mu-s", "0.25", "--alpha-max", "0.5"], "alpha_max"),
])
def test_bad_parameters_give_one_line(args, word):
    assert word in _one_line_error(runner.invoke(app, args))


def test_simulate_bad_friction_gives_one_line(two_column_record):
    result = runner.invoke(app, ["simulate", str(two_column_record), "--units", "g", "--mu-s", "0.06",
                                 "--mu-k", "0.1"])
    assert "mu_kinetic" in _one_line_error(result)


def test_help_is_instant_and_lists_commands():
    result = runner.invoke(app, ["--help"])
    assert result.exit_code == 0
    for command in ("harmonic", "threshold", "simulate", "info"):
        assert command in result.stdout
