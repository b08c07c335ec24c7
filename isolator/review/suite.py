"""Ground-motion suites: pairs of horizontal components (and optional verticals) read, checked and hashed.

A suite is given either as SUITE.toml::

    units = "g"            # optional default for files that do not state their units
    trim = false           # optional: trim the two components of a pair to their common span
    [[pair]]
    name = "Duzce 1999 DZC"
    x = "records/RSN1605_DUZCE_DZC180.AT2"        # a path, or {file = "CE89146.V2", component = "HN1"}
    y = "records/RSN1605_DUZCE_DZC270.AT2"
    z = "…"                # optional vertical
    units = "g"            # optional, this pair's units
    trim = true            # optional, this pair only
    scale_factor = 1.83    # optional: the engineer's factor (``--scaling given`` checks it, never rescales)
    matched = true         # optional: spectrally matched (not rescaled; the 110 % rule of 16.2.3.3 applies)
    rotate_to_fault_normal_deg = 35.0   # optional: fault strike [°]; x, y become fault-normal, fault-parallel
    azimuth_x_deg = 180.0  # optional: azimuth of x (and azimuth_y_deg of y) when the component name has none
    magnitude = 7.1        # optional metadata: moment magnitude, closest distance [km], mechanism,
    distance_km = 12.0     #   V_s30 [m/s], velocity pulse (true/false); shown on page 3, checked
    mechanism = "strike-slip"  # against the target's controlling magnitude and distance ranges
    vs30_m_s = 360.0
    pulse = false

(paths relative to the suite file), or as files, folders and globs of records, grouped into pairs
by station and event (a multi-channel file is one station: its two horizontals and its vertical).

Rules (REVIEW_RULES 1.4 and issue 11):

* the same samples twice in a suite (two files of one motion, or one component used twice) are
  refused, naming both, by the SHA-256 of the samples in m/s²;
* two components of different length are trimmed to the common span only when the suite asks
  (``trim``), and the trim is recorded in the pair's processing; otherwise the suite is refused
  with one line naming the pair; different time steps are always refused;
* a record that cannot be read fails its pair only (reported), not the review;
* the same *motion* twice — a pair that is a rotation, a scaling, a time shift or a resampling of
  another — is refused naming both (:func:`isolator.review.selection.closest_motions`);
* ``rotate_to_fault_normal_deg`` (the fault strike) rotates both components to the fault-normal
  (x, azimuth strike + 90°) and fault-parallel (y, azimuth strike) directions; the azimuths of the
  recorded components come from their names (``270``, ``HN1 (90)``, ``N55W``, ``EW``) or from
  ``azimuth_x_deg`` / ``azimuth_y_deg``; the rotation is recorded in the pair's processing.
"""

from __future__ import annotations

import hashlib
import math
import os
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from isolator.errors import SuiteError

SUITE_KEYS = {"units", "trim", "pair", "name", "description"}
METADATA_KEYS = ("magnitude", "distance_km", "mechanism", "vs30_m_s", "pulse")
PAIR_KEYS = {"name", "x", "y", "z", "units", "trim", "scale_factor", "matched", "rotate_to_fault_normal_deg",
             "azimuth_x_deg", "azimuth_y_deg", *METADATA_KEYS}
_CHECKSUMS_RE = re.compile(r"^(SHA\d*SUMS|MD5SUMS)(\.txt)?$", re.IGNORECASE)
_CORNER_RE = re.compile(r"(-?\d+)\s*POLE\s*@\s*([0-9.]+)", re.IGNORECASE)


@dataclass(frozen=True)
class ComponentSpec:
    """One component to read: a file and, for multi-channel files, the component label."""

    path: str
    component: str | None = None

    def label(self) -> str:
        return self.path if self.component is None else f"{self.path} [{self.component}]"


@dataclass(frozen=True)
class PairSpec:
    """A pair as the suite gives it."""

    name: str
    x: ComponentSpec
    y: ComponentSpec
    z: ComponentSpec | None = None
    units: str | None = None
    trim: bool = False
    scale_factor: float | None = None  #: the engineer's factor (SUITE.toml), checked, never changed
    matched: bool = False  #: spectrally matched record (16.2.3.3)
    strike_deg: float | None = None  #: rotate to fault-normal / fault-parallel for this strike [°]
    azimuths_deg: tuple = (None, None)  #: azimuths of x and y when their names carry none [°]
    metadata: dict = field(default_factory=dict)  #: magnitude, distance_km, mechanism, vs30_m_s, pulse


