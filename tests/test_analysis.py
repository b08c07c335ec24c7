"""The one analysis and its schema: every output is a slice of Analysis.to_dict()."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from isolator.analysis import ROW_ENGINEERING_KEYS, ROW_KEYS, SCHEMA_VERSION, analyse
from isolator.cli import app
from isolator.design import Design
from isolator.motion import GroundMotion
from isolator.units import STANDARD_GRAVITY

DESIGN = {"name": "FPS damped", "mass_kg": 2.0e5, "radius_m": 2.0, "mu_static": 0.06, "mu_kinetic": 0.05,
          "damping_ratio": 0.1}
#: units a dimensional key of the schema ends with
UNIT_SUFFIXES = ("_m", "_s", "_m_s", "_m_s2", "_J_per_kg", "_N", "_N_per_m", "_Ns_per_m", "_kg", "_rad_s")


def pulse(dt_s: float = 0.01, npts: int = 1200):
    """A modulated sine pulse train of 0.35 g (m/s²)."""
    t = np.arange(npts) * dt_s
    acc = np.sin(2 * np.pi * t / 0.8) * (t / t[-1]) ** 2 * np.exp(-6.0 * t / t[-1])
    return 0.35 * STANDARD_GRAVITY * acc / np.max(np.abs(acc)), dt_s


@pytest.fixture(scope="module")
def analysis():
    acc, dt = pulse()
    return analyse(Design.from_mapping(DESIGN), GroundMotion.from_array(acc, dt), record_label="pulse")


def test_to_dict_is_strict_json_with_version_model_and_units(analysis):
    d = json.loads(json.dumps(analysis.to_dict(), allow_nan=False))
    assert d["schema_version"] == SCHEMA_VERSION == 1
    assert d["model"] and d["model_reason"]
    # energies are per unit mass and balance (independent truth: the energy equation)
    assert abs(d["energy_balance_error_J_per_kg"]) < 1e-9 * d["energy_input_J_per_kg"]
    assert d["energy_input_J_per_kg"] > 0 and d["record"]["label"] == "pulse"
    # the point of Eq. 6 from the record's own PGA, by hand
    assert d["alpha"] == pytest.approx(0.35 / 0.06, rel=1e-12)
    pga, pgv = d["record"]["intensity_measures"]["pga_m_s2"], d["record"]["intensity_measures"]["pgv_m_s"]
    assert d["a0_m"] == pytest.approx(pgv ** 2 / pga, rel=1e-12)
    for key in ("peak_displacement_m", "slip_time_s", "peak_transmitted_acceleration_m_s2", "window_start_s"):
        assert key.endswith(UNIT_SUFFIXES)
    assert "energy_input" not in d and "status" not in d  # the old names are gone


def test_row_is_a_slice_of_to_dict(analysis):
    full, row = analysis.to_dict(), analysis.row()
    assert set(row) == set(ROW_KEYS) | set(ROW_ENGINEERING_KEYS)
    for key in ROW_KEYS:
        assert row[key] == full[key], key
    for key in ROW_ENGINEERING_KEYS:
        assert row[key] == full["engineering"][key], key
    # the engineering quantities by hand: F = M × peak transmitted acceleration, C = F / (M g)
    force = DESIGN["mass_kg"] * full["peak_transmitted_acceleration_m_s2"]
    assert row["peak_transmitted_force_N"] == pytest.approx(force, rel=1e-12)
    assert row["base_shear_coefficient"] == pytest.approx(force / (DESIGN["mass_kg"] * STANDARD_GRAVITY), rel=1e-9)


def test_without_the_harmonic_problem_its_keys_are_null(analysis):
    acc, dt = pulse()
    quick = analyse(Design.from_mapping(DESIGN), GroundMotion.from_array(acc, dt), harmonic=False).to_dict()
    assert quick["regime_harmonic"] is None and quick["n_disagreements"] is None
    assert quick["harmonic_status"] == "not computed" and quick["harmonic_seconds"] == 0.0
    assert quick["peak_displacement_m"] == analysis.to_dict()["peak_displacement_m"]


def test_simulate_json_is_the_response_slice(tmp_path, analysis):
    """`simulate --json` on the same record and system gives the schema's response keys, same values."""
    acc, dt = pulse()
    path = tmp_path / "pulse.csv"
    np.savetxt(path, np.column_stack([np.arange(acc.size) * dt, acc]), delimiter=",", fmt="%.17g")
    g_over_r = STANDARD_GRAVITY / DESIGN["radius_m"]
    damping = 2 * DESIGN["damping_ratio"] * math.sqrt(g_over_r)
    result = CliRunner().invoke(app, ["simulate", str(path), "--units", "m/s2", "--mu-s", "0.06", "--mu-k", "0.05",
                                      "--stiffness-per-mass", repr(g_over_r), "--damping-per-mass", repr(damping),
                                      "--json"])
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    full = analysis.to_dict()
    assert data["schema_version"] == full["schema_version"] and data["model"] == full["model"]
    assert data["record"]["npts"] == full["record"]["npts"]
    for key in ("peak_displacement_m", "residual_displacement_m", "n_events", "energy_input_J_per_kg",
                "energy_friction_J_per_kg", "solver_status", "configuration"):
        value = full[key]
        assert data[key] == (pytest.approx(value, rel=1e-9) if isinstance(value, float) else value), key
