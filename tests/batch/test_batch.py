"""Batch runner: grid parsing, cases, error rows, summary, chart, resume after a kill, Dask = local."""

from __future__ import annotations

import math
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from isolator.batch import (
    BatchError,
    ReadOptions,
    comparable,
    design_chart,
    expand_designs,
    expand_records,
    is_vertical,
    parse_grid,
    row_key,
    run_batch,
    suite_summary,
)

ISOLATOR = str(Path(sys.executable).with_name("isolator"))

DESIGNS = """
[[design]]
name = "FPS"
mass_kg = 200000.0
radius_m = 2.0
mu_static = 0.06

[[design]]
name = "FPS damped"
mass_kg = 200000.0
radius_m = 3.0
mu_static = 0.05
mu_kinetic = 0.04
damping_ratio = 0.1
"""

BAD_DESIGN = """
[[design]]
name = "kinetic above static"
mass_kg = 200000.0
radius_m = 2.0
mu_static = 0.05
mu_kinetic = 0.08
"""


def write_record(path: Path, pga_g: float, period_s: float, npts: int = 1500, dt_s: float = 0.01) -> Path:
    """A synthetic record (plain text stating its units): a modulated sine pulse train [g]."""
    t = np.arange(npts) * dt_s
    envelope = (t / t[-1]) ** 2 * np.exp(-6.0 * t / t[-1])
    acc = np.sin(2 * np.pi * t / period_s) * envelope
    acc *= pga_g / np.max(np.abs(acc))
    lines = ["# units: g"] + [f"{ti:.4f},{ai:.8e}" for ti, ai in zip(t, acc, strict=True)]
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.fixture
def suite(tmp_path):
    """Three synthetic records and a designs file with two designs."""
    records = tmp_path / "records"
    records.mkdir()
    for i, (pga, period) in enumerate([(0.35, 0.8), (0.25, 1.2), (0.5, 0.5)]):
        write_record(records / f"rec{i}.txt", pga, period)
    designs = tmp_path / "designs.toml"
    designs.write_text(DESIGNS)
    return records, designs


def read(path) -> pd.DataFrame:
    table = pd.read_csv(path, keep_default_na=False, na_values=[""])
    table["error"] = table["error"].astype(object).fillna("")
    return table


# --------------------------------------------------------------------------------------
# grid and cases
# --------------------------------------------------------------------------------------


def test_parse_grid_inclusive_values():
    key, values = parse_grid("radius_m=1:4:13")
    assert key == "radius_m" and len(values) == 13
    assert values[0] == 1.0 and values[-1] == 4.0 and values[1] == pytest.approx(1.25)
    assert parse_grid("mu_static = 0.03:0.12:10")[1][-1] == pytest.approx(0.12)
    assert parse_grid("damping_ratio=0.1:0.1:1") == ("damping_ratio", [0.1])


@pytest.mark.parametrize("spec, words", [
    ("radius_m", "KEY=START:STOP:COUNT"),
    ("radius=1:4:13", "not a numeric design key"),
    ("name=1:2:3", "not a numeric design key"),
    ("radius_m=1:4", "KEY=START:STOP:COUNT"),
    ("radius_m=a:4:3", "must be numbers"),
    ("radius_m=1:4:2.5", "whole number"),
    ("radius_m=1:4:0", ">= 1"),
    ("radius_m=1:4:1", "START = STOP"),
    ("radius_m=1:inf:3", "finite"),
])
def test_parse_grid_errors(spec, words):
    with pytest.raises(BatchError, match=words):
        parse_grid(spec)


def test_expand_designs_cartesian_product_and_invalid_grid_values():
    mappings = [{"name": "A", "mass_kg": 1e5, "radius_m": 2.0, "mu_static": 0.05},
                {"name": "B", "mass_kg": 1e5, "stiffness_N_per_m": 1e5, "mu_static": 0.05}]
    grids = [parse_grid("radius_m=-1:2:4"), parse_grid("mu_static=0.04:0.06:2")]
    cases = expand_designs(mappings, grids, source="d.toml")
    assert len(cases) == 2 * 4 * 2
    assert [c.index for c in cases] == list(range(16))
    assert cases[0].mapping["name"] == "A [radius_m=-1, mu_static=0.04]"
    assert cases[0].error == "d.toml[design 0]: key 'radius_m' must be > 0, got -1"
    assert cases[3].mapping["radius_m"] == 0.0 and "radius_m" in cases[3].error
    assert cases[4].error == "" and cases[4].mapping["radius_m"] == 1.0
    # B has a stiffness: sweeping the radius makes it invalid (both given), said in its rows
    assert all("either 'radius_m'" in c.error for c in cases[8:])
    assert len({c.design_hash for c in cases}) == 16


