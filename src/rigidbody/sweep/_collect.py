"""The sweep's results in the sweeping process: in memory for the Dataset, written to the store as they come.

The outputs' rule (names and shapes) does not depend on the order in which the tasks finish: the outputs of
a sweep are those of the first point of the run, in grid order, that succeeded. Until that point is known
(every point of the run before it has finished), the points that succeeded are held in memory, and their
journals kept; points that failed are written at once. Then every point that succeeded with other outputs
fails with a message saying so. A store holds the outputs of the sweep that made it: a run whose first
point returns other outputs is refused (the function changed).
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Iterable
from pathlib import Path
from typing import Any

import numpy as np

from ._deps import require
from ._executors import Lost
from ._grid import Layout
from ._results import NOT_COMPUTED, OK, RAISED, ChunkResult, Schema, read_journal
from ._store import Store, output_dims


def _fmt(schema: Schema) -> str:
    return json.dumps({k: list(v) for k, v in schema.items()})


class Results:
    """Status, message and outputs of every point (flat over the grid, C order), and the store they go to."""

    def __init__(self, grid: dict[str, np.ndarray], layout: Layout, store: Store | None, function: str) -> None:
        self.grid, self.layout, self.store, self.function = grid, layout, store, function
        n = math.prod(layout.shape)
        self.status = np.full(n, NOT_COMPUTED, dtype=np.int64)
        self.message = np.full(n, "not computed", dtype=object)
        self.outputs: dict[str, np.ndarray] = {}
        self.pending = np.ones(n, dtype=bool)  # points of this run not finished yet
        self.first_pending = 0
        self.schema: Schema | None = None  # the outputs in memory (and in the store)
        self.anchor: int | None = None  # the run's first point (grid order) that succeeded, once known
        self.held: list[tuple[ChunkResult, np.ndarray]] = []
        self.lost: list[tuple[int, str]] = []
        if store is not None:
            self._load()

    def _load(self) -> None:
        """The finished points of the store: done, readable, with a status (a flag alone does not count)."""
        assert self.store is not None
        st, layout = self.store, self.layout
        done = st.done(layout)
        status = st.read("status", layout, done)
        message = st.read("message", layout, done)
        if st.outputs is not None:
            self._add_outputs(st.outputs)
        values = {name: st.read(name, layout, done) for name in self.outputs}
        done &= status != NOT_COMPUTED
        mask = done.ravel()
        self.status[mask] = status.ravel()[mask]
        self.message[mask] = np.asarray(message, dtype=object).ravel()[mask]
        for name, arr in self.outputs.items():
            arr[mask] = values[name].reshape(arr.shape)[mask]
        self.pending = ~mask

    def _add_outputs(self, schema: Schema) -> None:
        self.schema = schema
        n = math.prod(self.layout.shape)
        self.outputs = {name: np.full((n, *shp), np.nan) for name, shp in schema.items()}

    # ----------------------------------------------------------------------------------------- arriving
    def add(self, res: ChunkResult) -> int:
        """Record a result (its points not already finished); returns how many points it finished."""
        flat = self.layout.flat(res.chunk, res.index)
        keep = self.pending[flat]
        if not keep.all():
            res, flat = res.select(keep), flat[keep]
        ok = np.zeros(res.n, dtype=bool)
        for g in res.groups:
            ok[g.rows] = True
        if self.anchor is not None or not ok.any():
            self._write(res, flat)
            self._forget(res.journal)
        else:
            self._write(res.select(~ok), flat[~ok])  # failures now; successes once the outputs are known
            self.held.append((res.select(ok), flat[ok]))
        self.pending[flat] = False
        self._decide()
        return res.n

    def lose(self, ev: Lost) -> int:
        """Points not computed (status -1; not written to the store, so the next run computes them)."""
        flat = self.layout.flat(ev.chunk, ev.index)
        flat = flat[self.pending[flat]]
        self.status[flat] = NOT_COMPUTED
        self.message[flat] = f"not computed: {ev.reason}"
        self.pending[flat] = False
        if flat.size:
            self.lost.append((int(flat.size), ev.reason))
        self._decide()
        return int(flat.size)

    def replay(self, journals: Iterable[tuple[Path, int]]) -> None:
        """Take in the points of journals left by an earlier run (or by this run's tasks when interrupted)."""
        for path, chunk in journals:
            res = read_journal(path, chunk)
            if res is not None:
                self.add(res)

    def finish(self) -> None:
        """The run is over: a point no result came back for stays not computed; the held points are written."""
        self.pending[:] = False
        self._decide()

    # ------------------------------------------------------------------------------------------ deciding
    def _decide(self) -> None:
        if self.anchor is not None or not self.held:
            return
        first = min(int(flat.min()) for _, flat in self.held)
        p = self.first_pending
        while p < self.pending.size and not self.pending[p]:
            p += 1
        self.first_pending = p
        if p < first:
            return  # a point of the run before it may still succeed
        res, flat = next((r, f) for r, f in self.held if int(f.min()) == first)
        g = next(g for g in res.groups if first in flat[g.rows])
        if self.schema is not None and g.schema != self.schema:
            held, self.held = self.held, []
            for r, _ in held:  # results of a function the store refuses: not kept for a later run
                self._forget(r.journal)
            assert self.store is not None
            self.store.check_outputs(g.schema, self.function)
        self.anchor = first
        if self.schema is None:
            self._add_outputs(g.schema)
            if self.store is not None:
                self.store.set_outputs(g.schema, self.layout)
        held, self.held = self.held, []
        for r, f in held:
            self._write(r, f)
            self._forget(r.journal)

    def _mismatch(self, schema: Schema) -> str:
        assert self.schema is not None and self.anchor is not None
        at = np.unravel_index(self.anchor, self.layout.shape)
        where = ", ".join(f"{n}={v[i].item()!r}" for (n, v), i in zip(self.grid.items(), at))
        return (f"ValueError: the outputs {_fmt(schema)} differ from the sweep's outputs {_fmt(self.schema)}, "
                f"those of the point {where} (a sweep's function returns the same names and shapes at every point)")

    def _write(self, res: ChunkResult, flat: np.ndarray) -> None:
        """Put points in memory and in the store (those that succeeded: with the sweep's outputs, or failed)."""
        if not res.n:
            return
        status = res.status.copy()
        message = np.array(res.message, dtype=object)
        outputs = {name: np.full((res.n, *arr.shape[1:]), np.nan) for name, arr in self.outputs.items()}
        for g in res.groups:
            if g.schema == self.schema:
                for name, values in g.outputs.items():
                    outputs[name][g.rows] = values
            else:
                status[g.rows] = RAISED
                message[g.rows] = self._mismatch(g.schema)
        if self.store is not None:
            self.store.write(self.layout, res.chunk, res.index, {"status": status, "message": message, **outputs})
        self.status[flat] = status
        self.message[flat] = message
        for name, arr in self.outputs.items():
            arr[flat] = outputs[name]

    def _forget(self, journal: str | None) -> None:
        """Delete a journal whose points are written (unless the same journal's points are held)."""
        if journal is not None and all(r.journal != journal for r, _ in self.held):
            try:
                os.unlink(journal)
            except FileNotFoundError:
                pass

    # -------------------------------------------------------------------------------------------- result
    def failed(self) -> int:
        return int(np.count_nonzero((self.status != OK) & (self.status != NOT_COMPUTED)))

    def dataset(self) -> Any:
        xr = require("xarray")
        dims = tuple(self.grid)
        shape = self.layout.shape
        data: dict[str, Any] = {name: (dims + output_dims(name, arr.shape[1:]), arr.reshape(shape + arr.shape[1:]))
                                for name, arr in self.outputs.items()}
        data["status"] = (dims, self.status.reshape(shape))
        data["message"] = (dims, self.message.reshape(shape))
        return xr.Dataset(data, coords=dict(self.grid), attrs={"function": self.function})
