"""The store of a sweep: a Zarr (v3) group on the local file system, written chunk by chunk.

Layout (``xarray.open_zarr(path)`` reads it as the sweep's Dataset, with the points not yet computed at
their fill values):

* one array per grid dimension (its coordinate), one per output (dims: the grid's, then
  ``<output>_dim_<i>`` for array outputs; fill NaN), ``status`` (fill -1 = not computed) and ``message``;
  every array is chunked by the sweep's blocks, so a chunk of the sweep is exactly one Zarr chunk of each;
* a sub-group ``sweep`` (ignored by xarray) with the sweep's identity in its attributes (function, grid
  names, block shape, outputs) and the array ``done``: one flag per chunk, written only after the chunk's
  data are written and flushed to disk (fsync). A chunk without its flag is computed again, so a write
  cut short (Ctrl-C, a killed process, a crashed machine) is never read as complete.
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

import numpy as np

from ._grid import Layout
from ._run import NOT_COMPUTED, ChunkResult

FORMAT = "rigidbody.sweep"
VERSION = 1


def _zarr() -> Any:
    from ._api import require

    return require("zarr")


def _fsync(path: Path) -> None:
    try:
        fd = os.open(path, os.O_RDONLY)
    except OSError:  # a chunk equal to the fill value is not written at all
        return
    try:
        os.fsync(fd)
    except OSError:  # pragma: no cover - a file system without fsync on directories
        pass
    finally:
        os.close(fd)


def output_dims(name: str, shape: tuple[int, ...]) -> tuple[str, ...]:
    return tuple(f"{name}_dim_{i}" for i in range(len(shape)))


class Store:
    """An open sweep store (see the module docstring)."""

    def __init__(self, path: Path, group: Any, meta: dict[str, Any]) -> None:
        self.path = path
        self.group = group
        self.meta = meta

    # ---------------------------------------------------------------------------------------- opening
    @classmethod
    def open(cls, path: Any, *, create: bool) -> Store | None:
        """The store at ``path``, or None if there is none (and ``create`` is False: nothing is written)."""
        zarr = _zarr()
        p = Path(os.fspath(path)).expanduser()
        if not p.exists():
            return None
        if not (p / "sweep" / "zarr.json").is_file():
            if p.is_dir() and not any(p.iterdir()):
                return None  # an empty directory: a store can be made there
            raise ValueError(f"store {str(p)!r} exists and is not a sweep store (no 'sweep' group): "
                             "choose another path")
        group = zarr.open_group(str(p), mode="a" if create else "r")
        meta = dict(group["sweep"].attrs)
        if meta.get("format") != FORMAT:
            raise ValueError(f"store {str(p)!r} is not a sweep store (format {meta.get('format')!r})")
        if meta.get("version") != VERSION:
            raise ValueError(f"store {str(p)!r} has format version {meta.get('version')!r}; this rigidbody "
                             f"reads version {VERSION}")
        return cls(p, group, meta)

    @classmethod
    def create(cls, path: Any, function: str, grid: dict[str, np.ndarray], layout: Layout) -> Store:
        zarr = _zarr()
        p = Path(os.fspath(path)).expanduser()
        group = zarr.open_group(str(p), mode="w", zarr_format=3)
        for name, values in grid.items():
            a = group.create_array(name, shape=values.shape, chunks=values.shape, dtype=_coord_dtype(values),
                                   dimension_names=[name])
            a[:] = values
        dims = list(grid)
        group.create_array("status", shape=layout.shape, chunks=layout.block, dtype="int64",
                           fill_value=NOT_COMPUTED, dimension_names=dims)
        group.create_array("message", shape=layout.shape, chunks=layout.block, dtype=str,
                           fill_value="not computed", dimension_names=dims)
        sub = group.create_group("sweep")
        sub.create_array("done", shape=(layout.n_chunks,), chunks=(1,), dtype="int8", fill_value=0)
        meta = {"format": FORMAT, "version": VERSION, "function": function, "grid": dims,
                "block": list(layout.block), "outputs": None}
        sub.attrs.update(meta)
        return cls(p, group, meta)

    # --------------------------------------------------------------------------------------- identity
    @property
    def block(self) -> tuple[int, ...]:
        return tuple(int(b) for b in self.meta["block"])

    @property
    def outputs(self) -> dict[str, tuple[int, ...]] | None:
        out = self.meta.get("outputs")
        return None if out is None else {k: tuple(int(s) for s in v) for k, v in out.items()}

    def check(self, function: str, grid: dict[str, np.ndarray]) -> None:
        """Refuse a store made by another function or over another grid (ValueError)."""
        where = f"store {str(self.path)!r}"
        if self.meta["function"] != function:
            raise ValueError(f"{where} holds a sweep of {self.meta['function']!r}, not of {function!r}: "
                             "use another store path (or delete this one)")
        if list(self.meta["grid"]) != list(grid):
            raise ValueError(f"{where} holds a sweep over the grid {list(self.meta['grid'])}, not over "
                             f"{list(grid)} (names and order must agree)")
        for name, values in grid.items():
            stored = self.coordinate(name)
            numeric = stored.dtype.kind in "biuf" and values.dtype.kind in "biuf"
            same = stored.shape == values.shape and (
                np.array_equal(stored.astype(float), values.astype(float), equal_nan=True) if numeric
                else stored.dtype.kind == values.dtype.kind and np.array_equal(stored, values))
            if not same:
                raise ValueError(f"{where} holds a sweep with other values of {name!r} ({stored.size} values "
                                 f"from {stored[0]!r} to {stored[-1]!r}); the grid given has {values.size} "
                                 f"from {values[0]!r} to {values[-1]!r}")

    def coordinate(self, name: str) -> np.ndarray:
        """A grid coordinate as stored (strings as a NumPy ``str`` array, whatever zarr returns)."""
        a = np.asarray(self.group[name][:])
        return np.array(a.tolist(), dtype=str) if a.dtype.kind in "OTU" else a

    def check_outputs(self, schema: dict[str, tuple[int, ...]], function: str) -> None:
        stored = self.outputs
        if stored is not None and stored != schema:
            raise ValueError(f"store {str(self.path)!r} holds the outputs {_fmt(stored)} of {function!r}; the "
                             f"function now returns {_fmt(schema)}: use another store path (or delete this one)")

    def set_outputs(self, schema: dict[str, tuple[int, ...]], layout: Layout) -> None:
        dims = list(self.meta["grid"])
        for name, shp in schema.items():
            self.group.create_array(name, shape=layout.shape + shp, chunks=layout.block + shp, dtype="float64",
                                    fill_value=np.nan, dimension_names=dims + list(output_dims(name, shp)))
        self.meta["outputs"] = {k: list(v) for k, v in schema.items()}
        self.group["sweep"].attrs["outputs"] = self.meta["outputs"]

    # ------------------------------------------------------------------------------------------ chunks
    def done(self, n_chunks: int) -> np.ndarray:
        """The flags of the finished chunks (a flag that cannot be read counts as not finished)."""
        arr = self.group["sweep"]["done"]
        try:
            return np.asarray(arr[:]).astype(bool)
        except Exception:  # a flag file cut short by a crash: read the flags one by one
            flags = np.zeros(n_chunks, dtype=bool)
            for c in range(n_chunks):
                try:
                    flags[c] = bool(arr[c])
                except Exception:
                    flags[c] = False
            return flags

    def write(self, res: ChunkResult, layout: Layout) -> None:
        """Write one chunk's data, flush them to disk, then set its flag (and flush that)."""
        sl = layout.slices(res.chunk)
        shape = tuple(s.stop - s.start for s in sl)
        names = ["status", "message"]
        self.group["status"][sl] = res.status.reshape(shape)
        self.group["message"][sl] = np.asarray(res.message, dtype=str).reshape(shape)
        for name, values in res.outputs.items():
            if res.schema is not None and name in res.schema:
                self.group[name][sl] = values.reshape(shape + values.shape[1:])
                names.append(name)
        idx = layout.index(res.chunk)
        outs = self.outputs or {}
        for name in names:
            extra = (0,) * len(outs.get(name, ()))
            key = "/".join(str(i) for i in (*idx, *extra))
            _fsync(self.path / name / "c" / key)
        self.group["sweep"]["done"][res.chunk] = 1
        _fsync(self.path / "sweep" / "done" / "c" / str(res.chunk))
        _fsync(self.path / "sweep" / "done" / "c")

    def read(self, name: str, layout: Layout, chunks: list[int]) -> np.ndarray:
        """An array of the store, of which only the given (finished) chunks are to be trusted."""
        arr = self.group[name]
        try:
            return np.asarray(arr[...])
        except Exception:  # an unfinished chunk torn by a crash: read the finished ones only
            out = np.asarray(arr[tuple(slice(0, 1) for _ in arr.shape)])
            full = np.empty(arr.shape, dtype=out.dtype)
            for c in chunks:
                sl = layout.slices(c)
                full[sl] = np.asarray(arr[sl])
            return full


def _coord_dtype(values: np.ndarray) -> Any:
    return str if values.dtype.kind == "U" else values.dtype


def _fmt(schema: dict[str, tuple[int, ...]]) -> str:
    return json.dumps({k: list(v) for k, v in schema.items()})
