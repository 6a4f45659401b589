"""Section 3: the dynamically symmetric gyrostat, W(R, kappa, theta, psi), (3.1)-(3.4)."""

from __future__ import annotations

import math
import warnings

import mpmath
import numpy as np
import pytest
from gyrostat_testlib import DPS
from hypothesis import assume, given, settings
from hypothesis import strategies as hst

from rigidbody import gyrostat


def _sym_sat(lR: float, a1: float, a3: float, *, R0: float = 1.0) -> gyrostat.Satellite:
    A = lR**2 * R0**2 * 3 / (2 * a1 + a3)
    return gyrostat.Satellite(M=1.0, A1=a1 * A, A2=a1 * A, A3=a3 * A)


def _mp_hessian_and_gradient(sat, ms):
    """Section-3 W transcribed again here and differentiated at 50 digits, motion recomputed at 50 digits."""
    with mpmath.workdps(DPS):
        M, A1, A3, mu = (mpmath.mpf(v) for v in (sat.M, sat.A1, sat.A3, sat.mu))
        R0, th = mpmath.mpf(ms.R0), mpmath.mpf(ms.theta0)
        n0 = mu / R0**3
        n2 = n0 * (1 + 3 * (A1 - A3) / (M * R0**2) * (1 - mpmath.mpf(3) / 2 * mpmath.sin(th) ** 2))
        kap = mpmath.atan(mpmath.mpf(3) / 2 * (A1 - A3) * n0 * mpmath.sin(2 * th) / (M * R0**2 * n2))
        om = mpmath.sign(ms.omega0) * mpmath.sqrt(n2) / mpmath.cos(kap)
        c = (A1 * om**2 * mpmath.sin(th + kap) * mpmath.cos(th + kap)
             + mpmath.mpf(3) / 2 * n0 * (A1 - A3) * mpmath.sin(2 * th)) / (om * mpmath.cos(th + kap))
        k = om * (M * R0**2 * mpmath.cos(kap) ** 2 + A1 * mpmath.cos(th + kap) ** 2) + c * mpmath.sin(th + kap)

        def W(R, ka, t, p):
            b3 = mpmath.cos(t) * mpmath.sin(ka) - mpmath.sin(t) * mpmath.cos(p) * mpmath.cos(ka)
            S1 = M * R**2 * mpmath.cos(ka) ** 2 + A1 * (1 - b3**2)
            U = mu * M / R + mu / R**3 * (A1 - A3) * (1 - mpmath.mpf(3) / 2 * mpmath.sin(t) ** 2)
            return (k - c * b3) ** 2 / (2 * S1) - U

        x = [R0, kap, th, mpmath.pi]
        H = np.empty((4, 4))
        G = np.empty(4)
        for i in range(4):
            G[i] = float(mpmath.diff(W, x, tuple(int(j == i) for j in range(4))))
            for j in range(i, 4):
                nn = [0] * 4
                nn[i] += 1
                nn[j] += 1
                H[i, j] = H[j, i] = float(mpmath.diff(W, x, tuple(nn)))
    return H, G, float(kap), float(om), float(c)


SYM_CASES = [(0.2, 1.0, 0.6, 0.7), (0.05, 0.7, 1.2, -1.1), (0.3, 1.0, 1.9, 2.3), (1e-3, 1.0, 0.5, 0.4),
             (0.1, 1.0, 1.2, -2.6)]


