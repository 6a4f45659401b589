"""DOP853 on one small system of Python floats: what :func:`rigidbody.core.ode.integrate` runs for
``engine='python'``.

SciPy's ``solve_ivp`` spends ~50 us of NumPy overhead per DOP853 step (~100 us with dense output) on any
system; for the 3- to 7-state systems of the analyses that is several times the cost of the right-hand side
itself. :func:`solve_small` runs the same method (:mod:`rigidbody.core.dop853`: Hairer's coefficients, SciPy's
error norm, step-size controller and initial-step heuristic; the 7th-order dense output; events located by
``brentq`` to 4 ulp) on lists of floats. The stages, the solution, the scaled error norms and the dense-output
coefficients of a step are generated as straight-line code for the system's size (:func:`stage_code`), so
that a step is float arithmetic and calls of the right-hand side.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from functools import cache
from typing import Any

import numpy as np
from scipy.optimize import brentq

from . import dop853 as rk
from .kernel import SCALAR

__all__ = ["DenseStep", "LazyDense", "StepRecord", "solve_small", "stage_code"]

_SUCCESS = "The solver successfully reached the end of the integration interval."


def _lin(terms: list[tuple[int, float]], comp: int) -> str:
    return " + ".join(f"{a!r} * k{j}[{comp}]" for j, a in terms) or "0.0"


def _nonzero(row: Any, upto: int) -> list[tuple[int, float]]:
    return [(j, float(row[j])) for j in range(upto) if row[j] != 0.0]


def _step_lines(n: int) -> list[str]:
    """Source of ``step(fun, t, y, k0, h, args, atol, rtol) -> (y_new, f_new, e5n, e3n, K)``."""
    ns = rk.N_STAGES
    lines = ["def step(fun, t, y, k0, h, args, atol, rtol):"]
    for s in range(1, ns):
        ys = ", ".join(f"y[{i}] + h * ({_lin(_nonzero(rk.A[s], s), i)})" for i in range(n))
        lines.append(f"    k{s} = fun(t + {float(rk.C[s])!r} * h, [{ys}], *args)")
    nzb = _nonzero(rk.B, ns)
    lines.append("    y_new = [" + ", ".join(f"float(y[{i}] + h * ({_lin(nzb, i)}))" for i in range(n)) + "]")
    lines.append(f"    k{ns} = fun(t + h, y_new, *args)")
    lines.append("    f_new = [" + ", ".join(f"float(k{ns}[{i}])" for i in range(n)) + "]")
    # the scaled error norms (dop853.error_norm takes them): scale = atol + rtol * max(|y_old|, |y_new|)
    for i in range(n):
        lines.append(f"    s{i} = atol[{i}] + max(abs(y[{i}]), abs(y_new[{i}])) * rtol[{i}]")
    for name, weights in (("e5n", rk.E5), ("e3n", rk.E3)):
        nz = _nonzero(weights, ns + 1)
        lines.append(f"    {name} = " + " + ".join(f"(({_lin(nz, i)}) / s{i}) ** 2" for i in range(n)))
    lines.append("    return y_new, f_new, e5n, e3n, (" + ", ".join(f"k{j}" for j in range(ns + 1)) + ")")
    return lines


def _dense_lines(n: int) -> list[str]:
    """Source of ``dense(fun, t, y, y_new, h, K, args) -> F`` (the 7 coefficient rows of the interpolant) and
    ``interp(F, y_old, x)`` (its value at ``x`` in [0, 1], as scipy's Dop853DenseOutput: factors x, 1 - x)."""
    ns = rk.N_STAGES
    lines = ["def dense(fun, t, y, y_new, h, K, args):",
             "    (" + ", ".join(f"k{j}" for j in range(ns + 1)) + ",) = K"]
    for e in range(3):
        s = ns + 1 + e
        ys = ", ".join(f"y[{i}] + h * ({_lin(_nonzero(rk.A_EXTRA[e], s), i)})" for i in range(n))
        lines.append(f"    k{s} = fun(t + {float(rk.C_EXTRA[e])!r} * h, [{ys}], *args)")
    lines.append("    dy = [b - a for a, b in zip(y, y_new)]")
    lines.append(f"    F = [dy, [h * k0[i] - dy[i] for i in range({n})], "
                 f"[2.0 * dy[i] - h * (k{ns}[i] + k0[i]) for i in range({n})]]")
    for r in range(rk.D.shape[0]):
        nz = _nonzero(rk.D[r], rk.D.shape[1])
        lines.append("    F.append([" + ", ".join(f"h * ({_lin(nz, i)})" for i in range(n)) + "])")
    lines.append("    return F")
    lines.append("def interp(F, y_old, x):")
    lines.append("    x1 = 1.0 - x")
    for i in range(n):
        expr = f"F[6][{i}]"
        for r, fac in zip(range(5, -1, -1), ["x", "x1", "x", "x1", "x", "x1"]):
            expr = f"({expr}) * {fac} + F[{r}][{i}]"
        lines.append(f"    v{i} = y_old[{i}] + ({expr}) * x")
    lines.append("    return [" + ", ".join(f"v{i}" for i in range(n)) + "]")
    return lines


@cache
def stage_code(n: int) -> tuple[Callable[..., Any], Callable[..., Any], Callable[..., Any]]:
    """One DOP853 step, its dense-output coefficients and the interpolant for ``n`` states, written out.

    Parameters
    ----------
    n : int
        Number of states.

    Returns
    -------
    step, dense, interp : callable
        ``step(fun, t, y, k0, h, args, atol, rtol) -> (y_new, f_new, e5n, e3n, K)`` (the stages with the
        tableau's zeros skipped; ``e5n``, ``e3n`` the squared scaled norms of the error estimates),
        ``dense(fun, t, y, y_new, h, K, args) -> F`` and ``interp(F, y_old, x) -> y``.
    """
    code: dict[str, Any] = {}
    exec("\n".join(_step_lines(n) + _dense_lines(n)), code)  # generated from the tableau of dop853, nothing else
    return code["step"], code["dense"], code["interp"]


class DenseStep:
    """The dense output of one accepted step: ``y(t) = y_old + sum`` of the 7 coefficient rows (Hairer's
    DOP853 interpolant, evaluated as scipy's Dop853DenseOutput does)."""

    __slots__ = ("F", "h", "interp", "t_old", "y_old")

    def __init__(self, t_old: float, h: float, y_old: list[float], F: list[list[float]],
                 interp: Callable[..., list[float]]) -> None:
        self.t_old, self.h, self.y_old, self.F, self.interp = t_old, h, y_old, F, interp

    def __call__(self, t: float) -> list[float]:
        return self.interp(self.F, self.y_old, (t - self.t_old) / self.h)


class StepRecord:
    """One accepted step and, from the first time it is asked for, its dense output (:meth:`dense`: three
    more evaluations of the right-hand side)."""

    __slots__ = ("K", "h", "run", "t_old", "value", "y_new", "y_old")

    def __init__(self, run: tuple[Callable[..., Any], tuple, Callable[..., Any], Callable[..., Any]], t_old: float,
                 h: float, y_old: list[float], y_new: list[float], K: tuple) -> None:
        self.run = run  # (fun, args, dense coefficients, interpolant) of the run
        self.t_old, self.h, self.y_old, self.y_new, self.K = t_old, h, y_old, y_new, K
        self.value: DenseStep | None = None

    def dense(self) -> DenseStep:
        if self.value is None:
            fun, args, coeffs, interp = self.run
            F = coeffs(fun, self.t_old, self.y_old, self.y_new, self.h, self.K, args)
            self.value = DenseStep(self.t_old, self.h, self.y_old, F, interp)
        return self.value


class LazyDense:
    """Dense output of a run of ``engine='python'`` over its whole span, like SciPy's ``OdeSolution``: each step
    keeps its stages, and the three extra stages of its interpolant are computed the first time a time in
    that step is asked for (so a run whose dense output is never used costs nothing more)."""

    def __init__(self, steps: list[StepRecord], y0: list[float]) -> None:
        self.steps = steps
        self.starts = np.array([st.t_old for st in steps], dtype=float)
        self.y0 = list(y0)

    def __call__(self, t: Any) -> np.ndarray:
        ta = np.asarray(t, dtype=float)
        tt = np.atleast_1d(ta).ravel()
        out = np.empty((len(self.y0), tt.size))
        if not self.steps:
            out[:] = np.asarray(self.y0, dtype=float)[:, None]
        else:
            idx = np.clip(np.searchsorted(self.starts, tt, side="right") - 1, 0, len(self.steps) - 1)
            for k, (i, tv) in enumerate(zip(idx.tolist(), tt.tolist())):
                out[:, k] = self.steps[i].dense()(tv)
        return out[:, 0] if ta.ndim == 0 else out


def _rms(v: list[float]) -> float:
    return math.sqrt(sum(x * x for x in v) / len(v))


def _first_step(fun: Callable[..., Any], t0: float, span: float, y: list[float], f: list[float], rtol: list[float],
                atol: list[float], args: tuple, max_step: float, first_step: float | None) -> tuple[float, int]:
    """The initial step size (given, or dop853's heuristic) and the evaluations it took."""
    if span == 0.0:
        return 0.0, 0
    if first_step is not None:
        return min(first_step, span, max_step), 0
    scale = [a + abs(v) * rt for a, v, rt in zip(atol, y, rtol)]
    d0 = _rms([v / s for v, s in zip(y, scale)])
    d1 = _rms([v / s for v, s in zip(f, scale)])
    h0 = rk.trial_step(SCALAR, d0, d1, span)
    f1 = fun(t0 + h0, [v + h0 * d for v, d in zip(y, f)], *args)
    d2 = _rms([(a - b) / s for a, b, s in zip(f1, f, scale)]) / h0
    return rk.initial_step(SCALAR, h0, d1, d2, span, max_step), 1


class _Samples:
    """The output of a run: every step's end (no ``t_eval``), or the requested times from the dense output."""

    def __init__(self, t_eval: np.ndarray | None, t0: float, y0: list[float]) -> None:
        self.ts: list[float] = []
        self.ys: list[list[float]] = []
        self.grid: list[float] = [] if t_eval is None else t_eval.tolist()
        self.every_step = t_eval is None
        self.next = 0
        if self.every_step:
            self.ts.append(t0)
            self.ys.append(y0)
        while self.next < len(self.grid) and self.grid[self.next] <= t0:
            if self.grid[self.next] == t0:
                self.ts.append(t0)
                self.ys.append(list(y0))
            self.next += 1

    def add(self, t: float, y: list[float], dense: Callable[[], DenseStep]) -> None:
        """Samples up to ``t``, the end of a step (``dense()`` gives the step's dense output)."""
        if self.every_step:
            self.ts.append(t)
            self.ys.append(y)
            return
        j, grid = self.next, self.grid
        while j < len(grid) and grid[j] <= t:
            j += 1
        if j > self.next:
            sol = dense()
            for tt in grid[self.next: j]:
                self.ts.append(tt)
                self.ys.append(sol(tt))
            self.next = j


def _event_roots(events: list[tuple[Callable[..., float], bool, float]], g: list[float], g_new: list[float],
                 t_old: float, t: float, dense: Callable[[], DenseStep], args: tuple) -> list[float] | None:
    """Per event, its root in the step ``[t_old, t]`` by ``brentq`` on the step's dense output (SciPy's
    tolerances), NaN where the event did not cross; None if none did."""
    active = [rk.crossed(a, b, d) for (_, _, d), a, b in zip(events, g, g_new)]
    if not any(active):
        return None
    sol = dense()
    return [brentq(lambda tt, e=e: events[e][0](tt, sol(tt), *args), t_old, t, xtol=rk.ROOT_TOL, rtol=rk.ROOT_TOL)
            if hit else math.nan for e, hit in enumerate(active)]


def _attempt(step: Callable[..., Any], fun: Callable[..., Any], t: float, t1: float, y: list[float], f: list[float],
             h_abs: float, tol: tuple[list[float], list[float], float], args: tuple) -> tuple[Any, float, int]:
    """Steps from ``t`` until one is accepted: ``((t_new, h, y_new, f_new, K) or None if the step size underflows,
    the next step size, evaluations)``; after a rejection the accepted step does not grow the size."""
    rtol, atol, max_step = tol
    n = len(y)
    min_step = rk.MIN_STEP_SPACINGS * abs(math.nextafter(t, math.inf) - t)
    h_abs = min(max(h_abs, min_step), max_step)
    nfev = 0
    rejected = False
    while h_abs >= min_step:
        t_new = t + h_abs
        if t_new > t1:
            t_new = t1
        h = t_new - t
        y_new, f_new, e5n, e3n, K = step(fun, t, y, f, h, args, atol, rtol)
        nfev += rk.N_STAGES
        err = rk.error_norm(SCALAR, h, e5n, e3n, n)
        h_abs *= rk.step_factor(SCALAR, err, rejected)
        if err < 1.0:
            return (t_new, h, y_new, f_new, K), h_abs, nfev
        rejected = True
    return None, h_abs, nfev


def solve_small(
    fun: Callable[..., Any], t0: float, t1: float, y0: list[float], t_eval: np.ndarray | None, rtol: list[float],
    atol: list[float], events: list[tuple[Callable[..., float], bool, float]], args: tuple, max_step: float,
    first_step: float | None = None, dense_output: bool = False,
) -> dict[str, Any]:
    """DOP853 on one system of floats, forward in time.

    Parameters
    ----------
    fun : callable
        ``fun(t, y, *args)``: ``y`` a list of floats, any sequence of floats returned.
    t0, t1 : float
        The time span, ``t1 >= t0``.
    y0 : list of float
        The initial state.
    t_eval : numpy.ndarray or None
        Output times (from the dense output), or None for every step's end.
    rtol, atol : list of float
        Per-component tolerances (``rtol`` floored at ``dop853.RTOL_FLOOR``).
    events : list of (callable, bool, float)
        ``(g(t, y, *args), terminal, direction)`` per event.
    args : tuple
        Extra arguments of ``fun`` and the events.
    max_step : float
        Largest step size.
    first_step : float, optional
        Initial step size (default: the heuristic of :mod:`rigidbody.core.dop853`).
    dense_output : bool
        Whether to return the dense output over the whole run.

    Returns
    -------
    dict
        What :func:`rigidbody.core.ode.integrate` reads from a ``solve_ivp`` result: ``t``, ``y``, ``t_events``,
        ``y_events``, ``status``, ``message``, ``nfev``, ``sol``, and ``last_step`` (the step size the
        integrator would take next).
    """
    n = len(y0)
    step, dense_coeffs, interp = stage_code(n)
    rtol = [max(v, rk.RTOL_FLOOR) for v in rtol]
    tol = (rtol, atol, max_step)
    t, y = t0, list(y0)
    f = [float(v) for v in fun(t0, y, *args)]
    h_abs, nfev = _first_step(fun, t0, t1 - t0, y, f, rtol, atol, args, max_step, first_step)
    nfev += 1
    g = [ev(t, y, *args) for ev, _, _ in events]
    terminal = [term for _, term, _ in events]
    t_events: list[list[float]] = [[] for _ in events]
    y_events: list[list[list[float]]] = [[] for _ in events]
    out = _Samples(t_eval, t0, y)
    status: int | None = None if t1 > t0 else 0
    message = _SUCCESS
    steps: list[StepRecord] = []  # the accepted steps, for the dense output
    run = (fun, args, dense_coeffs, interp)
    while status is None:
        accepted, h_abs, used = _attempt(step, fun, t, t1, y, f, h_abs, tol, args)
        nfev += used
        if accepted is None:
            status, message = -1, "Required step size is less than spacing between numbers."
            break
        t_new, h, y_new, f_new, K = accepted
        record = StepRecord(run, t, h, y, y_new, K)
        t_old, t, y, f = t, t_new, y_new, f_new
        if dense_output:
            steps.append(record)
        if events:
            g_new = [ev(t, y, *args) for ev, _, _ in events]
            roots = _event_roots(events, g, g_new, t_old, t, record.dense, args)
            if roots is not None:
                t_stop, stop, counted = rk.settle_events(SCALAR, roots, terminal, t)
                for e, keep in enumerate(counted):
                    if keep:
                        t_events[e].append(roots[e])
                        y_events[e].append(record.dense()(roots[e]))
                if stop >= 0:
                    status, t, y = 1, t_stop, record.dense()(t_stop)
            g = g_new
        out.add(t, y, record.dense)
        if record.value is not None:
            nfev += 3  # the step's dense output was needed
        if status is None and t >= t1:
            status = 0
    return {
        "sol": LazyDense(steps, list(y0)) if dense_output else None,
        "t": np.array(out.ts, dtype=float),
        "y": np.array(out.ys, dtype=float).reshape(-1, n).T,
        "t_events": [np.array(v, dtype=float) for v in t_events],
        "y_events": [np.array(v, dtype=float).reshape(-1, n) for v in y_events],
        "status": status, "message": message, "nfev": nfev, "last_step": h_abs,
    }
