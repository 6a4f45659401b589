"""Full equations (1), (3), (4) vs the body-frame formulation, and averaged vs full for decreasing eps."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from rigidbody import euler_poinsot as ep

BODY = ep.Body(3.2, 2.6, 1.67)
I_OFF = np.array([[2.322, 0.3, -0.2], [0.1, 1.31, 0.4], [0.25, -0.15, 1.425]])
CASE1 = np.diag([2.322, 1.31, 1.425])
CASE2 = np.diag([0.919, 5.228, 1.666])
FIELDS = ("G", "T", "k2", "delta", "lam")


@pytest.mark.parametrize("orbit", [None, ep.Orbit(0.3)])
def test_paper_equations_1_3_4_agree_with_body_frame_formulation(orbit):
    # two independent codings of the same motion: Euler angles relative to Oy with the projections (3)
    # and the energy equation (4), vs Euler's equations + quaternion with vector torques
    te = np.linspace(0, 0.3, 7)
    kw = dict(tau_span=(0, 0.3), tau_eval=te, k2_0=0.8, delta0=1.0, lam0=-0.4, nu0=0.7, orbit=orbit,
              u0=0.9, psi0=0.3)
    b = ep.simulate(BODY, I_OFF, 0.04, **kw)
    a = ep.simulate(BODY, I_OFF, 0.04, formulation="angles", **kw)
    assert a.status == 0 and b.status == 0
    for f in FIELDS:
        # both at rtol 1e-10 over ~ 200 time units of t~: global errors ~1e-8
        assert getattr(a, f) == pytest.approx(getattr(b, f), abs=1e-7), f
    # (4) integrated for T equals T recomputed from G, theta, phi (kinetic energy of the body)
    th, ph, G = a.theta, a.phi, a.G
    T_geom = 0.5 * G**2 * (np.sin(th) ** 2 * (np.sin(ph) ** 2 / BODY.A1 + np.cos(ph) ** 2 / BODY.A2)
                           + np.cos(th) ** 2 / BODY.A3)
    assert a.T == pytest.approx(T_geom, abs=1e-8)


def _errors(eps, I, tau1, k2_0=0.9):
    te = np.linspace(0, tau1, 11)
    s = ep.simulate(BODY, I, eps, tau_span=(0, tau1), tau_eval=te, k2_0=k2_0)
    a = ep.averaged(BODY, I, eps, tau_span=(0, tau1), tau_eval=te, k2_0=k2_0)
    assert s.status == 0 and a.status == 0
    return {f: np.abs(getattr(s, f) - getattr(a, f)).max() for f in FIELDS}


def _order(epss, errs):
    return np.polyfit(np.log(epss), np.log(errs), 1)[0]


def test_averaged_vs_full_error_shrinks_like_eps_squared():
    # Averaging over the fast rotation (rate ~1 in t~) of O(eps^2) torques over t~ ~ 1/eps^2: first-order
    # averaging predicts O(eps^2) errors for the slow variables against (9) with nu kept explicit.
    # Light version (eps = 0.04 .. 0.01, ~1 s); the slow version goes to eps = 0.0025.
    epss = np.array([0.04, 0.02, 0.01])
    errs = [_errors(e, I_OFF, 0.5) for e in epss]
    for f in FIELDS:
        order = _order(epss, [e[f] for e in errs])
        # measured orders: G 2.1, T 2.1, k2 2.7, delta 2.8, lambda 1.9 (noisy: passage through resonances)
        assert order > 1.6, (f, order)
    # and the absolute error at eps = 0.01 is O(eps^2) with an O(1) constant (k2 is the most sensitive)
    assert max(errs[-1].values()) < 20 * 0.01**2


@pytest.mark.slow
def test_averaged_vs_full_convergence_order_small_eps():
    # case 1 from k2 = 0.9 over tau in [0, 1]: k2 stays in (0.85, 0.9), no low-order resonance is crossed
    epss = np.array([0.02, 0.01, 0.005, 0.0025])
    errs = [_errors(e, CASE1, 1.0) for e in epss]
    for f in FIELDS:
        order = _order(epss, [e[f] for e in errs])
        assert order > 1.7, (f, order)  # measured 1.8 - 2.1


@pytest.mark.slow
def test_resonance_passage_gives_first_order_jumps():
    # case 2 from k2 = 0.9: k2 falls through 0.509 near tau = 0.47, where the mean precession rate is
    # three times the Euler-Poinsot frequency (rho = <dpsi/dt> P / 2 pi = 3). Passage through a resonance
    # is not covered by the averaging over (psi, t): delta and lambda jump by O(eps) (not O(eps^2)), while
    # G, T, k2 keep their O(eps^2) accuracy.
    m = ep.EulerPoinsot(BODY, 1.0, 0.509)
    assert m.psi_rate_mean() * m.period / (2 * math.pi) == pytest.approx(3.0, abs=0.01)
    epss = np.array([0.01, 0.005, 0.0025])
    errs = [_errors(e, CASE2, 1.0) for e in epss]
    for f in ("G", "T", "k2"):
        assert _order(epss, [e[f] for e in errs]) > 1.7, f
    for e, er in zip(epss, errs):
        jump = max(er["delta"], er["lam"]) / e
        assert 0.05 < jump < 2.0, (e, jump)  # measured 0.3 - 0.6: first order in eps


def test_full_vs_orbit_averaged_limit_is_first_order_in_eps():
    # The limit eps -> 0 also averages over nu: the oscillation of delta, lambda at the orbital frequency
    # has amplitude O(eps), so the full motion approaches the limit only like eps.
    te = np.linspace(0, 0.5, 11)
    lim = ep.averaged(BODY, I_OFF, 0.0, tau_span=(0, 0.5), tau_eval=te, k2_0=0.9)
    epss = np.array([0.04, 0.02, 0.01])
    errs = []
    for e in epss:
        s = ep.simulate(BODY, I_OFF, e, tau_span=(0, 0.5), tau_eval=te, k2_0=0.9)
        errs.append(max(np.abs(s.delta - lim.delta).max(), np.abs(s.lam - lim.lam).max()))
    order = _order(epss, errs)
    assert 0.7 < order < 1.5  # measured 1.1


def test_too_large_eps_leaves_the_theory():
    # eps = 0.1 at the paper's start k2 = 0.99: the Euler-Poinsot period (long near the separatrix) is longer
    # than the orbit: refused by default ...
    with pytest.raises(ValueError, match="not fast"):
        ep.simulate(BODY, CASE1, 0.1)
    with pytest.raises(ValueError, match="not fast"):
        ep.averaged(BODY, CASE1, 0.1)
    # ... and when forced, the full motion crosses the separatrix within the first slow-time unit, where the
    # averaged k2 stays below 0.99: the averaged answer is meaningless there
    s = ep.simulate(BODY, CASE1, 0.1, min_spin_ratio=0.0, tau_span=(0, 1))
    assert s.status == 1 and s.event == "separatrix" and s.tau[-1] < 1
    # asked to go on (k2_max=None), the full motion passes into the other kind there
    c = ep.simulate(BODY, CASE1, 0.1, min_spin_ratio=0.0, tau_span=(0, 1), k2_max=None)
    crossings = c.t_events["separatrix"]
    assert c.status == 0 and crossings.size and "min" in set(c.kind)
    assert crossings[0] == pytest.approx(s.tau[-1], abs=1e-3)  # k2 = 1 - 1e-6 is reached just before k2 = 1
    a = ep.averaged(BODY, CASE1, 0.1, min_spin_ratio=0.0, tau_span=(0, 1))
    assert a.k2.max() <= 0.99
    # a moderate eps passes the start check but the decaying rotation becomes slow: the run stops with status
    a = ep.averaged(BODY, CASE1, 0.03, tau_span=(0, 6))
    assert a.status == 1 and a.event == "slow_rotation" and "no longer fast" in a.message
    assert ep.spin_ratio(BODY, 0.03, a.G[-1], a.k2[-1]) == pytest.approx(1.0, abs=1e-6)


def _limit_by_quadrature(I, k2_0, k2, delta0):
    """(tau, G, lambda - lambda0) at k2 by quadratures in k2 (G0 = 1)."""
    q = dict(epsabs=1e-13, epsrel=1e-12, limit=200)

    def F(x):
        return ep.dk2_dtau(BODY, I, x)

    def lnG(x):
        return quad(lambda y: ep.drag_rates(BODY, I, 1.0, y)[0] / F(y), k2_0, x, **q)[0]

    def dlam(x):
        return ep.precession_rate(BODY, math.exp(lnG(x)), x, delta0) / F(x)

    tau = quad(lambda x: 1 / F(x), k2_0, k2, **q)[0]
    return tau, math.exp(lnG(k2)), quad(dlam, k2_0, k2, **q)[0]


@pytest.mark.parametrize("I", [CASE1, CASE2])
def test_orbit_averaged_limit_against_its_closed_form(I):
    # eps = 0: delta = delta0, and (G, k2, lambda) are quadratures in k2 (the k2 equation is autonomous):
    #   tau(k2) = int dk2 / F,  ln G = int (dG/G)/F dk2,  lambda = lambda0 + int (3/4) N* cos(delta0)/G / F dk2
    k2_0, d0, l0 = 0.99, math.pi / 4, math.pi / 4
    sol = ep.averaged(BODY, I, 0.0, tau_span=(0, 0.4), tau_eval=[0.1, 0.2, 0.4], k2_0=k2_0)
    assert np.all(sol.delta == pytest.approx(d0, abs=1e-12))
    for tau, k2, G, lam in zip(sol.tau, sol.k2, sol.G, sol.lam):
        tq, Gq, dl = _limit_by_quadrature(I, k2_0, k2, d0)
        # quadrature at 1e-12 vs integrator rtol 1e-10 (global error ~1e-9)
        assert tq == pytest.approx(tau, rel=1e-8, abs=0)
        assert G == pytest.approx(Gq, rel=1e-8, abs=0)
        assert lam == pytest.approx(l0 + dl, abs=1e-7)


def test_eps_to_zero_of_the_averaged_system_converges_to_the_limit():
    te = np.linspace(0, 1, 11)
    lim = ep.averaged(BODY, CASE2, 0.0, tau_span=(0, 1), tau_eval=te)
    errs = []
    epss = np.array([0.02, 0.01, 0.005])
    for e in epss:
        a = ep.averaged(BODY, CASE2, e, tau_span=(0, 1), tau_eval=te)
        assert a.G == pytest.approx(lim.G, rel=1e-9, abs=0)  # G, k2 do not feel nu at all
        errs.append(np.abs(a.delta - lim.delta).max() + np.abs(a.lam - lim.lam).max())
    assert 0.8 < _order(epss, errs) < 1.3  # O(eps) oscillation at the orbital frequency


def test_eccentric_orbit_limit_uses_the_mean_factor():
    orb = ep.Orbit(0.4)
    te = np.linspace(0, 0.5, 6)
    lim = ep.averaged(BODY, CASE1, 0.0, tau_span=(0, 0.5), tau_eval=te, orbit=orb)
    circ = ep.averaged(BODY, CASE1, 0.0, tau_span=(0, 0.5), tau_eval=te)
    # (lambda - lambda0) scales with (1 - e^2)^(-3/2)
    assert lim.lam - lim.lam[0] == pytest.approx((circ.lam - circ.lam[0]) * (1 - 0.16) ** -1.5, rel=1e-8, abs=0)
    a = ep.averaged(BODY, CASE1, 0.005, tau_span=(0, 0.5), tau_eval=te, orbit=orb)
    assert np.abs(a.lam - lim.lam).max() < 0.02  # O(eps) with the eccentric Kepler law


def test_sin_delta_zero_is_regular():
    # G along the orbit normal: the vector form keeps it there (gravity torque vanishes, drag only shrinks G)
    a = ep.averaged(BODY, CASE1, 0.01, delta0=0.0, tau_span=(0, 0.5))
    assert a.status == 0 and np.all(np.isfinite(a.lam))
    assert a.delta.max() < 1e-12
    # passing near the pole: delta0 tiny, the integration goes through
    b = ep.averaged(BODY, CASE1, 0.0, delta0=1e-9, tau_span=(0, 0.5))
    assert b.status == 0
    s = ep.simulate(BODY, CASE1, 0.04, delta0=0.0, k2_0=0.9, tau_span=(0, 0.1))
    # O(eps^2) wobble of G's direction (same constant as the averaged-vs-full bound: 20 eps^2)
    assert s.status == 0 and s.delta.max() < 20 * 0.04**2
    with pytest.raises(ValueError, match="formulation='body'"):
        ep.simulate(BODY, CASE1, 0.04, delta0=0.0, k2_0=0.9, formulation="angles")


def test_lambda_is_unwrapped_and_tau_eval_respected():
    te = np.linspace(0, 3, 301)
    a = ep.averaged(BODY, CASE2, 0.0, tau_span=(0, 3), tau_eval=te)
    assert a.tau == pytest.approx(te)
    assert a.lam[-1] < -9  # several turns, continuous
    assert np.all(np.diff(a.lam) < 0) and np.abs(np.diff(a.lam)).max() < 0.2
    assert a.lam[0] == pytest.approx(math.pi / 4, abs=1e-15)


def test_bad_arguments():
    with pytest.raises(ValueError, match="eps"):
        ep.averaged(BODY, CASE1, -0.1)
    with pytest.raises(ValueError, match="eps must be positive"):
        ep.simulate(BODY, CASE1, 0.0)
    with pytest.raises(ValueError, match="k2_0"):
        ep.averaged(BODY, CASE1, 0.0, k2_0=1.0)
    with pytest.raises(ValueError, match="G0"):
        ep.averaged(BODY, CASE1, 0.0, G0=-1.0)
    with pytest.raises(TypeError, match="Body"):
        ep.averaged((3.2, 2.6, 1.67), CASE1, 0.0)
    with pytest.raises(ValueError, match="formulation"):
        ep.simulate(BODY, CASE1, 0.01, formulation="euler")


def test_rotation_about_the_smallest_axis_averaged_vs_full():
    # kind='min' (not in the paper): labels 1 and 3 exchanged in every averaged formula; the full motion
    # agrees to O(eps^2) (errors at eps = 0.02 / 0.01: ~2e-3 / ~6e-4, ratio ~4)
    I = np.diag([1.0, 2.0, 3.0])
    te = np.linspace(0, 0.3, 7)
    errs = []
    for eps in (0.02, 0.01):
        s = ep.simulate(BODY, I, eps, k2_0=0.5, kind="min", tau_span=(0, 0.3), tau_eval=te)
        a = ep.averaged(BODY, I, eps, k2_0=0.5, kind="min", tau_span=(0, 0.3), tau_eval=te)
        assert s.status == 0 and a.status == 0
        assert s.k2[0] == pytest.approx(0.5, abs=1e-12)
        errs.append(max(np.abs(getattr(s, f) - getattr(a, f)).max() for f in FIELDS))
    assert errs[1] < 20 * 0.01**2 and errs[0] / errs[1] > 2.5


def test_eccentric_orbit_averaged_vs_full():
    # Kepler's law and the factor of (3) in both systems: O(eps^2) agreement (measured 6.8e-3 -> 9.9e-4)
    orb = ep.Orbit(0.3)
    te = np.linspace(0, 0.3, 7)
    errs = []
    for eps in (0.02, 0.01):
        kw = dict(k2_0=0.9, tau_span=(0, 0.3), tau_eval=te, orbit=orb, nu0=0.5)
        s = ep.simulate(BODY, CASE1, eps, **kw)
        a = ep.averaged(BODY, CASE1, eps, **kw)
        errs.append(max(np.abs(getattr(s, f) - getattr(a, f)).max() for f in FIELDS))
    assert errs[1] < 20 * 0.01**2 and errs[0] / errs[1] > 2.5


def test_averaged_vs_full_with_a_nonzero_initial_true_anomaly():
    # nu0 != 0 on the circular orbit (the other comparisons start at nu0 = 0): the orbital-frequency wobble
    # of delta, lambda (amplitude ~ (3/4) eps |N*| / G) must be in phase in both systems, leaving the O(eps^2)
    # averaging error (same constant as above, 20 eps^2; a phase error of the full system would give O(eps))
    eps = 0.02
    te = np.linspace(0, 0.2, 9)
    kw = dict(k2_0=0.6, delta0=1.0, lam0=0.3, nu0=1.1, tau_span=(0, 0.2), tau_eval=te)
    s = ep.simulate(BODY, CASE1, eps, **kw)
    a = ep.averaged(BODY, CASE1, eps, **kw)
    assert s.status == 0 and a.status == 0
    for f in FIELDS:
        assert np.abs(getattr(s, f) - getattr(a, f)).max() < 20 * eps**2, f


def dissipation(kappa):
    """A torque that removes kinetic energy at constant |G| (as internal energy dissipation does, on average).

    M = -kappa (omega - (omega . g) g / G^2) is perpendicular to g: dG = 0 exactly, dT = -kappa |omega_perp|^2.
    """
    A = BODY.A

    def torque(omega, C, nu):
        g = omega * A
        return -kappa * (omega - (omega * g).sum(-1, keepdims=True) * g / (g * g).sum(-1, keepdims=True))

    return torque


def test_full_motion_goes_through_the_separatrix():
    # a minor-axis spin ('min', k2 = 0.2) loses energy at constant G, crosses G^2 = 2 T A2 near tau = 1.55 and
    # ends as a major-axis spin: asked to (k2_max=None), the run goes on through the crossing, the osculating kind
    # switches, and the two independent codings of the full equations agree through it
    te = np.linspace(0, 3, 31)
    kw = dict(kind="min", k2_0=0.2, tau_span=(0, 3), tau_eval=te, delta0=1.0, lam0=0.3, u0=0.4, psi0=0.2,
              k2_max=None)
    b = ep.simulate(BODY, dissipation(3.0), 0.05, **kw)
    a = ep.simulate(BODY, dissipation(3.0), 0.05, formulation="angles", **kw)
    assert a.status == 0 and b.status == 0
    assert b.t_events["separatrix"].size >= 1
    tc = b.t_events["separatrix"][0]
    assert a.t_events["separatrix"][0] == pytest.approx(tc, abs=1e-6)
    before, after = te < tc, te > tc
    assert set(b.kind[before]) == {"min"} and set(b.kind[after]) == {"max"}
    assert np.array_equal(a.kind, b.kind) and np.array_equal(a.sigma, b.sigma)
    for f in FIELDS:
        # rtol 1e-10 over tau/eps^2 = 1200 units of t~, amplified near the saddles: ~1e-8; bound 1e-6
        assert getattr(a, f) == pytest.approx(getattr(b, f), abs=1e-6), f
    # an independent check of the body formulation: the torque conserves G exactly, and lowers T
    assert b.G == pytest.approx(1.0, abs=1e-8)
    assert np.all(np.diff(b.T) < 0)
    # T passes the separatrix value G^2/(2 A2) at the crossing
    assert np.interp(tc, te, b.T) == pytest.approx(1 / (2 * BODY.A2), abs=2e-3)  # O(eps^2) wobble of T
    # the osculating k2 is that of the kind at each time: rises to 1 in 'min', falls from 1 in 'max'
    assert np.all(np.diff(b.k2[before]) > 0) and np.all(np.diff(b.k2[after]) < 0)


@pytest.mark.parametrize("T0_kind", [("max", 0.99), ("min", 0.5)])
def test_initial_state_by_energy(T0_kind):
    kind, k2 = T0_kind
    T0 = ep.T_from(BODY, 1.2, k2, kind)
    kw = dict(G0=1.2, tau_span=(0, 0.05), tau_eval=[0, 0.05])
    s = ep.simulate(BODY, CASE1, 0.04, T0=T0, **kw)
    r = ep.simulate(BODY, CASE1, 0.04, k2_0=k2, kind=kind, **kw)
    assert s.kind[0] == kind and s.k2[0] == pytest.approx(k2, abs=1e-12) and s.T[0] == pytest.approx(T0, abs=1e-14)
    assert s.G == pytest.approx(r.G, abs=1e-12)
    with pytest.raises(ValueError, match="either by T0 or by k2_0"):
        ep.simulate(BODY, CASE1, 0.04, T0=T0, k2_0=0.5, **kw)
    with pytest.raises(ValueError, match="separatrix"):
        ep.simulate(BODY, CASE1, 0.04, T0=1.2**2 / (2 * BODY.A2), **kw)
    with pytest.raises(ValueError, match="T0 must lie"):
        ep.simulate(BODY, CASE1, 0.04, T0=1.2**2 / (2 * BODY.A1) * 0.9, **kw)
