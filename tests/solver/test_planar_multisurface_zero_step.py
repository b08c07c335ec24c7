"""The Radau matrix of the 2-D multi-surface kernel refuses a zero step instead of dividing by zero (h178)."""

import numpy as np

from isolator.solver import planar_multisurface_kernel as pmk


def test_radau_matrix_refuses_a_zero_step_and_factors_a_positive_one():
    na = 3
    jac = np.diag([-1.0, -2.0, -3.0])
    e1 = np.empty((na, na))
    e2 = np.empty((na, na), dtype=np.complex128)
    p1 = np.empty(na, dtype=np.int64)
    p2 = np.empty(na, dtype=np.int64)
    # on 4412bf7 this raised ZeroDivisionError (numba's python error model)
    assert not pmk._radau_matrix(0.0, jac, na, e1, p1, e2, p2)
    assert pmk._radau_matrix(1e-3, jac, na, e1, p1, e2, p2)
