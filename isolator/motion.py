"""Ground motion: a recorded acceleration history in m/s², its processing and intensity measures.

:func:`read_ground_motion` turns a record file — anything :func:`obspy.read` reads
(MiniSEED, SAC, K-NET, GSE2, SEISAN, …) plus isolator's own plugins (PEER AT2, CSMIP V2,
USGS SMC, plain text, see :mod:`isolator.io`) — into a :class:`GroundMotion`: one obspy
``Trace`` of float64 acceleration in m/s², with where its units came from, its
provenance and the list of processing steps applied.  Every malformed input raises
:class:`RecordError`, a one-line message naming the file and the problem.

Units are never guessed: they come from the file (AT2: g; V2, SMC: cm/s²; K-NET: the
header's scale factor; SAC: ``kuser0``), from an instrument response (StationXML), or
from the caller (``units=``, the CLI's ``--units``).  A record whose units are known
from nowhere is refused.

Reading applies no processing, with one exception that follows the data provider's own
convention: K-NET records have their mean removed (NIED's "counts × scale factor, minus
the mean").  It is recorded in :attr:`GroundMotion.processing` like any other step.
Processing methods (:meth:`GroundMotion.demeaned`, :meth:`~GroundMotion.tapered`,
:meth:`~GroundMotion.bandpassed`, …) use obspy's Trace methods and return a new object.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from isolator.units import STANDARD_GRAVITY, UnitsError, acceleration_factor_to_m_s2

MAX_ABS_ACCELERATION_G = 50.0  # [g] larger peaks are refused as a sign of wrong units
MIN_SAMPLES = 2  # a record needs at least two samples to have a time step
DEFAULT_DAMPING_RATIO = 0.05  # [-] response spectra are 5 % damped unless asked otherwise
#: Periods searched for the predominant period (peak of the 5 %-damped PSA) [s].
PREDOMINANT_PERIODS_S = np.geomspace(0.02, 5.0, 100)
#: Suffixes read as plain text when no reader claims the file by content.
TEXT_SUFFIXES = frozenset({".txt", ".csv", ".acc", ".dat", ".tsv", ".asc", ".th", ".xy"})
UNNAMED_COMPONENT = "unnamed"  # label of the one component of a file that names none
#: SAC ``idep`` codes for quantities that are not acceleration.
_SAC_NOT_ACCELERATION = {6: "displacement (IDISP)", 7: "velocity (IVEL)"}


_FORMAT_NAMES = {"PEER_AT2": "PEER AT2", "ISOLATOR_TEXT": "plain text", "CSMIP_V2": "CSMIP V2",
                 "USGS_SMC": "USGS SMC"}


class RecordError(ValueError):
    """A record that cannot be turned into a ground motion; the message is one line naming the file."""


def _one_line(message: str) -> str:
    return " ".join(str(message).split())


def _fail(path: Path | str, message: str) -> RecordError:
    return RecordError(_one_line(f"{path}: {message}"))


# --------------------------------------------------------------------------------------
# Intensity measures (pure functions on arrays)
# --------------------------------------------------------------------------------------


def _spacing(dt_s: float, time_s) -> dict:
    """The spacing argument of scipy's trapezoid rules: equal steps, or the sample times."""
    return {"dx": dt_s} if time_s is None else {"x": np.asarray(time_s, dtype=np.float64)}


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
    from scipy.integrate import cumulative_trapezoid

    return cumulative_trapezoid(acceleration_m_s2, initial=0.0, **_spacing(dt_s, time_s))


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
    from scipy.integrate import cumulative_trapezoid

    raw_m = cumulative_trapezoid(velocity_m_s(acceleration_m_s2, dt_s, time_s), initial=0.0,
                                 **_spacing(dt_s, time_s))
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
    from scipy.integrate import trapezoid as _trapezoid

    return float(math.pi / (2.0 * STANDARD_GRAVITY) * _trapezoid(acceleration_m_s2**2, **_spacing(dt_s, time_s)))


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
        Duration, the crossing times linearly interpolated on the cumulative
        (trapezoidal) integral of a²; 0 for a record of zeros [s].
    """
    from scipy.integrate import cumulative_trapezoid

    cumulative = cumulative_trapezoid(acceleration_m_s2**2, initial=0.0, **_spacing(dt_s, time_s))
    total = cumulative[-1]
    if not total > 0:
        return 0.0
    times_s = _times(cumulative.size, dt_s, time_s)
    start_s, end_s = np.interp([start_fraction * total, end_fraction * total], cumulative, times_s)
    return float(end_s - start_s)


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

    return np.asarray(solver_spectrum(np.ascontiguousarray(acceleration_m_s2, dtype=np.float64), float(dt_s),
                                      periods_s, damping_ratio=damping_ratio, time_s=time_s))


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


# --------------------------------------------------------------------------------------
# GroundMotion
# --------------------------------------------------------------------------------------


def _component_names(trace) -> dict[str, str]:
    """Channel code and orientation/component name of a trace, whatever its format."""
    stats = trace.stats
    orientation = ""
    for key, attribute in (("peer_at2", "component"), ("csmip_v2", "orientation"), ("usgs_smc", "component"),
                           ("isolator_text", "component")):
        if key in stats:
            orientation = str(stats[key].get(attribute, "") or "")
            break
    return {"channel": stats.channel or "", "orientation": orientation}


def _label(trace) -> str:
    """How a component is shown to the user: channel code, orientation, or both."""
    names = _component_names(trace)
    channel, orientation = names["channel"], names["orientation"]
    if channel and orientation and orientation.lower() != channel.lower():
        return f"{channel} ({orientation})"
    return channel or orientation or UNNAMED_COMPONENT


@dataclass(frozen=True, eq=False)  # compared and hashed by identity: it wraps a mutable Trace
class GroundMotion:
    """A ground acceleration history in m/s² around one obspy :class:`~obspy.Trace`.

    Build it with :func:`read_ground_motion` or :meth:`from_array`.  Processing methods
    return a new GroundMotion with the step appended to :attr:`processing`.

    Samples need not be evenly spaced (digitised analogue records): the times are then
    kept in ``trace.stats.sample_time_s`` (from the first sample [s]), :attr:`time_s`
    returns them, :attr:`dt_s` is the mean step and :attr:`sample_times_s` is not
    None; the solvers and intensity measures use the times, and the processing steps
    that assume equal steps (filters, taper, detrend, FFT resampling) refuse such a
    record until it is resampled (``resampled(dt, method="linear")``).

    Attributes
    ----------
    trace : obspy.Trace
        The acceleration, float64 [m/s²]; ``stats.units == "m/s2"``; the format header
        kept by the reader (``stats.peer_at2``, ``stats.sac``, …).
    units_source : str
        Where the units came from, e.g. ``"file header (AT2: g)"``, ``"--units g"`` [-].
    provenance : dict
        Path, format, network/station/channel, component, event and date when known [-].
    processing : list of dict
        Steps applied since reading, in order, each ``{"step": name, …parameters}`` [-].
    component : str
        The component read, as listed by :func:`list_components` [-].
    components : list of str
        All components the source file holds [-].
    """

    trace: Any
    units_source: str
    provenance: dict = field(default_factory=dict)
    processing: list = field(default_factory=list)
    component: str = ""
    components: list = field(default_factory=list)

    # ---- construction --------------------------------------------------------------

    @classmethod
    def from_array(
        cls,
        acceleration_m_s2: np.ndarray,
        dt_s: float | None = None,
        *,
        time_s: np.ndarray | None = None,
        units_source: str = "array in m/s2",
        component: str = "",
        provenance: dict | None = None,
    ) -> GroundMotion:
        """A GroundMotion from samples already in m/s² (synthetic or computed records).

        Parameters
        ----------
        acceleration_m_s2 : numpy.ndarray
            Acceleration samples [m/s²].
        dt_s : float, optional
            Time step, > 0 [s]; or give ``time_s``.
        time_s : numpy.ndarray, optional
            Sample times, strictly increasing; unequal steps are kept [s].
        units_source : str, optional
            Description of where the units came from [-].
        component : str, optional
            Component name [-].
        provenance : dict, optional
            Extra provenance entries [-].

        Returns
        -------
        GroundMotion
        """
        from obspy import Trace

        data = np.array(acceleration_m_s2, dtype=np.float64)
        if data.ndim != 1 or data.size < MIN_SAMPLES:
            raise ValueError(f"need a 1-D array of at least {MIN_SAMPLES} samples")
        sample_times_s = None
        if time_s is not None:
            from isolator.solver.record import RecordInputError, sample_timing

            if np.shape(time_s) != data.shape:
                raise ValueError(f"time_s {np.shape(time_s)} and acceleration {data.shape} differ in shape")
            try:
                dt_s, sample_times_s = sample_timing(time_s)
            except RecordInputError as err:
                raise ValueError(str(err)) from None
        if dt_s is None or not dt_s > 0:
            raise ValueError(f"dt_s = {dt_s} s is not positive")
        if not np.all(np.isfinite(data)):
            raise ValueError("acceleration holds NaN or infinite values")
        trace = Trace(data=data)
        trace.stats.delta = float(dt_s)
        trace.stats.units = "m/s2"
        if sample_times_s is not None:
            trace.stats.sample_time_s = sample_times_s
        return cls(trace=trace, units_source=units_source, provenance={"format": "array", **(provenance or {})},
                   component=component, components=[component] if component else [])

    def _derived(self, trace, step: dict) -> GroundMotion:
        trace.data = np.ascontiguousarray(trace.data, dtype=np.float64)
        return GroundMotion(trace=trace, units_source=self.units_source, provenance=self.provenance,
                            processing=[*self.processing, step], component=self.component,
                            components=list(self.components))

    # ---- data ----------------------------------------------------------------------

    @property
    def acceleration_m_s2(self) -> np.ndarray:
        """Acceleration samples, float64 [m/s²]."""
        return self.trace.data

    @property
    def dt_s(self) -> float:
        """Time step; the mean step when the steps are unequal (see :attr:`sample_times_s`) [s]."""
        return float(self.trace.stats.delta)

    @property
    def sample_times_s(self) -> np.ndarray | None:
        """Sample times from the first one when the steps are unequal, else None [s]."""
        return self.trace.stats.get("sample_time_s")

    @property
    def is_uniform(self) -> bool:
        """True when every step equals :attr:`dt_s` [-]."""
        return self.sample_times_s is None

    @property
    def npts(self) -> int:
        """Number of samples [-]."""
        return int(self.trace.stats.npts)

    @property
    def time_s(self) -> np.ndarray:
        """Time of each sample from the first one [s]."""
        if self.sample_times_s is not None:
            return np.array(self.sample_times_s)
        return np.arange(self.npts) * self.dt_s

    @property
    def duration_s(self) -> float:
        """Time from the first to the last sample [s]."""
        if self.sample_times_s is not None:
            return float(self.sample_times_s[-1])
        return (self.npts - 1) * self.dt_s

    def _require_uniform(self, what: str) -> None:
        if self.sample_times_s is not None:
            raise ValueError(f"{what} needs evenly spaced samples; this record's steps are unequal "
                             "(resample it first: resampled(dt_s, method='linear'))")

    @property
    def pga_m_s2(self) -> float:
        """Peak ground acceleration [m/s²]."""
        return float(np.max(np.abs(self.acceleration_m_s2)))

    def intensity_measures(self) -> IntensityMeasures:
        """Intensity measures of this motion (see :func:`intensity_measures`)."""
        return intensity_measures(self.acceleration_m_s2, self.dt_s, self.sample_times_s)

    def response_spectrum(
        self, periods_s: np.ndarray, damping_ratio: float = DEFAULT_DAMPING_RATIO
    ) -> np.ndarray:
        """Pseudo-acceleration response spectrum (see :func:`pseudo_acceleration_spectrum`).

        Parameters
        ----------
        periods_s : numpy.ndarray
            Oscillator periods [s].
        damping_ratio : float, optional
            Fraction of critical damping [-].

        Returns
        -------
        numpy.ndarray
            Pseudo-spectral acceleration [m/s²].
        """
        return pseudo_acceleration_spectrum(self.acceleration_m_s2, self.dt_s, periods_s, damping_ratio,
                                            time_s=self.sample_times_s)

    # ---- processing (obspy Trace methods on a copy) ------------------------------------

    def demeaned(self) -> GroundMotion:
        """Remove the mean (obspy ``detrend("demean")``)."""
        self._require_uniform("demean")
        trace = self.trace.copy()
        trace.detrend("demean")
        return self._derived(trace, {"step": "demean"})

    def baseline_corrected(self, order: int = 1) -> GroundMotion:
        """Remove the least-squares polynomial of ``order`` (obspy ``detrend``).

        Parameters
        ----------
        order : int, optional
            Polynomial order: 0 the mean, 1 a straight line [-].
        """
        self._require_uniform("baseline correction")
        trace = self.trace.copy()
        if order == 0:
            trace.detrend("demean")
        elif order == 1:
            trace.detrend("linear")
        else:
            trace.detrend("polynomial", order=int(order))
        return self._derived(trace, {"step": "baseline", "order": int(order)})

    def tapered(self, max_percentage: float = 0.05, taper_type: str = "hann") -> GroundMotion:
        """Taper both ends (obspy ``taper``).

        Parameters
        ----------
        max_percentage : float, optional
            Fraction of the record tapered at each end [-].
        taper_type : str, optional
            Window name understood by obspy [-].
        """
        self._require_uniform("taper")
        trace = self.trace.copy()
        trace.taper(max_percentage=max_percentage, type=taper_type)
        return self._derived(trace, {"step": "taper", "max_percentage": max_percentage, "type": taper_type})

    def bandpassed(
        self, freqmin_hz: float, freqmax_hz: float, corners: int = 4, zerophase: bool = True
    ) -> GroundMotion:
        """Butterworth band-pass (obspy ``filter("bandpass")``).

        Parameters
        ----------
        freqmin_hz, freqmax_hz : float
            Corner frequencies, 0 < freqmin < freqmax < Nyquist [Hz].
        corners : int, optional
            Filter order [-].
        zerophase : bool, optional
            Run forwards and backwards (no phase shift) [-].
        """
        self._require_uniform("band-pass")
        nyquist_hz = 0.5 / self.dt_s
        if not 0 < freqmin_hz < freqmax_hz < nyquist_hz:
            raise ValueError(
                f"band-pass needs 0 < freqmin < freqmax < Nyquist = {nyquist_hz:g} Hz "
                f"(got {freqmin_hz:g}, {freqmax_hz:g})"
            )
        trace = self.trace.copy()
        trace.filter("bandpass", freqmin=freqmin_hz, freqmax=freqmax_hz, corners=corners, zerophase=zerophase)
        return self._derived(trace, {"step": "bandpass", "freqmin_hz": freqmin_hz, "freqmax_hz": freqmax_hz,
                                     "corners": corners, "zerophase": zerophase})

    def resampled(self, dt_s: float, method: str = "fft") -> GroundMotion:
        """Resample to a new time step.

        Parameters
        ----------
        dt_s : float
            New time step [s].
        method : {"fft", "linear", "lanczos"}, optional
            ``"fft"``: obspy ``resample`` (Fourier, band-limited); ``"linear"`` or
            ``"lanczos"``: obspy ``interpolate`` (no anti-alias filter: use it to refine) [-].
            A record with unequal steps accepts ``"linear"`` only: the piecewise-linear
            record sampled at ``t0 + k dt``.
        """
        if not dt_s > 0:
            raise ValueError(f"target dt_s = {dt_s} s is not positive")
        if self.sample_times_s is not None and method == "linear":
            times_s = self.sample_times_s
            grid_s = dt_s * np.arange(int(math.floor(times_s[-1] / dt_s * (1 + 1e-12))) + 1)
            trace = self.trace.copy()
            del trace.stats.sample_time_s
            trace.data = np.interp(grid_s, times_s, self.trace.data)
            trace.stats.delta = float(dt_s)
            return self._derived(trace, {"step": "resample", "dt_s": dt_s, "method": "linear",
                                         "from": "unequal steps"})
        self._require_uniform(f"{method} resampling")
        trace = self.trace.copy()
        if method == "fft":
            trace.resample(1.0 / dt_s)
        elif method in ("linear", "lanczos"):
            options = {"a": 20} if method == "lanczos" else {}
            trace.interpolate(sampling_rate=1.0 / dt_s, method=method, **options)
        else:
            raise ValueError(f"unknown resampling method {method!r} (fft, linear, lanczos)")
        return self._derived(trace, {"step": "resample", "dt_s": dt_s, "method": method})

    def trimmed(self, start_s: float | None = None, end_s: float | None = None) -> GroundMotion:
        """Keep the samples between two times measured from the first sample (obspy ``trim``).

        Parameters
        ----------
        start_s, end_s : float, optional
            Window bounds from the first sample; None keeps that end [s].
        """
        if self.sample_times_s is not None:
            return self._trimmed_by_times(start_s, end_s)
        trace = self.trace.copy()
        origin = trace.stats.starttime
        trace.trim(None if start_s is None else origin + start_s, None if end_s is None else origin + end_s,
                   nearest_sample=True)
        if trace.stats.npts < MIN_SAMPLES:
            raise ValueError(f"trimming to [{start_s}, {end_s}] s leaves fewer than {MIN_SAMPLES} samples")
        return self._derived(trace, {"step": "trim", "start_s": start_s, "end_s": end_s})

    def _trimmed_by_times(self, start_s: float | None, end_s: float | None) -> GroundMotion:
        # unequal steps: keep the samples inside the window (nearest sample at each end)
        times_s = self.sample_times_s
        first = 0 if start_s is None else int(np.argmin(np.abs(times_s - start_s)))
        last = times_s.size - 1 if end_s is None else int(np.argmin(np.abs(times_s - end_s)))
        if last - first + 1 < MIN_SAMPLES:
            raise ValueError(f"trimming to [{start_s}, {end_s}] s leaves fewer than {MIN_SAMPLES} samples")
        trace = self.trace.copy()
        trace.data = np.ascontiguousarray(self.trace.data[first:last + 1])
        trace.stats.starttime = self.trace.stats.starttime + float(times_s[first])
        kept_s = times_s[first:last + 1] - times_s[first]
        trace.stats.delta = float(kept_s[-1] / (kept_s.size - 1))
        trace.stats.sample_time_s = kept_s
        return self._derived(trace, {"step": "trim", "start_s": start_s, "end_s": end_s})

    def scaled(self, factor: float) -> GroundMotion:
        """Multiply the acceleration by ``factor`` [-]."""
        if not math.isfinite(factor):
            raise ValueError(f"scale factor {factor} is not finite")
        trace = self.trace.copy()
        trace.data = trace.data * float(factor)
        return self._derived(trace, {"step": "scale", "factor": float(factor)})

    def scaled_to_pga(self, pga_m_s2: float) -> GroundMotion:
        """Scale so that the peak ground acceleration equals ``pga_m_s2`` [m/s²]."""
        current_m_s2 = self.pga_m_s2
        if not current_m_s2 > 0:
            raise ValueError("cannot scale a record of zeros to a PGA")
        if not pga_m_s2 > 0:
            raise ValueError(f"target PGA {pga_m_s2} m/s² is not positive")
        scaled = self.scaled(pga_m_s2 / current_m_s2)
        last = dict(scaled.processing[-1], target_pga_m_s2=float(pga_m_s2))
        return GroundMotion(trace=scaled.trace, units_source=self.units_source, provenance=self.provenance,
                            processing=[*self.processing, last], component=self.component,
                            components=list(self.components))


# --------------------------------------------------------------------------------------
# Reading
# --------------------------------------------------------------------------------------


def _read_stream(path: Path, dt_s: float | None):
    """obspy.read with our plugins; explicit text reading as the fallback; RecordError otherwise."""
    import obspy

    from isolator.io._common import looks_like_text, read_head
    from isolator.io.at2 import _is_at2
    from isolator.io.smc import _is_smc
    from isolator.io.text import _is_text
    from isolator.io.v2 import _is_v2

    own_detectors = {"PEER_AT2": _is_at2, "CSMIP_V2": _is_v2, "USGS_SMC": _is_smc, "ISOLATOR_TEXT": _is_text}
    head = read_head(path)
    if not head:
        raise _fail(path, "file is empty")
    if not head.strip():
        raise _fail(path, "file holds only blank space")
    suffix = path.suffix.lower()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        fmt = None
        if suffix == ".at2" and not _is_at2(path):
            if not looks_like_text(head):
                raise _fail(path, "binary content: not a PEER AT2 text file")
            fmt = "PEER_AT2"  # let the AT2 reader say what is wrong
        else:  # our own formats first: their errors then name the format, and --dt reaches text
            fmt = next((name for name, detect in own_detectors.items() if detect(path)), None)
        try:
            if fmt is None:
                try:
                    return obspy.read(str(path))
                except TypeError as err:
                    if "Unknown format" not in str(err):
                        raise
                if not looks_like_text(head):
                    raise _fail(path, "unrecognised binary format (not one obspy or isolator reads)")
                if suffix not in TEXT_SUFFIXES and not _plain_numeric(head):
                    raise _fail(path, "unsupported format: not a format obspy reads, nor AT2, V2, SMC "
                                      "or plain numeric columns")
                fmt = "ISOLATOR_TEXT"
            options = {"dt_s": dt_s} if fmt == "ISOLATOR_TEXT" else {}
            return obspy.read(str(path), format=fmt, **options)
        except RecordError:
            raise
        except Exception as err:  # obspy's readers raise many types for damaged files
            reason = _one_line(err) or type(err).__name__
            if fmt in _FORMAT_NAMES:  # our readers' messages say exactly what is wrong
                raise _fail(path, f"{_FORMAT_NAMES[fmt]}: {reason}") from None
            raise _fail(path, f"cannot be read with obspy: {reason}") from None


def _plain_numeric(head: bytes) -> bool:
    """True if the head's first non-comment line is made of numbers (a headerless text record)."""
    from isolator.io._common import head_lines
    from isolator.io.text import _is_comment, _numeric_fields

    lines = [line for line in head_lines(head) if not _is_comment(line)]
    return bool(lines) and _numeric_fields(lines[0]) in (1, 2)


