"""Closed forms (3.3)-(3.5), (4.5), (5.1), (5.2) against the full simulation of (1.2).

The simulation integrates Euler's equations + quaternion with DOP853 at rtol=1e-12, atol=1e-14; in the
polar formulation the rates carry a *relative* error of ~1e-12 per unit of (decay rate x t), so every
comparison below is relative, with tolerance 1e-10 (100x the integrator tolerance, for the accumulation
over ~10^2-10^3 steps). Derived quantities (n-double-dot) are computed here from Euler's equations on the
simulated state, not from the closed forms.
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from viscous_testlib import initial

from rigidbody import viscous as vs
from rigidbody.core import euler

# (body, medium, regime): theta3 < theta12 and theta3 > theta12 bodies, all three regimes
CASES = [
    (vs.Body(2.0, 1.0), vs.Medium(0.3, 0.1), "contracting"),
    (vs.Body(2.0, 1.0), vs.Medium(0.1, 0.1), "unwinding"),
    (vs.Body(2.0, 1.0), vs.Medium(0.2, 0.1), "circle"),
    (vs.Body(1.5, 2.5), vs.Medium(0.6, 0.5), "contracting"),
    (vs.Body(1.5, 2.5), vs.Medium(0.15, 0.5), "unwinding"),
]
IDS = [f"{c[2]}-{c[0].theta12}-{c[0].theta3}" for c in CASES]




def gauss_nodes(T, panels, order=20):
    """Gauss-Legendre nodes/weights on [0, T] split in equal panels (integrands are smooth exponentials
    times oscillations of period >= 1: 20 nodes per unit-length panel integrate them to rounding)."""
    x, w = np.polynomial.legendre.leggauss(order)
    edges = np.linspace(0.0, T, panels + 1)
    h = np.diff(edges)
    t = (edges[:-1, None] + (x[None, :] + 1) * h[:, None] / 2).ravel()
    ww = (w[None, :] * h[:, None] / 2).ravel()
    return t, ww


def nddot(body, medium, sim):
    """n-double-dot (inertial components) from Euler's equations on the simulated state:
    n'' = omega' x n + omega x (omega x n)."""
    R = euler.dcm_from_quat(sim.attitude.T)
    return np.einsum("tij,jt->it", R, body_kinematics(body, medium, sim)[1])


def body_kinematics(body, medium, sim):
    """(ndot, nddot) in BODY components, where n = e3: ndot = w x e3, nddot = w' x e3 + w x (w x e3),
    w' from Euler's equations. Free of the cancellation Omega n x n that the inertial route suffers when
    k = (theta3/theta12) Omega/v is large."""
    p, q, r = sim.omega_body
    t12, t3, B12, B3 = body.theta12, body.theta3, medium.B12, medium.B3
    dp = ((t12 - t3) * q * r - B12 * p) / t12
    dq = ((t3 - t12) * r * p - B12 * q) / t12
    dw = np.array([dp, dq, -B3 * r / t3])
    w = np.array([p, q, r])
    e3 = np.zeros_like(w)
    e3[2] = 1.0
    nd = np.cross(w, e3, axis=0)
    ndd = np.cross(dw, e3, axis=0) + np.cross(w, nd, axis=0)
    return nd, ndd


def triple_product(body, medium, sim):
    """n.(ndot x nddot) evaluated in body components (a rotation invariant)."""
    nd, ndd = body_kinematics(body, medium, sim)
    return np.cross(nd, ndd, axis=0)[2]


def rel(a, b):
    return np.max(np.abs(np.asarray(a) / np.asarray(b) - 1.0))


@pytest.mark.parametrize(("body", "medium", "reg"), CASES, ids=IDS)
def test_regime(body, medium, reg):
    assert vs.regime(body, medium) == reg


