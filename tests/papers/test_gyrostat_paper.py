"""Stepanov (1968), "On stationary motions of a gyrostat satellite": the paper's statements re-checked.

Each test names the statement of the paper it re-runs.  The algebraic checks of (2.2), the printed
second derivatives and (2.5) live in tests/gyrostat/; here are the paper's qualitative claims.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from rigidbody import gyrostat


def _body(lR: float, a=(1.2, 1.0, 0.8)) -> gyrostat.Satellite:
    s = lR**2 * 3 / sum(a)
    return gyrostat.Satellite(M=1.0, A1=a[0] * s, A2=a[1] * s, A3=a[2] * s)


def _kappa0(sat, th):
    return gyrostat.stationary_motion(sat, 1.0, th, k2=0.0).kappa0


def test_kappa0_is_order_l2_over_R2_and_maximal_near_pi_over_4():
    """Section 2: "the angle kappa0 is of order l^2/R^2 and is maximal at theta0 = pi/4"."""
    lRs = [0.2, 0.1, 0.05, 0.025]
    peaks, scaled = [], []
    for lR in lRs:
        sat = _body(lR)
        res = minimize_scalar(lambda t, sat=sat: -_kappa0(sat, t), bounds=(0.1, 1.4), method="bounded",
                              options={"xatol": 1e-10})
        peaks.append(res.x)
        scaled.append(_kappa0(sat, res.x) / lR**2)
    err = np.abs(np.array(peaks) - math.pi / 4)
    # the peak moves to pi/4 like (l/R)^2: halving l/R divides the offset by ~4
    assert np.all(err[1:] < err[:-1])
    ratios = err[:-1] / err[1:]
    assert np.all((ratios > 3.0) & (ratios < 5.0)), ratios
    # kappa0 / (l/R)^2 tends to its leading-order value 3/2 (A2 - A3)/(M l^2) = 3/2 * 0.2 * 3 / 3
    lead = 1.5 * (1.0 - 0.8) * 3 / 3.0
    dev = np.abs(np.array(scaled) - lead)
    assert np.all(dev[1:] < dev[:-1]) and dev[-1] < 4 * lRs[-1] ** 2 * lead


def test_orbit_plane_displacement_is_order_l2_over_R():
    """Introduction: "the displacement of the orbit plane is of order l^2/R" (here R0 sin kappa0)."""
    si = gyrostat.Satellite(M=1000.0, A1=1200.0, A2=1000.0, A3=800.0, mu=3.986e14)
    m = gyrostat.stationary_motion(si, 7.0e6, math.pi / 4, k2=0.0)
    l2_R = si.l**2 / m.R0
    assert 0.1 * l2_R < m.displacement < 10 * l2_R
    # "For real artificial Earth satellites these quantities are very small": ~1e-7 m here
    assert m.displacement < 1e-6


def test_restricted_inequalities_are_the_limit_of_s1_s2_s3():
    """After (2.5): to O(l^2/R^2) s1 > 0, s3 > 0, s2 > 0 coincide with the first, second and third
    restricted inequalities.  The fraction of a random sample where the signs disagree shrinks ~ (l/R)^2."""
    rng = np.random.default_rng(5)
    N = 300_000
    a = rng.uniform(0.3, 1.0, (N, 3))
    ok = (a[:, 0] <= a[:, 1] + a[:, 2]) & (a[:, 1] <= a[:, 0] + a[:, 2]) & (a[:, 2] <= a[:, 0] + a[:, 1])
    a = a[ok]
    th = rng.uniform(-1.4, 1.4, a.shape[0])
    u = rng.uniform(-6, 6, a.shape[0])  # k2 / (n0 Abar), n0 = sqrt(mu/R0^3) = 1
    fr = []
    for lR in (0.16, 0.08, 0.04):
        A = a / a.mean(axis=1, keepdims=True) * lR**2
        Abar = A.mean(axis=1)
        sat = gyrostat.Satellite(M=1.0, A1=0.01, A2=0.01, A3=0.01)
        mp = gyrostat.stability_map(sat, 1.0, th, k2=u * Abar, A1=A[:, 0], A2=A[:, 1], A3=A[:, 2], grid=False)
        assert np.all(mp.code >= 0)
        dis = (np.sign(mp.s1) != np.sign(mp.r1)) | (np.sign(mp.s3) != np.sign(mp.r2)) \
            | (np.sign(mp.s2) != np.sign(mp.r3))
        fr.append(dis.mean())
    fr = np.array(fr)
    assert fr[0] > 0.002  # the effect exists at l/R = 0.16
    ratios = fr[:-1] / fr[1:]
    # (l/R)^2 scaling: ratio 4 per halving; counting noise (~100 events at l/R = 0.04: +-10 %) and the
    # O(l/R) change of the density near the boundaries leave [3, 5.5]
    assert np.all((ratios > 3.0) & (ratios < 5.5)), (fr, ratios)


def test_odd_degree_statement():
    """End of section 2: s1 != 0, s2 < 0, s3 > 0 or s1 != 0, s2 > 0, s3 < 0 => odd degree => unstable."""
    sat = _body(0.1, (1.0, 1.2, 0.8))  # A2 > A1: s2 < 0 for k2 = 0 at moderate tilts
    th = np.linspace(-1.4, 1.4, 141)
    k2 = np.linspace(-0.05, 0.05, 101)
    mp = gyrostat.stability_map(sat, 1.0, th, k2=k2)
    odd = (mp.s1 != 0) & (((mp.s2 < 0) & (mp.s3 > 0)) | ((mp.s2 > 0) & (mp.s3 < 0)))
    assert np.any(odd)
    assert np.all(mp.verdict[odd] == "unstable")
    assert np.all(mp.degree[odd] % 2 == 1)
    assert np.all(mp.code[~odd & (mp.code >= 0)] != 1)


def test_34_reduces_to_A1_gt_A3_for_small_tilts():
    """Section 3: for |theta0| < pi/2, (3.4) reduces to A1 > A3."""
    th = np.linspace(-1.5, 1.5, 61)
    th = th[np.abs(th) > 1e-3]
    for a1, a3 in ((1.0, 0.6), (1.0, 1.3)):
        s = 0.01 * 3 / (2 * a1 + a3)
        sat = gyrostat.Satellite(M=1.0, A1=a1 * s, A2=a1 * s, A3=a3 * s)
        for t in th:
            ms = gyrostat.symmetric_stationary_motion(sat, 1.0, float(t))
            assert (gyrostat.W_psipsi_34(sat, 1.0, t, ms.kappa0) > 0) == (a1 > a3)


def test_section5_gravity_force_along_y2():
    """Section 5: the gravitational forces have a y2 resultant 3/2 mu R0^-4 (A2 - A3) sin 2 theta0,
    which displaces the orbit plane.  Independent route: the exact Newtonian force on a rigid cloud of
    point masses with the same mass and moments, projected on y2; the difference is O(l/R) relative
    (the cloud is centrally symmetric, so in fact O(l^2/R^2))."""
    mu = 1.0
    R0 = 1.0
    th = 0.6
    for lR, tol in ((0.02, 2e-3), (0.01, 5e-4)):
        # six masses on the body axes at +-d_i: A1 = m (d2^2 + d3^2) * 2 etc.
        d = np.array([1.0, 0.8, 0.5]) * lR
        m = 1.0 / 6
        pts_body = np.concatenate([np.diag(d), -np.diag(d)])
        d2 = d**2
        A = 2 * m * np.array([d2[1] + d2[2], d2[0] + d2[2], d2[0] + d2[1]])
        # body axes in the orbital frame (y1, y2, y3): x1 = y1, x2 = (0, cos th, -sin th), x3 = (0, sin th, cos th)
        Rb = np.array([[1, 0, 0], [0, math.cos(th), math.sin(th)], [0, -math.sin(th), math.cos(th)]])
        r = np.array([0, 0, R0]) + pts_body @ Rb.T
        F = -mu * m * np.sum(r / np.linalg.norm(r, axis=1)[:, None] ** 3, axis=0)
        paper = 1.5 * mu / R0**4 * (A[1] - A[2]) * math.sin(2 * th)
        # the force on the body along +y2 (from the centre towards... ) equals the paper's expression
        assert abs(F[1] - paper) <= tol * abs(paper)


@pytest.mark.parametrize("th", [0.3, -0.9])
def test_section4_lyapunov_addendum(th):
    """Section 4: when (2.5) holds the Jacobian (cos^2 ka0 / cos^2 th0) s2 s3 is nonzero, so stability
    is unconditional (k perturbed too)."""
    sat = _body(0.05)
    m = gyrostat.stationary_motion(sat, 1.0, th, k2=2 * sat.Abar)
    st = gyrostat.stability(m.satellite, m)
    assert st.verdict == "stable" and st.unconditionally_stable
    assert math.isclose(abs(st.jacobian), math.cos(m.kappa0) ** 2 / math.cos(th) ** 2 * st.s2 * st.s3, rel_tol=1e-12)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_s_quantities_tend_to_the_restricted_ones_first_third_second(seed):
    """After (2.5): s1, s2 and s3 (through a33) tend "respectively" to the first, third and second restricted
    inequalities: s1 ~ 3 n^2 r1, s2 ~ 3 n^4 r3, a33 ~ 4 omega0^2 r2, with relative errors O(l^2/R^2)
    (measured against the natural scale of each quantity, since r_i itself may be small)."""
    rng = np.random.default_rng(seed)
    errs = []
    lRs = (0.04, 0.02, 0.01)
    a = rng.uniform(0.5, 1.0, 3)
    th = float(rng.uniform(-1.2, 1.2))
    u = float(rng.uniform(-3, 3))
    for lR in lRs:
        s = lR**2 * 3 / a.sum()
        sat = gyrostat.Satellite(M=1.0, A1=a[0] * s, A2=a[1] * s, A3=a[2] * s)
        m = gyrostat.stationary_motion(sat, 1.0, th, k2=u * sat.Abar)
        st = gyrostat.stability(m.satellite, m)
        r1, r2, r3 = st.restricted
        A = sat.Abar
        om2 = m.omega0**2
        e1 = abs(st.s1 - 3 * r1) / (3 * A)  # n^2 = mu / R0^3 = 1
        e2 = abs(st.s2 - 3 * r3) / (3 * A**2 * (1 + abs(u)))
        e3 = abs(st.a[2, 2] - 4 * om2 * r2) / (4 * A * (1 + abs(u)))
        errs.append(max(e1, e2, e3))
    errs = np.array(errs)
    # O(l^2/R^2): halving l/R divides the error by ~4 (it is already tiny: < (l/R)^2 * 20)
    assert np.all(errs < 20 * np.array(lRs) ** 2)
    assert np.all(errs[:-1] / errs[1:] > 3.0)
