"""The batch integrator: every member is the single DOP853 run it replaces, with its own status and events."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from rigidbody.core.batch import integrate_batch
from rigidbody.core.ode import Event, integrate

RTOL, ATOL = 1e-10, 1e-12


def spiral(t, y, a, w):
    # y' = M y, M = [[-a, w], [-w, -a]]: y(t) = exp(-a t) R(w t) y0 exactly
    return np.stack([-a * y[:, 0] + w * y[:, 1], -w * y[:, 0] - a * y[:, 1]], axis=1)


def spiral_exact(t, y0, a, w):
    c, s = np.cos(w * t), np.sin(w * t)
    e = np.exp(-a * t)
    return np.stack([e * (c * y0[0] + s * y0[1]), e * (-s * y0[0] + c * y0[1])])


def pendulum(t, y):
    return np.stack([y[:, 1], -np.sin(y[:, 0])], axis=1)


def test_linear_systems_match_their_exponentials_and_single_runs():
    rng = np.random.default_rng(0)
    B = 40
    a = rng.uniform(0.0, 1.0, B)
    w = rng.uniform(0.5, 5.0, B)
    y0 = rng.normal(size=(B, 2))
    te = np.linspace(0.0, 6.0, 31)
    s = integrate_batch(spiral, (0.0, 6.0), y0, t_eval=te, args=(a, w), rtol=RTOL, atol=ATOL)
    assert s.batch_shape == (B,) and s.y.shape == (B, 2, te.size)
    assert np.all(s.status == 0) and np.all(s.success)
    for i in rng.choice(B, 6, replace=False):
        exact = spiral_exact(te, y0[i], a[i], w[i])
        # global error of an rtol-1e-10 DOP853 run over ~5 revolutions: a few 1e-10 of |y0|
        np.testing.assert_allclose(s.y[i], exact, rtol=0, atol=2e-9 * np.abs(y0[i]).max())
        ai, wi = a[i:i + 1], w[i:i + 1]
        one = solve_ivp(lambda t, y, ai=ai, wi=wi: spiral(np.array([t]), y[None], ai, wi)[0], (0.0, 6.0),
                        y0[i], method="DOP853", t_eval=te, rtol=RTOL, atol=ATOL)
        # the same method and step control: the two runs differ by rounding, far below the global error
        np.testing.assert_allclose(s.y[i], one.y, rtol=0, atol=1e-12 * np.abs(y0[i]).max())
        # same step sequence: the counts agree to one rejected step (rounding) and the dense-output stages
        # SciPy spends on the first step for the sample at t0
        assert abs(int(s.nfev[i]) - one.nfev) <= 15, (s.nfev[i], one.nfev)


def test_pendulum_energy_and_member_view():
    rng = np.random.default_rng(1)
    th0 = rng.uniform(0.1, 2.5, (3, 4))
    y0 = np.stack([th0, np.zeros_like(th0)], axis=-1)
    te = np.linspace(0.0, 10.0, 21)
    s = integrate_batch(pendulum, (0.0, 10.0), y0, t_eval=te, rtol=RTOL, atol=ATOL,
                        fields=lambda t, y: {"theta": y[:, 0], "E": 0.5 * y[:, 1] ** 2 - np.cos(y[:, 0])})
    assert s.batch_shape == (3, 4)
    assert s.theta.shape == (3, 4, te.size) and s.E.shape == (3, 4, te.size)
    # the energy is conserved: drift at the integrator's global error (rtol 1e-10 over ~2 periods)
    assert np.abs(s.E - s.E[..., :1]).max() < 1e-8
    m = s[1, 2]
    assert m.batch_shape == () and m.status == 0 and isinstance(m.message, str)
    np.testing.assert_array_equal(m.theta, s.theta[1, 2])
    np.testing.assert_array_equal(m.y, s.y[1, 2])
    one = integrate(lambda t, y: [y[1], -math.sin(y[0])], (0.0, 10.0), y0[1, 2], t_eval=te, rtol=RTOL, atol=ATOL)
    np.testing.assert_allclose(m.y, one.y, rtol=0, atol=1e-12)  # the same DOP853 run up to rounding
    with pytest.raises(TypeError, match="tuple of 2"):
        s[1]
    with pytest.raises(IndexError):
        s[3, 0]
    assert "batch_shape=(3, 4)" in repr(s)


def test_terminal_events_end_their_member_only():
    lam = np.array([0.1, 0.5, 1.0, 2.0])
    ev = Event(lambda t, y, lam: y[:, 0] - 0.5, "half", direction=-1.0, message="y reached one half")
    te = np.linspace(0.0, 3.0, 13)
    s = integrate_batch(lambda t, y, lam: -lam[:, None] * y, (0.0, 3.0), np.ones((4, 1)), t_eval=te,
                        args=(lam,), events=[ev], rtol=RTOL, atol=ATOL)
    # ln 2 / lam = 6.9, 1.39, 0.69, 0.35: the first member reaches t = 3, the others stop at their root
    assert list(s.status) == [0, 1, 1, 1]
    assert list(s.event) == [None, "half", "half", "half"]
    assert "one half" in s.message[2] and "successfully" in s.message[0]
    for i in range(1, 4):
        # located on the dense output to a few ulp; the trajectory itself carries the rtol-1e-10 error
        assert s.t_events["half"][i] == pytest.approx([math.log(2) / lam[i]], rel=1e-9, abs=0)
        assert s.t_final[i] == s.t_events["half"][i][0]
        after = te > s.t_final[i]
        assert np.all(np.isnan(s.y[i, 0, after])) and np.all(np.isfinite(s.y[i, 0, ~after]))
        m = s[i]
        assert m.t[-1] <= s.t_final[i] and m.y.shape[1] == np.count_nonzero(~after)
    assert s.t_events["half"][0].size == 0 and np.all(np.isfinite(s.y[0]))


def test_non_terminal_events_are_recorded_per_member():
    # harmonic oscillators x'' = -w^2 x, x(0) = 1: x = 0 at t = (k + 1/2) pi / w; downward crossings at even k
    w = np.array([1.0, 2.0, 3.5])
    f = lambda t, y, w: np.stack([y[:, 1], -(w**2) * y[:, 0]], axis=1)  # noqa: E731
    evs = [Event(lambda t, y, w: y[:, 0], "zero", terminal=False),
           Event(lambda t, y, w: y[:, 0], "down", terminal=False, direction=-1.0)]
    s = integrate_batch(f, (0.0, 10.0), np.tile([1.0, 0.0], (3, 1)), args=(w,), events=evs, rtol=RTOL, atol=ATOL)
    assert np.all(s.status == 0)
    for i, wi in enumerate(w):
        k = np.arange(int(10.0 * wi / math.pi - 0.5) + 1)
        exact = (k + 0.5) * math.pi / wi
        # event times inherit the trajectory's global error (rtol 1e-10 over a few dozen periods)
        np.testing.assert_allclose(s.t_events["zero"][i], exact, rtol=0, atol=1e-8)
        np.testing.assert_allclose(s.t_events["down"][i], exact[::2], rtol=0, atol=1e-8)
        assert s.y_events["zero"][i].shape == (exact.size, 2)
        np.testing.assert_allclose(s.y_events["zero"][i][:, 0], 0.0, atol=1e-8)


def test_a_failing_member_ends_alone_with_status_and_message():
    # member 1's right-hand side turns NaN after t = 0.5, member 2's blows up (y' = y^2 from 1: t = 1)
    def f(t, y, kind):
        out = -y.copy()
        out[kind == 1] = np.where(t[kind == 1, None] > 0.5, np.nan, -y[kind == 1])
        out[kind == 2] = y[kind == 2] ** 2
        return out

    kind = np.array([0, 1, 2, 0])
    te = np.linspace(0.0, 2.0, 9)
    s = integrate_batch(f, (0.0, 2.0), np.ones((4, 1)), t_eval=te, args=(kind,), rtol=1e-8, atol=1e-10)
    assert list(s.status) == [0, -1, -1, 0]
    assert "non-finite" in s.message[1] and "t = 0.5" in s.message[1]
    assert s.t_final[1] <= 0.5 + 1e-9 and s.t_final[2] < 1.0 + 1e-6
    np.testing.assert_allclose(s.y[0, 0], np.exp(-te), rtol=1e-7)  # the others go on (rtol 1e-8 run)
    np.testing.assert_allclose(s.y[3, 0], np.exp(-te), rtol=1e-7)
    # (the sample at t = 0.5 itself exists only if a step lands on 0.5 exactly: a matter of rounding)
    assert np.all(np.isnan(s.y[1, 0, te > 0.5])) and np.all(np.isfinite(s.y[1, 0, te < 0.5]))
    assert not s.success[1] and s.success[0]


def test_members_that_cannot_start_fail_and_the_others_run():
    def f(t, y, c):
        return c[:, None] * np.ones_like(y)

    c = np.array([1.0, np.nan, 2.0])
    s = integrate_batch(f, (0.0, 1.0), np.array([[0.0], [0.0], [np.inf]]), args=(c,), t_eval=[0.0, 1.0])
    assert list(s.status) == [0, -1, -1]
    assert "not finite at the initial state" in s.message[1]
    assert "initial state is not finite" in s.message[2]
    assert s.y[0, 0, -1] == pytest.approx(1.0, rel=1e-12, abs=0)


@pytest.mark.parametrize("shape", [(1,), (5,), (2, 3), (2, 1, 3)])
def test_batch_shapes_and_per_member_spans(shape):
    rng = np.random.default_rng(len(shape) * 10 + shape[-1])
    a = rng.uniform(0.1, 1.0, shape)
    w = rng.uniform(0.5, 2.0, shape)
    y0 = rng.normal(size=(*shape, 2))
    t0 = rng.uniform(0.0, 1.0, shape)
    t1 = t0 + rng.uniform(1.0, 3.0, shape)
    te = np.linspace(0.0, 4.0, 17)
    s = integrate_batch(spiral, (t0, t1), y0, t_eval=te, args=(a, w), rtol=RTOL, atol=ATOL)
    assert s.batch_shape == shape and s.y.shape == (*shape, 2, te.size) and s.status.shape == shape
    for idx in np.ndindex(*shape):
        inside = (te >= t0[idx]) & (te <= t1[idx])
        assert np.all(np.isnan(s.y[idx][:, ~inside])) and np.all(np.isfinite(s.y[idx][:, inside]))
        exact = spiral_exact(te[inside] - t0[idx], y0[idx], a[idx], w[idx])
        np.testing.assert_allclose(s.y[idx][:, inside], exact, rtol=0, atol=1e-9 * np.abs(y0[idx]).max())
        assert s.t_final[idx] == t1[idx]
        np.testing.assert_allclose(s.y_final[idx], spiral_exact(np.array([t1[idx] - t0[idx]]), y0[idx], a[idx],
                                                                w[idx])[:, 0], rtol=0, atol=1e-9)


def test_single_runs_keep_their_shape():
    sol = integrate(lambda t, y: -y, (0.0, 1.0), [1.0], t_eval=[0.0, 1.0])
    assert sol.batch_shape == ()
    assert isinstance(sol.status, int) and isinstance(sol.message, str)
    with pytest.raises(TypeError, match="no members"):
        sol[0]
    assert bool(sol)


def test_bad_input():
    f = lambda t, y: -y  # noqa: E731
    with pytest.raises(ValueError, match="forward"):
        integrate_batch(f, (1.0, 0.0), np.ones((2, 1)))
    with pytest.raises(ValueError, match="t_eval"):
        integrate_batch(f, (0.0, 1.0), np.ones((2, 1)), t_eval=[0.5, 0.2])
    with pytest.raises(ValueError, match="rtol"):
        integrate_batch(f, (0.0, 1.0), np.ones((2, 1)), rtol=0.0)
    with pytest.raises(ValueError, match="atol"):
        integrate_batch(f, (0.0, 1.0), np.ones((2, 1)), atol=-1.0)
    with pytest.raises(ValueError, match="args"):
        integrate_batch(lambda t, y, c: -y, (0.0, 1.0), np.ones((2, 1)), args=(np.ones(3),))
    with pytest.raises(ValueError, match="t_span"):
        integrate_batch(f, (0.0, np.ones(3)), np.ones((2, 1)))
    with pytest.raises(ValueError, match="at least one"):
        integrate_batch(f, (0.0, 1.0), np.ones((0, 1)))


def test_two_terminal_roots_in_one_step_stop_the_member_at_the_earlier():
    # y' = 1 with the step pinned to the whole span (first_step = max_step = 1; a constant field has no error
    # estimate to shrink it): the roots y = 0.3 and y = 0.6 of two terminal events fall in the one step. The
    # member stops at the earlier root, whichever event is listed first; a non-terminal root before it is recorded,
    # one after it is not (catches a member stopped at the later root, or at the first event listed)
    c = np.array([[0.6, 0.3], [0.3, 0.6]])  # member 0: the second event is the earlier, member 1: the first
    evs = [Event(lambda t, y, c: y[:, 0] - c[:, 0], "first", message="first level"),
           Event(lambda t, y, c: y[:, 0] - c[:, 1], "second", message="second level"),
           Event(lambda t, y, c: y[:, 0] - 0.1, "before", terminal=False),
           Event(lambda t, y, c: y[:, 0] - 0.8, "after", terminal=False)]
    s = integrate_batch(lambda t, y, c: np.ones_like(y), (0.0, 1.0), np.zeros((2, 1)), args=(c,), events=evs,
                        first_step=1.0, max_step=1.0)
    assert list(s.status) == [1, 1] and list(s.event) == ["second", "first"]
    # the roots of a linear event function on an exact (linear) dense output: located to the root finder's
    # tolerance, 4 ulp of t or 1e-12 of the step
    np.testing.assert_allclose(s.t_final, [0.3, 0.3], rtol=0, atol=1e-12)
    np.testing.assert_allclose(s.y_final[:, 0], [0.3, 0.3], rtol=0, atol=1e-12)
    assert "second level" in s.message[0] and "first level" in s.message[1]
    for i in range(2):
        assert s.t_events["before"][i] == pytest.approx([0.1], abs=1e-12)
        assert s.t_events["after"][i].size == 0
        assert s.t_events["first" if i else "second"][i] == pytest.approx([0.3], abs=1e-12)
        assert s.t_events["second" if i else "first"][i].size == 0
    # the float integrator follows the same rule
    for i in range(2):
        one = integrate(lambda t, y: [1.0], (0.0, 1.0), [0.0], engine="python", first_step=1.0, max_step=1.0,
                        events=[Event(lambda t, y, ci=ci: y[0] - ci, e.name, e.terminal)
                                for e, ci in zip(evs, [*c[i], 0.1, 0.8])])
        assert one.event == s.event[i] and one.t[-1] == pytest.approx(0.3, abs=1e-12)
        assert one.t_events["before"] == pytest.approx([0.1], abs=1e-12) and one.t_events["after"].size == 0


@pytest.mark.parametrize("events", [False, True])
def test_each_member_reports_the_step_size_its_single_run_would_take_next(events):
    # last_step is what continues a run (first_step of the next segment): each member's is its own single
    # run's. The two integrators take the same steps with the same controller, so the proposals agree to the
    # rounding of the error estimate: a combination of stages that cancel to rtol, so relative eps/rtol ~ 1e-6,
    # raised to the controller's power 1/8 (measured 5e-7); 1e-4 leaves room, while another member's or another
    # step's proposal differs by tens of percent
    a, w = np.array([0.1, 0.4, 0.05]), np.array([1.0, 2.5, 0.7])
    ev = [Event(lambda t, y, a, w: y[:, 0] - 0.2, "low", direction=-1.0)] if events else []
    ev1 = [Event(lambda t, y, a, w: y[0] - 0.2, "low", direction=-1.0)] if events else []
    s = integrate_batch(spiral, (0.0, 8.0), np.tile([1.0, 0.0], (3, 1)), args=(a, w), events=ev, rtol=RTOL,
                        atol=ATOL)
    for i in range(3):
        one = integrate(lambda t, y, a, w: [-a * y[0] + w * y[1], -w * y[0] - a * y[1]], (0.0, 8.0), [1.0, 0.0],
                        args=(a[i], w[i]), events=ev1, rtol=RTOL, atol=ATOL, engine="python")
        assert one.status == s.status[i]
        assert s.last_step[i] == pytest.approx(one.last_step, rel=1e-4, abs=0)
