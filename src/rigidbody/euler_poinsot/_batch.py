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

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core.batch import integrate_batch, member_records
from ..core.kernel import ARRAY, SCALAR
from ..core.ode import Event, Solution
from ..core.validate import positive, real
from . import _kernel as _k
from ._algebra import K2_SPIN_CAP, dk2_labelled
from ._branches import check_branch, choose_region
from ._checks import check_averaging, check_sigma
from ._full import initial_state, run_full
from ._fullbatch import FullRun, full_batch
from ._members import FIELDS, Members, common_checks, drag_batch, member_inputs, one_by_one
from ._model import Body, Drag, Orbit, as_orbit, labelled
from ._run import run_averaged
from ._separatrix import K2_SWITCH, separatrix_crossing
from ._start import StartRules, check_start
from ._stops import MAX_CROSSINGS, stop_message
from ._torques import GravityGradient, LinearDrag, drag_as_torque, probe, resolve

__all__ = ["averaged_batch", "closed_batch", "member_inputs", "simulate_batch"]

_AX = ARRAY
_SC = SCALAR









@dataclass
class ClosedRun:
    """What the members of a closed-form batch share: body, orbit, options; the drag diagonal (unlabelled, one
    entry per member) and the drag tensors (for the capture probabilities at a crossing)."""

    body: Body
    I: tuple[np.ndarray, np.ndarray, np.ndarray]
    tensors: np.ndarray
    orbit: Orbit
    rtol: float
    k2_max: float | None
    min_spin_ratio: float
    sigma: int = 1
    branch: Any = "likely"
    rng: Any = None

    @property
    def through(self) -> bool:
        return self.k2_max is None

    @property
    def k2_stop(self) -> float:
        return K2_SWITCH if self.k2_max is None else self.k2_max

    @property
    def spin_cap(self) -> float:
        return K2_SPIN_CAP if self.k2_max is None else 1.0

    def labelled(self, kind: str, idx: np.ndarray) -> tuple[tuple[float, float, float], tuple[Any, Any, Any]]:
        """Labelled moments and the members' labelled drag diagonal for ``kind``."""
        A = labelled(self.body, kind)
        d = (self.I[0][idx], self.I[1][idx], self.I[2][idx])
        return A, (d if kind == "max" else (d[2], d[1], d[0]))


def drag_members(mem: Members, tensors: np.ndarray) -> tuple[tuple[np.ndarray, np.ndarray, np.ndarray], np.ndarray]:
    """The members' drag tensors (validated like :class:`Drag`; an invalid one refuses its member): their
    diagonals and the tensors, flat over the batch."""
    T = np.broadcast_to(tensors, (*mem.batch_shape, 3, 3)).reshape(-1, 3, 3)
    diag = np.full((T.shape[0], 3), np.nan)
    one = None
    for i in range(T.shape[0]):
        if one is not None and tensors.ndim == 2:
            diag[i] = one
            continue
        try:
            diag[i] = Drag(T[i]).diag
            one = diag[i]
        except ValueError as exc:
            mem.refused.setdefault(i, str(exc))
    return (diag[:, 0], diag[:, 1], diag[:, 2]), T


def check_members(mem: Members, run: ClosedRun, full: bool = False, u0: Any = None, psi0: Any = None) -> None:
    """The single run's start checks (:func:`._start.check_start`), member by member: a refused member gets the
    single call's message (``full``: those of :func:`simulate`, with the members' phases ``u0``, ``psi0``)."""
    rules = StartRules(run.body, run.k2_max, run.min_spin_ratio, full)
    for i in range(mem.eps.size):
        if i in mem.refused:
            continue
        phase = (float(u0[i]), float(psi0[i])) if full else (0.0, 0.0)
        try:
            check_start(rules, mem.kind[i], float(mem.eps[i]), float(mem.G0[i]), float(mem.k2_0[i]),
                        float(mem.delta0[i]), float(mem.lam0[i]), float(mem.nu0[i]), *phase)
        except ValueError as exc:
            mem.refused[i] = str(exc)


