"""Batch: many records × many designs into one table — resumable, parallel, local or on Dask.

The work is planned in the parent process and executed by one of two executors chosen
at the start (local processes, or an existing ``dask.distributed`` cluster); the code
that computes rows (:func:`run_task`) is the same for both.

* **Cases.** Records (files, folders, globs) × components × designs (a ``[[design]]``
  list in a TOML file, each optionally swept by ``--grid KEY=START:STOP:COUNT``, the
  cartesian product).  One row per (record, component, design).
* **Tasks.** Work is grouped by record: a task reads one record (once per worker
  process: a small per-process cache serves the other tasks of the same record) and
  runs all its designs, so that reading, the intensity measures and process overhead
  are paid once per record, not once per row.  The harmonic classification at the
  equivalent point is cached per process per distinct (α, k, η, µs, µk).
* **Never lose work.** Each finished task is written as one JSON-lines part file in
  ``<output>.parts/`` (written to a temporary name, then renamed: a part is whole or
  absent).  A row has a deterministic key (record path, component, design hash, read
  options); a new run with the same arguments skips the keys already present and the
  final table (sorted by record, component, design index) is the same as that of an
  uninterrupted run, except the timing columns (:data:`TIMING_COLUMNS`).  The final
  CSV or Parquet file is written through a temporary file and an atomic rename; the
  parts are removed after it.
* **Errors.** A record that cannot be read gives one row per design with the one-line
  message in ``error``; an invalid design (from the file or a grid value) gives rows
  with ``error`` for that design; the batch goes on.
"""

from __future__ import annotations

import glob as _glob
import hashlib
import itertools
import json
import math
import os
import re
import time
import uuid
from dataclasses import dataclass, field
from pathlib import Path

from isolator.atomic import atomic_path

#: Numeric design keys a --grid may sweep.
GRID_KEYS = ("mass_kg", "radius_m", "stiffness_N_per_m", "mu_static", "mu_kinetic", "damping_Ns_per_m",
             "damping_ratio")

#: Columns that measure time: they differ between two runs of the same batch.
TIMING_COLUMNS = ("read_seconds", "solver_seconds", "harmonic_seconds", "row_seconds")

#: Column order of the table (columns of every row; a row may leave some empty).
COLUMNS = (
    "record", "component", "design_index", "design_name", "error",
    # record provenance
    "record_format", "record_station", "record_station_name", "record_network", "record_channel",
    "record_event", "record_date", "record_starttime", "record_units_source", "record_npts", "record_dt_s",
    "record_duration_s", "record_scale_factor",
    # intensity measures (of the motion analysed, after scaling)
    "pga_m_s2", "pgv_m_s", "pgd_m", "arias_m_s", "d5_95_s", "predominant_period_s", "a0_equiv_m",
    "omega_equiv_rad_s",
    # design
    "design_file_index", "design_kind", "mass_kg", "radius_m", "stiffness_N_per_m", "mu_static", "mu_kinetic",
    "damping_Ns_per_m", "damping_ratio", "isolated_period_s",
    # the paper's dimensionless point
    "alpha", "k", "eta", "configuration",
    # simulate
    "peak_displacement_m", "residual_displacement_m", "peak_velocity_m_s", "peak_transmitted_acceleration_m_s2",
    "slip_time_s", "n_events", "energy_input_J_per_kg", "energy_friction_J_per_kg", "energy_viscous_J_per_kg",
    "energy_balance_error_J_per_kg", "solver_status",
    # engineering quantities at the peak displacement
    "effective_period_s", "effective_damping_ratio", "peak_transmitted_force_N", "base_shear_coefficient",
    # classification (record, over D5-95) and harmonic (at the equivalent point)
    "regime_record", "zeta_record", "amplitude_record", "amplified_record", "dominant_force_record",
    "dominant_force_rho_record", "rho_ev_record", "rho_vf_record", "rho_ef_record", "window_start_s",
    "window_end_s",
    "regime_harmonic", "zeta_harmonic", "amplitude_harmonic", "amplified_harmonic", "dominant_force_harmonic",
    "dominant_force_rho_harmonic", "rho_ev_harmonic", "rho_vf_harmonic", "rho_ef_harmonic", "harmonic_steady",
    "harmonic_status", "n_disagreements",
    # timings (not compared between runs)
    "read_seconds", "solver_seconds", "harmonic_seconds", "row_seconds",
    "row_key",
)

