"""The averaged evolution of a body with two equal moments (SymmetricBody): its rates are the limits of the
triaxial ones, near-symmetric runs converge to it, and it follows the full motion (an own integration of Euler's
equations with a quaternion) to second order in eps."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation

from rigidbody import euler_poinsot as ep
from rigidbody.euler_poinsot._symengine import choose_grid

G, TH, DELTA, LAM, NU = 1.0, 0.8, 1.0, 0.3, 0.7


def _n(delta: float, lam: float) -> np.ndarray:
    return np.array([math.sin(delta) * math.cos(lam), math.sin(delta) * math.sin(lam), math.cos(delta)])


def _torques(body, axes=(0, 1, 2)):
    """A torque symmetric about z3 (gravity gradient, axisymmetric drag) and one that is not (a drag tensor with
    unequal transverse entries, a magnet off the axis in a field along x1): the second needs the mean over phi.
    ``axes``: where the symmetric body's axes z1, z2, z3 are in ``body``'s (the same physical torque)."""
    P = np.eye(3)[:, list(axes)]  # columns: z1, z2, z3 in body's axes

    def drag(d):
        return ep.LinearDrag(P @ np.diag(d) @ P.T)

    sym = drag([0.1, 0.1, 0.3]) + ep.GravityGradient(body)
    asym = drag([0.1, 0.25, 0.3]) + ep.MagneticDipole(P @ np.array([0.3, -0.2, 0.5]), [1.0, 0.0, 0.0])
    return {"symmetric": sym, "asymmetric": asym}


def _symmetric_rates(body, torque, theta):
    r = ep.symmetric_rates(body, torque, G, theta, DELTA, LAM, NU, quad_tol=1e-13)
    # dT from the nutation equation (dc = -sin(theta) dtheta) and dG, by the chain rule of
    # 2T = G^2 ((1 - c^2)/A + c^2/C): the same energy rate as <omega . M> only if the dc equation is right
    A, C = body.transverse, body.axial
    c, dc = math.cos(theta), -math.sin(theta) * r["dtheta"]
    dT_c = G * r["dG"] * ((1 - c * c) / A + c * c / C) + G * G * c * dc * (1 / C - 1 / A)
    # two combinations of means on one grid (terms of order 1): equal to rounding, 1e-12 leaves a factor 1000
    assert dT_c == pytest.approx(r["dT"], rel=1e-12, abs=1e-13)
    return r["dG"], dT_c, r["ddelta"], r["dlam"]


@pytest.mark.parametrize("shape", ["prolate", "oblate"])
@pytest.mark.parametrize("which", ["symmetric", "asymmetric"])
def test_rates_are_the_limits_of_the_triaxial_ones(shape, which):
    """The triaxial averaged rates (the engine over the Euler-Poinsot motion) of bodies whose two moments differ by a
    relative d tend to the symmetric body's (the mean over the regular precession), linearly in d: the motion and
    the torque depend smoothly on the moments, so the difference is O(d) times the rates' size (below 1 here); the
    bound 5 d (plus the engines' 1e-11 quadrature and the rounding of k2 ~ d) leaves a margin of about 5 over the
    coefficient these cases show, and a rate wrong by a fraction of a percent fails it at d = 1e-6 and 1e-9."""
    A, C = (2.0, 1.0) if shape == "prolate" else (1.0, 1.6)
    sym = ep.SymmetricBody(A, C)
    dG0, dT0, ddelta0, dlam0 = _symmetric_rates(sym, _torques(sym)[which], TH)
    c = math.cos(TH)
    T = 0.5 * G * G * ((1 - c * c) / A + c * c / C)
    for d in (1e-3, 1e-6, 1e-9):
        # the triaxial body with the two equal moments split by d: A1 > A2 > A3 in the paper's labelling, and the
        # symmetry axis z3 of the symmetric body is the axis of A3 (prolate) or of A1 (oblate)
        if shape == "prolate":
            body, kind, axes = ep.Body(A * (1 + d), A, C), "min", (0, 1, 2)
        else:  # z1, z2, z3 of the symmetric body along the triaxial axes 2, 3, 1 (a proper rotation)
            body, kind, axes = ep.Body(C, A * (1 + d), A), "max", (1, 2, 0)
        tq = _torques(body, axes)[which]
        k2 = ep.k2_from(body, G, T, kind)
        r = ep.averaged_rates(body, tq, G, k2, DELTA, LAM, NU, kind=kind)
        bound = 5 * d + 1e-10
        assert r["dG"] == pytest.approx(dG0, rel=0, abs=bound)
        assert r["dT"] == pytest.approx(dT0, rel=0, abs=bound)
        assert r["ddelta"] == pytest.approx(ddelta0, rel=0, abs=bound)
        assert r["dlam"] == pytest.approx(dlam0, rel=0, abs=bound)


@pytest.mark.parametrize(("which", "averaging"), [("symmetric", "auto"), ("asymmetric", "numerical")])
def test_near_symmetric_runs_converge_at_bounded_cost(which, averaging):
    """An averaged run of a triaxial body with A1 = A2 (1 + d) tends to the symmetric body's run as d -> 0 (O(d):
    the rates differ by O(d), test above, over a span of 2), with a number of right-hand-side evaluations that does
    not grow as d falls (the triaxial k2 is O(d) but its equation stays regular); through the triaxial closed forms
    and through its averaging engine (a torque that needs the mean over the body azimuth)."""
    A, C, th0 = 2.0, 1.0, 0.8
    te = np.linspace(0.0, 2.0, 5)
    sym = ep.SymmetricBody(A, C)
    s = ep.averaged(sym, _torques(sym)[which], 0.0, theta0=th0, tau_span=(0, 2), tau_eval=te, rtol=1e-11)
    c = math.cos(th0)
    T0 = 0.5 * ((1 - c * c) / A + c * c / C)
    nfev = []
    for d in (1e-3, 1e-6, 1e-9):
        body = ep.Body(A * (1 + d), A, C)
        r = ep.averaged(body, _torques(body)[which], 0.0, T0=T0, tau_span=(0, 2), tau_eval=te, rtol=1e-11,
                        averaging=averaging)
        assert r.status == 0
        # O(d) with the rates' coefficient (< 1 per unit tau) times the span 2, and the tolerance 1e-11
        assert np.abs(r.G - s.G).max() <= 2 * d + 1e-9
        assert np.abs(r.T - s.T).max() <= 2 * d + 1e-9
        assert np.abs(r.n - s.n).max() <= 2 * d + 1e-9
        nfev.append(int(r.nfev))
    assert max(nfev) <= 2 * min(nfev)


def _full(body, torque_fn, eps, th0, delta0, lam0, nu0, tau1, n_out):
    """Euler's equations with a quaternion (scalar last), our own: dg/dt = g x omega + eps^2 M, in the fast time
    t = tau / eps^2, the true anomaly nu0 + eps t; the start is the symmetric body's regular precession with
    G = 1 at the nutation angle th0 (Euler angles ZXZ: psi = 0, theta = th0, phi = 0 from the frame of G)."""
    n0 = _n(delta0, lam0)
    Y = np.array([[math.cos(delta0) * math.cos(lam0), -math.sin(lam0), n0[0]],
                  [math.cos(delta0) * math.sin(lam0), math.cos(lam0), n0[1]], [-math.sin(delta0), 0.0, n0[2]]])
    R0 = Y @ Rotation.from_euler("ZXZ", [0.0, th0, 0.0]).as_matrix()
    A = body.A

    def rhs(t, y):
        g, q = y[:3], y[3:]
        x, yq, z, s = q / np.linalg.norm(q)
        w = g / A
        M = torque_fn(w, Rotation.from_quat([x, yq, z, s]).as_matrix(), nu0 + eps * t)
        dq = 0.5 * np.array([s * w[0] + yq * w[2] - z * w[1], s * w[1] + z * w[0] - x * w[2],
                             s * w[2] + x * w[1] - yq * w[0], -(x * w[0] + yq * w[1] + z * w[2])])
        return np.concatenate([np.cross(g, w) + eps**2 * M, dq])

    t_out = np.linspace(0.0, tau1 / eps**2, n_out)
    sol = solve_ivp(rhs, (0.0, t_out[-1]), np.concatenate([R0.T @ n0, Rotation.from_matrix(R0).as_quat()]),
                    method="DOP853", rtol=1e-11, atol=1e-13, t_eval=t_out)
    out = []
    for k in range(n_out):
        g, R = sol.y[:3, k], Rotation.from_quat(sol.y[3:, k]).as_matrix()
        Gk = np.linalg.norm(g)
        out.append((Gk, g[2] / Gk, R @ g / Gk))
    return out


@pytest.mark.parametrize("shape", ["prolate", "sphere"])
def test_averaged_follows_the_full_motion_to_second_order(shape):
    """The averaged run against our own integration of the full equations, compared after whole orbits (where the
    orbital oscillation of the osculating variables returns to its start): the difference is the near-identity
    transformation of first-order averaging, O(eps^2) there. Checked as such: at eps and eps/2 over the same
    number of orbits the difference must fall by at least 2.5 (4 for a clean eps^2; a rate wrong by a percent
    leaves a difference that does not fall), and at eps = 0.02 stay below 4 eps^2 = 1.6e-3 (the change of G over
    the span is about 0.1). Gravity gradient, drag and (for the sphere, whose direction of G in the body is a slow
    variable) a magnet off the body axes in a field that turns with the orbit."""
    body = ep.SymmetricBody(2.0, 1.0) if shape == "prolate" else ep.SymmetricBody(1.5, 1.5)
    Id = np.diag([0.3, 0.3, 0.8])
    m_b = np.array([0.4, -0.3, 0.2])

    def field(nu):
        nu = np.asarray(nu, dtype=float)[..., None]
        return np.concatenate([np.cos(nu), np.sin(nu), 0.5 + 0 * nu], axis=-1)

    def torque_fn(w, R, nu):
        rho = R.T @ np.array([math.cos(nu), math.sin(nu), 0.0])
        M = 3.0 * np.cross(rho, body.A * rho) - Id @ w
        if shape == "sphere":
            M = M + np.cross(m_b, R.T @ field(nu))
        return M

    tq = ep.LinearDrag(Id) + ep.GravityGradient(body)
    if shape == "sphere":
        tq = tq + ep.MagneticDipole(m_b, field)
    th0, d0, l0, nu0 = 0.8, 1.0, 0.3, 0.2
    diffs = []
    for eps in (0.02, 0.01):
        tau1 = 2 * 2 * math.pi * eps  # two orbits
        full = _full(body, torque_fn, eps, th0, d0, l0, nu0, tau1, 3)
        avg = ep.averaged(body, tq, eps, theta0=th0, delta0=d0, lam0=l0, nu0=nu0, tau_span=(0, tau1),
                          tau_eval=np.linspace(0, tau1, 3), rtol=1e-11)
        assert avg.status == 0
        d = max(max(abs(Gk - avg.G[k]), abs(ck - math.cos(avg.theta[k])), np.abs(nk - avg.n[:, k]).max())
                for k, (Gk, ck, nk) in enumerate(full))
        diffs.append(d)
    assert diffs[0] <= 4 * 0.02**2
    assert diffs[1] <= diffs[0] / 2.5


def test_sphere_keeps_the_direction_of_G_in_the_body_and_T():
    """For the sphere T = G^2/2A at every time, and a torque that is a function of omega alone (drag, isotropic:
    M = -k omega) only shrinks G: dG/dtau = -k G/A exactly, so G = exp(-k tau/A), and neither the direction of G
    in space nor in the body moves."""
    body = ep.SymmetricBody(1.5, 1.5)
    k = 0.4
    te = np.linspace(0.0, 2.0, 5)
    s = ep.averaged(body, ep.LinearDrag(k * np.eye(3)), 0.0, theta0=1.1, tau_span=(0, 2), tau_eval=te, rtol=1e-12)
    # rtol 1e-12 per step over tau = 2 (tens of steps): ~1e-11 in ln G, bound 1e-10
    np.testing.assert_allclose(s.G, np.exp(-k * te / 1.5), rtol=1e-10, atol=0)
    np.testing.assert_allclose(s.T, s.G**2 / 3.0, rtol=1e-14, atol=0)  # the sphere's energy: rounding only
    # M = -k omega is along G: the rates of both directions are zero up to the rounding of the means (1e-16 each)
    np.testing.assert_allclose(s.theta, 1.1, rtol=0, atol=1e-12)
    np.testing.assert_allclose(s.delta, math.pi / 4, rtol=0, atol=1e-12)


def test_batch_equals_single_runs():
    """A batch (arrays of theta0 and eps) gives each member its single run (same driver, same rules)."""
    body = ep.SymmetricBody(2.0, 1.0)
    tq = _torques(body)["asymmetric"]
    te = np.linspace(0.0, 0.5, 3)
    batch = ep.averaged(body, tq, [0.0, 0.02], theta0=[0.5, 2.0], tau_span=(0, 0.5), tau_eval=te)
    for i, (eps, th) in enumerate([(0.0, 0.5), (0.02, 2.0)]):
        one = ep.averaged(body, tq, eps, theta0=th, tau_span=(0, 0.5), tau_eval=te)
        # each member runs alone on the scalar integrator, as its single call: the same arithmetic up to the
        # evaluation order of the output interpolation; 1e-12 (not bitwise: the house bans two-route equality)
        np.testing.assert_allclose(batch.G[i], one.G, rtol=1e-12, atol=0)
        np.testing.assert_allclose(batch.theta[i], one.theta, rtol=0, atol=1e-12)


def test_slow_proper_rotation_stops_a_torque_that_needs_it():
    """Near the spin about a transverse axis (c -> 0) the proper rotation G c (1/A - 1/C) stops: a torque whose mean
    depends on the body azimuth (an off-axis magnet) can no longer be averaged over it, and the run ends with the
    'slow_rotation' stop and its message; a torque symmetric about the axis (gravity gradient, axisymmetric drag) is
    not stopped by it (its mean needs no proper rotation)."""
    body = ep.SymmetricBody(2.0, 1.0)
    # energy dissipation at constant |G|: c -> 0 (the flat spin of a prolate body)
    damp = ep.FunctionTorque(lambda w, C, nu: -2.0 * (w - (w * (w * body.A)).sum(-1, keepdims=True)
                                                      * (w * body.A) / ((w * body.A) ** 2).sum(-1, keepdims=True)))
    s = ep.averaged(body, damp + ep.MagneticDipole([0.3, 0.0, 0.0], [0.0, 0.0, 0.1]), 0.01, theta0=0.5,
                    tau_span=(0, 5), min_spin_ratio=5.0)
    assert s.status == 1 and s.event == "slow_rotation" and "min_spin_ratio" in s.message
    s2 = ep.averaged(body, damp + ep.GravityGradient(body), 0.01, theta0=0.5, tau_span=(0, 0.5), min_spin_ratio=5.0)
    assert s2.status == 0


@pytest.mark.parametrize(("kwargs", "match"), [
    ({"k2_0": 0.5, "theta0": 0.3}, "k2 = 0"),
    ({}, "theta0"),
    ({"theta0": 0.3, "T0": 0.3}, "one of them"),
    ({"theta0": 4.0}, "theta0"),
    ({"theta0": 0.3, "k2_max": None}, "k2_max"),
    ({"T0": 5.0}, "T0"),
])
def test_bad_input_is_refused_by_name(kwargs, match):
    with pytest.raises(ValueError, match=match):
        ep.averaged(ep.SymmetricBody(2.0, 1.0), ep.GravityGradient(ep.SymmetricBody(2.0, 1.0)), 0.0, **kwargs)


def test_theta0_for_a_triaxial_body_is_refused():
    with pytest.raises(ValueError, match="theta0"):
        ep.averaged(ep.Body(3.2, 2.6, 1.67), np.eye(3), 0.0, theta0=0.3)


def test_the_standard_plot_shows_the_nutation_angle():
    """sol.plot() of a symmetric body's run draws theta where a triaxial run has k2 (identically 0 here)."""
    import matplotlib

    matplotlib.use("Agg")
    body = ep.SymmetricBody(2.0, 1.0)
    s = ep.averaged(body, ep.LinearDrag([0.1, 0.1, 0.3]), 0.0, theta0=1.0, tau_span=(0, 3), tau_eval=[0, 1, 2, 3])
    axes = s.plot()
    assert axes[2].get_ylabel() == "$\\theta$"
    assert np.array_equal(axes[2].lines[0].get_ydata(), s.theta)


