"""One turn of the spiral: the solid-angle theorem Δφ = χ + Δζ against the simulated attitude, the exact
solid angle χ against an independent polygon computation, and the error of χ ≈ 2π(1 - sqrt(1 - R²))."""

import math

import numpy as np
import pytest

from rigidbody import viscous as vs

BODY = vs.Body(2.0, 1.0)
MEDIA = {
    "contracting": vs.Medium(0.3, 0.1),
    "unwinding": vs.Medium(0.1, 0.1),
    "circle": vs.Medium(0.2, 0.1),
}
N0 = np.array([0.36, 0.48, 0.8])
ND0 = 0.3 * np.array([0.8, -0.6, 0.0])


def wrap(x):
    return (x + math.pi) % (2 * math.pi) - math.pi


@pytest.mark.parametrize("name", list(MEDIA))
@pytest.mark.parametrize(("Omega0", "t1"), [(5.0, 0.0), (5.0, 6.0), (-4.0, 3.0)])
def test_solid_angle_theorem_against_simulated_attitude(name, Omega0, t1):
    """Δφ (from the simulated quaternions, axis carried back along the closing great-circle arc)
    = χ (path geometry) + Δζ (5.1), mod 2π. Both routes at rtol 1e-12: agreement to 1e-10."""
    medium = MEDIA[name]
    tr = vs.turn(BODY, medium, N0, ND0, Omega0, t1)
    assert tr.t2 > tr.t1 == t1
    sim = vs.simulate(BODY, medium, N0, ND0, Omega0, (0.0, tr.t2), t_eval=[t1, tr.t2])
    dphi = vs.axial_rotation(sim.attitude[:, 0], sim.attitude[:, 1])
    assert abs(wrap(dphi - tr.dphi)) < 1e-10
    # the turn closes: n(t2) lies on the meridian from the centre through n(t1)
    n1, n2 = sim.n[:, 0], sim.n[:, 1]
    assert abs(np.cross(tr.centre, n1) @ n2) < 1e-10
    assert np.cross(tr.centre, n1) @ np.cross(tr.centre, n2) > 0
    # sign: chi and the turn of the path have the sign of Omega0 (k > 0: counterclockwise from outside)
    assert math.copysign(1.0, tr.chi) == math.copysign(1.0, Omega0)
    # without the solid angle the theorem would fail by chi (>= 0.01 here)
    assert abs(wrap(dphi - tr.dzeta)) > 1e-2


def polygon_solid_angle(c, pts):
    """Signed solid angle of the closed spherical polygon pts (3, m) as a fan of triangles (c, p_j, p_j+1),
    each by Van Oosterom & Strackee: tan(Ω/2) = a·(b×c)/(1 + a·b + b·c + c·a)."""
    a = pts
    b = np.roll(pts, -1, axis=1)
    cc = c[:, None]
    num = np.sum(cc * np.cross(a, b, axis=0), axis=0)
    den = 1 + np.sum(a * b, axis=0) + np.sum(b * cc, axis=0) + np.sum(cc * a, axis=0)
    return float(np.sum(2 * np.arctan2(num, den)))


@pytest.mark.parametrize("name", ["contracting", "unwinding"])
def test_exact_solid_angle_against_polygon_of_simulated_path(name):
    """χ from the turn's integral against a 4000-gon of simulated axis positions: the polygon misses the
    circular segments, a relative error ~ (k h)^2/12 + (h/R)^2 ~ 1e-6 for h = 2πR/4000; we allow 1e-5."""
    medium = MEDIA[name]
    tr = vs.turn(BODY, medium, N0, ND0, 5.0, 2.0)
    t = np.linspace(tr.t1, tr.t2, 4001)
    sim = vs.simulate(BODY, medium, N0, ND0, 5.0, (0.0, tr.t2), t_eval=t)
    chi_poly = polygon_solid_angle(tr.centre, sim.n)  # closing side n(t2) -> n(t1) is the meridian chord
    assert chi_poly == pytest.approx(tr.chi, rel=1e-5)


