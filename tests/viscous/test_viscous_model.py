"""Body/Medium validation and the ball-and-rod model (section 2, fig. 1) against direct sums."""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from rigidbody import viscous as vs


def structure(N, a, b, R):
    """Ball positions for axis n = R e3: N on the circle of radius a, two on the axis at ±b."""
    ang = 2 * np.pi * np.arange(N) / N + 0.37
    ring = np.stack([a * np.cos(ang), a * np.sin(ang), np.zeros(N)], axis=1)
    axis = np.array([[0, 0, b], [0, 0, -b]])
    return np.vstack([ring, axis]) @ R.T, R[:, 2]


@given(
    N=st.integers(3, 9),
    a=st.floats(0.1, 3.0),
    b=st.floats(0.0, 3.0),
    beta=st.floats(0.01, 2.0),
    seed=st.integers(0, 2**31 - 1),
)
def test_ball_model_torque_is_the_direct_sum_over_the_balls(N, a, b, beta, seed):
    """M = -β Σ r×(v_C + ω×r) (2.1) for random orientation, ω and v_C equals -B·ω with the B of section 2."""
    rng = np.random.default_rng(seed)
    R = Rotation.random(random_state=rng).as_matrix()
    r, n = structure(N, a, b, R)
    omega = rng.normal(size=3)
    vC = rng.normal(size=3)
    v = vC[None, :] + np.cross(omega[None, :], r)
    M = -beta * np.sum(np.cross(r, v), axis=0)
    body, medium = vs.ball_and_rod(N=N, a=a, b=b, beta=beta, mass=1.0)
    B = medium.B12 * (np.eye(3) - np.outer(n, n)) + medium.B3 * np.outer(n, n)
    # rounding of sums of O(10) terms of size beta (a^2 + b^2) |omega|
    assert np.allclose(M, -B @ omega, rtol=1e-12, atol=1e-12 * beta * (a * a + b * b + 1) * N * np.linalg.norm(omega))


@given(
    N=st.integers(3, 8),
    a=st.floats(0.1, 3.0),
    b=st.floats(0.0, 3.0),
    m=st.floats(0.1, 5.0),
    rb_frac=st.floats(0.0, 1.0),
    m_rod=st.floats(0.0, 3.0),
    m_spoke=st.floats(0.0, 3.0),
    seed=st.integers(0, 2**31 - 1),
)
def test_ball_model_inertia_is_the_direct_sum(N, a, b, m, rb_frac, m_rod, m_spoke, seed):
    """θ = Σ m (r²E - rr) + own inertia of the balls + thin rod and spokes integrated by Gauss-Legendre
    (exact for the quadratic integrands), at a random orientation."""
    rng = np.random.default_rng(seed)
    R = Rotation.random(random_state=rng).as_matrix()
    r, n = structure(N, a, b, R)
    # balls up to touching: half the smallest distance between two ball centres of the structure
    rb = rb_frac * 0.5 * min(np.linalg.norm(x - y) for i, x in enumerate(r) for y in r[:i])
    E = np.eye(3)
    J = sum(m * (x @ x * E - np.outer(x, x)) for x in r) + (N + 2) * 0.4 * m * rb**2 * E
    x, w = np.polynomial.legendre.leggauss(4)
    for xi, wi in zip(x, w):  # rod from -b n to b n, density m_rod/(2b)
        p = xi * b * n
        J = J + m_rod * wi / 2 * (p @ p * E - np.outer(p, p))
    for rk in r[:N]:  # spokes from C to each ring ball
        for xi, wi in zip(x, w):
            p = (xi + 1) / 2 * rk
            J = J + m_spoke * wi / 2 * (p @ p * E - np.outer(p, p))
    body, _ = vs.ball_and_rod(N=N, a=a, b=b, beta=1.0, mass=m, ball_radius=rb, rod_mass=m_rod, spoke_mass=m_spoke)
    theta = body.theta12 * (E - np.outer(n, n)) + body.theta3 * np.outer(n, n)
    # 4-point Gauss is exact for the quadratic rod integrands: only rounding of O(30) terms remains
    assert np.allclose(J, theta, rtol=1e-12, atol=1e-12 * np.max(np.abs(theta)))


