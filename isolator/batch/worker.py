"""The worker side of a batch: read a record once, run its designs; the function both executors run."""

from __future__ import annotations

import os
import re
import time
from pathlib import Path

from isolator.batch.plan import GRID_KEYS, DesignCase, ReadOptions, Task, _one_line

_CLASS_FIELDS = ("regime", "zeta", "amplitude", "amplified", "dominant_force", "dominant_force_rho",
                 "rho_ev", "rho_vf", "rho_ef")


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
