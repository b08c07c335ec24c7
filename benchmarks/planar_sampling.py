"""Does the planar engine's answer depend on how a record is sampled? (issue 10: it must not,
beyond the piecewise-linear reading of the record).

Usage::

    python -m benchmarks.planar_sampling [--pairs 20]   (from the repository root)

For each of ``--pairs`` white-noise pairs (seeds 3, 4, …; a_x every 0.02 s and a_y every
0.03 s over 6 s, σ = 2 m/s²), solves the same piecewise-linear motion twice: on the union
of the two components' sample times (unequal steps, each component interpolated linearly
onto the other's times), and on the 0.01 s grid that contains both. The two are the same
signal, so the peak and residual resultant displacements differ only by the integration
error. Prints the largest relative difference of the peak and the largest difference of
the residual over the peak, with the seeds where they occur and the median. Friction
pendulum R = 2 m, µ = 0.05, default tolerance. docs/planar.md quotes its output.
"""

from __future__ import annotations

import argparse

import numpy as np

from isolator.solver.planar import simulate_pair

SYSTEM = {"mu_static": 0.05, "radius_m": 2.0}


def differences(seed: int) -> tuple[float, float]:
    """(|peak_joined / peak_grid − 1|, |residual_joined − residual_grid| / peak_grid) of one pair."""
    rng = np.random.default_rng(seed)
    t_x, t_y = 0.02 * np.arange(301), 0.03 * np.arange(201)
    a_x, a_y = rng.normal(0.0, 2.0, t_x.size), rng.normal(0.0, 2.0, t_y.size)
    joined = np.union1d(t_x, t_y)
    grid = 0.01 * np.arange(601)
    j = simulate_pair(np.interp(joined, t_x, a_x), np.interp(joined, t_y, a_y), time_s=joined, **SYSTEM)
    u = simulate_pair(np.interp(grid, t_x, a_x), np.interp(grid, t_y, a_y), 0.01, **SYSTEM)
    peak = u.peak_displacement_m
    return (abs(j.peak_displacement_m / peak - 1.0),
            abs(j.residual_displacement_m - u.residual_displacement_m) / peak)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pairs", type=int, default=20, help="white-noise pairs (seeds 3, 4, …)")
    args = parser.parse_args(argv)
    seeds = range(3, 3 + max(1, args.pairs))
    rows = np.array([differences(s) for s in seeds])
    for k, what in enumerate(("peak (relative)", "residual (of the peak)")):
        worst = int(np.argmax(rows[:, k]))
        print(f"{what:24s} largest {rows[worst, k]:.2e} (seed {seeds[worst]}), median {np.median(rows[:, k]):.1e}, "
              f"{len(seeds)} pairs")


if __name__ == "__main__":
    main()