@dataclass
class Pair:
    """A pair read and checked: same dt, same length, in m/s²."""

    name: str
    ax_m_s2: np.ndarray
    ay_m_s2: np.ndarray
    az_m_s2: np.ndarray | None
    dt_s: float
    files: dict  #: component ("x", "y", "z") → label of the file read
    component_names: dict  #: component → component name in the file
    processing: list = field(default_factory=list)
    provenance: dict = field(default_factory=dict)
    high_pass_hz: float | None = None  #: the largest high-pass corner stated by the files (AT2 headers)
    sample_hashes: dict = field(default_factory=dict)
    paths: list = field(default_factory=list)  #: the files read (for the input hashes)
    scale_factor: float | None = None  #: the engineer's factor from SUITE.toml
    matched: bool = False  #: spectrally matched (16.2.3.3)
    metadata: dict = field(default_factory=dict)  #: magnitude, distance_km, mechanism, vs30_m_s, pulse

    @property
    def npts(self) -> int:
        return int(self.ax_m_s2.size)

    @property
    def pga_m_s2(self) -> float:
        """Larger horizontal component PGA [m/s²]."""
        return float(max(np.max(np.abs(self.ax_m_s2)), np.max(np.abs(self.ay_m_s2))))

    def content_key(self) -> str:
        """SHA-256 of the samples and dt (for caches)."""
        digest = hashlib.sha256()
        for array in (self.ax_m_s2, self.ay_m_s2, self.az_m_s2):
            digest.update(b"-" if array is None else np.ascontiguousarray(array, dtype=np.float64).tobytes())
        digest.update(repr(self.dt_s).encode())
        return digest.hexdigest()


@dataclass
class Suite:
    """The pairs that could be read, and the ones that could not (with the reason)."""

    pairs: list
    failed: list  #: [{"name": …, "error": …}]
    source: str
    specs: list = field(default_factory=list)
    arguments: list = field(default_factory=list)  #: what load_suite was given (a SUITE.toml, or files)
    options: dict = field(default_factory=dict)  #: units, trim given to load_suite (files and folders)
    closest: dict | None = None  #: the two pairs with the closest motion signatures and their distance

    @property
    def given_factors(self) -> list:
        """The engineer's scale factor of each pair (None where the suite gives none)."""
        return [p.scale_factor for p in self.pairs]

    @property
    def matched(self) -> bool:
        """Every pair is spectrally matched (16.2.3.3); a mixed suite is refused when read."""
        return bool(self.pairs) and all(p.matched for p in self.pairs)

    @property
    def names(self) -> list[str]:
        return [p.name for p in self.pairs]


# ---- reading a component -----------------------------------------------------------------

def _read(spec: ComponentSpec, units: str | None):
    from isolator.motion import read_ground_motion

    return read_ground_motion(spec.path, component=spec.component, units=units)


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


def _sample_hash(acceleration: np.ndarray) -> str:
    return hashlib.sha256(np.ascontiguousarray(acceleration, dtype=np.float64).tobytes()).hexdigest()


