"""Integrate many independent systems together: a vectorised DOP853 with per-member step control.

:func:`integrate_batch` advances ``B`` independent initial-value problems ``y_i' = f(t_i, y_i)`` at once.
The right-hand side is evaluated on all active members in one call, ``fun(t, y)`` with ``t`` of shape
``(m,)`` and ``y`` of shape ``(m, n)``, so its cost is that of a few NumPy operations on arrays instead of
``B`` Python calls. Everything else is per member, exactly as :func:`scipy.integrate.solve_ivp` does it for
one system with ``method='DOP853'``:

* the method: the explicit Runge-Kutta pair of order 8(5,3) of Dormand and Prince with Hairer's
  coefficients, its error estimate and its 7th-order dense output (:mod:`rigidbody.core.dop853`, shared
  with the float integrator of :func:`rigidbody.core.ode.integrate`);
* the error control: SciPy's norm of the local error scaled by ``atol + rtol * max(|y_old|, |y_new|)``,
  its step-size factor (safety 0.9, limits 0.2 and 10) and its initial-step heuristic, each member with its
  own step size, accepted or rejected on its own;
* output on a common grid ``t_eval`` from each member's dense output;
* named events (:class:`rigidbody.core.ode.Event`), evaluated on the active members in one call and located
  per member on its dense output; a terminal event ends that member only, with its own status, message and
  event name;
* a member whose right-hand side turns non-finite (or whose step size underflows) ends alone with
  ``status = -1`` and a message naming the time; the others go on.

Members that have finished drop out of the work arrays, so a batch in which a few members run long costs
what those few cost. The result is a batch :class:`rigidbody.core.ode.Solution` (``sol.batch_shape``,
per-member ``status``/``message``/``event``, fields of shape ``batch_shape + (..., n_t)`` with NaN after a
member's end, ``sol[i]`` the single-run view of member ``i``).

Each member's trajectory equals a single :func:`scipy.integrate.solve_ivp` run with the same ``rtol``,
``atol`` within the tolerance (the arithmetic is the same up to rounding; the step sequences can differ
by rounding only).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from . import dop853 as rk
from ._batchdense import BatchDense, comb, locate
from .kernel import ARRAY
from .ode import Event, Solution

__all__ = ["integrate_batch", "member_records"]

_SUCCESS = "The solver successfully reached the end of the integration interval."
_NS = rk.N_STAGES


def member_records(B: int, t0: float, status: int = -1, message: Any = None
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The per-member records a batch result carries, before its members run.

    Parameters
    ----------
    B : int
        Number of members.
    t0 : float
        Start of the time span (each member's final time until it runs).
    status : int
        Initial status of every member (-1: not run).
    message : object
        Initial message of every member.

    Returns
    -------
    status, message, event, nfev, t_final : numpy.ndarray
        Shapes ``(B,)``: int statuses, object messages, object terminal events (None), int function counts,
        float final times.

    See Also
    --------
    integrate_batch : whose results carry these records.

    Examples
    --------
    Before they run, members are failures (``-1``) with no event, no function call, at ``t0``:

    >>> from rigidbody.core.batch import member_records
    >>> status, message, event, nfev, t_final = member_records(2, 0.5)
    >>> status, event, nfev, t_final
    (array([-1, -1]), array([None, None], dtype=object), array([0, 0]), array([0.5, 0.5]))
    """
    msg = np.empty(B, dtype=object)
    msg[:] = message
    event = np.empty(B, dtype=object)
    event[:] = None
    return np.full(B, status, dtype=int), msg, event, np.zeros(B, dtype=int), np.full(B, float(t0))


def _as_member_array(value: Any, size: int, name: str) -> np.ndarray:
    """A per-member float array of shape ``(size,)`` from a scalar or an array of ``size`` entries."""
    a = np.asarray(value, dtype=float)
    if a.ndim == 0:
        return np.full(size, float(a))
    if a.size != size:
        raise ValueError(f"{name} must be a scalar or have one entry per member ({size}), got shape {a.shape}")
    return a.reshape(size).copy()


def _rms_rows(x: np.ndarray) -> np.ndarray:
    return np.sqrt(np.einsum("ij,ij->i", x, x) / x.shape[1])


