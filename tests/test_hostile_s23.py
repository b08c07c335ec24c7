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


# ---- 2. `design --vary` of a key that cannot vary says which keys can

@pytest.mark.parametrize("key, words", [
    ("bearing.surface.radius_m", "'bearing.surface.radius_m' cannot vary: the search varies a design file's top-level "
                                 "numbers, never its [bearing] keys (its [[bearing.surface]] entries)"),
    ("superstructure.floor.mass_kg", "never its [superstructure] keys: every candidate keeps the file's tables. Keys "
                                     "that can vary: radius_m, mu_kinetic"),
    ("name", "'name' is text, not a number"),
])
def test_design_vary_of_a_key_that_cannot_vary_says_which_can(key, words):
    """8e44dd2: `'bearing.surface.radius_m' is not a number of a design file that can vary (one of: …)`, the words
    of a typo, not that surface keys cannot vary."""
    line = assert_one_line_exit_2(RUNNER.invoke(app, ["design", "-d", "data/example_triple.toml", "-t", "example",
                                                      "-s", "example", "--vary", f"{key}=2,3"]))
    assert line.startswith(f"error: --vary '{key}=2,3': ") and words in line, line
    if key.startswith("bearing"):  # the keys a design given surface by surface keeps (bearing.REPLACED_DESIGN_KEYS)
        assert line.endswith("of these a design with [bearing] keeps mass_kg, damping_ratio, damping_Ns_per_m, "
                             "lambda_max, lambda_min, mu_upper, mu_lower, lambda_ae_max, lambda_ae_min, "
                             "lambda_test_max, lambda_test_min, lambda_spec_max, lambda_spec_min"), line


def test_design_vary_of_a_key_in_another_case_says_keys_are_case_sensitive():
    """783294d: `--vary RADIUS_M=2,3` was told the whole list of 21 keys (its own likeness test is case-sensitive);
    now the hint of every other unknown key (errors.key_hint): the key it meant, and that keys are case-sensitive."""
    line = assert_one_line_exit_2(RUNNER.invoke(app, ["design", "-d", "data/example_triple.toml", "-t", "example",
                                                      "-s", "example", "--vary", "RADIUS_M=2,3"]))
    assert "'RADIUS_M' is not a number of a design file that can vary (did you mean 'radius_m'? keys are " \
           "case-sensitive)" in line, line


def test_the_search_api_says_the_same_of_a_surface_key():
    """`design_space` (the Python API's ranges as pairs) said the bare `is not a number of a design file that can
    vary`, without the list: now the same words as `--vary`."""
    from isolator.errors import ReviewError
    from isolator.review.design_space import search
    from isolator.review.examples import EXAMPLES
    from isolator.review.suite import load_suite
    from isolator.review.target import two_period_target

    suite = load_suite(str(EXAMPLES["suite"]))
    with pytest.raises(ReviewError, match=r"cannot vary: .* Keys that can vary: radius_m"):
        search("data/example_triple.toml", two_period_target(0.75, 0.45, 8.0), suite,
               [("bearing.surface.radius_m", [2.0])], jobs=1)


# ---- 3. batch: resume files damaged by hand, a records folder with a link loop

def _parts_with_one_row(tmp_path):
    from isolator.batch.store import PartStore

    store = PartStore(tmp_path / "T.csv")
    store.write([{"record": "a.AT2", "row_key": "k1"}])
    store.write([{"record": "b.AT2", "row_key": "k2"}])
    return store, sorted(store.directory.glob("part-*.jsonl"))


def test_a_huge_part_file_is_read_in_bounded_memory(tmp_path):
    """8e44dd2 read each part whole (`read_bytes`, then split): a 1 GB part of NULs held 3.3 GB resident and took
    32 s (the sweep, `batch` resuming); now line by line, a line over 1 MiB ends the part (damage, recomputed)."""
    import tracemalloc

    store, parts = _parts_with_one_row(tmp_path)
    with open(parts[0], "ab") as stream:
        stream.truncate(256 << 20)  # sparse: no disk, 256 MiB of NULs after the row
    tracemalloc.start()
    rows = store.rows({"k1", "k2"})
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    assert [row["row_key"] for row in rows] == ["k1", "k2"] and store.damaged == 1  # the whole line before is kept
    assert peak < 16 << 20, peak  # 8e44dd2: > 256 MiB


