"""The components of a pair made one pair: processing corner, azimuths, fault rotation, one time base.

This module holds what is read from a component beyond its samples (:func:`high_pass_corner_hz`, the
high-pass corner of a PEER AT2 header; :func:`component_azimuth_deg`, the azimuth in its name), the rotation
of a pair to the fault-normal and fault-parallel directions (:func:`rotate_to_fault`) and the checks and
processing that put the components of a pair on one uniform time base, each a distinct motion in its place
(issue 26: :func:`uniform_exactly`, :func:`one_time_base`, with :data:`GRID_TOLERANCE`,
:data:`MAX_GRID_REFINEMENT` and :data:`SAME_MOTION_RTOL`).  :func:`isolator.review.suite.read_pair` uses them.
"""

from __future__ import annotations

import math
import re

import numpy as np

from isolator.errors import SuiteError

_CORNER_RE = re.compile(r"(-?\d+)\s*POLE\s*@\s*([0-9.]+)", re.IGNORECASE)


def high_pass_corner_hz(motion) -> float | None:
    """The high-pass corner of the record's processing, from a PEER AT2 header (``-5 POLE @ .06``) [Hz].

    A negative pole count is a high-pass (acausal Butterworth, NGA-West2 convention); ``None`` when the
    header states none.
    """
    stats = motion.trace.stats
    if "peer_at2" not in stats:
        return None
    corners = [float(f) for poles, f in _CORNER_RE.findall("\n".join(stats.peer_at2.get("header_lines", [])))
               if int(poles) < 0 and float(f) > 0]
    return max(corners) if corners else None


_QUADRANT_RE = re.compile(r"^([NS])\s*(\d{1,2}(?:\.\d+)?)\s*([EW])$")
_NAMED_AZIMUTH = {"N": 0.0, "NS": 0.0, "E": 90.0, "EW": 90.0, "S": 180.0, "SN": 180.0, "W": 270.0, "WE": 270.0}


def component_azimuth_deg(name) -> float | None:
    """Azimuth of a horizontal component from its name, clockwise from north [°] (``None`` when unknown).

    ``270``, ``HN1 (90)``, ``YER360`` (the trailing three digits of PEER names), ``N55W`` (= 305),
    ``S01W`` (= 181), ``E``, ``NS``, ``EW``.
    """
    if not name:
        return None
    text = str(name).strip().upper()
    inner = re.search(r"\((\d{1,3}(?:\.\d+)?)\)", text)
    if inner:
        return float(inner.group(1)) % 360.0
    if text in _NAMED_AZIMUTH:
        return _NAMED_AZIMUTH[text]
    quadrant = _QUADRANT_RE.match(text)
    if quadrant:
        base, angle, side = quadrant.group(1), float(quadrant.group(2)), quadrant.group(3)
        sign = 1.0 if (base == "N") == (side == "E") else -1.0
        return ((0.0 if base == "N" else 180.0) + sign * angle) % 360.0
    digits = re.search(r"(\d{1,3})$", text)
    if digits and (len(digits.group(1)) == 3 or text == digits.group(1)) and int(digits.group(1)) <= 360:
        return float(digits.group(1)) % 360.0
    return None


def rotate_to_fault(ax, ay, azimuth_x_deg: float, azimuth_y_deg: float, strike_deg: float):
    """The fault-normal and fault-parallel accelerations of a pair (both components, any orientation).

    The ground vector G solves G·u_x = a_x, G·u_y = a_y (u the horizontal unit vector of an azimuth,
    clockwise from north); fault-normal = G·u(strike + 90°), fault-parallel = G·u(strike) [m/s²].
    """
    def unit(azimuth):
        angle = math.radians(azimuth)
        return np.array([math.sin(angle), math.cos(angle)])  # (east, north)

    basis = np.vstack([unit(azimuth_x_deg), unit(azimuth_y_deg)])
    ground = np.linalg.solve(basis, np.vstack([ax, ay]))  # rows: east, north
    return unit(strike_deg + 90.0) @ ground, unit(strike_deg) @ ground


# ---- one time base, one motion per component (issue 26) ------------------------------------

#: Tolerance on a sample time's place on a uniform grid (fraction of the grid's step).
GRID_TOLERANCE = 1e-6
#: Largest refinement of the smallest step searched for a grid holding every sample time, and
#: the largest growth of a record it may cause.
MAX_GRID_REFINEMENT = 8
#: Two components of a pair equal to this fraction of their PGA are one motion (one file in g,
#: the other in gal, rounds differently in the last digits).
SAME_MOTION_RTOL = 1e-6


