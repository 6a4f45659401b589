"""The shared integration wrapper: named fields, events with messages, non-finite stop."""

import math

import numpy as np
import pytest

from rigidbody.core.ode import Event, integrate


def test_named_fields_and_time_name():
    sol = integrate(lambda t, y: -y, (0.0, 1.0), [1.0], t_eval=np.linspace(0, 1, 5), time_name="tau",
                    fields=lambda t, y: {"x": y[0]}, rtol=1e-12, atol=1e-14)
    assert sol.status == 0 and sol.success
    np.testing.assert_allclose(sol.x, np.exp(-sol.tau), rtol=1e-11)  # rtol 1e-12 integration
    assert sol.fields == ("x",)
    assert sol["x"] is sol.x
    with pytest.raises(AttributeError, match="fields"):
        sol.nope
    assert "tau=" in repr(sol)


def test_terminal_event_message():
    ev = Event(lambda t, y: y[0] - 0.5, "half", message="x reached one half")
    sol = integrate(lambda t, y: -y, (0.0, 5.0), [1.0], events=[ev])
    assert sol.status == 1 and sol.event == "half"
    assert "half" in sol.message and "one half" in sol.message
    assert sol.t_events["half"][0] == pytest.approx(math.log(2), rel=1e-9, abs=0)


def test_blow_up_ends_with_clear_status_not_nan():
    # y' = y^2 blows up at t = 1
    sol = integrate(lambda t, y: y * y, (0.0, 2.0), [1.0], method="RK45", rtol=1e-6)
    assert sol.status == -1
    assert np.all(np.isfinite(sol.y))
    assert sol.t[-1] < 1.0 + 1e-6


def test_bad_inputs():
    with pytest.raises(ValueError, match="t_span"):
        integrate(lambda t, y: y, (0.0,), [1.0])
    with pytest.raises(ValueError, match="y0"):
        integrate(lambda t, y: y, (0.0, 1.0), [math.nan])


def test_nonfinite_rhs_at_start_is_refused_not_a_hang():
    with pytest.raises(ValueError, match="not finite at the initial state"):
        integrate(lambda t, y: np.array([math.nan]), (0.0, 1.0), [1.0])


def test_rhs_turning_nan_mid_run_ends_with_failure_status():
    # the derivative becomes NaN for t > 0.5: SciPy rejects steps until the step size underflows
    def f(t, y):
        return np.array([math.nan if t > 0.5 else -y[0]])

    sol = integrate(f, (0.0, 1.0), [1.0], method="RK45", rtol=1e-6)
    assert sol.status == -1
    assert np.all(np.isfinite(sol.y))
    assert sol.t[-1] <= 0.5 + 1e-9


# ---------------------------------------------------------------------------------- engine='python'
def _pendulum_run(engine, **kw):
    evs = [Event(lambda t, y: y[0], "zero", terminal=False),
           Event(lambda t, y: y[1] - 0.3, "w", terminal=True, direction=1.0, message="speed 0.3")]
    return integrate(lambda t, y: [y[1], -math.sin(y[0])], (0.0, 20.0), [1.0, 0.0], t_eval=np.linspace(0, 20, 41),
                     rtol=1e-10, atol=1e-12, engine=engine, events=evs, **kw)


def test_python_engine_is_scipys_dop853():
    # the same method, error norm, controller, dense output and event location on floats: the two runs agree
    # to rounding (far below the rtol-1e-10 global error), with the same step count
    a, b = _pendulum_run("scipy"), _pendulum_run("python")
    assert a.status == b.status == 1 and a.event == b.event == "w" and a.message == b.message
    np.testing.assert_array_equal(a.t, b.t)
    np.testing.assert_allclose(b.y, a.y, rtol=0, atol=1e-13)
    for name in ("zero", "w"):
        np.testing.assert_allclose(b.t_events[name], a.t_events[name], rtol=0, atol=1e-13)
        np.testing.assert_allclose(b.y_events[name], a.y_events[name], rtol=0, atol=1e-13)
    # SciPy also builds the dense output of the first step for the sample at t0: 3 evaluations
    assert a.nfev - b.nfev == 3


def test_python_engine_steps_and_failures():
    # solver steps as output (no t_eval), a blow-up ending with status -1, a NaN right-hand side mid-run
    # (where the first tiny steps' error estimates are at the rounding level the two step sequences may part; the
    # controller then brings both to the same step sizes: the counts agree to a step or two)
    pend = lambda t, y: [y[1], -math.sin(y[0])]  # noqa: E731
    sol = integrate(pend, (0.0, 10.0), [2.0, 0.0], rtol=1e-9, atol=1e-12, engine="python")
    ref = integrate(pend, (0.0, 10.0), [2.0, 0.0], rtol=1e-9, atol=1e-12)
    assert abs(sol.t.size - ref.t.size) <= 2 and sol.t[-1] == 10.0
    energy = 0.5 * sol.y[1] ** 2 - np.cos(sol.y[0])
    np.testing.assert_allclose(energy, -math.cos(2.0), rtol=0, atol=1e-8)  # rtol 1e-9 over ~1.3 periods
    assert sol.last_step > 0.0
    blow = integrate(lambda t, y: [y[0] * y[0]], (0.0, 2.0), [1.0], rtol=1e-8, engine="python")
    assert blow.status == -1 and blow.t[-1] < 1.0 + 1e-6 and np.all(np.isfinite(blow.y))

    def f(t, y):
        return [math.nan if t > 0.5 else -y[0]]

    sol = integrate(f, (0.0, 1.0), [1.0], rtol=1e-6, engine="python")
    assert sol.status == -1 and sol.t[-1] <= 0.5 + 1e-9


