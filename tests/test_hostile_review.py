"""`isolator review` under hostile use (issue 26): outputs over inputs, a held lock, a read-only or full
output folder, a damaged or hand-edited cache, the resume after kill -9, and the same piecewise-linear
signal sampled two ways.

A small suite (two synthetic pairs of 10 s) keeps each review to seconds of CPU; the reviews that
run share a module fixture.
"""

from __future__ import annotations

import json
import os
import socket
import subprocess
import sys
import uuid
from pathlib import Path

import numpy as np
import pytest
from test_hostile_outputs import small_disk as small_disk  # the 256 KiB tmpfs fixture
from typer.testing import CliRunner

from isolator.cli import app

RUNNER = CliRunner()
DESIGN = ('name = "d"\nmass_kg = 1e6\nradius_m = 2.0\nmu_static = 0.06\nlambda_max = 1.2\nlambda_min = 0.9\n'
          'displacement_capacity_m = 0.5\n')
#: JSON keys that hold wall-clock measures or the command line: they differ between two equal runs.
TIMING_KEYS = {"timing", "timing_s", "created_utc", "command", "solver_seconds", "harmonic_seconds", "seconds",
               "analysis_seconds", "pdf"}


def _pair_values(k: int):
    rng = np.random.default_rng(10 + k)
    t = np.arange(1000) * 0.01
    envelope = np.minimum(1.0, t / 2.0) * np.exp(-np.maximum(t - 5.0, 0.0) / 2.0)
    return t, [envelope * sum(0.08 * np.sin(2 * np.pi * f * t + phase + k) for f in rng.uniform(0.3, 3.0, 6))
               for phase in (0.0, 1.0)]


def _write_record(path: Path, t, a, component: str) -> None:
    path.write_text(f"# units: g\n# component: {component}\n" + "".join(f"{x:.6f},{y:.9e}\n"
                                                                       for x, y in zip(t, a, strict=True)))


def _make_suite(folder: Path, *, midpoints: bool = False) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    text = ""
    for k in range(2):
        t, (ax, ay) = _pair_values(k)
        for component, a in (("000", ax), ("090", ay)):
            times, values = t, a
            if midpoints:  # the same piecewise-linear signal, a collinear midpoint in the first 400 intervals
                mids_t, mids_a = 0.5 * (t[:400] + t[1:401]), 0.5 * (a[:400] + a[1:401])
                times = np.concatenate([np.ravel(np.column_stack([t[:400], mids_t])), t[400:]])
                values = np.concatenate([np.ravel(np.column_stack([a[:400], mids_a])), a[400:]])
            _write_record(folder / f"p{k}_{component}.csv", times, values, component)
        text += f'[[pair]]\nname = "p{k}"\nx = "p{k}_000.csv"\ny = "p{k}_090.csv"\n'
    (folder / "suite.toml").write_text(text)
    (folder / "design.toml").write_text(DESIGN)
    return folder / "suite.toml"


def _review(folder: Path, output: Path, *extra) -> object:
    return RUNNER.invoke(app, ["review", "-d", str(folder / "design.toml"), "-t", "example", "-s",
                               str(folder / "suite.toml"), "-o", str(output), "-j", "1", *extra])


def _numbers(document):
    """The review JSON without its timings (what two equal runs must share)."""
    if isinstance(document, dict):
        return {k: _numbers(v) for k, v in document.items() if k not in TIMING_KEYS and "cache" not in k}
    if isinstance(document, list):
        return [_numbers(v) for v in document]
    return document


def _differences(a, b, where="") -> list:
    """Paths at which two JSON documents differ (for a readable assertion)."""
    if isinstance(a, dict) and isinstance(b, dict):
        return [d for k in sorted(set(a) | set(b)) for d in _differences(a.get(k), b.get(k), f"{where}/{k}")]
    if isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        return [d for i, (x, y) in enumerate(zip(a, b, strict=True)) for d in _differences(x, y, f"{where}[{i}]")]
    return [] if a == b or (a != a and b != b) else [f"{where}: {a!r} != {b!r}"]


