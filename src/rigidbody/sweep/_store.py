"""The store of a sweep: a Zarr (v3) group on the local file system, written chunk by chunk.

Layout (``xarray.open_zarr(path)`` reads it as the sweep's Dataset, with the points not yet computed at
their fill values):

* one array per grid dimension (its coordinate), one per output (dims: the grid's, then
  ``<output>_dim_<i>`` for array outputs; fill NaN), ``status`` (fill -1 = not computed) and ``message``;
  every array is chunked by the sweep's blocks, so a chunk of the sweep is exactly one Zarr chunk of each;
* a sub-group ``sweep`` (ignored by xarray) with the sweep's identity in its attributes (function, grid
  names, block shape, outputs) and the array ``done``: one flag per grid point (the grid's shape, chunked as
  the data), set only after the point's data are written and flushed to disk (fsync). A point without its
  flag is computed again, so a write cut short (Ctrl-C, a killed process, a crashed machine) is never read
  as complete; a data chunk that cannot be read counts as not done, whatever its flags say;
* ``sweep/journal/``: the journals of the tasks in flight (see ``_results``), read by the next sweep when the
  sweeping process was killed before writing their points;
* ``sweep/lock``: the lock that keeps a second sweep out while one writes the store (``_lock``).
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path
from typing import Any

import numpy as np

from ._deps import require
from ._grid import Layout
from ._lock import LOCK_PATH
from ._results import NOT_COMPUTED

FORMAT = "rigidbody.sweep"
VERSION = 2


def _zarr() -> Any:
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
    @staticmethod
    def check_path(path: Any) -> Path:
        """``path`` as a Path, if a store is or can be there (nothing, an empty directory, a sweep store)."""
        p = Path(os.fspath(path)).expanduser()
        if p.exists() and not (p / "sweep" / "zarr.json").is_file():
            if not p.is_dir() or not _nothing_but_a_lock(p):
                raise ValueError(f"store {str(p)!r} exists and is not a sweep store (no 'sweep' group): "
                                 "choose another path")
        return p

    @classmethod
    def open(cls, path: Any, *, create: bool) -> Store | None:
        """The store at ``path``, or None if there is none (and ``create`` is False: nothing is written)."""
        zarr = _zarr()
        p = cls.check_path(path)
        if not (p / "sweep" / "zarr.json").is_file():
            return None  # nothing, or an empty directory: a store can be made there
        group = zarr.open_group(str(p), mode="a" if create else "r")
        meta = dict(group["sweep"].attrs)
        if meta.get("format") != FORMAT:
            raise ValueError(f"store {str(p)!r} is not a sweep store (format {meta.get('format')!r})")
        if meta.get("version") != VERSION:
            raise ValueError(f"store {str(p)!r} has format version {meta.get('version')!r}; this rigidbody "
                             f"reads version {VERSION} (per-point done flags): it cannot resume that store; pass a "
                             "new store path to sweep again")
        return cls(p, group, meta)

    @classmethod
    def create(cls, path: Any, function: str, grid: dict[str, np.ndarray], layout: Layout) -> Store:
        zarr = _zarr()
        p = Path(os.fspath(path)).expanduser()
        group = zarr.open_group(str(p), mode="a", zarr_format=3)  # "a": keeps the lock file in sweep/
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
        sub.create_array("done", shape=layout.shape, chunks=layout.block, dtype="int8", fill_value=0,
                         dimension_names=dims)
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
        """Make the output arrays, then record the outputs (arrays left by a crash in between: made again)."""
        dims = list(self.meta["grid"])
        for name, shp in schema.items():
            self.group.create_array(name, shape=layout.shape + shp, chunks=layout.block + shp, dtype="float64",
                                    fill_value=np.nan, dimension_names=dims + list(output_dims(name, shp)),
                                    overwrite=True)
        self.meta["outputs"] = {k: list(v) for k, v in schema.items()}
        self.group["sweep"].attrs["outputs"] = self.meta["outputs"]

    # ------------------------------------------------------------------------------------------ points
    @property
    def journal_dir(self) -> Path:
        return self.path.absolute() / "sweep" / "journal"  # absolute: the workers' paths

    def journals(self) -> list[tuple[Path, int]]:
        """The journals left in the store, with their chunks (a journal is named ``<chunk>-<id>.jnl``)."""
        d = self.journal_dir
        found = sorted(d.glob("*.jnl")) if d.is_dir() else []
        return [(q, int(q.name.split("-", 1)[0])) for q in found if q.name.split("-", 1)[0].isdigit()]

    def done(self, layout: Layout) -> np.ndarray:
        """The flags of the finished points (a flag that cannot be read counts as not finished)."""
        return self.read("done", layout, np.ones(layout.shape, dtype=bool), group=self.group["sweep"]).astype(bool)

    def read(self, name: str, layout: Layout, done: np.ndarray, group: Any = None) -> np.ndarray:
        """An array of the store; a chunk that cannot be read (torn by a crash) is dropped from ``done``."""
        arr = (self.group if group is None else group)[name]
        try:
            return np.asarray(arr[...])
        except Exception:  # read chunk by chunk; those that fail keep the fill value and are not done
            full = np.full(arr.shape, arr.fill_value, dtype=arr.dtype if arr.dtype.kind in "biuf" else object)
            for c in range(layout.n_chunks):
                sl = layout.slices(c)
                if done[sl].any():
                    try:
                        full[sl] = np.asarray(arr[sl])
                    except Exception:
                        done[sl] = False
            return full

    def write(self, layout: Layout, chunk: int, index: np.ndarray, values: dict[str, Any]) -> None:
        """Write points of one chunk (flat positions ``index`` in it): their data, flushed to disk, then their flags.

        ``values`` maps ``status``, ``message`` and the outputs to one row per point. A chunk written in part
        is read, completed and written whole (zarr writes a chunk file whole, by a rename); if its old data
        cannot be read, the flags of its other points are cleared (they are computed again).
        """
        sl = layout.slices(chunk)
        shape = layout.block_of(chunk)
        whole = index.size == math.prod(shape)
        intact = True
        files = []
        for name, rows in values.items():
            arr = self.group[name]
            block, ok = self._block(arr, sl, shape, whole)
            intact &= ok
            flat = block.reshape((-1, *block.shape[len(shape):]))
            flat[index] = rows
            arr[sl] = np.asarray(block, dtype=str) if name == "message" else block
            files.append(self._chunk_file(name, layout, chunk, arr.ndim - len(shape)))
        for f in files:
            _fsync(f)
        done = self.group["sweep"]["done"]
        flags, ok = self._block(done, sl, shape, whole or not intact)
        flags.reshape(-1)[index] = 1
        done[sl] = flags
        key = self._chunk_file("sweep/done", layout, chunk, 0)
        _fsync(key)
        _fsync(key.parent)

    @staticmethod
    def _block(arr: Any, sl: tuple[slice, ...], shape: tuple[int, ...], fresh: bool) -> tuple[np.ndarray, bool]:
        """The chunk's current data (fill values if ``fresh``, or if they cannot be read: then False)."""
        full_shape = shape + tuple(arr.shape[len(shape):])
        dtype = object if arr.dtype.kind not in "biuf" else arr.dtype
        if not fresh:
            try:
                current = np.asarray(arr[sl])
                return (np.array(current.tolist(), dtype=object) if dtype is object else current.copy()), True
            except Exception:
                pass
        return np.full(full_shape, arr.fill_value, dtype=dtype), fresh

    def _chunk_file(self, name: str, layout: Layout, chunk: int, extra: int) -> Path:
        return self.path.joinpath(name, "c", *(str(i) for i in (*layout.index(chunk), *(0,) * extra)))


def _nothing_but_a_lock(p: Path) -> bool:
    """An empty directory, or one that holds only the lock of a store being made."""
    entries = list(p.iterdir())
    sub = p / LOCK_PATH[0]
    return not entries or (entries == [sub] and sub.is_dir()
                           and [q.name for q in sub.iterdir()] in ([], [LOCK_PATH[1]]))


def _coord_dtype(values: np.ndarray) -> Any:
    return str if values.dtype.kind == "U" else values.dtype


def _fmt(schema: dict[str, tuple[int, ...]]) -> str:
    return json.dumps({k: list(v) for k, v in schema.items()})
