"""The closed-form Euler-Poinsot motion (both kinds) against Euler's equations and equations (1) with L = 0."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation

from rigidbody import euler_poinsot as ep

BODY = ep.Body(3.2, 2.6, 1.67)


@settings(max_examples=20, deadline=None)
@given(k2=st.floats(0.0, 0.999), G=st.floats(0.3, 3.0), kind=st.sampled_from(["max", "min"]),
       sigma=st.sampled_from([1, -1]), u0=st.floats(-5.0, 5.0))
def test_closed_form_solves_eulers_equations_and_keeps_G_T(k2, G, kind, sigma, u0):
    m = ep.EulerPoinsot(BODY, G, k2, kind, sigma)
    A1, A2, A3 = BODY.A
    t = np.linspace(0.0, 2.0 * m.period, 9)
    h = 1e-5 * m.period
    w = m.omega(t, u0)
    wd = (m.omega(t + h, u0) - m.omega(t - h, u0)) / (2 * h)
    res = [A1 * wd[0] - (A2 - A3) * w[1] * w[2], A2 * wd[1] - (A3 - A1) * w[2] * w[0],
           A3 * wd[2] - (A1 - A2) * w[0] * w[1]]
    # central differences, h = 1e-5 P: truncation ~ (h/P)^2 (2 pi)^3 |G|/A ~ 1e-8 G
    assert np.abs(res).max() < 1e-7 * G
    g = m.g(t, u0)
    assert np.linalg.norm(g, axis=0) == pytest.approx(G, rel=1e-14, abs=0)
    T = 0.5 * (g * w).sum(0)
    assert T == pytest.approx(m.T, rel=1e-13, abs=0)
    assert ep.k2_from(BODY, G, T[0], kind) == pytest.approx(k2, abs=1e-11)
    assert m.g(t + m.period, u0) == pytest.approx(g, abs=1e-12 * G)


@pytest.mark.parametrize("kind", ["max", "min"])
@pytest.mark.parametrize("k2", [0.05, 0.7, 0.99])
def test_closed_form_angles_solve_equations_1_without_torque(kind, k2):
    G = 1.3
    A1, A2, A3 = BODY.A
    m = ep.EulerPoinsot(BODY, G, k2, kind)

    def f(t, y):  # (1) with L = 0
        th, ph, ps = y
        return [G * math.sin(th) * math.sin(ph) * math.cos(ph) * (1 / A1 - 1 / A2),
                G * math.cos(th) * (1 / A3 - math.sin(ph) ** 2 / A1 - math.cos(ph) ** 2 / A2),
                G * (math.sin(ph) ** 2 / A1 + math.cos(ph) ** 2 / A2)]

    t = np.linspace(0, 1.5 * m.period, 11)
    ps0, th0, ph0 = m.angles(0.0, 0.3, 0.4)
    s = solve_ivp(f, (0, t[-1]), [th0, ph0, ps0], rtol=1e-12, atol=1e-12, t_eval=t, method="DOP853")
    ps, th, ph = m.angles(t, 0.3, 0.4)
    # integrator tolerance 1e-12 over ~ 1.5 periods: errors ~1e-10
    assert s.y[0] == pytest.approx(th, abs=1e-9)
    assert np.abs(np.angle(np.exp(1j * (s.y[1] - ph)))).max() < 1e-9
    assert s.y[2] == pytest.approx(ps, abs=1e-9)


def test_period_limits():
    # k -> 0: harmonic oscillation about the axis, period 2 pi / Omega with the classical Euler frequency
    G = 1.0
    A1, A2, A3 = BODY.A
    m = ep.EulerPoinsot(BODY, G, 0.0)
    w1 = G / A1
    Omega = w1 * math.sqrt((A1 - A2) * (A1 - A3) / (A2 * A3))
    assert m.period == pytest.approx(2 * math.pi / Omega, rel=1e-14, abs=0)
    # the period diverges logarithmically at the separatrix: P ~ 4 ln(4/k') / rate
    m1 = ep.EulerPoinsot(BODY, G, 1 - 1e-12, mc=1e-12)
    assert m1.period == pytest.approx(4 * math.log(4 / 1e-6) / m1.rate, rel=1e-6, abs=0)


def test_separatrix_and_bad_input():
    with pytest.raises(ValueError, match="separatrix"):
        ep.EulerPoinsot(BODY, 1.0, 1.0)
    with pytest.raises(ValueError, match="sigma"):
        ep.EulerPoinsot(BODY, 1.0, 0.5, sigma=0)
    with pytest.raises(TypeError, match="Body"):
        ep.EulerPoinsot((3.2, 2.6, 1.67), 1.0, 0.5)
    m = ep.EulerPoinsot.from_GT(BODY, 1.0, 1.0 / (2 * 2.0))
    assert m.kind == "min"


# ---------------------------------------------------------------------------------------------------------
# attitude: the closed form (omega, angles) against Euler's equations with quaternion kinematics, integrated
# from the motion's own initial state; and the pure spin k^2 = 0 (and its neighbours) against its exact form
# ---------------------------------------------------------------------------------------------------------
BODIES = [BODY, ep.Body(1.0, 0.7, 0.45)]


def _qmul(a, b):
    """Hamilton product, scalar first (written here, independent of rigidbody.core.euler)."""
    a0, a1, a2, a3 = a
    b0, b1, b2, b3 = b
    return np.array([a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3, a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2,
                     a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1, a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0])


def _closed_form_attitude(m, t, u0, psi0):
    """The motion's attitude (body -> Oy_i) as scipy Rotations: 3-1-3 = intrinsic 'ZXZ' (docs/conventions.md)."""
    ps, th, ph = m.angles(t, u0, psi0)
    return Rotation.from_euler("ZXZ", np.stack(np.broadcast_arrays(ps, th, ph), axis=-1))


