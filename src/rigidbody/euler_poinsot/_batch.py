r"""A batch of averaged evolutions (9) integrated together, round by round.

The members share the body, the torque, the orbit, ``tau_span`` and the options; their initial slow variables
``G0, k2_0`` (or ``T0``), ``delta0, lam0``, the true anomaly ``nu0`` and ``eps`` are arrays broadcast to one
batch shape, and with a batch of drag tensors (shape ``batch_shape + (3, 3)``) each member has its own. The
closed forms of a drag tensor (:mod:`._kernel`, the equations of the single run) are evaluated on all active
members at once by :func:`rigidbody.core.batch.integrate_batch` (per-member DOP853 step control, events and
status). A round integrates the members that share a kind of motion and a state layout (``eps = 0``:
``(ln G, ln k^2, lambda)``; ``eps > 0``: ``(ln G, ln k^2, delta, lambda[, nu])``) together. A member that
reaches the separatrix in a run that goes through it (``k2_max=None``) crosses as its single run does (capture
probabilities at its crossing state, the region chosen by ``branch``, its drift checked) and continues in the
next round in the other kind of motion from its crossing point; a member ends on its own events
(``'separatrix'``, ``'slow_rotation'``) with the status and message of its single run; a member whose start the
single run refuses (a ``ValueError`` there) gets ``status = -1`` and that message, and the others go on.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..core.ode import Solution
from ..core.validate import positive, real
from ._boundary import as_torque, drag_equivalent
from ._branches import check_branch
from ._checks import check_averaging, check_sigma
from ._closed import ClosedSetup, drag_members, run_closed
from ._enginerun import EngineSetup, run_engine
from ._fullkinds import TriaxialKinds
from ._fullrun import FullRun, probe_members, run_full_members
from ._members import check_members, common_checks, drag_batch, member_inputs
from ._model import as_orbit
from ._start import StartRules

__all__ = ["averaged_batch", "simulate_batch"]


def averaged_batch(body: Any, torque: Any, eps: Any, G0: Any, k2_0: Any, delta0: Any, lam0: Any,
                   tau_span: Any, tau_eval: Any, nu0: Any, opts: dict[str, Any]) -> Solution:
    """The batch branch of :func:`rigidbody.euler_poinsot.averaged`.

    ``opts`` holds the keyword options of the call (validated here as the single run validates them); the members
    run through the piecewise driver as the single run does: the closed forms together, the engine member by
    member.
    """
    t0, t1, te = common_checks(body, tau_span, tau_eval, opts)
    orb = as_orbit(opts["orbit"])
    check_averaging(opts["averaging"], "averaging")
    sigma = check_sigma(opts["sigma"])
    positive(opts["quad_tol"], "quad_tol")
    branch = check_branch(opts["branch"])
    k2_max = opts["k2_max"]
    if k2_max is not None:
        k2_max = real(k2_max, "k2_max")
        if not 0.0 < k2_max <= 1.0:
            raise ValueError(f"k2_max (the separatrix stop) must lie in (0, 1], got {k2_max}")
    min_spin = real(opts["min_spin_ratio"], "min_spin_ratio")
    tensors = drag_batch(torque)
    mem = member_inputs(body, eps, G0, k2_0, delta0, lam0, nu0, opts["T0"], opts["kind"],
                        () if tensors is None else tensors.shape[:-2])
    if tensors is None:
        tq, drag = as_torque(torque, body, orb)
        if opts["averaging"] == "auto":  # a drag tensor, or the paper's two torques as objects: the closed forms
            tensors = drag.I if drag is not None else drag_equivalent(tq, body, orb)
    elif opts["averaging"] != "auto":
        raise ValueError("a batch of drag tensors is integrated with the closed forms (averaging='auto')")
    if tensors is not None:
        I, T = drag_members(mem, tensors)
        run = ClosedSetup(body, I, T, orb, float(opts["rtol"]), k2_max, min_spin, sigma, branch,
                          np.random.default_rng(opts["seed"]))
        check_members(mem, StartRules(body, k2_max, min_spin))
        return run_closed(run, mem, (t0, t1), te, False)

    # a torque object: the averaging engine (per state), member by member through the driver
    drift_tol = None if opts["drift_tol"] is None else positive(opts["drift_tol"], "drift_tol")
    resonance_tol = None if opts["resonance_tol"] is None else positive(opts["resonance_tol"], "resonance_tol")
    check_members(mem, StartRules(body, k2_max, min_spin))
    erun = EngineSetup(tq, body, orb, sigma, float(opts["rtol"]), float(opts["atol"]), opts["method"], k2_max, min_spin,
                       opts["averaging"], float(opts["quad_tol"]), drift_tol, resonance_tol, branch, opts["seed"])
    return run_engine(erun, mem, (t0, t1), te, False)


def simulate_batch(body: Any, torque: Any, eps: Any, G0: Any, k2_0: Any, delta0: Any, lam0: Any, tau_span: Any,
                   tau_eval: Any, nu0: Any, u0: Any, psi0: Any, opts: dict[str, Any]) -> Solution:
    """The batch branch of :func:`rigidbody.euler_poinsot.simulate` (``opts``: its keyword options; the ``'angles'``
    formulation runs member by member through the single run)."""
    t0, t1, te = common_checks(body, tau_span, tau_eval, {**opts, "method": "DOP853"})
    sigma = check_sigma(opts["sigma"])
    orb = as_orbit(opts["orbit"])
    if opts["formulation"] not in ("body", "angles"):
        raise ValueError(f"formulation must be 'body' or 'angles', got {opts['formulation']!r}")
    k2_max = None if opts["k2_max"] is None else real(opts["k2_max"], "k2_max")
    min_spin = real(opts["min_spin_ratio"], "min_spin_ratio")
    try:
        phases = np.broadcast_shapes(np.shape(u0), np.shape(psi0))
    except ValueError:
        raise ValueError(f"u0 and psi0 must broadcast to one batch shape, got {np.shape(u0)}, {np.shape(psi0)}"
                         ) from None
    mem = member_inputs(body, eps, G0, k2_0, delta0, lam0, nu0, opts["T0"], opts["kind"], phases, "u0 and psi0")
    try:
        ph = np.broadcast_to(np.asarray(u0, dtype=float), mem.batch_shape).reshape(-1)
        ps = np.broadcast_to(np.asarray(psi0, dtype=float), mem.batch_shape).reshape(-1)
    except ValueError:
        raise ValueError(f"u0 and psi0 must broadcast to the batch shape {mem.batch_shape}") from None
    tq, _ = as_torque(torque, body, orb)
    tq.check_setup(body, orb)
    check_members(mem, StartRules(body, k2_max, min_spin, True), ph, ps)  # the single run's checks, member by member
    kinds = TriaxialKinds(body, mem.k2_0, mem.kind, ph, ps, sigma, k2_max, min_spin)
    run = FullRun(body, drag_equivalent(tq, body, orb), tq, orb, kinds, float(opts["rtol"]), float(opts["atol"]),
                  opts["formulation"], opts["method"])
    probe_members(run, mem)
    return run_full_members(run, mem, (t0, t1), te, False)
