"""Where the chunks run: in-process, on local worker processes, on a Dask cluster.

Each driver takes an iterator of tasks and yields, as they complete, either a :class:`ChunkResult` or a
:class:`Lost` (a chunk whose task failed as a whole: its worker died, or the function could not be loaded
there). The sweeping process writes the results; the workers never touch the store.
"""

from __future__ import annotations

import multiprocessing
import os
import sys
from collections.abc import Iterator
from concurrent.futures import FIRST_COMPLETED, Executor, Future, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass
from typing import Any

from ._run import ChunkResult, Task, compute_chunk, ignore_sigint, run_task


@dataclass(frozen=True)
class Lost:
    """A chunk whose task failed as a whole (not written to a store: a re-run computes it)."""

    chunk: int
    reason: str


def local_cpu_count() -> int:
    """CPUs this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not on Linux
        return os.cpu_count() or 1


def run_serial(func: Any, tasks: Iterator[Task]) -> Iterator[ChunkResult | Lost]:
    for t in tasks:
        yield compute_chunk(func, t.is_batched, t.names, t.coords, t.chunk)


def _end_pool(pool: ProcessPoolExecutor) -> None:
    """Stop a pool we own at once (Ctrl-C): cancel what waits, end the running workers."""
    terminate = getattr(pool, "terminate_workers", None)  # Python >= 3.14
    if terminate is not None:
        terminate()
    else:
        # before 3.14 the pool has no public way to end running workers; its process table is private
        for p in list(getattr(pool, "_processes", {}).values()):
            p.terminate()
    pool.shutdown(wait=False, cancel_futures=True)


def new_pool(max_workers: int) -> ProcessPoolExecutor:
    # spawn: a fresh interpreter per worker (no fork of a process that may hold threads: a Dask client, a
    # GUI); the function travels pickled by value where it must (cloudpickle), so functions of a script's
    # or a notebook's __main__ work
    return ProcessPoolExecutor(max_workers=max_workers, mp_context=multiprocessing.get_context("spawn"),
                               initializer=ignore_sigint)


def run_executor(executor: Executor | None, max_workers: int, tasks: Iterator[Task]) -> Iterator[ChunkResult | Lost]:
    """Run on a ``concurrent.futures`` executor; ``None``: local processes we own (restarted if one dies)."""
    owned = executor is None
    pool: Executor = new_pool(max_workers) if executor is None else executor
    n_workers = max_workers if owned else int(getattr(executor, "_max_workers", None) or local_cpu_count())
    limit = 2 * max(1, n_workers)  # few chunks in flight: a broken pool or Ctrl-C loses little
    pending: dict[Future[ChunkResult], int] = {}
    todo = iter(tasks)
    exhausted = False
    clean = False
    completed = 0  # chunks finished by the current pool
    try:
        while True:
            while not exhausted and len(pending) < limit:
                t = next(todo, None)
                if t is None:
                    exhausted = True
                    break
                pending[pool.submit(run_task, t)] = t.chunk
            if not pending:
                break
            done, _ = wait(pending, return_when=FIRST_COMPLETED)
            broken = False
            for fut in done:
                c = pending.pop(fut)
                exc = fut.exception()
                if exc is None:
                    completed += 1
                    yield fut.result()
                elif isinstance(exc, BrokenProcessPool):
                    broken = True
                    yield Lost(c, f"a worker process died while this chunk was in flight ({exc})")
                elif not isinstance(exc, Exception):
                    raise exc  # KeyboardInterrupt, SystemExit raised in a worker: stop the sweep
                else:
                    yield Lost(c, f"the chunk's task failed: {type(exc).__name__}: {exc}")
            if broken:
                if not completed:
                    raise RuntimeError(
                        "a local worker process died before any chunk finished (a script must start the sweep "
                        "under `if __name__ == '__main__':`, since the workers are spawned and import the "
                        "script; or the function ended its process)")
                completed = 0
                for fut, c in list(pending.items()):
                    yield Lost(c, "a worker process died while this chunk was in flight")
                pending.clear()
                if not owned:
                    for t in todo:
                        yield Lost(t.chunk, "the executor broke (a worker process died)")
                    break
                pool.shutdown(wait=False, cancel_futures=True)
                pool = new_pool(max_workers)
        clean = True
    finally:
        if owned:
            assert isinstance(pool, ProcessPoolExecutor)
            if clean:
                pool.shutdown(wait=True)
            else:
                _end_pool(pool)
        else:
            for fut in pending:
                fut.cancel()


def dask_workers(client: Any) -> int:
    try:
        return max(1, sum(client.nthreads().values()))
    except Exception:  # pragma: no cover - a scheduler that does not answer: chunking only
        return 1


def run_dask(client: Any, tasks: Iterator[Task]) -> Iterator[ChunkResult | Lost]:
    """Run on a Dask cluster through ``client`` (its scheduler retries tasks of workers that die)."""
    distributed = sys.modules["distributed"]
    futures = {client.submit(run_task, t, pure=False): t.chunk for t in tasks}
    remaining = dict(futures)
    try:
        for fut in distributed.as_completed(list(futures)):
            c = remaining.pop(fut)
            if fut.status == "finished":
                yield fut.result()
            elif fut.status == "error":
                exc = fut.exception()
                if not isinstance(exc, Exception):
                    raise exc  # KeyboardInterrupt, SystemExit: stop the sweep
                yield Lost(c, f"the chunk's task failed on the cluster: {type(exc).__name__}: {exc}")
            else:
                yield Lost(c, f"the chunk's task was {fut.status} on the cluster")
            fut.release()
    finally:
        if remaining:
            client.cancel(list(remaining))
