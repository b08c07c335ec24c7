"""Planning a batch: designs (file × grid), records (files, folders, globs × components), tasks."""

from __future__ import annotations

import hashlib
import itertools
import json
import math
import os
from dataclasses import dataclass
from pathlib import Path

from isolator.batch.store import ROW_SCHEMA
from isolator.errors import BatchError, one_line, one_table_problem

# file discovery lives with the records (isolator.motion.files); its names stay importable from the batch
from isolator.motion.components import label_is_vertical as is_vertical  # noqa: F401
from isolator.motion.files import SET_COMPONENTS, expand_records, record_components, station_sets  # noqa: F401

#: Numeric design keys a --grid may sweep.
GRID_KEYS = ("mass_kg", "radius_m", "stiffness_N_per_m", "mu_static", "mu_kinetic", "damping_Ns_per_m",
             "damping_ratio")

#: Largest batch planned [rows]: 1,800 rows take ~7 s on 2 cores, so a million rows is about
#: an hour; larger sweeps are refused before anything is allocated (split them).
MAX_PLAN_ROWS = 1_000_000


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
    if count > MAX_PLAN_ROWS:
        raise BatchError(f"grid {spec!r}: COUNT = {count} exceeds the largest batch, {MAX_PLAN_ROWS:,} rows "
                         "(split the sweep)", parameter="grid")
    values = [float(v) for v in np.linspace(start, stop, count)]
    if len(set(values)) != len(values):  # 2:2:3 ran three identical rows of one name, `design --vary`'s refusal
        raise BatchError(f"grid {spec!r}: START = STOP with COUNT > 1 gives the same value twice", parameter="grid")
    return key, values


def load_design_mappings(path) -> list[dict]:
    """The ``[[design]]`` tables of a designs file (not validated: a bad design is a row error).

    Raises
    ------
    BatchError
        Missing or unreadable file, invalid TOML, no ``[[design]]`` list.
    """
    from isolator.design import MAX_TOML_BYTES, load_toml
    from isolator.errors import printable

    path = Path(path)
    content = load_toml(path, "designs file", BatchError, max_bytes=MAX_TOML_BYTES)
    designs = content.get("design")
    if (problem := one_table_problem(designs, "design")) is not None:
        raise BatchError(f"{path}: {problem}")
    if not isinstance(designs, list) or not designs:
        raise BatchError(f"{path}: expected a list of designs ([[design]] tables), found none")
    outside = [key for key in content if key != "design"]
    if outside:  # read as nothing: `radius_m = 3` above the tables looked like a value every design shares
        raise BatchError(f"{path}: key '{printable(outside[0])}' is outside the [[design]] tables, where it is read by "
                         "no design: a designs file holds only [[design]] tables (give each design its keys)")
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
    from isolator.design import Design
    from isolator.errors import DesignError

    n_cases = len(mappings) * math.prod(len(values) for _, values in grids)
    if n_cases > MAX_PLAN_ROWS:
        raise BatchError(f"the sweep plans {n_cases:,} designs, more than the largest batch ({MAX_PLAN_ROWS:,} "
                         "rows): split it")
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
                    error = one_line(err)
            else:
                swept, error = {"value": mapping}, f"{label}: a design must be a table of keys"
            digest = _design_hash(swept)
            seen[digest] = seen.get(digest, -1) + 1
            if seen[digest]:
                digest = f"{digest}#{seen[digest]}"
            cases.append(DesignCase(index=len(cases), file_index=file_index, mapping=swept, source=label,
                                    design_hash=digest, error=error))
    return cases


def set_digest(path: str, partners: tuple = ()) -> str:
    """:func:`record_digest` of a record, with its partner files' paths and digests for a
    set of several files (so that a changed partner recomputes the rows)."""
    content = record_digest(path)
    if not partners:
        return content
    text = "\0".join([content] + [f"{os.path.abspath(p)}:{record_digest(p)}" for p in partners])
    return hashlib.sha256(text.encode()).hexdigest()


@dataclass(frozen=True)
class ReadOptions:
    """How records are read and scaled (part of every row key)."""

    units: str | None = None
    scale_to_pga_g: float | None = None
    dt_s: float | None = None
    harmonic: bool = True  #: also classify the harmonic response at the equivalent point
    #: components of a pair that differ: cut to the common window, or the union of their sample times
    trim: bool = False
    resample: bool = False

    def fingerprint(self) -> str:
        options = {"units": self.units, "scale_to_pga_g": self.scale_to_pga_g, "dt_s": self.dt_s}
        if not self.harmonic:
            options["harmonic"] = False
        for name in ("trim", "resample"):  # only when set: the keys of earlier batches stay valid
            if getattr(self, name):
                options[name] = True
        return json.dumps(options, sort_keys=True)


_DIGESTS: dict = {}


def file_version(path: str):
    """(size, modification time, inode) of a file, or None: a file rewritten since it was
    cached (same name, other content) is read again."""
    try:
        stat = os.stat(path)
    except OSError:
        return None
    return stat.st_size, stat.st_mtime_ns, stat.st_ino


