"""Brent's root finder for one bracketed scalar root, without importing ``scipy.optimize``.

``from scipy.optimize import brentq`` imports the whole of ``scipy.optimize`` (linprog, HiGHS,
shgo, … : 0.45–0.7 s of CPU on the development machine), and the review's ELF fixed point
(ASCE 7-22 17.5.3) needs only this one function.  :func:`brentq` performs the same floating-point
operations in the same order as SciPy's ``brentq`` (``scipy/optimize/Zeros/brentq.c``: Brent
1973, ch. 4, inverse quadratic extrapolation with bisection fall-backs), so it returns the same
double, bit for bit: ``tests/test_roots.py`` compares the two on a corpus of functions and
brackets and on the review's own ELF equation.

References
----------
R. P. Brent (1973), *Algorithms for Minimization Without Derivatives*, Prentice-Hall, ch. 4.
"""

from __future__ import annotations

import math
from collections.abc import Callable

#: SciPy's smallest allowed relative tolerance, 4 × machine epsilon [-].
RTOL_MIN = 4.0 * 2.220446049250313e-16


def brentq(f: Callable[[float], float], a: float, b: float, *, xtol: float = 2e-12, rtol: float = RTOL_MIN,
           maxiter: int = 100) -> float:
    """A root of ``f`` in ``[a, b]``, where ``f(a)`` and ``f(b)`` have opposite signs.

    Parameters
    ----------
    f : callable
        ``f(x) -> float``, continuous on the bracket.
    a, b : float
        The bracket's ends [unit of x].
    xtol, rtol : float
        Convergence when half the bracket is below ``(xtol + rtol |x|) / 2`` [unit of x], [-];
        ``xtol > 0``, ``rtol ≥`` :data:`RTOL_MIN` (SciPy's limits).
    maxiter : int
        Iterations at most (bounds the loop) [-].

    Returns
    -------
    float
        The root, as ``scipy.optimize.brentq(f, a, b, xtol=xtol, rtol=rtol, maxiter=maxiter)`` returns it.

    Raises
    ------
    ValueError
        ``f(a)`` and ``f(b)`` of one sign, a NaN value of ``f``, ``xtol ≤ 0`` or ``rtol <`` :data:`RTOL_MIN`
        (as SciPy).
    RuntimeError
        No convergence within ``maxiter`` iterations (as SciPy).
    """
    if not xtol > 0:
        raise ValueError(f"xtol must be > 0, got {xtol!r}")
    if not rtol >= RTOL_MIN:
        raise ValueError(f"rtol must be ≥ {RTOL_MIN!r}, got {rtol!r}")
    x_previous, x_current = float(a), float(b)
    x_bracket, f_bracket, step_previous, step_current = 0.0, 0.0, 0.0, 0.0
    f_previous, f_current = _value(f, x_previous), _value(f, x_current)
    if f_previous == 0:
        return x_previous
    if f_current == 0:
        return x_current
    if math.copysign(1.0, f_previous) == math.copysign(1.0, f_current):
        raise ValueError(f"f({a!r}) and f({b!r}) must have opposite signs")
    for _ in range(int(maxiter)):
        if f_previous != 0 and f_current != 0 and math.copysign(1.0, f_previous) != math.copysign(1.0, f_current):
            x_bracket, f_bracket = x_previous, f_previous
            step_previous = step_current = x_current - x_previous
        if abs(f_bracket) < abs(f_current):  # keep the best estimate in x_current
            x_previous, x_current, x_bracket = x_current, x_bracket, x_current
            f_previous, f_current, f_bracket = f_current, f_bracket, f_current
        delta = (xtol + rtol * abs(x_current)) / 2
        bisection = (x_bracket - x_current) / 2
        if f_current == 0 or abs(bisection) < delta:
            return x_current
        if abs(step_previous) > delta and abs(f_current) < abs(f_previous):
            if x_previous == x_bracket:  # secant (linear interpolation)
                trial = -f_current * (x_current - x_previous) / (f_current - f_previous)
            else:  # inverse quadratic extrapolation
                d_previous = (f_previous - f_current) / (x_previous - x_current)
                d_bracket = (f_bracket - f_current) / (x_bracket - x_current)
                trial = (-f_current * (f_bracket * d_bracket - f_previous * d_previous)
                         / (d_bracket * d_previous * (f_bracket - f_previous)))
            if 2 * abs(trial) < min(abs(step_previous), 3 * abs(bisection) - delta):  # a good short step
                step_previous, step_current = step_current, trial
            else:
                step_previous = step_current = bisection
        else:
            step_previous = step_current = bisection
        x_previous, f_previous = x_current, f_current
        if abs(step_current) > delta:
            x_current += step_current
        else:
            x_current += delta if bisection > 0 else -delta
        f_current = _value(f, x_current)
    raise RuntimeError(f"no convergence in {maxiter} iterations (last estimate {x_current!r})")


def _value(f, x: float) -> float:
    """``f(x)`` as a float; NaN is refused (as SciPy does: a NaN has no sign to bracket with)."""
    value = float(f(x))
    if math.isnan(value):
        raise ValueError(f"the function value at x = {x!r} is NaN")
    return value
