r"""Speed against error: the exact solver against the usual numerical methods.

Every method answers the same question — the relative displacement ``X(t)`` of the
block (friction µs/µk, spring κ, dashpot c, per unit mass) under a ground
acceleration ``a_g(t)`` — through one interface::

    method(case, setting) -> MethodOutput

where ``case`` is a :class:`BenchCase` (a harmonic case of the paper, Eq. 2, or a
recorded accelerogram) and ``setting`` the method's knob (time step [s] or relative
tolerance [-]).  The output carries ``X`` and ``X'`` at the case's output times, the
peak (records) or amplitude A (harmonic), the residual displacement and the
slip-time ratio ζ.  :func:`run_bench` times every method (median of several runs in
one process; on a 2-D case ours and OpenSees at the record's dt in alternation, so that
their ratio comes from one stretch of time) and measures its errors against the reference:

* **baselines** are compared with our exact solver;
* **our solver** is compared with the tightest event-located ``solve_ivp`` run
  (DOP853, rtol 1e-12), so its error column is an *upper bound* (the discrepancy
  between two independent solutions); for the harmonic cases the exact analytic
  steady state (:func:`isolator.solver.harmonic.harmonic_response`) is checked as well.

Methods
-------
``exact event-driven (ours)``
    :func:`isolator.solver.record.simulate_record` / the harmonic driver's
    period loop: closed-form slip segments and exactly located events (numba).
``implicit Euler, fixed step (paper's check)``
    Backward Euler with the set-valued Coulomb law solved exactly at each step
    (Moreau–Jean time stepping): stick when the trial velocity cannot overcome
    µs g h.  Numba loop.
``Newmark avg. accel. + elastic-plastic friction``
    Newmark γ = 1/2, β = 1/4 with friction as a stiff elastic–perfectly-plastic
    element (yield µs g from stick, µk g while sliding, elastic stick displacement
    ``u_y``), the way OpenSees-like codes model a flat or pendulum slider; the
    piecewise-linear residual is solved exactly (return mapping).  Numba loop.
``solve_ivp RK45|LSODA + events``
    Phase-by-phase integration: slip phases end at the terminal event V = 0, stick
    phases are skipped to the break-away time, found on the (linear or harmonic)
    forcing.  Pure SciPy/Python.
``solve_ivp RK45|LSODA, tanh friction``
    One integration of the regularised law µk g tanh(V/v_reg) (no events, no
    static friction); slip is counted where |V| > v_reg.

2-D cases (:mod:`isolator.bench.pairs`): real pairs of ``records/pairs`` on a friction
pendulum, our planar engine (:func:`isolator.solver.planar.simulate_pair`), OpenSees'
``singleFPBearing`` (optional, :mod:`isolator.bench.opensees`) and a regularised
``solve_ivp``, all measured against the independent reference
:mod:`isolator.bench.planar_reference`.

The building cases (:mod:`isolator.bench.building`, issue 22): a 5-story shear building on
a friction pendulum under one component (1-D) and under a pair (2-D), ours
(:mod:`isolator.solver.building`, the registry's ``2d-building``) against OpenSees' 3-D model
(:mod:`isolator.bench.opensees_building`) and an independent ``solve_ivp`` reference
(:mod:`isolator.bench.building_reference`, :mod:`isolator.bench.planar_building_reference`).  The triple friction pendulum
(:mod:`isolator.bench.tfp`, issue 23): ours (:mod:`isolator.solver.multisurface`) against
OpenSees' ``TripleFrictionPendulum`` (:mod:`isolator.bench.opensees_tfp`).

References
----------
M. Nicolas (2017), hal-01432172, Eq. 2 (harmonic case), Eqs. 3 (ζ) and 15 (α_SL).
"""

