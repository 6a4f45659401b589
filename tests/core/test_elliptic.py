"""rigidbody.core.elliptic against mpmath, identities, derivatives and the separatrix."""

import math

import mpmath as mp
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import special

from rigidbody.core import elliptic as ell

mp.mp.dps = 40

# away from the separatrix: double-precision algorithms, target 1e-13 relative (issue's bound)
TOL_REGULAR = 1e-13
# 1 - k^2 down to 1e-12: the argument of the AGM near x = K/2 is ~pi/2 and cn = cos(phi) loses
# log10(1/cn) digits (cn ~ (1-k^2)^(1/4) there), i.e. ~1e-16 / 1e-3 = 1e-13 relative; 1e-9 is the bound.
TOL_SEPARATRIX = 1e-9

k_regular = st.floats(0.0, 0.999, allow_nan=False)
log_mc_near = st.floats(-12.0, -3.0)


def _mp_jacobi(u, m):
    m = mp.mpf(m)
    return [mp.ellipfun(name, u, m=m) for name in ("sn", "cn", "dn")]


@settings(max_examples=40)
@given(k=k_regular)
def test_K_E_against_mpmath_regular(k):
    m = mp.mpf(k) ** 2
    assert ell.K(k) == pytest.approx(float(mp.ellipk(m)), rel=TOL_REGULAR, abs=0)
    assert ell.E(k) == pytest.approx(float(mp.ellipe(m)), rel=TOL_REGULAR, abs=0)


@settings(max_examples=40)
@given(lmc=log_mc_near)
def test_K_E_against_mpmath_near_separatrix_with_mc(lmc):
    mc = 10.0**lmc
    m = 1 - mp.mpf(mc)
    # with the exact complementary parameter both integrals keep full precision
    assert ell.K(mc=mc) == pytest.approx(float(mp.ellipk(m)), rel=TOL_REGULAR, abs=0)
    assert ell.E(mc=mc) == pytest.approx(float(mp.ellipe(m)), rel=TOL_REGULAR, abs=0)


@settings(max_examples=40)
@given(k=k_regular, phi=st.floats(-7.0, 7.0))
def test_incomplete_against_mpmath(k, phi):
    m = mp.mpf(k) ** 2
    assert ell.F(phi, k) == pytest.approx(float(mp.ellipf(phi, m)), rel=TOL_REGULAR, abs=1e-15)
    assert ell.Einc(phi, k) == pytest.approx(float(mp.ellipe(phi, m)), rel=TOL_REGULAR, abs=1e-15)


@settings(max_examples=40)
@given(k=k_regular, x=st.floats(-4.0, 4.0))
def test_jacobi_against_mpmath_regular(k, x):
    u = x * ell.K(k)  # cover several quarter periods
    s, c, d, _ = ell.jacobi(u, k)
    es, ec, ed = _mp_jacobi(u, mp.mpf(k) ** 2)
    # absolute in sn, cn (they pass through zero), relative in dn (> k' > 0)
    assert abs(s - float(es)) < 4 * TOL_REGULAR
    assert abs(c - float(ec)) < 4 * TOL_REGULAR
    assert d == pytest.approx(float(ed), rel=TOL_REGULAR, abs=0)


@settings(max_examples=40)
@given(lmc=log_mc_near, x=st.floats(-5.0, 5.0))
def test_jacobi_against_mpmath_near_separatrix(lmc, x):
    mc = 10.0**lmc
    u = x * ell.K(mc=mc)
    s, c, d, _ = ell.jacobi(u, mc=mc)
    es, ec, ed = _mp_jacobi(u, 1 - mp.mpf(mc))
    # the input u carries a relative rounding error ~1e-16 that moves the functions by ~u*1e-16
    slack = abs(u) * 1e-15
    assert abs(s - float(es)) < TOL_SEPARATRIX + slack
    assert abs(c - float(ec)) <= TOL_SEPARATRIX * abs(float(ec)) + 1e-15 + slack
    assert abs(d - float(ed)) <= TOL_SEPARATRIX * float(ed) + slack


def test_separatrix_case_that_breaks_raw_ellipj():
    # SciPy issue 8480: raw ellipj is off by orders of magnitude for 1 - m <= 1e-9 and u > K.
    mc = 1e-12
    m = 1.0 - mc
    u = 3.3 * ell.K(mc=mc)  # raw ellipj returns cn, dn ~ 1e8 here (they must lie in [-1, 1])
    raw = special.ellipj(u, m)
    s, c, d, _ = ell.jacobi(u, mc=mc)
    es, ec, ed = (float(v) for v in _mp_jacobi(u, 1 - mp.mpf(mc)))
    raw_err = max(abs(raw[0] - es), abs(raw[1] - ec), abs(raw[2] - ed))
    ours = max(abs(s - es), abs(c - ec), abs(d - ed))
    assert raw_err > 1.0  # the failure this module exists to avoid (if SciPy fixes it, drop this line)
    assert ours < 1e-12
    for v in (s, c, d):
        assert abs(v) <= 1.0


