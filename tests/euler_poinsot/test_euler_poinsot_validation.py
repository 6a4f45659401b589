"""Adversarial input for the public functions of rigidbody.euler_poinsot.

Each case used to return a silent number (NaN, a negative ratio, a misclassified state, an empty result)
or a cryptic error from deep inside; it must now be a ValueError/TypeError naming the parameter.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rigidbody import euler_poinsot as ep

BODY = ep.Body(3.2, 2.6, 1.67)
CASE1 = np.diag([2.322, 1.31, 1.425])


@pytest.mark.parametrize(
    ("call", "exc", "match"),
    [
        # kind_of used to call G^2/2T = 0.05 < A3 (no rigid body has it) 'min', and T = 0 divided by zero
        (lambda: ep.kind_of(BODY, 1.0, 10.0), ValueError, r"\[A3, A1\]"),
        (lambda: ep.kind_of(BODY, 1.0, 0.0), ValueError, "positive"),
        (lambda: ep.kind_of(BODY, 0.0, 0.1), ValueError, "positive"),
        # precession_rate: G = 0 was a ZeroDivisionError, G < 0 and k2 = 2 returned numbers
        (lambda: ep.precession_rate(BODY, 0.0, 0.5, 0.3), ValueError, "G must be positive"),
        (lambda: ep.precession_rate(BODY, -1.0, 0.5, 0.3), ValueError, "G must be positive"),
        (lambda: ep.precession_rate(BODY, 1.0, 2.0, 0.3), ValueError, "k2"),
        (lambda: ep.precession_rate(BODY, 1.0, 0.5, math.nan), ValueError, "delta"),
        # spin_ratio returned a negative ratio for G < 0 and numbers for k2 outside [0, 1]
        (lambda: ep.spin_ratio(BODY, 0.01, -1.0, 0.5), ValueError, "G must be positive"),
        (lambda: ep.spin_ratio(BODY, 0.01, 1.0, -1.0), ValueError, "k2"),
        (lambda: ep.spin_ratio(BODY, 0.01, 1.0, 1.5), ValueError, "k2"),
        # averaged_rates returned NaN rates for nu = NaN or omega0 = NaN, "math domain error" for nu = inf
        (lambda: ep.averaged_rates(BODY, CASE1, 1.0, 0.5, 0.3, 0.1, math.nan), ValueError, "nu"),
        (lambda: ep.averaged_rates(BODY, CASE1, 1.0, 0.5, 0.3, 0.1, math.inf), ValueError, "nu"),
        (lambda: ep.averaged_rates(BODY, CASE1, 1.0, 0.5, 0.3, 0.1, 0.2, omega0=math.nan), ValueError, "omega0"),
        (lambda: ep.averaged_rates(BODY, CASE1, 1.0, 0.5, 0.3, 0.1, 0.2, omega0=-1.0), ValueError, "omega0"),
        # a non-Body was an AttributeError
        (lambda: ep.chi((3.2, 2.6, 1.67), CASE1), TypeError, "Body"),
        (lambda: ep.T_from(None, 1.0, 0.5), TypeError, "Body"),
        (lambda: ep.k2_from(BODY, "a", 0.18), TypeError, "G"),
        # a grid too coarse to bracket anything silently reported k2 = 0 alone
        (lambda: ep.k2_equilibria(BODY, CASE1, n_grid=2), ValueError, "n_grid"),
        (lambda: ep.k2_equilibria(BODY, CASE1, n_grid=2.5), ValueError, "n_grid"),
        # integrators: tau_eval outside tau_span (or NaN) gave an empty solution with status 0
        (lambda: ep.averaged(BODY, CASE1, 0.0, tau_span=(0, 1), tau_eval=[2, 3]), ValueError, "tau_eval"),
        (lambda: ep.averaged(BODY, CASE1, 0.0, tau_span=(0, 1), tau_eval=[math.nan]), ValueError, "tau_eval"),
        (lambda: ep.simulate(BODY, CASE1, 0.04, k2_0=0.5, tau_span=(0, 0.1), tau_eval=[0.2]), ValueError,
         "tau_eval"),
        # a reversed span ran backwards (G growing) into the 'separatrix' event; a scalar was a len() error
        (lambda: ep.averaged(BODY, CASE1, 0.0, tau_span=(3, 0)), ValueError, "tau_span"),
        (lambda: ep.averaged(BODY, CASE1, 0.0, tau_span=3), ValueError, "tau_span"),
        (lambda: ep.simulate(BODY, CASE1, 0.04, k2_0=0.5, tau_span=(0.05, 0)), ValueError, "tau_span"),
        # delta0 = 5 was accepted and came back as delta = 2 pi - 5 with lambda shifted by pi
        (lambda: ep.averaged(BODY, CASE1, 0.01, delta0=5.0), ValueError, "delta0"),
        (lambda: ep.averaged(BODY, CASE1, 0.0, delta0=-0.1), ValueError, "delta0"),
        # a negative rtol was a scipy UserWarning
        (lambda: ep.averaged(BODY, CASE1, 0.0, rtol=-1.0), ValueError, "rtol"),
        (lambda: ep.simulate(BODY, CASE1, 0.04, k2_0=0.5, atol=-1.0), ValueError, "atol"),
        # the initial phase was reported as 'u'/'psi' from deep inside
        (lambda: ep.simulate(BODY, CASE1, 0.04, k2_0=0.5, u0=math.nan), ValueError, "u0"),
        (lambda: ep.simulate(BODY, CASE1, 0.04, k2_0=0.5, psi0=math.inf), ValueError, "psi0"),
        # a start beyond the separatrix stop named only k2_max
        (lambda: ep.averaged(BODY, CASE1, 0.0, k2_0=1 - 1e-7), ValueError, "k2_0"),
    ],
)
def test_bad_input_is_named(call, exc, match):
    with pytest.raises(exc, match=match):
        call()


def test_boundary_inputs_that_stay_valid():
    # delta0 on the poles and k2 = 0 are legitimate states (not errors)
    for d0 in (0.0, math.pi):
        a = ep.averaged(BODY, CASE1, 0.01, delta0=d0, tau_span=(0, 0.2))
        assert a.status == 0 and np.all(np.isfinite(a.lam))
    a = ep.averaged(BODY, CASE1, 0.0, k2_0=0.0, tau_span=(0, 1))
    assert a.status == 0 and np.all(np.isfinite(a.G))
    # spin_ratio at the separatrix: infinite period -> ratio 0 (the integrators stop there)
    assert ep.spin_ratio(BODY, 0.01, 1.0, 1.0) == 0.0
    assert ep.kind_of(BODY, 1.0, 1.0 / (2 * BODY.A1)) == "max"
    assert ep.kind_of(BODY, 1.0, 1.0 / (2 * BODY.A3)) == "min"
