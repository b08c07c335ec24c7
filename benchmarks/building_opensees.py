"""The exact building against OpenSees on a real record (1-D) or a real pair (2-D): time and error of both, one run.

Usage::

    pip install "isolator[bench]"      # openseespy (Linux wheels need libblas3, liblapack3)
    python -m benchmarks.building_opensees   (from the repository root) [--seconds 20] [--rounds 5]
                                             [--pair] [--records ../shared/records] [--json]

The building of ``isolator bench`` (:mod:`isolator.bench.building`): 5 floors of 500 t,
3.5 m stories, fixed-base T1 = 0.5 s (along y in 2-D: 0.4 s), ζ = 5 % in every fixed-base
mode, a 500 t slab on a friction pendulum R = 2.5 m, µ = 0.06, under the first ``--seconds``
of Northridge NWH360, or with ``--pair`` of the Superstition Hills PTS pair (PTS225 along x,
PTS315 along y).  Ours (``1d-building`` / ``2d-building``) and OpenSees (singleFPBearing,
zeroLength stories, the damping as an exact dashpot network, Newmark + Newton at the record's
dt; a 3-D model in both cases) are timed in alternation (``--rounds`` rounds of 5 runs of ours
and 1 of OpenSees; medians); the independent ``solve_ivp`` reference runs once.  Our error is
against the reference; OpenSees' against ours (against the reference when ours is not
available).  The same numbers as the building rows of ``isolator bench``.
"""

from __future__ import annotations

import argparse
import json
import os
from pathlib import Path

from isolator.bench.building import (
    BUILDING_PAIR,
    BUILDING_RECORD,
    FIXED_BASE_PERIOD_Y_S,
    building_case,
    building_markdown,
    building_summary,
    run_building_case,
)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--records", default="../shared/records")
    parser.add_argument("--seconds", type=float, default=20.0)
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--pair", action="store_true", help="the 2-D building under the PTS pair")
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args(argv)
    from isolator.motion import read_ground_motion

    if args.pair:
        label, folder, fx, fy = BUILDING_PAIR
        mx, my = (read_ground_motion(Path(args.records) / folder / f) for f in (fx, fy))
        keep = round(args.seconds / mx.dt_s) + 1
        case = building_case(f"2-D building {label} 0-{args.seconds:g} s", mx.acceleration_m_s2[:keep], mx.dt_s,
                             acceleration_y_m_s2=my.acceleration_m_s2[:keep], period_y_s=FIXED_BASE_PERIOD_Y_S)
    else:
        label, rel = BUILDING_RECORD
        motion = read_ground_motion(Path(args.records) / rel)
        acc = motion.acceleration_m_s2[:round(args.seconds / motion.dt_s) + 1]
        case = building_case(f"building {label} 0-{args.seconds:g} s", acc, motion.dt_s)
    result = run_building_case(case, rounds=args.rounds)
    if args.json:
        print(json.dumps(result, indent=1))
        return
    print(building_markdown([result]))
    for line in building_summary([result]):
        print(line)
    print(f"load average (1, 5, 15 min): {os.getloadavg()}")


if __name__ == "__main__":
    main()
