"""The exact triple friction pendulum against OpenSees' TripleFrictionPendulum: time and error, one run.

Usage::

    pip install "isolator[bench]"      # openseespy (Linux wheels need libblas3, liblapack3)
    python -m benchmarks.tfp_opensees   (from the repository root) [--rounds 5] [--quick]
                                        [--records ../shared/records]

The cases of ``isolator bench`` (:mod:`isolator.bench.tfp`): Fenz & Constantinou's bearing
(R_eff 2.1/0.3/0.3/2.1 m, µ 0.06/0.02/0.02/0.10, d* 0.4/0.05/0.05/0.4 m) under a rigid mass,
Northridge NWH360 ×1 and ×2 (first 20 s), and the Superstition Hills PTS pair ×1 (first 20 s,
2-D).  Ours and OpenSees (Newmark + Newton at the record's dt) timed in alternation; OpenSees'
error against ours; ours against the tests' independent references (1-D: ``SeriesReference`` of
tests/solver/test_multisurface.py, element states, matrix exponential and Brent roots; 2-D:
``PlanarSeriesReference`` of tests/solver/test_planar_multisurface.py, solve_ivp with events, when
those tests are on the branch; run from the repository root).  ``--only-2d`` runs the pair alone.
In 2-D a second row times ours at ``TFP_LOOSE_RTOL`` (three-way alternation with ours at the
default and OpenSees), and both rows are also measured against the event kernel at its tightest
rtol (the reference's own error is ~3e-9 of the peak).
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

import numpy as np

from isolator.bench.tfp import TFP_LOOSE_RTOL, ours_tfp, run_tfp_case, tfp_cases, tfp_summary, trajectory_errors


def _reference(case):
    from tests.solver.test_multisurface import SeriesReference

    x, _ = SeriesReference(case.bearing, g=case.gravity_m_s2).run(case.acceleration_m_s2, case.dt_s)
    return x


def _planar_reference(case):
    """The tests' independent 2-D reference (``PlanarSeriesReference`` of tests/solver/test_planar_multisurface.py:
    solve_ivp on (X, V, ū_k) with events, rtol 1e-12), or None where those tests are not on this branch."""
    try:
        from tests.solver.test_planar_multisurface import PlanarSeriesReference
    except ImportError:
        return None

    def reference(c):
        t = c.dt_s * np.arange(c.acceleration_m_s2.size)
        try:
            x, _, _ = PlanarSeriesReference(c.bearing, g=c.gravity_m_s2).run(t, c.acceleration_m_s2,
                                                                               c.acceleration_y_m_s2)
            return x
        except (np.linalg.LinAlgError, RuntimeError) as exc:
            # the solve_ivp reference cannot follow three friction circles meeting at small angles (the PTS pair
            # stops it on a singular matrix): our implicit steps at a 100x tighter tolerance stand in, converged
            # (docs/multisurface.md: 1e-7 against 1e-8 agree to 2.2e-7 of the peak on PTS) but not independent
            from isolator.solver.planar_multisurface import DEFAULT_STEP_TOL, simulate_bearing_pair

            print(f"  the solve_ivp reference stops ({type(exc).__name__}: {exc}); the reference is our implicit "
                  f"steps at step_tol {DEFAULT_STEP_TOL / 100:g} (converged, not independent)")
            return simulate_bearing_pair(c.acceleration_m_s2, c.acceleration_y_m_s2, c.dt_s, bearing=c.bearing,
                                         gravity_m_s2=c.gravity_m_s2, method="steps",
                                         step_tol=DEFAULT_STEP_TOL / 100).displacement_m

    return reference


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--records", default="../shared/records")
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--only-2d", action="store_true", help="the 2-D case (the PTS pair) alone")
    args = parser.parse_args(argv)
    for case in tfp_cases(args.quick, Path(args.records)):
        if args.only_2d and not case.planar:
            continue
        result = run_tfp_case(case, rounds=args.rounds, reference=_planar_reference(case) if case.planar else _reference)
        for line in tfp_summary([result]):
            print(line)
        ours = result["ours"]
        if ours["seconds"] is not None:
            print(f"  peaks [m]: ours {ours['peak_m']:.4f} (exact; sampled {ours['sampled_peak_m']:.4f}), "
                  f"OpenSees {result['opensees'].get('sampled_peak_m', float('nan')):.4f} (sampled)")
        if case.planar and ours["seconds"] is not None:
            # the reference above is at its own ~3e-9: the two rows of ours against the kernel at its tightest
            # rtol, the most exact answer here (not independent)
            from isolator.solver.planar_multisurface import RTOL_RANGE

            tight = ours_tfp(case, rtol=RTOL_RANGE[0]).displacement_m
            print(f"  ours against the event kernel at rtol {RTOL_RANGE[0]:g}: at the default "
                  f"{trajectory_errors(ours_tfp(case).displacement_m, tight)['error_trajectory']:.1e}, at "
                  f"{TFP_LOOSE_RTOL:g} "
                  f"{trajectory_errors(ours_tfp(case, rtol=TFP_LOOSE_RTOL).displacement_m, tight)['error_trajectory']:.1e}")
    print(f"load average (1, 5, 15 min): {os.getloadavg()}")


if __name__ == "__main__":
    main()
