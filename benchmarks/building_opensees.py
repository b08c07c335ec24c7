"""The exact 1-D building against OpenSees on one real record: time and error of both, one run.

Usage::

    pip install "isolator[bench]"      # openseespy (Linux wheels need libblas3, liblapack3)
    python -m benchmarks.building_opensees   (from the repository root) [--seconds 20] [--rounds 5]
                                             [--records ../shared/records] [--json]

The building of ``isolator bench`` (:mod:`isolator.bench.building`): 5 floors of 500 t,
3.5 m stories, fixed-base T1 = 0.5 s, ζ = 5 % in every fixed-base mode, a 500 t slab on a
friction pendulum R = 2.5 m, µ = 0.06, under the first ``--seconds`` of Northridge NWH360.
Ours (``1d-building``) and OpenSees (singleFPBearing, zeroLength stories, the damping as
an exact dashpot network, Newmark + Newton at the record's dt) are timed in alternation
(``--rounds`` rounds of 5 runs of ours and 1 of OpenSees; medians); the independent
``solve_ivp`` reference runs once.  Our error is against the reference; OpenSees' against
ours.  The same numbers as the building rows of ``isolator bench``.
"""

from __future__ import annotations

import argparse
import json
import os
from pathlib import Path

from isolator.bench.building import (
    BUILDING_RECORD,
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
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args(argv)
    from isolator.motion import read_ground_motion

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
