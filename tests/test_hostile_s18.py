"""A hostile sweep (session 18): session 17's leftovers (a suite's magnitude of 1e-300 and a µk of 1e-300 read, the
per-mass flags bounded only by the solver, an interrupted review silent and its lock left by SIGTERM) and the one
escape of names shared by the design file and the command line (docs/security.md, "Session 18 sweep").
Each case but the parent-is-a-file outputs (right on main, kept as a regression test) failed on main before its fix.
"""

from __future__ import annotations

import math
import os
import signal
import subprocess
import sys
import time

import pytest
from _records import assert_one_line_exit_2, at2_text
from typer.testing import CliRunner

from isolator.cli import app
from isolator.errors import DesignError, SuiteError, TargetError

RUNNER = CliRunner()
DESIGN = 'name = "FPS"\nmass_kg = 1e6\nradius_m = 2.5\nmu_static = 0.06\n'


def _record(tmp_path, name="x.AT2"):
    """A 1 Hz sine of 0.1 g at 0.01 s, 2 s."""
    path = tmp_path / name
    path.write_text(at2_text([0.1 * math.sin(2 * math.pi * i * 0.01) for i in range(200)]))
    return path


# ---- 1. one escape: the design's name check shows a name as every command line does

@pytest.mark.parametrize("name, shown", [("\x1b]0;pwned\x07 FPS", "\\x1b]0;pwned\\x07 FPS"), ("FPS\u202e", "FPS\\u202e"),
                                         ("two\nlines", "two\\nlines")])
def test_the_design_name_check_and_the_cli_share_one_escape(name, shown):
    """main: the design hand-escaped every character as \\uXXXX ('\\u001b'), the CLI as '\\x1b'."""
    from isolator.cli import common
    from isolator.design import Design
    from isolator.errors import printable

    assert common.printable is printable and printable(name) == shown  # the one function, written out by hand
    with pytest.raises(DesignError) as info:
        Design.from_mapping({"name": name, "mass_kg": 1e6, "radius_m": 2.5, "mu_static": 0.06}, source="d.toml")
    assert f"key 'name' holds a control or format character ('{shown}')" in str(info.value)


# ---- 2. the per-mass flags: a meant range, one line naming the flag

@pytest.mark.parametrize("flag, value, words", [
    ("--stiffness-per-mass", "1e-300", "--stiffness-per-mass 1e-300 is outside 0 or [1e-06, 1e+10] 1/s²"),
    ("--stiffness-per-mass", "1e300", "--stiffness-per-mass 1e+300 is outside"),
    ("--stiffness-per-mass", "nan", "--stiffness-per-mass nan is outside"),
    ("--stiffness-per-mass", "-1", "--stiffness-per-mass -1 is outside"),
    ("--damping-per-mass", "1e-300", "--damping-per-mass 1e-300 is outside 0 or [1e-06, 1e+12] 1/s"),
    ("--damping-per-mass", "inf", "--damping-per-mass inf is outside"),
])
def test_simulate_per_mass_flags_have_a_meant_range_naming_the_flag(tmp_path, flag, value, words):
    """main: 1e-300 ran (a period of 6e150 s), the others named the System's keyword (stiffness_per_mass)."""
    result = RUNNER.invoke(app, ["simulate", str(_record(tmp_path)), "--mu-s", "0.05", flag, value])
    assert_one_line_exit_2(result, words)


@pytest.mark.parametrize("options", [[], ["--stiffness-per-mass", "3.9", "--damping-per-mass", "0.3"],
                                     ["--stiffness-per-mass", "-0"]])
def test_simulate_per_mass_flags_in_range_run(tmp_path, options):
    result = RUNNER.invoke(app, ["simulate", str(_record(tmp_path)), "--mu-s", "0.05", *options])
    assert result.exit_code == 0, result.output


# ---- 3. every µ of a design file goes through the meant range

