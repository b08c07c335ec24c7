"""The worker side of a batch: read a record once, run its designs; the function both executors run."""

from __future__ import annotations

import os
import re
import time
from pathlib import Path

from isolator.batch.pairs import read_pair
from isolator.batch.pairs import record_columns as pair_record_columns
from isolator.batch.plan import GRID_KEYS, SET_COMPONENTS, DesignCase, ReadOptions, Task, file_version
from isolator.batch.store import ROW_SCHEMA, model_columns
from isolator.serialize import json_safe

_MOTION_CACHE: dict = {}


def _read_motion(path: str, component: str | None, options: ReadOptions):
    """(GroundMotion, IntensityMeasures, strong-motion window, scale factor, read seconds), cached per process.

    ``--units`` is used for the files that do not state their units (text, MiniSEED …)
    and ``--dt`` for one-column text files that give no time step: a file that states
    them is read as it says, so that one batch can mix formats.
    """
    key = (os.path.abspath(path), file_version(path), component, options)
    if key in _MOTION_CACHE:
        return _MOTION_CACHE[key]
    from isolator.metrics import strong_motion_window_s
    from isolator.motion import RecordOptions, read_motion
    from isolator.units import STANDARD_GRAVITY

    start = time.perf_counter()
    # the batch's units and time step only go to the files that need them (read_motion, defaults=True)
    motion = read_motion(path, RecordOptions(component=component, units=options.units, dt_s=options.dt_s,
                                             defaults=True))
    factor = 1.0
    if options.scale_to_pga_g is not None:
        original = motion.pga_m_s2
        motion = motion.scaled_to_pga(options.scale_to_pga_g * STANDARD_GRAVITY)
        factor = motion.pga_m_s2 / original
    measures = motion.intensity_measures()
    window = strong_motion_window_s(motion.acceleration_m_s2, motion.dt_s, time_s=motion.sample_times_s)
    result = (motion, measures, window, factor, time.perf_counter() - start)
    if len(_MOTION_CACHE) >= 4:
        _MOTION_CACHE.pop(next(iter(_MOTION_CACHE)))
    _MOTION_CACHE[key] = result
    return result


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


def motion_digest(arrays, dt_s: float) -> str:
    """SHA-256 of the ground motion as analysed: its samples [m/s²] (float64) and time step [s].

    Two files that hold the same motion (the same samples under another header, e.g. two
    editions of one record) get the same digest, so that a suite summary counts it once.
    """
    import hashlib

    import numpy as np

    digest = hashlib.sha256(repr(float(dt_s)).encode())
    for array in arrays:
        digest.update(np.ascontiguousarray(array, dtype=np.float64).tobytes())
    return digest.hexdigest()


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
        "motion_sha256": motion_digest([motion.acceleration_m_s2], motion.dt_s),
    })
    out.update(measures.as_dict())
    return out


def _report_path(task: Task, case: DesignCase, motion) -> Path:
    label = task.component if task.component in SET_COMPONENTS else motion.component
    safe = re.sub(r"[^A-Za-z0-9_.-]+", "_", f"{case.index:05d}_{Path(task.record).stem}_{label}")
    return Path(task.reports_dir) / f"{safe.strip('_')}.pdf"


def _analysis_columns(task: Task, case: DesignCase, design, motion, measures, window, factor) -> dict:
    """The row's slice of the analysis (:meth:`isolator.analysis.Analysis.row`); writes the report if asked.

    ``motion`` is a GroundMotion, or a MotionPair for a task on ``"pair"``/``"all"``;
    :func:`~isolator.analysis.analyse` runs the model the scene needs (the registry chooses;
    a planar response leaves the harmonic columns empty, ``harmonic_status`` "not applicable").
    """
    import dataclasses

    from isolator.analysis import analyse

    note = motion.scaling_note  # from the motion's processing (a component's or a pair's scaling step)
    # the record's intensity measures and window are computed once per record, not per design
    analysis = analyse(design, motion, intensity=measures, window_s=window,
                       harmonic=task.options.harmonic or bool(task.reports_dir), record_label=task.record,
                       scaling_note=note, map_resolution=task.map_resolution if task.reports_dir else None,
                       workers=1)
    if task.reports_dir:
        from isolator.report.analysis_report import write_analysis_report
        from isolator.review.record_checks import with_record_checks

        target = _report_path(task, case, motion)
        target.parent.mkdir(parents=True, exist_ok=True)
        write_analysis_report(with_record_checks(analysis), target, command="isolator batch")
    if not task.options.harmonic and analysis.harmonic is not None:  # the table leaves the harmonic columns empty
        analysis = dataclasses.replace(analysis, harmonic=None, harmonic_class=None, disagreements=())
    # the building's and the multi-surface bearing's own numbers (absent for other models)
    return {**analysis.row(), **model_columns(json_safe(analysis.flat()))}


