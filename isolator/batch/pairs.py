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
    ``--units`` and ``--dt`` go only to the files that do not state them, file by file, as
    for one component (:func:`~isolator.motion.read_motion` with ``defaults=True``);
    ``--scale-to-pga`` scales every component by the one factor that brings the larger
    horizontal PGA to the target (:meth:`~isolator.motion.MotionPair.scaled_to_pga`).
    """
    # a file rewritten since it was cached (same name, other content) is read again
    key = (component, options) + tuple((os.path.abspath(p), file_version(p)) for p in (path, *partners))
    if key in _PAIR_CACHE:
        return _PAIR_CACHE[key]
    from isolator.errors import ComponentError
    from isolator.motion import RecordOptions, read_motion
    from isolator.units import STANDARD_GRAVITY

    start = time.perf_counter()
    if partners and component == "all" and len(partners) < 2:
        raise ComponentError(f"{path}: its station has no vertical component among the records given "
                             f"(beside {Path(partners[0]).name}); 'all' needs one", path=path)
    files = {"pair": partners[0], "vertical": partners[1] if component == "all" else None} if partners \
        else {"component": component}
    # the batch's units and time step only go to the files that need them, file by file, as for one component
    motions = read_motion(path, RecordOptions(**files, units=options.units, dt_s=options.dt_s, defaults=True,
                                              trim=options.trim, resample=options.resample))
    factor = 1.0
    if options.scale_to_pga_g is not None:
        motions = motions.scaled_to_pga(options.scale_to_pga_g * STANDARD_GRAVITY)
        factor = motions.processing[-1]["factor"]
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
