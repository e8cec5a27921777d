"""Chunking and executors, for every system: cases cut into fixed-size chunks, run in process
or on dask.

Chunks depend on the number of cases and the chunk size only, never on the worker count, and
every case is integrated independently (a system draws any random input from the case's own
seed), so results are identical whatever the executor layout.

* ``run_local(fn, n, chunk)``: fn(slice) for each chunk in order, in this process (the kernel
  parallelises over the cases of a chunk with numba threads), with an optional progress bar;
* ``map_threads(fn, n, chunk, consume, threads)``: fn(slice) for each chunk on ``threads``
  threads at once (fn runs a nogil kernel on one thread), ``consume`` called on the results in
  chunk order in the calling thread, a bounded number of results waiting;
* ``map_dask(task, args)``: task(*a) for each a on a dask.distributed cluster, either a running
  one (``scheduler`` address) or a LocalCluster of ``workers`` single-threaded workers; results
  in order.  Scheduler-connection checks belong to the caller (the CLI).
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Iterator, Sequence
from typing import Any

import numpy as np
from lgw.theory.errors import ParameterError


def check_chunk(chunk: int) -> int:
    if isinstance(chunk, bool) or not isinstance(chunk, int | np.integer) or chunk < 1:
        raise ParameterError("chunk", chunk, "must be an integer >= 1")
    return int(chunk)


def chunk_slices(n: int, chunk: int) -> list[slice]:
    """Deterministic chunking: depends on n and chunk only, never on the worker count."""
    chunk = check_chunk(chunk)
    return [slice(a, min(a + chunk, n)) for a in range(0, n, chunk)]


@contextlib.contextmanager
def _progress(n: int, label: str, show: bool) -> Iterator[Callable[[slice], None]]:
    """advance(sl): a rich progress bar on stderr over n cases moved past chunk sl (nothing
    when not ``show``)."""
    if not show:
        yield lambda sl: None
        return
    from rich.console import Console
    from rich.progress import Progress

    with Progress(console=Console(stderr=True), transient=True) as bar:
        task = bar.add_task(f"{label} {n} cases", total=n)
        yield lambda sl: bar.advance(task, sl.stop - sl.start)


def run_local(fn: Callable[[slice], None], n: int, chunk: int, *, progress: bool = False,
              label: str = "simulating") -> None:
    """Call fn(sl) for every chunk of n cases, in order; a rich progress bar on stderr if
    ``progress`` and there is more than one chunk."""
    slices = chunk_slices(n, chunk)
    with _progress(n, label, progress and len(slices) > 1) as advance:
        for sl in slices:
            fn(sl)
            advance(sl)


def map_threads(fn: Callable[[slice], Any], n: int, chunk: int,
                consume: Callable[[Any], None], *, threads: int, progress: bool = False,
                label: str = "simulating") -> None:
    """consume(fn(sl)) for every chunk of n cases, consumed in chunk order in the calling
    thread, with ``threads`` chunks computed at once in a thread pool (``fn`` releases the GIL
    for most of its time, e.g. a nogil kernel run on one thread).  Each thread flies whole
    chunks, so no thread waits for another between pieces of a chunk, and the calling thread's
    work on a result (``consume``) overlaps the flight of the next ones.  At most 2 x
    ``threads`` results are held at a time; an error stops the chunks not started.  The first
    chunk is flown in the calling thread before the others start: what a first call sets up
    (a kernel loaded or compiled, its cache directory checked) is set up once, not raced by
    the threads."""
    from collections import deque
    from concurrent.futures import ThreadPoolExecutor

    slices = chunk_slices(n, chunk)
    if threads <= 1 or len(slices) <= 1:
        run_local(lambda sl: consume(fn(sl)), n, chunk, progress=progress, label=label)
        return
    pending: deque = deque()
    with _progress(n, label, progress) as advance:
        def take() -> None:
            sl, fut = pending.popleft()
            consume(fut.result())
            advance(sl)

        consume(fn(slices[0]))
        advance(slices[0])
        with ThreadPoolExecutor(threads, thread_name_prefix="lgw-chunk") as pool:
            try:
                for sl in slices[1:]:
                    pending.append((sl, pool.submit(fn, sl)))
                    if len(pending) >= 2 * threads:
                        take()
                while pending:
                    take()
            finally:  # an error or an interrupt: chunks not started yet are dropped
                for _, fut in pending:
                    fut.cancel()


def check_workers(workers: int | None) -> None:
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int)
                                or workers < 1):
        raise ParameterError("--workers", workers, "must be an integer >= 1")


def map_dask(task: Callable[..., Any], args: Sequence[tuple], *, workers: int | None = None,
             scheduler: str | None = None, processes: bool = True,
             progress: bool = False) -> list[Any]:
    """[task(*a) for a in args] on dask.distributed (results in order).

    ``scheduler``: address of a running scheduler; otherwise a LocalCluster with ``workers``
    single-threaded workers (``processes=False`` keeps them in this process).  ``task`` must be
    importable by the workers (a module-level function)."""
    check_workers(workers)
    from dask.distributed import Client, LocalCluster
    from dask.distributed import progress as dask_progress

    cluster = None
    if scheduler is None:
        cluster = LocalCluster(n_workers=workers or 1, threads_per_worker=1,
                               processes=processes, dashboard_address=None)
        client = Client(cluster)
    else:
        client = Client(scheduler)
    try:
        futs = [client.submit(task, *a, pure=False) for a in args]
        if progress:
            dask_progress(futs)
        return client.gather(futs)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


def describe(scheduler: str | None, workers: int | None) -> str:
    """How a dask run was executed, for a result's info."""
    return f"dask ({scheduler or f'LocalCluster, {workers or 1} workers'})"