@pytest.mark.parametrize("damage", ["empty", "fifo", "folder"])
def test_a_part_file_emptied_or_replaced_is_counted_as_damage(tmp_path, damage):
    """8e44dd2 read an emptied part, a FIFO or a folder in its place as no rows, without the note `damaged
    line(s) … skipped`: its rows were recomputed silently (a part holds at least one row: empty is truncated)."""
    import os

    store, parts = _parts_with_one_row(tmp_path)
    parts[0].unlink()
    {"empty": lambda p: p.write_bytes(b""), "fifo": os.mkfifo, "folder": os.mkdir}[damage](parts[0])
    assert [row["row_key"] for row in store.rows({"k1", "k2"})] == ["k2"]
    assert store.damaged == 1


def test_a_records_folder_with_a_link_loop_lists_the_loop_as_a_record(tmp_path):
    """8e44dd2: `batch recs` with `recs/loop1 -> loop2 -> loop1` stopped the whole batch: `error: recs/loop1: cannot
    write (Too many levels of symbolic links)` (ELOOP from `DirEntry.is_dir`, taken for an output's error). Now the
    loop is a record whose row says `symbolic-link loop`, and the batch runs the others."""
    import os

    from isolator.motion.files import expand_records

    recs = tmp_path / "recs"
    (recs / "sub").mkdir(parents=True)
    (recs / "sub" / "a.AT2").write_text(SINE)
    os.symlink("loop1", recs / "loop2")
    os.symlink("loop2", recs / "loop1")
    found = expand_records([str(recs)])
    assert [os.path.relpath(p, recs) for p in found] == ["loop1", "loop2", "sub/a.AT2"]
    from isolator.io._common import input_file_problem

    assert input_file_problem(recs / "loop1") == "symbolic-link loop"


# ---- 4. TOML files: a key in another case is named as the key meant

@pytest.mark.parametrize("text, words", [
    (DESIGN + "MASS_KG = 2e6\n", "t.toml: unknown key 'MASS_KG' (did you mean 'mass_kg'? keys are case-sensitive)"),
    (DESIGN.replace("radius_m", "Radius_M"), "t.toml: unknown key 'Radius_M' (did you mean 'radius_m'? keys are "
                                             "case-sensitive)"),
    (DESIGN + "[Superstructure]\n", "unknown key 'Superstructure' (did you mean 'superstructure'? keys are "
                                    "case-sensitive)"),
])
def test_a_design_key_in_another_case_is_named(tmp_path, monkeypatch, text, words):
    """8e44dd2: `MASS_KG` was told the list of 24 valid keys (the likeness of difflib is case-sensitive), `Mass_kg`
    `did you mean 'mass_kg'?` without why."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "x.AT2").write_text(SINE)
    (tmp_path / "t.toml").write_text(text)
    line = assert_one_line_exit_2(RUNNER.invoke(app, ["simulate", "x.AT2", "--design", "t.toml"]))
    assert line.endswith(words), line


def test_a_target_and_a_suite_key_in_another_case_are_named(tmp_path):
    """8e44dd2: a target's `s_m1` and a pair's `Scale_Factor` were told the valid keys, not the one meant."""
    from isolator.errors import SuiteError, TargetError
    from isolator.review.suite_specs import specs_from_toml
    from isolator.review.target import load_target

    (tmp_path / "t.toml").write_text("s_ms = 1.0\nS_M1 = 0.6\nT_L = 8\n")
    with pytest.raises(TargetError, match=r"unknown key 's_ms' \(did you mean 'S_MS'\? keys are case-sensitive\)$"):
        load_target(tmp_path / "t.toml")
    (tmp_path / "s.toml").write_text('[[pair]]\nname = "a"\nx = "x.AT2"\ny = "y.AT2"\nScale_Factor = 2\n')
    with pytest.raises(SuiteError, match=r"pair 1: unknown key 'Scale_Factor' \(did you mean 'scale_factor'\? keys"):
        specs_from_toml(tmp_path / "s.toml")


# ---- 5. bench: its five files are one set; no openseespy is said in one line

def _stub_bench(monkeypatch, plot):
    """`bench` with no cases (its tables of nothing): the CLI's own work, in well under a second."""
    import isolator.bench as bench_module

    monkeypatch.setattr(bench_module, "bench_cases", lambda quick, records: [])
    monkeypatch.setattr(bench_module, "run_bench", lambda **kwargs: ([], []))
    monkeypatch.setattr(bench_module, "building_cases", lambda quick, records: [])
    monkeypatch.setattr(bench_module, "tfp_cases", lambda quick, records: [])
    monkeypatch.setattr(bench_module, "plot", plot)


