"""A hostile sweep (session 16): what session 15's sweep left (a batch that skipped a FIFO and a linked folder
without a word, a regime map computed before finding it could not be written, a cache entry that could not be
replaced, an inventory without a size bound, overlapping segments merged by a guess, a triple whose backbone had
a regime without a name) and what the new sweep found (docs/security.md, "Session 16 sweep").
Each case failed on main before its fix (a silent skip, lost work, a silent guess, a state without a name); the
mirror case of a triple documents why µ1 > µ4 is accepted.
"""

from __future__ import annotations

import math
import os

import numpy as np
import pytest
from _records import assert_one_line_exit_2, at2_text
from typer.testing import CliRunner

from isolator.cli import app

RUNNER = CliRunner()

#: 200 samples of a 1 Hz sine of 0.1 g at 0.01 s [g].
SINE_G = [0.1 * math.sin(2 * math.pi * i * 0.01) for i in range(200)]


# ---- 1. a records folder: a FIFO, a dangling link and a linked folder are never skipped unsaid

def _records_folder(tmp_path):
    records, other = tmp_path / "records", tmp_path / "other"
    records.mkdir()
    other.mkdir()
    (records / "a.AT2").write_text(at2_text(SINE_G))
    (other / "c.AT2").write_text(at2_text(SINE_G))
    os.mkfifo(records / "f.AT2")
    (records / "dangling.AT2").symlink_to("nowhere")
    (records / "linked").symlink_to(other)
    (other / "back").symlink_to(records)  # a way back: each folder is walked once
    return records


def test_a_records_folder_lists_fifos_dangling_links_and_linked_folders(tmp_path):
    """main: rglob left out the FIFO, the dangling link and the linked folder's records without a word (2 rows
    where the folder holds 4 entries)."""
    from isolator.motion.files import expand_records

    records = _records_folder(tmp_path)
    names = [os.path.relpath(path, records) for path in expand_records([str(records)])]
    assert names == ["a.AT2", "dangling.AT2", "f.AT2", os.path.join("linked", "c.AT2")]


def test_a_link_to_a_folder_holding_the_records_folder_is_refused(tmp_path):
    """A link up the tree would list the whole tree above: one line naming the link."""
    from isolator.errors import BatchError
    from isolator.motion.files import expand_records

    records = _records_folder(tmp_path)
    (records / "up").symlink_to(tmp_path)
    with pytest.raises(BatchError, match=r"records/up: links to .*, a folder holding it \(a loop\)"):
        expand_records([str(records)])


def test_a_batch_gives_a_fifo_and_a_dangling_link_their_rows(tmp_path):
    """main: "records: folder holds no record files", exit 2 (the two entries were skipped unsaid).  Now each is
    a row whose error says what it is; nothing is read from the FIFO (it would block)."""
    records = tmp_path / "records"
    records.mkdir()
    os.mkfifo(records / "f.AT2")
    (records / "d.AT2").symlink_to("nowhere")
    designs = tmp_path / "designs.toml"
    designs.write_text('[[design]]\nname = "FPS"\nmass_kg = 1e6\nradius_m = 2.5\nmu_static = 0.06\n')
    table = tmp_path / "t.csv"
    result = RUNNER.invoke(app, ["batch", str(records), "-d", str(designs), "-o", str(table), "-j", "1"])
    assert result.exit_code == 1, result.output
    import pandas as pd

    errors = sorted(pd.read_csv(table)["error"])
    assert errors[0].endswith("d.AT2: dangling symbolic link (to nowhere)"), errors
    assert errors[1].endswith("f.AT2: is a FIFO (named pipe), not a regular file"), errors


# ---- 2. regime-map -o into a folder that cannot be written: one line before the map is computed

def test_a_regime_map_figure_that_cannot_be_written_is_refused_before_the_map(tmp_path, monkeypatch):
    """main: `regime-map -o /proc/x.png` computed (and cached) the map, ~10 s at -n 100, before the write failed."""
    monkeypatch.setenv("ISOLATOR_CACHE_DIR", str(tmp_path))
    result = RUNNER.invoke(app, ["regime-map", "-n", "8", "-o", "/proc/x.png"])
    assert_one_line_exit_2(result, "/proc/x.png: cannot write")
    assert not (tmp_path / "maps").exists() or not list((tmp_path / "maps").iterdir())  # nothing was computed


# ---- 3. a regime-map cache entry that cannot be replaced is said

