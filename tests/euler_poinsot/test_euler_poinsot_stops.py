"""Stops say how to go on: each validity stop names the option that relaxes it, and relaxing it goes on.

The default stop next to the separatrix (``k2_max``) did not say that ``k2_max=None`` continues through it,
and the rotation-speed, drift and branch stops did not name their options. For each stop a run that ends
there must name the option in its message, and the same run with the option relaxed must go past the stop
(the resonance stop is checked so in test_euler_poinsot_engine_vs_full.py, whose scenario is costly).
"""

from __future__ import annotations

import numpy as np
import pytest

from rigidbody import euler_poinsot as ep

BODY = ep.Body(3.2, 2.6, 1.67)
CASE1 = np.diag([2.322, 1.31, 1.425])
# I11/A1 > I33/A3: k2 rises to the separatrix in finite time
UPWARD = np.diag([2.9, 1.31, 1.0])
M0 = np.array([0.4, 0.0, -0.5])


def constant(omega, C, nu):
    """A body-fixed torque: from ('min', 1) the separatrix crossing enters ('max', 1) or ('min', -1), never
    ('max', -1) (test_euler_poinsot_separatrix_crossing.py)."""
    return np.zeros(np.shape(omega)) + M0


#: stop -> (the run that ends there, its event, the option its message names, the options that relax it)
STOPS = {
    "separatrix, closed forms": (lambda **kw: ep.averaged(BODY, UPWARD, 0.0, k2_0=0.5, tau_span=(0, 5), **kw),
                                 "separatrix", "k2_max=None", {"k2_max": None}),
    "separatrix, torque object": (lambda **kw: ep.averaged(BODY, ep.LinearDrag(UPWARD) + ep.ConstantTorque(
        [0.0, 0.0, 1e-3]), 0.0, k2_0=0.5, tau_span=(0, 5), **kw), "separatrix", "k2_max=None", {"k2_max": None}),
    "separatrix, full equations": (lambda **kw: ep.simulate(BODY, CASE1, 0.1, min_spin_ratio=0.0, tau_span=(0, 1),
                                                            **kw), "separatrix", "k2_max=None", {"k2_max": None}),
    "slow rotation, averaged": (lambda **kw: ep.averaged(BODY, CASE1, 0.03, tau_span=(0, 6), **kw),
                                "slow_rotation", "a smaller min_spin_ratio", {"min_spin_ratio": 0.5}),
    "slow rotation, full equations": (lambda **kw: ep.simulate(BODY, 10 * CASE1, 0.1, k2_0=0.5, tau_span=(0, 1),
                                                               **kw), "slow_rotation", "a smaller min_spin_ratio",
                                      {"min_spin_ratio": 0.5}),
    "fast drift": (lambda **kw: ep.averaged(BODY, ep.LinearDrag(2 * CASE1), 0.04, k2_0=0.8, tau_span=(0, 2), **kw),
                   "fast_drift", "a larger drift_tol", {"drift_tol": None}),
    "branch of probability 0": (lambda **kw: ep.averaged(BODY, constant, 0.0, kind="min", k2_0=0.55, delta0=1.0,
                                                         lam0=0.3, tau_span=(0, 0.8), k2_max=None,
                                                         **{"branch": ("max", -1), **kw}),
                                "separatrix", "branch='likely'", {"branch": "likely"}),
}


@pytest.mark.parametrize("stop", list(STOPS))
def test_a_stop_names_its_option_and_relaxing_it_goes_on(stop):
    run, event, option, relaxed = STOPS[stop]
    a = run()
    assert a.status == 1 and a.event == event, a.message
    assert f"pass {option}" in a.message
    b = run(**relaxed)
    assert b.status >= 0 and b.tau[-1] > a.tau[-1], b.message


def test_a_batch_member_stops_with_the_single_calls_message():
    # the closed forms of a batch and the full equations of a batch fill in the same templates as the single run
    k2 = np.array([0.5, 0.2])
    a = ep.averaged(BODY, UPWARD, 0.0, k2_0=k2, tau_span=(0, 5))
    one = ep.averaged(BODY, UPWARD, 0.0, k2_0=0.5, tau_span=(0, 5))
    assert a.event[0] == "separatrix" and a.message[0] == one.message
    s = ep.simulate(BODY, CASE1, np.array([0.1, 0.1]), min_spin_ratio=0.0, tau_span=(0, 1))
    one = ep.simulate(BODY, CASE1, 0.1, min_spin_ratio=0.0, tau_span=(0, 1))
    assert s.event[0] == "separatrix" and s.message[0] == one.message
    s = ep.simulate(BODY, 10 * CASE1, np.array([0.1, 0.1]), k2_0=0.5, tau_span=(0, 1))
    one = ep.simulate(BODY, 10 * CASE1, 0.1, k2_0=0.5, tau_span=(0, 1))
    assert s.event[0] == "slow_rotation" and s.message[0] == one.message
