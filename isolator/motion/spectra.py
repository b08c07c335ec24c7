"""Response spectra of a ground-acceleration history (the friction-free case of the solver)."""

from __future__ import annotations

import numpy as np

DEFAULT_DAMPING_RATIO = 0.05  # [-] response spectra are 5 % damped unless asked otherwise


def pseudo_acceleration_spectrum(
    acceleration_m_s2: np.ndarray,
    dt_s: float,
    periods_s: np.ndarray,
    damping_ratio: float = DEFAULT_DAMPING_RATIO,
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

    Returns
    -------
    numpy.ndarray
        Pseudo-spectral acceleration at each period [m/s²].
    """
    from isolator.solver.linear import pseudo_acceleration_spectrum as solver_spectrum

    return np.asarray(solver_spectrum(np.ascontiguousarray(acceleration_m_s2, dtype=np.float64), float(dt_s),
                                      periods_s, damping_ratio=damping_ratio))

