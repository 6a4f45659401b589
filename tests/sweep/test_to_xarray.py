"""Solution.to_xarray on single runs of each module and on the batch shapes of the batch model."""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr

from rigidbody import euler_poinsot as ep
from rigidbody import gyrostat, lagrange
from rigidbody.core.ode import Solution


def _single_runs() -> dict[str, Solution]:
    body, I = ep.Body(3.2, 2.6, 1.67), np.diag([2.322, 1.31, 1.425])
    state = lagrange.paper_initial_state(2)
    sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    motion = gyrostat.stationary_motion(sat, 1.0, 0.3, k2=0.01)
    return {
        "lagrange.averaged": lagrange.averaged(lagrange.PAPER_TOP, lagrange.PAPER_DRAG,
                                               lagrange.integrals(lagrange.PAPER_TOP, *state[:5]), (0.0, 2.0),
                                               tau_eval=np.linspace(0, 2, 5)),
        "lagrange.simulate": lagrange.simulate(lagrange.PAPER_TOP, lagrange.PAPER_DRAG, 0.05, state, (0.0, 3.0),
                                               t_eval=np.linspace(0, 3, 7)),
        # a1 = I11/A1 > a3 = I33/A3: k2 reaches the separatrix (docs/euler_poinsot.md), an event ends the run
        "ep.averaged": ep.averaged(body, np.diag([6.4, 2.6, 1.67]), 0.0, k2_0=0.9, tau_span=(0, 3.0)),
        "ep.simulate": ep.simulate(body, I, 0.05, k2_0=0.9, tau_span=(0, 0.05), tau_eval=np.linspace(0, 0.05, 4)),
        "gyrostat.simulate": gyrostat.simulate(sat, motion, (0.0, 1.0), t_eval=np.linspace(0, 1, 3)),
    }


@pytest.mark.parametrize("name", ["lagrange.averaged", "lagrange.simulate", "ep.averaged", "ep.simulate",
                                  "gyrostat.simulate"])
def test_single_runs_of_each_module(name):
    sol = _single_runs()[name]
    ds = sol.to_xarray()
    t = sol.time_name
    np.testing.assert_array_equal(ds[t].values, sol.time)
    assert set(ds.data_vars) == {*sol.fields, "status", "message"}
    for f in sol.fields:
        a = np.asarray(sol[f])
        np.testing.assert_array_equal(ds[f].values, a)
        if a.ndim == 1:
            assert ds[f].dims == (t,)
        else:
            assert ds[f].dims == ("component" if a.shape[0] == 3 else f"{f}_component", t)
    assert ds.status.ndim == 0 and int(ds.status) == sol.status and ds.message.item() == sol.message
    assert ds.attrs["event"] == (sol.event or "") and ds.attrs["time_name"] == t
    if name == "ep.averaged":
        assert ds.attrs["event"] == "separatrix" and int(ds.status) == 1


def _batch(shape: tuple[int, ...], n_t: int = 4) -> Solution:
    """A Solution carrying the batch model's shapes (batch shape B, common time grid, per-member status)."""
    rng = np.random.default_rng(1)
    tau = np.linspace(0.0, 1.0, n_t)
    data = {"G": rng.random((*shape, n_t)), "n": rng.random((*shape, 3, n_t))}
    status = np.zeros(shape, dtype=int)
    status.flat[0] = 1
    message = np.full(shape, "ok", dtype=object)
    message.flat[0] = "stopped by event 'separatrix'"
    event = np.full(shape, None, dtype=object)
    event.flat[0] = "separatrix"
    data["G"].reshape(-1, n_t)[0, -1] = np.nan  # the member that ended early
    sol = Solution("tau", tau, rng.random((*shape, 4, n_t)), data, status, message, event, {}, {}, None, 0)
    sol.batch_shape = shape
    return sol


def test_batch_shapes_become_batch_dimensions():
    sol = _batch((2, 3))
    ds = sol.to_xarray()
    assert ds["G"].dims == ("batch_0", "batch_1", "tau") and ds["n"].dims == ("batch_0", "batch_1", "component", "tau")
    np.testing.assert_array_equal(ds["G"].values, sol.G)
    np.testing.assert_array_equal(ds["n"].values, sol.n)
    assert ds.status.dims == ("batch_0", "batch_1") and int(ds.status[0, 0]) == 1 and int(ds.status.sum()) == 1
    assert ds.event.values[0, 0] == "separatrix" and ds.event.values[1, 2] == ""
    named = sol.to_xarray(batch_dims={"k2_0": [0.1, 0.5], "delta0": None})
    assert named["G"].dims == ("k2_0", "delta0", "tau")
    np.testing.assert_array_equal(named["k2_0"].values, [0.1, 0.5])
    assert "delta0" not in named.coords
    assert sol.to_xarray(batch_dims=("a", "b"))["n"].dims == ("a", "b", "component", "tau")
    xr.testing.assert_identical(_batch((5,)).to_xarray(batch_dims=("k",)).isel(k=0).status.drop_vars([]),
                                xr.DataArray(1, name="status"))


def test_bad_batch_dims_are_refused():
    sol = _batch((2, 3))
    with pytest.raises(ValueError, match="must name the 2 batch axes"):
        sol.to_xarray(batch_dims=("a",))
    with pytest.raises(ValueError, match=r"batch_dims\['a'\] must have the 2 values"):
        sol.to_xarray(batch_dims={"a": [1, 2, 3], "b": None})
    with pytest.raises(TypeError, match="batch_dims must be a sequence"):
        sol.to_xarray(batch_dims="ab")
    assert math.isnan(float(sol.to_xarray()["G"][0, 0, -1]))
