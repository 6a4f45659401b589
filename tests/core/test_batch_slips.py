"""The batch integrator where a one-line slip passed the rest of the suite: two terminal events in one step, and
the step size a member hands over to its continuation.

The references are exact roots (linear motions) and the single run of the same DOP853
(:func:`rigidbody.core.ode.integrate` with ``engine='python'``), which the batch must reproduce member by member.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rigidbody.core.batch import integrate_batch
from rigidbody.core.ode import Event, integrate


def _drift(t, y, v, *_):
    # y' = v: y(t) = y0 + v t exactly; DOP853's error estimate vanishes, so the steps grow tenfold each time and
    # soon span several roots at once
    return np.broadcast_to(v[:, None], y.shape).copy()


@pytest.mark.parametrize("early_first", [True, False])
def test_two_terminal_roots_in_one_step_stop_the_member_at_the_earlier(early_first):
    # Slip caught: a member whose step holds the roots of two terminal events stops at the later root (the last
    # event in the loop wins, or the comparison with the stopping time is reversed). Member i crosses
    # y = a_i first and y = b_i = a_i + gap_i later; both lie in one step: the steps of y' = v are exact and grow
    # tenfold, and the gap is 1e-4 of the step that holds them. Each event is listed first in one of the runs.
    v = np.array([1.0, 2.0, 0.5])
    a = np.array([0.5, 3.0, 0.2])
    gap = np.array([1e-4, 2e-4, 1e-4])
    ev_a = Event(lambda t, y, v, a, b: y[:, 0] - a, "a", True, 1.0)
    ev_b = Event(lambda t, y, v, a, b: y[:, 0] - b, "b", True, 1.0)
    evs = [ev_a, ev_b] if early_first else [ev_b, ev_a]
    s = integrate_batch(_drift, (0.0, 10.0), np.zeros((3, 1)), args=(v, a, a + gap), events=evs, rtol=1e-10,
                        atol=1e-12)
    exact = a / v
    assert list(s.status) == [1, 1, 1] and list(s.event) == ["a", "a", "a"]
    # the roots of a linear motion are located to a few ulp of t by the Illinois iteration; the gap is 1e-4
    np.testing.assert_allclose(s.t_final, exact, rtol=1e-12, atol=0)
    np.testing.assert_allclose(s.y_final[:, 0], a, rtol=1e-12, atol=0)
    for i in range(3):
        assert s.t_events["b"][i].size == 0  # the later root lies beyond the member's end
        assert s.t_events["a"][i] == pytest.approx([exact[i]], rel=1e-12, abs=0)
    # the single run of the same method stops at the same root
    one = integrate(lambda t, y: [1.0], (0.0, 10.0), [0.0], events=[
        Event(lambda t, y: y[0] - 0.5, "a", True, 1.0), Event(lambda t, y: y[0] - 0.5001, "b", True, 1.0)],
        engine="python")
    assert one.event == "a" and one.t[-1] == pytest.approx(0.5, rel=1e-12, abs=0)


def _oscillator(t, y, w):
    return np.stack([y[:, 1], -(w**2) * y[:, 0]], axis=1)


def test_last_step_is_the_single_runs():
    # Slip caught: the batch records as a member's last_step the step it just took (or the one it would have
    # tried before the step-size update) instead of the next one SciPy's controller proposes; a continued run
    # then restarts with a step off by up to the factor 10 of the controller (0.19 against 1.61 in the slip
    # found). The single run integrate(engine='python') is the same DOP853 on floats: the step sequences agree to
    # rounding, and the next step h 0.9 err^(-1/8) inherits the rounding of the error estimate err (a difference
    # of stage sums cancelling to ~rtol of them: 1e-7..1e-6 relative) through an 8th root: 1e-7 observed. 1e-4
    # relative leaves three orders of margin above that and stays far below the factors (1.2 to 10) of the
    # controller that a misplaced update makes.
    w = np.array([1.0, 2.5, 0.7, 4.0])
    y0 = np.array([[1.0, 0.0], [0.1, 0.1], [1.0, 0.0], [0.2, 0.0]])
    # x = cos(w t) falls through 1/4 at t = acos(1/4)/w (1.32 and 1.88): members 0 and 2 stop there; members 1
    # and 3 swing with amplitudes 0.11 and 0.2 below 1/4 and reach t = 3
    ev = Event(lambda t, y, w: y[:, 0] - 0.25, "cross", True, -1.0)
    s = integrate_batch(_oscillator, (0.0, 3.0), y0, args=(w,), events=[ev], rtol=1e-10, atol=1e-12)
    assert list(s.status) == [1, 0, 1, 0]
    for i in range(w.size):
        wi = float(w[i])
        one = integrate(lambda t, y, wi=wi: [y[1], -wi * wi * y[0]], (0.0, 3.0), y0[i],
                        events=[Event(lambda t, y: y[0] - 0.25, "cross", True, -1.0)], rtol=1e-10, atol=1e-12,
                        engine="python")
        assert s.status[i] == one.status and s.event[i] == one.event
        assert s.last_step[i] == pytest.approx(one.last_step, rel=1e-4, abs=0), i
        # a member that reached the end proposes the step of its last (accepted) step's error, not a stub
        assert math.isfinite(s.last_step[i]) and s.last_step[i] > 0.0