@pytest.mark.parametrize("mapping, words", [
    ({"radius_m": 2.5, "mu_static": 0.06, "mu_kinetic": 1e-300}, "d.toml: key 'mu_kinetic' = 1e-300 is outside [0.0001, 1)"),
    ({"bearing": {"type": "single", "surface": [{"radius_m": 2.5, "mu_static": 0.06, "mu_kinetic": 1e-300}]}},
     "d.toml: bearing surface 1: key 'mu_kinetic' = 1e-300 is outside [0.0001, 1)"),
])
def test_a_kinetic_friction_of_1e_300_is_refused(mapping, words):
    """main: read, both (µk ≤ µs was the only bound below µs)."""
    from isolator.design import Design

    with pytest.raises(DesignError) as info:
        Design.from_mapping({"name": "F", "mass_kg": 1e6, **mapping}, source="d.toml")
    assert words in str(info.value)
    kept = Design.from_mapping({"name": "F", "mass_kg": 1e6, "radius_m": 2.5, "mu_static": 0.06, "mu_kinetic": 0.05})
    assert kept.mu_kinetic == 0.05
    paper = Design.from_mapping({"name": "F", "mass_kg": 1e6, "radius_m": 2.5, "mu_static": 0.06, "mu_kinetic": 0.0})
    assert paper.mu_kinetic == 0.0  # µk = 0: the paper's friction model, kept


# ---- 4. a suite's metadata and a target's controlling ranges: an earthquake an engineer means

@pytest.mark.parametrize("extra, words", [
    ("magnitude = 1e-300", "'magnitude' = 1e-300 is outside [1, 10]"),
    ("distance_km = 1e300", "'distance_km' = 1e+300 is outside [0, 1000] km"),
    ("distance_km = 12000.0", "'distance_km' = 12000 is outside"),  # metres
    ("vs30_m_s = 1e300", "'vs30_m_s' = 1e+300 is outside [50, 3500] m/s"),
    ("vs30_m_s = 1e-300", "'vs30_m_s' = 1e-300 is outside"),
])
def test_suite_metadata_outside_an_earthquake_is_refused(tmp_path, extra, words):
    """main: each was read and compared with the target's ranges."""
    from isolator.review.suite_specs import specs_from_toml

    record = _record(tmp_path)
    suite = tmp_path / "suite.toml"
    suite.write_text(f'[[pair]]\nname = "a"\nx = "{record}"\ny = "{record}"\n{extra}\n')
    with pytest.raises(SuiteError, match=r"suite\.toml: pair 1 \('a'\): ") as info:
        specs_from_toml(suite)
    assert words in str(info.value)
    suite.write_text(f'[[pair]]\nname = "a"\nx = "{record}"\ny = "{record}"\nmagnitude = 7.1\ndistance_km = 0.0\n'
                     "vs30_m_s = 180.0\n")
    assert specs_from_toml(suite)[0].metadata == {"magnitude": 7.1, "distance_km": 0.0, "vs30_m_s": 180.0}


@pytest.mark.parametrize("line, words", [("vs30_m_s_range = [0, 1e300]", "'vs30_m_s_range' end 1e+300 is outside"),
                                         ("magnitude_range = [1e-300, 7.0]", "'magnitude_range' end 1e-300 is outside"),
                                         ("distance_km_range = [0, 5e4]", "'distance_km_range' end 50000 is outside")])
def test_target_controlling_ranges_outside_an_earthquake_are_refused(tmp_path, line, words):
    from isolator.review.target import load_target

    target = tmp_path / "t.toml"
    target.write_text(f"S_MS = 1.5\nS_M1 = 0.9\nT_L = 8.0\n{line}\n")
    with pytest.raises(TargetError) as info:
        load_target(target)
    assert words in str(info.value)
    target.write_text("S_MS = 1.5\nS_M1 = 0.9\nT_L = 8.0\ndistance_km_range = [0, 30]\nmagnitude_range = [6.5, 7.5]\n")
    assert load_target(target).controlling["distance_km_range"] == [0.0, 30.0]


# ---- 5. an output whose parent is a file: one line, exit 2, the file kept (right on main: a regression test)

@pytest.mark.parametrize("command", ["simulate", "report", "batch"])
def test_an_output_under_a_file_is_one_line(tmp_path, command):
    record = _record(tmp_path)
    (tmp_path / "d.toml").write_text(DESIGN)
    (tmp_path / "ds.toml").write_text("[[design]]\n" + DESIGN)
    blocker = tmp_path / "afile"
    blocker.write_text("kept")
    args = {"simulate": ["simulate", str(record), "--mu-s", "0.05", "--out-csv", str(blocker / "o.csv")],
            "report": ["report", str(record), "-d", str(tmp_path / "d.toml"), "-o", str(blocker / "r.pdf")],
            "batch": ["batch", str(record), "-d", str(tmp_path / "ds.toml"), "-o", str(blocker / "t.csv")]}[command]
    assert_one_line_exit_2(RUNNER.invoke(app, args), "afile/", "cannot write (Not a directory)")
    assert blocker.read_text() == "kept" and sorted(p.name for p in tmp_path.iterdir()) == \
        ["afile", "d.toml", "ds.toml", "x.AT2"]


