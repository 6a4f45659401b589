r"""The piecewise driver of the averaged system (2.15): members run segment by segment through their charts.

One run is a batch of one. Every member carries its chart (:mod:`._avgcharts`), its slow state ``(Gz, H, r)``
at the start of its next segment, its signs ``delta1, delta2``, its time, its step size and its count of
segments. A round integrates the members in the u chart, then those in the GHr chart: a group of one on
:func:`rigidbody.core.ode.integrate` (the scalar DOP853 on floats, much cheaper for one member), a larger group
together on :func:`rigidbody.core.batch.integrate_batch`. After its segment a member either ends (the end of
the span, a degenerate state, a failure, each with its message) or, at the chart's switching event, continues
in the other chart from the switching state with the step size it reached. The events, the messages, the
chart switches and the segment count are written once here, for one run and for a batch alike.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..core.batch import integrate_batch, member_records
from ..core.ode import Solution, integrate
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


class _Segment:
    """The outcome of one segment for each member of a group, read from a single or a batch :class:`Solution`."""

    def __init__(self, sol: Solution, m: int, t1: float, tau0: float) -> None:
        if not sol.batch_shape:  # one member, on the scalar integrator (which does not record t_final)
            st, ev = int(sol.status), sol.event
            self.status, self.message, self.event = [st], [str(sol.message)], [ev]
            self.nfev = np.array([sol.nfev])
            self.last_step = np.array([np.nan if sol.last_step is None else sol.last_step])
            self.t_events = {k: [v] for k, v in sol.t_events.items()}
            self.y_events = {k: [v] for k, v in sol.y_events.items()}
            t_last = float(sol.tau[-1]) if sol.tau.size else tau0
            self.t_final = np.array([t1 if st == 0 else float(sol.t_events[ev][-1]) if st == 1 else t_last])
            return
        self.status = [int(s) for s in sol.status.reshape(m)]
        self.message = [str(s) for s in sol.message.reshape(m)]
        self.event = list(sol.event.reshape(m))
        self.nfev = np.asarray(sol.nfev, dtype=int).reshape(m)
        self.last_step = np.asarray(sol.last_step, dtype=float).reshape(m)
        self.t_events = {k: list(v.reshape(m)) for k, v in sol.t_events.items()}
        self.y_events = {k: list(v.reshape(m)) for k, v in sol.y_events.items()}
        self.t_final = np.asarray(sol.t_final, dtype=float).reshape(m)


class _Members:
    """Per-member records of a run of the averaged system, and the rounds that advance them. The chart and the
    segment count of each member are Python lists (read member by member when the groups are formed); what a
    group's integration takes (slow state, signs, times, step sizes) are arrays."""

    def __init__(self, st: ChartSetup, B: int, t0: float, t1: float, te: np.ndarray | None, method: str,
                 max_segments: int, grid: bool) -> None:
        self.st, self.B, self.t0, self.t1, self.max_segments = st, B, t0, t1, max_segments
        self.method = method
        self.engine = "python" if method == "DOP853" else "scipy"
        self.charts: dict[str, Chart] = {"u": UChart(st), "p": PolarChart(st), "plain": PlainChart(st)}
        self.status, self.message, self.event, self.nfev, self.t_final = member_records(B, t0, 0, MSG_END)
        self.cur = ["-"] * B  # 'u', 'p' (GHr), '-' done
        self.nseg = [0] * B
        self.slow = np.zeros((B, 3))
        self.D = np.ones((B, 2))
        self.tau = np.full(B, t0)
        self.hnext = np.full(B, np.nan)
        self.tev: dict[str, list[list[float]]] = {k: [[] for _ in range(B)]
                                                  for k in ("delta1_flip", "delta2_flip", "chart_switch")}
        self.output = _Output(B, te, grid)

    def finish(self, i: int, status: int, message: str, event: str | None, t_end: float) -> None:
        self.status[i], self.message[i], self.event[i], self.t_final[i] = status, message, event, t_end
        self.cur[i] = "-"

    def begin(self, i: int, chart: str, d1: float, d2: float, slow: Any) -> None:
        self.cur[i], self.D[i], self.slow[i] = chart, (d1, d2), slow

    # ---- rounds ------------------------------------------------------------------------------------------
    def run(self) -> None:
        """Advance every member to its end: rounds of u-chart segments, then GHr-chart segments."""
        cur, nseg, top = self.cur, self.nseg, self.max_segments
        while True:
            live = [i for i, c in enumerate(cur) if c != "-"]
            if not live:
                return
            for i in live:
                if nseg[i] >= top:
                    self.finish(i, -1, f"more than max_segments={top} chart switches (chattering)", None,
                                float(self.tau[i]))
            for name in ("u", "p"):
                idx = [i for i in live if cur[i] == name and nseg[i] < top]
                for i in idx:
                    nseg[i] += 1
                if name == "p":  # Gz = r = 0: no direction in the (Gz, C r) plane, the plain chart
                    plain = [i for i in idx if self.slow[i, 0] == 0.0 and self.slow[i, 2] == 0.0]
                    for i in plain:
                        self.segment(self.charts["plain"], [i])
                    idx = [i for i in idx if i not in plain] if plain else idx
                if idx:
                    self.segment(self.charts[name], idx)

    def segment(self, chart: Chart, members: list[int]) -> None:
        """One segment of ``members`` in ``chart``: integrate, store the output, then end or switch."""
        if len(members) == 1:
            i = members[0]
            tau, h = float(self.tau[i]), float(self.hnext[i])
            y0, args = chart.start(_k.SCALAR, *self.slow[i].tolist(), *self.D[i].tolist())
            rtol, atol = chart.tolerances(y0, self.engine)
            rhs, evs = chart.functions(True)
            sol = integrate(rhs, (tau, self.t1), y0, t_eval=self.output.t_eval(i, tau), rtol=rtol, atol=atol,
                            method=self.method, events=evs, time_name="tau", args=args, engine=self.engine,
                            first_step=None if math.isnan(h) else h)
            if sol.tau.size:
                self.output.put_one(i, sol.tau, chart.fields(sol.y, args))
            seg = _Segment(sol, 1, self.t1, tau)
            self.nfev[i] += seg.nfev[0]
            self.hnext[i] = seg.last_step[0]
        else:
            idx = np.array(members)
            S = self.slow[idx]
            with np.errstate(all="ignore"):
                y0, args = chart.start(_AX, S[:, 0], S[:, 1], S[:, 2], self.D[idx, 0], self.D[idx, 1])
            rtol, atol = chart.tolerances(y0, "python")
            rhs, evs = chart.functions(False)
            sol = integrate_batch(rhs, (self.tau[idx], self.t1), y0, t_eval=self.output.te, rtol=rtol, atol=atol,
                                  events=evs, args=args, time_name="tau", first_step=self.hnext[idx])
            with np.errstate(all="ignore"):
                self.output.put_block(idx, sol.y, chart.fields(sol.y, args))
            seg = _Segment(sol, idx.size, self.t1, float(self.t0))
            self.nfev[idx] += seg.nfev
            self.hnext[idx] = seg.last_step
        for name in chart.recorded:
            for j, i in enumerate(members):
                self.tev[name][i].extend(np.asarray(seg.t_events[name][j], dtype=float).tolist())
        go = []
        for j, i in enumerate(members):
            if seg.status[j] == 1 and seg.event[j] == chart.switch and self.st.chart == "auto":
                go.append(j)
            else:
                self.end(i, j, seg)
        if go:
            self.switch(chart, members, go, seg, args)

    def end(self, i: int, j: int, seg: _Segment) -> None:
        """Member ``i`` (``j`` in its group) ends with its segment's status, message and terminal event."""
        status, ev = seg.status[j], seg.event[j]
        if ev is not None:
            self.tev[ev] = self.tev.get(ev, [[] for _ in range(self.B)])
            self.tev[ev][i] = list(np.asarray(seg.t_events[ev][j], dtype=float))
        self.finish(i, status, MSG_END if status == 0 else seg.message[j], ev, float(seg.t_final[j]))

    def switch(self, chart: Chart, members: list[int], go: list[int], seg: _Segment, args: tuple[Any, ...]) -> None:
        """The members ``members[go]`` continue in the other chart from their switching states (one member on floats,
        several on arrays)."""
        ye = [seg.y_events[chart.switch][j][-1] for j in go]
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
                regular = None
            else:  # back to the u chart, with the signs at the switching state
                d1, d2 = deltas(self.st.top, Gz, r)
                v1, v2, v3 = self.st.roots_g(xp, Gz, H, r)
                regular = np.atleast_1d((v2 - v1) <= self.st.deg * (v3 - v1)).tolist()
        for j, k in enumerate(go):
            i = members[k]
            t = float(seg.t_events[chart.switch][k][-1])
            self.tau[i] = t
            self.tev["chart_switch"][i].append(t)
            if regular is None:
                self.begin(i, "p", self.D[i, 0], self.D[i, 1], (_at(Gz, j), _at(H, j), _at(r, j)))
            elif regular[j]:
                self.finish(i, 1, f"stopped by event 'u1_eq_u2' at tau = {t:.6g}: {MSG_DEG}", "u1_eq_u2", t)
            else:
                self.begin(i, "u", _at(d1, j), _at(d2, j), (_at(Gz, j), _at(H, j), _at(r, j)))

    # ---- starts ------------------------------------------------------------------------------------------
    def start_one(self, i: int, Gz: float, H: float, r: float) -> None:
        """Start member ``i`` by :func:`start_chart` (ValueError for a state with no average)."""
        c, d1, d2, _ = start_chart(self.st, Gz, H, r)
        self.begin(i, "u" if c == "u" else "p", d1, d2, (Gz, H, r))

    def start_all(self, init: np.ndarray) -> None:
        """Start a batch: the charts decided together, unusual members (no average, on a threshold, non-finite,
        ``Gz = r = 0``) one by one by :func:`start_chart`, a refused member ending with status -1 and its
        message."""
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
        for i in np.nonzero(~unusual)[0].tolist():
            self.begin(i, "u" if want_u[i] else "p", D1[i], D2[i], init[i])
        for i in np.nonzero(unusual)[0].tolist():
            if not finite[i]:
                self.finish(i, -1, "the initial state (Gz, H, r) is not finite", None, self.t0)
                continue
            try:
                self.start_one(i, *(float(v) for v in init[i]))
            except ValueError as err:
                self.finish(i, -1, str(err), None, self.t0)


