"""``sweep``: a function over the outer product of a grid, on any executor, into an ``xarray.Dataset``."""

from __future__ import annotations

import importlib
import math
import os
import sys
import warnings
from collections.abc import Callable, Iterator, Mapping
from concurrent.futures import Executor
from typing import Any

import numpy as np

from ._executors import Lost, dask_workers, local_cpu_count, run_dask, run_executor, run_serial
from ._grid import Layout, block_shape, check_grid, default_chunk_size, function_name
from ._run import NOT_COMPUTED, RAISED, ChunkResult, Task, dumps_function, is_batched
from ._store import Store, output_dims

_EXTRA = 'pip install "rigidbody[sweep]"'


def require(module: str) -> Any:
    """Import an optional dependency of the sweeps, or raise an ImportError saying how to install it."""
    try:
        return importlib.import_module(module)
    except ImportError as exc:
        raise ImportError(f"rigidbody.sweep needs {module!r}, an optional dependency: {_EXTRA}") from exc


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


class _Arrays:
    """The sweep's results in memory, filled chunk by chunk."""

    def __init__(self, layout: Layout, schema: dict[str, tuple[int, ...]] | None) -> None:
        self.layout = layout
        self.status = np.full(layout.shape, NOT_COMPUTED, dtype=np.int64)
        self.message = np.full(layout.shape, "not computed", dtype=object)
        self.outputs: dict[str, np.ndarray] = {}
        if schema is not None:
            self.add_outputs(schema)

    def add_outputs(self, schema: dict[str, tuple[int, ...]]) -> None:
        for name, shp in schema.items():
            self.outputs[name] = np.full(self.layout.shape + shp, np.nan)

    def put(self, res: ChunkResult) -> None:
        sl = self.layout.slices(res.chunk)
        shp = tuple(s.stop - s.start for s in sl)
        self.status[sl] = res.status.reshape(shp)
        msg = np.empty(res.n, dtype=object)
        msg[:] = res.message
        self.message[sl] = msg.reshape(shp)
        for name, arr in self.outputs.items():
            if res.schema is not None and name in res.outputs:
                arr[sl] = res.outputs[name].reshape(shp + arr.shape[len(shp):])

    def lost(self, chunk: int, message: str) -> None:
        sl = self.layout.slices(chunk)
        self.status[sl] = NOT_COMPUTED
        self.message[sl] = message

    def dataset(self, grid: dict[str, np.ndarray], function: str) -> Any:
        xr = require("xarray")
        dims = tuple(grid)
        data: dict[str, Any] = {name: (dims + output_dims(name, arr.shape[len(dims):]), arr)
                                for name, arr in self.outputs.items()}
        data["status"] = (dims, self.status)
        data["message"] = (dims, self.message)
        return xr.Dataset(data, coords=dict(grid), attrs={"function": function})


