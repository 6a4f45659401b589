"""The axis path rebuilt from v(t) and k(t) alone (Darboux frame) against the full simulation.

Both routes run DOP853 at rtol=1e-12 (the simulation in t on Euler's equations + quaternion, the
reconstruction in u = 1 - exp(-gamma t) on the frame equations); each carries ~1e-12 error per
e-folding, so the paths agree to 1e-10 rad (the must-show target). The angle between two unit vectors
this close is |n1 - n2| to O(angle^3).
"""

import math

import numpy as np
import pytest
from viscous_testlib import initial

from rigidbody import viscous as vs

CASES = [
    (vs.Body(2.0, 1.0), vs.Medium(0.3, 0.1)),    # contracting
    (vs.Body(2.0, 1.0), vs.Medium(0.1, 0.1)),    # unwinding
    (vs.Body(2.0, 1.0), vs.Medium(0.2, 0.1)),    # circle
    (vs.Body(1.5, 2.5), vs.Medium(0.6, 0.5)),    # contracting, theta3 > theta12
    (vs.Body(1.5, 2.5), vs.Medium(0.15, 0.5)),   # unwinding, theta3 > theta12
]




def angle(a, b):
    return np.max(np.linalg.norm(np.asarray(a) - np.asarray(b), axis=0))


def rotate(axis, ang, x):
    """Rodrigues rotation of the vector x about the unit axis by the angles ang (array)."""
    ang = np.asarray(ang)[None, :]
    ax = axis[:, None]
    xx = x[:, None]
    return xx * np.cos(ang) + np.cross(ax, xx, axis=0) * np.sin(ang) + ax * (ax[:, 0] @ x) * (1 - np.cos(ang))


@pytest.mark.parametrize(("body", "medium"), CASES)
@pytest.mark.parametrize("Omega0", [3.0, -1.2])
def test_axis_path_matches_simulation(body, medium, Omega0):
    """Also fixes the sign convention of k: k has the sign of Omega0 and turns the path towards
    g = n x tau. Flipping the sign of k in the reconstruction would fail this test."""
    n0, nd0 = initial()
    t = np.linspace(0.0, 60.0, 121)
    sim = vs.simulate(body, medium, n0, nd0, Omega0, (0.0, 60.0), t_eval=t)
    n = vs.axis_path(body, medium, n0, nd0, Omega0, t)
    assert n.shape == (3, t.size)
    assert angle(n, sim.n) < 1e-10
    # unsorted t_eval and a scalar-like list work
    n_rev = vs.axis_path(body, medium, n0, nd0, Omega0, t[::-1])
    assert angle(n_rev[:, ::-1], n) < 1e-12  # same integration, outputs only permuted: dense-output rounding


def test_wrong_sign_of_k_would_be_detected():
    body, medium = CASES[0]
    n0, nd0 = initial()
    t = np.linspace(0.0, 20.0, 21)
    sim = vs.simulate(body, medium, n0, nd0, 3.0, (0.0, 20.0), t_eval=t)
    n_flipped = vs.axis_path(body, medium, n0, nd0, -3.0, t)  # reconstruction with k -> -k
    assert angle(n_flipped, sim.n) > 1e-2


def test_regular_as_k_goes_to_infinity_and_at_infinite_time():
    """Strongly contracting: k = k0 exp(0.4 t) reaches ~1e10 by t = 60. The reconstruction (which never
    divides by v) still matches the simulation there, and its end point (t = inf) is the limit point:
    |n(inf) - n(60)| <= integral_60^inf v dt = v0 exp(-30)/0.5 ~ 7e-14."""
    body, medium = vs.Body(2.0, 1.0), vs.Medium(1.0, 0.1)
    n0, nd0 = initial(seed=5)
    t = np.array([0.0, 10.0, 30.0, 60.0])
    k = vs.curvature(body, medium, 3.0, 0.4, t)
    assert k[-1] > 1e10
    sim = vs.simulate(body, medium, n0, nd0, 3.0, (0.0, 60.0), t_eval=t)
    n = vs.axis_path(body, medium, n0, nd0, 3.0, np.append(t, np.inf))
    assert angle(n[:, :-1], sim.n) < 1e-10
    assert angle(n[:, -1:], n[:, -2:-1]) < 1e-12
    assert abs(np.linalg.norm(n[:, -1]) - 1) < 1e-12


def test_unwinding_path_tends_to_a_great_circle():
    """k -> 0: at late times the path's osculating centre c = (k n + g)/sqrt(1+k^2) is ~ g and the axis
    stays on the great circle with pole c(inf); its tip ends on that circle (c . n -> 0)."""
    body, medium = vs.Body(2.0, 1.0), vs.Medium(0.1, 0.2)   # a = 0.05 < b = 0.2
    n0, nd0 = initial(seed=6)
    t_late = np.array([150.0, 200.0, np.inf])
    n, tau, g = vs.axis_path(body, medium, n0, nd0, 2.0, t_late, frame=True)
    k = vs.curvature(body, medium, 2.0, 0.4, t_late[:2])
    assert np.all(k < 1e-6)
    pole = g[:, -1]
    # distance of the late points from the limiting great circle: <= integral of v k dt (tiny)
    assert np.max(np.abs(pole @ n)) < 1e-5
    sim = vs.simulate(body, medium, n0, nd0, 2.0, (0.0, 200.0), t_eval=t_late[:2])
    assert angle(n[:, :2], sim.n) < 1e-10


