"""Batches of averaged evolutions, the accuracy the tolerance promises, and the kernels behind both.

Every batch member must be the single run it replaces; the relative accuracy of the decaying slow variables
is checked against the exact spin r = r0 exp(-b tau/C) of linear drag (3.3) and against an independent
straightforward integration of the same averaged system in (Gz, H, r).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.special import ellipe, ellipk

from rigidbody import lagrange as L
from rigidbody.lagrange import _kernel as K

TOP, DRAG = L.PAPER_TOP, L.PAPER_DRAG
A, C, MGL = TOP.A, TOP.C, TOP.mgl


def spun(theta_deg, r0=L.PAPER_R0):
    return L.integrals(TOP, 0.0, 0.0, r0, 0.0, math.radians(theta_deg))


# ------------------------------------------------------------------------------------------------- kernels
def test_drag_kernel_is_the_printed_closed_form():
    # the u-chart rates of the kernel, converted back to (u1, u2, u3), against (3.4) as printed (drag_rhs):
    # d atanh(u)/dtau = u'/(1 - u^2); d tan(theta/2)/dtau follows from Gz, r by the chain rule
    rng = np.random.default_rng(3)
    kd = K.drag_constants(A, C, MGL, DRAG.a, DRAG.b)
    for _ in range(20):
        u1, u2 = np.sort(rng.uniform(-0.95, 0.95, 2))
        u3 = 1.0 + rng.uniform(0.01, 2.0)
        d1, d2 = rng.choice([-1.0, 1.0], 2)
        Gz, H, r = L.from_roots(TOP, u1, u2, u3, d1, d2)
        x1, x2 = math.atanh(u1), math.atanh(u2)
        Sp, Sm = abs(Gz + C * r), abs(Gz - C * r)
        q = Sm / (math.hypot(Sp, Sm) + Sp)
        dx1, dx2, _ = K.u_drag_rates(K.SCALAR, kd, x1, x2, q, d1, d2)
        U = L.drag_rhs(TOP, DRAG, u1, u2, u3, d1, d2)
        # (3.4) loses digits to cancellation in its bracket (terms ~1 summing to ~|U|): compare to 1e-12 of the
        # terms' size
        assert dx1 * (1 - u1 * u1) == pytest.approx(U[0], rel=0, abs=1e-12)
        assert dx2 * (1 - u2 * u2) == pytest.approx(U[1], rel=0, abs=1e-12)
        # and the decoded state is (2.8)
        s = K.decode_u(K.SCALAR, A, C, MGL, x1, x2, q, d1, d2)
        np.testing.assert_allclose([s.Gz, s.H, s.r, s.u3], [Gz, H, r, u3], rtol=1e-12, atol=1e-14)


def test_fused_and_array_kernels_agree_with_the_three_step_route():
    # random admissible u-chart points: roots u1 < u2 in (-1, 1) (gaps down to e^-16), u3 - 1 in (1e-4, 3)
    rng = np.random.default_rng(4)
    m = 50
    x1 = rng.uniform(-8.0, 1.0, m)
    x2 = x1 + rng.uniform(1e-4, 2.0, m)
    w1, z1 = 2 / (1 + np.exp(-2 * x1)), 2 / (1 + np.exp(2 * x1))
    w2, z2 = 2 / (1 + np.exp(-2 * x2)), 2 / (1 + np.exp(2 * x2))
    c = rng.uniform(1e-4, 3.0, m)
    tan_th = np.sqrt(z1 * z2 * c / (w1 * w2 * (2 + c)))  # tan^2 theta = Pi-/Pi+
    q = tan_th / (1 + np.sqrt(1 + tan_th**2))  # tan(theta/2)
    d1 = rng.choice([-1.0, 1.0], m)
    d2 = rng.choice([-1.0, 1.0], m)
    kd = K.drag_constants(A, C, MGL, DRAG.a, DRAG.b)
    fused = np.array(K.u_drag_rates(K.ARRAY, kd, x1, x2, q, d1, d2))
    s = K.decode_u(K.ARRAY, A, C, MGL, x1, x2, q, d1, d2)
    route = np.array(K.u_chart_rates(K.ARRAY, A, C, MGL, s, *K.drag_means(K.ARRAY, A, C, MGL, DRAG.a, DRAG.b, s)))
    # the same formulas in another order of operations: rounding apart. Where u1 and u2 both lie near -1 below a
    # distant u3 (a fast-spinning top hanging with a small nutation) dx/dtau is a difference of terms up to
    # 1/(1 + u2) ~ 1e5 larger, and the rounding shows at 1e-10
    np.testing.assert_allclose(fused, route, rtol=1e-9, atol=0)
    tame = x1 > -3.0  # gaps above 2e-3: a few ulp
    np.testing.assert_allclose(fused[:, tame], route[:, tame], rtol=1e-12, atol=0)
    for i in range(0, m, 7):
        one = K.u_drag_rates(K.SCALAR, kd, float(x1[i]), float(x2[i]), float(q[i]), float(d1[i]), float(d2[i]))
        np.testing.assert_allclose(one, fused[:, i], rtol=1e-12, atol=0)  # the same code on floats


@pytest.mark.parametrize("k2", [1e-12, 1e-6, 0.01, 0.3, 0.9, 1 - 1e-9])
def test_sn2_excess_without_cancellation(k2):
    # <sn^2> - 1/2 = (1 - E/K)/k^2 - 1/2, cancellation-free by the AGM series: against mpmath at 60 digits (the
    # subtractions there cost at most ~25 of them at k^2 = 1e-12)
    mpmath = pytest.importorskip("mpmath")
    with mpmath.workdps(60):
        m = mpmath.mpf(k2)
        ref = float((1 - mpmath.ellipe(m) / mpmath.ellipk(m)) / m - mpmath.mpf(1) / 2)
    got = K.sn2_excess(K.SCALAR, k2, 1.0 - k2)
    assert got == pytest.approx(ref, rel=1e-14, abs=0)  # a few ulp of a positive sum
    arr = K.sn2_excess(K.ARRAY, np.array([k2, 0.5]), np.array([1.0 - k2, 0.5]))
    assert arr[0] == pytest.approx(got, rel=1e-14, abs=0)
    if k2 >= 0.3:  # where SciPy's E, K lose no more than a digit to the subtractions
        assert got == pytest.approx((1.0 - ellipe(k2) / ellipk(k2)) / k2 - 0.5, rel=1e-13, abs=0)


# ------------------------------------------------------------------------------- what the tolerance means
def _straight_reference(ini, T, te):
    """The averaged system (2.7) with (3.1) in plain (Gz, H, r): the cubic (1.5) solved by NumPy's companion
    matrix, <u> by SciPy's complete integrals, a pure relative tolerance 1e-13 -- an independent route."""
    def rhs(t, y):
        Gz, H, r = y
        c3, c2, c1, c0 = L.cubic_coefficients(TOP, Gz, H, r)
        u1, u2, u3 = np.sort(np.roots([c3, c2, c1, c0]).real)
        m = (u2 - u1) / (u3 - u1)
        mean_u = u1 + (u2 - u1) * (ellipk(m) - ellipe(m)) / (m * ellipk(m))  # <sn^2> = (K - E)/(k^2 K)
        # (2.7) with M1 = -a p, M2 = -a q, M3 = -b r: F linear in u = cos(theta), so <F> = F(<u>)
        F = DRAG.slow_rates(TOP, Gz, H, r, np.array([mean_u]))
        return [float(F[0][0]), float(F[1][0]), float(F[2][0])]

    return solve_ivp(rhs, (0, T), ini, method="DOP853", rtol=1e-13, atol=0.0, t_eval=te).y


