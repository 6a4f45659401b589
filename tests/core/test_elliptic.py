"""rigidbody.core.elliptic against mpmath, identities, derivatives and the separatrix."""

import math
import warnings

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
# 1 - k^2 down to 1e-12: sums of positive terms in the complementary nome on a double-double reduced argument,
# a few ulp relative (tests/core/test_elliptic_near_separatrix.py goes to 1e-300 and to the zeros of cn)
TOL_SEPARATRIX = 1e-13

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


@settings(max_examples=60)
@given(lmc=st.floats(-20.0, 0.0))
def test_E_to_a_few_ulp_from_k_and_from_mc(lmc):
    # E = ellipe(m) (cephes: a rational approximation in 1 - m, to ~1 ulp). From mc, m = 1 - mc is rounded by
    # <= eps/4 and |dE/dm| = (K - E)/(2m) <= 10 for mc >= 1e-20: <= 2.5 eps more, so 4 ulp in all.
    mc = 10.0**lmc
    ulp = 2.0**-52
    with mp.workdps(40):
        ref = mp.ellipe(1 - mp.mpf(mc))
        assert abs(ell.E(mc=mc) - ref) <= 4 * ulp * ref
        k = math.sqrt(1.0 - mc)
        ref_k = mp.ellipe(mp.mpf(k) ** 2)  # the modulus as given: m = k**2 exactly
        assert abs(ell.E(k) - ref_k) <= 2 * ulp * ref_k
        assert abs(ell.E(np.array([k, k]))[1] - ref_k) <= 2 * ulp * ref_k


def test_dn_where_cn_vanishes():
    """At u = (2j+1)K, where cn = 0 and dn = k', SciPy's dn = cn / cos(phi - phi_1) is a quotient of two small
    numbers (relative error ~eps / |cn| nearby); dn^2 = mc + m cn^2 is a sum of positives and keeps 1e-15."""
    for mc in (0.5, 0.1, 0.02, 0.0101):
        k = math.sqrt(1 - mc)
        KK = ell.K(k)
        u = np.array([1, 3, -1, 7], dtype=float) * KK + np.array([0.0, 1e-9, -1e-7, 1e-12])
        d = ell.dn(u, k)
        with mp.workdps(40):
            ref = np.array([float(mp.ellipfun("dn", float(x), m=mp.mpf(k) ** 2)) for x in u])
        # the argument u = (2j+1) K + small carries an absolute rounding error ~ |u| eps, which moves dn by
        # k^2 |sn cn| |u| eps ~ 1e-15 |u| cn: far below the bound
        assert np.max(np.abs(d - ref) / ref) < 4e-15


@settings(max_examples=25)
@given(lmc=st.lists(st.floats(-12.0, 0.0), min_size=8, max_size=8), x=st.floats(-5.0, 5.0))
def test_array_calls_equal_scalar_calls_across_both_routes(lmc, x):
    """One array call mixing regular moduli (SciPy directly) and near-separatrix ones (period-reduced,
    the nome series) equals the scalar calls, element by element, to rounding; and near the separatrix
    the array route meets the same mpmath bound as the scalar one."""
    mc = np.array([10.0**v for v in lmc] + [0.0])
    u = x * np.minimum(ell.K(mc=np.maximum(mc, 1e-12)), 30.0)
    s, c, d, a = ell.jacobi(u, mc=mc)
    for i in range(mc.size):
        si, ci, di, ai = ell.jacobi(float(u[i]), mc=float(mc[i]))
        # the same algorithm in numpy and in Python floats: libm and numpy's sin/arcsin may differ by an ulp
        assert abs(s[i] - si) < 1e-14 and abs(c[i] - ci) < 1e-14 and abs(d[i] - di) < 1e-14 * di
        assert abs(a[i] - ai) < 1e-14 * (1 + abs(ai))
        if 0.0 < mc[i] < 1e-3:
            es, ec, ed = _mp_jacobi(float(u[i]), 1 - mp.mpf(float(mc[i])))
            slack = abs(u[i]) * 1e-15
            assert abs(s[i] - float(es)) < TOL_SEPARATRIX + slack
            assert abs(d[i] - float(ed)) <= TOL_SEPARATRIX * float(ed) + slack