def test_a_regime_map_cache_entry_that_cannot_be_replaced_is_said(tmp_path, monkeypatch):
    """main: a FIFO in a cached map's place was recomputed, the new map's save failed without a word, and every
    run computed the map again."""
    monkeypatch.setenv("ISOLATOR_CACHE_DIR", str(tmp_path))
    assert RUNNER.invoke(app, ["regime-map", "-n", "4"]).exit_code == 0
    (entry,) = (tmp_path / "maps").iterdir()
    entry.unlink()
    os.mkfifo(entry)
    result = RUNNER.invoke(app, ["regime-map", "-n", "4"])
    assert result.exit_code == 0, result.output
    assert "the map could not be cached" in result.output and "the next run computes it again" in result.output


# ---- 4. the --response inventory has a size bound

def test_an_enormous_response_inventory_is_refused_from_its_size(tmp_path):
    """main: read whole by obspy (100 MB of zero bytes: 16.6 s and 267 MB to "Unknown format").  A sparse file."""
    import obspy

    from isolator.motion.read import MAX_INVENTORY_BYTES

    record = tmp_path / "rjob.mseed"
    obspy.read().select(channel="EHZ").write(str(record), format="MSEED")  # obspy's example, in counts
    inventory = tmp_path / "big.xml"
    with open(inventory, "wb") as handle:
        handle.truncate(MAX_INVENTORY_BYTES + 2**20)
    assert_one_line_exit_2(RUNNER.invoke(app, ["info", str(record), "--response", str(inventory)]),
                           f"{inventory}: is 65.0 MiB", "isolator reads inventories up to 64 MiB")


# ---- 5. --merge: overlapping segments that differ are refused, identical ones merge

def _two_segments(path, second, start_s):
    from obspy import Stream, Trace, UTCDateTime

    header = {"network": "XX", "station": "STA", "channel": "HNE", "delta": 0.01}
    first = np.sin(np.arange(300) * 0.1)
    Stream([Trace(first[:200].copy(), header={**header, "starttime": UTCDateTime(0)}),
            Trace(second, header={**header, "starttime": UTCDateTime(start_s)})]).write(str(path), format="MSEED")
    return first


@pytest.mark.parametrize("case", ["different samples", "of a step apart"])
def test_merging_overlapping_segments_that_differ_is_refused(tmp_path, case):
    """main: obspy's method 1 kept the later segment's samples where the two overlap (a guess), exit 0."""
    path = tmp_path / "overlap.mseed"
    later = np.sin(np.arange(300) * 0.1)[150:].copy()
    if case == "different samples":
        later[10] += 0.5
    _two_segments(path, later, 1.5 if case == "different samples" else 1.505)
    line = assert_one_line_exit_2(RUNNER.invoke(app, ["info", str(path), "--units", "m/s2", "--merge"]),
                                  f"{path}: channel XX.STA..HNE: two segments overlap from 1970-01-01T00:00:01.5",
                                  "to 1970-01-01T00:00:01.990000Z")
    assert case in line


def test_merging_identical_overlapping_segments_keeps_every_sample(tmp_path):
    path = tmp_path / "same.mseed"
    first = _two_segments(path, np.sin(np.arange(300) * 0.1)[150:].copy(), 1.5)
    from isolator.motion import read_ground_motion

    motion = read_ground_motion(path, units="m/s2", merge=True)
    np.testing.assert_array_equal(motion.acceleration_m_s2, first)


# ---- 6. a triple pendulum: the outer surface of lower friction must reach regime III

def _triple(R=(2.1, 0.3, 0.3, 2.1), mu=(0.06, 0.02, 0.02, 0.10), d=(0.4, 0.05, 0.05, 0.4)):
    return {"type": "triple", "surface": [{"radius_m": r, "mu": m, "displacement_capacity_m": c}
                                          for r, m, c in zip(R, mu, d, strict=True)]}


def _parse(table):
    from isolator.bearing import parse_bearing
    from isolator.errors import DesignError

    return parse_bearing(table, DesignError)


@pytest.mark.parametrize("mu, d, surface, need", [((0.06, 0.02, 0.02, 0.10), (0.05, 0.05, 0.05, 0.4), 1, 0.084),
                                                  ((0.10, 0.02, 0.02, 0.06), (0.4, 0.05, 0.05, 0.05), 4, 0.084)])
def test_an_outer_surface_on_its_rim_before_regime_three_is_refused(tmp_path, mu, d, surface, need):
    """main: read; its backbone held a state no regime of Fenz & Constantinou names (one outer slider on its rim,
    no outer surface sliding: named "") and `simulate` listed the regimes entered as I, II, IV, V, then III."""
    from isolator.errors import DesignError

    with pytest.raises(DesignError, match=rf"bearing surface {surface}: effective capacity d\*_{surface} = 0.05 m "
                                          rf"is too small to reach regime III: it must be >= .* = {need:g} m"):
        _parse(_triple(mu=mu, d=d))


