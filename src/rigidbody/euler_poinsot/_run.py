"""One averaged run: its inputs checked, then a batch of one through the piecewise driver, as the closed forms of a
drag tensor (:mod:`._closed`) or as a torque object's averaged system (:mod:`._enginerun`)."""

from __future__ import annotations

from typing import Any

import numpy as np

from ..core.ode import Solution
from ..core.validate import positive, real, span
from ._boundary import as_torque
from ._branches import check_branch
from ._checks import check_averaging, check_sigma, check_tau_eval, check_tol
from ._closed import ClosedSetup, run_closed
from ._enginerun import EngineSetup, run_engine
from ._members import Members
from ._model import Orbit, as_orbit, check_body
from ._separatrix import K2_SWITCH
from ._start import StartRules, check_start, initial_kind

__all__ = ["run_averaged"]


def run_averaged(body: Any, torque: Any, eps: Any, G0: Any, k2_0: Any, delta0: Any, lam0: Any, tau_span: Any,
                 tau_eval: Any, nu0: Any, *, kind: str | None, T0: Any, orbit: Orbit | None, rtol: float,
                 atol: float, method: str, k2_max: float | None, min_spin_ratio: float, sigma: int, averaging: str,
                 quad_tol: float, drift_tol: float | None, resonance_tol: float | None, branch: Any,
                 seed: Any) -> Solution:
    """One averaged run (the single call of :func:`rigidbody.euler_poinsot.averaged`): the inputs checked, then the
    run as a batch of one."""
    check_body(body)
    k2_0, kind = initial_kind(body, real(G0, "G0"), k2_0, kind, T0)
    span(tau_span, "tau_span")
    check_tau_eval(tau_eval, tau_span)
    check_tol(rtol, atol)
    orb = as_orbit(orbit)
    check_averaging(averaging, "averaging")
    sigma = check_sigma(sigma)
    quad_tol = positive(quad_tol, "quad_tol")
    drift_tol = None if drift_tol is None else positive(drift_tol, "drift_tol")
    resonance_tol = None if resonance_tol is None else positive(resonance_tol, "resonance_tol")
    branch = check_branch(branch)
    tq, drag = as_torque(torque, body, orb)
    through = k2_max is None
    k2_stop = K2_SWITCH if through else real(k2_max, "k2_max")
    min_spin_ratio = real(min_spin_ratio, "min_spin_ratio")
    rules = StartRules(body, None if through else k2_stop, min_spin_ratio)
    eps, G0, k2_0, delta0, lam0, nu0 = check_start(rules, kind, eps, G0, k2_0, delta0, lam0, nu0)
    one = np.ones(1)
    mem = Members((), eps * one, G0 * one, k2_0 * one, delta0 * one, lam0 * one, nu0 * one,
                  np.array([kind], dtype=object))
    if drag is not None and averaging != "numerical":  # the closed forms (9) of the paper
        d = drag.diag
        rng = np.random.default_rng(seed) if branch == "random" else None  # the only branch rule that draws
        run = ClosedSetup(body, (d[0] * one, d[1] * one, d[2] * one), np.asarray(drag.I, dtype=float)[None], orb,
                          float(rtol), None if through else k2_stop, min_spin_ratio, sigma, branch, rng, method)
        return run_closed(run, mem, (float(tau_span[0]), float(tau_span[1])), tau_eval, True)
    erun = EngineSetup(tq, body, orb, sigma, rtol, atol, method, None if through else k2_stop, min_spin_ratio,
                       averaging, quad_tol, drift_tol, resonance_tol, branch, seed)
    return run_engine(erun, mem, (float(tau_span[0]), float(tau_span[1])), tau_eval, True)
