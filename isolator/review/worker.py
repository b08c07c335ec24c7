"""One analysis of the review (a scaled pair × a property bound) through :func:`isolator.analysis.analyse`, its cache.

A task is a plain dict (the pair's arrays, the scale factor, the design) so that local
processes and a Dask cluster ship it alike (:func:`isolator.parallel.iterate`).  Its result
is the batch row of the analysis (:meth:`isolator.analysis.Analysis.row`: the same keys as
``isolator batch`` and ``simulate --json``) with the pair's resultant PGA and PGV and its
decimated orbit.  Results are cached as JSON under a content key (the samples, the scale
factor, the design and the engine version), so an interrupted review resumes where it
stopped and a rerun with the same inputs analyses nothing.
"""

from __future__ import annotations

import functools
import hashlib
import json
from pathlib import Path

import numpy as np

#: bump when the numbers an analysis returns change meaning
CACHE_VERSION = "review-5"  # review-5: point_regime, mu_s (the paper point's regime and µ)
ORBIT_POINTS = 1500
#: Samples of the first task analysed by :func:`warm_up` (enough to reach the engine's compiled kernel).
WARM_UP_SAMPLES = 200
#: Design keys that do not change its analyses: its names, the property factors (a bound's friction is already
#: applied), the plan.  Not the displacement capacity: a single pendulum whose motion reaches it is run again
#: with its rim (1d-multisurface, 2d+rim; isolator.solver.models), so the capacity changes the analysis.
_NOT_ANALYSED = ("name", "source", "description", "property_factors", "plan")


def design_key(design) -> dict:
    """What of a design determines its analyses (the cache key): :meth:`Design.as_dict` without :data:`_NOT_ANALYSED`."""
    return {key: value for key, value in design.as_dict().items() if key not in _NOT_ANALYSED}


def task_key(pair_key: str, factor: float, design) -> str:
    """Content key of an analysis: the pair's samples, the scale factor, the design, the engine."""
    text = json.dumps([CACHE_VERSION, _engine_version(), pair_key, repr(float(factor)), design_key(design)],
                      sort_keys=True, default=str)
    return hashlib.sha256(text.encode()).hexdigest()[:32]


@functools.lru_cache(maxsize=1)
def _engine_version() -> str:
    """isolator's version and a digest of the solver's and the analysis' sources: a changed engine misses the cache."""
    from isolator import __version__

    digest = hashlib.sha256()
    package = Path(__file__).resolve().parents[1]
    for path in sorted((package / "solver").glob("*.py")) + [package / "analysis.py", package / "metrics.py",
                                                             package / "adapter.py", package / "bearing.py"]:
        digest.update(path.read_bytes())
    return f"{__version__}+{digest.hexdigest()[:16]}"


def _decimate(xy: np.ndarray, points: int = ORBIT_POINTS) -> list:
    """At most ``points`` rows of an orbit, keeping the row of the peak resultant (a 1-D path: y = 0)."""
    if xy.ndim == 1:
        xy = np.column_stack([xy, np.zeros_like(xy)])
    n = xy.shape[0]
    if n <= points:
        rows = np.arange(n)
    else:
        rows = np.unique(np.concatenate([np.linspace(0, n - 1, points).astype(int),
                                         [int(np.argmax(np.hypot(xy[:, 0], xy[:, 1])))]]))
    return np.round(xy[rows], 6).tolist()


def task_motion(task: dict):
    """The scaled pair of a task as a :class:`~isolator.motion.MotionPair` [m/s²]."""
    from isolator.motion import GroundMotion, MotionPair

    f, dt = task["factor"], task["dt"]
    parts = {axis: None if task[key] is None else GroundMotion.from_array(f * task[key], dt_s=dt, component=axis,
                                                                             units_source="review suite, m/s2")
             for axis, key in (("x", "ax"), ("y", "ay"), ("z", "az"))}
    return MotionPair(parts["x"], parts["y"], parts["z"])


