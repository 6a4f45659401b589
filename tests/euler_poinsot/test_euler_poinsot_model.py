"""Model, formula (5), chi and the k^2 equation (7)-(8) of Rachinskaya."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rigidbody import euler_poinsot as ep

BODY = ep.Body(3.2, 2.6, 1.67)
CASE1 = np.diag([2.322, 1.31, 1.425])
CASE2 = np.diag([0.919, 5.228, 1.666])


# ---------------------------------------------------------------------------------------------- validation
@pytest.mark.parametrize(
    ("args", "match"),
    [((1.0, 2.0, 0.5), "A1 > A2 > A3"), ((2.0, 2.0, 1.0), "A1 > A2 > A3"), ((3.0, 1.0, 0.5), "triangle"),
     ((2.0, 1.5, -1.0), "A3 must be positive"), ((math.nan, 1.0, 0.5), "finite")],
)
def test_body_rejects_bad_moments(args, match):
    with pytest.raises(ValueError, match=match):
        ep.Body(*args)


def test_body_type_errors():
    with pytest.raises(TypeError, match="A1"):
        ep.Body("3", 2.0, 1.0)


def test_drag_validation():
    with pytest.raises(ValueError, match="positive definite"):
        ep.Drag(np.diag([1.0, -1.0, 1.0]))
    with pytest.raises(ValueError, match="3x3"):
        ep.Drag(np.ones((2, 2)))
    d = ep.Drag([1.0, 2.0, 3.0])  # diagonal shorthand
    assert d.diag == (1.0, 2.0, 3.0)
    with pytest.raises(ValueError):  # frozen array
        d.I[0, 0] = 5.0


def test_orbit_validation():
    with pytest.raises(ValueError, match="eccentricity"):
        ep.Orbit(1.0)
    assert ep.Orbit().factor(1.3) == 1.0


def test_k2_from_errors():
    G = 1.0
    with pytest.raises(ValueError, match="kind='min'"):
        ep.k2_from(BODY, G, G**2 / (2 * 2.0))  # G^2/2T = 2.0 < A2: rotation about A3
    with pytest.raises(ValueError, match=r"\[A3, A1\]"):
        ep.k2_from(BODY, G, G**2 / (2 * 5.0))
    with pytest.raises(ValueError, match="kind"):
        ep.k2_from(BODY, G, 0.2, kind="middle")


# ---------------------------------------------------------------------------------------------- formula (5)
@settings(max_examples=40, deadline=None)
@given(k2=st.floats(0.0, 1.0), G=st.floats(0.1, 10.0), kind=st.sampled_from(["max", "min"]))
def test_T_from_inverts_k2_from(k2, G, kind):
    T = ep.T_from(BODY, G, k2, kind)
    # rational round trip: a few ulp relative to 1, amplified at most by the conditioning of (5)
    assert ep.k2_from(BODY, G, T, kind) == pytest.approx(k2, abs=1e-12)
    got = ep.kind_of(BODY, G, T)
    if got not in (kind, "separatrix"):
        # kind_of compares G^2/2T with A2 exactly; at k2 = 1 (T on the separatrix) T's rounding may fall an ulp on
        # the other side. That is the only way to get the other kind, and that kind then reads k2 = 1 as well
        assert k2 > 1.0 - 1e-12 and ep.k2_from(BODY, G, T, got) == pytest.approx(1.0, abs=1e-12)


def test_k2_limits_are_the_pure_rotations_and_the_separatrix():
    A1, A2, A3 = BODY.A1, BODY.A2, BODY.A3
    G = 1.7
    assert ep.T_from(BODY, G, 0.0, "max") == pytest.approx(G**2 / (2 * A1), rel=1e-15, abs=0)
    assert ep.T_from(BODY, G, 0.0, "min") == pytest.approx(G**2 / (2 * A3), rel=1e-15, abs=0)
    assert ep.T_from(BODY, G, 1.0, "max") == pytest.approx(G**2 / (2 * A2), rel=1e-15, abs=0)
    assert ep.T_from(BODY, G, 1.0, "min") == pytest.approx(G**2 / (2 * A2), rel=1e-15, abs=0)


# ---------------------------------------------------------------------------------------------- chi (7)
def test_chi_values_of_the_two_drag_cases():
    # direct arithmetic of (7) by hand (independent of the module's code path):
    A1, A2, A3 = 3.2, 2.6, 1.67
    for Ivals, printed in (((2.322, 1.31, 1.425), -4.477), ((0.919, 5.228, 1.666), 3.853)):
        I11, I22, I33 = Ivals
        hand = (2 * I22 * A1 * A3 - I11 * A2 * A3 - I33 * A1 * A2) / ((I33 * A1 - I11 * A3) * A2)
        val = ep.chi(BODY, np.diag(Ivals))
        assert val == pytest.approx(hand, rel=1e-14, abs=0)
        # printed to 3 decimals; the second case agrees to its last printed digit, the first differs by
        # 0.0027 (documented in docs/euler_poinsot.md: inside the rounding box of the printed I's)
        assert abs(val - printed) < 3e-3
    assert ep.chi(BODY, CASE1) == pytest.approx(-4.4743, abs=5e-5)
    assert ep.chi(BODY, CASE2) == pytest.approx(3.8523, abs=5e-5)


def test_printed_chi_case1_lies_within_the_rounding_of_the_printed_drag_coefficients():
    # chi is sensitive: its denominator I33 A1 - I11 A3 = 0.682 is a difference of 4.56 and 3.88.
    # Scan the box of I's that round to the printed 3 decimals: -4.477 must be attainable.
    grid = np.linspace(-5e-4, 5e-4, 11)
    vals = [ep.chi(BODY, np.diag([2.322 + a, 1.31 + b, 1.425 + c])) for a in grid for b in grid for c in grid]
    assert min(vals) < -4.477 < max(vals)
    assert min(vals) < ep.chi(BODY, CASE1) < max(vals)


def test_chi_from_the_k2_equation_is_the_printed_definition():
    # Independent route: dk2/dt from the chain rule of (5) along (6) is linear in chi,
    # dk2/dt = (1/N)[(1 - k2 - E/K) - chi (1 - k2 + k2 E/K ... )]; solve for chi at one k2.
    from rigidbody.core import elliptic as ell

    for I in (CASE1, CASE2):
        k2 = 0.37
        A1, A3 = BODY.A1, BODY.A3
        G = 1.0
        T = ep.T_from(BODY, G, k2)
        dG, dT = ep.drag_rates(BODY, I, G, k2)
        h = 1e-6
        dk2 = (ep.k2_from(BODY, G + h * dG, T + h * dT) - ep.k2_from(BODY, G - h * dG, T - h * dT)) / (2 * h)
        ek = ell.E(math.sqrt(k2)) / ell.K(math.sqrt(k2))
        invN = (I[2, 2] * A1 - I[0, 0] * A3) / (A1 * A3)
        # dk2 / invN = (1 - chi)(1 - k2) - [(1 - chi) + (1 + chi) k2] ek  ->  solve the linear equation
        a = (1 - k2) - ek - k2 * ek
        b = -(1 - k2) + ek - k2 * ek
        chi_num = (dk2 / invN - a) / b
        # central difference of a rational function, h = 1e-6: truncation ~1e-12, rounding ~1e-10
        assert chi_num == pytest.approx(ep.chi(BODY, I), rel=1e-7, abs=0)


def test_chi_undefined_raises():
    I = np.diag([BODY.A1, 1.0, BODY.A3])  # I33 A1 == I11 A3
    with pytest.raises(ValueError, match="undefined"):
        ep.chi(BODY, I)
    ep.dk2_dtau(BODY, I, 0.5)  # the k2 equation itself stays finite


# ---------------------------------------------------------------------------------------------- (8) vs (5)+(6)
@settings(max_examples=40, deadline=None)
@given(
    k2=st.floats(1e-3, 0.999),
    G=st.floats(0.1, 5.0),
    d=st.lists(st.floats(0.1, 5.0), min_size=3, max_size=3),
    kind=st.sampled_from(["max", "min"]),
)
def test_dk2_equals_chain_rule_of_5_along_6(k2, G, d, kind):
    I = np.diag(d)
    T = ep.T_from(BODY, G, k2, kind)
    dG, dT = ep.drag_rates(BODY, I, G, k2, kind)
    # exact chain rule of (5): k2 = c (A1 - D)/(D - A3), D = G^2/2T (labels 1<->3 for 'min')
    A1, A2, A3 = (BODY.A1, BODY.A2, BODY.A3) if kind == "max" else (BODY.A3, BODY.A2, BODY.A1)
    D = G**2 / (2 * T)
    dD = G * dG / T - G**2 * dT / (2 * T**2)
    c = (A2 - A3) / (A1 - A2)
    dk2 = c * (-(D - A3) - (A1 - D)) / (D - A3) ** 2 * dD
    # cancellation in dD = G dG/T - ...: relative error ~1e-13 of the terms (each O(|I| G^2/A))
    scale = max(d) / BODY.A3
    assert ep.dk2_dtau(BODY, I, k2, kind) == pytest.approx(dk2, abs=1e-11 * scale)


def test_dk2_printed_chi_form_matches():
    from rigidbody.core import elliptic as ell

    for I in (CASE1, CASE2):
        x = ep.chi(BODY, I)
        invN = 1.0 / ep.N_time(BODY, I)
        for k2 in (0.05, 0.5, 0.95):
            ek = ell.E(math.sqrt(k2)) / ell.K(math.sqrt(k2))
            printed = invN * ((1 - x) * (1 - k2) - ((1 - x) + (1 + x) * k2) * ek)
            assert ep.dk2_dtau(BODY, I, k2) == pytest.approx(printed, rel=1e-12, abs=1e-15)


def test_dk2_small_k_series_and_separatrix_limit():
    # near k2 = 0: dk2 = (1/N)(-3 - chi)/2 k2 + O(k2^2) — no 0/0 in the implementation
    for I in (CASE1, CASE2):
        slope = (-3 - ep.chi(BODY, I)) / 2 / ep.N_time(BODY, I)
        for k2 in (1e-6, 1e-10, 1e-14):
            assert ep.dk2_dtau(BODY, I, k2) / k2 == pytest.approx(slope, rel=10 * k2 + 1e-9, abs=0)
        assert ep.dk2_dtau(BODY, I, 0.0) == 0.0
        # at the separatrix the right-hand side tends to 0 like -2 (I33/A3 - I11/A1) E/K, E/K ~ 1/ln(4/k')
        assert ep.dk2_dtau(BODY, I, 1.0) == 0.0
        assert np.isfinite(ep.dk2_dtau(BODY, I, 1 - 1e-15))


# ---------------------------------------------------------------------------------------------- equilibria
def test_k2_equilibria_of_the_two_cases():
    eq1 = ep.k2_equilibria(BODY, CASE1)
    eq2 = ep.k2_equilibria(BODY, CASE2)
    # case 1: chi = -4.47 < -3 -> k2 = 0 unstable, one interior stable equilibrium
    assert eq1[0] == (0.0, "unstable")
    assert len(eq1) == 2 and eq1[1][1] == "stable" and 0 < eq1[1][0] < 1
    assert ep.dk2_dtau(BODY, CASE1, eq1[1][0]) == pytest.approx(0.0, abs=1e-13)
    # case 2: chi = 3.85 > -3 -> k2 = 0 stable, no interior root; near k2 = 1 the sign is that of
    # -(I33/A3 - I11/A1) < 0: every k2 in (0, 1) decreases to 0
    assert eq2 == [(0.0, "stable")]
    assert all(ep.dk2_dtau(BODY, CASE2, x) < 0 for x in np.linspace(0.01, 0.999, 50))


def test_k2_to_separatrix_when_I11_over_A1_exceeds_I33_over_A3():
    I = np.diag([3.0, 1.0, 0.5])  # I11/A1 = 0.94 > I33/A3 = 0.30
    assert ep.dk2_dtau(BODY, I, 0.999) > 0
    sol = ep.averaged(BODY, I, 0.0, k2_0=0.9, tau_span=(0, 50))
    assert sol.status == 1 and sol.event == "separatrix"
    assert "separatrix" in sol.message
    assert sol.k2[-1] == pytest.approx(1 - 1e-6, abs=1e-9)


def test_equilibrium_stability_by_integration():
    # the labels of k2_equilibria against trajectories of (8) (eps = 0 averaged system)
    kstar = ep.k2_equilibria(BODY, CASE1)[1][0]
    up = ep.averaged(BODY, CASE1, 0.0, k2_0=1e-6, tau_span=(0, 400), tau_eval=[400])
    assert up.k2[-1] == pytest.approx(kstar, abs=1e-6)  # k2 = 0 unstable, k* attracts from below
    down = ep.averaged(BODY, CASE2, 0.0, k2_0=0.05, tau_span=(0, 20), tau_eval=[20])
    assert down.k2[-1] < 1e-8  # case 2: k2 = 0 attracts


def test_start_next_to_the_separatrix():
    # k2 within 1e-8 of the separatrix: logarithmic period, finite right-hand sides, k2 moves away (case 1)
    sol = ep.averaged(BODY, CASE1, 0.0, k2_0=1 - 1e-8, k2_max=1 - 1e-10, tau_span=(0, 0.1))
    assert sol.status == 0 and np.all(np.diff(sol.k2) < 0) and np.all(np.isfinite(sol.lam))


@pytest.mark.parametrize("kind", ["max", "min"])
@pytest.mark.parametrize("k2", [0.0, 0.3, 0.99])
def test_spin_ratio_is_the_Euler_Poinsot_frequency_over_the_orbital_rate(kind, k2):
    # independent route: the period of the closed-form motion (tested against Euler's equations and the
    # classical k -> 0 frequency in test_euler_poinsot_motion.py); same elliptic K, rounding only
    G, eps = 1.3, 0.01
    P = ep.EulerPoinsot(BODY, G, k2, kind).period
    assert ep.spin_ratio(BODY, eps, G, k2, kind) == pytest.approx(2 * math.pi / P / eps, rel=1e-12, abs=0)
    # the number the docs quote for the paper's start: 2 pi / P = 0.052 at G = 1, k2 = 0.99
    if kind == "max" and k2 == 0.99:
        assert ep.spin_ratio(BODY, 1.0, 1.0, 0.99) == pytest.approx(0.0528, abs=5e-4)
