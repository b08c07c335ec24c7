"""Throughput of the 2-D building model (issue 22): solver time per pair for 1 to 6 stories.

Prints one row per case: stories, fixed-base period along x, events, fast sub-steps (exact
propagators), series pieces, located extrema, the kernel's wall time and the process's CPU time over
the call (best of 5 each; the propagators are built by the first call and reused) on one real pair
(Superstition Hills PTS by default). The CPU time is the figure to compare on a shared machine: the
wall time grows with the load. Rerun:

    .venv/bin/python benchmarks/planar_building_throughput.py [PAIR_FOLDER]

``--profile`` instead splits the kernel time of the bench's 2-D building (``isolator bench``, the OpenSees
comparison: 5 floors, PTS 0-20 s) into fast sub-steps and series pieces by phase (medians of ``--runs``)::

    OPENBLAS_NUM_THREADS=1 .venv/bin/python -m benchmarks.planar_building_throughput --profile [--runs 7]
        [--no-departure-series]

(``--no-departure-series``: the departures from rest by START and series in time, as before the departure
series; the same answer to 1e-10, docs/building.md.)

The split is a linear model, not an instrumented count: the same building with µ = 0.95 never slides and runs
fast sub-steps only (stuck), which gives a stuck sub-step's cost; the rest of the bench case's kernel time is
charged to its series pieces and sliding sub-steps (a sliding sub-step costs about twice a stuck one,
docs/building.md), so the per-piece figure printed is a range.

Timings depend on the machine and its load (the kernel runs on one core).
"""

from __future__ import annotations

import argparse
import os
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


def _bench_case(records: Path):
    """The bench's 2-D building case (:mod:`isolator.bench.building`): PTS 0-20 s, 5 floors."""
    from isolator.bench.building import BUILDING_PAIR, FIXED_BASE_PERIOD_Y_S, building_case

    _, folder, fx, fy = BUILDING_PAIR
    mx, my = (read_ground_motion(records / folder / f) for f in (fx, fy))
    keep = round(20.0 / mx.dt_s) + 1
    return building_case("2-D building PTS 0-20 s", mx.acceleration_m_s2[:keep], mx.dt_s,
                         acceleration_y_m_s2=my.acceleration_m_s2[:keep], period_y_s=FIXED_BASE_PERIOD_Y_S)


def _kernel_runs(case, mu: float, runs: int):
    """Median kernel wall time [s] and the last response of ``runs`` calls (the first call builds the tables)."""
    kernel = []
    for _ in range(runs + 1):
        r = simulate_planar_building(case.acceleration_m_s2, case.acceleration_y_m_s2, case.dt_s,
                                     superstructure=case.superstructure, total_mass_kg=case.total_mass_kg,
                                     stiffness_N_per_m=case.isolator_stiffness_N_per_m, mu_static=mu, mu_kinetic=mu,
                                     gravity_m_s2=case.gravity_m_s2)
        kernel.append(r.solver_seconds)
    return float(np.median(kernel[1:])), r


def profile(records: Path, runs: int) -> None:
    """Where the bench case's kernel time goes (module docstring)."""
    case = _bench_case(records)
    t_case, r = _kernel_runs(case, case.mu, runs)
    t_stuck, r_stuck = _kernel_runs(case, 0.95, runs)
    per_stuck = t_stuck / max(r_stuck.n_fast_steps, 1)
    stuck, start, slide, finish, approach, depart = r.n_pieces_by_phase
    stops = int(np.count_nonzero(r.event_kind == 1)) + int(np.count_nonzero(r.event_kind == 2))
    print(f"{case.name}: {case.acceleration_m_s2.size} samples, µ = {case.mu}, {r.n_events} events, "
          f"peak {r.peak_displacement_m:.6f} m")
    print(f"kernel {1e3 * t_case:.1f} ms (median of {runs}); {r.n_fast_steps} fast sub-steps, {r.n_pieces} series "
          f"pieces (stuck {stuck}, leaving rest by the departure series {depart}, by START {start}, sliding "
          f"{slide}, finishing a stop {finish}, in ln s {approach}; "
          f"{(depart + start + slide + finish + approach) / max(stops, 1):.1f} pieces per slide, departure to stop, "
          f"over {stops} stops); fast "
          f"sub-steps refused {r.n_fast_refused} (series not at rounding, end check, event, V = 0); extrema "
          f"located {r.n_extrema_located}")
    print(f"never sliding (µ = 0.95): kernel {1e3 * t_stuck:.1f} ms for {r_stuck.n_fast_steps} stuck sub-steps = "
          f"{1e6 * per_stuck:.1f} µs each")
    for factor, label in ((1.0, "stuck"), (2.0, "sliding")):
        fast = factor * per_stuck * r.n_fast_steps
        piece = (t_case - fast) / max(r.n_pieces, 1)
        print(f"  sub-steps at the {label} cost: {1e3 * fast:.1f} ms; series pieces {1e3 * (t_case - fast):.1f} ms "
              f"({100 * (t_case - fast) / t_case:.0f} %), {1e6 * piece:.1f} µs per piece")
    print(f"load average (1, 5, 15 min): {os.getloadavg()}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("pair", nargs="?", type=Path, default=DEFAULT_PAIR)
    parser.add_argument("--profile", action="store_true", help="split the bench case's kernel time")
    parser.add_argument("--records", type=Path, default=DEFAULT_PAIR.parents[1])
    parser.add_argument("--runs", type=int, default=7)
    parser.add_argument("--no-departure-series", action="store_true",
                        help="leave rest by START and series in time (planar_building.DEPARTURE_SERIES = False)")
    args = parser.parse_args()
    if args.no_departure_series:
        import isolator.solver.planar_building as planar_building

        planar_building.DEPARTURE_SERIES = False
    if args.profile:
        profile(args.records, args.runs)
    else:
        main(args.pair)