def run_members(st: ChartSetup, init: np.ndarray, batch_shape: tuple[int, ...], t0: float, t1: float,
                te: np.ndarray | None, method: str, max_segments: int) -> Solution:
    """Integrate the averaged system from the initial slow states ``init`` (shape ``(B, 3)``).

    ``batch_shape == ()`` is one run (``B = 1``): a state with no average raises ValueError, the output is on
    ``te`` where reached (the integrator's steps without it) and the result a single-run :class:`Solution`.
    Otherwise a refused member ends with status -1 and its message, and every field has shape
    ``batch_shape + (len(te),)``, NaN after a member's end.
    """
    B = init.shape[0]
    m = _Members(st, B, t0, t1, te, method, max_segments, batch_shape != ())
    if batch_shape == ():
        m.start_one(0, *(float(v) for v in init[0]))
    else:
        m.start_all(init)
    m.run()
    return _single_result(m) if batch_shape == () else _batch_result(m, batch_shape)


def _single_result(m: _Members) -> Solution:
    """The single-run :class:`Solution` of a run of one member."""
    tau, cols = m.output.single()
    U = np.array([cols["u1"], cols["u2"], cols["u3"]]).reshape(3, -1)
    tev = {k: np.asarray(v[0], dtype=float) for k, v in m.tev.items()}
    return Solution.build(producer=PRODUCER, time_name="tau", time=tau, y=U, status=int(m.status[0]),
                          message=str(m.message[0]), fields={"u": U, **cols}, event=m.event[0], t_events=tev,
                          nfev=int(m.nfev[0]), t_final=float(m.t_final[0]))


def _batch_result(m: _Members, batch_shape: tuple[int, ...]) -> Solution:
    """The batch :class:`Solution`: every field of shape ``batch_shape + (len(te),)``, per-member records."""
    te, out = m.output.te, m.output.out
    assert te is not None
    nt = te.size
    data: dict[str, np.ndarray] = {k: v.reshape((*batch_shape, nt)) for k, v in out.items()}
    U = np.stack([out["u1"], out["u2"], out["u3"]], axis=1).reshape((*batch_shape, 3, nt))
    t_events: dict[str, np.ndarray] = {}
    for name, lists in m.tev.items():
        arr = np.empty(m.B, dtype=object)
        for q in range(m.B):
            arr[q] = np.asarray(lists[q], dtype=float)
        t_events[name] = arr.reshape(batch_shape)
    return Solution.build(producer=PRODUCER, time_name="tau", time=te, y=U, status=m.status.reshape(batch_shape),
                          message=m.message.reshape(batch_shape), fields={"u": U, **data},
                          event=m.event.reshape(batch_shape), t_events=t_events, nfev=m.nfev.reshape(batch_shape),
                          t_final=m.t_final.reshape(batch_shape))
