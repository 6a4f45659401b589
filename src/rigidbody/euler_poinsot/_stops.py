"""What ends a run of the module, and how to go on: the message of every stop, defined once.

A run ends with a status and a message (never an exception part-way, never silent NaN) where its theory or its
equations stop holding. Each message says what happened and, where an option relaxes the stop, names it: the
averaged runs and the full equations, single and batch, fill in the same templates (:func:`stop_message`).
"""

from __future__ import annotations

import math
from typing import Any

__all__ = ["MAX_CROSSINGS", "STOPS", "drift_refusal", "slow_drift", "stop_message"]

#: a run that crosses the separatrix more often than this ends with a status (the averaged motion stalls there:
#: single runs and batches alike)
MAX_CROSSINGS = 50

#: stop -> message template (its fields are the keywords of :func:`stop_message`)
STOPS: dict[str, str] = {
    # the averaged runs: the separatrix stop k2_max (the averaging over the Euler-Poinsot motion fails at k2 = 1)
    "separatrix": ("k2 reached {k2_max:g}: the Euler-Poinsot motion approaches the separatrix 2T A2 = G^2, where "
                   "the averaging over it does not hold; pass k2_max=None to continue through the separatrix into "
                   "the other kind of motion (or a k2_max closer to 1 to stop later)"),
    # the full equations: the same stop, on the osculating k2
    "separatrix_full": ("the osculating k2 reached {k2_max:g}: the motion is at the separatrix 2T A2 = G^2; pass "
                        "k2_max=None to go on through it (the body-frame equations are regular there)"),
    "slow_rotation": ("the rotation is no longer fast: (2 pi / Euler-Poinsot period) / omega0 fell to "
                      "{min_spin_ratio:g}; the averaging over the Euler-Poinsot motion (eps << 1) no longer holds; "
                      "pass a smaller min_spin_ratio to go on (min_spin_ratio=0 switches the check off)"),
    "fast_drift": ("the slow variables change by more than {drift_tol:g} of themselves in one Euler-Poinsot "
                   "period: no separation of time scales, the averaging does not hold; pass a larger drift_tol to "
                   "go on (drift_tol=None switches the check off)"),
    "resonance": ("stopped by event 'resonance' at tau = {tau:.6g}: the rotation number crosses {rho:g} too slowly "
                  "(predicted jump {jump:.3g} > resonance_tol = {resonance_tol:g}); the averaging over psi and the "
                  "phase does not hold there; pass a larger resonance_tol to go on (resonance_tol=None switches the "
                  "check off)"),
    "resonance_bound": ("stopped by event 'resonance' at tau = {tau:.6g}: the rotation number crosses {rho:g}, an "
                        "order whose coefficient is too costly to compute, and the bound on its jump, {jump:.3g}, "
                        "exceeds resonance_tol = {resonance_tol:g}: the averaging may not hold there; pass a larger "
                        "resonance_tol to go on (resonance_tol=None switches the check off)"),
    # at a separatrix crossing (k2_max=None)
    "branch": ("the requested branch {region} is not entered: its averaged drift points back to the separatrix "
               "(capture probability 0; probabilities {probabilities}); pass branch='likely' to continue in the "
               "most probable region"),
    "attracts": ("the separatrix attracts from both sides: the averaged k2 of {region}, where the motion would "
                 "continue, points back to it"),
    "stall": ("the averaged motion stalls at the separatrix ({n} crossings, the last at tau = {tau:.6g}): the "
              "drifts on the two sides point to it"),
    "crossing": "stopped by event 'separatrix' at tau = {tau:.6g}: {why}",
    # a torque that misbehaves part-way (its output refused by the one check of _protocol.evaluate)
    "torque": "at tau = {tau:.6g}: {why}; integration stopped",
}


def stop_message(stop: str, **values: Any) -> str:
    """The message of ``stop`` (a key of :data:`STOPS`) with its fields filled in."""
    return STOPS[stop].format(**values)


def slow_drift(eps: float, freq: float, G: float, T: float, dG: float, dT: float, dn: float) -> float:
    r"""Relative change of the slow variables in one period :math:`P = 2\pi/` ``freq`` of the fast motion,
    :math:`\varepsilon^2P(|\dot G|/G + |\dot T|/T + |\dot{\mathbf n}|)` (rates per unit of :math:`\tau`): the
    measure of the ``'fast_drift'`` stop (``drift_tol``); infinite when the fast motion has stopped."""
    if freq <= 0.0:
        return math.inf
    return eps**2 * (2.0 * math.pi / freq) * (abs(dG) / G + abs(dT) / T + abs(dn))


def drift_refusal(eps: float, drift: float, drift_tol: float) -> str:
    """The message refusing a start whose slow variables drift by ``drift`` per period (> ``drift_tol``)."""
    return (f"the torque is too strong for eps = {eps:g} at this state: the slow variables change by {drift:.3g} of "
            f"themselves in one period of the fast motion (> drift_tol = {drift_tol:g}); the averaging needs a "
            "separation of time scales. Lower eps or the torque, or pass drift_tol=None to integrate anyway")
