"""Start-up stays light: ``import isolator`` and the CLI's module load no heavy library.

The list of modules is asserted, not the time (times depend on the machine; the timing
is ``benchmarks/main_job.py``, quoted in ``docs/performance.md``).  Each check runs in a
fresh interpreter, since this test process has long imported everything.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
HEAVY = ("numpy", "scipy", "obspy", "matplotlib", "numba", "dask", "pandas", "pyarrow")


def _loaded_after(statement: str) -> list[str]:
    code = (f"import sys\n{statement}\n"
            f"print(' '.join(sorted({{m.split('.')[0] for m in sys.modules}} & set({HEAVY!r}))))")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])}
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=120)
    assert done.returncode == 0, done.stderr
    return done.stdout.split()


@pytest.mark.parametrize("statement", ["import isolator", "import isolator.cli"])
def test_no_heavy_library_at_import(statement):
    assert _loaded_after(statement) == []


def test_the_lazy_api_still_resolves():
    """The names of ``isolator.__all__`` load on first use (here one that needs numba)."""
    loaded = _loaded_after("import isolator; isolator.simulate_record")
    assert "numba" in loaded and "numpy" in loaded  # the check above is not vacuous


def test_the_report_loads_only_what_it_uses(tmp_path):
    """The main job imports neither pandas, dask, pyarrow, pyplot nor scipy's integrate/ndimage.

    (numba itself imports scipy.linalg, for BLAS, on its first compiled call.)
    """
    data = ROOT / "data" / "example_pendulum.toml"
    statement = ("import contextlib, io\nfrom isolator.cli import app\n"
                 "with contextlib.redirect_stdout(io.StringIO()):\n"
                 f"    app(['report', '--design', {str(data)!r}, 'example:knet', '--scale-to-pga', '0.3', "
                 f"'-o', {str(tmp_path / 'r.pdf')!r}, '--map-resolution', '8'], standalone_mode=False)\n"
                 "import sys\nprint(' '.join(sorted(m for m in sys.modules if m.startswith(("
                 "'scipy.integrate', 'scipy.ndimage', 'matplotlib.pyplot', 'pandas', 'dask', 'pyarrow')))))")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]),
           "ISOLATOR_CACHE_DIR": str(tmp_path / "cache")}
    done = subprocess.run([sys.executable, "-c", statement], capture_output=True, text=True, env=env, timeout=300)
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "r.pdf").is_file()  # the report was written: the list is not vacuous
    assert done.stdout.split() == []