@pytest.mark.parametrize("case", [1, 2, 3])
def test_relative_accuracy_of_decaying_slow_variables_over_the_paper_spans(case):
    # over the paper's spans r decays by e^-15 (cases 1, 2), Gz and H + mgl by similar factors; with rtol 1e-10
    # each keeps a relative error near 1e-10: the charts' coordinates carry relative error control, the
    # remaining factor (below 20 here) is the growth of local errors over ~30 steps and the 7th-order dense
    # output between long steps. The former absolute control gave 3e-6 in r at tau = 100 (case 2).
    T = L.PAPER_TAU_END[case]
    te = np.linspace(0.0, T, 76)
    ini = spun(L.PAPER_CASES[case])
    s = L.averaged(TOP, DRAG, ini, (0.0, T), tau_eval=te, rtol=1e-10)
    assert s.status == 0
    r_exact = math.sqrt(3.0) * np.exp(-DRAG.b * te / C)  # (3.3), exact
    assert r_exact[-1] < 4e-6 * math.sqrt(3.0) or case == 3
    np.testing.assert_allclose(s.r, r_exact, rtol=2e-9, atol=0)
    ref = _straight_reference(ini, T, te)
    np.testing.assert_allclose(s.Gz, ref[0], rtol=2e-9, atol=0)
    # the energy above the hanging state, H + mgl, decays like Gz; the reference's own error in it is ~1e-11
    np.testing.assert_allclose(s.H + MGL, ref[1] + MGL, rtol=2e-9, atol=0)


