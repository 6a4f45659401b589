"""The DOP853 numerics both integrators share (core.dop853): against SciPy's own routines and the order conditions
of the method, and one definition giving the same on floats (SCALAR) as on arrays (ARRAY)."""

import math

import numpy as np
import pytest
from scipy.integrate import DOP853
from scipy.integrate._ivp.common import select_initial_step  # SciPy's initial-step heuristic: the reference

from rigidbody.core import dop853 as rk
from rigidbody.core.kernel import ARRAY, SCALAR


def test_the_tableau_satisfies_the_order_conditions_of_an_8th_order_pair():
    # independent of how the coefficients are stored: the quadrature conditions b . c^(k-1) = 1/k, k = 1..8, of an
    # 8th-order method, row sums of A equal to the nodes, and error estimators that are differences of two
    # consistent methods (weights summing to zero). A slip in any weight breaks one of them by far more than the
    # rounding of the sums (1e-15)
    c = rk.C
    for k in range(1, 9):
        assert rk.B @ c ** (k - 1) == pytest.approx(1.0 / k, abs=1e-14), k
    np.testing.assert_allclose(rk.A.sum(axis=1), c, rtol=0, atol=1e-14)
    np.testing.assert_allclose(rk.A_EXTRA.sum(axis=1), rk.C_EXTRA, rtol=0, atol=1e-14)
    assert abs(rk.E5.sum()) < 1e-14 and abs(rk.E3.sum()) < 1e-14
    # one copy serves both integrators: nobody may write into it
    with pytest.raises(ValueError):
        rk.B[0] = 0.0


def test_the_error_norm_is_scipys():
    rng = np.random.default_rng(3)
    solver = DOP853(lambda t, y: -y, 0.0, np.ones(4), 1.0)
    for _ in range(20):
        n = int(rng.integers(1, 5))
        K = rng.normal(size=(rk.N_STAGES + 1, n))
        h = float(rng.uniform(1e-3, 1.0))
        scale = rng.uniform(1e-3, 2.0, n)
        e5n = float(np.sum((rk.E5 @ K / scale) ** 2))
        e3n = float(np.sum((rk.E3 @ K / scale) ** 2))
        ref = solver._estimate_error_norm(K, h, scale)
        # the same formula with the squared norms summed in another order: rounding only
        assert rk.error_norm(SCALAR, h, e5n, e3n, n) == pytest.approx(ref, rel=1e-13, abs=0)
        assert rk.error_norm(ARRAY, np.array([h]), np.array([e5n]), np.array([e3n]), n)[0] == pytest.approx(
            ref, rel=1e-13, abs=0)
    assert rk.error_norm(SCALAR, 0.5, 0.0, 0.0, 3) == 0.0  # a step without error estimate (a constant field)


@pytest.mark.parametrize("case", ["generic", "zero state", "constant field", "capped", "short span"])
def test_the_initial_step_is_scipys_heuristic(case):
    rng = np.random.default_rng(len(case))
    n = 3
    M = rng.normal(size=(n, n))
    y0 = rng.normal(size=n)
    fun = lambda t, y: M @ y + np.sin(t)  # noqa: E731
    t_bound, max_step, rtol, atol = 10.0, np.inf, 1e-8, 1e-10
    if case == "zero state":
        y0 = np.zeros(n)  # d0 < 1e-5: h0 = 1e-6
    elif case == "constant field":
        fun = lambda t, y: np.zeros(n)  # noqa: E731  # d1, d2 = 0: the 1e-3 h0 branch
    elif case == "capped":
        max_step = 1e-4
    elif case == "short span":
        t_bound = 1e-7
    f0 = fun(0.0, y0)
    ref = select_initial_step(fun, 0.0, y0, t_bound, max_step, f0, 1.0, rk.ERROR_ORDER, rtol, atol)
    rms = lambda v: math.sqrt(float(np.mean(np.asarray(v) ** 2)))  # noqa: E731
    scale = atol + np.abs(y0) * rtol
    d0, d1 = rms(y0 / scale), rms(f0 / scale)
    h0 = rk.trial_step(SCALAR, d0, d1, t_bound)
    d2 = rms((fun(h0, y0 + h0 * f0) - f0) / scale) / h0
    h = rk.initial_step(SCALAR, h0, d1, d2, t_bound, max_step)
    # the norms by another route than SciPy's np.linalg.norm: rounding, raised to the power 1/8 at most
    assert h == pytest.approx(ref, rel=1e-13, abs=0)
    arr = lambda x: np.array([x])  # noqa: E731
    assert rk.initial_step(ARRAY, rk.trial_step(ARRAY, arr(d0), arr(d1), arr(t_bound)), arr(d1), arr(d2),
                           arr(t_bound), max_step)[0] == h


ERRORS = [0.0, 1e-300, 1e-12, 0.3, 0.999, 1.0, 2.0, 1e6, 1e300, math.inf, math.nan]


@pytest.mark.parametrize("after_rejection", [False, True])
def test_the_controller_is_one_rule_on_floats_and_arrays(after_rejection):
    arrays = rk.step_factor(ARRAY, np.array(ERRORS), np.full(len(ERRORS), after_rejection))
    for err, fa in zip(ERRORS, arrays):
        f = rk.step_factor(SCALAR, err, after_rejection)
        assert f == fa, err  # the same operations on the same doubles
        if err < 1.0:  # accepted: grows (never after a rejection), at most by MAX_FACTOR
            expected = min(rk.MAX_FACTOR, rk.SAFETY * err ** rk.ERROR_EXPONENT) if err > 0.0 else rk.MAX_FACTOR
            assert f == pytest.approx(min(1.0, expected) if after_rejection else expected, rel=1e-15, abs=0)
        else:  # rejected: shrinks, at least by MIN_FACTOR; a NaN or infinite error by MIN_FACTOR itself
            assert rk.MIN_FACTOR <= f < 1.0
            if not math.isfinite(err) or err > 1e6:
                assert f == rk.MIN_FACTOR


def test_settle_events_is_one_rule_on_floats_and_arrays():
    # per row: the roots of four events (NaN: no root) in a step ending at 1; events 0 and 1 terminal
    terminal = [True, True, False, False]
    rows = [
        ([0.6, 0.3, 0.1, 0.8], 0.3, 1, [False, True, True, False]),  # the earlier terminal root stops
        ([0.3, 0.3, 0.3, math.nan], 0.3, 0, [True, False, True, False]),  # a tie: the first listed; a non-terminal
        # root at the stop counts
        ([math.nan, math.nan, 0.5, 0.9], 1.0, -1, [False, False, True, True]),  # no terminal root: all count
    ]
    for roots, t_stop, stop, counted in rows:
        ts, sp, cn = rk.settle_events(SCALAR, roots, terminal, 1.0)
        assert (ts, sp, [bool(c) for c in cn]) == (t_stop, stop, counted)
    ts, sp, cn = rk.settle_events(ARRAY, [np.array([r[0][j] for r in rows]) for j in range(4)], terminal,
                                  np.ones(len(rows)))
    assert list(ts) == [r[1] for r in rows] and list(sp) == [r[2] for r in rows]
    for j in range(4):
        assert list(cn[j]) == [r[3][j] for r in rows]