def _axis_letter(name: str) -> str:
    """N, E or Z for an orientation name: azimuths on the N-S (0, 180, 360) or E-W (90, 270)
    axis, K-NET's NS/EW/UD, Up/Down; "" otherwise."""
    name = name.strip().upper()
    if name in ("NS", "N-S"):
        return "N"
    if name in ("EW", "E-W"):
        return "E"
    if name in ("UD", "U-D", "UP", "DOWN", "VERT", "Z"):
        return "Z"
    try:
        azimuth_deg = float(name)
    except ValueError:
        return ""
    remainder = azimuth_deg % 180.0
    return "N" if remainder == 0.0 else ("E" if remainder == 90.0 else "")


def _matches(trace, wanted: str) -> bool:
    names = _component_names(trace)
    channel = names["channel"]
    candidates = {trace.id, channel, names["orientation"], _label(trace)}
    candidates.add(_axis_letter(names["orientation"]) or _axis_letter(channel))
    if len(channel) == 3:
        candidates.add(channel[2])
    wanted = wanted.strip().lower()
    return wanted in {c.lower() for c in candidates if c}


def _select(path: Path, stream, component: str | None):
    labels = [_label(trace) for trace in stream]
    if component is None:
        if len(stream) == 1:
            return stream[0]
        raise _fail(path, f"holds {len(stream)} components ({', '.join(labels)}); choose one with --component")
    chosen = [trace for trace in stream if _matches(trace, component)]
    if not chosen:
        raise _fail(path, f"no component {component!r} (choices: {', '.join(labels)})")
    if len(chosen) > 1:
        names = ", ".join(f"{_label(t)} = {t.id}" for t in chosen)
        raise _fail(path, f"component {component!r} is ambiguous: it matches {names}; give the full trace id")
    return chosen[0]