_CLASS_FIELDS = ("regime", "zeta", "amplitude", "amplified", "dominant_force", "dominant_force_rho",
                 "rho_ev", "rho_vf", "rho_ef")

#: Files a folder holds that are never records.
_NOT_RECORDS = re.compile(r"^(readme.*|.*\.(md|json|toml|pdf|png|parquet|py|xml|zip|gz))$", re.IGNORECASE)


class BatchError(ValueError):
    """A mistake in the batch command itself (bad --grid, designs file, record pattern …)."""


def _one_line(message) -> str:
    return " ".join(str(message).split())


# ======================================================================================
# Cases: designs (file × grid) and records (files, folders, globs × components)
# ======================================================================================


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
        raise BatchError(f"--grid {spec!r}: expected KEY=START:STOP:COUNT, e.g. radius_m=1:4:13")
    key, _, values = (part.strip() for part in spec.partition("="))
    if key not in GRID_KEYS:
        raise BatchError(f"--grid {spec!r}: {key!r} is not a numeric design key (choose one of: "
                         f"{', '.join(GRID_KEYS)})")
    parts = values.split(":")
    if len(parts) != 3:
        raise BatchError(f"--grid {spec!r}: expected KEY=START:STOP:COUNT, e.g. {key}=1:4:13")
    try:
        start, stop = float(parts[0]), float(parts[1])
    except ValueError:
        raise BatchError(f"--grid {spec!r}: START and STOP must be numbers") from None
    try:
        count = int(parts[2])
    except ValueError:
        raise BatchError(f"--grid {spec!r}: COUNT must be a whole number, got {parts[2]!r}") from None
    if not (math.isfinite(start) and math.isfinite(stop)):
        raise BatchError(f"--grid {spec!r}: START and STOP must be finite")
    if count < 1:
        raise BatchError(f"--grid {spec!r}: COUNT must be >= 1, got {count}")
    if count == 1 and start != stop:
        raise BatchError(f"--grid {spec!r}: COUNT = 1 needs START = STOP")
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


# ======================================================================================
# The worker side: read a record once, run its designs
# ======================================================================================

_MOTION_CACHE: dict = {}
_HARMONIC_CACHE: dict = {}
_HARMONIC_CACHE_MAX = 200_000


def _read_motion(path: str, component: str | None, options: ReadOptions):
    """(GroundMotion, IntensityMeasures, strong-motion window, scale factor, read seconds), cached per process.

    ``--units`` is used for the files that do not state their units (text, MiniSEED …)
    and ``--dt`` for one-column text files that give no time step: a file that states
    them is read as it says, so that one batch can mix formats.
    """
    key = (os.path.abspath(path), component, options)
    if key in _MOTION_CACHE:
        return _MOTION_CACHE[key]
    from isolator.metrics import strong_motion_window_s
    from isolator.motion import RecordError, read_ground_motion
    from isolator.units import STANDARD_GRAVITY

    start = time.perf_counter()
    given: dict = {}
    while True:
        try:
            motion = read_ground_motion(path, component=component, **given)
            break
        except RecordError as err:
            message, before = str(err), dict(given)
            if options.units is not None and "does not state its units" in message:
                given["units"] = options.units
            if options.dt_s is not None and "no time step" in message:
                given["dt_s"] = options.dt_s
            if given == before:
                raise
    factor = 1.0
    if options.scale_to_pga_g is not None:
        original = motion.pga_m_s2
        motion = motion.scaled_to_pga(options.scale_to_pga_g * STANDARD_GRAVITY)
        factor = motion.pga_m_s2 / original
    measures = motion.intensity_measures()
    window = strong_motion_window_s(motion.acceleration_m_s2, motion.dt_s)
    result = (motion, measures, window, factor, time.perf_counter() - start)
    if len(_MOTION_CACHE) >= 4:
        _MOTION_CACHE.pop(next(iter(_MOTION_CACHE)))
    _MOTION_CACHE[key] = result
    return result