def test_repeated_design_keeps_its_rows(suite, tmp_path):
    records, designs = suite
    designs.write_text(DESIGNS + DESIGNS)
    result = run_batch([str(records / "rec0.txt")], designs, tmp_path / "t.csv", jobs=1)
    assert result.n_rows == 4 and list(result.table["design_index"]) == [0, 1, 2, 3]
    assert result.table["row_key"].nunique() == 4
    assert result.table["peak_displacement_m"].iloc[0] == result.table["peak_displacement_m"].iloc[2]


def test_expand_records_folders_globs_and_missing(tmp_path):
    (tmp_path / "a").mkdir()
    for name in ("x.AT2", "y.txt", "README.md", ".hidden"):
        (tmp_path / "a" / name).write_text("1")
    files = expand_records([str(tmp_path / "a"), str(tmp_path / "a" / "*.AT2"), str(tmp_path / "missing.at2")])
    assert [Path(f).name for f in files] == ["x.AT2", "y.txt", "missing.at2"]
    with pytest.raises(BatchError, match="no file matches"):
        expand_records([str(tmp_path / "*.nothing")])


def test_vertical_components():
    assert is_vertical("HN3 (Up)") and is_vertical("UD") and is_vertical("HNZ") and is_vertical("HN1 (U-D)")
    assert not is_vertical("HN1 (180)") and not is_vertical("HNE") and not is_vertical("NS")


def test_row_key_is_deterministic_and_depends_on_options():
    a = row_key("r.txt", None, "abc", ReadOptions())
    assert a == row_key(os.path.abspath("r.txt"), None, "abc", ReadOptions())
    assert a != row_key("r.txt", "E", "abc", ReadOptions())
    assert a != row_key("r.txt", None, "abc", ReadOptions(scale_to_pga_g=0.3))


# --------------------------------------------------------------------------------------
# rows: numbers equal to the report's analysis; bad records and designs
# --------------------------------------------------------------------------------------


def test_rows_equal_the_report_analysis(suite, tmp_path):
    from isolator.design import Design
    from isolator.motion import read_ground_motion
    from isolator.report.summary import analyse

    records, designs = suite
    result = run_batch([str(records / "rec0.txt")], designs, tmp_path / "t.csv", jobs=1)
    assert result.n_rows == 2 and result.n_failed == 0
    row = result.table.iloc[1]
    design = Design.from_mapping({**__import__("tomllib").loads(DESIGNS)["design"][1]})
    analysis = analyse(design, read_ground_motion(records / "rec0.txt"))
    r, p = analysis.response, analysis.adaptation.point
    assert row["design_name"] == "FPS damped"
    assert row["alpha"] == p.alpha and row["k"] == p.k and row["eta"] == p.eta
    assert row["peak_displacement_m"] == r.peak_displacement_m
    assert row["peak_transmitted_acceleration_m_s2"] == r.peak_transmitted_acceleration_m_s2
    assert row["n_events"] == r.n_events and row["energy_input_J_per_kg"] == r.energy_input_J_per_kg
    for name in ("regime", "zeta", "amplitude", "dominant_force"):
        assert row[f"{name}_record"] == getattr(analysis.record_class, name)
        assert row[f"{name}_harmonic"] == getattr(analysis.harmonic_class, name)
    assert row["pga_m_s2"] == analysis.adaptation.intensity.pga_m_s2
    assert row["record_format"] == "ISOLATOR_TEXT" and row["error"] == ""


def test_bad_record_and_bad_design_among_good_ones(suite, tmp_path):
    records, designs = suite
    (records / "garbage.txt").write_bytes(b"\x00\x01binary garbage\xff" * 20)
    designs.write_text(DESIGNS + BAD_DESIGN)
    out = tmp_path / "t.csv"
    result = run_batch([str(records), str(tmp_path / "absent.at2")], designs, out, jobs=2)
    table = read(out)
    assert len(table) == result.n_rows == 5 * 3
    failed = table[table["error"].astype(str) != ""]
    # 2 bad records × 3 designs + 3 good records × the bad design
    assert result.n_failed == len(failed) == 3 + 3 + 3
    garbage = table[table["record"].str.endswith("garbage.txt")]
    assert all("garbage.txt" in e for e in garbage["error"])
    assert all("no such file" in e for e in table[table["record"].str.endswith("absent.at2")]["error"])
    bad_design = table[(table["design_index"] == 2) & table["record"].map(lambda p: Path(p).name.startswith("rec"))]
    assert len(bad_design) == 3
    assert all("'mu_kinetic' (0.08) must not exceed 'mu_static' (0.05)" in e for e in bad_design["error"])
    good = table[table["error"].astype(str) == ""]
    assert len(good) == 6 and good["peak_displacement_m"].notna().all()
    assert set(good["regime_record"]) <= {"ST", "SS", "SL"}
    assert result.final_line() == "15 rows, 9 failed"
    assert not Path(str(out) + ".parts").exists()