@pytest.mark.parametrize(("lR", "a1", "a3", "th"), SYM_CASES)
def test_symmetric_solution_hessian_and_34(lR, a1, a3, th):
    sat = _sym_sat(lR, a1, a3)
    ms = gyrostat.symmetric_stationary_motion(sat, 1.0, th)
    H_mp, G_mp, kap, om, c = _mp_hessian_and_gradient(sat, ms)
    # (3.3) solved in closed form: float64 vs 50 digits
    assert np.isclose(ms.kappa0, kap, rtol=1e-13, atol=1e-300)
    assert np.isclose(ms.omega0, om, rtol=1e-14)
    assert np.isclose(ms.c, c, rtol=1e-12)
    # (3.2) is stationary: gradient (3.1) of W vanishes (50-digit route: to ~1e-40 of the terms)
    assert np.all(np.abs(G_mp) < 1e-30)
    # float64 chain-rule gradient at the float motion: rounding of terms ~ mu M / R^2 = 1
    g = gyrostat.gradient_W_sym(sat, ms.point, k=ms.k, c=ms.c)
    assert np.all(np.abs(g) < 1e-14)
    # the chain-rule Hessian equals the numerical one (rounding of O(1) terms, relative to row scale)
    H = gyrostat.hessian_W_sym(sat, ms.point, k=ms.k, c=ms.c)
    D = np.max(np.abs(H_mp), axis=1)
    assert np.all(np.abs(H - H_mp) <= 1e-11 * np.sqrt(np.outer(D, D)))
    # (3.4) is the psi-psi entry, and the psi row decouples
    assert np.isclose(gyrostat.W_psipsi_34(sat, ms.R0, ms.theta0, ms.kappa0), H_mp[3, 3], rtol=1e-10)
    assert np.all(np.abs(H_mp[3, :3]) < 1e-30)
    st = gyrostat.stability(sat, ms)
    assert st.degree == int(np.sum(np.linalg.eigvalsh(H_mp) < 0))


@pytest.mark.parametrize("th", [0.3, 1.0, -0.8, 2.0])
def test_symmetric_family_is_the_triaxial_family_with_A1_eq_A2(th):
    """(3.3) from (2.4) with A1 = A2, k2 = 0 and c = A3 omega0 beta3 + k3 (the spin integral)."""
    sat = _sym_sat(0.2, 1.0, 0.7)
    ms = gyrostat.symmetric_stationary_motion(sat, 1.0, th)
    m = gyrostat.stationary_motion(sat, 1.0, th, k2=0.0)
    assert math.isclose(ms.kappa0, m.kappa0, rel_tol=1e-14)
    assert math.isclose(ms.omega0, m.omega0, rel_tol=1e-14)
    c_from_triaxial = sat.A3 * m.omega0 * math.sin(th + m.kappa0) + m.k3
    assert math.isclose(ms.c, c_from_triaxial, rel_tol=1e-12)
    assert math.isclose(ms.k, m.k, rel_tol=1e-13)


def _scan(lR, a1, a3, thetas):
    sat = _sym_sat(lR, a1, a3)
    out = []
    for th in thetas:
        ms = gyrostat.symmetric_stationary_motion(sat, 1.0, float(th))
        out.append((th, gyrostat.stability(sat, ms)))
    return out


def test_paper_34_is_the_verdict_for_prolate_and_mildly_oblate_bodies():
    """A1 > A3: stable for |theta0| < pi/2 (paper: (3.4) <=> A1 > A3); A1 < A3 < 4 A1 / 3: degree 1,
    unstable as the paper says."""
    th = np.concatenate([np.linspace(-1.5, -0.05, 30), np.linspace(0.05, 1.5, 30)])
    for lR in (1e-3, 0.1):
        for _, st in _scan(lR, 1.0, 0.6, th):
            assert st.paper_condition and st.verdict == "stable"
        for _, st in _scan(lR, 1.0, 1.2, th):
            assert not st.paper_condition and st.verdict == "unstable" and st.degree == 1


def test_paper_instability_claim_fails_for_oblate_bodies_3A3_gt_4A1():
    """Erratum (overstated claim): with (3.4) reversed the paper asserts instability, but for
    3 A3 > 4 A1 also W_thth < 0 (W_thth ~ (4 A1 - 3 A3) omega0^2 cos^2 theta0 for l << R): the degree is
    2 and the second variation decides nothing (gyroscopic stabilisation is not excluded)."""
    th = np.concatenate([np.linspace(-1.5, -0.05, 20), np.linspace(0.05, 1.5, 20)])
    for lR in (1e-3, 0.1):
        for t, st in _scan(lR, 1.0, 1.6, th):
            assert not st.paper_condition
            assert st.degree == 2 and st.verdict == "undecided"
            om2 = st.hessian[1, 1]  # ~ M R0^2 omega0^2 (M = R0 = 1)
            A = _sym_sat(lR, 1.0, 1.6).A1
            # leading-order W_thth: (4 A1 - 3 A3) omega0^2 cos^2 theta0 = -0.8 A1 omega0^2 cos^2 theta0; the
            # neglected terms are O(l^2/R^2) A1 omega0^2 (absolute, not relative to cos^2 theta0)
            est = -0.8 * A * om2 * math.cos(t) ** 2
            assert abs(st.hessian[2, 2] - est) <= 5 * lR**2 * A * om2