def row_error(err: Exception, record: str, design_source: str | None, partners: tuple = ()) -> str:
    """The ``error`` column of a failed row: one line that blames the right thing.

    Our typed errors already say what is wrong: a record's (:class:`RecordError`,
    :class:`RecordInputError` — e.g. a record of zeros), a design's
    (:class:`DesignError`, :class:`InvalidSystemError` from its K/M, γ/M).  A write error
    names its path.  Anything else is a defect of isolator: the row says so without the
    raw exception text.  ``partners``: the other files of a set (Y, Z) read with ``record``;
    a row names them all (``X + Y``), or the one file at fault when its reader named it.
    """
    from isolator.design import DesignError
    from isolator.errors import analysis_owner, one_line
    from isolator.errors import owned as named
    from isolator.motion import RecordError
    from isolator.solver.record import RecordInputError
    from isolator.solver.system import InvalidSystemError
    from isolator.units import UnitsError

    files = (record, *partners)
    if isinstance(err, (RecordError, RecordInputError, UnitsError)):
        text = one_line(err)
        if any(text.startswith(f"{path}: ") for path in files):  # the reader named the file at fault
            return text
        return named(analysis_owner(files), text)
    if isinstance(err, DesignError):
        return named(design_source or analysis_owner(files), str(err))
    from isolator.errors import SolverError

    if isinstance(err, (InvalidSystemError, SolverError)):  # the engine refuses this design on this record
        return named(analysis_owner(files, design_source), err, design_source)
    if isinstance(err, OSError):
        return f"{err.filename or analysis_owner(files)}: cannot read or write ({err.strerror or type(err).__name__})"
    if isinstance(err, ValueError) and design_source is None:  # scaling a record (a sentence of ours)
        return named(analysis_owner(files), str(err))
    return (f"{analysis_owner(files, design_source)}: internal error in isolator (please report it with this "
            "record and design)")


def run_task(task: Task) -> list[dict]:
    """Rows of one task (the function both executors run).  Never raises for a bad record or design."""
    from isolator.design import Design

    base = {"record": task.record, "component": task.component or "", "row_schema": ROW_SCHEMA}
    try:
        if task.component in SET_COMPONENTS:  # the file's components together (isolator.batch.pairs)
            motion, factor, read_seconds = read_pair(task.record, task.component, task.options, task.partners)
            measures = window = None
        else:
            motion, measures, window, factor, read_seconds = _read_motion(task.record, task.component, task.options)
    except Exception as err:  # noqa: BLE001 - any failure to read is the rows' error, the batch goes on
        message = row_error(err, task.record, None, task.partners)
        return [{**base, **_design_columns(case), "error": message, "row_key": key} for case, key in task.designs]
    if task.component in SET_COMPONENTS:
        record_cols = pair_record_columns(task, motion, factor, read_seconds)
        record_cols["motion_sha256"] = motion_digest([m.acceleration_m_s2 for m in motion.components.values()],
                                                     motion.dt_s)
    else:
        record_cols = _record_columns(task.record, task.component, motion, measures, factor, read_seconds)
    rows = []
    for case, key in task.designs:
        row = {**record_cols, "row_key": key, "row_schema": ROW_SCHEMA}
        if case.error:
            rows.append({**row, **_design_columns(case), "error": case.error})
            continue
        try:
            start = time.perf_counter()
            design = Design.from_mapping(case.mapping, source=case.source)
            row.update(_design_columns(case, design))
            row.update(_analysis_columns(task, case, design, motion, measures, window, factor))
            row["row_seconds"] = time.perf_counter() - start
            row["error"] = ""
        except Exception as err:  # noqa: BLE001 - one design's failure is its row's error
            row.update(_design_columns(case))
            row["error"] = row_error(err, task.record, case.source, task.partners)
        rows.append(row)
    return rows
