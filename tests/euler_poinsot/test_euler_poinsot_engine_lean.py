"""The integrators' fast path of the averaging engine (``_lean.LeanMean``) against the engine's plain grid
evaluation (``_engine.lean_mean``): the same quadrature arranged differently (the Jacobi functions on a quarter
period extended by the symmetries of the motion, the attitudes as one matrix product, the contractions as small
matrix products), so the two must agree to rounding on every grid, kind, sense, modulus and torque."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rigidbody import euler_poinsot as ep
from rigidbody.euler_poinsot._engine import Averager, Grid, State, adaptive, lean_mean
from rigidbody.euler_poinsot._lean import LeanMean
from rigidbody.euler_poinsot._protocol import as_torque

BODY = ep.Body(3.2, 2.6, 1.67)
I_OFF = np.array([[2.322, 0.3, -0.2], [0.1, 1.31, 0.4], [0.25, -0.15, 1.425]])
N_DIR = np.array([0.3, -0.5, 0.8]) / math.sqrt(0.98)


def skewed(omega, C, nu):
    """Not odd in omega, depends on the attitude and on nu: every part of the arrangement is exercised."""
    omega, C, nu = np.asarray(omega), np.asarray(C), np.asarray(nu)
    return (np.cross(omega, [0.2, -0.4, 1.0]) * np.cos(nu)[..., None] + 0.3 * C[..., 0, :]
            + 0.1 * omega * omega[..., :1])


TORQUES = {
    "paper": ep.LinearDrag(I_OFF) + ep.GravityGradient(BODY, ep.Orbit(0.2)),
    "skewed": skewed,
}


@pytest.mark.parametrize("name", list(TORQUES))
@pytest.mark.parametrize("kind", ["max", "min"])
@pytest.mark.parametrize("sigma", [1, -1])
@pytest.mark.parametrize("k2", [0.0, 1e-8, 0.3, 0.99, 1 - 1e-8])  # 1 - 1e-8: the period-reduced Jacobi branch
@pytest.mark.parametrize("nu", [None, 0.7])
def test_lean_mean_equals_the_engines_grid_evaluation(name, kind, sigma, k2, nu):
    torque = TORQUES[name]
    orbit = ep.Orbit(0.2)
    for compact in (False, True):
        for grid in (Grid(4, 1.0, 4), Grid(8, 2.0, 16)):
            st = State(BODY, kind, sigma, 1.3, k2, N_DIR, nu, orbit)
            plain = lean_mean(torque, st, grid, compact)
            fast = np.array(LeanMean(torque, BODY, kind, sigma, grid, compact, orbit, nu is not None)(
                1.3, k2, *N_DIR, nu))
            # the same sums of ~10^3-10^4 products in another order: rounding, ~1e-15 of the largest mean
            # (measured 2e-14 at most); a wrong sign, node or axis would differ by O(1)
            assert np.abs(fast - plain).max() <= 1e-13 * np.abs(plain).max()


def test_the_averager_uses_the_fast_path_only_where_it_applies():
    # the integrators' fast path covers the calibrated kind, sense and nu mode; elsewhere the plain evaluation
    tq = ep.LinearDrag(I_OFF) + ep.GravityGradient(BODY)
    av = Averager(tq, "numerical", 1e-12)
    st = State(BODY, "max", 1, 1.0, 0.5, N_DIR, 0.4, ep.Orbit(0.0))
    av.calibrate(st)
    assert av.fast("max", 1, True) is not None
    assert av.fast("min", 1, True) is None and av.fast("max", -1, True) is None and av.fast("max", 1, False) is None
    # with a closed-form part the right-hand sides need the state objects
    mixed = Averager(tq, "auto", 1e-12)
    mixed.calibrate(st)
    assert mixed.fast("max", 1, True) is None
    # both give the same mean where both apply
    L1, L2, L3, dT, dk2 = av.fast("max", 1, True)(1.0, 0.5, *N_DIR, 0.4)
    m = av.mean(State(BODY, "max", -1, 1.0, 0.5, N_DIR, 0.4, ep.Orbit(0.0)))  # the other sense: plain path
    ref = av.mean(st)
    # the same fast path behind both (mean() uses it for the calibrated region): equal up to the rounding of
    # mean_of's few operations (~1e-16 relative), bounded generously
    np.testing.assert_allclose([L1, L2, L3], ref.L, rtol=0, atol=1e-14 * np.abs(ref.L).max())
    assert dk2 == pytest.approx(ref.dk2, rel=1e-12, abs=1e-16) and dT == pytest.approx(ref.dT, rel=1e-12, abs=1e-16)
    # the paper's torques are odd in omega: the other sense (the plain evaluation) has the same averages, up to
    # the quadrature error of the grid, quad_tol = 1e-12 of the torque's size
    np.testing.assert_allclose(m.L, ref.L, rtol=0, atol=1e-12 * np.abs(ref.L).max())


def test_the_report_at_the_calibration_state_is_the_calibrations_estimate():
    # report() at the state the grid was chosen at reuses that estimate; elsewhere it re-estimates
    tq = ep.LinearDrag(I_OFF) + ep.GravityGradient(BODY)
    av = Averager(tq, "numerical", 1e-12)
    st = State(BODY, "max", 1, 1.0, 0.9, N_DIR, None, ep.Orbit(0.0))
    av.calibrate(st)
    q = adaptive(tq, st, 1e-12, grid=av.first.grid, refine=False, compact=av.first.compact)
    _, err = av.report(st)
    expected = np.abs(lean_mean(tq, st, av.grid, av.first.compact) - q.mean)[:3] + q.error[:3]
    # the report's lean mean comes from the fast path: equal to the plain one to rounding (the test above)
    np.testing.assert_allclose(err.L, expected, rtol=0, atol=1e-15 * np.abs(q.mean[:3]).max())
    # elsewhere the report re-estimates: at another state it is not the calibration's estimate
    st2 = State(BODY, "max", 1, 0.8, 0.5, N_DIR, None, ep.Orbit(0.0))
    q2 = adaptive(tq, st2, 1e-12, grid=av.first.grid, refine=False, compact=av.first.compact)
    _, err2 = av.report(st2)
    expected2 = np.abs(lean_mean(tq, st2, av.grid, av.first.compact) - q2.mean)[:3] + q2.error[:3]
    np.testing.assert_allclose(err2.L, expected2, rtol=0, atol=1e-15 * np.abs(q2.mean[:3]).max())


def _declared():
    body = BODY
    return [ep.LinearDrag(I_OFF), ep.GravityGradient(body, ep.Orbit(0.2)), ep.ConstantTorque([0.3, -0.2, 0.5]),
            ep.ViscousCavity(body, [[0.4, 0.1, 0.0], [0.1, 0.7, 0.05], [0.0, 0.05, 0.3]])]


@pytest.mark.parametrize("i", range(4))
@pytest.mark.parametrize("nu", [None, 0.7])
def test_torques_that_declare_broadcasting_broadcast(i, nu):
    # the engine skips its compact-evaluation check for these: their compact and full evaluations must agree
    from rigidbody.euler_poinsot._engine import torque_grid

    tq = _declared()[i]
    assert tq._broadcasts
    st = State(BODY, "max", 1, 1.3, 0.6, N_DIR, nu, ep.Orbit(0.2))
    grid = Grid(8, 1.0, 8)
    full = torque_grid(tq, st, grid)[0]
    compact = torque_grid(tq, st, grid, compact=True)[0]
    # the same arithmetic per element, but on arrays of other shapes and strides, which NumPy may send to other
    # loops of its elementary functions (SIMD or scalar, an ulp apart): a torque that does not broadcast differs
    # by O(1), so a few ulps of the torque's scale (O(1) here) separate the two cases by 13 decades
    np.testing.assert_allclose(compact, full, rtol=0, atol=1e-14 * np.abs(full).max())
    # and a plain function, or a torque calling a user's field, is checked by the engine instead
    assert not ep.MagneticDipole([0.5, -0.3, 0.2], lambda v: np.zeros((*np.shape(v), 3)))._broadcasts
    assert not as_torque(skewed)._broadcasts


def test_an_averager_not_yet_calibrated_calibrates_at_the_first_state_it_is_asked_about():
    # the issue: the object worked only after calibrate(); mean() raised AssertionError (no parts, no grid) and
    # report() likewise. Now the first call calibrates there: the same numbers as calibrating first by hand, to
    # rounding of the same sums on the same grid (bitwise equal in practice; 1e-15 relative allows reordering)
    tq = ep.LinearDrag(I_OFF) + ep.GravityGradient(BODY)
    st = State(BODY, "max", 1, 1.0, 0.5, N_DIR, 0.4, ep.Orbit(0.0))
    by_hand = Averager(tq, "numerical", 1e-12)
    by_hand.calibrate(st)
    for ask in ("mean", "report"):
        lazy = Averager(tq, "numerical", 1e-12)
        got, ref = getattr(lazy, ask)(st), getattr(by_hand, ask)(st)
        got, ref = (got[0], ref[0]) if ask == "report" else (got, ref)
        assert np.allclose(got.L, ref.L, rtol=1e-15, atol=1e-15 * np.abs(ref.L).max())
        assert got.dT == pytest.approx(ref.dT, rel=1e-15, abs=1e-17) and got.dk2 == pytest.approx(ref.dk2, rel=1e-15,
                                                                                                   abs=1e-17)
