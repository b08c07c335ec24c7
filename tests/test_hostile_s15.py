"""A hostile sweep (session 15): record files with odd encodings, units stated twice, enormous files, segments
that cannot be merged; a design reader that let an engine's bound through; a design search that wrote over a
suite record; a per-user key file that blocked or filled the memory (docs/security.md, "Session 15 sweep").
Each case failed on main before its fix: a silent units guess, a traceback, a hang, or an input overwritten.

Every refusal comes before any analysis, so each case costs a read of a short synthetic record.
"""

from __future__ import annotations

import math
import os
import resource
import subprocess
import sys

import numpy as np
import pytest
from _records import assert_one_line_exit_2, at2_text
from typer.testing import CliRunner

from isolator.cli import app

RUNNER = CliRunner()

#: 300 samples of a 1 Hz sine of 0.1 g at 0.01 s [g]: its PGA is 0.1 g to 1e-15.
SINE_G = [0.1 * math.sin(2 * math.pi * i * 0.01) for i in range(300)]


def _csv(rows_header: str, values=SINE_G) -> str:
    return rows_header + "".join(f"{i * 0.01:.2f},{v:.9f}\n" for i, v in enumerate(values))


def _pga_g(result) -> float:
    """The PGA [g] of ``isolator info``'s table ("PGA  0.980665 m/s²  (0.1000 g)")."""
    line = next(line for line in result.output.splitlines() if line.startswith("PGA"))
    return float(line.split()[1]) / 9.80665


# ---- a UTF-8 byte-order mark (a spreadsheet's CSV) hid the '# units:' line

def test_a_byte_order_mark_does_not_hide_the_units_line(tmp_path):
    """main: the BOM glued to '# units: g' made it a row of column names; `--units m/s2` was then taken for the
    units of a file in g (PGA 0.0102 g instead of 0.1 g, exit 0), and without --units the file had "no units"."""
    path = tmp_path / "bom.csv"
    path.write_text(_csv("# units: g\n"), encoding="utf-8-sig")
    assert path.read_bytes()[:3] == b"\xef\xbb\xbf"
    result = RUNNER.invoke(app, ["info", str(path)])
    assert result.exit_code == 0, result.output
    assert _pga_g(result) == pytest.approx(0.1, rel=1e-6)
    assert_one_line_exit_2(RUNNER.invoke(app, ["info", str(path), "--units", "m/s2"]),
                           f"{path}: the file states g", "the units given are m/s2")


def test_a_byte_order_mark_before_column_names_is_read(tmp_path):
    """main: "non-numeric value 'time' … at row 0" (the BOM made the comment a header, and the header data)."""
    path = tmp_path / "bom_named.csv"
    path.write_text(_csv("# units: g\ntime,acc\n"), encoding="utf-8-sig")
    result = RUNNER.invoke(app, ["info", str(path)])
    assert result.exit_code == 0, result.output
    assert _pga_g(result) == pytest.approx(0.1, rel=1e-6)


# ---- a column named in an acceleration unit states the units, as a '# units:' line does

@pytest.mark.parametrize("column, unit", [("acc_cm/s2", "cm/s2"), ("a [gal]", "gal"), ("acc (m/s2)", "m/s2")])
def test_a_column_in_other_units_than_the_units_line_is_refused(tmp_path, column, unit):
    """main: '# units: g' over a column 'acc (cm/s2)' was read as g without a word (a factor of 980 unsettled)."""
    path = tmp_path / "two_units.csv"
    path.write_text(_csv(f"# units: g\ntime,{column}\n"))
    assert_one_line_exit_2(RUNNER.invoke(app, ["info", str(path)]), f"{path}: plain text: ",
                           f"'# units: g' but names its acceleration column '{column}' (in {unit})")


