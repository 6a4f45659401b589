"""Checks shared by the sweep tests: the grid of the store tests, its reference Dataset, resuming a sweep."""

from __future__ import annotations

import itertools
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import sweep_testlib as lib
import xarray as xr

from rigidbody.sweep import NOT_COMPUTED, load, sweep

A = np.arange(8.0)
B = np.array([0.0, -1.0, 0.5])
GRID = {"a": A, "b": B}
HERE = Path(__file__).resolve().parent
SRC = Path(__file__).resolve().parents[2] / "src"


def tag(a: float, b: float) -> str:
    return f"a={float(a)!r}_b={float(b)!r}"  # as lib.record_call names a call


def reference() -> xr.Dataset:
    return sweep(lib.poly, GRID, executor="serial", progress=False, chunk_size=3)


def same_results(ds: xr.Dataset, ref: xr.Dataset) -> None:
    xr.testing.assert_identical(ds.drop_attrs(), ref.drop_attrs())


def stored_points(store: Path) -> set[str]:
    part = load(store)
    done = part.status.values != NOT_COMPUTED
    return {tag(a, b) for (i, a), (j, b) in itertools.product(enumerate(A), enumerate(B)) if done[i, j]}


def calls_after(calls: Path, before: set[str]) -> list[str]:
    return sorted(p.name.split("__")[0] for p in calls.iterdir() if p.name not in before)


def resume(store: Path, calls: Path, func, in_flight: int = 0, stored_only: bool = False, **kw) -> xr.Dataset:
    """Resume a sweep and check that it computes exactly the points not finished before (a call is recorded
    when the function returns), except at most ``in_flight`` points: a run killed from outside at an arbitrary
    moment may end a process between a point's return and the record the sweep makes of it (a microsecond
    window; one per process computing). ``stored_only``: exactly the points the store does not hold."""
    finished = stored_points(store) if stored_only else set(lib.calls(str(calls)))
    all_points = {tag(a, b) for a, b in itertools.product(A, B)}
    assert finished and finished != all_points, "the interruption should leave a partial sweep"
    before = {p.name for p in calls.iterdir()}
    ds = sweep(func, GRID, store=store, progress=False, chunk_size=3, **kw)
    second = calls_after(calls, before)
    assert len(second) == len(set(second)), "a point was computed twice in the resumed run"
    again = set(second) & finished
    assert len(again) <= in_flight, f"finished points computed again: {sorted(again)}"
    assert set(second) - again == all_points - finished, "the resumed run must compute exactly the missing points"
    same_results(ds, reference())
    return ds


def run_python(code: str) -> subprocess.Popen:
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(SRC), str(HERE), os.environ.get("PYTHONPATH", "")]))
    return subprocess.Popen([sys.executable, "-c", code], env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)


def wait_for_calls(calls: Path, n: int, proc: subprocess.Popen, timeout: float = 60.0) -> None:
    t0 = time.monotonic()
    while len(list(calls.iterdir())) < n:
        assert proc.poll() is None, proc.communicate()
        assert time.monotonic() - t0 < timeout
        time.sleep(0.02)


def quiet(calls: Path, for_s: float = 1.0, timeout: float = 30.0) -> None:
    """Wait until no call file appears for ``for_s`` seconds (workers that outlive a killed parent finish)."""
    t0 = time.monotonic()
    n, since = -1, time.monotonic()
    while time.monotonic() - since < for_s:
        m = len(list(calls.iterdir()))
        if m != n:
            n, since = m, time.monotonic()
        assert time.monotonic() - t0 < timeout
        time.sleep(0.05)
