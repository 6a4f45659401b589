"""Batches of Euler-Poinsot evolutions, and what the tolerance of one run means for its decaying variables.

Every batch member must be the single call it replaces (random members, including ones that stop early or are
refused); the relative accuracy of G, T and k^2 at ``rtol = 1e-10`` is checked against an independent,
straightforward integration of the same averaged system (9) in the paper's variables (G, k^2, delta, lambda)
with SciPy's complete elliptic integrals and a pure relative tolerance 1e-13.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.special import ellipe, ellipk

from rigidbody import euler_poinsot as ep

BODY = ep.Body(3.2, 2.6, 1.67)
CASE1 = np.diag([2.322, 1.31, 1.425])
CASE2 = np.diag([0.919, 5.228, 1.666])
# I11/A1 > I33/A3: k2 rises to the separatrix in finite time (members stop there, event 'separatrix')
UPWARD = np.diag([2.9, 1.31, 1.0])
RTOL = 1e-10
# a member and its single call integrate the same equations with the same step control; their step sequences
# part by rounding, so they differ by the integrators' own (global) error: a few rtol relative (G, T, k2) or
# radians (delta, lambda; lambda relatively beyond a radian)
AGREE = 30 * RTOL


def _rel(a, b):
    return np.max(np.abs(np.asarray(a) / np.asarray(b) - 1.0))


def _agree(member, single, fields=("G", "T", "k2", "delta", "lam", "nu")):
    assert member.status == single.status and member.event == single.event
    assert member.message == single.message
    np.testing.assert_array_equal(member.tau, single.tau)
    for f in ("G", "T"):
        assert _rel(getattr(member, f), getattr(single, f)) <= AGREE, f
    k2m, k2s = member.k2, single.k2
    nz = k2s > 0
    assert np.array_equal(k2m > 0, nz) and (not nz.any() or _rel(k2m[nz], k2s[nz]) <= AGREE)
    assert np.max(np.abs(member.delta - single.delta)) <= AGREE
    lam_s = single.lam
    assert np.max(np.abs(member.lam - lam_s) / np.maximum(1.0, np.abs(lam_s))) <= AGREE
    np.testing.assert_allclose(member.nu, single.nu, rtol=1e-14, atol=1e-12)
    np.testing.assert_allclose(member.n, single.n, rtol=0, atol=AGREE)


# ------------------------------------------------------------------------------------- members = single calls
@pytest.mark.parametrize("eps", [0.0, 0.01])
def test_batch_members_equal_their_single_calls(eps):
    rng = np.random.default_rng(7)
    B = 12
    k2 = rng.uniform(0.05, 0.95, B)
    k2[0] = 0.0  # an equilibrium of (8): k2 stays 0
    k2[1] = 0.9999  # reaches k2_max = 1 - 1e-6 at once: stops early (event), NaN after
    d0 = rng.uniform(0.0, math.pi, B)
    d0[2] = 0.0  # the pole, a fixed point of the gravity-gradient average
    l0 = rng.uniform(-3.0, 3.0, B)
    G0 = rng.uniform(0.5, 2.0, B)
    te = np.linspace(0.0, 2.0, 21)
    kw = dict(tau_span=(0.0, 2.0), tau_eval=te, rtol=RTOL, k2_max=1 - 1e-6)
    sol = ep.averaged(BODY, UPWARD, eps, G0, k2, d0, l0, **kw)
    assert sol.batch_shape == (B,) and sol.G.shape == (B, te.size) and sol.n.shape == (B, 3, te.size)
    for i in range(B):
        one = ep.averaged(BODY, UPWARD, eps, float(G0[i]), float(k2[i]), float(d0[i]), float(l0[i]), **kw)
        _agree(sol[i], one)
    assert sol.event[1] == "separatrix" and sol.status[1] == 1
    assert np.isnan(sol.G[1, -1]) and np.all(sol.k2[0] == 0.0)
    assert 1 < np.sum(sol.status == 1) < B  # several members stop early, the others reach the end


def test_members_refused_at_the_start_get_the_single_calls_message():
    k2 = np.array([0.5, 1.2, 0.9999, 0.3])
    eps = np.array([0.0, 0.0, 0.2, 0.01])
    sol = ep.averaged(BODY, CASE1, eps, 1.0, k2, 0.7, 0.3, tau_span=(0.0, 1.0), tau_eval=[0.0, 1.0])
    assert sol.status.tolist() == [0, -1, -1, 0]
    for i in (1, 2):
        with pytest.raises(ValueError) as err:
            ep.averaged(BODY, CASE1, float(eps[i]), 1.0, float(k2[i]), 0.7, 0.3, tau_span=(0.0, 1.0))
        assert sol.message[i] == str(err.value)
        assert np.all(np.isnan(sol.G[i]))
    assert np.all(np.isfinite(sol.G[[0, 3]]))


def test_inputs_broadcast_to_one_batch_shape():
    k2 = np.linspace(0.1, 0.9, 4)[:, None]  # (4, 1)
    eps = np.array([0.0, 0.02, 0.01])  # (3,)
    nu0 = np.array([0.0, 1.0, 2.0])
    te = np.linspace(0.0, 0.5, 6)
    sol = ep.averaged(BODY, CASE1, eps, 1.0, k2, 0.4, 0.2, (0.0, 0.5), te, nu0)
    assert sol.batch_shape == (4, 3) and sol.k2.shape == (4, 3, 6) and sol.status.shape == (4, 3)
    one = ep.averaged(BODY, CASE1, 0.02, 1.0, float(k2[2, 0]), 0.4, 0.2, (0.0, 0.5), te, 1.0)
    _agree(sol[2, 1], one)
    np.testing.assert_allclose(sol.nu[:, 1], np.broadcast_to(te / 0.02 + 1.0, (4, 6)), rtol=1e-15, atol=0)
    # the default output grid of a batch: 101 times over the span
    assert ep.averaged(BODY, CASE1, 0.0, 1.0, k2[:, 0], tau_span=(0.0, 0.5)).tau.size == 101
    with pytest.raises(ValueError, match="broadcast"):
        ep.averaged(BODY, CASE1, np.zeros(3), 1.0, np.full(4, 0.5))


def test_a_batch_of_drag_tensors():
    # one drag tensor per member (shape batch_shape + (3, 3)): each member is the single call with its tensor
    rng = np.random.default_rng(3)
    diag = rng.uniform(0.5, 3.0, (5, 3))
    I = np.array([np.diag(d) for d in diag])
    I[4] = -I[4]  # not dissipative: refused, with Drag's message
    te = np.linspace(0.0, 3.0, 7)
    sol = ep.averaged(BODY, I, 0.0, 1.0, 0.6, 0.5, 0.1, (0.0, 3.0), te)
    for i in range(4):
        _agree(sol[i], ep.averaged(BODY, I[i], 0.0, 1.0, 0.6, 0.5, 0.1, (0.0, 3.0), te))
    with pytest.raises(ValueError) as err:
        ep.Drag(I[4])
    assert sol.status[4] == -1 and sol.message[4] == str(err.value)


def test_the_engine_path_runs_member_by_member():
    tq = ep.LinearDrag(CASE1) + ep.GravityGradient(BODY) + ep.ConstantTorque([0.0, 0.0, 0.2])
    k2 = np.array([0.3, 0.6])
    te = np.linspace(0.0, 0.5, 6)
    sol = ep.averaged(BODY, tq, 0.0, 1.0, k2, 0.6, 0.2, (0.0, 0.5), te)
    for i in range(2):
        one = ep.averaged(BODY, tq, 0.0, 1.0, float(k2[i]), 0.6, 0.2, (0.0, 0.5), te)
        np.testing.assert_array_equal(sol.G[i], one.G)  # the very same call
        assert sol.quad_error[i] == one.quad_error


def test_batch_to_xarray_keeps_the_batch_axes():
    pytest.importorskip("xarray")
    k2 = np.array([0.2, 0.5, 0.8])
    sol = ep.averaged(BODY, CASE1, 0.0, 1.0, k2, tau_span=(0.0, 1.0), tau_eval=np.linspace(0, 1, 5))
    ds = sol.to_xarray(batch_dims={"k2_0": k2})
    assert ds["G"].dims == ("k2_0", "tau") and ds["n"].dims == ("k2_0", "component", "tau")
    np.testing.assert_array_equal(ds["G"].values, sol.G)


# ------------------------------------------------------------------------------------------ full equations
def test_simulate_batch_members_equal_their_single_calls():
    rng = np.random.default_rng(11)
    B = 5
    eps = rng.uniform(0.03, 0.05, B)
    k2 = rng.uniform(0.2, 0.8, B)
    d0 = rng.uniform(0.3, 2.8, B)
    l0 = rng.uniform(-3.0, 3.0, B)
    u0 = rng.uniform(0.0, 3.0, B)
    te = np.linspace(0.0, 0.3, 4)  # coarse: lambda's continuity must not rely on the output grid
    tq = ep.LinearDrag(CASE1) + ep.GravityGradient(BODY) + ep.ConstantTorque([0.0, 0.1, 0.2])
    for torque in (CASE1, tq):
        sol = ep.simulate(BODY, torque, eps, 1.0, k2, d0, l0, (0.0, 0.3), te, u0=u0, psi0=0.4, k2_max=1 - 1e-6)
        for i in range(B):
            one = ep.simulate(BODY, torque, float(eps[i]), 1.0, float(k2[i]), float(d0[i]), float(l0[i]),
                              (0.0, 0.3), te, u0=float(u0[i]), psi0=0.4, k2_max=1 - 1e-6)
            # the full motion over tau/eps^2 ~ 200 fast periods: the integrators' global error is ~1e-8 here
            for f in ("G", "T", "k2", "delta", "lam"):
                np.testing.assert_allclose(getattr(sol[i], f), getattr(one, f), rtol=0, atol=1e-7, err_msg=f)
            np.testing.assert_allclose(sol[i].g, one.g, rtol=0, atol=1e-7)


def test_simulate_batch_lambda_is_continuous_through_many_turns():
    # a magnet in a field along x3 turns G about x3 many times between two output times: the batch follows the
    # turns through its branch-cut events, the single run through its solver steps
    tq = ep.MagneticDipole([40.0, 0.0, 0.0], [0.0, 0.0, 1.0])
    te = np.array([0.0, 0.25, 0.5])
    eps = np.array([0.05, 0.04])
    sol = ep.simulate(BODY, tq, eps, 1.0, 0.3, 1.0, 0.0, (0.0, 0.5), te, k2_max=1 - 1e-6)
    for i in range(2):
        one = ep.simulate(BODY, tq, float(eps[i]), 1.0, 0.3, 1.0, 0.0, (0.0, 0.5), te, k2_max=1 - 1e-6)
        assert abs(one.lam[-1] - one.lam[0]) > 4.0 * math.pi  # several turns
        np.testing.assert_allclose(sol.lam[i], one.lam, rtol=1e-8, atol=0)


# --------------------------------------------------------------- what rtol means for the decaying variables
def _sn2(k2: float) -> float:
    """(K - E)/(k^2 K) from SciPy's complete integrals, or for k^2 < 0.1 (where K - E cancels) from the power
    series K = (pi/2) sum a_n^2 k^2n, K - E = (pi/2) sum a_n^2 k^2n 2n/(2n - 1), a_n = (1/2)_n/n! (40 terms,
    converged to rounding): an independent route to the elliptic means."""
    if k2 >= 0.1:
        K, E = ellipk(k2), ellipe(k2)
        return (K - E) / (K * k2)
    a, num, den = 1.0, 0.0, 1.0
    for n in range(1, 40):
        a *= (n - 0.5) / n
        num += a * a * k2 ** (n - 1) * 2 * n / (2 * n - 1)
        den += a * a * k2**n
    return num / den


def _straight(I, eps, y0, T, te):
    """(9) in (G, k2, delta, lambda) with (6)-(8) as printed, (7) regrouped as dk2/dt = k2 [(1 - chi)(s - 1) -
    (1 + chi) E/K]/N (1 - E/K = k2 s, s = (K - E)/(k2 K), so that dk2 keeps its relative accuracy as k2 -> 0),
    a pure relative tolerance 1e-13: an independent route to the same averaged system."""
    A1, A2, A3 = BODY.A1, BODY.A2, BODY.A3
    I11, I22, I33 = np.diag(I)
    N = A1 * A3 / (I33 * A1 - I11 * A3)
    chi = (2 * I22 * A1 * A3 - I11 * A2 * A3 - I33 * A1 * A2) / ((I33 * A1 - I11 * A3) * A2)

    def parts(k2):
        s = _sn2(k2)
        W = k2 * s
        e_k = 1.0 - W
        R = A1 * (A2 - A3) + A3 * (A1 - A2) * k2
        dGG = -(I22 * (A1 - A3) * W + I11 * (A2 - A3) * (1 - W) + I33 * (A1 - A2) * (k2 - W)) / R
        dk2 = k2 * ((1 - chi) * (s - 1) - (1 + chi) * e_k) / N
        Ns = A2 + A3 - 2 * A1 + 3 * (k2 * (A1 - A2) * (A1 - A3) / R) * (A3 + (A2 - A3) * s)
        return dGG, dk2, Ns

    def rhs(t, y):
        G, k2, d, lam = y
        dGG, dk2, Ns = parts(k2)
        if eps == 0.0:
            return [dGG * G, dk2, 0.0, 0.75 * Ns * math.cos(d) / G]
        x = t / eps - lam
        return [dGG * G, dk2, -1.5 * math.sin(x) * math.cos(x) * math.sin(d) * Ns / G,
                1.5 * math.cos(x) ** 2 * math.cos(d) * Ns / G]

    return solve_ivp(rhs, (0.0, T), y0, method="DOP853", rtol=1e-13, atol=0.0, t_eval=te).y


def _check_accuracy(sol, ref, lam_bound):
    assert sol.status == 0
    T_ref = ep.T_from(BODY, ref[0], ref[1])
    # relative errors of G, T, k2 near rtol however far they decay (global error of a 1e-10 local control over
    # a few dozen steps); the angles to rtol radians, lambda relatively once it exceeds a radian
    assert _rel(sol.G, ref[0]) < 5 * RTOL
    assert _rel(sol.T, T_ref) < 10 * RTOL
    assert _rel(sol.k2, ref[1]) < 5 * RTOL
    assert np.max(np.abs(sol.delta - ref[2])) < 5 * RTOL
    assert np.max(np.abs(sol.lam - ref[3]) / np.maximum(1.0, np.abs(ref[3]))) < lam_bound


@pytest.mark.parametrize("I, eps, T, k2_0", [
    (CASE1, 0.0, 30.0, 0.99),  # G decays by e^-12, lambda turns ~1e4 times
    (CASE2, 0.0, 20.0, 0.5),  # k2 -> 0: it decays by 6 orders
    (CASE1, 0.005, 3.0, 0.99),  # the paper's span with the true anomaly kept
])
def test_rtol_is_the_relative_accuracy_of_the_decaying_variables(I, eps, T, k2_0):
    te = np.linspace(0.0, T, 31)
    ref = _straight(I, eps, [1.0, k2_0, math.pi / 4, math.pi / 4], T, te)
    sol = ep.averaged(BODY, I, eps, 1.0, k2_0, math.pi / 4, math.pi / 4, (0.0, T), te, rtol=RTOL)
    _check_accuracy(sol, ref, 5 * RTOL)
    if I is CASE2:
        assert sol.k2[-1] < 1e-5 * k2_0  # the test covers the decayed range


@pytest.mark.parametrize("averaging", ["auto", "numerical"])
@pytest.mark.parametrize("I, eps, T, k2_0", [
    (CASE1, 0.0, 3.0, 0.99),  # the paper's span
    (CASE2, 0.0, 20.0, 0.5),  # k2 -> 0 by 21 orders, G by 3, lambda turns 260 times
    (CASE1, 0.005, 3.0, 0.99),  # the true anomaly kept
])
def test_rtol_is_the_relative_accuracy_with_torque_objects(I, eps, T, k2_0, averaging):
    # the paper's two torques as objects (their closed forms, or the averaging engine for every part) are integrated
    # in (ln G, ln k2, delta, lambda) like the drag tensor, or with the unit vector of G where the torque turns it
    # about another axis than x3: the same meaning of rtol against the same independent route
    if averaging == "numerical" and eps > 0.0:
        T = 0.3  # the engine resolving every orbit costs ~60 us per right-hand side: a tenth of the span
    if averaging == "numerical" and I is CASE2:
        T = 6.0  # k2 falls by 6 orders to 3e-7: the engine has the relative accuracy of dk2 down to k2 ~ 1e-10
    te = np.linspace(0.0, T, 31)
    ref = _straight(I, eps, [1.0, k2_0, math.pi / 4, math.pi / 4], T, te)
    tq = ep.LinearDrag(I) + ep.GravityGradient(BODY)
    sol = ep.averaged(BODY, tq, eps, 1.0, k2_0, math.pi / 4, math.pi / 4, (0.0, T), te, rtol=RTOL, averaging=averaging)
    # as for the drag tensor (the test above); the engine adds its quadrature error (quad_tol 1e-12 of the torque).
    # lambda between the steps comes from DOP853's 7th-order interpolant, whose error exceeds the steps' (the drag
    # tensor's own reaches 6.5e-10 at mid-step in case 1): its bound is 10 rtol
    _check_accuracy(sol, ref, 10 * RTOL)
    if I is CASE2:  # the test covers the decayed range and the turns
        assert sol.k2[-1] < (1e-20 if averaging == "auto" else 1e-6) and abs(ref[3][-1]) > 20.0


@pytest.mark.parametrize("eps", [0.0, 0.01])
def test_batch_members_cross_the_separatrix_as_their_single_calls(eps):
    # k2_max=None: a member that reaches the separatrix crosses into the other kind of motion (capture
    # probabilities at its crossing state) and goes on in the next round; the others are unaffected
    k2 = np.array([0.3, 0.95, 0.99, 0.6])
    te = np.linspace(0.0, 1.5, 16)
    kw = dict(tau_span=(0.0, 1.5), tau_eval=te, rtol=RTOL, k2_max=None, min_spin_ratio=0.0)
    sol = ep.averaged(BODY, UPWARD, eps, 1.0, k2, 0.8, 0.3, **kw)
    crossed = 0
    for i in range(k2.size):
        one = ep.averaged(BODY, UPWARD, eps, 1.0, float(k2[i]), 0.8, 0.3, **kw)
        _agree(sol[i], one)
        assert list(sol.kind[i]) == list(one.kind) and list(sol.sigma[i]) == list(one.sigma)
        single = getattr(one, "crossings", [])  # a single run that did not cross has none
        assert len(sol.crossings[i]) == len(single)
        for a, b in zip(sol.crossings[i], single):
            # the crossing time inherits the run's relative accuracy; the same region from the same probabilities
            assert a["tau"] == pytest.approx(b["tau"], rel=AGREE, abs=0) and a["region"] == b["region"]
            assert a["probabilities"] == pytest.approx(b["probabilities"], rel=1e-6, abs=1e-9)
        np.testing.assert_allclose(sol.t_events["separatrix"][i], one.t_events["separatrix"], rtol=AGREE, atol=0)
        crossed += bool(single)
    assert 0 < crossed < k2.size  # some members cross, some do not


def test_the_single_runs_folded_right_hand_sides_are_the_kernels():
    # one run integrates closures with the constants folded in; a batch the generic kernels: the same arithmetic
    from rigidbody.core.kernel import ARRAY, SCALAR
    from rigidbody.euler_poinsot import _kernel as K

    A = (BODY.A1, BODY.A2, BODY.A3)
    co = K.DragCoefficients(A, (2.322, 1.31, 1.425))
    rng = np.random.default_rng(5)
    for _ in range(20):
        tau, lnG, s, de, la = (rng.uniform(a, b) for a, b in ((0, 3), (-5, 1), (-30, 0), (0, 3), (-9, 9)))
        for z in (0.0, 1.0):
            f = K.scalar_rhs(A, co.args(), z, 0.0, True, hl=0.4)
            assert f(tau, [lnG, s, la]) == pytest.approx(K.rhs_limit(SCALAR, A, tau, [lnG, s, la], *co.args(), z,
                                                                     0.4), rel=1e-14, abs=1e-300)
            g = K.scalar_rhs(A, co.args(), z, 0.0, False, ie=100.0, nu0=0.3)
            y = [lnG, s, de, la]
            ref = K.rhs_orbit(SCALAR, A, 0.0, tau, y, *co.args(), z, 100.0, 0.3)
            assert g(tau, y) == pytest.approx(ref, rel=1e-13, abs=1e-15)
            arr = K.rhs_orbit(ARRAY, A, 0.0, np.array([tau]), [np.array([v]) for v in y],
                              *(np.array([c]) for c in co.args()), np.array([z]), np.array([100.0]), np.array([0.3]))
            assert [float(v[0]) for v in arr] == pytest.approx(ref, rel=1e-13, abs=1e-15)


def test_the_papers_torques_as_objects_run_the_vectorised_closed_forms():
    # LinearDrag + GravityGradient is the drag tensor's meaning: its batch runs the same vectorised closed forms
    # (identical numbers); each member equals its single call, which integrates (G, k2, n) with the catalogue's
    # closed forms per state (rtol 1e-10 each: their global errors, ~1e-9 here, set the agreement)
    tq = ep.LinearDrag(CASE1) + ep.GravityGradient(BODY)
    k2 = np.array([0.2, 0.6, 0.9])
    te = np.linspace(0.0, 2.0, 9)
    for eps in (0.0, 0.01):
        sol = ep.averaged(BODY, tq, eps, 1.0, k2, 0.7, 0.3, (0.0, 2.0), te)
        ref = ep.averaged(BODY, CASE1, eps, 1.0, k2, 0.7, 0.3, (0.0, 2.0), te)
        np.testing.assert_array_equal(sol.G, ref.G)
        np.testing.assert_array_equal(sol.lam, ref.lam)
        for i in range(k2.size):
            one = ep.averaged(BODY, tq, eps, 1.0, float(k2[i]), 0.7, 0.3, (0.0, 2.0), te)
            for f in ("G", "T", "k2", "delta", "lam"):
                np.testing.assert_allclose(getattr(sol[i], f), getattr(one, f), rtol=1e-8, atol=1e-8, err_msg=f)
