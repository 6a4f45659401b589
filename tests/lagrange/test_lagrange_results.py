"""lagrange's results are built by keywords: the producer recorded, the raw state consistent with the times.

References: the function each result came from, the fields the same result carries (psi, phi are the rows of
the quadratures' state), and the end of the span or the stopping event's time for t_final.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rigidbody import lagrange as L

TOP, DRAG = L.PAPER_TOP, L.PAPER_DRAG


def test_averaged_records_its_producer_and_where_it_ended():
    Gz, H, r = L.integrals(TOP, 0.0, 0.0, 1.7, 0.0, math.radians(60.0))
    one = L.averaged(TOP, DRAG, (Gz, H, r), (0.0, 1.0))
    batch = L.averaged(TOP, DRAG, (Gz, H, r * np.array([1.0, 1.01])), (0.0, 1.0))
    assert one.producer == batch.producer == batch[1].producer == "lagrange.averaged"
    assert one.t_final == 1.0 and np.all(batch.t_final == 1.0)  # status 0: the end of the span, as given


def test_averaged_t_final_of_a_stopped_run_is_its_event_time():
    # a top spun at theta0 = 170 degrees slows to a regular precession: a terminal event (status 1)
    ini = L.integrals(TOP, 0.0, 0.0, L.PAPER_R0, 0.0, math.radians(170.0))
    s = L.averaged(TOP, DRAG, ini, (0.0, 40.0), degenerate_tol=1e-3)
    assert s.status == 1
    assert s.t_final == s.t_events[s.event][-1]


def test_lagrange_motion_state_has_a_column_per_output_time():
    # Slip caught: the raw state kept the quadratures' extra start column (t = 0 added when the output starts
    # later), one more column than times. Its rows are psi and phi, the fields of the same result.
    t = np.array([1.0, 2.0, 3.0])
    sol = L.lagrange_motion(TOP, L.paper_initial_state(2), t)
    assert sol.producer == "lagrange.lagrange_motion"
    assert sol.y.shape == (2, t.size)
    np.testing.assert_array_equal(sol.t, t)
    np.testing.assert_array_equal(sol.y, np.vstack([sol.psi, sol.phi]))
    # and the result agrees with the run from t = 0 at the shared times (same quadrature, tolerance 1e-12:
    # the two integrations step differently, so 1e-9 absolute on angles of order 10 is a wide margin)
    full = L.lagrange_motion(TOP, L.paper_initial_state(2), np.r_[0.0, t])
    np.testing.assert_allclose(sol.psi, full.psi[1:], rtol=0, atol=1e-9)
    assert sol.u[0] == pytest.approx(full.u[1], rel=0, abs=1e-12)  # u(t) in closed form: rounding only
