"""Session 23's hostile sweep (h213): session 22's leftovers (one wording of a step beyond a float, a text record's
``# dt_s: 1e-400``, the keys `design --vary` takes) and the inputs no sweep had covered — `bench`'s flags,
`report`'s outputs, `batch`'s resume files and record folders, `review`'s pairs, the environment, TOML files'
duplicate tables, marks, line ends and key case (docs/security.md, "Session 23 sweep").
"""

from __future__ import annotations

import math

import pytest
from _records import assert_one_line_exit_2, at2_text
from typer.testing import CliRunner

from isolator.cli import app
from isolator.errors import RecordFormatError

RUNNER = CliRunner()
DESIGN = 'name = "FPS"\nmass_kg = 1e6\nradius_m = 2.5\nmu_static = 0.06\n'
SINE = at2_text([0.1 * math.sin(2 * math.pi * i * 0.01) for i in range(200)])


# ---- 1. one wording of a step beyond a float, every reader's

@pytest.mark.parametrize("text, words", [
    ("# dt_s: 1e-400\n0.1\n0.2\n0.3\n", "'# dt_s: 1e-400' underflows: below a float's smallest normal number "
                                        "(2.2e-308); no accelerogram has such a step (1e-05 to 0.5 s); a corrupt file?"),
    ("# dt: -1D-999\n0.1\n0.2\n0.3\n", "'# dt: -1D-999' underflows: below a float's smallest normal number"),
])
def test_a_text_step_written_nonzero_and_read_as_zero_underflows(tmp_path, monkeypatch, text, words):
    """8e44dd2: `# dt_s: 1e-400` (float: 0.0) said `time step dt = 0 s is not positive`, where 5e-324 said it
    underflows."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "t.txt").write_text(text)
    line = assert_one_line_exit_2(RUNNER.invoke(app, ["simulate", "t.txt", "--mu-s", "0.05", "--units", "g"]))
    assert line.startswith("error: t.txt: plain text: " + words), line


def test_a_text_step_written_as_zero_is_not_positive(tmp_path):
    """`# dt_s: 0.0e-400` is a zero as written: it stays `not positive`, not an underflow."""
    from isolator.io import text

    (tmp_path / "z.txt").write_text("# dt_s: 0.0e-400\n0.1\n0.2\n")
    with pytest.raises(RecordFormatError, match="time step dt = 0 s is not positive"):
        text._read_text(tmp_path / "z.txt")


def test_at2_and_text_say_a_step_beyond_a_float_in_one_wording(tmp_path):
    """Both readers call `isolator.io._common.refuse_step_beyond_float` (8e44dd2 had two copies of the words):
    the same tail after the step's name, for overflow and underflow."""
    from isolator.io import at2, text

    tails = {}
    for dt in ("1e400", "1e-320", "1e-400"):
        (tmp_path / "x.AT2").write_text(at2_text([0.1, 0.2], dt=dt))
        (tmp_path / "x.txt").write_text(f"# dt_s: {dt}\n0.1\n0.2\n")
        with pytest.raises(RecordFormatError) as from_at2:
            at2._read_at2(tmp_path / "x.AT2")
        with pytest.raises(RecordFormatError) as from_text:
            text._read_text(tmp_path / "x.txt")
        a = str(from_at2.value).split("flows: ", 1)[1].replace("corrupt header?", "corrupt file?")
        b = str(from_text.value).split("flows: ", 1)[1]
        assert a == b, dt
        tails[dt] = b
    assert tails["1e-320"] == tails["1e-400"] != tails["1e400"]
