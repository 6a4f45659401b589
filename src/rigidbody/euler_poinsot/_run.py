"""One averaged run: segments of one kind of motion (a drag tensor's closed forms or a torque object) joined at
the separatrix crossings, each crossing continuing in the region the branch rule chooses."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core import kernel as _kn
from ..core.ode import Event, Solution, integrate
from ..core.validate import positive, real, span
from . import _kernel as _k
from ._algebra import K2_SPIN_CAP, dk2_labelled
from ._branches import check_branch, choose_region
from ._checks import check_averaging, check_sigma, check_tau_eval, check_tol
from ._engine import Averager
from ._model import Orbit, as_orbit, check_body, labelled
from ._output import PiecewiseDense, unit_of_angles
from ._segment import RunOptions, Setup, finish_kind, integrate_kind
from ._separatrix import K2_SWITCH, SeparatrixCrossing, separatrix_crossing
from ._start import StartRules, check_start, initial_kind
from ._state import State
from ._stops import MAX_CROSSINGS, stop_message
from ._torques import drag_as_torque, resolve

__all__ = ["run_averaged"]


# --------------------------------------------------------------------------------------------------
# through the separatrix: segments of one kind of motion joined at the crossings
# --------------------------------------------------------------------------------------------------


@dataclass
class _Piece:
    """One segment of an averaged run: its raw result, its region (kind, sigma), how to evaluate its output
    fields at given times (``finish(tau_eval, lam_start)``), its state as rows G, k2, n (``common(y)``), and
    the lambda it starts from."""

    res: Solution
    region: tuple[str, int]
    finish: Any
    common: Any
    lam_start: float


@dataclass(kw_only=True)
class _Generic(RunOptions):
    """What the segments after a crossing share: the whole perturbation as a torque object and the options
    of :func:`averaged`. The segments use the averaging engine (closed forms of the parts that have them)."""

    torque: Any
    averaging: str
    quad_tol: float

    def __post_init__(self) -> None:
        self.averager = Averager(self.torque, self.averaging, self.quad_tol)
        self.drag: Any = None  # a drag tensor run: its segments use the closed forms (9) of the paper
        # the rotation-speed check takes the period at min(k2, spin_cap): K2_SPIN_CAP in a run through the
        # separatrix (its momentary infinite period must not end the run), 1 (no cap) in a run that stops there
        self.spin_cap = K2_SPIN_CAP

    def setup(self, k2_stop: float) -> Setup:
        return Setup(**self.options(), averager=self.averager, k2_max=k2_stop, spin_cap=self.spin_cap)

    def piece(self, region: tuple[str, int], tau_span: Any, G: float, k2: float, n: np.ndarray, nu0: float,
              lam_s: float, k2_stop: float, first_step: float | None = None) -> _Piece:
        if self.drag is not None:
            return _drag_piece(self, self.drag, region, tau_span, G, k2, n, nu0, lam_s, k2_stop, first_step)
        seg = integrate_kind(self.setup(k2_stop), region[0], region[1], tau_span, G, k2, n, nu0, lam_s,
                              first_step)

        def finish(te: Any, lam: float) -> Solution:
            return finish_kind(seg, te, lam)

        def common(y: np.ndarray) -> np.ndarray:
            return np.vstack([y[0], y[1], y[2:5] / np.linalg.norm(y[2:5], axis=0)])

        return _Piece(seg.res, region, finish, common, lam_s)

    def crossing(self, G: float, delta: float, lam: float, nu: float | None, source: tuple[str, int]
                 ) -> SeparatrixCrossing:
        return separatrix_crossing(self.body, self.torque, G, delta, lam, nu, source, orbit=self.orbit)

    def dk2_at(self, region: tuple[str, int], G: float, n: np.ndarray, nu: float | None) -> float:
        """The averaged dk2/dtau of ``region`` at the switch next to the separatrix."""
        if self.drag is not None:
            A, Id = labelled(self.body, region[0], self.drag.diag)
            return dk2_labelled(A, Id, K2_SWITCH)
        st = State(self.body, region[0], region[1], G, K2_SWITCH, n, nu, self.orbit)
        self.averager.calibrate(st)
        return float(self.averager.mean(st).dk2)


def _through(first: _Piece, gen: _Generic, tau_span: Any, tau_eval: Any, through: bool, branch: Any,
             rng: np.random.Generator | None) -> Solution:
    """Continue an averaged run across the separatrix as often as it reaches it, then assemble the output."""
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
        c = gen.crossing(G, delta, lam, nu, cur.region)
        region, why = choose_region(c, branch, len(crossings), rng)
        if region is not None and gen.dk2_at(region, G, n, nu) >= 0.0:
            why = stop_message("attracts", region=region)
            region = None
        crossings.append({"tau": tc, "source": cur.region, "region": region, "probabilities": dict(c.probabilities),
                          "drifts": dict(c.drifts), "G": G, "n": n})
        if region is None:
            stop = why
            break
        if len(crossings) > MAX_CROSSINGS or (len(crossings) > 1 and tc <= crossings[-2]["tau"]):
            stop = stop_message("stall", n=len(crossings), tau=tc)
            break
        # a segment that starts next to the separatrix starts with the step its predecessor ended with: there
        # the rates' logarithmic singularity can fool the initial-step heuristic into a step whose error
        # estimate is too optimistic (1e-7 instead of 1e-10 relative in G, measured)
        cur = gen.piece(region, (tc, t1), G, K2_SWITCH, n, nu if nu is not None else gen.nu0, lam, K2_SWITCH,
                        first_step=cur.res.last_step)
        pieces.append(cur)
    if len(pieces) == 1 and not crossings:
        sol: Solution = first.finish(tau_eval, first.lam_start)
        sol.crossings = []  # type: ignore[attr-defined]  # an extra attribute of this result: no crossing
        return sol
    return _assemble(pieces, crossings, stop, tau_eval)


def _assemble(pieces: list[_Piece], crossings: list[dict[str, Any]], stop: str, tau_eval: Any) -> Solution:
    """One Solution from the segments: fields at the requested times (each from its segment's dense output),
    lambda continuous, the kind and sense at every time, the crossings as events."""
    outs: list[Solution] = []
    last = len(pieces) - 1
    for i, p in enumerate(pieces):
        a, b = float(p.res.time[0]), float(p.res.time[-1])
        if tau_eval is None:
            te = p.res.time if i == 0 else p.res.time[1:]
        else:
            t = np.asarray(tau_eval, dtype=float)
            te = t[(t >= a) & ((t <= b) if i == last else (t < b))]
        outs.append(p.finish(te, p.lam_start))
    names = [f for f in outs[-1].fields if all(f in o.fields for o in outs)]
    data = {f: np.concatenate([np.asarray(getattr(o, f)) for o in outs], axis=-1) for f in names}
    tau = np.concatenate([o.time for o in outs])
    y = np.vstack([data["G"], data["k2"], data["n"]])
    res = pieces[-1].res
    status, message, event = res.status, res.message, res.event
    if stop:
        tc = crossings[-1]["tau"]
        status, event = 1, "separatrix"
        message = stop_message("crossing", tau=tc, why=stop)
    t_events = dict(res.t_events)
    y_events = dict(res.y_events)
    t_events["separatrix"] = np.array([c["tau"] for c in crossings])
    y_events["separatrix"] = (np.array([[c["G"], K2_SWITCH, *c["n"]] for c in crossings]) if crossings
                              else np.empty((0, 5)))
    dense = PiecewiseDense([p.res.time[0] for p in pieces], [lambda t, p=p: p.common(p.res.sol(t)) for p in pieces],
                            5)
    sol = Solution(res.time_name, tau, y, data, status, message, event, t_events, y_events, dense,
                   sum(p.res.nfev for p in pieces))
    sol.crossings = crossings  # type: ignore[attr-defined]  # an extra attribute of this result
    qerr = [getattr(o, "quad_error", 0.0) for o in outs]
    sol.quad_error = max(qerr)  # type: ignore[attr-defined]  # an extra attribute of this result
    sol.resonances = [r for o in outs for r in getattr(o, "resonances", [])]  # type: ignore[attr-defined]
    return sol


def _drag_piece(gen: _Generic, drag: Any, region: tuple[str, int], tau_span: Any, G0: float, k2_0: float,
                n0: np.ndarray, nu_start: float, lam0: float, k2_stop: float, first_step: float | None = None
                ) -> _Piece:
    """A segment of the paper's averaged system (9) (drag tensor plus gravity gradient, closed forms), integrated
    in ``(ln G, ln k^2, [delta,] lambda[, nu])`` (:mod:`._kernel`: relative accuracy of the decaying variables,
    lambda continuous) by DOP853 on Python floats; its dense output is computed where it is asked for."""
    SC = _kn.SCALAR
    delta0 = math.acos(max(-1.0, min(1.0, float(n0[2]))))
    body, orb, eps, kind, sigma = gen.body, gen.orbit, gen.eps, region[0], region[1]
    A, Id = labelled(body, kind, drag.diag)
    g1, g2, g3, c3, c1 = _k.DragCoefficients(A, Id).args()
    nu0 = gen.nu0  # circular orbit: nu = tau / eps + nu0 with the run's nu0
    e = orb.e
    limit = eps == 0.0
    y0, z_a = _k.initial_state(eps, G0, k2_0, delta0, lam0, nu_start, e)
    z = float(z_a)
    hl = 0.75 * orb.mean_factor * math.cos(delta0)
    ie = 0.0 if limit else 1.0 / eps
    rhs = _k.scalar_rhs(A, (g1, g2, g3, c3, c1), z, e, limit, hl, ie, nu0)

    lnk_stop = math.log(k2_stop)
    events = [Event((lambda t, y: y[1] - lnk_stop) if z > 0.0 else (lambda t, y: -1.0), "separatrix", True, 1.0,
                    stop_message("separatrix", k2_max=k2_stop))]
    if not limit:
        cap, r = gen.spin_cap, gen.min_spin_ratio
        events.append(Event(lambda t, y: _k.nut_freq(SC, A, math.exp(y[0]), min(z * math.exp(y[1]), cap)) * ie - r,
                            "slow_rotation", True, -1.0, stop_message("slow_rotation", min_spin_ratio=r)))
    rt: Any
    rt, at = _k.tolerances(gen.rtol, y0.size)
    py = gen.method == "DOP853"
    res = integrate(rhs, tau_span, y0, rtol=rt if py else _k.RTOL_FLOOR, atol=at, method=gen.method,
                    dense_output=True, events=events, time_name="tau", engine="python" if py else "scipy",
                    first_step=first_step if py else None)
    def common(y: np.ndarray) -> np.ndarray:
        f = _k.fields(A, e, np.zeros(np.shape(y)[-1]), y, z, limit, delta0, nu0, ie)
        return np.vstack([f["G"], f["k2"], f["n"]])

    def make_fields(tau: np.ndarray, y: np.ndarray) -> dict[str, np.ndarray]:
        out = _k.fields(A, e, tau, y, z, limit, delta0, nu0, ie)
        out["kind"], out["sigma"] = np.full(tau.shape, kind), np.full(tau.shape, sigma)
        return out

    def finish(te: Any, lam_s: float) -> Solution:
        # the fields on te (the solver's steps by default) from the dense output; lambda is a state (continuous by
        # construction); the raw rows become G, k2, n like every run's
        steps = res.time
        if te is None:
            tau, y = steps, res.y
        else:
            tt = np.asarray(te, dtype=float)
            tau = tt[(tt >= steps[0]) & (tt <= steps[-1])] if steps.size else tt[:0]
            y = res.sol(tau) if tau.size else np.empty((res.y.shape[0], 0))
        f = make_fields(tau, y)
        out = Solution(res.time_name, tau, np.vstack([f["G"], f["k2"], f["n"]]), f, res.status, res.message,
                       res.event, res.t_events, res.y_events, lambda t: common(res.sol(t)), res.nfev)
        out.last_step = res.last_step
        return out

    return _Piece(res, region, finish, common, lam0)


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
    region0 = (kind, sigma)
    gen = _Generic(torque=tq if what == "torque" else drag_as_torque(tq, body, orb), averaging=averaging,
                   quad_tol=quad_tol, body=body, eps=eps, orbit=orb, nu0=nu0, rtol=rtol, atol=atol, method=method,
                   min_spin_ratio=min_spin_ratio, drift_tol=drift_tol, resonance_tol=resonance_tol)
    if what == "drag" and averaging != "numerical":
        gen.drag = tq  # the closed forms (9) of the paper; the torque object serves the crossings
    else:
        gen.torque.check_setup(body, orb)
    gen.spin_cap = K2_SPIN_CAP if through else 1.0
    # the true anomaly at the start: nu = tau/eps + nu0 on a circular orbit (as the drag tensor's closed forms and
    # simulate take it, also when tau_span starts after 0); on an eccentric orbit nu is a state starting at nu0
    nu_start = nu0 + float(tau_span[0]) / eps if eps > 0.0 and orb.e == 0.0 else nu0
    first = gen.piece(region0, tau_span, G0, k2_0, np.array(unit_of_angles(delta0, lam0)), nu_start, lam0, k2_stop)
    rng = np.random.default_rng(seed) if branch == "random" else None  # the only branch rule that draws
    return _through(first, gen, tau_span, tau_eval, through, branch, rng)