# -------------------------------------------------------------------------------------------------- batches
def _members():
    """A mix: the paper's cases (chart switches, delta1 flips), a fast sleeping top (GHr throughout), a
    non-spinning top (Gz = r = 0: the plain chart), random spun tops."""
    rng = np.random.default_rng(7)
    ini = [spun(5), spun(60), spun(170), L.integrals(TOP, 0.0, 0.0, 3.0, 0.0, 0.0),
           L.integrals(TOP, 0.0, 0.0, 0.0, 0.0, 1.0)]
    for th, r0 in zip(rng.uniform(20, 160, 7), rng.uniform(1.0, 2.5, 7)):
        ini.append(spun(th, r0))
    return np.array(ini)


def test_batch_members_equal_their_single_runs():
    ini = _members()
    te = np.linspace(0.0, 30.0, 31)
    b = L.averaged(TOP, DRAG, ini, (0.0, 30.0), tau_eval=te, rtol=1e-10)
    assert b.batch_shape == (len(ini),)
    assert b.Gz.shape == (len(ini), te.size) and b.u.shape == (len(ini), 3, te.size)
    for i in range(len(ini)):
        one = L.averaged(TOP, DRAG, ini[i], (0.0, 30.0), tau_eval=te, rtol=1e-10)
        m = b[i]
        assert m.status == one.status and m.event == one.event, (i, m.message, one.message)
        np.testing.assert_array_equal(m.tau, one.tau)
        # the same coordinates, tolerances and step control; NumPy's and libm's functions differ by an ulp, which
        # the step-size control may turn into a different step sequence: agreement to the global error, 1e-9
        for name in ("Gz", "r"):
            np.testing.assert_allclose(m[name], one[name], rtol=1e-9, atol=1e-13 * np.abs(one[name]).max())
        # H passes through zero: relative to its scale max(|H|, mgl)
        np.testing.assert_allclose(m.H, one.H, rtol=1e-9, atol=1e-9 * max(np.abs(one.H).max(), MGL))
        # roots: to 1e-9, except at a double root (the sleeping top, u1 = u2 = 1), where the roots of the cubic
        # are only sqrt(machine eps) ~ 1.5e-8 conditioned in either run
        np.testing.assert_allclose(m.u, one.u, rtol=0, atol=1e-9 if i != 3 else 1e-7)
        np.testing.assert_array_equal(m.chart, one.chart)
        np.testing.assert_allclose(m.t_events["chart_switch"], one.t_events["chart_switch"], rtol=0, atol=1e-8)
        np.testing.assert_allclose(m.t_events["delta1_flip"], one.t_events["delta1_flip"], rtol=0, atol=1e-8)


