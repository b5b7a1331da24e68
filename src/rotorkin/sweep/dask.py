"""The sweep's chunks on dask.distributed: a LocalCluster or an existing scheduler.

Each chunk is one task running :func:`rotorkin.sweep.engine.compute_chunk` on a
worker (one kernel thread per task: the workers give the parallelism); the
results come back to the client, which commits them (to the chunk store when
there is one) as they finish. The numbers are those of the local run, bit for
bit: the same function on the same chunks.

Workers must be able to import rotorkin (same version). dask.distributed is an
optional dependency (``pip install rotorkin[dask]``).
"""

from __future__ import annotations

import contextlib
import logging

from rotorkin.core.errors import ConfigError, ParameterError
from rotorkin.core.memory import tune_allocator
from rotorkin.sweep.engine import compute_chunk

__all__ = ["LOOPBACK", "local_client", "connect", "run_chunks"]

#: Most worker processes of a local cluster (a cluster beyond a machine: --scheduler).
MAX_WORKERS = 64

#: The only address a local cluster listens on: its dashboard has no authentication.
LOOPBACK = "127.0.0.1"


def _distributed():
    try:
        import distributed
    except ImportError:  # pragma: no cover - installed with the [dask] extra
        raise ConfigError(
            "--workers/--scheduler need dask.distributed: pip install 'rotorkin[dask]'"
        ) from None
    return distributed


@contextlib.contextmanager
def local_client(workers: int, processes: bool = True):
    """A :class:`distributed.Client` on a new LocalCluster of ``workers`` single-thread workers."""
    if not 1 <= int(workers) <= MAX_WORKERS:
        raise ParameterError("workers", workers, f"1 <= workers <= {MAX_WORKERS} (processes here)")
    distributed = _distributed()
    cluster = distributed.LocalCluster(
        n_workers=int(workers),
        threads_per_worker=1,
        processes=processes,
        host=LOOPBACK if processes else None,  # scheduler and workers: this machine only
        dashboard_address=f"{LOOPBACK}:0",  # a free port, on loopback only (no authentication)
        silence_logs=logging.ERROR,
    )
    try:
        with distributed.Client(cluster) as client:
            client.run(tune_allocator)  # the workers are this run's own processes
            yield client
    finally:
        cluster.close()


@contextlib.contextmanager
def connect(address: str, timeout: float = 10.0):
    """A :class:`distributed.Client` connected to the scheduler at ``address`` (tcp://HOST:PORT)."""
    distributed = _distributed()
    try:
        client = distributed.Client(address, timeout=timeout)
    except (OSError, TimeoutError, ValueError) as exc:
        raise ConfigError(f"--scheduler = {address!r} cannot be reached: {exc}") from None
    try:
        yield client
    finally:
        client.close()


def run_chunks(client, spec, todo, on_result) -> None:
    """Compute the chunks ``todo`` (list of ``(index, start, stop)``) on ``client``.

    ``on_result(index, result)`` is called in the client as each chunk finishes
    (in completion order); results are released once handed over.
    """

    distributed = _distributed()
    if not todo:
        return
    [spec_future] = client.scatter([spec], broadcast=True)
    futures = {}
    for index, start, stop in todo:
        fut = client.submit(compute_chunk, spec_future, start, stop, 1, pure=False,
                            key=f"rotorkin-chunk-{index}-{id(spec)}")  # fmt: skip
        futures[fut] = index
    for fut in distributed.as_completed(list(futures)):
        result = fut.result()
        on_result(futures.pop(fut), result)
        fut.release()
