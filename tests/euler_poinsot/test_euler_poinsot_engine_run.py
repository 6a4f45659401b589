"""The averaged evolution of a torque object: its coordinates (ln G, ln k2 and the direction of G in two charts),
what rtol means there, the direction through the poles, and the rotation number of the resonance check -- each
against an independent route (exact solutions, the spectral mean of the motion, the drag tensor's closed forms)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation
from scipy.special import ellipk

from rigidbody import euler_poinsot as ep
from rigidbody.euler_poinsot._segment import rotation_number

BODY = ep.Body(3.2, 2.6, 1.67)
CASE1 = np.diag([2.322, 1.31, 1.425])
RTOL = 1e-10


def _rel(a, b):
    return float(np.max(np.abs(np.asarray(a) / np.asarray(b) - 1.0)))


@pytest.mark.parametrize("kind", ["max", "min"])
def test_rotation_number_in_closed_form_equals_the_spectral_mean(kind):
    # rho = <dpsi/dt> P / 2 pi from the complete elliptic integral of the third kind (derived in its docstring)
    # against the spectral mean of dpsi/dt over the closed-form motion (EulerPoinsot.psi_rate_mean, trapezoid rule
    # converged to ~1e-13): they agree to rounding over the whole range, vectorised and one by one
    k2 = np.array([0.0, 1e-8, 0.1, 0.5, 0.9, 0.99, 1.0 - 1e-6])
    spectral = np.array([ep.EulerPoinsot(BODY, 1.7, float(x), kind).psi_rate_mean()
                         * ep.EulerPoinsot(BODY, 1.7, float(x), kind).period / (2.0 * math.pi) for x in k2])
    assert rotation_number(BODY, kind, k2) == pytest.approx(spectral, rel=1e-13, abs=0)
    assert rotation_number(BODY, kind, 0.3) == pytest.approx(
        ep.EulerPoinsot(BODY, 1.0, 0.3, kind).psi_rate_mean() * ep.EulerPoinsot(BODY, 1.0, 0.3, kind).period
        / (2.0 * math.pi), rel=1e-13, abs=0)


def _vertical(c):
    """A torque constant in the orbital axes, c along the orbit normal x3 (body components C^T c e3): symmetric about
    x3. Exact averaged motion: d(G n)/dtau = c e3, dT/dtau = c <C omega>.e3 = (2T/G) c n3, so T/G^2 and k2 stay
    constant while G n = G0 n0 + c tau e3 (lambda constant)."""
    def torque(omega, C, nu):
        return c * np.asarray(C)[..., 2, :]
    return torque


@pytest.mark.parametrize("averaging", ["auto", "numerical"])
@pytest.mark.parametrize("c, delta0, tau1", [
    (3.0, 0.6, 3.0),  # from mid-latitudes into the north pole: the angles, then the unit vector near the pole
    (-0.5, 0.05, 4.0),  # from next to the north pole across the equator to the south: vector, angles, vector
])
def test_the_direction_of_G_through_the_chart_switches(averaging, c, delta0, tau1):
    lam0 = 0.4
    te = np.linspace(0.0, tau1, 41)
    sol = ep.averaged(BODY, _vertical(c), 0.0, 1.0, 0.6, delta0, lam0, (0.0, tau1), te, averaging=averaging)
    assert sol.status == 0, sol.message
    n0 = np.array([math.sin(delta0) * math.cos(lam0), math.sin(delta0) * math.sin(lam0), math.cos(delta0)])
    g = n0[:, None] + c * te[None, :] * np.array([0.0, 0.0, 1.0])[:, None]
    G = np.linalg.norm(g, axis=0)
    # the integrator's global error (rtol 1e-10 relative in G, the angles to rtol/10 per step over ~30 steps) and,
    # with the engine, its quadrature error (1e-12 relative to the torque)
    assert _rel(sol.G, G) < 10 * RTOL
    assert np.abs(sol.n - g / G).max() < 10 * RTOL
    assert sol.k2 == pytest.approx(0.6, rel=10 * RTOL, abs=0)
    assert np.abs(sol.lam - lam0).max() < 10 * RTOL  # lambda is continuous and constant through the switches
    # the run did get near a pole (sin(delta) < 0.1 switches to the unit vector)
    assert math.sin(sol.delta.min()) < 0.06 or math.sin(sol.delta.max()) < 0.06


def test_a_field_fixed_in_space_turns_G_about_it_through_many_turns():
    # MagneticDipole with a constant field: G precesses about B at the rate a1 <omega1> m1 |B| / G^2 (the closed
    # form of its docstring: <omega1> = sigma c_dn pi/(2K)) with G, T, k2 constant; exact solution a rotation of n0
    # about B. The path passes near the pole x3 (delta0 = 0: it starts on it) six times.
    B, m1, k2, G0 = np.array([1.0, 0.3, 0.0]), 2.5, 0.5, 1.3
    tq = ep.MagneticDipole([m1, 0.1, -0.2], B)
    te = np.linspace(0.0, 24.0, 241)
    sol = ep.averaged(BODY, tq, 0.0, G0, k2, 0.0, 0.4, (0.0, 24.0), te, averaging="numerical")
    assert sol.status == 0
    A1, A2, A3 = BODY.A1, BODY.A2, BODY.A3
    R = A1 * (A2 - A3) + A3 * (A1 - A2) * k2
    w1 = G0 * math.sqrt((A2 - A3) / (A1 * R)) * math.pi / (2.0 * ellipk(k2))
    rate = A1 * w1 * m1 * np.linalg.norm(B) / G0**2
    rot = Rotation.from_rotvec(-np.outer(te * rate, B / np.linalg.norm(B)))
    n_exact = rot.apply(np.array([0.0, 0.0, 1.0])).T
    assert rate * 24.0 > 5 * 2 * math.pi
    # rtol 1e-10 relative per step over ~40 steps per turn, 5 turns; quadrature error 1e-12
    assert np.abs(sol.n - n_exact).max() < 1e-7
    assert _rel(sol.G, G0) < 10 * RTOL and sol.k2 == pytest.approx(k2, rel=10 * RTOL, abs=0)


def test_the_engine_below_its_relative_accuracy_of_dk2_keeps_an_absolute_one():
    # The engine's dk2 is O(k^2) while its zero-mean O(k) products carry rounding ~eps_mach k: relative noise
    # ~eps_mach/k, which ln k2 as a coordinate would turn into a right-hand side too noisy to step through (the run
    # took 1.5e5 steps to tau = 16 before ln(k2 + c)). Paper case 2, where k2 falls by 21 orders by tau = 20: the run
    # ends in a few hundred steps, k2 relatively accurate where it exceeds c = 1.2e-10 and absolutely to c rtol
    # below; against the drag tensor's closed forms (an independent integration in ln k2 of the printed (8))
    case2 = np.diag([0.919, 5.228, 1.666])
    te = np.linspace(0.0, 20.0, 41)
    ref = ep.averaged(BODY, case2, 0.0, 1.0, 0.5, 0.8, 0.3, (0.0, 20.0), te, rtol=1e-12)
    tq = ep.LinearDrag(case2) + ep.GravityGradient(BODY)
    sol = ep.averaged(BODY, tq, 0.0, 1.0, 0.5, 0.8, 0.3, (0.0, 20.0), te, averaging="numerical")
    assert sol.status == 0 and sol.nfev < 3000
    above = ref.k2 > 1e-8
    assert ref.k2[-1] < 1e-20 and above.sum() > 10
    assert _rel(sol.k2[above], ref.k2[above]) < 10 * RTOL
    assert np.abs(sol.k2 - ref.k2)[~above].max() < 10 * RTOL * (1e-8 + 1.2e-10)
    assert _rel(sol.G, ref.G) < 10 * RTOL