def test_ball_model_regimes():
    """Point balls: B = (β/m)θ, Routh's circle. With ball radius: contracting iff b² > N a²/4."""
    assert vs.regime(*vs.ball_and_rod(N=4, a=1.0, b=0.5, beta=0.1, mass=1.0)) == "circle"
    assert vs.regime(*vs.ball_and_rod(N=4, a=1.0, b=1.5, beta=0.1, mass=1.0, ball_radius=0.1)) == "contracting"
    assert vs.regime(*vs.ball_and_rod(N=4, a=1.0, b=0.5, beta=0.1, mass=1.0, ball_radius=0.1)) == "unwinding"
    assert vs.regime(*vs.ball_and_rod(N=4, a=1.0, b=1.0, beta=0.1, mass=1.0, ball_radius=0.1)) == "circle"
    # rod mass: inertia without drag about the equatorial axes -> B12/theta12 drops -> unwinding
    assert vs.regime(*vs.ball_and_rod(N=4, a=1.0, b=0.5, beta=0.1, mass=1.0, rod_mass=1.0)) == "unwinding"


def test_ball_model_printed_example():
    body, medium = vs.ball_and_rod(N=4, a=1.0, b=0.5, beta=0.1, mass=1.0)
    assert medium.B12 == pytest.approx(0.1 * (4 / 2 + 2 * 0.25))
    assert medium.B3 == pytest.approx(0.4)
    assert (body.theta12, body.theta3) == pytest.approx((2.5, 4.0))


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"N": 2}, "N must be >= 3"),
        ({"a": 0.0}, "a must be"),
        ({"b": -1.0}, "b must be"),
        ({"beta": -0.1}, "beta must be"),
        ({"mass": 0.0}, "mass must be"),
        ({"ball_radius": -0.1}, "ball_radius"),
        ({"rod_mass": math.nan}, "rod_mass"),
    ],
)
def test_ball_model_bad_input(kwargs, match):
    with pytest.raises(ValueError, match=match):
        vs.ball_and_rod(**kwargs)
    with pytest.raises(TypeError, match="N must be an int"):
        vs.ball_and_rod(N=4.0)


def test_body_and_medium_validation():
    with pytest.raises(ValueError, match="theta12"):
        vs.Body(-1.0, 1.0)
    with pytest.raises(ValueError, match="theta3"):
        vs.Body(1.0, 0.0)
    with pytest.raises(ValueError, match="triangle"):
        vs.Body(1.0, 2.5)
    vs.Body(1.0, 2.0)  # flat body (disc): allowed
    with pytest.raises(ValueError, match="B12"):
        vs.Medium(0.0, 1.0)
    with pytest.raises(ValueError, match="B3"):
        vs.Medium(1.0, math.inf)
    with pytest.raises(TypeError, match="theta12"):
        vs.Body("2", 1.0)
    with pytest.raises(TypeError, match="body"):
        vs.regime(vs.Medium(1.0, 1.0), vs.Medium(1.0, 1.0))
    b = vs.Body(np.float64(2.0), 1)
    assert isinstance(b.theta12, float) and isinstance(b.theta3, float)
    with pytest.raises(AttributeError):
        b.theta12 = 3.0  # frozen


def test_regime_tolerance():
    body = vs.Body(2.0, 1.0)
    assert vs.regime(body, vs.Medium(0.2 * (1 + 1e-14), 0.1)) == "circle"
    assert vs.regime(body, vs.Medium(0.2 * (1 + 1e-9), 0.1)) == "contracting"
    assert vs.regime(body, vs.Medium(0.2 * (1 + 1e-9), 0.1), rtol=1e-6) == "circle"
    with pytest.raises(ValueError, match="rtol"):
        vs.regime(body, vs.Medium(0.2, 0.1), rtol=-1.0)


