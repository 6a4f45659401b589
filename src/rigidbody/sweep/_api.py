"""``sweep``: a function over the outer product of a grid, on any executor, into an ``xarray.Dataset``."""

from __future__ import annotations

import math
import os
import shutil
import sys
import tempfile
import warnings
from collections.abc import Callable, Iterator, Mapping
from concurrent.futures import Executor
from pathlib import Path
from typing import Any

import numpy as np

from ._collect import Results
from ._deps import require
from ._executors import Lost, dask_workers, local_cpu_count, run_dask, run_executor, run_serial
from ._grid import Layout, block_shape, check_grid, default_chunk_size, function_label, function_name
from ._lock import StoreLock
from ._pool import run_local
from ._run import Task, dumps_function, is_batched
from ._store import Store

__all__ = ["load", "require", "sweep"]


def _resolve(executor: Any, max_workers: int | None) -> tuple[str, Any]:
    if max_workers is not None:
        if isinstance(max_workers, bool) or not isinstance(max_workers, (int, np.integer)) or max_workers < 1:
            raise ValueError(f"max_workers must be an integer >= 1, got {max_workers!r}")
        if executor not in (None, "processes"):
            raise ValueError("max_workers applies to the default executor (local processes) only")
    if executor is None or executor == "processes":
        return "processes", None
    if executor == "serial":
        return "serial", None
    if isinstance(executor, Executor):
        return "executor", executor
    if isinstance(executor, str):
        if "://" in executor or ":" in executor:
            return "address", executor
        raise ValueError(f"executor must be None or 'processes' (local processes), 'serial', a "
                         f"concurrent.futures.Executor, a distributed.Client or a scheduler address such as "
                         f"'tcp://host:8786'; got {executor!r}")
    distributed = sys.modules.get("distributed")
    if distributed is not None and isinstance(executor, distributed.Client):
        return "dask", executor
    raise TypeError(f"executor must be None, 'processes', 'serial', a concurrent.futures.Executor, a "
                    f"distributed.Client or a scheduler address string; got {type(executor).__name__}")


