"""The 2-D building's stop in one piece (``planar_building.STOP_PIECE``) on and off, alternated in one process.

With the flag off the kernel takes the route it replaced (the slowing piece cut at STOP_REACH r0, then a FINISH
piece with the friction frozen along e0); with it on, the slowing piece ends at the stop itself when the stop lies
within its reach (docs/building.md, "The stop in one piece").  For each case: the pieces, the stop pieces, the largest
difference of the histories (over their peaks), event times, peaks and energies between the two, and the kernel's
CPU time per call, medians of ``--runs`` calls each, the two routes alternated call by call::

    OPENBLAS_NUM_THREADS=1 .venv/bin/python -m benchmarks.planar_building_stop_piece [--records ../shared/records]
        [--runs 21]

Cases: the bench's 2-D building (5 floors, PTS 0-20 s, µ = 0.06), the same with µs = 0.072 > µk = 0.06, and
3 stories with a dashpot on Hector Mine ABY 0-30 s, and on the PTS x component with a zero second component.
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

import numpy as np

#: the histories compared, each over its own peak
_HISTORIES = ("displacement_m", "velocity_m_s", "floor_displacement_m", "floor_absolute_acceleration_m_s2",
              "superstructure_shear_N", "isolator_force_N", "overturning_moment_Nm", "energy_history_J_per_kg")


def cases(records: Path) -> dict:
    from isolator.bench.building import BUILDING_PAIR, FIXED_BASE_PERIOD_Y_S, building_case
    from isolator.motion import read_ground_motion
    from isolator.solver.planar_building import simulate_planar_building
    from isolator.superstructure import Floor, Superstructure

    _, folder, fx, fy = BUILDING_PAIR
    mx, my = (read_ground_motion(records / folder / f) for f in (fx, fy))
    keep = round(20.0 / mx.dt_s) + 1
    bench = building_case("bench", mx.acceleration_m_s2[:keep], mx.dt_s, acceleration_y_m_s2=my.acceleration_m_s2[:keep],
                          period_y_s=FIXED_BASE_PERIOD_Y_S)

    def bench_mu(mu_s, mu_k):
        return lambda: simulate_planar_building(
            bench.acceleration_m_s2, bench.acceleration_y_m_s2, bench.dt_s, superstructure=bench.superstructure,
            total_mass_kg=bench.total_mass_kg, stiffness_N_per_m=bench.isolator_stiffness_N_per_m, mu_static=mu_s,
            mu_kinetic=mu_k, gravity_m_s2=bench.gravity_m_s2)

    structure = Superstructure(floors=tuple(Floor(3e5, 3.5, k, 0.8 * k) for k in (8e8, 6e8, 4e8)), damping_ratio=0.05,
                               gravity_m_s2=9.80665)
    total = 1.4 * structure.mass_kg

    def three(ax, ay, dt, mu_s, mu_k):
        return lambda: simulate_planar_building(ax, ay, dt, superstructure=structure, total_mass_kg=total,
                                                stiffness_N_per_m=total * 9.80665 / 2.5, mu_static=mu_s,
                                                mu_kinetic=mu_k, damping_Ns_per_m=2e5)

    files = sorted((records / "pairs" / "hectormine1999_ABY").glob("*.AT2"))[:2]
    ax, ay = (read_ground_motion(f) for f in files)
    n = round(30.0 / ax.dt_s) + 1
    pts_x = bench.acceleration_m_s2
    return {
        "bench, µs = µk = 0.06": bench_mu(bench.mu, bench.mu),
        "bench, µs 0.072 > µk 0.06": bench_mu(0.072, 0.06),
        "3 stories + dashpot, ABY 0-30 s": three(ax.acceleration_m_s2[:n], ay.acceleration_m_s2[:n], ax.dt_s, 0.06, 0.05),
        "3 stories + dashpot, PTS x, zero y": three(pts_x, np.zeros_like(pts_x), bench.dt_s, 0.03, 0.02),
    }


def difference(new, old) -> str:
    hist = max(float(np.max(np.abs(getattr(new, k) - getattr(old, k))) / max(np.max(np.abs(getattr(old, k))), 1e-300))
               for k in _HISTORIES)
    same_events = new.event_names == old.event_names
    times = float(np.max(np.abs(new.event_time_s - old.event_time_s))) if same_events and new.n_events else 0.0
    peaks = float(np.max(np.abs(new.peak_resultants - old.peak_resultants) / np.abs(old.peak_resultants)))
    e_in = old.energy_input_J_per_kg
    energies = max(abs(getattr(new, k) - getattr(old, k)) for k in (
        "energy_input_J_per_kg", "energy_friction_J_per_kg", "energy_viscous_J_per_kg")) / e_in
    return (f"events {'alike' if same_events else 'DIFFER'} ({times:.1e} s), histories {hist:.1e}, peaks {peaks:.1e}, "
            f"energies {energies:.1e} of the input, balance {old.energy_balance_error_J_per_kg / e_in:.1e} -> "
            f"{new.energy_balance_error_J_per_kg / e_in:.1e}")


def alternate(records: Path, runs: int, name: str, off, on, describe) -> None:
    """Each case of :func:`cases` with ``planar_building.<name>`` set to ``off`` and ``on``: the answers' differences,
    ``describe(old, new)``'s counts and the CPU per call, the two settings alternated call by call (medians of
    ``runs``); the setting is left at ``on``."""
    from isolator.solver import planar_building

    for label, run in cases(records).items():
        results = {}
        for value in (off, on):
            setattr(planar_building, name, value)
            results[value] = run()
        old, new = results[off], results[on]
        print(f"{label}: {describe(old, new)}; {difference(new, old)}")
        times = {off: [], on: []}
        for k in range(runs):
            for value in ((off, on) if k % 2 == 0 else (on, off)):
                setattr(planar_building, name, value)
                start = time.process_time()
                run()
                times[value].append(time.process_time() - start)
        ratio = float(np.median(np.array(times[on]) / np.array(times[off])))
        print(f"    CPU per call, medians of {runs}: {name} = {off}: {1e3 * np.median(times[off]):.2f} ms, {on}: "
              f"{1e3 * np.median(times[on]):.2f} ms, ratio {ratio:.3f}; load {os.getloadavg()[0]:.1f}", flush=True)
    setattr(planar_building, name, on)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--records", default="../shared/records")
    parser.add_argument("--runs", type=int, default=21)
    args = parser.parse_args(argv)

    def describe(old, new):
        return (f"pieces {old.n_pieces} -> {new.n_pieces} (FINISH {old.n_pieces_by_phase[3]} -> "
                f"{new.n_pieces_by_phase[3]}, stop pieces {new.n_stop_pieces})")

    alternate(Path(args.records), args.runs, "STOP_PIECE", False, True, describe)


if __name__ == "__main__":
    main()
