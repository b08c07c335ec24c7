"""Ground-motion pairs: the two horizontal components (and the vertical) of one station.

:func:`read_ground_motion_pair` reads the components of a bidirectional analysis into a
:class:`MotionPair` of :class:`~isolator.motion.GroundMotion` objects on one time base:

* from two (or three) files, one component each: ``read_ground_motion_pair(x, y, z)``;
* from one file that holds several channels (CSMIP V2, MiniSEED/SAC streams) with
  ``component="pair"`` (the two horizontals, in the file's order) or ``"all"`` (with the
  vertical); a K-NET / KiK-net file (``.NS``, ``.EW``, ``.UD``, ``.NS2`` …) brings its
  sibling files of the same set.

Each file is read by :func:`~isolator.motion.read_ground_motion`, so the units rules
are the same as for one component, per file.  Components that do not share their time
step, length or start time are refused (:class:`ComponentMismatchError`, saying which)
unless the caller asks for ``trim=True`` (cut to the common window; equal steps on one
grid needed) or ``resample=True`` (the union of the components' sample times over the
common window, each component linearly interpolated onto it — the same
piecewise-linear signals, so nothing is approximated; the steps may become unequal,
which the solvers take as they are).  Either is recorded in :attr:`MotionPair.processing`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from isolator.errors import ComponentError, ComponentMismatchError, RecordValuesError
from isolator.motion.components import is_vertical, label_is_vertical
from isolator.motion.files import knet_siblings
from isolator.motion.ground_motion import GroundMotion, pga_scale_factor, scaling_note
from isolator.motion.read import list_components, read_ground_motion, read_ground_motions

#: Relative tolerance on equal time steps and on start times (fraction of the step).
TIME_TOLERANCE = 1e-6
PAIR_CHOICES = ("pair", "all")


@dataclass(frozen=True, eq=False)
class MotionPair:
    """Two horizontal ground motions (X, Y) and optionally the vertical (Z), on one time base.

    Attributes
    ----------
    x : GroundMotion
        The first horizontal component [m/s²] (the first in the file's or the command
        line's order).
    y : GroundMotion or None
        The second horizontal component [m/s²]; None for one horizontal with a vertical.
    z : GroundMotion or None
        The vertical component, positive up [m/s²].
    processing : list of dict
        Steps applied to the set (trimming to a common window, a common time grid) [-].
    """

    x: GroundMotion
    y: GroundMotion | None = None
    z: GroundMotion | None = None
    processing: list = field(default_factory=list)

    @property
    def components(self) -> dict[str, GroundMotion]:
        """The components present, by axis name ``x``, ``y`` (and ``z``)."""
        out = {"x": self.x}
        if self.y is not None:
            out["y"] = self.y
        if self.z is not None:
            out["z"] = self.z
        return out

    @property
    def dt_s(self) -> float:
        """Time step (mean step when unequal) [s]."""
        return self.x.dt_s

    @property
    def npts(self) -> int:
        """Number of samples of each component [-]."""
        return self.x.npts

    @property
    def time_s(self) -> np.ndarray:
        """Sample times from the first one [s]."""
        return self.x.time_s

    @property
    def sample_times_s(self) -> np.ndarray | None:
        """Sample times when the steps are unequal, else None [s]."""
        return self.x.sample_times_s

    @property
    def duration_s(self) -> float:
        """Time from the first to the last sample [s]."""
        return self.x.duration_s

    def scaled(self, factor: float) -> MotionPair:
        """All components multiplied by one ``factor`` [-] (keeps the direction of shaking)."""
        return MotionPair(*(None if m is None else m.scaled(factor) for m in (self.x, self.y, self.z)),
                          processing=list(self.processing))

    @property
    def horizontal_pga_m_s2(self) -> float:
        """The larger PGA of the horizontal components [m/s²]."""
        return max(m.pga_m_s2 for axis, m in self.components.items() if axis != "z")

    def scaled_to_pga(self, pga_m_s2: float) -> MotionPair:
        """Every component scaled by the one factor that brings the larger horizontal PGA to ``pga_m_s2`` [m/s²].

        One factor keeps the direction of shaking and the ratio of the vertical to the
        horizontals.  The step ``{"step": "scale_to_pga", "factor", "target_pga_m_s2",
        "from_pga_m_s2", "measured_on"}`` is appended to :attr:`processing` (each component
        records its ``scale`` step); :attr:`scaling_note` says it in words.

        Raises
        ------
        MotionError
            Every horizontal component is zero, or the target is outside [1e-6, 50] g
            (:func:`~isolator.motion.ground_motion.pga_scale_factor`).
        """
        current_m_s2 = self.horizontal_pga_m_s2
        factor = pga_scale_factor(current_m_s2, pga_m_s2)
        scaled = self.scaled(factor)
        step = {"step": "scale_to_pga", "factor": float(factor), "target_pga_m_s2": float(pga_m_s2),
                "from_pga_m_s2": current_m_s2, "measured_on": "larger horizontal"}
        return MotionPair(scaled.x, scaled.y, scaled.z, processing=[*self.processing, step])

    @property
    def scaling_note(self) -> str:
        """The scaling to a PGA in :attr:`processing`, in one sentence; "" when none [-]."""
        return scaling_note(self.processing)

    def describe(self) -> dict:
        """Path, component label, PGA and units source of each component (for JSON output)."""
        return {name: {"path": motion.provenance.get("path", ""), "component": motion.component,
                       "pga_m_s2": motion.pga_m_s2, "units_source": motion.units_source,
                       "processing": list(motion.processing)}
                for name, motion in self.components.items()}


def _read_set(path: Path, component: str, options: dict) -> tuple[list[GroundMotion], list[GroundMotion]]:
    """Horizontal and vertical components of one multi-channel file (or K-NET set)."""
    siblings = knet_siblings(path)
    if siblings is not None:
        motions = [read_ground_motion(p, allow_zero=True, **options) for p in siblings]
    else:
        motions = read_ground_motions(path, allow_zero=True, **options)  # the file parsed once
        if len(motions) < 2:
            raise ComponentError(f"{path}: holds one component ({motions[0].component}); a pair from one file "
                                 "needs two horizontal components (or give the second file)", path=path,
                                 parameter="pair")
    horizontal = [m for m in motions if not is_vertical(m)]
    vertical = [m for m in motions if is_vertical(m)]
    names = ", ".join(m.component for m in motions)
    if len(horizontal) != 2:
        raise ComponentError(f"{path}: holds {len(horizontal)} horizontal component(s) ({names}); a pair needs two",
                             path=path, parameter="pair")
    if component == "all" and len(vertical) != 1:
        raise ComponentError(f"{path}: holds {len(vertical)} vertical component(s) ({names}); the pair with its "
                             "vertical ('all') needs one", path=path, parameter="pair")
    return horizontal, vertical


def _vertical_channel(path: Path, merge: bool) -> str | None:
    """The component to read from a vertical (``--vertical``) file: None for a file of one
    component, else the label of its one vertical channel (HNZ, Up, UD …).

    Raises
    ------
    ComponentError
        The file holds several components and none, or several, of them are vertical.
    """
    labels = list_components(path, merge=merge)
    if len(labels) <= 1:
        return None
    vertical = [label for label in labels if label_is_vertical(label)]
    if len(vertical) != 1:
        raise ComponentError(f"{path}: holds {len(labels)} components ({', '.join(labels)}), "
                             f"{'no' if not vertical else len(vertical)} vertical; the vertical of a pair is a "
                             "file of one component or the one vertical channel of a file", path=path,
                             parameter="vertical")
    return vertical[0]


def _same_motion(a: GroundMotion, b: GroundMotion) -> bool:
    """True when two components hold the same samples at the same time step (one file given twice,
    or one motion in two files): not a pair."""
    return a.dt_s == b.dt_s and np.array_equal(a.acceleration_m_s2, b.acceleration_m_s2)


def _offsets_s(motions: dict[str, GroundMotion]) -> dict[str, float]:
    """Start time of each component after X's [s] (UTCDateTime differences: nanosecond precision;
    formats that state no start time, e.g. AT2, all start at 0)."""
    reference = motions["x"].trace.stats.starttime
    return {name: float(motion.trace.stats.starttime - reference) for name, motion in motions.items()}


def _where(motion: GroundMotion) -> str:
    path = motion.provenance.get("path", "")
    return f"{Path(path).name} {motion.component}" if path else motion.component


def _mismatch(motions: dict[str, GroundMotion]) -> tuple[str, str] | None:
    """(kind, description) of the first difference between the components, or None."""
    first = motions["x"]
    offsets = _offsets_s(motions)
    for kind, value, unit, fmt in (("dt", lambda n, m: m.dt_s, "s", "{:g}"),
                                   ("sampling", lambda n, m: m.is_uniform, "", "{}"),
                                   ("start", lambda n, m: offsets[n], "s", "{:.6f}"),
                                   ("length", lambda n, m: m.npts, "samples", "{}")):
        values = {name: value(name, m) for name, m in motions.items()}
        ref = values["x"]
        if kind in ("dt", "start"):
            same = all(abs(v - ref) <= TIME_TOLERANCE * first.dt_s for v in values.values())
        else:
            same = all(v == ref for v in values.values())
        if kind == "sampling" and same and not ref:
            same = all(np.array_equal(m.time_s, first.time_s) for m in motions.values())
        if not same:
            if kind == "start":
                listed = ", ".join(f"{_where(m)} {m.trace.stats.starttime}" for m in motions.values())
            elif kind == "sampling":
                listed = ", ".join(f"{_where(m)} {'equal' if m.is_uniform else 'unequal'} steps"
                                   for m in motions.values())
                kind = "dt"
            else:
                listed = ", ".join(f"{_where(m)} {fmt.format(values[n])} {unit}".rstrip()
                                   for n, m in motions.items())
            words = {"dt": "time steps", "start": "start times", "length": "lengths"}[kind]
            return kind, f"the components have different {words} ({listed})"
    return None


def _common_window(motions: dict[str, GroundMotion]) -> tuple[float, float]:
    """(start, end) of the time all components cover, after X's start [s]."""
    offsets = _offsets_s(motions)
    start = max(offsets.values())
    end = min(offsets[name] + motion.duration_s for name, motion in motions.items())
    if not end > start:
        raise ComponentMismatchError("the components do not overlap in time", kind="start")
    return start, end


