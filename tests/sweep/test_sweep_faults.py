"""Faults: a sweep loses only what it must and computes nothing twice (real processes, real kills; no mock).

A point that exits or raises any BaseException fails alone; a worker that dies costs the point it was
computing; a resumed sweep computes exactly the points not finished; a store is written by one sweep at a
time; the outputs' rule does not depend on which worker finishes first; duplicate grid values are refused.
"""

from __future__ import annotations

import itertools
import os
import re
import signal
import sys
from concurrent.futures import ProcessPoolExecutor
from functools import partial
from pathlib import Path

import numpy as np
import pytest
import sweep_testlib as lib
import xarray as xr
from sweep_checks import GRID, reference, resume, run_python, same_results, tag, wait_for_calls

from rigidbody.sweep import NOT_COMPUTED, RAISED, sweep

pytest.importorskip("zarr")


@pytest.fixture
def calls(tmp_path):
    d = tmp_path / "calls"
    d.mkdir()
    return d


# ----------------------------------------------------------------------------- a point that exits or aborts
def test_sys_exit_and_any_base_exception_fail_their_point_alone_on_every_executor(client):
    ref = reference()
    ours = {"serial": sweep(lib.exiting, GRID, executor="serial", progress=False, chunk_size=3),
            "processes": sweep(lib.exiting, GRID, progress=False, chunk_size=3, max_workers=2),
            "dask": sweep(lib.exiting, GRID, executor=client, progress=False, chunk_size=3)}
    for name, ds in ours.items():
        st, msg = ds.status.values, ds.message.values
        assert st[2, 0] == RAISED and msg[2, 0] == "SystemExit: the function called sys.exit(3)", name
        assert st[3, 2] == RAISED and msg[3, 2] == "Abort: abandoned", name
        others = np.ones(st.shape, dtype=bool)
        others[2, 0] = others[3, 2] = False
        for v in ("status", "message", "s", "p", "v"):  # every other point as in a sweep of poly
            np.testing.assert_array_equal(ds[v].values[others], ref[v].values[others], err_msg=f"{name}: {v}")
    xr.testing.assert_identical(ours["processes"], ours["serial"])
    xr.testing.assert_identical(ours["dask"], ours["serial"])


def test_a_keyboard_interrupt_raised_in_a_worker_fails_its_point_ctrl_c_in_the_sweeping_process_stops():
    f = partial(lib.exiting, interrupt=True)
    ds = sweep(f, GRID, progress=False, chunk_size=3, max_workers=2)  # workers ignore Ctrl-C: the function raised
    assert ds.status.values[1, 2] == RAISED and ds.message.values[1, 2] == "KeyboardInterrupt"
    assert int((ds.status.values == NOT_COMPUTED).sum()) == 0
    with pytest.raises(KeyboardInterrupt):
        sweep(f, GRID, executor="serial", progress=False, chunk_size=3)


# ------------------------------------------------------------------------------------- a worker that dies
GRID_15x20 = {"a": np.arange(15.0), "b": np.linspace(-1.0, 1.0, 20)}


def test_a_worker_killed_mid_chunk_costs_exactly_its_point(calls):
    # a chunk is a row of 20 points; the point (7, b[9]) kills its worker (SIGKILL) at every visit
    kill_at = (7.0, float(GRID_15x20["b"][9]))
    f = partial(lib.killing, calls_dir=str(calls), kill_at=kill_at)
    with pytest.warns(RuntimeWarning, match=r"^1 of 300 points were not computed"):
        ds = sweep(f, GRID_15x20, progress=False, chunk_size=20, max_workers=2)
    lost = ds.status.values == NOT_COMPUTED
    assert lost[7, 9] and lost.sum() == 1
    assert ds.message.values[7, 9] == ("not computed: its worker process died twice while computing this point "
                                       "(killed by signal SIGKILL)")
    assert lib.visits(str(calls)) == 2  # once in its chunk, once alone
    done = lib.calls(str(calls))  # every other point computed exactly once: the 9 before it in its row are kept
    assert len(done) == len(set(done)) == 299
    ref = sweep(lib.poly, GRID_15x20, executor="serial", progress=False)
    for v in ("s", "p", "v"):
        np.testing.assert_array_equal(ds[v].values[~lost], ref[v].values[~lost])


