"""Census of the planar engine's DOP853 steps: what limits the Cartesian step size.

Usage::

    python -m benchmarks.planar_steps [--pair hectormine1999_ABY] [--mu 0.06] [--radius 2.0]

Runs :func:`isolator.solver.planar.simulate_pair` once on one real pair with numba's
JIT disabled (plain Python, ≈ 3 s) and every DOP853 step logged, then prints, for the
Cartesian and POLAR steps, how the step h compares with the time scales of slow sliding:

* ``h·µn/r`` — the step times the stiff eigenvalue of the Cartesian form (the
  Jacobian of −µn V/|V| is −(µn/r)(I − e eᵀ), r = |V|, e = V/r).  DOP853 is stable on
  the negative real axis down to h·λ ≈ −6.6 (|R(−6.5)| = 1.20, |R(−6.25)| = 0.78);
  steps far below that are not held by stability; in POLAR form the stiff mode is
  the direction e, which relaxes at the rate e·F/r (``h·|F|/r``, bounded by 5);
* ``h·|ṙ|/r`` — the step relative to the time r/|ṙ| to the instant where V = 0 (the
  break-away behind, the stop ahead), where V/|V| is singular: the distance to the
  nearest singularity of the solution, which bounds the step of any method of order 8
  (explicit or implicit) at a fixed tolerance.

docs/dev-notes.md quotes its output.
"""

from __future__ import annotations

import os

os.environ["NUMBA_DISABLE_JIT"] = "1"  # before numba is imported: the kernel runs as Python

import argparse  # noqa: E402
import math  # noqa: E402

import numpy as np  # noqa: E402

import isolator.solver.planar_kernel as kernel  # noqa: E402
from benchmarks.planar_throughput import load  # noqa: E402
from isolator.solver.planar import simulate_pair  # noqa: E402
from isolator.solver.planar_rk import CARTESIAN, P_C, POLAR, forcing, friction_coefficient  # noqa: E402


def census(dt, ax, ay, az, **system):
    """Run the engine once with every DOP853 step logged.

    Returns
    -------
    tuple
        ``(response, steps)``: steps is an array of rows (mode, h [s or -], r [m/s],
        µn [m/s²], ṙ [m/s²], accepted, |F| [m/s²]); r, µn, ṙ and |F| are at the step
        start and only filled for Cartesian and POLAR steps.
    """
    original = kernel.dop853_step
    rows = []

    def logged(mode, x, y, f0, h, prm, frc, *rest):
        ok, err = original(mode, x, y, f0, h, prm, frc, *rest)
        accepted = bool(ok and err <= 1.0)
        if mode == CARTESIAN or mode == POLAR:
            r = math.hypot(y[2], y[3]) if mode == CARTESIAN else y[7]
            e1, e2 = (y[2] / r, y[3] / r) if mode == CARTESIAN and r > 0.0 else (y[2], y[3])
            nn = frc[4] + frc[5] * x
            fr = friction_coefficient(r, prm) * nn if (nn > 0.0 and frc[6] > 0.0) else 0.0
            _, _, _, _, _, fx, fy = forcing(x, y[0], y[1], prm, frc)
            rdot = e1 * fx + e2 * fy - fr - prm[P_C] * r if r > 0.0 else 0.0
            rows.append((mode, h, r, fr, rdot, accepted, math.hypot(fx, fy)))
        else:
            rows.append((mode, h, 0.0, 0.0, 0.0, accepted, 0.0))
        return ok, err

    kernel.dop853_step = logged
    try:
        response = simulate_pair(ax, ay, dt, az_m_s2=az, **system)
    finally:
        kernel.dop853_step = original
    return response, np.array(rows, dtype=float).reshape(-1, 7)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pair", default="hectormine1999_ABY")
    parser.add_argument("--mu", type=float, default=0.06)
    parser.add_argument("--radius", type=float, default=2.0)
    args = parser.parse_args(argv)
    dt, ax, ay, _ = load(args.pair)
    response, steps = census(dt, ax, ay, None, mu_static=args.mu, radius_m=args.radius)
    print(f"{args.pair}: {ax.size} samples, dt = {dt} s, R = {args.radius} m, µ = {args.mu}; "
          f"{steps.shape[0]} steps ({response.n_steps} counted by the engine), "
          f"peak {1e3 * response.peak_displacement_m:.3f} mm")
    for mode, name in ((1, "LOG"), (2, "START")):
        m = steps[:, 0] == mode
        print(f"{name:9s} steps {int(m.sum()):5d}, rejected {int((m & (steps[:, 5] == 0)).sum()):4d}")
    for mode, name in ((CARTESIAN, "Cartesian"), (POLAR, "POLAR")):
        table(steps[(steps[:, 0] == mode) & (steps[:, 2] > 0.0) & (steps[:, 3] > 0.0)], name, dt)


def table(cart, name, dt):
    """Steps of one form by speed band: step relative to dt, to the stability scales and to r/|ṙ|."""
    acc = cart[:, 5] > 0
    print(f"{name} sliding steps {cart.shape[0]}, rejected {int((~acc).sum())}, "
          f"a whole sample long {int((acc & (np.abs(cart[:, 1]) >= 0.999 * dt)).sum())}")
    print(f"{'|V| [m/s]':>18s} {'accepted':>8s} {'rejected':>8s} {'med h/dt':>8s} {'med h·µn/r':>10s} "
          f"{'med h·|F|/r':>11s} {'max h·|F|/r':>11s} {'med h·|ṙ|/r':>11s}")
    h = np.abs(cart[:, 1])
    stiff = h * cart[:, 3] / cart[:, 2]
    fstiff = h * cart[:, 6] / cart[:, 2]
    sing = h * np.abs(cart[:, 4]) / cart[:, 2]
    for lo, hi in ((0.0, 1e-4), (1e-4, 1e-3), (1e-3, 3e-3), (3e-3, 1e-2), (1e-2, np.inf)):
        band = (cart[:, 2] >= lo) & (cart[:, 2] < hi)
        a = band & acc
        if not a.any():
            continue
        print(f"{lo:8.0e} – {hi:7.0e} {int(a.sum()):8d} {int((band & ~acc).sum()):8d} "
              f"{np.median(h[a]) / dt:8.3f} {np.median(stiff[a]):10.2f} {np.median(fstiff[a]):11.2f} "
              f"{fstiff[a].max():11.2f} {np.median(sing[a]):11.2f}")

if __name__ == "__main__":
    np.seterr(all="ignore")
    main()
