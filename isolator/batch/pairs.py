"""The worker side of a batch on a pair: both horizontal components (and the vertical) of one file.

A task whose component is ``"pair"`` or ``"all"`` reads the file's components with
:func:`~isolator.motion.read_ground_motion_pair` and runs every design through
:func:`~isolator.solver.planar.simulate_motion` (the model the scene needs); each row
states ``model`` and ``model_reason``.  The 1-D classification against the harmonic
regime map does not apply to a coupled 2-D response: those columns stay empty.
"""

from __future__ import annotations

import time

from isolator.batch.plan import DesignCase, ReadOptions, Task

_PAIR_CACHE: dict = {}


def read_pair(path: str, component: str, options: ReadOptions):
    """(MotionPair, scale factor, read seconds), cached per process.

    ``--units`` is tried only when the file does not state its units (read once without
    it, again with it when that fails), as for one component; ``--scale-to-pga`` scales
    every component by the one factor that brings the larger horizontal PGA to the target.
    """
    key = (path, component, options)
    if key in _PAIR_CACHE:
        return _PAIR_CACHE[key]
    from isolator.motion import RecordError, read_ground_motion_pair
    from isolator.units import STANDARD_GRAVITY

    start = time.perf_counter()
    try:
        motions = read_ground_motion_pair(path, component=component, dt_s=options.dt_s)
    except RecordError:
        if options.units is None:
            raise
        motions = read_ground_motion_pair(path, component=component, units=options.units, dt_s=options.dt_s)
    factor = 1.0
    if options.scale_to_pga_g is not None:
        largest = max(motions.x.pga_m_s2, motions.y.pga_m_s2)
        if not largest > 0:
            raise ValueError("cannot scale a record of zeros to a PGA")
        factor = options.scale_to_pga_g * STANDARD_GRAVITY / largest
        motions = motions.scaled(factor)
    result = (motions, factor, time.perf_counter() - start)
    if len(_PAIR_CACHE) >= 4:
        _PAIR_CACHE.pop(next(iter(_PAIR_CACHE)))
    _PAIR_CACHE[key] = result
    return result


def record_columns(task: Task, motions, factor: float, read_seconds: float) -> dict:
    """The record columns of a pair row: provenance of X, each component's label and PGA."""
    prov = motions.x.provenance
    parts = motions.components
    out = {
        "record": task.record, "component": task.component,
        "record_format": prov.get("format", ""), "record_station": prov.get("station", ""),
        "record_station_name": prov.get("station_name", ""), "record_network": prov.get("network", ""),
        "record_event": prov.get("event", ""), "record_date": prov.get("date", ""),
        "record_starttime": prov.get("starttime", ""), "record_units_source": motions.x.units_source,
        "record_npts": motions.npts, "record_dt_s": motions.dt_s, "record_duration_s": motions.duration_s,
        "record_scale_factor": factor, "read_seconds": read_seconds,
        "record_processing": "; ".join(step["step"] for step in motions.processing),
    }
    for axis, motion in parts.items():
        out[f"component_{axis}"] = motion.component
        out[f"pga_{axis}_m_s2"] = motion.pga_m_s2
    return out


#: Columns of a batch row taken from :meth:`PairAnalysis.to_dict` ``["results"]`` (energies renamed).
_RESULT_COLUMNS = ("configuration", "peak_displacement_m", "residual_displacement_m", "residual_displacement_x_m",
                   "residual_displacement_y_m", "peak_velocity_m_s", "peak_transmitted_acceleration_m_s2",
                   "slip_time_s", "uplift_time_s", "n_uplifts", "n_events", "effective_period_s",
                   "effective_damping_ratio", "peak_transmitted_force_N", "base_shear_coefficient",
                   "displacement_capacity_m", "displacement_demand_ratio", "solver_seconds")


def analyse_motion_row(design, motions) -> dict:
    """The numbers of one (motion, design) on the model the scene needs (:func:`analyse_pair`), as a row.

    Parameters
    ----------
    design : Design
        The isolator (µ(v) selects the 2-D engine even for one component).
    motions : MotionPair or GroundMotion
        A pair (and a vertical), or one component.
    """
    from isolator.pair_analysis import analyse_pair

    numbers = analyse_pair(design, motions).to_dict()
    results = numbers["results"]
    row = {"model": numbers["model"], "model_reason": numbers["model_reason"], "solver_status": results["status"]}
    row.update({key: results[key] for key in _RESULT_COLUMNS})
    for name in ("input", "friction", "viscous", "balance_error"):
        row[f"energy_{name}_J_per_kg"] = results[f"energy_{name}"]
    return row


def write_pair_report(task: Task, case: DesignCase, design, motions, factor: float) -> None:
    """The PDF of one (pair, design) row in ``--reports`` (see :mod:`isolator.report.pair`)."""
    import re
    from pathlib import Path

    from isolator.pair_analysis import analyse_pair
    from isolator.report.pair import write_pair_report as write

    note = f"Record scaled by {factor:.4g} (larger horizontal PGA to {task.options.scale_to_pga_g:g} g)." \
        if task.options.scale_to_pga_g is not None else ""
    safe = re.sub(r"[^A-Za-z0-9_.-]+", "_", f"{case.index:05d}_{Path(task.record).stem}_{task.component}")
    target = Path(task.reports_dir) / f"{safe.strip('_')}.pdf"
    target.parent.mkdir(parents=True, exist_ok=True)
    write(analyse_pair(design, motions, record_label=task.record, scaling_note=note), target,
          command="isolator batch")