def _check_gaps(path: Path, stream, merge: bool) -> list[dict]:
    gaps = stream.get_gaps()
    if not gaps:
        if len({trace.id for trace in stream}) < len(stream) and merge:
            stream.merge(method=1, fill_value="interpolate")
            return [{"step": "merge", "method": "obspy Stream.merge(method=1, fill_value='interpolate')",
                     "gaps": 0}]
        if len({trace.id for trace in stream}) < len(stream):
            raise _fail(path, "holds several segments of the same channel; pass --merge to join them")
        return []
    first = gaps[0]
    if not merge:
        kind = "overlap" if first[6] < 0 else "gap"
        raise _fail(
            path,
            f"{len(gaps)} gap(s)/overlap(s) in the data (first: {kind} of {abs(first[6]):g} s in "
            f"{'.'.join(first[:4])} at {first[4]}); pass --merge to join the segments, filling gaps "
            f"by linear interpolation",
        )
    stream.merge(method=1, fill_value="interpolate")
    return [{"step": "merge", "method": "obspy Stream.merge(method=1, fill_value='interpolate')",
             "gaps": len(gaps), "gap_lengths_s": [float(g[6]) for g in gaps]}]


def _units_factor(path: Path, units: str, source: str) -> float:
    try:
        return acceleration_factor_to_m_s2(units)
    except UnitsError as err:
        raise _fail(path, f"{err} ({source})") from None


