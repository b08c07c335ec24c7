"""The CLI spares the interpreter its final garbage collection (gc.freeze at exit), once, only at exit."""

from __future__ import annotations

import gc
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_freeze_runs_at_exit_once_not_before():
    code = """
import atexit, gc, sys
atexit.register(lambda: print("frozen at exit:", gc.get_freeze_count() > 0))  # runs after the freeze (LIFO)
from isolator.cli.common import skip_final_collection
skip_final_collection(); skip_final_collection()
print("frozen before exit:", gc.get_freeze_count() > 0)
print("callbacks:", __import__("atexit")._ncallbacks())
"""
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])}
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=60)
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert lines[0] == "frozen before exit: False"  # a long-lived process keeps collecting until it ends
    assert lines[1] == "callbacks: 2"  # the checker and one freeze, however often main() runs
    assert lines[2] == "frozen at exit: True"


def test_cli_runner_process_is_not_frozen():
    from typer.testing import CliRunner

    from isolator.cli import app

    result = CliRunner().invoke(app, ["harmonic", "--alpha", "1.2", "--k", "0", "--eta", "0", "--mu-s", "0.25"])
    assert result.exit_code == 0, result.output
    assert gc.get_freeze_count() == 0  # tests calling the CLI many times keep their garbage collected


def test_objects_are_frozen_only_inside_the_block():
    from isolator.cli.common import collector_skips_existing_objects

    before = gc.get_freeze_count()
    assert before == 0
    with collector_skips_existing_objects():
        assert gc.get_freeze_count() > 0
        garbage = []
        garbage.append(garbage)  # a cycle made inside the block is still collectable
        del garbage
        assert gc.collect() >= 1
    assert gc.get_freeze_count() == 0
