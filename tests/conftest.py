"""Shared fixtures: the real records in ../shared/records and builders of malformed records.

The real records live beside the repository (``<repo>/../shared/records``) and are never
copied into the project; tests that need them skip with a reason when the folder is
absent (a user's clone has no ``../shared``).  Malformed files are written by the tests
themselves into ``tmp_path``.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest

# Make tests/_records.py importable from every test folder.
sys.path.insert(0, str(Path(__file__).resolve().parent))

from _records import BAD_RECORDS  # noqa: E402

# CI (CI=true): the property tests draw the same examples on every run, so that a result is
# reproducible from the commit alone; locally they draw new ones each run (and keep failures).
if os.environ.get("CI"):
    from hypothesis import settings

    settings.register_profile("ci", derandomize=True, database=None)
    settings.load_profile("ci")

#: ``<repository>/../shared/records``: real records beside the repository, never copied into it.
RECORDS_DIR = Path(__file__).resolve().parents[1].parent / "shared" / "records"


@pytest.fixture(scope="session")
def records_dir() -> Path:
    """``../shared/records``; skips the test when the folder is absent."""
    if not RECORDS_DIR.is_dir():
        pytest.skip(f"shared records not found at {RECORDS_DIR} (clone without ../shared)")
    return RECORDS_DIR


@pytest.fixture
def make_bad_record(tmp_path):
    """Build a malformed record by name; returns (path, read options, expected words)."""

    def build(name: str):
        file_name, builder, options, words = BAD_RECORDS[name]
        path = tmp_path / file_name
        builder(path)
        return path, dict(options), words

    return build


#: The engines whose compiled kernels the xdist controller builds before its workers start (module, warm-up),
#: the costliest first: cold on this project's 2-core CI machine the 2-D ones take 1.5-10 min of CPU each.
ENGINE_WARM_UPS = (
    ("isolator.solver.planar_multisurface_rate", "_warm_up"),
    ("isolator.solver.planar_building_multisurface", "_warm_up"),
    ("isolator.solver.planar_multisurface", "_warm_up"),
    ("isolator.solver.planar_building", "_warm_up"),
    ("isolator.solver.planar", "_warm_up"),
    ("isolator.solver.building_multisurface", "_warm_up"),
    ("isolator.solver.multisurface_rate", "_warm_up"),
    ("isolator.solver.building", "_warm_up"),
    ("isolator.solver.multisurface", "_warm_up"),
    ("isolator.solver.record", "_warm_up_kernel"),
)
#: A warm-up process that has not finished after this long is left to the workers (they compile what is missing).
WARM_UP_TIMEOUT_S = 1800.0
#: Prefixed to a warm-up process's code: on Linux it gets SIGTERM when pytest dies, however pytest died.
DIE_WITH_PARENT = ("import ctypes, signal\ntry:\n    ctypes.CDLL(None).prctl(1, signal.SIGTERM, 0, 0, 0)\n"
                   "except (OSError, AttributeError):\n    pass\n")
#: Where :func:`pytest_configure` leaves the warm-up's line for the terminal summary.
WARM_LINE = pytest.StashKey[str]()


def _warm_engines(processes: int) -> str:
    """Compile (or load) every engine's kernels into numba's disk cache, ``processes`` at a time.

    Under ``pytest -n N`` each worker is a fresh interpreter: on a cold cache (a fresh clone, CI) every worker
    compiled every kernel it met, at the same time as the others, since numba writes a kernel's cache only when
    its compilation ends.  Built once here, before the workers start, each worker loads them from the cache.
    Returns a line for the report's header; a warm-up that fails or times out is said there and changes nothing
    else (the workers then compile as before, and a test of that engine shows the failure)."""
    import subprocess
    import time

    start = time.monotonic()
    todo = list(ENGINE_WARM_UPS)
    running: list[tuple[str, subprocess.Popen]] = []
    failed: list[str] = []
    try:
        while todo or running:  # bounded: ≤ len(ENGINE_WARM_UPS) processes, each waited at most WARM_UP_TIMEOUT_S
            while todo and len(running) < processes:
                module, function = todo.pop(0)
                code = DIE_WITH_PARENT + f"import {module} as m; m.{function}()"
                running.append((module, subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.DEVNULL,
                                                         stderr=subprocess.DEVNULL)))
            module, process = running.pop(0)
            try:
                if process.wait(timeout=max(1.0, WARM_UP_TIMEOUT_S - (time.monotonic() - start))) != 0:
                    failed.append(module)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()
                failed.append(module)
    finally:  # Ctrl-C (or an error) here: no compilation goes on without its run
        for _, process in running:
            process.kill()
            process.wait()
    line = f"engines' kernels compiled or loaded before the workers: {time.monotonic() - start:.0f} s"
    return line + (f" (not warmed: {', '.join(failed)})" if failed else "")


def pytest_configure(config):
    """On the xdist controller (``-n N``, N ≥ 2), warm the engines' kernels before the workers start."""
    if hasattr(config, "workerinput"):
        return
    workers = getattr(config.option, "numprocesses", None)
    if isinstance(workers, int) and workers >= 2 and not config.option.collectonly:
        config.stash[WARM_LINE] = _warm_engines(workers)


def pytest_terminal_summary(terminalreporter, exitstatus, config):
    line = config.stash.get(WARM_LINE, None)
    if line:
        terminalreporter.write_line(line)


@pytest.fixture(scope="session", autouse=True)
def _engines_loaded():
    """Load (on a fresh clone: compile) the 1-D and 2-D engines once, before any test, so that a
    test reading a command's output never meets the first-compilation note of
    :mod:`isolator.solver.notice` (tests/solver/test_notice.py tests the note itself)."""
    from isolator.solver import planar, record

    record._warm_up_kernel()
    planar._warm_up()