def test_a_worker_killed_at_the_first_point_of_the_first_chunk_costs_that_point_and_resumes(tmp_path, calls):
    # no "__main__ guard" diagnosis: the workers had started; and a resume computes nothing twice. The point
    # ends its process with os._exit (as a compiled library that aborts)
    store = tmp_path / "s.zarr"
    f = partial(lib.killing, calls_dir=str(calls), kill_at=(0.0, 0.0), how="exit")
    for run in (1, 2):
        with pytest.warns(RuntimeWarning, match=r"^1 of 24 points were not computed \(its worker process died twice "
                                                r"while computing this point \(exit code 5\)\)"):
            ds = sweep(f, GRID, store=store, progress=False, chunk_size=3, max_workers=2)
        assert ds.status.values[0, 0] == NOT_COMPUTED and int((ds.status.values == NOT_COMPUTED).sum()) == 1
        assert lib.visits(str(calls)) == 2 * run  # the resume tries only that point (twice) again
        assert sorted(lib.calls(str(calls))) == sorted(tag(a, b) for a, b in itertools.product(*GRID.values())
                                                       if (a, b) != (0.0, 0.0))
    others = ds.status.values != NOT_COMPUTED
    np.testing.assert_array_equal(ds["s"].values[others], reference()["s"].values[others])


def test_a_function_the_workers_cannot_import_is_diagnosed_as_such(tmp_path):
    # pickled by reference to a module the workers cannot import (it is gone): not a death mid-computation
    mod = tmp_path / "gone_module.py"
    mod.write_text("def f(x):\n    return {'y': x}\n")
    sys.path.insert(0, str(tmp_path))
    try:
        import gone_module

        mod.unlink()
        with pytest.raises(RuntimeError, match=r"cannot be loaded in a local worker process \(ModuleNotFoundError"):
            sweep(gone_module.f, {"x": [1.0, 2.0]}, progress=False, max_workers=1)
    finally:
        sys.path.remove(str(tmp_path))
        sys.modules.pop("gone_module", None)


def test_a_point_that_kills_every_dask_worker_it_lands_on_is_lost_alone(client, calls):
    f = partial(lib.killing, calls_dir=str(calls), kill_at=(4.0, 0.5))
    with pytest.warns(RuntimeWarning, match=r"^1 of 24 points were not computed \(its worker process died each time"):
        ds = sweep(f, GRID, executor=client, progress=False, chunk_size=3)
    lost = ds.status.values == NOT_COMPUTED
    assert lost[4, 2] and lost.sum() == 1
    # twice each (Dask's allowed failures: 1, see conftest): its chunk's task, its own task (beside those of
    # its chunk's other points, which may fail with it), its task alone among the sweep's retries
    assert lib.visits(str(calls)) == 6
    np.testing.assert_array_equal(ds["s"].values[~lost], reference()["s"].values[~lost])


def test_a_worker_of_an_executor_you_made_that_dies_breaks_it_its_unfinished_points_are_lost(calls):
    # the sweep cannot restart an executor it did not make: the points of the tasks not returned get -1
    f = partial(lib.killing, calls_dir=str(calls), kill_at=(4.0, 0.5))
    with ProcessPoolExecutor(max_workers=1) as pool, pytest.warns(
            RuntimeWarning, match=r"^12 of 24 points were not computed \(the executor broke \(BrokenProcessPool\)"):
        ds = sweep(f, GRID, executor=pool, progress=False, chunk_size=3)
    lost = ds.status.values == NOT_COMPUTED
    assert lost[4:].all() and not lost[:4].any()  # one worker: the chunks (rows) before the killer had returned
    assert ds.message.values[7, 1].startswith("not computed: the executor broke (BrokenProcessPool): one of its")
    np.testing.assert_array_equal(ds["s"].values[:4], reference()["s"].values[:4])


# ------------------------------------------------------------------------ resuming computes nothing twice
B5 = np.array([0.0, 0.5, 1.0, 1.5, 2.5])
GRID_2D = {"a": np.arange(4.0), "b": B5}  # chunk_size 3: blocks of 1 x 3, the grid cut along both dimensions
STOP = (2.0, 1.0)  # the third point of the chunk (a = 2, b[0:3]): two points of its chunk finished before it


