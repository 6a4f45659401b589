"""The grid of a sweep: validation, the chunk layout and the points of one chunk."""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from dataclasses import dataclass
from functools import cached_property, partial
from typing import Any

import numpy as np

#: names a grid or an output may not take (the Dataset's own variables)
RESERVED = ("status", "message")


def check_grid(grid: Any) -> dict[str, np.ndarray]:
    """The grid as an ordered dict of 1-D arrays, or a clear TypeError/ValueError."""
    if not isinstance(grid, Mapping):
        raise TypeError(f"grid must be a mapping of parameter names to 1-D arrays, got {type(grid).__name__}")
    if not grid:
        raise ValueError("grid must name at least one parameter")
    out: dict[str, np.ndarray] = {}
    for name, values in grid.items():
        if not isinstance(name, str) or not name.isidentifier():
            raise TypeError(f"grid names must be valid Python identifiers (func is called as func(**point)), "
                            f"got {name!r}")
        if name in RESERVED:
            raise ValueError(f"grid name {name!r} is reserved for the sweep's own variables {RESERVED}")
        a = np.asarray(values)
        if a.ndim != 1:
            raise ValueError(f"grid[{name!r}] must be a 1-D array, got shape {a.shape}")
        if a.size == 0:
            raise ValueError(f"grid[{name!r}] is empty")
        if a.dtype.kind not in "biufU":
            raise TypeError(f"grid[{name!r}] must hold numbers or strings, got dtype {a.dtype}")
        _refuse_duplicates(name, a)
        out[name] = a
    return out


def _refuse_duplicates(name: str, a: np.ndarray) -> None:
    """A value given twice would name two points of the Dataset alike (``ds.sel`` could not tell them apart)."""
    _, inverse, counts = np.unique(a, return_inverse=True, return_counts=True)
    if np.any(counts > 1):
        where = np.flatnonzero(inverse == int(np.flatnonzero(counts > 1)[0]))
        raise ValueError(f"grid[{name!r}] holds the value {a[where[0]].item()!r} more than once (at positions "
                         f"{where.tolist()}): each value of a grid parameter must be distinct")


def default_chunk_size(n_points: int, n_workers: int, is_batched: bool) -> int:
    """At most 100 points (10^4 for a batched function), and about four chunks per worker or more."""
    base = 10_000 if is_batched else 100
    return max(1, min(base, math.ceil(n_points / (4 * max(1, n_workers)))))


def block_shape(shape: tuple[int, ...], chunk_size: int) -> tuple[int, ...]:
    """A block of at most ``chunk_size`` grid points, contiguous in C order.

    The trailing dimensions are taken whole while they fit, the next one in part, the leading ones by one.
    """
    if isinstance(chunk_size, bool) or not isinstance(chunk_size, (int, np.integer)) or chunk_size < 1:
        raise ValueError(f"chunk_size must be an integer >= 1, got {chunk_size!r}")
    block = [1] * len(shape)
    room = int(chunk_size)
    for d in range(len(shape) - 1, -1, -1):
        take = min(shape[d], room)
        block[d] = take
        room //= take
        if take < shape[d] or room <= 1:
            break
    return tuple(block)


@dataclass(frozen=True)
class Layout:
    """The grid cut into blocks: chunk ``c`` (a flat index in C order over the block grid)."""

    shape: tuple[int, ...]
    block: tuple[int, ...]

    @cached_property
    def n_chunks_per_dim(self) -> tuple[int, ...]:
        return tuple(-(-s // b) for s, b in zip(self.shape, self.block))

    @property
    def n_chunks(self) -> int:
        return math.prod(self.n_chunks_per_dim)

    def index(self, c: int) -> tuple[int, ...]:
        return tuple(int(i) for i in np.unravel_index(c, self.n_chunks_per_dim))

    def slices(self, c: int) -> tuple[slice, ...]:
        return tuple(slice(i * b, min((i + 1) * b, s)) for i, b, s in zip(self.index(c), self.block, self.shape))

    def size(self, c: int) -> int:
        return math.prod(s.stop - s.start for s in self.slices(c))

    def block_of(self, c: int) -> tuple[int, ...]:
        """The shape of chunk ``c`` (the last block along a dimension may be cut short)."""
        return tuple(s.stop - s.start for s in self.slices(c))

    def flat(self, c: int, local: np.ndarray) -> np.ndarray:
        """Grid positions (flat, C order over the grid) of the points ``local`` (flat, C order in the chunk)."""
        sl = self.slices(c)
        idx = np.unravel_index(np.asarray(local, dtype=np.int64), tuple(s.stop - s.start for s in sl))
        flat = idx[-1] + sl[-1].start
        stride = 1
        for d in range(len(sl) - 2, -1, -1):
            stride *= self.shape[d + 1]
            flat = flat + (idx[d] + sl[d].start) * stride
        return flat


def chunk_points(coords: list[np.ndarray]) -> list[np.ndarray]:
    """The points of a block (its coordinate slices, one per dimension) as flat arrays, C order."""
    mesh = np.meshgrid(*coords, indexing="ij")
    return [m.ravel() for m in mesh]


_ADDRESS = re.compile(r" at 0x[0-9a-fA-F]+")


def function_label(func: Any) -> str:
    """A short label of a sweep's function for its progress bar: the function's own name (a partial: the
    wrapped function's, marked ``partial``).

    Examples
    --------
    >>> from functools import partial
    >>> function_label(partial(function_name, 1)), function_label(function_name)
    ('function_name (partial)', 'function_name')
    """
    inner, wrapped = func, False
    while isinstance(inner, partial):
        inner, wrapped = inner.func, True
    name = getattr(inner, "__name__", None) or type(inner).__name__
    return f"{name} (partial)" if wrapped else name


def function_name(func: Any) -> str:
    """The identity of a sweep's function: its qualified name (a partial: with its bound arguments).

    Memory addresses in the reprs of bound arguments are dropped (they change from run to run).
    """
    if isinstance(func, partial):
        parts = [function_name(func.func)]
        parts += [repr(a) for a in func.args]
        parts += [f"{k}={v!r}" for k, v in sorted(func.keywords.items())]
        return _ADDRESS.sub("", f"functools.partial({', '.join(parts)})")
    module = getattr(func, "__module__", None) or type(func).__module__
    qualname = getattr(func, "__qualname__", None) or type(func).__qualname__
    return f"{module}.{qualname}"
