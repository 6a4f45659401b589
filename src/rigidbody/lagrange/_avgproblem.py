r"""The averaged system (2.15) as a problem for the piecewise driver :func:`rigidbody.core.piecewise.run_pieces`.

One run is a batch of one. A member's mode is its chart (:mod:`._avgcharts`): ``'u'`` (the paper's roots),
``'p'`` (the GHr chart, averaged (2.7) in log-polar form) or ``('plain', i)`` (plain ``(Gz, H, r)`` at ``Gz = r
= 0``, one member at a time). The problem keeps each member's slow state ``(Gz, H, r)`` at the start of its next
piece, its signs ``delta1, delta2`` and its count of pieces; the driver groups the members of a chart (a group
of one on the scalar DOP853, a larger group on the vectorised one) and carries their times and step sizes. A
piece ends at the end of the span, a degenerate state or a failure (the member ends with that status and
message) or, with ``chart='auto'``, at the chart's switching event, a continued event: the member goes on in
the other chart from the switching state, or stops there (a regular precession on the way back to the u chart;
more than ``max_segments`` pieces). The events, the messages, the chart switches and the piece count are written
once here, for one run and for a batch alike.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..core.ode import Solution
from ..core.piecewise import Continue, MemberRecords, PieceEnd, PieceSpec, Stop, run_pieces
from . import _kernel as _k
from ._avgcharts import Chart, PlainChart, PolarChart, UChart
from ._avgsetup import MSG_DEG, MSG_END, TRIPLE_TOL, ChartSetup, start_chart
from ._top import deltas

__all__ = ["run_members"]

#: the producer its results record (one run and a batch alike)
PRODUCER = "lagrange.averaged"
FIELDS = ("u1", "u2", "u3", "Gz", "H", "r", "k2", "delta1", "delta2", "chart")
_AX = _k.ARRAY


def _at(v: Any, j: int) -> float:
    """Entry ``j`` of a per-member array, or the float of a single member."""
    return float(v[j]) if np.ndim(v) else float(v)


class _Output:
    """The members' output: for a batch on the common grid ``te``; for one run the pieces of its segments (on
    ``te`` where given, else on the integrator's own steps)."""

    def __init__(self, B: int, te: np.ndarray | None, grid: bool) -> None:
        self.te = te
        self.grid = grid
        self.pieces: list[tuple[np.ndarray, dict[str, np.ndarray]]] = []
        self.last = np.full(B, -math.inf)  # the last output time of each member
        if grid:
            assert te is not None
            self.out = {k: np.full((B, te.size), np.nan) for k in FIELDS}

    def t_eval(self, i: int, tau: float) -> np.ndarray | None:
        """The grid points a member's next scalar segment still has to give."""
        te = self.te
        return None if te is None else te[(te >= tau) & (te > self.last[i])]

    def put_one(self, i: int, tau: np.ndarray, f: dict[str, np.ndarray]) -> None:
        self.last[i] = tau[-1]
        if not self.grid:
            self.pieces.append((tau, f))
            return
        cols = np.searchsorted(self.te, tau)  # type: ignore[arg-type]  # a grid has te
        for k in FIELDS:
            self.out[k][i, cols] = f[k]

    def put_block(self, idx: np.ndarray, Y: np.ndarray, f: dict[str, np.ndarray]) -> None:
        te = self.te
        assert te is not None
        mask = np.all(np.isfinite(Y), axis=1)
        for k in FIELDS:
            blk = self.out[k][idx]
            blk[mask] = np.broadcast_to(f[k], mask.shape)[mask]
            self.out[k][idx] = blk
        self.last[idx] = np.where(mask.any(axis=1), np.max(np.where(mask, te, -math.inf), axis=1), self.last[idx])

    def single(self) -> tuple[np.ndarray, dict[str, np.ndarray]]:
        """Times and fields of a run of one member (switching points kept once, from the later segment)."""
        if not self.pieces:
            return np.empty(0), {k: np.empty(0) for k in FIELDS}
        tau = np.concatenate([p[0] for p in self.pieces])
        cols = {k: np.concatenate([np.asarray(p[1][k], dtype=float).reshape(-1) for p in self.pieces]) for k in FIELDS}
        keep = np.append(np.diff(tau) > 0.0, True)
        return tau[keep], {k: v[keep] for k, v in cols.items()}


