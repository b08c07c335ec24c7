"""Independent reference for the planar (2-D) friction block, as the tests use it.

The reference lives in :mod:`isolator.bench.planar_reference` (the installed bench needs it as
its truth, and the package must not import ``tests``).  It is written independently of the
engine: scipy ``solve_ivp`` (DOP853/Radau, rtol 1e-12) with its own stick test and stop
events, sharing no code with :mod:`isolator.solver.planar`.
"""

from isolator.bench.planar_reference import reference_pair

__all__ = ["reference_pair"]