def _harmonic_classification(alpha, k, eta, mu_s, mu_k):
    """(Classification, steady, status, seconds) at a point; cached per process (seconds = 0 on a hit)."""
    key = (alpha, k, eta, mu_s, mu_k)
    hit = _HARMONIC_CACHE.get(key)
    if hit is not None:
        return hit[0], hit[1], hit[2], 0.0
    from isolator.metrics import classify_harmonic
    from isolator.solver.harmonic import harmonic_response

    start = time.perf_counter()
    # the classification reads the exact event metrics, not the dense output: 2 samples per period
    harmonic = harmonic_response(alpha, k, eta, mu_s, mu_k, samples_per_period=2)
    classification = classify_harmonic(harmonic)
    seconds = time.perf_counter() - start
    if len(_HARMONIC_CACHE) < _HARMONIC_CACHE_MAX:
        _HARMONIC_CACHE[key] = (classification, harmonic.steady, harmonic.status)
    return classification, harmonic.steady, harmonic.status, seconds


def _design_columns(case: DesignCase, design=None) -> dict:
    if design is not None:
        d = design.as_dict()
        out = {"design_name": d["name"], "design_kind": d["kind"]}
        out.update({key: d[key] for key in ("mass_kg", "radius_m", "stiffness_N_per_m", "mu_static", "mu_kinetic",
                                            "damping_Ns_per_m", "damping_ratio", "isolated_period_s")})
    else:
        mapping = case.mapping
        name = mapping.get("name")
        out = {"design_name": name if isinstance(name, str) else ""}
        for key in GRID_KEYS:
            value = mapping.get(key)
            if isinstance(value, (int, float)) and not isinstance(value, bool):
                out[key] = float(value)
    out["design_index"] = case.index
    out["design_file_index"] = case.file_index
    return out


def _record_columns(path: str, component: str | None, motion=None, measures=None, factor=1.0,
                    read_seconds=None) -> dict:
    out = {"record": path, "component": component or ""}
    if motion is None:
        return out
    prov = motion.provenance
    out.update({
        "component": motion.component, "record_format": prov.get("format", ""),
        "record_station": prov.get("station", ""), "record_station_name": prov.get("station_name", ""),
        "record_network": prov.get("network", ""), "record_channel": prov.get("channel", ""),
        "record_event": prov.get("event", ""), "record_date": prov.get("date", ""),
        "record_starttime": prov.get("starttime", ""), "record_units_source": motion.units_source,
        "record_npts": motion.npts, "record_dt_s": motion.dt_s, "record_duration_s": motion.duration_s,
        "record_scale_factor": factor, "read_seconds": read_seconds,
    })
    out.update(measures.as_dict())
    return out