@dataclass
class _Problem:
    """The checked input of a batch run, members flattened to ``B`` rows."""

    fun: Callable[..., Any]
    batch_shape: tuple[int, ...]
    Y0: np.ndarray  # (B, n)
    T0: np.ndarray  # (B,)
    T1: np.ndarray  # (B,)
    rtol: np.ndarray  # () or (n,)
    atol: np.ndarray  # (), (n,) or (B, n)
    te: np.ndarray  # the output grid
    events: list[Event]
    params: tuple[np.ndarray, ...]  # each with leading axis B
    max_step: float
    max_steps: int
    time_name: str

    @property
    def B(self) -> int:
        return self.Y0.shape[0]

    @property
    def n(self) -> int:
        return self.Y0.shape[1]


def _tolerances(rtol: Any, atol: Any, batch_shape: tuple[int, ...], B: int, n: int) -> tuple[np.ndarray, np.ndarray]:
    rtol_a = np.asarray(rtol, dtype=float)
    if rtol_a.shape not in ((), (n,)) or not (np.all(np.isfinite(rtol_a)) and np.all(rtol_a > 0.0)):
        raise ValueError(f"rtol must be finite and > 0, a scalar or of shape ({n},), got {rtol!r}")
    atol_a = np.asarray(atol, dtype=float)
    if atol_a.shape in ((*batch_shape, n), (B, n)) and atol_a.ndim >= 2:
        atol_a = atol_a.reshape(B, n)  # per member
    elif atol_a.shape not in ((), (n,)):
        raise ValueError(f"atol must be a scalar or of shape ({n},) or batch_shape + ({n},), got shape "
                         f"{atol_a.shape}")
    if np.any(~np.isfinite(atol_a)) or np.any(atol_a < 0.0):
        raise ValueError(f"atol must be finite and >= 0, got {atol!r}")
    return np.maximum(rtol_a, rk.RTOL_FLOOR), atol_a  # SciPy's floor of rtol (without its warning)


def _problem(fun: Callable[..., Any], t_span: tuple[Any, Any], y0: Any, t_eval: Any, rtol: Any, atol: Any,
             events: Iterable[Event], args: tuple[Any, ...], max_step: float, max_steps: int, time_name: str
             ) -> _Problem:
    """The input of :func:`integrate_batch`, checked (a ValueError naming the parameter) and flattened."""
    y0a = np.asarray(y0, dtype=float)
    if y0a.ndim < 1:
        raise ValueError("y0 must have shape batch_shape + (n,)")
    batch_shape = y0a.shape[:-1]
    n = y0a.shape[-1]
    B = int(np.prod(batch_shape)) if batch_shape else 1
    if B == 0 or n == 0:
        raise ValueError(f"y0 must hold at least one member with at least one state, got shape {y0a.shape}")
    if len(t_span) != 2:
        raise ValueError(f"t_span must be a pair (t0, t1), got {t_span!r}")
    T0 = _as_member_array(t_span[0], B, "t_span[0]")
    T1 = _as_member_array(t_span[1], B, "t_span[1]")
    if not (np.all(np.isfinite(T0)) and np.all(np.isfinite(T1))):
        raise ValueError("t_span must be finite")
    if np.any(T1 < T0):
        raise ValueError("t_span must run forward (t1 >= t0) for every member")
    rtol_a, atol_a = _tolerances(rtol, atol, batch_shape, B, n)
    if t_eval is None:
        te = np.linspace(float(T0.min()), float(T1.max()), 101)
    else:
        te = np.atleast_1d(np.asarray(t_eval, dtype=float))
        if te.ndim != 1 or (te.size > 1 and np.any(np.diff(te) <= 0.0)) or not np.all(np.isfinite(te)):
            raise ValueError("t_eval must be a finite, strictly increasing 1-D array")
    P = []
    for i, a in enumerate(args):
        aa = np.asarray(a)
        if aa.shape[: len(batch_shape)] == batch_shape and batch_shape:
            aa = aa.reshape((B, *aa.shape[len(batch_shape):]))
        elif aa.ndim == 0 or aa.shape[0] != B:
            raise ValueError(f"args[{i}] must have a leading batch axis of size {B} (or shape {batch_shape}), "
                             f"got shape {aa.shape}")
        P.append(aa)
    return _Problem(fun, batch_shape, y0a.reshape(B, n), T0, T1, rtol_a, atol_a, te, list(events), tuple(P),
                    float(max_step), max_steps, time_name)