@pytest.mark.parametrize(("body", "medium", "reg"), CASES, ids=IDS)
def test_first_integrals_against_simulation(body, medium, reg):
    n0, nd0 = initial()
    Om0, v0 = 3.0, 0.4
    t = np.linspace(0.0, 40.0, 161)
    sim = vs.simulate(body, medium, n0, nd0, Om0, (0.0, 40.0), t_eval=t)
    assert sim.status == 0
    # (3.3)-(3.4): relative, tolerance 1e-10 from rtol=1e-12 (see module docstring)
    assert rel(sim.Omega, vs.Omega(body, medium, Om0, t)) < 1e-10
    assert rel(np.linalg.norm(sim.ndot, axis=0), vs.v(body, medium, v0, t)) < 1e-10
    assert rel(np.sum(sim.n * sim.omega, axis=0), vs.Omega(body, medium, Om0, t)) < 1e-10
    # omega.omega = v^2 + Omega^2
    assert rel(np.sum(sim.omega**2, axis=0), vs.omega2(body, medium, Om0, v0, t)) < 1e-10
    nn = nddot(body, medium, sim)
    triple = triple_product(body, medium, sim)
    # (3.5) f^3 = n.(ndot x nddot); (after 3.6) F^4 = nddot.nddot
    assert rel(triple, vs.f3(body, medium, Om0, v0, t)) < 1e-10
    assert rel(np.sum(nn * nn, axis=0), vs.F4(body, medium, Om0, v0, t)) < 1e-10
    # (4.4)-(4.5): k = n.(ndot x nddot)/v^3 with v = |ndot| from the simulated vectors
    vv = np.linalg.norm(sim.ndot, axis=0)
    assert rel(triple / vv**3, vs.curvature(body, medium, Om0, v0, t)) < 1e-10
    # the second equation of (3.2): theta12 n.(ndot x nddot) = theta3 Omega v^2
    assert np.max(np.abs(body.theta12 * triple / (body.theta3 * sim.Omega * vv**2) - 1)) < 1e-10
    # the third equation of (3.2) in its verified form: theta12 ndot.nddot = -B12 ndot.ndot
    third = body.theta12 * np.sum(sim.ndot * nn, axis=0) / (-medium.B12 * vv**2)
    assert np.max(np.abs(third - 1)) < 1e-10


def test_printed_third_equation_of_32_is_wrong():
    """Printed theta12 n.nddot = -B12 ndot.ndot would force theta12 = B12 since n.nddot = -v^2 identically."""
    body, medium, _ = CASES[0]
    n0, nd0 = initial()
    t = np.linspace(0.0, 10.0, 11)
    sim = vs.simulate(body, medium, n0, nd0, 3.0, (0.0, 10.0), t_eval=t)
    nn = nddot(body, medium, sim)
    vv2 = np.sum(sim.ndot**2, axis=0)
    printed = body.theta12 * np.sum(sim.n * nn, axis=0) + medium.B12 * vv2
    assert np.min(np.abs(printed) / vv2) > 1.0  # = theta12 - B12 = 1.7, far from 0


@pytest.mark.parametrize(("body", "medium", "reg"), CASES[:3], ids=IDS[:3])
def test_quasi_coordinates_against_quadrature_of_simulation(body, medium, reg):
    n0, nd0 = initial(seed=2)
    Om0, v0, T = -2.0, 0.4, 12.0
    tq, wq = gauss_nodes(T, 12)
    sim = vs.simulate(body, medium, n0, nd0, Om0, (0.0, T), t_eval=np.concatenate([tq, [T]]))
    vv = np.linalg.norm(sim.ndot, axis=0)
    s_num = np.sum(wq * vv[:-1])
    # xi' = v k  ->  xi_dot = n.(ndot x nddot)/v^2  (4.4)
    xi_num = np.sum(wq * (triple_product(body, medium, sim) / vv**2)[:-1])
    zeta_num = np.sum(wq * np.sum(sim.n * sim.omega, axis=0)[:-1])
    s, xi, zeta = vs.quasi_coordinates(body, medium, Om0, v0, T)
    # quadrature is exact to rounding; the integrands carry the 1e-12 relative simulation error
    assert s_num == pytest.approx(s, rel=1e-10, abs=0)
    assert xi_num == pytest.approx(xi, rel=1e-10, abs=0)
    assert zeta_num == pytest.approx(zeta, rel=1e-10, abs=0)
    assert sim.zeta[-1] == pytest.approx(zeta, rel=1e-10, abs=0)
    # the printed form of xi in (5.1) has B12 in place of B3: wrong unless B12 = B3
    xi_printed = body.theta3**2 * Om0 / (medium.B12 * body.theta12) * (1 - math.exp(-medium.B3 * T / body.theta3))
    if medium.B12 != medium.B3:
        assert abs(xi_printed - xi_num) > 1e-2 * abs(xi_num)


