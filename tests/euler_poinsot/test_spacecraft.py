"""Spacecraft: a physical state in SI units mapped onto the paper's nondimensional problem and back (round trip to
1e-13), the units (scaling the body and the torques, the time), the orbit in SI units, symmetric bodies and the
refusals."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq
from scipy.spatial.transform import Rotation

from rigidbody import euler_poinsot as ep


def random_tensor(rng, A):
    """A non-diagonal tensor with principal moments ``A`` in random body axes."""
    Q = Rotation.random(random_state=rng).as_matrix()
    return Q @ np.diag(A) @ Q.T


def angle_between(R1, R2):
    return (R1 * R2.inv()).magnitude()


LEO = ep.KeplerOrbit(altitude=500e3, nu0=0.7, orientation=Rotation.from_euler("ZXZ", [0.4, 1.7, -2.0]))


@pytest.mark.parametrize("moments", [(12.0, 10.0, 7.0), (7.0, 10.0, 12.0), (2.113, 1.910, 1.950)])
@pytest.mark.parametrize("seed", range(4))
def test_round_trip_physical_paper_physical(moments, seed):
    rng = np.random.default_rng(seed)
    J = random_tensor(rng, moments)
    w = rng.normal(size=3) * 0.07
    R = Rotation.random(random_state=rng)
    sc = ep.Spacecraft(J, w, R, orbit=LEO)
    p = sc.paper
    # the paper's variables mean what they say: eps the orbital rate in units of |w|, G~0 = 1, A~ = A |w|/G
    assert p.eps == pytest.approx(LEO.n / np.linalg.norm(w), rel=1e-15, abs=0)
    G = np.linalg.norm(J @ w)
    A = np.linalg.eigvalsh(J)[::-1]
    assert [p.body.A1, p.body.A2, p.body.A3] == pytest.approx(A * np.linalg.norm(w) / G, rel=1e-13, abs=0)
    assert p.k2_0 == pytest.approx(ep.k2_from(p.body, 1.0, 0.5 * w @ J @ w / (G * np.linalg.norm(w)), p.kind),
                                   rel=1e-12, abs=1e-14)
    n = LEO.orientation.inv().apply(R.apply(J @ w)) / G  # G's direction in the orbital axes
    assert [np.sin(p.delta0) * np.cos(p.lam0), np.sin(p.delta0) * np.sin(p.lam0), np.cos(p.delta0)] == (
        pytest.approx(n, rel=0, abs=1e-15 * 10))  # rounding of the eigenvectors and of two rotations
    # back to the physical state through initial_state, the start of simulate: 1e-13 relative (the state passes
    # through the principal axes (eigh: ~1e-15), the elliptic phase and the Euler angles, each a few ulps)
    omega, attitude = p.state()
    assert np.abs(omega - w).max() <= 1e-13 * np.linalg.norm(w)
    assert angle_between(attitude, R) <= 1e-13


def test_round_trip_holds_for_principal_moments_given_in_any_order_and_a_quaternion():
    w, q = np.array([0.01, -0.12, 0.05]), np.array([0.1, -0.5, 0.3, 0.8])
    sc = ep.Spacecraft([7.0, 12.0, 10.0], w, q, orbit=ep.KeplerOrbit(radius=7.0e6, e=0.2))
    omega, attitude = sc.paper.state()
    assert np.abs(omega - w).max() <= 1e-13 * np.linalg.norm(w)  # as above
    assert angle_between(attitude, Rotation.from_quat(q)) <= 1e-13


def test_scaling_the_body_and_its_torques_scales_the_momentum_only():
    # J -> cJ with every torque times c (drag, magnet, constant; the gravity gradient is proportional to J) is the
    # same motion: omega(t) and the attitude unchanged, G and T times c. Both map to one nondimensional problem (to
    # rounding of the scales), so the runs agree to the integrator's accuracy: rtol 1e-12 over ~5 turns, bound
    # 1e-10 (as in test_spacecraft_physics)
    rng = np.random.default_rng(3)
    J, w, R = random_tensor(rng, (12.0, 10.0, 7.0)), rng.normal(size=3) * 0.04, Rotation.random(random_state=rng)
    torques = {"drag": np.diag([1e-4, 2e-4, 1.5e-4]), "dipole": [0.5, -0.3, 0.8], "field": [2e-5, -1e-5, 3e-5],
               "torque": [1e-5, -2e-5, 5e-6]}
    t = np.linspace(0.0, 600.0, 4)
    runs = []
    for c in (1.0, 4.0):  # 4: every length doubled, the mass kept
        scaled = {k: (v if k == "field" else c * np.asarray(v)) for k, v in torques.items()}
        sc = ep.Spacecraft(c * J, w, R, orbit=LEO)
        runs.append(sc.simulate((0.0, 600.0), t, rtol=1e-12, atol=1e-14, **scaled))
    one, four = runs
    assert np.abs(four.omega - one.omega).max() <= 1e-10 * 0.07
    assert angle_between(four.attitude, one.attitude).max() <= 1e-10
    assert four.G == pytest.approx(4 * one.G, rel=1e-10, abs=0)
    assert four.T == pytest.approx(4 * one.T, rel=1e-10, abs=0)
    # and the torques did something: omega moved by far more than the bound
    assert np.abs(one.omega[-1] - ep.Spacecraft(J, w, R, orbit=LEO).motion.omega(600.0)).max() >= 1e-3 * 0.04


def test_a_faster_clock_scales_time_and_rates():
    # w -> s w, n -> s n, drag -> s I, a constant torque -> s^2 M: the motion runs s times faster, omega s times
    # larger (Euler's equations are homogeneous in 1/time). Same nondimensional problem: bound 1e-10 as above
    # (the averaged run holds rtol 1e-10 relative)
    rng = np.random.default_rng(4)
    J, w, R = random_tensor(rng, (12.0, 10.0, 7.0)), rng.normal(size=3) * 0.04, Rotation.random(random_state=rng)
    s = 3.0
    runs = []
    for k in (1.0, s):
        orbit = ep.KeplerOrbit(mean_motion=k * 1.1e-3, e=0.05)
        sc = ep.Spacecraft(J, k * w, R, orbit=orbit)
        t = np.linspace(0.0, 20000.0, 5) / k
        runs.append(sc.averaged((0.0, t[-1]), t, drag=k * np.diag([2e-4, 1e-4, 3e-4]), torque=k * k * np.array(
            [1e-5, 0.0, -1e-5])))
    slow, fast = runs
    assert fast.t == pytest.approx(slow.t / s, rel=1e-13, abs=0)
    assert fast.spin_rate == pytest.approx(s * slow.spin_rate, rel=1e-10, abs=0)
    assert fast.G == pytest.approx(s * slow.G, rel=1e-10, abs=0)
    assert fast.T == pytest.approx(s * s * slow.T, rel=1e-10, abs=0)
    assert np.abs(fast.momentum / fast.G[:, None] - slow.momentum / slow.G[:, None]).max() <= 1e-10
    assert slow.G[-1] <= 0.9 * slow.G[0]  # the drag acted


def test_orbit_averaged_limit_is_within_eps_of_the_run_with_the_true_anomaly():
    sc = ep.Spacecraft([12.0, 10.0, 7.0], [0.08, 0.01, 0.06], orbit=ep.KeplerOrbit(altitude=500e3, e=0.01))
    t = np.linspace(0.0, 3 * 86400.0, 4)  # tau = 0.9: G turns by 27 degrees about the orbit normal
    drag = [2e-5, 2e-5, 2e-5]
    along, limit = sc.averaged((0.0, t[-1]), t, drag=drag), sc.averaged((0.0, t[-1]), t, drag=drag,
                                                                         orbit_averaged=True)
    eps = sc.paper.eps
    # G and T do not feel the gravity gradient on average, so they agree to the integrators' tolerance (rtol 1e-10
    # relative per step: 1e-9); the direction differs by the orbital-frequency oscillation, O(eps) (measured 0.3 eps)
    assert limit.G == pytest.approx(along.G, rel=1e-9, abs=0)
    turn = np.arctan2(np.linalg.norm(np.cross(along.momentum, limit.momentum), axis=1),
                      np.einsum("ij,ij->i", along.momentum, limit.momentum))
    assert turn.max() <= eps
    moved = np.arctan2(np.linalg.norm(np.cross(along.momentum[0], along.momentum[-1])),
                       along.momentum[0] @ along.momentum[-1])
    assert moved >= 20 * eps
    assert np.all(limit.nu == 0.0)  # nu0 = 0: the true anomaly is averaged out


def test_orbit_in_si_units():
    # the mean motion of a 500 km orbit: sqrt(mu/a^3), a = R_earth + 500 km (WGS 84, IERS 2010 mu)
    orbit = ep.KeplerOrbit(altitude=500e3)
    assert orbit.n == pytest.approx(math.sqrt(3.986004418e14 / 6878137.0**3), rel=1e-15, abs=0)
    assert orbit.period / 60.0 == pytest.approx(94.6, rel=0, abs=0.05)  # the textbook 94.6 min at 500 km
    assert ep.KeplerOrbit(radius=6878137.0).n == orbit.n
    # the true anomaly by Kepler's equation against root finding of M = E - e sin E, and continuous
    ecc = ep.KeplerOrbit(mean_motion=1e-3, e=0.3, nu0=2.0)
    t = np.linspace(0.0, 15000.0, 31)
    nu = ecc.true_anomaly(t)
    E0 = 2 * math.atan(math.sqrt(0.7 / 1.3) * math.tan(1.0))
    for ti, nui in zip(t, nu):
        M = E0 - 0.3 * math.sin(E0) + 1e-3 * ti
        E = brentq(lambda x, M=M: x - 0.3 * math.sin(x) - M, M - 1.0, M + 1.0, xtol=1e-15, rtol=1e-15)
        ref = 2 * math.atan2(math.sqrt(1.3) * math.sin(E / 2), math.sqrt(0.7) * math.cos(E / 2))
        assert math.remainder(nui - ref, 2 * math.pi) == pytest.approx(0.0, rel=0, abs=1e-13)  # a few ulps of 2 pi
    assert nu[0] == pytest.approx(2.0, rel=0, abs=1e-15)
    assert np.all(np.diff(nu) > 0)  # continuous through the turns: no wrap
    assert ecc.true_anomaly(2 * math.pi / 1e-3) == pytest.approx(2.0 + 2 * math.pi, rel=0, abs=1e-12)


def test_symmetric_body_torque_free_in_closed_form_and_averaged_with_torques():
    J, w, R = [2.0, 2.0, 1.5], np.array([0.03, 0.01, 0.1]), Rotation.from_euler("xyz", [0.3, -0.2, 1.0])
    sc = ep.Spacecraft(J, w, R, orbit=LEO)
    assert isinstance(sc.paper.body, ep.SymmetricBody)
    assert sc.averaged((0.0, 10.0)).status == 0  # the gravity gradient is on by default
    t = np.linspace(0.0, 100.0, 5)
    sol = sc.simulate((0.0, 100.0), t, gravity_gradient=False)
    # regular precession: omega_3 fixed, the transverse part turns at (At - As) w3 / At in body axes (exact)
    Om = (2.0 - 1.5) * 0.1 / 2.0
    ref = np.column_stack([0.03 * np.cos(Om * t) + 0.01 * np.sin(Om * t), -0.03 * np.sin(Om * t)
                           + 0.01 * np.cos(Om * t), np.full(len(t), 0.1)])
    assert np.abs(sol.omega - ref).max() <= 1e-15
    # the attitude against quaternion kinematics integrated with that omega (DOP853, rtol 1e-13: ~1e-12 rad)
    kin = solve_ivp(lambda ti, q: 0.5 * quat_rate(q, [0.03 * math.cos(Om * ti) + 0.01 * math.sin(Om * ti),
                                                      -0.03 * math.sin(Om * ti) + 0.01 * math.cos(Om * ti), 0.1]),
                    (0.0, 100.0), R.as_quat(), method="DOP853", rtol=1e-13, atol=1e-15, t_eval=t)
    assert angle_between(sol.attitude, Rotation.from_quat(kin.y.T)).max() <= 1e-10
    assert sol.status == 0 and sol.paper is None
    avg = sc.averaged((0.0, 100.0), t, gravity_gradient=False)
    assert np.all(avg.G == np.linalg.norm(np.array(J) * w)) and avg.attitude is None


def quat_rate(q, w):
    """q' = q (0, w) (scalar last) without the factor 1/2."""
    x, y, z, s = q
    wx, wy, wz = w
    return np.array([s * wx + y * wz - z * wy, s * wy + z * wx - x * wz, s * wz + x * wy - y * wx,
                     -x * wx - y * wy - z * wz])


