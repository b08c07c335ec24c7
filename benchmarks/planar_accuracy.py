"""Error of the planar engine against the independent reference (tests/planar_reference.py).

Usage::

    python -m benchmarks.planar_accuracy   (from the repository root)

Prints, for real pairs and the hard cases of tests/solver/test_planar.py, the relative
error of the peak and residual resultant displacement and the largest difference of the
sampled history (all relative to the reference peak), the engine at its default
tolerance (rtol 1e-11).  docs/planar.md quotes its output.
"""

from __future__ import annotations

import time

import numpy as np

from benchmarks.planar_throughput import load
from isolator.bench.planar_reference import reference_pair
from isolator.solver.planar import simulate_pair
from tests.solver.test_planar import HARD, _hard_case


def row(name, t, ax, ay, az, system):
    start = time.perf_counter()
    ref = reference_pair(t, ax, ay, az, mu_s=system["mu_static"], mu_k=system.get("mu_kinetic"),
                         radius=system.get("radius_m"), kappa=system.get("stiffness_per_mass", 0.0),
                         mu_slow=system.get("mu_slow"), mu_fast=system.get("mu_fast"),
                         rate=system.get("rate_s_per_m"))
    ref_s = time.perf_counter() - start
    r = simulate_pair(ax, ay, time_s=t, az_m_s2=az, **system)
    scale = max(ref.peak_displacement_m, 1e-300)
    e_peak = abs(r.peak_displacement_m - ref.peak_displacement_m) / scale
    e_res = abs(r.residual_displacement_m - ref.residual_displacement_m) / scale
    e_hist = np.max(np.abs(r.displacement_m - ref.displacement_m)) / scale
    print(f"{name:34s} {t.size:6d} {1e3 * ref.peak_displacement_m:9.3f} {e_peak:9.1e} {e_res:9.1e} {e_hist:9.1e} "
          f"{r.n_events:5d} {1e3 * r.solver_seconds:8.2f} {ref_s:7.1f}")


def main() -> None:
    print(f"{'case':34s} {'n':>6s} {'peak mm':>9s} {'peak err':>9s} {'resid err':>9s} {'hist err':>9s} "
          f"{'events':>5s} {'ms':>8s} {'ref s':>7s}")
    for folder, system in (("superstitionhills1987_PTS", dict(mu_static=0.06, radius_m=2.0)),
                           ("lomaprieta1989_APEEL2", dict(mu_static=0.05, mu_kinetic=0.04, radius_m=1.5)),
                           ("hectormine1999_ABY", dict(mu_static=0.06, radius_m=2.0))):
        dt, ax, ay, az = load(folder)
        t = dt * np.arange(ax.size)
        row(folder, t, ax, ay, None, system)
        if az is not None:
            row(folder + " + vertical", t, ax, ay, az, system)
    for name in HARD:
        t, ax, ay, az, system = _hard_case(name)
        row(name, t, ax, ay, az, system)


if __name__ == "__main__":
    main()
