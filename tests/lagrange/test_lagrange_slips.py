"""Lagrange-top batches and the near-double-root average where a one-line slip passed the rest of the suite.

The references: the single run each batch member replaces, the exact spin r = r0 exp(-b tau/C) of linear drag
(3.3), and the roots of the cubic (1.5) from the state's construction (near a regular precession).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rigidbody import lagrange as L

TOP, DRAG, R0 = L.PAPER_TOP, L.PAPER_DRAG, L.PAPER_R0


def spun(theta_deg, r0=R0):
    """Slow variables of a top spun about its axis with r0, tilted by theta0."""
    return L.integrals(TOP, 0.0, 0.0, r0, 0.0, math.radians(theta_deg))


def _agree(member, one, names=("Gz", "H", "r")):
    # the same coordinates, tolerances and step control: the two runs differ by their global error (rtol 1e-10
    # runs: 1e-9 relative), H relative to its scale max(|H|, mgl) as it passes through zero
    assert member.status == one.status and member.event == one.event, (member.message, one.message)
    np.testing.assert_array_equal(member.tau, one.tau)
    for name in names:
        scale = max(np.abs(one[name]).max(), TOP.mgl if name == "H" else 0.0)
        np.testing.assert_allclose(member[name], one[name], rtol=1e-9, atol=1e-9 * scale)


def test_the_GHr_chart_past_90_degrees_keeps_the_signs_of_Gz_and_r():
    # Slip caught: the batch's GHr output decodes psi - n without the chart's offset n (the integer nearest psi at
    # the segment's start, 1 for a top past 90 degrees: Gz < 0 < r puts psi = angle(Gz, C r)/pi in (1/2, 1)).
    # cos(pi psi) and sin(pi psi) then change sign: Gz and r come out negated. Independent of the single run, r
    # must be the exact (3.3) r0 exp(-b tau/C) > 0, and Gz = C r cos(theta0) < 0 at the start.
    ths = (60.0, 100.0, 150.0)
    ini = np.array([spun(t) for t in ths])
    te = np.linspace(0.0, 10.0, 11)
    b = L.averaged(TOP, DRAG, ini, (0.0, 10.0), tau_eval=te, rtol=1e-10, chart="GHr")
    r_exact = R0 * np.exp(-DRAG.b * te / TOP.C)
    for i, th in enumerate(ths):
        assert np.all(b.chart[i] == 1)
        # r's relative accuracy is rtol times the growth of local errors over a few dozen steps
        np.testing.assert_allclose(b.r[i], r_exact, rtol=1e-9, atol=0)
        assert b.Gz[i, 0] == pytest.approx(TOP.C * R0 * math.cos(math.radians(th)), rel=1e-12, abs=0)
        _agree(b[i], L.averaged(TOP, DRAG, ini[i], (0.0, 10.0), tau_eval=te, rtol=1e-10, chart="GHr"))


def test_leaving_the_GHr_chart_where_psi_is_off_its_first_interval():
    # Slip caught: at the switch back from the GHr chart to the u chart the batch decodes the switching state
    # without the chart's offset n. A top spun the other way (r0 < 0) at 60 degrees has Gz = C r cos(60) < 0
    # and r < 0: psi = angle(Gz, C r)/pi lies in (-1, -1/2), n = -1. Its Gz^2 - C^2 r^2 changes sign at Gz = C r
    # (delta1 flips) inside the GHr chart, which it leaves at psi ~ -0.77: decoded as psi + 1 the state has
    # both signs wrong and continues far from the single run (an O(1) difference). The mirror image of the
    # same top spun with r0 > 0 is the exact reference too: (Gz, H, r) -> (-Gz, H, -r) is a symmetry of (2.7)
    # with linear drag.
    te = np.linspace(0.0, 40.0, 21)
    ini = np.array([spun(60.0, -R0), spun(60.0)])
    b = L.averaged(TOP, DRAG, ini, (0.0, 40.0), tau_eval=te, rtol=1e-10)
    one = L.averaged(TOP, DRAG, ini[0], (0.0, 40.0), tau_eval=te, rtol=1e-10)
    assert one.t_events["chart_switch"].size == 2 and one.t_events["delta1_flip"].size == 1
    _agree(b[0], one)
    np.testing.assert_allclose(b.t_events["chart_switch"][0], one.t_events["chart_switch"], rtol=0, atol=1e-8)
    # the mirror: the same run with Gz and r negated (to the runs' global error)
    np.testing.assert_allclose(b.Gz[0], -b.Gz[1], rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(b.r[0], -b.r[1], rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(b.r[0], -R0 * np.exp(-DRAG.b * te / TOP.C), rtol=1e-9, atol=0)


def test_the_step_size_is_handed_over_between_chart_segments():
    # Slip caught: the batch restarts every chart segment from SciPy's initial-step heuristic instead of the step
    # size its predecessor reached (the single run hands it over). The member then spends the steps the
    # controller needs to grow the step back at each switch: about 10 % more evaluations over these runs (two
    # switches each). With the hand-over a member takes its single run's steps: the counts differ only where
    # a rounding-level difference moves a step boundary across an output time (3 dense-output evaluations) --
    # a handful out of ~400 (0.5 % observed). 3 % separates the two with margin on either side.
    ini = np.array([spun(60.0), spun(95.0), spun(110.0)])
    te = np.linspace(0.0, 100.0, 51)
    b = L.averaged(TOP, DRAG, ini, (0.0, 100.0), tau_eval=te, rtol=1e-10)
    for i in range(len(ini)):
        one = L.averaged(TOP, DRAG, ini[i], (0.0, 100.0), tau_eval=te, rtol=1e-10)
        assert one.t_events["chart_switch"].size == 2  # u -> GHr -> u: two hand-overs
        assert abs(b.nfev[i] / one.nfev - 1.0) <= 0.03, (i, b.nfev[i], one.nfev)


def test_a_batch_whose_torque_reverses_the_spin_equals_its_single_runs():
    # Defect fixed: with a general torque the batch evaluated the nutation means on every member's Runge-Kutta
    # stage, also on stages outside the chart's domain (a trial step past a root collision, NaN coordinates),
    # where the engine raises ValueError (mc = nan) -- which ended the whole batch; the single run rejects such
    # a stage (NaN rates, a smaller step). A purely axial torque M3 = -0.3 - 0.1 r opposite to the spin
    # r0 = sqrt(3) reverses it: r' = (-0.3 - 0.1 r)/C, r = 0 at tau* = (C/0.1) ln((r0 + 3)/3) = 4.56 (exact);
    # delta2 flips there.
    rev = L.ProportionalTorque(f=lambda G, H, r, th: 0.0 * th, M3=lambda G, H, r, th: -0.3 - 0.1 * r + 0.0 * th)
    ini = np.array([spun(30.0), spun(60.0)])
    te = np.linspace(0.0, 8.0, 9)
    b = L.averaged(TOP, rev, ini, (0.0, 8.0), tau_eval=te, rtol=1e-10)
    t_star = TOP.C / 0.1 * math.log((R0 + 3.0) / 3.0)
    r_exact = (R0 + 3.0) * np.exp(-0.1 * te / TOP.C) - 3.0
    for i in range(2):
        one = L.averaged(TOP, rev, ini[i], (0.0, 8.0), tau_eval=te, rtol=1e-10)
        assert one.status == 0
        _agree(b[i], one)
        # r passes through zero at the exact time (event location on the rtol-1e-10 run)
        assert b.t_events["delta2_flip"][i] == pytest.approx([t_star], rel=0, abs=1e-8)
        np.testing.assert_allclose(b.r[i], r_exact, rtol=0, atol=1e-9)


@pytest.mark.parametrize(
    ("u1", "u3", "d1", "d2"),
    [(-0.3, 1.8, -1.0, 1.0), (0.5, 1.2, 1.0, 1.0), (0.1, 3.0, -1.0, -1.0), (-0.8, 1.05, 1.0, -1.0)],
)
def test_the_near_double_root_average_is_the_value_at_the_double_root(u1, u3, d1, d2):
    # Slip caught: a sign slip in the double-root formula (s1 -+ sqrt(s1^2 - 3 s2))/3 (the local maximum of the
    # cubic) on averaged_slow_rates' branch (the formula is the kernel's double_root, shared with the GHr
    # chart's decoding; averaged_slow_rates kept a copy of it once). The branch is taken when the roots come
    # from the cubic and u2 - u1 <= 1e-6 max(u3 - u1, 1) (near a regular precession); the wrong sign gives the
    # local minimum, beyond u3 >= 1. References independent of that formula: the state is built from roots
    # u1 < u2 = u1 + 1e-9 < u3 (2.8), so the double root lies in [u1, u2]; and the zero of Q'(u) in [-1, 1]
    # from NumPy's companion-matrix roots of the derivative of (1.5).
    f = lambda G, H, r, th: -0.2 * (1.0 + np.cos(th) ** 2)  # noqa: E731
    m3 = lambda G, H, r, th: 0.1 * np.cos(th) - 0.05 * r + 0.3 * np.cos(th) ** 3  # noqa: E731
    torque = L.ProportionalTorque(f=f, M3=m3)
    u2 = u1 + 1e-9
    Gz, H, r = L.from_roots(TOP, u1, u2, u3, d1, d2)
    got = L.averaged_slow_rates(TOP, torque, Gz, H, r)
    c3, c2, c1, _ = L.cubic_coefficients(TOP, Gz, H, r)
    crit = np.roots([3.0 * c3, 2.0 * c2, c1]).real
    c = float(crit[np.argmin(np.abs(crit - u1))])
    # the double root is conditioned like a simple one for Q' (its location moves by rounding / curvature):
    # NumPy's root and the pair's midpoint both lie within 1e-9 of it; the rates vary by O(1) per unit of u
    assert abs(c - 0.5 * (u1 + u2)) < 1e-8
    for u in (c, 0.5 * (u1 + u2)):
        ref = [float(np.mean(x)) for x in torque.slow_rates(TOP, Gz, H, r, np.array([u]))]
        np.testing.assert_allclose(got, ref, rtol=0, atol=1e-7)
