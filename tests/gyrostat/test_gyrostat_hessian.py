"""The printed first (2.2) and second derivatives of W1 against extended-precision numerical ones."""

from __future__ import annotations

import numpy as np
import pytest
from gyrostat_testlib import MPMotion, motion_cases, mp_derivatives, row_scale
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from rigidbody import gyrostat

CASES = motion_cases()
IDS = [f"th{m.theta0:+.2f}-br{m.branch[0]:+d}{m.branch[1]:+d}-R{m.R0:g}" for _, m in CASES]


@pytest.mark.parametrize(("sat", "m"), CASES, ids=IDS)
def test_printed_hessian_equals_numerical(sat, m):
    """Every printed second derivative, and the vanishing of the unlisted ones, at (2.3)."""
    # W1 is written out again in the test helper (an independent transcription of section 2) and
    # differentiated at 50 digits at the motion recomputed at 50 digits
    H_num = MPMotion(m, given="k2" if abs(np.sin(m.theta0 + m.kappa0)) < 0.5 else "k3").hessian()
    H_pr = gyrostat.hessian_W1(m.satellite, m, form="printed")
    H_st = gyrostat.hessian_W1(m.satellite, m)
    scale = row_scale(H_num)
    # The printed W_g2g2 = -lambda0 sin(th+ka)/cos^3 th + 3 mu R^-3 (A2 - A3) is a difference of terms
    # that agree to O(l^2/R^2) (exactly, to leading order, at th = pi/4): float64 rounding of the
    # terms (1e-16) is amplified by (R/l)^2 relative to the entry's row.  mpmath at 50 digits is exact
    # by comparison.
    lR2 = (m.satellite.l / m.R0) ** 2
    err_pr = np.abs(H_pr - H_num) / scale
    assert np.max(err_pr) < 1e-13 / lR2 + 1e-12, (np.unravel_index(np.argmax(err_pr), err_pr.shape), err_pr.max())
    # the stable form (same values, no cancellation): float64 rounding of O(1) terms only; 1e-12 leaves
    # room for the 1/cos^3 amplification in the mixed-branch cases (cos(th + ka) ~ 0.13)
    err_st = np.abs(H_st - H_num) / scale
    assert np.max(err_st) < 1e-12, (np.unravel_index(np.argmax(err_st), err_st.shape), err_st.max())
    # and entry by entry: a row-scaled error hides the small entries of a row (in SI, W_Rk ~ l^2/R of W_RR);
    # the stable form has no cancellation, so each entry is exact to the rounding of its own terms
    listed = np.zeros((6, 6), bool)
    for i, j in [(0, 0), (1, 1), (2, 2), (3, 3), (4, 4), (5, 5), (0, 1), (0, 3), (1, 3), (0, 5), (2, 4), (3, 5)]:
        listed[i, j] = listed[j, i] = True
    err_entry = np.abs(H_st - H_num)[listed] / np.abs(H_num[listed])
    assert np.max(err_entry) < 1e-12, err_entry.max()
    # unlisted entries vanish (exactly, by the symmetry beta1 = gamma1 = 0 and the structure of W1)
    assert np.all(np.abs(H_num[~listed]) < 1e-13 * scale[~listed])


@pytest.mark.parametrize(("sat", "m"), CASES, ids=IDS)
def test_gradient_22_closed_form_equals_numerical_off_the_motion(sat, m):
    """(2.2) is a claim about W1 anywhere: test it at a point displaced from the motion."""
    rng = np.random.default_rng(7)
    x = np.array(m.point) + rng.normal(0, 1e-2, 6) * np.array([m.R0, 1, 1, 0, 1, 0])
    x[3] *= 0.98  # shrink |beta3|, |gamma2| so that the displaced point stays inside the unit disks
    x[5] *= 0.98
    lam = 1.3 * m.lambda0 + 1e-3 * m.satellite.Abar * m.omega0**2
    f = lambda *y: gyrostat.amended_potential(  # noqa: E731
        m.satellite, y, k=m.k, lam=lam, branch=m.branch, lib=__import__("mpmath"))
    g_num = mp_derivatives(f, x, 1)
    g_cf = gyrostat.gradient_W1(m.satellite, x, k=m.k, lam=lam, branch=m.branch)
    # displaced point: the gradient is not small; float64 rounding of its terms ~1e-16 relative,
    # the terms of dW1/dR (~ mu M / R^2) dominate in SI, so compare relative to the term scale
    H = gyrostat.hessian_W1(m.satellite, m)
    scale = np.abs(g_num) + np.max(np.abs(H), axis=1) * 1e-2 * np.array([m.R0, 1, 1, 1, 1, 1])
    assert np.all(np.abs(g_cf - g_num) <= 1e-10 * scale)


