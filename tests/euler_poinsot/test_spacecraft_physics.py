"""Spacecraft in SI units against an independent integration of a spacecraft's motion: Euler's equations in the
user's (non-principal) body axes with quaternion kinematics and the true anomaly, each SI torque written here from
its physics (no code of the library); the averaged run against the same full motion at a small eps."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation

from rigidbody import euler_poinsot as ep


def random_tensor(rng, A):
    """A non-diagonal tensor with principal moments ``A`` in random body axes."""
    Q = Rotation.random(random_state=rng).as_matrix()
    return Q @ np.diag(A) @ Q.T


def integrate_si(J, w0, R0, t, *, a=None, mu=None, e=0.0, nu0=0.0, gravity=True, orientation=None, drag=None,
                 dipole=None, field=None, torque=None, eddy=None, rtol=1e-13):
    """Body angular velocity (N, 3), attitude (body -> inertial, a Rotation) and true anomaly at ``t`` (s).

    The torques (N m, body axes): the gravity gradient 3 mu / r^3 rho x J rho (``a``, ``mu`` given; rho the unit
    radius vector in body axes, r = a (1 - e^2) / (1 + e cos nu); off with ``gravity=False``), the drag -I w, the
    magnet m x B (B in the inertial frame, T: constant or a function of the true anomaly), a constant torque, the
    eddy currents (P (w x b)) x b (P in S m^4, b = B in body axes);
    nu' = sqrt(mu / a^3) (1 + e cos nu)^2 / (1 - e^2)^1.5 (Kepler's second law). The orbital axes: x1 to the
    pericentre, x3 the normal, turned by ``orientation`` into the inertial frame."""
    J = np.asarray(J, float)
    Ji = np.linalg.inv(J)
    O = np.eye(3) if orientation is None else orientation.as_matrix()
    n = 0.0 if a is None else np.sqrt(mu / a**3)

    def rhs(_, y):
        w, (x, yy, z, s), nu = y[:3], y[3:7], y[7]
        R = Rotation.from_quat([x, yy, z, s]).as_matrix()  # body -> inertial (normalised by SciPy)
        M = -np.cross(w, J @ w)
        if a is not None and gravity:
            r = a * (1 - e * e) / (1 + e * np.cos(nu))
            rho = R.T @ O @ np.array([np.cos(nu), np.sin(nu), 0.0])
            M = M + 3 * mu / r**3 * np.cross(rho, J @ rho)
        if drag is not None:
            M = M - np.asarray(drag, float) @ w
        if dipole is not None:
            M = M + np.cross(dipole, R.T @ np.asarray(field(nu) if callable(field) else field, float))
        if torque is not None:
            M = M + np.asarray(torque, float)
        if eddy is not None:
            b = R.T @ np.asarray(field(nu) if callable(field) else field, float)
            M = M + np.cross(np.asarray(eddy, float) @ np.cross(w, b), b)
        wx, wy, wz = w
        dq = 0.5 * np.array([s * wx + yy * wz - z * wy, s * wy + z * wx - x * wz, s * wz + x * wy - yy * wx,
                             -x * wx - yy * wy - z * wz])
        dnu = n * (1 + e * np.cos(nu)) ** 2 / (1 - e * e) ** 1.5
        return np.concatenate([Ji @ M, dq, [dnu]])

    y0 = np.concatenate([w0, R0.as_quat(), [nu0]])
    sol = solve_ivp(rhs, (0.0, float(t[-1])), y0, method="DOP853", rtol=rtol, atol=1e-16, t_eval=t)
    assert sol.status == 0
    return sol.y[:3].T, Rotation.from_quat(sol.y[3:7].T), sol.y[7]


def angle_between(R1, R2):
    return (R1 * R2.inv()).magnitude()


START = np.random.default_rng(5)
J5 = random_tensor(START, [12.0, 10.0, 7.0])  # kg m^2, principal axes off the body axes
W5 = START.normal(size=3)
W5 *= 0.05 / np.linalg.norm(W5)  # rad/s: 5 turns in the 600 s of a run, eps = n/|w| = 0.022 at 500 km
R5 = Rotation.random(random_state=START)
A500 = ep.R_EARTH + 500e3
CASES = {
    "gravity gradient and drag, circular orbit": (
        {"radius": A500}, {"drag": np.diag([1e-4, 2e-4, 1.5e-4]) + 2e-5}),
    "gravity gradient, magnet and a constant torque, eccentric orbit turned in space": (
        {"radius": A500, "e": 0.1, "nu0": 0.4, "orientation": Rotation.from_euler("ZXZ", [0.3, 0.9, 1.2])},
        {"dipole": [0.5, -0.3, 0.8], "field": [2e-5, -1e-5, 3e-5], "torque": [1e-5, -2e-5, 5e-6]}),
    "magnet in a field that turns with the true anomaly, no gravity gradient": (
        {"altitude": 600e3, "e": 0.05, "orientation": Rotation.from_euler("ZXZ", [-1.0, 0.4, 0.2])},
        {"gravity_gradient": False, "dipole": [2.0, 1.0, -1.5],
         "field": lambda nu: 3e-5 * np.stack([np.cos(nu), np.sin(nu), 0.5 + 0 * nu], -1)}),
}


@pytest.mark.parametrize("case", list(CASES))
def test_simulate_in_si_units_matches_an_independent_integration(case):
    orbit_args, torques = CASES[case]
    orbit = ep.KeplerOrbit(**orbit_args)
    t = np.linspace(0.0, 600.0, 7)
    sol = ep.Spacecraft(J5, W5, R5, orbit=orbit).simulate((0.0, 600.0), t, rtol=1e-12, atol=1e-14, **torques)
    assert sol.status == 0
    reference = dict(torques)
    gravity = reference.pop("gravity_gradient", True)
    a = orbit_args["radius"] if "radius" in orbit_args else ep.R_EARTH + orbit_args["altitude"]
    w, R, nu = integrate_si(J5, W5, R5, t, a=a, mu=ep.MU_EARTH, e=orbit.e, nu0=orbit.nu0, gravity=gravity,
                            orientation=orbit.orientation, **reference)
    G = R.apply(w @ J5.T)
    # both runs hold a local error of 1e-12 (library) and 1e-13 (reference) per step over ~5 turns (a few hundred
    # steps): the global error is ~1e-12 relative (measured 1e-13 in omega, 5e-12 rad in attitude); 1e-10 leaves
    # a factor 20, and a wrong scale of any torque (or a wrong frame) would show at its effect, 1e-2 (below)
    assert np.abs(sol.omega - w).max() <= 1e-10 * 0.05
    assert angle_between(sol.attitude, R).max() <= 1e-10
    assert np.abs(sol.momentum - G).max() <= 1e-10 * np.linalg.norm(G[0])
    assert np.abs(sol.G - np.linalg.norm(G, axis=1)).max() <= 1e-10 * np.linalg.norm(G[0])
    assert np.abs(sol.T - 0.5 * np.einsum("ij,ij->i", w, w @ J5.T)).max() <= 1e-10 * sol.T[0]
    assert np.abs(sol.nu - nu).max() <= 1e-12  # the true anomaly: Kepler's law against its ODE, both ~1e-15
    assert np.array_equal(sol.t, t) or np.abs(sol.t - t).max() <= 1e-12 * t[-1]  # times back in s, to rounding
    # the torques matter far beyond the tolerances: the torque-free motion is 1e-2 away
    wf, Rf, _ = integrate_si(J5, W5, R5, t)
    assert np.abs(wf - w).max() >= 1e-2 * 0.05
    assert angle_between(Rf, R).max() >= 1e-2


def test_torque_free_simulate_matches_the_closed_form():
    orbit = ep.KeplerOrbit(altitude=800e3, orientation=Rotation.from_euler("ZXZ", [1.0, 0.5, -0.7]))
    sc = ep.Spacecraft(J5, W5, R5, orbit=orbit)
    t = np.linspace(0.0, 900.0, 10)
    sol = sc.simulate((0.0, 900.0), t, gravity_gradient=False, rtol=1e-12, atol=1e-14)
    assert sol.status == 0
    # FreeMotion (closed form, exact to rounding) against the integration at rtol 1e-12 over 7 turns: 1e-12
    # relative, bound 1e-10 (as above)
    free = ep.EulerPoinsot.from_state(J5, W5, R5)
    assert np.abs(sol.omega - free.omega(t)).max() <= 1e-10 * 0.05
    assert angle_between(sol.attitude, free.rotation(t)).max() <= 1e-10
    G0 = R5.apply(J5 @ W5)  # the angular momentum in the inertial frame, constant
    assert np.abs(sol.momentum - G0).max() <= 1e-10 * np.linalg.norm(G0)
    T0 = 0.5 * W5 @ J5 @ W5
    assert sol.spin_rate == pytest.approx(np.full(len(t), 2 * T0 / np.linalg.norm(G0)), rel=1e-10, abs=0)


def test_averaged_follows_the_full_motion_at_small_eps():
    rng = np.random.default_rng(7)
    J = random_tensor(rng, [12.0, 10.0, 7.0])
    V = np.linalg.eigh(J)[1]  # principal axes, the largest moment last
    w0 = V[:, 2] + 0.3 * V[:, 1] + 0.2 * V[:, 0]  # about the axis of the largest moment (N* far from 0)
    w0 *= 0.05 / np.linalg.norm(w0)
    n = np.array([np.sin(0.8) * np.cos(0.3), np.sin(0.8) * np.sin(0.3), np.cos(0.8)])  # G at 46 deg from x3
    R0 = Rotation.align_vectors([n], [J @ w0])[0]
    a = ep.R_EARTH + 700e3
    sc = ep.Spacecraft(J, w0, R0, orbit=ep.KeplerOrbit(radius=a))
    eps = sc.paper.eps  # 0.021
    drag = np.diag([1.0, 2.0, 1.5]) * 1e-4  # N m s
    av, G, Gn, T = _averaged_and_full(sc, J, w0, R0, a, drag=drag)  # tau = 0.2: 8900 s, 70 turns, 1.5 orbits
    # First-order averaging with the true anomaly kept explicit: the slow variables G, T of the averaged system (9)
    # follow the osculating ones of the full motion to O(eps^2) over tau = O(1) (the oscillation they carry is of
    # relative size eps^2: the torques are eps^2 of the spin's scale; docs/euler_poinsot.md, "Averaged vs full",
    # measured <= 19 eps^2 from k2 = 0.99); the direction of G carries the orbital-frequency oscillation of the
    # gravity gradient, O(eps) (measured <= 0.23 eps there). Measured here 0.8 eps^2 (G), 1.6 eps^2 (T), 0.012 eps
    # (direction); bounds 5 eps^2 and 0.25 eps.
    assert np.abs(av.G / Gn - 1.0).max() <= 5 * eps**2
    assert np.abs(av.T / T - 1.0).max() <= 5 * eps**2
    assert angles(G, av.momentum).max() <= 0.25 * eps
    # what the torques do is far beyond those bounds, so a wrong scale of either fails: the drag takes 10 % of G
    # (45 times the bound), the gravity gradient turns G by 8 times the bound
    assert Gn[-1] <= (1.0 - 30 * 5 * eps**2) * Gn[0]
    assert angles(G[:1], G[-1:])[0] >= 4 * 0.25 * eps


def _averaged_and_full(sc, J, w0, R0, a, **torques):
    """The averaged run of ``sc`` over tau = 0.2 (5 samples) and the independent full motion at the same times:
    the averaged run, and the full motion's angular momentum (inertial), its magnitude and the kinetic energy."""
    t_end = 0.2 / sc.paper.tau_per_second
    t = np.linspace(0.0, t_end, 5)
    av = sc.averaged((0.0, t_end), t, **torques)
    assert av.status == 0
    w, R, _ = integrate_si(J, w0, R0, t, a=a, mu=ep.MU_EARTH, rtol=1e-10, **torques)
    G = R.apply(w @ J.T)
    return av, G, np.linalg.norm(G, axis=1), 0.5 * np.einsum("ij,ij->i", w, w @ J.T)


