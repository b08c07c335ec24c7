"""No command writes over one of its inputs, onto a non-regular file, or without naming the path."""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

import numpy as np
import pytest
from _records import at2_text
from typer.testing import CliRunner

from isolator.cli import app

RUNNER = CliRunner()
DESIGN = 'name = "d"\nmass_kg = 1000.0\nradius_m = 2.0\nmu_static = 0.06\n'


def _digest(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


@pytest.fixture
def inputs(tmp_path):
    record = tmp_path / "in.AT2"
    record.write_text(at2_text([0.2 * np.sin(0.3 * i) for i in range(400)]))
    design = tmp_path / "d.json"  # a design file may have any name, .json included
    design.write_text(DESIGN)
    return record, design


def _one_line_exit_2(result, *words):
    assert result.exit_code == 2, (result.stdout, result.stderr)
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ") and "Traceback" not in result.stderr, result.stderr
    for word in words:
        assert word in lines[0]


def test_simulate_never_writes_over_its_record(inputs, tmp_path):
    record, _ = inputs
    before = _digest(record)
    (tmp_path / "alias.csv").symlink_to(record)
    os.link(record, tmp_path / "hard.csv")
    for out in (record, tmp_path / "alias.csv", tmp_path / "hard.csv", tmp_path / "sub" / ".." / "in.AT2"):
        result = RUNNER.invoke(app, ["simulate", str(record), "--mu-s", "0.1", "--out-csv", str(out)])
        _one_line_exit_2(result, f"{out}: is an input of this command")
    assert _digest(record) == before


def test_report_json_sidecar_never_writes_over_the_design(inputs, tmp_path):
    record, design = inputs
    before = _digest(design)
    result = RUNNER.invoke(app, ["report", str(record), "-d", str(design), "-o", str(tmp_path / "d.pdf")])
    _one_line_exit_2(result, f"{tmp_path / 'd.json'}: is an input of this command")
    assert _digest(design) == before and not (tmp_path / "d.pdf").exists()


def test_output_symlink_is_written_through(inputs, tmp_path):
    record, _ = inputs
    target = tmp_path / "store" / "histories.csv"
    target.parent.mkdir()
    target.write_text("old")
    (tmp_path / "link.csv").symlink_to(target)
    result = RUNNER.invoke(app, ["simulate", str(record), "--mu-s", "0.1", "--out-csv", str(tmp_path / "link.csv")])
    assert result.exit_code == 0, result.stderr
    assert (tmp_path / "link.csv").is_symlink()
    assert target.read_text().startswith("time_s,ground_acceleration_m_s2") and len(target.read_text().splitlines()) == 401


def test_non_regular_outputs(inputs, tmp_path):
    record, design = inputs
    fifo = tmp_path / "pipe.pdf"
    os.mkfifo(fifo)
    result = RUNNER.invoke(app, ["report", str(record), "-d", str(design), "-o", str(fifo)])
    _one_line_exit_2(result, f"{fifo}: is a FIFO (named pipe), not a regular file")
    result = RUNNER.invoke(app, ["simulate", str(record), "--mu-s", "0.1", "--out-csv", str(tmp_path)])
    _one_line_exit_2(result, f"{tmp_path}: is a folder")
    result = RUNNER.invoke(app, ["simulate", str(record), "--mu-s", "0.1", "--out-csv", "/dev/full"])
    _one_line_exit_2(result, "/dev/full: cannot write (No space left on device)")  # streamed, never replaced
    assert Path("/dev/full").is_char_device()


def test_csv_to_standard_output(inputs):
    record, _ = inputs
    result = RUNNER.invoke(app, ["simulate", str(record), "--mu-s", "0.1", "--out-csv", "-"])
    assert result.exit_code == 0 and result.stderr == ""
    lines = result.stdout.splitlines()
    assert lines[0].startswith("time_s,") and len(lines) == 401  # the CSV only, no table after it


def test_regime_map_output_format_and_write_error(tmp_path):
    result = RUNNER.invoke(app, ["regime-map", "-n", "8", "-o", str(tmp_path / "m.xyz")])
    _one_line_exit_2(result, "m.xyz: cannot tell the figure format from '.xyz'")
    blocker = tmp_path / "file"
    blocker.write_text("")
    result = RUNNER.invoke(app, ["regime-map", "-n", "8", "--no-cache", "-o", str(blocker / "m.png")])
    _one_line_exit_2(result, f"{blocker / 'm.png'}: cannot write")