def read_pair(spec: PairSpec, seen: dict | None = None) -> Pair:
    """Read the components of a pair and make them one piecewise-linear pair.

    ``seen`` maps the SHA-256 of samples already in the suite to where they are (updated here).

    Raises
    ------
    isolator.motion.RecordError, isolator.units.UnitsError
        A component cannot be read (the pair fails, not the suite).
    SuiteError
        The same samples twice, different time steps, or lengths without ``trim`` (the suite is refused).
    """
    motions = {"x": _read(spec.x, spec.units), "y": _read(spec.y, spec.units)}
    if spec.z is not None:
        motions["z"] = _read(spec.z, spec.units)
    specs = {"x": spec.x, "y": spec.y, "z": spec.z}
    motions, time_base = one_time_base(spec, motions)
    hashes = {key: _sample_hash(m.acceleration_m_s2) for key, m in motions.items()}
    seen = {} if seen is None else seen
    for key, digest in hashes.items():
        where = f"pair '{spec.name}' {key} ({specs[key].label()})"
        if digest in seen:
            raise SuiteError(f"the same samples twice: {seen[digest]} and {where} (sha256 {digest[:12]}…)")
        seen[digest] = where
    dts = {key: m.dt_s for key, m in motions.items()}
    if max(dts.values()) - min(dts.values()) > 1e-9 * max(dts.values()):
        raise SuiteError(f"pair '{spec.name}': components have different time steps "
                         f"({', '.join(f'{k} {v:g} s' for k, v in dts.items())}); resample them first")
    lengths = {key: m.npts for key, m in motions.items()}
    processing = list(time_base)
    n = min(lengths.values())
    if len(set(lengths.values())) > 1:
        if not spec.trim:
            raise SuiteError(f"pair '{spec.name}': components differ in length "
                             f"({', '.join(f'{k} {v}' for k, v in lengths.items())} samples); "
                             "set trim = true for this pair (or the suite) to use the common span")
        processing.append({"step": "trim to the common span (suite asked: trim = true)",
                           "samples": {k: v for k, v in lengths.items()}, "kept": n})
    arrays = {key: np.ascontiguousarray(m.acceleration_m_s2[:n], dtype=np.float64) for key, m in motions.items()}
    if spec.strike_deg is not None:
        azimuths = [given if given is not None else component_azimuth_deg(motions[key].component)
                    for key, given in zip(("x", "y"), spec.azimuths_deg, strict=True)]
        for key, azimuth in zip(("x", "y"), azimuths, strict=True):
            if azimuth is None:
                raise SuiteError(f"pair '{spec.name}': the azimuth of component {key} "
                                 f"('{motions[key].component}') is not in its name; give azimuth_{key}_deg "
                                 "to rotate to the fault-normal direction")
        gap = (azimuths[1] - azimuths[0]) % 180.0
        if abs(gap - 90.0) > 1.0:
            raise SuiteError(f"pair '{spec.name}': components at azimuths {azimuths[0]:g}° and {azimuths[1]:g}° "
                             "are not orthogonal (within 1°); they cannot be rotated")
        arrays["x"], arrays["y"] = (np.ascontiguousarray(a) for a in rotate_to_fault(
            arrays["x"], arrays["y"], azimuths[0], azimuths[1], spec.strike_deg))
        processing.append({"step": "rotated to fault-normal (x) / fault-parallel (y)", "strike_deg": spec.strike_deg,
                           "azimuth_x_deg": azimuths[0], "azimuth_y_deg": azimuths[1],
                           "fault_normal_azimuth_deg": (spec.strike_deg + 90.0) % 360.0})
    corners = [c for c in (high_pass_corner_hz(m) for m in motions.values()) if c is not None]
    provenance = {key: dict(m.provenance) for key, m in motions.items()}
    for m in motions.values():
        processing.extend(dict(step) for step in m.processing)
    return Pair(name=spec.name, ax_m_s2=arrays["x"], ay_m_s2=arrays["y"], az_m_s2=arrays.get("z"),
                dt_s=float(motions["x"].dt_s), files={k: specs[k].label() for k in motions},
                component_names={k: m.component for k, m in motions.items()}, processing=processing,
                provenance=provenance, high_pass_hz=max(corners) if corners else None,
                sample_hashes=hashes, paths=sorted({s.path for s in specs.values() if s is not None}),
                scale_factor=spec.scale_factor, matched=spec.matched, metadata=dict(spec.metadata))


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


# ---- SUITE.toml --------------------------------------------------------------------------

def _component(value, base: Path, where: str) -> ComponentSpec:
    if isinstance(value, str):
        return ComponentSpec(str(base / value))
    if isinstance(value, dict) and isinstance(value.get("file"), str) and set(value) <= {"file", "component"}:
        component = value.get("component")
        if component is not None and not isinstance(component, str):
            raise SuiteError(f"{where}: 'component' must be text")
        return ComponentSpec(str(base / value["file"]), component)
    raise SuiteError(f"{where}: must be a file name or {{file = \"…\", component = \"…\"}}, got {value!r}")


