"""Every command over a malformed-input corpus: exit 2, one line on stderr, no traceback, quickly,
and no input file changed.

The corpus is generated here (issue 13): paths with glob characters, a FIFO, symbolic links and
a loop, a dangling link, /dev/full and /dev/null, absurd numbers in options and design files,
time steps no accelerogram has, a record of zeros, an output that is an input, a locked output,
damaged batch parts and a damaged map cache.  Commands run in-process (typer's CliRunner).
"""

from __future__ import annotations

import hashlib
import os
import socket
import stat
import time
from pathlib import Path

import numpy as np
import pytest
from _records import at2_text
from typer.testing import CliRunner

from isolator.cli import app

RUNNER = CliRunner()
#: Wall-time bound of one refused command [s] (most answer in milliseconds; report and batch
#: import matplotlib and pandas on their first call).
TIME_BOUND_S = 15.0

DESIGN = 'name = "d"\nmass_kg = 1000.0\nradius_m = 2.0\nmu_static = 0.06\n'
DESIGNS = '[[design]]\nname = "d"\nmass_kg = 1000.0\nradius_m = 2.0\nmu_static = 0.06\n'


def _record_values(n=400, amplitude=0.2):
    return [amplitude * np.sin(0.3 * i) * min(1.0, i / 50) for i in range(n)]


@pytest.fixture(scope="module")
def corpus(tmp_path_factory):
    root = tmp_path_factory.mktemp("corpus")
    (root / "good.AT2").write_text(at2_text(_record_values()))
    (root / "x[1].AT2").write_text(at2_text(_record_values(300, 0.1), dt=".0200"))
    (root / "x1.AT2").write_text(at2_text(_record_values(500, 0.3)))  # what a glob would read instead
    (root / "zeros.AT2").write_text(at2_text([0.0] * 50))
    (root / "dt_tiny.AT2").write_text(at2_text(_record_values(40), dt="1e-300"))
    (root / "dt_huge.AT2").write_text(at2_text(_record_values(40), dt="100.0"))
    (root / "empty.AT2").write_text("")
    (root / "record.csv").write_text("# units: g\n" + "".join(f"{0.01 * i:.2f},{v:.6f}\n"
                                                              for i, v in enumerate(_record_values())))
    os.mkfifo(root / "pipe.AT2")
    os.mkfifo(root / "pipe.toml")
    (root / "loop.AT2").symlink_to(root / "loop2.AT2")
    (root / "loop2.AT2").symlink_to(root / "loop.AT2")
    (root / "dangling.AT2").symlink_to(root / "gone.AT2")
    (root / "alias.csv").symlink_to(root / "good.AT2")
    (root / "folder.AT2").mkdir()
    (root / "design.toml").write_text(DESIGN)
    (root / "design.json").write_text(DESIGN)  # a design file may be named .json: the report's sidecar
    (root / "designs.toml").write_text(DESIGNS)
    (root / "tiny_radius.toml").write_text(DESIGN.replace("radius_m = 2.0", "radius_m = 1e-300"))
    (root / "tiny_mass.toml").write_text(DESIGN.replace("mass_kg = 1000.0", "mass_kg = 1e-320"))
    (root / "stiff.toml").write_text(DESIGN.replace("radius_m = 2.0", "stiffness_N_per_m = 1e300"))
    (root / "design_loop.toml").symlink_to(root / "design_loop.toml")
    (root / "records").mkdir()
    (root / "records" / "a.AT2").write_text(at2_text(_record_values()))
    (root / "short.AT2").write_text(at2_text(_record_values(150)))  # a second component of another length
    (root / "bench_records").mkdir()
    (root / "bench_records" / "bench.csv").write_text("a record that happens to be named like a bench output\n")
    # issue 26: targets, suites and records a review or a command must refuse
    os.mkfifo(root / "table_pipe.csv")
    (root / "t_zero.toml").write_text('spectrum_csv = "/dev/zero"\n')
    (root / "t_pipe.toml").write_text('spectrum_csv = "table_pipe.csv"\n')
    (root / "two_headers.csv").write_text("MCE_R, site B\nperiod_s,sa_g\n0.1,1.0\n1.0,0.5\n")
    (root / "t_headers.toml").write_text('spectrum_csv = "two_headers.csv"\n')
    (root / "t_tiny.toml").write_text("S_MS = 1e-308\nS_M1 = 0.9\nT_L = 8\n")
    os.mkfifo(root / "suite_pipe.toml")
    (root / "suite_names.toml").write_text('[[pair]]\nname = "a"\nx = "good.AT2"\ny = "x1.AT2"\n'
                                           '[[pair]]\nname = " a"\nx = "short.AT2"\ny = "records/a.AT2"\n')
    (root / "two_units.csv").write_text("# units: g\n# units: cm/s2\n" + "".join(
        f"{0.01 * i:.2f},{v:.6f}\n" for i, v in enumerate(_record_values())))
    # a batch output whose lock is held by a live process (pid 1) on this host
    (root / "locked.csv.lock").write_text(f"pid=1 host={socket.gethostname()} since=earlier\n")
    return root


