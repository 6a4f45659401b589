"""The in-process maps of the studies (``evaluate``: one call, the points integrated as batches) hold the numbers
of a sweep of the same functions point by point (single runs); the readers take either kind of map."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from rigidbody import studies as S
from rigidbody.sweep import batched, sweep

# Both routes integrate the same equations with the same tolerances (full runs rtol 1e-10, atol 1e-12; the
# averaged ones rtol 1e-10 by default) on the same output times: each slow variable (of order 1) carries a
# global error of order 1e-10-1e-9 in either route, so their largest differences agree to a few 1e-9.
# 1e-8 keeps a margin of 5 and stays far below the smallest error compared (4e-6, Lagrange at 170 deg).
ROUTES_ATOL = 1e-8


def _compare(func, grid):
    m = S.evaluate(func, grid)
    ds = sweep(func, grid, executor="serial", progress=False)  # not batched: one single call per point
    assert m.dims == tuple(grid) and m.shape == ds["status"].shape
    np.testing.assert_array_equal(S.grid_values(m, "status"), ds["status"].values)
    outputs = [k for k in ds.data_vars if k not in ("status", "message")]
    assert sorted(k for k in m.data if k not in ("status", "message")) == sorted(outputs)
    for k in outputs:
        np.testing.assert_allclose(S.grid_values(m, k), ds[k].values, rtol=0, atol=ROUTES_ATOL, equal_nan=True,
                                   err_msg=k)
    return m, ds


def test_lagrange_map_equals_the_point_by_point_sweep():
    grid = {"eps": [0.04, 0.02], "theta0": np.radians([5.0, 90.0, 170.0])}
    m, _ = _compare(S.averaging_error_lagrange, grid)
    assert (S.grid_values(m, "status") == 0).all()
    # the map is not vacuous: the errors are the O(eps) differences of the study, not zeros
    assert np.all(S.grid_values(m, "error") > 1e-6)


def test_euler_poinsot_map_equals_the_point_by_point_sweep_failed_point_included():
    # next to the separatrix at eps = 0.04 the full run stops (slow rotation): both routes record the point
    grid = {"eps": [0.04, 0.02], "k2_0": [0.5, 0.99]}
    m, ds = _compare(S.averaging_error_euler_poinsot, grid)
    status = S.grid_values(m, "status")
    np.testing.assert_array_equal(status, [[0, 1], [0, 0]])
    for msg in (S.grid_values(m, "message")[0, 1], str(ds["message"].values[0, 1])):
        assert msg.startswith("RuntimeError: the full run ended early") and "rotation is no longer fast" in msg
    assert np.isnan(S.grid_values(m, "error")[0, 1])
    assert np.all(S.grid_values(m, "error")[status == 0] > 1e-5)


def test_array_calls_refuse_bad_points_naming_the_parameter():
    with pytest.raises(ValueError, match=r"eps must be > 0 .*got 0\.0"):
        S.averaging_error_euler_poinsot(np.array([0.01, 0.0]), 0.5)
    with pytest.raises(ValueError, match=r"k2_0 must lie in \(0, 1\), got 1\.0"):
        S.averaging_error_euler_poinsot(0.01, np.array([0.5, 1.0]))
    with pytest.raises(ValueError, match=r"theta0 must lie in \(0, pi\), got 4\.0"):
        S.averaging_error_lagrange(0.01, np.array([1.0, 4.0]))
    with pytest.raises(TypeError, match="theta0"):
        S.averaging_error_lagrange(0.01, np.array(["a"]))


def test_evaluate_lays_out_the_grid_in_c_order_and_blanks_failed_points():
    @batched
    def f(a, b):  # a toy on arrays of points: a + 10 b, the point (a, b) = (2, 30) failed
        bad = (a == 2.0) & (b == 30.0)
        return {"s": a + 10 * b, "pair": np.stack([a, b], axis=1), "status": bad.astype(int),
                "message": np.where(bad, "ValueError: no", "")}

    m = S.evaluate(f, {"a": [1.0, 2.0], "b": [10.0, 20.0, 30.0]})
    np.testing.assert_array_equal(S.grid_values(m, "s"), [[101.0, 201.0, 301.0], [102.0, 202.0, np.nan]])
    assert m["pair"].dims == ("a", "b", "pair_dim_0") and S.grid_values(m, "pair")[1, 0].tolist() == [2.0, 10.0]
    np.testing.assert_array_equal(S.grid_values(m, "s", ("b", "a")), S.grid_values(m, "s").T)
    assert S.grid_values(m, "message")[1, 2] == "ValueError: no" and S.grid_values(m, "status").sum() == 1
    # the same layout as the sweep's Dataset of the same function
    ds = sweep(f, {"a": [1.0, 2.0], "b": [10.0, 20.0, 30.0]}, executor="serial", progress=False)
    xr.testing.assert_equal(m.to_xarray(), ds)  # the sweep adds attrs["function"] only
    assert "1 failed" in repr(m)


def test_evaluate_refuses_a_bad_grid_or_output():
    def f(a):
        return {"x": a[:1]}

    with pytest.raises(ValueError, match=r"grid\['a'\] must be a non-empty 1-D array"):
        S.evaluate(f, {"a": [[1.0, 2.0]]})
    with pytest.raises(ValueError, match="grid names must be Python identifiers"):
        S.evaluate(f, {"status": [1.0]})
    with pytest.raises(ValueError, match=r"output 'x' .* must have a leading axis over the 2 points"):
        S.evaluate(f, {"a": [1.0, 2.0]})
    with pytest.raises(TypeError, match="must return a mapping"):
        S.evaluate(lambda a: a, {"a": [1.0]})


def test_readers_take_a_map_or_a_dataset_alike():
    eps = np.array([0.04, 0.02, 0.01])
    err = eps[:, None] ** np.array([2.0, 1.0])[None, :] * 3.0
    err[0, 1] = np.nan  # a failed point, left out of its fit
    ds = xr.Dataset({"error": (("eps", "k"), err), "status": (("eps", "k"), np.zeros((3, 2), dtype=int))},
                    coords={"eps": eps, "k": [0.1, 0.2]})
    m = S.as_study_map(ds)
    assert m.dims == ("eps", "k") and S.as_study_map(m) is m
    np.testing.assert_array_equal(S.grid_values(m, "error"), err)
    # the exponents 2 and 1 built into the data, from either kind of map
    np.testing.assert_allclose(S.fitted_order(m), [2.0, 1.0], rtol=1e-12, atol=0)
    np.testing.assert_allclose(S.fitted_order(ds).values, [2.0, 1.0], rtol=1e-12, atol=0)
    # a Dataset whose variable has its dimensions in another order is read in the grid's order
    m2 = S.as_study_map(ds.transpose("k", "eps"))
    np.testing.assert_array_equal(S.grid_values(m2, "error", ("eps", "k")), err)
    with pytest.raises(ValueError, match=r"'error' has the dimensions \('eps', 'k'\), not \('eps',\)"):
        S.grid_values(m, "error", ("eps",))
    with pytest.raises(KeyError, match="neither a grid name"):
        m["nope"]