class _Records:
    """What the result carries per member, filled as members end."""

    def __init__(self, pb: _Problem) -> None:
        B, n = pb.B, pb.n
        self.Y = np.full((B, n, pb.te.size), np.nan)
        self.status, self.message, self.event, self.nfev, self.t_final = member_records(B, 0.0, 0, _SUCCESS)
        self.t_final[:] = pb.T0
        self.y_final = pb.Y0.copy()
        self.last_step = np.full(B, np.nan)
        self.tev: list[list[list[float]]] = [[[] for _ in range(B)] for _ in pb.events]
        self.yev: list[list[list[np.ndarray]]] = [[[] for _ in range(B)] for _ in pb.events]

    def finish(self, gidx: np.ndarray, st: int, msg: str, t_end: np.ndarray, y_end: np.ndarray) -> None:
        """Members ``gidx`` end with status ``st``, message ``msg``, at ``t_end`` in ``y_end``."""
        self.status[gidx] = st
        self.message[gidx] = msg
        self.t_final[gidx] = t_end
        self.y_final[gidx] = y_end

    def solution(self, pb: _Problem, fields: Callable[..., Mapping[str, np.ndarray]] | None) -> Solution:
        """The batch :class:`~rigidbody.core.ode.Solution`."""
        bs, n, nt = pb.batch_shape, pb.n, pb.te.size
        t_events: dict[str, np.ndarray] = {}
        y_events: dict[str, np.ndarray] = {}
        none_t, none_y = np.empty(0), np.empty((0, n))  # shared by the members without this event (read-only)
        none_t.setflags(write=False)
        none_y.setflags(write=False)
        for j, ev in enumerate(pb.events):
            te_obj = np.empty(pb.B, dtype=object)
            ye_obj = np.empty(pb.B, dtype=object)
            te_obj.fill(none_t)
            ye_obj.fill(none_y)
            for q in (q for q in range(pb.B) if self.tev[j][q]):
                te_obj[q] = np.asarray(self.tev[j][q], dtype=float)
                ye_obj[q] = np.asarray(self.yev[j][q], dtype=float).reshape(-1, n)
            t_events[ev.name] = te_obj.reshape(bs)
            y_events[ev.name] = ye_obj.reshape(bs)
        data: dict[str, np.ndarray] = {}
        if fields is not None and nt:
            with np.errstate(all="ignore"):
                for name, arr in dict(fields(pb.te, self.Y)).items():
                    a = np.asarray(arr)
                    data[name] = a.reshape(bs + a.shape[1:])
        return Solution.build(
            producer="core.batch.integrate_batch", time=pb.te, y=self.Y.reshape((*bs, n, nt)),
            status=self.status.reshape(bs), message=self.message.reshape(bs), fields=data,
            event=self.event.reshape(bs), t_events=t_events, y_events=y_events, nfev=self.nfev.reshape(bs),
            time_name=pb.time_name, t_final=self.t_final.reshape(bs), y_final=self.y_final.reshape((*bs, n)),
            last_step=self.last_step.reshape(bs))


class _Active:
    """The members still running, as work arrays (rows in the order of ``gidx``, their indices into the batch)."""

    def __init__(self, pb: _Problem, live: np.ndarray, F0: np.ndarray, G0: list[np.ndarray]) -> None:
        self.gidx = np.nonzero(live)[0]
        self.t = pb.T0[live].copy()
        self.t1 = pb.T1[live].copy()
        self.y = pb.Y0[live].copy()
        self.f = F0[live].copy()
        self.prm = tuple(p[live] for p in pb.params)
        self.g = [g.copy() for g in G0]  # the events' values at t
        self.rejected = np.zeros(self.gidx.size, dtype=bool)
        self.attempts = np.zeros(self.gidx.size, dtype=int)
        self.atol = pb.atol[live] if pb.atol.ndim == 2 else pb.atol
        self.h_abs = np.zeros(self.gidx.size)

    def keep(self, rows: np.ndarray) -> None:
        """Drop the members not in ``rows`` (a boolean mask)."""
        for name in ("gidx", "t", "t1", "y", "f", "rejected", "attempts", "h_abs"):
            setattr(self, name, getattr(self, name)[rows])
        self.prm = tuple(p[rows] for p in self.prm)
        self.g = [g[rows] for g in self.g]
        if self.atol.ndim == 2:
            self.atol = self.atol[rows]


