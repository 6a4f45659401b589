"""The averaged right-hand sides (6) against numerical averages over the closed-form Euler-Poinsot motion."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rigidbody import euler_poinsot as ep
from rigidbody.core import elliptic as ell
from rigidbody.core import euler

BODY = ep.Body(3.2, 2.6, 1.67)
NPSI = 8  # the torques are trigonometric polynomials of degree <= 2 in psi: 8 nodes average them exactly


def numerical_average_torque(body, I, G, k2, kind, delta, lam, nu, n=None):
    """Mean of the unaveraged torque (3) in Oy over psi (uniform) and over one period of the closed form."""
    m = ep.EulerPoinsot(body, G, k2, kind)
    t, g = m.nodes(n)
    omega = g / body.A[:, None]
    theta = np.arctan2(np.hypot(g[0], g[1]), g[2])
    phi = np.arctan2(g[0], g[1])
    psi = np.arange(NPSI) * 2 * np.pi / NPSI
    alpha = euler.dcm(psi[:, None], theta[None, :], phi[None, :])  # (npsi, n, 3, 3): alpha_ij = y_i . z_j
    # independent check of the angle convention: the third row of alpha is g / G
    np.testing.assert_allclose(alpha[0, :, 2, :], (g / G).T, atol=1e-14)
    beta = np.array([math.cos(nu - lam) * math.cos(delta), math.sin(nu - lam), math.cos(nu - lam) * math.sin(delta)])
    S = np.einsum("...ip,p,...jp->...ij", alpha, body.A, alpha)
    Lg = 3.0 * np.cross(beta, np.einsum("...ij,j->...i", S, beta))
    Lr = -np.einsum("...mi,ij,j...->...m", alpha, I, omega)
    power = -np.einsum("in,ij,jn->n", omega, I, omega)  # dT/dt = omega . L^r (gravity: zero mean)
    return Lg.mean(axis=(0, 1)), Lr.mean(axis=(0, 1)), power.mean()


@settings(max_examples=25, deadline=None)
@given(
    k2=st.floats(1e-4, 0.995),
    G=st.floats(0.2, 3.0),
    delta=st.floats(0.05, 3.09),
    lam=st.floats(-3.1, 3.1),
    nu=st.floats(-3.1, 3.1),
    off=st.lists(st.floats(-0.4, 0.4), min_size=6, max_size=6),
    kind=st.sampled_from(["max", "min"]),
)
def test_averaged_terms_of_6_equal_numerical_averages(k2, G, delta, lam, nu, off, kind):
    I = np.diag([2.322, 1.31, 1.425])
    I[0, 1], I[1, 0], I[0, 2], I[2, 0], I[1, 2], I[2, 1] = off  # off-diagonal drag: must drop out
    Lg, Lr, power = numerical_average_torque(BODY, I, G, k2, kind, delta, lam, nu)
    r = ep.averaged_rates(BODY, I, G, k2, delta, lam, nu, kind=kind)
    # trapezoid rule on the elliptic phase with core.n_nodes: ~1e-13 relative; torques are O(10)
    tol = 1e-11
    # drag: averaged L^r has no components across G (drops out of the delta, lambda equations)
    assert abs(Lr[0]) < tol and abs(Lr[1]) < tol
    assert r["dG"] == pytest.approx(Lr[2] + Lg[2], abs=tol)
    assert abs(Lg[2]) < tol  # gravity does not change G on average
    assert r["dT"] == pytest.approx(power, abs=tol)
    # gravity: d delta/dt = L1/G, d lambda/dt = L2/(G sin delta)
    assert r["ddelta"] == pytest.approx((Lg[0] + Lr[0]) / G, abs=tol / G)
    assert r["dlam"] == pytest.approx((Lg[1] + Lr[1]) / (G * math.sin(delta)), abs=tol / (G * math.sin(delta)))
    # the off-diagonal entries drop out: the module gives the same with the diagonal alone
    rd = ep.averaged_rates(BODY, np.diag(np.diag(I)), G, k2, delta, lam, nu, kind=kind)
    assert rd == pytest.approx(r, rel=1e-15, abs=0)


def printed_dT(body, I, G, k2):
    """dT/dt exactly as printed in (6) (with 2T from (5))."""
    A1, A2, A3 = body.A1, body.A2, body.A3
    I11, I22, I33 = I[0, 0], I[1, 1], I[2, 2]
    k = math.sqrt(k2)
    W = 1 - ell.E(k) / ell.K(k)
    R = A1 * (A2 - A3) + A3 * (A1 - A2) * k2
    S = A2 - A3 + (A1 - A2) * k2
    AA = (A1 - A2) * (A1 - A3) * (A2 - A3)
    T = ep.T_from(body, G, k2)
    return -2 * T / R * (
        I22 * (A1 - A3) * W + I33 * (A1 - A2) * (k2 - W)
        + AA / S * (I33 / A3 * (k2 - W) + I22 / A2 * (1 - k2) * W)
        + I11 / A1 * (A2 - A3) * R / S * (1 - W)
    )


@pytest.mark.parametrize("k2", [0.01, 0.3, 0.7, 0.99])
def test_printed_dT_equals_the_implemented_form(k2):
    I = np.diag([0.919, 5.228, 1.666])
    # algebraic identity with 2T = G^2 S/R: agreement to rounding
    assert ep.drag_rates(BODY, I, 1.3, k2)[1] == pytest.approx(printed_dT(BODY, I, 1.3, k2), rel=1e-13, abs=0)


def test_N_star_is_the_mean_moment_about_G():
    # independent meaning: N* = A1 + A2 + A3 - 3 <J_GG>, J_GG = sum A_j (g_j/G)^2 averaged over the motion
    for kind in ("max", "min"):
        for k2 in (0.0, 0.2, 0.8, 0.999):
            m = ep.EulerPoinsot(BODY, 1.0, k2, kind)
            _, g = m.nodes()
            JGG = (BODY.A[:, None] * g**2).sum(0).mean()
            assert ep.N_star(BODY, k2, kind) == pytest.approx(BODY.A.sum() - 3 * JGG, abs=1e-12)


def test_limits_k2_to_0_and_1_are_finite_and_continuous():
    I = np.diag([2.322, 1.31, 1.425])
    for kind in ("max", "min"):
        for name in ("dG", "dT", "dk2", "ddelta", "dlam"):
            f = [ep.averaged_rates(BODY, I, 1.0, x, 0.7, 0.2, 0.4, kind=kind)[name] for x in (0.0, 1e-12, 1e-8)]
            assert all(np.isfinite(f))
            # O(k2) continuity at 0 (series: W = k2/2 + O(k2^2))
            assert f[1] == pytest.approx(f[0], abs=1e-10) and f[2] == pytest.approx(f[0], abs=1e-6)
            g = [ep.averaged_rates(BODY, I, 1.0, 1 - x, 0.7, 0.2, 0.4, kind=kind)[name] for x in (0.0, 1e-14, 1e-10)]
            assert all(np.isfinite(g))
            # the approach to the separatrix is logarithmic: E/K ~ 1/ln(4/k') ~ 0.06 at k' = 1e-7
            assert g[1] == pytest.approx(g[0], abs=0.2 * max(1.0, abs(g[0])))


def test_regular_at_sin_delta_zero():
    I = np.diag([2.322, 1.31, 1.425])
    r = ep.averaged_rates(BODY, I, 1.0, 0.5, 0.0, 0.3, 1.0)
    assert all(np.isfinite(list(r.values())))
    assert r["ddelta"] == 0.0


def test_G_and_T_strictly_decrease_for_every_k2():
    rng = np.random.default_rng(5)
    for _ in range(20):
        d = rng.uniform(0.01, 5.0, 3)
        for k2 in np.linspace(0.0, 1.0, 21):
            for kind in ("max", "min"):
                dG, dT = ep.drag_rates(BODY, np.diag(d), 1.0, k2, kind)
                assert dG < 0 and dT < 0


@settings(max_examples=20, deadline=None)
@given(G0=st.floats(0.5, 50.0), Omega0=st.floats(0.5, 20.0), omega0=st.floats(1e-3, 0.05),
       scale=st.floats(0.1, 10.0), k2=st.floats(0.0, 0.99), nu=st.floats(-3.0, 3.0))
def test_dimensional_6_and_nondimensional_9_are_the_same_system(G0, Omega0, omega0, scale, k2, nu):
    # sec. 3 scaling: A~ = A Omega0/G0, eps = omega0/Omega0, eps^2 I~ = I/G0, tau = eps^2 Omega0 t,
    # T~ = T/(G0 Omega0). (9) per tau is (6) with omega0 = 1 and I~.
    Adim = ep.Body(3.2 * scale, 2.6 * scale, 1.67 * scale)
    Idim = np.diag([2.322, 1.31, 1.425]) * scale * 1e-3
    G = 0.7 * G0
    eps = omega0 / Omega0
    And = ep.Body(*(Adim.A * Omega0 / G0))
    Ind = Idim / (G0 * eps**2)
    d = ep.averaged_rates(Adim, Idim, G, k2, 0.6, 0.2, nu, omega0=omega0)
    n = ep.averaged_rates(And, Ind, G / G0, k2, 0.6, 0.2, nu)
    rate = eps**2 * Omega0  # d/dt = rate * d/dtau
    # the same floating-point expressions up to rescaling: agreement to rounding (1e-12 relative)
    assert d["dG"] == pytest.approx(G0 * rate * n["dG"], rel=1e-12, abs=0)
    assert d["dT"] == pytest.approx(G0 * Omega0 * rate * n["dT"], rel=1e-12, abs=0)
    assert d["dk2"] == pytest.approx(rate * n["dk2"], rel=1e-12, abs=1e-300)
    assert d["ddelta"] == pytest.approx(rate * n["ddelta"], rel=1e-12, abs=1e-300)
    assert d["dlam"] == pytest.approx(rate * n["dlam"], rel=1e-12, abs=1e-300)


def test_motion_average_method_reproduces_the_independent_average():
    I = np.array([[2.0, 0.3, 0.1], [0.0, 1.0, -0.2], [0.1, 0.2, 1.5]])
    G, k2, delta, lam, nu = 1.2, 0.6, 0.9, 0.3, -0.5
    Lg, Lr, _ = numerical_average_torque(BODY, I, G, k2, "max", delta, lam, nu)
    beta = np.array([math.cos(nu - lam) * math.cos(delta), math.sin(nu - lam), math.cos(nu - lam) * math.sin(delta)])

    def torque(alpha, omega):
        S = np.einsum("...ip,p,...jp->...ij", alpha, BODY.A, alpha)
        return 3.0 * np.cross(beta, S @ beta) - np.einsum("...mi,ij,...j->...m", alpha, I, omega)

    m = ep.EulerPoinsot(BODY, G, k2)
    assert m.average(torque) == pytest.approx(Lg + Lr, abs=1e-12)


@pytest.mark.parametrize("orbit", [None, ep.Orbit(0.3)])
@pytest.mark.parametrize("nu0", [0.0, 1.1, -2.5])
def test_integrator_starts_on_the_rates_of_6(nu0, orbit):
    # The integrated system (unit-vector form) has, at tau = 0, the right-hand sides of (6)/(9) evaluated at
    # nu = nu0 (those are checked above against numerical averages): guards the nu0 phase and the
    # n <-> (delta, lambda) map of the integrator.
    I = np.diag([2.322, 1.31, 1.425])
    eps, h = 0.02, 1e-6
    kw = dict(G0=0.8, k2_0=0.6, delta0=1.0, lam0=0.3, nu0=nu0, orbit=orbit, rtol=1e-13, atol=1e-15)
    s = ep.averaged(BODY, I, eps, tau_span=(0, 2 * h), tau_eval=[0, h, 2 * h], **kw)
    r = ep.averaged_rates(BODY, I, 0.8, 0.6, 1.0, 0.3, nu0, orbit=orbit)
    # second-order one-sided difference: truncation h^2 |f'''| / 3 ~ 1e-12 * 5 / eps^2 ~ 1e-8 (the rates
    # vary at the orbital rate 1/eps in tau), rounding ~ 1e-16 / h = 1e-10
    for name, field in (("dG", "G"), ("dk2", "k2"), ("ddelta", "delta"), ("dlam", "lam")):
        y = getattr(s, field)
        assert (-3 * y[0] + 4 * y[1] - y[2]) / (2 * h) == pytest.approx(r[name], abs=1e-7), name
