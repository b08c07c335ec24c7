"""One analysis of the review (a scaled pair × a property bound), its cache, and the executors.

A task is a plain dict (arrays and numbers, no objects) so that local processes and a Dask
cluster ship it alike.  Results are cached as JSON under a content key (the samples, the
scale factor, the friction and the engine version), so an interrupted review resumes where it
stopped and a rerun with the same inputs analyses nothing.
"""

from __future__ import annotations

import functools
import hashlib
import json
import math
from pathlib import Path

import numpy as np

#: bump when the numbers an analysis returns change meaning
CACHE_VERSION = "review-2"
ORBIT_POINTS = 1500


def design_parameters(design) -> dict:
    """The numbers of a design the 2-D engine needs (per unit mass; SI)."""
    return {"mu_static": design.mu_static, "mu_kinetic": design.mu_kinetic, "radius_m": design.radius_m,
            "stiffness_per_mass": design.stiffness_per_mass, "damping_per_mass": design.damping_per_mass,
            "gravity_m_s2": design.gravity_m_s2, "mu_slow": design.mu_slow, "mu_fast": design.mu_fast,
            "rate_s_per_m": design.rate_s_per_m}


def task_key(pair_key: str, factor: float, parameters: dict) -> str:
    """Content key of an analysis."""
    text = json.dumps([CACHE_VERSION, _engine_version(), pair_key, repr(float(factor)), parameters], sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:32]


@functools.lru_cache(maxsize=1)
def _engine_version() -> str:
    """isolator's version and a digest of the 2-D engine's source: a changed engine misses the cache."""
    from isolator import __version__

    digest = hashlib.sha256()
    for path in sorted((Path(__file__).resolve().parents[1] / "solver").glob("planar*.py")):
        digest.update(path.read_bytes())
    return f"{__version__}+{digest.hexdigest()[:16]}"


def _decimate(xy: np.ndarray, points: int = ORBIT_POINTS) -> list:
    """At most ``points`` rows of an orbit, keeping the row of the peak resultant."""
    n = xy.shape[0]
    if n <= points:
        rows = np.arange(n)
    else:
        rows = np.unique(np.concatenate([np.linspace(0, n - 1, points).astype(int),
                                         [int(np.argmax(np.hypot(xy[:, 0], xy[:, 1])))]]))
    return np.round(xy[rows], 6).tolist()


def _ground_measures(ax, ay, dt):
    """Resultant PGA [m/s²], PGV [m/s] and the D5–95 window (t5, t95) [s] of the horizontal ground motion."""
    pga = float(np.max(np.hypot(ax, ay)))
    vx = np.concatenate([[0.0], np.cumsum(0.5 * (ax[1:] + ax[:-1]) * dt)])
    vy = np.concatenate([[0.0], np.cumsum(0.5 * (ay[1:] + ay[:-1]) * dt)])
    pgv = float(np.max(np.hypot(vx, vy)))
    energy = np.concatenate([[0.0], np.cumsum(0.5 * ((ax ** 2 + ay ** 2)[1:] + (ax ** 2 + ay ** 2)[:-1]) * dt)])
    t = np.arange(ax.size) * dt
    if energy[-1] > 0:
        t5, t95 = np.interp([0.05 * energy[-1], 0.95 * energy[-1]], energy, t)
    else:
        t5 = t95 = 0.0
    return pga, pgv, (float(t5), float(t95))


def simulate(task: dict):
    """Run the model the pair needs (:func:`isolator.solver.models.simulate`) on a task."""
    from isolator.solver.models import Scene
    from isolator.solver.models import simulate as run_model

    p = task["design"]
    kwargs = {"mu_static": p["mu_static"], "damping_per_mass": p["damping_per_mass"], "gravity_m_s2": p["gravity_m_s2"]}
    if p["radius_m"] is not None:
        kwargs["radius_m"] = p["radius_m"]
    else:
        kwargs["stiffness_per_mass"] = p["stiffness_per_mass"]
    if p["rate_s_per_m"] is not None:  # µ(v) replaces the constant kinetic friction
        kwargs.update(mu_slow=p["mu_slow"], mu_fast=p["mu_fast"], rate_s_per_m=p["rate_s_per_m"])
    else:
        kwargs["mu_kinetic"] = p["mu_kinetic"]
    f = task["factor"]
    az = None if task["az"] is None else f * task["az"]
    return run_model(Scene(ax_m_s2=f * task["ax"], ay_m_s2=f * task["ay"], az_m_s2=az, dt_s=task["dt"], isolator=kwargs))