def _analyse_row(design, motion, measures, window, harmonic: bool = True) -> dict:
    """The numbers of one (record, design): point, simulate, classifications (no dict of the report)."""
    from isolator.adapter import adapt, engineering_quantities
    from isolator.metrics import classify_record, compare
    from isolator.solver.record import simulate_record

    # the record's intensity measures are computed once per record, not per design
    adaptation = adapt(design, motion, measures)
    point, system = adaptation.point, adaptation.system
    response = simulate_record(motion.acceleration_m_s2, motion.dt_s, system=system)
    record_class = classify_record(response, point, design, window_s=window)
    if harmonic:
        harmonic_class, steady, status, harmonic_seconds = _harmonic_classification(
            point.alpha, point.k, point.eta, point.mu_s, point.mu_k)
    else:
        harmonic_class, steady, status, harmonic_seconds = None, None, "not computed (--no-harmonic)", 0.0
    engineering = engineering_quantities(design, response)
    row = {
        "alpha": point.alpha, "k": point.k, "eta": point.eta, "configuration": system.configuration,
        "peak_displacement_m": response.peak_displacement_m,
        "residual_displacement_m": response.residual_displacement_m,
        "peak_velocity_m_s": response.peak_velocity_m_s,
        "peak_transmitted_acceleration_m_s2": response.peak_transmitted_acceleration_m_s2,
        "slip_time_s": response.slip_time_s, "n_events": int(response.n_events),
        "energy_input_J_per_kg": response.energy_input_J_per_kg,
        "energy_friction_J_per_kg": response.energy_friction_J_per_kg,
        "energy_viscous_J_per_kg": response.energy_viscous_J_per_kg,
        "energy_balance_error_J_per_kg": response.energy_balance_error_J_per_kg,
        "solver_status": response.message,
        "effective_period_s": engineering["effective_period_s"],
        "effective_damping_ratio": engineering["effective_damping_ratio"],
        "peak_transmitted_force_N": engineering["peak_transmitted_force_N"],
        "base_shear_coefficient": engineering["base_shear_coefficient"],
        "window_start_s": record_class.window_s[0], "window_end_s": record_class.window_s[1],
        "harmonic_steady": None if steady is None else bool(steady), "harmonic_status": status,
        "n_disagreements": None if harmonic_class is None else len(compare(record_class, harmonic_class)),
        "solver_seconds": response.solver_seconds, "harmonic_seconds": harmonic_seconds,
    }
    for name in _CLASS_FIELDS:
        row[f"{name}_record"] = getattr(record_class, name)
        row[f"{name}_harmonic"] = None if harmonic_class is None else getattr(harmonic_class, name)
    return row


def _write_report(task: Task, case: DesignCase, design, motion, factor) -> None:
    from isolator.report.pdf import write_report
    from isolator.report.summary import analyse

    note = f"Record scaled to PGA {task.options.scale_to_pga_g:g} g (factor {factor:.4g})." \
        if task.options.scale_to_pga_g is not None else ""
    analysis = analyse(design, motion, record_label=task.record, scaling_note=note)
    safe = re.sub(r"[^A-Za-z0-9_.-]+", "_", f"{case.index:05d}_{Path(task.record).stem}_{motion.component}")
    target = Path(task.reports_dir) / f"{safe.strip('_')}.pdf"
    target.parent.mkdir(parents=True, exist_ok=True)
    write_report(analysis, target, map_resolution=task.map_resolution, command="isolator batch", workers=1)


def run_task(task: Task) -> list[dict]:
    """Rows of one task (the function both executors run).  Never raises for a bad record or design."""
    from isolator.design import Design

    base = {"record": task.record, "component": task.component or ""}
    try:
        motion, measures, window, factor, read_seconds = _read_motion(task.record, task.component, task.options)
    except Exception as err:  # noqa: BLE001 - any failure to read is the rows' error, the batch goes on
        message = _one_line(err) if str(err) else type(err).__name__
        if task.record not in message:
            message = f"{task.record}: {message}"
        return [{**base, **_design_columns(case), "error": message, "row_key": key} for case, key in task.designs]
    record_cols = _record_columns(task.record, task.component, motion, measures, factor, read_seconds)
    rows = []
    for case, key in task.designs:
        row = {**record_cols, "row_key": key}
        if case.error:
            rows.append({**row, **_design_columns(case), "error": case.error})
            continue
        try:
            start = time.perf_counter()
            design = Design.from_mapping(case.mapping, source=case.source)
            row.update(_design_columns(case, design))
            row.update(_analyse_row(design, motion, measures, window, task.options.harmonic))
            row["row_seconds"] = time.perf_counter() - start
            if task.reports_dir:
                _write_report(task, case, design, motion, factor)
            row["error"] = ""
        except Exception as err:  # noqa: BLE001 - one design's failure is its row's error
            row.update(_design_columns(case))
            row["error"] = f"{case.source}: {type(err).__name__}: {_one_line(err)}"
        rows.append(row)
    return rows


# ======================================================================================
# Part files: an append-only record of finished tasks
# ======================================================================================


def _json_default(value):
    if hasattr(value, "item"):
        return value.item()
    if isinstance(value, tuple):
        return list(value)
    return str(value)