def _finished_before_stop() -> set[str]:
    return {tag(a, b) for a, b in itertools.product(*GRID_2D.values()) if (a, b) < STOP}


def _stopping(calls: Path, stop: str, sig: int):
    return partial(lib.counted, calls_dir=str(calls), stop_at=STOP, stop=stop, stop_signal=sig)


def _check_flags_and_resume(store: Path, calls: Path, f, flags_hold: str) -> None:
    """The flags on disk (one per grid point, read with zarr alone) mark finished points; a resume computes
    exactly the points not finished."""
    import zarr

    flags = np.asarray(zarr.open_group(str(store), mode="r")["sweep"]["done"][...]).astype(bool)
    assert flags.shape == (4, 5)
    flagged = {tag(a, b) for (i, a), (j, b) in itertools.product(*map(enumerate, GRID_2D.values())) if flags[i, j]}
    finished = _finished_before_stop()
    assert set(lib.calls(str(calls))) == finished
    if flags_hold == "all":  # Ctrl-C: the points of the interrupted chunk are written before the sweep stops
        assert flagged == finished
    elif flags_hold == "whole chunks":  # killed: those points are in the journal of their task, for the next run
        assert flagged == finished - {tag(2.0, 0.0), tag(2.0, 0.5)}
    else:  # killed while it wrote an earlier result (a worker computes the next chunk meanwhile): in journals too
        assert flagged <= finished
    before = {p.name for p in calls.iterdir()}
    ds = sweep(f, GRID_2D, store=store, progress=False, executor="serial")
    second = sorted(p.name.split("__")[0] for p in calls.iterdir() if p.name not in before)
    assert second == sorted({tag(a, b) for a, b in itertools.product(*GRID_2D.values())} - finished)
    same_results(ds, sweep(lib.poly, GRID_2D, executor="serial", progress=False))


@pytest.mark.parametrize("executor", ["serial", "processes"])
def test_ctrl_c_then_resume_computes_exactly_the_unfinished_points(tmp_path, calls, executor):
    # a real SIGINT to this process: from the point itself (serial), or from the worker to its parent
    store = tmp_path / "s.zarr"
    f = _stopping(calls, "self" if executor == "serial" else "parent", signal.SIGINT)
    kw = {"executor": "serial"} if executor == "serial" else {"max_workers": 1}  # one worker: points in order
    with pytest.raises(KeyboardInterrupt):
        sweep(f, GRID_2D, store=store, progress=False, chunk_size=3, **kw)
    _check_flags_and_resume(store, calls, f, flags_hold="all")


_KILLED = """
import cloudpickle, sweep_testlib as lib, signal
from functools import partial
import numpy as np
from rigidbody.sweep import sweep
cloudpickle.register_pickle_by_value(lib)
if __name__ == "__main__":
    sweep(partial(lib.counted, calls_dir={calls!r}, stop_at=(2.0, 1.0), stop={stop!r}, stop_signal=signal.SIGKILL),
          {{"a": np.arange(4.0), "b": np.array([0.0, 0.5, 1.0, 1.5, 2.5])}}, store={store!r}, progress=False,
          chunk_size=3, **{kw})
"""


@pytest.mark.parametrize("executor", ["serial", "processes"])
def test_a_killed_sweeping_process_then_resume_computes_exactly_the_unfinished_points(tmp_path, calls, executor):
    store = tmp_path / "s.zarr"
    kw = {"executor": "serial"} if executor == "serial" else {"max_workers": 1}
    stop = "self" if executor == "serial" else "parent"
    proc = run_python(_KILLED.format(calls=str(calls), store=str(store), stop=stop, kw=kw))
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == -signal.SIGKILL, err
    _check_flags_and_resume(store, calls, _stopping(calls, stop, signal.SIGKILL),
                            flags_hold="whole chunks" if executor == "serial" else "some")


