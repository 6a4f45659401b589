r"""The closed-form averaged system (9) (drag plus gravity gradient, :mod:`._kernel`) as a problem for the
piecewise driver :func:`rigidbody.core.piecewise.run_pieces`: one run is a batch of one.

A member's mode is its kind of motion and its state layout (``eps = 0``: :math:`(\ln G, \ln k^2, \lambda)`;
``eps > 0``: :math:`(\ln G, \ln k^2, \delta, \lambda[, \nu])`). A piece of one member integrates the closed forms
folded into closures on floats (:func:`._kernel.scalar_rhs`), a piece of several the same formulas vectorised
over members; both end on the events ``'separatrix'`` and ``'slow_rotation'`` with the messages of
:mod:`._stops`. In a run through the separatrix (``k2_max=None``) the separatrix event is a crossing
(:func:`._crossing.cross_separatrix`): the member goes on in the region it chooses, or stops there with its
reason. One run's output is on ``tau_eval`` (the integrator's steps without it) from each piece's dense output;
a batch's on the common grid.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core.kernel import ARRAY, SCALAR
from ..core.ode import Event, Solution
from ..core.piecewise import Continue, MemberRecords, PieceEnd, PieceSpec, Stop, run_pieces
from . import _kernel as _k
from ._algebra import dk2_labelled
from ._crossing import Piece, assemble_pieces, cross_separatrix
from ._members import FIELDS, Members
from ._model import Body, Drag, Orbit, labelled, relabel
from ._regions import Region
from ._separatrix import K2_SWITCH
from ._spin import K2_SPIN_CAP
from ._stops import stop_message
from ._torques import drag_as_torque

__all__ = ["ClosedSetup", "drag_members", "run_closed"]

PRODUCER = "euler_poinsot.averaged"


@dataclass
class ClosedSetup:
    """What the members of a closed-form run share: body, orbit, options; the drag diagonal (unlabelled, one
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
    method: str = "DOP853"

    @property
    def through(self) -> bool:
        return self.k2_max is None

    @property
    def k2_stop(self) -> float:
        return K2_SWITCH if self.k2_max is None else self.k2_max

    @property
    def spin_cap(self) -> float:
        return K2_SPIN_CAP if self.k2_max is None else 1.0

    def labelled(self, kind: str, idx: Any) -> tuple[tuple[float, float, float], tuple[Any, Any, Any]]:
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


@dataclass
class _Context:
    """The constants of the piece just integrated (for its output and its events' states)."""

    kind: str
    limit: bool
    members: list[int]
    A: tuple[float, float, float]
    z: np.ndarray
    ie: np.ndarray
    delta0: np.ndarray
    nu0: np.ndarray
    e: float

    def fields(self, tau: np.ndarray, y: np.ndarray, sub: Any = slice(None)) -> dict[str, np.ndarray]:
        """The output fields of members ``sub`` of the piece's group from raw states ``y`` of shape
        ``(m, n_state, n_t)``."""
        return _k.fields(self.A, self.e, tau, y, self.z[sub], self.limit, self.delta0[sub], self.nu0[sub], self.ie[sub])


class ClosedProblem:
    """The closed-form averaged system of the members of ``mem`` (see the module docstring); ``te``: the common
    output grid of a batch, or the ``tau_eval`` of one run (``single``; None: the integrator's steps)."""

    def __init__(self, run: ClosedSetup, mem: Members, te: Any, single: bool) -> None:
        self.run, self.mem, self.te, self.single = run, mem, te, single
        self.continues: tuple[str, ...] = ("separatrix",) if run.through else ()
        B = mem.eps.size
        # the members' current state (the start of their next piece), updated at their crossings: the run's own
        # arrays (``mem`` is made for the run)
        self.kind = mem.kind
        self.sigma = np.full(B, float(run.sigma))
        self.G, self.k2, self.dl, self.lm, self.nus = mem.G0, mem.k2_0, mem.delta0, mem.lam0, mem.nu0.copy()
        self.crossings: list[list[dict[str, Any]]] = [[] for _ in range(B)]
        self.pieces: list[Piece] = []
        self.ctx: _Context | None = None
        self.stop = ""  # why a single run ended at its last crossing (empty: as its last piece did)
        if not single:
            nt = te.size
            self.out = {k: np.full((B, 3, nt) if k == "n" else (B, nt), np.nan) for k in FIELDS if k != "kind"}
            self.out["kind"] = np.full((B, nt), "", dtype="<U3")
            self.y_final = np.full((B, 5), np.nan)  # rows G, k2, n at each member's end
            none = np.empty(0)
            none.setflags(write=False)
            self.tev: dict[str, np.ndarray] = {}
            for name in ("separatrix", "slow_rotation"):
                self.tev[name] = np.empty(B, dtype=object)
                self.tev[name].fill(none)

    def mode(self, i: int) -> tuple[str, bool]:
        return str(self.kind[i]), bool(self.mem.eps[i] == 0.0)

    # ---- the pieces ----------------------------------------------------------------------------------------
    def piece(self, mode: tuple[str, bool], members: list[int], scalar: bool, tau: np.ndarray) -> PieceSpec:
        kind, limit = mode
        if scalar:
            return self._scalar_piece(kind, limit, members[0], float(tau[0]))
        idx = np.array(members)
        A, Id = self.run.labelled(kind, idx)
        eps, nu0 = self.mem.eps[idx], self.mem.nu0[idx]
        y0, z = _k.initial_state(0.0 if limit else eps, self.G[idx], self.k2[idx], self.dl[idx], self.lm[idx],
                                 self.nus[idx], self.run.orbit.e)
        ie = np.zeros(idx.size) if limit else 1.0 / eps
        self.ctx = _Context(kind, limit, members, A, z, ie, self.dl[idx], nu0, self.run.orbit.e)
        rt: Any
        rt, at = _k.tolerances(self.run.rtol, y0.shape[1])
        hl = 0.75 * self.run.orbit.mean_factor * np.cos(self.dl[idx])
        fun, events = self._vector(A, limit)
        args = (*_k.DragCoefficients(A, Id).args(), z, *((hl,) if limit else (ie, nu0)))
        return PieceSpec(fun, y0, rt, at, events, args, self.te)

    def _scalar_piece(self, kind: str, limit: bool, i: int, tau: float) -> PieceSpec:
        """One member's piece on floats (the closed forms folded into a closure, :func:`._kernel.scalar_rhs`)."""
        run, mem = self.run, self.mem
        A = labelled(run.body, kind)
        Id = relabel(kind, (float(run.I[0][i]), float(run.I[1][i]), float(run.I[2][i])))
        eps, nu0, dl = float(mem.eps[i]), float(mem.nu0[i]), float(self.dl[i])
        y0, z = _k.initial_state(0.0 if limit else eps, float(self.G[i]), float(self.k2[i]), dl, float(self.lm[i]),
                                 float(self.nus[i]), run.orbit.e)
        ie = 0.0 if limit else 1.0 / eps
        self.ctx = _Context(kind, limit, [i], A, np.array([z]), np.array([ie]), np.array([dl]), np.array([nu0]),
                            run.orbit.e)
        rt: Any
        rt, at = _k.tolerances(run.rtol, len(y0))
        c = _k.DragCoefficients(A, Id).args()
        rhs = _k.scalar_rhs(A, c, z, run.orbit.e, limit, 0.75 * run.orbit.mean_factor * math.cos(dl), ie, nu0)
        te = None if self.single else self.te[self.te >= tau]
        return PieceSpec(rhs, y0, rt if run.method == "DOP853" else _k.RTOL_FLOOR, at,
                         self._scalar_events(A, z, limit, ie), (), te, True, run.method)

    def _scalar_events(self, A: tuple[float, float, float], z: float, limit: bool, ie: float) -> list[Event]:
        lnk_stop = math.log(self.run.k2_stop)
        events = [Event((lambda t, y: y[1] - lnk_stop) if z > 0.0 else (lambda t, y: -1.0), "separatrix", True, 1.0,
                        stop_message("separatrix", k2_max=self.run.k2_stop))]
        if not limit:
            cap, r = self.run.spin_cap, self.run.min_spin_ratio
            events.append(Event(lambda t, y: _k.nut_freq(SCALAR, A, math.exp(y[0]), min(z * math.exp(y[1]), cap)) * ie
                                - r, "slow_rotation", True, -1.0, stop_message("slow_rotation", min_spin_ratio=r)))
        return events

    def _vector(self, A: tuple[float, float, float], limit: bool) -> tuple[Any, list[Event]]:
        e = self.run.orbit.e
        lnk_stop = math.log(self.run.k2_stop)
        r, cap = self.run.min_spin_ratio, self.run.spin_cap

        def sep(t: np.ndarray, y: np.ndarray, *a: np.ndarray) -> np.ndarray:
            return np.where(a[5] > 0.0, y[:, 1] - lnk_stop, -1.0)

        def slow(t: np.ndarray, y: np.ndarray, *a: np.ndarray) -> np.ndarray:
            k2_ = np.minimum(_k.k2_of(ARRAY, y[:, 1], a[5]), cap)
            return _k.nut_freq(ARRAY, A, np.exp(y[:, 0]), k2_) * a[6] - r

        def rhs_lim(t: np.ndarray, y: np.ndarray, *a: np.ndarray) -> np.ndarray:
            return np.stack(_k.rhs_limit(ARRAY, A, t, y.T, *a), axis=1)

        def rhs_orb(t: np.ndarray, y: np.ndarray, *a: np.ndarray) -> np.ndarray:
            return np.stack(_k.rhs_orbit(ARRAY, A, e, t, y.T, *a), axis=1)

        events = [Event(sep, "separatrix", True, 1.0, stop_message("separatrix", k2_max=self.run.k2_stop))]
        if limit:
            return rhs_lim, events
        events.append(Event(slow, "slow_rotation", True, -1.0, stop_message("slow_rotation", min_spin_ratio=r)))
        return rhs_orb, events

    def fields(self, tau: np.ndarray, y: np.ndarray, sub: Any = slice(None)) -> dict[str, np.ndarray]:
        """The output fields of the piece just integrated (members ``sub`` of its group)."""
        assert self.ctx is not None
        return self.ctx.fields(tau, y, sub)

    # ---- the output ----------------------------------------------------------------------------------------
    def record(self, mode: tuple[str, bool], members: list[int], sol: Solution, end: PieceEnd) -> None:
        if self.single:
            self.pieces.append(self._single_piece(sol))
            return
        idx = np.array(members)
        te = self.te
        if sol.batch_shape:
            Y, got = sol.y, np.isfinite(sol.y[:, 0, :])  # the samples this piece covers (a crossing's: the later)
            tev = sol.t_events
        else:  # one member on the scalar integrator: its samples are those of te it reached
            Y = np.full((1, sol.y.shape[0], te.size), np.nan)
            Y[0][:, np.searchsorted(te, sol.time)] = sol.y
            got = np.isfinite(Y[:, 0, :])
            tev = {k: _one(v) for k, v in sol.t_events.items()}
        f = self.fields(te, Y)
        kd = mode[0]
        sg = self.sigma[idx]
        for k in FIELDS:
            if k == "kind":
                self.out[k][idx] = np.where(got, kd, self.out[k][idx])
            elif k == "sigma":
                self.out[k][idx] = np.where(got, sg[:, None], self.out[k][idx])
            elif k == "n":
                self.out[k][idx] = np.where(got[:, None, :], f[k], self.out[k][idx])
            else:
                self.out[k][idx] = np.where(got, f[k], self.out[k][idx])
        if "slow_rotation" in tev:
            self.tev["slow_rotation"][idx] = tev["slow_rotation"]
        if not self.run.through and "separatrix" in tev:
            self.tev["separatrix"][idx] = tev["separatrix"]
        yf = np.array([self._end_state(end, j, sol) for j in range(idx.size)])
        ff = self.fields(np.zeros(1), yf[:, :, None])
        self.y_final[idx] = np.concatenate([ff["G"], ff["k2"], ff["n"][:, :, 0]], axis=1)

    @staticmethod
    def _end_state(end: PieceEnd, j: int, sol: Solution) -> np.ndarray:
        if sol.batch_shape:
            return np.asarray(sol.y_final[j], dtype=float)
        return np.asarray(sol.sol(float(end.t_final[0])), dtype=float)

    def _single_piece(self, res: Solution) -> Piece:
        """One run's piece: its fields evaluated where asked from its dense output."""
        c = self.ctx
        assert c is not None
        region = Region(c.kind, int(self.sigma[0]))
        fields = c.fields  # the piece's own constants (not the problem's: no reference cycle through it)

        def common(y: np.ndarray) -> np.ndarray:
            f = fields(np.zeros(np.shape(y)[-1]), y[None])
            return np.vstack([f["G"][0], f["k2"][0], f["n"][0]])

        def finish(te: Any, lam_s: float) -> Solution:
            steps = res.time
            if te is None:
                tau, y = steps, res.y
            else:
                tt = np.asarray(te, dtype=float)
                tau = tt[(tt >= steps[0]) & (tt <= steps[-1])] if steps.size else tt[:0]
                y = res.sol(tau) if tau.size else np.empty((res.y.shape[0], 0))
            f = {k: v[0] for k, v in fields(tau, y[None]).items()}
            f["kind"], f["sigma"] = np.full(tau.shape, region[0]), np.full(tau.shape, region[1])
            return Solution.build(producer=PRODUCER, time_name=res.time_name, time=tau,
                                  y=np.vstack([f["G"], f["k2"], f["n"]]), fields=f, status=res.status,
                                  message=res.message, event=res.event, t_events=res.t_events,
                                  y_events=res.y_events, dense=lambda t: common(res.sol(t)), nfev=res.nfev,
                                  last_step=res.last_step)

        return Piece(res, region, finish, common, float(self.lm[0]))

    # ---- the crossings -------------------------------------------------------------------------------------
    def on_event(self, mode: tuple[str, bool], i: int, j: int, end: PieceEnd) -> Continue | Stop:
        """Member ``i`` at the separatrix in a run through it: as every run crosses (:func:`cross_separatrix`)."""
        run = self.run
        tc = float(end.t_final[j])
        f = self.fields(np.array([tc]), end.event_state(j, "separatrix")[None, :, None], [j])
        G, delta, lam = float(f["G"][0, 0]), float(f["delta"][0, 0]), float(f["lam"][0, 0])
        n = f["n"][0, :, 0]
        nu = float(f["nu"][0, 0]) if self.mem.eps[i] > 0.0 else None

        def dk2_at(region: Region, *state: Any) -> float:  # the closed form: independent of G, n, nu
            An, Idn = run.labelled(region[0], i)
            return dk2_labelled(An, Idn, K2_SWITCH)

        tq = drag_as_torque(Drag(run.tensors[i]), run.body, run.orbit)
        source = Region(mode[0], int(self.sigma[i]))
        region, stop = cross_separatrix(run.body, tq, run.orbit, source, tc, G, delta, lam, n, nu, run.branch, run.rng,
                                        self.crossings[i], dk2_at)
        if not self.single:
            self.tev["separatrix"][i] = np.array([x["tau"] for x in self.crossings[i]])
        if region is None:
            self.stop = stop
            return Stop(1, stop_message("crossing", tau=tc, why=stop), "separatrix", tc)
        self.kind[i], self.sigma[i] = region[0], float(region[1])
        self.G[i], self.k2[i], self.dl[i], self.lm[i] = G, K2_SWITCH, delta, lam
        if run.orbit.e != 0.0 and nu is not None:
            self.nus[i] = nu
        return Continue((region[0], mode[1]))

    # ---- the result ----------------------------------------------------------------------------------------
    def result(self, rec: MemberRecords) -> Solution:
        if self.single:
            return assemble_pieces(self.pieces, self.crossings[0], self.te, PRODUCER, self.stop)
        shape = self.mem.batch_shape
        te = self.te
        data = {k: v.reshape(shape + v.shape[1:]) for k, v in self.out.items()}
        Y = np.concatenate([self.out["G"][:, None], self.out["k2"][:, None], self.out["n"]], axis=1)  # G, k2, n
        crossings = np.empty(len(self.crossings), dtype=object)
        for i, c in enumerate(self.crossings):
            crossings[i] = c
        return Solution.build(producer=PRODUCER, time_name="tau", time=te, y=Y.reshape(shape + Y.shape[1:]),
                              fields=data, status=rec.status.reshape(shape), message=rec.message.reshape(shape),
                              event=rec.event.reshape(shape),
                              t_events={k: v.reshape(shape) for k, v in self.tev.items()},
                              nfev=rec.nfev.reshape(shape), t_final=rec.t_final.reshape(shape),
                              y_final=self.y_final.reshape((*shape, 5)), crossings=crossings.reshape(shape))


def _one(v: Any) -> np.ndarray:
    out = np.empty(1, dtype=object)
    out[0] = np.asarray(v, dtype=float)
    return out


def run_closed(run: ClosedSetup, mem: Members, tau_span: tuple[float, float], te: Any, single: bool) -> Solution:
    """Integrate the closed-form averaged system of the members ``mem`` over ``tau_span`` (``mem.refused``: members
    that end at once with status -1 and their message) through the piecewise driver. ``single``: one run (``mem``
    of batch shape ``()``; an error at a piece's start raises; the output on ``te``, the ``tau_eval`` of the call,
    or on the integrator's steps when it is None); otherwise ``te`` is the batch's common output grid."""
    pb = ClosedProblem(run, mem, te, single)
    rec = MemberRecords.start([pb.mode(i) for i in range(mem.eps.size)], float(tau_span[0]), mem.refused)
    run_pieces(pb, rec, float(tau_span[1]), strict=single)
    return pb.result(rec)
