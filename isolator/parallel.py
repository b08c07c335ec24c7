"""Process pools and one way to run tasks: the worker count by default, the warm-up before forking, one pool,
and :func:`iterate` (local processes or a dask.distributed cluster).

Used by the regime maps (:mod:`isolator.maps`), the batch runner (:mod:`isolator.batch`) and the
review (:mod:`isolator.review`): they fork local processes that inherit the compiled solver
functions loaded once by :func:`warm_up` in the parent, or ship their tasks to a dask cluster.
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
    from isolator.solver import models, record
    from isolator.solver.harmonic import harmonic_response

    wave = np.sin(np.arange(400) * 0.05)
    intensity_measures(wave, 0.01)
    models.warm_up(record.MODEL_NAME)  # the registry's warm-up of the 1-D engine, the one a batch runs
    harmonic_response(2.0, 0.1, 0.1, 0.05, samples_per_period=2)
    _WARM = True


def die_with_parent(parent_pid: int) -> None:
    """This process ends when the process ``parent_pid`` (the one that started it) ends.

    The initializer of :func:`process_pool`'s workers, and the first line of the tests' warm-up processes
    (tests/conftest.py).

    On Linux the kernel sends SIGTERM on the parent's death (``prctl(PR_SET_PDEATHSIG)``),
    whatever killed it (kill -9 included); elsewhere, and against the race where the
    parent died before this line, a daemon thread checks the parent once a second.
    """
    import signal
    import threading
    import time

    try:
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, signal.SIGTERM, 0, 0, 0)  # 1 = PR_SET_PDEATHSIG
    except (OSError, AttributeError):  # pragma: no cover - not Linux
        pass

    def watch() -> None:
        while True:
            if os.getppid() != parent_pid:
                os._exit(1)  # orphaned: nobody will collect our results
            time.sleep(1.0)

    if os.getppid() != parent_pid:
        os._exit(1)
    threading.Thread(target=watch, name="isolator-parent-watch", daemon=True).start()


@contextmanager
def process_pool(workers: int, *, warm: bool = True):
    """A :class:`~concurrent.futures.ProcessPoolExecutor` of ``workers`` forked processes, warmed up.

    Forking (where the platform has it) lets workers inherit the compiled solver; on
    exit the pool is shut down and the futures not started are cancelled.  ``warm=False``: the
    caller has loaded what its tasks run (the review: its own engine), :func:`warm_up` is skipped.
    """
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    if warm:
        warm_up()
    try:
        context = multiprocessing.get_context("fork")
    except ValueError:  # pragma: no cover - no fork on this platform
        context = None
    # workers die with their parent: a killed batch leaves no process computing for nobody
    pool = ProcessPoolExecutor(max_workers=workers, mp_context=context, initializer=die_with_parent,
                               initargs=(os.getpid(),))
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


# ---------------------------------------------------------------------------------------
# one way to run tasks: local processes or a dask.distributed cluster (batch and review)
# ---------------------------------------------------------------------------------------
#: Schemes of a scheduler address: plain TCP, or TLS with the certificates of dask's configuration.
SCHEDULER_SCHEMES = ("tcp", "tls")


def iterate(tasks: list, function, *, jobs: int = 1, scheduler: str | None = None, warm: bool = True):
    """Yield ``(task, function(task))`` as tasks finish — or ``(task, exception)`` for a lost worker.

    One interface for the batch and the review: ``jobs`` local processes (forked after
    :func:`warm_up`; 1 runs here, in order), or the dask.distributed cluster at ``scheduler``
    (then ``jobs`` is unused).  ``function`` and the tasks must be picklable.

    Parameters
    ----------
    tasks : list
        The work [-].
    function : callable
        ``function(task) -> result`` [-].
    jobs : int
        Local processes [-].
    scheduler : str, optional
        ``tcp://HOST:PORT`` or ``tls://HOST:PORT`` of a dask scheduler [-].
    warm : bool
        Load the solver functions (:func:`warm_up`) before forking; False when the caller loaded what
        ``function`` runs.

    Raises
    ------
    isolator.errors.BatchError
        A scheduler address that is not valid, or that cannot be reached (``parameter`` = "scheduler").
    """
    if scheduler:
        yield from _iterate_dask(tasks, scheduler, function)
    else:
        yield from _iterate_local(tasks, max(1, int(jobs)), function, warm)


def _iterate_local(tasks: list, jobs: int, function, warm: bool = True):
    if jobs <= 1:  # in this process: each engine loads on its first use (the pool warms up before it forks)
        for task in tasks:
            yield task, function(task)
        return
    from concurrent.futures import as_completed

    with process_pool(min(jobs, max(1, len(tasks))), warm=warm) as pool:
        futures = {pool.submit(function, task): task for task in tasks}
        for future in as_completed(futures):
            try:
                yield futures[future], future.result()
            except Exception as err:  # noqa: BLE001 - a lost worker: the caller reports the task, a rerun retries it
                yield futures[future], err


def check_scheduler(address: str) -> list[str]:
    """Validate a scheduler address; return sentences for the user (an unencrypted remote link).

    The trust model (``docs/security.md``): dask ships tasks and results as pickles, so
    the scheduler and its workers can run code on this client and see every record.  Use
    only a cluster you control; across a network, use ``tls://`` with the certificates of
    dask's configuration (``distributed.comm.tls.*``).

    Raises
    ------
    isolator.errors.BatchError
        Not ``tcp://HOST:PORT`` or ``tls://HOST:PORT``.
    """
    import ipaddress
    from urllib.parse import urlsplit

    from isolator.errors import BatchError

    usage = f"scheduler address {address!r}: expected tcp://HOST:PORT or tls://HOST:PORT (e.g. tls://10.0.0.5:8786)"
    try:
        parts = urlsplit(address)
        port = parts.port
    except ValueError:
        raise BatchError(usage, parameter="scheduler") from None
    if parts.scheme not in SCHEDULER_SCHEMES or not parts.hostname or port is None or parts.path not in ("", "/"):
        raise BatchError(usage, parameter="scheduler")
    if parts.scheme == "tcp":
        host = parts.hostname
        try:
            loopback = ipaddress.ip_address(host).is_loopback
        except ValueError:
            loopback = host == "localhost"
        if not loopback:
            return [f"scheduler {address} is plain TCP to another machine: tasks and results travel unencrypted "
                    "and unauthenticated, and dask's pickles let that scheduler run code here; use tls:// "
                    "(docs/security.md)"]
    return []


def _security(address: str):
    """dask's TLS settings from its configuration for a ``tls://`` address (None for tcp)."""
    if not address.startswith("tls://"):
        return None
    from distributed.security import Security

    from isolator.errors import BatchError

    security = Security()  # reads distributed.comm.tls.* (ca-file, client cert and key) from the dask config
    if not security.tls_ca_file:
        raise BatchError(f"scheduler {address}: tls:// needs certificates in the dask configuration "
                         "(distributed.comm.tls.ca-file, .client.cert, .client.key; see docs/security.md)",
                         parameter="scheduler")
    return security


def _iterate_dask(tasks: list, address: str, function):
    from distributed import Client, as_completed

    from isolator.errors import BatchError

    check_scheduler(address)
    security = _security(address)
    try:
        client = Client(address, timeout=10, security=security)
    except (OSError, TimeoutError, ValueError) as err:
        raise BatchError(f"scheduler {address}: cannot connect ({' '.join(str(err).split())})",
                         parameter="scheduler") from None
    try:
        futures = {}
        for task in tasks:
            future = client.submit(function, task, pure=False)
            futures[future.key] = (future, task)
        for future in as_completed([f for f, _ in futures.values()]):
            task = futures[future.key][1]
            try:
                yield task, future.result()
            except Exception as err:  # noqa: BLE001 - a lost worker: a rerun retries the task
                yield task, err
    finally:
        client.close()
