"""Where the tasks run: in-process, on an executor the user made, on a Dask cluster (local worker processes
owned by the sweep: ``_pool``).

Each driver takes an iterator of tasks and yields, as they complete, a :class:`ChunkResult` (the points of a
task, or those a dead worker had finished) or a :class:`Lost` (points not computed, with the reason). The
sweeping process writes the results; the workers never touch the store (only their tasks' journals).
"""

from __future__ import annotations

import os
import sys
import uuid
from collections import deque
from collections.abc import Generator, Iterator
from concurrent.futures import FIRST_COMPLETED, BrokenExecutor, Executor, Future, wait
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np

from ._results import ChunkResult
from ._run import Task, compute, run_task


@dataclass(frozen=True)
class Lost:
    """Points of a chunk not computed (not written to a store: a re-run computes them), and why."""

    chunk: int
    index: np.ndarray
    reason: str


#: what a driver yields as its tasks complete
Events = Generator[ChunkResult | Lost, None, None]


def local_cpu_count() -> int:
    """CPUs this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not on Linux
        return os.cpu_count() or 1


def with_journal(task: Task, journal_dir: Path | None) -> Task:
    """The task with a fresh journal file in ``journal_dir`` (none without a directory)."""
    if journal_dir is None:
        return task
    return replace(task, journal=str(journal_dir / f"{task.chunk}-{uuid.uuid4().hex}.jnl"))


def run_serial(func: Any, tasks: Iterator[Task], journal_dir: Path | None) -> Events:
    """In the sweeping process (a Ctrl-C in the function stops the sweep)."""
    for t in tasks:
        yield compute(func, with_journal(t, journal_dir), in_caller=True)


def run_executor(executor: Executor, tasks: Iterator[Task]) -> Events:
    """Run on a ``concurrent.futures`` executor the user made.

    An executor that breaks (a ``ProcessPoolExecutor`` whose worker died) cannot be restarted by the sweep:
    the tasks not finished are lost (status -1; a re-run with the same store computes them).
    """
    n_workers = int(getattr(executor, "_max_workers", None) or local_cpu_count())
    limit = 2 * max(1, n_workers)  # few tasks in flight: a broken executor or Ctrl-C loses little
    pending: dict[Future[ChunkResult], Task] = {}
    todo = iter(tasks)
    broken = ""
    try:
        while True:
            while not broken and len(pending) < limit:
                t = next(todo, None)
                if t is None:
                    break
                try:
                    pending[executor.submit(run_task, t)] = t
                except BrokenExecutor as err:
                    broken = _broken(err)
                    yield Lost(t.chunk, t.positions(), broken)
            if not pending:
                break
            # a broken executor fails all its tasks at once: then wait for them all
            done, _ = wait(pending, return_when="ALL_COMPLETED" if broken else FIRST_COMPLETED)
            for fut in done:
                t = pending.pop(fut)
                exc = fut.exception()
                if exc is None:
                    yield fut.result()
                elif isinstance(exc, BrokenExecutor):
                    broken = _broken(exc)
                    yield Lost(t.chunk, t.positions(), broken)
                elif not isinstance(exc, Exception):
                    raise exc  # not a point's failure (those are recorded): the executor's own interruption
                else:
                    yield Lost(t.chunk, t.positions(), f"the task failed: {type(exc).__name__}: {exc}")
        for t in todo:
            yield Lost(t.chunk, t.positions(), broken)
    finally:
        for fut in pending:
            fut.cancel()


def _broken(exc: BaseException) -> str:
    return (f"the executor broke ({type(exc).__name__}): one of its worker processes died (the function ended "
            "it, or, if no task finished, the workers could not start: a script must start the sweep under "
            "`if __name__ == '__main__':`); a sweep cannot restart an executor it did not make (executor=None "
            "gives local processes that it restarts)")


def dask_workers(client: Any) -> int:
    try:
        return max(1, sum(client.nthreads().values()))
    except Exception:  # pragma: no cover - a scheduler that does not answer: chunking only
        return 1


def run_dask(client: Any, tasks: Iterator[Task]) -> Events:
    """Run on a Dask cluster through ``client``.

    The scheduler runs a task again when its worker dies, up to its ``allowed-failures``, then fails it
    with ``KilledWorker``. Such a task's points are then run again one per task. The scheduler fails every
    task a dying worker held, the innocent ones queued beside the one that killed it too: a point whose
    task fails so is run once more, alone among the sweep's retries (one such task on the cluster at a
    time). Only a point that kills its worker then too is lost (status -1).
    """
    distributed = sys.modules["distributed"]
    futures = {client.submit(run_task, t, pure=False): t for t in tasks}
    ac = distributed.as_completed(list(futures), loop=client.loop)
    alone: deque[Task] = deque()  # points to run one at a time
    running_alone = False

    def submit(t: Task) -> None:
        fut = client.submit(run_task, t, pure=False)
        futures[fut] = t
        ac.add(fut)

    try:
        for fut in ac:
            t = futures.pop(fut)
            running_alone = running_alone and not t.alone
            try:
                # a result whose worker died after it finished is recomputed by the scheduler: result() waits
                res = fut.result()
            except distributed.KilledWorker as exc:
                if t.alone:
                    yield Lost(t.chunk, t.positions(), f"its worker process died each time the cluster ran this "
                                                      f"point ({type(exc).__name__})")
                elif t.retry:
                    alone.append(replace(t, alone=True))
                else:
                    for p in t.positions().tolist():
                        submit(replace(t, subset=(p,), retry=True))
            except Exception as exc:  # the task failed as a whole
                yield Lost(t.chunk, t.positions(), f"the task failed on the cluster: {type(exc).__name__}: {exc}")
            else:
                yield res
            fut.release()
            if alone and not running_alone:
                submit(alone.popleft())
                running_alone = True
    finally:
        if futures:
            client.cancel(list(futures))
