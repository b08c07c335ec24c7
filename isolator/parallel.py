"""Process pools: the worker count by default, the warm-up before forking, and one pool.

Used by the regime maps (:mod:`isolator.maps`) and the batch runner
(:mod:`isolator.batch`): both fork local processes that inherit the compiled solver
functions loaded once by :func:`warm_up` in the parent.
"""

from __future__ import annotations

import os
from contextlib import contextmanager


def available_cores() -> int:
    """Cores this process may run on (its CPU affinity; ``os.cpu_count()`` elsewhere) [-]."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover - not Linux
        return max(1, os.cpu_count() or 1)


def default_workers() -> int:
    """Worker processes when the user gives none: the idle cores, at least 1 [-].

    On a busy shared machine (load average at or above the core count) extra processes
    only add start-up time and contention, so the cores already loaded are not counted.
    """
    cores = available_cores()
    try:
        idle = cores - int(os.getloadavg()[0])
    except OSError:  # pragma: no cover - no load average on this platform
        idle = cores
    return max(1, min(cores, idle))


def capped_workers(requested: int | None) -> tuple[int, str]:
    """Processes to use, and a sentence when the request was capped at the available cores.

    More processes than cores only add start-up time and contention (``--workers 16``
    on 2 cores runs 2).  None gives :func:`default_workers` without a note.
    """
    if requested is None:
        return default_workers(), ""
    cores = available_cores()
    if requested > cores:
        return cores, f"{requested} workers asked, {cores} used (this machine gives this process {cores} cores)"
    return max(1, int(requested)), ""


_WARM = False


def warm_up() -> None:
    """Import the readers and load the compiled solver functions (numba's disk cache) once.

    Called in the parent before a pool forks, so that workers inherit them instead of
    each loading them again (≈ 2 s of CPU per process).  Later calls return at once.
    """
    global _WARM
    if _WARM:
        return
    import numpy as np

    from isolator.motion import intensity_measures
    from isolator.solver.harmonic import harmonic_response
    from isolator.solver.record import simulate_record

    wave = np.sin(np.arange(400) * 0.05)
    intensity_measures(wave, 0.01)
    simulate_record(wave, 0.01, mu_static=0.05, stiffness_per_mass=1.0, damping_per_mass=0.1)
    harmonic_response(2.0, 0.1, 0.1, 0.05, samples_per_period=2)
    _WARM = True


@contextmanager
def process_pool(workers: int):
    """A :class:`~concurrent.futures.ProcessPoolExecutor` of ``workers`` forked processes, warmed up.

    Forking (where the platform has it) lets workers inherit the compiled solver; on
    exit the pool is shut down and the futures not started are cancelled.
    """
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    warm_up()
    try:
        context = multiprocessing.get_context("fork")
    except ValueError:  # pragma: no cover - no fork on this platform
        context = None
    pool = ProcessPoolExecutor(max_workers=workers, mp_context=context)
    try:
        yield pool
    finally:
        pool.shutdown(wait=True, cancel_futures=True)


def map_interleaved(function, items: list, workers: int, chunks_per_worker: int = 8) -> list:
    """``[function(chunk) for chunk]`` over interleaved chunks of ``items`` on a pool, flattened in order.

    ``function`` takes a list of items and returns one result per item.  Interleaving
    (items i, i + n, i + 2n, … in chunk i) balances chunks whose items cost unevenly.

    Parameters
    ----------
    function : callable
        Picklable; ``function(list of items) -> list of results`` [-].
    items : list
        The work [-].
    workers : int
        Processes; 1 runs in this process [-].
    chunks_per_worker : int
        Chunks per process [-].
    """
    if workers <= 1:
        return list(function(items))
    n_chunks = workers * chunks_per_worker
    chunks = [items[i::n_chunks] for i in range(n_chunks)]
    with process_pool(workers) as pool:
        results = list(pool.map(function, chunks))
    out: list = [None] * len(items)
    for c, result in enumerate(results):
        out[c::n_chunks] = result
    return out
