"""The README's Python example runs and prints what the README says it prints.

The block under "## Python API" is executed as written, from the repository root, in a
fresh interpreter; each top-level ``# …`` comment line of the block is the expected output
of the ``print`` before it.  The README's ci blocks are checked by ``.ci/run`` itself.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _python_api_block() -> str:
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    section = readme.split("## Python API", 1)[1]
    match = re.search(r"```python\n(.*?)```", section, flags=re.S)
    assert match, "README.md: no python block under '## Python API'"
    return match.group(1)


def test_readme_python_example_runs_and_prints_what_it_says(tmp_path):
    code = _python_api_block()
    expected = [line[2:] for line in code.splitlines() if line.startswith("# ")]
    assert len(expected) >= 2  # the example states its results
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]),
           "ISOLATOR_CACHE_DIR": str(tmp_path / "cache")}
    done = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, env=env,
                          timeout=300)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == expected


def test_ci_blocks_are_present_and_single_commands():
    """``.ci/run`` reads these two blocks; each must hold one shell command line."""
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    for name in ("ci:setup", "ci:test"):
        block = re.search(rf"<!-- {name} -->\n```\n(.*?)\n```\n<!-- /{name} -->", readme, flags=re.S)
        assert block, f"README.md lacks the {name} block"
        assert len(block.group(1).strip().splitlines()) == 1