def test_the_outer_rule_is_exactly_the_backbone_having_a_name_for_every_regime():
    """Random triples the other rules read: refused by the new rule if and only if their backbone (the series
    model's monotonic loading) holds a regime without a name, and the names then run I..V in order."""
    from isolator.errors import DesignError

    rng = np.random.default_rng(16)
    refused = named = 0
    for _ in range(300):
        R = (rng.uniform(1, 4), rng.uniform(0.1, 0.9), rng.uniform(0.1, 0.9), rng.uniform(1, 4))
        mu = (rng.uniform(0.03, 0.15), rng.uniform(0.01, 0.03), rng.uniform(0.01, 0.03), rng.uniform(0.03, 0.15))
        d = tuple(rng.uniform(0.002, 0.6, 4))
        f, o = (0, 3) if mu[0] <= mu[3] else (3, 0)
        outer_ok = d[f] >= (mu[o] - mu[f]) * R[f]
        try:
            names = _parse(_triple(R, mu, d)).backbone().regimes
        except DesignError as err:
            if "regime III" in str(err):
                refused += 1
                assert not outer_ok
            continue
        named += 1
        assert outer_ok and "" not in names, (R, mu, d, names)
        order = ["I", "II", "III", "IV", "V"]  # a state of one inner slider alone is its regime's "(one inner)"
        counts = [order.index(name.removesuffix(" (one inner)")) for name in names]
        assert counts == sorted(counts) and len(set(names)) == len(names), names
    assert refused > 10 and named > 10


def test_a_triple_upside_down_is_the_same_bearing(tmp_path):
    """Why µ1 > µ4 is accepted: the bearing with its surfaces in reverse order (µ1 > µ4, the larger capacities on
    top) has the same backbone and regime names, and under a record the same response to the last digit."""
    import json

    R, mu, d = (2.1, 0.3, 0.25, 2.6), (0.06, 0.02, 0.03, 0.10), (0.4, 0.05, 0.07, 0.5)
    up = _parse(_triple(R, mu, d))
    down = _parse(_triple(R[::-1], mu[::-1], d[::-1]))
    assert down.backbone().regimes == up.backbone().regimes == ("I (one inner)", "I", "II", "III", "IV", "V",
                                                                     "V (one inner)")
    np.testing.assert_array_equal(down.backbone().force_per_weight, up.backbone().force_per_weight)
    record = tmp_path / "x.AT2"
    record.write_text(at2_text([0.4 * math.sin(2 * math.pi * 0.7 * i * 0.01) for i in range(300)]))
    answers = []
    for name, order in (("up", slice(None)), ("down", slice(None, None, -1))):
        design = tmp_path / f"{name}.toml"
        design.write_text(f'name = "{name}"\nmass_kg = 1.0e5\n[bearing]\ntype = "triple"\n' + "".join(
            f"[[bearing.surface]]\nradius_m = {r}\nmu = {m}\ndisplacement_capacity_m = {c}\n"
            for r, m, c in zip(R[order], mu[order], d[order], strict=True)))
        result = RUNNER.invoke(app, ["simulate", str(record), "--design", str(design), "--json"])
        assert result.exit_code == 0, result.output
        answers.append(json.loads(result.output[result.output.index("{"):]))
    for key in ("peak_displacement_m", "residual_displacement_m", "energy_friction_J_per_kg", "regimes"):
        assert answers[0][key] == answers[1][key], key
    assert answers[0]["surface_peak_displacement_m"] == answers[1]["surface_peak_displacement_m"][::-1]


# ---- the new sweep: a count without a bound, a name that drives the terminal, a layout without a bound

def test_a_bench_of_a_billion_repeats_is_refused_before_any_run(tmp_path):
    """main: `bench --repeats 1000000000` ran on without end (past `timeout 25`, the harmonic cases' first
    timings printed)."""
    import subprocess
    import sys

    command = os.path.join(os.path.dirname(sys.executable), "isolator")
    done = subprocess.run([command, "bench", "--quick", "--repeats", "1000000000", "--records", str(tmp_path),
                           "--out", str(tmp_path / "out")], capture_output=True, text=True, timeout=60)
    lines = [line for line in done.stderr.splitlines() if line.strip()]
    assert done.returncode == 2 and len(lines) == 1, done.stderr
    assert "--repeats" in lines[0] and "20" in lines[0]
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("name, shown", [("nope\x1b]0;title\x07.AT2", "nope\\x1b]0;title\\x07.AT2"),
                                         ("nope\u202egpj.AT2", "nope\\u202egpj.AT2")])
def test_a_file_name_cannot_drive_the_terminal(tmp_path, name, shown):
    """main: the error line printed the name's ESC sequence raw (an OSC that sets the terminal's title; click
    strips only colour codes, and only off a terminal), and a right-to-left override showed the name reversed."""
    path = tmp_path / name
    line = assert_one_line_exit_2(RUNNER.invoke(app, ["info", str(path)]), f"{shown}: no such file")
    assert line.isprintable()


