"""The cost of a vertical (and of µ(v)) on the 2-D building (issue 22): the example building under APEEL2.

The README's example building (``data/example_building.toml``: 5 floors, bearing layout) on its pendulum under
the Loma Prieta APEEL2 station (133° along x, 43° along y, up; 7 165 samples × 0.005 s): the pair alone, the pair
with its vertical (N = W (1 + a_z/g)), and the pair with µ(v) (µ_slow = µk − 0.02, µ_fast = µk, a = 20 s/m).
With a vertical or µ(v) the kernel takes no fast sub-steps (the exact propagators need a constant normal force
and µ), so every sample is covered by Taylor series pieces at most THETA/ρ(A) long.  Prints per case the events,
fast sub-steps, series pieces, the solver's wall and the process's CPU time over the call (medians of
``--runs``, after one warm call).  Rerun from the repository root::

    .venv/bin/python -m benchmarks.planar_building_vertical [--runs 5] [--records ../shared/records]

Timings depend on the machine and its load (the kernel runs on one core).
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
from pathlib import Path

from isolator.design import Design
from isolator.motion import read_ground_motion
from isolator.solver.planar_building import simulate_planar_building

APEEL2 = ("lomaprieta1989_APEEL2", ("np01002p_4225a_a.smc", "np01002p_4225c_a.smc", "np01002p_4225b_a.smc"))
EXAMPLE = Path(__file__).resolve().parents[1] / "data" / "example_building.toml"


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--records", default="../shared/records")
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args(argv)
    design = Design.from_toml(EXAMPLE)
    motions = [read_ground_motion(Path(args.records) / "pairs" / APEEL2[0] / name) for name in APEEL2[1]]
    n = min(m.npts for m in motions)
    ax, ay, az = (m.acceleration_m_s2[:n] for m in motions)
    dt = motions[0].dt_s
    g = design.gravity_m_s2
    common = dict(superstructure=design.superstructure, total_mass_kg=design.mass_kg,
                  stiffness_N_per_m=design.mass_kg * g / design.radius_m, mu_static=design.mu_static,
                  pendulum=True, bearing_layout=design.bearing_layout, gravity_m_s2=g)
    cases = {
        "pair": {"mu_kinetic": design.mu_kinetic},
        "pair + vertical": {"mu_kinetic": design.mu_kinetic, "az_m_s2": az},
        "pair + µ(v)": {"mu_kinetic": None, "mu_slow": design.mu_kinetic - 0.02, "mu_fast": design.mu_kinetic,
                        "rate_s_per_m": 20.0},
    }
    print(f"example building, APEEL2 pair: {n} samples × {dt:g} s; µs = {design.mu_static:g}, "
          f"µk = {design.mu_kinetic:g}, R = {design.radius_m:g} m")
    print(f"{'case':<16} {'events':>6} {'fast':>6} {'pieces':>7} {'wall [ms]':>9} {'cpu [ms]':>8} {'peak [m]':>9}")
    base = None
    for label, extra in cases.items():
        simulate_planar_building(ax, ay, dt, **common, **extra)  # compile/load and build the propagators
        walls, cpus = [], []
        for _ in range(args.runs):
            w0, c0 = time.perf_counter(), time.process_time()
            r = simulate_planar_building(ax, ay, dt, **common, **extra)
            walls.append(time.perf_counter() - w0)
            cpus.append(time.process_time() - c0)
        wall, cpu = 1e3 * statistics.median(walls), 1e3 * statistics.median(cpus)
        base = base or cpu
        print(f"{label:<16} {r.n_events:>6} {r.n_fast_steps:>6} {r.n_pieces:>7} {wall:>9.1f} {cpu:>8.1f} "
              f"{r.peak_displacement_m:>9.4f}  (cpu {cpu / base:.2f}× the pair's; series pieces stuck/start/slide/finish "
              f"{'/'.join(str(v) for v in r.n_pieces_by_phase)})")
    print(f"load average (1, 5, 15 min): {os.getloadavg()}")


if __name__ == "__main__":
    main()
