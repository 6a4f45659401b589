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
