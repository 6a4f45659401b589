"""What a worker does with one chunk: call the function on its points and pack the results.

This module is imported by the worker processes (local or Dask): it needs NumPy only.
"""

from __future__ import annotations

import hashlib
import pickle
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from functools import partial
from typing import Any

import numpy as np

from ._grid import RESERVED, chunk_points

#: status of a point: computed
OK = 0
#: status of a point whose function raised (its message has the exception)
RAISED = 1
#: status of a point not computed (a lost chunk, or missing from a partial store)
NOT_COMPUTED = -1

_BATCHED_ATTR = "__rigidbody_batched__"


def batched(func: Callable[..., Any]) -> Callable[..., Any]:
    """Mark ``func`` as batch-capable for :func:`rigidbody.sweep.sweep` (sets an attribute, returns ``func``).

    A batched function is called once per chunk with each grid parameter as a 1-D array of the chunk's
    points (all of the same length ``n``) and returns a mapping of output names to arrays of shape
    ``(n,)`` or ``(n, ...)``; optionally also ``'status'`` (``n`` integers >= 0, 0 = ok) and
    ``'message'`` (``n`` strings) per point. If the call raises, the chunk is retried point by point
    (arrays of length 1), so one bad point does not sink its chunk.

    Parameters
    ----------
    func : callable
        ``func(**arrays) -> mapping``.

    Returns
    -------
    callable
        ``func`` itself, marked.
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


@dataclass
class ChunkResult:
    """The outputs of one chunk: arrays over its points (flat, C order), with a status and message each."""

    chunk: int
    n: int
    schema: dict[str, tuple[int, ...]] | None
    outputs: dict[str, np.ndarray] = field(default_factory=dict)
    status: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    message: list[str] = field(default_factory=list)


@dataclass(frozen=True)
class Task:
    """One chunk to compute: its index, the pickled function and the coordinates of its block."""

    chunk: int
    func: bytes
    is_batched: bool
    names: tuple[str, ...]
    coords: tuple[np.ndarray, ...]


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


def _describe(exc: BaseException) -> str:
    return f"{type(exc).__name__}: {exc}"


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


def _schema(outputs: dict[str, Any], lead: int = 0) -> dict[str, tuple[int, ...]]:
    return {k: () if type(v) is float else tuple(int(s) for s in np.shape(v)[lead:]) for k, v in outputs.items()}


def _pack(chunk: int, rows: list[dict[str, Any] | None], status: np.ndarray,
          message: list[str]) -> ChunkResult:
    """Stack per-point outputs; a point whose outputs differ from the chunk's first good point fails."""
    n = len(rows)
    schema: dict[str, tuple[int, ...]] | None = None
    for i, row in enumerate(rows):
        if row is None:
            continue
        s = _schema(row)
        if schema is None:
            schema = s
        elif s != schema:
            rows[i] = None
            status[i] = RAISED
            message[i] = (f"ValueError: the outputs {s} differ from those of the other points {schema} "
                          "(a sweep's function returns the same names and shapes at every point)")
    outputs: dict[str, np.ndarray] = {}
    if schema is not None:
        for k, shp in schema.items():
            if shp == ():
                outputs[k] = np.array([np.nan if row is None else row[k] for row in rows], dtype=float)
                continue
            a = np.full((n, *shp), np.nan)
            for i, row in enumerate(rows):
                if row is not None:
                    a[i] = row[k]
            outputs[k] = a
    return ChunkResult(chunk, n, schema, outputs, status, message)


def _per_point(func: Any, names: tuple[str, ...], points: list[np.ndarray], chunk: int) -> ChunkResult:
    n = points[0].size if points else 0
    rows: list[dict[str, Any] | None] = []
    status = np.zeros(n, dtype=np.int64)
    message = [""] * n
    columns = [p.tolist() for p in points]  # Python scalars
    for i in range(n):
        kwargs = {name: c[i] for name, c in zip(names, columns)}
        try:
            rows.append(_as_outputs(func(**kwargs), names))
        except Exception as exc:  # a failing point is recorded, the sweep goes on
            rows.append(None)
            status[i] = RAISED
            message[i] = _describe(exc)
    return _pack(chunk, rows, status, message)


def _batched_call(func: Any, names: tuple[str, ...], points: list[np.ndarray], chunk: int) -> ChunkResult:
    n = points[0].size
    out = func(**dict(zip(names, points)))
    outputs = _as_outputs(out, names, allow_status=True)
    for k, v in outputs.items():
        if v.ndim == 0 or v.shape[0] != n:
            raise ValueError(f"a batched function returns arrays with a leading axis of the chunk's {n} "
                             f"points; output {k!r} has shape {v.shape}")
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
    bad = status != OK
    for v in outputs.values():
        v[bad] = np.nan  # outputs of a point that did not succeed are not results
    return ChunkResult(chunk, n, _schema(outputs, lead=1) if not np.all(bad) else None, outputs, status, message)


def compute_chunk(func: Any, is_batched_func: bool, names: tuple[str, ...], coords: tuple[np.ndarray, ...],
                  chunk: int) -> ChunkResult:
    """Call ``func`` on the points of one block (once for a batched function, else once per point)."""
    points = chunk_points(list(coords))
    if not is_batched_func:
        return _per_point(func, names, points, chunk)
    try:
        return _batched_call(func, names, points, chunk)
    except Exception:
        # isolate the failing point(s): the same function on one point at a time
        parts = []
        for i in range(points[0].size):
            one = [p[i:i + 1] for p in points]
            try:
                parts.append(_batched_call(func, names, one, chunk))
            except Exception as exc:
                parts.append(ChunkResult(chunk, 1, None, {}, np.array([RAISED]), [_describe(exc)]))
        rows: list[dict[str, Any] | None] = []
        for part in parts:
            ok = part.schema is not None and part.status[0] == OK
            rows.append({k: v[0] for k, v in part.outputs.items()} if ok else None)
        status = np.concatenate([p.status for p in parts])
        message = [m for p in parts for m in p.message]
        return _pack(chunk, rows, status, message)


def run_task(task: Task) -> ChunkResult:
    """The worker's entry point: load the function, compute the chunk."""
    func = _load_function(task.func)
    return compute_chunk(func, task.is_batched, task.names, task.coords, task.chunk)


def init_worker(parent: int) -> None:
    """Initializer of local worker processes.

    Ctrl-C is handled by the sweeping process, which ends its workers. A worker whose sweeping process
    died (killed: it could not end them) ends itself: its task queue would never close, and it would wait
    forever.
    """
    import os
    import signal
    import threading
    import time

    signal.signal(signal.SIGINT, signal.SIG_IGN)

    def watch() -> None:
        while os.getppid() == parent:
            time.sleep(0.5)
        os._exit(1)

    threading.Thread(target=watch, name="rigidbody-sweep-parent-watch", daemon=True).start()