def analyse_task(task: dict) -> dict:
    """The numbers of one analysis (see :func:`simulate`), or ``{"error": …}``.

    Returns
    -------
    dict
        ``peak_displacement_m`` (resultant), ``residual_displacement_m`` (resultant),
        ``residual_displacement_x_m``/``_y_m``, ``peak_velocity_m_s``,
        ``peak_transmitted_acceleration_m_s2`` (resultant), ``base_shear_coefficient`` (= that /g),
        ``transmitted_over_pga``, ``slip_time_s``, ``uplift_time_s``, ``n_uplifts``, ``n_events``,
        ``model``, ``model_reason``, the paper's measures (``paper_A`` = D/A0 with A0 = PGV²/PGA of
        the resultant ground motion, ``paper_alpha`` = PGA/(µs g), ``paper_slip_ratio`` = share of the
        D5–95 window spent sliding, read at the samples) and ``orbit_m`` (decimated X–Y path).
    """
    import time

    start = time.perf_counter()
    try:
        r = simulate(task)
    except Exception as err:  # noqa: BLE001 - one analysis fails, the review reports it
        return {"error": f"{type(err).__name__}: {' '.join(str(err).split())}"}
    f, dt = task["factor"], task["dt"]
    pga, pgv, (t5, t95) = _ground_measures(f * task["ax"], f * task["ay"], dt)
    # the paper's ζ: the share of the D5–95 window spent sliding (read at the samples)
    window = slice(int(np.ceil(t5 / dt)), int(np.floor(t95 / dt)) + 1)
    speed = np.hypot(*np.asarray(r.velocity_m_s, dtype=np.float64)[window].T)
    slip_ratio = float(np.mean(speed > 0.0)) if speed.size else math.nan
    g = task["design"]["gravity_m_s2"]
    peak = float(r.peak_displacement_m)
    a0 = pgv * pgv / pga if pga > 0 else math.nan
    transmitted = float(r.peak_transmitted_acceleration_m_s2)
    return {
        "peak_displacement_m": peak,
        "residual_displacement_m": float(r.residual_displacement_m),
        "residual_displacement_x_m": float(r.residual_displacement_x_m),
        "residual_displacement_y_m": float(r.residual_displacement_y_m),
        "peak_velocity_m_s": float(r.peak_velocity_m_s),
        "peak_transmitted_acceleration_m_s2": transmitted,
        "base_shear_coefficient": transmitted / g,
        "pga_m_s2": pga,
        "pgv_m_s": pgv,
        "transmitted_over_pga": transmitted / pga if pga > 0 else math.nan,
        "slip_time_s": float(r.slip_time_s),
        "uplift_time_s": float(getattr(r, "uplift_time_s", 0.0)),
        "n_uplifts": int(getattr(r, "n_uplifts", 0)),
        "n_events": int(r.n_events),
        "model": str(getattr(r, "model", "")),
        "model_reason": str(getattr(r, "model_reason", "")),
        "paper_A": peak / a0 if a0 > 0 else math.nan,
        "paper_A0_m": a0,
        "paper_alpha": pga / (task["design"]["mu_static"] * g),
        "paper_slip_ratio": slip_ratio,
        "orbit_m": _decimate(np.asarray(r.displacement_m, dtype=np.float64)),
        "seconds": time.perf_counter() - start,
    }


def warm_up() -> None:
    """Load the compiled engines once in the parent before workers fork."""
    from isolator.parallel import warm_up as warm_solvers

    warm_solvers()
    t = np.linspace(0.0, 2.0, 201)
    task = {"ax": np.sin(5 * t), "ay": np.cos(5 * t), "az": None, "dt": 0.01, "factor": 1.0,
            "design": {"mu_static": 0.05, "mu_kinetic": 0.05, "radius_m": 2.0, "stiffness_per_mass": 9.80665 / 2,
                       "damping_per_mass": 0.0, "gravity_m_s2": 9.80665, "mu_slow": None, "mu_fast": None,
                       "rate_s_per_m": None}}
    simulate(task)


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
        from isolator.atomic import digest_matches

        if self.directory is None:
            return None
        path = self.directory / f"{key}.json"
        try:
            entry = json.loads(path.read_bytes().decode("utf-8"))
        except FileNotFoundError:
            return None
        except (OSError, ValueError):
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

    Local processes (fork) when ``jobs`` > 1, a Dask cluster when ``scheduler`` is given.
    """
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
    if scheduler:
        iterator = _iterate_dask(todo, scheduler)
    else:
        iterator = _iterate_local(todo, jobs)
    for key, result in iterator:
        results[key] = result
        cache.put(key, result)
    return results, n_cached


def _iterate_local(todo: dict, jobs: int):
    """(key, result) on local processes through the batch executor (longest records first)."""
    from isolator.batch.executors import _iterate_local as iterate

    warm_up()
    order = sorted(todo, key=lambda k: -todo[k]["ax"].size)  # the pool finishes together
    tasks = [dict(todo[key], key=key) for key in order]
    for task, result in iterate(tasks, max(1, min(int(jobs), len(tasks))), function=analyse_task):
        yield task["key"], _result(result)


def _iterate_dask(todo: dict, address: str):
    """(key, result) on a Dask cluster through the batch executor."""
    from isolator.batch.executors import _iterate_dask as iterate
    from isolator.batch.plan import BatchError
    from isolator.errors import ReviewError

    tasks = [dict(task, key=key) for key, task in todo.items()]
    try:
        for task, result in iterate(tasks, address, function=analyse_task):
            yield task["key"], _result(result)
    except BatchError as err:
        raise ReviewError(str(err)) from None


def _result(result) -> dict:
    """A worker's result, or the exception of a lost worker as an error entry."""
    if isinstance(result, Exception):
        return {"error": f"worker lost ({type(result).__name__}: {' '.join(str(result).split())})"}
    return result


def default_jobs() -> int:
    """Worker processes when the user gives none (:func:`isolator.parallel.default_workers`)."""
    from isolator.parallel import default_workers

    return default_workers()

