"""The batched sweep wrappers of the averaged evolutions equal the same sweep computed point by point.

``lagrange_averaged`` and ``euler_poinsot_averaged`` send a chunk of grid points to one batch integration;
the reference is a plain per-point function calling the single-run API, swept the ordinary way. A batch
member equals its single run within the tolerance (both are DOP853 with the same step control in the same
coordinates; their step sequences differ by rounding), so the Datasets agree to a few times ``rtol``.
"""

from __future__ import annotations

import math
from functools import partial

import numpy as np
import pytest

from rigidbody import euler_poinsot as ep
from rigidbody import lagrange as L
from rigidbody.sweep import RUN_FAILED, euler_poinsot_averaged, lagrange_averaged, sweep

RTOL = 1e-10
# members of a batch and their single runs differ by the integrators' error: a few rtol of each (relative)
AGREE = 50 * RTOL


def _single_outputs(sol, names, end_only):
    out = {}
    for name in names:
        a = np.asarray(getattr(sol, name), dtype=float)
        out[name] = float(a[-1]) if end_only else a
    out["run_status"] = float(sol.status)
    return out


def _lagrange_point(Gz0, H0, r0, *, tau_eval=None):
    te = [40.0] if tau_eval is None else tau_eval
    sol = L.averaged(L.PAPER_TOP, L.PAPER_DRAG, (Gz0, H0, r0), (0.0, 40.0), tau_eval=te, rtol=RTOL)
    return _single_outputs(sol, ("Gz", "H", "r", "k2"), tau_eval is None)


def _compare(ds_b, ds_p, names):
    for name in names:
        a, b = ds_b[name].values, ds_p[name].values
        np.testing.assert_allclose(a, b, rtol=AGREE, atol=AGREE * np.nanmax(np.abs(b)))


def test_lagrange_batched_sweep_equals_the_point_by_point_sweep():
    # initial slow variables (1.2) around those of a top spun at r = 1.7 and tilted by 70 degrees
    Gz, H0, r = L.integrals(L.PAPER_TOP, 0.0, 0.0, 1.7, 0.0, math.radians(70.0))
    # (the last r0 leaves no admissible state at this energy: both sweeps record that point as failed)
    grid = {"Gz0": Gz * np.array([0.9, 1.0, 1.1]), "r0": r * np.array([0.9, 1.0, 1.05])}
    f = partial(lagrange_averaged, top=L.PAPER_TOP, torque=L.PAPER_DRAG, H0=H0, tau_span=(0.0, 40.0), rtol=RTOL)
    ds_b = sweep(f, grid, executor="serial", progress=False, chunk_size=4)
    ds_p = sweep(partial(_lagrange_point, H0=H0), grid, executor="serial", progress=False)
    bad = ds_p.status.values != 0
    assert bad[:, 2].all() and not bad[:, :2].any()
    np.testing.assert_array_equal(ds_b.status.values, np.where(bad, RUN_FAILED, 0))
    for b, p in zip(ds_b.message.values[bad], ds_p.message.values[bad]):
        assert p.endswith(b)  # the single call's ValueError, as the point sweep recorded it
    _compare(ds_b, ds_p, ("Gz", "H", "r", "k2", "run_status"))
    assert np.all(ds_b.tau_end.values[~bad] == 40.0)


def _ep_point(k2_0, delta0, *, eps, tau_eval=None):
    te = [2.0] if tau_eval is None else tau_eval
    sol = ep.averaged(ep.Body(3.2, 2.6, 1.67), np.diag([2.322, 1.31, 1.425]), eps, 1.0, k2_0, delta0, 0.4,
                      (0.0, 2.0), te, rtol=RTOL)
    if sol.status != 0:
        raise RuntimeError(sol.message)
    return _single_outputs(sol, ("G", "T", "k2", "delta", "lam"), tau_eval is None)


@pytest.mark.parametrize("eps", [0.0, 0.01])
def test_euler_poinsot_batched_sweep_equals_the_point_by_point_sweep(eps):
    body, I = ep.Body(3.2, 2.6, 1.67), np.diag([2.322, 1.31, 1.425])
    grid = {"k2_0": np.array([0.0, 0.2, 0.6, 0.95]), "delta0": np.array([0.3, 1.5, 2.9])}
    te = np.linspace(0.0, 2.0, 5)
    f = partial(euler_poinsot_averaged, body=body, torque=I, eps=eps, lam0=0.4, tau_span=(0.0, 2.0), rtol=RTOL)
    for kw in ({}, {"tau_eval": te}):
        ds_b = sweep(partial(f, **kw), grid, executor="serial", progress=False, chunk_size=5)
        ds_p = sweep(partial(_ep_point, eps=eps, **kw), grid, executor="serial", progress=False)
        assert (ds_p.status == 0).all() and (ds_b.status == 0).all()
        _compare(ds_b, ds_p, ("G", "T", "k2", "delta", "lam", "run_status"))
        if kw:
            assert ds_b["G"].shape == (4, 3, te.size)


def test_a_refused_member_gets_the_run_failed_status_and_the_single_calls_message():
    body, I = ep.Body(3.2, 2.6, 1.67), np.diag([2.322, 1.31, 1.425])
    f = partial(euler_poinsot_averaged, body=body, torque=I, eps=0.05, tau_span=(0.0, 1.0))
    ds = sweep(f, {"k2_0": np.array([0.3, 0.9999])}, executor="serial", progress=False)
    # at eps = 0.05 next to the separatrix the rotation is not fast: the single call refuses that start
    with pytest.raises(ValueError) as err:
        ep.averaged(body, I, 0.05, 1.0, 0.9999, tau_span=(0.0, 1.0))
    assert ds.status.values.tolist() == [0, RUN_FAILED]
    assert ds.message.values[1] == str(err.value)
    # the outputs of a point that did not succeed are not results (NaN), its run_status included
    assert math.isnan(float(ds.G.values[1])) and math.isnan(float(ds.run_status.values[1]))
    assert float(ds.run_status.values[0]) == 0.0