def angles(U, V):
    """Angles between the rows of ``U`` and ``V``."""
    return np.arctan2(np.linalg.norm(np.cross(U, V), axis=1), np.einsum("ij,ij->i", U, V))


@pytest.mark.parametrize("moments", [(10.0, 10.0, 6.0), (10.0, 10.0, 14.0)])
def test_averaged_of_a_symmetric_body_follows_the_full_motion(moments):
    """A body with two equal moments (prolate and oblate, its tensor in random body axes) under the gravity gradient
    and eddy currents in the geomagnetic dipole: the averaged run over the regular precession (a SymmetricBody)
    against the full motion in SI units, with the bounds and the argument of the triaxial test above (first-order
    averaging: G and T to O(eps^2), the direction of G to O(eps))."""
    rng = np.random.default_rng(11)
    J = random_tensor(rng, moments)
    V = np.linalg.eigh(J)[1]
    w0 = V @ np.array([0.4, 0.3, 1.0]) if moments[2] < moments[0] else V @ np.array([1.0, 0.3, 0.4])
    w0 *= 0.05 / np.linalg.norm(w0)  # about 40 degrees from the symmetry axis
    R0 = Rotation.random(random_state=rng)
    a = ep.R_EARTH + 700e3
    field = ep.DipoleField(1.2, 0.3, a)  # tesla, in the orbital axes (= the inertial frame: no orientation)
    P = np.diag([2.0, 3.0, 2.5]) * 1e5  # S m^4: G falls by ~15 % in 1.5 orbits
    sc = ep.Spacecraft(J, w0, R0, orbit=ep.KeplerOrbit(radius=a))
    assert isinstance(sc.paper.body, ep.SymmetricBody)
    eps = sc.paper.eps  # 0.021
    av, G, Gn, T = _averaged_and_full(sc, J, w0, R0, a, eddy=P, field=field)
    assert np.abs(av.G / Gn - 1.0).max() <= 5 * eps**2
    assert np.abs(av.T / T - 1.0).max() <= 5 * eps**2
    assert angles(G, av.momentum).max() <= 0.25 * eps
    # the eddy currents take far more than the bound (11 %), the gravity gradient and they turn G beyond it
    assert Gn[-1] <= (1.0 - 30 * 5 * eps**2) * Gn[0]
    # measured (prolate) 0.4 eps^2 in G, 0.9 eps^2 in T, 0.013 eps in the direction, which the torques turn by
    # 0.65 eps (50 times the measured difference, twice the bound)
    assert angles(G[:1], G[-1:])[0] >= 2 * 0.25 * eps


