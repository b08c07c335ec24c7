"""Executors: local processes or a dask.distributed cluster, one interface (yield task, rows or error)."""

from __future__ import annotations

from isolator.batch.plan import BatchError, Task, _one_line
from isolator.batch.worker import run_task
from isolator.parallel import process_pool, warm_up


def _iterate_local(tasks: list[Task], jobs: int):
    """Yield (task, rows or exception) as tasks finish, on ``jobs`` local processes."""
    warm_up()
    if jobs <= 1:
        for task in tasks:
            yield task, run_task(task)
        return
    from concurrent.futures import as_completed

    with process_pool(jobs) as pool:
        futures = {pool.submit(run_task, task): task for task in tasks}
        for future in as_completed(futures):
            try:
                yield futures[future], future.result()
            except Exception as err:  # noqa: BLE001 - a lost worker: the task is not written, a rerun retries it
                yield futures[future], err


def _iterate_dask(tasks: list[Task], address: str):
    """Yield (task, rows or exception) as tasks finish on the dask.distributed cluster at ``address``."""
    from distributed import Client, as_completed

    try:
        client = Client(address, timeout=10)
    except (OSError, TimeoutError) as err:
        raise BatchError(f"scheduler {address}: cannot connect ({_one_line(err)})", parameter="scheduler") from None
    try:
        futures = {}
        for task in tasks:
            future = client.submit(run_task, task, pure=False)
            futures[future.key] = (future, task)
        for future in as_completed([f for f, _ in futures.values()]):
            task = futures[future.key][1]
            try:
                yield task, future.result()
            except Exception as err:  # noqa: BLE001 - a lost worker: a rerun retries the task
                yield task, err
    finally:
        client.close()