def _one_line(result, words: str) -> None:
    assert result.exit_code == 2, (result.exit_code, result.stdout[-500:], result.stderr)
    assert len(result.stderr.splitlines()) == 1 and result.stderr.startswith("error: "), result.stderr
    assert words in result.stderr, result.stderr
    assert "Traceback" not in result.stderr + result.stdout


@pytest.fixture(scope="module")
def reviewed(tmp_path_factory):
    """A suite folder and one complete review of it (PDF, JSON, cache)."""
    folder = tmp_path_factory.mktemp("review")
    _make_suite(folder / "suite")
    output = folder / "out" / "r.pdf"
    result = _review(folder / "suite", output)
    assert result.exit_code == 0, result.stderr
    return folder / "suite", output


# ---------------------------------------------------------------- refused before any work
@pytest.mark.parametrize("case", ["record_is_json", "record_is_pdf", "target_table_is_json", "cache_holds_record"])
def test_outputs_that_are_inputs_are_refused_before_any_work(tmp_path, case):
    suite = _make_suite(tmp_path / "s")
    output = tmp_path / "s" / "X.pdf"
    target = "example"
    if case in ("record_is_json", "record_is_pdf"):
        name = "X.json" if case == "record_is_json" else "X.pdf"
        os.replace(tmp_path / "s" / "p1_090.csv", tmp_path / "s" / name)
        suite.write_text(suite.read_text().replace("p1_090.csv", name))
        words = "is an input of this command"
    elif case == "target_table_is_json":
        (tmp_path / "s" / "X.json").write_text("period_s,sa_g\n0.1,1.0\n1.0,0.5\n5.0,0.1\n")
        (tmp_path / "s" / "t.toml").write_text('spectrum_csv = "X.json"\n')
        target, words = str(tmp_path / "s" / "t.toml"), "is an input of this command"
    else:  # the cache folder .X.cache is where the suite keeps a record
        cache = tmp_path / "s" / ".X.cache"
        cache.mkdir()
        os.replace(tmp_path / "s" / "p0_000.csv", cache / "p0_000.csv")
        suite.write_text(suite.read_text().replace('"p0_000.csv"', '".X.cache/p0_000.csv"'))
        words = "the review's cache folder holds an input"
    before = {p: p.read_bytes() for p in (tmp_path / "s").rglob("*") if p.is_file()}
    result = RUNNER.invoke(app, ["review", "-d", str(tmp_path / "s" / "design.toml"), "-t", target, "-s",
                                 str(suite), "-o", str(output)])
    _one_line(result, words)
    assert {p: p.read_bytes() for p in (tmp_path / "s").rglob("*") if p.is_file()} == before


def test_a_review_whose_output_is_locked_is_refused_naming_the_holder(tmp_path):
    suite = _make_suite(tmp_path / "s")
    output = tmp_path / "out" / "r.pdf"
    output.parent.mkdir()
    (tmp_path / "out" / "r.pdf.lock").write_text(f"pid=1 host={socket.gethostname()} since=earlier\n")
    result = _review(suite.parent, output)
    _one_line(result, "is being written by process 1")
    assert sorted(p.name for p in output.parent.iterdir()) == ["r.pdf.lock"]


def test_a_read_only_output_folder_is_one_line(tmp_path):
    if os.geteuid() != 0:
        pytest.skip("needs root to mount a read-only tmpfs")
    suite = _make_suite(tmp_path / "s")
    mount = tmp_path / "ro"
    mount.mkdir()
    if subprocess.run(["mount", "-t", "tmpfs", "-o", "size=64k,ro", "tmpfs", str(mount)]).returncode != 0:
        pytest.skip("cannot mount a tmpfs here")
    try:
        result = _review(suite.parent, mount / "r.pdf")
        _one_line(result, "Read-only file system")
        assert str(mount / "r.pdf") in result.stderr
    finally:
        subprocess.run(["umount", "-l", str(mount)], check=False)


