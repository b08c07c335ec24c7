"""The building case of the bench (isolator.bench.building): ours, the independent reference, OpenSees.

The wiring (stiffness for a given T1, the dashpot network, the errors, the tables, the CLI
without the record) runs everywhere; the comparisons on a real record skip without
``../shared``, the OpenSees ones without openseespy.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from typer.testing import CliRunner

from isolator import bench
from isolator.bench import building as building_bench
from isolator.bench.opensees import opensees_available
from isolator.bench.opensees_building import dashpot_network
from isolator.cli import app

OPENSEES_OK, OPENSEES_WHY = opensees_available()
needs_opensees = pytest.mark.skipif(not OPENSEES_OK, reason=f"OpenSees baseline: {OPENSEES_WHY}")


def _case(records_dir, seconds: float, start_s: float = 0.0, **kwargs):
    from isolator.motion import read_ground_motion

    motion = read_ground_motion(records_dir / building_bench.BUILDING_RECORD[1])
    i0 = round(start_s / motion.dt_s)
    acc = motion.acceleration_m_s2[i0:i0 + round(seconds / motion.dt_s) + 1]
    return building_bench.building_case("test building", acc, motion.dt_s, **kwargs)


def test_uniform_story_stiffness_gives_the_fixed_base_period():
    # the closed form against the superstructure's own eigenproblem (scipy eigh)
    for n in (1, 2, 5, 9):
        case = building_bench.building_case("t", np.zeros(3), 0.01, n_floors=n, period_s=0.7)
        assert case.superstructure.fixed_base_periods_s()[0] == pytest.approx(0.7, rel=1e-12)
    case = building_bench.building_case("t", np.zeros(3), 0.01)
    assert case.total_mass_kg == 3.0e6 and case.isolator_stiffness_N_per_m == pytest.approx(9.80665 * 3e6 / 2.5)
    # one story: ω = sqrt(k/m) by hand
    k = building_bench.uniform_story_stiffness(1, 2.0, 2 * math.pi)
    assert k == pytest.approx(2.0, rel=1e-12)


def test_dashpot_network_reproduces_the_damping_matrix():
    case = building_bench.building_case("t", np.zeros(3), 0.01)
    c = case.superstructure.damping_matrix()
    to_base, between = dashpot_network(c)
    rng = np.random.default_rng(3)
    for _ in range(5):
        v = rng.normal(size=c.shape[0])
        # force on floor i by hand: its dashpot to the slab plus those to every other floor
        force = np.array([to_base[i] * v[i] + sum(between[i, j] * (v[i] - v[j]) for j in range(v.size) if j != i)
                          for i in range(v.size)])
        np.testing.assert_allclose(force, c @ v, rtol=1e-12, atol=1e-12 * np.abs(c).max())
        assert np.sum(to_base * v) == pytest.approx(np.sum(c @ v), rel=1e-10)  # what the slab receives
    assert np.all(np.diag(between) == 0.0)


def test_errors_and_tables():
    t = np.linspace(0.0, 1.0, 11)
    truth = building_bench._histories(np.sin(t), np.outer(np.sin(t), [1.0, 3.0]), np.outer(np.cos(t), [2.0, 1.0]))
    assert building_bench.building_errors(truth, truth)["error_max"] == 0.0
    shifted = {k: v.copy() for k, v in truth.items()}
    shifted["drift"][:, 1] += 0.01  # drift of story 2 is 2 sin t: largest |drift| 2 sin 1
    e = building_bench.building_errors(shifted, truth)
    assert e["error_drift"] == pytest.approx(0.01 / (2 * math.sin(1.0)))
    assert e["error_slab"] == 0.0 and e["error_max"] == e["error_drift"]
    result = {"case": "c", "ours": {"method": building_bench.BUILDING_OURS, "seconds": 0.01, "runs": 5,
                                    "peaks": building_bench._listed(building_bench.sampled_peaks(truth)), **e},
              "reference": {"method": building_bench.BUILDING_TRUTH, "seconds": 1.0, "runs": 1,
                            "sampled_peaks": building_bench._listed(building_bench.sampled_peaks(truth))},
              "opensees": {"method": building_bench.BUILDING_OPENSEES, "seconds": None, "note": "openseespy not installed"},
              "time_ratio": None, "error_ratio": None}
    table = building_bench.building_markdown([result])
    assert table.count("\n") == 5 and "openseespy not installed" in table
    (line,) = building_bench.building_summary([result])
    assert "not measured (openseespy not installed)" in line


def test_no_building_record_is_a_note(tmp_path):
    assert building_bench.building_cases(True, tmp_path) == []
    assert bench.building_cases(False, tmp_path) == []


def test_reference_agrees_with_ours_and_the_tests_reference(records_dir):
    # three solutions of one building on 3 s of the record: ours, the bench's reference and the tests' own
    from tests.solver.test_building import reference_building as tests_reference

    case = _case(records_dir, 3.0, start_s=2.0)
    ours = building_bench.ours_building(case)
    ref = building_bench.reference_building(case)
    errors = building_bench.building_errors(ours, ref)
    assert errors["error_max"] < 1e-9, errors
    s = case.superstructure
    other = tests_reference(case.acceleration_m_s2, case.dt_s, s.masses_kg, s.story_stiffnesses(), s.damping_ratio,
                            case.total_mass_kg, case.isolator_stiffness_N_per_m, 0.0, case.mu, case.mu)
    assert float(np.max(np.abs(other["x_b"] - ref["slab"]))) < 1e-10 * float(np.max(np.abs(ref["slab"])))
    other_drift = np.diff(np.concatenate([np.zeros((other["u"].shape[0], 1)), other["u"]], axis=1), axis=1)
    assert float(np.max(np.abs(other_drift - ref["drift"]))) < 1e-9 * float(np.max(np.abs(ref["drift"])))
    assert float(np.max(np.abs(ref["slab"]))) > 0.01  # it slid


@needs_opensees
def test_opensees_building_converges_to_ours_when_the_plane_holds(records_dir):
    # µ = 0.9 under half the record: the plane never slides, the building is the fixed-base linear
    # structure (on the bearing's stiff elastic branch); Newmark's error shrinks with its step towards ours
    case = _case(records_dir, 4.0)
    case = replace(case, mu=0.9, acceleration_m_s2=0.5 * case.acceleration_m_s2)
    ours = building_bench.ours_building(case)
    assert float(np.max(np.abs(ours["slab"]))) == 0.0
    err = {}
    for substeps in (1, 8):
        e = building_bench.building_errors(building_bench.opensees_building_solver(case, substeps), ours)
        err[substeps] = max(e["error_drift"], e["error_floor_acc"])
    assert err[8] < err[1] / 5 and err[8] < 2e-2, err


@needs_opensees
def test_opensees_building_agrees_with_ours_within_its_error(records_dir):
    # sliding (µ = 0.06, the bench's building) on the first 6 s of the record: OpenSees at the record's dt
    # within its known error (elastic stick branch, Newmark at dt): peak isolator displacement within 5 %,
    # drifts within 15 % of their peaks (measured: 1.2 % and 6 % on the quick case)
    case = _case(records_dir, 6.0)
    ours = building_bench.ours_building(case)
    theirs = building_bench.opensees_building_solver(case, 1)
    e = building_bench.building_errors(theirs, ours)
    assert float(np.max(np.abs(ours["slab"]))) > 0.05
    assert e["error_peak_slab"] < 0.05 and e["error_slab"] < 0.15, e
    assert e["error_peak_drift"] < 0.15, e


@needs_opensees
def test_run_building_case_times_both_and_reports_ratios(records_dir):
    case = _case(records_dir, 3.0)
    result = building_bench.run_building_case(case, rounds=1, ours_per_round=2)
    assert result["ours"]["runs"] == 2 and result["opensees"]["runs"] == 1
    assert result["ours"]["error_max"] < 1e-9
    assert result["time_ratio"] == pytest.approx(result["opensees"]["seconds"] / result["ours"]["seconds"])
    assert result["error_ratio"] > 1e3
    assert "faster than OpenSees" in building_bench.building_summary([result])[0]


def test_run_building_case_without_opensees(records_dir, monkeypatch):
    import isolator.bench.opensees as opensees_module

    monkeypatch.setattr(opensees_module, "opensees_available", lambda: (False, "openseespy not installed"))
    result = building_bench.run_building_case(_case(records_dir, 2.0), rounds=1, ours_per_round=1)
    assert result["time_ratio"] is None and result["opensees"]["note"] == "openseespy not installed"
    assert result["ours"]["error_max"] < 1e-9


def test_cli_bench_without_the_building_record_says_so(tmp_path, monkeypatch):
    monkeypatch.setattr(bench, "bench_cases", lambda quick=False, records_dir=None: [])
    monkeypatch.setattr(bench, "run_bench", lambda **kwargs: ([], []))
    monkeypatch.setattr(bench, "plot", lambda rows, path: path.write_bytes(b"png"))
    result = CliRunner().invoke(app, ["bench", "--quick", "--out", str(tmp_path), "--records", str(tmp_path)])
    assert result.exit_code == 0, result.output
    assert "no building case" in result.stderr