#: where a member goes at its chart's switching event: the slow state there and the chart's signs (None: the
#: signs it has, from the u chart to the GHr chart), or ``"regular"`` (a regular precession: back to the u chart
#: is singular, the member stops)
_Exit = tuple[float, float, float, Any]


class AveragedProblem:
    """The averaged system of ``B`` members in their charts (see the module docstring); ``te``: the common output
    grid of a batch (``grid``), or the ``tau_eval`` of one run (None: the integrator's steps)."""

    def __init__(self, st: ChartSetup, B: int, te: np.ndarray | None, method: str, max_segments: int,
                 grid: bool) -> None:
        self.st, self.B, self.max_segments, self.method = st, B, max_segments, method
        self.engine = "python" if method == "DOP853" else "scipy"
        self.charts: dict[str, Chart] = {"u": UChart(st), "p": PolarChart(st), "plain": PlainChart(st)}
        #: the switching events of the two charts go on in the other chart (with chart='auto' only)
        self.continues: tuple[str, ...] = (UChart.switch, PolarChart.switch) if st.chart == "auto" else ()
        self.nseg = [0] * B
        self.slow = np.zeros((B, 3))
        self.D = np.ones((B, 2))
        self.tev: dict[str, list[list[float]]] = {k: [[] for _ in range(B)]
                                                  for k in ("delta1_flip", "delta2_flip", "chart_switch")}
        self.output = _Output(B, te, grid)
        self.args: tuple[Any, ...] = ()  # the per-member arguments of the piece just integrated
        self.exits: dict[int, _Exit] = {}

    # ---- modes -------------------------------------------------------------------------------------------
    def begin(self, i: int, chart: str, d1: float, d2: float, slow: Any) -> Any:
        """Member ``i``'s next piece in ``chart`` (``'u'`` or ``'p'``) from ``slow`` with signs ``d1, d2``; its
        mode (``Gz = r = 0`` in the GHr chart: the plain chart, no direction in the ``(Gz, C r)`` plane)."""
        self.D[i], self.slow[i] = (d1, d2), slow
        if chart == "p" and self.slow[i, 0] == 0.0 and self.slow[i, 2] == 0.0:
            return ("plain", i)
        return chart

    def chart(self, mode: Any) -> Chart:
        return self.charts["plain" if isinstance(mode, tuple) else mode]

    # ---- the pieces ----------------------------------------------------------------------------------------
    def piece(self, mode: Any, members: list[int], scalar: bool, tau: np.ndarray) -> PieceSpec:
        chart = self.chart(mode)
        for i in members:
            self.nseg[i] += 1
        if scalar:
            i = members[0]
            y0, self.args = chart.start(_k.SCALAR, *self.slow[i].tolist(), *self.D[i].tolist())
            rtol, atol = chart.tolerances(y0, self.engine)
            rhs, evs = chart.functions(True)
            return PieceSpec(rhs, y0, rtol, atol, evs, self.args, self.output.t_eval(i, float(tau[0])),
                             method=self.method)
        idx = np.array(members)
        S = self.slow[idx]
        with np.errstate(all="ignore"):
            y0, self.args = chart.start(_AX, S[:, 0], S[:, 1], S[:, 2], self.D[idx, 0], self.D[idx, 1])
        rtol, atol = chart.tolerances(y0, "python")
        rhs, evs = chart.functions(False)
        return PieceSpec(rhs, y0, rtol, atol, evs, self.args, self.output.te)

    def record(self, mode: Any, members: list[int], sol: Solution, end: PieceEnd) -> None:
        """Store the piece's output and event times; for the members at the switching event, where they go."""
        chart, args = self.chart(mode), self.args
        if not sol.batch_shape:
            if sol.time.size:
                self.output.put_one(members[0], sol.time, chart.fields(sol.y, args))
        else:
            with np.errstate(all="ignore"):
                self.output.put_block(np.array(members), sol.y, chart.fields(sol.y, args))
        for name in chart.recorded:
            for j, i in enumerate(members):
                self.tev[name][i].extend(np.asarray(end.t_events[name][j], dtype=float).tolist())
        go = []
        for j, i in enumerate(members):
            ev = end.event[j]
            if end.status[j] == 1 and ev in self.continues:
                go.append(j)
            elif ev is not None:  # the member ends on this event: its times in this piece
                self.tev.setdefault(ev, [[] for _ in range(self.B)])
                self.tev[ev][i] = list(np.asarray(end.t_events[ev][j], dtype=float))
        if go:
            self.exits.update(self.exit_states(chart, members, go, end, args))

    def exit_states(self, chart: Chart, members: list[int], go: list[int], end: PieceEnd,
                    args: tuple[Any, ...]) -> dict[int, _Exit]:
        """Where the members ``members[go]`` go from their switching states (one member on floats, several on
        arrays, as their piece was integrated)."""
        ye = [end.event_state(j, chart.switch) for j in go]
        if len(go) == 1:
            xp: Any = _k.SCALAR
            y: tuple[Any, ...] = tuple(float(v) for v in ye[0])
            sub: tuple[Any, ...] = tuple(float(np.asarray(a).reshape(-1)[go[0]]) for a in args)
        else:
            xp, Y = _AX, np.array(ye, dtype=float).reshape(-1, 3)
            y, sub = (Y[:, 0], Y[:, 1], Y[:, 2]), tuple(np.asarray(a, dtype=float)[go] for a in args)
        with np.errstate(all="ignore"):
            Gz, H, r = chart.exit_state(xp, y, sub)
            if isinstance(chart, UChart):
                return {members[k]: (_at(Gz, j), _at(H, j), _at(r, j), None) for j, k in enumerate(go)}
            # back to the u chart, with the signs at the switching state
            d1, d2 = deltas(self.st.top, Gz, r)
            v1, v2, v3 = self.st.roots_g(xp, Gz, H, r)
            regular = np.atleast_1d((v2 - v1) <= self.st.deg * (v3 - v1)).tolist()
        return {members[k]: (_at(Gz, j), _at(H, j), _at(r, j), "regular" if regular[j] else (_at(d1, j), _at(d2, j)))
                for j, k in enumerate(go)}

    def on_event(self, mode: Any, i: int, j: int, end: PieceEnd) -> Continue | Stop:
        """Member ``i`` at its chart's switching event: on in the other chart, or a stop there."""
        t = float(end.t_events[self.chart(mode).switch][j][-1])
        self.tev["chart_switch"][i].append(t)
        Gz, H, r, signs = self.exits.pop(i)
        if signs == "regular":
            return Stop(1, f"stopped by event 'u1_eq_u2' at tau = {t:.6g}: {MSG_DEG}", "u1_eq_u2", t)
        if self.nseg[i] >= self.max_segments:
            return Stop(-1, f"more than max_segments={self.max_segments} chart switches (chattering)", None, t)
        if signs is None:
            return Continue(self.begin(i, "p", self.D[i, 0], self.D[i, 1], (Gz, H, r)))
        return Continue(self.begin(i, "u", signs[0], signs[1], (Gz, H, r)))

    # ---- starts ------------------------------------------------------------------------------------------
    def start_one(self, i: int, Gz: float, H: float, r: float) -> Any:
        """Member ``i``'s first mode by :func:`start_chart` (ValueError for a state with no average)."""
        c, d1, d2, _ = start_chart(self.st, Gz, H, r)
        return self.begin(i, "u" if c == "u" else "p", d1, d2, (Gz, H, r))

    def start_all(self, init: np.ndarray) -> tuple[list[Any], dict[int, str]]:
        """The first modes of a batch, and the members refused (index -> message): the charts decided together,
        unusual members (no average, on a threshold, non-finite, ``Gz = r = 0``) one by one by
        :func:`start_chart`."""
        st = self.st
        Gz0, H0, r0 = init[:, 0], init[:, 1], init[:, 2]
        with np.errstate(all="ignore"):
            finite = np.isfinite(init).all(axis=1)
            Cr0 = st.C * r0
            S2 = Gz0 * Gz0 + Cr0 * Cr0
            g0 = _k.decode_g(_AX, st.A, st.C, st.mgl, *_k.slow_to_polar(_AX, st.C, Gz0, H0, r0, st.mgl))
            u1, u2, u3 = g0.u1, g0.u2, g0.u3
            b = np.minimum(np.abs(Gz0 * Gz0 - Cr0 * Cr0), Cr0 * Cr0) / S2
            deg = (u2 - u1) <= st.deg * (u3 - u1)
            want_u = np.full(self.B, st.chart != "GHr")
            if st.chart == "auto":
                want_u &= (b >= st.sw) & ~deg
            raw_lo, raw_hi = g0.msum - g0.half, g0.msum + g0.half
            unusual = (~finite | (S2 == 0.0) | ~g0.ok | ~g0.inside | (raw_lo < -1.0) | (raw_hi > 1.0) | (g0.K < 0.0)
                       | ((u3 - u2) <= 10.0 * st.deg * (u3 - u1)) | (g0.spread <= 2.0 * TRIPLE_TOL)
                       | (np.abs(b - st.sw) <= 1e-9) | ((st.chart == "u") & ((b <= st.sw) | deg)))
            D1 = np.where(Gz0 * Gz0 - Cr0 * Cr0 >= 0.0, 1.0, -1.0)
            D2 = np.where(r0 >= 0.0, 1.0, -1.0)
        modes: list[Any] = [None] * self.B
        refused: dict[int, str] = {}
        for i in np.nonzero(~unusual)[0].tolist():
            modes[i] = self.begin(i, "u" if want_u[i] else "p", D1[i], D2[i], init[i])
        for i in np.nonzero(unusual)[0].tolist():
            if not finite[i]:
                refused[i] = "the initial state (Gz, H, r) is not finite"
                continue
            try:
                modes[i] = self.start_one(i, *(float(v) for v in init[i]))
            except ValueError as err:
                refused[i] = str(err)
        return modes, refused