@pytest.mark.parametrize(("body", "medium", "reg"), CASES[:3], ids=IDS[:3])
def test_limits_against_long_integration(body, medium, reg):
    """s_inf, xi_inf, zeta_inf: integrate over 40 e-folding times of the slower of v and Omega (the
    remaining tail e^{-40} ~ 4e-18 is below rounding) and compare."""
    n0, nd0 = initial(seed=3)
    Om0, v0 = 1.5, 0.4
    T = 40.0 / min(vs.decay_rates(body, medium))
    tq, wq = gauss_nodes(T, int(T / 2))
    sim = vs.simulate(body, medium, n0, nd0, Om0, (0.0, T), t_eval=np.concatenate([tq, [T]]))
    vv = np.linalg.norm(sim.ndot, axis=0)
    s_inf, xi_inf, zeta_inf = vs.limits(body, medium, Om0, v0)
    xi_dot = triple_product(body, medium, sim) / vv**2
    assert np.sum(wq * vv[:-1]) == pytest.approx(s_inf, rel=1e-10, abs=0)
    assert np.sum(wq * xi_dot[:-1]) == pytest.approx(xi_inf, rel=1e-10, abs=0)
    assert sim.zeta[-1] == pytest.approx(zeta_inf, rel=1e-10, abs=0)
    # and the closed forms at t = inf are the limits
    at_inf = vs.quasi_coordinates(body, medium, Om0, v0, np.inf)
    assert at_inf == pytest.approx((s_inf, xi_inf, zeta_inf), rel=1e-15, abs=0)


def test_polar_formulation_keeps_relative_accuracy_over_many_e_foldings():
    """After 60 e-folding times of v the polar state still gives v, Omega, k to 1e-10 relative.
    The cartesian formulation with the same absolute tolerance cannot (v ~ 1e-27 << atol)."""
    body, medium, _ = CASES[0]
    n0, nd0 = initial()
    t = np.array([0.0, 100.0, 200.0, 400.0])
    sim = vs.simulate(body, medium, n0, nd0, 3.0, (0.0, 400.0), t_eval=t)
    assert rel(sim.v, vs.v(body, medium, 0.4, t)) < 1e-10
    assert rel(sim.Omega, vs.Omega(body, medium, 3.0, t)) < 1e-10
    assert rel(sim.k, vs.curvature(body, medium, 3.0, 0.4, t)) < 1e-10
    cart = vs.simulate(body, medium, n0, nd0, 3.0, (0.0, 400.0), t_eval=t, formulation="cartesian")
    assert rel(cart.v[-1:], vs.v(body, medium, 0.4, t[-1:])) > 1e-3


@pytest.mark.parametrize(("body", "medium", "reg"), CASES, ids=IDS)
def test_polar_and_cartesian_formulations_agree(body, medium, reg):
    n0, nd0 = initial(seed=4)
    t = np.linspace(0.0, 20.0, 41)
    a = vs.simulate(body, medium, n0, nd0, 3.0, (0.0, 20.0), t_eval=t)
    b = vs.simulate(body, medium, n0, nd0, 3.0, (0.0, 20.0), t_eval=t, formulation="cartesian")
    # both at rtol 1e-12 over ~60 radians of spin: attitudes agree to ~1e-11
    assert np.max(np.abs(a.attitude - b.attitude)) < 1e-10
    assert np.max(np.abs(a.omega - b.omega)) < 1e-10
    assert np.max(np.abs(a.quat_norm_error)) < 1e-11


def test_spiral_radius_and_full_curvature():
    """(5.2) R = 1/sqrt(1+k^2) and K^2 = n''.n'' = 1 + k^2 (d/ds): n'' = (nddot - vdot n')/v^2."""
    body, medium, _ = CASES[0]
    n0, nd0 = initial()
    t = np.linspace(0.0, 30.0, 31)
    sim = vs.simulate(body, medium, n0, nd0, 3.0, (0.0, 30.0), t_eval=t)
    vv = np.linalg.norm(sim.ndot, axis=0)
    vdot = -medium.B12 / body.theta12 * vv  # from the simulated nddot: ndot.nddot/v, checked above
    nn = nddot(body, medium, sim)
    vdot_sim = np.sum(sim.ndot * nn, axis=0) / vv
    assert rel(vdot_sim, vdot) < 1e-10
    n2 = (nn - vdot_sim * sim.ndot / vv) / vv**2
    K2 = np.sum(n2 * n2, axis=0)
    k = vs.curvature(body, medium, 3.0, 0.4, t)
    assert rel(K2, 1 + k**2) < 1e-10
    assert rel(1 / np.sqrt(K2), vs.spiral_radius(body, medium, 3.0, 0.4, t)) < 1e-10
    # the printed companion formula K^2 = n''.n is wrong: n''.n = -1 identically
    assert np.allclose(np.sum(n2 * sim.n, axis=0), -1.0, atol=1e-10)