# ---- 6. an interrupted command: one line, exit 130, its lock and temporaries gone

def test_sigterm_in_a_command_is_an_interrupt_and_restored_after():
    """main: SIGTERM's default ended the process at once (no finally: a review's lock stayed)."""
    from isolator.cli.common import terminate_as_interrupt

    before = signal.getsignal(signal.SIGTERM)
    with pytest.raises(KeyboardInterrupt), terminate_as_interrupt():
        os.kill(os.getpid(), signal.SIGTERM)
        time.sleep(5)  # not reached: the handler raises at once
    assert signal.getsignal(signal.SIGTERM) is before


def test_an_interrupted_review_says_so_in_one_line(tmp_path, monkeypatch):
    """main: typer turned the interrupt into a silent exit 130."""
    import isolator.review.run as run

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt
    monkeypatch.setattr(run, "run_review", interrupted)
    x = _record(tmp_path)
    y = tmp_path / "y.AT2"
    y.write_text(at2_text([0.1 * math.cos(2 * math.pi * i * 0.013) for i in range(200)]))
    (tmp_path / "suite.toml").write_text(f'[[pair]]\nname = "a"\nx = "{x}"\ny = "{y}"\n')
    (tmp_path / "d.toml").write_text(DESIGN)
    (tmp_path / "t.toml").write_text("S_MS = 1.5\nS_M1 = 0.9\nT_L = 8.0\n")
    result = RUNNER.invoke(app, ["review", "-d", str(tmp_path / "d.toml"), "-t", str(tmp_path / "t.toml"), "-s",
                                 str(tmp_path / "suite.toml"), "-o", str(tmp_path / "out" / "r.pdf"), "-j", "1"])
    lines = [line for line in result.output.splitlines() if line.strip()]
    assert result.exit_code == 130 and len(lines) == 1 and lines[0].startswith("interrupted: "), result.output
    assert not (tmp_path / "out" / "r.pdf.lock").exists() and not (tmp_path / "out" / "r.pdf").exists()


def test_a_report_killed_by_sigterm_leaves_no_lock(tmp_path):
    """A real process: SIGTERM once its lock exists; main: killed at once, `r.pdf.lock` left, nothing said."""
    record = _record(tmp_path)
    (tmp_path / "d.toml").write_text(DESIGN)
    output = tmp_path / "r.pdf"
    process = subprocess.Popen([sys.executable, "-c", "from isolator.cli import app; app()", "report", str(record), "-d",
                                str(tmp_path / "d.toml"), "-o", str(output)], stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True, env={**os.environ, "OPENBLAS_NUM_THREADS": "1"})
    lock = tmp_path / "r.pdf.lock"
    deadline = time.monotonic() + 60
    while not lock.exists() and process.poll() is None and time.monotonic() < deadline:
        time.sleep(0.01)
    if not lock.exists():
        process.kill()
        pytest.skip("the report finished before its lock was seen")
    process.send_signal(signal.SIGTERM)
    _, err = process.communicate(timeout=60)
    lines = [line for line in err.splitlines() if line.strip()]
    assert process.returncode == 130 and len(lines) == 1 and lines[0].startswith("interrupted: "), err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["d.toml", "x.AT2"]


def test_a_sigterm_between_the_lock_and_its_holder_leaves_no_lock(tmp_path, monkeypatch):
    """CI, 2026-11-29: SIGTERM just after the lock's creation, before its holder was written: the clean-up read the
    empty lock as another run's and left `r.pdf.lock` (the subprocess test above, flaky).  Now the two signals are
    held while the lock is made, and the interrupt is raised where the clean-up reaches it."""
    from isolator.atomic import output_lock
    from isolator.cli.common import terminate_as_interrupt

    real_fdopen = os.fdopen

    def fdopen_after_sigterm(*args, **kwargs):
        os.kill(os.getpid(), signal.SIGTERM)  # arrives with the lock created and still empty
        return real_fdopen(*args, **kwargs)

    ran = []
    monkeypatch.setattr(os, "fdopen", fdopen_after_sigterm)
    with pytest.raises(KeyboardInterrupt), terminate_as_interrupt(), output_lock(tmp_path / "r.pdf"):
        ran.append("body")
    monkeypatch.undo()
    assert ran == [] and sorted(p.name for p in tmp_path.iterdir()) == []
    with output_lock(tmp_path / "r.pdf") as lock:  # taken again at once, and released
        assert lock.read_text().startswith(f"pid={os.getpid()} ")
    assert not lock.exists()