@pytest.mark.parametrize("moments", [(2.0, 2.0, 1.5), (1.5, 2.0, 2.0), (3.0, 3.0, 3.0)])
@pytest.mark.parametrize("seed", range(3))
def test_round_trip_of_a_symmetric_body(moments, seed):
    """Two equal moments (in a random tensor: equal to rounding only): the start is a SymmetricBody whose axial
    moment is the distinct one, theta0 the angle of G from that principal axis (its eigenvector, found here), and
    the state comes back to rounding through the regular precession's start (1e-13, as for a triaxial body)."""
    rng = np.random.default_rng(seed)
    J = random_tensor(rng, moments)
    w = rng.normal(size=3) * 0.07
    R = Rotation.random(random_state=rng)
    p = ep.Spacecraft(J, w, R, orbit=LEO).paper
    assert isinstance(p.body, ep.SymmetricBody)
    vals, vecs = np.linalg.eigh(J)
    distinct = 0 if abs(vals[1] - vals[2]) < 1e-9 else 2  # the moment that differs (any for the sphere)
    scale = np.linalg.norm(w) / np.linalg.norm(J @ w)
    # two eigensolvers (ours through principal_axes, numpy's here) on a tensor of condition ~2: a few ulps of the
    # moments; 1e-13 leaves a factor ~100 (and the equal pair is averaged: their rounding split is 1e-16)
    assert p.body.axial == pytest.approx(vals[distinct] * scale, rel=1e-13, abs=0)
    assert p.body.transverse == pytest.approx(vals[1] * scale, rel=1e-13, abs=0)
    if moments[0] != moments[2]:
        g = J @ w
        cos_theta = abs(vecs[:, distinct] @ g) / np.linalg.norm(g)
        # the symmetry axis is a well-separated eigenvector (gap ~0.5 of the moments): its rounding is ~1e-16 rad
        assert abs(math.cos(p.theta0)) == pytest.approx(cos_theta, rel=0, abs=1e-14)
    omega, attitude = p.state()
    # the bound of the triaxial round trip above (a few rotations and the Euler angles, each a few ulps)
    assert np.abs(omega - w).max() <= 1e-13 * np.linalg.norm(w)
    assert angle_between(attitude, R) <= 1e-13


