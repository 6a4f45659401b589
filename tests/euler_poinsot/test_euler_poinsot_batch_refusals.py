"""A batch member that its single call refuses gets the single call's message, on every batch path.

The members of a batch used to be checked by a copy of the single call's rules with its own messages
(``averaged(..., k2_0=np.array([0.5, np.nan]))`` said "the initial values must be finite", the single call
"k2_0 must be finite"), a NaN phase of a full batch raised for the whole batch, and a batch of a torque object
whose members were all refused had no fields at all ("Solution has no field 'G'"; through the sweep wrapper
every point said "AttributeError"). Each invalid value, on each path (the closed forms of a drag tensor, a
torque object run member by member, the full equations together and member by member), must give the member
status -1, NaN fields and exactly the message the single call raises.
"""

from __future__ import annotations

import math
from functools import partial

import numpy as np
import pytest

from rigidbody import euler_poinsot as ep

BODY = ep.Body(3.2, 2.6, 1.67)
CASE1 = np.diag([2.322, 1.31, 1.425])
GOOD = dict(eps=0.02, G0=1.0, k2_0=0.5, delta0=0.7, lam0=0.3, nu0=0.0)
SPAN = dict(tau_span=(0.0, 0.01), tau_eval=[0.0, 0.01])

#: (parameter, invalid value[, options]): every rule of a start (finite, range, the separatrix stop, the spin)
INVALID = [
    ("eps", -1.0), ("eps", math.nan), ("eps", 5.0),  # 5: the rotation is not fast (min_spin_ratio)
    ("G0", 0.0), ("G0", math.nan), ("G0", math.inf),
    ("k2_0", 1.2), ("k2_0", -0.1), ("k2_0", math.nan),
    ("delta0", 4.0), ("delta0", math.nan),
    ("lam0", math.nan), ("nu0", math.inf),
    ("k2_0", 0.95, {"k2_max": 0.9}),  # a start beyond the separatrix stop
]

#: the averaged paths: the drag tensor's closed forms, the same as torque objects, an engine torque (one by one)
AVERAGED = {
    "drag tensor": CASE1,
    "drag objects": ep.LinearDrag(CASE1) + ep.GravityGradient(BODY),
    "engine": ep.LinearDrag(CASE1) + ep.ConstantTorque([0.0, 0.0, 0.1]),
}
#: the full equations: the body formulation together (a drag tensor, a torque object), the angles one by one
FULL = {
    "drag tensor": {"torque": CASE1},
    "torque object": {"torque": ep.LinearDrag(CASE1) + ep.ConstantTorque([0.0, 0.0, 0.1])},
    "angles": {"torque": CASE1, "formulation": "angles"},
}


def _check_member(sol, single, args, opts):
    with pytest.raises(ValueError) as err:
        single(**args, **opts)
    assert sol.status[1] == -1 and sol.message[1] == str(err.value)
    assert sol.status[0] == 0, sol.message[0]
    assert np.all(np.isnan(sol.G[1])) and np.all(np.isfinite(sol.G[0]))


def _case(case):
    name, bad = case[0], case[1]
    opts = case[2] if len(case) > 2 else {}
    return name, bad, opts


@pytest.mark.parametrize("path", list(AVERAGED))
@pytest.mark.parametrize("case", INVALID, ids=lambda c: f"{c[0]}={c[1]}")
def test_an_averaged_batch_member_says_what_the_single_call_says(path, case):
    name, bad, opts = _case(case)
    single = partial(ep.averaged, BODY, AVERAGED[path], **SPAN)
    sol = single(**{**GOOD, name: np.array([GOOD[name], bad])}, **opts)
    _check_member(sol, single, {**GOOD, name: bad}, opts)


@pytest.mark.parametrize("path", list(FULL))
@pytest.mark.parametrize("case", [*INVALID, ("eps", 0.0), ("u0", math.nan), ("psi0", math.inf)],
                         ids=lambda c: f"{c[0]}={c[1]}")
def test_a_full_batch_member_says_what_the_single_call_says(path, case):
    name, bad, opts = _case(case)
    good = {**GOOD, "u0": 0.4, "psi0": 0.2}
    kw = dict(FULL[path])
    single = partial(ep.simulate, BODY, kw.pop("torque"), **SPAN, **kw)
    sol = single(**{**good, name: np.array([good[name], bad])}, **opts)
    _check_member(sol, single, {**good, name: bad}, opts)


@pytest.mark.parametrize("T0", [math.nan, 10.0, 1.0 / (2 * BODY.A2)])  # NaN, beyond G0^2/2A3, the separatrix
def test_a_member_given_by_its_energy_says_what_the_single_call_says(T0):
    start = {k: v for k, v in GOOD.items() if k != "k2_0"}
    single = partial(ep.averaged, BODY, CASE1, **SPAN)
    sol = single(**start, T0=np.array([0.17, T0]))
    _check_member(sol, single, {**start, "T0": T0}, {})


def test_a_torque_batch_whose_members_are_all_refused_keeps_its_fields():
    tq = AVERAGED["engine"]
    te = np.linspace(0.0, 0.5, 6)
    k2 = np.array([[1.5, math.nan], [-1.0, 2.0]])
    sol = ep.averaged(BODY, tq, 0.0, 1.0, k2, tau_span=(0.0, 0.5), tau_eval=te)
    assert sol.batch_shape == (2, 2) and np.all(sol.status == -1)
    for f in ("G", "T", "k2", "delta", "lam", "nu", "sigma"):
        assert getattr(sol, f).shape == (2, 2, te.size) and np.all(np.isnan(getattr(sol, f))), f
    assert sol.n.shape == (2, 2, 3, te.size) and np.all(np.isnan(sol.n))
    assert sol.kind.shape == (2, 2, te.size) and np.all(sol.kind == "")
    for idx in np.ndindex(2, 2):
        with pytest.raises(ValueError) as err:
            ep.averaged(BODY, tq, 0.0, 1.0, float(k2[idx]), tau_span=(0.0, 0.5))
        assert sol.message[idx] == str(err.value)
    # the full equations member by member ('angles') as well
    full = ep.simulate(BODY, CASE1, 0.02, k2_0=np.array([1.5, 2.0]), tau_span=(0.0, 0.01), formulation="angles")
    assert np.all(full.status == -1) and full.G.shape == (2, 101) and np.all(np.isnan(full.G))


def test_the_sweep_wrapper_reports_the_reason_of_refused_torque_members():
    pytest.importorskip("xarray")
    from rigidbody.sweep import RUN_FAILED, euler_poinsot_averaged, sweep

    tq = AVERAGED["engine"]
    f = partial(euler_poinsot_averaged, body=BODY, torque=tq, eps=0.0, tau_span=(0.0, 0.5))
    ds = sweep(f, {"k2_0": np.array([1.5, 2.0])}, executor="serial", progress=False)
    assert ds.status.values.tolist() == [RUN_FAILED, RUN_FAILED]
    for i, k2 in enumerate((1.5, 2.0)):
        with pytest.raises(ValueError) as err:
            ep.averaged(BODY, tq, 0.0, 1.0, k2, tau_span=(0.0, 0.5))
        assert ds.message.values[i] == str(err.value)