def test_batch_per_member_status_and_nan_tail():
    # case 3 with a loose degenerate_tol ends early by 'u1_eq_u2' (test_degenerate_state_ends_with_clear_status;
    # k^2 falls from 1.9e-3), a slow sleeping top sits on the separatrix (no average: refused as a member), case 2
    # (k^2 = 0.25 falling to ~0.04 by tau = 40) runs to the end
    ini = np.array([spun(170), L.integrals(TOP, 0.0, 0.0, 1.0, 0.0, 0.0), spun(60)])
    te = np.linspace(0.0, 40.0, 41)
    b = L.averaged(TOP, DRAG, ini, (0.0, 40.0), tau_eval=te, degenerate_tol=1e-3)
    assert list(b.status) == [1, -1, 0]
    assert b.event[0] == "u1_eq_u2" and "regular precession" in b.message[0]
    assert "separatrix" in b.message[1] and np.all(np.isnan(b.Gz[1]))
    assert b.event[2] is None and b.message[2] == "the end of tau_span was reached"
    one = L.averaged(TOP, DRAG, ini[0], (0.0, 40.0), degenerate_tol=1e-3)
    assert b.t_final[0] == pytest.approx(one.tau[-1], rel=0, abs=1e-8)  # event located to ~1e-12 of a step
    after = te > b.t_final[0]
    assert np.all(np.isnan(b.r[0, after])) and np.all(np.isfinite(b.r[0, ~after]))
    assert np.all(np.isfinite(b.r[2]))
    with pytest.raises(ValueError, match="separatrix"):
        L.averaged(TOP, DRAG, ini[1], (0.0, 1.0))  # the single call refuses the same state


def test_the_regular_precession_stop_names_the_options_that_go_on():
    # case 3 tends to a regular precession (u2 - u1 -> 0): with degenerate_tol = 1e-3 the u chart stops there
    # (tau = 19.8); its message names the two ways on, and each goes past: the (2.7)-averaged chart is regular
    # at u1 = u2 (to the end of the span), a smaller degenerate_tol stops later (k^2 falls below it later)
    ini = spun(170)
    s = L.averaged(TOP, DRAG, ini, (0.0, 30.0), degenerate_tol=1e-3)
    assert s.status == 1 and s.event == "u1_eq_u2"
    assert "pass chart='GHr'" in s.message and "a smaller degenerate_tol" in s.message
    g = L.averaged(TOP, DRAG, ini, (0.0, 30.0), degenerate_tol=1e-3, chart="GHr")
    assert g.status == 0 and g.tau[-1] == 30.0
    d = L.averaged(TOP, DRAG, ini, (0.0, 30.0), degenerate_tol=1e-5)
    assert d.tau[-1] > s.tau[-1]
    # a batch member stops with the same message
    b = L.averaged(TOP, DRAG, np.array([ini, spun(60)]), (0.0, 30.0), degenerate_tol=1e-3)
    assert b.event[0] == "u1_eq_u2" and b.message[0] == s.message


def test_batch_shape_and_default_grid():
    ini = np.array([[spun(40), spun(80), spun(120)], [spun(30), spun(90), spun(150)]])
    b = L.averaged(TOP, DRAG, ini, (0.0, 5.0))
    assert b.batch_shape == (2, 3)
    assert b.tau.shape == (101,) and b.r.shape == (2, 3, 101) and b.u.shape == (2, 3, 3, 101)
    assert b.status.shape == (2, 3) and np.all(b.status == 0)
    one = L.averaged(TOP, DRAG, ini[1, 2], (0.0, 5.0), tau_eval=b.tau)
    np.testing.assert_allclose(b[1, 2].r, one.r, rtol=1e-10, atol=0)  # rtol-1e-12 runs (the default)
    with pytest.raises(ValueError, match=r"batch_shape \+ \(3,\)"):
        L.averaged(TOP, DRAG, np.ones((4, 2)), (0.0, 1.0))