def test_a_record_name_in_a_table_cannot_drive_the_terminal(tmp_path):
    path = tmp_path / "e\x1b[2Jx.AT2"
    path.write_text(at2_text(SINE_G))
    result = RUNNER.invoke(app, ["info", str(path)])
    assert result.exit_code == 0, result.output
    assert "\x1b" not in result.output and "e\\x1b[2Jx.AT2" in result.output


def test_a_layout_of_more_bearings_than_any_building_is_refused_at_reading(tmp_path):
    """main: read (30,000 bearings in 40 s: each place compared with every other; 100,000 ran past 120 s)."""
    from _model_designs import BUILDING

    from isolator.design import Design
    from isolator.errors import DesignError
    from isolator.superstructure import MAX_BEARINGS

    head = BUILDING[:BUILDING.index("[[bearing_position]]")]
    n = MAX_BEARINGS + 1
    design = tmp_path / "many.toml"
    design.write_text(head + "".join(f"[[bearing_position]]\nx_m = {10 * math.cos(2 * math.pi * i / n):.12f}\n"
                                     f"y_m = {10 * math.sin(2 * math.pi * i / n):.12f}\n" for i in range(n)))
    with pytest.raises(DesignError, match=rf"many.toml: \[\[bearing_position\]\]: {n} entries, more than 10,000"):
        Design.from_toml(design)
    design.write_text(head + "[[bearing_position]]\nx_m = 1\ny_m = 1\n" * 2)
    with pytest.raises(DesignError, match="bearing_position 2: at the same place as bearing_position 1"):
        Design.from_toml(design)


def test_a_time_history_file_that_cannot_be_written_is_refused_before_the_analysis(tmp_path):
    """main: `simulate --out-csv /proc/x.csv` ran the analysis (a building: 13 s with its compile) before the write
    failed.  Now its lock is made first, as report's and regime-map's; a stream (`-`) still works."""
    record = tmp_path / "x.AT2"
    record.write_text(at2_text(SINE_G))
    result = RUNNER.invoke(app, ["simulate", str(record), "--mu-s", "0.05", "--out-csv", "/proc/x.csv"])
    assert_one_line_exit_2(result, "/proc/x.csv: cannot write (its lock /proc/x.csv.lock")
    assert "peak" not in result.output  # no analysis ran: its table is not printed
    streamed = RUNNER.invoke(app, ["simulate", str(record), "--mu-s", "0.05", "--out-csv", "-"])
    assert streamed.exit_code == 0 and streamed.output.startswith("time_s,"), streamed.output


def test_matplotlib_logs_nothing_on_stderr_for_a_config_folder_it_cannot_write(tmp_path):
    """main: MPLCONFIGDIR=/proc/x printed matplotlib's "mkdir -p failed …" and "Matplotlib created a temporary
    cache directory …" (its logger, not a Python warning) before a figure written correctly."""
    import subprocess
    import sys

    command = os.path.join(os.path.dirname(sys.executable), "isolator")
    done = subprocess.run([command, "regime-map", "-n", "4", "-o", str(tmp_path / "m.png")], capture_output=True,
                          text=True, timeout=120, env={**os.environ, "MPLCONFIGDIR": "/proc/x",
                                                       "ISOLATOR_CACHE_DIR": str(tmp_path)})
    assert done.returncode == 0 and done.stderr == "", done.stderr
    assert (tmp_path / "m.png").stat().st_size > 1000


def test_a_record_of_more_segments_than_any_accelerogram_is_refused_before_its_gaps(tmp_path):
    """main: obspy's get_gaps compares every pair of segments: a 1 MB MiniSEED of 2,000 three-sample segments took
    42 s to "1999 gap(s)/overlap(s) … not merged", 20,000 segments (10 MB) ran past 120 s."""
    from obspy import Stream, Trace, UTCDateTime

    from isolator.motion.read import MAX_SEGMENTS

    header = {"network": "XX", "station": "STA", "channel": "HNE", "delta": 0.01}
    path = tmp_path / "segments.mseed"
    Stream([Trace(np.full(3, 1.0 + i % 7), header={**header, "starttime": UTCDateTime(0) + i * 0.05})
            for i in range(MAX_SEGMENTS + 1)]).write(str(path), format="MSEED", reclen=512)
    assert_one_line_exit_2(RUNNER.invoke(app, ["info", str(path), "--units", "m/s2", "--merge"]),
                           f"{path}: holds {MAX_SEGMENTS + 1} segments, more than any accelerogram",
                           f"up to {MAX_SEGMENTS} segments")
