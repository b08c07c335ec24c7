"""The 2-D cases of the bench (isolator.bench.pairs): real pairs, the independent truth, OpenSees.

The quick 2-D case (the first 12 s of the Superstition Hills PTS pair on a friction
pendulum R = 2 m, µ = 0.06) runs once per module through the harness.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from isolator import bench
from isolator.bench import building as bench_building
from isolator.bench import opensees as opensees_module
from isolator.bench import tfp as bench_tfp
from isolator.cli import app
from tests.planar_reference import reference_pair as independent_reference_pair

RECORDS = Path(__file__).resolve().parents[2].parent / "shared" / "records"
OPENSEES_OK, OPENSEES_WHY = opensees_module.opensees_available()


def _quick_case():
    if not (RECORDS / "pairs" / "superstitionhills1987_PTS").is_dir():
        pytest.skip(f"shared records not found at {RECORDS} (clone without ../shared)")
    cases = bench.pair_cases(True, RECORDS)
    assert len(cases) == 1  # --quick keeps a single small 2-D case
    return cases[0]


@pytest.fixture(scope="module")
def quick_rows():
    case = _quick_case()
    rows, pareto = bench.run_bench(quick=True, repeats=1, cases=[case])
    return case, rows, pareto


def test_quick_case_is_the_start_of_a_real_pair():
    case = _quick_case()
    assert case.dt_s == 0.01 and case.ax_m_s2.size == 1201 and case.az_m_s2 is None
    assert case.mu_static == 0.06 and case.radius_m == 2.0
    # the two horizontals differ (a real pair, not one component twice)
    assert np.max(np.abs(case.ax_m_s2 - case.ay_m_s2)) > 1.0


def test_rows_have_the_expected_methods(quick_rows):
    case, rows, _ = quick_rows
    names = [r["method"] for r in rows]
    assert names[:2] == [bench.PAIR_OURS, bench.PAIR_TRUTH]
    assert names.count(bench.OPENSEES) == 1  # dt/1 in --quick
    assert names.count(bench.IVP_REGULARISED) == 2  # two tolerances
    assert all(r["case"] == case.name for r in rows)


def test_ours_agrees_with_the_truth(quick_rows):
    _, rows, _ = quick_rows
    ours = rows[0]
    assert ours["error_peak_rel"] <= 1e-9
    assert ours["error_residual_abs"] <= 1e-9  # [m], of a 0.3 m response
    assert ours["error_trajectory"] <= 1e-9
    # and its error is a real comparison, not a copy: the regularised baseline is far off
    ivp = [r for r in rows if r["method"] == bench.IVP_REGULARISED]
    assert all(1e-6 < r["error_trajectory"] < 0.2 for r in ivp)


@pytest.mark.skipif(not OPENSEES_OK, reason=f"openseespy does not import here: {OPENSEES_WHY}")
def test_opensees_row_is_present_and_sane(quick_rows):
    _, rows, pareto = quick_rows
    row = next(r for r in rows if r["method"] == bench.OPENSEES)
    assert not row.get("note") and row["seconds"] > 0.0
    assert 1e-6 < row["error_peak_rel"] < 0.10  # a different model (elastic stick branch), not a broken one
    assert row["error_trajectory"] < 0.10
    p = pareto[0]
    assert p["opensees_time_ratio"] == pytest.approx(row["seconds"] / rows[0]["seconds"])
    assert p["opensees_error_ratio"] > 1e3
    lines = bench.opensees_summary(pareto)
    assert len(lines) == 2 and "OpenSees" in lines[-1] and "faster" in lines[-1]


def test_without_openseespy_the_rows_say_so_and_the_bench_runs(monkeypatch, tmp_path):
    monkeypatch.setattr(opensees_module, "opensees_available", lambda: (False, "openseespy not installed"))
    t = np.arange(301) * 0.01
    case = bench.pair_case("synthetic pair", 4.0 * np.sin(5.0 * t), 3.0 * np.cos(4.0 * t), 0.01)
    monkeypatch.setattr(bench, "bench_cases", lambda quick=False, records_dir=None: [case])
    result = CliRunner().invoke(app, ["bench", "--quick", "--json", "--repeats", "1", "--out", str(tmp_path),
                                      "--records", str(tmp_path)])
    assert result.exit_code == 0, result.output
    cli_rows = json.loads(result.stdout)  # strict JSON: the missing times are null
    assert [r["seconds"] for r in cli_rows if r["method"] == bench.OPENSEES] == [None]
    rows = bench.run_pair_case(case, quick=True, repeats=1)
    theirs = [r for r in rows if r["method"] == bench.OPENSEES]
    assert theirs and all(r["note"] == "openseespy not installed" and math.isnan(r["seconds"]) for r in theirs)
    pareto = bench.pareto_summary(rows)
    assert pareto[0]["opensees_time_ratio"] is None
    assert bench.opensees_summary(pareto) == [
        "2-D vs OpenSees: not measured (openseespy not installed, or it does not load here)"]
    assert "openseespy not installed" in bench.rows_markdown(rows)
    assert "openseespy not installed" in bench.rows_to_csv(rows)


def test_ours_and_the_headline_baseline_are_timed_in_alternation(monkeypatch):
    """The headline ratio comes from one stretch of time: ours ×5, OpenSees once, two rounds per
    repeat; the OpenSees dt/1 row reuses those runs (it is not timed a second time)."""
    calls = []
    t = np.arange(201) * 0.01
    case = bench.pair_case("synthetic pair", 4.0 * np.sin(5.0 * t), 3.0 * np.cos(4.0 * t), 0.01)
    ours_output = bench.planar_solver(case)

    def ours(c, setting=None):
        calls.append("o")
        return ours_output

    def theirs(c, setting):
        calls.append(f"b{setting}")
        return replace(ours_output, displacement=ours_output.displacement * 1.01)

    methods = [replace(m, function=theirs, available=lambda: (True, "")) if m.name == bench.OPENSEES else m
               for m in bench.pair_methods(True)]
    monkeypatch.setattr(bench.harness, "pair_methods", lambda quick=False: methods)
    monkeypatch.setattr(bench.harness, "planar_solver", ours)
    rows = bench.run_pair_case(case, quick=True, repeats=3)
    assert "".join(c[0] for c in calls) == ("o" * 5 + "b") * 6  # no further OpenSees run
    assert set(c for c in calls if c != "o") == {"bdt/1"}
    row = next(r for r in rows if r["method"] == bench.OPENSEES)
    assert row["runs"] == 6 and rows[0]["runs"] == 30 and row["seconds"] > 0.0
    _, _, n_ours, _, _, n_base = bench.harness.time_interleaved(ours, theirs, case, "dt/1", 2, 4)
    assert (n_ours, n_base) == (8, 2)


def test_bench_reference_is_the_tests_reference():
    """The bench's truth is the reference called with the case's own system (no parameter lost on the way)."""
    t = np.arange(401) * 0.01
    ax, ay, az = 4.0 * np.sin(5.0 * t), 3.0 * np.cos(4.0 * t) * np.exp(-0.2 * t), 2.0 * np.sin(9.0 * t)
    case = bench.pair_case("synthetic pair", ax, ay, 0.01, az, **bench.pairs.PAIR_MU_V)
    ours = bench.reference_solver(case)
    theirs = independent_reference_pair(t, ax, ay, az, mu_s=case.mu_static, radius=2.0, mu_slow=case.mu_slow,
                                        mu_fast=case.mu_fast, rate=case.rate_s_per_m)
    np.testing.assert_array_equal(ours.displacement, theirs.displacement_m)
    assert ours.peak == theirs.peak_displacement_m and ours.peak > 0.05


def test_pair_errors_measure_the_resultant():
    t = np.arange(5) * 0.1
    ref = bench.MethodOutput(np.column_stack([t, 0 * t]), np.zeros((5, 2)), 0.4, 0.4, 0.5)
    out = bench.MethodOutput(np.column_stack([t, 0 * t + 0.03]), np.zeros((5, 2)), 0.41, 0.401, 0.5)
    e = bench.pair_errors(out, ref)
    assert e["error_peak_rel"] == pytest.approx(0.025)
    assert e["error_residual_abs"] == pytest.approx(0.03)  # |X_end − X_ref,end|, a vector difference
    assert e["error_trajectory"] == pytest.approx(0.03 / 0.4)


def test_cli_bench_quick_with_pairs(tmp_path, monkeypatch):
    """The command runs the quick 2-D case from a records folder and writes its rows and summary; the building
    and triple-pendulum cases read from the same folder run on the first second of their records (their
    numbers are tested in test_bench_building.py and test_bench_tfp.py; here, that the command carries them)."""
    case = _quick_case()  # its first 3 s, to keep the command's test short
    small = bench.pair_case(case.name, case.ax_m_s2[:301], case.ay_m_s2[:301], case.dt_s)
    monkeypatch.setattr(bench, "bench_cases", lambda quick=False, records_dir=None: [small])
    for table in (bench_building.BUILDING_SECONDS, bench_building.BUILDING_PAIR_SECONDS, bench_tfp.TFP_SECONDS,
                  bench_tfp.TFP_PAIR_SECONDS):
        monkeypatch.setitem(table, "quick", 1.0)
    result = CliRunner().invoke(app, ["bench", "--quick", "--repeats", "1", "--out", str(tmp_path),
                                      "--records", str(RECORDS)])
    assert result.exit_code == 0, result.output
    document = json.loads((tmp_path / "bench.json").read_text())
    methods = {r["method"] for r in document["rows"]}
    assert {bench.PAIR_OURS, bench.PAIR_TRUTH, bench.OPENSEES, bench.IVP_REGULARISED} <= methods
    assert document["summary_2d"] and document["summary_2d"][-1] in result.stdout
    assert "load_average_1_5_15" in document["machine"]
    # the 1-D and 2-D building and the 1-D and 2-D triple pendulum, each exact against its reference
    assert len(document["building"]) == 2 and len(document["triple_friction_pendulum"]) == 2
    assert all(result["ours"]["error_max"] < 1e-9 for result in document["building"])
    assert document["summary_building"] and document["summary_building"][-1] in result.stdout


@pytest.mark.skipif(not OPENSEES_OK, reason=f"openseespy does not import here: {OPENSEES_WHY}")
def test_opensees_leaves_no_line_on_stderr_at_exit():
    """openseespy prints "Process 0 Terminating" at exit; the bench's module keeps it off the terminal."""
    code = ("import openseespy.opensees as ops\n"
            "from isolator.bench.opensees import opensees_available\n"
            "assert opensees_available()[0]\n"
            "ops.wipe()\n"
            "print('done')\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0
    assert done.stdout == "done\n"
    assert done.stderr == ""
    # and without the module, the library's line is there (the test can fail)
    raw = subprocess.run([sys.executable, "-c", "import openseespy.opensees as ops\nops.wipe()\n"],
                         capture_output=True, text=True, timeout=120)
    assert "Terminating" in raw.stderr