# --------------------------------------------------------------------------------------------------
# the closed-form batch, round by round
# --------------------------------------------------------------------------------------------------
def closed_batch(run: ClosedRun, mem: Members, tau_span: tuple[float, float], te: np.ndarray) -> Solution:
    """The batch of closed-form runs (``te`` the common output grid); ``mem.refused`` members end at once."""
    B = mem.eps.size
    nt = te.size
    t0, t1 = float(tau_span[0]), float(tau_span[1])
    e = run.orbit.e
    out = {k: np.full((B, 3, nt) if k == "n" else (B, nt), np.nan) for k in FIELDS if k != "kind"}
    out["kind"] = np.full((B, nt), "", dtype="<U3")
    status, message, event, nfev, t_final = member_records(B, t0)
    y_final = np.full((B, 5), np.nan)  # rows G, k2, n at each member's end
    none = np.empty(0)
    none.setflags(write=False)
    tev: dict[str, np.ndarray] = {}
    for name in ("separatrix", "slow_rotation"):
        tev[name] = np.empty(B, dtype=object)
        tev[name].fill(none)
    crossings = np.empty(B, dtype=object)
    for i in range(B):
        crossings[i] = []
    for i, msg in mem.refused.items():
        message[i] = msg
    # the members' current piece: kind, sense, start time and state (G, k2, delta, lambda, nu at the start)
    kind = mem.kind.copy()
    sigma = np.full(B, float(run.sigma))
    tau = np.full(B, t0)
    G, k2, dl, lm, nus = mem.G0.copy(), mem.k2_0.copy(), mem.delta0.copy(), mem.lam0.copy(), mem.nu0.copy()
    active = np.ones(B, dtype=bool)
    active[list(mem.refused)] = False
    hnext = np.full(B, np.nan)
    lnk_stop = math.log(run.k2_stop)
    r, cap = run.min_spin_ratio, run.spin_cap

    def rhs_lim(A: Any) -> Any:
        def f(t: np.ndarray, y: np.ndarray, *a: np.ndarray) -> np.ndarray:
            return np.stack(_k.rhs_limit(_AX, A, t, y.T, *a), axis=1)
        return f

    def rhs_orb(A: Any) -> Any:
        def f(t: np.ndarray, y: np.ndarray, *a: np.ndarray) -> np.ndarray:
            return np.stack(_k.rhs_orbit(_AX, A, e, t, y.T, *a), axis=1)
        return f

    def sep(t: np.ndarray, y: np.ndarray, *a: np.ndarray) -> np.ndarray:
        return np.where(a[5] > 0.0, y[:, 1] - lnk_stop, -1.0)

    def slow(A: Any) -> Any:
        def f(t: np.ndarray, y: np.ndarray, *a: np.ndarray) -> np.ndarray:
            k2_ = np.minimum(_k.k2_of(_AX, y[:, 1], a[5]), cap)
            return _k.nut_freq(_AX, A, np.exp(y[:, 0]), k2_) * a[6] - r
        return f

    def finish(i: int, st: int, msg: str, ev: str | None, tend: float) -> None:
        status[i], message[i], event[i], t_final[i] = st, msg, ev, tend
        active[i] = False

    while np.any(active):
        groups = []
        for kd in ("max", "min"):
            for limit in (True, False):
                idx = np.nonzero(active & (kind == kd) & ((mem.eps == 0.0) if limit else (mem.eps > 0.0)))[0]
                if idx.size:
                    groups.append((kd, limit, idx))
        for kd, limit, idx in groups:
            A, Id = run.labelled(kd, idx)
            co = _k.DragCoefficients(A, Id)
            y0, z = _k.initial_state(0.0 if limit else mem.eps[idx], G[idx], k2[idx], dl[idx], lm[idx], nus[idx], e)
            args: tuple[np.ndarray, ...] = (*co.args(), z)
            events = [Event(sep, "separatrix", True, 1.0, stop_message("separatrix", k2_max=run.k2_stop))]
            if limit:
                args = (*args, 0.75 * run.orbit.mean_factor * np.cos(dl[idx]))
                ie = np.zeros(idx.size)
                rhs = rhs_lim(A)
            else:
                ie = 1.0 / mem.eps[idx]
                args = (*args, ie, mem.nu0[idx])
                rhs = rhs_orb(A)
                events.append(Event(slow(A), "slow_rotation", True, -1.0,
                                    stop_message("slow_rotation", min_spin_ratio=r)))
            rt, at = _k.tolerances(run.rtol, y0.shape[1])
            sol = integrate_batch(rhs, (tau[idx], t1), y0, t_eval=te, rtol=rt, atol=at, events=events, args=args,
                                  time_name="tau", first_step=hnext[idx])
            nfev[idx] += sol.nfev
            hnext[idx] = sol.last_step
            f = _k.fields(A, e, te, sol.y, z, limit, dl[idx], mem.nu0[idx], ie)
            got = np.isfinite(sol.y[:, 0, :])  # the samples this piece covers (a crossing's sample: the later)
            for k in FIELDS:
                if k == "kind":
                    out[k][idx] = np.where(got, kd, out[k][idx])
                elif k == "sigma":
                    out[k][idx] = np.where(got, sigma[idx, None], out[k][idx])
                elif k == "n":
                    out[k][idx] = np.where(got[:, None, :], f[k], out[k][idx])
                else:
                    out[k][idx] = np.where(got, f[k], out[k][idx])
            tev["slow_rotation"][idx] = sol.t_events["slow_rotation"] if "slow_rotation" in sol.t_events else \
                tev["slow_rotation"][idx]
            ff = _k.fields(A, e, np.zeros(1), sol.y_final[:, :, None], z, limit, dl[idx], mem.nu0[idx], ie)
            y_final[idx] = np.concatenate([ff["G"], ff["k2"], ff["n"][:, :, 0]], axis=1)
            for j, i in enumerate(idx.tolist()):
                st_, ev_ = int(sol.status[j]), sol.event[j]
                if not (run.through and st_ == 1 and ev_ == "separatrix"):
                    if not run.through and ev_ == "separatrix":
                        tev["separatrix"][i] = sol.t_events["separatrix"][j]
                    finish(i, st_, str(sol.message[j]), ev_, float(sol.t_final[j]))
                    continue
                # a crossing: the state there, the capture probabilities, the region (as the single run does)
                tc = float(sol.t_final[j])
                yf = sol.y_final[j]
                fc = _k.fields(A, e, np.array([tc]), yf[:, None], z[j], limit, dl[i], mem.nu0[i], ie[j])
                Gc, dc, lc = float(fc["G"][0]), float(fc["delta"][0]), float(fc["lam"][0])
                nc = fc["n"][:, 0]
                nu_c = float(fc["nu"][0]) if mem.eps[i] > 0.0 else None
                tq = drag_as_torque(Drag(run.tensors[i]), run.body, run.orbit)
                c = separatrix_crossing(run.body, tq, Gc, dc, lc, nu_c, (kd, int(sigma[i])), orbit=run.orbit)
                region, why = choose_region(c, run.branch, len(crossings[i]), run.rng)
                if region is not None:
                    An, Idn = run.labelled(region[0], np.array([i]))
                    if dk2_labelled(An, tuple(float(v[0]) for v in Idn), K2_SWITCH) >= 0.0:  # type: ignore[arg-type]
                        why = stop_message("attracts", region=region)
                        region = None
                crossings[i].append({"tau": tc, "source": (kd, int(sigma[i])), "region": region,
                                     "probabilities": dict(c.probabilities), "drifts": dict(c.drifts), "G": Gc,
                                     "n": nc})
                stop = why if region is None else ""
                cr = crossings[i]
                if not stop and (len(cr) > MAX_CROSSINGS or (len(cr) > 1 and tc <= cr[-2]["tau"])):
                    stop = stop_message("stall", n=len(cr), tau=tc)
                tev["separatrix"][i] = np.array([x["tau"] for x in cr])
                if stop:
                    finish(i, 1, stop_message("crossing", tau=tc, why=stop), "separatrix", tc)
                    continue
                assert region is not None
                kind[i], sigma[i] = region[0], float(region[1])
                tau[i], G[i], k2[i], dl[i], lm[i] = tc, Gc, K2_SWITCH, dc, lc
                if e != 0.0 and nu_c is not None:
                    nus[i] = nu_c
    shape = mem.batch_shape
    data = {k: v.reshape(shape + v.shape[1:]) for k, v in out.items()}
    Y = np.concatenate([out["G"][:, None], out["k2"][:, None], out["n"]], axis=1)  # rows G, k2, n
    t_events = {name: arr.reshape(shape) for name, arr in tev.items()}
    sol = Solution("tau", te, Y.reshape(shape + Y.shape[1:]), data, status.reshape(shape), message.reshape(shape),
                   event.reshape(shape), t_events, {}, None, nfev.reshape(shape), batch_shape=shape,
                   t_final=t_final.reshape(shape), y_final=y_final.reshape((*shape, 5)))
    sol.crossings = crossings.reshape(shape)  # type: ignore[attr-defined]  # per member, as the single run's
    return sol












