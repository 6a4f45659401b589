"""The separatrix k^2 = 1: its motion, the limits of the averaged rates there, and the capture probabilities.

Independent routes: Euler's equations integrated numerically; the closed-form Euler-Poinsot motion at
1 - k^2 = 1e-14; numerical averages over that motion at 1 - k^2 = 1e-6 and 1e-10 (``mc`` of the core);
the paper's (8) near k^2 = 1; quadrature of the energy rate in time; and ensembles of full runs.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp

from rigidbody import euler_poinsot as ep
from rigidbody.core import elliptic as ell

BODY = ep.Body(3.2, 2.6, 1.67)
A1, A2, A3 = BODY.A1, BODY.A2, BODY.A3
I_OFF = np.array([[0.919, 0.3, -0.2], [0.1, 5.228, 0.4], [0.25, -0.15, 1.666]])  # case 2 + off-diagonal


def constant(M0, drag=0.0):
    """A constant body-fixed torque M0 (plus an optional isotropic drag -drag*omega), as a plain function."""
    M0 = np.asarray(M0, dtype=float)

    def torque(omega, C, nu):
        return M0 - drag * omega

    return torque


def p_max_plus(M0):
    """P(('max', +1)) from ('min', +1) for a constant torque with M01 > 0 > M03, |a| < |b| (derived by hand).

    Along arc (s1, s3) the energy h = T - G^2/2A2 changes by Theta = s1 a' + s3 b' with a' prop. to
    c1 (1/A1 - 1/A2) M01 < 0 and b' prop. to c3 (1/A3 - 1/A2) M03 < 0. From ('min', 1) a crossing motion
    enters ('max', 1) across arc (1, 1) and stays there iff it does not come back across (1, -1); following
    the h-interval of one loop (length 2|b'|) gives P(('max', 1)) = |a'|/|b'| and P(('min', -1)) = 1 - |a'|/|b'|
    (the motions entering ('max', -1) leave it across (-1, -1)). With c1/c3 and the 1/A differences:
    |a'|/|b'| = sqrt(A3 (A1 - A2) / (A1 (A2 - A3))) M01 / |M03|.
    """
    return math.sqrt(A3 * (A1 - A2) / (A1 * (A2 - A3))) * M0[0] / abs(M0[2])


# ------------------------------------------------------------------------------------------------ the motion
@pytest.mark.parametrize("arc", ep.ARCS)
def test_arc_motion_solves_eulers_equations(arc):
    sep = ep.Separatrix(BODY, 1.3)
    lam = sep.rate
    t0, t1 = -3.0 / lam, 4.0 / lam
    sol = solve_ivp(lambda t, g: np.cross(g, g / BODY.A), (t0, t1), sep.g(t0, arc), rtol=1e-12, atol=1e-14,
                    method="DOP853")
    # DOP853 at rtol 1e-12 over a few units of 1/lambda: 1e-10 (the saddles amplify errors by e^{lambda t})
    np.testing.assert_allclose(sol.y[:, -1], sep.g(t1, arc), atol=1e-10)
    # G and the separatrix energy, and the direction of travel: +e2 -> -e2 when s1 s3 = 1
    g = sep.g(np.array([-40.0, 0.0, 40.0]) / lam, arc)
    assert np.linalg.norm(g, axis=0) == pytest.approx(1.3, abs=1e-14)
    assert 0.5 * (g**2 / BODY.A[:, None]).sum(0) == pytest.approx(1.3**2 / (2 * A2), abs=1e-14)
    s1, s3 = arc
    np.testing.assert_allclose(g[:, 0], [0, s1 * s3 * 1.3, 0], atol=1e-15)
    np.testing.assert_allclose(g[:, 2], [0, -s1 * s3 * 1.3, 0], atol=1e-15)
    assert np.sign(g[0, 1]) == s1 and np.sign(g[2, 1]) == s3


@pytest.mark.parametrize("kind", ep.KINDS)
@pytest.mark.parametrize("sigma", [1, -1])
def test_arcs_are_the_k_to_1_limit_of_the_euler_poinsot_motion(kind, sigma):
    mc = 1e-14
    m = ep.EulerPoinsot(BODY, 0.8, 1.0 - mc, kind, sigma, mc=mc)
    sep = ep.Separatrix(BODY, 0.8)
    t = np.linspace(-5.0, 5.0, 21) / m.rate  # |u| <= 5: sn = tanh + O(mc cosh^2 u) ~ 1e-10
    # the 'max' motion runs along (sigma, +1) around u = 0 and (sigma, -1) around u = 2K; 'min' along
    # (+1, sigma) and (-1, sigma)
    arcs = [(sigma, 1), (sigma, -1)] if kind == "max" else [(1, sigma), (-1, sigma)]
    for u0, arc in zip((0.0, 2.0 * m.K), arcs):
        np.testing.assert_allclose(m.g(t, u0), sep.g(t, arc), atol=1e-9)
    assert m.rate == pytest.approx(sep.rate, rel=1e-13, abs=0)


# ------------------------------------------------------------------------------------------ the limits
def ep_average_rates(body, torque, G, k2, mc, kind, sigma, delta, lam, nu):
    """Mean of (dG, dT, dn) over psi and one period of the closed-form motion (EulerPoinsot.average)."""
    m = ep.EulerPoinsot(body, G, k2, kind, sigma, mc=mc)
    n = np.array([math.sin(delta) * math.cos(lam), math.sin(delta) * math.sin(lam), math.cos(delta)])
    sd, cd, sl, cl = math.sin(delta), math.cos(delta), math.sin(lam), math.cos(lam)
    Y = np.array([[cd * cl, -sl, sd * cl], [cd * sl, cl, sd * sl], [-sd, 0.0, cd]])  # y1, y2, y3 in Ox
    nus = [nu] if nu is not None else np.arange(16) * 2 * math.pi / 16

    def f(alpha, omega):
        C = np.einsum("ij,...jk->...ik", Y, alpha)
        w = np.broadcast_to(omega, C.shape[:-1])
        out = 0.0
        for v in nus:
            L = torque(w, C, np.full(C.shape[:-2], v))
            Lo = np.einsum("...ij,...j->...i", C, L)
            dn = (Lo - np.multiply.outer(Lo @ n, n)) / G
            out = out + np.concatenate([((w * body.A * L).sum(-1) / G)[..., None], (w * L).sum(-1)[..., None], dn],
                                       -1)
        return out / len(nus)

    return m.average(f)


def drag_and_gravity(I):
    def torque(omega, C, nu):
        er = np.stack([np.cos(nu), np.sin(nu), np.zeros_like(nu)], -1)
        rho = np.einsum("...ji,...j->...i", C, er)
        return 3.0 * np.cross(rho, BODY.A * rho) - omega @ I.T

    return torque


CASES = {
    "drag+gravity": (I_OFF, drag_and_gravity(I_OFF), 0.2),
    "drag+gravity, orbit mean": (I_OFF, drag_and_gravity(I_OFF), None),
    "constant+drag": (constant([0.4, 0.2, -0.5], 0.3), constant([0.4, 0.2, -0.5], 0.3), 0.2),
}


@pytest.mark.parametrize("case", list(CASES))
@pytest.mark.parametrize("region", ep.REGIONS)
def test_averaged_rates_tend_to_their_value_at_the_saddles_with_a_1_over_K_term(case, region):
    arg, fn, nu = CASES[case]
    G, delta, lam = 1.3, 0.7, 0.3
    lim = ep.separatrix_limits(BODY, arg, G, delta, lam, nu)
    limit = np.concatenate([[lim.dG, lim.dT], lim.dn])
    for mc in (1e-6, 1e-10):
        avg = ep_average_rates(BODY, fn, G, 1.0 - mc, mc, *region, delta, lam, nu)
        near = lim.near(region, mc)
        two_term = np.concatenate([[near["dG"], near["dT"]], near["dn"]])
        # the limit alone is far off: the loop term is ~1/K = 1/ln(4/k'), 0.12 at mc = 1e-6, 0.08 at 1e-10
        assert np.abs(avg - limit).max() > 0.01
        # with the loop term, what remains is O(k'^2) = O(mc) (the orbit passes the saddles at distance
        # ~k'; first-order terms cancel between the two sides of a saddle), rates are O(5): bound 50 mc
        assert np.abs(avg - two_term).max() < 50 * mc, (mc, np.abs(avg - two_term).max())


def test_drag_limits_are_the_intermediate_axis_rotation_and_the_limit_of_8():
    I = np.diag([0.919, 5.228, 1.666])
    G = 1.3
    lim = ep.separatrix_limits(BODY, I, G, 0.7, 0.3, None)
    # rotation about the intermediate axis: omega = G e2 / A2, drag -I omega
    assert lim.dG == pytest.approx(-I[1, 1] * G / A2, rel=1e-13, abs=0)
    assert lim.dT == pytest.approx(-I[1, 1] * G**2 / A2**2, rel=1e-13, abs=0)
    # the direction of G turns about x3 at the orbit-averaged precession rate of (9) at k = 1: |dn| = sin(delta)
    # |dlambda/dtau|
    assert np.linalg.norm(lim.dn) == pytest.approx(
        math.sin(0.7) * abs(ep.precession_rate(BODY, G, 1.0, 0.7)), rel=1e-12, abs=0)
    # k^2: (8) as k -> 1 is -2(I33/A3 - I11/A1) E/K ('max'; labels exchanged for 'min'); E(1) = 1
    for region in ep.REGIONS:
        kind = region[0]
        k2 = 1.0 - 1e-13
        K = float(ell.K(mc=1.0 - k2))  # the complementary parameter dk2_dtau sees
        k8 = ep.dk2_dtau(BODY, I, k2, kind) * K
        # K dk2 -> slope with error O(mc K^2) from (8)'s k^2 - W = (E - mc K)/K
        assert lim.slope[region]["dk2"] == pytest.approx(k8, rel=1e-9, abs=0)


# -------------------------------------------------------------------------------------- capture
def test_drift_along_an_arc_equals_the_time_integral_of_the_energy_rate():
    M0 = np.array([0.4, 0.2, -0.5])
    fn = constant(M0, 0.3)
    sep = ep.Separatrix(BODY, 1.1)
    c = ep.separatrix_crossing(BODY, fn, 1.1, 0.7, 0.3, 0.0, ("min", 1))
    for arc in ep.ARCS:
        def hdot(t, arc=arc):
            g = sep.g(t, arc)
            w = g / BODY.A
            return float((w - g / A2) @ fn(w, None, None))
        ref = quad(hdot, -60 / sep.rate, 60 / sep.rate, limit=400, epsabs=1e-13)[0]
        assert c.drifts[arc] == pytest.approx(ref, abs=1e-10)
    assert c.quad_error < 1e-12


def test_capture_probabilities_of_a_constant_torque_follow_the_hand_calculation():
    M0 = [0.4, 0.0, -0.5]
    c = ep.separatrix_crossing(BODY, constant(M0), 1.0, 0.5, 0.0, 0.0, ("min", 1))
    p = p_max_plus(M0)
    assert 0.3 < p < 0.7  # a non-trivial split
    assert c.probabilities[("max", 1)] == pytest.approx(p, abs=1e-12)
    assert c.probabilities[("min", -1)] == pytest.approx(1 - p, abs=1e-12)
    assert c.probabilities[("max", -1)] == 0.0 and c.probabilities[("min", 1)] == 0.0
    # ('max', -1) attracts as well (its loop drift points to the separatrix): a motion continuing there would
    # stall; the bookkeeping sends it on across (-1, -1) into ('min', -1)
    assert c.loop_drifts[("max", -1)] > 0 and ("max", -1) not in c.capturing
    assert set(c.capturing) == {("max", 1), ("min", -1)}
    assert c.crosses and c.undetermined == 0.0 and c.most_probable() == ("min", -1)
    # the opposite torque about z1 mirrors the split
    c2 = ep.separatrix_crossing(BODY, constant([-0.4, 0.0, -0.5]), 1.0, 0.5, 0.0, 0.0, ("min", 1))
    assert c2.probabilities[("max", -1)] == pytest.approx(p, abs=1e-12)
    # a motion of a region whose loop drift points away does not reach the separatrix
    c3 = ep.separatrix_crossing(BODY, constant(M0), 1.0, 0.5, 0.0, 0.0, ("min", -1))
    assert not c3.crosses and sum(c3.probabilities.values()) == 0.0
    with pytest.raises(ValueError, match="do not cross"):
        c3.most_probable()


def test_capture_probabilities_do_not_depend_on_the_arc_the_bookkeeping_starts_from():
    from rigidbody.euler_poinsot._separatrix import _propagate

    rng = np.random.default_rng(5)
    for _ in range(200):
        d = dict(zip(ep.ARCS, rng.normal(size=4)))
        for src in ep.REGIONS:
            p0, u0, x0 = _propagate(d, src, first=0)
            p1, u1, x1 = _propagate(d, src, first=1)
            assert x0 == x1
            if x0:
                assert u0 == pytest.approx(0.0, abs=1e-12) and sum(p0.values()) == pytest.approx(1.0, abs=1e-12)
                for r in ep.REGIONS:
                    assert p0[r] == pytest.approx(p1[r], abs=1e-12)


def test_gravity_gradient_has_no_net_drift_along_any_arc():
    # psi-averaged, the gravity torque's energy rate (omega - g/A2).L is odd along each arc (like g1 g2 g3):
    # it moves no motion across the separatrix, at any true anomaly and direction of G
    gg = ep.GravityGradient(BODY)
    for nu, delta, lam in ((0.2, 0.7, 0.3), (1.9, 2.5, -1.0), (None, 1.2, 0.4)):
        c = ep.separatrix_crossing(BODY, gg, 1.1, delta, lam, nu, ("min", 1))
        assert max(abs(v) for v in c.drifts.values()) < 1e-13
        assert not c.crosses


def test_odd_torques_split_evenly():
    for src in (("min", 1), ("min", -1)):
        c = ep.separatrix_crossing(BODY, np.diag([0.919, 5.228, 1.666]), 1.0, 0.7, 0.3, 0.2, src)
        assert c.probabilities[("max", 1)] == pytest.approx(0.5, abs=1e-12)
        assert c.probabilities[("max", -1)] == pytest.approx(0.5, abs=1e-12)


def full_ensemble(M0, eps, n, seed, tau1=2.0):
    """Final regions of n full runs (Euler's equations; a body-fixed torque needs no attitude) from ('min', 1).

    Initial states: a cell of phase space, k^2 uniform in [0.5, 0.6] and the phase uniform over a period, so
    the crossing phases fill the loop uniformly (a single orbit of initial phases at one k^2 gives a
    deterministic, eps-dependent split instead).
    """
    rng = np.random.default_rng(seed)
    g0 = np.empty((3, n))
    for i in range(n):
        m = ep.EulerPoinsot(BODY, 1.0, rng.uniform(0.5, 0.6), "min", 1)
        g0[:, i] = m.g(rng.uniform(0.0, m.period))
    M0 = np.asarray(M0, float)[:, None]
    ie2 = 1.0 / eps**2

    def rhs(t, y):
        g = y.reshape(3, -1)
        w = g / BODY.A[:, None]
        return (np.cross(g, w, axis=0) * ie2 + M0).ravel()

    sol = solve_ivp(rhs, (0.0, tau1), g0.ravel(), method="DOP853", rtol=1e-9, atol=1e-11)
    g = sol.y[:, -1].reshape(3, -1)
    D = (g**2).sum(0) / (g**2 / BODY.A[:, None]).sum(0)
    assert np.abs(D - A2).min() > 0.1  # every run is far from the separatrix again
    kinds = np.where(D > A2, "max", "min")
    sig = np.where(D > A2, np.sign(g[0]), np.sign(g[2])).astype(int)
    return {r: int(np.sum((kinds == r[0]) & (sig == r[1]))) for r in ep.REGIONS}


def check_frequencies(M0, eps, n, seed):
    c = ep.separatrix_crossing(BODY, constant(M0), 1.0, 0.5, 0.0, 0.0, ("min", 1))
    counts = full_ensemble(M0, eps, n, seed)
    for r in ep.REGIONS:
        p = c.probabilities[r]
        if p == 0.0:
            assert counts[r] == 0, (r, counts)
            continue
        # binomial error bar; 4 sigma keeps the (fixed-seed) test from flaking; the theory's own error is
        # o(1) as eps -> 0 and measured below the binomial noise at these eps
        sd = math.sqrt(p * (1 - p) / n)
        assert abs(counts[r] / n - p) < 4 * sd, (r, counts[r] / n, p, sd)
    return counts


def test_branch_frequencies_of_full_runs_match_the_capture_probabilities():
    # 1000 runs at eps = 0.05 cost ~0.5 s (one vectorised integration); measured 0.460 vs p = 0.464
    check_frequencies([0.4, 0.0, -0.5], 0.05, 1000, seed=1)


@pytest.mark.slow
@pytest.mark.parametrize("ratio", [0.8, 1.5])
@pytest.mark.parametrize("eps", [0.03, 0.015])
def test_branch_frequencies_of_full_runs_match_the_capture_probabilities_slow(ratio, eps):
    check_frequencies([0.5 * ratio, 0.0, -0.5], eps, 4000, seed=2)


# ------------------------------------------------------------------------------------------ validation
def test_bad_input_is_refused_with_the_parameter_named():
    fn = constant([0.4, 0.0, -0.5])
    with pytest.raises(ValueError, match="source"):
        ep.separatrix_crossing(BODY, fn, 1.0, 0.5, 0.0, 0.0, ("mid", 1))
    with pytest.raises(ValueError, match="sigma"):
        ep.separatrix_crossing(BODY, fn, 1.0, 0.5, 0.0, 0.0, ("min", 0))
    with pytest.raises(ValueError, match="G must be positive"):
        ep.separatrix_crossing(BODY, fn, -1.0, 0.5, 0.0, 0.0, ("min", 1))
    with pytest.raises(ValueError, match="delta"):
        ep.separatrix_limits(BODY, fn, 1.0, 4.0, 0.0, 0.0)
    with pytest.raises(ValueError, match="n_x"):
        ep.separatrix_limits(BODY, fn, 1.0, 0.5, 0.0, 0.0, n_x=2)
    with pytest.raises(ValueError, match="shape"):  # (a constant (3,) broadcasts: a valid torque)
        ep.separatrix_limits(BODY, lambda w, C, nu: np.zeros((*np.shape(w)[:-1], 2)), 1.0, 0.5, 0.0, 0.0)
    with pytest.raises(ValueError, match="non-finite"):
        ep.separatrix_limits(BODY, lambda w, C, nu: w * np.nan, 1.0, 0.5, 0.0, 0.0)
    with pytest.raises(ValueError, match="arc"):
        ep.Separatrix(BODY, 1.0).g(0.0, (1, 2))
    with pytest.raises(TypeError, match="body"):
        ep.Separatrix("body", 1.0)
    with pytest.raises(ValueError, match="mc"):
        ep.separatrix_limits(BODY, fn, 1.0, 0.5, 0.0, 0.0).near(("max", 1), 0.0)


@pytest.mark.slow
def test_branch_frequencies_of_simulate_match_the_capture_probabilities():
    # the same check through the library's full equations (attitude and all: ep.simulate), 400 runs at
    # eps = 0.05 (~90 s): initial k2 in [0.5, 0.6], phase u0 and precession angle psi0 uniform
    M0 = [0.4, 0.0, -0.5]
    p = p_max_plus(M0)
    rng = np.random.default_rng(7)
    n, hits = 400, 0
    for _ in range(n):
        k2 = rng.uniform(0.5, 0.6)
        K = ep.EulerPoinsot(BODY, 1.0, k2, "min", 1).K
        s = ep.simulate(BODY, constant(M0), 0.05, kind="min", k2_0=k2, u0=rng.uniform(0, 4 * K),
                        psi0=rng.uniform(0, 2 * math.pi), tau_span=(0, 2.0), tau_eval=[2.0], min_spin_ratio=0,
                        k2_max=None)
        region = (str(s.kind[-1]), int(s.sigma[-1]))
        assert region in (("max", 1), ("min", -1)), region  # the two regions of positive probability only
        hits += region == ("max", 1)
    assert abs(hits / n - p) < 4 * math.sqrt(p * (1 - p) / n), (hits / n, p)
