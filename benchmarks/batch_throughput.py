"""Batch throughput: 18 real records × a 10 × 10 friction-pendulum grid (1,800 analyses) on 2 jobs.

Runs ``isolator batch`` as a user would (a fresh process each time, from launch to exit),
three times, and prints the median wall time and where the time goes: reading (file,
units, intensity measures and the D5-95 window, once per record), solving (the exact
record solver's kernel, its ``solver_seconds``), the rest of each row (simulate_record's
set-up, the record classification, the design, the row: ``row_seconds`` minus the
solver and harmonic times), the harmonic classification at the equivalent point, and writing the
table.  Reading/solving/harmonic are summed over the workers from the table's timing
columns (wall-clock seconds inside the workers, so they grow when other jobs share the
cores); plan/compute/write are the batch's own wall-clock phases.

    .venv/bin/python benchmarks/batch_throughput.py [--jobs 2] [--repeat 3] [--no-harmonic]

The 18 records: the 12 AT2 files of ../shared/records/at2, and from ../shared/records/other
the USGS SMC file, the four K-NET files (AOM008 NS/EW/UD, test.knet) and the Chi-Chi CSV
(which does not state its units: ``--units g``, used only for files that do not state theirs).
"""

from __future__ import annotations

import argparse
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pandas as pd

ROOT = Path(__file__).resolve().parents[1]
RECORDS = ROOT.parent / "shared" / "records"
OTHER = ["0111a.smc", "AOM0081801241951.NS", "AOM0081801241951.EW", "AOM0081801241951.UD", "test.knet",
         "Chi-Chi_1999_TCU068-090.csv"]
DESIGN = """[[design]]
name = "FPS"
mass_kg = 250000.0
radius_m = 2.0
mu_static = 0.06
"""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--no-harmonic", action="store_true", help="pass --no-harmonic to the batch")
    args = parser.parse_args()
    records = sorted(str(p) for p in (RECORDS / "at2").iterdir()) + [str(RECORDS / "other" / n) for n in OTHER]
    assert len(records) == 18, records
    isolator = str(Path(sys.executable).with_name("isolator"))
    walls, phases, splits = [], [], []
    with tempfile.TemporaryDirectory() as tmp:
        designs = Path(tmp) / "designs.toml"
        designs.write_text(DESIGN)
        for run in range(args.repeat):
            out = Path(tmp) / f"run{run}.csv"
            command = [isolator, "batch", *records, "--designs", str(designs), "--grid", "radius_m=1:4:10",
                       "--grid", "mu_static=0.03:0.12:10", "--units", "g", "-o", str(out), "--jobs", str(args.jobs)]
            command += ["--no-harmonic"] if args.no_harmonic else []
            start = time.perf_counter()
            done = subprocess.run(command, capture_output=True, text=True)
            walls.append(time.perf_counter() - start)
            if done.returncode != 0:
                sys.exit(f"batch failed ({done.returncode}): {done.stdout}{done.stderr}")
            found = re.search(r"plan ([\d.e+-]+) s, compute ([\d.e+-]+) s, write ([\d.e+-]+) s", done.stdout)
            phases.append(tuple(float(x) for x in found.groups()))
            table = pd.read_csv(out)
            assert len(table) == 1800 and (table["error"].isna() | (table["error"] == "")).all()
            other = table["row_seconds"] - table["solver_seconds"] - table["harmonic_seconds"]
            splits.append((table.groupby("record")["read_seconds"].first().sum(), table["solver_seconds"].sum(),
                           other.sum(), table["harmonic_seconds"].sum(),
                           int((table["harmonic_seconds"] == 0).sum())))
    median = statistics.median
    print(f"batch: 18 records x 100 designs = 1800 analyses, --jobs {args.jobs}, {args.repeat} runs"
          + (", --no-harmonic" if args.no_harmonic else ""))
    print(f"{'':34s}{'median':>9s}   runs")
    print(f"{'wall, launch to exit [s]':34s}{median(walls):9.2f}   " + " ".join(f"{w:.2f}" for w in walls))
    for i, name in enumerate(("plan (expand, resume check)", "compute (pool + tasks)", "write table")):
        values = [p[i] for p in phases]
        print(f"{name + ' [s]':34s}{median(values):9.3f}   " + " ".join(f"{v:.3f}" for v in values))
    print("seconds inside the workers (wall clock, summed over workers):")
    for i, name in enumerate(("read (file, units, IMs, D5-95)", "solve (record solver kernel)",
                              "set-up + record classification", "harmonic classification")):
        values = [s[i] for s in splits]
        print(f"  {name + ' [s]':33s}{median(values):9.3f}   " + " ".join(f"{v:.3f}" for v in values))
    if not args.no_harmonic:
        print(f"  harmonic cache hits: {splits[-1][4]} of 1800 rows")
    print(f"throughput: {1800 / median(walls):.0f} analyses/s (wall, launch to exit)")


if __name__ == "__main__":
    main()
