"""Usage mistakes are one line naming the flag, with the command's --help hint; exit 2; no warning."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest
from typer.testing import CliRunner

from isolator.cli import app

RUNNER = CliRunner()


@pytest.mark.parametrize("args, words", [
    (["simulate", "r.AT2", "--mu-s", "0.1", "--bogus"], ["No such option: --bogus", "'isolator simulate --help'"]),
    (["simulate", "r.AT2"], ["Missing option '--mu-s'", "'isolator simulate --help'"]),
    (["simulate", "--mu-s", "0.1"], ["Missing argument", "'isolator simulate --help'"]),
    (["batch", "r.AT2", "-d", "d.toml", "-o", "t.csv", "--jobs", "0"], ["'--jobs'", "'isolator batch --help'"]),
    (["info", "r.AT2", "--dt", "abc"], ["'--dt'", "valid number", "'isolator info --help'"]),
    (["regime-map", "--resolution", "2"], ["'--resolution'", "'isolator regime-map --help'"]),
    (["threshold", "--mu-s", "0.2", "--grid", "2"], ["'--grid'", "'isolator threshold --help'"]),
    (["no-such-command"], ["No such command 'no-such-command'", "'isolator --help'"]),
])
def test_usage_error_is_one_line(args, words):
    result = RUNNER.invoke(app, args)
    assert result.exit_code == 2
    assert result.stdout == ""
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), result.stderr
    assert "╭" not in result.stderr and "Traceback" not in result.stderr
    for word in words:
        assert word in lines[0]


def test_help_still_works():
    result = RUNNER.invoke(app, ["simulate", "--help"])
    assert result.exit_code == 0 and "--mu-s" in result.stdout


def test_python_warnings_never_reach_stderr():
    # library code that warns (numpy's RuntimeWarning, matplotlib's glyph UserWarning) under
    # PYTHONWARNINGS=always: the command prints its result and nothing on stderr.  In a
    # subprocess, because pytest records warnings itself.
    script = (
        "import sys, warnings\n"
        "import isolator.solver.harmonic as h\n"
        "solve = h.harmonic_response\n"
        "def noisy(*a, **k):\n"
        "    warnings.warn('divide by zero encountered', RuntimeWarning)\n"
        "    warnings.warn('Glyph 8320 missing from font', UserWarning)\n"
        "    return solve(*a, **k)\n"
        "h.harmonic_response = noisy\n"
        "if sys.argv[1] == 'control':\n"
        "    noisy(2.0, 0.0, 0.0, 0.25)\n"
        "else:\n"
        "    from isolator.cli import app\n"
        "    app(['harmonic', '--alpha', '2', '--mu-s', '0.25', '--json'])\n")
    env = {**os.environ, "PYTHONWARNINGS": "always", "PYTHONPATH": os.pathsep.join(sys.path)}
    control = subprocess.run([sys.executable, "-c", script, "control"], capture_output=True, text=True, env=env,
                             timeout=120)
    assert "RuntimeWarning" in control.stderr and "UserWarning" in control.stderr  # the setup warns
    run = subprocess.run([sys.executable, "-c", script, "cli"], capture_output=True, text=True, env=env, timeout=120)
    assert run.returncode == 0 and run.stderr == "", run.stderr
    assert json.loads(run.stdout)["regime"] in ("ST", "SS", "SL")
