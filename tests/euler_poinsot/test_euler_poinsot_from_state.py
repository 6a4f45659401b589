"""EulerPoinsot.from_state: the torque-free motion of any body from a physical state, against an independent
integration of Euler's equations with quaternion kinematics, closed forms of the symmetric top, and the paper's
variables (round trip)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation

from rigidbody import euler_poinsot as ep
from rigidbody.core import euler


def integrate_euler(J, w0, R0, t):
    """Euler's equations J w' = -w x J w with the quaternion (scalar last) q' = q (0, w) / 2, DOP853 at
    rtol 1e-13; returns the body angular velocities (N, 3) and the attitudes (body -> inertial) at ``t``."""
    J = np.asarray(J, float)
    Ji = np.linalg.inv(J)

    def rhs(_, y):
        w, (x, yy, z, s) = y[:3], y[3:]
        wx, wy, wz = w
        dq = 0.5 * np.array([s * wx + yy * wz - z * wy, s * wy + z * wx - x * wz, s * wz + x * wy - yy * wx,
                             -x * wx - yy * wy - z * wz])
        return np.concatenate([Ji @ -np.cross(w, J @ w), dq])

    sol = solve_ivp(rhs, (0.0, float(t[-1])), np.concatenate([w0, R0.as_quat()]), method="DOP853", rtol=1e-13,
                    atol=1e-15, t_eval=t)
    assert sol.status == 0
    return sol.y[:3].T, Rotation.from_quat(sol.y[3:].T)


def random_tensor(rng, A):
    """A non-diagonal tensor with principal moments ``A`` in random body axes."""
    Q = Rotation.random(random_state=rng).as_matrix()
    return Q @ np.diag(A) @ Q.T


def angle_between(R1, R2):
    return (R1 * R2.inv()).magnitude()


BODIES = {
    "triaxial": (2.113, 1.910, 1.950),  # any order
    "triaxial_reversed": (1.67, 2.6, 3.2),
    "A1=A2": (2.0, 2.0, 1.5),
    "A2=A3": (1.5, 2.5, 1.5),
    "near A1=A2": (2.0, 2.0 + 1e-7, 1.5),
    "near A2=A3": (2.5, 1.5, 1.5 + 1e-9),
}


@pytest.mark.parametrize("name", list(BODIES))
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_matches_eulers_equations_from_random_states(name, seed):
    rng = np.random.default_rng(100 * seed + len(name))
    A = BODIES[name]
    J = random_tensor(rng, A)
    w0 = rng.normal(size=3)
    w0 *= 1.0 / np.linalg.norm(w0)  # |omega| = 1: t = 40 is 40 rad of spin
    R0 = Rotation.random(random_state=rng)
    m = ep.EulerPoinsot.from_state(J, w0, R0.as_quat())
    t = np.linspace(0.0, 40.0, 41)
    w_ref, R_ref = integrate_euler(J, w0, R0, t)
    # DOP853 at rtol 1e-13 over ~1000 steps: global error ~1e-12 (measured 1e-13 to 1e-12); the closed form is
    # exact to rounding (1e-14), so 5e-11 is a margin of 50 on the reference and a slip of a sign, a factor or a
    # phase anywhere shows as O(1) or at least O(1e-3).
    assert np.abs(m.omega(t) - w_ref).max() < 5e-11
    assert angle_between(m.rotation(t), R_ref).max() < 5e-11
    # the user's body axes and attitude come back at t = 0 (rounding of the eigenvectors and of sn, cn, dn)
    assert np.abs(m.omega(0.0) - w0).max() < 1e-14
    assert angle_between(m.rotation(0.0), R0) < 1e-14


@pytest.mark.parametrize("attitude", ["rotation", "quaternion", "matrix"])
def test_next_to_the_separatrix_and_the_three_attitude_forms(attitude):
    """A state 1e-8 (relative) off the separatrix, on both sides, in a rotated body."""
    rng = np.random.default_rng(7)
    A = np.array([3.0, 2.0, 1.5])
    J = random_tensor(rng, A)
    P = np.linalg.eigh(J)[1][:, ::-1]
    R0 = Rotation.random(random_state=rng)
    given = {"rotation": R0, "quaternion": R0.as_quat(), "matrix": R0.as_matrix()}[attitude]
    for side in (1.0, -1.0):
        w3 = 2.0 * 0.4 * (1.0 + side * 1e-8)  # on the separatrix A1(A1-A2) w1^2 = A3(A2-A3) w3^2 at w3 = 2 w1
        w0 = P @ np.array([0.4, 0.3, w3])
        m = ep.EulerPoinsot.from_state(J, w0, given)
        assert m.kind == ("min" if side > 0 else "max")
        assert m.mc < 1e-7
        t = np.linspace(0.0, 12.0, 13)
        w_ref, R_ref = integrate_euler(J, w0, R0, t)
        # near the saddles perturbations grow like exp(lambda t), lambda ~ 0.8 here: the reference's 1e-13 per
        # step becomes ~1e-11 by t = 12; a wrong branch (kind or sign) is O(1).
        assert np.abs(m.omega(t) - w_ref).max() < 1e-9
        assert angle_between(m.rotation(t), R_ref).max() < 1e-9


@pytest.mark.parametrize("signs", [(1, 1, 1), (1, -1, -1), (-1, 1, 1), (-1, -1, -1)])
def test_exactly_on_the_separatrix_the_asymptotic_motion(signs):
    A = (3.0, 2.0, 1.5)
    s1, s2, s3 = signs
    w0 = np.array([0.4 * s1, 0.3 * s2, 0.8 * s3])  # A1(A1-A2) w1^2 = 0.48 = A3(A2-A3) w3^2
    m = ep.EulerPoinsot.from_state(A, w0)
    assert (m.kind, m.k2, m.mc) == ("separatrix", 1.0, 0.0)
    t = np.linspace(0.0, 8.0, 9)
    w_ref, R_ref = integrate_euler(np.diag(A), w0, Rotation.identity(), t)
    # exponential growth of the reference's error near the saddle (see above): 1e-13 * exp(0.9 * 8) ~ 1e-10
    assert np.abs(m.omega(t) - w_ref).max() < 1e-9
    assert angle_between(m.rotation(t), R_ref).max() < 1e-9
    # asymptotic: omega tends to the permanent spin about the intermediate axis, G = A2 |omega_2|
    w_inf = m.omega(200.0)
    # lambda^2 = (A1 - A2) E3 / (A1 A2 A3) = 0.09 here: sech(0.3 * 200 + u0) ~ 1e-26 times amplitudes ~ 1
    assert np.abs(w_inf[[0, 2]]).max() < 1e-20
    assert abs(A[1] * abs(w_inf[1]) - m.G) < 1e-14


def test_permanent_rotations_rest_sphere_intermediate_axis():
    R0 = Rotation.from_rotvec([0.3, -1.2, 0.5])
    t = np.array([0.0, 1.0, 10.0, 37.5])
    cases = [((2.0, 3.0, 4.0), [0.0, 0.0, 0.0], "rest"),
             ((3.0, 3.0, 3.0), [1.0, 2.0, 4.0], "sphere"),
             ((2.0, 3.0, 4.0), [0.0, 6.0, 0.0], "separatrix"),  # the unstable spin, exactly
             ((3.0, 3.0, 2.0), [0.6, -0.8, 0.0], "separatrix")]  # equatorial spin of a symmetric top
    for A, w0, kind in cases:
        m = ep.EulerPoinsot.from_state(A, w0, R0)
        assert m.uniform and m.kind == kind
        expected = R0 * Rotation.from_rotvec(t[:, None] * np.asarray(w0)[None, :])
        assert angle_between(m.rotation(t), expected).max() < 1e-14
        assert np.array_equal(m.omega(t), np.tile(w0, (4, 1)))


@pytest.mark.parametrize("case", ["A1=A2", "A2=A3"])
def test_symmetric_top_is_regular_precession(case):
    """Exactly symmetric: R(t) = exp(t G/A_t [n]) R0 P exp(t Omega [e_s]) P^T (Omega = (A_t - A_s) w_s / A_t about
    the symmetry axis e_s, n the inertial direction of G), written independently of the library."""
    rng = np.random.default_rng(3)
    A = np.array([2.0, 2.0, 1.5]) if case == "A1=A2" else np.array([2.5, 1.5, 1.5])
    axis = 2 if case == "A1=A2" else 0
    A_t, A_s = A[1], A[axis]
    for _ in range(4):
        w0, R0 = rng.normal(size=3), Rotation.random(random_state=rng)
        m = ep.EulerPoinsot.from_state(A, w0, R0)
        assert m.k2 == 0.0
        t = np.linspace(-20.0, 30.0, 11)
        n = R0.apply(A * w0)
        G = np.linalg.norm(n)
        e_s = np.eye(3)[axis]
        Omega = (A_t - A_s) * w0[axis] / A_t
        expected = (Rotation.from_rotvec(t[:, None] * (G / A_t) * (n / G)) * R0
                    * Rotation.from_rotvec(t[:, None] * Omega * e_s))
        # rounding of the elliptic route at k = 0 (sn = sin) and of the rotations: ~1e-15 per radian of phase
        assert angle_between(m.rotation(t), expected).max() < 1e-13
        w_perp = (w0 - w0[axis] * e_s)
        expected_w = np.array([Rotation.from_rotvec(-Omega * s * e_s).apply(w_perp) + w0[axis] * e_s for s in t])
        assert np.abs(m.omega(t) - expected_w).max() < 1e-13


@pytest.mark.parametrize("case", ["A1=A2", "A2=A3"])
def test_near_symmetric_bodies_converge_to_the_symmetric_motion(case):
    """delta = 1e-3, 1e-6, 1e-9, then 0: the distance to the symmetric motion is first order in delta, d = C delta
    with the same C at every delta (the second-order term changes C by O(delta) = 1e-3 relative; rounding adds
    ~1e-14, 1e-5 of d at delta = 1e-9), and exactly zero at delta = 0: no loss of accuracy as delta -> 0, and
    the cost is one closed form whatever delta."""
    rng = np.random.default_rng(11)
    w0, R0 = rng.normal(size=3), Rotation.random(random_state=rng)
    t = np.linspace(0.0, 20.0, 21)
    base = np.array([2.0, 2.0, 1.5]) if case == "A1=A2" else np.array([2.5, 1.5, 1.5])
    i = 1 if case == "A1=A2" else 2
    sym = ep.EulerPoinsot.from_state(base, w0, R0)
    ratios = []
    for delta in (1e-3, 1e-6, 1e-9, 0.0):
        A = base.copy()
        A[i] += delta
        m = ep.EulerPoinsot.from_state(A, w0, R0)
        d_rot = angle_between(m.rotation(t), sym.rotation(t)).max()
        d_w = np.abs(m.omega(t) - sym.omega(t)).max()
        if delta == 0.0:
            assert d_rot == 0.0 and d_w == 0.0
        else:
            ratios.append((d_rot / delta, d_w / delta))
    C = np.array(ratios)
    assert np.all(C > 0.1)  # the perturbation does change the motion at first order (C ~ 1 to 100 here)
    assert np.abs(C / C[-1] - 1.0).max() < 0.02


@pytest.mark.parametrize("moments", [(1.67, 3.2, 2.6), (2.113, 1.910, 1.950)])
def test_round_trip_physical_paper_physical(moments):
    """Physical state -> (Body, G, k2, kind, sigma, phase, frame, axes) -> the paper's EulerPoinsot -> physical
    state, at t = 0 to 1e-13, and the paper's psi (closed form about z3) against from_state's (about the labelled
    axis) at later times."""
    rng = np.random.default_rng(5)
    seen = []
    for _ in range(10):
        J = random_tensor(rng, moments)
        R0 = Rotation.random(random_state=rng)
        w0 = rng.normal(size=3)
        m = ep.EulerPoinsot.from_state(J, w0, R0)
        seen.append(m.kind)
        p, A = m.paper, m.axes
        assert isinstance(p, ep.EulerPoinsot)
        assert p.body.A == pytest.approx(sorted(moments, reverse=True), rel=1e-15, abs=0)  # eigenvalues
        for t in (0.0, 7.3, 40.0):
            w = A @ p.omega(t, m.phase)
            R = m.frame @ euler.dcm(*p.angles(t, m.phase)) @ A.T
            tol = 1e-13 if t == 0.0 else 1e-12  # rounding; ~40 rad of phase at t = 40
            assert np.abs(w - m.omega(t)).max() < tol
            assert np.abs(R - m.rotation(t).as_matrix()).max() < tol
            if t == 0.0:
                assert np.abs(w - w0).max() < 1e-13
                assert np.abs(R - R0.as_matrix()).max() < 1e-13
        assert m.frame[:, 2] @ m.momentum == pytest.approx(m.G, rel=1e-14, abs=0)
    assert set(seen) == {"max", "min"}  # both kinds were exercised


def test_refusals_name_the_parameter():
    good = np.diag([2.0, 3.0, 4.0])
    with pytest.raises(ValueError, match="inertia must be a symmetric"):
        ep.EulerPoinsot.from_state(good + np.triu(np.full((3, 3), 1e-6), 1), [1, 0, 0])
    with pytest.raises(ValueError, match="inertia must be positive definite"):
        ep.EulerPoinsot.from_state([[1, 2, 0], [2, 1, 0], [0, 0, 1]], [1, 0, 0])
    with pytest.raises(ValueError, match="inertia violates the triangle inequality"):
        ep.EulerPoinsot.from_state([3.0, 5.0, 9.0], [1, 0, 0])
    with pytest.raises(ValueError, match="inertia must be three principal moments"):
        ep.EulerPoinsot.from_state(np.ones(4), [1, 0, 0])
    with pytest.raises(ValueError, match="omega must be the body angular velocity"):
        ep.EulerPoinsot.from_state(good, [1, 0])
    with pytest.raises(ValueError, match="omega must be finite"):
        ep.EulerPoinsot.from_state(good, [1, 0, math.nan])
    with pytest.raises(ValueError, match="attitude must be a proper rotation"):
        ep.EulerPoinsot.from_state(good, [1, 0, 0], -np.eye(3))
    with pytest.raises(ValueError, match="attitude: a quaternion must not be zero"):
        ep.EulerPoinsot.from_state(good, [1, 0, 0], np.zeros(4))
    with pytest.raises(ValueError, match="attitude must be a single rotation"):
        ep.EulerPoinsot.from_state(good, [1, 0, 0], Rotation.random(2, random_state=1))
    with pytest.raises(TypeError, match="inertia"):
        ep.EulerPoinsot.from_state("heavy", [1, 0, 0])
    m = ep.EulerPoinsot.from_state(good, [1, 0.1, 0])
    for method in (m.omega, m.rotation, m.psi):
        with pytest.raises(ValueError, match="t must be finite"):
            method([0.0, math.nan])


def test_the_repr_names_the_sorted_moments_and_the_kind_of_motion():
    # moments given in any order are shown sorted (the paper's A1 >= A2 >= A3); a spin about the intermediate axis
    # is exactly on the separatrix (G^2 = 2 T A2 = 4 here), a slip in the kind or the sort shows in the text
    text = repr(ep.EulerPoinsot.from_state([1.0, 3.0, 2.0], [0.0, 0.0, 1.0]))
    assert text.startswith("<FreeMotion moments=(3, 2, 1)") and "kind='separatrix'" in text and "k2=1" in text