def test_state_validation():
    body, medium = vs.Body(2.0, 1.0), vs.Medium(0.3, 0.1)
    n0 = np.array([0.0, 0.0, 1.0])
    with pytest.raises(ValueError, match="unit vector"):
        vs.simulate(body, medium, 2 * n0, [0.1, 0, 0], 1.0, (0, 1))
    with pytest.raises(ValueError, match="perpendicular"):
        vs.axis_path(body, medium, n0, [0.1, 0, 0.1], 1.0, [0.0, 1.0])
    with pytest.raises(ValueError, match="3-vector"):
        vs.simulate(body, medium, [0, 1], [0.1, 0, 0], 1.0, (0, 1))
    with pytest.raises(ValueError, match="t_eval"):
        vs.axis_path(body, medium, n0, [0.1, 0, 0], 1.0, [-1.0])
    with pytest.raises(ValueError, match="t must be >= 0"):
        vs.curvature(body, medium, 1.0, 0.3, -1.0)
    with pytest.raises(ValueError, match="v0"):
        vs.v(body, medium, -0.3, 1.0)
    with pytest.raises(ValueError, match="formulation"):
        vs.simulate(body, medium, n0, [0.1, 0, 0], 1.0, (0, 1), formulation="euler")
    with pytest.raises(ValueError, match="attitude0"):
        vs.simulate(body, medium, n0, [0.1, 0, 0], 1.0, (0, 1), attitude0=[0.0, 1.0, 0.0, 0.0])
    with pytest.raises(TypeError, match="Omega0"):
        vs.simulate(body, medium, n0, [0.1, 0, 0], "x", (0, 1))


def test_attitude0_sets_the_body_axes():
    """A user attitude (body z on n0) changes only the body x reference: n(t) is the same; the body
    turn about n differs by a constant."""
    body, medium = vs.Body(2.0, 1.0), vs.Medium(0.3, 0.1)
    n0 = np.array([0.0, 0.0, 1.0])
    q = np.array([math.cos(0.3), 0.0, 0.0, math.sin(0.3)])  # 0.6 rad about z
    t = np.linspace(0, 10, 11)
    a = vs.simulate(body, medium, n0, [0.3, 0, 0], 2.0, (0, 10), t_eval=t)
    b = vs.simulate(body, medium, n0, [0.3, 0, 0], 2.0, (0, 10), t_eval=t, attitude0=q)
    # same dynamics, different initial body axes: differ only by the rtol=1e-12 integration error
    assert np.max(np.abs(a.n - b.n)) < 1e-11
    assert np.max(np.abs(a.omega - b.omega)) < 1e-11


