"""`isolator report` under hostile use (issue 26): its PDF and JSON are one output set under a lock.

- a second run on a locked output is refused in one line naming the holder;
- a full disk (a real 256 KiB tmpfs) or a read-only folder is one line naming the output, exit 2, and the
  older PDF and JSON stay whole, with no temporary left (before: a 119-line zlib traceback);
- a kill -9 while the PDF is written leaves temporaries and a lock that the next run removes.

Each report is one component of 8 s with an 8 × 8 regime map (a few seconds of CPU).
"""

from __future__ import annotations

import json
import os
import signal
import socket
import subprocess
import sys
import textwrap

import numpy as np
import pytest
from _records import at2_text
from test_hostile_outputs import small_disk as small_disk  # the 256 KiB tmpfs fixture
from typer.testing import CliRunner

from isolator import atomic
from isolator.cli import app

RUNNER = CliRunner()
DESIGN = 'name = "d"\nmass_kg = 1000.0\nradius_m = 2.0\nmu_static = 0.06\n'


@pytest.fixture
def inputs(tmp_path):
    t = np.arange(800) * 0.01
    values = [float(v) for v in 0.25 * np.sin(2 * np.pi * 0.7 * t) * np.minimum(1.0, t / 2.0)]
    (tmp_path / "r.AT2").write_text(at2_text(values))
    (tmp_path / "d.toml").write_text(DESIGN)
    return tmp_path / "r.AT2", tmp_path / "d.toml"


def _args(inputs, output) -> list[str]:
    return ["report", str(inputs[0]), "-d", str(inputs[1]), "-o", str(output), "--map-resolution", "8"]


def _one_line(result, words: str) -> None:
    assert result.exit_code == 2, (result.exit_code, result.stdout[-500:], result.stderr[-2000:])
    assert len(result.stderr.splitlines()) == 1 and result.stderr.startswith("error: "), result.stderr[-2000:]
    assert words in result.stderr, result.stderr
    assert "Traceback" not in result.stderr + result.stdout


def test_a_report_whose_output_is_locked_is_refused_naming_the_holder(inputs, tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / "r.pdf.lock").write_text(f"pid=1 host={socket.gethostname()} since=earlier\n")
    _one_line(RUNNER.invoke(app, _args(inputs, out / "r.pdf")), "is being written by process 1")
    assert sorted(p.name for p in out.iterdir()) == ["r.pdf.lock"]  # nothing written, the holder's lock kept


@pytest.mark.parametrize("no_pdf", [False, True])
def test_a_report_holds_the_lock_while_it_runs_and_releases_it(inputs, tmp_path, monkeypatch, no_pdf):
    seen = []
    real = atomic.output_lock

    def watching(path):
        seen.append(atomic.lock_path(path))
        return real(path)
    monkeypatch.setattr(atomic, "output_lock", watching)
    output = tmp_path / "out" / "r.pdf"
    result = RUNNER.invoke(app, _args(inputs, output) + (["--no-pdf"] if no_pdf else []))
    assert result.exit_code == 0, result.stderr
    assert seen == [output.parent / "r.pdf.lock"]
    expected = ["r.json"] if no_pdf else ["r.json", "r.pdf"]
    assert sorted(p.name for p in output.parent.iterdir()) == expected  # the lock is gone


def test_a_full_disk_leaves_the_older_report_whole(inputs, small_disk):
    (small_disk / "r.pdf").write_bytes(b"old pdf")
    (small_disk / "r.json").write_text('{"run": "old"}')
    (small_disk / "filler").write_bytes(b"\0" * 200_000)  # about 56 KiB left: the PDF (~100 KiB) does not fit
    result = RUNNER.invoke(app, _args(inputs, small_disk / "r.pdf"))
    _one_line(result, "No space left on device")
    assert f"{small_disk / 'r.pdf'}: cannot write" in result.stderr
    assert (small_disk / "r.pdf").read_bytes() == b"old pdf" and (small_disk / "r.json").read_text() == '{"run": "old"}'
    assert sorted(p.name for p in small_disk.iterdir()) == ["filler", "r.json", "r.pdf"]  # no temporary, no lock
    (small_disk / "filler").unlink()  # room again: the new set lands whole
    result = RUNNER.invoke(app, _args(inputs, small_disk / "r.pdf"))
    assert result.exit_code == 0, result.stderr
    assert json.loads((small_disk / "r.json").read_text())["pdf"] == str(small_disk / "r.pdf")
    assert (small_disk / "r.pdf").read_bytes().startswith(b"%PDF")


def test_a_read_only_folder_is_one_line_naming_the_output(inputs, small_disk):
    subprocess.run(["mount", "-o", "remount,ro", str(small_disk)], check=True)
    result = RUNNER.invoke(app, _args(inputs, small_disk / "r.pdf"))
    _one_line(result, "Read-only file system")
    assert str(small_disk / "r.pdf") in result.stderr


def test_a_kill_during_the_pdf_write_leaves_nothing_the_next_run_keeps(inputs, tmp_path):
    output = tmp_path / "out" / "r.pdf"
    output.parent.mkdir()
    output.write_bytes(b"old pdf")
    output.with_suffix(".json").write_text('{"run": "old"}')
    # a real process killed by SIGKILL while the PDF's second page is written
    code = textwrap.dedent(f"""
        import os, signal
        from matplotlib.backends import backend_pdf
        from isolator.cli import app
        pages = []
        real = backend_pdf.PdfPages.savefig
        def savefig(self, *args, **kwargs):
            pages.append(1)
            if len(pages) == 2:
                os.kill(os.getpid(), signal.SIGKILL)
            return real(self, *args, **kwargs)
        backend_pdf.PdfPages.savefig = savefig
        app({_args(inputs, output)!r})
    """)
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert done.returncode == -signal.SIGKILL, done.stderr[-2000:]
    left = sorted(p.name for p in output.parent.iterdir())
    assert "r.pdf.lock" in left and any(name.startswith(".r.pdf.~") for name in left), left  # the kill's trace
    assert output.read_bytes() == b"old pdf"  # the older set is whole
    atomic._CLEANED_FOLDERS.discard(os.path.realpath(output.parent))  # the next run is a new process
    result = RUNNER.invoke(app, _args(inputs, output))
    assert result.exit_code == 0, result.stderr
    assert sorted(p.name for p in output.parent.iterdir()) == ["r.json", "r.pdf"]  # no temporary, no lock
    assert json.loads(output.with_suffix(".json").read_text())["pdf"] == str(output)