def specs_from_toml(path) -> list[PairSpec]:
    """The pairs of a SUITE.toml (see the module docstring).

    Raises
    ------
    SuiteError
    """
    from isolator.design import load_toml

    path = Path(path)
    mapping = load_toml(path, "suite file", SuiteError)
    unknown = sorted(set(mapping) - SUITE_KEYS)
    if unknown:
        raise SuiteError(f"{path}: unknown key '{unknown[0]}' (valid: units, trim, [[pair]])")
    units = mapping.get("units")
    if units is not None and not isinstance(units, str):
        raise SuiteError(f"{path}: 'units' must be text (g, m/s2, gal, cm/s2)")
    trim = mapping.get("trim", False)
    if not isinstance(trim, bool):
        raise SuiteError(f"{path}: 'trim' must be true or false")
    pairs = mapping.get("pair")
    if not isinstance(pairs, list) or not pairs:
        raise SuiteError(f"{path}: no [[pair]] tables")
    specs, names = [], set()
    for index, table in enumerate(pairs, 1):
        where = f"{path}: pair {index}"
        if not isinstance(table, dict):
            raise SuiteError(f"{where}: must be a table")
        bad = sorted(set(table) - PAIR_KEYS)
        if bad:
            raise SuiteError(f"{where}: unknown key '{bad[0]}' (valid: {', '.join(sorted(PAIR_KEYS))})")
        for key in ("x", "y"):
            if key not in table:
                raise SuiteError(f"{where}: missing key '{key}'")
        name = table.get("name", f"pair{index}")
        if not isinstance(name, str) or not name.strip():
            raise SuiteError(f"{where}: 'name' must be a non-empty text")
        key = " ".join(name.split()).casefold()  # "a" and " a" name one pair in every table
        if key in names:
            raise SuiteError(f"{where}: name '{name}' is used twice (names are compared without case and "
                             "surrounding or repeated spaces)")
        names.add(key)
        pair_units = table.get("units", units)
        if pair_units is not None and not isinstance(pair_units, str):
            raise SuiteError(f"{where}: 'units' must be text")
        pair_trim = table.get("trim", trim)
        if not isinstance(pair_trim, bool):
            raise SuiteError(f"{where}: 'trim' must be true or false")
        specs.append(PairSpec(name=name.strip(), x=_component(table["x"], path.parent, f"{where} x"),
                              y=_component(table["y"], path.parent, f"{where} y"),
                              z=_component(table["z"], path.parent, f"{where} z") if "z" in table else None,
                              units=pair_units, trim=pair_trim, **_pair_options(table, f"{where} ('{name}')")))
    return specs


def _number(table: dict, key: str, where: str, *, positive: bool = True, upper: float | None = None):
    value = table.get(key)
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or (
            positive and value <= 0) or (not positive and value < 0) or (upper is not None and value > upper):
        bound = f"in (0, {upper:g}]" if upper is not None else ("> 0" if positive else "≥ 0")
        raise SuiteError(f"{where}: '{key}' must be a number {bound}, got {value!r}")
    return float(value)


def _pair_options(table: dict, where: str) -> dict:
    """scale_factor, matched, the fault rotation and the metadata of a [[pair]] table, checked."""
    matched = table.get("matched", False)
    if not isinstance(matched, bool):
        raise SuiteError(f"{where}: 'matched' must be true or false")
    strike = table.get("rotate_to_fault_normal_deg")
    if strike is not None:
        strike = _number(table, "rotate_to_fault_normal_deg", where, positive=False, upper=360.0)
    azimuths = tuple(_number(table, f"azimuth_{k}_deg", where, positive=False, upper=360.0) for k in ("x", "y"))
    if strike is None and any(a is not None for a in azimuths):
        raise SuiteError(f"{where}: azimuth_x_deg / azimuth_y_deg serve rotate_to_fault_normal_deg, which is absent")
    metadata = {"magnitude": _number(table, "magnitude", where, upper=10.0),
                "distance_km": _number(table, "distance_km", where, positive=False),
                "vs30_m_s": _number(table, "vs30_m_s", where)}
    mechanism = table.get("mechanism")
    if mechanism is not None and (not isinstance(mechanism, str) or not mechanism.strip()):
        raise SuiteError(f"{where}: 'mechanism' must be a non-empty text (e.g. \"strike-slip\", \"reverse\")")
    pulse = table.get("pulse")
    if pulse is not None and not isinstance(pulse, bool):
        raise SuiteError(f"{where}: 'pulse' must be true or false")
    metadata.update(mechanism=mechanism.strip() if mechanism else None, pulse=pulse)
    return {"scale_factor": _number(table, "scale_factor", where), "matched": matched, "strike_deg": strike,
            "azimuths_deg": azimuths, "metadata": {k: v for k, v in metadata.items() if v is not None}}