def _start(pb: _Problem, rec: _Records, first_step: Any) -> _Active:
    """Samples at each member's start; members that cannot start fail at once; the initial step sizes."""
    B, nt, te = pb.B, pb.te.size, pb.te
    first = np.searchsorted(te, pb.T0, side="left")
    at0 = (first < nt) & (te[np.minimum(first, nt - 1)] == pb.T0)
    rec.Y[np.nonzero(at0)[0], :, first[at0]] = pb.Y0[at0]
    finite0 = np.all(np.isfinite(pb.Y0), axis=1)
    with np.errstate(all="ignore"):
        F0 = np.full((B, pb.n), np.nan)
        if np.any(finite0):
            F0[finite0] = np.asarray(pb.fun(pb.T0[finite0], pb.Y0[finite0], *(p[finite0] for p in pb.params)),
                                     dtype=float)
    rec.nfev[finite0] += 1
    ok0 = finite0 & np.all(np.isfinite(F0), axis=1)
    rec.status[~ok0] = -1
    rec.message[~finite0] = "the initial state is not finite"
    for g in np.nonzero(finite0 & ~ok0)[0]:
        rec.message[g] = (f"the right-hand side is not finite at the initial state ({pb.time_name} = "
                          f"{pb.T0[g]:.6g}): check the model's parameters")
    live = ok0 & (pb.T1 > pb.T0)
    G0 = [np.empty(0) for _ in pb.events]
    if np.any(live) and pb.events:
        with np.errstate(all="ignore"):
            G0 = [np.asarray(ev.fun(pb.T0[live], pb.Y0[live], *(p[live] for p in pb.params)), dtype=float
                             ).reshape(-1) for ev in pb.events]
    act = _Active(pb, live, F0, G0)
    if act.gidx.size:
        act.h_abs = _initial_steps(pb, act)
        rec.nfev[act.gidx] += 1
        if first_step is not None:
            fs = _as_member_array(first_step, B, "first_step")[act.gidx]
            act.h_abs = np.where(np.isfinite(fs) & (fs > 0.0), np.minimum(fs, act.t1 - act.t), act.h_abs)
    return act


def _initial_steps(pb: _Problem, act: _Active) -> np.ndarray:
    """The heuristic's first step of each active member (:func:`rigidbody.core.dop853.initial_step`)."""
    t, y, f, span = act.t, act.y, act.f, act.t1 - act.t
    with np.errstate(all="ignore"):
        scale = act.atol + np.abs(y) * pb.rtol
        d0, d1 = _rms_rows(y / scale), _rms_rows(f / scale)
        h0 = rk.trial_step(ARRAY, d0, d1, span)
        f1 = np.asarray(pb.fun(t + h0, y + h0[:, None] * f, *act.prm), dtype=float)
        d2 = _rms_rows((f1 - f) / scale) / h0
        h: np.ndarray = rk.initial_step(ARRAY, h0, d1, d2, span, pb.max_step)
    return h


class _Stages:
    """The stage array of the active members: stages 0..11, f_new (12), the dense output's 13..15."""

    def __init__(self) -> None:
        self.K = np.empty((_NS + 4, 0, 0))
        self.K2 = self.K.reshape(_NS + 4, 0)  # the same memory, one row per stage: combinations are products

    def sized(self, m: int, n: int) -> None:
        if self.K.shape[1:] != (m, n):
            self.K = np.empty((_NS + 4, m, n))
            self.K2 = self.K.reshape(_NS + 4, m * n)


