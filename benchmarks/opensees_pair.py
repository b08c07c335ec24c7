"""The planar engine against OpenSees on one real pair: time and error of both, one run.

Usage::

    pip install "isolator[bench]"      # openseespy (Linux wheels need libblas3, liblapack3)
    python -m benchmarks.opensees_pair   (from the repository root) [--pair superstitionhills1987_PTS] [--mu 0.06]
                                                    [--radius 2.0] [--yield-mm 0.5] [--repeat 3]

Model (the same for both): a rigid mass on a single friction pendulum of radius R,
Coulomb friction µ, both horizontal components at once, no vertical.

* **isolator** — :func:`isolator.solver.planar.simulate_pair` (DOP853 between exact
  events, its default rtol, 1e-11).
* **OpenSees** — openseespy, a 3-D model (ndm 3, ndf 6) with two coincident nodes and
  ``singleFPBearing`` (``frictionModel Coulomb``, Reff = R, its usual elastic
  stiffness before sliding kInit = µW/u_y with u_y = ``--yield-mm``, a stiff
  elastic vertical material), gravity applied statically, then both components as
  ``UniformExcitation`` patterns; Newmark (γ = 1/2, β = 1/4) with Newton at the
  record's dt (step halved on non-convergence, as in the OpenSees examples).
* **truth** — the independent reference of the tests (tests/planar_reference.py:
  scipy solve_ivp, DOP853 / Radau at rtol 1e-12 with stop events).

Errors are relative to the reference's peak resultant displacement: of the peak, of
the residual, and the largest difference over the sampled history.
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np

from benchmarks.planar_throughput import load
from isolator.bench.planar_reference import reference_pair
from isolator.solver.planar import simulate_pair
from isolator.units import STANDARD_GRAVITY as G  # noqa: E402


def opensees_pair(dt, ax, ay, *, mu, radius, yield_m, substeps=1):
    """Relative displacement history (n, 2) of a single friction pendulum in OpenSees (the bench's model)."""
    from isolator.bench.opensees import opensees_pair as model

    return model(dt, ax, ay, mu=mu, radius_m=radius, gravity_m_s2=G, yield_m=yield_m, substeps=substeps)


def errors(history, ref):
    resultant = np.hypot(history[:, 0], history[:, 1])
    scale = ref.peak_displacement_m
    return (abs(resultant.max() - scale) / scale,
            abs(resultant[-1] - ref.residual_displacement_m) / scale,
            np.max(np.abs(history - ref.displacement_m)) / scale)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pair", default="superstitionhills1987_PTS")
    parser.add_argument("--mu", type=float, default=0.06)
    parser.add_argument("--radius", type=float, default=2.0)
    parser.add_argument("--yield-mm", type=float, default=0.5)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--substeps", type=int, default=1, help="OpenSees steps per sample interval")
    args = parser.parse_args(argv)
    try:
        import openseespy.opensees  # noqa: F401
    except (ImportError, RuntimeError) as exc:  # openseespy raises RuntimeError when libblas is missing
        raise SystemExit(f"openseespy does not import here: {exc}") from None
    dt, ax, ay, _ = load(args.pair)
    t = dt * np.arange(ax.size)
    start = time.perf_counter()
    ref = reference_pair(t, ax, ay, mu_s=args.mu, radius=args.radius)
    ref_seconds = time.perf_counter() - start

    ours, theirs = [], []
    for _ in range(args.repeat):
        r = simulate_pair(ax, ay, dt, mu_static=args.mu, radius_m=args.radius)
        ours.append(r.solver_seconds)
        start = time.perf_counter()
        history = opensees_pair(dt, ax, ay, mu=args.mu, radius=args.radius, yield_m=1e-3 * args.yield_mm,
                                substeps=args.substeps)
        theirs.append(time.perf_counter() - start)
    t_ours, t_theirs = statistics.median(ours), statistics.median(theirs)
    e_ours = errors(r.displacement_m, ref)
    # our peak is located between samples; compare the sampled one too, as OpenSees only has samples
    e_ours = (abs(r.peak_displacement_m - ref.peak_displacement_m) / ref.peak_displacement_m,) + e_ours[1:]
    e_theirs = errors(history, ref)
    print(f"pair {args.pair}: {ax.size} samples, dt = {dt} s; single friction pendulum R = {args.radius} m, "
          f"µ = {args.mu}; reference (solve_ivp) {ref_seconds:.1f} s, peak {1e3 * ref.peak_displacement_m:.3f} mm")
    print(f"{'method':30s} {'seconds':>9s} {'peak err':>9s} {'resid err':>9s} {'hist err':>9s}")
    print(f"{'isolator simulate_pair':30s} {t_ours:9.4f} {e_ours[0]:9.1e} {e_ours[1]:9.1e} {e_ours[2]:9.1e}")
    label = f"OpenSees FP uy={args.yield_mm}mm dt/{args.substeps}"
    print(f"{label:30s} {t_theirs:9.4f} {e_theirs[0]:9.1e} {e_theirs[1]:9.1e} {e_theirs[2]:9.1e}")
    print(f"isolator is {t_theirs / t_ours:.0f}x faster, with {e_theirs[2] / max(e_ours[2], 1e-300):.1e}x lower "
          f"history error ({e_theirs[0] / max(e_ours[0], 1e-300):.1e}x on the peak)")


if __name__ == "__main__":
    main()
