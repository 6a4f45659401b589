"""rigidbody.sweep: the Dataset, failing points, executors giving identical results, batched chunks."""

from __future__ import annotations

import subprocess
import sys
from concurrent.futures import ProcessPoolExecutor
from functools import partial

import numpy as np
import pytest
import sweep_testlib as lib
import xarray as xr

from rigidbody import gyrostat
from rigidbody.sweep import NOT_COMPUTED, RAISED, batched, gyrostat_stability, sweep

A = np.array([0.0, 1.0, 2.0, 3.5])
B = np.array([-1.0, 0.0, 0.5])
GRID = {"a": A, "b": B}


def _check_poly(ds: xr.Dataset) -> None:
    """The Dataset of lib.poly over GRID against the closed form (numpy broadcasting, no sweep)."""
    exp = lib.expected(A, B)
    assert list(ds["s"].dims) == ["a", "b"] and list(ds["v"].dims) == ["a", "b", "v_dim_0"]
    np.testing.assert_array_equal(ds["a"].values, A)
    np.testing.assert_array_equal(ds["b"].values, B)
    for name in ("s", "p", "v"):
        np.testing.assert_array_equal(ds[name].values, exp[name])
    bad = (ds.a == lib.BAD[0]) & (ds.b == lib.BAD[1])
    assert int(bad.sum()) == 1
    assert (ds.status.where(bad, drop=True) == RAISED).all()
    assert ds.message.where(bad, drop=True).item() == "ValueError: no value at a=2.0, b=-1.0"
    good = ~bad.values
    assert (ds.status.values[good] == 0).all()
    assert set(ds.message.values[good]) == {""}


def test_serial_dataset_matches_the_closed_form_and_records_the_failing_point():
    ds = sweep(lib.poly, GRID, executor="serial", progress=False, chunk_size=5)
    _check_poly(ds)
    assert ds.attrs["function"] == "sweep_testlib.poly"
    assert ds.status.dtype == np.int64 and ds.message.dtype == object


def test_grid_order_is_kept_and_points_are_python_scalars():
    seen = []

    def f(y, x):
        seen.append((type(y), type(x)))
        return {"d": y - x}

    ds = sweep(f, {"y": [3, 4], "x": [0.5, 1.5, 2.5]}, executor="serial", progress=False)
    assert list(ds.dims) == ["y", "x"] and ds["d"].shape == (2, 3)
    np.testing.assert_array_equal(ds["d"].values, np.subtract.outer([3, 4], [0.5, 1.5, 2.5]))
    assert set(seen) == {(int, float)}


@pytest.mark.parametrize("chunk_size", [1, 2, 3, 12, 1000])
def test_chunking_does_not_change_the_result(chunk_size):
    ds = sweep(lib.poly, GRID, executor="serial", progress=False, chunk_size=chunk_size)
    _check_poly(ds)


def test_local_processes_and_a_user_executor_give_the_serial_dataset():
    ref = sweep(lib.poly, GRID, executor="serial", progress=False, chunk_size=2)
    default = sweep(lib.poly, GRID, progress=False, chunk_size=2, max_workers=2)  # executor=None: processes
    xr.testing.assert_identical(default, ref)
    with ProcessPoolExecutor(max_workers=2) as pool:
        mine = sweep(lib.poly, GRID, executor=pool, progress=False, chunk_size=3)
        again = sweep(lib.poly, GRID, executor=pool, progress=False, chunk_size=5)  # the pool is reused
    xr.testing.assert_identical(mine, ref)
    xr.testing.assert_identical(again, ref)


def test_a_function_of_a_scripts_main_runs_on_spawned_workers(tmp_path):
    # the function lives in __main__ of a script: it travels by value to the spawned workers
    script = tmp_path / "s.py"
    script.write_text(
        "import numpy as np\n"
        "from rigidbody.sweep import sweep\n"
        "def f(x):\n    return {'y': x * x}\n"
        "if __name__ == '__main__':\n"
        "    ds = sweep(f, {'x': np.arange(6.0)}, max_workers=2, progress=False, chunk_size=2)\n"
        "    print(ds['y'].values.tolist(), ds.attrs['function'])\n"
    )
    out = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, timeout=120, check=True)
    assert out.stdout.strip() == "[0.0, 1.0, 4.0, 9.0, 16.0, 25.0] __main__.f"


