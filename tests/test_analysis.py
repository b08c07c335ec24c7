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
    assert d["schema_version"] == SCHEMA_VERSION == 2
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


# ---- one analysis for one component and for a pair (issue 21) ----------------------------------------------


@pytest.fixture(scope="module")
def one_and_pair():
    """The pulse as one component, and as a pair whose second component is zero (the 2-D engine runs)."""
    from isolator.motion import MotionPair

    acc, dt = pulse()
    x = GroundMotion.from_array(acc, dt, component="X")
    y = GroundMotion.from_array(np.zeros_like(acc), dt, component="Y")
    design = Design.from_mapping(DESIGN)
    return analyse(design, x, record_label="pulse"), analyse(design, MotionPair(x, y), record_label="pulse")


def test_one_component_and_a_pair_give_one_type_whose_shared_keys_mean_the_same(one_and_pair):
    """Independent truth: a pair with a zero second component is the 1-D motion, whose exact kernel the
    2-D engine matches to 1e-9 (tests/solver/test_planar.py) — so every key both carry has the same value."""
    from isolator.analysis import HARMONIC_NOT_APPLICABLE, Analysis

    one, two = one_and_pair
    assert type(one) is type(two) is Analysis
    assert one.model == "1d-exact" and two.model == "2d" and "two horizontal components" in two.model_reason
    a, b = one.to_dict(), two.to_dict()
    assert set(a) == set(b) and set(a["record"]) == set(b["record"]) and set(one.row()) == set(two.row())
    scale = a["peak_displacement_m"]
    for key in ("peak_displacement_m", "peak_velocity_m_s", "slip_time_s", "energy_input_J_per_kg",
                "energy_friction_J_per_kg", "energy_viscous_J_per_kg", "peak_transmitted_acceleration_m_s2",
                "displacement_demand_ratio", "peak_displacement_over_a0", "transmitted_over_pga"):
        if a[key] is not None:
            assert b[key] == pytest.approx(a[key], rel=1e-8), key
    assert abs(b["residual_displacement_x_m"] - a["residual_displacement_x_m"]) <= 1e-9 * scale
    assert abs(b["residual_displacement_m"]) == pytest.approx(abs(a["residual_displacement_m"]), abs=1e-9 * scale)
    # the point and the window: the resultant of (a_x, 0) is |a_x|
    for key in ("alpha", "k", "eta", "a0_m", "omega_rad_s", "window_start_s", "window_end_s"):
        assert b[key] == pytest.approx(a[key], rel=1e-12), key
    for key in ("pga_m_s2", "pgv_m_s", "pgd_m", "arias_m_s", "d5_95_s"):
        assert b["record"]["intensity_measures"][key] == pytest.approx(a["record"]["intensity_measures"][key],
                                                                       rel=1e-12), key
    # ζ is the exact slip time over D5–95 in both (the 2-D stop instants agree with the kernel's to ~1e-9 s)
    assert b["regime_record"] == a["regime_record"] and a["regime_record"] in ("SS", "SL")
    assert b["zeta_record"] == pytest.approx(a["zeta_record"], abs=1e-7)
    # what does not apply to the planar response is null, and says why
    for key in ("amplitude_record", "amplified_record", "dominant_force_record", "rho_ev_record", "regime_harmonic"):
        assert a[key] is not None and b[key] is None and b["not_applicable"][key], key
    assert b["harmonic_status"] == HARMONIC_NOT_APPLICABLE and "one dimension" in b["not_applicable"]["harmonic_status"]
    assert a["harmonic_status"] != HARMONIC_NOT_APPLICABLE and "amplitude_record" not in a["not_applicable"]
    assert b["record"]["component"] is None and a["record"]["component"] == "X"
    assert set(b["record"]["components"]) == {"x", "y"} and set(a["record"]["components"]) == {"x"}


def test_zeta_is_the_exact_slip_time_over_the_window(one_and_pair):
    """ζ × window = the slip time inside D5–95, from the solver's own event list (independent of the samples)."""
    for analysis in one_and_pair:
        d = analysis.to_dict()
        window = d["window_end_s"] - d["window_start_s"]
        r = analysis.response
        # sliding instants from the response's own slip intervals: V ≠ 0 at samples strictly inside them
        t = r.time_s
        inside = (t > d["window_start_s"]) & (t < d["window_end_s"])
        speed = np.abs(r.velocity_m_s) if r.velocity_m_s.ndim == 1 else np.hypot(*r.velocity_m_s.T)
        sample_share = float(np.mean(speed[inside] > 0))
        # the sampled share approximates ζ to about one sample per slip interval
        n_slips = int(np.sum(np.asarray(r.event_kind) == 0))
        assert d["zeta_record"] == pytest.approx(sample_share, abs=(2 * n_slips + 2) * (t[1] - t[0]) / window)
        # and the whole record: the slip intervals add up to the solver's slip time
        from isolator.metrics import slip_intervals

        intervals = slip_intervals(r)
        assert float(np.sum(intervals[:, 1] - intervals[:, 0])) == pytest.approx(r.slip_time_s, rel=1e-9)


def test_checks_are_added_by_the_caller_and_say_so_when_absent(one_and_pair):
    from isolator.review.record_checks import with_record_checks

    one, two = one_and_pair
    assert one.checks is None and one.to_dict()["checks"] == [] and one.to_dict()["not_applicable"]["checks"]
    checked = with_record_checks(one)
    assert checked is not one and one.checks is None  # a new analysis: nothing filled in place
    ids = [row["id"] for row in checked.to_dict()["checks"]]
    assert "displacement_capacity" in ids and "transmitted_over_pga" in ids
    assert "checks" not in checked.to_dict()["not_applicable"]
    assert with_record_checks(two) is two  # a pair's checks are the review's


def test_batch_columns_are_record_design_analysis_and_timing_listed_once():
    from isolator.analysis import ROW_ENGINEERING_KEYS, ROW_KEYS, TIMING_KEYS
    from isolator.batch.store import COLUMNS, DESIGN_COLUMNS, MODEL_COLUMNS, RECORD_COLUMNS, TIMING_COLUMNS

    assert len(COLUMNS) == len(set(COLUMNS))
    assert set(COLUMNS) == {*RECORD_COLUMNS, *DESIGN_COLUMNS, *ROW_KEYS, *ROW_ENGINEERING_KEYS, *MODEL_COLUMNS,
                            *TIMING_COLUMNS, "row_key", "row_schema"}
    assert set(TIMING_KEYS) <= set(TIMING_COLUMNS) and not set(RECORD_COLUMNS) & set(ROW_KEYS)


def test_simulate_json_batch_rows_and_review_results_share_the_response_names():
    """`simulate --json` is SolverResult.summary(): its keys are batch row keys (and so review per-pair keys)."""
    from isolator.solver.base import SUMMARY_KEYS

    assert set(SUMMARY_KEYS) <= set(ROW_KEYS)