def _try_step(pb: _Problem, act: _Active, st: _Stages, h: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """One DOP853 step of size ``h`` for every active member: ``y_new``, ``f_new`` and the scaled error."""
    m, n = act.y.shape
    K, K2, t, y, prm = st.K, st.K2, act.t, act.y, act.prm
    with np.errstate(all="ignore"):
        K[0] = act.f
        hc = h[:, None]
        for s in range(1, _NS):
            dy = comb(rk.A[s, :s], K2[:s]).reshape(m, n) * hc
            K[s] = pb.fun(t + rk.C[s] * h, y + dy, *prm)
        y_new = y + comb(rk.B, K2[:_NS]).reshape(m, n) * hc
        f_new = np.asarray(pb.fun(t + h, y_new, *prm), dtype=float)
        K[_NS] = f_new
        scale = act.atol + np.maximum(np.abs(y), np.abs(y_new)) * pb.rtol
        e5 = comb(rk.E5, K2[: _NS + 1]).reshape(m, n) / scale
        e3 = comb(rk.E3, K2[: _NS + 1]).reshape(m, n) / scale
        err = rk.error_norm(ARRAY, h, np.einsum("ij,ij->i", e5, e5), np.einsum("ij,ij->i", e3, e3), n)
    return y_new, f_new, err


def _dense(pb: _Problem, act: _Active, st: _Stages, ia: np.ndarray, nd: np.ndarray, h: np.ndarray,
           y_new: np.ndarray, f_new: np.ndarray, rec: _Records) -> BatchDense:
    """The dense output of this step for the accepted members ``ia[nd]`` (three more stages each)."""
    n = act.y.shape[1]
    rows = ia[nd]
    # the stages of those members (all of them, often: then K itself; a reshape must be a view)
    Kd = st.K if (nd.size == act.gidx.size and ia.size == nd.size) else np.ascontiguousarray(st.K[:, rows])
    md = nd.size
    Kd2 = Kd.reshape(_NS + 4, md * n)
    hd = h[rows][:, None]
    td, yd = act.t[rows], act.y[rows]
    prm_d = tuple(p[rows] for p in act.prm)
    with np.errstate(all="ignore"):
        for s in range(_NS + 1, _NS + 4):
            dy = comb(rk.A_EXTRA[s - _NS - 1, :s], Kd2[:s]).reshape(md, n) * hd
            Kd[s] = pb.fun(td + rk.C_EXTRA[s - _NS - 1] * h[rows], yd + dy, *prm_d)
    rec.nfev[act.gidx[rows]] += 3
    dly = y_new[rows] - yd
    Fd = np.empty((7, md, n))
    Fd[0] = dly
    Fd[1] = hd * Kd[0] - dly
    Fd[2] = 2.0 * dly - hd * (f_new[rows] + Kd[0])
    Fd[3:] = hd * comb(rk.D, Kd2).reshape(4, md, n)
    return BatchDense(td, h[rows], yd, Fd)


def _events(pb: _Problem, act: _Active, rec: _Records, ia: np.ndarray, crossing: list[np.ndarray],
            dense: BatchDense | None, pos: np.ndarray, t_new: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Roots of the events that crossed in this step (accepted members ``ia``), the ones that count recorded
    (:func:`rigidbody.core.dop853.settle_events`); returns where each member's step ends and the index of
    the terminal event that ends it (-1: none)."""
    if dense is None or not any(c.any() for c in crossing):
        return t_new[ia], np.full(ia.size, -1)
    ta, tb = act.t[ia], t_new[ia]
    roots = []
    for j, ev in enumerate(pb.events):
        r = np.full(ia.size, np.nan)
        kk = np.nonzero(crossing[j])[0]
        if kk.size:
            r[kk] = locate(ev, dense, pos[kk], ta[kk], tb[kk], act.g[j][ia[kk]], tuple(p[ia[kk]] for p in act.prm))
        roots.append(r)
    t_stop, stop, counted = rk.settle_events(ARRAY, roots, [ev.terminal for ev in pb.events], tb)
    for j, keep in enumerate(counted):
        kk = np.nonzero(keep)[0]
        if kk.size:
            for k, rt, yk in zip(kk, roots[j][kk], dense(roots[j][kk], pos[kk])):
                rec.tev[j][act.gidx[ia[k]]].append(float(rt))
                rec.yev[j][act.gidx[ia[k]]].append(yk)
    return t_stop, stop


def _accept(pb: _Problem, act: _Active, rec: _Records, st: _Stages, acc: np.ndarray, h: np.ndarray,
            y_new: np.ndarray, f_new: np.ndarray, done: np.ndarray) -> None:
    """The accepted members ``acc``: events, output samples, terminal events, the end of the span; then they
    advance. Members that end are marked in ``done``."""
    ia = np.nonzero(acc)[0]
    te, evs = pb.te, pb.events
    t_new = act.t + h
    ta, tna, yna = act.t[ia], t_new[ia], y_new[ia]
    lo = np.searchsorted(te, ta, side="right")
    gnew: list[np.ndarray] = []
    if evs:
        with np.errstate(all="ignore"):
            prm_a = tuple(p[ia] for p in act.prm)
            gnew = [np.asarray(ev.fun(tna, yna, *prm_a), dtype=float).reshape(-1) for ev in evs]
    crossing = [rk.crossed(act.g[j][ia], gnew[j], ev.direction) for j, ev in enumerate(evs)]
    need = np.searchsorted(te, tna, side="right") > lo
    for hit in crossing:
        need = need | hit
    nd = np.nonzero(need)[0]
    dense = _dense(pb, act, st, ia, nd, h, y_new, f_new, rec) if nd.size else None
    pos = np.full(ia.size, -1)  # position of each accepted member in the dense output
    pos[nd] = np.arange(nd.size)
    t_stop, stop = _events(pb, act, rec, ia, crossing, dense, pos, t_new)
    cnt = np.maximum(np.searchsorted(te, t_stop, side="right") - lo, 0)  # output samples in (t_old, t_stop]
    if cnt.any():
        assert dense is not None
        mm = np.nonzero(cnt)[0]  # members with samples in this step: grid indices lo .. hi - 1 each
        which, jj, ys = dense.on_grid(te, pos[mm], lo[mm], cnt[mm])
        rec.Y[act.gidx[ia[mm[which]]], :, jj] = ys
    term = np.nonzero(stop >= 0)[0]
    if term.size:  # terminal events end their member at the root
        assert dense is not None
        for k, y_end in zip(term, dense(t_stop[term], pos[term])):
            ev, g = evs[int(stop[k])], act.gidx[ia[k]]
            rec.finish(np.array([g]), 1, f"stopped by event {ev.name!r} at {pb.time_name} = {t_stop[k]:.6g}" + (
                f": {ev.message}" if ev.message else ""), t_stop[k: k + 1], y_end[None, :])
            rec.event[g] = ev.name
            done[ia[k]] = True
    act.t[ia], act.y[ia], act.f[ia] = tna, yna, f_new[ia]
    for j in range(len(evs)):
        act.g[j][ia] = gnew[j]
    reached = np.nonzero((tna >= act.t1[ia]) & (stop < 0))[0]
    if reached.size:
        rec.finish(act.gidx[ia[reached]], 0, _SUCCESS, tna[reached], yna[reached])
        done[ia[reached]] = True


def _fail(pb: _Problem, act: _Active, rec: _Records, rows: np.ndarray, good: np.ndarray, stuck: np.ndarray) -> None:
    """Members ``rows`` fail: a non-finite step, a step size that underflows, or too many attempts."""
    for k in rows:
        if not good[k]:
            msg = (f"the state or its derivative became non-finite near {pb.time_name} = {act.t[k]:.6g}; "
                   "integration stopped")
        elif stuck[k]:
            msg = "Required step size is less than spacing between numbers."
        else:
            msg = f"more than max_steps={pb.max_steps} step attempts"
        rec.finish(act.gidx[k: k + 1], -1, msg, act.t[k: k + 1], act.y[k: k + 1])


def integrate_batch(
    fun: Callable[..., Any],
    t_span: tuple[Any, Any],
    y0: Any,
    *,
    t_eval: Any = None,
    rtol: Any = 1e-10,
    atol: Any = 1e-12,
    events: Iterable[Event] = (),
    args: tuple[Any, ...] = (),
    max_step: float = np.inf,
    time_name: str = "t",
    fields: Callable[[np.ndarray, np.ndarray], Mapping[str, np.ndarray]] | None = None,
    max_steps: int = 1_000_000,
    first_step: Any = None,
) -> Solution:
    """Integrate a batch of independent systems ``dy/dt = fun(t, y)`` with per-member DOP853 step control.

    Parameters
    ----------
    fun : callable
        ``fun(t, y, *args) -> dydt`` vectorised over members: ``t`` of shape ``(m,)``, ``y`` of shape
        ``(m, n)``, the result of shape ``(m, n)``, for any subset of ``m`` active members (the ``args`` are
        sliced to the same subset).
    t_span : (t0, t1)
        Start and end times, scalars or arrays with one entry per member (``t1 >= t0``; integration runs
        forward).
    y0 : array_like
        Initial states, shape ``batch_shape + (n,)``.
    t_eval : array_like, optional
        Common increasing output grid (default: 101 points spanning ``[min t0, max t1]``). A member
        contributes the samples that lie in its own ``[t0, t_end]`` and NaN elsewhere.
    rtol, atol : float
        Tolerances as in :func:`scipy.integrate.solve_ivp`; ``rtol`` may be an array of shape ``(n,)`` (per
        component), ``atol`` of shape ``(n,)`` or ``batch_shape + (n,)`` (per member and component).
    events : iterable of Event
        Named events; ``Event.fun(t, y, *args)`` is vectorised like ``fun`` and returns shape ``(m,)``.
        A terminal event ends its member (``status = 1``, ``event`` its name).
    args : tuple of array_like
        Per-member parameters, each with leading axis of size ``B`` (the flattened batch) or
        ``batch_shape``; they are sliced to the active members before each call of ``fun`` and events.
    max_step : float
        Largest step size.
    time_name : str
        Name of the time array in the result (``'t'`` or ``'tau'``).
    fields : callable, optional
        ``fields(t, y) -> {name: array}`` on the output grid, ``y`` of shape ``(B, n, n_t)`` (NaN where a
        member has no sample); each array has leading axis ``B``.
    max_steps : int
        Step attempts per member before it ends with ``status = -1`` (a guard against runaway runs).
    first_step : float or array_like, optional
        Initial step size per member (NaN or None: SciPy's heuristic), e.g. the ``last_step`` of a batch being
        continued.

    Returns
    -------
    rigidbody.core.ode.Solution
        A batch solution: ``batch_shape``, ``time`` (the grid), ``y`` of shape ``batch_shape + (n, n_t)``,
        per-member ``status`` (0 end reached, 1 terminal event, -1 failure), ``message``, ``event``,
        ``success``, ``t_events``/``y_events`` (name -> object array of per-member arrays), ``nfev`` (per
        member), ``t_final``/``y_final`` (each member's last time and state), ``last_step`` (the step size each
        member would have taken next).

    Raises
    ------
    ValueError
        For an empty batch, a ``t_span`` that runs backwards or is not finite, a non-increasing
        ``t_eval``, or non-positive tolerances.

    See Also
    --------
    rigidbody.core.ode.integrate : one system.
    rigidbody.core.ode.Event : the events it takes (vectorised).

    Examples
    --------
    ``dy/dt = -k y`` for three decay rates at once; member ``i`` ends at ``exp(-k_i)``:

    >>> import numpy as np
    >>> from rigidbody.core.batch import integrate_batch
    >>> k = np.array([1.0, 2.0, 3.0])
    >>> sol = integrate_batch(lambda t, y, k: -k[:, None] * y, (0.0, 1.0), np.ones((3, 1)), args=(k,))
    >>> print(" ".join(f"{x:.9f}" for x in sol.y[:, 0, -1]))
    0.367879441 0.135335283 0.049787068
    >>> print(" ".join(f"{x:.9f}" for x in np.exp(-k)))
    0.367879441 0.135335283 0.049787068
    >>> sol.status
    array([0, 0, 0])
    """
    pb = _problem(fun, t_span, y0, t_eval, rtol, atol, events, args, max_step, max_steps, time_name)
    rec = _Records(pb)
    act = _start(pb, rec, first_step)
    st = _Stages()
    while act.gidx.size:
        m = act.gidx.size
        st.sized(m, pb.n)
        min_step = rk.MIN_STEP_SPACINGS * np.abs(np.nextafter(act.t, np.inf) - act.t)
        act.h_abs = np.clip(act.h_abs, min_step, pb.max_step)
        h = np.minimum(act.h_abs, act.t1 - act.t)
        y_new, f_new, err = _try_step(pb, act, st, h)
        rec.nfev[act.gidx] += _NS
        act.attempts += 1
        good = np.isfinite(err) & np.isfinite(y_new).all(axis=1) & np.isfinite(f_new).all(axis=1)
        acc = good & (err < 1.0)
        with np.errstate(all="ignore"):
            h_next = act.h_abs * np.where(good, rk.step_factor(ARRAY, err, act.rejected), rk.MIN_FACTOR)
        stuck = ~acc & (act.h_abs <= min_step)  # a rejected step already at the smallest size
        failed = stuck | (~acc & (act.attempts >= pb.max_steps))
        done = failed.copy()
        if failed.any():
            _fail(pb, act, rec, np.nonzero(failed)[0], good, stuck)
        if acc.any():
            _accept(pb, act, rec, st, acc, h, y_new, f_new, done)
        act.rejected = ~acc
        act.h_abs = h_next
        if done.any():
            rec.last_step[act.gidx[done]] = h_next[done]
            act.keep(~done)
    return rec.solution(pb, fields)
