"""A hostile sweep (session 19): session 18's leftovers (`design` interrupted while it writes its outputs left a
mixture of two runs; `batch x.AT2 x.AT2` ran one row without a word; 17.5.4.3(3)'s factor printed as 1.5 whatever it
was set to) and what the sweep of sessions 17-18's additions found (docs/security.md, "Session 19 sweep").
"""

from __future__ import annotations

import math
import os
import signal

import pytest
from _records import at2_text
from typer.testing import CliRunner

from isolator.cli import app

RUNNER = CliRunner()
DESIGN = 'name = "FPS"\nmass_kg = 1e6\nradius_m = 2.5\nmu_static = 0.06\n'
#: A 1 Hz sine of 0.1 g at 0.01 s, 2 s, as a PEER AT2 file.
SINE = at2_text([0.1 * math.sin(2 * math.pi * i * 0.01) for i in range(200)])


def _record(folder, name="x.AT2"):
    (folder / name).write_text(SINE)
    return folder / name


# ---- 1. design's outputs are one set: an interrupt leaves the old set or the new one

def _search(tmp_path):
    """A search of two candidates that could not be analysed: what write_outputs needs, without a review."""
    from isolator.design import Design
    from isolator.review.design_space import DesignSearch

    (tmp_path / "d.toml").write_text(DESIGN)
    design = Design.from_toml(tmp_path / "d.toml")
    rows = [{"candidate": i, "radius_m": r, "error": "no suite"} for i, r in enumerate((2.0, 3.0))]
    return DesignSearch(design=design, vary=[("radius_m", [2.0, 3.0])], objective="displacement", rows=rows,
                        code="asce7-22", scaling="common", parameters={}, target_name="t", suite_source="s",
                        mappings=[{**design.as_dict(), "radius_m": r} for r in (2.0, 3.0)])


OLD_SET = ("c.csv", "c.parquet", "c.pdf", "c.json", "c.recommended.pdf", "c.recommended.json", "c.recommended.toml")


def test_design_interrupted_while_writing_leaves_the_old_set_whole(tmp_path, monkeypatch):
    """d556246: the CSV and Parquet were renamed into place before the chart was drawn (and the chart before the JSON),
    so a Ctrl-C there left c.csv, c.parquet new and c.pdf, c.json old (docs/security.md, Session 18's standing list)."""
    import isolator.report.design_chart as chart
    from isolator.review import design_outputs

    for name in OLD_SET:
        (tmp_path / name).write_text("old run")
    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(chart, "write_design_chart", interrupted)
    with pytest.raises(KeyboardInterrupt):
        design_outputs.write_outputs(_search(tmp_path), tmp_path / "c.pdf", None, None, paper_map_resolution=0)
    assert {name: (tmp_path / name).read_bytes() for name in OLD_SET} == dict.fromkeys(OLD_SET, b"old run")
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([*OLD_SET, "d.toml"])  # no temporary left


def test_design_set_lands_whole_and_removes_the_old_recommendation(tmp_path):
    """No candidate passes: the new set lands, the earlier run's recommended review goes with the same renames."""
    from isolator.review import design_outputs

    for name in OLD_SET:
        (tmp_path / name).write_text("old run")
    out = design_outputs.write_outputs(_search(tmp_path), tmp_path / "c.pdf", None, None, paper_map_resolution=0)
    assert out["outputs"]["recommended_pdf"] is None and out["outputs"]["chart_pages"] == 2
    for name in OLD_SET[:4]:
        assert (tmp_path / name).read_bytes() != b"old run"
    assert not any((tmp_path / name).exists() for name in OLD_SET[4:])
    assert (tmp_path / "c.pdf").read_bytes().startswith(b"%PDF")


def test_a_signal_during_the_renames_waits_until_the_set_is_whole(tmp_path, monkeypatch):
    """d556246: a Ctrl-C that came between two renames of atomic_paths stopped it there (a.json new, b.json old)."""
    from isolator import atomic

    targets = [tmp_path / "a.json", tmp_path / "b.json", tmp_path / "c.json"]
    for path in targets:
        path.write_text("old")
    replace = os.replace
    calls = []

    def replace_and_interrupt(src, dst):
        replace(src, dst)
        calls.append(dst)
        if len(calls) == 1:
            os.kill(os.getpid(), signal.SIGINT)  # the handler runs at the next bytecode: here, before the second

    monkeypatch.setattr(atomic.os, "replace", replace_and_interrupt)
    # Python's own Ctrl-C handler: a process started as a background job of a script (CI's `bash .ci/run &`) starts
    # with SIGINT ignored, and an ignored signal is (rightly) left alone by interrupts_deferred
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        with pytest.raises(KeyboardInterrupt):
            with atomic.atomic_paths(targets) as temporaries:
                for temporary in temporaries:
                    temporary.write_text("new")
        assert signal.getsignal(signal.SIGINT) is signal.default_int_handler  # the handler is back
    finally:
        signal.signal(signal.SIGINT, previous)
    assert [p.read_text() for p in targets] == ["new", "new", "new"] and len(calls) == 3


