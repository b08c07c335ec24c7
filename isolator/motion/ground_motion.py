"""GroundMotion: an acceleration history in m/s² around one obspy Trace, and its processing.

Processing methods (:meth:`GroundMotion.demeaned`, :meth:`~GroundMotion.tapered`,
:meth:`~GroundMotion.bandpassed`, …) use obspy's Trace methods and return a new object
with the step appended to :attr:`GroundMotion.processing`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from isolator.errors import MotionError, RecordInputError
from isolator.motion.components import UNNAMED_COMPONENT  # noqa: F401 - the name callers know it by
from isolator.motion.measures import IntensityMeasures, intensity_measures
from isolator.motion.spectra import DEFAULT_DAMPING_RATIO, pseudo_acceleration_spectrum
from isolator.units import STANDARD_GRAVITY

MIN_SAMPLES = 2  # a record needs at least two samples to have a time step
MIN_TARGET_PGA_G = 1e-6  # [g] a smaller target PGA is below any accelerometer's noise
MAX_ABS_ACCELERATION_G = 50.0  # [g] larger peaks are refused as a sign of wrong units (and as a scaling target)


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

        raw = np.asarray(acceleration_m_s2)
        if raw.dtype.kind not in "biuf":  # complex, text, objects: not an accelerogram
            raise MotionError(f"acceleration_m_s2 must hold real numbers, got {raw.dtype}")
        data = np.array(raw, dtype=np.float64)
        if data.ndim != 1 or data.size < MIN_SAMPLES:
            raise MotionError(f"need a 1-D array of at least {MIN_SAMPLES} samples")
        sample_times_s = None
        if time_s is not None:
            from isolator.solver.record import sample_timing

            if np.shape(time_s) != data.shape:
                raise MotionError(f"time_s {np.shape(time_s)} and acceleration {data.shape} differ in shape")
            try:
                dt_s, sample_times_s = sample_timing(time_s)
            except RecordInputError as err:
                raise MotionError(str(err)) from None
        if isinstance(dt_s, bool) or not isinstance(dt_s, (int, float, np.integer, np.floating)):
            raise MotionError(f"dt_s must be a number of seconds, got {dt_s!r}")
        if not (math.isfinite(dt_s) and dt_s > 0):
            raise MotionError(f"dt_s = {dt_s} s is not a finite positive number")
        if not np.all(np.isfinite(data)):
            raise MotionError("acceleration holds NaN or infinite values")
        if np.max(np.abs(data)) > MAX_ABS_ACCELERATION_G * STANDARD_GRAVITY:  # what the readers refuse too
            raise MotionError(f"|acceleration| reaches {np.max(np.abs(data)):g} m/s², above "
                              f"{MAX_ABS_ACCELERATION_G:g} g: not an accelerogram in m/s²")
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
            raise MotionError(f"{what} needs evenly spaced samples; this record's steps are unequal "
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
            raise MotionError(
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
            raise MotionError(f"target dt_s = {dt_s} s is not positive")
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
            raise MotionError(f"unknown resampling method {method!r} (fft, linear, lanczos)")
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
            raise MotionError(f"trimming to [{start_s}, {end_s}] s leaves fewer than {MIN_SAMPLES} samples")
        return self._derived(trace, {"step": "trim", "start_s": start_s, "end_s": end_s})

    def _trimmed_by_times(self, start_s: float | None, end_s: float | None) -> GroundMotion:
        # unequal steps: keep the samples inside the window (nearest sample at each end)
        times_s = self.sample_times_s
        first = 0 if start_s is None else int(np.argmin(np.abs(times_s - start_s)))
        last = times_s.size - 1 if end_s is None else int(np.argmin(np.abs(times_s - end_s)))
        if last - first + 1 < MIN_SAMPLES:
            raise MotionError(f"trimming to [{start_s}, {end_s}] s leaves fewer than {MIN_SAMPLES} samples")
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
            raise MotionError(f"scale factor {factor} is not finite")
        trace = self.trace.copy()
        trace.data = trace.data * float(factor)
        return self._derived(trace, {"step": "scale", "factor": float(factor)})

    def scaled_to_pga(self, pga_m_s2: float) -> GroundMotion:
        """Scale so that the peak ground acceleration equals ``pga_m_s2`` [m/s²].

        The step appended to :attr:`processing` is ``{"step": "scale", "factor",
        "target_pga_m_s2", "from_pga_m_s2"}``; :attr:`scaling_note` says it in words.

        Raises
        ------
        MotionError
            A target that is not a number, a record of zeros, or a target outside [:data:`MIN_TARGET_PGA_G`,
            :data:`MAX_ABS_ACCELERATION_G`] g (see :func:`pga_scale_factor`).
        """
        if isinstance(pga_m_s2, bool) or not isinstance(pga_m_s2, (int, float, np.integer, np.floating)):
            raise MotionError(f"target PGA must be a number of m/s², got {pga_m_s2!r}")
        current_m_s2 = self.pga_m_s2
        scaled = self.scaled(pga_scale_factor(current_m_s2, pga_m_s2))
        last = dict(scaled.processing[-1], target_pga_m_s2=float(pga_m_s2), from_pga_m_s2=current_m_s2)
        return GroundMotion(trace=scaled.trace, units_source=self.units_source, provenance=self.provenance,
                            processing=[*self.processing, last], component=self.component,
                            components=list(self.components))

    @property
    def scaling_note(self) -> str:
        """The last scaling to a PGA in :attr:`processing`, in one sentence; "" when none [-]."""
        return scaling_note(self.processing)


def pga_scale_factor(current_pga_m_s2: float, target_pga_m_s2: float) -> float:
    """The factor that brings a record's PGA to a target: ``target / current`` [-].

    The one place the target is checked, for a component (:meth:`GroundMotion.scaled_to_pga`)
    and a pair (:meth:`~isolator.motion.MotionPair.scaled_to_pga`).

    Parameters
    ----------
    current_pga_m_s2 : float
        The record's PGA (a pair: its larger horizontal PGA) [m/s²].
    target_pga_m_s2 : float
        The PGA wanted, in [:data:`MIN_TARGET_PGA_G`, :data:`MAX_ABS_ACCELERATION_G`] g [m/s²].

    Raises
    ------
    MotionError
        A record of zeros; a target that is not positive, above 50 g (what the reader refuses
        is not reachable by scaling either) or below 1e-6 g (instrument noise).
    """
    from isolator.units import STANDARD_GRAVITY

    if not current_pga_m_s2 > 0:
        raise MotionError("cannot scale a record of zeros to a PGA")
    if not target_pga_m_s2 > 0:
        raise MotionError(f"target PGA {target_pga_m_s2} m/s² is not positive")
    target_g = target_pga_m_s2 / STANDARD_GRAVITY
    if target_g > MAX_ABS_ACCELERATION_G:
        raise MotionError(f"target PGA {target_g:g} g exceeds {MAX_ABS_ACCELERATION_G:g} g")
    if target_g < MIN_TARGET_PGA_G:
        raise MotionError(f"target PGA {target_g:g} g is below {MIN_TARGET_PGA_G:g} g (instrument noise; "
                          "the record's measures underflow)")
    return target_pga_m_s2 / current_pga_m_s2


def scaling_note(processing: list) -> str:
    """One sentence for the last scaling to a PGA among processing steps ("" when there is none).

    Parameters
    ----------
    processing : list of dict
        :attr:`GroundMotion.processing` or :attr:`~isolator.motion.MotionPair.processing` [-].
    """
    from isolator.units import STANDARD_GRAVITY

    step = next((s for s in reversed(processing) if "target_pga_m_s2" in s), None)
    if step is None:
        return ""
    target_g, factor = step["target_pga_m_s2"] / STANDARD_GRAVITY, step["factor"]
    from_g = step.get("from_pga_m_s2", step["target_pga_m_s2"] / factor) / STANDARD_GRAVITY
    if step.get("measured_on"):
        return (f"Record scaled to the design PGA {target_g:g} g by one factor {factor:.4g} on every component "
                f"(its {step['measured_on']} PGA was {from_g:.4g} g).")
    return f"Record scaled to the design PGA {target_g:g} g (from {from_g:.4g} g, factor {factor:.4g})."