def _term_scales(sat, m):
    """Magnitude of the largest single term in each equation (2.2): the float64 rounding scale."""
    M, R, om = sat.M, m.R0, m.omega0
    n0 = sat.mu / R**3
    L = abs(m.lambda0)
    ct, cp = abs(np.cos(m.theta0)), abs(np.cos(m.theta0 + m.kappa0))
    return np.array([
        M * sat.mu / R**2,                           # dW1/dR: centrifugal vs Newtonian
        M * R**2 * om**2 * abs(np.sin(m.kappa0)) + L,
        abs(om * sat.k2) + sat.Abar * om**2,         # dW1/dbeta1 (zero by symmetry)
        (abs(om * m.k3) + abs(om * m.k2) + L) / cp + sat.Abar * om**2,   # terms ~ beta3 / beta2
        sat.Abar * n0 + L,
        sat.Abar * n0 + L / ct,                      # lambda beta3 gamma2 / gamma3
    ])


@pytest.mark.parametrize(("sat", "m"), CASES, ids=IDS)
def test_gradient_and_chi_vanish_at_the_solution_of_24(sat, m):
    g = gyrostat.gradient_W1(m.satellite, m.point, k=m.k, lam=m.lambda0, branch=m.branch)
    scale = _term_scales(m.satellite, m)
    # (2.3)-(2.4) solved in closed form in float64: residual = rounding of the largest terms,
    # a few ulps (the area constant k ~ omega0 S0 is rounded once: 1e-16 relative)
    assert np.all(np.abs(g) <= 2e-14 * np.maximum(scale, 1e-300)), g / scale
    c = gyrostat.chi(m.point, branch=m.branch)
    # beta2, gamma3 are recomputed from sqrt(1 - ...): rounding amplified by 1/|beta2|, 1/|gamma3|
    eps = np.finfo(float).eps
    assert abs(c) <= 8 * eps * (1 + 1 / abs(np.cos(m.theta0 + m.kappa0)) + 1 / abs(np.cos(m.theta0)))


def test_complex_step_gradient_matches_22_nondimensional():
    """A second, float64-only independent route (complex step) for (2.2)."""
    from rigidbody.core.quadform import gradient_cs

    sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.007, k1=0.001, k2=0.002, k3=-0.003)
    x = np.array([1.02, 0.03, 0.1, 0.5, -0.2, 0.3])
    g_cs = gradient_cs(lambda z: gyrostat.amended_potential(sat, z, k=0.9, lam=0.01), x)
    g_cf = gyrostat.gradient_W1(sat, x, k=0.9, lam=0.01)
    # complex step has no subtractive cancellation: agreement to rounding of the terms (~1e-16 * |W| ~ 1)
    assert np.allclose(g_cs, g_cf, rtol=1e-13, atol=1e-14)


def test_branch_matters():
    """On the wrong square-root branch the point of (2.3) is not stationary (the branch is state)."""
    sat, m = next((s, m) for s, m in CASES if m.branch == (-1, -1))
    g = gyrostat.gradient_W1(m.satellite, m.point, k=m.k, lam=m.lambda0, branch=(1, 1))
    assert np.max(np.abs(g)) > 1e-3 * m.satellite.Abar * m.omega0**2
    with pytest.raises(ValueError, match="branch"):
        gyrostat.chi(m.point, branch=(1, 0))


