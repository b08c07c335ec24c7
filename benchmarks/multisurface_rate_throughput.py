"""Throughput of the µ(v) multi-surface model (1d-multisurface+mu(v)) on real records.

Runs :func:`isolator.solver.multisurface_rate.simulate_bearing_rate` for Fenz & Constantinou's
triple pendulum (R_eff = 2.1/0.3/0.3/2.1 m, d* = 0.4/0.05/0.05/0.4 m) with µ(v) on every surface
(µ_slow = 0.03/0.01/0.01/0.05, µ_fast = 0.06/0.02/0.02/0.10, rate 20 s/m) on real AT2 records of
../shared/records/at2, at their own amplitude and ×3, and prints per record the samples per second
of the compiled kernel (kernel time only, median of --repeat runs), the collocation steps, the
events, the peak, the regimes reached and the energy balance.  The constant-µ kernel
(``1d-multisurface`` at µ = µ_fast) is timed beside it on the same record.

    python benchmarks/multisurface_rate_throughput.py --repeat 3
    python benchmarks/multisurface_rate_throughput.py --quick --repeat 5   # two records
    python benchmarks/multisurface_rate_throughput.py --quick --repeat 3 --compare-newton

``--compare-newton`` times the collocation's full Newton iteration (a Jacobian per stage and iteration, the
kernel before h74) beside the default simplified one (one Jacobian per step), alternating in one process at the
same load, and prints the largest difference of the two displacement histories (a fraction of the peak).
"""

from __future__ import annotations

import argparse
import statistics
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
RECORDS = ROOT.parent / "shared" / "records" / "at2"
QUICK = ("RSN1044_NORTHR_NWH360.AT2", "elCentro.AT2")
DEFAULT = QUICK + ("IELC180.AT2", "RSN1120_KOBE_TAK000.AT2", "ARL360.at2")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="two records only")
    parser.add_argument("--repeat", type=int, default=3, help="runs per record (median)")
    parser.add_argument("--compare-newton", action="store_true",
                        help="time full Newton beside the simplified one (same runs, alternating)")
    args = parser.parse_args(argv)
    if not RECORDS.is_dir():
        print(f"no records at {RECORDS}", file=sys.stderr)
        return 2

    from isolator.bearing import parse_bearing
    from isolator.errors import DesignError, SolverError
    from isolator.motion import read_ground_motion
    from isolator.solver.multisurface import simulate_bearing
    from isolator.solver.multisurface_rate import simulate_bearing_rate

    geometry = ((2.1, 0.4), (0.3, 0.05), (0.3, 0.05), (2.1, 0.4))
    slow, fast = (0.03, 0.01, 0.01, 0.05), (0.06, 0.02, 0.02, 0.10)
    rate_tfp = parse_bearing({"type": "triple", "surface": [
        {"radius_m": r, "mu_slow": s, "mu_fast": f, "rate_s_per_m": 20.0, "displacement_capacity_m": d}
        for (r, d), s, f in zip(geometry, slow, fast, strict=True)]}, DesignError)
    const_tfp = parse_bearing({"type": "triple", "surface": [
        {"radius_m": r, "mu": f, "displacement_capacity_m": d}
        for (r, d), f in zip(geometry, fast, strict=True)]}, DesignError)
    print(f"{'record':30s} {'scale':>5s} {'samples':>7s} {'k samples/s':>11s} {'steps':>7s} {'events':>6s} "
          f"{'peak x [m]':>10s} {'balance/input':>13s} {'const M samples/s':>17s}  regimes")
    rates = []
    for name in QUICK if args.quick else DEFAULT:
        motion = read_ground_motion(RECORDS / name)
        for scale in (1.0, 3.0):
            acc = np.ascontiguousarray(motion.acceleration_m_s2 * scale)
            times, const_times, full_times = [], [], []
            try:
                for _ in range(args.repeat):
                    res = simulate_bearing_rate(acc, motion.dt_s, bearing=rate_tfp)
                    times.append(res.solver_seconds)
                    const_times.append(simulate_bearing(acc, motion.dt_s, bearing=const_tfp).solver_seconds)
                    if args.compare_newton:
                        full = simulate_bearing_rate(acc, motion.dt_s, bearing=rate_tfp, simplified_newton=False)
                        full_times.append(full.solver_seconds)
            except SolverError as error:
                print(f"{name[:30]:30s} {scale:5.1f} {acc.size:7d} stopped: {error}")
                continue
            if args.compare_newton:
                diff = float(np.max(np.abs(full.displacement_m - res.displacement_m))) / res.peak_displacement_m
                print(f"{'  full Newton':30s} {scale:5.1f} {acc.size:7d} {acc.size / statistics.median(full_times) / 1e3:11.1f} "
                      f"{full.model_reason.split('(')[-1].split()[0]:>7s} {full.n_events:6d}  max |x_full - x| / peak "
                      f"{diff:.1e}")
            rate = acc.size / statistics.median(times)
            rates.append(rate)
            steps = res.model_reason.split("(")[-1].split()[0]
            balance = abs(res.energy_balance_error_J_per_kg) / max(res.energy_input_J_per_kg, 1e-300)
            print(f"{name[:30]:30s} {scale:5.1f} {acc.size:7d} {rate / 1e3:11.1f} {steps:>7s} {res.n_events:6d} "
                  f"{res.peak_displacement_m:10.4f} {balance:13.1e} "
                  f"{acc.size / statistics.median(const_times) / 1e6:17.2f}  {' '.join(res.regimes)}")
    print(f"median {statistics.median(rates) / 1e3:.1f} k samples/s, slowest {min(rates) / 1e3:.1f} k samples/s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
