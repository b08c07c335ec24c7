"""Intensity measures of a ground-acceleration history: pure functions on arrays.

PGA, PGV, PGD (baseline-corrected), Arias intensity, significant duration D5-95, the
predominant period (peak of the 5 %-damped PSA) and the equivalent harmonic amplitude
and frequency that map a record onto the paper's parameters.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

from isolator.motion.spectra import DEFAULT_DAMPING_RATIO, pseudo_acceleration_spectrum
from isolator.units import STANDARD_GRAVITY

#: Periods searched for the predominant period (peak of the 5 %-damped PSA) [s].
PREDOMINANT_PERIODS_S = np.geomspace(0.02, 5.0, 100)

__all__ = ["DEFAULT_DAMPING_RATIO", "IntensityMeasures", "arias_intensity_m_s", "arias_window_s",
           "cumulative_trapezoid", "displacement_m", "energy_window_s", "intensity_measures", "significant_duration_s",
           "velocity_m_s"]


def cumulative_trapezoid(values: np.ndarray, dt_s: float, time_s=None) -> np.ndarray:
    """Cumulative trapezoidal integral of sampled values, 0 at the first sample.

    The operations of ``scipy.integrate.cumulative_trapezoid(values, dx=dt_s, initial=0)``,
    in the same order (so the same bits), without importing ``scipy.integrate``: that
    import alone is ~0.2 s of a report's start-up.

    Parameters
    ----------
    values : numpy.ndarray
        Samples of the integrand [unit].
    dt_s : float
        Time step [s] (unused when ``time_s`` is given).
    time_s : numpy.ndarray, optional
        Sample times of a record with unequal steps [s].

    Returns
    -------
    numpy.ndarray
        The running integral at each sample [unit·s], same length as ``values``.
    """
    values = np.asarray(values, dtype=float)
    steps = dt_s if time_s is None else np.diff(np.asarray(time_s, dtype=float))
    return np.concatenate(([0.0], np.cumsum(steps * (values[1:] + values[:-1]) / 2.0)))


def _times(n: int, dt_s: float, time_s) -> np.ndarray:
    return np.arange(n) * dt_s if time_s is None else np.asarray(time_s, dtype=np.float64) - time_s[0]


def velocity_m_s(acceleration_m_s2: np.ndarray, dt_s: float, time_s=None) -> np.ndarray:
    """Ground velocity by trapezoidal integration from rest, no correction.

    The trapezoidal rule is the exact integral of the piecewise-linear record.

    Parameters
    ----------
    acceleration_m_s2 : numpy.ndarray
        Ground acceleration samples [m/s²].
    dt_s : float
        Time step [s].
    time_s : numpy.ndarray, optional
        Sample times of a record with unequal steps (then ``dt_s`` is unused) [s].

    Returns
    -------
    numpy.ndarray
        Velocity at the samples, 0 at the first one [m/s].
    """
    return cumulative_trapezoid(acceleration_m_s2, dt_s, time_s)


def displacement_m(acceleration_m_s2: np.ndarray, dt_s: float, time_s=None) -> np.ndarray:
    """Ground displacement by double trapezoidal integration with a baseline correction.

    Raw double integration drifts: a small constant error in the acceleration (or an
    initial velocity) grows into a parabola in the displacement.  The correction removes
    the least-squares quadratic from the doubly-integrated displacement, which is the
    same as removing the best constant acceleration offset and initial velocity and
    displacement; it leaves a record that starts and ends near rest almost unchanged
    and does not filter.

    .. math:: d(t) = \\iint a \\,\\mathrm{d}t^2 - (c_0 + c_1 t + c_2 t^2)

    Parameters
    ----------
    acceleration_m_s2 : numpy.ndarray
        Ground acceleration samples [m/s²].
    dt_s : float
        Time step [s].
    time_s : numpy.ndarray, optional
        Sample times of a record with unequal steps (then ``dt_s`` is unused) [s].

    Returns
    -------
    numpy.ndarray
        Baseline-corrected displacement at the samples [m].
    """
    raw_m = cumulative_trapezoid(velocity_m_s(acceleration_m_s2, dt_s, time_s), dt_s, time_s)
    times_s = _times(raw_m.size, dt_s, time_s)
    if raw_m.size < 3:
        return raw_m - raw_m.mean()
    coefficients = np.polynomial.polynomial.polyfit(times_s, raw_m, 2)
    return raw_m - np.polynomial.polynomial.polyval(times_s, coefficients)


def arias_intensity_m_s(acceleration_m_s2: np.ndarray, dt_s: float, time_s=None) -> float:
    """Arias intensity.

    .. math:: I_A = \\frac{\\pi}{2 g} \\int_0^{t_f} a^2(t) \\,\\mathrm{d}t

    Parameters
    ----------
    acceleration_m_s2 : numpy.ndarray
        Ground acceleration samples [m/s²].
    dt_s : float
        Time step [s].
    time_s : numpy.ndarray, optional
        Sample times of a record with unequal steps (then ``dt_s`` is unused) [s].

    Returns
    -------
    float
        Arias intensity (trapezoidal rule) [m/s].
    """
    squared = np.asarray(acceleration_m_s2, dtype=float) ** 2
    steps = dt_s if time_s is None else np.diff(np.asarray(time_s, dtype=float))
    integral = (steps * (squared[1:] + squared[:-1]) / 2.0).sum()  # scipy.integrate.trapezoid's operations
    return float(math.pi / (2.0 * STANDARD_GRAVITY) * integral)


def significant_duration_s(
    acceleration_m_s2: np.ndarray, dt_s: float, start_fraction: float = 0.05, end_fraction: float = 0.95,
    time_s=None,
) -> float:
    """Significant duration: time between two fractions of the Arias intensity (D5–95).

    Parameters
    ----------
    acceleration_m_s2 : numpy.ndarray
        Ground acceleration samples [m/s²].
    dt_s : float
        Time step [s].
    start_fraction, end_fraction : float, optional
        Fractions of the total Arias intensity that bound the interval [-].
    time_s : numpy.ndarray, optional
        Sample times of a record with unequal steps (then ``dt_s`` is unused) [s].

    Returns
    -------
    float
        Duration between the crossings of the exact integral of a² of the piecewise-linear
        record (:func:`energy_window_s`); 0 for a record of zeros [s].
    """
    window = arias_window_s(acceleration_m_s2, dt_s, start_fraction, end_fraction, time_s)
    return 0.0 if window is None else window[1] - window[0]


def arias_window_s(acceleration_m_s2: np.ndarray, dt_s: float, start_fraction: float = 0.05,
                   end_fraction: float = 0.95, time_s=None) -> tuple[float, float] | None:
    """Times at which the Arias intensity reaches two fractions of its total (D5–95 window).

    Parameters
    ----------
    acceleration_m_s2 : numpy.ndarray
        Ground acceleration samples [m/s²].
    dt_s : float
        Time step [s].
    start_fraction, end_fraction : float, optional
        Fractions of the total Arias intensity [-].
    time_s : numpy.ndarray, optional
        Sample times of a record with unequal steps (then ``dt_s`` is unused) [s].

    Returns
    -------
    tuple of float or None
        (start, end) from the first sample, the crossings of the exact integral of a² of the
        piecewise-linear record (:func:`energy_window_s`) [s]; None for a record of zeros.
    """
    return energy_window_s([acceleration_m_s2], dt_s, (start_fraction, end_fraction), time_s)


def energy_window_s(components, dt_s: float, fractions=(0.05, 0.95), time_s=None) -> tuple[float, ...] | None:
    """Times at which ∫ Σ_c a_c² dt of the piecewise-linear record reaches fractions of its total.

    The integral is exact for the record read as piecewise linear between its samples (on a step h,
    ∫ a² = h (a₀² + a₀a₁ + a₁²)/3, a cubic in the step's local time), and each crossing is the root of
    that cubic located by bisection to rounding: extra collinear samples change nothing (issue 26),
    where the trapezoidal rule on a² (which over-counts the squares of a line) moved D5–95 by ~5e-4.

    Parameters
    ----------
    components : sequence of numpy.ndarray
        Acceleration samples of one or more components on one time base [m/s²] (two for the
        resultant of a pair).
    dt_s : float
        Time step [s] (unused when ``time_s`` is given).
    fractions : sequence of float, optional
        Fractions of the total, each in [0, 1] [-].
    time_s : numpy.ndarray, optional
        Sample times of a record with unequal steps [s].

    Returns
    -------
    tuple of float or None
        One time per fraction, from the first sample [s]; None for a record of zeros.
    """
    values = [np.asarray(a, dtype=np.float64) for a in components]
    n = values[0].size
    times_s = _times(n, dt_s, time_s)
    if n < 2:
        return None
    steps = np.diff(times_s)
    a0 = np.stack([a[:-1] for a in values])
    a1 = np.stack([a[1:] for a in values])
    slope = a1 - a0
    # per step and power of the local time σ in [0, 1]: E(σ) = h (c1 σ + c2 σ² + c3 σ³)
    c1 = (a0 * a0).sum(axis=0)
    c2 = (a0 * slope).sum(axis=0)
    c3 = (slope * slope).sum(axis=0) / 3.0
    cumulative = np.concatenate(([0.0], np.cumsum(steps * (c1 + c2 + c3))))
    total = cumulative[-1]
    if not total > 0:
        return None
    out = []
    for fraction in fractions:
        target = float(fraction) * total
        k = int(np.clip(np.searchsorted(cumulative, target, side="left") - 1, 0, n - 2))
        low, high = 0.0, 1.0
        for _ in range(80):  # bounded: the bracket halves to below rounding well before 80 steps
            sigma = 0.5 * (low + high)
            value = cumulative[k] + steps[k] * sigma * (c1[k] + sigma * (c2[k] + sigma * c3[k]))
            if value < target:
                low = sigma
            else:
                high = sigma
            if high - low <= 1e-17:
                break
        out.append(float(times_s[k] + 0.5 * (low + high) * steps[k]))
    return tuple(out)



@dataclass(frozen=True)
class IntensityMeasures:
    """Intensity measures of a ground motion; every name carries its unit.

    ``a0_equiv_m`` = PGV²/PGA and ``omega_equiv_rad_s`` = PGA/PGV are the amplitude and
    angular frequency of the harmonic ground motion with the same PGA and PGV (exact for
    a harmonic record); they map a record onto the paper's harmonic parameters.
    """

    pga_m_s2: float
    pgv_m_s: float
    pgd_m: float
    arias_m_s: float
    d5_95_s: float
    predominant_period_s: float
    a0_equiv_m: float
    omega_equiv_rad_s: float

    def as_dict(self) -> dict[str, float]:
        """The measures as a plain dict of floats."""
        return asdict(self)


def intensity_measures(acceleration_m_s2: np.ndarray, dt_s: float, time_s=None) -> IntensityMeasures:
    """Intensity measures of an acceleration history.

    PGV is the peak of the raw trapezoidal integral from rest (what strong-motion tables
    such as ``../shared/records/README.md`` quote for unfiltered records); PGD uses the
    baseline-corrected double integral (:func:`displacement_m`); the predominant period
    is the period of the peak of the 5 %-damped pseudo-acceleration spectrum over
    ``PREDOMINANT_PERIODS_S``.

    Parameters
    ----------
    acceleration_m_s2 : numpy.ndarray
        Ground acceleration samples [m/s²].
    dt_s : float
        Time step [s].
    time_s : numpy.ndarray, optional
        Sample times of a record with unequal steps (then ``dt_s`` is unused) [s].

    Returns
    -------
    IntensityMeasures
        PGA [m/s²], PGV [m/s], PGD [m], Arias [m/s], D5–95 [s], predominant period [s],
        A0 = PGV²/PGA [m], Ω = PGA/PGV [rad/s] (NaN when PGA or PGV is zero).
    """
    acceleration_m_s2 = np.asarray(acceleration_m_s2, dtype=np.float64)
    pga_m_s2 = float(np.max(np.abs(acceleration_m_s2)))
    pgv_m_s = float(np.max(np.abs(velocity_m_s(acceleration_m_s2, dt_s, time_s))))
    pgd_m = float(np.max(np.abs(displacement_m(acceleration_m_s2, dt_s, time_s))))
    psa_m_s2 = pseudo_acceleration_spectrum(acceleration_m_s2, dt_s, PREDOMINANT_PERIODS_S, time_s=time_s)
    predominant_period_s = float(PREDOMINANT_PERIODS_S[int(np.argmax(psa_m_s2))]) if pga_m_s2 > 0 else math.nan
    both = pga_m_s2 > 0 and pgv_m_s > 0
    return IntensityMeasures(
        pga_m_s2=pga_m_s2,
        pgv_m_s=pgv_m_s,
        pgd_m=pgd_m,
        arias_m_s=arias_intensity_m_s(acceleration_m_s2, dt_s, time_s),
        d5_95_s=significant_duration_s(acceleration_m_s2, dt_s, time_s=time_s),
        predominant_period_s=predominant_period_s,
        a0_equiv_m=pgv_m_s**2 / pga_m_s2 if both else math.nan,
        omega_equiv_rad_s=pga_m_s2 / pgv_m_s if both else math.nan,
    )

