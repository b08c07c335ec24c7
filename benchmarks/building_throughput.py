"""Throughput of the 1-D building model (issue 22): solver time per record for 1 to 6 stories.

Prints one row per case: stories, fixed-base period, sub-steps per sample, events, located extrema,
solver time (best of 5, the kernel only) and samples per second, on one real record. Rerun:

    .venv/bin/python benchmarks/building_throughput.py [RECORD.AT2]

Timings depend on the machine and its load (the kernel runs on one core).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from isolator.motion import read_ground_motion
from isolator.solver.building import simulate_building
from isolator.superstructure import Floor, Superstructure
from isolator.units import STANDARD_GRAVITY

DEFAULT_RECORD = Path(__file__).resolve().parents[2] / "shared" / "records" / "at2" / "RSN1044_NORTHR_NWH360.AT2"


def main(record: Path = DEFAULT_RECORD) -> None:
    motion = read_ground_motion(record)
    acc, dt = motion.acceleration_m_s2, motion.dt_s
    print(f"record {record.name}: {acc.size} samples × {dt:g} s; pendulum R = 2.5 m, µs = 0.06, µk = 0.05")
    print(f"{'stories':>7} {'T1 [s]':>8} {'sub':>4} {'events':>6} {'located':>7} {'solver [ms]':>11} "
          f"{'samples/s':>10}")
    for n, stiffness_scale in ((1, 1.0), (3, 1.0), (5, 1.0), (6, 1.0), (5, 30.0)):
        floors = tuple(Floor(2.5e5, 3.5, stiffness_scale * k, stiffness_scale * k)
                       for k in np.linspace(9e8, 4e8, n))
        s = Superstructure(floors=floors, damping_ratio=0.05, gravity_m_s2=STANDARD_GRAVITY)
        total = 1.4 * s.mass_kg
        best = np.inf
        for _ in range(5):
            r = simulate_building(acc, dt, superstructure=s, total_mass_kg=total,
                                  stiffness_N_per_m=total * STANDARD_GRAVITY / 2.5, mu_static=0.06, mu_kinetic=0.05)
            best = min(best, r.solver_seconds)
        print(f"{n:>7} {s.fixed_base_periods_s()[0]:>8.3f} {r.substeps_per_interval:>4} {r.n_events:>6} "
              f"{r.n_extrema_located:>7} {1e3 * best:>11.2f} {acc.size / best:>10.3g}")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else DEFAULT_RECORD)