def _file_units(trace) -> tuple[str | None, str]:
    """Units stated by the file itself, and a description of where they were found."""
    stats = trace.stats
    fmt = str(stats.get("_format", ""))
    if fmt == "PEER_AT2":
        return "g", "file header (AT2: g)"
    if fmt == "CSMIP_V2":
        return stats.units, f"file header (CSMIP V2: {stats.units})"
    if fmt == "USGS_SMC":
        return stats.units, "file format (USGS SMC corrected: cm/s2)"
    if fmt == "ISOLATOR_TEXT" and stats.get("units"):
        return stats.units, f"file header ('# units: {stats.units}')"
    if fmt == "SAC":
        stated = str(stats.sac.get("kuser0", "") or "").strip()
        if stated and stated.lower().replace(" ", "") in _known_units():
            return stated, f"SAC header kuser0 = {stated!r}"
    return None, ""


def _known_units() -> set[str]:
    from isolator.units import ACCELERATION_UNITS_TO_M_S2

    return set(ACCELERATION_UNITS_TO_M_S2)


def _to_m_s2(path: Path, trace, units, response, counts_factor) -> tuple[np.ndarray, str, list[dict]]:
    """Acceleration in m/s² and the description of the units' source."""
    stats = trace.stats
    fmt = str(stats.get("_format", ""))
    steps: list[dict] = []
    if fmt == "SAC" and int(stats.sac.get("idep", 5)) in _SAC_NOT_ACCELERATION:
        raise _fail(path, f"SAC header says the data are {_SAC_NOT_ACCELERATION[int(stats.sac.idep)]}, "
                          "not acceleration")
    if response is not None:
        if units is not None or counts_factor is not None:
            raise _fail(path, "give either an instrument response or --units/--counts-factor, not both")
        import obspy

        try:
            inventory = obspy.read_inventory(str(response))
            corrected = trace.copy()
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                corrected.remove_response(inventory=inventory, output="ACC")
        except Exception as err:
            raise _fail(path, f"cannot remove the instrument response from {response}: {_one_line(err)}") from None
        steps.append({"step": "remove_response", "inventory": str(response), "output": "ACC"})
        return corrected.data.astype(np.float64), f"instrument response ({Path(response).name}, output ACC)", steps
    if counts_factor is not None:
        if units is None:
            raise _fail(path, "--counts-factor needs --units for the units it converts counts into")
        if not (math.isfinite(counts_factor) and counts_factor > 0):
            raise _fail(path, f"counts factor {counts_factor} is not a positive number")
        factor = counts_factor * _units_factor(path, units, "--units")
        return _as_float64(trace) * factor, f"--counts-factor {counts_factor:g} {units} per count", steps
    if fmt == "KNET":
        # obspy's K-NET reader turns the header's 'Scale Factor' (gal per count) into calib [m/s² per count]
        data = _as_float64(trace) * float(stats.calib)
        steps.append({"step": "demean", "reason": "K-NET convention (NIED): counts × scale factor, minus the mean"})
        if units is not None and _units_factor(path, units, "--units") != 1.0:
            raise _fail(path, f"the K-NET scale factor gives m/s2 but --units says {units}")
        return data - data.mean(), "K-NET scale factor (header, gal per count → m/s2)", steps
    if np.issubdtype(trace.data.dtype, np.integer):
        raise _fail(path, "holds integer counts: give the instrument response (StationXML) or "
                          "--counts-factor with --units")
    file_units, source = _file_units(trace)
    if file_units is not None:
        factor = _units_factor(path, file_units, source)
        if units is not None and _units_factor(path, units, "--units") != factor:
            raise _fail(path, f"the file states {file_units} ({source}) but --units says {units}")
        return _as_float64(trace) * factor, source, steps
    if units is None:
        kind = fmt or "this"
        raise _fail(path, f"{kind} file does not state its units; pass --units (g, m/s2, gal, cm/s2)")
    channel = stats.channel or ""
    if fmt in ("MSEED", "SAC", "GSE2", "SEISAN") and len(channel) == 3 and channel[1] in "HL":
        raise _fail(path, f"channel {channel} is a seismometer (velocity) channel; acceleration from it "
                          "needs the instrument response")
    return _as_float64(trace) * _units_factor(path, units, "--units"), f"--units {units}", steps


