"""Stores: resuming an interrupted sweep computes only the missing points; mismatched stores are refused."""

from __future__ import annotations

import itertools
import signal
from functools import partial

import numpy as np
import pytest
import sweep_testlib as lib
import xarray as xr
from sweep_checks import (
    GRID,
    A,
    B,
    calls_after,
    quiet,
    reference,
    resume,
    run_python,
    same_results,
    stored_points,
    tag,
    wait_for_calls,
)

from rigidbody.sweep import NOT_COMPUTED, load, sweep

pytest.importorskip("zarr")  # stores need zarr-python 3 (Python >= 3.11); the sweep extra installs it there

@pytest.fixture
def calls(tmp_path):
    d = tmp_path / "calls"
    d.mkdir()
    return d


def test_a_complete_store_is_not_recomputed_and_loads_as_the_dataset(tmp_path, calls):
    store = tmp_path / "s.zarr"
    f = partial(lib.counted, calls_dir=str(calls))
    ds = sweep(f, GRID, executor="serial", store=store, progress=False, chunk_size=3)
    assert len(lib.calls(str(calls))) == A.size * B.size
    again = sweep(f, GRID, executor="serial", store=store, progress=False, chunk_size=3)
    assert len(lib.calls(str(calls))) == A.size * B.size  # nothing called again
    xr.testing.assert_identical(again, ds)
    xr.testing.assert_identical(load(store), ds)
    same_results(ds, reference())
    # the store is a plain Zarr store: xarray reads it (the sweep's bookkeeping is a sub-group it ignores)
    z = xr.open_zarr(store, consolidated=False).load()
    np.testing.assert_array_equal(z["v"].values, ds["v"].values)
    np.testing.assert_array_equal(z["status"].values, ds["status"].values)


def test_ctrl_c_in_process_then_resume_serial(tmp_path, calls):
    store = tmp_path / "s.zarr"
    f = partial(lib.counted, calls_dir=str(calls), interrupt_at=5.0)
    with pytest.raises(KeyboardInterrupt):
        sweep(f, GRID, executor="serial", store=store, progress=False, chunk_size=3)
    # chunks are rows of 3 points: rows a = 0..4 finished, row 5 was interrupted at its first point
    assert stored_points(store) == {tag(a, b) for a, b in itertools.product(A[:5], B)}
    resume(store, calls, f, executor="serial")


def test_a_worker_killed_once_loses_nothing(tmp_path, calls):
    # the point its worker was computing runs again alone and completes; the other workers go on
    f = partial(lib.counted, calls_dir=str(calls), kill_at=4.0, delay=0.02)
    ds = sweep(f, GRID, progress=False, chunk_size=3, max_workers=2)
    same_results(ds, reference())
    assert (tmp_path / "killed.0").exists()


def test_a_point_that_kills_its_worker_twice_is_lost_and_a_rerun_computes_it(tmp_path, calls):
    store = tmp_path / "s.zarr"
    f = partial(lib.counted, calls_dir=str(calls), kill_at=4.0, kill_times=2, delay=0.02)
    with pytest.warns(RuntimeWarning, match=r"1 of 24 points were not computed \(its worker process died twice"):
        ds = sweep(f, GRID, store=store, progress=False, chunk_size=3, max_workers=2)
    lost = ds.status.values == NOT_COMPUTED
    assert lost[4, 0] and lost.sum() == 1, "only the point whose worker died twice is lost"
    assert ds.message.values[4, 0] == ("not computed: its worker process died twice while computing this point "
                                       "(exit code 3)")
    resume(store, calls, f, max_workers=2)  # its third visit computes


_SCRIPT = """
import cloudpickle, sweep_testlib as lib
from functools import partial
from rigidbody.sweep import sweep
import numpy as np
cloudpickle.register_pickle_by_value(lib)
if __name__ == "__main__":
    grid = {{"a": np.arange(8.0), "b": np.array([0.0, -1.0, 0.5])}}
    sweep(partial(lib.counted, calls_dir={calls!r}, delay=0.05), grid,
          store={store!r}, progress=False, chunk_size=3, executor={executor})
"""


@pytest.mark.parametrize("executor", ['"serial"', "None, max_workers=2"], ids=["serial", "processes"])
@pytest.mark.parametrize("sig", [signal.SIGKILL, signal.SIGINT], ids=["killed", "ctrl-c"])
def test_a_killed_or_interrupted_sweeping_process_resumes_from_its_store(tmp_path, calls, sig, executor):
    # the whole sweeping process ends (a killed machine: SIGKILL; Ctrl-C: SIGINT) at an arbitrary moment,
    # possibly in the middle of writing a chunk: what the store says is finished must be, and the rest is
    # computed by the next run
    store = tmp_path / "s.zarr"
    # each call held to >= 0.2 s: the 14 points left after the 10th call need >= 1.4 s even on two worker
    # processes, so the signal lands before the sweep can finish, also on a loaded machine
    lib.hold(calls)
    proc = run_python(_SCRIPT.format(calls=str(calls), store=str(store), executor=executor))
    wait_for_calls(calls, 10, proc)
    proc.send_signal(sig)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode != 0
    if sig == signal.SIGINT:
        assert "KeyboardInterrupt" in err
    quiet(calls)  # the workers of a killed sweeping process end themselves (communicate() waited for them)
    lib.hold(calls, on=False)
    resume(store, calls, partial(lib.counted, calls_dir=str(calls), delay=0.05), executor="serial",
            in_flight=1 if executor == '"serial"' else 2)