def _snapshot(root: Path) -> dict:
    """Every entry under ``root``: kind, and content hash or link target (FIFOs are never opened)."""
    state = {}
    for path in sorted(root.rglob("*")):
        mode = path.lstat().st_mode
        if stat.S_ISLNK(mode):
            state[str(path)] = ("link", os.readlink(path))
        elif stat.S_ISREG(mode):
            state[str(path)] = ("file", hashlib.sha256(path.read_bytes()).hexdigest())
        else:
            state[str(path)] = (stat.S_IFMT(mode), None)
    return state


def _cases(c: Path):
    """(command line, words the one stderr line must hold) for every command."""
    good, design = str(c / "good.AT2"), str(c / "design.toml")
    return [
        # info: files that are not records, paths that are not what they seem
        (["info", str(c / "pipe.AT2")], "FIFO"),
        (["info", str(c / "loop.AT2")], "symbolic-link loop"),
        (["info", str(c / "dangling.AT2")], "dangling symbolic link"),
        (["info", str(c / "folder.AT2")], "is a directory"),
        (["info", str(c / "empty.AT2")], "empty"),
        (["info", "/dev/null"], "character device"),
        (["info", str(c / "solo[2].AT2")], "no such file"),
        (["info", str(c / "zeros.AT2")], "is zero"),
        (["info", str(c / "dt_tiny.AT2")], "below 1e-05 s"),
        (["info", str(c / "dt_huge.AT2")], "above 0.5 s"),
        (["info", good, "--dt", "abc"], "'--dt'"),
        (["info", good, "--bogus"], "No such option"),
        # simulate: absurd system, outputs that are inputs or not files
        (["simulate", good, "--mu-s", "0.1", "--stiffness-per-mass", "1e300"], "--stiffness-per-mass 1e+300 is outside"),
        (["simulate", good, "--mu-s", "0.1", "--damping-per-mass", "1e300"], "--damping-per-mass 1e+300 is outside"),
        (["simulate", good, "--mu-s", "0.1", "--out-csv", good], "is an input"),
        (["simulate", good, "--mu-s", "0.1", "--out-csv", str(c / "alias.csv")], "is an input"),
        (["simulate", good, "--mu-s", "0.1", "--out-csv", "/dev/full"], "No space left on device"),
        (["simulate", good, "--mu-s", "0.1", "--out-csv", str(c / "folder.AT2")], "is a folder"),
        (["simulate", good], "Missing option '--mu-s'"),
        # harmonic and threshold: unbounded work refused
        (["harmonic", "--alpha", "2", "--mu-s", "0.2", "--k", "1e300"], "k = 1e+300 exceeds"),
        (["harmonic", "--alpha", "1e300", "--mu-s", "0.2"], "alpha = 1e+300 exceeds"),
        (["harmonic", "--alpha", "2", "--mu-s", "0.2", "--eta", "1e300"], "eta = 1e+300 exceeds"),
        (["threshold", "--mu-s", "0.2", "--grid", "10000000"], "4 to 20000 points"),
        (["threshold", "--mu-s", "0.2", "--alpha-max", "1e300"], "alpha_max = 1e+300"),
        # report: the record's fault, the design's fault, outputs
        (["report", good, "-d", design, "--scale-to-pga", "1e-300", "-o", str(c / "out" / "r.pdf")], "--scale-to-pga"),
        (["report", good, "-d", design, "--scale-to-pga", "100", "-o", str(c / "out" / "r.pdf")], "--scale-to-pga"),
        (["report", str(c / "zeros.AT2"), "-d", design, "-o", str(c / "out" / "r.pdf")], "is zero"),
        (["report", good, "-d", str(c / "tiny_radius.toml"), "-o", str(c / "out" / "r.pdf")], "key 'radius_m'"),
        (["report", good, "-d", str(c / "tiny_mass.toml"), "-o", str(c / "out" / "r.pdf")], "key 'mass_kg'"),
        (["report", good, "-d", str(c / "stiff.toml"), "-o", str(c / "out" / "r.pdf")], "key 'stiffness_N_per_m'"),
        (["report", good, "-d", str(c / "pipe.toml"), "-o", str(c / "out" / "r.pdf")], "FIFO"),
        (["report", good, "-d", str(c / "design_loop.toml"), "-o", str(c / "out" / "r.pdf")], "symbolic-link loop"),
        (["report", good, "-d", str(c / "design.json"), "-o", str(c / "design.pdf")], "is an input"),
        (["report", good, "-d", design, "-o", str(c / "pipe.AT2")], "must end with .pdf"),
        # regime-map
        (["regime-map", "-n", "8", "-o", str(c / "m.xyz")], "cannot tell the figure format"),
        (["regime-map", "-n", "8", "--k-max", "1e300", "--no-cache"], "the k range [0, 1e+300] must lie within"),
        (["regime-map", "--resolution", "2"], "'--resolution'"),
        # batch
        (["batch", good, "-d", str(c / "designs.toml"), "-o", str(c / "out" / "t.csv"), "--scheduler", "not a url"],
         "expected tcp://HOST:PORT"),
        (["batch", good, "-d", str(c / "designs.toml"), "-o", str(c / "out" / "t.csv"), "--grid",
          "radius_m=1:2:100000000"], "exceeds the largest batch"),
        (["batch", str(c / "record.csv"), "-d", str(c / "designs.toml"), "-o", str(c / "record.csv")], "is an input"),
        (["batch", good, "-d", str(c / "designs.toml"), "-o", str(c / "locked.csv")], "is being written by process 1"),
        (["batch", good, "-d", str(c / "pipe.toml"), "-o", str(c / "out" / "t.csv")], "FIFO"),
        (["batch", good, "-d", str(c / "designs.toml"), "-o", str(c / "out" / "t.csv"), "--jobs", "0"], "'--jobs'"),
        (["batch", good, "-d", str(c / "designs.toml"), "-o", str(c / "out" / "t.csv"), "--dt", "1e-300"],
         "below 1e-05 s"),
        # simulate on a pair: the second file's faults, mismatched components, bad µ(v), outputs that are inputs
        (["simulate", good, "--pair", str(c / "solo[2].AT2"), "--mu-s", "0.1"], "no such file"),
        (["simulate", good, "--pair", str(c / "pipe.AT2"), "--mu-s", "0.1"], "FIFO"),
        (["simulate", good, "--pair", str(c / "short.AT2"), "--mu-s", "0.1"], "different lengths"),
        (["simulate", good, "--component", "pair", "--mu-s", "0.1"], "holds one component"),
        (["simulate", good, "--pair", str(c / "short.AT2"), "--trim", "--mu-s", "0.1", "--mu-slow", "0.2",
          "--mu-fast", "0.1", "--rate-s-per-m", "20"], "must not exceed mu_fast"),
        (["simulate", good, "--pair", str(c / "short.AT2"), "--trim", "--mu-s", "0.1", "--out-csv",
          str(c / "short.AT2")], "is an input"),
        (["simulate", good, "--pair", str(c / "short.AT2"), "--mu-s", "0.1", "--radius-m", "-1"], "--radius-m"),
        # review: suite, target, parameters and outputs
        (["review", "-d", design, "--target", "example", "--suite", str(c / "empty.AT2"), "-o",
          str(c / "out" / "r.pdf")], "no pair could be read"),
        (["review", "-d", design, "--target", str(c / "nowhere.toml"), "--suite", "example", "-o",
          str(c / "out" / "r.pdf")], "no such target file"),
        (["review", "-d", str(c / "design.json"), "--target", "example", "--suite", "example", "-o",
          str(c / "design.pdf")], "is an input"),
        (["review", "-d", design, "--target", "example", "--suite", "example", "--set", "min_ratio=abc", "-o",
          str(c / "out" / "r.pdf")], "must be a number"),
        (["review", "-d", design, "--target", "example", "--suite", "example", "--code", "foo", "-o",
          str(c / "out" / "r.pdf")], "--code must be one of"),
        (["review", "-d", str(c / "pipe.toml"), "--target", "example", "--suite", "example", "-o",
          str(c / "out" / "r.pdf")], "FIFO"),
        (["review", "-d", design, "--target", "example", "--suite", "example", "--jobs", "0", "-o",
          str(c / "out" / "r.pdf")], "--jobs"),
        # issue 26: review parameters, targets and suites; units; options that contradict each other
        *[(["review", "-d", design, "--target", "example", "--suite", "example", "--set", setting, "-o",
            str(c / "out" / "r.pdf")], words) for setting, words in (
            ("usable_band_factor=0", "'usable_band_factor' = 0 is outside"),
            ("min_ratio=1e300", "'min_ratio' = 1e+300 is outside"),
            ("min_ratio=0", "'min_ratio' = 0 is outside"),
            ("grid_points=1e7", "'grid_points' = 1e+07 is outside"),
            ("grid_points=1", "'grid_points' = 1 is outside"),
            ("range_lo_factor=1e-6", "'range_lo_factor' = 1e-06 is outside"),
            ("f_ae=1e6", "'f_ae' = 1e+06 is outside"),
        )],
        (["review", "-d", design, "--target", "example", "--suite", "example", "--set", "sf_flag_low=1", "--set",
          "sf_flag_high=1", "-o", str(c / "out" / "r.pdf")], "the first must be below"),
        *[(["review", "-d", design, "--target", str(c / name), "--suite", "example", "-o", str(c / "out" / "r.pdf")],
           words) for name, words in (("t_zero.toml", "character device"), ("t_pipe.toml", "FIFO"),
                                      ("t_headers.toml", "a second header line"),
                                      ("t_tiny.toml", "'S_MS' = 1e-308 is outside"))],
        (["review", "-d", design, "--target", "example", "--suite", str(c / "suite_pipe.toml"), "-o",
          str(c / "out" / "r.pdf")], "FIFO"),
        (["review", "-d", design, "--target", "example", "--suite", str(c / "suite_names.toml"), "-o",
          str(c / "out" / "r.pdf")], "name ' a' is used twice"),
        (["info", str(c / "two_units.csv")], "ambiguous"),
        (["simulate", good, "--pair", str(c / "short.AT2"), "--trim", "--resample", "--mu-s", "0.1"],
         "give one"),
        (["batch", good, "-d", str(c / "designs.toml"), "-o", str(c / "out" / "t.csv"), "--summary",
          str(c / "out" / "t.csv")], "give each output its own file"),
        (["simulate", good, "--mu-s", "1.5"], "must be < 1"),
        (["simulate", good, "--mu-s", "0"], "--mu-s 0 is no friction at all"),
        (["simulate", good, "--mu-s", "0", "--radius-m", "2", "--pair", str(c / "x1.AT2")], "needs µs > 0"),
        (["simulate", good, "--mu-s", "0.05", "--radius-m", "2", "--mu-slow", "0.03", "--mu-fast", "1",
          "--rate-s-per-m", "20"], "mu_fast = 1 must be < 1"),
        (["simulate", good, "--mu-s", "0.05", "--radius-m", "2", "--mu-slow", "0.03", "--mu-fast", "0.08",
          "--rate-s-per-m", "0"], "rate_s_per_m must be a finite number > 0"),
        (["batch", good, "-d", str(c / "designs.toml"), "-o", str(c / "out" / "t.csv"), "--scheduler",
          "http://localhost:8786"], "expected tcp://HOST:PORT"),
        (["batch", good, "-d", str(c / "designs.toml"), "-o", str(c / "out" / "t.csv"), "--scheduler",
          "tcp://localhost"], "expected tcp://HOST:PORT"),
        (["simulate", good, "--mu-s", "0.05", "--radius-m", "2", "--mu-slow", "0.03", "--mu-fast", "0.08",
          "--rate-s-per-m", "1e8"], "exceeds 10000 s/m"),
        (["harmonic", "--alpha", "2", "--mu-s", "1e-300"], "must lie in [0.0001, 1)"),
        (["threshold", "--mu-s", "2"], "must lie in [0.0001, 1)"),
        # bench
        (["bench", "--records", str(c / "nowhere"), "--out", str(c / "out" / "bench")], "no such folder"),
        (["bench", "--repeats", "0"], "'--repeats'"),
        (["bench", "--records", str(c / "bench_records"), "--out", str(c / "bench_records")], "is an input"),
    ]