def test_a_column_named_in_g_states_g(tmp_path):
    """main: a column 'acc_g' was no statement: `--units cm/s2` read the g values as cm/s² (PGA 1e-4 g, exit 0)."""
    path = tmp_path / "named.csv"
    path.write_text(_csv("time,acc_g\n"))
    result = RUNNER.invoke(app, ["info", str(path)])
    assert result.exit_code == 0, result.output
    assert "column 'acc_g'" in result.output and _pga_g(result) == pytest.approx(0.1, rel=1e-6)
    assert_one_line_exit_2(RUNNER.invoke(app, ["info", str(path), "--units", "cm/s2"]),
                           f"{path}: the file states g", "the units given are cm/s2")
    same = tmp_path / "same.csv"  # the same units twice are one statement
    same.write_text(_csv("# units: G\ntime,acc_g\n"))
    assert RUNNER.invoke(app, ["info", str(same)]).exit_code == 0


# ---- an enormous file is refused from its size, before a reader opens it

def test_an_enormous_record_file_is_refused_from_its_size(tmp_path):
    """main: 100 MB of zero bytes read 39 s (262 MB) before "unrecognised binary format"; 8 GB ran past 60 s and
    2.9 GB of memory.  A sparse file: no disk is used."""
    from isolator.motion.read import MAX_RECORD_BYTES

    path = tmp_path / "big.dat"
    with open(path, "wb") as handle:
        handle.truncate(MAX_RECORD_BYTES + 1)
    assert_one_line_exit_2(RUNNER.invoke(app, ["info", str(path)]), f"{path}: is 64.0 MiB, larger than any "
                           "accelerogram", "up to 64 MiB")


# ---- --merge of one channel's segments at two sampling rates

def test_merging_segments_of_two_sampling_rates_is_one_line(tmp_path):
    """main: obspy's bare Exception "Can not merge traces with same ids … differing sampling rates" was a
    traceback, exit 1."""
    from obspy import Stream, Trace, UTCDateTime

    samples = np.sin(np.arange(200) * 0.1)
    header = {"network": "XX", "station": "STA", "channel": "HNE"}
    path = tmp_path / "two_rates.mseed"
    Stream([Trace(samples.copy(), header={**header, "delta": 0.01, "starttime": UTCDateTime(0)}),
            Trace(samples.copy(), header={**header, "delta": 0.02, "starttime": UTCDateTime(10)})]).write(
        str(path), format="MSEED")
    assert_one_line_exit_2(RUNNER.invoke(app, ["info", str(path), "--units", "m/s2", "--merge"]),
                           f"{path}: channel XX.STA..HNE has segments at different sampling rates (50, 100 Hz)")


# ---- a SAC header naming a velocity unit

def test_a_sac_header_in_a_velocity_unit_is_not_read_as_acceleration(tmp_path):
    """main: kuser0 = 'cm/s' with idep = IACC and `--units m/s2` was read as m/s² (a note to check the units)."""
    from obspy.io.sac import SACTrace

    path = tmp_path / "vel.sac"
    trace = SACTrace(data=np.sin(np.arange(200) * 0.1).astype(np.float32), delta=0.01, kstnm="STA", kcmpnm="HNE",
                     idep="iacc")
    trace.kuser0 = "cm/s"
    trace.write(str(path))
    assert_one_line_exit_2(RUNNER.invoke(app, ["info", str(path), "--units", "m/s2"]),
                           f"{path}: SAC header kuser0 = 'cm/s' is a unit of length or velocity")


# ---- a µ(v) single pendulum steeper than the engine follows is refused at reading

MUV = ('name = "muv"\nmass_kg = 1e6\nradius_m = 2.5\nmu_static = 0.06\nmu_slow = 0.04\nmu_fast = 0.06\nrate_s_per_m = {rate}\n'
       'displacement_capacity_m = 0.6\n')


def test_a_single_pendulum_rate_above_the_engines_bound_is_refused_at_reading(tmp_path):
    """main: read as a design and refused by the engine ("D under X: …"), so `design --vary rate_s_per_m=1e5,1e6`
    analysed both candidates to the engine's refusal and wrote a chart of none, exit 0 (30 s)."""
    record = tmp_path / "x.AT2"
    record.write_text(at2_text(SINE_G[:100]))
    steep = tmp_path / "steep.toml"
    steep.write_text(MUV.format(rate="1e5"))
    line = assert_one_line_exit_2(RUNNER.invoke(app, ["simulate", str(record), "--design", str(steep), "--json"]),
                                  f"{steep}: key 'rate_s_per_m' = 100000 s/m exceeds 10000 s/m")
    assert "under" not in line
    from isolator.design import Design

    assert Design.from_toml(_write(tmp_path / "edge.toml", MUV.format(rate="1e4"))).rate_s_per_m == 1e4