def test_circle_solid_angle_is_the_cap_exactly():
    """Routh's circle: the turn closes exactly and χ = 2π(1 - cos ρ) = 2π(1 - sqrt(1 - R²))."""
    tr = vs.turn(BODY, MEDIA["circle"], N0, ND0, 5.0, 1.0)
    assert tr.chi == pytest.approx(tr.chi_approx, rel=1e-11)
    assert tr.R1 == tr.R2 == tr.R_mid
    # closes on itself: the polygon route agrees too
    assert np.linalg.norm(tr.n[:, 0] - tr.n[:, -1]) < 1e-10


@pytest.mark.parametrize("name", ["contracting", "unwinding"])
@pytest.mark.parametrize("Omega0", [5.0, 20.0])
def test_error_of_the_cap_approximation(name, Omega0):
    """The paper's χ ≈ 2π(1 - sqrt(1 - R²)) for a spiral with k ∝ exp(λt): with R at the start (or end)
    of the turn the relative error is first order in λT (the relative change of k over the turn),
    with R at mid-turn second order. Measured (docs/viscous.md): |err_start| ≈ |λT|, |err_mid| ≈ 0.5 (λT)²."""
    medium = MEDIA[name]
    a, b = vs.decay_rates(BODY, medium)
    tr = vs.turn(BODY, medium, N0, ND0, Omega0, 0.0)
    lamT = abs((a - b) * (tr.t2 - tr.t1))
    err_start = abs(tr.chi_approx_start / tr.chi - 1)
    err_end = abs(tr.chi_approx_end / tr.chi - 1)
    err_mid = abs(tr.chi_approx / tr.chi - 1)
    assert 0.5 * lamT < err_start < 1.5 * lamT
    assert 0.5 * lamT < err_end < 1.5 * lamT
    assert err_mid < lamT**2
    # chi lies between the caps at the start and at the end of the turn (R is monotone)
    lo, hi = sorted([tr.chi_approx_start, tr.chi_approx_end])
    assert lo < tr.chi < hi


def test_no_turn_cases_raise():
    medium = MEDIA["contracting"]
    with pytest.raises(ValueError, match="no turn"):
        vs.turn(BODY, medium, N0, ND0, 0.0)
    # total turning xi_inf = theta3^2 Omega0/(theta12 B3) = 5 rad < 2 pi: not even one turn
    with pytest.raises(ValueError, match="no complete turn"):
        vs.turn(BODY, medium, N0, ND0, 1.0)


def test_axial_rotation_rejects_antipodal_axes():
    q1 = np.array([1.0, 0, 0, 0])
    q2 = np.array([0.0, 1, 0, 0])  # 180 degrees about x: z -> -z
    with pytest.raises(ValueError, match="antipodal"):
        vs.axial_rotation(q1, q2)


def test_fast_spiral_needs_the_limit_point_as_centre():
    """λ = 0.49 per unit time, turns slow: the path never circles its initial osculating centre (clear
    error), but it does circle the limit point; the theorem holds for that centre too (1e-10)."""
    body, medium = vs.Body(2.0, 1.0), vs.Medium(1.0, 0.01)
    n0, nd0 = [0.0, 0.0, 1.0], [0.3, 0.0, 0.0]
    with pytest.raises(ValueError, match="no complete turn"):
        vs.turn(body, medium, n0, nd0, 1.0)
    n_inf = vs.axis_path(body, medium, n0, nd0, 1.0, np.inf)[:, 0]
    tr = vs.turn(body, medium, n0, nd0, 1.0, centre=n_inf)
    sim = vs.simulate(body, medium, n0, nd0, 1.0, (0.0, tr.t2), t_eval=[0.0, tr.t2])
    assert abs(wrap(vs.axial_rotation(sim.attitude[:, 0], sim.attitude[:, 1]) - tr.dphi)) < 1e-10
    # here the paper's cap formula is useless (the 'turn' is far from a circle)
    assert abs(tr.chi_approx / tr.chi - 1) > 0.5
    # a faster one converges onto the centre itself: the azimuth is undefined -> clear error
    medium = vs.Medium(3.0, 0.01)
    n_inf = vs.axis_path(body, medium, n0, nd0, 1.0, np.inf)[:, 0]
    with pytest.raises(ValueError, match="reaches the centre"):
        vs.turn(body, medium, n0, nd0, 1.0, centre=n_inf)
    with pytest.raises(ValueError, match="centre must be"):
        vs.turn(body, medium, n0, nd0, 1.0, centre=[0.0, 0.0, 2.0])
