"""Session 21's hostile sweep (h203): the inputs no sweep had covered — `isolator design`'s ranges, `simulate
--design` of multi-surface bearings and building layouts, a SUITE.toml's scale factors and matched records, odd
files (empty, binary, sparse, folders, FIFOs, names with pattern characters) — and session 20's leftovers
(docs/security.md, "Session 21 sweep").
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from _records import assert_one_line_exit_2, at2_text
from typer.testing import CliRunner

from isolator.cli import app
from isolator.design import Design
from isolator.errors import DesignError

RUNNER = CliRunner()
DESIGN = 'name = "FPS"\nmass_kg = 1e6\nradius_m = 2.5\nmu_static = 0.06\n'
SINE = at2_text([0.1 * math.sin(2 * math.pi * i * 0.01) for i in range(200)])


# ---- a design's description is bounded, and the bound said

def test_a_description_beyond_its_bound_is_refused_with_the_bound(tmp_path, monkeypatch):
    """edf7ccb read a description of 10^6 characters (carried by every candidate of a search, every batch row)."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "x.AT2").write_text(SINE)
    (tmp_path / "d.toml").write_text(DESIGN + 'description = "' + "x" * 10**6 + '"\n')
    DESCRIPTION_MAX_CHARS = 10_000  # noqa: N806 - isolator.design's, written out (the base has none)
    line = assert_one_line_exit_2(RUNNER.invoke(app, ["simulate", "x.AT2", "--design", "d.toml"]))
    assert line == ("error: d.toml: key 'description' is 1,000,000 characters long, more than a design's description "
                    "may be (10,000): it is free text, shortened to 40 characters in reports; keep longer notes in a "
                    "file of their own")
    base = {"name": "FPS", "mass_kg": 1e6, "radius_m": 2.5, "mu_static": 0.06}
    assert len(Design.from_mapping({**base, "description": "d" * DESCRIPTION_MAX_CHARS}).description) == 10_000
    with pytest.raises(DesignError, match="10,001 characters long"):
        Design.from_mapping({**base, "description": "d" * (DESCRIPTION_MAX_CHARS + 1)})


def test_a_batch_design_with_a_long_description_is_a_row_error(tmp_path, monkeypatch):
    """A designs file's design is validated per row (a batch survives one bad design): the long one fails its row
    with the bound, the other design runs."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "x.AT2").write_text(SINE)
    (tmp_path / "ds.toml").write_text("[[design]]\n" + DESIGN + 'description = "' + "x" * 20_000 + '"\n'
                                      "[[design]]\n" + DESIGN.replace('"FPS"', '"FPS 2"'))
    result = RUNNER.invoke(app, ["batch", "x.AT2", "-d", "ds.toml", "-o", "o.csv"])
    assert result.exit_code == 1 and result.exception is None or isinstance(result.exception, SystemExit)
    assert result.stdout.strip().splitlines()[-1] == "2 rows, 1 failed"
    import pandas as pd

    errors = pd.read_csv(tmp_path / "o.csv", keep_default_na=False)["error"].tolist()
    assert errors[0].endswith("key 'description' is 20,000 characters long, more than a design's description may be "
                              "(10,000): it is free text, shortened to 40 characters in reports; keep longer notes in "
                              "a file of their own") and errors[1] == ""


def test_designs_sharing_a_name_are_noted(tmp_path, monkeypatch):
    """edf7ccb: two [[design]] tables named 'a' gave two rows named 'a' (told apart only by design_index), silently."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "x.AT2").write_text(SINE)
    table = DESIGN.replace('"FPS"', '"a"')
    (tmp_path / "ds.toml").write_text("[[design]]\n" + table + "[[design]]\n" + table.replace("2.5", "3.5")
                                      + "[[design]]\n" + table.replace('"a"', '"b"') + "[[design]]\n"
                                      + table.replace('"a"', '" A "'))
    result = RUNNER.invoke(app, ["batch", "x.AT2", "-d", "ds.toml", "-o", "o.csv", "--grid", "mu_static=0.05:0.06:2"])
    assert result.exit_code == 0, result.stderr
    assert result.stderr.strip().splitlines() == [
        "note: ds.toml: [[design]] tables 1, 2 and 4 share the name 'a [mu_static=0.05]': their rows are told apart "
        "only by design_index (give each design its own name)"]
    assert result.stdout.strip().splitlines()[-1] == "8 rows, 0 failed"


# ---- a text record's step beyond a float is named as the file gives it, not "dt = 0 s"

