"""Throughput of the compiled record kernel against the same algorithm in pure Python.

Runs the exact solver on every real AT2 record in ../shared/records/at2 (or on a
synthetic record when that folder is absent) for a typical friction pendulum
(R = 2 m, µ = 0.06, with and without a 10 % damper) and prints, per record, the
samples per second of the compiled kernel (median of --repeat runs, kernel time
only) and of the very same code with numba's JIT disabled (NUMBA_DISABLE_JIT=1, in
a subprocess started by this script, median of --python-repeat runs).

    python benchmarks/kernel_throughput.py            # full table
    python benchmarks/kernel_throughput.py --quick    # two records
    python benchmarks/kernel_throughput.py --no-python  # compiled kernel only
"""

from __future__ import annotations

import argparse
import json
import math
import os
import statistics
import subprocess
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
RECORDS = ROOT.parent / "shared" / "records" / "at2"
from isolator.units import STANDARD_GRAVITY as G  # noqa: E402

RADIUS_M = 2.0
MU = 0.06
DESIGNS = {
    "R=2m mu=0.06": dict(mu_static=MU, stiffness_per_mass=G / RADIUS_M),
    "R=2m mu=0.06 +10% damper": dict(mu_static=MU, stiffness_per_mass=G / RADIUS_M,
                                      damping_per_mass=2 * 0.10 * math.sqrt(G / RADIUS_M)),
}


def load_records(quick: bool):
    """(name, acceleration m/s², dt s) of the benchmark records."""
    if RECORDS.is_dir():
        from isolator.motion import read_ground_motion

        paths = sorted(RECORDS.iterdir())
        if quick:
            paths = [p for p in paths if p.name.startswith(("RSN1044", "elCentro.AT2"))] or paths[:2]
        out = []
        for path in paths:
            motion = read_ground_motion(path)
            out.append((path.name, motion.acceleration_m_s2, motion.dt_s))
        return out
    rng = np.random.default_rng(0)
    t = np.arange(0.0, 40.0, 0.01)
    acc = 3.0 * np.sin(2 * np.pi * 0.7 * t) * np.exp(-((t - 10) / 6) ** 2) + rng.normal(0, 0.8, t.size)
    return [("synthetic (no ../shared)", acc, 0.01)]


def time_records(records, design, repeat):
    """Median kernel seconds per record for one design."""
    from isolator.solver.record import simulate_record
    from isolator.solver.system import System

    system = System(**design)
    rows = []
    for name, acc, dt in records:
        result = simulate_record(acc, dt, system=system)
        seconds = statistics.median(simulate_record(acc, dt, system=system).solver_seconds for _ in range(repeat))
        rows.append({"record": name, "npts": int(acc.size), "events": result.n_events, "seconds": seconds})
    return rows


def _python_columns(n: float, python_s: float, compiled_s: float) -> str:
    """The pure-Python throughput and the speed-up, or dashes when not measured (--no-python)."""
    if math.isnan(python_s):
        return f"{'-':>12s} {'-':>9s}"
    return f"{n / python_s / 1e6:12.3f} {python_s / compiled_s:8.0f}x"


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--repeat", type=int, default=21)
    parser.add_argument("--python-repeat", type=int, default=3)
    parser.add_argument("--no-python", action="store_true", help="skip the pure-Python comparison")
    parser.add_argument("--_python-worker", dest="python_worker", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    records = load_records(args.quick)
    if args.python_worker:
        result = {label: time_records(records, design, args.python_repeat) for label, design in DESIGNS.items()}
        print(json.dumps(result))
        return
    env = dict(os.environ, NUMBA_DISABLE_JIT="1")
    cmd = [sys.executable, __file__, "--_python-worker", "--python-repeat", str(args.python_repeat)]
    if args.quick:
        cmd.append("--quick")
    compiled = {label: time_records(records, design, args.repeat) for label, design in DESIGNS.items()}
    if args.no_python:
        python = {label: [{"seconds": math.nan}] * len(rows) for label, rows in compiled.items()}
    else:
        python = json.loads(subprocess.run(cmd, env=env, check=True, capture_output=True, text=True).stdout)
    for label in DESIGNS:
        print(f"\n{label}")
        print(f"{'record':34s} {'npts':>6s} {'events':>6s} {'compiled Ms/s':>14s} {'python Ms/s':>12s} "
              f"{'speed-up':>9s}")
        total_n = total_c = total_p = 0.0
        for c_row, p_row in zip(compiled[label], python[label], strict=False):
            n = c_row["npts"]
            total_n += n
            total_c += c_row["seconds"]
            total_p += p_row["seconds"]
            print(f"{c_row['record']:34s} {n:6d} {c_row['events']:6d} {n / c_row['seconds'] / 1e6:14.1f} "
                  + _python_columns(n, p_row["seconds"], c_row["seconds"]))
        print(f"{'all records':34s} {int(total_n):6d} {'':6s} {total_n / total_c / 1e6:14.1f} "
              + _python_columns(total_n, total_p, total_c))


if __name__ == "__main__":
    main()
