"""simulate for a body with two equal moments (SymmetricBody): the full equations from the nutation angle theta0.

Each run is checked against a route written here, independently of the library: the closed form of the regular
precession (torque-free), an integration of Euler's equations with quaternion kinematics by SciPy's solve_ivp
(torques), the single calls (a batch), and the triaxial body's simulate as two of its moments come together.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation

from rigidbody import euler_poinsot as ep

BODIES = {
    "prolate": ep.SymmetricBody(2.0, 1.1),
    "oblate": ep.SymmetricBody(1.2, 2.0),
    "sphere": ep.SymmetricBody(1.5, 1.5),
}
TOL = {"rtol": 1e-12, "atol": 1e-14}


def rot3(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def rot1(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def frame(delta: float, lam: float) -> np.ndarray:
    """Columns y1, y2, y3 = n of the frame attached to G, in the orbital axes (n along (delta, lam))."""
    sd, cd, sl, cl = math.sin(delta), math.cos(delta), math.sin(lam), math.cos(lam)
    n = [sd * cl, sd * sl, cd]
    y1 = [cd * cl, cd * sl, -sd]  # dn/d delta
    y2 = [-sl, cl, 0.0]  # n x y1
    return np.array([y1, y2, n]).T


def start(G: float, theta: float, delta: float, lam: float, phi: float, psi: float) -> tuple[np.ndarray, np.ndarray]:
    """The documented start: g = G (sin th sin phi, sin th cos phi, cos th), C = Y R3(psi) R1(theta) R3(phi)."""
    g = G * np.array([math.sin(theta) * math.sin(phi), math.sin(theta) * math.cos(phi), math.cos(theta)])
    return g, frame(delta, lam) @ rot3(psi) @ rot1(theta) @ rot3(phi)


def attitudes(q: np.ndarray) -> np.ndarray:
    """Body -> orbital matrices from the library's quaternions (scalar first, shape (4, n))."""
    return Rotation.from_quat(np.roll(q.T, -1, axis=1)).as_matrix()


