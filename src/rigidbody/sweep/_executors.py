"""Where the chunks run: in-process, on local worker processes, on a Dask cluster.

Each driver takes an iterator of tasks and yields, as they complete, either a :class:`ChunkResult` or a
:class:`Lost` (a chunk whose task failed as a whole: its worker died, or the function could not be loaded
there). The sweeping process writes the results; the workers never touch the store.
"""

from __future__ import annotations

import multiprocessing
import os
import sys
from collections import deque
from collections.abc import Iterator
from concurrent.futures import FIRST_COMPLETED, Executor, Future, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass
from typing import Any

from ._run import ChunkResult, Task, compute_chunk, init_worker, run_task


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
                               initializer=init_worker, initargs=(os.getpid(),))


def run_executor(executor: Executor | None, max_workers: int, tasks: Iterator[Task]) -> Iterator[ChunkResult | Lost]:
    """Run on a ``concurrent.futures`` executor; ``None``: local processes we own.

    When a worker process dies, every chunk in flight fails with the pool. We restart the pool and run
    those chunks again one at a time: the one that kills its worker again is lost (reported, not stored),
    the others complete. A pool that breaks before finishing any chunk at all raises (the workers cannot
    start, typically a script without a ``__main__`` guard).
    """
    owned = executor is None
    pool: Executor = new_pool(max_workers) if executor is None else executor
    n_workers = max_workers if owned else int(getattr(executor, "_max_workers", None) or local_cpu_count())
    limit = 2 * max(1, n_workers)  # few chunks in flight: a broken pool or Ctrl-C loses little
    pending: dict[Future[ChunkResult], Task] = {}
    backlog: deque[Task] = deque()
    todo = iter(tasks)
    clean = False
    completed = 0

    def restart() -> Executor:
        pool.shutdown(wait=False, cancel_futures=True)
        return new_pool(max_workers)

    try:
        while True:
            broken = False
            while len(pending) < limit:
                t = backlog.popleft() if backlog else next(todo, None)
                if t is None:
                    break
                try:
                    pending[pool.submit(run_task, t)] = t
                except BrokenProcessPool:
                    backlog.appendleft(t)
                    broken = True
                    break
            if not pending and not broken:
                break
            suspects: list[Task] = []
            if pending:
                done, _ = wait(pending, return_when=FIRST_COMPLETED)
                for fut in done:
                    t = pending.pop(fut)
                    exc = fut.exception()
                    if exc is None:
                        completed += 1
                        yield fut.result()
                    elif isinstance(exc, BrokenProcessPool):
                        broken = True
                        suspects.append(t)
                    elif not isinstance(exc, Exception):
                        raise exc  # KeyboardInterrupt, SystemExit raised in a worker: stop the sweep
                    else:
                        yield Lost(t.chunk, f"the chunk's task failed: {type(exc).__name__}: {exc}")
            if not broken:
                continue
            if not completed:
                raise RuntimeError(
                    "a local worker process died before any chunk finished: a script must start the sweep under "
                    "`if __name__ == '__main__':` (the workers are spawned and import the script), or the "
                    "function ended its process")
            suspects += list(pending.values())  # they fail with the pool
            pending.clear()
            if not owned:
                for t in [*suspects, *backlog, *todo]:
                    yield Lost(t.chunk, "a worker process died and broke the executor")
                break
            pool = restart()
            for t in sorted(suspects, key=lambda x: x.chunk):  # one at a time: find the chunk that kills
                fut = pool.submit(run_task, t)
                exc = wait([fut]) and fut.exception()
                if exc is None:
                    yield fut.result()
                elif isinstance(exc, BrokenProcessPool):
                    yield Lost(t.chunk, "its worker process died (twice: once among others, once alone)")
                    pool = restart()
                elif not isinstance(exc, Exception):
                    raise exc
                else:
                    yield Lost(t.chunk, f"the chunk's task failed: {type(exc).__name__}: {exc}")
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
        for fut in distributed.as_completed(list(futures), loop=client.loop):
            c = remaining.pop(fut)
            try:
                # a result whose worker died after it finished is recomputed by the scheduler: result() waits
                res = fut.result()
            except Exception as exc:  # the task failed as a whole (e.g. KilledWorker after Dask's retries)
                yield Lost(c, f"the chunk's task failed on the cluster: {type(exc).__name__}: {exc}")
            else:
                yield res
            fut.release()
    finally:
        if remaining:
            client.cancel(list(remaining))