def drag_equivalent(torque: Any, body: Body, orbit: Orbit) -> np.ndarray | None:
    """The drag tensor whose meaning (linear drag plus the gravity gradient) a torque object has, or None: a sum
    of :class:`LinearDrag` parts and one :class:`GravityGradient` of this body and orbit in the module's scaling
    (``omega0 = 1``). Such a batch runs the closed forms of the drag tensor vectorised over its members."""
    parts = torque.parts()
    gg = [p for p in parts if isinstance(p, GravityGradient)]
    lin = [p for p in parts if isinstance(p, LinearDrag)]
    if len(gg) != 1 or not lin or len(gg) + len(lin) != len(parts):
        return None
    g = gg[0]
    if g.omega0 != 1.0 or g.body != body or g.orbit != orbit:
        return None
    return np.sum([np.asarray(p.I, dtype=float) for p in lin], axis=0)




def averaged_batch(body: Any, torque: Any, eps: Any, G0: Any, k2_0: Any, delta0: Any, lam0: Any,
                   tau_span: Any, tau_eval: Any, nu0: Any, opts: dict[str, Any]) -> Solution:
    """The batch branch of :func:`rigidbody.euler_poinsot.averaged`.

    ``opts`` holds the keyword options of the call (validated here as the single run validates them); the members
    of the engine path run one by one through the single run.
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
        what, tq = resolve(torque)
        if what == "drag" and opts["averaging"] == "auto":
            tensors = tq.I
        elif what == "torque" and opts["averaging"] == "auto":
            tensors = drag_equivalent(tq, body, orb)  # the paper's two torques as objects: the same closed forms
    elif opts["averaging"] != "auto":
        raise ValueError("a batch of drag tensors is integrated with the closed forms (averaging='auto')")
    if tensors is not None:
        I, T = drag_members(mem, tensors)
        run = ClosedRun(body, I, T, orb, float(opts["rtol"]), k2_max, min_spin, sigma, branch,
                        np.random.default_rng(opts["seed"]))
        check_members(mem, run)
        return closed_batch(run, mem, (t0, t1), te)

    # the engine path: member by member through the single run (its adaptive quadrature is per state)
    one = {k: v for k, v in opts.items() if k not in ("T0", "kind")}

    def call(eps_: float, G0_: float, k2_: float, d0: float, l0: float, n0: float, te_: np.ndarray,
             kind: str) -> Solution:
        return run_averaged(body, torque, eps_, G0_, k2_, d0, l0, (t0, t1), te_, n0, kind=kind, T0=None, **one)

    return one_by_one(call, mem, te, FIELDS, kind=mem.kind)


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
    what, tq = resolve(torque)
    if what == "torque":
        tq._check_setup(body, orb)
    if opts["formulation"] == "angles" or opts["method"] != "DOP853":
        one = {k: v for k, v in opts.items() if k not in ("T0", "kind", "u0", "psi0")}

        def call(eps_: float, G0_: float, k2_: float, d0: float, l0: float, n0: float, te_: np.ndarray,
                 u0: float, psi0: float, kind: str) -> Solution:
            return run_full(body, torque, eps_, G0_, k2_, d0, l0, (t0, t1), te_, n0, u0=u0, psi0=psi0, kind=kind,
                            T0=None, **one)

        names = ("G", "T", "k2", "delta", "lam", "nu", "n", "kind", "sigma")
        return one_by_one(call, mem, te, names, u0=ph, psi0=ps, kind=mem.kind)
    # the single run's checks, member by member
    zero = np.zeros(1)
    crun = ClosedRun(body, (zero, zero, zero), np.zeros((1, 3, 3)), orb, float(opts["rtol"]), k2_max, min_spin)
    check_members(mem, crun, True, ph, ps)
    run = FullRun(body, what, tq, orb, mem.kind, sigma, float(opts["rtol"]), float(opts["atol"]), k2_max, min_spin,
                  K2_SPIN_CAP if k2_max is None else 1.0)
    if what == "torque":  # one evaluation at a valid member's start, with the single run's message on failure
        good = [i for i in range(mem.eps.size) if i not in mem.refused]
        if good:
            i = good[0]
            st = initial_state(body, float(mem.G0[i]), float(mem.k2_0[i]), float(mem.delta0[i]), float(mem.lam0[i]),
                               kind=mem.kind[i], u0=float(ph[i]), psi0=float(ps[i]), sigma=sigma)
            probe(tq, st["g"] / body.A, st["R"], float(mem.nu0[i]))
    return full_batch(run, mem, ph, ps, (t0, t1), te)
