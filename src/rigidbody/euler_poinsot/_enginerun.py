"""The averaged system of a torque object (the averaging engine, and the closed forms of the parts that have them) as
a problem for the piecewise driver :func:`rigidbody.core.piecewise.run_pieces`: one run and a batch.

The engine's quadrature is chosen per state, so every member has a mode of its own and runs on the scalar
integrator, piece by piece: a piece is one chart of the direction of G (:class:`._segment.KindRun`) within one kind of
motion; a chart event continues in the other chart; in a run through the separatrix (``k2_max=None``) the
separatrix event is a crossing (:func:`._crossing.cross_separatrix`) into the next kind of motion. After the run each
kind of motion is finished (output fields, the resonance check, the quadrature report: :func:`._segment.finish_kind`)
and the member's result stitched (:func:`._crossing.assemble_pieces`); a batch collects its members' results on the
common grid (:func:`._members.assemble`), a member refused at its start or failing at a later start with status -1
and the message its single call raises.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..core.ode import Solution
from ..core.piecewise import Continue, MemberRecords, PieceEnd, PieceSpec, Stop, run_pieces
from ._crossing import Piece, assemble_pieces, cross_separatrix
from ._engine import Averager
from ._members import FIELDS, Members, assemble
from ._output import unit_of_angles
from ._regions import Region
from ._segment import KindRun, RunOptions, Setup, finish_kind
from ._separatrix import K2_SWITCH
from ._spin import K2_SPIN_CAP
from ._state import State
from ._stops import stop_message

__all__ = ["EngineSetup", "run_engine"]

PRODUCER = "euler_poinsot.averaged"


@dataclass
class EngineSetup:
    """What the members of a run with a torque object share: the torque object, the body, orbit and options."""

    torque: Any
    body: Any
    orbit: Any
    sigma: int
    rtol: float
    atol: float
    method: str
    k2_max: float | None
    min_spin_ratio: float
    averaging: str
    quad_tol: float
    drift_tol: float | None
    resonance_tol: float | None
    branch: Any
    seed: Any

    @property
    def through(self) -> bool:
        return self.k2_max is None


@dataclass(kw_only=True)
class _Member(RunOptions):
    """One member's run: its options (those of :func:`averaged` its segments share), its averager, the kind of
    motion being integrated (``kr``), the next one to start (``next``), the finished kinds and the crossings."""

    torque: Any
    averaging: str
    quad_tol: float
    spin_cap: float
    rng: Any
    next: tuple[Any, ...] | None = None
    kr: KindRun | None = None
    kinds: list[Piece] = field(default_factory=list)
    crossings: list[dict[str, Any]] = field(default_factory=list)
    stop: str = ""
    pending: bool = False

    def __post_init__(self) -> None:
        self.averager = Averager(self.torque, self.averaging, self.quad_tol)

    def start_kind(self, region: Region, tau0: float, G: float, k2: float, n: np.ndarray, nu0: float, lam0: float,
                   k2_stop: float) -> KindRun:
        setup = Setup(**self.options(), averager=self.averager, k2_max=k2_stop, spin_cap=self.spin_cap)
        return KindRun(setup, region[0], region[1], tau0, G, k2, n, nu0, lam0)

    def close(self) -> None:
        """Finish the kind of motion being integrated: its output on demand, its state as rows G, k2, n."""
        kr = self.kr
        assert kr is not None
        seg = kr.segment()

        def finish(te: Any, lam: float) -> Solution:
            return finish_kind(seg, te, lam)

        def common(y: np.ndarray) -> np.ndarray:
            return np.vstack([y[0], y[1], y[2:5] / np.linalg.norm(y[2:5], axis=0)])

        self.kinds.append(Piece(seg.res, Region(kr.kind, kr.sigma), finish, common, kr.pieces[0].lam_start))
        self.kr = None

    def dk2_at(self, region: Region, G: float, n: np.ndarray, nu: float | None) -> float:
        """The averaged dk2/dtau of ``region`` at the switch next to the separatrix."""
        st = State(self.body, region[0], region[1], G, K2_SWITCH, n, nu, self.orbit)
        self.averager.calibrate(st)
        return float(self.averager.mean(st).dk2)


class EngineProblem:
    """The averaged system of a torque object for the members of ``mem`` (see the module docstring)."""

    def __init__(self, run: EngineSetup, mem: Members, tau_span: tuple[float, float], te: Any, single: bool) -> None:
        self.run, self.mem, self.te, self.single = run, mem, te, single
        self.t0, self.t1 = tau_span
        self.continues: tuple[str, ...] = ("chart", "separatrix") if run.through else ("chart",)
        self.k2_stop = K2_SWITCH if run.through else float(run.k2_max)  # type: ignore[arg-type]  # set when not through
        self.members: dict[int, _Member] = {}

    def _member(self, i: int) -> _Member:
        run, mem = self.run, self.mem
        eps, nu0 = float(mem.eps[i]), float(mem.nu0[i])
        m = _Member(torque=run.torque, averaging=run.averaging, quad_tol=run.quad_tol, body=run.body, eps=eps,
                    orbit=run.orbit, nu0=nu0, rtol=run.rtol, atol=run.atol, method=run.method,
                    min_spin_ratio=run.min_spin_ratio, drift_tol=run.drift_tol, resonance_tol=run.resonance_tol,
                    spin_cap=K2_SPIN_CAP if run.through else 1.0,
                    rng=np.random.default_rng(run.seed) if run.branch == "random" else None)
        # the true anomaly at the start: nu = tau/eps + nu0 on a circular orbit (as the drag tensor's closed forms and
        # simulate take it, also when tau_span starts after 0); on an eccentric orbit nu is a state starting at nu0
        nu_start = nu0 + self.t0 / eps if eps > 0.0 and run.orbit.e == 0.0 else nu0
        d0, l0 = float(mem.delta0[i]), float(mem.lam0[i])
        m.next = (Region(str(mem.kind[i]), run.sigma), self.t0, float(mem.G0[i]), float(mem.k2_0[i]),
                  np.array(unit_of_angles(d0, l0)), nu_start, l0, self.k2_stop)
        return m

    def piece(self, mode: Any, members: list[int], scalar: bool, tau: np.ndarray) -> PieceSpec:
        i = members[0]
        m = self.members.get(i)
        if m is None:
            self.run.torque.check_setup(self.run.body, self.run.orbit)
            m = self.members[i] = self._member(i)
        m.pending = True  # until the piece's result comes: a start that raises refuses the member
        if m.kr is None:
            assert m.next is not None
            m.kr = m.start_kind(*m.next)
            m.next = None
        rhs, y0, rt, at, events = m.kr.piece()
        return PieceSpec(rhs, y0, rt, at, events, (), None, True, self.run.method)

    def record(self, mode: Any, members: list[int], sol: Solution, end: PieceEnd) -> None:
        m = self.members[members[0]]
        assert m.kr is not None
        m.pending = False
        if not m.kr.add(sol):
            m.close()
        end.message[0] = str(sol.message)  # a torque's failure named (KindRun.add)

    def on_event(self, mode: Any, i: int, j: int, end: PieceEnd) -> Continue | Stop:
        m = self.members[i]
        tc = float(end.t_final[j])
        if end.event[j] == "chart":
            if m.kr is None:  # too many chart switches: the joined segment says so
                res = m.kinds[-1].res
                return Stop(int(res.status), str(res.message), res.event, tc)
            m.kr.switch()
            return Continue(mode)
        cur = m.kinds[-1]
        at = cur.finish(np.array([tc]), cur.lam_start)
        G, n = float(at.G[0]), np.asarray(at.n[:, 0], dtype=float)
        delta, lam = float(at.delta[0]), float(at.lam[0])
        nu = float(at.nu[0]) if m.eps > 0.0 else None
        region, m.stop = cross_separatrix(m.body, m.torque, m.orbit, cur.region, tc, G, delta, lam, n, nu,
                                          self.run.branch, m.rng, m.crossings, m.dk2_at)
        if region is None:
            return Stop(1, stop_message("crossing", tau=tc, why=m.stop), "separatrix", tc)
        # the next kind starts next to the separatrix with the step its predecessor ended with (the driver hands it
        # over): there the rates' logarithmic singularity can fool the initial-step heuristic into a step whose
        # error estimate is too optimistic (1e-7 instead of 1e-10 relative in G, measured)
        m.next = (region, tc, G, K2_SWITCH, n, nu if nu is not None else m.nu0, lam, K2_SWITCH)
        return Continue(mode)

    def result(self, rec: MemberRecords) -> Solution:
        out: list[Solution | str] = []
        for i in range(self.mem.eps.size):
            m = self.members.get(i)
            if m is None or m.pending or not m.kinds:  # refused at the start, or a later start failed
                out.append(str(rec.message[i]))
                continue
            out.append(assemble_pieces(m.kinds, m.crossings, self.te, PRODUCER, m.stop))
        if self.single:
            assert isinstance(out[0], Solution)
            return out[0]
        return assemble(out, self.mem.batch_shape, self.te, FIELDS, PRODUCER)


def run_engine(run: EngineSetup, mem: Members, tau_span: tuple[float, float], te: Any, single: bool) -> Solution:
    """Integrate the averaged system of a torque object for the members ``mem`` over ``tau_span`` through the
    piecewise driver (``mem.refused``: members that end at once with status -1 and their message; ``single``: one
    run, whose errors raise and whose output is on ``te``, the call's ``tau_eval``, or the integrator's steps)."""
    pb = EngineProblem(run, mem, tau_span, te, single)
    rec = MemberRecords.start(list(range(mem.eps.size)), float(tau_span[0]), mem.refused)
    run_pieces(pb, rec, float(tau_span[1]), strict=single)
    return pb.result(rec)