# ---- files, folders, globs ---------------------------------------------------------------

def specs_from_records(arguments, *, units: str | None = None, trim: bool = False) -> tuple[list, list]:
    """Pairs from files, folders and globs: grouped by station and event.

    A file with several channels is one station (its two horizontals, and its vertical). Files
    of one component are grouped by (station, event) from their headers; components left alone
    are grouped by folder when a folder holds exactly two horizontals (and at most one vertical).

    Returns
    -------
    (list of PairSpec, list of {"name", "error"})
        The pairs, and the files that could not be placed in a pair (with the reason).
    """
    from isolator.errors import BatchError, RecordError, UnitsError
    from isolator.motion import list_components, read_ground_motion
    from isolator.motion.components import label_is_vertical as is_vertical
    from isolator.motion.files import expand_records

    try:
        files = expand_records(arguments)
    except BatchError as err:
        raise SuiteError(str(err)) from None
    specs, failed, singles = [], [], {}
    for path in files:
        if _CHECKSUMS_RE.match(Path(path).name):
            continue  # checksum lists travel with record folders
        try:
            labels = list_components(path)
            if len(labels) > 1:
                horizontal = [label for label in labels if not is_vertical(label)]
                vertical = [label for label in labels if is_vertical(label)]
                if len(horizontal) != 2:
                    failed.append({"name": Path(path).name, "error": f"{path}: {len(horizontal)} horizontal "
                                   "components (a pair needs 2)"})
                    continue
                specs.append(PairSpec(Path(path).stem, ComponentSpec(path, horizontal[0]),
                                      ComponentSpec(path, horizontal[1]),
                                      ComponentSpec(path, vertical[0]) if len(vertical) == 1 else None,
                                      units=units, trim=trim))
                continue
            head = read_ground_motion(path, units=units)
        except (RecordError, UnitsError, ValueError, OSError) as err:
            failed.append({"name": Path(path).name, "error": " ".join(str(err).split())})
            continue
        p = head.provenance
        key = (p.get("network", ""), p.get("station", ""), p.get("event", p.get("event_origin_time", "")))
        singles.setdefault(key if key[1] else ("folder", str(Path(path).parent), ""), []).append(
            (path, is_vertical(head.component)))
    # a station key that holds one file only: fall back to its folder
    grouped = {}
    for key, items in singles.items():
        if len(items) == 1:
            grouped.setdefault(("folder", str(Path(items[0][0]).parent), ""), []).extend(items)
        else:
            grouped.setdefault(key, []).extend(items)
    for key, items in grouped.items():
        horizontal = sorted(path for path, vertical in items if not vertical)
        vertical = sorted(path for path, vertical in items if vertical)
        name = (key[1] if key[0] != "folder" else Path(key[1]).name) or Path(horizontal[0]).stem
        if len(horizontal) != 2 or len(vertical) > 1:
            failed.append({"name": name, "error": f"cannot form a pair from {', '.join(horizontal + vertical)} "
                           f"({len(horizontal)} horizontal, {len(vertical)} vertical); list the pair in a SUITE.toml"})
            continue
        specs.append(PairSpec(name, ComponentSpec(horizontal[0]), ComponentSpec(horizontal[1]),
                              ComponentSpec(vertical[0]) if vertical else None, units=units, trim=trim))
    return specs, failed


# ---- the suite ---------------------------------------------------------------------------

def distinct_names(specs: list) -> list:
    """Pairs named after one station (two events, two folders) told apart by their folders.

    Names are compared without case and surrounding or repeated spaces; pairs whose names clash
    get the shortest tail of their folder paths that tells them apart (``STA (kobe/STA)``,
    ``STA (chichi/STA)``), so that no pair is lost where results are kept by name.
    """
    import dataclasses

    def key(name):
        return " ".join(name.split()).casefold()

    groups: dict = {}
    for index, spec in enumerate(specs):
        groups.setdefault(key(spec.name), []).append(index)
    names = [" ".join(spec.name.split()) for spec in specs]
    for members in groups.values():
        if len(members) < 2:
            continue
        folders = [Path(os.path.abspath(specs[i].x.path)).parent.parts for i in members]
        depth = max(len(parts) for parts in folders)
        for count in range(1, depth + 1):  # bounded by the deepest folder
            tails = ["/".join(parts[-count:]) for parts in folders]
            if len(set(tails)) == len(tails):
                break
        else:
            tails = [Path(specs[i].x.path).name + f" #{n}" for n, i in enumerate(members, 1)]
        for i, tail in zip(members, tails, strict=True):
            names[i] = f"{names[i]} ({tail})"
    return [dataclasses.replace(spec, name=name) if name != spec.name else spec
            for spec, name in zip(specs, names, strict=True)]


