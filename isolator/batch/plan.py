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

#: Files a folder holds that are never records (a batch's own lock and MAC files, and the checksum
#: lists that travel with record folders, included).
_NOT_RECORDS = re.compile(r"^(readme.*|(sha\d*sums|md5sums)(\.txt)?"
                          r"|.*\.(md|json|toml|pdf|png|parquet|py|xml|zip|gz|lock|jsonl))$", re.IGNORECASE)
#: Largest batch planned [rows]: 1,800 rows take ~7 s on 2 cores, so a million rows is about
#: an hour; larger sweeps are refused before anything is allocated (split them).
MAX_PLAN_ROWS = 1_000_000
#: Version of what a row holds: part of every row key, so that rows of an older isolator
#: whose columns meant something else are never reused.
ROW_SCHEMA_VERSION = 2


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
    if count > MAX_PLAN_ROWS:
        raise BatchError(f"grid {spec!r}: COUNT = {count} exceeds the largest batch, {MAX_PLAN_ROWS:,} rows "
                         "(split the sweep)", parameter="grid")
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


def _is_output(path, outputs) -> bool:
    """True if ``path`` is one of the batch's outputs, its part files, lock or report folder."""
    real = os.path.realpath(path)
    for output in outputs:
        out = os.path.realpath(output)
        if real in (out, out + ".lock") or real.startswith(out + ".parts" + os.sep) or \
                real.startswith(out.rstrip(os.sep) + os.sep):
            return True
    return False


def expand_records(arguments, outputs=(), excluded: list | None = None) -> list[str]:
    """Record files from files, folders (recursively, sorted) and glob patterns.

    A literal path that does not exist is kept (its rows will say why); a glob that
    matches nothing and an empty folder are user mistakes.  Files of the batch itself
    (``outputs``: the table, its ``.parts/`` and lock, the summary, chart and reports
    folder) and any ``*.parts`` folder are never records, so that ``-o`` may sit inside
    the records folder.

    Raises
    ------
    BatchError
    """
    files: list[str] = []
    outputs = [str(item) for item in outputs if item]
    excluded = [] if excluded is None else excluded

    def wanted(path) -> bool:
        if _is_output(path, outputs):
            excluded.append(str(path))  # run_batch checks that such a file is the batch's own
            return False
        return True

    for argument in arguments:
        argument = str(argument)
        if os.path.isdir(argument):
            found = sorted(str(p) for p in Path(argument).rglob("*")
                           if p.is_file() and not any(part.startswith(".") or part.endswith(".parts")
                                                      for part in p.relative_to(argument).parts[:-1])
                           and not p.name.startswith(".") and not _NOT_RECORDS.match(p.name) and wanted(p))
            if not found:
                raise BatchError(f"{argument}: folder holds no record files")
            files.extend(found)
        elif _glob.has_magic(argument) and not os.path.lexists(argument):
            found = sorted(p for p in _glob.glob(argument, recursive=True) if os.path.isfile(p) and wanted(p))
            if not found:
                raise BatchError(f"{argument}: no file matches this pattern")
            files.extend(found)
        else:  # a literal path, even with [ ] * ? in its name, names exactly that file
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
    """True for a vertical component label (Z, UD, U-D, Up, Down, Vert; channel code ending in Z):
    :func:`isolator.motion.pair.label_is_vertical`."""
    from isolator.motion.pair import label_is_vertical

    return label_is_vertical(label)


#: Suffixes of formats that hold one component per file: never listed at planning.
_ONE_COMPONENT_SUFFIXES = frozenset({".at2", ".smc", ".txt", ".csv", ".acc", ".dat", ".tsv", ".asc", ".th", ".xy",
                                     ".sac"})
#: Analyses of a whole file: its two horizontal components ("pair") or with the vertical ("all").
SET_COMPONENTS = ("pair", "all")


def _knet_set_member(path: str) -> tuple[bool, bool]:
    """(belongs to a K-NET/KiK-net set of two horizontals, is the set's first existing file)."""
    from isolator.motion.pair import _knet_siblings

    siblings = _knet_siblings(Path(path))
    if siblings is None:
        return False, False
    horizontal = [p for p in siblings if not p.suffix.upper().startswith(".UD")]
    if len(horizontal) != 2:
        return False, False
    return True, os.path.abspath(siblings[0]) == os.path.abspath(path)