def sweep(
    func: Callable[..., Mapping[str, Any]],
    grid: Mapping[str, Any],
    *,
    executor: Any = None,
    store: str | os.PathLike[str] | None = None,
    progress: bool | None = None,
    chunk_size: int | None = None,
    max_workers: int | None = None,
) -> Any:
    """Evaluate ``func`` over the outer product of ``grid`` and gather the results in an ``xarray.Dataset``.

    Parameters
    ----------
    func : callable
        ``func(**point) -> {output name: float or array of fixed shape}``, called with one value of each
        grid parameter (a Python float, int or str). A function marked with :func:`batched` is called
        once per chunk with 1-D arrays instead. A point whose call raises any exception, ``SystemExit``
        and other ``BaseException`` included, is recorded (``status`` 1, ``message`` with the exception's
        type and text) and the sweep goes on; only a ``KeyboardInterrupt`` in the sweeping process (the
        user's Ctrl-C) stops it. The outputs (names and shapes) are those of the first point, in grid
        order, that succeeded: a point returning others fails (status 1) on every executor alike. On
        local processes and on Dask the function travels pickled (by value when it lives in a script's
        or notebook's ``__main__``).
    grid : mapping of str to 1-D array_like
        Parameter names (valid identifiers) to their values, each value once; the sweep runs over the
        outer product, in the given order (the last name varies fastest).
    executor : None, 'processes', 'serial', concurrent.futures.Executor, distributed.Client or str
        ``None`` (default) or ``'processes'``: local worker processes started for this call (spawned,
        ``max_workers`` of them, by default one per CPU; no server; a worker that dies costs only the
        point it was computing); ``'serial'``: in this process; an executor you made (e.g. a
        ``ProcessPoolExecutor`` reused over many sweeps; one whose worker dies breaks, and its unfinished
        points are lost); a ``distributed.Client``, or the address of a Dask scheduler
        (``'tcp://host:8786'``), to run on a Dask cluster. All give the same Dataset.
    store : path, optional
        A directory (a Zarr store, created if missing) where the points are written as their chunks
        complete, with a flag per point. Calling ``sweep`` again with the same function, grid and store
        computes only the points not finished, so an interrupted sweep (Ctrl-C, a killed worker, sweeping
        process or machine) loses nothing finished (on Dask and on an executor you made: nothing of the
        tasks that had returned). A store made by another function (qualified name), over another grid or
        with other outputs is refused (``ValueError``); a store that another sweep is writing is refused
        at once (``RuntimeError``). Its chunk layout wins over ``chunk_size``.
    progress : bool or None
        A tqdm progress bar on stderr: ``None`` (default) when stderr is a terminal, ``True`` always,
        ``False`` never.
    chunk_size : int, optional
        Points per chunk (one task; one write to the store): at most this many, cut along the grid's
        last dimensions. Default: 100 (10^4 for a batched function), fewer when needed to give every
        worker about four chunks.
    max_workers : int, optional
        Number of local worker processes (default executor only).

    Returns
    -------
    xarray.Dataset
        One dimension per grid name with the grid values as coordinates; one variable per output (array
        outputs add dimensions ``<output>_dim_0, ...``; float64, NaN where a point failed); ``status``
        (0 ok, 1 the function raised, a batched function's own positive codes, -1 not computed: its
        worker died computing it, or its task was lost) and ``message`` (str; empty where ok; why, where
        not) per point; ``attrs['function']``: the function's name.

    Raises
    ------
    TypeError, ValueError
        For a bad grid (duplicate values included), executor, chunk size, or a store that does not match.
    RuntimeError
        If the store is in use by another sweep; if local worker processes cannot start (a script must
        start the sweep under ``if __name__ == '__main__':``) or cannot load the function.
    ImportError
        If the optional dependencies are missing (``pip install "rigidbody[sweep]"``).

    Warns
    -----
    RuntimeWarning
        When some points were not computed (their worker died twice computing them, or their task
        failed as a whole): they have status -1; a re-run with the same store computes them.

    See Also
    --------
    rigidbody.studies.evaluate : the same grid in-process into NumPy arrays (base install).
    load : read a sweep's Zarr store back.

    Examples
    --------
    >>> from rigidbody.sweep import sweep
    >>> def f(a, b):
    ...     return {"sum": a + b}
    >>> ds = sweep(f, {"a": [0.0, 1.0], "b": [10.0, 20.0, 30.0]}, executor="serial", progress=False)
    >>> ds["sum"].shape, int(ds["sum"].sel(a=1.0, b=20.0)), int(ds.status.sum())
    ((2, 3), 21, 0)
    """
    require("xarray")
    if not callable(func):
        raise TypeError(f"func must be callable, got {type(func).__name__}")
    if progress is not None and not isinstance(progress, bool):
        raise TypeError(f"progress must be None, True or False, got {progress!r}")
    g = check_grid(grid)
    shape = tuple(int(v.size) for v in g.values())
    n_points = math.prod(shape)
    name = function_name(func)
    fb = is_batched(func)
    kind, target = _resolve(executor, max_workers)
    client = lock = None
    try:
        if kind == "address":
            distributed = require("distributed")
            client = distributed.Client(target, set_as_default=False)
            kind, target = "dask", client
        n_workers = {"serial": 1, "processes": max_workers or local_cpu_count()}.get(kind)
        if n_workers is None:
            n_workers = dask_workers(target) if kind == "dask" else int(
                getattr(target, "_max_workers", None) or local_cpu_count())
        st = None
        if store is not None:
            path = Store.check_path(store)
            lock = StoreLock(path).acquire()  # one sweep at a time per store
            st = Store.open(path, create=True)
            if st is not None:
                st.check(name, g)
                layout = Layout(shape, st.block)
        if st is None:
            cs = default_chunk_size(n_points, n_workers, fb) if chunk_size is None else chunk_size
            layout = Layout(shape, block_shape(shape, cs))
            if store is not None:
                st = Store.create(path, name, g, layout)
        return _run(func, fb, name, g, layout, st, kind, target, n_workers, progress)
    finally:
        if lock is not None:
            lock.release()
        if client is not None:
            client.close()


def _tasks(func: Any, kind: str, fb: bool, g: dict[str, np.ndarray], layout: Layout,
           pending: np.ndarray) -> Iterator[Task]:
    """A task per chunk with points not finished (only those points)."""
    blob = b"" if kind == "serial" else dumps_function(func)
    names = tuple(g)
    values = list(g.values())
    pending = pending.reshape(layout.shape)
    for c in range(layout.n_chunks):
        sl = layout.slices(c)
        todo = pending[sl].ravel()
        if todo.any():
            subset = None if todo.all() else tuple(np.flatnonzero(todo).tolist())
            yield Task(c, blob, fb, names, tuple(v[s] for v, s in zip(values, sl)), subset)