@settings(max_examples=30)
@given(k=st.floats(0.0, 1.0), u=st.floats(-60.0, 60.0))
def test_identities(k, u):
    s, c, d, _ = ell.jacobi(u, k)
    assert s * s + c * c == pytest.approx(1.0, abs=4e-15)
    assert d * d + k * k * s * s == pytest.approx(1.0, abs=4e-15)


@settings(max_examples=30)
@given(k=st.floats(0.0, 0.99), u=st.floats(-10.0, 10.0))
def test_derivatives_by_finite_differences(k, u):
    h = 1e-3
    # 4th-order central difference: truncation h^4 |f^(5)|/30 ~ 1e-13 for |f^(5)| = O(10)
    def d4(f):
        return (-f(u + 2 * h) + 8 * f(u + h) - 8 * f(u - h) + f(u - 2 * h)) / (12 * h)

    s, c, d, a = ell.jacobi(u, k)
    assert d4(lambda x: ell.sn(x, k)) == pytest.approx(c * d, abs=1e-10)
    assert d4(lambda x: ell.cn(x, k)) == pytest.approx(-s * d, abs=1e-10)
    assert d4(lambda x: ell.dn(x, k)) == pytest.approx(-k * k * s * c, abs=1e-10)
    assert d4(lambda x: ell.am(x, k)) == pytest.approx(d, abs=1e-10)


@settings(max_examples=30)
@given(k=st.floats(0.0, 0.999999), u=st.floats(-5.0, 5.0), j=st.integers(-3, 3))
def test_quasi_periodicity(k, u, j):
    KK = ell.K(k)
    s0, c0, d0, a0 = ell.jacobi(u, k)
    s1, c1, d1, a1 = ell.jacobi(u + 2 * j * KK, k)
    sign = (-1) ** j
    slack = 1e-14 * (1 + abs(j) * KK)  # rounding of u + 2jK
    assert s1 == pytest.approx(sign * s0, abs=slack)
    assert c1 == pytest.approx(sign * c0, abs=slack)
    assert d1 == pytest.approx(d0, abs=slack)
    assert a1 == pytest.approx(a0 + j * math.pi, abs=slack * 10)
    s2, c2, d2, _ = ell.jacobi(u + KK, k)
    kp = math.sqrt(1 - k * k)
    assert s2 == pytest.approx(c0 / d0, abs=1e-13)  # sn(u + K) = cd u
    assert c2 == pytest.approx(-kp * s0 / d0, abs=1e-13)


def test_k_equals_one_limits():
    u = np.array([-800.0, -3.0, 0.0, 0.5, 800.0])
    s, c, d, a = ell.jacobi(u, 1.0)
    np.testing.assert_allclose(s, np.tanh(u), atol=1e-16)
    np.testing.assert_allclose(c, 1 / np.cosh(np.clip(u, -700, 700)), atol=1e-300)
    np.testing.assert_allclose(a, np.arctan(np.sinh(np.clip(u, -700, 700))), atol=1e-15)
    assert ell.K(1.0) == math.inf
    assert ell.E(1.0) == 1.0
    assert ell.Einc(math.pi / 2, 1.0) == pytest.approx(1.0)
    assert ell.F(0.5, 1.0) == pytest.approx(math.atanh(math.sin(0.5)), rel=1e-14, abs=0)


def test_k_zero_limits():
    u = np.linspace(-7, 7, 11)
    s, c, d, a = ell.jacobi(u, 0.0)
    np.testing.assert_allclose(s, np.sin(u), atol=1e-15)
    np.testing.assert_allclose(c, np.cos(u), atol=1e-15)
    np.testing.assert_allclose(d, 1.0, atol=1e-15)
    np.testing.assert_allclose(a, u, atol=1e-14)
    assert ell.K(0.0) == pytest.approx(math.pi / 2, rel=1e-15, abs=0)


def test_scalar_in_scalar_out_and_broadcasting():
    s = ell.sn(0.3, 0.5)
    assert isinstance(s, float)
    out = ell.sn(np.linspace(0, 1, 4)[:, None], np.array([0.1, 0.5, 0.9]))
    assert out.shape == (4, 3)
    assert ell.jacobi(0.2, k=None, mc=0.75)[0] == pytest.approx(ell.sn(0.2, 0.5), rel=1e-15, abs=0)


@pytest.mark.parametrize("bad", [-0.1, 1.0000001, math.nan, math.inf])
def test_bad_modulus_raises(bad):
    with pytest.raises(ValueError, match=r"\[0, 1\]|finite"):
        ell.sn(0.3, bad)
    with pytest.raises(ValueError):
        ell.K(bad)


def test_bad_types_and_inconsistent_inputs():
    with pytest.raises(TypeError, match="k"):
        ell.K("half")
    with pytest.raises(TypeError, match="mc"):
        ell.K()
    with pytest.raises(ValueError, match="inconsistent"):
        ell.K(0.5, mc=0.5)
    with pytest.raises(ValueError, match="u must be finite"):
        ell.sn(math.nan, 0.5)


@settings(max_examples=30)
@given(k=st.floats(0.0, 0.999999), x=st.floats(-3.0, 3.0))
def test_F_inverts_am(k, x):
    u = x * ell.K(k)
    a = ell.am(u, k)
    assert ell.F(a, k) == pytest.approx(u, abs=1e-12 * (1 + abs(u)))