# ---------------------------------------------------------------- the cache, the resume
def test_edited_or_malformed_cache_entries_are_recomputed_with_a_note(reviewed, tmp_path):
    folder, output = reviewed
    reference = _numbers(json.loads(output.with_suffix(".json").read_text()))
    copy = tmp_path / "r.pdf"
    cache = output.parent / ".r.cache"
    import shutil

    shutil.copytree(cache, tmp_path / ".r.cache")
    entries = sorted((tmp_path / ".r.cache").glob("*.json"))
    assert len(entries) >= 4
    edited = json.loads(entries[0].read_text())
    edited["result"]["peak_displacement_m"] = 0.001  # the hand edit: D to 1 mm
    entries[0].write_text(json.dumps(edited))
    for entry, text in zip(entries[1:5], ["[]", "{}", '"x"', '{"schema": 1, "key": [], "result": "a", "mac": 0}'],
                           strict=False):
        entry.write_text(text)
    result = _review(folder, copy, "--json")
    assert result.exit_code == 0 and result.stderr == "", result.stderr
    document = json.loads(result.stdout)
    assert any("review cache entries" in note and "recomputed, not trusted" in note for note in document["notes"])
    assert _differences(_numbers({k: v for k, v in document.items() if k != "notes"}),
                        {k: v for k, v in reference.items() if k != "notes"}) == []


def test_the_resume_after_a_kill_gives_the_same_review(reviewed, tmp_path):
    """The state kill -9 leaves: half the cache, a temporary of a dead writer, the dead run's lock."""
    folder, output = reviewed
    import shutil

    shutil.copytree(output.parent / ".r.cache", tmp_path / ".r.cache")
    for entry in sorted((tmp_path / ".r.cache").glob("*.json"))[::2]:
        entry.unlink()
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True, text=True)
    pid = int(dead.stdout)
    host = socket.gethostname()
    (tmp_path / "r.pdf.lock").write_text(f"pid={pid} host={host} since=earlier\n")
    tag = "".join(c if c.isalnum() or c == "-" else "-" for c in host)[:32]
    stale = tmp_path / f".r.pdf.~{tag}-{pid}.{uuid.uuid4().hex[:8]}.pdf"
    stale.write_bytes(b"%PDF-1.4 half")
    from isolator import atomic

    atomic._CLEANED_FOLDERS.discard(os.path.realpath(tmp_path))  # the next run is a new process
    result = _review(folder, tmp_path / "r.pdf")
    assert result.exit_code == 0, result.stderr
    resumed = json.loads((tmp_path / "r.json").read_text())
    first = json.loads(output.with_suffix(".json").read_text())
    assert _differences(_numbers(resumed), _numbers(first)) == []
    assert 0 < resumed["timing_s"]["analyses_cached"] < resumed["timing_s"]["analyses_total"]
    assert sorted(p.name for p in tmp_path.iterdir()) == [".r.cache", "r.json", "r.pdf"]  # no lock, no temporary