def reference(A: np.ndarray, torque, eps: float, g0: np.ndarray, C0: np.ndarray, nu0: float,
              tau: np.ndarray, e: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Euler's equations dg/dtau = g x omega / eps^2 + M and the quaternion dq/dtau = q (x) (omega, 0) / (2 eps^2)
    (scalar last, body -> orbital), by solve_ivp at rtol 1e-13, with Kepler's law for the true anomaly,
    dnu/dtau = (1 + e cos nu)^2 / ((1 - e^2)^(3/2) eps)."""

    def rhs(t: float, y: np.ndarray) -> np.ndarray:
        g, q, nu = y[:3], y[3:7] / np.linalg.norm(y[3:7]), y[7]
        w = g / A
        M = torque(w, Rotation.from_quat(q).as_matrix(), nu)
        v, s = q[:3], q[3]
        dq = 0.5 * np.concatenate([s * w + np.cross(v, w), [-v @ w]]) / eps**2
        dnu = (1.0 + e * math.cos(nu)) ** 2 / ((1.0 - e * e) ** 1.5 * eps)
        return np.concatenate([np.cross(g, w) / eps**2 + M, dq, [dnu]])

    y0 = np.concatenate([g0, Rotation.from_matrix(C0).as_quat(), [nu0]])
    sol = solve_ivp(rhs, (tau[0], tau[-1]), y0, method="DOP853", t_eval=tau, rtol=1e-13, atol=1e-15)
    assert sol.success
    return sol.y[:3], Rotation.from_quat((sol.y[3:7] / np.linalg.norm(sol.y[3:7], axis=0)).T).as_matrix()


def random_state(seed: int) -> dict[str, float]:
    rng = np.random.default_rng(seed)
    return {"G0": rng.uniform(0.8, 1.4), "theta0": rng.uniform(0.2, math.pi - 0.2), "delta0": rng.uniform(0.3, 2.8),
            "lam0": rng.uniform(-math.pi, math.pi), "phi0": rng.uniform(-math.pi, math.pi),
            "psi0": rng.uniform(-math.pi, math.pi), "nu0": rng.uniform(0.0, 2.0 * math.pi)}


@pytest.mark.parametrize("name", list(BODIES))
def test_torque_free_is_the_regular_precession(name):
    body = BODIES[name]
    A, C = body.transverse, body.axial
    s = random_state(11 + len(name))
    eps, tau = 0.2, np.linspace(0.0, 1.0, 6)  # 25 units of the fast time: 15-25 rad about G
    sol = ep.simulate(body, ep.ConstantTorque([0.0, 0.0, 0.0]), eps, s["G0"], None, s["delta0"], s["lam0"],
                      (0.0, 1.0), tau, s["nu0"], theta0=s["theta0"], phi0=s["phi0"], psi0=s["psi0"], **TOL)
    assert sol.status == 0
    G, th = s["G0"], s["theta0"]
    # the closed form: G fixed, theta constant, psi turning at G/A, phi (azimuth of G in the body) at
    # G cos(theta) (1/C - 1/A), both in the fast time tau/eps^2
    t = tau / eps**2
    want = np.array([frame(s["delta0"], s["lam0"]) @ rot3(s["psi0"] + G / A * tk) @ rot1(th)
                     @ rot3(s["phi0"] + G * math.cos(th) * (1.0 / C - 1.0 / A) * tk) for tk in t])
    # the integrator's error at rtol 1e-12 over at most 25 rad of turning stays below 1e-10; a wrong sign of a
    # rate or a wrong start convention is O(1)
    assert np.max(np.abs(attitudes(sol.q) - want)) < 1e-9
    assert np.max(np.abs(sol.G - G)) < 1e-11 * G
    assert np.max(np.abs(sol.theta - th)) < 1e-10
    assert np.max(np.abs(sol.delta - s["delta0"])) < 1e-10 and np.max(np.abs(sol.lam - s["lam0"])) < 1e-10
    assert np.allclose(sol.T, 0.5 * G * G * (math.sin(th) ** 2 / A + math.cos(th) ** 2 / C), rtol=1e-11, atol=0)


def drag_and_gravity(A: np.ndarray, I: np.ndarray, e: float = 0.0):
    """The drag tensor's meaning, written out: -I omega + 3 f(nu) rho x (J rho), rho the radius in body axes,
    f = (1 + e cos nu)^3 / (1 - e^2)^3 (the orbital rate at nu over the mean motion, squared, times (a/r))."""

    def torque(w, C, nu):
        rho = C.T @ np.array([math.cos(nu), math.sin(nu), 0.0])
        f = (1.0 + e * math.cos(nu)) ** 3 / (1.0 - e * e) ** 3
        return -I @ w + 3.0 * f * np.cross(rho, A * rho)

    return torque


def callable_torque(w, C, nu):
    """A torque of the user's own (vectorised over leading axes): a body-fixed thruster, drag along the orbital
    x3 axis."""
    w = np.asarray(w)
    x3_in_body = np.asarray(C)[..., 2, :]  # C^T e3
    return np.array([0.05, -0.02, 0.08]) - 0.3 * (w * x3_in_body).sum(axis=-1)[..., None] * x3_in_body


@pytest.mark.parametrize("name", list(BODIES))
@pytest.mark.parametrize("kind", ["drag tensor", "callable"])
def test_torqued_run_matches_an_independent_integration(name, kind):
    body = BODIES[name]
    A = body.A
    s = random_state(23 + len(name) + len(kind))
    I = np.array([[0.6, 0.1, 0.0], [0.1, 0.4, 0.05], [0.0, 0.05, 0.5]])
    torque, ref_torque = (I, drag_and_gravity(A, I)) if kind == "drag tensor" else (callable_torque, callable_torque)
    eps, tau = 0.2, np.linspace(0.0, 0.8, 5)  # 20 units of the fast time
    sol = ep.simulate(body, torque, eps, s["G0"], None, s["delta0"], s["lam0"], (0.0, 0.8), tau, s["nu0"],
                      theta0=s["theta0"], phi0=s["phi0"], psi0=s["psi0"], **TOL)
    assert sol.status == 0, sol.message
    g0, C0 = start(s["G0"], s["theta0"], s["delta0"], s["lam0"], s["phi0"], s["psi0"])
    g, Cs = reference(A, ref_torque, eps, g0, C0, s["nu0"], tau)
    # the torque moves the slow variables (G, theta, the direction n) by 1e-2 or more over the span, so the
    # comparison is not one of a torque-free motion; both integrations at rtol <= 1e-12 over ~20 rad agree to
    # ~1e-10, 1e-8 leaves a margin
    moved = [abs(sol.G[-1] - sol.G[0]), abs(sol.theta[-1] - sol.theta[0]), np.abs(sol.n[:, -1] - sol.n[:, 0]).max()]
    assert max(moved) > 1e-2
    assert np.max(np.abs(sol.g - g)) < 1e-8
    assert np.max(np.abs(attitudes(sol.q) - Cs)) < 1e-8
    Gref = np.linalg.norm(g, axis=0)
    assert np.max(np.abs(sol.G - Gref)) < 1e-8
    assert np.max(np.abs(sol.theta - np.arccos(g[2] / Gref))) < 1e-7  # arccos: conditioned 1/sin(theta) >= 1/3
    n = np.einsum("kij,jk->ik", Cs, g) / Gref
    assert np.max(np.abs(sol.n - n)) < 1e-8


def test_a_batch_is_its_members_single_calls():
    body = BODIES["oblate"]
    theta0 = np.array([0.4, 2.6, 3.5])  # the last is beyond pi: refused alone
    kw = dict(delta0=1.1, lam0=0.3, tau_span=(0.0, 0.3), tau_eval=np.linspace(0.0, 0.3, 4), nu0=0.5, **TOL)
    b = ep.simulate(body, [0.5, 0.3, 0.4], 0.2, np.array([1.0, 1.3, 1.0]), theta0=theta0, phi0=0.7, **kw)
    assert b.status.tolist() == [0, 0, -1]
    assert "theta0" in b.message[2] and np.isnan(b.G[2]).all()
    for i, G0 in enumerate([1.0, 1.3]):
        one = ep.simulate(body, [0.5, 0.3, 0.4], 0.2, G0, theta0=float(theta0[i]), phi0=0.7, **kw)
        # the same equations on the vectorised and the scalar DOP853 at rtol 1e-12: steps may differ in the last
        # bits, so the runs agree to the tolerance, not bit for bit
        for f in ("G", "theta", "delta", "lam", "T"):
            assert np.max(np.abs(getattr(b, f)[i] - getattr(one, f))) < 1e-9, f
        assert np.max(np.abs(b.g[i] - one.g)) < 1e-9
    # a member alone in the batch (the other refused) runs on the scalar integrator inside the batch
    alone = ep.simulate(body, [0.5, 0.3, 0.4], 0.2, 1.0, theta0=np.array([0.4, -0.2]), phi0=0.7, **kw)
    one = ep.simulate(body, [0.5, 0.3, 0.4], 0.2, 1.0, theta0=0.4, phi0=0.7, **kw)
    assert alone.status.tolist() == [0, -1] and "theta0" in alone.message[1]
    for f in ("G", "theta", "lam"):  # the same scalar DOP853 (output through its dense output): as above
        assert np.max(np.abs(getattr(alone, f)[0] - getattr(one, f))) < 1e-9, f


@pytest.mark.parametrize("kind", ["drag tensor", "callable"])
def test_a_batch_on_an_eccentric_orbit_matches_an_independent_integration(kind):
    # the members integrated together with the true anomaly as a state (Kepler's law): the drag tensor's torque
    # written out, or the user's callable evaluated on all members at once
    body, e, eps = BODIES["prolate"], 0.3, 0.2
    I = np.diag([0.5, 0.3, 0.4])
    torque, ref_torque = (I, drag_and_gravity(body.A, I, e)) if kind == "drag tensor" else (callable_torque,
                                                                                          callable_torque)
    theta0, tau = np.array([0.5, 2.2]), np.linspace(0.0, 0.6, 4)
    kw = dict(delta0=0.9, lam0=-0.4, tau_span=(0.0, 0.6), tau_eval=tau, nu0=1.0, phi0=0.3, psi0=-1.2)
    b = ep.simulate(body, torque, eps, 1.1, theta0=theta0, orbit=ep.Orbit(e), **kw, **TOL)
    assert b.status.tolist() == [0, 0]
    for i, th in enumerate(theta0.tolist()):
        g0, C0 = start(1.1, th, 0.9, -0.4, 0.3, -1.2)
        g, Cs = reference(body.A, ref_torque, eps, g0, C0, 1.0, tau, e)
        # as in the circular case: both integrations at rtol <= 1e-12 agree to ~1e-10
        assert np.max(np.abs(b.g[i] - g)) < 1e-8
        assert np.max(np.abs(attitudes(b.q[i]) - Cs)) < 1e-8


def test_slow_rotation_stops_at_the_precession_rate():
    # strong drag: G decays, and the run stops where the precession rate over the orbital rate, G/(A eps), falls
    # to min_spin_ratio = 2
    body = BODIES["prolate"]
    eps = 0.1
    sol = ep.simulate(body, ep.LinearDrag(np.eye(3) * 3.0), eps, 1.0, theta0=0.8, delta0=1.0, tau_span=(0.0, 5.0),
                      min_spin_ratio=2.0, **TOL)
    assert sol.status == 1 and sol.event == "slow_rotation"
    # the event is located to the integrator's tolerance (rtol 1e-12), 1e-9 leaves a margin; a criterion on
    # another rate (|omega|, or the proper rate G cos(theta)(1/C - 1/A)) would stop at another G
    assert sol.G[-1] == pytest.approx(2.0 * eps * body.transverse, rel=1e-9, abs=0)


def test_T0_with_sigma_gives_the_nutation_angle():
    body = BODIES["prolate"]
    A, C, G0, th = body.transverse, body.axial, 1.2, 0.7
    T0 = 0.5 * G0**2 * (math.sin(th) ** 2 / A + math.cos(th) ** 2 / C)
    for sigma, want in ((1, th), (-1, math.pi - th)):
        sol = ep.simulate(body, [0.1, 0.1, 0.1], 0.2, G0, T0=T0, sigma=sigma, tau_span=(0.0, 0.01), tau_eval=[0.0])
        # T0 fixes cos^2(theta) to rounding; arccos amplifies it by 1/sin(0.7) < 2
        assert sol.theta[0] == pytest.approx(want, rel=0, abs=1e-12)
    # a batch over T0: a member whose energy no nutation angle gives is refused, naming T0
    b = ep.simulate(body, [0.1, 0.1, 0.1], 0.2, G0, T0=np.array([T0, 10.0]), sigma=-1, tau_span=(0.0, 0.01),
                    tau_eval=[0.0])
    assert b.status.tolist() == [0, -1] and "T0" in b.message[1]
    assert b.theta[0, 0] == pytest.approx(math.pi - th, rel=0, abs=1e-12)


def near_symmetric_gap(d: float) -> float:
    """The largest difference of g and of the attitude between the triaxial Body (A(1 + d/2), A(1 - d/2), C) and
    the SymmetricBody (A, C) started from the same physical state, over 2 units of the fast time."""
    A, C, eps = 2.0, 1.1, 0.2
    tri = ep.Body(A * (1 + d / 2), A * (1 - d / 2), C)
    # k2 of the triaxial 'min' motion at nutation angle ~0.6 is ~ d C tan^2(0.6)/(A - C): a generic physical state
    k2 = d * C * math.tan(0.6) ** 2 / (A - C)
    tau = np.linspace(0.0, 2.0 * eps**2, 5)
    torque = [0.5, 0.3, 0.4]  # drag and the gravity gradient of each body
    kw = dict(delta0=1.0, lam0=0.4, tau_span=(0.0, tau[-1]), tau_eval=tau, nu0=0.3, **TOL)
    a = ep.simulate(tri, torque, eps, 1.2, k2, kind="min", u0=0.3, psi0=0.8, **kw)
    g0, C0 = a.g[:, 0], attitudes(a.q[:, :1])[0]
    G0 = float(np.linalg.norm(g0))
    theta0, phi0 = math.atan2(math.hypot(g0[0], g0[1]), g0[2]), math.atan2(g0[0], g0[1])
    M = frame(1.0, 0.4).T @ C0 @ rot3(phi0).T @ rot1(theta0).T  # = R3(psi0)
    psi0 = math.atan2(M[1, 0], M[0, 0])
    _, C_start = start(G0, theta0, 1.0, 0.4, phi0, psi0)
    assert np.max(np.abs(C_start - C0)) < 1e-13  # the same physical start (to rounding)
    b = ep.simulate(ep.SymmetricBody(A, C), torque, eps, G0, theta0=theta0, phi0=phi0, psi0=psi0, **kw)
    assert a.status == 0 and b.status == 0
    return max(float(np.max(np.abs(a.g - b.g))), float(np.max(np.abs(attitudes(a.q) - attitudes(b.q)))))


def test_near_symmetric_bodies_converge_to_the_symmetric_run():
    # The two bodies' angular velocities differ by |1/A1 - 1/A| G <= (d/2)(1 + d) G/A for the same g (and their
    # gravity gradients by O(d)); over the fast time t = 2 the solutions drift apart by at most
    # (d/2)(G/A) t e^{L t} + O(d) torque terms (Gronwall, L = 2G/C the Lipschitz bound of g x omega in g):
    # 0.5 * 0.6 * 2 * e^{4.4} ~ 50 d. 100 d bounds it with margin; the integrators add ~1e-11 at rtol 1e-12.
    gaps = {d: near_symmetric_gap(d) for d in (1e-3, 1e-6, 1e-9)}
    for d, gap in gaps.items():
        assert gap < 100.0 * d + 1e-10, d
    # and the gap is linear in d (no offset that stays as d -> 0): its leading term is d times a fixed
    # function of the state, the next O(d^2), so gap/d agrees across the three d to O(1e-3) plus the
    # integrators' ~1e-11/1e-9 = 1e-2 at d = 1e-9; a factor 1.5 leaves a margin
    ratios = [gap / d for d, gap in gaps.items()]
    assert max(ratios) < 1.5 * min(ratios)


@pytest.mark.parametrize(("kw", "name"), [
    ({}, "theta0"),
    ({"theta0": -0.1}, "theta0"),
    ({"theta0": 3.2}, "theta0"),
    ({"theta0": float("nan")}, "theta0"),
    ({"theta0": 0.5, "k2_0": 0.3}, "k2_0"),
    ({"theta0": 0.5, "kind": "min"}, "kind"),
    ({"theta0": 0.5, "u0": 0.2}, "u0"),
    ({"theta0": 0.5, "T0": 0.5}, "theta0"),
    ({"theta0": 0.5, "formulation": "angles"}, "formulation"),
    ({"theta0": 0.5, "k2_max": 0.9}, "k2_max"),
    ({"theta0": 0.5, "sigma": -1}, "sigma"),
    ({"T0": 10.0}, "T0"),
])
def test_bad_start_of_a_symmetric_body_is_named(kw, name):
    body = BODIES["prolate"]
    args = dict(kw)
    k2_0 = args.pop("k2_0", None)
    with pytest.raises(ValueError, match=name):
        ep.simulate(body, [0.1, 0.1, 0.1], 0.1, 1.0, k2_0, tau_span=(0.0, 0.01), **args)


@pytest.mark.parametrize("name", ["theta0", "phi0"])
def test_a_triaxial_body_refuses_the_symmetric_start(name):
    with pytest.raises(ValueError, match=name):
        ep.simulate(ep.Body(3.2, 2.6, 1.67), [0.1, 0.1, 0.1], 0.1, k2_0=0.5, tau_span=(0.0, 0.01), **{name: 0.5})
