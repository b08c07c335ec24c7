"""The speed-against-error benchmark (isolator.bench) and the `isolator bench` command, on tiny cases."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from isolator import bench
from isolator.cli import app

ROW_KEYS = {"method", "case", "setting", "seconds", "error_peak_rel", "error_residual_abs", "error_zeta",
            "error_trajectory"}


def tiny_cases():
    """One harmonic case (configuration 1, 3 periods) and a 4 s synthetic record on a pendulum."""
    t = np.arange(0.0, 4.0, 0.01)
    acc = 3.0 * np.sin(2 * np.pi * 1.1 * t) * np.exp(-0.3 * t)  # [m/s²]
    return [bench.harmonic_case("tiny harmonic", 1.2, 0.0, 0.0, 0.25, 0.25, n_periods=3),
            bench.record_case("tiny record", acc, 0.01, mu_static=0.06, mu_kinetic=0.05,
                              stiffness_per_mass=bench.STANDARD_GRAVITY_M_S2 / 2.0)]


@pytest.fixture(scope="module")
def tiny_run():
    return bench.run_bench(quick=True, repeats=1, cases=tiny_cases())


def test_rows_have_the_keys_and_ours_is_exact(tiny_run):
    rows, pareto = tiny_run
    assert rows and all(ROW_KEYS <= set(row) for row in rows)
    ours = [row for row in rows if "exact" in row["method"]]
    assert len(ours) == 2  # one per case
    for row in rows:
        assert row["seconds"] > 0.0
        for key in ROW_KEYS - {"method", "case", "setting", "seconds"}:
            assert row[key] >= 0.0 and math.isfinite(row[key]), (row["method"], key)


def test_ours_is_the_most_accurate_and_on_the_pareto_front(tiny_run):
    rows, pareto = tiny_run
    for case in {row["case"] for row in rows}:
        ours = next(r for r in rows if r["case"] == case and "exact" in r["method"])
        assert ours["error_trajectory"] < 1e-7
        others = [r for r in rows if r["case"] == case and "exact" not in r["method"]
                  and "tightest" not in r["method"]]  # the cross-check ties with ours by construction
        assert all(r["error_trajectory"] > 10 * ours["error_trajectory"] for r in others)
    assert all(p["on_pareto_front"] for p in pareto)


def test_harmonic_exact_matches_the_analytic_steady_state(tiny_run):
    rows, _ = tiny_run
    ours = next(r for r in rows if r["case"] == "tiny harmonic" and "exact" in r["method"])
    assert ours["error_zeta_analytic"] < 1e-12
    assert ours["error_amplitude_analytic_rel"] < 1e-10


def test_baselines_converge_with_their_setting():
    case = tiny_cases()[1]
    ref = bench.exact_solver(case)
    coarse = bench.errors(case, bench.implicit_fixed_step(case, 1e-2), ref)["error_trajectory"]
    fine = bench.errors(case, bench.implicit_fixed_step(case, 1e-4), ref)["error_trajectory"]
    assert fine < coarse / 20  # first order
    loose = bench.errors(case, bench.ivp_with_events(case, 1e-3), ref)["error_trajectory"]
    tight = bench.errors(case, bench.ivp_with_events(case, 1e-8), ref)["error_trajectory"]
    assert tight < loose / 100


def test_cli_bench_json_and_files(tmp_path, monkeypatch, tiny_run):
    # the command hands the cases it reads to run_bench with its flags; run_bench on these very cases and
    # flags is the module's tiny_run (its rows are checked by the tests above), so it is not run a second
    # time here (3.9 s of CPU): the spy checks the call and returns tiny_run's result
    cases = tiny_cases()
    monkeypatch.setattr(bench, "bench_cases", lambda quick=False, records_dir=None: cases)
    calls = []

    def run_bench(**kwargs):
        calls.append(kwargs)
        return tiny_run

    monkeypatch.setattr(bench, "run_bench", run_bench)
    result = CliRunner().invoke(app, ["bench", "--quick", "--json", "--repeats", "1", "--out", str(tmp_path),
                                      "--records", str(tmp_path)])  # any folder: the cases are patched
    assert result.exit_code == 0, result.output
    assert len(calls) == 1 and calls[0]["cases"] is cases
    assert calls[0]["quick"] is True and calls[0]["repeats"] == 1
    rows = json.loads(result.stdout)
    assert isinstance(rows, list) and all(ROW_KEYS <= set(row) for row in rows)
    assert any("exact" in row["method"] for row in rows)
    assert len(rows) == len(tiny_run[0])  # every row of the run reaches the JSON
    for name in ("bench.csv", "bench_pareto.csv", "bench.json", "bench.md", "bench.png"):
        assert (tmp_path / name).stat().st_size > 0
    assert not list(tmp_path.glob(".*tmp")) and not list(tmp_path.glob(".bench.*"))
    document = json.loads((tmp_path / "bench.json").read_text())
    assert document["machine"]["cpus"] and document["pareto"]


def test_cli_bench_missing_records_folder_is_one_line(tmp_path):
    result = CliRunner().invoke(app, ["bench", "--quick", "--records", str(tmp_path / "nowhere"),
                                      "--out", str(tmp_path)])
    assert result.exit_code == 2
    assert result.stderr.strip().count("\n") == 0 and "nowhere" in result.stderr
