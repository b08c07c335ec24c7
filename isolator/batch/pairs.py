"""The worker side of a batch on a pair: both horizontal components (and the vertical) of one file.

A task whose component is ``"pair"`` or ``"all"`` reads the file's components with
:func:`~isolator.motion.read_ground_motion_pair`; :func:`isolator.analysis.analyse`
then runs every design on the model the scene needs and each row states ``model`` and
``model_reason``.  The 1-D classification against the harmonic regime map does not
apply to a coupled 2-D response: those columns stay empty.
"""

from __future__ import annotations

import os
import time
from pathlib import Path

from isolator.batch.plan import ReadOptions, Task, file_version

_PAIR_CACHE: dict = {}


def read_pair(path: str, component: str, options: ReadOptions, partners: tuple = ()):
    """(MotionPair, scale factor, read seconds), cached per process.

    ``partners`` are the other files of a set of one-component files (Y, and Z:
    :func:`isolator.batch.plan.station_sets`); without them the file holds the components.
    ``--units`` is tried only when the file does not state its units (read once without
    it, again with it when that fails), as for one component; ``--scale-to-pga`` scales
    every component by the one factor that brings the larger horizontal PGA to the target.
    """
    # a file rewritten since it was cached (same name, other content) is read again
    key = (component, options) + tuple((os.path.abspath(p), file_version(p)) for p in (path, *partners))
    if key in _PAIR_CACHE:
        return _PAIR_CACHE[key]
    from isolator.errors import ComponentError, MissingUnitsError
    from isolator.motion import read_ground_motion_pair
    from isolator.units import STANDARD_GRAVITY

    start = time.perf_counter()
    align = {"trim": options.trim, "resample": options.resample, "dt_s": options.dt_s}
    if partners:
        if component == "all" and len(partners) < 2:
            raise ComponentError(f"{path}: its station has no vertical component among the records given "
                                 f"(beside {Path(partners[0]).name}); 'all' needs one", path=path)
        files = {"y": partners[0], "z": partners[1] if component == "all" else None}
    else:
        files = {"component": component}
    try:
        motions = read_ground_motion_pair(path, **files, **align)
    except MissingUnitsError:
        if options.units is None:
            raise
        motions = read_ground_motion_pair(path, **files, units=options.units, **align)
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
        "record_files": "; ".join(Path(p).name for p in (task.record, *task.partners)),
    }
    for axis, motion in parts.items():
        out[f"component_{axis}"] = motion.component
        out[f"pga_{axis}_m_s2"] = motion.pga_m_s2
    return out