def test_a_torque_that_turns_bad_part_way_ends_its_run_with_a_status():
    """A torque that returns NaN once G has fallen to 0.9 (here: after a drag of 0.3 has acted for about half a unit
    of tau) ends the run there with status -1 and a message naming the torque and the time, G at 0.9 to the
    integrator's step control; in a batch the member whose torque stays finite is not touched."""
    body = ep.SymmetricBody(2.0, 1.0)

    def turns_bad(w, C, nu):
        G = np.linalg.norm(w * body.A, axis=-1, keepdims=True)
        return np.where(G < 0.9, np.nan, -0.3 * w)

    s = ep.averaged(body, turns_bad, 0.0, theta0=1.0, tau_span=(0, 3))
    assert s.status == -1 and "turns_bad" in s.message and "at tau = " in s.message
    # the failing steps shrink onto the turn (the last step measured 2e-15 in tau; dG/dtau ~ 0.2): 1e-6 is generous
    # yet far below the 0.1 a stop at the wrong place (the start, the end) would be off
    assert s.G[-1] == pytest.approx(0.9, rel=0, abs=1e-6)
    b = ep.averaged(body, turns_bad, 0.0, G0=[1.0, 10.0], theta0=1.0, tau_span=(0, 0.3), tau_eval=[0.0, 0.3])
    assert list(b.status) == [0, 0]  # neither reaches G = 0.9 within tau = 0.3 (G(0.3) is 0.94 and 9.4)
    b = ep.averaged(body, turns_bad, 0.0, G0=[1.0, 10.0], theta0=1.0, tau_span=(0, 3), tau_eval=[0.0, 3.0])
    assert b.status[0] == -1 and b.status[1] == 0


