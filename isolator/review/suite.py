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

The suite's specifications (SUITE.toml, files, folders and globs) are read by :mod:`isolator.review.suite_specs`;
the components of a pair are put on one time base and rotated by :mod:`isolator.review.suite_components`; this
module reads the pairs (:func:`read_pair`), refuses duplicates and holds :class:`Pair`, :class:`Suite` and
:func:`load_suite`.
"""

from __future__ import annotations

import hashlib
import os
from dataclasses import dataclass, field

import numpy as np

from isolator.errors import SuiteError
from isolator.review.suite_components import (
    component_azimuth_deg,
    high_pass_corner_hz,
    one_time_base,
    rotate_to_fault,
)
from isolator.review.suite_specs import (
    ComponentSpec,
    PairSpec,
    distinct_names,
    specs_from_records,
    specs_from_toml,
)


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
                         f"({', '.join(f'{k} {v:g} s in {specs[k].label()}' for k, v in dts.items())}): the "
                         "components of a pair are recorded together; resample them first")
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


# ---- the suite ---------------------------------------------------------------------------

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
        except SuiteError as err:  # named no suite: `error: pair 'a': components have different time steps …`
            raise SuiteError(f"suite {source}: {err}") from None
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
