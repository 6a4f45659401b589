"""3-1-3 Euler angles: orthogonality, round trips, kinematics, SciPy agreement, degenerate rule."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from rigidbody.core import euler

ang = st.floats(-math.pi, math.pi)
nut = st.floats(1e-6, math.pi - 1e-6)


@settings(max_examples=50)
@given(psi=ang, theta=st.floats(0.0, math.pi), phi=ang)
def test_dcm_orthogonal_det_one_and_scipy_zxz(psi, theta, phi):
    R = euler.dcm(psi, theta, phi)
    np.testing.assert_allclose(R @ R.T, np.eye(3), atol=1e-15)
    assert np.linalg.det(R) == pytest.approx(1.0, abs=1e-14)
    # intrinsic Z-X-Z in SciPy is the same convention, independently implemented
    Rs = Rotation.from_euler("ZXZ", [psi, theta, phi]).as_matrix()
    np.testing.assert_allclose(R, Rs, atol=1e-15)
    # third column: the body symmetry axis in the reference frame
    np.testing.assert_allclose(
        R[:, 2], [math.sin(theta) * math.sin(psi), -math.sin(theta) * math.cos(psi), math.cos(theta)], atol=1e-15
    )


@settings(max_examples=50)
@given(psi=ang, theta=nut, phi=ang)
def test_angles_round_trip(psi, theta, phi):
    p2, t2, f2 = euler.angles(euler.dcm(psi, theta, phi))
    # angles are recovered up to rounding amplified by 1/sin(theta)
    tol = 1e-15 / math.sin(theta) + 1e-14
    assert t2 == pytest.approx(theta, abs=tol)
    assert math.remainder(p2 - psi, 2 * math.pi) == pytest.approx(0.0, abs=tol)
    assert math.remainder(f2 - phi, 2 * math.pi) == pytest.approx(0.0, abs=tol)


@pytest.mark.parametrize("theta", [0.0, math.pi])
def test_degenerate_rule(theta):
    psi, phi = 0.7, -0.4
    R = euler.dcm(psi, theta, phi)
    p2, t2, f2 = euler.angles(R)
    assert f2 == 0.0
    assert t2 == pytest.approx(theta, abs=1e-15)
    # the documented rule reproduces the same matrix, no NaN
    np.testing.assert_allclose(euler.dcm(p2, t2, f2), R, atol=1e-15)
    expected = psi + phi if theta == 0.0 else psi - phi
    assert math.remainder(p2 - expected, 2 * math.pi) == pytest.approx(0.0, abs=1e-15)


@settings(max_examples=40)
@given(psi=ang, theta=nut, phi=ang, rates=st.lists(st.floats(-3, 3), min_size=3, max_size=3))
def test_kinematic_equations_against_finite_difference_of_dcm(psi, theta, phi, rates):
    dpsi, dth, dphi = rates
    p, q, r = euler.body_rates(theta, phi, dpsi, dth, dphi)
    h = 1e-5

    def Rt(t):
        return euler.dcm(psi + dpsi * t, theta + dth * t, phi + dphi * t)

    Rdot = (Rt(h) - Rt(-h)) / (2 * h)  # central difference, error ~ h^2 |R'''| ~ 1e-9
    W = Rt(0.0).T @ Rdot  # = skew(omega_body) for x_ref = R x_body
    np.testing.assert_allclose(W, euler.skew([p, q, r]), atol=1e-8)
    back = euler.euler_rates(theta, phi, p, q, r)
    np.testing.assert_allclose(back, rates, atol=1e-12 / math.sin(theta) + 1e-12)


def test_euler_rates_singular_raises():
    with pytest.raises(ValueError, match="theta"):
        euler.euler_rates(0.0, 0.1, 1.0, 0.0, 1.0)


@settings(max_examples=50)
@given(psi=ang, theta=st.floats(0.0, math.pi), phi=ang)
def test_quaternion_round_trips_and_scipy(psi, theta, phi):
    q = euler.quat_from_euler(psi, theta, phi)
    R = euler.dcm(psi, theta, phi)
    np.testing.assert_allclose(euler.dcm_from_quat(q), R, atol=1e-15)
    q2 = euler.quat_from_dcm(R)
    # same rotation up to the sign of q
    assert min(np.abs(q2 - q).max(), np.abs(q2 + q).max()) < 1e-14
    xs = Rotation.from_matrix(R).as_quat()  # scalar-last in SciPy
    qs = np.array([xs[3], *xs[:3]])
    assert min(np.abs(qs - q2).max(), np.abs(qs + q2).max()) < 1e-14
    np.testing.assert_allclose(euler.dcm(*euler.euler_from_quat(q)), R, atol=1e-14)


def test_quat_rate_integrates_constant_body_rate():
    # constant body rate omega: R(t) = R0 expm(skew(omega) t); compare with SciPy's rotation vector
    from scipy.integrate import solve_ivp

    om = np.array([0.3, -0.2, 1.1])
    q0 = euler.quat_from_euler(0.2, 0.9, -0.5)
    sol = solve_ivp(lambda t, q: euler.quat_rate(q, om), (0, 2.0), q0, rtol=1e-12, atol=1e-12)
    R_end = euler.dcm_from_quat(sol.y[:, -1])
    R_ref = euler.dcm(0.2, 0.9, -0.5) @ Rotation.from_rotvec(om * 2.0).as_matrix()
    np.testing.assert_allclose(R_end, R_ref, atol=1e-10)  # integrator rtol 1e-12 over ~2 rad


def test_vectorised_shapes_and_errors():
    R = euler.dcm(np.zeros(5), np.linspace(0, 3, 5), np.ones(5))
    assert R.shape == (5, 3, 3)
    ps, th, ph = euler.angles(R)
    assert ps.shape == (5,)
    assert euler.skew(np.ones((2, 3))).shape == (2, 3, 3)
    with pytest.raises(ValueError, match="shape"):
        euler.angles(np.eye(2))
    with pytest.raises(ValueError, match="finite"):
        euler.dcm(math.nan, 0, 0)
    with pytest.raises(ValueError, match="non-zero"):
        euler.dcm_from_quat([0, 0, 0, 0])