def _as_float64(trace) -> np.ndarray:
    """The trace's samples as float64 (a masked array is refused upstream)."""
    return np.asarray(trace.data, dtype=np.float64)


def _check_values(path: Path, acceleration_m_s2: np.ndarray, dt_s: float) -> None:
    if acceleration_m_s2.size < MIN_SAMPLES:
        raise _fail(path, f"only {acceleration_m_s2.size} sample(s); a record needs at least {MIN_SAMPLES}")
    if not (math.isfinite(dt_s) and dt_s > 0):
        raise _fail(path, f"time step dt = {dt_s:g} s is not positive")
    finite = np.isfinite(acceleration_m_s2)
    if not finite.all():
        index = int(np.flatnonzero(~finite)[0])
        raise _fail(path, f"non-finite value ({acceleration_m_s2[index]}) at sample {index} "
                          f"(t = {index * dt_s:g} s)")
    peak_m_s2 = float(np.max(np.abs(acceleration_m_s2)))
    if peak_m_s2 > MAX_ABS_ACCELERATION_G * STANDARD_GRAVITY:
        raise _fail(path, f"peak |a| = {peak_m_s2:.4g} m/s2 ({peak_m_s2 / STANDARD_GRAVITY:.4g} g) exceeds "
                          f"{MAX_ABS_ACCELERATION_G:g} g: wrong units?")


