"""The 2-D building on a double pendulum against the exact 1-D building, step_tol by step_tol, on one real record.

Usage::

    python -m benchmarks.building_tolerance_sweep [--tols 1e-9,5e-10,4e-10,3e-10] [--folder iwatemiyagi2008_AOM017]
                                                  [--records ../shared/records/pairs] [--seconds 8] [--scale 1.5]

The case of h174/h200/h214 (docs/building.md): the folder's first horizontal component, SECONDS from 1 s before its
peak, ×SCALE, along x; a one-story building (4e5 kg, 3e8 N/m, ζ 0.05) on the double [(R 2.5 m, µ 0.04, d 0.3 m),
(1.5, 0.07, 0.3)], 6e5 kg in all, a dashpot of 5e4 N s/m.  Prints, per step_tol, the `2d-building-multisurface`
history error over the exact `1d-building-multisurface` peak, its steps, CPU time and slip time, and the first sample
where the error passes 10 × step_tol of the peak.  docs/building.md ("A tighter step_tol gives a worse answer")
quotes its output: on AOM017 the error grows from 1.9e-9 at 1e-9 to 0.2 at 3e-10 (the departure from rest).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

from isolator.motion.pair import read_ground_motion_pair
from isolator.solver import planar_building_multisurface as pbm
from isolator.solver.building_multisurface import simulate_building_bearing
from tests.solver.test_building import make_superstructure
from tests.solver.test_building_multisurface import bearing

#: files of a folder of ../shared/records/pairs that are not its first two sorted files
COMPONENTS = {"iwatemiyagi2008_AOM017": (".EW", ".NS"),
              "lomaprieta1989_APEEL2": ("np01002p_4225a_a.smc", "np01002p_4225c_a.smc")}


def components(folder: Path) -> list[Path]:
    """The folder's two horizontal components (one file: that file)."""
    files = sorted(p for p in folder.iterdir() if p.is_file())
    named = COMPONENTS.get(folder.name)
    if named and named[0].startswith("."):
        return [folder / (files[0].stem + suffix) for suffix in named]
    if named:
        return [folder / name for name in named]
    return files[:2]


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--tols", default="1e-9,5e-10,4e-10,3e-10")
    parser.add_argument("--folder", default="iwatemiyagi2008_AOM017")
    parser.add_argument("--records", default=str(Path(__file__).resolve().parents[1].parent / "shared/records/pairs"))
    parser.add_argument("--seconds", type=float, default=8.0)
    parser.add_argument("--scale", type=float, default=1.5)
    args = parser.parse_args(argv)
    folder = Path(args.records) / args.folder
    if not folder.is_dir():
        print(f"error: {folder}: no such folder of a record pair (give --records)", file=sys.stderr)
        return 2
    try:
        tols = [float(text) for text in args.tols.split(",")]
    except ValueError:
        print(f"error: --tols {args.tols!r}: numbers separated by commas", file=sys.stderr)
        return 2
    pair = read_ground_motion_pair(*components(folder)[:2], trim=True)
    a = np.asarray(pair.x.acceleration_m_s2, dtype=float)
    dt = pair.dt_s
    start = max(0, int(np.argmax(np.abs(a))) - int(round(1.0 / dt)))
    acc = args.scale * a[start:start + int(round(args.seconds / dt)) + 1]
    story = make_superstructure([4e5], [3e8], 0.05)
    double = bearing("double", [(2.5, 0.04, 0.3), (1.5, 0.07, 0.3)])
    exact = simulate_building_bearing(acc, dt, superstructure=story, bearing=double, total_mass_kg=6e5,
                                      damping_Ns_per_m=5e4)
    peak = float(np.max(np.abs(exact.displacement_m)))
    print(f"{folder.name} ×{args.scale:g}, {acc.size} samples of {dt:g} s; exact: peak {peak:.4g} m, slip "
          f"{exact.slip_time_s:.6g} s")
    for tol in tols:
        clock = time.process_time()
        plane = pbm.simulate_building_bearing_pair(acc, 0 * acc, dt, superstructure=story, bearing=double,
                                                   total_mass_kg=6e5, damping_Ns_per_m=5e4, step_tol=tol)
        cpu = time.process_time() - clock
        error = np.abs(plane.displacement_m[:, 0] - exact.displacement_m)
        over = np.flatnonzero(error > 10 * tol * peak)
        first = f"t = {over[0] * dt:.4g} s" if over.size else "none"
        print(f"step_tol {tol:.0e}: error {error.max() / peak:.3e} of the peak, {plane.n_steps} steps, {cpu:.2f} s "
              f"CPU, slip {plane.slip_time_s:.6g} s; first sample over 10 step_tol: {first}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
