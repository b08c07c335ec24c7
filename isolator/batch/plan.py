"""Planning a batch: designs (file × grid), records (files, folders, globs × components), tasks."""

from __future__ import annotations

import glob as _glob
import hashlib
import itertools
import json
import math
import os
import re
from dataclasses import dataclass
from pathlib import Path

#: Numeric design keys a --grid may sweep.
GRID_KEYS = ("mass_kg", "radius_m", "stiffness_N_per_m", "mu_static", "mu_kinetic", "damping_Ns_per_m",
             "damping_ratio")

#: Columns that measure time: they differ between two runs of the same batch.
TIMING_COLUMNS = ("read_seconds", "solver_seconds", "harmonic_seconds", "row_seconds")

#: Files a folder holds that are never records.
_NOT_RECORDS = re.compile(r"^(readme.*|.*\.(md|json|toml|pdf|png|parquet|py|xml|zip|gz))$", re.IGNORECASE)


from isolator.errors import BatchError  # noqa: E402,F401 - defined with the other typed errors


def _one_line(message) -> str:
    return " ".join(str(message).split())


def parse_grid(spec: str) -> tuple[str, list[float]]:
    """Parse ``KEY=START:STOP:COUNT`` into the key and COUNT values from START to STOP inclusive.

    Parameters
    ----------
    spec : str
        e.g. ``"radius_m=1:4:13"`` [-].

    Returns
    -------
    (str, list of float)

    Raises
    ------
    BatchError
        Unknown key, unparsable numbers, COUNT < 1, COUNT = 1 with START ≠ STOP.
    """
    import numpy as np

    if "=" not in spec:
        raise BatchError(f"grid {spec!r}: expected KEY=START:STOP:COUNT, e.g. radius_m=1:4:13", parameter="grid")
    key, _, values = (part.strip() for part in spec.partition("="))
    if key not in GRID_KEYS:
        raise BatchError(f"grid {spec!r}: {key!r} is not a numeric design key (choose one of: "
                         f"{', '.join(GRID_KEYS)})", parameter="grid")
    parts = values.split(":")
    if len(parts) != 3:
        raise BatchError(f"grid {spec!r}: expected KEY=START:STOP:COUNT, e.g. {key}=1:4:13", parameter="grid")
    try:
        start, stop = float(parts[0]), float(parts[1])
    except ValueError:
        raise BatchError(f"grid {spec!r}: START and STOP must be numbers", parameter="grid") from None
    try:
        count = int(parts[2])
    except ValueError:
        raise BatchError(f"grid {spec!r}: COUNT must be a whole number, got {parts[2]!r}", parameter="grid") from None
    if not (math.isfinite(start) and math.isfinite(stop)):
        raise BatchError(f"grid {spec!r}: START and STOP must be finite", parameter="grid")
    if count < 1:
        raise BatchError(f"grid {spec!r}: COUNT must be >= 1, got {count}", parameter="grid")
    if count == 1 and start != stop:
        raise BatchError(f"grid {spec!r}: COUNT = 1 needs START = STOP", parameter="grid")
    return key, [float(v) for v in np.linspace(start, stop, count)]


def load_design_mappings(path) -> list[dict]:
    """The ``[[design]]`` tables of a designs file (not validated: a bad design is a row error).

    Raises
    ------
    BatchError
        Missing or unreadable file, invalid TOML, no ``[[design]]`` list.
    """
    from isolator.design import load_toml

    path = Path(path)
    content = load_toml(path, "designs file", BatchError)
    designs = content.get("design")
    if not isinstance(designs, list) or not designs:
        raise BatchError(f"{path}: expected a list of designs ([[design]] tables), found none")
    return designs


@dataclass(frozen=True)
class DesignCase:
    """One design of the batch: its position, its keys, and why it is invalid (or "")."""

    index: int
    file_index: int
    mapping: dict
    source: str
    design_hash: str
    error: str = ""


def _design_hash(mapping) -> str:
    text = json.dumps(mapping, sort_keys=True, default=str)
    return hashlib.sha1(text.encode()).hexdigest()[:16]


def expand_designs(mappings: list, grids: list[tuple[str, list[float]]], source: str = "designs") -> list[DesignCase]:
    """Every design of the file × the cartesian product of the grids, validated.

    A grid value replaces the key in every design; the name gets the values appended,
    e.g. ``"FPS [radius_m=2, mu_static=0.06]"``.  Invalid designs keep their
    :class:`~isolator.design.DesignError` message in ``error``.
    """
    from isolator.design import Design, DesignError

    combos = list(itertools.product(*[[(key, value) for value in values] for key, values in grids])) or [()]
    cases = []
    seen: dict = {}  # the same design twice (a repeated table, coinciding grid values) keeps both rows
    for file_index, mapping in enumerate(mappings):
        for combo in combos:
            label = f"{source}[design {file_index}]"
            if isinstance(mapping, dict):
                swept = dict(mapping)
                for key, value in combo:
                    swept[key] = value
                if combo and isinstance(swept.get("name"), str):
                    swept["name"] = f"{swept['name']} [" + ", ".join(f"{k}={v:g}" for k, v in combo) + "]"
                error = ""
                try:
                    Design.from_mapping(swept, source=label)
                except DesignError as err:
                    error = _one_line(err)
            else:
                swept, error = {"value": mapping}, f"{label}: a design must be a table of keys"
            digest = _design_hash(swept)
            seen[digest] = seen.get(digest, -1) + 1
            if seen[digest]:
                digest = f"{digest}#{seen[digest]}"
            cases.append(DesignCase(index=len(cases), file_index=file_index, mapping=swept, source=label,
                                    design_hash=digest, error=error))
    return cases


