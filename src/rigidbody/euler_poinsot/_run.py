"""One averaged run: the closed forms of a drag tensor through the piecewise driver (:mod:`._closed`), or a torque
object's segments of one kind of motion joined at the separatrix crossings, each crossing continuing in the
region the branch rule chooses."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core.ode import Solution
from ..core.validate import positive, real, span
from ._algebra import K2_SPIN_CAP
from ._branches import check_branch
from ._checks import check_averaging, check_sigma, check_tau_eval, check_tol
from ._closed import ClosedSetup, run_closed
from ._crossing import Piece, assemble_pieces, cross_separatrix
from ._engine import Averager
from ._members import Members
from ._model import Orbit, as_orbit, check_body
from ._output import unit_of_angles
from ._regions import Region
from ._segment import RunOptions, Setup, finish_kind, integrate_kind
from ._separatrix import K2_SWITCH
from ._start import StartRules, check_start, initial_kind
from ._state import State
from ._torques import drag_as_torque, resolve

__all__ = ["run_averaged"]

PRODUCER = "euler_poinsot.averaged"


@dataclass(kw_only=True)
class _Generic(RunOptions):
    """What the segments of a run with a torque object share: the whole perturbation and the options of
    :func:`averaged`. The segments use the averaging engine (closed forms of the parts that have them)."""

    torque: Any
    averaging: str
    quad_tol: float

    def __post_init__(self) -> None:
        self.averager = Averager(self.torque, self.averaging, self.quad_tol)
        # the rotation-speed check takes the period at min(k2, spin_cap): K2_SPIN_CAP in a run through the
        # separatrix (its momentary infinite period must not end the run), 1 (no cap) in a run that stops there
        self.spin_cap = K2_SPIN_CAP

    def setup(self, k2_stop: float) -> Setup:
        return Setup(**self.options(), averager=self.averager, k2_max=k2_stop, spin_cap=self.spin_cap)

    def piece(self, region: Region, tau_span: Any, G: float, k2: float, n: np.ndarray, nu0: float,
              lam_s: float, k2_stop: float, first_step: float | None = None) -> Piece:
        seg = integrate_kind(self.setup(k2_stop), region[0], region[1], tau_span, G, k2, n, nu0, lam_s,
                             first_step)

        def finish(te: Any, lam: float) -> Solution:
            return finish_kind(seg, te, lam)

        def common(y: np.ndarray) -> np.ndarray:
            return np.vstack([y[0], y[1], y[2:5] / np.linalg.norm(y[2:5], axis=0)])

        return Piece(seg.res, region, finish, common, lam_s)

    def dk2_at(self, region: Region, G: float, n: np.ndarray, nu: float | None) -> float:
        """The averaged dk2/dtau of ``region`` at the switch next to the separatrix."""
        st = State(self.body, region[0], region[1], G, K2_SWITCH, n, nu, self.orbit)
        self.averager.calibrate(st)
        return float(self.averager.mean(st).dk2)


def _through(first: Piece, gen: _Generic, tau_span: Any, tau_eval: Any, through: bool, branch: Any,
             rng: np.random.Generator | None) -> Solution:
    """Continue an averaged run with a torque object across the separatrix as often as it reaches it (each
    crossing by :func:`cross_separatrix`), then assemble the output."""
    t1 = float(tau_span[1])
    pieces = [first]
    crossings: list[dict[str, Any]] = []
    stop = ""
    cur = first
    while through and cur.res.status == 1 and cur.res.event == "separatrix":
        tc = float(cur.res.t_events["separatrix"][-1])
        at = cur.finish(np.array([tc]), cur.lam_start)
        G, n = float(at.G[0]), np.asarray(at.n[:, 0], dtype=float)
        delta, lam = float(at.delta[0]), float(at.lam[0])
        nu = float(at.nu[0]) if gen.eps > 0.0 else None
        region, stop = cross_separatrix(gen.body, gen.torque, gen.orbit, cur.region, tc, G, delta, lam, n, nu, branch,
                                        rng, crossings, gen.dk2_at)
        if region is None:
            break
        # a segment that starts next to the separatrix starts with the step its predecessor ended with: there
        # the rates' logarithmic singularity can fool the initial-step heuristic into a step whose error
        # estimate is too optimistic (1e-7 instead of 1e-10 relative in G, measured)
        cur = gen.piece(region, (tc, t1), G, K2_SWITCH, n, nu if nu is not None else gen.nu0, lam, K2_SWITCH,
                        first_step=cur.res.last_step)
        pieces.append(cur)
    return assemble_pieces(pieces, crossings, tau_eval, PRODUCER, stop)


def run_averaged(body: Any, torque: Any, eps: Any, G0: Any, k2_0: Any, delta0: Any, lam0: Any, tau_span: Any,
                 tau_eval: Any, nu0: Any, *, kind: str | None, T0: Any, orbit: Orbit | None, rtol: float,
                 atol: float, method: str, k2_max: float | None, min_spin_ratio: float, sigma: int, averaging: str,
                 quad_tol: float, drift_tol: float | None, resonance_tol: float | None, branch: Any,
                 seed: Any) -> Solution:
    """One averaged run (the single call of :func:`rigidbody.euler_poinsot.averaged`; a batch runs its engine
    members through it): the inputs checked, the first segment, the crossings."""
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
    what, tq = resolve(torque)
    through = k2_max is None
    k2_stop = K2_SWITCH if through else real(k2_max, "k2_max")
    min_spin_ratio = real(min_spin_ratio, "min_spin_ratio")
    rules = StartRules(body, None if through else k2_stop, min_spin_ratio)
    eps, G0, k2_0, delta0, lam0, nu0 = check_start(rules, kind, eps, G0, k2_0, delta0, lam0, nu0)
    rng = np.random.default_rng(seed) if branch == "random" else None  # the only branch rule that draws
    if what == "drag" and averaging != "numerical":  # the closed forms (9) of the paper
        d = tq.diag
        one = np.ones(1)
        mem = Members((), eps * one, G0 * one, k2_0 * one, delta0 * one, lam0 * one, nu0 * one,
                      np.array([kind], dtype=object))
        run = ClosedSetup(body, (d[0] * one, d[1] * one, d[2] * one), np.asarray(tq.I, dtype=float)[None], orb,
                          float(rtol), None if through else k2_stop, min_spin_ratio, sigma, branch, rng, method)
        return run_closed(run, mem, (float(tau_span[0]), float(tau_span[1])), tau_eval, True)
    gen = _Generic(torque=tq if what == "torque" else drag_as_torque(tq, body, orb), averaging=averaging,
                   quad_tol=quad_tol, body=body, eps=eps, orbit=orb, nu0=nu0, rtol=rtol, atol=atol, method=method,
                   min_spin_ratio=min_spin_ratio, drift_tol=drift_tol, resonance_tol=resonance_tol)
    gen.torque.check_setup(body, orb)
    gen.spin_cap = K2_SPIN_CAP if through else 1.0
    # the true anomaly at the start: nu = tau/eps + nu0 on a circular orbit (as the drag tensor's closed forms and
    # simulate take it, also when tau_span starts after 0); on an eccentric orbit nu is a state starting at nu0
    nu_start = nu0 + float(tau_span[0]) / eps if eps > 0.0 and orb.e == 0.0 else nu0
    first = gen.piece((kind, sigma), tau_span, G0, k2_0, np.array(unit_of_angles(delta0, lam0)), nu_start, lam0,
                      k2_stop)
    return _through(first, gen, tau_span, tau_eval, through, branch, rng)