def _from_store(st: Store, layout: Layout) -> tuple[_Arrays, np.ndarray]:
    """The finished chunks of a store, in memory (the others: not computed); and the flags."""
    arrays = _Arrays(layout, st.outputs)
    done = st.done(layout.n_chunks)
    if done.any():
        mask = np.zeros(layout.shape, dtype=bool)
        for c in np.flatnonzero(done):
            mask[layout.slices(int(c))] = True
        chunks = [int(c) for c in np.flatnonzero(done)]
        arrays.status[mask] = st.read("status", layout, chunks)[mask]
        arrays.message[mask] = st.read("message", layout, chunks).astype(object)[mask]
        for name, arr in arrays.outputs.items():
            arr[mask] = st.read(name, layout, chunks)[mask]
    return arrays, done


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
        once per chunk with 1-D arrays instead. A point whose call raises is recorded (``status`` 1,
        ``message`` with the exception's type and text) and the sweep goes on. On local processes and
        on Dask the function travels pickled (by value when it lives in a script's or notebook's
        ``__main__``).
    grid : mapping of str to 1-D array_like
        Parameter names (valid identifiers) to their values; the sweep runs over the outer product, in
        the given order (the last name varies fastest).
    executor : None, 'processes', 'serial', concurrent.futures.Executor, distributed.Client or str
        ``None`` (default) or ``'processes'``: local worker processes started for this call
        (:class:`concurrent.futures.ProcessPoolExecutor`, spawn, ``max_workers`` of them, by default one
        per CPU; no server); ``'serial'``: in this process; an executor you made (e.g. a
        ``ProcessPoolExecutor`` reused over many sweeps); a ``distributed.Client``, or the address of a
        Dask scheduler (``'tcp://host:8786'``), to run on a Dask cluster. All give the same Dataset.
    store : path, optional
        A directory (a Zarr store, created if missing) where each finished chunk is written as it
        completes. Calling ``sweep`` again with the same function, grid and store computes only the
        chunks not yet there, so an interrupted sweep (Ctrl-C, a killed worker or machine) loses nothing
        finished. A store made by another function (qualified name), over another grid or with other
        outputs is refused (``ValueError``). Its chunk layout wins over ``chunk_size``.
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
        (0 ok, 1 the function raised, a batched function's own positive codes, -1 not computed) and
        ``message`` (str; empty where ok) per point; ``attrs['function']``: the function's name.

    Raises
    ------
    TypeError, ValueError
        For a bad grid, executor, chunk size, or a store that does not match.
    ImportError
        If the optional dependencies are missing (``pip install "rigidbody[sweep]"``).

    Warns
    -----
    RuntimeWarning
        When some chunks were lost (their worker died, or their task failed as a whole): their points
        have status -1; a re-run with the same store computes them.

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
    client = None
    if kind == "address":
        distributed = require("distributed")
        client = distributed.Client(target, set_as_default=False)
        kind, target = "dask", client
    try:
        n_workers = {"serial": 1, "processes": max_workers or local_cpu_count()}.get(kind)
        if n_workers is None:
            n_workers = dask_workers(target) if kind == "dask" else int(
                getattr(target, "_max_workers", None) or local_cpu_count())
        st = Store.open(store, create=True) if store is not None else None
        if st is not None:
            st.check(name, g)
            layout = Layout(shape, st.block)
            arrays, done = _from_store(st, layout)
        else:
            cs = default_chunk_size(n_points, n_workers, fb) if chunk_size is None else chunk_size
            layout = Layout(shape, block_shape(shape, cs))
            arrays, done = _Arrays(layout, None), np.zeros(layout.n_chunks, dtype=bool)
        if st is None and store is not None:
            st = Store.create(store, name, g, layout)
        return _run(func, fb, name, g, layout, arrays, done, st, kind, target, n_workers, progress)
    finally:
        if client is not None:
            client.close()


def _run(func: Any, fb: bool, name: str, g: dict[str, np.ndarray], layout: Layout, arrays: _Arrays,
         done: np.ndarray, st: Store | None, kind: str, target: Any, n_workers: int, progress: bool | None) -> Any:
    names = tuple(g)
    values = list(g.values())
    blob = b"" if kind == "serial" else dumps_function(func)

    def tasks() -> Iterator[Task]:
        for c in range(layout.n_chunks):
            if not done[c]:
                sl = layout.slices(c)
                yield Task(c, blob, fb, names, tuple(v[s] for v, s in zip(values, sl)))

    if kind == "serial":
        results = run_serial(func, tasks())
    elif kind == "dask":
        results = run_dask(target, tasks())
    else:
        results = run_executor(target, n_workers, tasks())

    show = sys.stderr.isatty() if progress is None else progress
    bar = None
    if show:
        tqdm = require("tqdm")
        initial = int(sum(layout.size(int(c)) for c in np.flatnonzero(done)))
        bar = tqdm.tqdm(total=math.prod(layout.shape), initial=initial, unit="pt", file=sys.stderr,
                        desc=f"sweep {name.rsplit('.', 1)[-1][:30]}", dynamic_ncols=True)
    schema = st.outputs if st is not None else None
    confirmed = st is None or schema is None
    lost: list[Lost] = []
    try:
        for res in results:
            if isinstance(res, Lost):
                lost.append(res)
                arrays.lost(res.chunk, f"not computed: {res.reason}")
                continue
            if res.schema is not None:
                if schema is None:
                    schema = res.schema
                    arrays.add_outputs(schema)
                    if st is not None:
                        st.set_outputs(schema, layout)
                elif res.schema != schema:
                    if not confirmed and st is not None:
                        st.check_outputs(res.schema, name)
                    _refuse_outputs(res, schema)
                confirmed = True
            arrays.put(res)
            if st is not None:
                st.write(res, layout)
            if bar is not None:
                bar.update(res.n)
                failed = int(np.count_nonzero((arrays.status != 0) & (arrays.status != NOT_COMPUTED)))
                if failed:
                    bar.set_postfix(failed=failed, refresh=False)
    finally:
        close = getattr(results, "close", None)
        if close is not None:
            close()
        if bar is not None:
            bar.close()
    if lost:
        n_lost = sum(layout.size(x.chunk) for x in lost)
        hint = ("run the same sweep again with the same store to compute them" if st is not None
                else "pass store=PATH to keep the finished chunks across runs")
        warnings.warn(f"{n_lost} of {math.prod(layout.shape)} points were not computed ({lost[0].reason}); "
                      f"their status is -1: {hint}", RuntimeWarning, stacklevel=3)
    return arrays.dataset(g, name)


def _refuse_outputs(res: ChunkResult, schema: dict[str, tuple[int, ...]]) -> None:
    """A chunk whose points return other outputs than the sweep's: its good points become failures."""
    bad = res.status == 0
    res.status[bad] = RAISED
    for i in np.flatnonzero(bad):
        res.message[i] = (f"ValueError: the outputs {res.schema} differ from those of the other points {schema} "
                          "(a sweep's function returns the same names and shapes at every point)")
    res.schema = None
    res.outputs = {}


def load(store: str | os.PathLike[str]) -> Any:
    """The Dataset of a sweep store as it stands (finished chunks; the other points have status -1).

    Works while a sweep is writing the store (from another process), and on a store whose sweep was
    interrupted.

    Parameters
    ----------
    store : path
        A store written by :func:`sweep`.

    Returns
    -------
    xarray.Dataset
        As :func:`sweep` returns it; points of unfinished chunks have status -1, message
        ``'not computed'`` and NaN outputs.
    """
    st = Store.open(store, create=False)
    if st is None:
        raise FileNotFoundError(f"no sweep store at {os.fspath(store)!r}")
    g = {n: st.coordinate(n) for n in st.meta["grid"]}
    layout = Layout(tuple(v.size for v in g.values()), st.block)
    arrays, _ = _from_store(st, layout)
    return arrays.dataset(g, st.meta["function"])