def expand_records(arguments) -> list[str]:
    """Record files from files, folders (recursively, sorted) and glob patterns.

    A literal path that does not exist is kept (its rows will say why); a glob that
    matches nothing and an empty folder are user mistakes.

    Raises
    ------
    BatchError
    """
    files: list[str] = []
    for argument in arguments:
        argument = str(argument)
        if os.path.isdir(argument):
            found = sorted(str(p) for p in Path(argument).rglob("*")
                           if p.is_file() and not any(part.startswith(".") for part in p.relative_to(argument).parts)
                           and not _NOT_RECORDS.match(p.name))
            if not found:
                raise BatchError(f"{argument}: folder holds no record files")
            files.extend(found)
        elif _glob.has_magic(argument):
            found = sorted(p for p in _glob.glob(argument, recursive=True) if os.path.isfile(p))
            if not found:
                raise BatchError(f"{argument}: no file matches this pattern")
            files.extend(found)
        else:
            files.append(argument)
    unique, seen = [], set()
    for path in files:
        key = os.path.abspath(path)
        if key not in seen:
            seen.add(key)
            unique.append(path)
    if not unique:
        raise BatchError("no record given")
    return unique


def is_vertical(label: str) -> bool:
    """True for a vertical component label (Z, UD, U-D, Up, Down, Vert; channel code ending in Z)."""
    text = label.upper()
    orientation = re.search(r"\(([^)]*)\)", text)
    names = [text.split(" (")[0].strip()] + ([orientation.group(1).strip()] if orientation else [])
    for name in names:
        if name in ("Z", "UD", "U-D", "UP", "DOWN", "VERT", "VERTICAL", "V"):
            return True
        if len(name) == 3 and name.isalpha() and name.endswith("Z"):
            return True
    return False


def record_components(path: str, component: str | None) -> list[str | None]:
    """Components to analyse in a file: ``[component]``, or every horizontal one for ``all-horizontal``.

    For ``all-horizontal`` a single-component file gives ``[None]`` (its one
    component); a file that cannot be listed also gives ``[None]`` (the read then fails
    with the file's message, in the rows).
    """
    if component != "all-horizontal":
        return [component]
    from isolator.motion import RecordError, list_components

    try:
        labels = list_components(path)
    except (RecordError, ValueError, OSError):
        return [None]
    if len(labels) <= 1:
        return [None]
    return [label for label in labels if not is_vertical(label)] or [None]


@dataclass(frozen=True)
class ReadOptions:
    """How records are read and scaled (part of every row key)."""

    units: str | None = None
    scale_to_pga_g: float | None = None
    dt_s: float | None = None
    harmonic: bool = True  #: also classify the harmonic response at the equivalent point

    def fingerprint(self) -> str:
        options = {"units": self.units, "scale_to_pga_g": self.scale_to_pga_g, "dt_s": self.dt_s}
        if not self.harmonic:
            options["harmonic"] = False
        return json.dumps(options, sort_keys=True)


def row_key(record_path: str, component: str | None, design_hash: str, options: ReadOptions) -> str:
    """Deterministic key of a row: absolute record path, component asked, design hash, read options."""
    text = "\0".join([os.path.abspath(record_path), component or "", design_hash, options.fingerprint()])
    return hashlib.sha1(text.encode()).hexdigest()[:20]


@dataclass
class Task:
    """One unit of work: one record (component) and some of its designs; picklable."""

    record: str
    component: str | None
    options: ReadOptions
    designs: list  #: list of (DesignCase, row key)
    reports_dir: str | None = None
    map_resolution: int = 30


def plan(records, designs_file, grids=(), component: str | None = None, options: ReadOptions = ReadOptions(),
         design_mappings: list | None = None):
    """(record files, [(record, component)], design cases) of a batch."""
    files = expand_records(records)
    mappings = design_mappings if design_mappings is not None else load_design_mappings(designs_file)
    cases = expand_designs(mappings, list(grids), source=str(designs_file))
    pairs = [(path, comp) for path in files for comp in record_components(path, component)]
    return files, pairs, cases


def make_tasks(pairs, cases, options: ReadOptions, done: set, workers: int, reports_dir=None,
               map_resolution: int = 30) -> tuple[list[Task], int]:
    """Tasks for the rows not done yet (grouped by record; a record's designs split only if
    there are fewer records than 2 × workers).  Returns (tasks, rows to do)."""
    chunks = max(1, math.ceil(2 * workers / max(1, len(pairs))))
    size = max(1, math.ceil(len(cases) / chunks))
    tasks, n_rows = [], 0
    for path, comp in pairs:
        todo = [(case, row_key(path, comp, case.design_hash, options)) for case in cases]
        todo = [(case, key) for case, key in todo if key not in done]
        for start in range(0, len(todo), size):
            chunk = todo[start:start + size]
            tasks.append(Task(record=path, component=comp, options=options, designs=chunk,
                              reports_dir=reports_dir, map_resolution=map_resolution))
            n_rows += len(chunk)

    def size(task):
        try:
            return os.path.getsize(task.record)
        except OSError:
            return 0

    # longest first (file size ~ samples ~ reading and solving time): a short tail on the last worker
    tasks.sort(key=lambda task: (-size(task), task.record))
    return tasks, n_rows
