"""Local worker processes owned by a sweep, one task per worker at a time.

The sweep knows which task each worker runs and reads the task's journal when the worker dies, so a death
costs only the point being computed: the points the worker had finished are kept, the point it was
computing runs again alone (it is lost, status -1, only if it ends its worker again), the rest of the task
runs again elsewhere. The other workers go on. A worker that dies before it is ready to take a task (the
spawned interpreter could not start: typically a script without its ``__main__`` guard, which each worker
imports) stops the sweep with that diagnosis; a function that cannot be loaded in a worker stops it too.

Workers are spawned (a fresh interpreter each: nothing is inherited from a process that holds threads),
ignore Ctrl-C (the sweeping process handles it and ends them) and end themselves when the sweeping process
dies.
"""

from __future__ import annotations

import multiprocessing
import os
import signal
from collections import deque
from collections.abc import Iterator
from dataclasses import replace
from multiprocessing.connection import wait
from pathlib import Path
from typing import Any

import numpy as np

from ._executors import Events, Lost, with_journal
from ._results import ChunkResult, read_journal
from ._run import Task, worker_main

_NOT_STARTED = ("a local worker process died while starting, before it could take any task ({how}): a script "
                "must start the sweep under `if __name__ == '__main__':` (the workers are spawned and import "
                "the script)")
_UNLOADABLE = ("the function cannot be loaded in a local worker process ({why}): a function of the script or "
               "notebook that calls sweep travels by value, any other is imported by its module's name, which "
               "the workers must be able to import")


def exit_description(code: int | None) -> str:
    """How a process ended, from its exit code."""
    if code is not None and code < 0:
        try:
            return f"killed by signal {signal.Signals(-code).name}"
        except ValueError:  # pragma: no cover - a signal Python does not name
            return f"killed by signal {-code}"
    return f"exit code {code}"


class _Worker:
    """A worker process, the pipe to it, and the task it runs."""

    def __init__(self, ctx: Any) -> None:
        self.conn, child = ctx.Pipe()
        self.process = ctx.Process(target=worker_main, args=(child, os.getpid()), name="rigidbody-sweep-worker")
        self.process.start()
        child.close()
        self.ready = False
        self.task: Task | None = None

    def receive(self) -> tuple[Any, ...] | None:
        """The worker's next message, or None if it died (then reaped).

        Called when its pipe or its sentinel is ready: no data on the pipe means it is ending.
        """
        try:
            if self.conn.poll():
                msg: tuple[Any, ...] = self.conn.recv()
                return msg
        except (EOFError, OSError):  # its end of the pipe closed
            pass
        self.process.join(5.0)
        return None

    def end(self, clean: bool) -> None:
        if clean and self.process.is_alive():
            try:
                self.conn.send(None)
            except OSError:
                pass
            self.process.join(5.0)
        if self.process.is_alive():
            self.process.terminate()
            self.process.join(2.0)
        if self.process.is_alive():  # pragma: no cover - a worker that ignores SIGTERM
            self.process.kill()
            self.process.join()
        self.conn.close()


def _salvage(t: Task) -> tuple[ChunkResult | None, tuple[int, ...]]:
    """The points a task's journal holds (None: no journal, the function was not loaded) and those not done."""
    partial = read_journal(t.journal, t.chunk) if t.journal is not None else None
    finished = set() if partial is None else set(partial.index.tolist())
    return partial, tuple(p for p in t.positions().tolist() if p not in finished)


def after_death(t: Task, how: str) -> tuple[list[ChunkResult | Lost], list[Task]]:
    """What a worker's death while running ``t`` leaves: the points it had finished, and the tasks to run again.

    The first point the journal does not hold is the one the worker was computing: it runs again alone; the
    others run again together. A point that ends its worker again alone is lost. A batched function's chunk
    is first run again one point at a time, to find that point.
    """
    partial, rest = _salvage(t)
    if partial is None:  # no journal yet: the worker died loading the function
        if t.deaths_loading >= 1:
            raise RuntimeError(f"local worker processes died twice while loading the function ({how}): the "
                               "function (or a module it imports) ends the process that unpickles it")
        return [], [replace(t, journal=None, deaths_loading=t.deaths_loading + 1)]
    events: list[ChunkResult | Lost] = [partial]  # possibly empty: the sweep then deletes its journal
    if not rest:
        return events, []
    base = replace(t, journal=None, deaths_loading=0)
    if t.is_batched and not t.one_by_one and not t.retry:
        return events, [replace(base, subset=rest, one_by_one=True)]
    if t.retry:
        events.append(Lost(t.chunk, np.array(rest[:1]), f"its worker process died twice while computing this "
                                                        f"point ({how})"))
        return events, [replace(base, subset=rest[1:], retry=False)] if rest[1:] else []
    again = [replace(base, subset=rest[:1], retry=True)]
    return events, again + ([replace(base, subset=rest[1:])] if rest[1:] else [])


