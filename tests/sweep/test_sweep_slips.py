"""Resuming a sweep whose chunks cut the grid along two dimensions (public behaviour only).

Slip caught: the on-disk record of which chunks are finished losing its meaning when the chunks form a grid of
more than one dimension (a flag written under another numbering of the chunks than the one read back). With the
chunks cut along one dimension only every numbering agrees, which is all the other store tests use.
"""

from __future__ import annotations

import itertools
import os
from functools import partial
from pathlib import Path

import numpy as np
import pytest

from rigidbody.sweep import NOT_COMPUTED, load, sweep

pytest.importorskip("zarr")  # stores need zarr-python 3

A = np.array([0.0, 1.0, 2.0, 3.0])
B = np.array([10.0, 20.0, 30.0, 40.0, 50.0, 60.0])
GRID = {"a": A, "b": B}
# chunks of at most 4 points: one value of a times four of b, then the remaining two: a 4 x 2 grid of chunks
CHUNK = 4
# the first point of the chunk (a = 2, b = 50..60): the first run finishes the chunks before it, in the grid's
# order, and is interrupted as that chunk starts (no point computed and lost)
STOP = (2.0, 50.0)


def logged(a: float, b: float, *, log: str) -> dict:
    """a + b/100 and a b, each call appended to ``log``; the first visit of STOP raises KeyboardInterrupt (like
    Ctrl-C; "first" told by a marker file next to the log, so the resumed run is the same function)."""
    if (a, b) == STOP:
        try:
            os.close(os.open(f"{log}.interrupted", os.O_CREAT | os.O_EXCL | os.O_WRONLY))
        except FileExistsError:
            pass
        else:
            raise KeyboardInterrupt
    with open(log, "a", encoding="utf-8") as fh:
        fh.write(f"{a!r} {b!r}\n")
    return {"s": a + b / 100.0, "p": a * b}


def _log(path: Path) -> list[tuple[float, float]]:
    if not path.exists():
        return []
    return [tuple(float(x) for x in line.split()) for line in path.read_text().splitlines()]


def test_a_sweep_chunked_along_two_dimensions_resumes_each_point_once(tmp_path):
    log = tmp_path / "calls.log"
    store = tmp_path / "s.zarr"
    f = partial(logged, log=str(log))
    with pytest.raises(KeyboardInterrupt):
        sweep(f, GRID, executor="serial", store=store, progress=False, chunk_size=CHUNK)
    first = _log(log)
    # the first run computed whole chunks up to STOP (rows a = 0, 1 and the first four points of a = 2)...
    order = list(itertools.product(A, B))
    assert first == order[: order.index(STOP)]
    # ... and the store holds exactly those points as finished
    part = load(store)
    stored = {(float(a), float(b)) for (i, a), (j, b) in itertools.product(enumerate(A), enumerate(B))
              if part.status.values[i, j] != NOT_COMPUTED}
    assert stored == set(first)

    ds = sweep(f, GRID, executor="serial", store=store, progress=False, chunk_size=CHUNK)
    calls = _log(log)
    assert sorted(calls) == sorted(order)  # every point computed, each exactly once over the two runs
    assert np.all(ds.status.values == 0)
    Aa, Bb = np.meshgrid(A, B, indexing="ij")
    np.testing.assert_array_equal(ds["s"].values, Aa + Bb / 100.0)  # the same arithmetic: exact
    np.testing.assert_array_equal(ds["p"].values, Aa * Bb)
    # and the store now loads as the finished sweep
    np.testing.assert_array_equal(load(store)["s"].values, ds["s"].values)