def _integrated(m, t, u0, psi0):
    """omega and attitude by Euler's equations and q' = q (x) (0, omega) / 2, DOP853 at rtol 1e-12."""
    A1, A2, A3 = m.body.A

    def f(_, y):
        w, q = y[:3], y[3:]
        wd = [(A2 - A3) * w[1] * w[2] / A1, (A3 - A1) * w[2] * w[0] / A2, (A1 - A2) * w[0] * w[1] / A3]
        return np.concatenate([wd, 0.5 * _qmul(q, np.array([0.0, *w]))])

    q0 = _closed_form_attitude(m, 0.0, u0, psi0).as_quat(scalar_first=True)
    y0 = np.concatenate([m.omega(0.0, u0), q0])
    s = solve_ivp(f, (0.0, t[-1]), y0, method="DOP853", rtol=1e-12, atol=1e-15, t_eval=t)
    assert s.status == 0
    return s.y[:3], Rotation.from_quat(s.y[3:].T, scalar_first=True)


@pytest.mark.parametrize("body", BODIES, ids=["paper-body", "body-2"])
@pytest.mark.parametrize("sigma", [1, -1])
@pytest.mark.parametrize("k2", [0.0, 1e-300, 1e-12, 0.3])
@pytest.mark.parametrize("kind", ["max", "min"])
def test_attitude_and_omega_against_integrated_euler_equations(kind, k2, sigma, body):
    """The full attitude R(psi, theta, phi) of the closed form follows the integrated motion. Catches a psi
    advancing at the wrong rate or a phi frozen where theta = 0 (the pure spin of kind 'min' was 1.7 rad off
    after 10 time units), a wrong sign of sigma in either component, and the angle convention (ZXZ)."""
    m = ep.EulerPoinsot(body, 1.3, k2, kind, sigma)
    u0, psi0 = 0.4, 0.2
    t = np.linspace(0.0, 30.0, 31)  # ~ 8-15 rotations and 1-3 periods of the body components
    w_int, R_int = _integrated(m, t, u0, psi0)
    err_R = (_closed_form_attitude(m, t, u0, psi0).inv() * R_int).magnitude()
    # DOP853 at rtol 1e-12: local errors ~1e-12 per unit time, global growing at most linearly over 30 time
    # units (the phase error of a periodic orbit) -> ~3e-11 in rad and in omega/|omega|; 1e-9 leaves 30x
    assert err_R.max() < 1e-9
    assert np.abs(m.omega(t, u0) - w_int).max() < 1e-9 * np.abs(w_int).max()


@pytest.mark.parametrize("body", BODIES, ids=["paper-body", "body-2"])
@pytest.mark.parametrize("sigma", [1, -1])
@pytest.mark.parametrize("k2", [0.0, 1e-300, 1e-20, 1e-12])
@pytest.mark.parametrize("kind", ["max", "min"])
def test_pure_spin_exact_rotation_about_G(kind, k2, sigma, body):
    """At k^2 = 0 the body spins about the axis of the largest ('max') or smallest ('min') moment, which lies
    along +-G: R(t) = R_Z(G t / A_axis) R(0) exactly (G is along Z of Oy_i, and omega = G / A_axis along +Z for
    either sigma). Small k^2 > 0 stays within a cone of half-angle O(k) about it: continuity at k^2 = 0."""
    G = 1.3
    m = ep.EulerPoinsot(body, G, k2, kind, sigma)
    A1, A2, A3 = body.A
    A_axis, A_other = (A1, A3) if kind == "max" else (A3, A1)
    u0, psi0 = 0.4, 0.2
    t = np.linspace(0.0, 50.0, 201)
    R0 = _closed_form_attitude(m, 0.0, u0, psi0)
    spin = Rotation.from_rotvec(np.outer(G * t / A_axis, [0.0, 0.0, 1.0])) * R0
    err = (spin.inv() * _closed_form_attitude(m, t, u0, psi0)).magnitude()
    # k = 0: the same rotation by two routes, rounding of angles ~ G t / A ~ 40 rad -> ~1e-14 relative, 1e-12.
    # k > 0 (Landau's amplitudes as k -> 0): the spin axis circles G at a tilt sin(beta) <= c k, c^2 the larger
    # of A2 (A1 - A3) / (A_axis |A2 - A_other|) (the sn-component) and the cn-component's smaller ratio; the
    # spin carries the initial tilt round, so the two attitudes differ by two tilts, <= 2 c k; the twist about
    # G drifts by O(k^2) t (psi' + phi' = r + psi' (1 - cos theta)), negligible here. 2.2 c k leaves 10% for the
    # O(k) relative corrections of the amplitudes, and is far below the 1.7 rad of a wrong rate.
    c = math.sqrt(A2 * (A1 - A3) / (A_axis * abs(A2 - A_other)))
    k = math.sqrt(k2)
    assert err.max() < 1e-12 + 2.2 * c * k
    # omega_axis = G cos(beta) / A_axis: 1 - cos(beta) <= (c k)^2 / 2
    w = m.omega(t, u0)
    axis = 0 if kind == "max" else 2
    assert w[axis] == pytest.approx(sigma * G / A_axis * np.ones_like(t), rel=1e-14 + (c * k) ** 2, abs=0)
