"""Period averages: closed forms in E/K, spectral convergence, separatrix node counts."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rigidbody.core import averaging as avg
from rigidbody.core import elliptic as ell


@settings(max_examples=40)
@given(lmc=st.floats(-10.0, -0.01))
def test_mean_sn2_equals_one_minus_E_over_K(lmc):
    # <sn^2> = (1 - E/K)/k^2 (classical; from the integral of dn^2 = E over a quarter period)
    mc = 10.0**lmc
    m = 1 - mc
    ref = (1 - ell.E(mc=mc) / ell.K(mc=mc)) / m
    got = avg.sn2_average(lambda u: u, 0.0, 1.0, mc=mc)
    # default node count targets 1e-13 relative
    assert got == pytest.approx(ref, rel=1e-13, abs=0)


@settings(max_examples=30)
@given(k=st.floats(0.05, 0.999))
def test_mean_dn_over_4K_is_pi_over_2K(k):
    # <dn> = am(2K)/(2K) = pi/(2K) ; <cn^2> = (E - k'^2 K)/(k^2 K) ; <sn> = 0 over 4K
    KK, EE = ell.K(k), ell.E(k)
    assert avg.jacobi_average(lambda s, c, d: d, k) == pytest.approx(math.pi / (2 * KK), rel=1e-13, abs=0)
    cn2 = (EE - (1 - k * k) * KK) / (k * k * KK)
    assert avg.jacobi_average(lambda s, c, d: c * c, k) == pytest.approx(cn2, rel=1e-12, abs=0)
    assert abs(avg.jacobi_average(lambda s, c, d: s, k)) < 1e-14


def test_spectral_convergence_and_node_count_grows_to_separatrix():
    k = 0.99
    ref = (1 - ell.E(k) / ell.K(k)) / k**2
    errs = [abs(avg.sn2_average(lambda u: u, 0.0, 1.0, k, n=n) - ref) for n in (8, 16, 32)]
    assert errs[1] < errs[0] * 1e-2 and errs[2] < max(errs[1] * 1e-2, 1e-15)  # geometric, not algebraic
    assert avg.n_nodes(mc=1e-10) > avg.n_nodes(0.5) >= 16
    assert avg.n_nodes(mc=1e-10) <= 200  # cheap even at 1 - k^2 = 1e-10


def test_vector_valued_integrand_and_u_range():
    u1, u2, k = -0.3, 0.6, 0.7
    res = avg.sn2_average(lambda u: np.stack([np.ones_like(u), u]), u1, u2, k)
    assert res.shape == (2,)
    assert res[0] == pytest.approx(1.0)
    assert res[1] == pytest.approx(u1 + (u2 - u1) * (1 - ell.E(k) / ell.K(k)) / k**2, rel=1e-13, abs=0)


def test_errors():
    with pytest.raises(ValueError, match="infinite"):
        avg.n_nodes(1.0)
    with pytest.raises(ValueError, match="period"):
        avg.jacobi_average(lambda s, c, d: s, 0.5, period="3K")
    with pytest.raises(ValueError, match="n must"):
        avg.phase_grid(0.5, n=1)


@pytest.mark.parametrize("mc", [0.7, 1e-3, 1e-6, 2e-9, 1e-9, 1e-11])
def test_phase_grid_agrees_with_careful_jacobi(mc):
    # the fast path (raw ellipj for 1 - k^2 >= 1e-3) against the period-reduced evaluation with exact mc;
    # both are accurate to a few ulp in absolute terms there
    s, sn, cn, dn = avg.phase_grid(mc=mc, n=64)
    s2, c2, d2, _ = ell.jacobi(s, mc=mc)
    np.testing.assert_allclose(sn, s2, atol=1e-14)
    np.testing.assert_allclose(cn, c2, atol=1e-14)
    np.testing.assert_allclose(dn, d2, atol=1e-14)


def test_scalar_fast_validation_of_mc():
    with pytest.raises(ValueError, match="mc"):
        avg.phase_grid(mc=1.5)
    with pytest.raises(ValueError, match="mc"):
        avg.phase_grid(mc=float("nan"))
    with pytest.raises(ValueError, match="scalar"):
        avg.n_nodes(np.array([0.1, 0.2]))
    # the same grid whether the modulus comes as k or as mc
    a = avg.phase_grid(0.6, n=16)
    b = avg.phase_grid(mc=1 - 0.36, n=16)
    np.testing.assert_allclose(a[1], b[1], atol=1e-15)


@pytest.mark.parametrize("mc", [0.99, 0.5, 0.36, 0.2, 0.1, 0.03, 1e-2, 1e-3, 1e-4, 1e-6, 1e-8, 1e-10])
def test_default_nodes_reach_1e_13_over_the_whole_range(mc):
    # the contract: default node counts give 1e-13 relative for sn-type averages up to 1 - k^2 = 1e-10,
    # over both periods; references are closed forms in E and K (independent of the quadrature)
    m = 1 - mc
    KK, EE = ell.K(mc=mc), ell.E(mc=mc)
    sn2 = (1 - EE / KK) / m
    cn2 = (EE - mc * KK) / (m * KK)
    for period in ("2K", "4K"):
        assert avg.jacobi_average(lambda s, c, d: s * s, mc=mc, period=period) == pytest.approx(sn2, rel=1e-13, abs=0)
        assert avg.jacobi_average(lambda s, c, d: c * c, mc=mc, period=period) == pytest.approx(cn2, rel=1e-13, abs=0)
        dn2 = avg.jacobi_average(lambda s, c, d: d * d, mc=mc, period=period)
        assert dn2 == pytest.approx(EE / KK, rel=1e-13, abs=0)
    assert avg.jacobi_average(lambda s, c, d: d, mc=mc) == pytest.approx(math.pi / (2 * KK), rel=1e-13, abs=0)
