"""Torque objects: the protocol, the paper's two torques as objects, and `simulate` with any torque."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rigidbody import euler_poinsot as ep
from rigidbody.core import euler

BODY = ep.Body(3.2, 2.6, 1.67)
I_OFF = np.array([[2.322, 0.3, -0.2], [0.1, 1.31, 0.4], [0.25, -0.15, 1.425]])
FIELDS = ("G", "T", "k2", "delta", "lam")


def random_attitudes(rng, n):
    q = rng.normal(size=(n, 4))
    return euler.dcm_from_quat(q)


def test_gravity_gradient_object_equals_the_projections_3_of_the_paper():
    # independent route: (3) written in the frame Oy, L^g = 3 f(nu) beta x S beta, S = alpha A alpha^T, with
    # beta the radius vector in Oy from (delta, lambda, nu); the object works in body axes with C = Y alpha
    rng = np.random.default_rng(1)
    orb = ep.Orbit(0.25)
    gg = ep.GravityGradient(BODY, orb)
    for _ in range(20):
        psi, theta, phi, delta, lam, nu = rng.uniform(-3, 3, 6)
        alpha = euler.dcm(psi, theta, phi)
        cnl = math.cos(nu - lam)
        beta = np.array([cnl * math.cos(delta), math.sin(nu - lam), cnl * math.sin(delta)])
        S = alpha @ np.diag(BODY.A) @ alpha.T
        f = (1 + 0.25 * math.cos(nu)) ** 3 / (1 - 0.25**2) ** 3
        L_paper = 3 * f * np.cross(beta, S @ beta)
        sd, cd, sl, cl = math.sin(delta), math.cos(delta), math.sin(lam), math.cos(lam)
        Y = np.array([[cd * cl, -sl, sd * cl], [cd * sl, cl, sd * sl], [-sd, 0.0, cd]])  # columns y1, y2, y3
        M = gg(rng.normal(size=3), Y @ alpha, nu)  # omega does not enter
        # the same torque in two frames: rounding only
        np.testing.assert_allclose(alpha @ M, L_paper, rtol=0, atol=1e-13)


def test_torques_are_vectorised_over_leading_axes():
    rng = np.random.default_rng(2)
    C = random_attitudes(rng, 24).reshape(2, 3, 4, 3, 3)
    omega = rng.normal(size=(2, 3, 4, 3))
    nu = rng.uniform(-3, 3, (2, 3, 4))
    tq = ep.LinearDrag(I_OFF) + ep.GravityGradient(BODY, ep.Orbit(0.1))
    M = tq(omega, C, nu)
    assert M.shape == (2, 3, 4, 3)
    for idx in np.ndindex(2, 3, 4):  # each grid point as a single state
        np.testing.assert_allclose(M[idx], tq(omega[idx], C[idx], float(nu[idx])), rtol=0, atol=1e-14)
    # broadcasting: one omega for all attitudes (read-only views are fine)
    Mb = tq(np.broadcast_to(omega[0, 0, 0], omega.shape), C, nu)
    np.testing.assert_allclose(Mb[0, 0, 0], M[0, 0, 0], rtol=0, atol=1e-14)
    np.testing.assert_allclose(ep.LinearDrag(I_OFF)(omega[0, 0, 0], C[0, 0, 0], 0.0), -I_OFF @ omega[0, 0, 0])


@pytest.mark.parametrize("c_shape, nu_shape", [
    ((1, 4, 60), (4, 1, 1)),  # the engine's compact grids, small and large (two code paths)
    ((1, 8, 120), (16, 1, 1)),
    ((1, 4, 60), (1, 1, 1)),  # nu held
    ((16, 8, 20), (16, 8, 20)),  # full arrays
    ((3000,), ()),
    ((), ()),
])
def test_gravity_gradient_broadcasts_on_small_and_large_grids(c_shape, nu_shape):
    # every element against the single-state evaluation of the projections test above
    rng = np.random.default_rng(3)
    gg = ep.GravityGradient(BODY, ep.Orbit(0.25))
    n_c = math.prod(c_shape)
    C = random_attitudes(rng, n_c).reshape(*c_shape, 3, 3)
    nu = rng.uniform(-3, 3, nu_shape)
    M = gg(None, C, nu)
    shape = np.broadcast_shapes(c_shape, nu_shape)
    assert M.shape == (*shape, 3)
    Cb, nub = np.broadcast_to(C, (*shape, 3, 3)), np.broadcast_to(nu, shape)
    for idx in list(np.ndindex(shape))[:: max(1, math.prod(shape) // 200)]:
        # the same products in another grouping: rounding of torques of size <= 3 f |A1 - A3| ~ 11 (1e-15 each)
        np.testing.assert_allclose(M[idx], gg(None, Cb[idx], float(nub[idx])), rtol=0, atol=1e-13)


def test_sums_flatten_and_accept_plain_functions():
    def const(omega, C, nu):
        return np.broadcast_to([0.1, 0.0, -0.2], np.shape(omega))

    a, b = ep.LinearDrag(np.eye(3)), ep.GravityGradient(BODY)
    s = a + b + const
    assert isinstance(s, ep.TorqueSum) and len(s.terms) == 3
    assert isinstance(s.terms[2], ep.FunctionTorque) and s.terms[2].fun is const
    assert len((const + a).terms) == 2
    omega, C = np.array([0.3, -0.1, 0.2]), np.eye(3)
    np.testing.assert_allclose(s(omega, C, 0.4), a(omega, C, 0.4) + b(omega, C, 0.4) + const(omega, C, 0.4))
    # frozen, validated, compared by value
    assert ep.LinearDrag(np.eye(3)) == ep.LinearDrag([1.0, 1.0, 1.0])
    assert hash(ep.LinearDrag(np.eye(3))) == hash(ep.LinearDrag(np.eye(3)))
    assert ep.GravityGradient(BODY) == ep.GravityGradient(BODY, ep.Orbit(0.0))
    with pytest.raises(AttributeError):
        a.I = np.zeros((3, 3))  # type: ignore[misc]


@pytest.mark.parametrize(
    ("call", "exc", "match"),
    [
        (lambda: ep.LinearDrag(-np.eye(3)), ValueError, "positive definite"),
        (lambda: ep.LinearDrag("a"), TypeError, "I"),
        (lambda: ep.GravityGradient((3.2, 2.6, 1.67)), TypeError, "Body"),
        (lambda: ep.GravityGradient(BODY, omega0=-1.0), ValueError, "omega0"),
        (lambda: ep.LinearDrag(np.eye(3)) + 3.0, TypeError, "callable"),
        (lambda: ep.FunctionTorque(3.0), TypeError, "callable"),
        (lambda: ep.simulate(BODY, "drag", 0.04, k2_0=0.5), TypeError, "torque"),
        # a torque bound to another body or orbit than the run's
        (lambda: ep.simulate(BODY, ep.GravityGradient(ep.Body(3, 2, 1.5)), 0.04, k2_0=0.5), ValueError, "Body"),
        (lambda: ep.simulate(BODY, ep.GravityGradient(BODY), 0.04, k2_0=0.5, orbit=ep.Orbit(0.2)), ValueError,
         "Orbit"),
        # a callable returning the wrong shape or NaN is refused at the start, naming the torque
        (lambda: ep.simulate(BODY, lambda o, C, nu: 0.0, 0.04, k2_0=0.5), ValueError, "shape"),
        (lambda: ep.simulate(BODY, lambda o, C, nu: np.full(3, np.nan), 0.04, k2_0=0.5), ValueError, "non-finite"),
    ],
)
def test_bad_torques_are_named(call, exc, match):
    with pytest.raises(exc, match=match):
        call()


@pytest.mark.parametrize("formulation", ["body", "angles"])
@pytest.mark.parametrize("orbit", [None, ep.Orbit(0.3)])
def test_drag_tensor_and_torque_objects_give_the_same_full_motion(formulation, orbit):
    # Two independent codings of the right-hand side: the drag-tensor path (scalar formulas of (3), written
    # out by hand) and the generic path (the torque objects' vectorised formulas, called through the
    # protocol). Same solver, same steps: the difference is rounding amplified by the integration (~1e-12).
    te = np.linspace(0, 0.3, 7)
    kw = dict(tau_span=(0, 0.3), tau_eval=te, k2_0=0.8, delta0=1.0, lam0=-0.4, nu0=0.7, orbit=orbit,
              u0=0.9, psi0=0.3, formulation=formulation)
    a = ep.simulate(BODY, I_OFF, 0.04, **kw)
    b = ep.simulate(BODY, ep.LinearDrag(I_OFF) + ep.GravityGradient(BODY, orbit), 0.04, **kw)
    assert a.status == 0 and b.status == 0
    for f in FIELDS:
        assert getattr(b, f) == pytest.approx(getattr(a, f), rel=0, abs=1e-10), f


def test_plain_function_torque_in_simulate():
    # the drag written by hand as a plain function, the gravity gradient as an object: the sum acts as the
    # drag tensor does (a third coding of -I omega)
    def drag(omega, C, nu):
        return -np.einsum("ij,...j->...i", I_OFF, omega)

    te = np.linspace(0, 0.2, 5)
    kw = dict(tau_span=(0, 0.2), tau_eval=te, k2_0=0.6, sigma=-1, u0=0.4)
    a = ep.simulate(BODY, I_OFF, 0.04, **kw)
    b = ep.simulate(BODY, ep.GravityGradient(BODY) + drag, 0.04, **kw)
    for f in FIELDS:
        assert getattr(b, f) == pytest.approx(getattr(a, f), rel=0, abs=1e-10), f


def test_a_torque_object_is_the_whole_perturbation():
    # a torque along G (M = c g in body axes) gives exactly dG/dtau = c G, dT/dtau = omega . M = 2 c T: so
    # G(tau) = exp(c tau) while G^2/2T (hence k2) and the direction of G stay constant -- which holds only
    # if no drag or gravity is added to the torque object
    c = -0.7

    def along_g(omega, C, nu):
        return c * omega * BODY.A

    te = np.linspace(0, 0.5, 6)
    s = ep.simulate(BODY, along_g, 0.04, k2_0=0.6, tau_span=(0, 0.5), tau_eval=te)
    assert s.status == 0
    # integrator tolerance rtol 1e-10 over ~ 300 time units: 1e-8
    assert s.G == pytest.approx(np.exp(c * te), rel=1e-8, abs=0)
    assert s.k2 == pytest.approx(0.6, abs=1e-8)
    assert s.delta == pytest.approx(math.pi / 4, abs=1e-8) and s.lam == pytest.approx(math.pi / 4, abs=1e-8)