@pytest.mark.parametrize("text, words", [
    ("# dt_s: 5e-324\n0.1\n0.2\n0.3\n", "t.txt: plain text: '# dt_s: 5e-324' of 4.94e-324 s underflows: below a float's smallest "
                                        "normal number (2.2e-308); no accelerogram has such a step"),
    ("# dt: 1e400\n0.1\n0.2\n0.3\n", "t.txt: plain text: '# dt: 1e400' overflows: beyond any number (a float ends at 1.8e308 s)"),
    ("time,acc\n0,0.1\n5e-324,0.2\n1e-323,0.3\n", "t.txt: plain text: the time column's step of 4.94e-324 s underflows"),
])
def test_a_text_record_step_beyond_a_float_is_named(tmp_path, monkeypatch, text, words):
    """edf7ccb: each said `time step dt = 0 s is not positive` (ObsPy keeps 1/dt: inf, then a step of 0)."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "t.txt").write_text(text)
    line = assert_one_line_exit_2(RUNNER.invoke(app, ["simulate", "t.txt", "--mu-s", "0.05", "--units", "g"]))
    assert line.startswith("error: " + words), line
    assert "dt = 0 s" not in line


def test_a_text_record_normal_steps_read_as_before(tmp_path):
    from isolator.io import text

    (tmp_path / "b.txt").write_text("time,acc\n0,0.1\n0.01,0.2\n0.02,0.3\n")
    assert text._read_text(tmp_path / "b.txt")[0].stats.delta == 0.01
    (tmp_path / "c.txt").write_text("# dt_s: 0.005\n0.1\n0.2\n")
    assert text._read_text(tmp_path / "c.txt")[0].stats.delta == 0.005


# ---- the AT2 reader reads its DT text once on the error paths

def test_the_at2_dt_text_is_read_once(tmp_path, monkeypatch):
    """edf7ccb computed `_dt_text` twice on the underflow path (test and message; and a third time on overflow's
    test-free path, the brief's count): once now, the message unchanged."""
    import isolator.io.at2 as at2
    from isolator.errors import RecordFormatError

    calls = []
    original = at2._dt_text
    monkeypatch.setattr(at2, "_dt_text", lambda line: calls.append(line) or original(line))
    for dt, words in (("1e-320", "header DT=1e-320 s underflows"), ("1e400", "header DT=1e400 s overflows")):
        calls.clear()
        (tmp_path / "x.AT2").write_text(at2_text([0.1, 0.2], dt=dt))
        with pytest.raises(RecordFormatError, match=words):
            at2._read_at2(tmp_path / "x.AT2")
        assert len(calls) == 1, dt
    calls.clear()
    (tmp_path / "x.AT2").write_text(at2_text([0.1, 0.2]))
    assert at2._read_at2(tmp_path / "x.AT2")[0].stats.delta == 0.01 and calls == []  # a normal DT: not at all


# ---- `design --jobs` is capped at the cores as review's and batch's are

def test_design_jobs_beyond_the_cores_are_capped_with_a_note(tmp_path, monkeypatch):
    """edf7ccb took `design --jobs 100000000` as it was: one forked process per candidate (up to 20,000, each
    ~300 MB); `review` and `batch` capped theirs at the cores with a note."""
    from isolator.parallel import available_cores

    monkeypatch.chdir(tmp_path)
    (tmp_path / "d.toml").write_text(DESIGN)
    result = RUNNER.invoke(app, ["design", "--isolator", "d.toml", "--target", "example", "--suite", "example",
                                 "--vary", "radius_m=", "--jobs", "100000000"])
    assert result.exit_code == 2
    lines = result.stderr.strip().splitlines()
    assert lines[0] == (f"note: 100000000 workers asked, {available_cores()} used (this machine gives this process "
                        f"{available_cores()} cores)")
    assert lines[1:] == ["error: --vary 'radius_m=': the list must hold numbers separated by commas"]


# ---- `--scaling given` with a pair without its factor names the suite

def test_scaling_given_without_every_factor_names_the_suite(tmp_path):
    """edf7ccb: `error: scaling 'given' needs a scale_factor for every pair; pair 'Landers 1992 YER' has none (and 6
    more)`, no file named."""
    import shutil

    from isolator.review.examples import resolve_example

    suite_dir = tmp_path / "s"
    shutil.copytree(Path(resolve_example("suite", "example")).parent, suite_dir)
    text = (suite_dir / "suite.toml").read_text()
    (suite_dir / "suite.toml").write_text(text.replace("trim = true", "trim = true\nscale_factor = 1.5", 1))
    (tmp_path / "d.toml").write_text(DESIGN + "displacement_capacity_m = 1.0\nlambda_max = 1.2\nlambda_min = 0.9\n")
    result = RUNNER.invoke(app, ["review", "--design", str(tmp_path / "d.toml"), "--target", "example", "--suite",
                                 str(suite_dir / "suite.toml"), "--scaling", "given", "-o", str(tmp_path / "r.pdf")])
    line = assert_one_line_exit_2(result)
    assert line.startswith(f"error: suite {suite_dir / 'suite.toml'}: scaling 'given' needs a scale_factor for every "
                           "pair; pair ") and line.endswith("has none (and 6 more)"), line
    assert not (tmp_path / "r.pdf").exists()


# ---- a binary or non-UTF-8 TOML file says so in its own terms

@pytest.mark.parametrize("content, words", [
    (bytes(range(256)) * 4, "d.toml: not UTF-8 text (line 2: byte 0x80): a binary file, or text saved in another "
                            "encoding (save it as UTF-8; TOML is UTF-8)"),
    (DESIGN.encode() + b"# \xb5 = 0.06 (cp1252)\n", "d.toml: not UTF-8 text (line 5: byte 0xb5)"),
    (b" \n\n", "d.toml: the design file is empty"),
])
def test_a_toml_file_that_is_not_utf8_is_named_so(tmp_path, monkeypatch, content, words):
    """edf7ccb: `d.toml: cannot read the design file ('utf-8' codec can't decode byte 0x80 in position 128: invalid
    start byte)`: Python's words, and no line."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "x.AT2").write_text(SINE)
    (tmp_path / "d.toml").write_bytes(content)
    line = assert_one_line_exit_2(RUNNER.invoke(app, ["simulate", "x.AT2", "--design", "d.toml"]))
    assert line.startswith("error: " + words), line
