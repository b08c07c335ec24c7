"""The tests' warm-up schedule (tests/conftest.py :func:`run_at_most`): a free core takes the next command as soon
as any running one ends, and a time-out kills what runs and names what did not run."""

from __future__ import annotations

import sys

from tests.conftest import run_at_most


def test_a_free_slot_takes_the_next_command_while_the_oldest_still_runs(tmp_path):
    """Two slots, three commands: the first ends only once the third has started (it waits for the third's file, at
    most 20 s), the second ends at once.  Waiting for the oldest command before starting the next (the schedule up
    to edf7ccb) never starts the third while the first runs: the first gives up after 20 s and fails."""
    flag = tmp_path / "third-started"
    waits = (f"import pathlib, sys, time\nfor _ in range(400):\n    if pathlib.Path({str(flag)!r}).exists():\n"
             "        sys.exit(0)\n    time.sleep(0.05)\nsys.exit(1)")
    jobs = {"first": [sys.executable, "-c", waits], "second": [sys.executable, "-c", "pass"],
            "third": [sys.executable, "-c", f"import pathlib; pathlib.Path({str(flag)!r}).touch()"]}
    failed = run_at_most(jobs, 2, timeout_s=120.0)
    assert failed == [], failed
    assert flag.exists()


def test_a_time_out_kills_the_running_and_names_the_rest(tmp_path):
    """One slot: a command that would run for 10 min is killed at the time-out, the one behind it is not started;
    both are named, a failing command too."""
    never = tmp_path / "never-started"
    jobs = {"fails": [sys.executable, "-c", "raise SystemExit(3)"],
            "sleeps": [sys.executable, "-c", "import time; time.sleep(600)"],
            "behind": [sys.executable, "-c", f"import pathlib; pathlib.Path({str(never)!r}).touch()"]}
    assert run_at_most(jobs, 1, timeout_s=1.0) == ["fails", "sleeps", "behind"]
    assert not never.exists()
