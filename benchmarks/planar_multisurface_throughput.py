"""Throughput of the 2-D multi-surface kernel (triple friction pendulum) on the real pairs.

Runs :func:`isolator.solver.planar_multisurface.simulate_bearing_pair` on every pair of
../shared/records/pairs (both horizontals, trimmed to the shorter) for Fenz &
Constantinou's triple pendulum (R_eff = 2.1/0.3/0.3/2.1 m, µ = 0.06/0.02/0.02/0.10,
d* = 0.4/0.05/0.05/0.4 m), each pair at its own amplitude, and prints per pair the samples
per second of the compiled kernel (kernel time only, median of --repeat runs), the DOP853
steps, the events and the regimes reached; a pair that drives a slider to its rim is
reported as such (the rim in the plane is not modelled: the run stops there).

    python -m benchmarks.planar_multisurface_throughput [--repeat 5]
"""

from __future__ import annotations

import argparse
import statistics

from benchmarks.planar_throughput import SOURCES, load


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5, help="runs per pair (median)")
    args = parser.parse_args(argv)

    from isolator.bearing import parse_bearing
    from isolator.errors import DesignError, SolverError
    from isolator.solver.planar_multisurface import simulate_bearing_pair

    tfp = parse_bearing({"type": "triple", "surface": [
        {"radius_m": r, "mu": m, "displacement_capacity_m": d}
        for r, m, d in ((2.1, 0.06, 0.4), (0.3, 0.02, 0.05), (0.3, 0.02, 0.05), (2.1, 0.10, 0.4))]}, DesignError)
    print(f"{'pair':26s} {'samples':>8s} {'M samples/s':>12s} {'steps':>7s} {'events':>7s} {'peak x [m]':>10s}  regimes")
    rates = []
    total_n = 0
    total_t = 0.0
    for folder in SOURCES:
        dt, ax, ay, _ = load(folder)
        try:
            times = []
            for _ in range(args.repeat):
                res = simulate_bearing_pair(ax, ay, dt, bearing=tfp)
                times.append(res.solver_seconds)
        except SolverError as exc:
            print(f"{folder:26s} {ax.size:8d}   {str(exc)[:70]}")
            continue
        t = statistics.median(times)
        rate = ax.size / t / 1e6
        rates.append(rate)
        total_n += ax.size
        total_t += t
        print(f"{folder:26s} {ax.size:8d} {rate:12.2f} {res.n_steps:7d} {res.n_events:7d} "
              f"{res.peak_displacement_m:10.4f}  {' '.join(res.regimes)}")
    if rates:
        print(f"median {statistics.median(rates):.2f} M samples/s, slowest {min(rates):.2f}, "
              f"all samples / all time {total_n / total_t / 1e6:.2f} M samples/s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
