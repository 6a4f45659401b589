"""The grouped keyword options of ``averaged`` and ``simulate``: a group as one value (``Solver``, ``Stops``) gives the
run its fields give one by one, an unknown keyword is named in a TypeError, a field given twice is refused."""

from __future__ import annotations

import numpy as np
import pytest

from rigidbody import euler_poinsot as ep

BODY = ep.Body(3.2, 2.6, 1.67)
DRAG = np.diag([2.322, 1.31, 1.425])


def test_stops_group_gives_the_run_its_fields_give_one_by_one():
    # a stop read from the wrong field of the group (say the default k2_max) ends the run elsewhere: both routes
    # run the same code on the same floats, and the stop at k2 = 0.9 must be the one reached (in the kind 'min'
    # k2 grows towards the separatrix under this drag)
    kw = dict(k2_0=0.5, kind="min", tau_span=(0, 50))
    one = ep.averaged(BODY, DRAG, 0.0, k2_max=0.9, **kw)
    grouped = ep.averaged(BODY, DRAG, 0.0, stops=ep.Stops(k2_max=0.9), **kw)
    assert one.event == grouped.event == "separatrix"
    assert grouped.k2[-1] == pytest.approx(0.9, rel=1e-8, abs=1e-8)  # the event is located to ~1e-12
    assert grouped.tau[-1] == pytest.approx(one.tau[-1], rel=1e-12, abs=1e-12)  # same integration, same floats


def test_solver_group_reaches_the_integrator():
    # a looser rtol takes fewer steps: a group whose fields were dropped would run the default rtol = 1e-10
    tight = ep.averaged(BODY, DRAG, 0.0, tau_span=(0, 3))
    loose = ep.averaged(BODY, DRAG, 0.0, tau_span=(0, 3), solver=ep.Solver(rtol=1e-5))
    assert loose.nfev < tight.nfev
    assert loose.nfev == ep.averaged(BODY, DRAG, 0.0, tau_span=(0, 3), rtol=1e-5).nfev


@pytest.mark.parametrize("call", [ep.averaged, ep.simulate])
def test_an_unknown_keyword_is_named(call):
    with pytest.raises(TypeError, match="'rtoll'"):
        call(BODY, DRAG, 0.1, rtoll=1e-8)


@pytest.mark.parametrize("call", [ep.averaged, ep.simulate])
def test_a_field_given_alone_and_in_its_group_is_refused(call):
    with pytest.raises(TypeError, match=r"'rtol'.*solver"):
        call(BODY, DRAG, 0.1, rtol=1e-8, solver=ep.Solver())


def test_a_group_of_the_wrong_type_is_refused():
    with pytest.raises(TypeError, match="stops must be a Stops"):
        ep.averaged(BODY, DRAG, 0.0, stops={"k2_max": None})


def test_simulate_takes_no_option_of_the_averaged_system():
    # drift_tol is a stop of the averaged system with a torque object; the full equations have none
    with pytest.raises(TypeError, match="'drift_tol'"):
        ep.simulate(BODY, DRAG, 0.1, drift_tol=0.1)


def test_simulate_refuses_a_stop_it_does_not_have_given_in_the_group():
    # the full equations have no drift or resonance stop: a Stops carrying one must not be dropped silently
    with pytest.raises(TypeError, match=r"stops\.drift_tol"):
        ep.simulate(BODY, DRAG, 0.1, stops=ep.Stops(drift_tol=0.1))
    # the stops it has are taken from the group: at eps = 0.1 this start turns 0.53 times per orbit, below the default
    # min_spin_ratio = 1 (refused); the group's min_spin_ratio = 0 must reach the start's check as the keyword does
    with pytest.raises(ValueError, match="min_spin_ratio"):
        ep.simulate(BODY, DRAG, 0.1, tau_span=(0, 0.01), stops=ep.Stops())
    kw = dict(tau_span=(0, 0.01), tau_eval=[0, 0.01])
    one = ep.simulate(BODY, DRAG, 0.1, min_spin_ratio=0, **kw)
    grouped = ep.simulate(BODY, DRAG, 0.1, stops=ep.Stops(min_spin_ratio=0), **kw)
    assert one.status == grouped.status == 0
    assert one.nfev == grouped.nfev  # the same run on the same floats