def record_components(path: str, component: str | None) -> list[str | None]:
    """Components to analyse in a file.

    * ``None`` (the default): ``["pair"]`` for a file with two horizontal components
      (a multi-channel file, or the first file of a K-NET set), ``[]`` for the other
      files of that set, ``[None]`` (the file's one component) otherwise;
    * ``"pair"`` / ``"all"``: the same, the vertical included for ``"all"``;
    * ``"all-horizontal"``: every horizontal component of a multi-component file, one by one;
    * any other label: ``[component]``.

    A file that cannot be listed gives ``[None]`` (or ``[component]``): the read then
    fails with the file's message, in the rows.
    """
    if component not in (None, "all-horizontal", *SET_COMPONENTS):
        return [component]
    knet, first = _knet_set_member(path)
    if knet and component != "all-horizontal":
        return [component or "pair"] if first else []
    if component is None and Path(path).suffix.lower() in _ONE_COMPONENT_SUFFIXES:
        return [None]
    from isolator.motion import RecordError, list_components

    try:
        labels = list_components(path)
    except (RecordError, ValueError, OSError):
        return [component if component in SET_COMPONENTS else None]
    horizontal = [label for label in labels if not is_vertical(label)]
    if component == "all-horizontal":
        return horizontal if len(labels) > 1 and horizontal else [None]
    if len(horizontal) == 2:
        return [component or "pair"]
    return [component if component in SET_COMPONENTS else None]


def station_sets(files, component: str | None) -> dict[str, tuple[str, ...]]:
    """Pairs made of several one-component files: one station's horizontals (and vertical).

    Files of one component each (PEER AT2, SMC, …) that sit in one folder and whose headers
    name the same network, station and event form a set when it holds exactly two
    horizontal components with different labels, and at most one vertical.  Only the
    headers are read (a few lines a file).  Anything else (one file of the station, the same
    component twice, as ``TAK000.AT2`` beside ``RSN1120_KOBE_TAK000.AT2``, a header without
    station or event, a file that cannot be read) leaves the files alone, analysed one
    component each; two files of one motion under different labels are refused when the
    pair is read (an error row).

    Returns
    -------
    dict
        ``{x path: (y path,) or (y path, z path)}`` for the first horizontal (sorted) of
        each set; the other members of a set are the keys' partners.  Empty unless
        ``component`` is None, ``"pair"`` or ``"all"``.
    """
    if component not in (None, *SET_COMPONENTS):
        return {}
    groups: dict = {}
    for path in files:
        header = _station_header(path)
        if header is not None:
            key, label = header
            groups.setdefault(key, []).append((path, label, is_vertical(label)))
    sets = {}
    for items in groups.values():
        horizontal = sorted(item for item in items if not item[2])
        vertical = [item for item in items if item[2]]
        if len(horizontal) != 2 or len(vertical) > 1 or horizontal[0][1] == horizontal[1][1]:
            continue
        sets[horizontal[0][0]] = (horizontal[1][0], *(item[0] for item in vertical))
    return sets


def _station_header(path: str):
    """((folder, network, station, event), component label) from the header of a PEER AT2 or USGS SMC
    file (a few lines read, not the samples), or None: another format, no station or event in the
    header, a file that cannot be read (its rows will say why)."""
    from isolator.motion.read import read_header

    header = read_header(path)
    if header is None:
        return None
    label, prov = header
    station, event = prov.get("station", ""), prov.get("event", prov.get("event_origin_time", ""))
    if not station or not event:
        return None
    return (os.path.dirname(os.path.abspath(path)), prov.get("network", ""), station, event), label


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
    (``design_hash``), the read options that change results, and
    :data:`ROW_SCHEMA_VERSION`.

    Parameters
    ----------
    content : str, optional
        :func:`record_digest` of the file, if already computed.
    """
    content = record_digest(record_path) if content is None else content
    text = "\0".join([os.path.abspath(record_path), content, component or "", design_hash, options.fingerprint(),
                      str(ROW_SCHEMA_VERSION)])
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
         design_mappings: list | None = None, outputs=(), excluded: list | None = None):
    """(record files, [(record, component, partners)], design cases) of a batch.

    ``partners`` are the other files of a station's set of one-component files
    (:func:`station_sets`: analysed as a pair from its first horizontal), else ``()``.

    Raises
    ------
    BatchError
        Including a plan of more than :data:`MAX_PLAN_ROWS` rows.
    """
    files = expand_records(records, outputs, excluded)
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