def _trimmed(motions: dict[str, GroundMotion]) -> tuple[dict[str, GroundMotion], dict]:
    """Cut equal-step components on one grid to their common window."""
    start, _ = _common_window(motions)
    offsets = _offsets_s(motions)
    dt = motions["x"].dt_s
    firsts = {}
    for name, motion in motions.items():
        first = (start - offsets[name]) / dt
        if abs(first - round(first)) > TIME_TOLERANCE:
            raise ComponentMismatchError(
                f"{_where(motion)} is sampled {abs(first - round(first)) * dt:g} s off the grid of the others; "
                "trimming cannot align it", kind="start")
        firsts[name] = int(round(first))
    # by sample index: every component keeps the samples all of them cover
    count = min(motion.npts - firsts[name] for name, motion in motions.items())
    out, dropped = {}, {}
    for name, motion in motions.items():
        first = firsts[name]
        trace = motion.trace.copy()
        trace.data = np.ascontiguousarray(motion.acceleration_m_s2[first:first + count])
        trace.stats.starttime = motion.trace.stats.starttime + first * dt
        out[name] = motion._derived(trace, {"step": "trim", "first_sample": first, "npts": count})
        dropped[name] = motion.npts - out[name].npts
    return out, {"step": "trim_to_common_window", "npts": out["x"].npts, "dropped_samples": dropped}


