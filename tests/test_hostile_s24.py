"""Session 24's hostile sweep (h222): inputs no earlier sweep had tried — special files given to `review --verify`,
an empty bearing layout, two outputs on one standard output, a paper frame with its range flags, numba's thread
count in the environment (docs/security.md, "Session 24 sweep").
"""

from __future__ import annotations

import math
import os
import threading

from _records import assert_one_line_exit_2, at2_text
from typer.testing import CliRunner

from isolator.cli import app

RUNNER = CliRunner()
SINE = at2_text([0.1 * math.sin(2 * math.pi * i * 0.01) for i in range(200)])
BUILDING = """name = "B"
mass_kg = 2e6
radius_m = 2.5
mu_static = 0.06
[superstructure]
damping_ratio = 0.05
[[superstructure.floor]]
mass_kg = 1e6
story_height_m = 3.5
stiffness_x_N_per_m = 1e9
"""


# ---- 1. `review --verify` reads a regular file, up to a bound

def test_review_verify_of_a_file_past_the_bound_is_refused_unread(tmp_path):
    """783294d read the file whole (`read_text`): /dev/zero until the memory ran out (15 GB in 4 min, by hand), a
    65 MiB file of NULs into memory, then `Expecting value: line 1 column 1`; now the size is checked first."""
    big = tmp_path / "big.json"
    with open(big, "wb") as stream:
        stream.truncate(64 * 2**20 + 1)  # `isolator.review.verify.MAX_REVIEW_JSON_BYTES` + 1; sparse: no disk used
    line = assert_one_line_exit_2(RUNNER.invoke(app, ["review", "--verify", str(big)]))
    assert line == f"error: {big}: cannot read the review JSON ([Errno 27] longer than 67108864 bytes: '{big}')", line


def test_review_verify_of_a_fifo_is_refused_without_blocking(tmp_path):
    """783294d opened a FIFO and waited for a writer for ever (`timeout 40`: killed); now one line, unopened.
    The writer thread here lets 783294d's read end (it reads the thread's `{}`: "not a review JSON") instead of
    hanging the test."""
    fifo = tmp_path / "v.json"
    os.mkfifo(fifo)

    def writer():
        try:
            with open(fifo, "w") as stream:  # blocks until a reader opens the FIFO
                stream.write("{}")
        except BrokenPipeError:  # released below without a read: the reader closed first
            pass

    thread = threading.Thread(target=writer, daemon=True)
    thread.start()
    try:
        line = assert_one_line_exit_2(RUNNER.invoke(app, ["review", "--verify", str(fifo)]))
    finally:
        os.close(os.open(fifo, os.O_RDONLY | os.O_NONBLOCK))  # release the writer if nothing read the FIFO
        thread.join(5)
    assert line == f"error: {fifo}: cannot read the review JSON (is a FIFO (named pipe), not a regular file)", line


# ---- 2. an empty bearing layout

def test_an_empty_bearing_layout_is_one_line(tmp_path, monkeypatch):
    """783294d: `bearing_position = []` was a `ZeroDivisionError` traceback (W shared among no bearings)."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "x.AT2").write_text(SINE)
    (tmp_path / "b.toml").write_text(BUILDING.replace("[superstructure]", "bearing_position = []\n[superstructure]"))
    line = assert_one_line_exit_2(RUNNER.invoke(app, ["simulate", "x.AT2", "--design", "b.toml"]))
    assert line.startswith("error: b.toml: [[bearing_position]]: the array is empty; give at least three bearings"), line


# ---- 2b. a building's numbers beyond any building

def test_a_plan_length_longer_than_the_plan_and_an_r_off_the_table_are_refused(tmp_path, monkeypatch):
    """783294d read `eccentricity_m = 1e300` and `y_m = 500` on a 34 x 26 m plan, and `response_modification_R` of
    1e300 or 0.5 (R_I then clamped to 2 or 1 without a word): each ran (exit 0)."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "x.AT2").write_text(SINE)
    plan = "[plan]\nb_m = 34.0\nd_m = 26.0\n"
    cases = {
        plan + "eccentricity_m = 1e300\n": "key 'plan.eccentricity_m' = 1e+300 m is longer than the plan's diagonal "
                                            "(42.8 m, b_m = 34, d_m = 26): the centres of mass and rigidity both lie "
                                            "within the plan",
        plan + "y_m = 500.0\n": "key 'plan.y_m' = 500 m is longer than the plan's diagonal (42.8 m",
        "": "key 'response_modification_R' must lie in [1, 8], ASCE 7-22 Table 12.2-1's R of a system, got 0.5",
    }
    for extra, words in cases.items():
        text = BUILDING.replace("damping_ratio = 0.05", "damping_ratio = 0.05\nresponse_modification_R = "
                                + ("0.5" if not extra else "4.0"))
        (tmp_path / "b.toml").write_text(extra + text if not extra else text.replace("[superstructure]",
                                                                                     extra + "[superstructure]"))
        line = assert_one_line_exit_2(RUNNER.invoke(app, ["simulate", "x.AT2", "--design", "b.toml"]))
        assert line.startswith("error: b.toml: ") and words in line, line


