"""The 2-D multi-surface event kernel's START → Cartesian hand-over speed: accuracy and cost on the real pairs.

After a break-away the kernel follows the departure in its START form and hands over to Cartesian coordinates once
the speed reaches ``R_SWITCH_MULTI_FACTOR`` × the speed scale (:mod:`isolator.solver.planar_multisurface`).  For
each pair of ``../shared/records/pairs`` under Fenz & Constantinou's triple pendulum, this runs the event kernel with
the hand-over at each ``--factors`` value and prints its largest history distance, as a fraction of the peak, from
the same kernel with the hand-over and its lowest speed (``R_SWITCH_MULTI_LO_FACTOR``) both at ``--reference`` and rtol
1e-13, and its CPU median (docs/multisurface.md, "The START form's hand-over")::

    OPENBLAS_NUM_THREADS=1 .venv/bin/python -m benchmarks.planar_multisurface_handover \\
        [--records ../shared/records] [--factors 1e-3 1e-4 1e-5] [--reference 1e-6] [--repeat 3] [PAIR ...]

Pairs that reach a rim (the event kernel has none) are reported as such.
"""

from __future__ import annotations

import argparse
import statistics
import time
from pathlib import Path

import numpy as np

import benchmarks.planar_throughput as _records
from benchmarks.planar_throughput import SOURCES, load


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("pairs", nargs="*", help="only the pairs whose folder name contains one of these")
    parser.add_argument("--records", help="the records folder (holding pairs/); default: ../shared/records")
    parser.add_argument("--factors", type=float, nargs="+", default=[1e-3, 1e-4, 1e-5])
    parser.add_argument("--reference", type=float, default=1e-6, help="the reference's hand-over factor")
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args(argv)
    if args.records:
        _records.PAIRS = Path(args.records) / "pairs"

    import isolator.solver.planar_multisurface as pm
    from isolator.bearing import parse_bearing
    from isolator.errors import DesignError, SolverError

    tfp = parse_bearing({"type": "triple", "surface": [
        {"radius_m": r, "mu": m, "displacement_capacity_m": d}
        for r, m, d in ((2.1, 0.06, 0.4), (0.3, 0.02, 0.05), (0.3, 0.02, 0.05), (2.1, 0.10, 0.4))]}, DesignError)
    default = pm.R_SWITCH_MULTI_FACTOR
    default_lo = pm.R_SWITCH_MULTI_LO_FACTOR
    print(f"hand-over factor now {default:g} (lowest speed {default_lo:g}); reference: both at "
          f"{min(default_lo, args.reference):g}/{args.reference:g}, rtol 1e-13; "
          "per factor: distance / peak, CPU median [ms]")
    try:
        for folder in SOURCES:
            if args.pairs and not any(p in folder for p in args.pairs):
                continue
            dt, ax, ay, _ = load(folder)

            def run(factor, rtol=pm.DEFAULT_RTOL, lo=default_lo, ax=ax, ay=ay, dt=dt):
                pm.R_SWITCH_MULTI_FACTOR = factor
                pm.R_SWITCH_MULTI_LO_FACTOR = lo
                started = time.process_time()
                result = pm.simulate_bearing_pair(ax, ay, dt, bearing=tfp, method="events", rtol=rtol)
                return result, time.process_time() - started

            try:
                reference, _ = run(args.reference, 1e-13, min(default_lo, args.reference))
            except SolverError as err:
                print(f"{folder:28s} {err}")
                continue
            cells = []
            for factor in args.factors:
                times = []
                for _ in range(args.repeat):
                    result, seconds = run(factor)
                    times.append(seconds)
                apart = np.max(np.abs(result.displacement_m - reference.displacement_m))
                cells.append(f"{factor:g}: {apart / reference.peak_displacement_m:.1e}, "
                             f"{1e3 * statistics.median(times):.1f} ms")
            print(f"{folder:28s} " + " | ".join(cells), flush=True)
    finally:
        pm.R_SWITCH_MULTI_FACTOR = default
        pm.R_SWITCH_MULTI_LO_FACTOR = default_lo
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
