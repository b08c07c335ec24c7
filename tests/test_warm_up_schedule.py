"""The tests' warm-up schedule (tests/conftest.py :func:`run_at_most`): a free core takes the next command as soon
as any running one ends, and a time-out kills what runs and names what did not run."""

from __future__ import annotations

import sys
from types import SimpleNamespace

import pytest

from tests.conftest import DEFAULT_DIST, default_dist, run_at_most


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


@pytest.mark.parametrize(("given", "after_xdist", "expected"), [
    ("no", "load", "worksteal"),  # `-n auto` alone: xdist set `load`, the command named none
    ("load", "load", "load"),  # `-n 2 --dist load` (or PYTEST_ADDOPTS): the user's choice stays
    ("loadfile", "loadfile", "loadfile"),
    ("no", "no", "no"),  # no xdist run
])
def test_the_default_scheduler_applies_only_when_the_command_names_none(given, after_xdist, expected):
    """xdist turns `dist` into `load` under `-n` without `--dist`; the early parse still says `no` then."""
    config = SimpleNamespace(known_args_namespace=SimpleNamespace(dist=given), option=SimpleNamespace(dist=after_xdist))
    default_dist(config)
    assert config.option.dist == expected


def test_the_default_scheduler_is_one_xdist_knows():
    """`worksteal` came with pytest-xdist 3.2: an older xdist would reject the scheduler at the first run."""
    import xdist
    from packaging.version import Version
    from xdist.scheduler import WorkStealingScheduling  # noqa: F401  (absent before 3.2)

    assert DEFAULT_DIST == "worksteal" and Version(xdist.__version__) >= Version("3.2")