def test_a_script_without_main_guard_gets_a_clear_error(tmp_path):
    script = tmp_path / "s.py"
    script.write_text(
        "from rigidbody.sweep import sweep\n"
        "def f(x):\n    return {'y': x}\n"
        "sweep(f, {'x': [1.0, 2.0]}, max_workers=1, progress=False)\n"
    )
    out = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, timeout=120)
    assert out.returncode != 0
    assert "if __name__ == '__main__':" in out.stderr


def test_every_way_a_point_can_fail_is_recorded_and_the_rest_computed():
    def f(a):
        if a == 0:
            return 1.0  # not a mapping
        if a == 1:
            return {"x": "text"}  # not numbers
        if a == 6:
            return {"x": 1.0, "extra": 2.0}  # other outputs than the first point that succeeded
        if a == 3:
            return {"status": 1.0}  # a reserved name
        if a == 4:
            raise ZeroDivisionError("division by zero")
        return {"x": float(a)}

    ds = sweep(f, {"a": np.arange(8)}, executor="serial", progress=False, chunk_size=8)
    np.testing.assert_array_equal(ds.status.values, [1, 1, 0, 1, 1, 0, 1, 0])
    np.testing.assert_array_equal(ds["x"].values, [np.nan, np.nan, 2.0, np.nan, np.nan, 5.0, np.nan, 7.0])
    assert "extra" not in ds
    msg = ds.message.values
    assert msg[0].startswith("TypeError: the function must return a mapping")
    assert msg[1].startswith("TypeError: output 'x' must be real numbers")
    assert "differ from the sweep's outputs {\"x\": []}, those of the point a=2" in msg[6]
    assert "reserved" in msg[3] or "collides" in msg[3]
    assert msg[4] == "ZeroDivisionError: division by zero"


def test_outputs_that_change_between_chunks_make_those_points_fail():
    def f(a):
        return {"x": a} if a < 2 else {"y": a}

    ds = sweep(f, {"a": np.arange(4.0)}, executor="serial", progress=False, chunk_size=2)
    assert "y" not in ds
    np.testing.assert_array_equal(ds.status.values, [0, 0, 1, 1])
    assert "differ from the sweep's outputs {\"x\": []}, those of the point a=0.0" in ds.message.values[3]


def test_no_successful_point_gives_status_and_message_only():
    def f(a):
        raise RuntimeError("never")

    ds = sweep(f, {"a": [1.0, 2.0]}, executor="serial", progress=False)
    assert set(ds.data_vars) == {"status", "message"}
    assert (ds.status == RAISED).all()


def test_bad_arguments_are_refused_clearly():
    with pytest.raises(TypeError, match="grid must be a mapping"):
        sweep(lib.poly, [1, 2], executor="serial")
    with pytest.raises(ValueError, match=r"grid\['a'\] must be a 1-D array"):
        sweep(lib.poly, {"a": [[1.0]], "b": B}, executor="serial")
    with pytest.raises(ValueError, match=r"grid\['a'\] is empty"):
        sweep(lib.poly, {"a": [], "b": B}, executor="serial")
    with pytest.raises(ValueError, match="reserved"):
        sweep(lib.poly, {"status": A}, executor="serial")
    with pytest.raises(TypeError, match="identifiers"):
        sweep(lib.poly, {"a b": A}, executor="serial")
    with pytest.raises(ValueError, match="executor must be"):
        sweep(lib.poly, GRID, executor="threads")
    with pytest.raises(TypeError, match="executor must be"):
        sweep(lib.poly, GRID, executor=3)
    with pytest.raises(ValueError, match="chunk_size must be an integer >= 1"):
        sweep(lib.poly, GRID, executor="serial", chunk_size=0)
    with pytest.raises(ValueError, match="max_workers applies to the default executor"):
        sweep(lib.poly, GRID, executor="serial", max_workers=2)
    with pytest.raises(ValueError, match="max_workers must be an integer >= 1"):
        sweep(lib.poly, GRID, max_workers=0)
    with pytest.raises(TypeError, match="progress must be None, True or False"):
        sweep(lib.poly, GRID, executor="serial", progress="yes")
    with pytest.raises(TypeError, match="func must be callable"):
        sweep(3, GRID, executor="serial")


