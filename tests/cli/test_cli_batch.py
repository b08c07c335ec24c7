"""`isolator batch`: command-line mistakes (exit 2), failed rows (exit 1), outputs, --reports."""

from __future__ import annotations

import pandas as pd
import pytest
from typer.testing import CliRunner

from isolator.cli import app
from tests.batch.test_batch import DESIGNS, write_record

runner = CliRunner()


@pytest.fixture
def files(tmp_path):
    write_record(tmp_path / "a.txt", 0.3, 0.8)
    write_record(tmp_path / "b.txt", 0.4, 0.6)
    designs = tmp_path / "designs.toml"
    designs.write_text(DESIGNS)
    return tmp_path, designs


def run(*args):
    return runner.invoke(app, ["batch", *[str(a) for a in args]])


def test_batch_in_help():
    result = runner.invoke(app, ["--help"])
    assert result.exit_code == 0 and "batch" in result.output
    result = runner.invoke(app, ["batch", "--help"])
    assert result.exit_code == 0 and "--scheduler" in result.output and "all-horizontal" in result.output


@pytest.mark.parametrize("extra, words", [
    (["--grid", "radius_m=1:4"], "KEY=START:STOP:COUNT"),
    (["--grid", "radius=1:4:3"], "not a numeric design key"),
    (["--grid", "radius_m=1:2:2", "--grid", "radius_m=2:3:2"], "swept once"),
    (["--chart", "c.pdf"], "two --grid"),
    (["--summary", "s.txt"], "must end with .csv"),
    (["--units", "furlongs"], "--units"),
    (["--scale-to-pga", "-1"], "must be > 0"),
])
def test_command_mistakes_exit_2_with_one_line(files, extra, words):
    folder, designs = files
    result = run(folder / "a.txt", "--designs", designs, "-o", folder / "t.csv", *extra)
    assert result.exit_code == 2
    assert words in result.stderr and len(result.stderr.strip().splitlines()) == 1
    assert "Traceback" not in result.output


def test_bad_designs_file_and_output_suffix_exit_2(files):
    folder, designs = files
    (folder / "empty.toml").write_text("name = 'not a list'\n")
    for args, words in (((folder / "a.txt", "--designs", folder / "none.toml", "-o", folder / "t.csv"), "no such"),
                        ((folder / "a.txt", "--designs", folder / "empty.toml", "-o", folder / "t.csv"), "[[design]]"),
                        ((folder / "a.txt", "--designs", designs, "-o", folder / "t.xlsx"), ".csv or .parquet"),
                        ((folder / "*.none", "--designs", designs, "-o", folder / "t.csv"), "no file matches"),
                        ((folder / "a.txt", "--designs", designs, "-o", "/proc/none/t.csv"), "cannot write")):
        result = run(*args)
        assert result.exit_code == 2 and words in result.stderr, result.output


def test_failed_rows_exit_1_and_final_line(files):
    folder, designs = files
    (folder / "broken.txt").write_text("# units: g\n0,0.1\n0.01,abc\n")
    out = folder / "t.csv"
    result = run(folder / "a.txt", folder / "broken.txt", folder / "b.txt", "--designs", designs, "-o", out,
                 "--jobs", "2")
    assert result.exit_code == 1, result.output
    assert result.stdout.strip().splitlines()[-1] == "6 rows, 2 failed"
    assert "first error" in result.stdout and "broken.txt" in result.stdout
    table = pd.read_csv(out, keep_default_na=False)
    assert list(table["record"].map(lambda p: p.rsplit("/", 1)[-1])) == ["a.txt"] * 2 + ["b.txt"] * 2 + ["broken.txt"] * 2


def test_parquet_summary_chart_and_scaling(files):
    from pypdf import PdfReader

    folder, designs = files
    result = run(folder / "*.txt", "--designs", designs, "-o", folder / "t.parquet", "--grid", "radius_m=1:3:3",
                 "--grid", "mu_static=0.05:0.07:2", "--scale-to-pga", "0.3", "--summary", folder / "s.csv",
                 "--chart", folder / "c.pdf")
    assert result.exit_code == 0, result.output
    assert result.stdout.strip().splitlines()[-1] == "24 rows, 0 failed"
    table = pd.read_parquet(folder / "t.parquet")
    assert len(table) == 24 and table["pga_m_s2"].to_numpy() == pytest.approx(0.3 * 9.80665)
    summary = pd.read_csv(folder / "s.csv")
    assert len(summary) == 12 and (summary["n_rows"] == 2).all()
    assert len(PdfReader(folder / "c.pdf").pages) == 4


def test_reports_one_row(files):
    folder, designs = files
    (folder / "one.toml").write_text(DESIGNS.split("[[design]]")[0] + "[[design]]" + DESIGNS.split("[[design]]")[1])
    result = run(folder / "a.txt", "--designs", folder / "one.toml", "-o", folder / "t.csv", "--reports",
                 folder / "reports", "--map-resolution", "8", "--jobs", "1")
    assert result.exit_code == 0, result.output
    pdfs = list((folder / "reports").glob("*.pdf"))
    assert len(pdfs) == 1 and pdfs[0].stat().st_size > 10_000
    assert pdfs[0].with_suffix(".json").is_file()


def test_units_and_dt_apply_only_to_files_that_need_them(files):
    import numpy as np

    folder, designs = files
    values = np.loadtxt(folder / "a.txt", delimiter=",", comments="#")[:, 1]
    np.savetxt(folder / "a.acc", values)  # one column, no units, no time step
    out = folder / "t.csv"
    result = run(folder / "a.acc", folder / "b.txt", "--designs", designs, "-o", out)
    assert result.exit_code == 1 and result.stdout.strip().splitlines()[-1] == "4 rows, 2 failed"
    result = run(folder / "a.acc", folder / "a.txt", folder / "b.txt", "--designs", designs, "-o", out,
                 "--units", "g", "--dt", "0.01")
    assert result.exit_code == 0, result.output
    table = pd.read_csv(out, keep_default_na=False).set_index(["record", "design_index"])
    acc, txt = table.loc[(str(folder / "a.acc"), 0)], table.loc[(str(folder / "a.txt"), 0)]
    assert acc["record_units_source"] == "--units g" and "units" in txt["record_units_source"]
    assert acc["peak_displacement_m"] == pytest.approx(txt["peak_displacement_m"], rel=1e-6)


def test_no_harmonic_leaves_its_columns_empty(files):
    folder, designs = files
    out = folder / "t.csv"
    assert run(folder / "a.txt", "--designs", designs, "-o", out, "--jobs", "1").exit_code == 0
    full = pd.read_csv(out)
    result = run(folder / "a.txt", "--designs", designs, "-o", out, "--jobs", "1", "--no-harmonic")
    assert result.exit_code == 0, result.output
    assert "resumed" not in result.stdout  # other options, other row keys
    quick = pd.read_csv(out)
    assert quick["regime_harmonic"].isna().all() and (quick["harmonic_seconds"] == 0).all()
    assert list(quick["peak_displacement_m"]) == list(full["peak_displacement_m"])
    assert list(quick["regime_record"]) == list(full["regime_record"])