from isolator.bench.building import (
                                  BUILDING_OPENSEES,
                                  BUILDING_OURS,
                                  BUILDING_OURS_2D,
                                  BUILDING_TRUTH,
                                  BUILDING_TRUTH_2D,
                                  BuildingCase,
                                  building_case,
                                  building_cases,
                                  building_errors,
                                  building_markdown,
                                  building_summary,
                                  run_building_case,
)
from isolator.bench.cases import (
                                  HARMONIC_CASES,
                                  HARMONIC_PHASE,
                                  PENDULUM_MU_KINETIC,
                                  PENDULUM_MU_STATIC,
                                  PENDULUM_RADIUS_M,
                                  RECORD_FILES,
                                  STANDARD_GRAVITY_M_S2,
                                  BenchCase,
                                  bench_cases,
                                  harmonic_case,
                                  record_case,
)
from isolator.bench.harness import (
                                  CROSS_CHECK,
                                  ENGINEERING_ERROR,
                                  ERROR_FLOOR,
                                  OURS_METHODS,
                                  REFERENCE_METHODS,
                                  errors,
                                  pareto_by_case,
                                  pareto_summary,
                                  run_bench,
                                  run_pair_case,
                                  time_method,
                                  warm_up,
)
from isolator.bench.methods import (
                                  METHODS,
                                  OURS,
                                  Method,
                                  MethodOutput,
                                  exact_solver,
                                  implicit_fixed_step,
                                  ivp_tanh,
                                  ivp_with_events,
                                  methods,
                                  newmark_elastic_plastic,
)
from isolator.bench.output import (
                                  ROW_KEYS,
                                  opensees_summary,
                                  pareto_markdown,
                                  pareto_to_csv,
                                  plot,
                                  rows_markdown,
                                  rows_to_csv,
)
from isolator.bench.pairs import (
                                  IVP_REGULARISED,
                                  OPENSEES,
                                  PAIR_METHODS,
                                  PAIR_OURS,
                                  PAIR_TRUTH,
                                  PairCase,
                                  ivp_regularised,
                                  opensees_solver,
                                  pair_case,
                                  pair_cases,
                                  pair_errors,
                                  pair_methods,
                                  planar_solver,
                                  reference_solver,
)
from isolator.bench.tfp import TFP_OPENSEES, TFP_OURS, TfpCase, run_tfp_case, tfp_bearing, tfp_cases, tfp_summary

__all__ = ["TFP_OPENSEES", "TFP_OURS", "TfpCase", "run_tfp_case", "tfp_bearing", "tfp_cases", "tfp_summary",
           "BUILDING_OPENSEES", "BUILDING_OURS", "BUILDING_OURS_2D", "BUILDING_TRUTH", "BUILDING_TRUTH_2D",
           "BuildingCase", "building_case",
           "building_cases", "building_errors", "building_markdown", "building_summary", "run_building_case",
           "IVP_REGULARISED", "OPENSEES", "OURS_METHODS", "PAIR_METHODS", "PAIR_OURS", "PAIR_TRUTH",
           "REFERENCE_METHODS", "PairCase", "ivp_regularised", "opensees_solver", "opensees_summary", "pair_case",
           "pair_cases", "pair_errors", "pair_methods", "planar_solver", "reference_solver", "run_pair_case",
           "CROSS_CHECK", "ENGINEERING_ERROR", "ERROR_FLOOR", "HARMONIC_CASES", "HARMONIC_PHASE", "METHODS", "OURS",
           "PENDULUM_MU_KINETIC", "PENDULUM_MU_STATIC", "PENDULUM_RADIUS_M", "RECORD_FILES", "ROW_KEYS",
           "STANDARD_GRAVITY_M_S2", "BenchCase", "Method", "MethodOutput", "bench_cases", "errors",
           "exact_solver", "harmonic_case", "implicit_fixed_step", "ivp_tanh", "ivp_with_events", "methods",
           "newmark_elastic_plastic", "pareto_by_case", "pareto_markdown", "pareto_summary", "pareto_to_csv",
           "plot", "record_case", "rows_markdown", "rows_to_csv", "run_bench", "time_method", "warm_up"]
