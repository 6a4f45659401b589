"""Integrate many independent systems together: a vectorised DOP853 with per-member step control.

:func:`integrate_batch` advances ``B`` independent initial-value problems ``y_i' = f(t_i, y_i)`` at once.
The right-hand side is evaluated on all active members in one call, ``fun(t, y)`` with ``t`` of shape
``(m,)`` and ``y`` of shape ``(m, n)``, so its cost is that of a few NumPy operations on arrays instead of
``B`` Python calls. Everything else is per member, exactly as :func:`scipy.integrate.solve_ivp` does it for
one system with ``method='DOP853'``:

* the method: the explicit Runge-Kutta pair of order 8(5,3) of Dormand and Prince with Hairer's
  coefficients (read from :class:`scipy.integrate.DOP853`), its error estimate and its 7th-order dense
  output;
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
from typing import Any

import numpy as np
from scipy.integrate import DOP853

from .ode import Event, Solution, crossed

__all__ = ["integrate_batch", "member_records"]

# Hairer's DOP853 coefficients as SciPy ships them (12 stages, 3 more for the dense output)
_N_STAGES: int = DOP853.n_stages
_A: np.ndarray = np.asarray(DOP853.A, dtype=float)
_B: np.ndarray = np.asarray(DOP853.B, dtype=float)
_C: np.ndarray = np.asarray(DOP853.C, dtype=float)
_E3: np.ndarray = np.asarray(DOP853.E3, dtype=float)
_E5: np.ndarray = np.asarray(DOP853.E5, dtype=float)
_D: np.ndarray = np.asarray(DOP853.D, dtype=float)
_A_EXTRA: np.ndarray = np.asarray(DOP853.A_EXTRA, dtype=float)
_C_EXTRA: np.ndarray = np.asarray(DOP853.C_EXTRA, dtype=float)
_ORDER_EST = DOP853.error_estimator_order  # 7: the error is O(h^8)
_ERR_EXP = -1.0 / (_ORDER_EST + 1)
# SciPy's step-size controller (scipy/integrate/_ivp/rk.py)
_SAFETY, _MIN_FACTOR, _MAX_FACTOR = 0.9, 0.2, 10.0
_EPS = np.finfo(float).eps


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


def _comb(c: np.ndarray, K: np.ndarray) -> np.ndarray:
    """The linear combination ``c @ K`` of stage rows by einsum's own loop: a BLAS call would spread these
    memory-bound products over threads, which on a loaded machine costs more than it saves."""
    return np.einsum("...j,jk->...k", c, K)


def _all_members(ia: np.ndarray, nd: np.ndarray, m: int) -> bool:
    """Whether the members ``ia[nd]`` are all ``m`` active members in order (their stages are ``K`` itself)."""
    return bool(nd.size == m and ia.size == m)


def _rms_rows(x: np.ndarray) -> np.ndarray:
    return np.sqrt(np.einsum("ij,ij->i", x, x) / x.shape[1])


class _Dense:
    """The DOP853 dense output of one accepted step for a set of members (``F`` of shape (7, m, n))."""

    __slots__ = ("F", "h", "t_old", "y_old")

    def __init__(self, t_old: np.ndarray, h: np.ndarray, y_old: np.ndarray, F: np.ndarray) -> None:
        self.t_old, self.h, self.y_old, self.F = t_old, h, y_old, F

    def __call__(self, t: np.ndarray, rows: np.ndarray) -> np.ndarray:
        """States at times ``t`` (shape (p,)) of the members ``rows`` (indices into this step's members)."""
        x = ((t - self.t_old[rows]) / self.h[rows])[:, None]
        F = self.F[:, rows, :]
        y = np.zeros_like(F[0])
        for i, f in enumerate(F[::-1]):
            y += f
            if i % 2 == 0:
                y *= x
            else:
                y *= 1.0 - x
        return y + self.y_old[rows]

    def on_grid(self, te: np.ndarray, rows: np.ndarray, lo: np.ndarray, cnt: np.ndarray) -> tuple[np.ndarray, ...]:
        """States on the grid points ``te[lo_i], ..., te[lo_i + cnt_i - 1]`` of each member ``rows_i`` (``cnt_i
        >= 1``): the interpolant evaluated per member on a block of its samples (the member's coefficients
        gathered once, not once per sample), members grouped by their number of samples (up to 2, 4, 8, ...) so
        that a block is never more than half empty. Returns the members' positions (into ``rows``), the grid
        indices and the states, one row per sample."""
        out_w, out_j, out_y = [], [], []
        bucket = np.ceil(np.log2(np.maximum(cnt, 1))).astype(int)
        for b in np.unique(bucket):
            sel = np.nonzero(bucket == b)[0]
            r, c = rows[sel], cnt[sel]
            S = int(c.max())
            k = np.arange(S)
            J = lo[sel, None] + k
            valid = k < c[:, None]
            t = te[np.minimum(J, te.size - 1)]
            x = ((t - self.t_old[r][:, None]) / self.h[r][:, None])[:, :, None]
            x1 = 1.0 - x
            F = self.F[:, r, :][:, :, None, :]
            y = F[6] * x
            for q in range(5, -1, -1):  # the alternating factors of scipy's Dop853DenseOutput, innermost first
                y += F[q]
                y *= x1 if q % 2 else x
            y += self.y_old[r][:, None, :]
            out_w.append(np.repeat(sel, c))
            out_j.append(J[valid])
            out_y.append(y[valid])
        if len(out_w) == 1:
            return out_w[0], out_j[0], out_y[0]
        return np.concatenate(out_w), np.concatenate(out_j), np.concatenate(out_y)


def _locate(
    ev: Event, dense: _Dense, rows: np.ndarray, ta: np.ndarray, tb: np.ndarray, ga: np.ndarray,
    args_rows: tuple[np.ndarray, ...],
) -> np.ndarray:
    """Zero of ``ev.fun`` on each member's step ``[ta, tb]`` (a bracket with ``ga`` at ``ta``).

    A vectorised Illinois (modified regula falsi) iteration with a bisection fallback, each member until its
    estimate moves by less than 4 ulp of ``t`` or 1e-12 of the step: every iteration evaluates the event once
    on the unconverged members.
    """
    a, b = ta.copy(), tb.copy()
    fa = ga.copy()
    fb = np.asarray(ev.fun(b, dense(b, rows), *args_rows), dtype=float).reshape(-1)
    ta_val, tb_val = fa.copy(), fb.copy()  # the event's values at a and b (fa, fb are Illinois-weighted)
    side = np.zeros(a.size)
    root = np.where(fb == 0.0, b, np.where(fa == 0.0, a, 0.5 * (a + b)))
    todo = (fa != 0.0) & (fb != 0.0)
    # converged when an estimate moves by less than 4 ulp of t or 1e-12 of the step: far below the integration
    # error of the state at the event (the event function's own rounding would stall a tighter criterion)
    tol_all = np.maximum(4.0 * _EPS * np.maximum(np.abs(ta), np.abs(tb)), 1e-12 * (tb - ta))
    small_all = 1e-10 * np.maximum(np.abs(fa), np.abs(fb))
    for _ in range(100):
        idx = np.nonzero(todo)[0]
        if not idx.size:
            break
        ai, bi, fai, fbi = a[idx], b[idx], fa[idx], fb[idx]
        with np.errstate(all="ignore"):
            c = bi - fbi * (bi - ai) / (fbi - fai)
        # a secant estimate on (or, by rounding, beyond) an end whose event value is already negligible: that end
        # is the root; on an end otherwise (the Illinois weights at work), or not finite: bisect
        small = small_all[idx]
        hit_a = (c <= ai) & (np.abs(ta_val[idx]) <= small)
        hit_b = (c >= bi) & (np.abs(tb_val[idx]) <= small)
        done_end = hit_a | hit_b
        if done_end.any():
            root[idx[done_end]] = np.where(hit_a, ai, bi)[done_end]
            todo[idx[done_end]] = False
            keep = ~done_end
            idx, ai, bi, fai, fbi, c = idx[keep], ai[keep], bi[keep], fai[keep], fbi[keep], c[keep]
            if not idx.size:
                break
        c = np.where(np.isfinite(c) & (c > ai) & (c < bi), c, 0.5 * (ai + bi))
        sub_args = tuple(x[idx] for x in args_rows)
        fc = np.asarray(ev.fun(c, dense(c, rows[idx]), *sub_args), dtype=float).reshape(-1)
        tol = tol_all[idx]
        conv = (fc == 0.0) | (np.abs(c - root[idx]) <= tol) | (bi - ai <= 2.0 * tol)
        root[idx] = c
        keep_a = np.sign(fc) == np.sign(fai)  # c replaces a (the root lies in [c, b])
        si = side[idx]
        # Illinois: halve the value at the end kept twice in a row
        fb[idx] = np.where(keep_a & (si == -1), 0.5 * fbi, fbi)
        fa[idx] = np.where(~keep_a & (si == 1), 0.5 * fai, fai)
        a[idx] = np.where(keep_a, c, ai)
        fa[idx] = np.where(keep_a, fc, fa[idx])
        ta_val[idx] = np.where(keep_a, fc, ta_val[idx])
        b[idx] = np.where(keep_a, bi, c)
        fb[idx] = np.where(keep_a, fb[idx], fc)
        tb_val[idx] = np.where(keep_a, tb_val[idx], fc)
        side[idx] = np.where(keep_a, -1, 1)
        todo[idx] = ~conv
    # never report a root outside the step
    return np.clip(root, ta, tb)


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
    """
    y0a = np.asarray(y0, dtype=float)
    if y0a.ndim < 1:
        raise ValueError("y0 must have shape batch_shape + (n,)")
    batch_shape = y0a.shape[:-1]
    n = y0a.shape[-1]
    B = int(np.prod(batch_shape)) if batch_shape else 1
    if B == 0 or n == 0:
        raise ValueError(f"y0 must hold at least one member with at least one state, got shape {y0a.shape}")
    Y0 = y0a.reshape(B, n)
    if len(t_span) != 2:
        raise ValueError(f"t_span must be a pair (t0, t1), got {t_span!r}")
    T0 = _as_member_array(t_span[0], B, "t_span[0]")
    T1 = _as_member_array(t_span[1], B, "t_span[1]")
    if not (np.all(np.isfinite(T0)) and np.all(np.isfinite(T1))):
        raise ValueError("t_span must be finite")
    if np.any(T1 < T0):
        raise ValueError("t_span must run forward (t1 >= t0) for every member")
    rtol_a = np.asarray(rtol, dtype=float)
    if rtol_a.shape not in ((), (n,)) or not (np.all(np.isfinite(rtol_a)) and np.all(rtol_a > 0.0)):
        raise ValueError(f"rtol must be finite and > 0, a scalar or of shape ({n},), got {rtol!r}")
    rtol = np.maximum(rtol_a, 100.0 * _EPS)  # SciPy's floor (without its warning)
    atol_a = np.asarray(atol, dtype=float)
    if atol_a.shape in ((*batch_shape, n), (B, n)) and atol_a.ndim >= 2:
        atol_a = atol_a.reshape(B, n)  # per member
    elif atol_a.shape not in ((), (n,)):
        raise ValueError(f"atol must be a scalar or of shape ({n},) or batch_shape + ({n},), got shape "
                         f"{atol_a.shape}")
    if np.any(~np.isfinite(atol_a)) or np.any(atol_a < 0.0):
        raise ValueError(f"atol must be finite and >= 0, got {atol!r}")
    per_member_atol = atol_a.ndim == 2
    if t_eval is None:
        te = np.linspace(float(T0.min()), float(T1.max()), 101)
    else:
        te = np.atleast_1d(np.asarray(t_eval, dtype=float))
        if te.ndim != 1 or (te.size > 1 and np.any(np.diff(te) <= 0.0)) or not np.all(np.isfinite(te)):
            raise ValueError("t_eval must be a finite, strictly increasing 1-D array")
    nt = te.size
    evs = list(events)
    P = []
    for i, a in enumerate(args):
        aa = np.asarray(a)
        if aa.shape[: len(batch_shape)] == batch_shape and batch_shape:
            aa = aa.reshape((B, *aa.shape[len(batch_shape):]))
        elif aa.ndim == 0 or aa.shape[0] != B:
            raise ValueError(f"args[{i}] must have a leading batch axis of size {B} (or shape {batch_shape}), "
                             f"got shape {aa.shape}")
        P.append(aa)
    params = tuple(P)

    # ---- outputs ----------------------------------------------------------------------------------
    Yout = np.full((B, n, nt), np.nan)
    status = np.zeros(B, dtype=int)
    message = np.empty(B, dtype=object)
    message[:] = "The solver successfully reached the end of the integration interval."
    event_name = np.empty(B, dtype=object)
    event_name[:] = None
    nfev = np.zeros(B, dtype=int)
    t_final = T0.copy()
    y_final = Y0.copy()
    last_step = np.full(B, np.nan)
    tev: list[list[list[float]]] = [[[] for _ in range(B)] for _ in evs]
    yev: list[list[list[np.ndarray]]] = [[[] for _ in range(B)] for _ in evs]

    def _finish(gidx: np.ndarray, st: int, msg: str | list[str], t_end: np.ndarray, y_end: np.ndarray) -> None:
        status[gidx] = st
        if isinstance(msg, str):
            message[gidx] = msg
        else:
            for k, g in enumerate(gidx):
                message[g] = msg[k]
        t_final[gidx] = t_end
        y_final[gidx] = y_end

    # samples at the start time
    first = np.searchsorted(te, T0, side="left")
    at0 = (first < nt) & (te[np.minimum(first, nt - 1)] == T0)
    Yout[np.nonzero(at0)[0], :, first[at0]] = Y0[at0]

    # members that start with a non-finite state or right-hand side fail at once; zero-length spans end at once
    finite0 = np.all(np.isfinite(Y0), axis=1)
    gidx = np.arange(B)
    with np.errstate(all="ignore"):
        F0 = np.full((B, n), np.nan)
        if np.any(finite0):
            F0[finite0] = np.asarray(fun(T0[finite0], Y0[finite0], *(p[finite0] for p in params)), dtype=float)
    nfev[finite0] += 1
    ok0 = finite0 & np.all(np.isfinite(F0), axis=1)
    for g in np.nonzero(~finite0)[0]:
        status[g], message[g] = -1, "the initial state is not finite"
    for g in np.nonzero(finite0 & ~ok0)[0]:
        status[g] = -1
        message[g] = (f"the right-hand side is not finite at the initial state ({time_name} = {T0[g]:.6g}): "
                      "check the model's parameters")
    live = ok0 & (T1 > T0)

    G0 = [np.empty(0) for _ in evs]
    if np.any(live) and evs:
        with np.errstate(all="ignore"):
            G0 = [np.asarray(ev.fun(T0[live], Y0[live], *(p[live] for p in params)), dtype=float).reshape(-1)
                  for ev in evs]

    # ---- active work arrays -----------------------------------------------------------------------
    gidx = np.nonzero(live)[0]
    t = T0[live].copy()
    t1 = T1[live].copy()
    y = Y0[live].copy()
    f = F0[live].copy()
    prm = tuple(p[live] for p in params)
    gval = [g.copy() for g in G0]
    rejected = np.zeros(gidx.size, dtype=bool)
    nattempt = np.zeros(gidx.size, dtype=int)
    atol_m = atol_a[live] if per_member_atol else atol_a

    # initial step (Hairer, Norsett, Wanner, II.4, as scipy.integrate._ivp.common.select_initial_step)
    if gidx.size:
        with np.errstate(all="ignore"):
            scale = atol_m + np.abs(y) * rtol
            d0 = _rms_rows(y / scale)
            d1 = _rms_rows(f / scale)
            h0 = np.where((d0 < 1e-5) | (d1 < 1e-5), 1e-6, 0.01 * d0 / d1)
            h0 = np.minimum(h0, t1 - t)
            f1 = np.asarray(fun(t + h0, y + h0[:, None] * f, *prm), dtype=float)
            nfev[gidx] += 1
            d2 = _rms_rows((f1 - f) / scale) / h0
            h1 = np.where((d1 <= 1e-15) & (d2 <= 1e-15), np.maximum(1e-6, h0 * 1e-3),
                          (0.01 / np.maximum(d1, d2)) ** (1.0 / (_ORDER_EST + 1)))
            h_abs = np.minimum.reduce([100.0 * h0, h1, t1 - t, np.full(t.size, float(max_step))])
        h_abs = np.where(np.isfinite(h_abs) & (h_abs > 0.0), h_abs, t1 - t)
        if first_step is not None:
            fs = _as_member_array(first_step, B, "first_step")[gidx]
            h_abs = np.where(np.isfinite(fs) & (fs > 0.0), np.minimum(fs, t1 - t), h_abs)

    K = np.empty((_N_STAGES + 4, 0, n))  # stages 0..11, f_new (12), dense-output stages 13..15
    K2 = K.reshape(_N_STAGES + 4, 0)  # the same memory, one row per stage: linear combinations are matrix products
    while gidx.size:
        m = gidx.size
        if K.shape[1] != m:
            K = np.empty((_N_STAGES + 4, m, n))
            K2 = K.reshape(_N_STAGES + 4, m * n)
        min_step = 10.0 * np.abs(np.nextafter(t, np.inf) - t)
        h_abs = np.clip(h_abs, min_step, max_step)
        h = np.minimum(h_abs, t1 - t)
        t_new = t + h
        # ---- one DOP853 step for every active member ------------------------------------------------
        with np.errstate(all="ignore"):
            K[0] = f
            hc = h[:, None]
            for s in range(1, _N_STAGES):
                dy = _comb(_A[s, :s], K2[:s]).reshape(m, n) * hc
                K[s] = fun(t + _C[s] * h, y + dy, *prm)
            y_new = y + _comb(_B, K2[:_N_STAGES]).reshape(m, n) * hc
            f_new = np.asarray(fun(t_new, y_new, *prm), dtype=float)
            K[_N_STAGES] = f_new
            scale = atol_m + np.maximum(np.abs(y), np.abs(y_new)) * rtol
            e5 = _comb(_E5, K2[: _N_STAGES + 1]).reshape(m, n) / scale
            e3 = _comb(_E3, K2[: _N_STAGES + 1]).reshape(m, n) / scale
            e5n = np.einsum("ij,ij->i", e5, e5)
            e3n = np.einsum("ij,ij->i", e3, e3)
            denom = e5n + 0.01 * e3n
            err = np.where((e5n == 0.0) & (e3n == 0.0), 0.0, h * e5n / np.sqrt(denom * n))
        nfev[gidx] += _N_STAGES
        nattempt += 1
        good = np.isfinite(err) & np.isfinite(y_new).all(axis=1) & np.isfinite(f_new).all(axis=1)
        acc = good & (err < 1.0)
        with np.errstate(all="ignore"):
            fac = np.where(err == 0.0, _MAX_FACTOR, np.minimum(_MAX_FACTOR, _SAFETY * err ** _ERR_EXP))
            fac = np.where(acc & rejected, np.minimum(1.0, fac), fac)
            fac_rej = np.where(good, np.maximum(_MIN_FACTOR, _SAFETY * err ** _ERR_EXP), _MIN_FACTOR)
        h_next = np.where(acc, h_abs * fac, h_abs * fac_rej)
        # members whose rejected step is already at the smallest size fail
        stuck = ~acc & (h_abs <= min_step)
        too_many = ~acc & (nattempt >= max_steps)
        done = np.zeros(m, dtype=bool)
        if np.any(stuck | too_many):
            for k in np.nonzero(stuck | too_many)[0]:
                if not good[k]:
                    msg = (f"the state or its derivative became non-finite near {time_name} = {t[k]:.6g}; "
                           "integration stopped")
                elif stuck[k]:
                    msg = "Required step size is less than spacing between numbers."
                else:
                    msg = f"more than max_steps={max_steps} step attempts"
                _finish(gidx[k: k + 1], -1, msg, t[k: k + 1], y[k: k + 1])
            done |= stuck | too_many

        ia = np.nonzero(acc)[0]
        if ia.size:
            ta, ya, ha = t[ia], y[ia], h[ia]
            tna, yna = t_new[ia], y_new[ia]
            # output samples and events need this step's dense output
            lo = np.searchsorted(te, ta, side="right")
            hi = np.searchsorted(te, tna, side="right")
            gnew: list[np.ndarray] = []
            if evs:
                with np.errstate(all="ignore"):
                    prm_a = tuple(p[ia] for p in prm)
                    gnew = [np.asarray(ev.fun(tna, yna, *prm_a), dtype=float).reshape(-1) for ev in evs]
            crossing = []
            for j, ev in enumerate(evs):
                crossing.append(crossed(gval[j][ia], gnew[j], ev.direction))
            need = hi > lo
            for hit in crossing:
                need = need | hit
            dense: _Dense | None = None
            nd = np.nonzero(need)[0]
            if nd.size:
                # the stages of the members that need the dense output (all of them, often: then K itself)
                Kd = K if _all_members(ia, nd, m) else np.ascontiguousarray(K[:, ia[nd]])  # a reshape must be a view
                md = nd.size
                Kd2 = Kd.reshape(_N_STAGES + 4, md * n)
                hd = ha[nd][:, None]
                prm_d = tuple(p[ia[nd]] for p in prm)
                with np.errstate(all="ignore"):
                    for s in range(_N_STAGES + 1, _N_STAGES + 4):
                        dy = _comb(_A_EXTRA[s - _N_STAGES - 1, :s], Kd2[:s]).reshape(md, n) * hd
                        Kd[s] = fun(ta[nd] + _C_EXTRA[s - _N_STAGES - 1] * ha[nd], ya[nd] + dy, *prm_d)
                nfev[gidx[ia[nd]]] += 3
                dly = yna[nd] - ya[nd]
                Fd = np.empty((7, nd.size, n))
                Fd[0] = dly
                Fd[1] = hd * Kd[0] - dly
                Fd[2] = 2.0 * dly - hd * (f_new[ia[nd]] + Kd[0])
                Fd[3:] = hd * _comb(_D, Kd2).reshape(4, md, n)
                dense = _Dense(ta[nd], ha[nd], ya[nd], Fd)
            # position of each accepted member in the dense arrays
            pos = np.full(ia.size, -1)
            pos[nd] = np.arange(nd.size)

            # events: earliest terminal root per member; non-terminal roots before it are recorded
            t_stop = tna.copy()
            stop_ev = np.full(ia.size, -1)
            roots: list[tuple[int, np.ndarray, np.ndarray]] = []
            for j, ev in enumerate(evs):
                kk = np.nonzero(crossing[j])[0]
                if not kk.size:
                    continue
                assert dense is not None
                rts = _locate(ev, dense, pos[kk], ta[kk], tna[kk], gval[j][ia[kk]],
                              tuple(p[ia[kk]] for p in prm))
                roots.append((j, kk, rts))
                if ev.terminal:
                    earlier = rts < t_stop[kk]
                    t_stop[kk[earlier]] = rts[earlier]
                    stop_ev[kk[earlier]] = j
            for j, kk, rts in roots:
                # roots up to the stopping time; at the stopping time itself only the terminal event that stops
                keep = (rts < t_stop[kk]) | ((rts == t_stop[kk]) & ((stop_ev[kk] == j) | (not evs[j].terminal)))
                if not np.any(keep):
                    continue
                assert dense is not None
                yv = dense(rts[keep], pos[kk[keep]])
                for k, rt, yk in zip(kk[keep], rts[keep], yv):
                    tev[j][gidx[ia[k]]].append(float(rt))
                    yev[j][gidx[ia[k]]].append(yk)

            # output samples in (t_old, t_stop]
            hi = np.searchsorted(te, t_stop, side="right")
            cnt = np.maximum(hi - lo, 0)
            tot = int(cnt.sum())
            if tot:
                assert dense is not None
                mm = np.nonzero(cnt)[0]  # members with samples in this step: grid indices lo .. hi - 1 each
                which, jj, ys = dense.on_grid(te, pos[mm], lo[mm], cnt[mm])
                Yout[gidx[ia[mm[which]]], :, jj] = ys

            # terminal events end their member at the root
            term = np.nonzero(stop_ev >= 0)[0]
            if term.size:
                assert dense is not None
                y_stop = dense(t_stop[term], pos[term])
                for k, y_end in zip(term, y_stop):
                    ev = evs[int(stop_ev[k])]
                    g = gidx[ia[k]]
                    msg = f"stopped by event {ev.name!r} at {time_name} = {t_stop[k]:.6g}" + (
                        f": {ev.message}" if ev.message else "")
                    _finish(np.array([g]), 1, msg, t_stop[k: k + 1], y_end[None, :])
                    event_name[g] = ev.name
                    done[ia[k]] = True

            # advance the accepted members
            t[ia] = tna
            y[ia] = yna
            f[ia] = f_new[ia]
            for j in range(len(evs)):
                gval[j][ia] = gnew[j]
            reached = np.nonzero(tna >= t1[ia])[0]
            reached = reached[stop_ev[reached] < 0]
            if reached.size:
                _finish(gidx[ia[reached]], 0, "The solver successfully reached the end of the integration "
                        "interval.", tna[reached], yna[reached])
                done[ia[reached]] = True
        rejected = np.where(acc, False, True)
        h_abs = h_next
        if np.any(done):
            last_step[gidx[done]] = h_abs[done]
            keep_ = ~done
            gidx, t, t1, y, f = gidx[keep_], t[keep_], t1[keep_], y[keep_], f[keep_]
            h_abs, rejected, nattempt = h_abs[keep_], rejected[keep_], nattempt[keep_]
            prm = tuple(p[keep_] for p in prm)
            gval = [g[keep_] for g in gval]
            if per_member_atol:
                atol_m = atol_m[keep_]

    # ---- assemble ---------------------------------------------------------------------------------
    t_events: dict[str, np.ndarray] = {}
    y_events: dict[str, np.ndarray] = {}
    none_t, none_y = np.empty(0), np.empty((0, n))  # shared by the members without this event (read-only)
    none_t.setflags(write=False)
    none_y.setflags(write=False)
    for j, ev in enumerate(evs):
        te_obj = np.empty(B, dtype=object)
        ye_obj = np.empty(B, dtype=object)
        te_obj.fill(none_t)
        ye_obj.fill(none_y)
        for q in (q for q in range(B) if tev[j][q]):
            te_obj[q] = np.asarray(tev[j][q], dtype=float)
            ye_obj[q] = np.asarray(yev[j][q], dtype=float).reshape(-1, n)
        t_events[ev.name] = te_obj.reshape(batch_shape)
        y_events[ev.name] = ye_obj.reshape(batch_shape)
    data: dict[str, np.ndarray] = {}
    if fields is not None and nt:
        with np.errstate(all="ignore"):
            for name, arr in dict(fields(te, Yout)).items():
                a = np.asarray(arr)
                data[name] = a.reshape(batch_shape + a.shape[1:])
    sol = Solution(
        time_name, te, Yout.reshape((*batch_shape, n, nt)), data, status.reshape(batch_shape),
        message.reshape(batch_shape), event_name.reshape(batch_shape), t_events, y_events, None,
        nfev.reshape(batch_shape), batch_shape=batch_shape, t_final=t_final.reshape(batch_shape),
        y_final=y_final.reshape((*batch_shape, n)),
    )
    sol.last_step = last_step.reshape(batch_shape)
    return sol
