"""Passing the separatrix: the averaged evolution against the full equations next to it and through it."""

from __future__ import annotations

import numpy as np

from rigidbody import euler_poinsot as ep

BODY = ep.Body(3.2, 2.6, 1.67)
CASE1 = np.diag([2.322, 1.31, 1.425])


def near_separatrix_errors(eps, mc, phases, span=0.2):
    """Max over phases and time of |full - averaged| for G, T, k2, lambda, from k2_0 = 1 - mc (case 1, 'max')."""
    te = np.linspace(0, span, 21)
    a = ep.averaged(BODY, CASE1, eps, k2_0=1 - mc, tau_span=(0, span), tau_eval=te, min_spin_ratio=0, k2_max=1.0)
    K = ep.EulerPoinsot(BODY, 1.0, 1 - mc, mc=mc).K
    errs, crossed = [], 0
    for u0 in np.linspace(0, 4 * K, phases, endpoint=False):
        s = ep.simulate(BODY, CASE1, eps, k2_0=1 - mc, tau_span=(0, span), tau_eval=te, u0=u0, min_spin_ratio=0)
        assert s.status == 0
        crossed += s.t_events["separatrix"].size > 0
        errs.append([np.abs(getattr(s, f) - getattr(a, f)).max() for f in ("G", "T", "k2", "lam")])
    return np.max(errs, axis=0) / eps**2, crossed


def test_averaging_error_next_to_the_separatrix_does_not_grow_with_the_period():
    # Case 1 from the separatrix side (k2 decreases away from it). At 1 - k2 = 1e-8 the period is 4.2 times
    # that at 1 - k2 = 0.1, and the osculating motion of every run crosses the separatrix back and forth
    # (its energy oscillates by O(eps^2) around the averaged one, more than the distance to the separatrix).
    # The error of the slow variables stays second order with the same constant: the oscillating part of the
    # torque's effect is concentrated on the passages along the separatrix arcs (the rest of the period is
    # spent next to the saddles, where the torque equals its mean), so it is bounded by the arc drifts, not
    # by the period. Measured (eps = 0.02, 8 phases): G 5.7 / 5.7 eps^2, T 1.9 / 2.1, k2 11 / 10, lambda
    # 6.5 / 9.1 (1 - k2 = 0.1 / 1e-8); at eps = 0.01 the same within 10 %.
    P = [ep.EulerPoinsot(BODY, 1.0, 1 - mc, mc=mc).period for mc in (0.1, 1e-8)]
    assert P[1] / P[0] > 4
    far, c_far = near_separatrix_errors(0.02, 0.1, 4)
    near, c_near = near_separatrix_errors(0.02, 1e-8, 4)
    assert c_far == 0 and c_near == 4
    assert np.all(far[:3] < [8, 3, 15]) and np.all(near[:3] < [8, 3, 15])
    # no growth like the period (x 4.2) in G, T, k2; lambda grows by at most 2 (measured 1.4): its rate goes
    # with N*(k2), whose slope in k2 is infinite at the separatrix, so the O(eps^2) error of k2 weighs more
    assert np.all(near[:3] < 1.5 * far[:3]) and near[3] < 2 * far[3]
