"""Executors: local processes or a dask.distributed cluster, one interface (yield task, rows or error)."""

from __future__ import annotations

from isolator.batch.plan import BatchError, Task
from isolator.batch.worker import run_task
from isolator.errors import one_line
from isolator.parallel import process_pool, warm_up


def _iterate_local(tasks: list[Task], jobs: int, function=run_task):
    """Yield (task, ``function(task)`` or exception) as tasks finish, on ``jobs`` local processes.

    ``function`` is the batch's :func:`run_task` unless another driver (the review) passes its own.
    """
    warm_up()
    if jobs <= 1:
        for task in tasks:
            yield task, function(task)
        return
    from concurrent.futures import as_completed

    with process_pool(jobs) as pool:
        futures = {pool.submit(function, task): task for task in tasks}
        for future in as_completed(futures):
            try:
                yield futures[future], future.result()
            except Exception as err:  # noqa: BLE001 - a lost worker: the task is not written, a rerun retries it
                yield futures[future], err


#: Schemes of a scheduler address: plain TCP, or TLS with the certificates of dask's configuration.
SCHEDULER_SCHEMES = ("tcp", "tls")


def check_scheduler(address: str) -> list[str]:
    """Validate a scheduler address; return sentences for the user (an unencrypted remote link).

    The trust model (``docs/security.md``): dask ships tasks and results as pickles, so
    the scheduler and its workers can run code on this client and see every record.  Use
    only a cluster you control; across a network, use ``tls://`` with the certificates of
    dask's configuration (``distributed.comm.tls.*``).

    Raises
    ------
    BatchError
        Not ``tcp://HOST:PORT`` or ``tls://HOST:PORT``.
    """
    import ipaddress
    from urllib.parse import urlsplit

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

    security = Security()  # reads distributed.comm.tls.* (ca-file, client cert and key) from the dask config
    if not security.tls_ca_file:
        raise BatchError(f"scheduler {address}: tls:// needs certificates in the dask configuration "
                         "(distributed.comm.tls.ca-file, .client.cert, .client.key; see docs/security.md)",
                         parameter="scheduler")
    return security


def _iterate_dask(tasks: list[Task], address: str, function=run_task):
    """Yield (task, ``function(task)`` or exception) as tasks finish on the dask.distributed cluster at ``address``."""
    from distributed import Client, as_completed

    check_scheduler(address)
    security = _security(address)
    try:
        client = Client(address, timeout=10, security=security)
    except (OSError, TimeoutError, ValueError) as err:
        raise BatchError(f"scheduler {address}: cannot connect ({one_line(err)})", parameter="scheduler") from None
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