class _Pool:
    """The workers, the tasks to give them, and what their messages and deaths mean."""

    def __init__(self, max_workers: int, tasks: Iterator[Task], journal_dir: Path) -> None:
        self.ctx = multiprocessing.get_context("spawn")
        self.workers = [_Worker(self.ctx) for _ in range(max_workers)]
        self.retries: deque[Task] = deque()
        self.todo = tasks
        self.journal_dir = journal_dir
        self.exhausted = self.started = False
        self.start_deaths = 0

    def _next_task(self) -> Task | None:
        if self.retries:
            return self.retries.popleft()
        t = None if self.exhausted else next(self.todo, None)
        self.exhausted = t is None
        return t

    def dispatch(self) -> None:
        """Give each ready, idle worker a task."""
        for w in self.workers:
            if w.ready and w.task is None:
                t = self._next_task()
                if t is None:
                    return
                w.task = with_journal(t, self.journal_dir)
                try:
                    w.conn.send(w.task)
                except OSError:  # it just died: its death is seen next
                    self.retries.appendleft(t)
                    w.task = None

    def finished(self) -> bool:
        return self.exhausted and not self.retries and all(w.task is None for w in self.workers)

    def handle(self, w: _Worker) -> list[ChunkResult | Lost]:
        """What a worker said (or its death) means for the sweep."""
        msg = w.receive()
        if msg is None:
            return self._died(w)
        if msg[0] == "ready":
            w.ready = self.started = True
            self.start_deaths = 0
        elif msg[0] == "unloadable":
            raise RuntimeError(_UNLOADABLE.format(why=msg[1]))
        elif msg[0] in ("done", "failed") and w.task is not None:
            t, w.task = w.task, None
            if msg[0] == "done":
                return [msg[1]]
            partial, rest = _salvage(t)  # the task failed as a whole: keep what its journal holds
            return [*([partial] if partial is not None else []),
                    Lost(t.chunk, np.array(rest, dtype=np.int64), f"the task failed: {msg[1]}")]
        return []

    def _died(self, w: _Worker) -> list[ChunkResult | Lost]:
        how = exit_description(w.process.exitcode)
        events: list[ChunkResult | Lost] = []
        if not w.ready:
            self.start_deaths += 1
            if not self.started or self.start_deaths > 3:
                raise RuntimeError(_NOT_STARTED.format(how=how))
        elif w.task is not None:
            events, again = after_death(w.task, how)
            self.retries.extendleft(reversed(again))
        w.end(clean=False)
        self.workers[self.workers.index(w)] = _Worker(self.ctx)
        return events

    def end(self, clean: bool) -> None:
        for w in self.workers:
            w.end(clean)


def run_local(max_workers: int, tasks: Iterator[Task], journal_dir: Path) -> Events:
    """Run the tasks on ``max_workers`` local worker processes started for this call."""
    pool = _Pool(max_workers, iter(tasks), journal_dir)
    clean = False
    try:
        while True:
            pool.dispatch()
            if pool.finished():
                break
            waitables: dict[Any, _Worker] = {}
            for w in pool.workers:
                waitables[w.conn] = waitables[w.process.sentinel] = w
            events: list[ChunkResult | Lost] = []
            for w in {id(w): w for w in (waitables[o] for o in wait(list(waitables)))}.values():
                events += pool.handle(w)
            pool.dispatch()  # the workers get their next tasks before the sweeping process writes the results
            yield from events
        clean = True
    finally:
        pool.end(clean)