def load_suite(arguments, *, units: str | None = None, trim: bool = False) -> Suite:
    """Read a suite: a SUITE.toml, or files/folders/globs of records.

    Parameters
    ----------
    arguments : str or list of str
        One ``.toml`` file, or record files, folders and globs.
    units : str, optional
        Units for records that do not state them (files/folders only; SUITE.toml has its own).
    trim : bool
        Trim pairs of different lengths to the common span (files/folders only).

    Returns
    -------
    Suite

    Raises
    ------
    SuiteError
        Duplicated samples, mismatched components, a malformed SUITE.toml, or no pair at all.
    """
    from isolator.errors import RecordError, UnitsError

    if isinstance(arguments, (str, os.PathLike)):
        arguments = [arguments]
    elif isinstance(arguments, (list, tuple)) and all(isinstance(a, (str, os.PathLike)) for a in arguments):
        arguments = list(arguments)
    else:
        raise SuiteError(f"a suite is a SUITE.toml or a list of record files, folders and globs, got {arguments!r}")
    if not arguments or not all(os.fspath(a) for a in arguments):
        raise SuiteError(f"a suite is a SUITE.toml or a list of record files, folders and globs, got {arguments!r}")
    tomls = [a for a in arguments if str(a).lower().endswith(".toml")]
    if tomls and len(arguments) > 1:
        raise SuiteError(f"{tomls[0]}: give one SUITE.toml, or record files, folders and globs, not both")
    if tomls:
        source = str(arguments[0])
        specs, failed = specs_from_toml(arguments[0]), []
    else:
        source = ", ".join(str(a) for a in arguments)
        specs, failed = specs_from_records(arguments, units=units, trim=trim)
        specs = distinct_names(specs)
    pairs, seen = [], {}
    for spec in specs:
        try:
            pair = read_pair(spec, seen)
        except (RecordError, UnitsError) as err:
            failed.append({"name": spec.name, "error": " ".join(str(err).split())})
            continue
        pairs.append(pair)
    if not pairs:
        detail = ""
        if failed:  # the reader's message names the file already when the pair is named after it
            name, error = failed[0]["name"], str(failed[0]["error"])
            detail = f": {error}" if error.startswith(name) else f": {name}: {error}"
        raise SuiteError(f"suite {source}: no pair could be read{detail}")
    matched = [p.name for p in pairs if p.matched]
    if matched and len(matched) < len(pairs):
        other = next(p.name for p in pairs if not p.matched)
        raise SuiteError(f"suite {source}: pair '{matched[0]}' is spectrally matched and pair '{other}' is not; a "
                         "suite is either amplitude-scaled (16.2.3.2) or spectrally matched (16.2.3.3)")
    closest = _refuse_same_motions(pairs)
    return Suite(pairs=pairs, failed=failed, source=source, specs=specs, arguments=[str(a) for a in arguments],
                 options={"units": units, "trim": trim}, closest=closest)


def _refuse_same_motions(pairs: list) -> dict | None:
    """One line naming both pairs' files when two pairs are the same motion (rotated, scaled, shifted,
    resampled); otherwise the closest two pairs (:func:`isolator.review.selection.closest_motions`)."""
    from isolator.review.selection import SAME_MOTION_TOLERANCE, closest_motions

    closest = closest_motions(pairs)
    if closest is not None and closest["distance"] <= SAME_MOTION_TOLERANCE:
        distance = closest["distance"]
        a, b = (next(p for p in pairs if p.name == name) for name in closest["pairs"])
        raise SuiteError(f"the same motion twice: pair '{b.name}' ({b.files['x']}, {b.files['y']}) is a rotation, "
                         f"scaling, time shift or resampling of pair '{a.name}' ({a.files['x']}, {a.files['y']}) "
                         f"(motion signatures {distance:.2g} apart)")
    return closest