def test_python_engine_per_component_rtol_and_first_step():
    # y1 = exp(-t) relative to 1e-12, y2 = 1e6 exp(-t) with only an absolute tolerance: the loose component
    # does not drive the step; a given first step is taken
    f = lambda t, y: [-y[0], -y[1]]  # noqa: E731
    sol = integrate(f, (0.0, 3.0), [1.0, 1e6], rtol=np.array([1e-12, 2.3e-14]), atol=np.array([1e-300, 1.0]),
                    engine="python", t_eval=[3.0], first_step=0.01)
    assert sol.y[0, -1] == pytest.approx(math.exp(-3.0), rel=1e-11, abs=0)
    with pytest.raises(ValueError, match="engine"):
        integrate(f, (0.0, 1.0), [1.0, 1.0], engine="fortran")
    with pytest.raises(ValueError, match="forward"):
        integrate(f, (1.0, 0.0), [1.0, 1.0], engine="python")


def test_python_engine_dense_output_is_scipys():
    # the same interpolant as solve_ivp's OdeSolution (Hairer's 7th-order DOP853 dense output): between the
    # solvers' steps the two agree to rounding (the same steps, see above), and at a step's end it returns the
    # step's state; a terminal event ends the dense output's span there
    a, b = _pendulum_run("scipy", dense_output=True), _pendulum_run("python", dense_output=True)
    t = np.linspace(0.0, float(a.t_events["w"][-1]), 301)
    np.testing.assert_allclose(b.sol(t), a.sol(t), rtol=0, atol=1e-13)
    assert b.sol(1.234).shape == (2,) and b.sol(t).shape == (2, t.size)
    np.testing.assert_allclose(b.sol(b.t), b.y, rtol=0, atol=1e-14)
    # a run with no step (an empty span) has a constant dense output
    c = integrate(lambda t, y: [y[1], -y[0]], (1.0, 1.0), [0.5, 0.2], engine="python", dense_output=True)
    np.testing.assert_array_equal(c.sol(1.0), [0.5, 0.2])


def test_a_root_on_a_step_boundary_is_one_event_on_every_integrator():
    # y' = 1 with steps pinned to 0.25 (first_step = max_step; the error estimate of a constant field is zero,
    # so the step never shrinks): the event g = t - 1 is exactly zero at the end of the fourth step and the start
    # of the fifth. One passage is one event (the rule of crossed()); counting g_old <= 0 <= g_new in both steps
    # listed t = 1 twice (the duplicated separatrix crossings of euler_poinsot.simulate)
    from rigidbody.core.batch import integrate_batch
    from rigidbody.core.ode import Event, crossed, integrate

    ev = [Event(lambda t, y: t - 1.0, "one", False, 0.0)]
    kw = dict(max_step=0.25, first_step=0.25, events=ev)
    runs = [integrate(lambda t, y: [1.0], (0.0, 2.0), [0.0], engine=e, **kw).t_events["one"]
            for e in ("python", "scipy")]
    evb = [Event(lambda t, y: t - 1.0, "one", False, 0.0)]
    b = integrate_batch(lambda t, y: np.ones_like(y), (0.0, 2.0), np.zeros((2, 1)), max_step=0.25,
                        first_step=0.25, events=evb)
    runs += [b.t_events["one"][i] for i in range(2)]
    for te in runs:
        assert np.asarray(te) == pytest.approx([1.0], abs=1e-15)
    # the rule itself, on floats and arrays: a root at the end of a step counts, at its start does not
    assert crossed(-1.0, 0.0, 1) and not crossed(0.0, 1.0, 1) and not crossed(0.0, -1.0, -1)
    assert list(crossed(np.array([-1.0, 0.0, 1.0]), np.array([0.0, 0.0, 0.0]), 0)) == [True, False, True]


@pytest.mark.parametrize("options", [{}, {"method": "RK45"}, {"engine": "python"}])
def test_an_output_grid_with_no_point_in_the_span_gives_an_empty_trajectory_of_the_states_size(options):
    # solve_ivp returns y of shape (0,) when t_eval is empty; a piece of a piecewise run whose span holds no
    # output time gets that (lagrange's GHr chart between two grid points): the result must still be a run
    # that reached its end, with y of shape (n_state, 0), on every engine (it raised from Solution.build)
    sol = integrate(lambda t, y: [-y[0], y[1]], (0.0, 1.0), [1.0, 2.0], t_eval=np.array([]), **options)
    assert sol.status == 0 and sol.y.shape == (2, 0) and sol.time.shape == (0,)