def _run(func: Any, fb: bool, name: str, g: dict[str, np.ndarray], layout: Layout, st: Store | None, kind: str,
         target: Any, n_workers: int, progress: bool | None) -> Any:
    results = Results(g, layout, st, name)
    scratch = None
    journal_dir: Path | None = None
    if st is not None:
        st.journal_dir.mkdir(exist_ok=True)
        results.replay(st.journals())  # points a killed sweep had finished after its last write
        if kind in ("serial", "processes"):
            journal_dir = st.journal_dir
    elif kind == "processes":  # journals tell which point a dying worker was computing
        journal_dir = scratch = Path(tempfile.mkdtemp(prefix="rigidbody-sweep-"))
    tasks = _tasks(func, kind, fb, g, layout, results.pending.copy())
    if kind == "serial":
        events = run_serial(func, tasks, journal_dir)
    elif kind == "dask":
        events = run_dask(target, tasks)
    elif kind == "processes":
        assert journal_dir is not None
        events = run_local(n_workers, tasks, journal_dir)
    else:
        events = run_executor(target, tasks)
    show = sys.stderr.isatty() if progress is None else progress
    bar = None
    if show:
        tqdm = require("tqdm")
        bar = tqdm.tqdm(total=math.prod(layout.shape), initial=int(np.count_nonzero(~results.pending)), unit="pt",
                        file=sys.stderr, desc=f"sweep {function_label(func)[:40]}", dynamic_ncols=True)
    try:
        for ev in events:
            n = results.lose(ev) if isinstance(ev, Lost) else results.add(ev)
            if bar is not None:
                bar.update(n)
                failed = results.failed()
                if failed:
                    bar.set_postfix(failed=failed, refresh=False)
        results.finish()
    except BaseException as exc:
        events.close()  # ends the workers: their journals are complete
        if st is not None and journal_dir is not None and not isinstance(exc, ValueError):
            try:
                results.replay(st.journals())  # write the points the interrupted tasks had finished
            except Exception:  # pragma: no cover - the next run reads the journals again
                pass
        raise
    finally:
        events.close()
        if bar is not None:
            bar.close()
        if scratch is not None:
            shutil.rmtree(scratch, ignore_errors=True)
    if results.lost:
        n_lost = sum(n for n, _ in results.lost)
        hint = ("run the same sweep again with the same store to compute them" if st is not None
                else "pass store=PATH to keep the finished points across runs")
        warnings.warn(f"{n_lost} of {math.prod(layout.shape)} points were not computed ({results.lost[0][1]}); "
                      f"their status is -1: {hint}", RuntimeWarning, stacklevel=3)
    return results.dataset()


def load(store: str | os.PathLike[str]) -> Any:
    """The Dataset of a sweep store as it stands (the points written; the others have status -1).

    Works while a sweep is writing the store (from another process), and on a store whose sweep was
    interrupted. Points that a killed sweeping process had finished but not yet written are in the
    store's journals: the next :func:`sweep` on the store writes them (without computing them again).

    Parameters
    ----------
    store : path
        A store written by :func:`sweep`.

    Returns
    -------
    xarray.Dataset
        As :func:`sweep` returns it; points not written have status -1, message ``'not computed'`` and
        NaN outputs.

    See Also
    --------
    sweep : which writes the store.

    Examples
    --------
    A store written in a temporary directory reads back with the sweep's values. Stores need zarr-python 3
    (Python >= 3.11), which the ``[sweep]`` extra installs only there, so the store part is not run as a
    doctest (the store tests of the test suite check :func:`load` where zarr is present):

    >>> import os, tempfile
    >>> from rigidbody.sweep import load, sweep
    >>> def f(a, b):
    ...     return {"sum": a + b}
    >>> with tempfile.TemporaryDirectory() as folder:  # doctest: +SKIP
    ...     store = os.path.join(folder, "sums.zarr")
    ...     _ = sweep(f, {"a": [0.0, 1.0], "b": [10.0, 20.0]}, executor="serial", store=store, progress=False)
    ...     ds = load(store)
    ...     print(ds["sum"].values.tolist(), int(ds.status.sum()))
    [[10.0, 20.0], [11.0, 21.0]] 0
    """
    st = Store.open(store, create=False)
    if st is None:
        raise FileNotFoundError(f"no sweep store at {os.fspath(store)!r}")
    g = {n: st.coordinate(n) for n in st.meta["grid"]}
    layout = Layout(tuple(v.size for v in g.values()), st.block)
    return Results(g, layout, st, st.meta["function"]).dataset()