def test_zero_spin_gives_a_great_circle_arc():
    """Omega0 = 0: k = 0, n(t) = cos s(t) n0 + sin s(t) tau0 exactly, s from (5.1)."""
    body, medium = CASES[0]
    n0, nd0 = initial(seed=7)
    t = np.linspace(0.0, 40.0, 41)
    s = vs.quasi_coordinates(body, medium, 0.0, 0.4, t)[0]
    exact = np.cos(s) * n0[:, None] + np.sin(s) * (nd0 / 0.4)[:, None]
    sim = vs.simulate(body, medium, n0, nd0, 0.0, (0.0, 40.0), t_eval=t)
    # great circle: the rotation is about a fixed axis, errors ~ rtol * s_inf = 1e-12 * 2.7
    assert angle(sim.n, exact) < 1e-11
    assert angle(vs.axis_path(body, medium, n0, nd0, 0.0, t), exact) < 1e-11
    assert np.all(vs.curvature(body, medium, 0.0, 0.4, t) == 0.0)
    assert np.all(sim.Omega == 0.0) and np.all(sim.zeta == 0.0)
    # the end point t = inf is at arc length s_inf along the great circle (contracting medium: b < a,
    # the compactified-time exponent of the spin term is negative: it used to raise ZeroDivisionError)
    s_inf = vs.limits(body, medium, 0.0, 0.4)[0]
    end = vs.axis_path(body, medium, n0, nd0, 0.0, [np.inf])[:, 0]
    assert np.linalg.norm(end - (np.cos(s_inf) * n0 + np.sin(s_inf) * nd0 / 0.4)) < 1e-11


def test_fixed_axis_when_v0_is_zero():
    body, medium = CASES[0]
    n0, _ = initial(seed=8)
    t = np.linspace(0.0, 10.0, 11)
    sim = vs.simulate(body, medium, n0, np.zeros(3), 2.0, (0.0, 10.0), t_eval=t)
    # p = q = 0 is invariant; the quaternion only turns about n, so n moves by rounding only
    assert angle(sim.n, np.repeat(n0[:, None], t.size, axis=1)) < 1e-14
    assert np.all(np.isinf(sim.k)) and np.all(sim.k > 0)
    assert np.max(np.abs(sim.Omega / vs.Omega(body, medium, 2.0, t) - 1)) < 1e-12  # log-polar: rtol * |rho|
    n = vs.axis_path(body, medium, n0, np.zeros(3), 2.0, t)
    assert angle(n, np.repeat(n0[:, None], t.size, axis=1)) < 1e-15  # n0 renormalised: rounding only
    assert np.all(vs.curvature(body, medium, 2.0, 0.0, t) == np.inf)
    assert np.all(vs.spiral_radius(body, medium, 2.0, 0.0, t) == 0.0)
    with pytest.raises(ValueError, match="at rest"):
        vs.curvature(body, medium, 0.0, 0.0, t)
    with pytest.raises(ValueError, match="no turn"):
        vs.turn(body, medium, n0, np.zeros(3), 2.0)


def test_routh_case_is_an_exact_circle_with_exponentially_decaying_momentum():
    """B12/theta12 = B3/theta3 = alpha (1.3): K = K0 exp(-alpha t) in inertial space, and the axis runs on
    the small circle with centre c = (k n0 + g0)/sqrt(1+k^2), angle psi(t) = s(t) sqrt(1+k^2)."""
    body, medium = CASES[2]
    alpha = medium.B12 / body.theta12
    n0, nd0 = initial(seed=9)
    Om0, v0 = 1.7, 0.4
    t = np.linspace(0.0, 50.0, 51)
    sim = vs.simulate(body, medium, n0, nd0, Om0, (0.0, 50.0), t_eval=t)
    K = body.theta12 * np.cross(sim.n, sim.ndot, axis=0) + body.theta3 * sim.Omega * sim.n
    K0 = body.theta12 * np.cross(n0, nd0) + body.theta3 * Om0 * n0
    assert np.max(np.linalg.norm(K * np.exp(alpha * t) - K0[:, None], axis=0)) < 1e-10 * np.linalg.norm(K0)
    k = body.theta3 * Om0 / (body.theta12 * v0)
    c = (k * n0 + np.cross(n0, nd0 / v0)) / math.hypot(1.0, k)
    psi = vs.quasi_coordinates(body, medium, Om0, v0, t)[0] * math.hypot(1.0, k)
    exact = rotate(c, psi, n0)
    assert angle(sim.n, exact) < 1e-10
    assert angle(vs.axis_path(body, medium, n0, nd0, Om0, t), exact) < 1e-10
    assert np.allclose(vs.curvature(body, medium, Om0, v0, t), k, rtol=1e-14)


def test_axis_path_accepts_repeated_unsorted_and_scalar_times():
    body, medium = CASES[0]
    n0, nd0 = initial()
    a = vs.axis_path(body, medium, n0, nd0, 2.0, [5.0, 1.0, 5.0, 0.0])
    b = vs.axis_path(body, medium, n0, nd0, 2.0, [0.0, 1.0, 5.0])
    assert np.array_equal(a[:, 0], a[:, 2]) and np.array_equal(a[:, 3], b[:, 0])
    assert angle(a[:, [3, 1, 0]], b) < 1e-13  # same steps, different output grids: interpolation rounding
    assert vs.axis_path(body, medium, n0, nd0, 2.0, 0.0).shape == (3, 1)
