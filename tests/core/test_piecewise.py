"""The piecewise driver (core.piecewise): members run piece by piece, grouped by mode, on the two integrators.

The problem here is exact: y' = -y from y0 in mode 'a' until y = 1/2 (a terminal event the problem continues),
then in mode 'b' (the same equation) to the end, so every member ends at y0 exp(-t1) whatever its pieces.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rigidbody.core.ode import Event
from rigidbody.core.piecewise import Continue, MemberRecords, PieceSpec, Stop, run_pieces

RTOL = 1e-10


class Decay:
    continues = ("half",)

    def __init__(self, y0, stop=False, bad=()):
        self.y = [float(v) for v in y0]
        self.stop, self.bad = stop, set(bad)
        self.calls = []  # (mode, members, scalar) of every piece
        self.sols = []

    def piece(self, mode, members, scalar, tau):
        self.calls.append((mode, list(members), scalar))
        k = [math.nan if i in self.bad else 1.0 for i in members]
        if scalar:
            half = Event(lambda t, y: y[0] - 0.5, "half", True, -1.0)
            return PieceSpec(lambda t, y: [-k[0] * y[0]], [self.y[members[0]]], RTOL, 1e-14,
                             [half] if mode == "a" else [])
        half = Event(lambda t, y, kk: y[:, 0] - 0.5, "half", True, -1.0)
        return PieceSpec(lambda t, y, kk: -kk[:, None] * y, np.array([[self.y[i]] for i in members]), RTOL, 1e-14,
                         [half] if mode == "a" else [], (np.array(k),))

    def record(self, mode, members, sol, end):
        self.sols.append(sol)
        for j, i in enumerate(members):
            if end.status[j] == 1 and end.event[j] == "half":
                self.y[i] = float(end.event_state(j, "half")[0])
            elif end.status[j] == 0:
                self.y[i] = float(np.asarray(sol.y)[..., 0, -1].reshape(-1)[j])

    def on_event(self, mode, i, j, end):
        if self.stop:
            return Stop(1, "stopped at one half", "half", float(end.t_final[j]))
        return Continue("b")


def test_members_go_on_in_the_next_mode_and_end_where_the_exact_solution_does():
    y0 = np.array([1.0, 2.0, 4.0, 0.25])
    p = Decay(y0)
    rec = run_pieces(p, MemberRecords.start(["a"] * 4, 0.0), 3.0)
    assert rec.status.tolist() == [0, 0, 0, 0] and rec.mode == [None] * 4
    # each member's value at the end is y0 exp(-3) whatever its pieces: a driver that drops the state handed over
    # at the event, or ends the member there, is off by O(1); the bound is 100 times the integrator's rtol
    np.testing.assert_allclose(p.y, y0 * math.exp(-3.0), rtol=100 * RTOL, atol=0)
    # the groups: all four in 'a' (the vectorised integrator); the three that reach y = 1/2 then in 'b' together;
    # the fourth starts below 1/2 and ends in 'a' (a driver that groups across modes mixes them)
    assert p.calls == [("a", [0, 1, 2, 3], False), ("b", [0, 1, 2], False)]


def test_a_group_of_one_runs_on_the_scalar_integrator():
    # a single run (and a member alone in its mode) goes through integrate on floats: a driver that sends it to
    # the vectorised integrator hands its fun arrays (the scalar fun here would fail on them)
    p = Decay([1.0, 0.25])
    rec = run_pieces(p, MemberRecords.start(["a", "a"], 0.0), 2.0)
    assert p.calls == [("a", [0, 1], False), ("b", [0], True)]
    assert rec.status.tolist() == [0, 0]
    assert p.y[0] == pytest.approx(math.exp(-2.0), rel=100 * RTOL, abs=0)  # as above


def test_the_next_piece_starts_with_the_step_size_the_last_one_reached():
    # one member: piece 'a' ends at the event; piece 'b' must begin with a's last step (the integrator's own
    # choice), not with the initial-step heuristic (a smaller step: more evaluations, and next to a singularity an
    # error estimate that can be too optimistic). y' = -y is smooth, so that first step is accepted as given.
    p = Decay([1.0])
    run_pieces(p, MemberRecords.start(["a"], 0.0), 3.0)
    a, b = p.sols
    assert b.time[0] == pytest.approx(math.log(2.0), rel=100 * RTOL, abs=0)  # the event: y = 1/2 at t = ln 2
    assert b.time[1] - b.time[0] == pytest.approx(a.last_step, rel=1e-9, abs=0)  # the rounding of t0 + h - t0


def test_a_stop_at_an_event_ends_the_member_with_the_problem_s_status_and_message():
    p = Decay([1.0, 2.0], stop=True)
    rec = run_pieces(p, MemberRecords.start(["a", "a"], 0.0), 3.0)
    assert rec.status.tolist() == [1, 1] and list(rec.event) == ["half", "half"]
    assert list(rec.message) == ["stopped at one half"] * 2
    # the final times are the event times ln(2 y0): a driver that records the end of the span there is off by O(1)
    np.testing.assert_allclose(rec.t_final, np.log([2.0, 4.0]), rtol=100 * RTOL, atol=0)


def test_a_member_whose_piece_cannot_start_is_refused_in_a_batch_and_raises_alone():
    # a right-hand side that is NaN at the start: one run (strict) raises the integrator's ValueError; in a batch
    # the member ends with status -1 and that message while the others go on
    with pytest.raises(ValueError, match="not finite at the initial state"):
        run_pieces(Decay([1.0], bad=[0]), MemberRecords.start(["a"], 0.0), 1.0, strict=True)
    p = Decay([1.0, 0.25], bad=[1])
    rec = run_pieces(p, MemberRecords.start(["b", None], 0.0), 1.0)  # member 1 refused up front: mode None
    assert rec.status.tolist() == [0, -1]
    p = Decay([1.0], bad=[0])
    rec = run_pieces(p, MemberRecords.start(["a"], 0.0), 1.0)
    assert rec.status.tolist() == [-1] and "not finite" in rec.message[0]