def test_summary_against_a_hand_computation():
    table = pd.DataFrame({
        "design_index": [0, 0, 0, 1, 1], "design_name": ["a"] * 3 + ["b"] * 2, "design_file_index": [0] * 5,
        "radius_m": [2.0] * 3 + [3.0] * 2, "error": ["", "", "", "", "bad record"],
        "peak_displacement_m": [0.10, 0.20, 0.60, 0.05, np.nan],
        "peak_transmitted_acceleration_m_s2": [1.0, 2.0, 3.0, 0.5, np.nan],
        "regime_record": ["SS", "SS", "SL", "ST", None], "regime_harmonic": ["SL", "SL", "SL", "ST", None],
    })
    summary = suite_summary(table, ["radius_m"])
    a, b = summary.iloc[0], summary.iloc[1]
    sigma = math.sqrt(((0.1 - 0.3) ** 2 + (0.2 - 0.3) ** 2 + (0.6 - 0.3) ** 2) / 2)  # sample σ (n − 1)
    assert a["peak_displacement_m_mean"] == pytest.approx(0.3)
    assert a["peak_displacement_m_max"] == pytest.approx(0.6)
    assert a["peak_displacement_m_mean_plus_std"] == pytest.approx(0.3 + sigma)
    assert a["peak_transmitted_acceleration_m_s2_mean_plus_std"] == pytest.approx(2.0 + 1.0)
    assert (a["n_SS_record"], a["n_SL_record"], a["n_ST_record"], a["n_SL_harmonic"]) == (2, 1, 0, 3)
    assert (b["n_rows"], b["n_failed"], b["n_ST_record"]) == (2, 1, 1)
    assert b["peak_displacement_m_mean"] == pytest.approx(0.05) and math.isnan(b["peak_displacement_m_std"])


def test_same_motion_in_two_files_is_counted_once(suite, tmp_path):
    """Two files holding the same samples in another layout (another edition of one record): one motion."""
    records, designs = suite
    rows = (records / "rec0.txt").read_text().splitlines()[1:]
    again = ["# units: g", "# the same record, another edition: semicolons, a comment line"]
    (records / "rec0_again.txt").write_text("\n".join(again + [row.replace(",", ";") for row in rows]) + "\n")
    result = run_batch([str(records)], str(designs), str(tmp_path / "t.csv"), jobs=1,
                       options=ReadOptions(harmonic=False))
    table = read(tmp_path / "t.csv")
    assert table.groupby("motion_sha256")["record"].nunique().max() == 2  # the two files: one digest
    assert any("the same motion is in 2 files" in note for note in result.notes)
    summary = suite_summary(table)
    distinct = table[~table["record"].str.endswith("rec0_again.txt")]
    for design_index, row in summary.set_index("design_index").iterrows():
        expected = distinct[distinct["design_index"] == design_index]["peak_displacement_m"]
        assert row["n_duplicate_motions"] == 1 and row["n_rows"] == 4
        assert row["peak_displacement_m_mean"] == pytest.approx(expected.mean(), rel=1e-12)


def test_chart_pdf_has_its_pages(suite, tmp_path):
    from pypdf import PdfReader

    records, designs = suite
    grids = [parse_grid("radius_m=1:3:3"), parse_grid("mu_static=0.04:0.08:3")]
    result = run_batch([str(records / "rec0.txt"), str(records / "rec2.txt")], designs, tmp_path / "t.parquet",
                       grids=grids, jobs=2)
    assert result.n_rows == 2 * 2 * 9 and result.n_failed == 0
    assert len(pd.read_parquet(tmp_path / "t.parquet")) == 36
    pages = design_chart(result.table, ["radius_m", "mu_static"], tmp_path / "chart.pdf")
    reader = PdfReader(tmp_path / "chart.pdf")
    assert pages == len(reader.pages) == 4  # 2 designs in the file × (displacement, acceleration)
    text = reader.pages[0].extract_text()
    assert "mean peak displacement" in text and "radius_m" in text and "mu_static" in text
    assert "transmitted acceleration" in reader.pages[1].extract_text()


