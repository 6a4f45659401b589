"""The closed-form averaged system on the piecewise driver: one run is a batch of one, pieces keep their own kind.

Independent route: the separatrix 2 T A2 = G^2 divides the two kinds of motion, so at every output time of a run
the energy and the momentum must lie on the side of the kind the run reports ('max', about the axis of A1:
2 T A2 < G^2; 'min': 2 T A2 > G^2), whichever piece the time belongs to.
"""

from __future__ import annotations

import numpy as np
import pytest

from rigidbody import euler_poinsot as ep

BODY = ep.Body(3.2, 2.6, 1.67)
UPWARD = np.diag([2.9, 1.31, 1.0])  # k2 grows to the separatrix, the motion goes on about the axis of A3


@pytest.mark.parametrize("eps", [0.0, 0.01])
@pytest.mark.parametrize("tau_eval", [None, np.linspace(0.0, 1.5, 16)])
def test_every_piece_of_a_run_through_the_separatrix_gives_its_fields_in_its_own_kind(eps, tau_eval):
    # slip caught: the fields of a piece evaluated with the constants of the last piece (its kind's labelled
    # moments), not its own: T before the crossing then lies on the wrong side of the separatrix (O(1) off)
    sol = ep.averaged(BODY, UPWARD, eps, 1.0, 0.95, 0.8, 0.3, tau_span=(0.0, 1.5), tau_eval=tau_eval, k2_max=None,
                      min_spin_ratio=0.0)
    assert sol.status == 0 and len(sol.crossings) >= 1 and {"max", "min"} <= set(sol.kind.tolist())
    side = (2.0 * sol.T * BODY.A2 - sol.G**2) / sol.G**2  # < 0 for 'max', > 0 for 'min'
    # the crossing switches at 1 - k2 = 1e-9, where |side| is of that order: the bound 1e-12 is far below
    # every sample's |side| away from the switch and far above the rounding of T, G (1e-16 relative)
    away = np.abs(side) > 1e-12
    assert np.all(np.where(sol.kind == "max", side < 0.0, side > 0.0)[away])
    assert away.sum() >= sol.tau.size - 1


def test_a_batch_member_alone_in_its_kind_runs_as_its_single_call():
    # two members, one crosses into 'min' alone (a group of one: the scalar integrator inside the batch), the
    # other stays in 'max'; each must be its single call within the agreement of two DOP853 runs of rtol 1e-10
    # (the same steps up to rounding: 1e-9 relative leaves room for the crossing time's sensitivity)
    te = np.linspace(0.0, 1.5, 16)
    kw = dict(tau_span=(0.0, 1.5), tau_eval=te, rtol=1e-10, k2_max=None, min_spin_ratio=0.0)
    k2 = np.array([0.3, 0.95])
    sol = ep.averaged(BODY, UPWARD, 0.0, 1.0, k2, 0.8, 0.3, **kw)
    assert [len(c) for c in sol.crossings] == [0, 1]
    for i in range(2):
        one = ep.averaged(BODY, UPWARD, 0.0, 1.0, float(k2[i]), 0.8, 0.3, **kw)
        assert sol.status[i] == one.status and sol.message[i] == one.message
        assert list(sol.kind[i]) == list(one.kind)
        for f in ("G", "T", "k2", "lam"):
            np.testing.assert_allclose(getattr(sol, f)[i], getattr(one, f), rtol=1e-9, atol=1e-12, err_msg=f)


CASE1 = np.diag([2.322, 1.31, 1.425])


def test_a_full_batch_member_alone_runs_as_its_single_call_through_the_branch_cut():
    # member 1 is refused (G0 < 0), so member 0 is alone in its mode: the scalar integrator inside the batch. Its
    # lambda passes through the branch cut of the azimuth at -pi (located by the cut events, also on the scalar
    # route: a member that loses them is off by 2 pi, or fails). The single call runs the same scalar DOP853 with
    # the same steps, so the two agree to rounding; 1e-9 relative leaves room for the output's interpolation.
    te = np.linspace(0.0, 0.3, 7)
    kw = dict(k2_0=0.9, delta0=1.2, lam0=-3.1, tau_span=(0.0, 0.3), tau_eval=te)
    one = ep.simulate(BODY, CASE1, 0.05, 1.0, **kw)
    sol = ep.simulate(BODY, CASE1, 0.05, np.array([1.0, -1.0]), **kw)
    assert one.lam[-1] < -np.pi < one.lam[0]  # the case crosses the cut
    assert sol.status.tolist() == [0, -1] and "G0 must be positive" in sol.message[1]
    for f in ("G", "T", "k2", "delta", "lam"):
        np.testing.assert_allclose(getattr(sol, f)[0], getattr(one, f), rtol=1e-9, atol=1e-12, err_msg=f)


def test_a_batch_of_the_angles_form_refuses_a_member_whose_start_is_singular():
    # the 'angles' formulation runs member by member (a mode per member); a member at sin(delta) = 0 gets the
    # single call's ValueError as its message (status -1) and the other runs as its single call (same route)
    te = np.linspace(0.0, 0.01, 3)
    kw = dict(k2_0=0.9, lam0=0.3, tau_span=(0.0, 0.01), tau_eval=te, formulation="angles")
    with pytest.raises(ValueError, match="singular at sin\\(delta\\) = 0") as exc:
        ep.simulate(BODY, CASE1, 0.02, delta0=0.0, **kw)
    sol = ep.simulate(BODY, CASE1, 0.02, delta0=np.array([0.0, 0.8]), **kw)
    one = ep.simulate(BODY, CASE1, 0.02, delta0=0.8, **kw)
    assert sol.status.tolist() == [-1, 0] and sol.message[0] == str(exc.value)
    np.testing.assert_allclose(sol.G[1], one.G, rtol=1e-12, atol=0)  # the same run: equal to rounding


def test_a_batch_of_a_torque_object_runs_each_member_as_its_single_call_through_the_separatrix():
    # the engine route (a torque object that is not the drag tensor's meaning): a mode per member on the scalar
    # integrator, a crossing a continued event; each member must be its single call (the same route and steps, so
    # equal to rounding; 1e-12 relative leaves room for nothing else), crossings and reports included
    tq = ep.LinearDrag(UPWARD)
    te = np.linspace(0.0, 1.5, 16)
    kw = dict(tau_span=(0.0, 1.5), tau_eval=te, k2_max=None, min_spin_ratio=0.0)
    k2 = np.array([0.3, 0.95])
    sol = ep.averaged(BODY, tq, 0.0, 1.0, k2, 0.8, 0.3, **kw)
    assert [len(c) for c in sol.crossings] == [0, 1]  # one member crosses into 'min', the other does not
    for i in range(2):
        one = ep.averaged(BODY, tq, 0.0, 1.0, float(k2[i]), 0.8, 0.3, **kw)
        assert sol.status[i] == one.status and sol.message[i] == one.message
        assert [c["region"] for c in sol.crossings[i]] == [c["region"] for c in one.crossings]
        assert list(sol.kind[i]) == list(one.kind)
        for f in ("G", "T", "k2", "lam"):
            np.testing.assert_allclose(getattr(sol, f)[i], getattr(one, f), rtol=1e-12, atol=0, err_msg=f)