def test_a_chunk_cut_short_before_its_flag_is_computed_again(tmp_path, calls):
    # a crash between writing a chunk's data and its flag: data on disk (here: a torn, empty file), no flag
    store = tmp_path / "s.zarr"
    f = partial(lib.counted, calls_dir=str(calls))
    ref = sweep(f, GRID, executor="serial", store=store, progress=False, chunk_size=3)
    (store / "sweep" / "done" / "c" / "2" / "0").unlink()  # chunk 2 = row a = 2 (flags: one per point)
    (store / "s" / "c" / "2" / "0").write_bytes(b"")  # its data torn
    part = load(store)
    assert (part.status.values[2] == NOT_COMPUTED).all() and np.isnan(part["s"].values[2]).all()
    assert (part.status.values[[0, 1, 3]] != NOT_COMPUTED).all()
    before = {p.name for p in calls.iterdir()}
    again = sweep(f, GRID, executor="serial", store=store, progress=False, chunk_size=3)
    assert calls_after(calls, before) == sorted(tag(2.0, b) for b in B)
    xr.testing.assert_identical(again, ref)


def test_a_torn_flag_counts_as_not_finished(tmp_path, calls):
    store = tmp_path / "s.zarr"
    f = partial(lib.counted, calls_dir=str(calls))
    ref = sweep(f, GRID, executor="serial", store=store, progress=False, chunk_size=3)
    (store / "sweep" / "done" / "c" / "5" / "0").write_bytes(b"\x28")  # a flag file cut short
    part = load(store)
    assert (part.status.values[5] == NOT_COMPUTED).all()
    xr.testing.assert_identical(sweep(f, GRID, executor="serial", store=store, progress=False), ref)


def test_mismatched_stores_are_refused(tmp_path, calls):
    store = tmp_path / "s.zarr"
    sweep(lib.poly, GRID, executor="serial", store=store, progress=False, chunk_size=3)
    with pytest.raises(ValueError, match=r"holds a sweep of 'sweep_testlib\.poly', not of 'sweep_testlib\.other"):
        sweep(lib.other_outputs, GRID, executor="serial", store=store, progress=False)
    with pytest.raises(ValueError, match=r"over the grid \['a', 'b'\], not over \['b', 'a'\]"):
        sweep(lib.poly, {"b": B, "a": A}, executor="serial", store=store, progress=False)
    with pytest.raises(ValueError, match="other values of 'b'"):
        sweep(lib.poly, {"a": A, "b": B + 1e-9}, executor="serial", store=store, progress=False)
    with pytest.raises(ValueError, match="other values of 'a'"):
        sweep(lib.poly, {"a": A[:-1], "b": B}, executor="serial", store=store, progress=False)
    # same name, other outputs (the function's code changed): refused at its first result, nothing written
    store2 = tmp_path / "s2.zarr"
    f = partial(lib.changing, calls_dir=str(calls))
    with pytest.raises(KeyboardInterrupt):
        sweep(f, GRID, executor="serial", store=store2, progress=False, chunk_size=3)
    (tmp_path / "new_outputs").touch()
    with pytest.raises(ValueError, match=r'holds the outputs \{"s": \[\]\} .* now returns \{"s": \[\], "q": \[2\]\}'):
        sweep(f, GRID, executor="serial", store=store2, progress=False)
    assert set(load(store2).data_vars) == {"s", "status", "message"}
    # a directory that is not a sweep store
    other = tmp_path / "other"
    other.mkdir()
    (other / "file.txt").write_text("x")
    with pytest.raises(ValueError, match="is not a sweep store"):
        sweep(lib.poly, GRID, executor="serial", store=other, progress=False)
    with pytest.raises(FileNotFoundError, match="no sweep store"):
        load(tmp_path / "missing")


def test_the_stores_chunk_layout_wins(tmp_path, calls):
    store = tmp_path / "s.zarr"
    f = partial(lib.counted, calls_dir=str(calls))
    ref = sweep(f, GRID, executor="serial", store=store, progress=False, chunk_size=3)
    again = sweep(f, GRID, executor="serial", store=store, progress=False, chunk_size=7)
    xr.testing.assert_identical(again, ref)
    assert len(lib.calls(str(calls))) == A.size * B.size


def test_a_string_grid_in_a_store(tmp_path):
    def f(kind, x):
        return {"y": x if kind == "max" else -x}

    store = tmp_path / "s.zarr"
    grid = {"kind": ["max", "min"], "x": [1.0, 2.0, 3.0]}
    ds = sweep(f, grid, executor="serial", store=store, progress=False, chunk_size=2)
    np.testing.assert_array_equal(ds["y"].values, [[1.0, 2.0, 3.0], [-1.0, -2.0, -3.0]])
    xr.testing.assert_identical(load(store), ds)
    xr.testing.assert_identical(sweep(f, grid, executor="serial", store=store, progress=False), ds)
    with pytest.raises(ValueError, match="other values of 'kind'"):
        sweep(f, {"kind": ["max", "mid"], "x": [1.0, 2.0, 3.0]}, executor="serial", store=store, progress=False)
    # equal numbers are the same grid whatever their dtype
    ints = sweep(lambda_free_int, {"n": [1, 2, 3]}, executor="serial", store=tmp_path / "i.zarr", progress=False)
    floats = sweep(lambda_free_int, {"n": [1.0, 2.0, 3.0]}, executor="serial", store=tmp_path / "i.zarr",
                   progress=False)
    np.testing.assert_array_equal(ints["m"].values, floats["m"].values)


def lambda_free_int(n):
    return {"m": 2.0 * n}