@pytest.mark.parametrize("shape", ["prolate", "oblate", "sphere"])
@pytest.mark.parametrize("nu", [0.4, None])
def test_eddy_current_mean_over_the_regular_precession_is_its_closed_form(shape, nu):
    """The eddy-current torque M = (P (omega x b)) x b averaged over the regular precession (the engine: psi, phi
    and, for nu=None, the orbit) against the closed form of docs/euler_poinsot.md, "Eddy currents":
    <C M> = -cbar (tr S - S) n, cbar = <tr P gamma.omega - gamma.P omega>/2, gamma = g/G; on the regular precession
    gamma.omega = G (s^2/A + c^2/C) and <gamma.P omega> = G (s^2 (P1 + P2)/2A + P3 c^2/C) (the mean of sin^2 phi and
    cos^2 phi is 1/2), S = B B^T at nu or its time mean over the orbit (our own trapezoid mean in the true anomaly
    with Kepler's weights on 4096 nodes, exact to rounding for the dipole's trigonometric polynomial). The engine's
    quadrature is exact for this trigonometric polynomial, so both agree to rounding: 1e-12 relative."""
    A, C = {"prolate": (2.0, 1.0), "oblate": (1.0, 1.6), "sphere": (1.5, 1.5)}[shape]
    body = ep.SymmetricBody(A, C)
    P = np.array([0.3, 0.5, 0.2])
    orbit = ep.Orbit(0.1)
    field = ep.DipoleField(1.1, 0.4, 7.5e6, orbit=orbit, scale=1e5)  # a field of order 1 (units of 10 uT)
    tq = ep.EddyCurrent(P, field)
    th = 0.7
    c, s = math.cos(th), math.sin(th)
    gb, n = np.array([0.0, s, c]), _n(DELTA, LAM)
    _, m = choose_grid(tq, body, G, gb, n, nu, orbit, 1e-13)
    if nu is None:
        x = np.arange(4096) * 2 * math.pi / 4096
        w = (1 + orbit.e * np.cos(x)) ** -2.0
        B = field(x)
        S = np.einsum("k,ki,kj->ij", w / w.sum(), B, B)
    else:
        b = field(nu)
        S = np.outer(b, b)
    if shape == "sphere":  # no proper rotation: gamma.P omega at the body azimuth phi = 0 of gb (g in the z2-z3 plane)
        gPw = G * (P[1] * s * s / A + P[2] * c * c / C)
    else:
        gPw = G * (s * s * (P[0] + P[1]) / (2 * A) + P[2] * c * c / C)
    cbar = 0.5 * (P.sum() * G * (s * s / A + c * c / C) - gPw)
    L = -cbar * (np.trace(S) * np.eye(3) - S) @ n
    np.testing.assert_allclose(m.L, L, rtol=0, atol=1e-12 * np.abs(L).max())


