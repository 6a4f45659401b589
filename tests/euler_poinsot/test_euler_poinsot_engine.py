"""The averaging engine against independent routes: the closed forms (6), an independent average over the
closed-form motion, exact averages of non-smooth torques, and the dispatch of averaged_rates/averaged."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from rigidbody import euler_poinsot as ep
from rigidbody.core import averaging as avg

BODY = ep.Body(3.2, 2.6, 1.67)
I_OFF = np.array([[2.322, 0.3, -0.2], [0.1, 1.31, 0.4], [0.25, -0.15, 1.425]])
CASE1 = np.diag([2.322, 1.31, 1.425])
EPS64 = 2.2e-16
DELTA, LAM = 1.0, 0.3


def frame(delta, lam):
    """Columns y1, y2, y3 of the frame of G in the orbital axes (the paper's Oy)."""
    sd, cd, sl, cl = math.sin(delta), math.cos(delta), math.sin(lam), math.cos(lam)
    return np.array([[cd * cl, -sl, sd * cl], [cd * sl, cl, sd * sl], [-sd, 0.0, cd]])


# --------------------------------------------------------------------------------------------------
# the closed forms of (6)
# --------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("kind", ["max", "min"])
@pytest.mark.parametrize("k2", [1e-8, 1e-4, 0.3, 0.9, 1 - 1e-4, 1 - 1e-8])
@pytest.mark.parametrize("nu", [0.7, None])
def test_engine_reproduces_the_closed_forms_of_6(kind, k2, nu):
    # The engine (trapezoid rule over psi, the elliptic phase and, for nu = None, the orbit) against the
    # closed forms of (6)/(8) for the paper's two torques, separately: the drag with off-diagonal entries
    # (they average out) and the gravity gradient (N* of (6)).
    drag, grav = ep.LinearDrag(I_OFF), ep.GravityGradient(BODY)
    for tq in (drag, grav):
        closed = ep.averaged_rates(BODY, tq, 1.3, k2, DELTA, LAM, nu, kind=kind)
        eng = ep.average_torque(BODY, tq, 1.3, k2, DELTA, LAM, nu, kind=kind)
        assert eng.converged
        # the torque across and along G, L_y = (G ddelta, G sin(delta) dlam, dG)
        Ly = lambda r: np.array([1.3 * r["ddelta"], 1.3 * math.sin(DELTA) * r["dlam"], r["dG"]])  # noqa: E731
        Lc, Le = Ly(closed), Ly(eng.rates)
        # 1e-12 relative to the size of the averaged torque (the requirement)
        assert np.abs(Le - Lc).max() <= 1e-12 * np.abs(Lc).max()
        if tq is drag:
            assert eng.rates["dT"] == pytest.approx(closed["dT"], rel=1e-12, abs=0)
            diff = abs(eng.rates["dk2"] - closed["dk2"])
            if k2 >= 1e-6:
                assert diff <= 1e-12 * abs(closed["dk2"])
            else:
                # dk2 = O(k2) is a mean of terms omega_i M_i of which the off-diagonal drag makes O(k) with zero
                # mean: their rounding (eps k) limits the relative accuracy to ~eps/k (2e-12 at k2 = 1e-8); the
                # engine's reported error accounts for it
                assert diff <= 1e-12 * abs(closed["dk2"]) + eng.error["dk2"]
                assert diff <= 16 * EPS64 / math.sqrt(k2) * abs(closed["dk2"])
        else:  # gravity changes neither G, T nor k2 on average: zero to rounding of the torque's size
            scale = np.abs(Lc).max()
            assert abs(eng.rates["dT"]) < 1e-14 * scale and abs(eng.rates["dk2"]) < 1e-14 * scale
        # the reported errors bound the actual ones (here: the difference from the closed form)
        assert np.abs(Le - Lc).max() <= 2 * max(eng.error["dG"], 1e-14 * np.abs(Lc).max())


@pytest.mark.parametrize("orbit", [ep.Orbit(0.3), ep.Orbit(0.7)])
def test_engine_orbit_average_uses_keplers_law(orbit):
    # nu = None on an eccentric orbit: the mean over time weights nu by (1 + e cos nu)^-2; the closed form
    # has the factor (1 - e^2)^(-3/2) (orbit.mean_factor)
    grav = ep.GravityGradient(BODY, orbit)
    closed = ep.averaged_rates(BODY, grav, 1.0, 0.6, DELTA, LAM, None, orbit=orbit)
    eng = ep.average_torque(BODY, grav, 1.0, 0.6, DELTA, LAM, None, orbit=orbit)
    assert eng.rates["dlam"] == pytest.approx(closed["dlam"], rel=1e-12, abs=0)
    assert abs(eng.rates["ddelta"]) < 1e-13 * abs(closed["dlam"])
    # e = 0.7 needs more orbit nodes than e = 0.3 (the weight has poles at 1 + e cos nu = 0, nearer for
    # larger e): the node count follows the smoothness
    assert eng.nodes[2] >= 8


# --------------------------------------------------------------------------------------------------
# any torque: an independent average over the closed-form motion
# --------------------------------------------------------------------------------------------------
def odd_torque(omega, C, nu):
    """A torque that is not odd in omega (constant body part, quadratic part) and depends on the attitude and
    the true anomaly: a test of the general protocol."""
    e_r = np.stack([np.cos(nu), np.sin(nu), np.zeros_like(nu)], axis=-1)
    rho = np.einsum("...ij,...i->...j", C, e_r)  # C^T e_r
    sun = np.einsum("...ij,i->...j", C, [0.6, 0.0, 0.8])  # a fixed direction in Ox, in body axes
    w = np.asarray(omega)
    return (np.array([0.2, -0.1, 0.15]) + 0.3 * np.cross(w, rho) * rho[..., :1]
            + 0.05 * w * np.sum(w * w, axis=-1, keepdims=True) + 0.4 * sun * sun[..., 2:3])


def independent_average(torque, G, k2, kind, sigma, delta, lam, nu, n_psi=16):
    """<C M> and <omega . M> by EulerPoinsot.average (its own attitude construction and node set), and dk2
    by the chain rule of (5) in G and T (which cancels as k2 -> 0, not at the k2 used here)."""
    m = ep.EulerPoinsot(BODY, G, k2, kind, sigma)
    Y = frame(delta, lam)
    n = 2 * avg.n_nodes(mc=1 - k2, period="4K")

    def f(alpha, omega):
        C = Y @ alpha
        om = np.broadcast_to(omega, (*alpha.shape[:2], 3))
        M = torque(om, C, np.full(alpha.shape[:2], nu))
        CM = np.einsum("...ij,...j->...i", C, M)
        return np.concatenate([CM, np.sum(om * M, axis=-1)[..., None]], axis=-1)

    out = m.average(f, n=n, n_psi=n_psi)
    L, dT = out[:3], out[3]
    dG = L @ Y[:, 2]
    T = m.T
    A1, A2, A3 = BODY.A if kind == "max" else BODY.A[::-1]

    P, Q = 2 * T * A1 - G * G, G * G - 2 * T * A3  # k2 = c P / Q, (5)
    dP, dQ = 2 * A1 * dT - 2 * G * dG, 2 * G * dG - 2 * A3 * dT
    dk2 = (A2 - A3) / (A1 - A2) * (dP * Q - P * dQ) / Q**2
    return L, dT, dk2


@pytest.mark.parametrize("kind", ["max", "min"])
@pytest.mark.parametrize("sigma", [1, -1])
def test_engine_equals_an_independent_average_for_any_torque(kind, sigma):
    G, k2, nu = 1.2, 0.7, 0.4
    L, dT, dk2 = independent_average(odd_torque, G, k2, kind, sigma, DELTA, LAM, nu)
    eng = ep.average_torque(BODY, odd_torque, G, k2, DELTA, LAM, nu, kind=kind, sigma=sigma)
    Y = frame(DELTA, LAM)
    # both are spectrally accurate trapezoid rules (the torque is a polynomial in C of degree 3 in psi, exact on
    # 16 psi nodes): rounding only
    np.testing.assert_allclose(eng.L, L, rtol=0, atol=1e-13)
    assert eng.rates["dG"] == pytest.approx(L @ Y[:, 2], abs=1e-13)
    assert eng.rates["dT"] == pytest.approx(dT, abs=1e-13)
    # the chain rule loses about one digit to cancellation in dP and dQ at this k2
    assert eng.rates["dk2"] == pytest.approx(dk2, abs=1e-12)


def test_the_sense_of_rotation_matters_for_torques_not_odd_in_omega():
    # a constant body-fixed torque: its mean along G is <g> . M0 / G, and <g_1> = sigma A1 a1 pi/(2K) for 'max'
    M0 = np.array([0.3, 0.2, -0.1])

    def const(omega, C, nu):
        return np.broadcast_to(M0, np.shape(omega))

    r = {s: ep.average_torque(BODY, const, 1.0, 0.5, DELTA, LAM, None, sigma=s).rates for s in (1, -1)}
    assert r[1]["dG"] == pytest.approx(-r[-1]["dG"], rel=1e-12, abs=0)
    assert abs(r[1]["dG"]) > 0.1
    # the paper's torques do not care (quadratic in omega, or independent of it)
    d = {s: ep.average_torque(BODY, CASE1, 1.0, 0.5, DELTA, LAM, 0.3, sigma=s).rates for s in (1, -1)}
    assert d[1] == pytest.approx(d[-1], rel=1e-12, abs=1e-15)


# --------------------------------------------------------------------------------------------------
# non-smooth torques: the engine must not claim spectral accuracy
# --------------------------------------------------------------------------------------------------
SUN = np.array([0.48, -0.6, 0.64])  # a unit vector in Ox
P_BODY = np.array([0.1, 0.4, -0.2])


def illuminated(omega, C, nu):
    """A torque proportional to the illumination max(0, cos) of the body face with normal z1: a kink."""
    cos_i = np.einsum("...i,i->...", C[..., :, 0], SUN)
    return np.maximum(cos_i, 0.0)[..., None] * P_BODY


def test_reported_error_bounds_the_true_error_for_a_kinked_torque():
    # reference for dT = <max(0, s . C z1)> (omega . p): the psi-mean of max(0, a + b cos psi) is exact,
    # (a psi0 + b sin psi0)/pi with psi0 = arccos(-a/b), leaving a one-dimensional integral over the period
    # done by adaptive quadrature (independent of the engine's grids)
    G, k2, kind = 1.0, 0.6, "max"
    m = ep.EulerPoinsot(BODY, G, k2, kind)
    Y = frame(DELTA, LAM)
    s_y = Y.T @ SUN  # the sun in Oy

    def dT_density(t):
        g = m.g(t)
        om = g / BODY.A
        _, theta, phi = m.angles(t)
        v = np.array([math.cos(phi), math.cos(theta) * math.sin(phi), math.sin(theta) * math.sin(phi)])  # z1 in Oy
        a = s_y[2] * v[2]
        b = math.hypot(s_y[0], s_y[1]) * math.hypot(v[0], v[1])
        if b <= abs(a):
            mean = max(a, 0.0)
        else:
            psi0 = math.acos(-a / b)
            mean = (a * psi0 + b * math.sin(psi0)) / math.pi
        return mean * float(om @ P_BODY)

    ref = quad(dT_density, 0.0, m.period, epsabs=1e-13, epsrel=1e-12, limit=400)[0] / m.period
    eng = ep.average_torque(BODY, illuminated, G, k2, DELTA, LAM, 0.3, tol=1e-6)
    err = abs(eng.rates["dT"] - ref)
    assert err <= eng.error["dT"]  # the estimate bounds the true error
    # ... and it is honest: algebraic convergence is reported, not the 1e-13 of smooth torques
    assert eng.error["dT"] > 1e-11
    assert max(eng.convergence.values()) > 0.05


def eclipsed_drag(omega, C, nu):
    """Linear drag switched off in the shadow, |nu - pi| < 0.6 (a jump in nu)."""
    lit = (np.abs(np.mod(nu, 2 * np.pi) - np.pi) >= 0.6).astype(float)
    return -lit[..., None] * np.einsum("ij,...j->...i", CASE1, omega)


def test_reported_error_bounds_the_true_error_for_a_jump_over_the_orbit():
    # exact: on a circular orbit the drag acts a fraction 1 - 1.2/(2 pi) of the time, so the orbit average is
    # that fraction times the closed form (6)
    frac = 1 - 1.2 / (2 * math.pi)
    closed = ep.averaged_rates(BODY, ep.LinearDrag(CASE1), 1.0, 0.6, DELTA, LAM, None)
    eng = ep.average_torque(BODY, eclipsed_drag, 1.0, 0.6, DELTA, LAM, None, tol=1e-6)
    for name in ("dG", "dT", "dk2"):
        err = abs(eng.rates[name] - frac * closed[name])
        assert err <= eng.error[name], name
        assert eng.error[name] > 1e-10 * abs(closed[name]), name  # first-order convergence, not spectral
    assert eng.convergence["nu"] > 0.05


# --------------------------------------------------------------------------------------------------
# averaged_rates and averaged: the dispatch
# --------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("nu", [1.1, None])
@pytest.mark.parametrize("orbit", [None, ep.Orbit(0.2)])
def test_averaged_rates_torque_objects_equal_the_drag_tensor(nu, orbit):
    objs = ep.LinearDrag(I_OFF) + ep.GravityGradient(BODY, orbit)
    for kind in ("max", "min"):
        a = ep.averaged_rates(BODY, I_OFF, 0.9, 0.4, DELTA, LAM, nu, kind=kind, orbit=orbit)
        b = ep.averaged_rates(BODY, objs, 0.9, 0.4, DELTA, LAM, nu, kind=kind, orbit=orbit)
        c = ep.averaged_rates(BODY, I_OFF, 0.9, 0.4, DELTA, LAM, nu, kind=kind, orbit=orbit, method="numerical")
        # b: the same closed forms through the vector form (rounding); c: the engine (1e-12, see above)
        assert b == pytest.approx(a, rel=1e-13, abs=1e-15)
        assert c == pytest.approx(a, rel=1e-12, abs=1e-13)


def test_dlam_at_the_pole_is_the_limit_along_the_meridian():
    objs = ep.LinearDrag(CASE1) + ep.GravityGradient(BODY)
    a = ep.averaged_rates(BODY, CASE1, 1.0, 0.5, 0.0, 0.3, 1.0)  # the closed form is regular there
    b = ep.averaged_rates(BODY, objs, 1.0, 0.5, 0.0, 0.3, 1.0)
    assert b["ddelta"] == pytest.approx(0.0, abs=1e-14)
    # central difference with h = 1e-5: O(h^2) relative
    assert b["dlam"] == pytest.approx(a["dlam"], rel=1e-8, abs=0)

    def push(omega, C, nu):  # a torque across G at the pole: lambda turns infinitely fast there
        return np.einsum("...ji,j->...i", C, [0.0, 0.3, 0.0])

    assert ep.averaged_rates(BODY, push, 1.0, 0.5, 0.0, 0.0, 1.0)["dlam"] == math.inf


@pytest.mark.parametrize("eps", [0.0, 0.02])
def test_averaged_with_torque_objects_equals_the_drag_tensor_path(eps):
    # three codings of the same averaged system: (9) for the drag tensor (state G, k2, n or Lambda), the torque
    # objects' closed forms in the vector form, and the engine; integrator rtol 1e-10
    span = (0, 2.0) if eps == 0 else (0, 0.4)
    te = np.linspace(*span, 9)
    kw = dict(k2_0=0.9, tau_span=span, tau_eval=te, orbit=ep.Orbit(0.1), nu0=0.3)
    a = ep.averaged(BODY, CASE1, eps, **kw)
    b = ep.averaged(BODY, ep.LinearDrag(CASE1) + ep.GravityGradient(BODY, ep.Orbit(0.1)), eps, **kw)
    c = ep.averaged(BODY, CASE1, eps, averaging="numerical", **kw)
    for s in (a, b, c):
        assert s.status == 0, s.message
    for f in ("G", "T", "k2", "delta", "lam"):
        assert getattr(b, f) == pytest.approx(getattr(a, f), rel=0, abs=1e-8), f
        assert getattr(c, f) == pytest.approx(getattr(a, f), rel=0, abs=1e-8), f
    assert b.quad_error == 0.0  # closed forms only
    assert c.quad_error < 1e-11  # the engine's estimate along the run


def test_averaged_reports_the_quadrature_error_of_a_kinked_torque():
    s = ep.averaged(BODY, ep.LinearDrag(CASE1) + illuminated, 0.0, k2_0=0.6, tau_span=(0, 0.2),
                    tau_eval=[0, 0.2], quad_tol=1e-4)
    assert s.status == 0
    # the kink makes the quadrature converge algebraically: the run reports an error near its tolerance
    assert 1e-8 < s.quad_error < 1e-3


@pytest.mark.parametrize(
    ("call", "exc", "match"),
    [
        (lambda: ep.averaged_rates(BODY, CASE1, 1.0, 0.5, 0.3, 0.1, 0.2, method="exact"), ValueError, "method"),
        (lambda: ep.averaged_rates(BODY, CASE1, 1.0, 0.5, 0.3, 0.1, 0.2, sigma=0), ValueError, "sigma"),
        (lambda: ep.averaged_rates(BODY, ep.LinearDrag(CASE1), 1.0, 0.5, 0.3, 0.1, 0.2, omega0=2.0), ValueError,
         "omega0"),
        (lambda: ep.averaged_rates(BODY, ep.LinearDrag(CASE1), 1.0, 1.0, 0.3, 0.1, 0.2), ValueError, "separatrix"),
        (lambda: ep.averaged_rates(BODY, ep.GravityGradient(BODY, ep.Orbit(0.1)), 1.0, 0.5, 0.3, 0.1, 0.2),
         ValueError, "Orbit"),
        (lambda: ep.average_torque(BODY, CASE1, 1.0, 0.5, 0.3, 0.1, 0.2, tol=0.0), ValueError, "tol"),
        (lambda: ep.average_torque(BODY, CASE1, 1.0, 1.0, 0.3, 0.1, 0.2), ValueError, "k2"),
        (lambda: ep.averaged(BODY, CASE1, 0.0, averaging="fast"), ValueError, "averaging"),
        (lambda: ep.averaged(BODY, ep.LinearDrag(CASE1), 0.0, quad_tol=-1.0), ValueError, "quad_tol"),
        (lambda: ep.averaged(BODY, ep.LinearDrag(CASE1), 0.02, drift_tol=0.0), ValueError, "drift_tol"),
        (lambda: ep.averaged(BODY, ep.LinearDrag(CASE1), 0.02, resonance_tol="a"), TypeError, "resonance_tol"),
        (lambda: ep.averaged(BODY, lambda o, C, nu: np.zeros(2), 0.0), ValueError, "shape"),
    ],
)
def test_bad_input_is_named(call, exc, match):
    with pytest.raises(exc, match=match):
        call()


@pytest.mark.parametrize("kind", ["max", "min"])
@pytest.mark.parametrize("sigma", [1, -1])
@pytest.mark.parametrize("k2", [0.05, 0.7, 0.999])
def test_engine_nodes_are_a_motion_that_solves_eulers_equations(kind, sigma, k2):
    # The averages alone cannot tell a motion from its mirror image traversed backwards (the same set of
    # states); the resonance harmonics, paired with the times of the motion, can. Independent check of the
    # engine's nodes: their derivative by FFT over the period equals A^-1 ((A omega) x omega), Euler's
    # equations, and the attitude's third row is g/G. Spectral derivative of an analytic periodic function on
    # 512 nodes: rounding times the largest wavenumber, ~1e-12 relative.
    from rigidbody.euler_poinsot._engine import State, motion_nodes

    n_u = 512
    st = State(BODY, kind, sigma, 1.2, k2, np.array([0.6, 0.0, 0.8]), 0.3, ep.Orbit(0.0))
    omega, al = motion_nodes(st, n_u)
    period = ep.EulerPoinsot(BODY, 1.2, k2, kind, sigma).period
    wave = np.fft.fftfreq(n_u, d=period / n_u) * 2 * np.pi
    domega = np.fft.ifft(1j * wave[:, None] * np.fft.fft(omega, axis=0), axis=0).real
    g = omega * BODY.A
    rhs = np.cross(g, omega) / BODY.A
    assert np.abs(domega - rhs).max() <= 1e-10 * np.abs(rhs).max()
    assert np.sign(omega[0, 0 if kind == "max" else 2]) == sigma  # the sense about the axis of rotation
    np.testing.assert_allclose(al[:, 2, :], g / 1.2, rtol=0, atol=1e-15)
    np.testing.assert_allclose(al @ al.transpose(0, 2, 1), np.broadcast_to(np.eye(3), al.shape), rtol=0, atol=1e-14)