def record_digest(path: str) -> str:
    """SHA-256 of a record file's bytes (``absent`` or ``unreadable: …`` when there are none).

    Cached per process by (path, size, modification time), so a batch reads each file once
    for its keys.  Non-regular files are never opened (a FIFO would block).
    """
    from isolator.io._common import input_file_problem

    problem = input_file_problem(path)
    if problem is not None:
        return f"unreadable: {problem}"
    stat = os.stat(path)
    cache_key = (os.path.abspath(path), stat.st_size, stat.st_mtime_ns)
    if cache_key not in _DIGESTS:
        digest = hashlib.sha256()
        try:
            with open(path, "rb") as stream:
                for block in iter(lambda: stream.read(1 << 20), b""):
                    digest.update(block)
        except OSError as err:
            return f"unreadable: {err.strerror or err}"
        _DIGESTS[cache_key] = digest.hexdigest()
    return _DIGESTS[cache_key]


def row_key(record_path: str, component: str | None, design_hash: str, options: ReadOptions,
            content: str | None = None) -> str:
    """Key of a row, from what the row *is*: never from a position in a plan.

    The record (absolute path and the SHA-256 of its content: a file changed since an
    earlier run is recomputed), the component asked, the design's own keys and values
    (``design_hash``), the read options that change results, and what a row holds
    (:data:`isolator.batch.store.ROW_SCHEMA`: the analysis schema's version and the columns), so
    that a row stored by an isolator of another schema is recomputed.

    Parameters
    ----------
    content : str, optional
        :func:`record_digest` of the file, if already computed.
    """
    content = record_digest(record_path) if content is None else content
    text = "\0".join([os.path.abspath(record_path), content, component or "", design_hash, options.fingerprint(),
                      ROW_SCHEMA])
    return hashlib.sha256(text.encode()).hexdigest()[:32]


@dataclass
class Task:
    """One unit of work: one record (component) and some of its designs; picklable."""

    record: str
    component: str | None
    options: ReadOptions
    designs: list  #: list of (DesignCase, row key)
    reports_dir: str | None = None
    map_resolution: int = 30
    #: the other files of a set of one-component files (:func:`station_sets`): Y, and Z
    partners: tuple = ()


def plan(records, designs_file, grids=(), component: str | None = None, options: ReadOptions = ReadOptions(),
         design_mappings: list | None = None, outputs=(), excluded: list | None = None, repeated: list | None = None):
    """(record files, [(record, component, partners)], design cases) of a batch.

    ``partners`` are the other files of a station's set of one-component files
    (:func:`station_sets`: analysed as a pair from its first horizontal), else ``()``.

    Raises
    ------
    BatchError
        Including a plan of more than :data:`MAX_PLAN_ROWS` rows.
    """
    files = expand_records(records, outputs, excluded, repeated)
    mappings = design_mappings if design_mappings is not None else load_design_mappings(designs_file)
    cases = expand_designs(mappings, list(grids), source=str(designs_file))
    sets = station_sets(files, component)
    members = {os.path.abspath(p) for partners in sets.values() for p in partners}
    pairs = []
    for path in files:
        if path in sets:
            pairs.append((path, component or "pair", sets[path]))
        elif os.path.abspath(path) not in members:
            pairs.extend((path, comp, ()) for comp in record_components(path, component))
    if len(pairs) * len(cases) > MAX_PLAN_ROWS:
        raise BatchError(f"the batch plans {len(pairs) * len(cases):,} rows ({len(pairs)} record components × "
                         f"{len(cases)} designs), more than the largest batch ({MAX_PLAN_ROWS:,}): split it")
    return files, pairs, cases


def make_tasks(pairs, cases, options: ReadOptions, done: set, workers: int, reports_dir=None,
               map_resolution: int = 30) -> tuple[list[Task], int]:
    """Tasks for the rows not done yet (grouped by record; a record's designs split only if
    there are fewer records than 2 × workers).  Returns (tasks, rows to do)."""
    chunks = max(1, math.ceil(2 * workers / max(1, len(pairs))))
    size = max(1, math.ceil(len(cases) / chunks))
    tasks, n_rows = [], 0
    for path, comp, partners in pairs:
        content = set_digest(path, partners)
        todo = [(case, row_key(path, comp, case.design_hash, options, content)) for case in cases]
        todo = [(case, key) for case, key in todo if key not in done]
        for start in range(0, len(todo), size):
            chunk = todo[start:start + size]
            tasks.append(Task(record=path, component=comp, options=options, designs=chunk,
                              reports_dir=reports_dir, map_resolution=map_resolution, partners=partners))
            n_rows += len(chunk)

    def size(task):
        try:
            return os.path.getsize(task.record)
        except OSError:
            return 0

    # longest first (file size ~ samples ~ reading and solving time): a short tail on the last worker
    tasks.sort(key=lambda task: (-size(task), task.record))
    return tasks, n_rows