@pytest.mark.parametrize("by", ["k", "mc"])
def test_long_arrays_with_a_modulus_per_element_equal_scalar_calls(by):
    """An array longer than the blocks the evaluation takes at a time (a few times 10^4), with a modulus per
    element mixing the three routes (theta series, complementary nome, k = 1): each element as the scalar
    call gives it, at the block edges and the ragged end included (a shifted or dropped block, or moduli
    paired with the wrong arguments, are off by far more)."""
    rng = np.random.default_rng(19)
    n = 3 * 2**14 + 7
    mc = np.where(rng.uniform(size=n) < 0.2, 10.0 ** rng.uniform(-40, -1.3, n), rng.uniform(0.0, 1.0, n))
    mc[rng.integers(0, n, 20)] = 0.0
    k = np.sqrt(1.0 - mc)
    u = rng.uniform(-10.0, 10.0, n) * np.minimum(ell.K(mc=np.maximum(mc, 1e-300)), 50.0)
    got = ell.jacobi(u, k) if by == "k" else ell.jacobi(u, mc=mc)
    edges = [i + d for i in range(0, n + 1, 2**10) for d in (-1, 0)]
    for i in sorted({min(max(i, 0), n - 1) for i in edges} | set(range(n - 10, n))):
        one = ell.jacobi(float(u[i]), float(k[i])) if by == "k" else ell.jacobi(float(u[i]), mc=float(mc[i]))
        for g, o in zip((x[i] for x in got), one):
            # each within 8 ulp of the exact value (tests/core/test_elliptic_ulps.py), so within 16 of each
            # other; an ulp of the scalar value is at least half that of the exact one: 32 of its spacings
            assert abs(g - o) <= 32 * np.spacing(abs(o)), (i, u[i], mc[i])


def test_arguments_at_multiples_of_K_raise_no_warning():
    """At the floats nearest to n K, a modulus each, sn rounds to within an ulp of +-1; the root that gives
    cn from sn where sn is small must not warn (invalid value in sqrt) where it is not taken."""
    rng = np.random.default_rng(2028)
    k = np.sqrt(rng.uniform(0.0, 0.999, 3000))
    u = rng.integers(1, 11, k.size) * ell.K(k)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        s, c, d, _ = ell.jacobi(u, k)
    assert np.all(np.isfinite(s) & np.isfinite(c) & np.isfinite(d))


def test_scalar_fast_paths_return_python_floats_and_validate():
    for val in (ell.K(0.5), ell.E(0.5), ell.K(mc=0.75), ell.E(mc=0.75), ell.K(np.float64(0.5)), ell.E(1),
                *ell.jacobi(0.3, 0.5), *ell.jacobi(0.3, mc=1e-6), *ell.jacobi(2, 1), *ell.jacobi(np.float64(0.3), 0.5)):
        assert type(val) is float
    assert ell.K(0.5) == ell.K(np.array([0.5]))[0] and ell.E(mc=0.75) == ell.E(mc=np.array([0.75]))[0]
    # the same algorithm on a float and on an array: libm's and NumPy's sin, cos, atan2 may differ by an ulp,
    # which a few roundings carry to at most 4
    for one, arr in zip(ell.jacobi(0.3, 0.5), ell.jacobi(np.array([0.3]), 0.5)):
        assert one == pytest.approx(float(arr[0]), rel=4 * 2.0**-52, abs=0)
    for bad in (-0.1, 1.5, math.nan, math.inf):
        with pytest.raises(ValueError, match=r"\[0, 1\]|finite"):
            ell.K(bad)
        with pytest.raises(ValueError, match=r"\[0, 1\]|finite"):
            ell.E(mc=bad)
        with pytest.raises(ValueError, match=r"\[0, 1\]|finite"):
            ell.jacobi(0.3, bad)
    with pytest.raises(ValueError, match="u must be finite"):
        ell.jacobi(math.inf, 0.5)
    with pytest.raises(ValueError, match="u must be finite"):
        ell.jacobi(np.array([0.0, math.nan]), 0.5)
    with pytest.raises(ValueError, match="must lie in"):
        ell.E(np.array([0.2, 1.2]))
    # no NaN for valid input, even where SciPy's phase 2^n a u overflows (the digits are gone, not the value)
    for u in (1.7e308, -1e305, np.array([1.7e308, 0.3])):
        for v in (*ell.jacobi(u, 0.5), *ell.jacobi(u, mc=1e-6)):
            assert np.all(np.isfinite(v))


@settings(max_examples=80)
@given(lmc=st.floats(-4.0, 0.0), x=st.floats(-5.0, 5.0))
def test_jacobi_from_mc_to_the_rounding_of_u(lmc, x):
    """From the exact complementary parameter, 1 - k^2 >= 1e-4: sn, cn to the rounding of the argument
    (|u| eps, times the derivative, <= 1) plus a few ulp, dn to 1e-14 relative. Where 1 - k^2 is small,
    only the period-reduced route with the exact mc meets this: SciPy's ellipj on m = 1 - mc sees mc rounded
    by eps/2 and so a period wrong by ~eps/mc (2e-13 at mc = 1e-4 over five quarter periods)."""
    mc = 10.0**lmc
    u = x * ell.K(mc=mc)
    s, c, d, _ = ell.jacobi(u, mc=mc)
    es, ec, ed = (float(v) for v in _mp_jacobi(u, 1 - mp.mpf(mc)))
    bound = 4 * (1e-16 + abs(u) * 2.2e-16)
    assert abs(s - es) <= bound and abs(c - ec) <= bound
    assert abs(d - ed) <= 1e-14 * ed