def _write(path, text):
    path.write_text(text)
    return path


# ---- a design search's table over a record its SUITE.toml lists

def test_a_design_search_does_not_write_its_table_over_a_suite_record(tmp_path):
    """main: `design -s suite.toml -o rec.pdf` wrote its table rec.csv over the suite's record rec.csv (exit 0):
    the check saw the SUITE.toml, not the files it lists."""
    record = tmp_path / "rec.csv"
    record.write_text(_csv("# units: g\n# component: 0\n"))
    (tmp_path / "y.AT2").write_text(at2_text([0.1 * (-1) ** (i // 30) for i in range(300)]))
    suite = _write(tmp_path / "suite.toml", '[[pair]]\nname = "a"\nx = "rec.csv"\ny = "y.AT2"\n')
    design = _write(tmp_path / "fps.toml", 'name = "FPS"\nmass_kg = 1e6\nradius_m = 2.5\nmu_static = 0.06\n'
                                           'displacement_capacity_m = 0.6\n')
    before = record.read_bytes()
    result = RUNNER.invoke(app, ["design", "-t", "example", "-s", str(suite), "-d", str(design), "--vary",
                                 "radius_m=2.5", "-o", str(tmp_path / "rec.pdf"), "-j", "1"])
    assert_one_line_exit_2(result, f"{record}: is an input of this command")
    assert record.read_bytes() == before
    assert not (tmp_path / "rec.pdf").exists()


# ---- the per-user key file: a FIFO blocked every batch, a link to /dev/zero filled the memory

@pytest.mark.parametrize("kind", ["fifo", "dev_zero"])
def test_a_key_file_that_is_not_a_regular_file_is_not_read(tmp_path, kind):
    """main: ``user_secret`` read ``batch.key`` whole: a FIFO blocked `batch` for ever (past `timeout 40`), a link
    to /dev/zero was a MemoryError traceback under a 2 GB limit (and all the memory without one).  Now such a key
    is not trusted: the key lives for this process only, as without a writable cache."""
    key = tmp_path / "batch.key"
    if kind == "fifo":
        os.mkfifo(key)
    else:
        key.symlink_to("/dev/zero")

    def limit():  # the child's memory, so that a regression fails here instead of filling the machine
        resource.setrlimit(resource.RLIMIT_AS, (2 * 2**30, 2 * 2**30))

    code = "from isolator.atomic import user_secret; print(len(user_secret()))"
    done = subprocess.run([sys.executable, "-c", code], env={**os.environ, "ISOLATOR_CACHE_DIR": str(tmp_path)},
                          capture_output=True, text=True, timeout=60, preexec_fn=limit)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "32"


def test_a_batch_table_key_that_is_a_fifo_does_not_block_the_batch(tmp_path):
    """main: a rerun into ``t.csv`` read ``.t.csv.key`` whole to trust the finished table: a FIFO there blocked the
    batch for ever (past `timeout 60`), a link to /dev/zero was a MemoryError traceback.  Now the key is not read
    (the table is not trusted) and the table's write refuses the FIFO in one line; the rows stay in t.csv.parts."""
    records = tmp_path / "records"
    records.mkdir()
    (records / "x.AT2").write_text(at2_text(SINE_G[:100]))
    designs = _write(tmp_path / "designs.toml", '[[design]]\nname = "FPS"\nmass_kg = 1e6\nradius_m = 2.5\n'
                                                 'mu_static = 0.06\n')
    table = _write(tmp_path / "t.csv", "an older table\n")
    os.mkfifo(tmp_path / ".t.csv.key")
    command = os.path.join(os.path.dirname(sys.executable), "isolator")  # the venv's console script
    done = subprocess.run([command, "batch", str(records), "-d", str(designs), "-o",
                           str(table), "-j", "1"], env={**os.environ, "ISOLATOR_CACHE_DIR": str(tmp_path / "cache")},
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 2, done.stderr
    lines = [line for line in done.stderr.splitlines() if line.strip() and not line.startswith("note:")]
    assert len(lines) == 1 and ".t.csv.key: is a FIFO (named pipe), not a regular file" in lines[0], done.stderr


@pytest.mark.parametrize("store", ["isolator.review.worker:Cache", "isolator.review.design_store:RowStore"])
def test_a_cache_entry_that_is_a_fifo_is_no_entry(tmp_path, store):
    """main: a review's cache entry (``.NAME.cache/KEY.json``) or a design search's finished row
    (``.NAME.design/KEY.json``) replaced by a FIFO blocked the run for ever.  Now it is no entry (recomputed)."""
    os.mkfifo(tmp_path / "k.json")
    module, name = store.split(":")
    code = f"from {module} import {name}; print({name}({str(tmp_path)!r}).get('k'))"
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0 and done.stdout.strip() == "None", done.stderr


def test_a_regime_map_cache_entry_that_is_a_fifo_is_recomputed(tmp_path):
    """main: ``regime-map`` with a FIFO in place of its cached ``.npz`` blocked in ``np.load`` (past `timeout 60`).
    Now the entry is damaged (``CacheEntryError``): the map is recomputed with a note."""
    entry = tmp_path / "map.npz"
    os.mkfifo(entry)
    code = ("from isolator.maps import RegimeMap\nfrom isolator.errors import CacheEntryError\n"
            f"try:\n    RegimeMap.load({str(entry)!r})\nexcept CacheEntryError as err:\n    print(err)\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0 and "not a regular file" in done.stdout, (done.stdout, done.stderr)


def test_a_plan_too_small_for_its_torsion_ratio_is_refused_at_reading(tmp_path):
    """main: ``[plan] b_m = d_m = 1e-300`` was read; `report` of the building then divided by r_I = sqrt((b² + d²)/12),
    which underflows to 0 (ASCE 7-22 Eq. 17.5-4's P_T): a ZeroDivisionError traceback, exit 1."""
    from _model_designs import BUILDING

    record = tmp_path / "x.AT2"
    record.write_text(at2_text(SINE_G[:100]))
    design = _write(tmp_path / "plan.toml", BUILDING.replace("[superstructure]", "[plan]\nb_m = 1e-300\nd_m = 1e-300\n"
                                                                                 "[superstructure]", 1))
    assert_one_line_exit_2(RUNNER.invoke(app, ["report", str(record), "--design", str(design), "--no-pdf", "-o",
                                               str(tmp_path / "r.pdf")]),
                           f"{design}: key 'plan.b_m' must lie in [0.01, 10000] m, a plan dimension, got 1e-300")
    assert not (tmp_path / "r.json").exists()


def test_a_torsion_period_ratio_floor_near_zero_is_refused(tmp_path):
    """main: ``--set P_T_min=1e-300`` was in (0, 10]; with the plan's ``P_T = 1e-300`` the torsion factor of ASCE 7-22
    Eq. 17.5-3 divided by P_T² = 0 (underflow): a ZeroDivisionError traceback from `report`, exit 1."""
    from _model_designs import BUILDING

    record = tmp_path / "x.AT2"
    record.write_text(at2_text(SINE_G[:100]))
    design = _write(tmp_path / "pt.toml", BUILDING.replace("[superstructure]", "[plan]\nb_m = 10\nd_m = 20\n"
                                                                               "P_T = 1e-300\n[superstructure]", 1))
    assert_one_line_exit_2(RUNNER.invoke(app, ["report", str(record), "--design", str(design), "--no-pdf", "-o",
                                               str(tmp_path / "r.pdf"), "--set", "P_T_min=1e-300"]),
                           "review parameter 'P_T_min' = 1e-300 is outside [0.1, 10]")