@pytest.mark.parametrize(("w", "match"), [([0.0, 0.0, 0.0], "at rest"), ([0.0, 0.1, 0.0], "separatrix")])
def test_rest_and_separatrix_are_refused_with_a_torque(w, match):
    sc = ep.Spacecraft([12.0, 10.0, 7.0], w, orbit=LEO)
    with pytest.raises(ValueError, match=match):
        sc.averaged((0.0, 10.0))
    sol = sc.simulate((0.0, 10.0), [10.0], gravity_gradient=False)  # torque-free: the closed form
    assert np.array_equal(sol.omega[0], w)


def test_bad_input_is_refused_naming_the_parameter():
    J, w = [12.0, 10.0, 7.0], [0.05, 0.01, 0.02]
    with pytest.raises(ValueError, match="exactly one of radius"):
        ep.KeplerOrbit(radius=7e6, altitude=5e5)
    with pytest.raises(ValueError, match="exactly one of radius"):
        ep.KeplerOrbit()
    with pytest.raises(ValueError, match="mu must be finite and > 0"):
        ep.KeplerOrbit(radius=7e6, mu=-1.0)
    with pytest.raises(ValueError, match="altitude must be finite and > 0"):
        ep.KeplerOrbit(altitude=-1.0)
    with pytest.raises(ValueError, match="eccentricity"):
        ep.KeplerOrbit(radius=7e6, e=1.0)
    with pytest.raises(TypeError, match="orientation must be a single scipy Rotation"):
        ep.KeplerOrbit(radius=7e6, orientation=np.eye(3))
    with pytest.raises(TypeError, match="orbit must be a KeplerOrbit"):
        ep.Spacecraft(J, w, orbit=ep.Orbit())
    sc = ep.Spacecraft(J, w, orbit=LEO)
    with pytest.raises(ValueError, match=r"field .* goes with dipole .* or eddy"):
        sc.averaged((0.0, 10.0), dipole=[1.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="drag must be a 3x3 tensor"):
        sc.averaged((0.0, 10.0), drag=[1.0, 2.0])
    with pytest.raises(ValueError, match="torque must have 3 components"):
        sc.averaged((0.0, 10.0), torque=[1.0])
    with pytest.raises(TypeError, match="gravity_gradient must be True or False"):
        sc.averaged((0.0, 10.0), gravity_gradient=1)
    with pytest.raises(TypeError, match="u0 follow from the spacecraft's state"):
        sc.simulate((0.0, 10.0), u0=0.3)
    with pytest.raises(TypeError, match="eps follow from the spacecraft's state"):
        sc.averaged((0.0, 10.0), eps=0.0)
    with pytest.raises(ValueError, match="t_eval must be finite"):
        sc.averaged((0.0, 10.0), [0.0, np.nan])
    with pytest.raises(ValueError, match=r"t_eval must lie within t_span = \(0.0, 10.0\), got \[0.0, 20.0\]"):
        sc.simulate((0.0, 10.0), [0.0, 20.0])
    with pytest.raises(ValueError, match="t_span must be finite with end >= start"):
        sc.averaged((10.0, 0.0))