# --------------------------------------------------------------------------------------- one sweep a store
_HOLDING = """
import cloudpickle, sweep_testlib as lib
from functools import partial
import numpy as np
from rigidbody.sweep import sweep
cloudpickle.register_pickle_by_value(lib)
sweep(partial(lib.counted, calls_dir={calls!r}), {{"a": np.arange(8.0), "b": np.array([0.0, -1.0, 0.5])}},
      store={store!r}, progress=False, chunk_size=3, executor="serial")
"""


def test_a_store_in_use_is_refused_and_a_killed_sweep_leaves_no_lock(tmp_path, calls):
    store = tmp_path / "s.zarr"
    lib.hold(calls)  # each call >= 0.2 s: the 24 points take >= 4.8 s, the sweep is still writing below
    proc = run_python(_HOLDING.format(calls=str(calls), store=str(store)))
    try:
        wait_for_calls(calls, 2, proc)
        f = partial(lib.counted, calls_dir=str(calls))
        in_use = (rf"^store '{re.escape(str(store))}' is in use: another sweep is writing it \(pid {proc.pid} on .*, "
                  r"since .*\); a store is written by one sweep")
        with pytest.raises(RuntimeError, match=in_use):
            sweep(f, GRID, store=store, progress=False, chunk_size=3, executor="serial")
    finally:
        proc.kill()  # SIGKILL: the OS releases its lock
        proc.communicate(timeout=60)
    lib.hold(calls, on=False)
    # killed from outside at an arbitrary moment: at most its one point in flight may be computed again
    resume(store, calls, partial(lib.counted, calls_dir=str(calls)), executor="serial", in_flight=1)


def test_a_second_sweep_on_a_store_in_use_in_the_same_process_is_refused(tmp_path):
    store = tmp_path / "s.zarr"
    ds = sweep(partial(lib.nested, store=str(store)), {"a": [1.0, 2.0]}, store=store, progress=False,
               executor="serial")
    assert (ds.status.values == RAISED).all()
    assert all(m.startswith(f"RuntimeError: store '{store}' is in use: another sweep is writing it (in this "
                            f"process, pid {os.getpid()})") for m in ds.message.values)
    again = sweep(partial(lib.nested, store=str(tmp_path / "other.zarr")), {"a": [3.0]}, progress=False,
                  executor="serial")  # the lock of the first sweep was released
    assert again.status.values.tolist() == [0]


# ------------------------------------------------------------------------------------------ the outputs
def test_the_outputs_are_those_of_the_first_point_in_grid_order_on_every_executor(client):
    # the first point is slow: on workers, later chunks (with other outputs) finish first
    grid = {"a": np.arange(4.0), "b": np.array([0.0, 1.0])}
    f = partial(lib.shifting, slow=0.5)
    ref = sweep(f, grid, executor="serial", progress=False, chunk_size=2)
    assert set(ref.data_vars) == {"x", "status", "message"}
    np.testing.assert_array_equal(ref.status.values, [[0, 0], [0, 0], [1, 1], [1, 1]])
    np.testing.assert_array_equal(ref["x"].values[:2], [[0.0, 1.0], [1.0, 2.0]])
    assert ref.message.values[3, 1] == ('ValueError: the outputs {"y": [2]} differ from the sweep\'s outputs '
                                        '{"x": []}, those of the point a=0.0, b=0.0 (a sweep\'s function returns the '
                                        'same names and shapes at every point)')
    xr.testing.assert_identical(sweep(f, grid, progress=False, chunk_size=2, max_workers=2), ref)
    xr.testing.assert_identical(sweep(f, grid, executor=client, progress=False, chunk_size=2), ref)


def test_duplicate_grid_values_are_refused(tmp_path):
    with pytest.raises(ValueError, match=r"^grid\['b'\] holds the value 0.5 more than once \(at positions \[1, 3\]\)"):
        sweep(lib.poly, {"a": [1.0, 2.0], "b": [0.0, 0.5, 1.0, 0.5]}, executor="serial", store=tmp_path / "d.zarr")
    assert not (tmp_path / "d.zarr").exists()  # refused before anything is written
    with pytest.raises(ValueError, match=r"^grid\['kind'\] holds the value 'x' more than once"):
        sweep(lib.poly, {"kind": ["x", "y", "x"]}, executor="serial")