# ---- 2c. a review's target and suite files

def test_a_target_number_out_of_range_names_its_file_once(tmp_path):
    """783294d: `t.toml: t.toml: key 'S_MS' = 150 is outside …` (the two-period form's `try` named the file again)."""
    target = tmp_path / "t.toml"
    target.write_text("S_MS = 150.0\nS_M1 = 0.9\nT_L = 8.0\n")
    line = assert_one_line_exit_2(RUNNER.invoke(app, ["review", "-d", "data/example_design.toml", "-t", str(target),
                                                      "-s", "example", "-o", str(tmp_path / "r.pdf")]))
    assert line == (f"error: {target}: key 'S_MS' = 150 is outside [0.0001, 10], a spectral acceleration [g]"), line


def test_a_suite_pair_with_an_empty_file_name_or_too_many_pairs_is_refused(tmp_path, monkeypatch):
    """783294d: `x = ""` read the suite's folder (`a: .: is a directory, not a record file`), and 100,000 pairs were
    each read and hashed before any other check (43.8 s); 1,001 pairs here."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "x.AT2").write_text(SINE)
    (tmp_path / "y.AT2").write_text(SINE.replace("1.0000000E-01", "2.0000000E-01"))
    review = ["review", "-d", "d.toml", "-t", "example", "-s", "s.toml", "-o", "r.pdf"]
    (tmp_path / "d.toml").write_text('name = "FPS"\nmass_kg = 1e6\nradius_m = 2.5\nmu_static = 0.06\n')
    (tmp_path / "s.toml").write_text('[[pair]]\nname = "a"\nx = {file = ""}\ny = "y.AT2"\n')
    line = assert_one_line_exit_2(RUNNER.invoke(app, review))
    assert line == "error: s.toml: pair 1 x: the file name is empty", line
    (tmp_path / "s.toml").write_text("".join(f'[[pair]]\nname = "p{i}"\nx = "x.AT2"\ny = "y.AT2"\n'
                                             for i in range(1001)))
    line = assert_one_line_exit_2(RUNNER.invoke(app, review))
    assert line.startswith("error: s.toml: 1,001 [[pair]] tables, more than a suite holds (1,000: "), line


# ---- 2d. a batch grid of one value repeated

def test_a_batch_grid_of_one_value_repeated_is_refused(tmp_path, monkeypatch):
    """783294d: `batch --grid radius_m=2:2:3` ran three identical rows named `FPS [radius_m=2]` (exit 0, 9.6 s by
    hand); `design --vary radius_m=2:2:3` refuses it."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "x.AT2").write_text(SINE)
    (tmp_path / "ds.toml").write_text('[[design]]\nname = "FPS"\nmass_kg = 1e6\nradius_m = 2.5\nmu_static = 0.06\n')
    line = assert_one_line_exit_2(RUNNER.invoke(app, ["batch", "x.AT2", "-d", "ds.toml", "-o", "t.csv", "--grid",
                                                      "radius_m=2:2:3", "-j", "1", "--no-harmonic"]))
    assert line == ("error: grid 'radius_m=2:2:3': START = STOP with COUNT > 1 gives the same value twice; "
                    "check --grid"), line
    assert not (tmp_path / "t.csv").exists()


# ---- 2e. a table written with one bracket where an array of tables is read

def test_a_one_bracket_table_where_double_brackets_are_read_says_so(tmp_path, monkeypatch):
    """783294d: `[design]` said `expected a list of designs ([[design]] tables), found none`, `[pair]` `no [[pair]]
    tables` and `[superstructure.floor]` `needs at least one [[superstructure.floor]] entry`: none said why."""
    (tmp_path / "data").mkdir()
    (tmp_path / "data" / "example_design.toml").write_text('name = "FPS"\nmass_kg = 1e6\nradius_m = 2.5\n'
                                                            'mu_static = 0.06\n')
    monkeypatch.chdir(tmp_path)
    (tmp_path / "x.AT2").write_text(SINE)
    (tmp_path / "ds.toml").write_text('[design]\nname = "FPS"\nmass_kg = 1e6\nradius_m = 2.5\nmu_static = 0.06\n')
    (tmp_path / "s.toml").write_text('[pair]\nname = "a"\nx = "x.AT2"\ny = "x.AT2"\n')
    (tmp_path / "b.toml").write_text(BUILDING.replace("[[superstructure.floor]]", "[superstructure.floor]"))
    for args, words in (
            (["batch", "x.AT2", "-d", "ds.toml", "-o", "t.csv"], "error: ds.toml: 'design' is one table ([design]); "
                                                                  "write each design as [[design]], double brackets"),
            (["review", "-d", "data/example_design.toml", "-t", "example", "-s", "s.toml", "-o", "r.pdf"],
             "error: s.toml: 'pair' is one table ([pair]); write each pair as [[pair]], double brackets"),
            (["simulate", "x.AT2", "--design", "b.toml"],
             "error: b.toml: [superstructure]: 'floor' is one table ([superstructure.floor]); write each floor as "
             "[[superstructure.floor]], double brackets, bottom to top")):
        assert assert_one_line_exit_2(RUNNER.invoke(app, args)) == words


