"""The batch of averaged runs with a drag tensor (the closed forms (9), :mod:`._kernel`), integrated together round by
round: a round integrates the members that share a kind of motion and a state layout; a member that reaches the
separatrix in a run through it crosses as its single run does and continues in the next round."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core.batch import integrate_batch, member_records
from ..core.kernel import ARRAY, SCALAR
from ..core.ode import Event, Solution
from . import _kernel as _k
from ._algebra import K2_SPIN_CAP, dk2_labelled
from ._branches import choose_region
from ._members import FIELDS, Members
from ._model import Body, Drag, Orbit, labelled, relabel
from ._separatrix import K2_SWITCH, separatrix_crossing
from ._start import StartRules, check_start
from ._stops import MAX_CROSSINGS, stop_message
from ._torques import GravityGradient, LinearDrag, drag_as_torque

__all__ = ["ClosedRun", "check_members", "closed_batch", "drag_equivalent", "drag_members"]

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
        return A, relabel(kind, d)


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
            rhs, y0, z, ie, args, events = _group_problem(run, A, Id, limit, mem.eps[idx], G[idx], k2[idx], dl[idx],
                                                          lm[idx], nus[idx], mem.nu0[idx])
            rt, at = _k.tolerances(run.rtol, y0.shape[1])
            sol = integrate_batch(rhs, (tau[idx], t1), y0, t_eval=te, rtol=rt, atol=at, events=events, args=args,
                                  time_name="tau", first_step=hnext[idx])
            nfev[idx] += sol.nfev
            hnext[idx] = sol.last_step
            f = _k.fields(A, e, te, sol.y, z, limit, dl[idx], mem.nu0[idx], ie)
            got = np.isfinite(sol.y[:, 0, :])  # the samples this piece covers (a crossing's sample: the later)
            _fill(out, idx, got, f, kd, sigma[idx])
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
                region, stop = _cross(run, i, (kd, int(sigma[i])), tc, Gc, dc, lc, nc, nu_c, crossings[i])
                cr = crossings[i]
                tev["separatrix"][i] = np.array([x["tau"] for x in cr])
                if stop:
                    finish(i, 1, stop_message("crossing", tau=tc, why=stop), "separatrix", tc)
                    continue
                assert region is not None
                kind[i], sigma[i] = region[0], float(region[1])
                tau[i], G[i], k2[i], dl[i], lm[i] = tc, Gc, K2_SWITCH, dc, lc
                if e != 0.0 and nu_c is not None:
                    nus[i] = nu_c
    return _result(mem.batch_shape, te, out, tev, crossings, (status, message, event, nfev, t_final), y_final)


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


def _group_problem(run: ClosedRun, A: Any, Id: Any, limit: bool, eps: np.ndarray, G: np.ndarray, k2: np.ndarray,
                   dl: np.ndarray, lm: np.ndarray, nus: np.ndarray, nu0: np.ndarray) -> tuple[Any, ...]:
    """The vectorised closed forms of members that share a kind and a state layout: right-hand side, initial
    states, the offset ``z`` of ln k^2, ``1/eps``, the extra arguments and the events (as the single run's)."""
    e = run.orbit.e
    lnk_stop = math.log(run.k2_stop)
    r, cap = run.min_spin_ratio, run.spin_cap
    co = _k.DragCoefficients(A, Id)
    y0, z = _k.initial_state(0.0 if limit else eps, G, k2, dl, lm, nus, e)
    args: tuple[np.ndarray, ...] = (*co.args(), z)

    def sep(t: np.ndarray, y: np.ndarray, *a: np.ndarray) -> np.ndarray:
        return np.where(a[5] > 0.0, y[:, 1] - lnk_stop, -1.0)

    def slow(t: np.ndarray, y: np.ndarray, *a: np.ndarray) -> np.ndarray:
        k2_ = np.minimum(_k.k2_of(_AX, y[:, 1], a[5]), cap)
        return _k.nut_freq(_AX, A, np.exp(y[:, 0]), k2_) * a[6] - r

    def rhs_lim(t: np.ndarray, y: np.ndarray, *a: np.ndarray) -> np.ndarray:
        return np.stack(_k.rhs_limit(_AX, A, t, y.T, *a), axis=1)

    def rhs_orb(t: np.ndarray, y: np.ndarray, *a: np.ndarray) -> np.ndarray:
        return np.stack(_k.rhs_orbit(_AX, A, e, t, y.T, *a), axis=1)

    events = [Event(sep, "separatrix", True, 1.0, stop_message("separatrix", k2_max=run.k2_stop))]
    if limit:
        return rhs_lim, y0, z, np.zeros(G.size), (*args, 0.75 * run.orbit.mean_factor * np.cos(dl)), events
    ie = 1.0 / eps
    events.append(Event(slow, "slow_rotation", True, -1.0, stop_message("slow_rotation", min_spin_ratio=r)))
    return rhs_orb, y0, z, ie, (*args, ie, nu0), events


def _fill(out: dict[str, np.ndarray], idx: np.ndarray, got: np.ndarray, f: dict[str, np.ndarray], kind: str,
          sigma: np.ndarray) -> None:
    """The output fields of members ``idx`` where their piece covers the samples (``got``)."""
    for k in FIELDS:
        if k == "kind":
            out[k][idx] = np.where(got, kind, out[k][idx])
        elif k == "sigma":
            out[k][idx] = np.where(got, sigma[:, None], out[k][idx])
        elif k == "n":
            out[k][idx] = np.where(got[:, None, :], f[k], out[k][idx])
        else:
            out[k][idx] = np.where(got, f[k], out[k][idx])


def _cross(run: ClosedRun, i: int, source: tuple[str, int], tc: float, G: float, delta: float, lam: float,
           n: np.ndarray, nu: float | None, cr: list[dict[str, Any]]) -> tuple[tuple[str, int] | None, str]:
    """Member ``i`` at a separatrix crossing, as the single run: the capture probabilities, the region chosen, the
    crossing appended to ``cr``; the region (or None) and why the run cannot go on (empty when it can)."""
    tq = drag_as_torque(Drag(run.tensors[i]), run.body, run.orbit)
    c = separatrix_crossing(run.body, tq, G, delta, lam, nu, source, orbit=run.orbit)
    region, why = choose_region(c, run.branch, len(cr), run.rng)
    if region is not None:
        An, Idn = run.labelled(region[0], np.array([i]))
        if dk2_labelled(An, tuple(float(v[0]) for v in Idn), K2_SWITCH) >= 0.0:  # type: ignore[arg-type]
            why = stop_message("attracts", region=region)
            region = None
    cr.append({"tau": tc, "source": source, "region": region, "probabilities": dict(c.probabilities),
               "drifts": dict(c.drifts), "G": G, "n": n})
    stop = why if region is None else ""
    if not stop and (len(cr) > MAX_CROSSINGS or (len(cr) > 1 and tc <= cr[-2]["tau"])):
        stop = stop_message("stall", n=len(cr), tau=tc)
    return region, stop


def _result(shape: tuple[int, ...], te: np.ndarray, out: dict[str, np.ndarray], tev: dict[str, np.ndarray],
            crossings: np.ndarray, records: tuple[np.ndarray, ...], y_final: np.ndarray) -> Solution:
    """The batch Solution of the closed-form runs (raw rows G, k2, n; crossings per member)."""
    status, message, event, nfev, t_final = records
    data = {k: v.reshape(shape + v.shape[1:]) for k, v in out.items()}
    Y = np.concatenate([out["G"][:, None], out["k2"][:, None], out["n"]], axis=1)  # rows G, k2, n
    t_events = {name: arr.reshape(shape) for name, arr in tev.items()}
    sol = Solution("tau", te, Y.reshape(shape + Y.shape[1:]), data, status.reshape(shape), message.reshape(shape),
                   event.reshape(shape), t_events, {}, None, nfev.reshape(shape), batch_shape=shape,
                   t_final=t_final.reshape(shape), y_final=y_final.reshape((*shape, 5)))
    sol.crossings = crossings.reshape(shape)  # type: ignore[attr-defined]  # per member, as the single run's
    return sol