# --------------------------------------------------------------------------------------------- batched
def test_batched_function_gets_whole_chunks(tmp_path):
    calls = tmp_path / "calls"
    calls.mkdir()
    f = partial(lib.poly_batched, calls_dir=str(calls))
    ds = sweep(f, GRID, executor="serial", progress=False, chunk_size=5)
    # 12 points in blocks of at most 5 cut along the last axis: rows of 3 -> one block of 3 per a value
    assert sorted(p.name.split("__")[0] for p in calls.iterdir()) == ["n=3"] * 4
    exp = lib.expected(A, B)
    for name in ("s", "p", "v"):
        np.testing.assert_array_equal(ds[name].values, exp[name])  # NaN at the point with status 7
    bad = (ds.a == lib.BAD[0]) & (ds.b == lib.BAD[1])
    assert ds.status.where(bad, drop=True).item() == 7
    assert ds.message.where(bad, drop=True).item() == "bad point"
    ds_proc = sweep(f, GRID, progress=False, chunk_size=5, max_workers=2)
    xr.testing.assert_identical(ds_proc, ds)


def test_a_raising_batch_is_retried_point_by_point():
    ds = sweep(lib.poly_batched_raising, GRID, executor="serial", progress=False, chunk_size=6)
    exp = lib.expected(A, B)
    for name in ("s", "p", "v"):
        np.testing.assert_array_equal(ds[name].values, exp[name])
    bad = (ds.a == lib.BAD[0]) & (ds.b == lib.BAD[1])
    assert ds.message.where(bad, drop=True).item() == "ValueError: bad point in this batch"
    assert int((ds.status != 0).sum()) == 1


def test_batched_protocol_errors_are_recorded():
    @batched
    def wrong_length(a):
        return {"x": np.zeros(a.size + 1)}

    @batched
    def negative_status(a):
        return {"x": a, "status": -np.ones(a.size, dtype=int)}

    for f, text in ((wrong_length, "leading axis"), (negative_status, "integers >= 0")):
        ds = sweep(f, {"a": np.arange(3.0)}, executor="serial", progress=False)
        assert (ds.status == RAISED).all()
        assert all(text in m for m in ds.message.values)
    with pytest.raises(TypeError, match="needs a callable"):
        batched(3)


def test_gyrostat_stability_wrapper_reproduces_the_stability_map():
    sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    theta0 = np.linspace(-1.2, 1.2, 7)
    k2 = np.linspace(-0.05, 0.05, 5)
    ds = sweep(partial(gyrostat_stability, sat=sat, R0=1.0), {"theta0": theta0, "k2": k2},
               executor="serial", progress=False, chunk_size=4)
    mp = gyrostat.stability_map(sat, 1.0, theta0, k2=k2)  # one vectorised call over the whole grid
    np.testing.assert_array_equal(ds["code"].values, mp.code)
    np.testing.assert_array_equal(ds["degree"].values, mp.degree)
    for name in ("s1", "s2", "s3", "kappa0", "omega0", "k3"):
        np.testing.assert_allclose(ds[name].values, getattr(mp, name), rtol=1e-12, atol=0)
    assert (ds.status == 0).all()
    assert "k2" not in ds.data_vars  # swept, not an output
    with pytest.raises(TypeError, match="needs R0"):
        gyrostat_stability(sat=sat, theta0=theta0, k2=k2)


def test_status_constants():
    assert (NOT_COMPUTED, RAISED) == (-1, 1)


def test_docstring_example_runs():
    import doctest

    import rigidbody.sweep._api as api

    result = doctest.testmod(api, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert result.attempted > 0 and result.failed == 0
