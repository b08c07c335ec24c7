"""Response spectra of a ground-acceleration history (the friction-free case of the solver)."""

from __future__ import annotations

import numpy as np

DEFAULT_DAMPING_RATIO = 0.05  # [-] response spectra are 5 % damped unless asked otherwise


def pseudo_acceleration_spectrum(
    acceleration_m_s2: np.ndarray,
    dt_s: float,
    periods_s: np.ndarray,
    damping_ratio: float = DEFAULT_DAMPING_RATIO,
    time_s=None,
) -> np.ndarray:
    """Pseudo-acceleration response spectrum of a linear SDOF oscillator.

    Delegates to the core solver's exact piecewise-linear propagator
    (:func:`isolator.solver.linear.pseudo_acceleration_spectrum`: the friction-free case
    of the solver, the record linear between samples, peaks between samples included),
    so the spectrum and the isolator response come from one physics engine.

    .. math:: S_a(T) = \\omega^2 \\max_t |u(t)|, \\quad \\omega = 2\\pi / T

    Parameters
    ----------
    acceleration_m_s2 : numpy.ndarray
        Ground acceleration samples [m/s²].
    dt_s : float
        Time step [s].
    periods_s : numpy.ndarray
        Oscillator periods, all > 0 [s].
    damping_ratio : float, optional
        Fraction of critical damping [-].
    time_s : numpy.ndarray, optional
        Sample times of a record with unequal steps (then ``dt_s`` is unused) [s].

    Returns
    -------
    numpy.ndarray
        Pseudo-spectral acceleration at each period [m/s²].
    """
    from isolator.solver.linear import pseudo_acceleration_spectrum as solver_spectrum

    acceleration, dt, periods, damping = _checked(acceleration_m_s2, dt_s, periods_s, damping_ratio, time_s)
    return np.asarray(solver_spectrum(acceleration, dt, periods, damping_ratio=damping, time_s=time_s))


def _real_array(name: str, values, ndim: int = 1) -> np.ndarray:
    from isolator.errors import MotionError

    array = np.asarray(values)
    if array.dtype.kind not in "biuf" or array.ndim != ndim:
        raise MotionError(f"{name} must be a {ndim}-D array of real numbers, got {array.dtype} of shape {array.shape}")
    array = np.ascontiguousarray(array, dtype=np.float64)
    if not np.all(np.isfinite(array)):
        raise MotionError(f"{name} holds NaN or infinite values")
    return array


def _checked(acceleration_m_s2, dt_s, periods_s, damping_ratio, time_s):
    """The spectrum's arguments checked (issue 26: NaN gave [0.], dt = 0 a ZeroDivisionError)."""
    import math

    from isolator.errors import MotionError

    acceleration = _real_array("acceleration_m_s2", acceleration_m_s2)
    if acceleration.size < 2:
        raise MotionError("acceleration_m_s2: a record needs at least two samples")
    periods = _real_array("periods_s", np.atleast_1d(periods_s))
    if not np.all(periods > 0.0):
        raise MotionError("periods_s must all be > 0 [s]")
    try:
        dt, damping = float(dt_s), float(damping_ratio)
    except (TypeError, ValueError):
        raise MotionError(f"dt_s and damping_ratio must be numbers, got {dt_s!r} and {damping_ratio!r}") from None
    if time_s is None and not (math.isfinite(dt) and dt > 0.0):
        raise MotionError(f"dt_s must be a finite number > 0 [s], got {dt_s!r}")
    if not (math.isfinite(damping) and 0.0 <= damping < 1.0):
        raise MotionError(f"damping_ratio must lie in [0, 1), got {damping_ratio!r}")
    return acceleration, dt, periods, damping