def analyse_task(task: dict) -> dict:
    """The numbers of one analysis, or ``{"error": …}``.

    Returns
    -------
    dict
        :meth:`isolator.analysis.Analysis.row` of the design under the scaled pair (the
        model that ran and why, the paper's point α, k, η of the resultant horizontal
        motion, the response keys, ``zeta_record`` over its D5–95, ``peak_displacement_over_a0``,
        ``transmitted_over_pga``, ``base_shear_coefficient`` …), plus ``point_regime`` and ``mu_s`` (the
        backbone regime a double or triple's point stands on and its line's µ; None and µs for one surface),
        ``pga_m_s2`` and ``pgv_m_s``
        (the resultant's), ``orbit_m`` (decimated X–Y path) and ``analysis_seconds``; and the model's own
        summary keys (``EXTRA_SUMMARY_KEYS``: a building's ``story_drift_ratio``,
        ``superstructure_shear_coefficient``, ``floor_peak_acceleration_m_s2``, bearing axial loads; a
        multi-surface bearing's ``ultimate_displacement_reached``, ``impact_impulse_m_s``,
        ``surface_peak_displacement_m`` …), which the review's rows read.
    """
    import time

    from isolator.analysis import analyse
    from isolator.serialize import json_safe

    start = time.perf_counter()
    try:
        analysis = analyse(task["design"], task_motion(task), harmonic=False)
    except Exception as err:  # noqa: BLE001 - one analysis fails, the review reports it
        return {"error": f"{type(err).__name__}: {' '.join(str(err).split())}"}
    intensity = analysis.adaptation.intensity
    row = analysis.row()
    response = analysis.response
    extra = {key: value.tolist() if isinstance(value, np.ndarray) else value
             for key, value in response.summary().items() if key in response.EXTRA_SUMMARY_KEYS and key not in row}
    extra = json_safe(extra)
    point = analysis.adaptation.point  # a double or triple: the regime the paper's point stands on, and its µ
    return {**row, **extra, "point_regime": point.regime, "mu_s": point.mu_s,
            "pga_m_s2": intensity.pga_m_s2, "pgv_m_s": intensity.pgv_m_s,
            "orbit_m": _decimate(np.asarray(analysis.response.displacement_m, dtype=np.float64)),
            "analysis_seconds": time.perf_counter() - start}


def warm_up(task: dict | None = None) -> None:
    """Load the compiled engines once in the parent before workers fork: with ``task``, the engine its analyses
    run (its design and components on their first :data:`WARM_UP_SAMPLES` samples), else the rigid block's."""
    from isolator.design import Design
    from isolator.parallel import warm_up as warm_solvers

    if task is not None:
        head = {key: value[:WARM_UP_SAMPLES] if key in ("ax", "ay", "az") and value is not None else value
                for key, value in task.items()}
        analyse_task(head)  # an engine that refuses the scene says so again in the worker, where it counts
        return
    warm_solvers()
    t = np.linspace(0.0, 2.0, 201)
    design = Design.from_mapping({"name": "warm-up", "mass_kg": 1.0, "radius_m": 2.0, "mu_static": 0.05})
    analyse_task({"ax": np.sin(5 * t), "ay": np.cos(5 * t), "az": None, "dt": 0.01, "factor": 1.0, "design": design})


#: Version of a review cache entry's layout; an entry of another version is recomputed.
CACHE_SCHEMA = "isolator-review-cache/1"
#: Depth of nested values an analysis result may hold (a row of numbers, texts, lists, small tables).
_MAX_DEPTH = 4


def _plain(value, depth: int = 0) -> bool:
    """True for JSON made of numbers, texts, booleans, None, lists and string-keyed tables (bounded depth)."""
    if value is None or isinstance(value, (bool, int, float, str)):
        return True
    if depth >= _MAX_DEPTH:
        return False
    if isinstance(value, list):
        return all(_plain(item, depth + 1) for item in value)
    if isinstance(value, dict):
        return all(isinstance(k, str) and _plain(v, depth + 1) for k, v in value.items())
    return False


def _canonical(key: str, result: dict) -> bytes:
    return json.dumps({"schema": CACHE_SCHEMA, "key": key, "result": result}, sort_keys=True,
                      allow_nan=True).encode("utf-8")