def _provenance(path: Path, trace, label: str) -> dict:
    stats = trace.stats
    provenance: dict[str, Any] = {
        "path": str(path),
        "format": str(stats.get("_format", "")),
        "network": stats.network,
        "station": stats.station,
        "location": stats.location,
        "channel": stats.channel,
        "component": label,
    }
    if stats.starttime.timestamp != 0:
        provenance["starttime"] = str(stats.starttime)
    for key in ("peer_at2", "usgs_smc", "csmip_v2"):
        if key in stats:
            header = stats[key]
            for name in ("event", "date", "station_name"):
                if header.get(name):
                    provenance[name] = header[name]
            if key == "peer_at2" and header.get("station"):
                provenance["station"] = header["station"]
    if "knet" in stats:
        provenance["event_origin_time"] = str(stats.knet.get("evot", ""))
        provenance["magnitude"] = float(stats.knet.get("mag", math.nan))
    if "sac" in stats and stats.sac.get("kevnm"):
        provenance["event"] = str(stats.sac.kevnm).strip()
    return {key: value for key, value in provenance.items() if value not in ("", None)}


def _check_path(path: Path) -> None:
    if not path.exists():
        raise _fail(path, "no such file")
    if path.is_dir():
        raise _fail(path, "is a directory, not a record file")
    try:
        with open(path, "rb") as handle:
            handle.read(1)
    except OSError as err:
        raise _fail(path, f"cannot be opened: {err.strerror or err}") from None
    if path.stat().st_size == 0:
        raise _fail(path, "file is empty")


