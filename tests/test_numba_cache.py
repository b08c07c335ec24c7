"""numba's disk cache of isolator's kernels follows the sources they import (isolator.solver.jit).

numba keys a cached function on its own file only; a kernel that inlines a constant or an ``@njit``
function of another module kept its stale machine code when only that module changed.  Here:

* a tiny package built in a temporary folder with the real ``jit.py``: a kernel returns a constant of
  another module; the constant changes, the kernel file does not; a fresh process must give the new
  value, compiled again (with numba's own ``cache=True`` it gives the old one, from its cache: the bug);
* a temporary copy of the real package: a change in ``multisurface_series.py`` alone (imported by
  ``multisurface_kernel.py``) moves that kernel's cache folder and not the 2-D engine's; a change in a
  module no kernel imports moves none;
* every module of the package that uses numba decorates through ``isolator.solver.jit``.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "isolator"

KERNEL = """from isolator.solver.jit import njit
from isolator.solver.probe_constants import LEVEL


@njit(cache=True)
def level(x):
    return x + LEVEL
"""

NUMBA_ONLY = KERNEL.replace("from isolator.solver.jit import njit", "from numba import njit")

RUN = """import sys
sys.path.insert(0, sys.argv[1])
from isolator.solver.probe_kernel import level
print(level(1.0), sum(level.stats.cache_hits.values()), sum(level.stats.cache_misses.values()))
"""


def _probe_package(root: Path, kernel: str) -> None:
    """isolator/{__init__, solver/__init__, solver/jit (the real one), solver/probe_kernel, solver/probe_constants}."""
    solver = root / "isolator" / "solver"
    solver.mkdir(parents=True)
    (root / "isolator" / "__init__.py").write_text("")
    (solver / "__init__.py").write_text("")
    shutil.copy(PACKAGE / "solver" / "jit.py", solver / "jit.py")
    (solver / "probe_kernel.py").write_text(kernel)
    (solver / "probe_constants.py").write_text("LEVEL = 1.0\n")


def _run(root: Path, tmp_path: Path) -> tuple[float, bool]:
    """(level(1.0), compiled in this process) from a fresh interpreter."""
    env = {**os.environ, "ISOLATOR_CACHE_DIR": str(tmp_path / "user-cache"), "PYTHONPATH": str(root)}
    env.pop("NUMBA_CACHE_DIR", None)
    done = subprocess.run([sys.executable, "-c", RUN, str(root)], capture_output=True, text=True, env=env,
                          timeout=300, cwd=root)
    assert done.returncode == 0, done.stderr
    value, hits, misses = done.stdout.split()
    assert int(hits) + int(misses) == 1  # one signature: loaded from the disk cache, or compiled
    return float(value), int(misses) == 1


def _changed_constant(root: Path) -> None:
    constants = root / "isolator" / "solver" / "probe_constants.py"
    constants.write_text("LEVEL = 2.0\n")
    stat = constants.stat()  # a later mtime, as an editor leaves it
    os.utime(constants, (stat.st_atime + 5, stat.st_mtime + 5))


def test_a_changed_imported_constant_is_compiled_again(tmp_path):
    root = tmp_path / "tree"
    _probe_package(root, KERNEL)
    first = _run(root, tmp_path)
    again = _run(root, tmp_path)
    _changed_constant(root)
    changed = _run(root, tmp_path)
    assert first[0] == 2.0 and again[0] == 2.0
    assert again[1] is False  # the second process loaded the machine code from the disk cache
    assert changed == (3.0, True)  # the new constant, compiled again: not the stale 2.0
    assert (root / "isolator" / "__pycache__").is_dir()  # the cache is filed beside the sources
    assert len(list((root / "isolator" / "__pycache__").glob("numba-*"))) == 2


def test_numba_alone_keeps_the_stale_kernel(tmp_path):
    """The same sequence with numba's own decorator: the bug this module fixes (so the test above can fail)."""
    root = tmp_path / "tree"
    _probe_package(root, NUMBA_ONLY)
    assert _run(root, tmp_path)[0] == 2.0
    _changed_constant(root)
    assert _run(root, tmp_path)[0] == 2.0  # stale: numba looked only at probe_kernel.py, unchanged