# ---- 2f. record flags given with a SUITE.toml

def test_units_and_trim_given_with_a_suite_file_are_refused(tmp_path):
    """783294d: `review -s SUITE.toml --units g` (or `--trim`, and `design`'s) dropped the flag without a word (the
    SUITE.toml states its own) and ran the review (exit 0, 22 s by hand)."""
    for command in (["review"], ["design", "--vary", "radius_m=2,3"]):
        line = assert_one_line_exit_2(RUNNER.invoke(app, [*command, "-d", "data/example_design.toml", "-t", "example",
                                                          "-s", "example", "-o", str(tmp_path / "r.pdf"), "--trim"]))
        assert line.startswith("error: --trim serves record files and folders given to --suite, not a SUITE.toml"), line
    line = assert_one_line_exit_2(RUNNER.invoke(app, ["review", "-d", "data/example_design.toml", "-t", "example",
                                                      "-s", "example", "-o", str(tmp_path / "r.pdf"), "-u", "g",
                                                      "--trim"]))
    assert line.startswith("error: --units and --trim serve record files"), line


# ---- 2g. a batch table named by its suffix alone

def test_a_batch_table_named_by_its_suffix_alone_is_told_so(tmp_path, monkeypatch):
    """783294d: `batch -o .csv` said `.csv: the table must end with .csv or .parquet` (session 23 fixed `-o .pdf`)."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "x.AT2").write_text(SINE)
    (tmp_path / "ds.toml").write_text('[[design]]\nname = "FPS"\nmass_kg = 1e6\nradius_m = 2.5\nmu_static = 0.06\n')
    for name in (".csv", ".parquet"):
        line = assert_one_line_exit_2(RUNNER.invoke(app, ["batch", "x.AT2", "-d", "ds.toml", "-o", name]))
        assert line == f"error: {name}: names no file: give a name before {name} (e.g. table{name}); check --output"


# ---- 3. two answers on one standard output

def test_json_and_a_csv_on_standard_output_are_refused(tmp_path, monkeypatch):
    """783294d: `simulate --json --out-csv -` wrote the CSV and dropped the JSON asked for (exit 0)."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "x.AT2").write_text(SINE)
    line = assert_one_line_exit_2(RUNNER.invoke(app, ["simulate", "x.AT2", "--mu-s", "0.05", "--json",
                                                      "--out-csv", "-"]))
    assert line == "error: --json and --out-csv - both write to standard output: give one (or the CSV a file)", line


# ---- 4. a paper frame and the range flags it sets

def test_a_paper_frame_with_its_range_flags_is_refused():
    """783294d: `regime-map --frame fig5a --k-max 3` drew k in [0, 6] (the frame's), the 3 dropped without a word."""
    line = assert_one_line_exit_2(RUNNER.invoke(app, ["regime-map", "--frame", "fig6", "--k-max", "3", "-n", "4",
                                                      "--no-cache"]))
    assert line == "error: --frame fig6 sets k in [0, 5] and α in [0, 10]: drop --k-max (or --frame)", line
    line = assert_one_line_exit_2(RUNNER.invoke(app, ["regime-map", "--frame", "fig5a", "--alpha-max", "6",
                                                      "--k-max", "6", "-n", "4", "--no-cache"]))
    assert line.endswith("drop --k-max and --alpha-max (or --frame)"), line


# ---- 5. numba's thread count in the environment

def test_a_numba_thread_count_below_one_or_not_a_number_is_one_line(tmp_path, monkeypatch):
    """783294d: NUMBA_NUM_THREADS=0 or -1 was a 61-line traceback (`ValueError: Number of threads specified must be
    > 0`, numba's import) from `simulate`; `abc` was dropped for every core without a word. In this process numba
    is imported already, so 783294d ran the command (exit 0)."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "x.AT2").write_text(SINE)
    for value in ("0", "-1", "abc"):
        monkeypatch.setenv("NUMBA_NUM_THREADS", value)
        line = assert_one_line_exit_2(RUNNER.invoke(app, ["info", "x.AT2"]))
        assert line.startswith(f"error: NUMBA_NUM_THREADS={value} is not a whole number of threads ≥ 1"), line
    monkeypatch.setenv("NUMBA_NUM_THREADS", "")  # empty is unset, as numba reads it
    assert RUNNER.invoke(app, ["info", "x.AT2"]).exit_code == 0
