r"""The full (unaveraged) equations as a problem for the piecewise driver: one run and a batch.

:func:`run_full` is the single call of :func:`rigidbody.euler_poinsot.simulate` (a batch of one, on the scalar
integrator), :func:`run_full_members` runs any members. A batch in the ``formulation='body'`` integrates its
members together: Euler's equations
for the body components :math:`\mathbf g` of :math:`\mathbf G` and the attitude quaternion (body -> orbital
axes), in the slow time :math:`\tau`, with :math:`d\mathbf g/d\tau = \varepsilon^{-2}\mathbf g\times
\boldsymbol\omega + \mathbf M`. The members share the body, the torque, the orbit, ``tau_span`` and the
options; their initial slow variables, the phase ``u0``, ``psi0`` of the Euler--Poinsot motion, ``nu0`` and
``eps`` are per member. The torque is evaluated on all active members at once: the drag tensor (drag plus
gravity gradient) by its formula, a torque object through its vectorised protocol ``torque(omega, C, nu)``
(arrays of shape ``(m, 3)``, ``(m, 3, 3)``, ``(m,)``).

The direction of :math:`\mathbf G` in the orbital axes is output as ``delta`` and a continuous ``lam``: the
azimuth ``atan2(n2, n1)`` plus :math:`2\pi` for every passage through its branch cut (``n2 = 0`` with
``n1 < 0``), located as events of the integration, so the output grid may be as coarse as one likes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core.euler import dcm_from_unit_quat
from ..core.ode import Event, Solution
from ..core.piecewise import MemberRecords, PieceEnd, PieceSpec, Stop, run_pieces
from ..core.validate import result_message
from . import _kernel as _k
from ._full import FullKinds, FullSingle, check_full, full_single
from ._fullkinds import TriaxialKinds
from ._gravity import drag_gravity, radius_in_body
from ._members import Members, assemble
from ._model import Body, Orbit
from ._protocol import ROLE, evaluate
from ._stops import stop_message
from ._symbody import SymmetricBody
from ._torques import probe

__all__ = ["FullRun", "probe_members", "run_full", "run_full_members"]

PRODUCER = "euler_poinsot.simulate"


@dataclass
class FullRun:
    """What the members share: the body, the drag tensor whose meaning the torque has (its formula written out) or
    None, the torque object, the orbit, the body's part of the run (``kinds``: each member's start, the events and
    the body-shape fields; see :mod:`._fullkinds`), tolerances, the formulation and the method."""

    body: Body | SymmetricBody
    tensor: np.ndarray | None
    torque: Any
    orbit: Orbit
    kinds: FullKinds
    rtol: float
    atol: float
    formulation: str = "body"
    method: str = "DOP853"


class FullProblem:
    """The full equations of the members of ``mem`` as a problem for :func:`rigidbody.core.piecewise.run_pieces`:
    one piece per member, ended by the end of the span or a terminal event (none is continued). ``te``: the common
    output grid of a batch, or the ``tau_eval`` of one run (``single``). The body-frame members of a batch share
    the mode ``'body'`` (vectorised together, :func:`_rhs`); the ``'angles'`` formulation and a ``method`` other
    than DOP853 give each member a mode of its own (the scalar integrator, member by member)."""

    continues: tuple[str, ...] = ()

    def __init__(self, run: FullRun, mem: Members, te: Any, single: bool) -> None:
        self.run, self.mem, self.te, self.single = run, mem, te, single
        B = mem.eps.size
        self.ns = 7 if run.orbit.e == 0.0 else 8
        self.solutions: list[Solution | str] = [mem.refused.get(i, "") for i in range(B)]
        self.t_bad = np.full(B, np.nan)
        self.vector = run.formulation == "body" and run.method == "DOP853" and not single
        if self.vector:
            nt = te.size
            self.Y = np.full((B, self.ns, nt), np.nan)
            self.lam_shift = np.zeros((B, nt))
            none = np.empty(0)
            none.setflags(write=False)
            self.t_ev = {name: np.empty(B, dtype=object) for name in run.kinds.event_names}
            for arr in self.t_ev.values():
                arr.fill(none)
        self.singles: dict[int, FullSingle] = {}

    def mode(self, i: int) -> Any:
        return "body" if self.vector else ("one", i)

    def piece(self, mode: Any, members: list[int], scalar: bool, tau: np.ndarray) -> PieceSpec:
        run, mem = self.run, self.mem
        if scalar:
            i = members[0]
            G0, delta0, lam0 = float(mem.G0[i]), float(mem.delta0[i]), float(mem.lam0[i])
            one = full_single(run.body, run.tensor, run.torque, run.orbit, float(mem.eps[i]), G0, delta0, lam0,
                              float(mem.nu0[i]), run.kinds.start(i, G0, delta0, lam0), run.kinds, i,
                              formulation=run.formulation, cuts=self.vector)
            self.singles[i] = one
            return PieceSpec(one.rhs, one.y0, run.rtol, run.atol, one.events, (),
                             self.te if self.vector else None, True, run.method)
        return self._vector_piece(np.array(members))

    def _vector_piece(self, idx: np.ndarray) -> PieceSpec:
        run, mem = self.run, self.mem
        Ab = np.array([run.body.A1, run.body.A2, run.body.A3])
        y0 = _initial_states(run, mem, idx, self.ns)
        ie = 1.0 / mem.eps[idx]

        def GD(y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            g2 = y[:, 0:3] ** 2
            G2 = g2.sum(axis=1)
            return np.sqrt(G2), G2 / (g2 / Ab).sum(axis=1)

        # the two cut events are evaluated in turn on the same arrays: one evaluation serves both (the cache holds
        # the arrays themselves, so their ids cannot be reused while cached)
        ncache: list[Any] = [None, None]

        def n2(t: np.ndarray, y: np.ndarray, *a: np.ndarray) -> np.ndarray:
            if ncache[0] is not y:
                ncache[:] = [y, _n_of(y)[:, 1]]
            return ncache[1]

        events, extra = run.kinds.vector_events(idx, GD)
        # the fourth arg: each member's index, to note where its torque turned non-finite (t_bad; see _rhs)
        args = (ie, ie * ie, mem.nu0[idx], idx.astype(float), *extra)
        # passages of the azimuth through its branch cut (n2 = 0 with n1 < 0), both ways
        events = [*events, Event(n2, "_cut_up", False, 1.0, ""), Event(n2, "_cut_down", False, -1.0, "")]
        return PieceSpec(_rhs(run, self.t_bad), y0, run.rtol, run.atol, events, args, self.te)

    def record(self, mode: Any, members: list[int], sol: Solution, end: PieceEnd) -> None:
        if not self.vector:  # one member by the single call's route: its result on te (or its steps)
            i = members[0]
            self.solutions[i] = self.singles.pop(i).finish(sol, self.te)
            return
        idx = np.array(members)
        te = self.te
        if sol.batch_shape:
            self.Y[idx] = sol.y
            tev, yev = sol.t_events, sol.y_events
        else:  # a member alone in the batch: the scalar integrator, its samples those of te it reached
            self.singles.pop(members[0]).misfire.settle(sol)
            end.message[0] = str(sol.message)
            self.Y[idx[0]][:, np.searchsorted(te, sol.time)] = sol.y
            tev = {k: _one(v) for k, v in sol.t_events.items()}
            yev = {k: _one(v) for k, v in sol.y_events.items()}
        for name in self.t_ev:
            self.t_ev[name][idx] = tev[name]
        _cut_shifts(tev, yev, idx, te, self.lam_shift)

    def on_event(self, mode: Any, i: int, j: int, end: PieceEnd) -> Stop:
        raise AssertionError("the full equations continue no event")  # continues is empty: never called

    def result(self, rec: MemberRecords) -> Solution:
        mem = self.mem
        shape = mem.batch_shape
        if self.single:
            out = self.solutions[0]
            assert isinstance(out, Solution)
            return out
        if not self.vector:
            return assemble(self.solutions, shape, self.te, self.run.kinds.field_names, PRODUCER)
        # a member whose torque turned non-finite where it failed: the message names the torque and the time
        why = result_message(getattr(self.run.torque, "fun", self.run.torque), (3,), "non-finite values (NaN or inf)",
                             ROLE)
        for i in np.nonzero((rec.status == -1) & (self.t_bad >= rec.t_final))[0].tolist():
            rec.message[i] = stop_message("torque", tau=self.t_bad[i], why=why)
        data = _fields(self.run, self.Y, self.lam_shift, mem, self.te)
        data = {k: v.reshape(shape + v.shape[1:]) for k, v in data.items()}
        return Solution.build(producer=PRODUCER, time_name="tau", time=self.te,
                              y=self.Y.reshape(shape + self.Y.shape[1:]), fields=data, status=rec.status.reshape(shape),
                              message=rec.message.reshape(shape), event=rec.event.reshape(shape),
                              t_events={k: v.reshape(shape) for k, v in self.t_ev.items()},
                              nfev=rec.nfev.reshape(shape), t_final=rec.t_final.reshape(shape))


def run_full_members(run: FullRun, mem: Members, tau_span: tuple[float, float], te: Any, single: bool) -> Solution:
    """Integrate the full equations of the members ``mem`` over ``tau_span`` through the piecewise driver
    (``mem.refused``: members that end at once with status -1 and their message; ``single``: one run, whose errors
    raise and whose output is on ``te``, the call's ``tau_eval``, or the integrator's steps)."""
    pb = FullProblem(run, mem, te, single)
    rec = MemberRecords.start([pb.mode(i) for i in range(mem.eps.size)], float(tau_span[0]), mem.refused)
    run_pieces(pb, rec, float(tau_span[1]), strict=single)
    if not pb.vector:
        for i in range(mem.eps.size):  # a member the driver ended before its piece ran (its start failed)
            if rec.mode[i] is None and pb.solutions[i] == "" and rec.status[i] == -1:
                pb.solutions[i] = str(rec.message[i])
    return pb.result(rec)


def probe_members(run: FullRun, mem: Members) -> None:
    """Evaluate the torque object once at a valid member's start when the members are integrated together, with the
    single run's message on failure (member by member, each member's start probes it)."""
    if run.tensor is None and run.formulation == "body" and run.method == "DOP853":
        good = [i for i in range(mem.eps.size) if i not in mem.refused]
        if good:
            i = good[0]
            st = run.kinds.start(i, float(mem.G0[i]), float(mem.delta0[i]), float(mem.lam0[i]))
            probe(run.torque, st["g"] / run.body.A, st["R"], float(mem.nu0[i]))


def _one(v: Any) -> np.ndarray:
    out = np.empty(1, dtype=object)
    out[0] = np.asarray(v, dtype=float)
    return out


def _initial_states(run: FullRun, mem: Members, idx: np.ndarray, ns: int) -> np.ndarray:
    """The body-frame start (g, q[, nu]) of each member in ``idx``."""
    y0 = np.empty((idx.size, ns))
    for j, i in enumerate(idx.tolist()):
        st = run.kinds.start(i, float(mem.G0[i]), float(mem.delta0[i]), float(mem.lam0[i]))
        y0[j, :3], y0[j, 3:7] = st["g"], st["q"]
        if ns == 8:
            y0[j, 7] = mem.nu0[i]
    return y0


def _n_of(y: np.ndarray) -> np.ndarray:
    """The unit vector of G in the orbital axes from body-frame states ``y`` of shape ``(m, n_state)``."""
    q = y[:, 3:7] / np.linalg.norm(y[:, 3:7], axis=1, keepdims=True)
    g = np.einsum("mij,mj->mi", dcm_from_unit_quat(*q.T), y[:, 0:3])
    return g / np.sqrt((y[:, 0:3] ** 2).sum(axis=1))[:, None]


def _cut_shifts(t_events: Any, y_events: Any, idx: np.ndarray, te: np.ndarray, lam_shift: np.ndarray) -> None:
    """Add 2 pi to lambda of each member at every passage of its azimuth through the branch cut (n2 = 0, n1 < 0)."""
    for j, i in enumerate(idx):
        for name, sign in (("_cut_up", -1.0), ("_cut_down", 1.0)):
            tc, yc = np.asarray(t_events[name][j], dtype=float), np.asarray(y_events[name][j], dtype=float)
            if tc.size:
                tc = tc[_n_of(yc.reshape(tc.size, -1))[:, 0] < 0.0]
                lam_shift[i] += sign * 2.0 * math.pi * (tc[:, None] <= te[None, :]).sum(axis=0)


def _rhs(run: FullRun, t_bad: np.ndarray) -> Any:
    """The vectorised body-frame equations of the members (drag tensor plus gravity gradient written out, or the
    torque object through its vectorised protocol; where it turns non-finite, the time is noted in ``t_bad``)."""
    A1, A2, A3 = run.body.A1, run.body.A2, run.body.A3
    e = run.orbit.e
    drag = run.tensor is not None
    if drag:
        rows = tuple(tuple(row) for row in np.asarray(run.tensor, dtype=float).tolist())

    def rhs(t: np.ndarray, y: np.ndarray, ie: np.ndarray, ie2: np.ndarray, nu0: np.ndarray, who: np.ndarray,
            *rest: np.ndarray) -> np.ndarray:
        g1, g2, g3, w, x, yq, z = y[:, 0], y[:, 1], y[:, 2], y[:, 3], y[:, 4], y[:, 5], y[:, 6]
        nrm = np.sqrt(w * w + x * x + yq * yq + z * z)
        w, x, yq, z = w / nrm, x / nrm, yq / nrm, z / nrm
        o1, o2, o3 = g1 / A1, g2 / A2, g3 / A3
        nu = t * ie + nu0 if e == 0.0 else y[:, 7]
        if drag:  # drag plus gravity gradient, written out as in the single run
            r = radius_in_body(w, x, yq, z, np.cos(nu), np.sin(nu))
            f3 = 3.0 * _k.orbit_factor(np, e, nu) if e != 0.0 else 3.0
            L1, L2, L3 = drag_gravity((A1, A2, A3), f3, r, rows, (o1, o2, o3))
        else:  # the torque's type and shape checked, its finiteness per member (a NaN ends that member only)
            C = dcm_from_unit_quat(w, x, yq, z)
            M = np.broadcast_to(evaluate(run.torque, np.stack([o1, o2, o3], axis=1), C, nu, (t.size, 3),
                                         finite=False), (t.size, 3))
            bad = ~np.isfinite(M).all(axis=1)
            if bad.any():
                t_bad[who[bad].astype(int)] = t[bad]
            L1, L2, L3 = M[:, 0], M[:, 1], M[:, 2]
        out = np.empty_like(y)
        out[:, 0] = (g2 * o3 - g3 * o2) * ie2 + L1
        out[:, 1] = (g3 * o1 - g1 * o3) * ie2 + L2
        out[:, 2] = (g1 * o2 - g2 * o1) * ie2 + L3
        h = 0.5 * ie2
        out[:, 3] = h * (-x * o1 - yq * o2 - z * o3)
        out[:, 4] = h * (w * o1 + yq * o3 - z * o2)
        out[:, 5] = h * (w * o2 - x * o3 + z * o1)
        out[:, 6] = h * (w * o3 + x * o2 - yq * o1)
        if e != 0.0:
            out[:, 7] = ie * _k.nu_rate(np, e, y[:, 7])
        return out

    return rhs


def _fields(run: FullRun, Y: np.ndarray, lam_shift: np.ndarray, mem: Members, te: np.ndarray) -> dict[str, np.ndarray]:
    """The output fields of the batch from its raw rows ``Y`` (g, q[, nu]; NaN after a member's end), lambda
    continuous from the counted passages through the branch cut (``lam_shift``)."""
    A1, A2, A3 = run.body.A1, run.body.A2, run.body.A3
    g = Y[:, 0:3]
    qn = Y[:, 3:7] / np.linalg.norm(Y[:, 3:7], axis=1, keepdims=True)
    R = dcm_from_unit_quat(*np.moveaxis(qn, 1, 0))  # (B, nt, 3, 3)
    n = np.einsum("bkij,bjk->bik", R, g)
    G = np.sqrt((g * g).sum(axis=1))
    n = n / G[:, None, :]
    T = 0.5 * (g[:, 0] ** 2 / A1 + g[:, 1] ** 2 / A2 + g[:, 2] ** 2 / A3)
    nan = np.isnan(G)
    az = np.arctan2(n[:, 1], n[:, 0])
    lam = az + lam_shift
    # the branch of the initial value given by the user
    lam = lam + 2.0 * math.pi * np.round((mem.lam0[:, None] - lam[:, :1]) / (2.0 * math.pi))
    if run.orbit.e == 0.0:
        with np.errstate(divide="ignore", invalid="ignore"):  # refused members (eps = 0) are NaN anyway
            nu = np.where(nan, np.nan, te[None, :] / mem.eps[:, None] + mem.nu0[:, None])
    else:
        nu = Y[:, 7]
    return {"G": G, "T": T, **run.kinds.vector_fields(g, G, T), "delta": np.arccos(np.clip(n[:, 2], -1.0, 1.0)),
            "n": n, "nu": nu, "lam": lam, "g": g, "q": qn}


def run_full(body: Any, torque: Any, eps: Any, G0: Any, k2_0: Any, delta0: Any, lam0: Any, tau_span: Any,
             tau_eval: Any, nu0: Any, *, kind: str | None, T0: Any, orbit: Orbit | None, u0: Any, psi0: Any,
             sigma: int, formulation: str, rtol: float, atol: float, method: str, k2_max: float | None,
             min_spin_ratio: float) -> Solution:
    """One run of the full equations (the single call of :func:`rigidbody.euler_poinsot.simulate`): the inputs
    checked (:func:`._full.check_full`), then a batch of one through the driver."""
    tensor, tq, orb, kind, k2_max, min_spin_ratio, start, u0, psi0 = check_full(
        body, torque, eps, G0, k2_0, delta0, lam0, tau_span, tau_eval, nu0, kind=kind, T0=T0, orbit=orbit, u0=u0,
        psi0=psi0, formulation=formulation, rtol=rtol, atol=atol, k2_max=k2_max, min_spin_ratio=min_spin_ratio)
    one = np.ones(1)
    eps, G0, k2_0, delta0, lam0, nu0 = start
    mem = Members((), eps * one, G0 * one, k2_0 * one, delta0 * one, lam0 * one, nu0 * one,
                  np.array([kind], dtype=object))
    kinds = TriaxialKinds(body, mem.k2_0, mem.kind, u0 * one, psi0 * one, sigma, k2_max, min_spin_ratio)
    run = FullRun(body, tensor, tq, orb, kinds, rtol, atol, formulation, method)
    return run_full_members(run, mem, (float(tau_span[0]), float(tau_span[1])), tau_eval, True)