def test_every_command_refuses_the_corpus_in_one_line(corpus, tmp_path, monkeypatch):
    monkeypatch.setenv("ISOLATOR_CACHE_DIR", str(tmp_path / "cache"))
    before = _snapshot(corpus)
    full = os.stat("/dev/full")
    failures = []
    for args, words in _cases(corpus):
        start = time.perf_counter()
        result = RUNNER.invoke(app, args)
        seconds = time.perf_counter() - start
        lines = result.stderr.splitlines()
        problems = []
        if result.exit_code != 2:
            problems.append(f"exit {result.exit_code}")
        if len(lines) != 1 or not lines[0].startswith("error: "):
            problems.append(f"stderr {result.stderr!r}")
        if "Traceback" in result.stderr + result.stdout or result.exception and not isinstance(result.exception,
                                                                                               SystemExit):
            problems.append(f"exception {result.exception!r}")
        if words not in result.stderr:
            problems.append(f"{words!r} not in {result.stderr!r}")
        if seconds > TIME_BOUND_S:
            problems.append(f"{seconds:.1f} s")
        if problems:
            failures.append(f"{' '.join(args)}: {'; '.join(problems)}")
    assert failures == []
    assert _snapshot(corpus) == before  # no input changed, no output appeared among them
    assert os.stat("/dev/full").st_rdev == full.st_rdev and stat.S_ISCHR(os.stat("/dev/full").st_mode)