def list_components(path: str | Path, *, merge: bool = False) -> list[str]:
    """Components (channels) a record file holds, as accepted by ``component=``.

    Parameters
    ----------
    path : str or path-like
        Record file [-].
    merge : bool, optional
        Join segments of the same channel (see :func:`read_ground_motion`) [-].

    Returns
    -------
    list of str
        One label per component: channel code, orientation, or ``"HN1 (180)"`` [-].

    Raises
    ------
    RecordError
        If the file cannot be read.
    """
    path = Path(path)
    _check_path(path)
    stream = _read_stream(path, None)
    _check_gaps(path, stream, merge)
    return [_label(trace) for trace in stream]


def read_ground_motion(
    path: str | Path,
    *,
    component: str | None = None,
    units: str | None = None,
    merge: bool = False,
    response: str | Path | None = None,
    counts_factor: float | None = None,
    dt_s: float | None = None,
) -> GroundMotion:
    """Read a record file into a :class:`GroundMotion` in m/s².

    Parameters
    ----------
    path : str or path-like
        Record file: any obspy format, PEER AT2, CSMIP V2, USGS SMC or plain text [-].
    component : str, optional
        Channel code (``HNE``), its last letter (``E``), orientation (``180``, ``Up``,
        ``NS``), the axis letter of an orientation (``N`` for azimuth 0/180/360, ``E``
        for 90/270, ``Z`` for Up/UD) or trace id; required when the file holds several
        components [-].
    units : {"g", "m/s2", "gal", "cm/s2"}, optional
        Units of the values, for formats that do not state them; must agree with the
        file when it does [-].
    merge : bool, optional
        Join segments of a channel with gaps, filling gaps by linear interpolation
        (obspy ``Stream.merge(method=1, fill_value="interpolate")``); without it a gap
        is an error [-].
    response : str or path-like, optional
        StationXML inventory; the response is removed with obspy ``remove_response``
        (output acceleration) [-].
    counts_factor : float, optional
        Units (given by ``units``) per count, for records in counts [unit/count].
    dt_s : float, optional
        Time step of a one-column text file; checked against the file otherwise [s].

    Returns
    -------
    GroundMotion
        float64 acceleration [m/s²] with units source, provenance and (empty or
        provider-convention) processing.

    Raises
    ------
    RecordError
        One line naming the file and the problem: missing, empty, unrecognised or
        damaged file, truncated data, dt ≤ 0, NaN/inf, non-monotonic time, text in a
        numeric column, fewer than two samples, |a| > 50 g, gaps without ``merge``,
        unknown or conflicting units, ambiguous or unknown component.
    """
    path = Path(path)
    _check_path(path)
    if dt_s is not None and not (math.isfinite(dt_s) and dt_s > 0):
        raise _fail(path, f"--dt {dt_s:g} s is not positive")
    stream = _read_stream(path, dt_s)
    if len(stream) == 0:
        raise _fail(path, "holds no data")
    components = [_label(trace) for trace in stream]
    steps = _check_gaps(path, stream, merge)
    trace = _select(path, stream, component)
    if np.ma.isMaskedArray(trace.data):
        raise _fail(path, "data are masked (gaps); pass --merge")
    if trace.stats.npts < MIN_SAMPLES:
        raise _fail(path, f"only {trace.stats.npts} sample(s); a record needs at least {MIN_SAMPLES}")
    if dt_s is not None and abs(trace.stats.delta - dt_s) > 1e-9 * max(dt_s, 1.0):
        raise _fail(path, f"the file's time step is {trace.stats.delta:g} s but --dt says {dt_s:g} s")
    raw = np.asarray(trace.data, dtype=np.float64)
    finite = np.isfinite(raw)
    if not finite.all():
        index = int(np.flatnonzero(~finite)[0])
        raise _fail(path, f"non-finite value ({raw[index]}) at sample {index} (t = {index * trace.stats.delta:g} s)")
    acceleration_m_s2, units_source, unit_steps = _to_m_s2(path, trace, units, response, counts_factor)
    acceleration_m_s2 = np.ascontiguousarray(acceleration_m_s2, dtype=np.float64)
    _check_values(path, acceleration_m_s2, float(trace.stats.delta))
    label = _label(trace)
    result = trace.copy() if response is None else trace
    result.data = acceleration_m_s2
    result.stats.units = "m/s2"
    result.stats.units_source = units_source
    provenance = _provenance(path, trace, label)
    text_info = trace.stats.get("isolator_text") or {}
    if text_info.get("time_s") is not None:  # a time column with unequal steps: kept as it is
        result.stats.sample_time_s = np.asarray(text_info["time_s"], dtype=np.float64)
        steps_s = np.diff(result.stats.sample_time_s)
        provenance["sampling"] = f"unequal steps from {steps_s.min():g} to {steps_s.max():g} s"
    return GroundMotion(
        trace=result,
        units_source=units_source,
        provenance=provenance,
        processing=steps + unit_steps,
        component=label,
        components=components,
    )