def test_more_bad_input_names_the_parameter():
    """Adversarial input found in review: each raises naming the parameter (no cryptic numpy error,
    no RuntimeWarning, no silent acceptance of a bool as a number)."""
    body, medium = vs.Body(2.0, 1.0), vs.Medium(0.3, 0.1)
    n0, nd0 = np.array([0.0, 0.0, 1.0]), np.array([0.3, 0.0, 0.0])
    with pytest.raises(TypeError, match="Omega0"):
        vs.curvature(body, medium, True, 0.3, 1.0)
    with pytest.raises(TypeError, match="Omega0"):
        vs.simulate(body, medium, n0, nd0, True, (0, 1))
    with pytest.raises(TypeError, match="v0"):
        vs.v(body, medium, "0.3", 1.0)
    with pytest.raises(TypeError, match="t must be"):
        vs.curvature(body, medium, 1.0, 0.3, "a")
    with pytest.raises(TypeError, match="b must be"):
        vs.ball_and_rod(b=True)
    with pytest.raises(TypeError, match="rod_mass"):
        vs.ball_and_rod(rod_mass="1")
    with pytest.raises(ValueError, match="t1 must be finite and >= 0"):
        vs.turn(body, medium, n0, nd0, 5.0, -1.0)
    with pytest.raises(ValueError, match="samples"):
        vs.turn(body, medium, n0, nd0, 5.0, samples=0)
    with pytest.raises(ValueError, match="samples"):
        vs.turn(body, medium, n0, nd0, 5.0, samples=1.5)
    with pytest.raises(ValueError, match="q1 must be a unit quaternion"):
        vs.axial_rotation([0.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="q2 must be a finite"):
        vs.axial_rotation([1.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0])
    # 0-d arrays are numbers
    assert vs.curvature(body, medium, np.array(1.0), np.array(0.3), 0.0) == pytest.approx(1.0 / 2.0 / 0.3)
    # absurdly large rates saturate to inf without a RuntimeWarning (strict pytest turns it into an error),
    # and v = 0 gives F4 = 0 even when (θ3 Ω/θ12)² overflows (no 0·inf = NaN)
    assert vs.F4(body, medium, 1e200, 1e200, 1.0) == math.inf
    assert vs.F4(body, medium, 1e200, 0.0, 1.0) == 0.0
    assert vs.omega2(body, medium, 1e200, 1e200, 1.0) == math.inf


def test_ndot0_perpendicularity_tolerance_is_relative_to_the_rates():
    """n0·ndot0 is tolerated only up to 1e-10 max(|ndot0|, |Omega0|) (rounding of ndot0 = ω0×n0) — a
    criterion independent of the unit of time. Before the review it was 1e-10 max(|ndot0|, 1): in slow
    units (rates ~1e-6) a component along n0 of 1e-4 relative was silently projected away."""
    body, medium = vs.Body(2.0, 1.0), vs.Medium(0.3, 0.1)
    n0 = np.array([0.0, 0.0, 1.0])
    with pytest.raises(ValueError, match="perpendicular"):
        vs.axis_path(body, medium, n0, [1e-6, 0.0, 1e-10], 1e-6, [0.0, 1.0])
    # rounding-level along-component of ω0×n0 is accepted and removed (|along| / |ω0| ~ 1e-16)
    rng = np.random.default_rng(0)
    w0 = rng.normal(size=3) * 1e-6
    m = rng.normal(size=3)
    m /= np.linalg.norm(m)
    nd = np.cross(w0, m)
    sim = vs.simulate(body, medium, m, nd, float(w0 @ m), (0.0, 1.0), t_eval=[0.0])
    assert abs(sim.ndot[:, 0] @ sim.n[:, 0]) < 1e-20


@pytest.mark.parametrize("b", [0.5, 0.8, 1.5, 2.0])
def test_rotational_drag_of_finite_balls_reverses_the_verdict(b):
    """Documented caveat (docs/viscous.md): with the Stokes rotational drag (4/3) β r² of each of the N+2
    balls added to B12 and B3 by hand, the ball model contracts iff b² < N a²/4 — the opposite of the
    paper's drag model (force only), for which it contracts iff b² > N a²/4."""
    N, a, beta, r = 4, 1.0, 0.1, 0.1
    body, medium = vs.ball_and_rod(N=N, a=a, b=b, beta=beta, mass=1.0, ball_radius=r)
    paper = "contracting" if b * b > N * a * a / 4 else "unwinding"
    assert vs.regime(body, medium) == paper
    rot = (N + 2) * 4.0 / 3.0 * beta * r * r
    stokes = vs.regime(body, vs.Medium(medium.B12 + rot, medium.B3 + rot))
    assert stokes == ("unwinding" if paper == "contracting" else "contracting")


@pytest.mark.parametrize(("N", "a", "b"), [(3, 1.0, 2.0), (6, 1.0, 2.0), (4, 1.0, 0.2), (4, 0.3, 0.05), (4, 1.0, 0.0)])
def test_ball_and_rod_refuses_overlapping_balls(N, a, b):
    """Solid balls cannot overlap: the radius is bounded by half the smallest distance between two ball
    centres, measured here on the explicit ball positions (independent of the model's formula)."""
    r, _ = structure(N, a, b, np.eye(3))
    half = 0.5 * min(np.linalg.norm(x - y) for i, x in enumerate(r) for y in r[:i])
    if half > 0:
        vs.ball_and_rod(N=N, a=a, b=b, beta=0.1, mass=1.0, ball_radius=half * (1 - 1e-9))  # just apart: fine
    with pytest.raises(ValueError, match=r"ball_radius .* overlap"):
        vs.ball_and_rod(N=N, a=a, b=b, beta=0.1, mass=1.0, ball_radius=half * (1 + 1e-9) + 1e-300)


@pytest.mark.parametrize("func", ["axis_path", "simulate"])
@pytest.mark.parametrize(
    ("n0", "ndot0", "name"), [(["x", 0, 1], [0.3, 0, 0], "n0"), ([0, 0, 1], [0.3, "y", 0], "ndot0")]
)
def test_non_numeric_initial_axis_is_named(func, n0, ndot0, name):
    body, medium = vs.Body(theta12=2.0, theta3=1.0), vs.Medium(B12=0.3, B3=0.1)
    args = (5.0, [0.0, 1.0]) if func == "axis_path" else (5.0, (0.0, 1.0))
    with pytest.raises(TypeError, match=f"{name} must be real numbers"):
        getattr(vs, func)(body, medium, n0, ndot0, *args)
