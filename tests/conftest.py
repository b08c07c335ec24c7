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


#: The models whose compiled kernels the xdist controller builds before its workers start, in this order (the
#: costliest first, :data:`isolator.solver.models.WARM_UP_ORDER`), each in its own process by
#: :func:`isolator.solver.models.warm_up`.
def engine_warm_ups() -> tuple[str, ...]:
    from isolator.solver import models

    return models.WARM_UP_ORDER


#: A warm-up process that has not finished after this long is left to the workers (they compile what is missing).
WARM_UP_TIMEOUT_S = 1800.0
#: How often the warm-up looks whether one of its processes has ended (a free core waits at most this long).
WARM_UP_POLL_S = 0.1
#: Prefixed to a warm-up process's code (``{pid}``: pytest's): it ends when pytest dies, however pytest died
#: (:func:`isolator.parallel.die_with_parent`, the initializer of the batch's pool workers too).
DIE_WITH_PARENT = "from isolator.parallel import die_with_parent\ndie_with_parent({pid})\n"
#: Where :func:`pytest_configure` leaves the warm-up's line for the terminal summary.
WARM_LINE = pytest.StashKey[str]()


def run_at_most(jobs: dict[str, list[str]], processes: int, timeout_s: float) -> list[str]:
    """Run the commands ``jobs`` (name → argv, in this order), at most ``processes`` at a time, and return the
    names of those that failed (non-zero exit) or had not ended ``timeout_s`` after the first started (killed then,
    the ones not started yet named too).

    A command starts as soon as any running one ends, not when the oldest ends: waiting for the oldest left a core
    idle behind a long compilation for ~3 min of last session's cold CI warm-up (docs/performance.md, h198)."""
    import subprocess
    import time

    start = time.monotonic()
    todo = list(jobs)
    running: dict[str, subprocess.Popen] = {}
    failed: list[str] = []
    try:
        # bounded: each command is started once and polled until it ends or timeout_s has passed
        while todo or running:
            while todo and len(running) < processes:
                name = todo.pop(0)
                running[name] = subprocess.Popen(jobs[name], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            ended = [name for name, process in running.items() if process.poll() is not None]
            for name in ended:
                if running.pop(name).returncode != 0:
                    failed.append(name)
            if ended:
                continue
            if time.monotonic() - start > timeout_s:
                failed += list(running) + todo
                todo.clear()
                break  # the finally kills what still runs
            time.sleep(WARM_UP_POLL_S)
    finally:  # Ctrl-C (or an error, or the time-out) here: no compilation goes on without its run
        for process in running.values():
            process.kill()
            process.wait()
    return failed


def _warm_engines(processes: int) -> str:
    """Compile (or load) every engine's kernels into numba's disk cache, ``processes`` at a time.

    Under ``pytest -n N`` each worker is a fresh interpreter: on a cold cache (a fresh clone, CI) every worker
    compiled every kernel it met, at the same time as the others, since numba writes a kernel's cache only when
    its compilation ends.  Built once here, before the workers start, each worker loads them from the cache.
    Returns a line for the report's header; a warm-up that fails or times out is said there and changes nothing
    else (the workers then compile as before, and a test of that engine shows the failure)."""
    import time

    start = time.monotonic()
    jobs = {module: [sys.executable, "-c", DIE_WITH_PARENT.format(pid=os.getpid())
                     + f"from isolator.solver import models\nmodels.warm_up({module!r})"]
            for module in engine_warm_ups()}  # a model's name → its warm-up process
    failed = run_at_most(jobs, processes, WARM_UP_TIMEOUT_S)
    line = f"engines' kernels compiled or loaded before the workers: {time.monotonic() - start:.0f} s"
    return line + (f" (not warmed: {', '.join(failed)})" if failed else "")


#: The xdist scheduler of ``-n N`` when the command names none: an idle worker takes half of the other's queue
#: (xdist ≥ 3.2).  xdist's own default, ``load``, hands each worker its queue ahead, and one core sat idle for the
#: last ~1–2 min of a run while the other worked through its queue (docs/performance.md, h208, h217).
DEFAULT_DIST = "worksteal"


def default_dist(config) -> None:
    """Use :data:`DEFAULT_DIST` under ``-n N`` unless the command line (or ``PYTEST_ADDOPTS``) names a ``--dist``.

    xdist sets ``dist`` to ``load`` when ``-n`` comes without ``--dist``; the early parse (``known_args_namespace``)
    still says ``no`` then, and says what the user gave otherwise.  It cannot go in pyproject's ``addopts``: the
    per-file command ``-p no:xdist`` would reject the option."""
    given = getattr(config.known_args_namespace, "dist", "no")
    if config.option.dist == "load" and given == "no":
        config.option.dist = DEFAULT_DIST


def pytest_configure(config):
    """On the xdist controller (``-n N``, N ≥ 2), warm the engines' kernels before the workers start, and
    schedule the tests by :data:`DEFAULT_DIST` unless the command names a ``--dist``."""
    if hasattr(config, "workerinput"):
        return
    workers = getattr(config.option, "numprocesses", None)
    if isinstance(workers, int) and workers >= 2 and not config.option.collectonly:
        default_dist(config)
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
    from isolator.solver import models, planar, record

    models.warm_up(record.MODEL_NAME, planar.MODEL_NAME)