def test_symmetric_rejects():
    with pytest.raises(ValueError, match="A1 == A2"):
        gyrostat.symmetric_stationary_motion(gyrostat.Satellite(M=1, A1=0.3, A2=0.2, A3=0.2), 1.0, 0.3)
    sat = _sym_sat(0.1, 1.0, 0.6)
    with pytest.raises(ValueError, match="singular line"):
        gyrostat.symmetric_stationary_motion(sat, 1.0, 0.0)
    with pytest.raises(ValueError, match="k1 = k2 = 0"):
        gyrostat.symmetric_stationary_motion(gyrostat.Satellite(M=1, A1=0.3, A2=0.3, A3=0.2, k2=1.0), 1.0, 0.3)


def test_34_alone_is_not_enough_for_large_bodies():
    """'For real satellites' (3.4) is the single condition: a random sample with l/R <= 0.25 has no
    counterexample, but at l/R ~ 0.3 a needle-like body (A3 = 0.07 A1) satisfies (3.4) and has degree 1."""
    rng = np.random.default_rng(2)
    for _ in range(300):
        lR, a3, th = rng.uniform(0.01, 0.25), rng.uniform(0.05, 0.95), rng.uniform(-1.5, 1.5)
        if abs(th) < 1e-3:
            continue
        sat = _sym_sat(lR, 1.0, a3)
        st = gyrostat.stability(sat, gyrostat.symmetric_stationary_motion(sat, 1.0, th))
        assert st.paper_condition and st.verdict == "stable"
    sat = _sym_sat(0.30509094874109205, 1.0, 0.07144399935950324)
    st = gyrostat.stability(sat, gyrostat.symmetric_stationary_motion(sat, 1.0, -0.2273222483527575))
    assert st.paper_condition and st.verdict == "unstable" and st.degree == 1


def test_symmetric_map_matches_scalar_calls_and_the_4A1_3A3_line():
    s = 0.01
    sat = gyrostat.Satellite(M=1.0, A1=s, A2=s, A3=0.6 * s)
    th = np.linspace(-3.0, 3.0, 41)
    th = th[np.abs(np.sin(th)) > 1e-6]
    r = np.linspace(0.1, 1.9, 19)
    mp = gyrostat.symmetric_stability_map(sat, 1.0, th, A3=r * s)
    assert mp.code.shape == (th.size, r.size)
    for i in range(0, th.size, 5):
        for j in range(0, r.size, 3):
            sat2 = gyrostat.Satellite(M=1.0, A1=s, A2=s, A3=float(r[j] * s))
            st = gyrostat.stability(sat2, gyrostat.symmetric_stationary_motion(sat2, 1.0, float(th[i])))
            assert mp.verdict[i, j] == st.verdict and mp.degree[i, j] == st.degree
    # l/R = 0.1: away from the lines A3 = A1, A3 = 4/3 A1 (by 0.1 >> (l/R)^2) and from cos th0 = 0
    ok_th = np.abs(np.cos(th)) > 0.3
    for j, rr in enumerate(r):
        col = mp.verdict[ok_th, j]
        if rr < 0.9:
            assert np.all(col == "stable")
        elif 1.1 < rr < 1.23:
            assert np.all(col == "unstable")
        elif rr > 1.45:
            assert np.all(col == "undecided")