@pytest.mark.parametrize("moments", [(10.0, 10.0, 6.0), (10.0, 10.0, 14.0), (9.0, 9.0, 9.0)])
def test_simulate_of_a_symmetric_body_in_si_units_matches_an_independent_integration(moments):
    """A tensor with two (or three) equal moments in random body axes: Spacecraft.simulate (a SymmetricBody, its
    start read by symmetric_start) against the independent integration, with the bounds of the triaxial cases above
    (both at local error 1e-13 over ~5 turns: at 1e-12 the sphere's attitude drifts by 2e-10 over the run, its
    error falling with the tolerance, 1.6e-11 at 1e-13)."""
    rng = np.random.default_rng(3)
    J = random_tensor(rng, moments)
    w0 = rng.normal(size=3)
    w0 *= 0.05 / np.linalg.norm(w0)
    R0 = Rotation.random(random_state=rng)
    a = ep.R_EARTH + 600e3
    field = ep.DipoleField(1.0, 0.2, a)
    torques = {"drag": np.diag([1e-4, 2e-4, 1.5e-4]), "eddy": np.diag([2.0, 3.0, 2.5]) * 1e5, "field": field}
    sc = ep.Spacecraft(J, w0, R0, orbit=ep.KeplerOrbit(radius=a))
    assert isinstance(sc.paper.body, ep.SymmetricBody)
    t = np.linspace(0.0, 600.0, 7)
    sol = sc.simulate((0.0, 600.0), t, rtol=1e-13, atol=1e-15, **torques)
    assert sol.status == 0
    w, R, _ = integrate_si(J, w0, R0, t, a=a, mu=ep.MU_EARTH, **torques)
    assert np.abs(sol.omega - w).max() <= 1e-10 * 0.05
    assert angle_between(sol.attitude, R).max() <= 1e-10
    G = R.apply(w @ J.T)
    assert np.abs(sol.momentum - G).max() <= 1e-10 * np.linalg.norm(G[0])
    wf, Rf, _ = integrate_si(J, w0, R0, t)  # the torques act far beyond the bounds
    assert np.abs(wf - w).max() >= 1e-3 * 0.05
