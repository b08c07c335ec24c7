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


@pytest.fixture(scope="session", autouse=True)
def _engines_loaded():
    """Load (on a fresh clone: compile) the 1-D and 2-D engines once, before any test, so that a
    test reading a command's output never meets the first-compilation note of
    :mod:`isolator.solver.notice` (tests/solver/test_notice.py tests the note itself)."""
    from isolator.solver import planar, record

    record._warm_up_kernel()
    planar._warm_up()