@settings(max_examples=20, deadline=None)
@given(lR=hst.floats(1e-3, 0.3), a3=hst.floats(0.05, 1.95), th=hst.floats(-3.0, 3.0), sign=hst.sampled_from([-1, 1]))
def test_symmetric_hessian_hypothesis(lR, a3, th, sign):
    assume(abs(np.sin(th)) > 0.05)
    sat = _sym_sat(lR, 1.0, a3)
    try:
        ms = gyrostat.symmetric_stationary_motion(sat, 1.0, th, omega_sign=sign)
    except ValueError:
        assume(False)
    assume(abs(np.cos(ms.theta0 + ms.kappa0)) > 0.05)
    H_mp, G_mp, *_ = _mp_hessian_and_gradient(sat, ms)
    H = gyrostat.hessian_W_sym(sat, ms.point, k=ms.k, c=ms.c)
    D = np.max(np.abs(H_mp), axis=1)
    # float64 chain rule: rounding of O(row-scale) terms, amplified by 1/cos(th + ka) <= 20 through c
    assert np.all(np.abs(H - H_mp) <= 1e-11 * np.sqrt(np.outer(D, D)))
    assert np.all(np.abs(G_mp) < 1e-30)


@pytest.mark.parametrize("d", [1e-7, 1e-6, 1e-4])
def test_si_theta_theta_entry_near_pi_over_2_has_no_cancellation(d):
    """Real satellite (SI), theta0 = pi/2 - d.  The chain-rule W_thth is a sum of terms ~ mu R0^-3 (A1 - A3)
    that cancel to O(l^2/R^2 + cos^2 theta0) of them (~1e-17 against terms ~1e-3 here): the float64 chain
    rule got W_thth wrong by 54 % at d = 1e-7 and called this 'stable' motion 'unstable' (degree 1).  The
    library uses the cancellation-free form :func:`W_thetatheta_stable`; checked against 50-digit
    derivatives of W at the motion recomputed at 50 digits."""
    sat = gyrostat.Satellite(M=1000.0, A1=1200.0, A2=1200.0, A3=800.0, mu=3.986e14)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", gyrostat.GyrostatWarning)  # |cos(theta0 + kappa0)| < 1e-6 at d = 1e-7
        ms = gyrostat.symmetric_stationary_motion(sat, 7e6, math.pi / 2 - d)
    H_mp, *_ = _mp_hessian_and_gradient(sat, ms)
    st = gyrostat.stability(sat, ms)
    # float64 inputs (theta0 + kappa0, c) carry relative errors ~ eps / cos(theta0 + kappa0) <= 1e-9 here
    assert abs(st.hessian[2, 2] - H_mp[2, 2]) <= 1e-7 * abs(H_mp[2, 2])
    # degree of the 50-digit Hessian (its float64 entries are exact to rounding; the (kappa, theta) minor
    # W_kk W_thth - W_kth^2 is ~0.8 W_kth^2 here, far above that rounding), by extended-precision eigenvalues
    with mpmath.workdps(DPS):
        ev = mpmath.eigsy(mpmath.matrix(H_mp.tolist()))[0]
        degree = sum(1 for e in ev if e < 0)
    assert degree == 0 and st.degree == degree and st.verdict == "stable"
    mp = gyrostat.symmetric_stability_map(sat, 7e6, np.array([ms.theta0, 0.5]))
    if abs(math.cos(ms.theta0 + ms.kappa0)) > 1e-6:
        assert mp.verdict[0] == st.verdict and mp.degree[0] == st.degree
    else:  # the map marks the near-singular places of (3.3) invalid (the scalar call warns)
        assert mp.verdict[0] == "invalid"


def test_si_theta0_exactly_pi_over_2_is_not_called_unstable():
    """At theta0 = pi/2 (x3 along the orbit normal) c is free in (3.3) and the (kappa, theta) block of the
    second variation is degenerate to float64 resolution (its 50-digit determinant is ~1e-19 of its terms,
    positive); the old chain-rule W_thth reported degree 1 ('unstable')."""
    sat = gyrostat.Satellite(M=1000.0, A1=1200.0, A2=1200.0, A3=800.0, mu=3.986e14)
    with pytest.warns(gyrostat.GyrostatWarning):
        ms = gyrostat.symmetric_stationary_motion(sat, 7e6, math.pi / 2)
    assert gyrostat.stability(sat, ms).verdict in ("stable", "undecided")