class Cache:
    """One JSON file per analysis under ``directory`` (atomic writes), each with its schema and a content key.

    An entry is ``{"schema", "key", "result", "mac"}``: ``key`` the task it answers, ``mac`` the
    HMAC-SHA256 of the rest under this user's key (:func:`isolator.atomic.keyed_digest`).  An entry
    that is not JSON, not of this schema, for another task, holds values that are not plain numbers,
    texts and tables, or whose content key does not match (hand-edited: issue 26 turned a capacity
    check with an edited D into 0.001 m) is never trusted: it is recomputed and counted in
    :attr:`rejected`.
    """

    def __init__(self, directory):
        self.directory = None if directory is None else Path(directory)
        self.rejected: list[Path] = []  #: entries found damaged or edited, recomputed

    def get(self, key: str):
        from isolator.atomic import MAX_CACHE_ENTRY_BYTES, digest_matches, read_regular_file

        if self.directory is None:
            return None
        path = self.directory / f"{key}.json"
        try:  # a FIFO or a link to /dev/zero in the cache is a damaged entry, never a blocked or endless read
            entry = json.loads(read_regular_file(path, MAX_CACHE_ENTRY_BYTES).decode("utf-8"))
        except FileNotFoundError:
            return None
        except (OSError, ValueError, RecursionError):  # RecursionError: nesting past the stack (s17)
            self.rejected.append(path)
            return None
        if not (isinstance(entry, dict) and set(entry) == {"schema", "key", "result", "mac"}
                and entry["schema"] == CACHE_SCHEMA and entry["key"] == key and isinstance(entry["result"], dict)
                and "error" not in entry["result"] and _plain(entry["result"])
                and digest_matches(_canonical(key, entry["result"]), entry["mac"])):
            self.rejected.append(path)
            return None
        return entry["result"]

    def put(self, key: str, result: dict) -> None:
        if self.directory is None or "error" in result:
            return
        from isolator.atomic import keyed_digest, write_text_atomically

        entry = {"schema": CACHE_SCHEMA, "key": key, "result": result, "mac": keyed_digest(_canonical(key, result))}
        write_text_atomically(self.directory / f"{key}.json", json.dumps(entry, allow_nan=True))

    def note(self) -> str | None:
        """A sentence for the review's notes when entries were rejected, else None."""
        if not self.rejected:
            return None
        return (f"{len(self.rejected)} review cache entr{'y' if len(self.rejected) == 1 else 'ies'} in "
                f"{self.directory} damaged, edited or from another version (e.g. {self.rejected[0].name}): "
                "recomputed, not trusted")


def run_tasks(tasks: dict, *, jobs: int = 1, scheduler: str | None = None, cache: Cache | None = None):
    """Analyse ``{key: task}``; return ``({key: result}, n_cached)``.

    Local processes (fork) when ``jobs`` > 1, a Dask cluster when ``scheduler`` is given
    (:func:`isolator.parallel.iterate`; the longest records first, so that the pool finishes together).

    Raises
    ------
    ReviewError
        The scheduler cannot be reached.
    """
    from isolator.errors import BatchError, ReviewError
    from isolator.parallel import iterate

    cache = cache or Cache(None)
    results, todo = {}, {}
    for key, task in tasks.items():
        hit = cache.get(key)
        if hit is not None:
            results[key] = hit
        else:
            todo[key] = task
    n_cached = len(results)
    if not todo:
        return results, n_cached
    order = sorted(todo, key=lambda k: -todo[k]["ax"].size)
    if not scheduler and jobs > 1 and len(todo) > 1:  # forked workers inherit it; one process warms as it goes
        warm_up(todo[order[0]])
    work = [dict(todo[key], key=key) for key in order]
    try:
        for task, result in iterate(work, analyse_task, jobs=jobs, scheduler=scheduler, warm=False):
            results[task["key"]] = _result(result)
            cache.put(task["key"], results[task["key"]])
    except BatchError as err:
        raise ReviewError(str(err)) from None
    return results, n_cached


def _result(result) -> dict:
    """A worker's result, or the exception of a lost worker as an error entry."""
    if isinstance(result, Exception):
        return {"error": f"worker lost ({type(result).__name__}: {' '.join(str(result).split())})"}
    return result


def default_jobs() -> int:
    """Worker processes when the user gives none (:func:`isolator.parallel.default_workers`)."""
    from isolator.parallel import default_workers

    return default_workers()
