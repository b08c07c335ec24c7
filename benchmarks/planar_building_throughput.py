"""Throughput of the 2-D building model (issue 22): solver time per pair for 1 to 6 stories.

Prints one row per case: stories, fixed-base period along x, events, fast sub-steps (exact
propagators), series pieces, located extrema, the kernel's wall time and the process's CPU time over
the call (best of 5 each; the propagators are built by the first call and reused) on one real pair
(Superstition Hills PTS by default). The CPU time is the figure to compare on a shared machine: the
wall time grows with the load. Rerun:

    .venv/bin/python benchmarks/planar_building_throughput.py [PAIR_FOLDER]

Timings depend on the machine and its load (the kernel runs on one core).
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

from isolator.motion import read_ground_motion
from isolator.solver.planar_building import simulate_planar_building
from isolator.superstructure import Floor, Superstructure
from isolator.units import STANDARD_GRAVITY

DEFAULT_PAIR = Path(__file__).resolve().parents[2] / "shared" / "records" / "pairs" / "superstitionhills1987_PTS"


def main(folder: Path = DEFAULT_PAIR) -> None:
    motions = [read_ground_motion(f) for f in sorted(folder.glob("*.AT2"))[:2]]
    n_samples = min(m.npts for m in motions)
    ax, ay = (m.acceleration_m_s2[:n_samples] for m in motions)
    dt = motions[0].dt_s
    print(f"pair {folder.name}: {n_samples} samples × {dt:g} s; pendulum R = 2.5 m, µs = 0.06, µk = 0.05, "
          "k_y = 0.8 k_x")
    print(f"{'stories':>7} {'T1x [s]':>8} {'events':>6} {'fast':>6} {'pieces':>7} {'located':>7} {'wall [ms]':>9} "
          f"{'cpu [ms]':>8}")
    for n, stiffness_scale in ((1, 1.0), (3, 1.0), (5, 1.0), (6, 1.0), (5, 30.0)):
        floors = tuple(Floor(2.5e5, 3.5, stiffness_scale * k, 0.8 * stiffness_scale * k)
                       for k in np.linspace(9e8, 4e8, n))
        s = Superstructure(floors=floors, damping_ratio=0.05, gravity_m_s2=STANDARD_GRAVITY)
        total = 1.4 * s.mass_kg
        wall = cpu = np.inf
        for _ in range(5):
            start = time.process_time()
            r = simulate_planar_building(ax, ay, dt, superstructure=s, total_mass_kg=total,
                                         stiffness_N_per_m=total * STANDARD_GRAVITY / 2.5, mu_static=0.06,
                                         mu_kinetic=0.05)
            cpu = min(cpu, time.process_time() - start)
            wall = min(wall, r.solver_seconds)
        print(f"{n:>7} {s.fixed_base_periods_s()[0]:>8.3f} {r.n_events:>6} {r.n_fast_steps:>6} {r.n_pieces:>7} "
              f"{r.n_extrema_located:>7} {1e3 * wall:>9.1f} {1e3 * cpu:>8.1f}")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else DEFAULT_PAIR)
