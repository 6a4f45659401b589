"""The closed-form Euler-Poinsot motion (both kinds) against Euler's equations and equations (1) with L = 0."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

from rigidbody import euler_poinsot as ep

BODY = ep.Body(3.2, 2.6, 1.67)


@settings(max_examples=20, deadline=None)
@given(k2=st.floats(0.0, 0.999), G=st.floats(0.3, 3.0), kind=st.sampled_from(["max", "min"]),
       sigma=st.sampled_from([1, -1]), u0=st.floats(-5.0, 5.0))
def test_closed_form_solves_eulers_equations_and_keeps_G_T(k2, G, kind, sigma, u0):
    m = ep.EulerPoinsot(BODY, G, k2, kind, sigma)
    A1, A2, A3 = BODY.A
    t = np.linspace(0.0, 2.0 * m.period, 9)
    h = 1e-5 * m.period
    w = m.omega(t, u0)
    wd = (m.omega(t + h, u0) - m.omega(t - h, u0)) / (2 * h)
    res = [A1 * wd[0] - (A2 - A3) * w[1] * w[2], A2 * wd[1] - (A3 - A1) * w[2] * w[0],
           A3 * wd[2] - (A1 - A2) * w[0] * w[1]]
    # central differences, h = 1e-5 P: truncation ~ (h/P)^2 (2 pi)^3 |G|/A ~ 1e-8 G
    assert np.abs(res).max() < 1e-7 * G
    g = m.g(t, u0)
    assert np.linalg.norm(g, axis=0) == pytest.approx(G, rel=1e-14, abs=0)
    T = 0.5 * (g * w).sum(0)
    assert T == pytest.approx(m.T, rel=1e-13, abs=0)
    assert ep.k2_from(BODY, G, T[0], kind) == pytest.approx(k2, abs=1e-11)
    assert m.g(t + m.period, u0) == pytest.approx(g, abs=1e-12 * G)


@pytest.mark.parametrize("kind", ["max", "min"])
@pytest.mark.parametrize("k2", [0.05, 0.7, 0.99])
def test_closed_form_angles_solve_equations_1_without_torque(kind, k2):
    G = 1.3
    A1, A2, A3 = BODY.A
    m = ep.EulerPoinsot(BODY, G, k2, kind)

    def f(t, y):  # (1) with L = 0
        th, ph, ps = y
        return [G * math.sin(th) * math.sin(ph) * math.cos(ph) * (1 / A1 - 1 / A2),
                G * math.cos(th) * (1 / A3 - math.sin(ph) ** 2 / A1 - math.cos(ph) ** 2 / A2),
                G * (math.sin(ph) ** 2 / A1 + math.cos(ph) ** 2 / A2)]

    t = np.linspace(0, 1.5 * m.period, 11)
    ps0, th0, ph0 = m.angles(0.0, 0.3, 0.4)
    s = solve_ivp(f, (0, t[-1]), [th0, ph0, ps0], rtol=1e-12, atol=1e-12, t_eval=t, method="DOP853")
    ps, th, ph = m.angles(t, 0.3, 0.4)
    # integrator tolerance 1e-12 over ~ 1.5 periods: errors ~1e-10
    assert s.y[0] == pytest.approx(th, abs=1e-9)
    assert np.abs(np.angle(np.exp(1j * (s.y[1] - ph)))).max() < 1e-9
    assert s.y[2] == pytest.approx(ps, abs=1e-9)


def test_period_limits():
    # k -> 0: harmonic oscillation about the axis, period 2 pi / Omega with the classical Euler frequency
    G = 1.0
    A1, A2, A3 = BODY.A
    m = ep.EulerPoinsot(BODY, G, 0.0)
    w1 = G / A1
    Omega = w1 * math.sqrt((A1 - A2) * (A1 - A3) / (A2 * A3))
    assert m.period == pytest.approx(2 * math.pi / Omega, rel=1e-14, abs=0)
    # the period diverges logarithmically at the separatrix: P ~ 4 ln(4/k') / rate
    m1 = ep.EulerPoinsot(BODY, G, 1 - 1e-12, mc=1e-12)
    assert m1.period == pytest.approx(4 * math.log(4 / 1e-6) / m1.rate, rel=1e-6, abs=0)


def test_separatrix_and_bad_input():
    with pytest.raises(ValueError, match="separatrix"):
        ep.EulerPoinsot(BODY, 1.0, 1.0)
    with pytest.raises(ValueError, match="sigma"):
        ep.EulerPoinsot(BODY, 1.0, 0.5, sigma=0)
    with pytest.raises(TypeError, match="Body"):
        ep.EulerPoinsot((3.2, 2.6, 1.67), 1.0, 0.5)
    m = ep.EulerPoinsot.from_GT(BODY, 1.0, 1.0 / (2 * 2.0))
    assert m.kind == "min"
