"""Cost of one DOP853 step of the planar engine, per form of the motion, in isolation.

Usage (from the repository root)::

    python -m benchmarks.planar_step [--steps 200000] [--repeat 5]

Times ``isolator.solver.planar_dop853.dop853_step`` called in a compiled loop on a fixed
state (a friction pendulum R = 2 m, µ = 0.06, a ground acceleration ramp), the best of
``--repeat`` runs: the floor of what a step costs, without the record loop around it.
docs/performance.md quotes its output.
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from numba import njit

from isolator.solver import planar_rk as rk
from isolator.solver.planar_dop853 import dop853_step

FORMS = {  # name: (mode, x, state)
    "Cartesian": (rk.CARTESIAN, 0.0, [0.01, 0.02, 0.1, 0.05, 0.0, 0.0, 0.0, 0.0]),
    "POLAR": (rk.POLAR, 0.0, [0.01, 0.02, 0.8, 0.6, 0.0, 0.0, 0.0, 0.1]),
    "START": (rk.START, 0.0, [0.01, 0.02, 0.01, 0.0, 0.0, 0.0, 0.0, 0.0]),
}


@njit(cache=False)
def _loop(mode, x, y, prm, frc, h, n):
    f = np.zeros(rk.NSTATE)
    ynew = np.zeros(rk.NSTATE)
    fnew = np.zeros(rk.NSTATE)
    atol = np.full(rk.NSTATE, 1e-13)
    atol[7] = np.inf
    rk.rhs(mode, x, y, prm, frc, f)
    total = 0.0
    for _ in range(n):
        _, err = dop853_step(mode, x, y, f, h, prm, frc, ynew, fnew, atol, 1e-11)
        total += err
    return total


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=200_000)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args(argv)
    prm = np.zeros(rk.P_SIZE)
    prm[rk.P_MU_S] = prm[rk.P_MU_K] = 0.06
    prm[rk.P_INV_R] = 0.5
    prm[rk.P_PENDULUM] = 1.0
    frc = np.array([1.0, 10.0, 0.5, -3.0, 9.80665, 0.0, 1.0])
    print(f"one DOP853 step, best of {args.repeat} runs of {args.steps} steps")
    for name, (mode, x, state) in FORMS.items():
        y = np.array(state)
        _loop(mode, x, y, prm, frc, 1e-3, 10)
        best = min(_timed(mode, x, y, prm, frc, args.steps) for _ in range(args.repeat))
        print(f"{name:10s} {1e9 * best / args.steps:7.0f} ns")


def _timed(mode, x, y, prm, frc, n):
    start = time.perf_counter()
    _loop(mode, x, y, prm, frc, 1e-3, n)
    return time.perf_counter() - start


if __name__ == "__main__":
    main()
