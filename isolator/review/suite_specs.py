"""What a review suite is made of before any record is read: SUITE.toml and files, folders and globs.

This module holds the keys of a SUITE.toml (:data:`SUITE_KEYS`, :data:`PAIR_KEYS`, :data:`METADATA_KEYS`),
the specifications of a component and of a pair (:class:`ComponentSpec`, :class:`PairSpec`), the parsing and
checking of a SUITE.toml (:func:`specs_from_toml`: names, units, trim, scale factor, matched, fault rotation,
metadata), the grouping of record files, folders and globs into pairs by station and event
(:func:`specs_from_records`) and the naming apart of pairs of one station (:func:`distinct_names`).  The
format is described in :mod:`isolator.review.suite`, which reads the pairs.
"""

from __future__ import annotations

import math
import os
import re
from dataclasses import dataclass, field
from pathlib import Path

from isolator.errors import SuiteError, key_hint, one_table_problem

SUITE_KEYS = {"units", "trim", "pair", "name", "description"}
METADATA_KEYS = ("magnitude", "distance_km", "mechanism", "vs30_m_s", "pulse")
PAIR_KEYS = {"name", "x", "y", "z", "units", "trim", "scale_factor", "matched", "rotate_to_fault_normal_deg",
             "azimuth_x_deg", "azimuth_y_deg", *METADATA_KEYS}
#: The most [[pair]] tables a SUITE.toml holds: a code review takes 7 to 11 pairs (ASCE 7-22 17.3.2: at least 7),
#: FEMA P695's far- and near-field sets 22 and 28.  100,000 pairs were each read and hashed before any other
#: check (43.8 s to refuse one record named twice; session 24 sweep).
MAX_SUITE_PAIRS = 1000
_CHECKSUMS_RE = re.compile(r"^(SHA\d*SUMS|MD5SUMS)(\.txt)?$", re.IGNORECASE)


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


# ---- SUITE.toml --------------------------------------------------------------------------

def _component(value, base: Path, where: str) -> ComponentSpec:
    if isinstance(value, dict) and set(value) <= {"file", "component"}:
        file = value.get("file")
    else:
        file = value
    if isinstance(file, str) and not file.strip():  # `x = ""` read the suite's own folder (". : is a directory",
        # session 24 sweep)
        raise SuiteError(f"{where}: the file name is empty")
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
    if (problem := one_table_problem(pairs, "pair")) is not None:
        raise SuiteError(f"{path}: {problem}")
    if not isinstance(pairs, list) or not pairs:
        raise SuiteError(f"{path}: no [[pair]] tables")
    if len(pairs) > MAX_SUITE_PAIRS:
        raise SuiteError(f"{path}: {len(pairs):,} [[pair]] tables, more than a suite holds ({MAX_SUITE_PAIRS:,}: a "
                         "review takes 7 to 11 pairs, FEMA P695's sets 22 and 28); run many records with "
                         "`isolator batch`")
    specs, names = [], set()
    for index, table in enumerate(pairs, 1):
        where = f"{path}: pair {index}"
        if not isinstance(table, dict):
            raise SuiteError(f"{where}: must be a table")
        bad = sorted(set(table) - PAIR_KEYS)
        if bad:
            raise SuiteError(f"{where}: unknown key '{bad[0]}'{key_hint(bad[0], sorted(PAIR_KEYS), 'valid')}")
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
    from isolator.review.target import outside_earthquake

    for key in ("magnitude", "distance_km", "vs30_m_s"):
        problem = "" if metadata[key] is None else outside_earthquake(key, metadata[key])
        if problem:
            raise SuiteError(f"{where}: '{key}' = {metadata[key]:g} is {problem}")
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


# ---- pair names ---------------------------------------------------------------------------

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
