"""The worker side of a batch: read a record once, run its designs; the function both executors run."""

from __future__ import annotations

import os
import re
import time
from pathlib import Path

from isolator.batch.plan import GRID_KEYS, DesignCase, ReadOptions, Task, _one_line

_MOTION_CACHE: dict = {}


def _read_motion(path: str, component: str | None, options: ReadOptions):
    """(GroundMotion, IntensityMeasures, strong-motion window, scale factor, read seconds), cached per process.

    ``--units`` is used for the files that do not state their units (text, MiniSEED …)
    and ``--dt`` for one-column text files that give no time step: a file that states
    them is read as it says, so that one batch can mix formats.
    """
    key = (os.path.abspath(path), component, options)
    if key in _MOTION_CACHE:
        return _MOTION_CACHE[key]
    from isolator.errors import MissingTimeStepError, MissingUnitsError
    from isolator.metrics import strong_motion_window_s
    from isolator.motion import read_ground_motion
    from isolator.units import STANDARD_GRAVITY

    start = time.perf_counter()
    given: dict = {}
    # the batch's units and time step only go to the files that need them: retried by error type
    fallbacks = {MissingUnitsError: ("units", options.units), MissingTimeStepError: ("dt_s", options.dt_s)}
    for _ in range(len(fallbacks) + 1):
        try:
            motion = read_ground_motion(path, component=component, **given)
            break
        except (MissingUnitsError, MissingTimeStepError) as err:
            name, value = fallbacks[type(err)]
            if value is None or name in given:
                raise
            given[name] = value
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


def _report_path(task: Task, case: DesignCase, motion) -> Path:
    safe = re.sub(r"[^A-Za-z0-9_.-]+", "_", f"{case.index:05d}_{Path(task.record).stem}_{motion.component}")
    return Path(task.reports_dir) / f"{safe.strip('_')}.pdf"


def _analysis_columns(task: Task, case: DesignCase, design, motion, measures, window, factor) -> dict:
    """The row's slice of the analysis (:meth:`isolator.analysis.Analysis.row`); writes the report if asked."""
    from isolator.analysis import analyse

    note = f"Record scaled to PGA {task.options.scale_to_pga_g:g} g (factor {factor:.4g})." \
        if task.options.scale_to_pga_g is not None else ""
    # the record's intensity measures and window are computed once per record, not per design
    analysis = analyse(design, motion, intensity=measures, window_s=window,
                       harmonic=task.options.harmonic or bool(task.reports_dir), record_label=task.record,
                       scaling_note=note, map_resolution=task.map_resolution if task.reports_dir else None,
                       workers=1)
    if task.reports_dir:
        from isolator.report.pdf import write_report

        target = _report_path(task, case, motion)
        target.parent.mkdir(parents=True, exist_ok=True)
        write_report(analysis, target, command="isolator batch")
    if not task.options.harmonic and analysis.harmonic is not None:
        analysis.harmonic = analysis.harmonic_class = None  # the table leaves the harmonic columns empty
        analysis.disagreements = []
    return analysis.row()


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
            row.update(_analysis_columns(task, case, design, motion, measures, window, factor))
            row["row_seconds"] = time.perf_counter() - start
            row["error"] = ""
        except Exception as err:  # noqa: BLE001 - one design's failure is its row's error
            row.update(_design_columns(case))
            row["error"] = f"{case.source}: {type(err).__name__}: {_one_line(err)}"
        rows.append(row)
    return rows
