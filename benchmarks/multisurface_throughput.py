"""Throughput of the 1-D multi-surface kernel (triple friction pendulum) on real records.

Runs :func:`isolator.solver.multisurface.simulate_bearing` on every real AT2 record in
../shared/records/at2 (a synthetic record when that folder is absent) for Fenz &
Constantinou's triple pendulum (R_eff = 2.1/0.3/0.3/2.1 m, µ = 0.06/0.02/0.02/0.10,
d* = 0.4/0.05/0.05/0.4 m), each record at its own amplitude and scaled ×3 (which drives
the bearing to its rims), and prints per record the samples per second of the compiled
kernel (kernel time only, median of --repeat runs), the events and the regimes reached.

    python benchmarks/multisurface_throughput.py            # full table
    python benchmarks/multisurface_throughput.py --quick    # two records
"""

from __future__ import annotations

import argparse
import statistics
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
RECORDS = ROOT.parent / "shared" / "records" / "at2"


def load_records(quick: bool):
    """(name, acceleration m/s², dt s) of the benchmark records."""
    if RECORDS.is_dir():
        from isolator.motion import read_ground_motion

        paths = sorted(RECORDS.iterdir())
        if quick:
            paths = [p for p in paths if p.name.startswith(("RSN1044", "elCentro.AT2"))] or paths[:2]
        return [(p.name, read_ground_motion(p).acceleration_m_s2, read_ground_motion(p).dt_s) for p in paths]
    rng = np.random.default_rng(0)
    t = np.arange(0.0, 40.0, 0.01)
    acc = 3.0 * np.sin(2 * np.pi * 0.7 * t) * np.exp(-((t - 10) / 6) ** 2) + rng.normal(0, 0.8, t.size)
    return [("synthetic (no ../shared)", acc, 0.01)]


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="two records only")
    parser.add_argument("--repeat", type=int, default=15, help="runs per record (median)")
    args = parser.parse_args(argv)

    from isolator.bearing import parse_bearing
    from isolator.errors import DesignError
    from isolator.solver.multisurface import simulate_bearing

    tfp = parse_bearing({"type": "triple", "surface": [
        {"radius_m": r, "mu": m, "displacement_capacity_m": d}
        for r, m, d in ((2.1, 0.06, 0.4), (0.3, 0.02, 0.05), (0.3, 0.02, 0.05), (2.1, 0.10, 0.4))]}, DesignError)
    print(f"{'record':34s} {'scale':>5s} {'samples':>8s} {'M samples/s':>12s} {'events':>7s} "
          f"{'peak x [m]':>10s}  regimes")
    rates = []
    for name, acc, dt in load_records(args.quick):
        for scale in (1.0, 3.0):
            a = np.ascontiguousarray(acc * scale)
            simulate_bearing(a, dt, bearing=tfp)  # warm-up
            times = [simulate_bearing(a, dt, bearing=tfp).solver_seconds for _ in range(args.repeat)]
            res = simulate_bearing(a, dt, bearing=tfp)
            rate = a.size / statistics.median(times) / 1e6
            rates.append(rate)
            regimes = ",".join(res.regimes) + (" +ultimate" if res.ultimate_displacement_reached else "")
            print(f"{name[:34]:34s} {scale:5.1f} {a.size:8d} {rate:12.1f} {res.n_events:7d} "
                  f"{res.peak_displacement_m:10.4f}  {regimes}")
    print(f"median over records: {statistics.median(rates):.1f} M samples/s, slowest {min(rates):.1f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
