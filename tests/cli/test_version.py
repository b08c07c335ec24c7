"""``isolator --version``: the version of pyproject.toml, the checkout's commit, and no heavy import."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
HEAVY = ("numpy", "scipy", "obspy", "matplotlib", "numba", "dask", "pandas", "pyarrow")


def _project_version() -> str:
    """The version pyproject.toml declares: what an installation's metadata says."""
    with open(ROOT / "pyproject.toml", "rb") as f:
        return tomllib.load(f)["project"]["version"]


def _run(code: str) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])}
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=120)


def test_package_version_is_the_project_version():
    import isolator

    assert isolator.__version__ == _project_version()


def test_version_prints_the_version_and_the_commit_and_loads_no_heavy_library():
    code = ("import sys\nfrom isolator.cli import app\n"
            "try:\n    app(['--version'])\nexcept SystemExit as stop:\n    code = stop.code\n"
            f"print('exit', code, ' '.join(sorted({{m.split('.')[0] for m in sys.modules}} & set({HEAVY!r}))))")
    done = _run(code)
    assert done.returncode == 0, done.stderr
    first, last = done.stdout.splitlines()[0], done.stdout.splitlines()[-1]
    assert last == "exit 0 "  # exit 0, and none of the heavy libraries was imported
    match = re.fullmatch(r"isolator (\S+)(?: \(git ([0-9a-f]{4,40})(\+modified)?\))?", first)
    assert match, first
    assert match.group(1) == _project_version()
    git = shutil.which("git")
    if git and (ROOT / ".git").exists():  # a checkout: the commit is HEAD's
        head = subprocess.run([git, "-C", str(ROOT), "rev-parse", "HEAD"], capture_output=True, text=True)
        assert head.returncode == 0
        assert match.group(2) and head.stdout.strip().startswith(match.group(2))


def test_outside_a_checkout_there_is_no_commit(tmp_path):
    from isolator.cli import checkout_commit

    assert checkout_commit(tmp_path) is None


@pytest.mark.skipif(shutil.which("git") is None, reason="git is not installed")
def test_a_modified_checkout_says_so(tmp_path):
    from isolator.cli import checkout_commit

    def git(*args):
        subprocess.run(["git", "-C", str(tmp_path), *args], check=True, capture_output=True,
                       env={**os.environ, "GIT_AUTHOR_NAME": "t", "GIT_AUTHOR_EMAIL": "t@t",
                            "GIT_COMMITTER_NAME": "t", "GIT_COMMITTER_EMAIL": "t@t"})

    git("init", "-q")
    (tmp_path / "a.txt").write_text("one\n")
    git("add", "a.txt")
    git("commit", "-q", "-m", "one")
    head = subprocess.run(["git", "-C", str(tmp_path), "rev-parse", "--short", "HEAD"], capture_output=True,
                          text=True).stdout.strip()
    assert checkout_commit(tmp_path) == head
    (tmp_path / "a.txt").write_text("two\n")
    assert checkout_commit(tmp_path) == head + "+modified"
