"""Euler-Poinsot batches and the separatrix choice where a one-line slip passed the rest of the suite: a forced
branch, per-member separatrix stops in a batch that mixes eps = 0 and eps > 0, and the tie rule between two
equally probable regions.

A batch member is checked against its single call (the reference of every batch test); the tie rule against
its documented statement (sigma = +1 first, then 'max') on crossings built with exact ties.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rigidbody import euler_poinsot as ep

BODY = ep.Body(3.2, 2.6, 1.67)
# I11/A1 > I33/A3: k2 rises to the separatrix in finite time
UPWARD = np.diag([2.9, 1.31, 1.0])
RTOL = 1e-10
# a member and its single call integrate the same equations with the same step control; their step sequences
# part by rounding: the event times agree to the integrators' global error, a few rtol
AGREE = 30 * RTOL


def test_a_forced_branch_is_followed_by_every_batch_member():
    # Slip caught: the batch keeps sigma = +1 after a crossing into a forced region ('min', -1) (the kind is
    # switched, the sense is not). Member 0 reaches the separatrix at tau = 0.27 and is forced into ('min', -1)
    # (probability 1/2: the drifts of the paper's drag on the four arcs are equal, the region is entered);
    # member 1 stays below it.
    te = np.linspace(0.0, 0.5, 6)
    kw = dict(tau_span=(0.0, 0.5), tau_eval=te, rtol=RTOL, k2_max=None, min_spin_ratio=0.0, branch=("min", -1))
    k2 = np.array([0.95, 0.3])
    sol = ep.averaged(BODY, UPWARD, 0.0, 1.0, k2, 0.8, 0.3, **kw)
    assert list(sol.status) == [0, 0]
    assert [c["region"] for c in sol.crossings[0]] == [("min", -1)] and sol.crossings[1] == []
    after = te > sol.crossings[0][0]["tau"]
    assert after.any() and not after.all()
    assert np.all(sol.kind[0, after] == "min") and np.all(sol.sigma[0, after] == -1)
    assert np.all(sol.sigma[0, ~after] == 1) and np.all(sol.sigma[1] == 1)
    for i in range(2):
        one = ep.averaged(BODY, UPWARD, 0.0, 1.0, float(k2[i]), 0.8, 0.3, **kw)
        assert list(sol.kind[i]) == list(one.kind) and list(sol.sigma[i]) == list(one.sigma)
        # after the crossing the motion is the other kind's: G and k2 as the single call's to the run's error
        np.testing.assert_allclose(sol.G[i], one.G, rtol=AGREE, atol=0)
        np.testing.assert_allclose(sol.k2[i], one.k2, rtol=AGREE, atol=0)


def test_separatrix_stops_are_per_member_in_a_batch_mixing_eps_zero_and_positive():
    # Slip caught: the batch reads a member's separatrix event time from the round's solution by the member's
    # index in the whole batch instead of its index in the round; the rounds group the members by eps = 0 and
    # eps > 0, so a mixed batch then takes another member's time or raises IndexError. Members 0, 1 and 3 reach
    # k2_max = 0.999 (the first two from the same state, with and without the orbit), member 2 does not.
    te = np.linspace(0.0, 0.5, 6)
    eps = np.array([0.0, 0.01, 0.0, 0.01])
    k2 = np.array([0.99, 0.99, 0.3, 0.95])
    kw = dict(tau_span=(0.0, 0.5), tau_eval=te, rtol=RTOL, k2_max=0.999)
    sol = ep.averaged(BODY, UPWARD, eps, 1.0, k2, 0.8, 0.3, **kw)
    assert list(sol.status) == [1, 1, 0, 1]
    for i in range(4):
        one = ep.averaged(BODY, UPWARD, float(eps[i]), 1.0, float(k2[i]), 0.8, 0.3, **kw)
        assert sol.status[i] == one.status and sol.event[i] == one.event
        np.testing.assert_allclose(sol.t_events["separatrix"][i], one.t_events["separatrix"], rtol=AGREE, atol=0)
        if one.status == 1:
            assert sol.t_final[i] == pytest.approx(float(one.t_events["separatrix"][-1]), rel=AGREE, abs=0)
    # the two members that start alike stop within O(eps) of each other, not at the same time as member 3
    t = [float(sol.t_events["separatrix"][i][0]) for i in (0, 1, 3)]
    assert abs(t[0] - t[1]) < 0.01 and t[2] > 2 * t[0]


def _crossing(probabilities):
    """A crossing from ('max', 1) with the given capture probabilities (the drifts do not enter the choice)."""
    probs = {r: 0.0 for r in ep.REGIONS}
    probs.update(probabilities)
    loops = {r: (1.0 if r[0] == "max" else -1.0) for r in ep.REGIONS}
    return ep.SeparatrixCrossing(("max", 1), {}, loops, probs, 0.0, True, 0.0)


@pytest.mark.parametrize(
    ("tied", "winner"),
    [
        ({("min", 1): 0.5, ("min", -1): 0.5}, ("min", 1)),  # sigma = +1 first
        ({("max", -1): 0.5, ("min", 1): 0.5}, ("min", 1)),  # ... before 'max'
        ({("max", -1): 0.5, ("min", -1): 0.5}, ("max", -1)),  # the same sigma: 'max'
        ({("max", 1): 0.5, ("min", 1): 0.5}, ("max", 1)),
        ({r: 0.25 for r in ep.REGIONS}, ("max", 1)),
    ],
)
def test_ties_between_regions_follow_the_documented_rule(tied, winner):
    # Slip caught: the tie rule of most_probable() turned around (sigma = -1 first, or 'min' before 'max').
    # The documented rule (averaged's branch='likely'): ties go to sigma = +1, then to 'max'.
    assert _crossing(tied).most_probable() == winner
    # probabilities equal up to rounding (the propagation of the arc drifts gives 0.5 +- 1 ulp) are a tie too
    wobbly = {r: p * (1.0 + (2 - i) * 2.2e-16) for i, (r, p) in enumerate(tied.items())}
    assert _crossing(wobbly).most_probable() == winner
    # and a real difference decides: the other region of the pair made more probable wins
    other = next(r for r in tied if r != winner)
    clear = {r: (p + 1e-6 if r == other else p - 1e-6) for r, p in tied.items()}
    if len(tied) == 2:
        assert _crossing(clear).most_probable() == other


def test_the_likely_branch_of_a_symmetric_crossing_keeps_sigma_plus_one():
    # the paper's drag has equal drifts on the four arcs (a symmetric crossing, probabilities 1/2 for the two
    # 'min' regions): 'likely' continues in ('min', +1) by the tie rule, in the batch and in the single call
    c = ep.separatrix_crossing(BODY, UPWARD, 0.85, 0.8, 0.3, None, ("max", 1))
    assert c.probabilities[("min", 1)] == pytest.approx(0.5, rel=0, abs=1e-12)
    assert c.probabilities[("min", -1)] == pytest.approx(0.5, rel=0, abs=1e-12)
    assert c.most_probable() == ("min", 1)
    assert math.isclose(sum(c.probabilities.values()), 1.0, rel_tol=0, abs_tol=1e-12)
