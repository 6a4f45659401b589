"""The pieces of an averaged run: the step size carried across a chart switch, and the ``max_segments`` guard.

A top spun at 60 degrees under the paper's drag leaves the u chart near Gz = C r (a branch point of (2.8)),
crosses it in the GHr chart and comes back: three pieces (u, GHr, u), two chart switches. The references are the
step-size controller's bounds (SciPy's, ``rigidbody.core.dop853``) and the count of pieces itself.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rigidbody import lagrange as L
from rigidbody.core.dop853 import MIN_FACTOR, SAFETY

TOP, DRAG, R0 = L.PAPER_TOP, L.PAPER_DRAG, L.PAPER_R0
SPAN = (0.0, 100.0)


def spun(theta_deg, r0=R0):
    """Slow variables of a top spun about its axis with r0, tilted by theta0."""
    return L.integrals(TOP, 0.0, 0.0, r0, 0.0, math.radians(theta_deg))


@pytest.mark.parametrize("theta", [60.0, 95.0])
def test_a_single_run_starts_the_next_chart_with_the_step_it_reached(theta):
    # Slip caught: the driver restarts a piece after a chart switch from the initial-step heuristic instead of
    # the step size the piece before reached (the hand-over of core.piecewise; the batch-against-single test
    # of test_lagrange_slips cannot see it, both go through the same driver). Without tau_eval one run's
    # output is on the integrator's steps, so the first step of the last piece (u chart) is tau[k+1] - tau[k]
    # at the last switch tau[k]. The GHr piece before it ended inside an accepted step at least as long as
    # its last output step h; the controller proposes after an accepted step at least SAFETY * h (its factor
    # min(10, 0.9 err^(-1/8)) >= 0.9 for err <= 1), and a rejected first try in the new chart shrinks it by at
    # most MIN_FACTOR: one rejection allowed, the first step is >= SAFETY * MIN_FACTOR * h. A restart from the
    # heuristic takes a first step between 3 and 4 times below that bound (0.05 against h ~ 0.9 here), the
    # hand-over's is several times h (the step grows back to the u chart's).
    one = L.averaged(TOP, DRAG, spun(theta), SPAN, rtol=1e-10)
    assert one.status == 0
    switches = one.t_events["chart_switch"]
    assert switches.size == 2  # u -> GHr -> u
    tau = one.tau
    k = int(np.argmin(np.abs(tau - switches[-1])))
    assert tau[k] == pytest.approx(switches[-1], rel=0, abs=1e-12)  # the switch is a sample of the run
    h_ghr, h_first = tau[k] - tau[k - 1], tau[k + 1] - tau[k]
    assert one.chart[k - 1] == 1 and one.chart[k + 1] == 0
    assert h_first >= SAFETY * MIN_FACTOR * h_ghr, (h_first, h_ghr)


def test_max_segments_counts_the_pieces_of_a_run():
    # Slip caught: the guard counts chart switches instead of pieces (off by one), or is never checked. The run
    # has three pieces: with max_segments=3 it ends at the end of the span as with the default; with 2 it stops
    # at its second switch, with 1 at its first, status -1 and the message naming the option; a batch member
    # stops where its single run does (the guard is the driver's, the same for both).
    ini = spun(60.0)
    full = L.averaged(TOP, DRAG, ini, SPAN, rtol=1e-10)
    switches = full.t_events["chart_switch"]
    assert full.status == 0 and switches.size == 2
    other = L.averaged(TOP, DRAG, spun(20.0), SPAN, rtol=1e-10).t_events["chart_switch"]  # earlier switches
    assert other.size == 2
    three = L.averaged(TOP, DRAG, ini, SPAN, rtol=1e-10, max_segments=3)
    assert three.status == 0
    # the same pieces, the same steps: the same run to rounding
    np.testing.assert_allclose(three.r, full.r, rtol=1e-14, atol=0)
    te = np.linspace(*SPAN, 11)
    batch = L.averaged(TOP, DRAG, np.array([ini, spun(20.0)]), SPAN, tau_eval=te, rtol=1e-10, max_segments=2)
    for cap, t_stop in ((2, switches[1]), (1, switches[0])):
        cut = L.averaged(TOP, DRAG, ini, SPAN, rtol=1e-10, max_segments=cap)
        assert cut.status == -1 and f"max_segments={cap}" in cut.message
        # the pieces before the stop are the full run's: the stop at the same switch to the event location's
        # accuracy (rtol 1e-10 runs, switch times of order 10: 1e-8 absolute)
        assert cut.t_final == pytest.approx(t_stop, rel=0, abs=1e-8)
        assert cut.tau[-1] == pytest.approx(t_stop, rel=0, abs=1e-8)
    for i, t_stop in enumerate((switches[1], other[1])):
        assert batch.status[i] == -1 and "max_segments=2" in batch.message[i]
        assert batch.t_final[i] == pytest.approx(t_stop, rel=0, abs=1e-8)
