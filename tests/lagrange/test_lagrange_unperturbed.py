"""Unperturbed Lagrange top: integrals (1.2), cubic (1.5), roots, maps (1.6)/(2.8), motion (1.3)-(1.7)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rigidbody import lagrange as L
from rigidbody.core import elliptic as ell
from rigidbody.core import euler

TOP = L.Top(A=1.5, C=1.0, mgl=0.5)


# ---------------------------------------------------------------------------------------------- input
@pytest.mark.parametrize("kw", [dict(A=-1, C=1, mgl=1), dict(A=1, C=0, mgl=1), dict(A=1, C=1, mgl=math.nan)])
def test_top_rejects_bad_parameters(kw):
    with pytest.raises(ValueError, match=r"Top\.(A|C|mgl)"):
        L.Top(**kw)


def test_top_rejects_bodies_violating_the_triangle_inequality():
    # 2A - C = 2 * integral of z^2 dm >= 0 for any real body (moments about any point on the axis)
    with pytest.raises(ValueError, match=r"Top\.C must satisfy C <= 2A"):
        L.Top(A=1.0, C=2.5, mgl=1.0)
    assert L.Top(A=1.0, C=2.0, mgl=1.0).C == 2.0  # the limiting flat body is still accepted


def test_maps_reject_non_finite_input():
    with pytest.raises(ValueError, match="finite"):
        L.from_roots(TOP, math.nan, 0.5, 2.0)
    with pytest.raises(ValueError, match="finite"):
        L.from_roots(TOP, np.array([0.1, math.nan]), 0.5, 2.0)
    with pytest.raises(ValueError, match="theta must be finite"):
        L.integrals(TOP, 0.1, 0.2, 1.0, 0.3, math.inf)


def test_singular_formulas_reject_coincident_roots():
    # (2.13) and (3.4) divide by (u_i - u_j): regular precession / separatrix must not give inf or nan
    for u in [(0.3, 0.3, 2.0), (0.3, 1.0, 1.0)]:
        with pytest.raises(ValueError, match="distinct roots"):
            L.V_matrix(TOP, *u, 1.0, 1.0)
        with pytest.raises(ValueError, match="distinct roots"):
            L.drag_rhs(TOP, L.LinearDrag(0.1, 0.1), *u)
        with pytest.raises(ValueError, match="distinct roots"):
            L.drag_rhs(TOP, L.LinearDrag(0.1, 0.1), np.array([0.1, u[0]]), np.array([0.5, u[1]]), u[2])


def test_top_rejects_non_numbers():
    with pytest.raises(TypeError, match=r"Top\.A"):
        L.Top(A="1", C=1, mgl=1)


def test_from_roots_rejects_bad_ordering_and_signs():
    with pytest.raises(ValueError, match="u1 <= u2 <= 1 <= u3"):
        L.from_roots(TOP, 0.5, 0.2, 2.0)
    with pytest.raises(ValueError, match="u1 <= u2 <= 1 <= u3"):
        L.from_roots(TOP, 0.1, 0.2, 0.9)
    with pytest.raises(ValueError, match="delta1"):
        L.from_roots(TOP, 0.1, 0.2, 2.0, 0.5, 1)


def test_roots_rejects_unattainable_integrals():
    # energy below the minimum mgl*cos(theta) over all attitudes for this Gz, r
    with pytest.raises(ValueError, match="not attainable"):
        L.roots(TOP, 0.0, -2.0, 0.0)


# ------------------------------------------------------------------------------------------ integrals
def _independent_integrals(p, q, r, phi, theta, psi=0.3):
    """Gz = vertical component of K = R (Ap, Aq, Cr); H = T + mgl z_G (z_G from the body axis)."""
    R = euler.dcm(psi, theta, phi)
    K = R @ np.array([TOP.A * p, TOP.A * q, TOP.C * r])
    zG = R[2, 2]
    H = 0.5 * (TOP.A * (p * p + q * q) + TOP.C * r * r) + TOP.mgl * zG
    return K[2], H, r


@settings(max_examples=30, deadline=None)
@given(st.floats(-2, 2), st.floats(-2, 2), st.floats(-3, 3), st.floats(0, 6.28), st.floats(0.01, 3.13))
def test_integrals_match_vertical_angular_momentum(p, q, r, phi, theta):
    Gz, H, rr = L.integrals(TOP, p, q, r, phi, theta)
    G2, H2, _ = _independent_integrals(p, q, r, phi, theta)
    # same quantities by two routes: rounding only
    assert Gz == pytest.approx(G2, abs=1e-12)
    assert H == pytest.approx(H2, abs=1e-12)


# ------------------------------------------------------------------------------------------------ roots
def _cubic_from_definition(Gz, H, r):
    """Q(u) of (1.5) built by polynomial arithmetic (not through Vieta (1.6))."""
    P = np.polynomial.Polynomial
    A, C, mgl = TOP.A, TOP.C, TOP.mgl
    Q = (P([2 * H - C * r * r, -2 * mgl]) * P([1, 0, -1]) * A - P([Gz, -C * r]) ** 2) / A**2
    return Q


@settings(max_examples=40, deadline=None)
@given(st.floats(-2, 2), st.floats(-2, 2), st.floats(-3, 3), st.floats(0, 6.28), st.floats(0.02, 3.12))
def test_roots_are_the_roots_of_Q_and_bracket_cos_theta(p, q, r, phi, theta):
    Gz, H, rr = L.integrals(TOP, p, q, r, phi, theta)
    u1, u2, u3 = L.roots(TOP, Gz, H, rr)
    assert -1.0 <= u1 <= u2 <= 1.0 <= u3
    u0 = math.cos(theta)
    # the actual cos(theta) lies between the turning points (Q(u0) = u'^2 >= 0); slack: root conditioning
    assert u1 - 1e-7 <= u0 <= u2 + 1e-7
    ref = np.sort(_cubic_from_definition(Gz, H, rr).roots().real)
    # independent root finder (companion matrix); double roots are only sqrt(eps)-conditioned
    np.testing.assert_allclose([u1, u2, u3], ref, atol=5e-7 * (1 + abs(ref).max()))


def test_spinning_top_has_cos_theta0_as_a_root_exactly():
    # p = q = 0 means u' = 0 at t = 0: u0 is a turning point, and the others are 1 -+ sqrt(2 - 2 u0)
    # for the paper's parameters (C^2 r0^2 = 2 A mgl * 2): a closed form derived in docs/lagrange.md
    for th in (5, 60, 170):
        u0 = math.cos(math.radians(th))
        us = sorted([u0, 1 - math.sqrt(2 - 2 * u0), 1 + math.sqrt(2 - 2 * u0)])
        got = L.roots(TOP, *L.integrals(TOP, 0, 0, math.sqrt(3), 0.0, math.radians(th)))
        np.testing.assert_allclose(got, us, rtol=0, atol=1e-13)  # simple roots: a few ulp


def test_regular_precession_gives_nearly_double_root():
    # steady precession: theta' = 0 and psi' solving A cos(th) psi'^2 - G psi' + mgl = 0 (with G = C n)
    th, r = 0.7, 3.0
    cth, sth = math.cos(th), math.sin(th)
    # r = n (axial spin) and A psi'^2 cos th - C r psi' + mgl = 0
    dpsi = (TOP.C * r - math.sqrt((TOP.C * r) ** 2 - 4 * TOP.A * cth * TOP.mgl)) / (2 * TOP.A * cth)
    # body rates for theta' = 0: (p, q) = psi' sin(th) (sin phi, cos phi), r_body = psi' cos th + phi'
    phi = 0.4
    p, q = dpsi * sth * math.sin(phi), dpsi * sth * math.cos(phi)
    Gz, H, rr = L.integrals(TOP, p, q, r, phi, th)
    u1, u2, u3 = L.roots(TOP, Gz, H, rr)
    # a double root is computed to ~sqrt(machine eps) ~ 1.5e-8 (times the scale of the coefficients)
    assert abs(u1 - cth) < 1e-7 and abs(u2 - cth) < 1e-7
    assert u1 <= u2 and u3 > 1


def test_sleeping_top_roots():
    # spinning upright: Q(u) = (1-u)^2 [2 mgl A (1+u) - C^2 r^2] / A^2 -> roots 1, 1, C^2 r^2/(2 A mgl) - 1
    for r in (0.5, 1.2):  # slow sleeping tops: u* < 1, so u1 = u*, u2 = u3 = 1
        ustar = (TOP.C * r) ** 2 / (2 * TOP.A * TOP.mgl) - 1
        u1, u2, u3 = L.roots(TOP, *L.integrals(TOP, 0, 0, r, 0, 0.0))
        assert u1 == pytest.approx(ustar, abs=1e-12)  # simple root
        assert abs(u2 - 1) < 1e-7 and abs(u3 - 1) < 1e-7  # double root at 1: sqrt(eps)-conditioned
    r = 2.5  # fast sleeping top: u1 = u2 = 1 < u3 = u*
    ustar = (TOP.C * r) ** 2 / (2 * TOP.A * TOP.mgl) - 1
    u1, u2, u3 = L.roots(TOP, *L.integrals(TOP, 0, 0, r, 0, 0.0))
    assert u3 == pytest.approx(ustar, abs=1e-12)
    assert abs(u1 - 1) < 1e-7 and abs(u2 - 1) < 1e-7


def test_roots_vectorised():
    Gz, H, r = L.integrals(TOP, [0.1, 0.0], [0.2, 0.3], [1.0, 2.0], [0.3, 0.4], [1.0, 2.0])
    U = np.array(L.roots(TOP, Gz, H, r))
    for j in range(2):
        # arrays and scalars may reach different loops of NumPy's elementary functions (SIMD and scalar), which
        # differ in the last bit: agreement to a few ulps of the roots' scale (they are O(1) here)
        np.testing.assert_allclose(U[:, j], L.roots(TOP, Gz[j], H[j], r[j]), rtol=0, atol=1e-14)


# ------------------------------------------------------------------------------------- maps both ways
@settings(max_examples=50, deadline=None)
@given(st.floats(-2, 2), st.floats(-2, 2), st.floats(-3, 3).filter(lambda x: abs(x) > 1e-3),
       st.floats(0, 6.28), st.floats(0.02, 3.12))
def test_state_to_roots_to_integrals_round_trip(p, q, r, phi, theta):
    Gz, H, rr = L.integrals(TOP, p, q, r, phi, theta)
    u = L.roots(TOP, Gz, H, rr)
    d1, d2 = L.deltas(TOP, Gz, rr)
    back = L.from_roots(TOP, *u, d1, d2)
    # (2.8) inverts (1.6); near double roots u carries sqrt(eps) errors but (Gz, H, r) are smooth in the
    # symmetric functions s1, s2, s3, so the round trip is accurate to ~1e-8 of the scale
    scale = 1 + abs(Gz) + abs(H) + abs(rr)
    np.testing.assert_allclose(back, (Gz, H, rr), atol=1e-8 * scale)


@st.composite
def admissible_roots(draw, gap=0.02):
    u1 = draw(st.floats(-0.98, 0.9))
    u2 = draw(st.floats(u1 + gap, 0.99))
    u3 = draw(st.floats(1.01, 4.0))
    d1 = draw(st.sampled_from([-1.0, 1.0]))
    d2 = draw(st.sampled_from([-1.0, 1.0]))
    return u1, u2, u3, d1, d2


@settings(max_examples=50, deadline=None)
@given(admissible_roots())
def test_roots_to_integrals_to_roots_round_trip(x):
    u1, u2, u3, d1, d2 = x
    Gz, H, r = L.from_roots(TOP, u1, u2, u3, d1, d2)
    # (1.6) by the independent cubic: the roots come back
    np.testing.assert_allclose(L.roots(TOP, Gz, H, r), (u1, u2, u3), atol=1e-9)  # simple roots (gap>=0.01)
    # and the signs (2.8) are those of the constructed Gz, r
    assert L.deltas(TOP, Gz, r) == (d1, d2)


def test_V_matrix_is_the_jacobian_of_the_roots():
    # (2.13) against central differences of roots(Gz, H, r): truncation O(h^2) ~ 1e-10, rounding 1e-16/h
    Gz, H, r = L.integrals(TOP, 0.2, -0.4, 1.3, 0.5, 1.1)
    u = L.roots(TOP, Gz, H, r)
    V = L.V_matrix(TOP, *u, Gz, r)
    J = np.zeros((3, 3))
    h = 1e-5
    for j in range(3):
        x = np.array([Gz, H, r])
        x[j] += h
        up = np.array(L.roots(TOP, *x))
        x[j] -= 2 * h
        um = np.array(L.roots(TOP, *x))
        J[:, j] = (up - um) / (2 * h)
    np.testing.assert_allclose(V, J, atol=1e-8 * np.abs(V).max())


# ------------------------------------------------------------------------------------------- motion
def test_closed_form_motion_matches_full_equations_without_torque():
    state = (0.3, -0.2, math.sqrt(3), 0.4, 1.0, 0.2)
    t = np.linspace(0, 40, 120)
    m = L.lagrange_motion(TOP, state, t)
    f = L.simulate(TOP, L.LinearDrag(0.1, 0.1), 0.0, state, (0, 40), t_eval=t, rtol=1e-12, atol=1e-13)
    # (1.3) with the elliptic core vs the quaternion integration (rtol 1e-12 over ~10 periods)
    np.testing.assert_allclose(m.u, f.u, atol=1e-9)
    dpsi = np.angle(np.exp(1j * (m.psi - f.psi)))
    dphi = np.angle(np.exp(1j * (m.phi - f.phi)))
    assert np.abs(dpsi).max() < 1e-8 and np.abs(dphi).max() < 1e-8  # quadratures (1.7), rtol 1e-12
    # u stays between the turning points u1, u2 and reaches them (one period fits in t)
    assert m.u.min() >= float(m.u1) - 1e-12 and m.u.max() <= float(m.u2) + 1e-12
    T = 2 * ell.K(mc=1 - float(m.k2)) / float(m.alpha)
    m2 = L.lagrange_motion(TOP, state, np.array([5.0, 5.0 + T]))
    assert m2.u[1] == pytest.approx(m2.u[0], abs=1e-10)  # period 2K/alpha of (1.3)


def test_closed_form_motion_refuses_motions_through_a_pole():
    # a planar pendulum (r = 0, Gz = 0) swings through theta = pi: u1 = -1 and the quadratures (1.7)
    # for psi, phi would silently miss the jump of the Euler angles there
    with pytest.raises(ValueError, match="theta = pi"):
        L.lagrange_motion(TOP, (0.5, 0.0, 0.0, 0.0, 1.0, 0.0), [0.0, 1.0])
    # Gz = C r exactly: the top passes through the upright position theta = 0
    with pytest.raises(ValueError, match="theta = 0"):
        L.lagrange_motion(TOP, (0.0, 0.3, 2.0, 0.0, 1e-300, 0.0), [0.0, 1.0])


def test_full_equations_pass_through_the_vertical():
    # theta0 = 0 exactly with a small transverse rate: Euler angles are singular there, the quaternion is not
    state = (0.05, 0.0, 1.0, 0.0, 0.0, 0.0)
    f = L.simulate(TOP, L.LinearDrag(0.1, 0.1), 0.0, state, (0, 30), rtol=1e-11, atol=1e-12)
    assert f.status == 0 and np.all(np.isfinite(f.theta))
    assert np.ptp(f.Gz) < 1e-9 and np.ptp(f.H) < 1e-9 and np.ptp(f.r) == 0.0  # integrals (1.2), rtol
    assert f.theta[0] == 0.0 and f.theta.max() > 0.1  # it did leave the pole


def test_simulate_rejects_bad_input():
    with pytest.raises(ValueError, match="eps"):
        L.simulate(TOP, L.LinearDrag(0.1, 0.1), -1.0, (0, 0, 1, 0, 1, 0), (0, 1))
    with pytest.raises(TypeError, match="torque"):
        L.simulate(TOP, object(), 0.1, (0, 0, 1, 0, 1, 0), (0, 1))
    star = L.StarTorque(lambda G, H, r, th: 0 * th, lambda G, H, r, th: 0 * th)
    with pytest.raises(TypeError, match="body moments"):
        L.simulate(TOP, star, 0.1, (0, 0, 1, 0, 1, 0), (0, 1))


@settings(max_examples=30, deadline=None)
@given(st.floats(0.15, 2.9), st.floats(2.5, 5.0), st.floats(0, 6.28))
def test_regular_precessions_round_trip(th, r, phi):
    # steady precession (theta' = 0): a double root at cos(theta); Gz, H, r still round-trip accurately
    cth, sth = math.cos(th), math.sin(th)
    disc = (TOP.C * r) ** 2 - 4 * TOP.A * cth * TOP.mgl
    dpsi = (TOP.C * r - math.sqrt(disc)) / (2 * TOP.A * cth) if abs(cth) > 1e-9 else TOP.mgl / (TOP.C * r)
    p, q = dpsi * sth * math.sin(phi), dpsi * sth * math.cos(phi)
    Gz, H, rr = L.integrals(TOP, p, q, r, phi, th)
    u1, u2, u3 = L.roots(TOP, Gz, H, rr)
    assert abs(u1 - cth) < 1e-6 and abs(u2 - cth) < 1e-6  # double root: sqrt(eps) times the scale
    back = L.from_roots(TOP, u1, u2, u3, *L.deltas(TOP, Gz, rr))
    np.testing.assert_allclose(back, (Gz, H, rr), atol=1e-7 * (1 + abs(H)))  # symmetric functions smooth


def test_bad_types_name_the_parameter():
    top = L.Top(A=1.5, C=1.0, mgl=0.5)
    with pytest.raises(TypeError, match="Gz"):
        L.roots(top, "a", 1.0, 1.0)
    with pytest.raises(ValueError, match="theta must be finite"):
        L.integrals(top, 0.0, 0.0, 1.0, 0.0, float("nan"))
    with pytest.raises(ValueError, match="u2 must be finite"):
        L.from_roots(top, 0.0, np.array([np.nan]), 2.0, 1, 1)


def test_integrals_names_mismatched_shapes():
    with pytest.raises(ValueError, match=r"p \(2,\), q \(3,\)"):
        L.integrals(TOP, [0.1, 0.2], [0.1, 0.2, 0.3], 1.0, 0.0, 1.0)
    Gz, H, r = L.integrals(TOP, [0.1, 0.2], [[0.1], [0.3]], 1.0, 0.0, 1.0)  # broadcasting shapes are fine
    assert np.shape(Gz) == (2, 2)