def test_the_same_signal_sampled_two_ways_gives_the_same_review(reviewed, tmp_path):
    """The suite with a collinear midpoint in the first 400 intervals of each component is the same piecewise-linear
    signal: the spectra (peaks of the continuous response, between samples), the scale factors and the engines'
    answers agree to 1e-9 (measured: 5e-12 on the factors, 4e-11 on the spreads; 1.6e-5 when the spectra took
    their peaks at the sample instants), and so do the D5–95 windows (exact ∫a², 5e-4 apart with the trapezoidal
    rule) and the record-selection rows (bandwidth on a fixed band of the exact transform: 2.7e-2 apart before)."""
    folder, output = reviewed
    _make_suite(tmp_path / "m", midpoints=True)
    result = _review(tmp_path / "m", tmp_path / "m.pdf", "--no-cache")
    assert result.exit_code == 0, result.stderr
    refined = json.loads((tmp_path / "m.json").read_text())
    first = json.loads(output.with_suffix(".json").read_text())
    for name, factor in first["scale_factors"].items():
        assert refined["scale_factors"][name] == pytest.approx(factor, rel=1e-9)
    assert refined["period_grid"]["suite_ratio"] == pytest.approx(first["period_grid"]["suite_ratio"], rel=1e-9)
    assert refined["suite_mean_ratio"] == pytest.approx(first["suite_mean_ratio"], rel=1e-9)
    for bound, values in first["bounds"].items():
        for name, analysis in values["pairs"].items():
            mine = refined["bounds"][bound]["pairs"][name]
            for key in ("peak_displacement_m", "peak_transmitted_acceleration_m_s2", "base_shear_coefficient",
                        "window_start_s", "window_end_s"):
                assert mine[key] == pytest.approx(analysis[key], rel=1e-9), (bound, name, key)
        assert refined["bounds"][bound]["D_M_rha_m"] == pytest.approx(values["D_M_rha_m"], rel=1e-9)
    checks = {row["id"]: row for row in refined["checks"]}
    for row in first["checks"]:  # the record-selection rows: the Vanmarcke bandwidth and the motion signatures
        if row["id"] in ("record_nature", "distinct_motions"):
            assert checks[row["id"]]["value"] == pytest.approx(row["value"], rel=1e-9), row["id"]
            assert checks[row["id"]]["status"] == row["status"]
    for bound, quantities in first["spread"].items():
        for quantity, stats in quantities.items():
            for stat, value in stats.items():
                assert refined["spread"][bound][quantity][stat] == pytest.approx(value, rel=1e-9), (bound, quantity)

