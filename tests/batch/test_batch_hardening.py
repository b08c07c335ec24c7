"""Batch under hostile conditions: reruns with other plans, outputs among the records, damaged or
crafted parts, failing analyses, huge plans, two runs on one output, a killed parent, bad schedulers."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd
import pytest

from isolator.atomic import OutputIsInputError, OutputLockedError, output_lock
from isolator.batch import BatchError, comparable, expand_designs, parse_grid, run_batch
from isolator.batch.plan import MAX_PLAN_ROWS
from isolator.batch.store import PartStore, write_table_atomically
from isolator.parallel import check_scheduler

sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_batch import DESIGNS, read, write_record


@pytest.fixture(autouse=True)
def _private_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("ISOLATOR_CACHE_DIR", str(tmp_path / "cache"))
    from isolator import atomic

    monkeypatch.setattr(atomic, "_SECRET", None)  # this test's own key (shared by batch parts and review cache)


@pytest.fixture
def suite(tmp_path):
    records = tmp_path / "records"
    records.mkdir()
    for i, (pga, period) in enumerate([(0.35, 0.8), (0.25, 1.2)]):
        write_record(records / f"rec{i}.txt", pga, period, npts=800)
    designs = tmp_path / "designs.toml"
    designs.write_text(DESIGNS)
    return records, designs


def test_rerun_with_another_grid_reuses_only_identical_rows(suite, tmp_path):
    records, designs = suite
    out = tmp_path / "t.csv"
    first = run_batch([str(records)], designs, out, grids=[parse_grid("radius_m=1:3:3")], jobs=1)
    assert first.n_rows == 2 * 2 * 3
    # another grid: R = 2 and 3 m are in both plans (reused), R = 4 m is new; every position differs
    second = run_batch([str(records)], designs, out, grids=[parse_grid("radius_m=2:4:3")], jobs=1)
    straight = run_batch([str(records)], designs, tmp_path / "s.csv", grids=[parse_grid("radius_m=2:4:3")], jobs=1)
    assert second.n_resumed == 2 * 2 * 2  # two records × two designs × (R = 2, 3 m), nothing else
    pd.testing.assert_frame_equal(comparable(read(out)).drop(columns=["row_key"]),
                                  comparable(read(tmp_path / "s.csv")).drop(columns=["row_key"]))
    assert list(read(out)["design_index"]) == list(straight.table["design_index"])


def test_a_changed_record_is_recomputed(suite, tmp_path):
    records, designs = suite
    out = tmp_path / "t.csv"
    run_batch([str(records)], designs, out, jobs=1)
    write_record(records / "rec0.txt", 0.6, 0.8, npts=800)  # same name, other content
    again = run_batch([str(records)], designs, out, jobs=1)
    assert again.n_resumed == 2  # only rec1's rows
    run_batch([str(records)], designs, tmp_path / "fresh.csv", jobs=1)
    pd.testing.assert_frame_equal(comparable(read(out)), comparable(read(tmp_path / "fresh.csv")))
    rec0 = read(out)[read(out)["record"].str.endswith("rec0.txt")]
    assert rec0["pga_m_s2"].tolist() == pytest.approx([0.6 * 9.80665] * 2, rel=1e-6)  # the new content


def test_output_inside_the_records_folder_is_never_a_record(suite, monkeypatch):
    records, designs = suite
    out = records / "table.csv"
    summary_rows = []
    for _ in range(3):
        result = run_batch([str(records)], designs, out, jobs=1, extra_outputs=[records / "summary.csv"])
        summary_rows.append((result.n_rows, result.n_failed))
    # the summary this batch writes (with its content key) sits there too: not a record, not an input
    write_table_atomically(pd.DataFrame({"a": [1], "b": [2]}), records / "summary.csv", keyed=True)
    # keep the parts of a run: they sit in records/table.csv.parts/ and must not be read as records
    monkeypatch.setattr(PartStore, "remove", lambda self: None)
    out.unlink()
    run_batch([str(records)], designs, out, jobs=1, extra_outputs=[records / "summary.csv"])
    assert list((records / "table.csv.parts").glob("part-*.jsonl"))
    final = run_batch([str(records)], designs, out, jobs=1, extra_outputs=[records / "summary.csv"])
    assert summary_rows == [(4, 0)] * 3 and (final.n_rows, final.n_failed) == (4, 0)
    assert set(Path(p).name for p in final.table["record"]) == {"rec0.txt", "rec1.txt"}


def test_output_that_is_an_input_is_refused(suite, tmp_path):
    records, designs = suite
    record = write_record(records / "in.csv", 0.3, 0.7, npts=400)  # a record that is itself a CSV
    before = record.read_bytes()
    with pytest.raises(OutputIsInputError, match="in.csv: is an input"):
        run_batch([str(records)], designs, record, jobs=1)
    foreign = records / "summary.csv"  # a file among the records that this batch did not write
    foreign.write_text("time,acc\n0,0.1\n0.01,0.2\n")
    with pytest.raises(OutputIsInputError, match="summary.csv: is an input"):
        run_batch([str(records)], designs, tmp_path / "t.csv", jobs=1, extra_outputs=[foreign])
    assert foreign.read_text() == "time,acc\n0,0.1\n0.01,0.2\n"
    with pytest.raises(OutputIsInputError, match="designs.toml: is an input"):
        run_batch([str(record)], designs, tmp_path / "t.csv", jobs=1, extra_outputs=[designs])
    assert record.read_bytes() == before and not (tmp_path / "t.csv").exists()


def _kept_parts(records, designs, out, monkeypatch):
    with monkeypatch.context() as patch:
        patch.setattr(PartStore, "remove", lambda self: None)
        run_batch([str(records)], designs, out, jobs=1)
    out.unlink()  # no finished table: everything must come from the parts
    return sorted(Path(str(out) + ".parts").glob("part-*.jsonl"))


def test_damaged_and_crafted_parts_are_skipped_counted_and_recomputed(suite, tmp_path, monkeypatch):
    records, designs = suite
    out = tmp_path / "t.csv"
    straight = run_batch([str(records)], designs, tmp_path / "straight.csv", jobs=1)
    parts = _kept_parts(records, designs, out, monkeypatch)
    assert len(parts) == 2
    lines = parts[0].read_bytes().splitlines()
    # part 0: its first line truncated mid-way, its second line with a flipped byte
    truncated = lines[0][: len(lines[0]) // 2]
    flipped = bytearray(lines[1])
    flipped[40] ^= 0x01
    parts[0].write_bytes(truncated + b"\n" + bytes(flipped) + b"\n")
    # part 1: kept intact, plus a crafted line (a planned key with a made-up value and column) and invalid UTF-8
    good = json.loads(parts[1].read_bytes().splitlines()[0])
    crafted = dict(good["row"], peak_displacement_m=123.0, injected="x")
    with open(parts[1], "ab") as stream:
        stream.write(json.dumps({"row": crafted, "key": good["key"]}).encode() + b"\n")
        stream.write(b"\xff\xfe{not json\n")
    result = run_batch([str(records)], designs, out, jobs=1)
    assert result.notes == [f"4 damaged line(s) in {out}.parts skipped (truncated, corrupt or not written by this "
                            "user); their rows are recomputed"]
    assert result.n_resumed == 2  # the intact part's rows
    table = read(out)
    assert "injected" not in table.columns and 123.0 not in set(table["peak_displacement_m"])
    pd.testing.assert_frame_equal(comparable(table), comparable(read(tmp_path / "straight.csv")))
    assert straight.n_rows == 4


def test_edited_finished_table_is_not_reused(suite, tmp_path):
    records, designs = suite
    out = tmp_path / "t.csv"
    run_batch([str(records)], designs, out, jobs=1)
    assert run_batch([str(records)], designs, out, jobs=1).n_resumed == 4  # an intact table is reused
    table = read(out)
    table.loc[0, "peak_displacement_m"] = 99.0
    table.to_csv(out, index=False)
    again = run_batch([str(records)], designs, out, jobs=1)
    assert again.n_resumed == 0 and 99.0 not in set(read(out)["peak_displacement_m"])


def test_failures_blame_the_right_thing_without_raw_exception_text(suite, tmp_path, monkeypatch):
    records, designs = suite
    zeros = records / "zeros.txt"
    zeros.write_text("# units: g\n" + "".join(f"{0.01 * i:.2f},0\n" for i in range(50)))
    designs.write_text(DESIGNS + '\n[[design]]\nname = "absurd"\nmass_kg = 1000.0\nradius_m = 1e-300\n'
                       'mu_static = 0.05\n')
    from isolator.batch import worker

    real = worker._analysis_columns

    def failing(task, case, design, *args, **kwargs):
        if design.name == "FPS damped":
            return 1.0 / 0.0
        return real(task, case, design, *args, **kwargs)

    monkeypatch.setattr(worker, "_analysis_columns", failing)
    table = run_batch([str(records)], designs, tmp_path / "t.csv", jobs=1).table
    errors = table.set_index(["record", "design_name"])["error"]
    assert all(str(zeros) in e and "is zero" in e for e in table[table["record"] == str(zeros)]["error"])
    absurd = table[(table["design_index"] == 2) & (table["record"] != str(zeros))]["error"]
    assert all("key 'radius_m' = 1e-300 m" in e and str(designs) in e for e in absurd)
    damped = table[(table["design_index"] == 1) & (table["record"] != str(zeros))]["error"]
    assert all("internal error in isolator" in e for e in damped)
    assert not any("ZeroDivisionError" in e or "division by zero" in e for e in errors)


def test_plans_above_the_limit_are_refused_at_once():
    start = time.perf_counter()
    with pytest.raises(BatchError, match="COUNT = 100000000 exceeds the largest batch"):
        parse_grid("radius_m=1:2:100000000")
    grids = [parse_grid("radius_m=1:2:1000"), parse_grid("mu_static=0.01:0.1:1001")]
    with pytest.raises(BatchError, match="1,001,000 designs, more than the largest batch"):
        expand_designs([{"name": "x"}], grids)
    assert time.perf_counter() - start < 2.0
    assert MAX_PLAN_ROWS == 1_000_000


def test_second_run_on_the_same_output_is_refused(suite, tmp_path):
    records, designs = suite
    out = tmp_path / "t.csv"
    with output_lock(out):
        with pytest.raises(OutputLockedError, match=f"is being written by process {os.getpid()} on "):
            run_batch([str(records)], designs, out, jobs=1)
    assert not out.exists()
    assert run_batch([str(records)], designs, out, jobs=1).n_rows == 4  # released


def test_scheduler_addresses():
    for bad in ("not a url", "http://h:1", "tcp://", "tcp://host", "tcp://host:notaport", "tcp://h:1/path"):
        with pytest.raises(BatchError, match="expected tcp://HOST:PORT or tls://HOST:PORT"):
            check_scheduler(bad)
    assert check_scheduler("tcp://127.0.0.1:8786") == [] and check_scheduler("tcp://localhost:8786") == []
    assert check_scheduler("tls://10.0.0.5:8786") == []
    (note,) = check_scheduler("tcp://10.0.0.5:8786")
    assert "unencrypted" in note and "tls://" in note


def test_tls_without_certificates_is_a_clear_error(suite, tmp_path):
    pytest.importorskip("distributed")
    records, designs = suite
    with pytest.raises(BatchError, match="tls:// needs certificates in the dask configuration"):
        run_batch([str(records)], designs, tmp_path / "t.csv", scheduler="tls://127.0.0.1:1")


def test_workers_die_with_their_parent(tmp_path):
    script = (
        "import os, sys, time\n"
        "from isolator.parallel import process_pool\n"
        "with process_pool(2) as pool:\n"
        "    pids = set(pool.map(os.getpid().__class__, [0]))\n"  # start the workers
        "    futures = [pool.submit(time.sleep, 600) for _ in range(2)]\n"
        "    time.sleep(1.0)\n"
        "    print(' '.join(str(p) for p in pool._processes), flush=True)\n"
        "    time.sleep(600)\n")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    parent = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True, env=env)
    workers = [int(p) for p in parent.stdout.readline().split()]
    assert len(workers) == 2 and all(_alive(p) for p in workers)
    parent.send_signal(signal.SIGKILL)
    parent.wait()
    deadline = time.monotonic() + 10
    while time.monotonic() < deadline and any(_alive(p) for p in workers):
        time.sleep(0.1)
    assert not any(_alive(p) for p in workers)


def _alive(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat") as stream:
            return stream.read().split()[2] != "Z"  # a zombie has exited
    except OSError:
        return False