# ---- 2. batch: a file given twice is said, once

def test_batch_says_a_record_given_twice(tmp_path):
    """d556246: `batch x.AT2 x.AT2 ./x.AT2` ran one row without a word.  A note, not a refusal: folders and patterns
    that overlap are a batch's usual input; a second row of the same file would be counted twice."""
    from isolator.batch.run import repeated_records_note
    from isolator.motion.files import expand_records

    x, y = _record(tmp_path), _record(tmp_path, "y.AT2")
    repeated: list = []
    files = expand_records([str(x), str(y), str(x), str(tmp_path / "." / "x.AT2"), str(tmp_path)], (), [], repeated)
    assert files == [str(x), str(y)] and repeated == [str(x), str(y)]
    assert repeated_records_note([str(x)]) == f"{x} was given more than once: it is analysed once (one row per design)"
    assert repeated_records_note(["a", "b", "c", "d"]) == ("4 record files were given more than once (a, b, c and 1 "
                                                           "more): each is analysed once")


def test_batch_prints_the_note_and_one_row(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    _record(tmp_path)
    (tmp_path / "ds.toml").write_text("[[design]]\n" + DESIGN)
    result = RUNNER.invoke(app, ["batch", "x.AT2", "x.AT2", "-d", "ds.toml", "-o", "t.csv", "--jobs", "1",
                                 "--no-harmonic"])
    assert result.exit_code == 0, result.output
    assert "note: x.AT2 was given more than once: it is analysed once (one row per design)" in result.stderr
    assert len((tmp_path / "t.csv").read_text().strip().splitlines()) == 2  # header and one row


# ---- 3. 17.5.4.3(3)'s factor: one default, and the row's words say the factor in use

def test_the_activation_row_says_the_factor_it_used():
    """d556246: `--set activation_nominal_factor=1.2` computed with 1.2 but the row still said 'max(µs upper, 1.5 µs
    nominal)' (and the multi-surface wording 'max(upper, 1.5 × nominal)')."""
    from isolator.review import parameters as P
    from isolator.review.codes import asce7_22

    elf = {b: {"T_M_s": 3.0, "beta_M": 0.2, "V_s_over_W": 0.2} for b in ("lower", "upper")}
    for multi, said in ((False, "max(µs upper, 1.2 µs nominal)"), (True, "max(upper, 1.2 × nominal) of the backbone")):
        params = P.resolve("asce7-22", {"activation_nominal_factor": 1.2})
        row = next(r for r in asce7_22.requirement_rows(elf, params, mu_static_lower=0.04, mu_static_upper=0.07,
                                                        mu_static_nominal=0.06, multisurface=multi)
                   if r["id"] == "V_s_activation_limit")
        assert said in row["note"] and "1.5" not in row["note"]
        assert row["limit"] == pytest.approx(0.072 * (1.0 ** (1 - 2.5 * 0.2)), rel=1e-14)  # Ws/W = 1: V_st = V_b
    default = P.PARAMETERS["activation_nominal_factor"].default
    params = {"wind_shear_over_W": None, "Ws_over_W": 1.0, "abrupt_hysteresis": False, "drift_limit_rha": 0.02}
    row = next(r for r in asce7_22.requirement_rows(elf, params, mu_static_lower=0.04, mu_static_upper=0.07,
                                                    mu_static_nominal=0.06) if r["id"] == "V_s_activation_limit")
    assert row["limit"] == pytest.approx(default * 0.06, rel=1e-14)  # unresolved parameters: the one default


# ---- 4. what the sweep found

def test_an_empty_output_name_is_one_line(tmp_path, monkeypatch):
    """d556246: `simulate x.AT2 --mu-s 0.05 --out-csv ''` took the lock of '' (the folder '.'): an OutputError traceback,
    exit 1, after the analysis."""
    monkeypatch.chdir(tmp_path)
    _record(tmp_path)
    result = RUNNER.invoke(app, ["simulate", "x.AT2", "--mu-s", "0.05", "--out-csv", ""])
    assert result.exit_code == 2 and result.exception is None or isinstance(result.exception, SystemExit)
    assert result.stderr.strip().splitlines() == ["error: an output is named by a file path, got ''"]


def test_out_csv_dev_stdout_is_written_in_place(tmp_path, monkeypatch):
    """d556246: /dev/stdout resolved to the file standard output was redirected to, and the CSV was renamed onto it:
    `isolator simulate x.AT2 --mu-s 0.05 --out-csv /dev/stdout >> log.txt` replaced log.txt (its earlier lines lost).
    Now /dev/stdout is standard output, written in place as '-' is (here CliRunner's captured stream)."""
    monkeypatch.chdir(tmp_path)
    _record(tmp_path)
    result = RUNNER.invoke(app, ["simulate", "x.AT2", "--mu-s", "0.05", "--out-csv", "/dev/stdout"])
    assert result.exit_code == 0, result.output
    lines = result.stdout.splitlines()
    assert lines[0] == "time_s,ground_acceleration_m_s2,displacement_m,velocity_m_s,absolute_acceleration_m_s2"
    assert len(lines) == 201


def test_a_toml_integer_beyond_a_float_is_one_line(tmp_path):
    """d556246: `mass_kg = 1000…0` (401 digits) was an OverflowError traceback from float()."""
    from isolator.design import Design
    from isolator.errors import DesignError

    path = tmp_path / "d.toml"
    path.write_text(DESIGN.replace("1e6", "1" + "0" * 400) + "[[bearing_position]]\nx_m = 0\ny_m = -" + "9" * 309 + "\n")
    with pytest.raises(DesignError, match=r"d.toml: key 'mass_kg' is an integer of 401 digits, beyond any number"):
        Design.from_toml(path)
    path.write_text(DESIGN + "[[bearing_position]]\nx_m = 0\ny_m = -" + "9" * 309 + "\n")
    with pytest.raises(DesignError, match=r"key 'bearing_position.y_m' is an integer of 309 digits"):
        Design.from_toml(path)
    from isolator.design import load_toml

    path.write_text(f"a = {2**1023}\nb = -{2**1024}\n")  # the largest power of two a float holds is read as ever
    with pytest.raises(DesignError, match=r"key 'b' is an integer of 309 digits"):
        load_toml(path, "design file", DesignError)
    path.write_text(f"a = {2**1023}\n")
    assert float(load_toml(path, "design file", DesignError)["a"]) == 2.0**1023


def test_batch_refuses_an_empty_record_name_and_keys_outside_the_designs(tmp_path):
    """d556246: `batch '' -d ds.toml` ran a failing row (exit 1), and a designs file's top-level `radius_m = 3` was
    read by no design, silently."""
    from isolator.batch.plan import load_design_mappings
    from isolator.errors import BatchError
    from isolator.motion.files import expand_records

    with pytest.raises(BatchError, match="a record is named by a file path, got ''"):
        expand_records([str(_record(tmp_path)), ""])
    path = tmp_path / "ds.toml"
    path.write_text("radius_m = 3.0\n[[design]]\n" + DESIGN)
    with pytest.raises(BatchError, match=r"ds.toml: key 'radius_m' is outside the \[\[design\]\] tables"):
        load_design_mappings(path)
    path.write_text("# comments stay\n[[design]]\n" + DESIGN)
    assert load_design_mappings(path)[0]["radius_m"] == 2.5


@pytest.mark.parametrize("args, words", [
    (["--out", "", "--quick"], "--out '': a folder is named by a path"),
    (["--records", "", "--quick"], "--records '': a folder is named by a path"),
    (["--out", "-", "--quick"], "--out is a folder for five files, not standard output; print the rows with --json"),
])
def test_bench_folders_named_empty_or_dash_are_refused(tmp_path, monkeypatch, args, words):
    """d556246: `bench --records ''` benched the working folder's records and `--out -` made a folder named '-'."""
    monkeypatch.chdir(tmp_path)
    result = RUNNER.invoke(app, ["bench", *args])
    assert result.exit_code == 2 and words in result.stderr and len(result.stderr.strip().splitlines()) == 1
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("rtol", ["x", "1e-10", float("nan"), float("inf"), -1.0, 0.0, True, [1e-10]])
def test_a_scene_rtol_that_is_no_tolerance_is_refused_by_every_model(rtol):
    """d556246: the exact 1-D model (one component) ignored the scene's `rtol` whatever it held ("x", NaN, -1 ran
    without a word); the 2-D engines refused them in their own words and read the text "1e-10" as a number."""
    import numpy as np

    from isolator.errors import InvalidSystemError
    from isolator.solver.models import simulate_motion

    ax = np.sin(np.linspace(0.0, 6.0, 50))
    with pytest.raises(InvalidSystemError, match=r"rtol must be a finite number > 0 \(a relative tolerance"):
        simulate_motion(ax, dt_s=0.01, mu_static=0.05, mu_kinetic=0.05, radius_m=2.5, rtol=rtol)


def test_a_toml_file_with_a_byte_order_mark_is_read(tmp_path):
    """d556246: a design file saved as Notepad's "UTF-8 with BOM" was `not valid TOML (Invalid statement (at line 1,
    column 1))`; the mark is the encoding's, as for CSV records (session 15)."""
    from isolator.design import Design

    path = tmp_path / "d.toml"
    path.write_text(DESIGN, encoding="utf-8-sig")
    assert path.read_bytes()[:3] == b"\xef\xbb\xbf" and Design.from_toml(path).radius_m == 2.5


@pytest.mark.parametrize("flag", ["--target", "--suite", "--design"])
def test_review_says_an_empty_file_name_is_empty_not_missing(flag):
    """d556246: `review --target ''` said `missing option --target`."""
    args = {"--design": "d.toml", "--target": "example", "--suite": "example", flag: ""}
    result = RUNNER.invoke(app, ["review", *[x for kv in args.items() for x in kv], "-o", "r.pdf"])
    assert result.exit_code == 2 and result.stderr.strip().splitlines()[-1].startswith(f"error: {flag} '': a file is "
                                                                                       "named by a path")
