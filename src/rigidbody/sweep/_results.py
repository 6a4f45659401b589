"""What a sweep's task sends back: the results of some points of one chunk; and the journal they are recorded in.

Imported by the worker processes (local or Dask): it needs NumPy only.

A task's *journal* is a file to which the process computing the task appends each point as it finishes (one
length-prefixed pickle per record, each written with a single ``os.write``). The file is created once the
function is loaded, so the sweeping process can tell, when a worker dies, whether it died loading the function
(no file), which points it had finished (the records) and so which point it was computing (the first after
them); and a sweep that resumes after its process was killed finds there the points finished since the last
write to its store.
"""

from __future__ import annotations

import os
import pickle
import struct
from dataclasses import dataclass, field
from typing import Any

import numpy as np

#: status of a point: computed
OK = 0
#: status of a point whose function raised (its message has the exception)
RAISED = 1
#: status of a point not computed (its worker died computing it, a lost task, or missing from a partial store)
NOT_COMPUTED = -1

Schema = dict[str, tuple[int, ...]]


def describe(exc: BaseException) -> str:
    """The message of a point whose function raised."""
    if isinstance(exc, SystemExit):
        return f"SystemExit: the function called sys.exit({exc.code!r})"
    text = str(exc)
    return f"{type(exc).__name__}: {text}" if text else type(exc).__name__


def schema_of(outputs: dict[str, Any], lead: int = 0) -> Schema:
    """Output names and shapes (without the ``lead`` leading axes) of a point's or a batch's outputs."""
    return {k: () if type(v) is float else tuple(int(s) for s in np.shape(v)[lead:]) for k, v in outputs.items()}


@dataclass
class Group:
    """Points of a result that succeeded with the same outputs: their rows in the result, and the outputs."""

    schema: Schema
    rows: np.ndarray
    outputs: dict[str, np.ndarray]


@dataclass
class ChunkResult:
    """Results of some points of one chunk (flat positions in the chunk, C order): status, message, outputs.

    The points that succeeded are in ``groups``, one per set of output names and shapes (one, unless the
    function returns different outputs at different points). ``journal`` is the file the points were recorded
    in while they were computed (deleted by the sweeping process once they are written).
    """

    chunk: int
    index: np.ndarray
    status: np.ndarray
    message: list[str]
    groups: list[Group] = field(default_factory=list)
    journal: str | None = None

    @property
    def n(self) -> int:
        return int(self.index.size)

    def select(self, keep: np.ndarray) -> ChunkResult:
        """The result restricted to the points where ``keep`` (a mask over ``index``) is true."""
        new_row = np.cumsum(keep) - 1
        groups = []
        for g in self.groups:
            k = keep[g.rows]
            if k.any():
                groups.append(Group(g.schema, new_row[g.rows[k]], {n: v[k] for n, v in g.outputs.items()}))
        return ChunkResult(self.chunk, self.index[keep], self.status[keep],
                           [m for m, k in zip(self.message, keep) if k], groups, self.journal)


def pack(chunk: int, index: np.ndarray, rows: list[dict[str, Any] | None], status: np.ndarray,
         message: list[str]) -> ChunkResult:
    """Stack per-point outputs (``None`` for a point that did not succeed), one group per set of outputs."""
    members: dict[tuple[tuple[str, tuple[int, ...]], ...], tuple[list[int], list[dict[str, Any]]]] = {}
    for i, row in enumerate(rows):
        if row is not None:  # outputs are floats or float arrays (see _run._as_outputs)
            key = tuple([(k, () if type(v) is float else v.shape) for k, v in row.items()])
            at, got = members.setdefault(key, ([], []))
            at.append(i)
            got.append(row)
    groups = []
    for key, (at, got) in members.items():
        outputs = {name: np.array([r[name] for r in got], dtype=float) if shp == ()
                   else np.stack([r[name] for r in got]).astype(float) for name, shp in key}
        groups.append(Group(dict(key), np.array(at, dtype=np.int64), outputs))
    return ChunkResult(chunk, np.asarray(index, dtype=np.int64), status, message, groups)


def merge(chunk: int, parts: list[ChunkResult]) -> ChunkResult:
    """Results of disjoint sets of points of one chunk as one result."""
    offsets = np.cumsum([0] + [p.n for p in parts])
    groups = [Group(g.schema, g.rows + off, g.outputs) for p, off in zip(parts, offsets) for g in p.groups]
    index = np.concatenate([p.index for p in parts]) if parts else np.zeros(0, dtype=np.int64)
    status = np.concatenate([p.status for p in parts]) if parts else np.zeros(0, dtype=np.int64)
    return ChunkResult(chunk, index, status, [m for p in parts for m in p.message], groups)


# ----------------------------------------------------------------------------------------------- journals
_LENGTH = struct.Struct("<Q")


class Journal:
    """Appends a task's finished points to its journal file (nothing when ``path`` is None)."""

    def __init__(self, path: str | None) -> None:
        flags = os.O_WRONLY | os.O_CREAT | os.O_APPEND | getattr(os, "O_BINARY", 0)  # O_BINARY: Windows
        self.fd = None if path is None else os.open(path, flags, 0o644)

    def _add(self, record: Any) -> None:
        if self.fd is not None:
            data = pickle.dumps(record, protocol=pickle.HIGHEST_PROTOCOL)
            os.write(self.fd, _LENGTH.pack(len(data)) + data)

    def point(self, i: int, status: int, message: str, row: dict[str, Any] | None) -> None:
        self._add((int(i), int(status), message, row))

    def result(self, res: ChunkResult) -> None:
        self._add(res)

    def close(self) -> None:
        if self.fd is not None:
            os.close(self.fd)
            self.fd = None


def read_journal(path: str | os.PathLike[str], chunk: int) -> ChunkResult | None:
    """The points a journal holds, as one result (None if there is no such file).

    A record cut short (its process killed while writing it) ends the reading: the records before it are
    whole, since each was written by one ``os.write`` after the previous one had returned.
    """
    try:
        with open(path, "rb") as f:
            data = f.read()
    except FileNotFoundError:
        return None
    parts: list[ChunkResult] = []
    points: list[tuple[int, int, str, dict[str, Any] | None]] = []
    pos = 0
    while pos + _LENGTH.size <= len(data):
        (size,) = _LENGTH.unpack_from(data, pos)
        if pos + _LENGTH.size + size > len(data):
            break
        try:
            record = pickle.loads(data[pos + _LENGTH.size:pos + _LENGTH.size + size])  # written by our own tasks
        except Exception:
            break
        pos += _LENGTH.size + size
        if isinstance(record, ChunkResult):
            parts.append(record)
        else:
            points.append(record)
    if points:
        index = np.array([p[0] for p in points], dtype=np.int64)
        status = np.array([p[1] for p in points], dtype=np.int64)
        parts.append(pack(chunk, index, [p[3] for p in points], status, [p[2] for p in points]))
    res = merge(chunk, parts)
    res.journal = os.fspath(path)
    return res