def test_glob_characters_read_exactly_the_file_named(corpus):
    import json

    result = RUNNER.invoke(app, ["info", str(corpus / "x[1].AT2"), "--json"])
    assert result.exit_code == 0 and result.stderr == ""
    summary = json.loads(result.stdout)
    assert (summary["npts"], summary["dt_s"]) == (300, 0.02)  # not x1.AT2's 500 × 0.01 s


def test_damaged_cache_and_parts_are_repaired_and_said(corpus, tmp_path, monkeypatch):
    monkeypatch.setenv("ISOLATOR_CACHE_DIR", str(tmp_path / "cache"))
    # a map cache entry cut in half: the map is recomputed, the table says so
    first = RUNNER.invoke(app, ["regime-map", "-n", "8", "--k-max", "2", "--alpha-max", "3"])
    assert first.exit_code == 0, first.stderr
    (entry,) = (tmp_path / "cache" / "maps").glob("map-*.npz")
    entry.write_bytes(entry.read_bytes()[:100])
    again = RUNNER.invoke(app, ["regime-map", "-n", "8", "--k-max", "2", "--alpha-max", "3"])
    assert again.exit_code == 0 and again.stderr == ""
    assert f"cached map {entry} was damaged" in again.stdout and "recomputed" in again.stdout
    # the report's map too: its table says the damaged entry was recomputed
    report = ["report", str(corpus / "good.AT2"), "-d", str(corpus / "design.toml"), "-o", str(tmp_path / "r.pdf"),
              "--map-resolution", "8", "--no-pdf"]
    assert RUNNER.invoke(app, report).exit_code == 0
    for entry in (tmp_path / "cache" / "maps").glob("map-*-refined.npz"):
        entry.write_bytes(b"PK\x03\x04 not a zip")
    result = RUNNER.invoke(app, report)
    assert result.exit_code == 0 and result.stderr == ""
    assert any(line.startswith("note") and "was damaged" in line for line in result.stdout.splitlines())
    # batch parts with a truncated line and bytes that are not UTF-8: skipped, counted, recomputed
    out = tmp_path / "t.csv"
    parts = Path(str(out) + ".parts")
    parts.mkdir()
    (parts / "part-00000000000000000001-aaaaaaaa.jsonl").write_bytes(b'{"row": {"record": "x"\n\xff\xfe\n')
    result = RUNNER.invoke(app, ["batch", str(corpus / "records"), "-d", str(corpus / "designs.toml"), "-o", str(out),
                                 "--jobs", "1"])
    assert result.exit_code == 0, result.stderr
    assert result.stderr.splitlines() == [f"note: 2 damaged line(s) in {parts} skipped (truncated, corrupt or not "
                                          "written by this user); their rows are recomputed"]
    assert result.stdout.strip().splitlines()[-1] == "1 rows, 0 failed"


def test_worker_counts_are_capped_at_the_cores_with_a_note(corpus, tmp_path, monkeypatch):
    from isolator.parallel import available_cores

    monkeypatch.setenv("ISOLATOR_CACHE_DIR", str(tmp_path / "cache"))
    result = RUNNER.invoke(app, ["batch", str(corpus / "records"), "-d", str(corpus / "designs.toml"), "-o",
                                 str(tmp_path / "t.csv"), "-j", "100000", "--no-harmonic"])
    assert result.exit_code == 0, result.stderr
    cores = available_cores()
    assert f"note: 100000 workers asked, {cores} used" in result.stderr
    assert result.stdout.strip().splitlines()[-1] == "1 rows, 0 failed"