# --------------------------------------------------------------------------------------
# never lose work: kill, resume, same table
# --------------------------------------------------------------------------------------


def test_interrupted_then_resumed_equals_uninterrupted(tmp_path):
    records = tmp_path / "records"
    records.mkdir()
    for i in range(10):
        write_record(records / f"r{i:02d}.txt", 0.2 + 0.04 * i, 0.4 + 0.1 * i, npts=2500)
    designs = tmp_path / "designs.toml"
    designs.write_text(DESIGNS)
    args = [str(records), "--designs", str(designs), "--grid", "mu_static=0.03:0.09:4", "--jobs", "1"]
    env = {**os.environ, "PYTHONWARNINGS": "ignore"}

    killed = tmp_path / "killed.csv"
    parts = Path(str(killed) + ".parts")
    process = subprocess.Popen([ISOLATOR, "batch", *args, "-o", str(killed)], stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL, start_new_session=True, env=env)
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and not (parts.is_dir() and list(parts.glob("part-*.jsonl"))):
        time.sleep(0.01)
    os.killpg(process.pid, signal.SIGKILL)
    process.wait()
    n_parts = len(list(parts.glob("part-*.jsonl")))
    assert 1 <= n_parts < 10 and not killed.exists(), "the batch was not interrupted mid-way"

    resumed = subprocess.run([ISOLATOR, "batch", *args, "-o", str(killed)], capture_output=True, text=True, env=env)
    # the damped design has mu_kinetic = 0.04 > mu_static = 0.03 at the first grid value: 10 error rows
    assert resumed.returncode == 1, resumed.stderr
    assert "resumed" in resumed.stdout and resumed.stdout.strip().splitlines()[-1] == "80 rows, 10 failed"
    assert not parts.exists()

    straight = tmp_path / "straight.csv"
    clean = subprocess.run([ISOLATOR, "batch", *args, "-o", str(straight)], capture_output=True, text=True, env=env)
    assert clean.returncode == 1, clean.stderr
    pd.testing.assert_frame_equal(comparable(read(killed)), comparable(read(straight)))

    # a third run with the same arguments finds every row done
    again = subprocess.run([ISOLATOR, "batch", *args, "-o", str(killed)], capture_output=True, text=True, env=env)
    assert again.stdout.strip().splitlines()[-1] == "80 rows, 10 failed"
    assert re.search(r"resumed\s+80 rows", again.stdout)
    pd.testing.assert_frame_equal(comparable(read(killed)), comparable(read(straight)))


# --------------------------------------------------------------------------------------
# one code path, two executors: a real LocalCluster gives the local table
# --------------------------------------------------------------------------------------


def test_local_cluster_table_equals_local_table(suite, tmp_path):
    distributed = pytest.importorskip("distributed")
    records, designs = suite
    grids = [parse_grid("mu_static=0.04:0.08:3")]
    local = run_batch([str(records)], designs, tmp_path / "local.csv", grids=grids, jobs=2)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                                  dashboard_address=None) as cluster:
        remote = run_batch([str(records)], designs, tmp_path / "dask.csv", grids=grids,
                           scheduler=cluster.scheduler_address)
    assert local.n_rows == remote.n_rows == 3 * 6 and remote.n_failed == 0
    pd.testing.assert_frame_equal(comparable(read(tmp_path / "local.csv")), comparable(read(tmp_path / "dask.csv")))


# --------------------------------------------------------------------------------------
# real records
# --------------------------------------------------------------------------------------


def test_real_records_all_horizontal(records_dir, tmp_path):
    designs = tmp_path / "designs.toml"
    designs.write_text(DESIGNS)
    paths = [str(records_dir / "other" / "ce89486SampleInput.v2"), str(records_dir / "at2" / "RSN1044_NORTHR_NWH360.AT2")]
    result = run_batch(paths, designs, tmp_path / "t.csv", component="all-horizontal", jobs=2)
    table = result.table
    assert result.n_failed == 0
    v2 = table[table["record"].str.endswith(".v2")]
    assert len(v2) == 4 and len(set(v2["component"])) == 2
    assert not any("Up" in c for c in v2["component"])
    at2 = table[table["record"].str.endswith(".AT2")]
    assert len(at2) == 2 and at2["pga_m_s2"].iloc[0] == pytest.approx(0.5904 * 9.80665, rel=1e-3)
