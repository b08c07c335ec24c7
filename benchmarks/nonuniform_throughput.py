"""Cost of unequal sample steps in the exact 1-D kernel.

Solves one real record (RSN1004 SPV360, 9559 samples, dt 0.005 s) on its uniform
grid and with every interior sample time moved by up to ±30 % of dt (the record then
has unequal steps and takes the per-interval path of the kernel), for a friction
pendulum R = 2 m, µ = 0.06, with and without a 10 % damper; prints the samples per
second of the kernel (median of --repeat runs).  Needs ../shared/records.

    python benchmarks/nonuniform_throughput.py
"""

from __future__ import annotations

import argparse
import math
import statistics
from pathlib import Path

import numpy as np

RECORD = Path(__file__).resolve().parents[1].parent / "shared" / "records" / "at2" / "RSN1004_NORTHR_SPV360.AT2"
G = 9.80665
DESIGNS = {
    "R=2m mu=0.06": dict(mu_static=0.06, stiffness_per_mass=G / 2.0),
    "R=2m mu=0.06 +10% damper": dict(mu_static=0.06, stiffness_per_mass=G / 2.0,
                                      damping_per_mass=2 * 0.10 * math.sqrt(G / 2.0)),
}


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=21)
    args = parser.parse_args(argv)
    from isolator.motion import read_ground_motion
    from isolator.solver.record import simulate_record

    motion = read_ground_motion(RECORD)
    acc, dt = motion.acceleration_m_s2, motion.dt_s
    times = dt * np.arange(acc.size)
    times[1:-1] += np.random.default_rng(0).uniform(-0.3, 0.3, acc.size - 2) * dt
    print(f"{'design':28s} {'uniform Ms/s':>13s} {'unequal steps Ms/s':>19s}")
    for label, design in DESIGNS.items():
        uniform = statistics.median(simulate_record(acc, dt, **design).solver_seconds for _ in range(args.repeat))
        unequal = statistics.median(simulate_record(acc, time_s=times, **design).solver_seconds
                                    for _ in range(args.repeat))
        print(f"{label:28s} {acc.size / uniform / 1e6:13.1f} {acc.size / unequal / 1e6:19.1f}")


if __name__ == "__main__":
    main()