def test_curvature_and_radius_are_finite_and_warning_free_for_huge_t():
    body, medium, _ = CASES[0]
    k = vs.curvature(body, medium, 1.0, 0.3, np.array([0.0, 1e5, np.inf]))
    assert k[1] == np.inf and k[2] == np.inf
    R = vs.spiral_radius(body, medium, 1.0, 0.3, np.array([0.0, 1e3, 1e5]))
    # R ~ 1e-22 = 1/k: abs=0, pytest.approx's default abs=1e-12 would make this vacuous
    assert np.all(np.isfinite(R))
    assert R[1] == pytest.approx(math.exp(-(0.15 - 0.1) * 1e3) * 2 / 1 * 0.3, rel=1e-12, abs=0)
    body, medium, _ = CASES[1]
    assert vs.curvature(body, medium, 1.0, 0.3, np.inf) == 0.0
    assert vs.spiral_radius(body, medium, 1.0, 0.3, 1e5) == 1.0


@settings(max_examples=20)
@given(
    theta12=st.floats(0.5, 3.0),
    ratio=st.floats(0.2, 2.0),
    B12=st.floats(0.05, 1.0),
    B3=st.floats(0.05, 1.0),
    Omega0=st.floats(-5.0, 5.0).filter(lambda x: abs(x) > 1e-3),
    v0=st.floats(0.05, 2.0),
    seed=st.integers(0, 1000),
)
def test_random_parameters_closed_forms_and_path(theta12, ratio, B12, B3, Omega0, v0, seed):
    """Random bodies/media (any regime): f3 (3.5) from the simulated triple product, k (4.5) from the
    simulated rates, zeta (5.1) from the
    simulated turn about n, and the (v, k) reconstruction against the simulated axis at T = 15 (the same
    1e-10 budget as above: DOP853 rtol 1e-12 on both routes)."""
    body, medium = vs.Body(theta12, ratio * theta12), vs.Medium(B12, B3)
    n0, nd0 = initial(seed, v0)
    t = np.array([0.0, 5.0, 15.0])
    sim = vs.simulate(body, medium, n0, nd0, Omega0, (0.0, 15.0), t_eval=t)
    vv = np.linalg.norm(sim.ndot, axis=0)
    nd, ndd = body_kinematics(body, medium, sim)
    # the triple product suffers cancellation (v-dot tau is parallel to ndot): rounding ~ eps |ndot| |nddot|
    bound = 1e-10 * np.abs(vs.f3(body, medium, Omega0, v0, t)) + 1e-13 * vv * np.linalg.norm(ndd, axis=0)
    assert np.all(np.abs(triple_product(body, medium, sim) - vs.f3(body, medium, Omega0, v0, t)) <= bound)
    assert rel(sim.k, vs.curvature(body, medium, Omega0, v0, t)) < 1e-10
    assert np.allclose(sim.zeta, vs.quasi_coordinates(body, medium, Omega0, v0, t)[2], rtol=1e-10, atol=1e-12)
    n = vs.axis_path(body, medium, n0, nd0, Omega0, t)
    assert np.max(np.linalg.norm(n - sim.n, axis=0)) < 1e-10


@pytest.mark.parametrize(("body", "medium", "reg"), CASES[:3], ids=IDS[:3])
def test_simulation_survives_underflow_of_v_and_Omega(body, medium, reg):
    """Over 2000 e-folding times of Omega both v and Omega underflow to 0 in double precision. The polar
    state (logarithms) keeps k = (θ3/θ12) Ω/v of (4.5) exact in relative terms in every regime (the
    Routh circle keeps its constant k, no 0/0); the error of log k is absolute, ~rtol per e-folding, so
    1e-10 relative at t = 100 and 1e-9 at t = 2e4 (|log k| ~ 500, 1e-12 x 2000 e-foldings)."""
    n0, nd0 = initial()
    t = np.array([0.0, 100.0, 1e4, 2e4])
    sim = vs.simulate(body, medium, n0, nd0, 1.0, (0.0, 2e4), t_eval=t)
    assert sim.status == 0
    assert sim.v[-1] == 0.0 and sim.Omega[-1] == 0.0  # underflowed: the regime in which 0/0 used to occur
    k = vs.curvature(body, medium, 1.0, 0.4, t)
    finite = np.isfinite(k) & (k > 0)
    assert rel(sim.k[finite], k[finite]) < 1e-9
    assert np.array_equal(sim.k[~finite], k[~finite])  # inf (contracting) or 0 (unwinding) where k saturates
    assert np.max(np.abs(sim.quat_norm_error)) < 1e-11