def test_symmetric_rates_refuse_bad_input_by_name():
    body = ep.SymmetricBody(2.0, 1.0)
    with pytest.raises(TypeError, match="SymmetricBody"):
        ep.symmetric_rates(ep.Body(3.2, 2.6, 1.67), np.eye(3), 1.0, 0.5, 0.5, 0.0, None)
    for args, match in [((0.0, 0.5, 0.5), "G must be positive"), ((1.0, 4.0, 0.5), "theta"),
                        ((1.0, 0.5, -0.1), "delta")]:
        with pytest.raises(ValueError, match=match):
            ep.symmetric_rates(body, np.eye(3), *args, 0.0, None)


def test_fast_drift_stops_a_run_whose_torque_outgrows_the_fast_motion():
    """At eps = 0.05 a drag that spins the body down makes the slow variables change faster and faster against the
    precession period 2 pi A/G (the drift per period is eps^2 (2 pi A/G)(|dG|/G + |dT|/T + |dn|): it first falls
    as theta grows, then grows as G falls):
    the run ends with the 'fast_drift' stop and its message where that measure reaches drift_tol (twice its start
    value here), before the slow-rotation stop (switched off); with drift_tol=None it goes on to the end. A start
    already past drift_tol is refused, naming the option."""
    body = ep.SymmetricBody(2.0, 1.0)
    drag = ep.LinearDrag([0.2, 0.2, 0.6])

    def drift(s, k):  # the measure at output k of a run, from the result's state and the public rates
        G, T, delta = float(s.G[k]), float(s.T[k]), float(s.delta[k])
        r = ep.symmetric_rates(body, drag, G, float(s.theta[k]), delta, float(s.lam[k]), None)
        dn = math.hypot(r["ddelta"], math.sin(delta) * r["dlam"])
        return 0.05**2 * (2 * math.pi * 2.0 / G) * (abs(r["dG"]) / G + abs(r["dT"]) / T + dn)

    free = ep.averaged(body, drag, 0.05, theta0=1.0, tau_span=(0, 30), drift_tol=None, min_spin_ratio=0.0)
    assert free.status == 0
    tol = 2 * drift(free, 0)
    s = ep.averaged(body, drag, 0.05, theta0=1.0, tau_span=(0, 30), drift_tol=tol, min_spin_ratio=0.0)
    assert s.status == 1 and s.event == "fast_drift" and "drift_tol" in s.message
    assert drift(s, -1) == pytest.approx(tol, rel=1e-6, abs=0)  # the event's root, to its location tolerance
    with pytest.raises(ValueError, match="drift_tol"):
        ep.averaged(body, drag, 0.05, theta0=1.0, tau_span=(0, 10), drift_tol=tol / 4)


