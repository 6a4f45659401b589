"""What a worker does with a task: call the function on the task's points of one chunk and pack the results.

This module is imported by the worker processes (local or Dask): it needs NumPy only.
"""

from __future__ import annotations

import hashlib
import math
import os
import pickle
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from functools import partial
from typing import Any

import numpy as np

from ._grid import RESERVED, chunk_points
from ._results import OK, RAISED, ChunkResult, Group, Journal, describe, pack, schema_of

_BATCHED_ATTR = "__rigidbody_batched__"


def batched(func: Callable[..., Any]) -> Callable[..., Any]:
    """Mark ``func`` as batch-capable for :func:`rigidbody.sweep.sweep` (sets an attribute, returns ``func``).

    A batched function is called once per chunk with each grid parameter as a 1-D array of the chunk's
    points (all of the same length ``n``) and returns a mapping of output names to arrays of shape
    ``(n,)`` or ``(n, ...)``; optionally also ``'status'`` (``n`` integers >= 0, 0 = ok) and
    ``'message'`` (``n`` strings) per point. If the call raises, or ends its worker process, the chunk is
    retried point by point (arrays of length 1), so one bad point does not sink its chunk.

    Parameters
    ----------
    func : callable
        ``func(**arrays) -> mapping``.

    Returns
    -------
    callable
        ``func`` itself, marked.

    See Also
    --------
    sweep : which calls it once per chunk.

    Examples
    --------
    One call per chunk with arrays of the points; the product table ``a b``:

    >>> from rigidbody.sweep import batched, sweep
    >>> @batched
    ... def product(a, b):
    ...     return {"prod": a * b}
    >>> ds = sweep(product, {"a": [1.0, 2.0], "b": [3.0, 4.0, 5.0]}, executor="serial", progress=False)
    >>> ds["prod"].values
    array([[ 3.,  4.,  5.],
           [ 6.,  8., 10.]])
    """
    if not callable(func):
        raise TypeError(f"batched() needs a callable, got {type(func).__name__}")
    setattr(func, _BATCHED_ATTR, True)
    return func


def is_batched(func: Any) -> bool:
    """Whether ``func`` (or the function a ``functools.partial`` wraps) is marked by :func:`batched`."""
    while isinstance(func, partial):
        func = func.func
    return bool(getattr(func, _BATCHED_ATTR, False))


@dataclass(frozen=True)
class Task:
    """Points of one chunk to compute: the chunk's index, the pickled function, the coordinates of its block.

    ``subset``: the flat positions in the chunk to compute (default all, in C order); ``journal``: the file to
    record them in as they finish; ``retry``: a point run again alone after its worker process died computing
    it; ``alone``: on Dask, such a point run once more, with no other retry on the cluster; ``one_by_one``: a
    batched function called on one point at a time (to find a point that ends its process);
    ``deaths_loading``: how often a worker died loading the function for these points.
    """

    chunk: int
    func: bytes
    is_batched: bool
    names: tuple[str, ...]
    coords: tuple[np.ndarray, ...]
    subset: tuple[int, ...] | None = None
    journal: str | None = None
    retry: bool = False
    alone: bool = False
    one_by_one: bool = False
    deaths_loading: int = 0

    def positions(self) -> np.ndarray:
        if self.subset is not None:
            return np.array(self.subset, dtype=np.int64)
        return np.arange(math.prod(c.size for c in self.coords), dtype=np.int64)


def dumps_function(func: Any) -> bytes:
    """Pickle the function by value where needed (cloudpickle: functions of ``__main__`` or a notebook)."""
    try:
        import cloudpickle
    except ImportError:  # pragma: no cover - cloudpickle comes with dask; plain pickle handles module functions
        return pickle.dumps(func)
    return cloudpickle.dumps(func)


_loaded: dict[str, Any] = {}


def _load_function(blob: bytes) -> Any:
    key = hashlib.sha256(blob).hexdigest()
    if key not in _loaded:
        if len(_loaded) > 8:
            _loaded.clear()
        _loaded[key] = pickle.loads(blob)  # pickled by the sweeping process itself
    return _loaded[key]


def _as_outputs(out: Any, names: tuple[str, ...], allow_status: bool = False) -> dict[str, Any]:
    if not isinstance(out, Mapping):
        raise TypeError(f"the function must return a mapping of output names to numbers or arrays, "
                        f"got {type(out).__name__}")
    res: dict[str, Any] = {}
    for key, value in out.items():
        if allow_status and key in RESERVED:
            continue
        if not isinstance(key, str) or not key.isidentifier():
            raise TypeError(f"output names must be valid identifiers, got {key!r}")
        if key in RESERVED or key in names:
            raise ValueError(f"output name {key!r} collides with a grid name or the sweep's own "
                             f"variables {RESERVED}")
        if type(value) is float:  # the common case, without a NumPy round trip
            res[key] = value
            continue
        a = np.asarray(value)
        if a.dtype.kind not in "biuf":
            raise TypeError(f"output {key!r} must be real numbers, got dtype {a.dtype}")
        res[key] = a.astype(float) if a.ndim else float(a)
    return res