def test_batch_with_the_general_engine():
    # a torque without a closed form (class (2.4) with an axial motor): nutation means member by member
    motor = L.ProportionalTorque(f=lambda G, H, r, th: -0.125 * (1 + 0.5 * np.cos(th)),
                                 M3=lambda G, H, r, th: 0.15 - 0.1 * r + 0 * th)
    ini = np.array([spun(60), spun(100)])
    te = np.linspace(0.0, 3.0, 7)
    b = L.averaged(TOP, motor, ini, (0.0, 3.0), tau_eval=te, rtol=1e-10)
    for i in range(2):
        one = L.averaged(TOP, motor, ini[i], (0.0, 3.0), tau_eval=te, rtol=1e-10)
        np.testing.assert_allclose(b[i].r, one.r, rtol=1e-9, atol=0)  # as in the drag batch test
        np.testing.assert_allclose(b[i].Gz, one.Gz, rtol=1e-9, atol=0)


# ----------------------------------------------------------------------------------------------- simulate
def test_simulate_batch_members_equal_single_runs():
    # initial states and eps per member (eps broadcast over a (2, 3) batch); the same DOP853 on the same
    # equations: agreement to rounding, far below the rtol-1e-10 global error
    rng = np.random.default_rng(11)
    st = np.zeros((2, 3, 6))
    st[..., 0] = rng.uniform(-0.2, 0.2, (2, 3))
    st[..., 2] = rng.uniform(1.0, 2.5, (2, 3))
    st[..., 4] = rng.uniform(0.2, 2.9, (2, 3))
    st[0, 0, [0, 4]] = 0.0, math.pi  # spun and hanging at the pole: exact solution, theta stays pi
    eps = np.array([0.02, 0.05, 0.0])
    te = np.linspace(0.0, 30.0, 16)
    b = L.simulate(TOP, DRAG, eps, st, (0.0, 30.0), t_eval=te)
    assert b.batch_shape == (2, 3) and b.theta.shape == (2, 3, 16) and b.quat.shape == (2, 3, 4, 16)
    assert np.all(b.status == 0)
    for idx in np.ndindex(2, 3):
        one = L.simulate(TOP, DRAG, float(eps[idx[1]]), tuple(st[idx]), (0.0, 30.0), t_eval=te)
        m = b[idx]
        for name in ("p", "q", "r", "Gz", "H", "u"):
            np.testing.assert_allclose(m[name], one[name], rtol=0, atol=1e-11)
        np.testing.assert_allclose(m.tau, one.tau, rtol=1e-15, atol=0)
    assert np.all(b.theta[0, 0] == math.pi)
    np.testing.assert_allclose(b.H[:, 2], np.broadcast_to(b.H[:, 2, :1], (2, 16)), rtol=0, atol=1e-9)  # eps = 0


def test_simulate_batch_with_user_torque_functions():
    # class (2.4) with user functions of (Gz, H, r, theta): in a batch they receive arrays of members
    calls = []

    def f(G, H, r, th):
        calls.append(np.ndim(th))
        return -0.1 * (1 + 0.3 * np.cos(th))

    torque = L.ProportionalTorque(f=f, M3=lambda G, H, r, th: 0.05 - 0.1 * r)
    st = np.array([[0.1, 0.0, 1.5, 0.0, 1.0, 0.0], [0.0, 0.2, 2.0, 0.3, 2.0, 0.1]])
    te = np.linspace(0.0, 10.0, 6)
    b = L.simulate(TOP, torque, 0.05, st, (0.0, 10.0), t_eval=te)
    assert max(calls) == 1  # vectorised calls happened
    for i in range(2):
        one = L.simulate(TOP, torque, 0.05, tuple(st[i]), (0.0, 10.0), t_eval=te)
        np.testing.assert_allclose(b[i].r, one.r, rtol=0, atol=1e-11)  # rounding apart (see above)
    with pytest.raises(ValueError, match="broadcast"):
        L.simulate(TOP, DRAG, np.ones(3) * 0.01, np.zeros((2, 6)), (0.0, 1.0))
    with pytest.raises(ValueError, match="eps"):
        L.simulate(TOP, DRAG, np.array([0.01, -1.0]), np.zeros((2, 6)), (0.0, 1.0))
