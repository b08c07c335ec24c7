"""The solvers: the model registry (:mod:`.models`: select_model, simulate), the exact 1-D kernel (:mod:`.record`),
the 2-D engine (:mod:`.planar`), the buildings, the multi-surface bearings, the harmonic problem (:mod:`.harmonic`).

Importing any module of this package (``isolator.solver.base`` for the summary keys, ``isolator.solver.notice``
for the CLI's compile notes) runs this file first, so it imports nothing: each engine, with numba and its
kernels, loads where a caller imports it.  The public names are :mod:`isolator`'s (``isolator.simulate``,
``isolator.simulate_record`` …, loaded on first use) or those of the modules here.
"""
