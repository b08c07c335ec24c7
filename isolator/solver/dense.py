"""Small dense linear algebra for the compiled kernels.

The implicit steps of the multi-surface kernels (1-D with µ(v), :mod:`isolator.solver.multisurface_rate_kernel`;
2-D, :mod:`isolator.solver.planar_multisurface_kernel`) factor Newton matrices of a few dozen unknowns inside
numba-compiled loops, many thousands of times per record.  ``np.linalg.solve`` there allocates and re-factors on each
call; these factor once in place and solve many times with the stored factors (Golub & Van Loan, *Matrix
Computations*, 4th ed., Alg. 3.4.1 and 3.4.2: Gaussian elimination with partial pivoting).
"""

from __future__ import annotations

import math

import numpy as np

from isolator.solver.jit import njit


@njit(cache=True)
def lu_factor(mat, piv):
    """LU factorisation with partial pivoting of ``mat`` (real or complex) in place (row swaps in ``piv``).

    Returns False when a pivot is zero or not finite (a singular or non-finite matrix): the caller refuses the step.
    """
    size = mat.shape[0]
    for col in range(size):
        best = col
        top = abs(mat[col, col])
        for i in range(col + 1, size):
            if abs(mat[i, col]) > top:
                top = abs(mat[i, col])
                best = i
        if not (top > 0.0 and math.isfinite(top)):
            return False
        piv[col] = best
        if best != col:
            for q in range(size):
                tmp = mat[col, q]
                mat[col, q] = mat[best, q]
                mat[best, q] = tmp
        inv = 1.0 / mat[col, col]
        for i in range(col + 1, size):
            f = mat[i, col] * inv
            mat[i, col] = f
            if f != 0.0:
                for q in range(col + 1, size):
                    mat[i, q] -= f * mat[col, q]
    return True


@njit(cache=True)
def lu_solve(lu, piv, rhs_vec):
    """Solve with the factors of :func:`lu_factor`, in place on ``rhs_vec``."""
    size = lu.shape[0]
    for i in range(size):
        k = piv[i]
        if k != i:
            tmp = rhs_vec[i]
            rhs_vec[i] = rhs_vec[k]
            rhs_vec[k] = tmp
    for i in range(size):
        total = rhs_vec[i]
        for q in range(i):
            total -= lu[i, q] * rhs_vec[q]
        rhs_vec[i] = total
    for i in range(size - 1, -1, -1):
        total = rhs_vec[i]
        for q in range(i + 1, size):
            total -= lu[i, q] * rhs_vec[q]
        rhs_vec[i] = total / lu[i, i]


@njit(cache=True)
def solve_or_refuse(mat, rhs_vec, out):
    """``out`` = ``mat``⁻¹ ``rhs_vec`` by LAPACK's LU with partial pivoting (``np.linalg.solve``: the same arithmetic
    as a direct call); False where ``mat`` is singular (a zero pivot) or not finite instead of raising ``LinAlgError``.  The full
    Newton of the µ(v) kernels' Radau steps calls it so that a singular stage matrix refuses the step, which the
    caller then shortens (docs/multisurface.md, h141: the corner of two saturated circles raised here)."""
    try:
        out[:] = np.linalg.solve(mat, rhs_vec)
    except Exception:  # np.linalg.LinAlgError: a zero pivot, or a non-finite entry
        return False
    return True