def _on_union_grid(motions: dict[str, GroundMotion]) -> tuple[dict[str, GroundMotion], dict]:
    """Every component on the union of all sample times inside the common window (exact)."""
    start, end = _common_window(motions)
    offsets = _offsets_s(motions)
    smallest = min(m.dt_s for m in motions.values())
    absolute = np.concatenate([offsets[n] - start + m.time_s for n, m in motions.items()])
    grid = np.unique(absolute[(absolute >= -TIME_TOLERANCE * smallest)
                              & (absolute <= end - start + TIME_TOLERANCE * smallest)])
    keep = np.concatenate([[True], np.diff(grid) > TIME_TOLERANCE * smallest])  # merge coincident times
    grid = np.clip(grid[keep], 0.0, end - start)
    out = {}
    for name, motion in motions.items():
        values = np.interp(grid, offsets[name] - start + motion.time_s, motion.acceleration_m_s2)
        common = GroundMotion.from_array(values, time_s=grid, units_source=motion.units_source,
                                         component=motion.component, provenance=motion.provenance)
        out[name] = GroundMotion(trace=common.trace, units_source=motion.units_source,
                                 provenance=motion.provenance, processing=list(motion.processing),
                                 component=motion.component, components=list(motion.components))
        out[name].trace.stats.starttime = motion.trace.stats.starttime + (start - offsets[name])
    step = {"step": "common_time_grid", "npts": int(grid.size), "uniform": out["x"].is_uniform,
            "method": "union of the components' sample times over their common window; linear "
                      "interpolation (the same piecewise-linear signals, nothing approximated)"}
    return out, step


def align(motions: dict[str, GroundMotion], *, trim: bool = False,
          resample: bool = False) -> tuple[dict[str, GroundMotion], list[dict]]:
    """Put the components on one time base, or say what differs.

    Parameters
    ----------
    motions : dict of str to GroundMotion
        Components by axis name (``x`` first) [-].
    trim : bool
        Cut to the common window when lengths or start times differ (equal steps on one
        grid needed) [-].
    resample : bool
        Interpolate every component onto the union of their sample times over the
        common window (handles any difference; exact for piecewise-linear records) [-].

    Returns
    -------
    tuple
        The aligned components and the processing steps applied [-].

    Raises
    ------
    ComponentMismatchError
        The components differ and the difference was not asked to be repaired.
    """
    problem = _mismatch(motions)
    if problem is None:
        return motions, []
    kind, message = problem
    if resample:
        aligned, step = _on_union_grid(motions)
        return aligned, [step]
    if trim and kind in ("length", "start"):
        aligned, step = _trimmed(motions)
        left = _mismatch(aligned)
        if left is not None:
            raise ComponentMismatchError(left[1], kind=left[0])
        return aligned, [step]
    raise ComponentMismatchError(message, kind=kind)