def test_bench_writes_its_five_files_as_one_set(tmp_path, monkeypatch):
    """8e44dd2 renamed bench.csv, bench_pareto.csv, bench.json, bench.md one after the other, then drew the plot:
    an interrupt while drawing left four new files beside an old bench.png (a mixture of two benches)."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "recs").mkdir()
    out = tmp_path / "out"
    out.mkdir()
    for name in ("bench.csv", "bench_pareto.csv", "bench.json", "bench.md", "bench.png"):
        (out / name).write_text("old")

    def interrupted(rows, path):
        raise KeyboardInterrupt

    _stub_bench(monkeypatch, interrupted)
    result = RUNNER.invoke(app, ["bench", "--quick", "--out", "out", "--records", "recs"])
    assert result.exit_code == 130, result.output
    assert {p.name: p.read_text() for p in out.iterdir()} == dict.fromkeys(
        ("bench.csv", "bench_pareto.csv", "bench.json", "bench.md", "bench.png"), "old")

    _stub_bench(monkeypatch, lambda rows, path: path.write_bytes(b"\x89PNG new"))
    result = RUNNER.invoke(app, ["bench", "--quick", "--out", "out", "--records", "recs"])
    assert result.exit_code == 0, result.output
    assert all(p.read_bytes() != b"old" for p in out.iterdir()) and len(list(out.iterdir())) == 5


def test_bench_without_openseespy_says_so_in_one_line(tmp_path, monkeypatch):
    """8e44dd2 said nothing of a missing openseespy until the 2-D summary at the end, and its progress lines said
    `…: ours and OpenSees, 3 rounds in alternation` of runs where OpenSees did not run."""
    import isolator.bench.opensees as opensees
    from isolator.bench.harness import time_ours_and_opensees

    monkeypatch.chdir(tmp_path)
    (tmp_path / "recs").mkdir()
    monkeypatch.setattr(opensees, "opensees_available", lambda: (False, "openseespy not installed"))
    _stub_bench(monkeypatch, lambda rows, path: path.write_bytes(b"png"))
    result = RUNNER.invoke(app, ["bench", "--quick", "--out", "out", "--records", "recs"])
    assert result.exit_code == 0, result.output
    notes = [line for line in result.stderr.splitlines() if "openseespy" in line]
    assert notes == ['note: openseespy not installed: the OpenSees baselines are left out, ours is timed alone '
                     '(pip install "isolator[bench]" for them)'], result.stderr

    class Case:
        name = "TFP x"

    said = []
    out = time_ours_and_opensees(lambda case, setting: "ours", None, Case(), rounds=2, ours_per_round=3,
                                 progress=said.append)
    assert said == ["TFP x: ours alone (openseespy not installed), 6 runs"]
    assert out[1] == "ours" and out[2] == 6 and out[3:] == (None, None, None, "openseespy not installed")


# ---- 6. a text record written with decimal commas says so

@pytest.mark.parametrize("text, words", [
    ("# dt_s: 0,01\n0,0123\n-0,0456\n0,0789\n", "time column does not increase at data row 2 (t = 0 s then -0 s); "
                                                 "decimal commas? (0,0123 is read as two numbers, 0 and 123: write "
                                                 "the numbers with a decimal point, 0.0123)"),
    ("t;acc\n0,00;0,0123\n0,01;-0,0456\n0,02;0,0789\n", "3 columns; expected 1 (acceleration, with a time step) or 2 "
                                                        "(time, acceleration); decimal commas?"),
    ("# dt_s: 0,01\n0.1\n0.2\n0.3\n", "'# dt_s: 0,01' is not a number (a decimal comma? write the step with a "
                                      "decimal point)"),
])
def test_a_text_record_with_decimal_commas_says_so(tmp_path, text, words):
    """8e44dd2: a comma locale's export (`0,0123`) was read with the comma as the separator and refused in other
    words (`time column does not increase`, `3 columns`), and `# dt_s: 0,01` in float()'s (`could not convert
    string to float: '0,01'`). No locale with decimal commas is installed here (`locale -a`: C, C.utf8, POSIX): the
    commands read numbers in the C locale whatever LC_ALL says."""
    from isolator.io import text as reader

    (tmp_path / "t.txt").write_text(text)
    with pytest.raises(RecordFormatError) as caught:
        reader._read_text(tmp_path / "t.txt")
    assert str(caught.value).endswith(words) or words in str(caught.value), str(caught.value)


def test_a_record_with_decimal_points_and_commas_as_separators_reads_as_before(tmp_path):
    from isolator.io import text as reader

    (tmp_path / "t.txt").write_text("time,acc\n0,1\n0.01,2\n0.02,-1\n")  # a CSV of whole numbers: no hint, read
    assert reader._read_text(tmp_path / "t.txt")[0].data.tolist() == [1.0, 2.0, -1.0]


# ---- 7. review: a pair that is not a pair names the suite and the files

def test_a_pair_of_different_time_steps_names_the_suite_and_its_files(tmp_path, monkeypatch):
    """8e44dd2: `error: pair 'a': components have different time steps (x 0.01 s, y 0.02 s); resample them first`
    named neither the suite file nor the records (a pair's other refusals, `--scaling given`'s since session 21,
    name the suite)."""
    from isolator.errors import SuiteError
    from isolator.review.suite import load_suite

    monkeypatch.chdir(tmp_path)
    (tmp_path / "x.AT2").write_text(SINE)
    (tmp_path / "y2.AT2").write_text(at2_text([0.1 * math.cos(0.08 * i) for i in range(200)], dt=".0200"))
    (tmp_path / "y3.AT2").write_text(at2_text([0.1 * math.cos(0.08 * i) for i in range(300)]))
    for y, words in (("y2.AT2", "suite s.toml: pair 'a': components have different time steps (x 0.01 s in x.AT2, y "
                                "0.02 s in y2.AT2): the components of a pair are recorded together; resample them "
                                "first"),
                     ("y3.AT2", "suite s.toml: pair 'a': components differ in length (x 200, y 300 samples)")):
        (tmp_path / "s.toml").write_text(f'[[pair]]\nname = "a"\nx = "x.AT2"\ny = "{y}"\n')
        with pytest.raises(SuiteError) as caught:
            load_suite("s.toml")
        assert str(caught.value).startswith(words), str(caught.value)


# ---- 8. an output named `.pdf`

@pytest.mark.parametrize("command", [["report", "x.AT2", "-d", "d.toml"],
                                     ["review", "-d", "d.toml", "-t", "example", "-s", "example"],
                                     ["design", "-d", "d.toml", "-t", "example", "-s", "example", "--vary",
                                      "radius_m=2,3"]])
def test_an_output_named_dot_pdf_is_told_it_names_no_file(tmp_path, monkeypatch, command):
    """8e44dd2: `-o .pdf` said `--output must end with .pdf, got .pdf` (to Python `.pdf` is a hidden file with no
    suffix), in each of the three commands' copies of the check."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "x.AT2").write_text(SINE)
    (tmp_path / "d.toml").write_text(DESIGN)
    line = assert_one_line_exit_2(RUNNER.invoke(app, [*command, "-o", "sub/.PDF"]))
    assert line == "error: --output sub/.PDF names no file: give a name before .pdf (e.g. review.pdf)"


def test_bench_records_given_a_file_says_it_is_a_file(tmp_path, monkeypatch):
    """8e44dd2: `bench --records x.AT2` said `x.AT2: no such folder of records` of a file that exists."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "x.AT2").write_text(SINE)
    line = assert_one_line_exit_2(RUNNER.invoke(app, ["bench", "--quick", "--records", "x.AT2"]))
    assert line == ("error: x.AT2: is a file, not a folder of records (give the folder of the bench records with "
                    "--records)")
    line = assert_one_line_exit_2(RUNNER.invoke(app, ["bench", "--quick", "--records", "nowhere"]))
    assert line.startswith("error: nowhere: no such folder of records")