class PartStore:
    """``<output>.parts/``: one JSON-lines file per finished task, written atomically."""

    def __init__(self, output):
        output = Path(output)
        self.directory = output.with_name(output.name + ".parts")

    def rows(self) -> list[dict]:
        """Rows of every complete part (temporary files of an interrupted write are ignored)."""
        if not self.directory.is_dir():
            return []
        rows = []
        for part in sorted(self.directory.glob("part-*.jsonl")):
            with open(part, encoding="utf-8") as stream:
                for line in stream:
                    line = line.strip()
                    if line:
                        rows.append(json.loads(line))
        return rows

    def write(self, rows: list[dict]) -> None:
        if not rows:
            return
        self.directory.mkdir(parents=True, exist_ok=True)
        name = f"part-{time.time_ns():020d}-{uuid.uuid4().hex[:8]}.jsonl"
        tmp = self.directory / f".{name}.tmp"
        with open(tmp, "w", encoding="utf-8") as stream:
            for row in rows:
                stream.write(json.dumps(row, default=_json_default) + "\n")
            stream.flush()
            os.fsync(stream.fileno())
        os.replace(tmp, self.directory / name)

    def remove(self) -> None:
        import shutil

        shutil.rmtree(self.directory, ignore_errors=True)


# ======================================================================================
# Executors: local processes or a dask.distributed cluster, one interface
# ======================================================================================