def uniform_exactly(motion, where: str):
    """A record sampled at unequal steps as the same piecewise-linear signal on a uniform grid.

    The grid's step divides every sample time (the smallest step or a fraction 1/k of it,
    k ≤ :data:`MAX_GRID_REFINEMENT`); linear interpolation onto it keeps every sample and adds
    points on the straight segments between them: the same signal, so spectra, PGA, PGV, RotD
    and the engines give the answers the unequal samples define.

    Returns
    -------
    (GroundMotion, dict or None)
        The motion (itself when uniform) and the processing step (None when uniform).

    Raises
    ------
    SuiteError
        No such grid (sample times that share no step): the review refuses rather than read
        the samples as equally spaced.
    """
    from isolator.motion import GroundMotion

    if motion.is_uniform:
        return motion, None
    times = np.asarray(motion.time_s, dtype=np.float64)
    times = times - times[0]
    smallest = float(np.min(np.diff(times)))
    for refinement in range(1, MAX_GRID_REFINEMENT + 1):
        step = smallest / refinement
        places = times / step
        if np.max(np.abs(places - np.round(places))) <= GRID_TOLERANCE * refinement:
            count = int(round(places[-1])) + 1
            if count > MAX_GRID_REFINEMENT * times.size:
                break
            step = float(times[-1] / (count - 1))  # the mean step: no drift of the grid over the record
            grid = np.arange(count) * step
            values = np.interp(grid, times, motion.acceleration_m_s2)
            values[np.round(places).astype(np.int64)] = motion.acceleration_m_s2  # the samples, bit for bit
            uniform = GroundMotion.from_array(values, dt_s=step, units_source=motion.units_source,
                                              component=motion.component, provenance=motion.provenance)
            uniform = GroundMotion(trace=uniform.trace, units_source=motion.units_source,
                                   provenance=motion.provenance, processing=list(motion.processing),
                                   component=motion.component, components=list(motion.components))
            uniform.trace.stats.starttime = motion.trace.stats.starttime
            return uniform, {"step": "uniform_grid", "component_file": where, "dt_s": step,
                             "npts": {"before": int(times.size), "after": count},
                             "method": "unequal steps put on the uniform grid through every sample time; "
                                       "linear interpolation (the same piecewise-linear signal)"}
    raise SuiteError(f"{where}: sampled at unequal steps ({smallest:g} to {float(np.max(np.diff(times))):g} s) "
                     "that share no common grid; the review needs equal steps (resample the record)")


def _looks_horizontal(motion) -> bool:
    from isolator.motion.components import axis_letter, is_vertical

    if is_vertical(motion):
        return False
    channel = str(motion.provenance.get("channel", "") or "")
    names = [part.strip(" ()") for part in str(motion.component).split("(")] + [channel[-1:]]
    return any(axis_letter(name) in ("N", "E") or re.fullmatch(r"\d{1,3}(\.\d+)?", name) is not None
               or (len(channel) == 3 and channel[2] in "NE12") for name in names if name)


def one_time_base(spec, motions: dict) -> tuple[dict, list]:
    """The components of a pair on one uniform time base, each a distinct motion in its place.

    * unequal steps: put exactly on a uniform grid (:func:`uniform_exactly`) or refused;
    * start times that differ (a component starting 1 s after the other): aligned on the time
      axes to the common window when the suite asks (``trim``), refused otherwise — never paired
      sample by sample (as ``simulate --pair`` does, :func:`isolator.motion.pair.align`);
    * a vertical labelled as a horizontal (``090``) or a horizontal labelled vertical, and two
      components that are one motion (one file twice, or in g and in gal), are refused.

    Returns
    -------
    (dict, list of dict)
        The components and the processing steps applied.

    Raises
    ------
    SuiteError
        One line naming the pair and the files.
    """
    from isolator.errors import ComponentMismatchError
    from isolator.motion.components import is_vertical
    from isolator.motion.pair import align

    labels = {"x": spec.x.label(), "y": spec.y.label(), "z": spec.z.label() if spec.z is not None else ""}
    steps = []
    for key in list(motions):
        motions[key], step = uniform_exactly(motions[key], f"pair '{spec.name}' {key} ({labels[key]})")
        if step is not None:
            steps.append(step)
    if "z" in motions and _looks_horizontal(motions["z"]):
        raise SuiteError(f"pair '{spec.name}': z ({labels['z']}) is labelled '{motions['z'].component}', a "
                         "horizontal component; give the vertical as z")
    for key in ("x", "y"):
        if is_vertical(motions[key]):
            raise SuiteError(f"pair '{spec.name}': {key} ({labels[key]}) is labelled '{motions[key].component}', "
                             "a vertical component; give it as z")
    keys = list(motions)
    for i, first in enumerate(keys):
        for second in keys[i + 1:]:
            a, b = motions[first].acceleration_m_s2, motions[second].acceleration_m_s2
            scale = max(float(np.max(np.abs(a))), float(np.max(np.abs(b))))
            if (a.shape == b.shape and scale > 0 and not np.array_equal(a, b)  # equal samples: said below by hash
                    and float(np.max(np.abs(a - b))) <= SAME_MOTION_RTOL * scale):
                raise SuiteError(f"pair '{spec.name}': {first} ({labels[first]}) and {second} ({labels[second]}) "
                                 f"are one motion (equal to {SAME_MOTION_RTOL:g} of the PGA in m/s²; one file "
                                 "twice, or one record in two units)")
    try:
        align(motions)  # only asks what differs
    except ComponentMismatchError as err:
        if err.kind != "start":
            return motions, steps  # time steps and lengths: refused or trimmed below, in the suite's words
        if not spec.trim:
            raise SuiteError(f"pair '{spec.name}': {err}; they are not paired sample by sample: set trim = true "
                             "to align them on their time axes and use their common window") from None
        try:
            motions, aligned = align(motions, trim=True)
        except ComponentMismatchError as again:
            raise SuiteError(f"pair '{spec.name}': {again}") from None
        steps.extend(aligned)
    return motions, steps