def _folders(root: Path, tmp_path: Path) -> dict:
    """The cache folder of two kernel modules of the package copy at ``root``, from a fresh interpreter."""
    env = {**os.environ, "ISOLATOR_CACHE_DIR": str(tmp_path / "user-cache"), "PYTHONPATH": str(root)}
    code = ("import sys; from isolator.solver import jit; solver = jit.PACKAGE / 'solver'\n"
            "for name in ('multisurface_kernel.py', 'planar_kernel.py'): print(name, jit.cache_dir(str(solver / name)))")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=120,
                          cwd=root)
    assert done.returncode == 0, done.stderr
    return dict(line.split() for line in done.stdout.splitlines())


def test_the_real_kernels_follow_their_imported_modules(tmp_path):
    root = tmp_path / "copy"
    shutil.copytree(PACKAGE, root / "isolator", ignore=shutil.ignore_patterns("__pycache__"))
    solver = root / "isolator" / "solver"
    before = _folders(root, tmp_path)
    assert before["multisurface_kernel.py"].startswith(str(root / "isolator" / "__pycache__" / "numba-"))
    assert before["multisurface_kernel.py"] != before["planar_kernel.py"]
    with (solver / "multisurface_series.py").open("a") as series:  # imported by multisurface_kernel.py only
        series.write("\n# a changed dependency of a kernel\n")
    after_series = _folders(root, tmp_path)
    with (root / "isolator" / "cli" / "review.py").open("a") as cli:  # no kernel imports the CLI
        cli.write("\n# a change no kernel sees\n")
    after_cli = _folders(root, tmp_path)
    assert after_series["multisurface_kernel.py"] != before["multisurface_kernel.py"]
    assert after_series["planar_kernel.py"] == before["planar_kernel.py"]  # only what imports the change moves
    assert after_cli == after_series


def test_kernel_sources_hold_the_imported_modules():
    from isolator.solver.jit import kernel_sources

    def names(module: str) -> set:
        return {path.relative_to(PACKAGE).as_posix() for path in kernel_sources(str(PACKAGE / module))}

    assert {"solver/multisurface_kernel.py", "solver/multisurface_series.py", "solver/kernel.py",
            "solver/events.py", "solver/segments.py"} <= names("solver/multisurface_kernel.py")
    assert {"solver/planar_layout.py", "solver/planar_rk.py", "solver/planar_dop853.py"} <= names(
        "solver/planar_kernel.py")
    assert {"solver/events.py", "solver/linear.py", "solver/segments.py"} <= names("review/spectra.py")
    assert "solver/multisurface_series.py" not in names("solver/planar_kernel.py")
    assert "solver/jit.py" not in names("solver/kernel.py")


def test_every_kernel_module_decorates_through_jit():
    """A module that took numba's ``njit`` directly would be cached on its own file only (the stale kernel)."""
    direct = []
    sources = sorted(PACKAGE.rglob("*.py")) + sorted((ROOT / "tools").rglob("*.py"))
    assert any(path.name == "generate_dop853.py" for path in sources)  # tools/ is scanned too
    for path in sources:
        if path.name == "jit.py" and path.parent.name == "solver":
            continue
        text = path.read_text(encoding="utf-8")
        if re.search(r"^\s*(from numba import .*\b(njit|jit)\b|import numba\b)", text, re.MULTILINE):
            direct.append(path.relative_to(ROOT).as_posix())
    assert direct == []


@pytest.mark.parametrize("form", ["bare", "called"])
def test_njit_restores_numba_setting(form):
    """Other numba code of the process keeps its own cache setting."""
    from numba.core import config

    from isolator.solver.jit import cache_dir, njit

    before = config.CACHE_DIR

    def add(x):
        return x + 1

    kernel = njit(add) if form == "bare" else njit(cache=True)(add)
    assert kernel(1) == 2
    assert config.CACHE_DIR == before
    assert cache_dir(__file__)  # a folder for this file's functions was set while decorating


def test_numba_cache_dir_of_the_user_is_honoured(tmp_path, monkeypatch):
    """``$NUMBA_CACHE_DIR`` (numba's own setting) holds the digest folders when set; else they sit beside the
    sources."""
    from isolator.solver.jit import cache_dir

    kernel = str(PACKAGE / "solver" / "kernel.py")
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    beside = cache_dir.__wrapped__(kernel)
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "numba"))
    chosen = cache_dir.__wrapped__(kernel)
    assert Path(beside).parent == PACKAGE / "__pycache__"
    assert Path(chosen).parent == tmp_path / "numba" and Path(chosen).is_dir()
    assert Path(chosen).name == Path(beside).name  # the same digest of the same sources