def default_jobs() -> int:
    """All cores this process may use."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover - not Linux
        return max(1, os.cpu_count() or 1)


def warm_up() -> None:
    """Import the readers and load the compiled solver functions (numba's disk cache) once.

    Called in the parent before the local pool forks, so that workers inherit them
    instead of each loading them again (≈ 2 s of CPU per process).
    """
    import numpy as np

    from isolator.motion import intensity_measures
    from isolator.solver.harmonic import harmonic_response
    from isolator.solver.record import simulate_record

    wave = np.sin(np.arange(400) * 0.05)
    intensity_measures(wave, 0.01)
    simulate_record(wave, 0.01, mu_static=0.05, stiffness_per_mass=1.0, damping_per_mass=0.1)
    harmonic_response(2.0, 0.1, 0.1, 0.05, samples_per_period=2)


def _iterate_local(tasks: list[Task], jobs: int):
    """Yield (task, rows or exception) as tasks finish, on ``jobs`` local processes."""
    warm_up()
    if jobs <= 1:
        for task in tasks:
            yield task, run_task(task)
        return
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor, as_completed

    pool = ProcessPoolExecutor(max_workers=jobs, mp_context=multiprocessing.get_context("fork"))
    try:
        futures = {pool.submit(run_task, task): task for task in tasks}
        for future in as_completed(futures):
            try:
                yield futures[future], future.result()
            except Exception as err:  # noqa: BLE001 - a lost worker: the task is not written, a rerun retries it
                yield futures[future], err
    finally:
        pool.shutdown(wait=True, cancel_futures=True)


def _iterate_dask(tasks: list[Task], address: str):
    """Yield (task, rows or exception) as tasks finish on the dask.distributed cluster at ``address``."""
    from distributed import Client, as_completed

    try:
        client = Client(address, timeout=10)
    except (OSError, TimeoutError) as err:
        raise BatchError(f"--scheduler {address}: cannot connect ({_one_line(err)})") from None
    try:
        futures = {}
        for task in tasks:
            future = client.submit(run_task, task, pure=False)
            futures[future.key] = (future, task)
        for future in as_completed([f for f, _ in futures.values()]):
            task = futures[future.key][1]
            try:
                yield task, future.result()
            except Exception as err:  # noqa: BLE001 - a lost worker: a rerun retries the task
                yield task, err
    finally:
        client.close()


# ======================================================================================
# The batch
# ======================================================================================


@dataclass
class BatchResult:
    """What a batch did."""

    output: str
    n_rows: int
    n_failed: int  #: rows with an error
    n_resumed: int  #: rows found done from an earlier run
    n_lost_tasks: int  #: tasks whose worker died (rerun to finish them)
    lost_messages: list = field(default_factory=list)
    seconds: dict = field(default_factory=dict)
    table: object = None  #: pandas.DataFrame

    def final_line(self) -> str:
        line = f"{self.n_rows} rows, {self.n_failed} failed"
        if self.n_lost_tasks:
            line += f", {self.n_lost_tasks} task(s) lost: rerun the same command to finish them"
        return line


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


def _existing_rows(output: Path, keys: set) -> list[dict]:
    """Rows of a finished table at ``output`` whose key is planned (a rerun after completion)."""
    if not output.is_file():
        return []
    import pandas as pd

    try:
        table = pd.read_parquet(output) if output.suffix.lower() == ".parquet" else pd.read_csv(
            output, keep_default_na=False, na_values=[""])
    except Exception:  # noqa: BLE001 - an unreadable old table is simply recomputed
        return []
    if "row_key" not in table.columns:
        return []
    table = table[table["row_key"].isin(keys)]
    table = table.astype(object).where(table.notna(), None)
    rows = table.to_dict("records")
    for row in rows:
        if row.get("error") is None:
            row["error"] = ""
    return rows


def to_table(rows: list[dict]):
    """Rows → DataFrame in the column order of :data:`COLUMNS`, sorted by record, component, design."""
    import pandas as pd

    table = pd.DataFrame(rows)
    for column in COLUMNS:
        if column not in table.columns:
            table[column] = None
    extra = [c for c in table.columns if c not in COLUMNS]
    table = table[list(COLUMNS) + extra]
    table["error"] = table["error"].fillna("").astype(str)
    table = table.sort_values(["record", "component", "design_index"], kind="mergesort").reset_index(drop=True)
    return table


def write_table_atomically(table, path) -> None:
    """CSV or Parquet (by suffix) through a temporary file and a rename: never half a file."""
    path = Path(path)
    with atomic_path(path) as tmp:
        if path.suffix.lower() == ".parquet":
            out = table.copy()
            for column in out.columns:
                if out[column].dtype == object:
                    values = out[column].dropna()
                    if len(values) and all(isinstance(v, str) for v in values):
                        out[column] = out[column].astype("string")
                    elif len(values) and all(isinstance(v, bool) for v in values):
                        out[column] = out[column].astype("boolean")
                    elif len(values) and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
                        out[column] = out[column].astype(float)
                    else:
                        out[column] = out[column].astype("string")
            out.to_parquet(tmp, index=False)
        else:
            table.to_csv(tmp, index=False)


def run_batch(records, designs_file, output, *, grids=(), component: str | None = None,
              options: ReadOptions = ReadOptions(), jobs: int | None = None, scheduler: str | None = None,
              reports_dir: str | None = None, map_resolution: int = 30, progress=None,
              design_mappings: list | None = None) -> BatchResult:
    """Run a batch and write its table (see the module docstring).

    Parameters
    ----------
    records : list of str
        Record files, folders or glob patterns [-].
    designs_file : str or Path
        TOML file with ``[[design]]`` tables [-].
    output : str or Path
        ``.csv`` or ``.parquet`` table to write [-].
    grids : list of (str, list of float)
        From :func:`parse_grid` [-].
    component : str, optional
        Component to read, or ``"all-horizontal"`` [-].
    options : ReadOptions
        Units for records that do not state them; scaling to a PGA [g].
    jobs : int, optional
        Local processes (default: all cores); ignored with ``scheduler``.
    scheduler : str, optional
        Address of a dask.distributed scheduler, e.g. ``tcp://10.0.0.1:8786``.
    reports_dir : str, optional
        Also write the PDF report of every row there (slow).
    progress : callable, optional
        ``progress(total=n)`` once, then ``progress(advance=n)`` per finished task.

    Returns
    -------
    BatchResult

    Raises
    ------
    BatchError
        A mistake in the command (records, designs file, grid, output suffix, scheduler).
    """
    clock = time.perf_counter()
    output = Path(output)
    if output.suffix.lower() not in (".csv", ".parquet"):
        raise BatchError(f"-o {output}: the table must end with .csv or .parquet")
    _, pairs, cases = plan(records, designs_file, grids, component, options, design_mappings)
    planned = {row_key(path, comp, case.design_hash, options) for path, comp in pairs for case in cases}
    store = PartStore(output)
    done_rows = {}
    for row in _existing_rows(output, planned) + store.rows():
        if row.get("row_key") in planned:
            done_rows[row["row_key"]] = row
    workers = 1 if scheduler is None and (jobs or default_jobs()) <= 1 else (jobs or default_jobs())
    tasks, n_todo = make_tasks(pairs, cases, options, set(done_rows), workers, reports_dir, map_resolution)
    if progress is not None:
        progress(total=len(planned), completed=len(done_rows))
    lost, lost_messages = 0, []
    planning_seconds = time.perf_counter() - clock
    if tasks:
        iterator = _iterate_dask(tasks, scheduler) if scheduler else _iterate_local(tasks, workers)
        for task, result in iterator:
            if isinstance(result, BaseException):
                lost += 1
                lost_messages.append(f"{task.record}: {type(result).__name__}: {_one_line(result)}")
                continue
            store.write(result)
            for row in result:
                done_rows[row["row_key"]] = row
            if progress is not None:
                progress(advance=len(result))
    compute_seconds = time.perf_counter() - clock - planning_seconds
    write_start = time.perf_counter()
    table = to_table(list(done_rows.values()))
    write_table_atomically(table, output)
    if not lost:
        store.remove()
    write_seconds = time.perf_counter() - write_start
    n_failed = int((table["error"] != "").sum())
    return BatchResult(output=str(output), n_rows=len(table), n_failed=n_failed,
                       n_resumed=len(planned) - n_todo, n_lost_tasks=lost, lost_messages=lost_messages,
                       seconds={"plan": planning_seconds, "compute": compute_seconds, "write": write_seconds},
                       table=table)


def comparable(table):
    """The table without its timing columns (what must be equal between two runs)."""
    return table.drop(columns=[c for c in TIMING_COLUMNS if c in table.columns])


# ======================================================================================
# Suite summary and design chart
# ======================================================================================

#: Responses summarised per design across records.
SUMMARY_RESPONSES = ("peak_displacement_m", "peak_transmitted_acceleration_m_s2")
REGIMES = ("ST", "SS", "SL")


def suite_summary(table, swept_keys=()):
    """Per design, across its records (rows without error): n, mean, max and mean + σ of the
    peak displacement and the peak transmitted acceleration, and the count of each regime
    (record and harmonic).

    σ is the sample standard deviation (n − 1 in the denominator; NaN for one record).

    Parameters
    ----------
    table : pandas.DataFrame
        The batch table.
    swept_keys : sequence of str
        Design keys of the grid, kept as columns.

    Returns
    -------
    pandas.DataFrame
        One row per design, in design order.
    """
    import pandas as pd

    keys = ["design_index", "design_name", "design_file_index"] + [k for k in GRID_KEYS if k in table.columns]
    out = []
    for index, rows in table.groupby("design_index", sort=True):
        good = rows[rows["error"] == ""]
        first = rows.iloc[0]
        entry = {key: first[key] for key in keys}
        entry["n_rows"] = len(rows)
        entry["n_failed"] = len(rows) - len(good)
        for name in SUMMARY_RESPONSES:
            values = pd.to_numeric(good[name], errors="coerce").dropna()
            mean = float(values.mean()) if len(values) else math.nan
            sigma = float(values.std(ddof=1)) if len(values) > 1 else math.nan
            entry[f"{name}_mean"] = mean
            entry[f"{name}_max"] = float(values.max()) if len(values) else math.nan
            entry[f"{name}_std"] = sigma
            entry[f"{name}_mean_plus_std"] = mean + sigma
        for source in ("record", "harmonic"):
            counts = good[f"regime_{source}"].value_counts()
            for regime in REGIMES:
                entry[f"n_{regime}_{source}"] = int(counts.get(regime, 0))
        out.append(entry)
    summary = pd.DataFrame(out)
    ordered = [c for c in summary.columns if c not in swept_keys or c in keys]
    return summary[ordered]


def _regime_code(values) -> float:
    """Most frequent regime of a design across records, as 0 (ST), 1 (SS), 2 (SL); NaN if none."""
    counts = {regime: int((values == regime).sum()) for regime in REGIMES}
    if not any(counts.values()):
        return math.nan
    return float(REGIMES.index(max(REGIMES, key=lambda r: (counts[r], -REGIMES.index(r)))))


def design_chart(table, keys, path) -> int:
    """Design chart of a grid sweep over two keys: a PDF, two pages per design of the file.

    Page 1: contours of the mean peak displacement over (key 1, key 2); page 2: the
    mean peak transmitted acceleration (in g).  The regime boundaries are overlaid: solid
    black where the most frequent record regime changes (ST | SS | SL), dashed grey for
    the harmonic regime at the equivalent points.

    Returns
    -------
    int
        Number of pages written.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    from matplotlib.backends.backend_pdf import PdfPages

    from isolator.units import STANDARD_GRAVITY

    if len(keys) < 2:
        raise BatchError("the design chart needs a sweep over two keys")
    key_x, key_y = keys[0], keys[1]
    summary = suite_summary(table, keys)
    for source in ("record", "harmonic"):
        codes = []
        for index in summary["design_index"]:
            rows = table[(table["design_index"] == index) & (table["error"] == "")]
            codes.append(_regime_code(rows[f"regime_{source}"]))
        summary[f"regime_code_{source}"] = codes
    pages = 0
    quantities = (("peak_displacement_m_mean", "mean peak displacement [m]", 1.0),
                  ("peak_transmitted_acceleration_m_s2_mean", "mean peak transmitted acceleration [g]",
                   1.0 / STANDARD_GRAVITY))
    with atomic_path(path) as tmp:
        with PdfPages(tmp) as pdf:
            for file_index, group in summary.groupby("design_file_index", sort=True):
                xs = np.unique(group[key_x].astype(float))
                ys = np.unique(group[key_y].astype(float))
                if xs.size < 2 or ys.size < 2:
                    continue
                grid_of = {}
                for column in [q[0] for q in quantities] + ["regime_code_record", "regime_code_harmonic"]:
                    values = np.full((ys.size, xs.size), np.nan)
                    for _, row in group.iterrows():
                        i = int(np.searchsorted(ys, float(row[key_y])))
                        j = int(np.searchsorted(xs, float(row[key_x])))
                        values[i, j] = row[column]
                    grid_of[column] = values
                base = str(group.iloc[0]["design_name"]).split(" [")[0]
                n_records = int(group["n_rows"].max())
                for column, label, factor in quantities:
                    fig, ax = plt.subplots(figsize=(8.27, 6.5))
                    values = grid_of[column] * factor
                    if np.isfinite(values).sum() >= 4 and np.nanmax(values) > np.nanmin(values):
                        filled = ax.contourf(xs, ys, values, levels=14, cmap="viridis")
                        lines = ax.contour(xs, ys, values, levels=filled.levels[::2], colors="white", linewidths=0.6)
                        ax.clabel(lines, fmt="%.3g", fontsize=7)
                        fig.colorbar(filled, ax=ax, label=label)
                    for source, style, colour in (("record", "solid", "black"), ("harmonic", "dashed", "0.45")):
                        codes = grid_of[f"regime_code_{source}"]
                        finite = codes[np.isfinite(codes)]
                        if finite.size and finite.min() != finite.max():
                            ax.contour(xs, ys, codes, levels=[0.5, 1.5], colors=colour, linestyles=style,
                                       linewidths=1.6)
                    ax.plot([], [], color="black", label="regime boundary (record, most frequent)")
                    ax.plot([], [], color="0.45", linestyle="dashed", label="regime boundary (harmonic map)")
                    ax.legend(loc="upper right", fontsize=8, framealpha=0.8)
                    ax.set_xlabel(key_x)
                    ax.set_ylabel(key_y)
                    ax.set_title(f"{base}: {label}\nacross {n_records} record(s) per design", fontsize=10)
                    fig.tight_layout()
                    pdf.savefig(fig)
                    plt.close(fig)
                    pages += 1
        if pages == 0:
            raise BatchError("the design chart needs at least 2 values of each swept key")
    return pages
