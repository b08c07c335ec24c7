"""Session 23's sweep of outputs (coordinator): `bench` given a file where a folder belongs, `batch -o` over a file
the batch did not write (docs/security.md, "Session 23: outputs").
"""

from __future__ import annotations

import math

from _records import assert_one_line_exit_2, at2_text
from typer.testing import CliRunner

from isolator.cli import app

RUNNER = CliRunner()


# ---- `bench` told a file where a folder belongs

def test_bench_told_a_file_for_a_folder_says_so(tmp_path, monkeypatch):
    """8e44dd2: `--records FILE` said "no such folder of records" (it exists) and `--out FILE` "cannot create the
    output folder (File exists)"; the file is left as it was."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "a.AT2").write_text("x")
    (tmp_path / "recs").mkdir()
    line = assert_one_line_exit_2(RUNNER.invoke(app, ["bench", "--quick", "--records", "a.AT2"]))
    assert line == "error: a.AT2: is a file, not a folder of records (give the folder of the bench records with --records)"
    line = assert_one_line_exit_2(RUNNER.invoke(app, ["bench", "--quick", "--records", "recs", "--out", "a.AT2"]))
    assert line.startswith("error: --out a.AT2: is a file, not a folder (--out is the folder for bench.csv, "), line
    assert (tmp_path / "a.AT2").read_text() == "x"
    line = assert_one_line_exit_2(RUNNER.invoke(app, ["bench", "--quick", "--records", "none"]))
    assert line.startswith("error: none: no such folder of records"), line


# ---- `batch -o` over a file it did not write says so

def test_batch_over_a_table_it_did_not_write_says_it_replaces_it(tmp_path, monkeypatch):
    """8e44dd2 replaced `-o mine.csv` (the user's own table, or a batch table edited by hand) without a word; now a
    note names it, and a rerun over the batch's own table resumes without the note."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "x.AT2").write_text(at2_text([0.1 * math.sin(2 * math.pi * i * 0.01) for i in range(200)]))
    (tmp_path / "ds.toml").write_text('[[design]]\nname = "FPS"\nmass_kg = 1e6\nradius_m = 2.5\nmu_static = 0.06\n')
    (tmp_path / "mine.csv").write_text("my,own,table\n1,2,3\n")
    first = RUNNER.invoke(app, ["batch", "x.AT2", "-d", "ds.toml", "-o", "mine.csv", "--jobs", "1"])
    assert first.exit_code == 0, first.output
    note = ("note: mine.csv exists and is not a table this batch wrote whole (edited by hand, truncated, or another "
            "file): none of its rows are trusted, and it is replaced by the new table")
    assert note in first.stderr.splitlines()
    assert (tmp_path / "mine.csv").read_text().startswith("record,component,design_index")
    again = RUNNER.invoke(app, ["batch", "x.AT2", "-d", "ds.toml", "-o", "mine.csv", "--jobs", "1"])
    assert again.exit_code == 0 and "resumed" in again.stdout and "not a table this batch wrote" not in again.stderr