def run_members(st: ChartSetup, init: np.ndarray, batch_shape: tuple[int, ...], t0: float, t1: float,
                te: np.ndarray | None, method: str, max_segments: int) -> Solution:
    """Integrate the averaged system from the initial slow states ``init`` (shape ``(B, 3)``).

    ``batch_shape == ()`` is one run (``B = 1``): a state with no average raises ValueError, the output is on
    ``te`` where reached (the integrator's steps without it) and the result a single-run :class:`Solution`.
    Otherwise a refused member ends with status -1 and its message, and every field has shape
    ``batch_shape + (len(te),)``, NaN after a member's end.
    """
    B = init.shape[0]
    single = batch_shape == ()
    pb = AveragedProblem(st, B, te, method, max_segments, not single)
    refused: dict[int, str] = {}
    if single:
        modes = [pb.start_one(0, *(float(v) for v in init[0]))]
    else:
        modes, refused = pb.start_all(init)
    rec = run_pieces(pb, MemberRecords.start(modes, t0, refused), t1, strict=single)
    rec.message[rec.status == 0] = MSG_END
    return _single_result(pb, rec) if single else _batch_result(pb, rec, batch_shape)


def _single_result(pb: AveragedProblem, rec: MemberRecords) -> Solution:
    """The single-run :class:`Solution` of a run of one member."""
    tau, cols = pb.output.single()
    U = np.array([cols["u1"], cols["u2"], cols["u3"]]).reshape(3, -1)
    tev = {k: np.asarray(v[0], dtype=float) for k, v in pb.tev.items()}
    return Solution.build(producer=PRODUCER, time_name="tau", time=tau, y=U, status=int(rec.status[0]),
                          message=str(rec.message[0]), fields={"u": U, **cols}, event=rec.event[0], t_events=tev,
                          nfev=int(rec.nfev[0]), t_final=float(rec.t_final[0]))


def _batch_result(pb: AveragedProblem, rec: MemberRecords, batch_shape: tuple[int, ...]) -> Solution:
    """The batch :class:`Solution`: every field of shape ``batch_shape + (len(te),)``, per-member records."""
    te, out = pb.output.te, pb.output.out
    assert te is not None
    nt = te.size
    data: dict[str, np.ndarray] = {k: v.reshape((*batch_shape, nt)) for k, v in out.items()}
    U = np.stack([out["u1"], out["u2"], out["u3"]], axis=1).reshape((*batch_shape, 3, nt))
    t_events: dict[str, np.ndarray] = {}
    for name, lists in pb.tev.items():
        arr = np.empty(pb.B, dtype=object)
        for q in range(pb.B):
            arr[q] = np.asarray(lists[q], dtype=float)
        t_events[name] = arr.reshape(batch_shape)
    return Solution.build(producer=PRODUCER, time_name="tau", time=te, y=U, status=rec.status.reshape(batch_shape),
                          message=rec.message.reshape(batch_shape), fields={"u": U, **data},
                          event=rec.event.reshape(batch_shape), t_events=t_events, nfev=rec.nfev.reshape(batch_shape),
                          t_final=rec.t_final.reshape(batch_shape))