def test_two_concurrent_reviews_on_one_output_one_wins_and_the_set_is_its_own(tmp_path):
    """Two real `isolator review` processes started together on one -o: one writes, the other is refused in one
    line naming the holder (exit 2); the PDF and the JSON left are both the winner's (each run reviews a design
    of its own name: the JSON's design and the PDF's title say which run wrote them)."""
    suite = _make_suite(tmp_path / "s")
    output = tmp_path / "out" / "r.pdf"
    runs = {}
    for name in ("first", "second"):
        design = tmp_path / "s" / f"{name}.toml"
        design.write_text(DESIGN.replace('name = "d"', f'name = "{name}"'))
        arguments = ["review", "-d", str(design), "-t", "example", "-s", str(suite), "-o", str(output), "-j", "1",
                     "--no-cache"]
        runs[name] = subprocess.Popen([sys.executable, "-c", f"from isolator.cli import app; app({arguments!r})"],
                                      stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    done = {name: (process.wait(timeout=600), *process.communicate()) for name, process in runs.items()}
    codes = sorted(code for code, _, _ in done.values())
    assert codes == [0, 2], {name: (code, err[-500:]) for name, (code, _, err) in done.items()}
    winner = next(name for name, (code, _, _) in done.items() if code == 0)
    loser = "second" if winner == "first" else "first"
    refusal = done[loser][2]
    assert len(refusal.splitlines()) == 1 and refusal.startswith("error: ") and "Traceback" not in refusal
    assert f"is being written by process {runs[winner].pid}" in refusal
    assert json.loads(output.with_suffix(".json").read_text())["design"]["name"] == winner
    assert f"/Title (isolator review: {winner})".encode() in output.read_bytes()
    assert sorted(p.name for p in output.parent.iterdir()) == ["r.json", "r.pdf"]  # no lock, no temporary


# ---------------------------------------------------------------- issue 26, Tests: what was not yet tested
def test_a_real_kill_9_during_a_review_then_the_resume_gives_the_same_review(reviewed, tmp_path):
    """A review process killed by SIGKILL once it has cached some analyses (a real kill, not a built state): the next
    run takes over the dead run's lock, removes nothing it needs, reuses the cache, and its JSON equals a clean
    run's apart from timings; no lock or temporary is left."""
    import signal
    import time

    folder, output = reviewed
    target = tmp_path / "r.pdf"
    arguments = ["review", "-d", str(folder / "design.toml"), "-t", "example", "-s", str(folder / "suite.toml"),
                 "-o", str(target), "-j", "1"]
    process = subprocess.Popen([sys.executable, "-c", f"from isolator.cli import app; app({arguments!r})"],
                               stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    cache = tmp_path / ".r.cache"
    deadline = time.monotonic() + 300
    while time.monotonic() < deadline and process.poll() is None and len(list(cache.glob("*.json"))) < 2:
        time.sleep(0.02)
    if process.poll() is not None:
        pytest.skip("the review finished before it could be killed (machine too fast for this small suite)")
    process.send_signal(signal.SIGKILL)
    assert process.wait(timeout=60) == -signal.SIGKILL
    assert (tmp_path / "r.pdf.lock").exists() and not target.exists()  # the dead run's trace
    from isolator import atomic

    atomic._CLEANED_FOLDERS.discard(os.path.realpath(tmp_path))  # the next run is a new process
    # the resume and the clean run it is compared with are fresh processes, as a user runs them: inside this test
    # process, after the rest of the suite has run, the same review came out different in the last bits (seen in
    # the full suite only, not understood yet; a fresh process reproduces a fresh process bit for bit)
    clean = output.parent.parent / "clean" / "r.pdf"
    runs = []  # the two are independent (other outputs, the clean one without a cache): run side by side
    for out, extra in ((target, []), (clean, ["--no-cache"])):
        arguments = ["review", "-d", str(folder / "design.toml"), "-t", "example", "-s", str(folder / "suite.toml"),
                     "-o", str(out), "-j", "1", *extra]
        runs.append(subprocess.Popen([sys.executable, "-c", f"from isolator.cli import app; app({arguments!r})"],
                                     stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True))
    for run in runs:
        _, err = run.communicate(timeout=600)
        assert run.returncode == 0, err[-2000:]
    resumed = json.loads(target.with_suffix(".json").read_text())
    assert _differences(_numbers(resumed), _numbers(json.loads(clean.with_suffix(".json").read_text()))) == []
    assert resumed["timing_s"]["analyses_cached"] >= 1  # the killed run's analyses were reused
    assert sorted(p.name for p in tmp_path.iterdir()) == [".r.cache", "r.json", "r.pdf"]


def test_a_full_disk_under_a_review_leaves_the_older_set_whole(tmp_path, small_disk):
    """A review whose PDF does not fit on a real 256 KiB tmpfs: one line naming the output, exit 2, the older PDF
    and JSON left whole, no temporary and no lock."""
    suite = _make_suite(tmp_path / "s")
    (small_disk / "r.pdf").write_bytes(b"old pdf")
    (small_disk / "r.json").write_text('{"run": "old"}')
    (small_disk / "filler").write_bytes(b"\0" * 200_000)
    result = _review(suite.parent, small_disk / "r.pdf", "--no-cache")
    _one_line(result, "No space left on device")
    assert str(small_disk / "r.") in result.stderr
    assert (small_disk / "r.pdf").read_bytes() == b"old pdf" and (small_disk / "r.json").read_text() == '{"run": "old"}'
    assert sorted(p.name for p in small_disk.iterdir()) == ["filler", "r.json", "r.pdf"]


@pytest.mark.parametrize("kind", ["target", "suite"])
def test_an_example_in_the_working_folder_is_read_not_the_bundled_one(tmp_path, monkeypatch, kind):
    """`--target example` / `--suite example` with a ./example in the working folder read that one (here a folder
    that is no target and holds no record: the error names it), never the bundled example silently."""
    suite = _make_suite(tmp_path / "s")
    (tmp_path / "w" / "example").mkdir(parents=True)
    monkeypatch.chdir(tmp_path / "w")
    args = ["review", "-d", str(tmp_path / "s" / "design.toml"), "-o", str(tmp_path / "out" / "r.pdf"),
            "-t", "example" if kind == "target" else "example", "-s", "example" if kind == "suite" else str(suite)]
    if kind == "suite":
        args[args.index("-t") + 1] = str(Path(__file__).resolve().parents[1] / "isolator" / "data" / "targets"
                                         / "example.toml")
    result = RUNNER.invoke(app, args)
    assert result.exit_code == 2, result.stderr
    assert len(result.stderr.splitlines()) == 1 and "Traceback" not in result.stderr
    assert "example" in result.stderr and "isolator/data" not in result.stderr
