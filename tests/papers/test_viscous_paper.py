"""Krivtsov (2000), "Description of the motion of an axisymmetric rigid body in a linearly viscous medium
by quasi-coordinates" (PMM): the paper's statements re-run, in the spirit of galpy's test_galpypaper.py.

Numbers: the paper prints no numerical example; its claims are structural (formulas and the three
regimes). Every check is against the full simulation at rtol = 1e-12 (tolerances 1e-10, see
tests/viscous/test_viscous_closed.py for the error budget).
"""

import math

import numpy as np
import pytest

from rigidbody import viscous as vs

N0 = np.array([0.0, 0.6, 0.8])
ND0 = np.array([0.4, 0.0, 0.0])


def test_section2_structure_of_fig1_has_the_torque_11():
    """B12 = β(N a²/2 + 2b²), B3 = β N a² (end of section 2)."""
    body, medium = vs.ball_and_rod(N=6, a=0.8, b=1.3, beta=0.25, mass=1.0)
    assert medium.B12 == pytest.approx(0.25 * (6 * 0.64 / 2 + 2 * 1.69), rel=1e-15, abs=0)
    assert medium.B3 == pytest.approx(0.25 * 6 * 0.64, rel=1e-15, abs=0)


def test_routh_case_13_is_free_motion_with_decaying_speed():
    """B = αθ: K = K0 e^{-αt}; 'the motion is like the motion in vacuum with exponentially decreasing
    angular velocity': n(t) is the torque-free regular precession about K0 at the rate |K0|/θ12 run in
    the time τ = (1 - e^{-αt})/α."""
    body = vs.Body(2.0, 1.0)
    alpha = 0.1
    medium = vs.Medium(alpha * body.theta12, alpha * body.theta3)
    assert vs.regime(body, medium) == "circle"
    Om0 = 1.3
    t = np.linspace(0.0, 40.0, 41)
    sim = vs.simulate(body, medium, N0, ND0, Om0, (0.0, 40.0), t_eval=t)
    K0 = body.theta12 * np.cross(N0, ND0) + body.theta3 * Om0 * N0
    kh = K0 / np.linalg.norm(K0)
    tau = -np.expm1(-alpha * t) / alpha
    ang = np.linalg.norm(K0) / body.theta12 * tau
    free = (N0[:, None] * np.cos(ang) + np.cross(kh, N0)[:, None] * np.sin(ang)
            + (kh @ N0) * kh[:, None] * (1 - np.cos(ang)))
    assert np.max(np.linalg.norm(sim.n - free, axis=0)) < 1e-10


def test_section3_first_integrals_and_omega_squared():
    body, medium = vs.Body(2.0, 1.0), vs.Medium(0.3, 0.1)
    t = np.linspace(0.0, 30.0, 31)
    sim = vs.simulate(body, medium, N0, ND0, 2.0, (0.0, 30.0), t_eval=t)
    assert np.allclose(sim.Omega, 2.0 * np.exp(-0.1 * t), rtol=1e-10, atol=0)
    assert np.allclose(np.linalg.norm(sim.ndot, axis=0), 0.4 * np.exp(-0.15 * t), rtol=1e-10, atol=0)
    assert np.allclose(np.sum(sim.omega**2, axis=0), 0.16 * np.exp(-0.3 * t) + 4 * np.exp(-0.2 * t), rtol=1e-10, atol=0)


@pytest.mark.parametrize(
    ("medium", "reg"),
    [(vs.Medium(0.3, 0.1), "contracting"), (vs.Medium(0.1, 0.1), "unwinding"), (vs.Medium(0.2, 0.1), "circle")],
)
def test_section4_three_conclusions(medium, reg):
    """1. B12/θ12 > B3/θ3: k grows monotonically to ∞, the spiral shrinks to a point (fig. 2);
    2. B12/θ12 < B3/θ3: k → 0, the spiral unwinds towards a great circle (fig. 3);
    3. equality: k = const, a circle."""
    body = vs.Body(2.0, 1.0)
    assert vs.regime(body, medium) == reg
    t = np.linspace(0.0, 300.0, 301)
    k = vs.curvature(body, medium, 2.0, 0.4, t)
    sim = vs.simulate(body, medium, N0, ND0, 2.0, (0.0, 300.0), t_eval=t[[0, 100, 200, 300]])
    assert np.allclose(sim.k, k[[0, 100, 200, 300]], rtol=1e-10)
    dk = np.diff(k)
    if reg == "contracting":
        assert np.all(dk > 0) and k[-1] > 1e6
        # a point: the remaining arc length after t is s_inf - s(t) -> 0, and n(t) converges
        n = vs.axis_path(body, medium, N0, ND0, 2.0, [200.0, 300.0, np.inf])
        assert np.linalg.norm(n[:, 1] - n[:, 2]) < vs.limits(body, medium, 2.0, 0.4)[0] - vs.quasi_coordinates(
            body, medium, 2.0, 0.4, 300.0)[0] + 1e-12
        assert vs.spiral_radius(body, medium, 2.0, 0.4, 300.0) < 1e-6
    elif reg == "unwinding":
        assert np.all(dk < 0) and k[-1] < 1e-6
        assert vs.spiral_radius(body, medium, 2.0, 0.4, 300.0) == pytest.approx(1.0, abs=1e-12)
    else:
        assert np.allclose(k, k[0], rtol=1e-14)


def test_section5_quasi_coordinates_and_solid_angle_theorem():
    """s∞, ξ∞, ζ∞ are the length of the spiral, its total turning and the body's total turn about n
    (relative to parallel transport); over one turn Δφ = χ + Δζ."""
    body, medium = vs.Body(2.0, 1.0), vs.Medium(0.3, 0.1)
    Om0 = 5.0
    s_inf, xi_inf, zeta_inf = vs.limits(body, medium, Om0, 0.4)
    expected = (2.0 * 0.4 / 0.3, 1.0 * Om0 / (2.0 * 0.1), Om0 / 0.1)
    assert (s_inf, xi_inf, zeta_inf) == pytest.approx(expected, rel=1e-15, abs=0)
    sim = vs.simulate(body, medium, N0, ND0, Om0, (0.0, 400.0), t_eval=[400.0])
    assert sim.zeta[-1] == pytest.approx(zeta_inf, rel=1e-10, abs=0)
    tr = vs.turn(body, medium, N0, ND0, Om0, 1.0)
    s2 = vs.simulate(body, medium, N0, ND0, Om0, (0.0, tr.t2), t_eval=[tr.t1, tr.t2])
    dphi = vs.axial_rotation(s2.attitude[:, 0], s2.attitude[:, 1])
    assert abs((dphi - tr.chi - tr.dzeta + math.pi) % (2 * math.pi) - math.pi) < 1e-10
    # "if the turns are dense, χ ≈ 2π(1 - sqrt(1 - R²))": here λT ≈ 0.14, error at mid-turn ≈ 1 %
    assert tr.chi_approx == pytest.approx(tr.chi, rel=0.02, abs=0)