def read_ground_motion_pair(
    x: str | Path,
    y: str | Path | None = None,
    z: str | Path | None = None,
    *,
    component: str | None = None,
    units: str | None = None,
    merge: bool = False,
    response: str | Path | None = None,
    counts_factor: float | None = None,
    dt_s: float | None = None,
    trim: bool = False,
    resample: bool = False,
    defaults: bool = False,
) -> MotionPair:
    """Read the horizontal components (and the vertical) of one station into a :class:`MotionPair`.

    Parameters
    ----------
    x : str or path-like
        The X record file; with ``y`` and ``z`` None, a file that holds several
        channels (or one file of a K-NET set) [-].
    y, z : str or path-like, optional
        The Y (second horizontal) and Z (vertical) record files; ``z`` without ``y``
        gives one horizontal with its vertical [-].
    component : {"pair", "all"} or str, optional
        For one multi-channel ``x``: ``"pair"`` (the two horizontals, the default) or
        ``"all"`` (with the vertical).  With ``y`` or ``z`` given: the component to
        take from ``x`` when it holds several [-].
    units, merge, response, counts_factor, dt_s, defaults
        As for :func:`~isolator.motion.read_ground_motion`, applied to each file [-].
    trim, resample : bool
        Repair components that differ (see :func:`align`) [-].

    Returns
    -------
    MotionPair

    Raises
    ------
    RecordError
        One line naming the file and the problem (any reading error, not two
        horizontals, a vertical given as a horizontal or the reverse).
    ComponentMismatchError
        The components differ in time step, length or start time (one line saying which).
    """
    options = {"units": units, "merge": merge, "response": response, "counts_factor": counts_factor,
               "dt_s": dt_s, "defaults": defaults}
    x = Path(x)
    vertical: list[GroundMotion] = []
    if y is None and z is None:
        wanted = (component or "pair").lower()
        if wanted not in PAIR_CHOICES:
            raise ComponentError(f"{x}: a pair from one file takes component 'pair' or 'all', not {component!r}",
                                 path=x)
        horizontal, vertical = _read_set(x, wanted, options)
        if wanted == "pair":
            vertical = []
    else:
        if component is not None and component.lower() in PAIR_CHOICES:
            raise ComponentError(f"{x}: component {component!r} reads a pair from one file; "
                                 "with a second file give one component (or none)", path=x)
        horizontal = [read_ground_motion(x, component=component, allow_zero=y is not None, **options)]
        if y is not None:
            second = read_ground_motions(y, allow_zero=True, **options)  # the file parsed once
            if len(second) > 1:
                labels = [motion.component for motion in second]
                raise ComponentError(f"{y}: holds {len(labels)} components ({', '.join(labels)}); the second "
                                     "horizontal of a pair is a file of one component", path=y,
                                     parameter="second_file")
            horizontal.append(second[0])
        for motion in horizontal:
            if is_vertical(motion):
                raise ComponentError(f"{motion.provenance.get('path')}: component {motion.component} is vertical; "
                                     "X and Y are the horizontal components", path=motion.provenance.get("path", ""))
        if z is not None:
            vertical = [read_ground_motion(z, component=_vertical_channel(Path(z), merge), allow_zero=True,
                                           **options)]
            if not is_vertical(vertical[0]) and vertical[0].component.lower() not in ("", "unnamed"):
                raise ComponentError(f"{z}: component {vertical[0].component} is not a vertical (Up, UD, HNZ …)",
                                     path=z, parameter="vertical")
    if all(motion.pga_m_s2 == 0.0 for motion in horizontal):  # the record's fault: no ground motion at all
        source = horizontal[0].provenance.get("path", str(x))
        raise RecordValuesError(f"{source}: every horizontal component is zero: no ground motion", path=source)
    if len(horizontal) == 2 and _same_motion(*horizontal):
        first, second = (_where(m) for m in horizontal)
        path = horizontal[1].provenance.get("path", "")
        what = "is given as both X and Y" if first == second else f"is the same motion as {first} (the same samples)"
        raise ComponentError(f"{path or x}: {second} {what}; a pair is two different horizontal components",
                             path=path, parameter="pair")
    motions = dict(zip(("x", "y"), horizontal, strict=False))
    if vertical:
        motions["z"] = vertical[0]
    aligned, steps = align(motions, trim=trim, resample=resample)
    return MotionPair(x=aligned["x"], y=aligned.get("y"), z=aligned.get("z"), processing=steps)