@settings(max_examples=25, deadline=None)
@given(
    lR=st.floats(0.01, 0.35),
    a=st.tuples(st.floats(0.4, 1.0), st.floats(0.4, 1.0), st.floats(0.4, 1.0)),
    th=st.floats(-3.1, 3.1),
    u=st.floats(-5, 5),
    sign=st.sampled_from([-1, 1]),
)
def test_printed_hessian_hypothesis(lR, a, th, u, sign):
    """Random parameter sets over all branches: stable-form Hessian vs the 50-digit route."""
    a = np.array(a)
    assume(all(a[i] <= a[(i + 1) % 3] + a[(i + 2) % 3] for i in range(3)))
    assume(min(abs(np.cos(th)), abs(np.sin(th))) > 0.05)
    A = a / a.mean() * lR**2
    sat = gyrostat.Satellite(M=1.0, A1=float(A[0]), A2=float(A[1]), A3=float(A[2]))
    try:
        m = gyrostat.stationary_motion(sat, 1.0, th, k2=u * sat.Abar, omega_sign=sign)
    except ValueError:
        assume(False)
    assume(abs(np.cos(m.theta0 + m.kappa0)) > 0.05)
    H_num = MPMotion(m, given="k2").hessian()
    H = gyrostat.hessian_W1(m.satellite, m)
    # rounding of O(row-scale) terms, amplified by at most 1/cos^3 = 8e3 near the chart's edges here; the
    # floor 1e-12 Abar (attitude entries ~ Abar n0^2, n0 = 1) covers rows that vanish (a sphere)
    assert np.max(np.abs(H - H_num) / (row_scale(H_num) + 1e-12 * sat.Abar)) < 1e-10


def test_finite_difference_hessian_route():
    """The library's float64 numerical route (8th-order differences) on a nondimensional motion."""
    sat = gyrostat.Satellite(M=1.0, A1=0.03, A2=0.02, A3=0.012)
    m = gyrostat.stationary_motion(sat, 1.0, 0.7, k2=0.01)
    H_fd = gyrostat.hessian_W1_numerical(m.satellite, m)
    H = gyrostat.hessian_W1(m.satellite, m)
    # truncation O(h^8) ~ 1e-24, round-off ~ eps |W1| / h^2 ~ 1e-10 (|W1| ~ 1, h = 1e-3)
    assert np.max(np.abs(H - H_fd)) < 1e-8 * np.max(np.abs(H))


@settings(max_examples=50, deadline=None)
@given(
    lR=st.floats(1e-4, 0.4),
    a=st.tuples(st.floats(0.3, 1.0), st.floats(0.3, 1.0), st.floats(0.3, 1.0)),
    th=st.floats(-3.1, 3.1),
    u=st.floats(-5, 5),
    use_k3=st.booleans(),
)
def test_gradient_vanishes_hypothesis(lR, a, th, u, use_k3):
    a = np.array(a)
    assume(all(a[i] <= a[(i + 1) % 3] + a[(i + 2) % 3] for i in range(3)))
    assume(min(abs(np.cos(th)), abs(np.sin(th))) > 1e-3)
    A = a / a.mean() * lR**2
    sat = gyrostat.Satellite(M=1.0, A1=float(A[0]), A2=float(A[1]), A3=float(A[2]))
    kw = {"k3": u * sat.Abar} if use_k3 else {"k2": u * sat.Abar}
    try:
        m = gyrostat.stationary_motion(sat, 1.0, th, **kw)
    except ValueError:
        assume(False)
    assume(abs(np.cos(m.theta0 + m.kappa0)) > 1e-3 and abs(np.sin(m.theta0 + m.kappa0)) > 1e-3)
    g = gyrostat.gradient_W1(m.satellite, m.point, k=m.k, lam=m.lambda0, branch=m.branch)
    # rounding of the largest terms of each equation; k2 from k3 divides by sin(th + ka) >= 1e-3 (x1e3)
    amp = 1.0 / min(abs(np.sin(m.theta0 + m.kappa0)), 1.0) if use_k3 else 1.0
    assert np.all(np.abs(g) <= 4e-14 * amp * _term_scales(m.satellite, m))
