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
