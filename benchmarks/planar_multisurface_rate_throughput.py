"""Throughput of the 2-D µ(v) multi-surface model (``2d-multisurface+mu(v)``) on the real pairs.

Runs :func:`isolator.solver.planar_multisurface_rate.simulate_bearing_pair_rate` on every pair of
../shared/records/pairs (both horizontals, trimmed to the shorter; :data:`benchmarks.planar_throughput.SOURCES`)
for Fenz & Constantinou's triple pendulum with µ(v) on its four surfaces (R_eff = 2.1/0.3/0.3/2.1 m,
µ_slow = 0.03/0.01/0.01/0.05, µ_fast = 0.06/0.02/0.02/0.10, a = 20 s/m, d* = 0.4/0.05/0.05/0.4 m: the 1-D
model's test bearing), each pair at its own amplitude times ``--scale``, and prints per pair the samples per
second of the compiled code (solver time, median of --repeat runs), the steps, the peak, the energy balance
(|input − kinetic − stored − friction − viscous| / input) and the regimes; a pair that reaches a rim (not
modelled in the plane with µ(v)) or that the model cannot finish is reported with its one-line reason.

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.planar_multisurface_rate_throughput [--repeat 3] [--scale 1]
                                                                [--records ../shared/records] [--seconds S]
"""

from __future__ import annotations

import argparse
import statistics
from pathlib import Path

import benchmarks.planar_throughput as _records
from benchmarks.planar_throughput import SOURCES, load
from isolator.bearing import parse_bearing
from isolator.errors import DesignError, SolverError
from isolator.solver.planar_multisurface_rate import simulate_bearing_pair_rate

GEOMETRY = [(2.1, 0.4), (0.3, 0.05), (0.3, 0.05), (2.1, 0.4)]
MU_SLOW = [0.03, 0.01, 0.01, 0.05]
MU_FAST = [0.06, 0.02, 0.02, 0.10]


def rate_tfp(rate=20.0):
    """The µ(v) triple of the 1-D model's tests (Fenz & Constantinou's geometry)."""
    return parse_bearing({"type": "triple", "surface": [
        {"radius_m": r, "mu_slow": s, "mu_fast": f, "rate_s_per_m": rate, "displacement_capacity_m": d}
        for (r, d), s, f in zip(GEOMETRY, MU_SLOW, MU_FAST, strict=True)]}, DesignError)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3, help="runs per pair (median)")
    parser.add_argument("--scale", type=float, default=1.0, help="factor on both components")
    parser.add_argument("--records", default=None, help="the shared records folder (default ../shared/records)")
    parser.add_argument("--seconds", type=float, default=None, help="only the first S seconds of each pair")
    args = parser.parse_args(argv)
    if args.records:
        _records.PAIRS = Path(args.records) / "pairs"
    bearing = rate_tfp()
    print(f"{'pair':28s} {'n':>7s} {'k samples/s':>11s} {'steps':>7s} {'peak m':>8s} {'balance':>9s}  regimes")
    rates = []
    for folder in SOURCES:
        dt, ax, ay, _ = load(folder)
        if args.seconds is not None:
            n = min(ax.size, int(round(args.seconds / dt)) + 1)
            ax, ay = ax[:n], ay[:n]
        times = []
        try:
            for _ in range(args.repeat):
                res = simulate_bearing_pair_rate(args.scale * ax, args.scale * ay, dt, bearing=bearing)
                times.append(res.solver_seconds)
        except SolverError as exc:
            print(f"{folder:28s} {ax.size:7d}  not answered: {exc}")
            continue
        seconds = statistics.median(times)
        rates.append(ax.size / seconds)
        balance = abs(res.energy_balance_error_J_per_kg) / res.energy_input_J_per_kg
        print(f"{folder:28s} {ax.size:7d} {ax.size / seconds / 1e3:11.2f} {res.n_steps:7d} "
              f"{res.peak_displacement_m:8.4f} {balance:9.1e}  {','.join(res.regimes)}")
    if rates:
        print(f"median over {len(rates)} answered pairs: {statistics.median(rates) / 1e3:.2f} k samples/s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
