r"""A batch of averaged evolutions (2.15) integrated together, chart by chart.

Every member carries its own chart (``u`` or ``GHr``), signs ``delta1, delta2``, time and step size. A round
integrates the members that are in the u chart together with :func:`rigidbody.core.batch.integrate_batch`
(vectorised right-hand side and events), then those in the GHr chart; a member that reaches a branch point
(or leaves its neighbourhood) continues in the other chart in the next batch from its switching point, a
member that meets a degenerate state ends with its own status. Each member follows exactly the steps of its
single run (:func:`rigidbody.lagrange.averaged`): the same coordinates, tolerances, events, switching rules
and step-size hand-over.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..core.batch import integrate_batch, member_records
from ..core.ode import Event, Solution
from . import _kernel as _k
from ._avgrun import (
    _KAPPA_FLOOR,
    _MSG_BRANCH,
    _MSG_DEG,
    _MSG_END,
    _MSG_SEP,
    _MSG_TRIPLE,
    _PSI_FLOOR,
    _RTOL_FLOOR,
    _TRIPLE_TOL,
    _Setup,
    _single,
    _start_chart,
)

__all__ = ["averaged_batch"]

_FIELDS = ("u1", "u2", "u3", "Gz", "H", "r", "k2", "delta1", "delta2", "chart")
_AX = _k.ARRAY


def _cols(y: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    return y[:, 0], y[:, 1], y[:, 2]


def averaged_batch(st: _Setup, initial: Any, t0: float, t1: float, te: np.ndarray | None,
                   max_segments: int) -> Solution:
    """The batch branch of :func:`rigidbody.lagrange.averaged` (``initial`` of shape ``batch_shape + (3,)``)."""
    try:
        ini = np.asarray(initial, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"initial must be (Gz, H, r) or an array of shape batch_shape + (3,), got {initial!r}"
                         ) from None
    if ini.ndim < 2 or ini.shape[-1] != 3:
        raise ValueError(f"a batch of initial states has shape batch_shape + (3,), got {ini.shape}")
    batch_shape = ini.shape[:-1]
    B = int(np.prod(batch_shape))
    if B == 0:
        raise ValueError("the batch of initial states is empty")
    init = ini.reshape(B, 3)
    te = np.linspace(t0, t1, 101) if te is None else te
    nt = te.size
    chart_mode = st.chart

    out = {k: np.full((B, nt), np.nan) for k in _FIELDS}
    status, message, event, nfev, t_final = member_records(B, t0, 0, _MSG_END)
    tev: dict[str, list[list[float]]] = {k: [[] for _ in range(B)] for k in ("delta1_flip", "delta2_flip",
                                                                             "chart_switch")}

    cur = np.array(["-"] * B, dtype=object)  # 'u', 'p' (GHr, log-polar), '-' done
    X = np.zeros((B, 3))
    D1 = np.ones(B)
    D2 = np.ones(B)
    tau = np.full(B, t0)
    hnext = np.full(B, np.nan)
    nseg = np.zeros(B, dtype=int)

    def finish(i: int, st_: int, msg: str, ev: str | None, t_end: float) -> None:
        status[i], message[i], event[i], t_final[i] = st_, msg, ev, t_end
        cur[i] = "-"

    # ---- starting charts: decided together; unusual members (no average, on a threshold, Gz = r = 0) one by one
    Gz0, H0, r0 = init[:, 0], init[:, 1], init[:, 2]
    with np.errstate(all="ignore"):
        finite = np.isfinite(init).all(axis=1)
        Cr0 = st.C * r0
        S2 = Gz0 * Gz0 + Cr0 * Cr0
        g0 = _k.decode_g(_AX, st.A, st.C, st.mgl, *_k.slow_to_polar(_AX, st.C, Gz0, H0, r0, st.mgl))
        u1, u2, u3 = g0.u1, g0.u2, g0.u3
        D1[:] = np.where(Gz0 * Gz0 - Cr0 * Cr0 >= 0.0, 1.0, -1.0)
        D2[:] = np.where(r0 >= 0.0, 1.0, -1.0)
        b = np.minimum(np.abs(Gz0 * Gz0 - Cr0 * Cr0), Cr0 * Cr0) / S2
        deg = (u2 - u1) <= st.deg * (u3 - u1)
        want_u = np.full(B, chart_mode != "GHr")
        if chart_mode == "auto":
            want_u &= (b >= st.sw) & ~deg
        raw_lo, raw_hi = g0.msum - g0.half, g0.msum + g0.half
        unusual = (~finite | (S2 == 0.0) | ~g0.ok | ~g0.inside | (raw_lo < -1.0) | (raw_hi > 1.0) | (g0.K < 0.0)
                   | ((u3 - u2) <= 10.0 * st.deg * (u3 - u1)) | (g0.spread <= 2.0 * _TRIPLE_TOL)
                   | (np.abs(b - st.sw) <= 1e-9) | ((chart_mode == "u") & ((b <= st.sw) | deg)))
    done0 = np.zeros(B, dtype=bool)
    for i in np.nonzero(unusual)[0]:
        Gz, H, r = (float(v) for v in init[i])
        done0[i] = True
        if not finite[i]:
            finish(int(i), -1, "the initial state (Gz, H, r) is not finite", None, t0)
            continue
        try:
            c, d1, d2, _ = _start_chart(st, Gz, H, r)
        except ValueError as err:
            finish(int(i), -1, str(err), None, t0)
            continue
        done0[i] = False
        D1[i], D2[i] = d1, d2
        want_u[i] = c == "u"
        if c != "u" and S2[i] == 0.0:
            done0[i] = True
            # Gz = r = 0: the plain (Gz, H, r) chart, one member at a time (the single run)
            one = _single(st, Gz, H, r, t0, t1, te, "DOP853", max_segments)
            cols = np.searchsorted(te, one.tau)
            for k in _FIELDS:
                out[k][i, cols] = one[k]
            for k, v in one.t_events.items():
                tev.setdefault(k, [[] for _ in range(B)])[i] = list(v)
            nfev[i] = one.nfev
            finish(int(i), int(one.status), str(one.message), one.event,
                   float(one.tau[-1]) if one.tau.size else t0)
    iu0 = np.nonzero(~done0 & want_u)[0]
    ip0 = np.nonzero(~done0 & ~want_u)[0]
    cur[:] = "-"
    if iu0.size:
        with np.errstate(all="ignore"):
            X[iu0] = np.stack(st.slow_to_x(_AX, Gz0[iu0], H0[iu0], r0[iu0],
                                           *st.roots_g(_AX, Gz0[iu0], H0[iu0], r0[iu0])), axis=1)
        cur[iu0] = "u"
    if ip0.size:
        X[ip0] = np.stack(_k.slow_to_polar(_AX, st.C, Gz0[ip0], H0[ip0], r0[ip0], st.mgl), axis=1)
        cur[ip0] = "p"

    # ---- vectorised right-hand sides and events ----------------------------------------------------------
    def rhs_u(t: np.ndarray, y: np.ndarray, d1: np.ndarray, d2: np.ndarray) -> np.ndarray:
        x1, x2, th = _cols(y)
        d = np.stack(st.rhs_x(_AX, x1, x2, th, d1, d2), axis=1)
        bad = ~(x1 < x2)
        if bad.any():
            d[bad] = np.nan  # a stage with the root order violated is rejected
        return d

    # the GHr chart integrates psi - n per member (see the single run); n rides along as an argument
    def rhs_p(t: np.ndarray, y: np.ndarray, n_off: np.ndarray) -> np.ndarray:
        return np.stack(st.rhs_p(_AX, y[:, 0], y[:, 1] + n_off, y[:, 2]), axis=1)

    # the three u-chart events are evaluated in turn on the same arrays: one evaluation serves them (the cache
    # holds the arrays themselves, so their ids cannot be reused while cached)
    ucache: list[Any] = [None, None, None]

    def u_events(t: np.ndarray, y: np.ndarray, d1: np.ndarray) -> tuple[np.ndarray, ...]:
        if ucache[0] is not t or ucache[1] is not y:
            ucache[:] = [t, y, st.u_events(_AX, *_cols(y), d1)]
        return ucache[2]

    def ev_deg(t: np.ndarray, y: np.ndarray, d1: np.ndarray, d2: np.ndarray) -> np.ndarray:
        return u_events(t, y, d1)[0]

    def ev_sep(t: np.ndarray, y: np.ndarray, d1: np.ndarray, d2: np.ndarray) -> np.ndarray:
        return u_events(t, y, d1)[1]

    def ev_branch(t: np.ndarray, y: np.ndarray, d1: np.ndarray, d2: np.ndarray) -> np.ndarray:
        return u_events(t, y, d1)[2]

    def ev_w(t: np.ndarray, y: np.ndarray, n_off: np.ndarray) -> np.ndarray:
        return st.ev_w(_AX, y[:, 1] + n_off)

    def ev_r(t: np.ndarray, y: np.ndarray, n_off: np.ndarray) -> np.ndarray:
        return st.ev_r(_AX, y[:, 1] + n_off)

    def ev_sep_p(t: np.ndarray, y: np.ndarray, n_off: np.ndarray) -> np.ndarray:
        return st.ev_roots_g(_AX, y[:, 0], y[:, 1] + n_off, y[:, 2])[0]

    def ev_triple(t: np.ndarray, y: np.ndarray, n_off: np.ndarray) -> np.ndarray:
        return st.ev_roots_g(_AX, y[:, 0], y[:, 1] + n_off, y[:, 2])[1]

    def ev_leave(t: np.ndarray, y: np.ndarray, n_off: np.ndarray) -> np.ndarray:
        return st.ev_leave(_AX, y[:, 1] + n_off)

    def merge(idx: np.ndarray, Y: np.ndarray, f: dict[str, np.ndarray]) -> None:
        mask = np.all(np.isfinite(Y), axis=1)
        for k in _FIELDS:
            blk = out[k][idx]
            blk[mask] = np.broadcast_to(f[k], mask.shape)[mask]
            out[k][idx] = blk

    def end_member(i: int, k: int, sol: Solution) -> None:
        ev = sol.event[k]
        st_ = int(sol.status[k])
        msg = _MSG_END if st_ == 0 else str(sol.message[k])
        if ev is not None:
            tev[ev] = tev.get(ev, [[] for _ in range(B)])
            tev[ev][i] = list(sol.t_events[ev][k])
        finish(i, st_, msg, ev, float(sol.t_final[k]))

    # ---- rounds: the u-chart members, then the GHr-chart members ---------------------------------------
    while True:
        iu = np.nonzero(cur == "u")[0]
        ip = np.nonzero(cur == "p")[0]
        if not iu.size and not ip.size:
            break
        over = np.concatenate([iu, ip])
        over = over[nseg[over] >= max_segments]
        for i in over:
            finish(int(i), -1, f"more than max_segments={max_segments} chart switches (chattering)", None,
                   float(tau[i]))
        iu = iu[nseg[iu] < max_segments]
        if iu.size:
            nseg[iu] += 1
            evs = [Event(ev_deg, "u1_eq_u2", True, -1.0, _MSG_DEG), Event(ev_sep, "separatrix", True, -1.0, _MSG_SEP)]
            if chart_mode in ("auto", "u"):
                evs.append(Event(ev_branch, "branch_point", True, -1.0, _MSG_BRANCH))
            sol = integrate_batch(rhs_u, (tau[iu], t1), X[iu], t_eval=te, rtol=_RTOL_FLOOR, atol=st.rtol,
                                  events=evs, args=(D1[iu], D2[iu]), time_name="tau", first_step=hnext[iu])
            nfev[iu] += sol.nfev
            with np.errstate(all="ignore"):
                f = st.fields_x(sol.y, D1[iu], D2[iu])
            f["chart"] = np.zeros((iu.size, nt))
            merge(iu, sol.y, f)
            hnext[iu] = sol.last_step
            sw_k = (sol.status == 1) & (sol.event == "branch_point") & (chart_mode == "auto")
            for j in np.nonzero(~sw_k)[0].tolist():
                end_member(int(iu[j]), int(j), sol)
            if np.any(sw_k):
                ks = np.nonzero(sw_k)[0]
                isw = iu[ks]
                t_sw = np.array([sol.t_events["branch_point"][j][-1] for j in ks])
                ye = np.array([sol.y_events["branch_point"][j][-1] for j in ks])
                s = _k.decode_u(_AX, st.A, st.C, st.mgl, ye[:, 0], ye[:, 1], ye[:, 2], D1[isw], D2[isw])
                X[isw] = np.stack(_k.slow_to_polar(_AX, st.C, s.Gz, s.H, s.r, st.mgl), axis=1)
                tau[isw] = t_sw
                for i, tsw in zip(isw, t_sw):
                    tev["chart_switch"][i].append(float(tsw))
                cur[isw] = "p"
        ip = np.nonzero(cur == "p")[0]
        ip = ip[nseg[ip] < max_segments]
        if ip.size:
            nseg[ip] += 1
            evs = [Event(ev_w, "delta1_flip", False, 0.0), Event(ev_r, "delta2_flip", False, 0.0),
                   Event(ev_sep_p, "separatrix", True, -1.0, _MSG_SEP),
                   Event(ev_triple, "triple_root", True, -1.0, _MSG_TRIPLE)]
            if chart_mode == "auto":
                evs.append(Event(ev_leave, "leave_branch", True, 1.0))
            n_off = np.rint(X[ip, 1])
            Y0 = X[ip] - np.stack([np.zeros(ip.size), n_off, np.zeros(ip.size)], axis=1)
            rtol_p, _ = st.polar_tolerances(1.0, "python")
            atol = np.stack([np.full(ip.size, st.rtol), np.full(ip.size, st.rtol * _PSI_FLOOR),
                             st.rtol * np.maximum(np.abs(X[ip, 2]), _KAPPA_FLOOR)], axis=1)
            sol = integrate_batch(rhs_p, (tau[ip], t1), Y0, t_eval=te, rtol=rtol_p, atol=atol,
                                  events=evs, args=(n_off,), time_name="tau", first_step=hnext[ip])
            nfev[ip] += sol.nfev
            f = st.fields_p(sol.y + np.stack([np.zeros(ip.size), n_off, np.zeros(ip.size)], axis=1)[:, :, None])
            f["chart"] = np.ones((ip.size, nt))
            merge(ip, sol.y, f)
            hnext[ip] = sol.last_step
            for j, mm in enumerate(ip.tolist()):
                tev["delta1_flip"][mm].extend(sol.t_events["delta1_flip"][j].tolist())
                tev["delta2_flip"][mm].extend(sol.t_events["delta2_flip"][j].tolist())
            lv = (sol.status == 1) & (sol.event == "leave_branch")
            for j in np.nonzero(~lv)[0].tolist():
                end_member(int(ip[j]), int(j), sol)
            if np.any(lv):
                ks = np.nonzero(lv)[0]
                ilv = ip[ks]
                t_sw = np.array([sol.t_events["leave_branch"][j][-1] for j in ks])
                ye = np.array([sol.y_events["leave_branch"][j][-1] for j in ks])
                with np.errstate(all="ignore"):
                    g = _k.decode_g(_AX, st.A, st.C, st.mgl, ye[:, 0], ye[:, 1] + n_off[ks], ye[:, 2])
                    D1[ilv] = np.where(g.Gz * g.Gz - g.Cr * g.Cr >= 0.0, 1.0, -1.0)
                    D2[ilv] = np.where(g.r >= 0.0, 1.0, -1.0)
                    v1, v2, v3 = st.roots_g(_AX, g.Gz, g.H, g.r)
                    dg = (v2 - v1) <= st.deg * (v3 - v1)
                    X[ilv] = np.stack(st.slow_to_x(_AX, g.Gz, g.H, g.r, v1, v2, v3), axis=1)
                tau[ilv] = t_sw
                for i, tsw, d in zip(ilv, t_sw, dg):
                    tev["chart_switch"][i].append(float(tsw))
                    if d:
                        finish(int(i), 1, f"stopped by event 'u1_eq_u2' at tau = {tsw:.6g}: {_MSG_DEG}", "u1_eq_u2",
                               float(tsw))
                    else:
                        cur[i] = "u"

    # ---- assemble -------------------------------------------------------------------------------------
    data: dict[str, np.ndarray] = {k: v.reshape((*batch_shape, nt)) for k, v in out.items()}
    U = np.stack([out["u1"], out["u2"], out["u3"]], axis=1).reshape((*batch_shape, 3, nt))
    data = {"u": U, **data}
    t_events: dict[str, np.ndarray] = {}
    for name, lists in tev.items():
        arr = np.empty(B, dtype=object)
        for q in range(B):
            arr[q] = np.asarray(lists[q], dtype=float)
        t_events[name] = arr.reshape(batch_shape)
    return Solution("tau", te, U, data, status.reshape(batch_shape), message.reshape(batch_shape),
                    event.reshape(batch_shape), t_events, {}, None, nfev.reshape(batch_shape),
                    batch_shape=batch_shape, t_final=t_final.reshape(batch_shape))