def _per_point(func: Any, task: Task, points: list[np.ndarray], journal: Journal, in_caller: bool) -> ChunkResult:
    index = task.positions()
    n = index.size
    rows: list[dict[str, Any] | None] = []
    status = np.zeros(n, dtype=np.int64)
    message = [""] * n
    columns = [p.tolist() for p in points]  # Python scalars
    names = task.names
    record = journal.point if journal.fd is not None else None
    for k, i in enumerate(index.tolist()):
        kwargs = {name: c[i] for name, c in zip(names, columns)}
        row: dict[str, Any] | None = None
        try:
            row = _as_outputs(func(**kwargs), names)
        except BaseException as exc:  # a failing point is recorded, the sweep goes on
            if in_caller and isinstance(exc, KeyboardInterrupt):
                raise  # the user's Ctrl-C in the sweeping process
            status[k] = RAISED
            message[k] = describe(exc)
        rows.append(row)
        if record is not None:
            record(i, status[k], message[k], row)
    return pack(task.chunk, index, rows, status, message)


def _batched_call(func: Any, names: tuple[str, ...], points: list[np.ndarray], chunk: int,
                  index: np.ndarray) -> ChunkResult:
    n = points[0].size
    out = func(**dict(zip(names, points)))
    outputs = _as_outputs(out, names, allow_status=True)
    for k, v in outputs.items():
        if np.ndim(v) == 0 or np.shape(v)[0] != n:
            raise ValueError(f"a batched function returns arrays with a leading axis of the chunk's {n} "
                             f"points; output {k!r} has shape {np.shape(v)}")
    status = np.zeros(n, dtype=np.int64)
    message = [""] * n
    if "status" in out:
        st = np.asarray(out["status"])
        if st.shape != (n,) or st.dtype.kind not in "biu" or np.any(st < 0):
            raise ValueError(f"a batched function's 'status' must be {n} integers >= 0 (0 = ok), got {st!r}")
        status = st.astype(np.int64)
    if "message" in out:
        msg = [str(m) for m in np.asarray(out["message"], dtype=object).ravel()]
        if len(msg) != n:
            raise ValueError(f"a batched function's 'message' must hold {n} strings, got {len(msg)}")
        message = msg
    good = np.flatnonzero(status == OK)
    groups = [Group(schema_of(outputs, lead=1), good, {k: v[good] for k, v in outputs.items()})] if good.size else []
    return ChunkResult(chunk, index, status, message, groups)


def _batched(func: Any, task: Task, points: list[np.ndarray], journal: Journal, in_caller: bool) -> ChunkResult:
    index = task.positions()
    if not task.one_by_one:
        try:
            res = _batched_call(func, task.names, [p[index] for p in points], task.chunk, index)
        except BaseException as exc:
            if in_caller and isinstance(exc, KeyboardInterrupt):
                raise
        else:
            journal.result(res)
            return res
    # isolate the failing point(s): the same function on one point at a time
    rows: list[dict[str, Any] | None] = []
    status = np.zeros(index.size, dtype=np.int64)
    message = [""] * index.size
    for k, i in enumerate(index.tolist()):
        try:
            part = _batched_call(func, task.names, [p[i:i + 1] for p in points], task.chunk, index[k:k + 1])
            status[k], message[k] = part.status[0], part.message[0]
            rows.append({name: v[0] for name, v in part.groups[0].outputs.items()} if part.groups else None)
        except BaseException as exc:
            if in_caller and isinstance(exc, KeyboardInterrupt):
                raise
            status[k], message[k] = RAISED, describe(exc)
            rows.append(None)
        journal.point(i, status[k], message[k], rows[-1])
    return pack(task.chunk, index, rows, status, message)


def compute(func: Any, task: Task, in_caller: bool = False) -> ChunkResult:
    """Call ``func`` on the task's points (once for a batched function, else once per point).

    Every exception a point raises is recorded as its failure (status 1), ``SystemExit`` included; a
    ``KeyboardInterrupt`` too, except in the sweeping process itself (``in_caller``), where it is the
    user's Ctrl-C. Each finished point is recorded in the task's journal.
    """
    points = chunk_points(list(task.coords))
    journal = Journal(task.journal)
    try:
        if task.is_batched:
            res = _batched(func, task, points, journal, in_caller)
        else:
            res = _per_point(func, task, points, journal, in_caller)
    finally:
        journal.close()
    res.journal = task.journal
    return res


def run_task(task: Task) -> ChunkResult:
    """The entry point of a task on a Dask worker or an executor: load the function, compute the points."""
    return compute(_load_function(task.func), task)


def worker_main(conn: Any, parent: int) -> None:
    """A local worker process: says it is ready, then computes the tasks it receives until it gets None.

    Answers ``('ready', pid)`` once started, then per task ``('done', result)``, or ``('unloadable', why)``
    when the function cannot be loaded here, or ``('failed', why)`` when the task fails as a whole.
    """
    init_worker(parent)
    conn.send(("ready", os.getpid()))
    while True:
        try:
            task = conn.recv()
        except EOFError:  # the sweeping process is gone
            return
        if task is None:
            return
        try:
            func = _load_function(task.func)
        except BaseException as exc:
            conn.send(("unloadable", describe(exc)))
            continue
        try:
            res = compute(func, task)
        except BaseException as exc:  # not a point's failure (those are recorded): e.g. the journal's disk is full
            conn.send(("failed", describe(exc)))
            continue
        conn.send(("done", res))


def init_worker(parent: int) -> None:
    """Prepare a local worker process.

    Ctrl-C is handled by the sweeping process, which ends its workers. A worker whose sweeping process
    died (killed: it could not end them) ends itself: nobody would read its results.
    """
    import signal
    import threading
    import time

    signal.signal(signal.SIGINT, signal.SIG_IGN)

    def watch() -> None:
        while os.getppid() == parent:
            time.sleep(0.5)
        os._exit(1)

    threading.Thread(target=watch, name="rigidbody-sweep-parent-watch", daemon=True).start()