@pytest.mark.parametrize("nu", [0.3, None])
def test_which_torques_need_the_proper_rotation(nu):
    """A torque symmetric about the symmetry axis (axisymmetric drag and eddy tensor, the gravity gradient, a magnet
    along the axis) has means over psi that do not depend on the body azimuth phi: the averaging needs no proper
    rotation. One that is not (unequal transverse drag, an off-axis magnet) does. (The body components of M across
    the axis turn with phi even for the first kind; they do not enter the rates.)"""
    from rigidbody.euler_poinsot._symengine import phase_invariant

    body = ep.SymmetricBody(2.0, 1.0)
    n, gb = _n(DELTA, LAM), np.array([0.0, math.sin(1.0), math.cos(1.0)])
    field = ep.DipoleField(1.0, 0.0, 7e6, scale=1e5)
    cases = {ep.LinearDrag([0.2, 0.2, 0.6]): True, ep.GravityGradient(body): True,
             ep.MagneticDipole([0.0, 0.0, 0.3], field): True, ep.EddyCurrent([0.2, 0.2, 0.5], field): True,
             ep.LinearDrag([0.2, 0.3, 0.6]): False, ep.MagneticDipole([0.3, 0.0, 0.0], field): False}
    for tq, invariant in cases.items():
        grid, _ = choose_grid(tq, body, 1.0, gb, n, nu, ep.Orbit(), 1e-12)
        assert phase_invariant(tq, body, grid, 1.0, n, nu, ep.Orbit()) is invariant, tq


def test_symmetric_rates_at_a_pole_are_the_limit_along_the_meridian():
    """At the pole delta = 0 the gravity gradient's mean torque vanishes, and dlam is its limit along the meridian
    lam (one rule with the triaxial averaged_rates): it equals the rate just off the pole (delta = 1e-4) to O(delta^2)
    = 1e-8 relative, bound 1e-6."""
    body = ep.SymmetricBody(2.0, 1.0)
    gg = ep.GravityGradient(body)
    at, near = (ep.symmetric_rates(body, gg, 1.0, 0.8, d, 0.3, None) for d in (0.0, 1e-4))
    assert math.isfinite(at["dlam"]) and at["dlam"] != 0.0
    assert at["dlam"] == pytest.approx(near["dlam"], rel=1e-6, abs=0)
