"""One way to integrate and return a trajectory, shared by all modules.

:func:`integrate` is a thin layer over :func:`scipy.integrate.solve_ivp` that keeps its conventions
(``t_span``, ``t_eval``, ``rtol``, ``atol``, ``method``, ``dense_output``, events) and adds

* named terminal events (:class:`Event`) whose name and message end up in the result, so a singular state
  ends an integration with a clear status instead of silent NaNs;
* a built-in terminal check on non-finite states (status -1 and a message naming the time);
* named output arrays (``fields``) computed from the states, returned as attributes of a
  :class:`Solution` (``sol.Gz``, ``sol.theta``, ...), with the time under the name the module uses
  (``sol.t`` or ``sol.tau``).

Status codes are SciPy's: ``-1`` failure (including a non-finite state), ``0`` the end of ``t_span``
was reached, ``1`` a terminal event ended the run (``sol.event`` names it).

``integrate(..., engine='python')`` runs SciPy's DOP853 itself on lists of floats (the same coefficients,
error norm, step-size control, dense output and event location), for the small systems of the analyses where
``solve_ivp``'s per-step NumPy overhead costs more than the right-hand side; it also accepts a per-component
``rtol``. A :class:`Solution` describes one run or a batch of runs (:mod:`rigidbody.core.batch`).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from functools import cache
from types import SimpleNamespace
from typing import Any

import numpy as np
from scipy.integrate import DOP853, solve_ivp
from scipy.optimize import brentq

from . import _display

__all__ = ["Event", "Solution", "crossed", "integrate"]


@dataclass(frozen=True)
class Event:
    """A named event for :func:`integrate`.

    Parameters
    ----------
    fun : callable
        ``fun(t, y) -> float``; the event is a zero crossing of it. For
        :func:`rigidbody.core.batch.integrate_batch` it is vectorised: ``t`` of shape ``(m,)``, ``y`` of
        shape ``(m, n)``, the result of shape ``(m,)``.
    name : str
        Short identifier (``'separatrix'``, ``'u1_eq_u2'``...): a key of ``Solution.t_events``.
    terminal : bool
        Whether the event ends the integration.
    direction : float
        As in ``solve_ivp``: 0 any crossing, +1 upward, -1 downward.
    message : str
        Human-readable explanation written to ``Solution.message`` when the event ends the run.
    """

    fun: Callable[..., Any]
    name: str
    terminal: bool = True
    direction: float = 0.0
    message: str = ""


def crossed(g_old: Any, g_new: Any, direction: float) -> Any:
    """Whether an event function crossed zero over a step, in the sense of ``direction``.

    A root at the end of a step (``g_new == 0``) belongs to that step; a step that starts on a root
    (``g_old == 0``) does not count it again, so one passage through zero is one event even when the
    event function is exactly zero at a step boundary (a motion held on a separatrix). Works on floats
    and elementwise on arrays (the batch integrator).

    Parameters
    ----------
    g_old, g_new : float or ndarray
        The event function at the start and at the end of the step.
    direction : float
        As in ``solve_ivp``: 0 any crossing, +1 upward, -1 downward.

    Returns
    -------
    bool or ndarray of bool

    Examples
    --------
    >>> crossed(-1.0, 0.0, 0), crossed(0.0, 1.0, 0), crossed(1.0, -1.0, +1)
    (True, False, False)
    """
    up = (g_old < 0) & (g_new >= 0)
    down = (g_old > 0) & (g_new <= 0)
    if direction > 0:
        return up
    if direction < 0:
        return down
    return up | down


class Solution:
    """Result of an integration: named arrays plus SciPy's status, for one run or a batch of runs.

    A single run (``batch_shape == ()``) has the time array of shape ``(n_t,)``, scalar fields of shape
    ``(n_t,)``, vector fields of shape ``(k, n_t)``, ``y`` of shape ``(n_state, n_t)`` and a scalar
    ``status``, ``message`` and ``event``. A batch run (:func:`rigidbody.core.batch.integrate_batch` and the
    batch calls of the analyses) has a leading ``batch_shape`` on every field and on ``y``, the common output
    grid as ``time``, per-member ``status`` (int array), ``message`` and ``event`` (object arrays),
    ``success`` (bool array) and NaN in a member's samples after its end; ``sol[i]`` (or
    :meth:`member`) is the single-run view of member ``i``.

    Attributes
    ----------
    time_name : str
        ``'t'`` or ``'tau'``; the time array is available under that name (and as ``time``).
    batch_shape : tuple of int
        ``()`` for a single run, the shape of the batch otherwise.
    y : numpy.ndarray
        Raw state, shape ``batch_shape + (n_state, n_t)``.
    fields : tuple of str
        Names of the derived arrays, each an attribute.
    status : int or numpy.ndarray
        -1 failure, 0 end of the span reached, 1 a terminal event (per member for a batch).
    message : str or numpy.ndarray
    success : bool or numpy.ndarray
        ``status >= 0``.
    event : str or None, or numpy.ndarray
        Name of the terminal event that ended the run (per member for a batch).
    t_events : dict
        Event name -> times at which it occurred (for a batch: an object array of per-member arrays).
    y_events : dict
        Event name -> states at those times (likewise).
    sol : scipy.integrate.OdeSolution or None
        Dense output of the raw state when requested (single runs only).
    nfev : int or numpy.ndarray
        Number of right-hand-side evaluations (per member for a batch).
    t_final, y_final : float and numpy.ndarray, or arrays
        The time at which the run ended (the end of the span, a terminal event, a failure) and the raw state
        there; per member for a batch. None where the producer does not record them.
    last_step : float or None
        The step size the integrator would have taken next (``engine='python'`` runs), to continue a run.
    """

    def __init__(
        self,
        time_name: str,
        time: np.ndarray,
        y: np.ndarray,
        data: Mapping[str, np.ndarray],
        status: Any,
        message: Any,
        event: Any,
        t_events: dict[str, np.ndarray],
        y_events: dict[str, np.ndarray],
        sol: Any,
        nfev: Any,
        *,
        batch_shape: tuple[int, ...] = (),
        t_final: Any = None,
        y_final: Any = None,
    ) -> None:
        self.time_name = time_name
        self.time = time
        self.y = y
        self._data = dict(data)
        self.fields = tuple(self._data)
        self.batch_shape = tuple(int(b) for b in batch_shape)
        self.status = status
        self.message = message
        self.success = status >= 0
        self.event = event
        self.t_events = t_events
        self.y_events = y_events
        self.sol = sol
        self.nfev = nfev
        self.t_final = t_final
        self.y_final = y_final
        self.last_step: Any = None

    def __getattr__(self, name: str) -> Any:
        if name == self.__dict__.get("time_name"):
            return self.__dict__["time"]
        data = self.__dict__.get("_data", {})
        if name in data:
            return data[name]
        raise AttributeError(f"Solution has no field {name!r}; fields: {self.__dict__.get('fields')}")

    def __getitem__(self, key: Any) -> Any:
        if isinstance(key, str):
            return getattr(self, key)
        return self.member(key)

    def member(self, index: Any) -> Solution:
        """The single-run :class:`Solution` of one member of a batch.

        Parameters
        ----------
        index : int or tuple of int
            Position in ``batch_shape`` (a flat int is accepted for a 1-D batch; negative indices count
            from the end).

        Returns
        -------
        Solution
            Fields, ``y``, status, message, event and event records of that member, with the samples where
            it has no value (before its start, after its end) left out.

        Raises
        ------
        TypeError
            For a single run (it has no members) or a non-integer index.
        IndexError
            For an index outside ``batch_shape``.
        """
        if not self.batch_shape:
            raise TypeError("a single run has no members; index fields by name (sol['Gz'])")
        idx = index if isinstance(index, tuple) else (index,)
        if len(idx) != len(self.batch_shape) or not all(
            isinstance(i, (int, np.integer)) and not isinstance(i, bool) for i in idx
        ):
            raise TypeError(f"a member index is a tuple of {len(self.batch_shape)} int(s) for batch_shape "
                            f"{self.batch_shape}, got {index!r}")
        for i, nb in zip(idx, self.batch_shape):
            if not -nb <= i < nb:
                raise IndexError(f"member index {index!r} is out of range for batch_shape {self.batch_shape}")
        y = self.y[idx]
        keep = np.all(np.isfinite(y), axis=0) if y.ndim > 1 else np.isfinite(y)
        data = {}
        for name, arr in self._data.items():
            a = np.asarray(arr)[idx]
            data[name] = a[..., keep]
        t_events = {k: np.asarray(v[idx], dtype=float) for k, v in self.t_events.items()}
        y_events = {k: np.asarray(v[idx], dtype=float) for k, v in self.y_events.items()}
        nfev = self.nfev[idx] if np.ndim(self.nfev) else self.nfev
        t_final = None if self.t_final is None else float(np.asarray(self.t_final)[idx])
        y_final = None if self.y_final is None else np.asarray(self.y_final)[idx]
        return Solution(self.time_name, self.time[keep], y[..., keep], data, int(self.status[idx]),
                        str(self.message[idx]), self.event[idx], t_events, y_events, None, int(nfev),
                        t_final=t_final, y_final=y_final)

    def __bool__(self) -> bool:
        return True

    def __len__(self) -> int:
        if not self.batch_shape:
            raise TypeError("a single run has no members (len() is defined for batch solutions)")
        return self.batch_shape[0]

    def __dir__(self) -> list[str]:
        return sorted(set(super().__dir__()) | set(self._data) | {self.time_name})

    def _repr_html_(self) -> str:
        return _display.solution_html(self)

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """Draw the module's standard figure (:func:`rigidbody.plotting.plot_solution`); returns the Axes."""
        return _display.plot_solution(self, ax, **kwargs)
    def to_xarray(self, batch_dims: Any = None) -> Any:
        """This result as an ``xarray.Dataset``: time as a dimension, batch axes kept (needs xarray).

        Parameters
        ----------
        batch_dims : sequence of str or mapping of str to array_like, optional
            Names (and coordinates) of the batch dimensions; default ``batch_0, batch_1, ...``.

        Returns
        -------
        xarray.Dataset
            One variable per field (dimensions: the batch's, ``component`` for vector fields, then the
            time ``t`` or ``tau`` with the times as coordinate), ``status`` and ``message`` per member.
        """
        from ._xarray import solution_to_xarray

        return solution_to_xarray(self, batch_dims)

    def __repr__(self) -> str:
        n = self.time.size
        span = f"[{self.time[0]:.6g}, {self.time[-1]:.6g}]" if n else "[]"
        if self.batch_shape:
            st = np.asarray(self.status)
            return (
                f"Solution({self.time_name}={span}, n={n}, batch_shape={self.batch_shape}, "
                f"fields={list(self.fields)}, status: {int(np.sum(st == 0))} reached the end, "
                f"{int(np.sum(st == 1))} ended by an event, {int(np.sum(st < 0))} failed)"
            )
        return (
            f"Solution({self.time_name}={span}, n={n}, fields={list(self.fields)}, "
            f"status={self.status}, message={self.message!r})"
        )


# ==================================================================================================
# DOP853 for one small system in plain Python floats
# ==================================================================================================
# SciPy's solve_ivp spends ~50 us of NumPy overhead per DOP853 step (~100 us with dense output) on any
# system; for the 3- to 7-state systems of the analyses that is several times the cost of the right-hand
# side itself. engine='python' runs the same method (Hairer's coefficients as scipy.integrate.DOP853 holds
# them, the same error norm, step-size controller, initial-step heuristic, 7th-order dense output and event
# location by brentq to 4 ulp) on lists of floats, with each stage written out for the system's size.
_SAFETY, _MIN_FACTOR, _MAX_FACTOR = 0.9, 0.2, 10.0
_ERR_EXP = -1.0 / (DOP853.error_estimator_order + 1)
_EPS = float(np.finfo(float).eps)


def _lin(terms: list[tuple[int, float]], comp: int) -> str:
    return " + ".join(f"{a!r} * k{j}[{comp}]" for j, a in terms) or "0.0"


@cache
def _dop853_code(n: int) -> tuple[Callable[..., Any], Callable[..., Any], Callable[..., Any]]:
    """One DOP853 step and its dense-output coefficients for ``n`` states, the stages written out (the
    Butcher tableau's zeros skipped) so that a step is straight-line float arithmetic."""
    A, C = np.asarray(DOP853.A), np.asarray(DOP853.C)
    ns = DOP853.n_stages
    lines = ["def step(fun, t, y, k0, h, args):"]
    for s in range(1, ns):
        nz = [(j, float(A[s, j])) for j in range(s) if A[s, j] != 0.0]
        ys = ", ".join(f"y[{i}] + h * ({_lin(nz, i)})" for i in range(n))
        lines.append(f"    k{s} = fun(t + {float(C[s])!r} * h, [{ys}], *args)")
    nzb = [(j, float(DOP853.B[j])) for j in range(ns) if DOP853.B[j] != 0.0]
    lines.append("    y_new = [" + ", ".join(f"y[{i}] + h * ({_lin(nzb, i)})" for i in range(n)) + "]")
    lines.append(f"    k{ns} = fun(t + h, y_new, *args)")
    nz5 = [(j, float(DOP853.E5[j])) for j in range(ns + 1) if DOP853.E5[j] != 0.0]
    nz3 = [(j, float(DOP853.E3[j])) for j in range(ns + 1) if DOP853.E3[j] != 0.0]
    lines.append("    e5 = [" + ", ".join(_lin(nz5, i) for i in range(n)) + "]")
    lines.append("    e3 = [" + ", ".join(_lin(nz3, i) for i in range(n)) + "]")
    lines.append("    return y_new, k12, e5, e3, (" + ", ".join(f"k{j}" for j in range(ns + 1)) + ")")
    Ax, Cx, D = np.asarray(DOP853.A_EXTRA), np.asarray(DOP853.C_EXTRA), np.asarray(DOP853.D)
    lines.append("def dense(fun, t, y, y_new, h, K, args):")
    lines.append("    (" + ", ".join(f"k{j}" for j in range(ns + 1)) + ",) = K")
    for e in range(3):
        s = ns + 1 + e
        nz = [(j, float(Ax[e, j])) for j in range(s) if Ax[e, j] != 0.0]
        ys = ", ".join(f"y[{i}] + h * ({_lin(nz, i)})" for i in range(n))
        lines.append(f"    k{s} = fun(t + {float(Cx[e])!r} * h, [{ys}], *args)")
    lines.append("    dy = [b - a for a, b in zip(y, y_new)]")
    lines.append(f"    F = [dy, [h * k0[i] - dy[i] for i in range({n})], "
                 f"[2.0 * dy[i] - h * (k{ns}[i] + k0[i]) for i in range({n})]]")
    for r in range(D.shape[0]):
        nz = [(j, float(D[r, j])) for j in range(D.shape[1]) if D[r, j] != 0.0]
        lines.append("    F.append([" + ", ".join(f"h * ({_lin(nz, i)})" for i in range(n)) + "])")
    lines.append("    return F")
    # evaluation of the interpolant at x in [0, 1] (scipy's Dop853DenseOutput: alternate factors x, 1 - x)
    lines.append("def interp(F, y_old, x):")
    lines.append("    x1 = 1.0 - x")
    for i in range(n):
        expr = f"F[6][{i}]"
        for r, fac in zip(range(5, -1, -1), ["x", "x1", "x", "x1", "x", "x1"]):
            expr = f"({expr}) * {fac} + F[{r}][{i}]"
        lines.append(f"    v{i} = y_old[{i}] + ({expr}) * x")
    lines.append("    return [" + ", ".join(f"v{i}" for i in range(n)) + "]")
    code: dict[str, Any] = {}
    exec("\n".join(lines), code)  # generated from the coefficient tables above, nothing else
    return code["step"], code["dense"], code["interp"]


class _DenseStep:
    """The dense output of one accepted step: ``y(t) = y_old + sum`` of the 7 coefficient rows (Hairer's
    DOP853 interpolant, evaluated as scipy's Dop853DenseOutput does)."""

    __slots__ = ("F", "h", "interp", "t_old", "y_old")

    def __init__(self, t_old: float, h: float, y_old: list[float], F: list[list[float]],
                 interp: Callable[..., list[float]]) -> None:
        self.t_old, self.h, self.y_old, self.F, self.interp = t_old, h, y_old, F, interp

    def __call__(self, t: float) -> list[float]:
        return self.interp(self.F, self.y_old, (t - self.t_old) / self.h)


class _LazyDense:
    """Dense output of a run of ``engine='python'`` over its whole span, like SciPy's ``OdeSolution``: each step
    keeps its stages, and the three extra stages of its interpolant are computed the first time a time in
    that step is asked for (so a run whose dense output is never used costs nothing more)."""

    def __init__(self, fun: Callable[..., Any], args: tuple, coeffs: Callable[..., Any], interp: Callable[..., Any],
                 steps: list[list[Any]], y0: list[float]) -> None:
        self.fun, self.args, self.coeffs, self.interp = fun, args, coeffs, interp
        self.steps = steps  # [t_old, h, y_old, y_new, K, _DenseStep or None] per accepted step
        self.starts = np.array([st[0] for st in steps], dtype=float)
        self.y0 = list(y0)

    def _step(self, i: int) -> _DenseStep:
        st = self.steps[i]
        if st[5] is None:
            t_old, h, y_old, y_new, K = st[:5]
            st[5] = _DenseStep(t_old, h, y_old, self.coeffs(self.fun, t_old, y_old, y_new, h, K, self.args),
                               self.interp)
        return st[5]

    def __call__(self, t: Any) -> np.ndarray:
        ta = np.asarray(t, dtype=float)
        tt = np.atleast_1d(ta).ravel()
        out = np.empty((len(self.y0), tt.size))
        if not self.steps:
            out[:] = np.asarray(self.y0, dtype=float)[:, None]
        else:
            idx = np.clip(np.searchsorted(self.starts, tt, side="right") - 1, 0, len(self.steps) - 1)
            for k, (i, tv) in enumerate(zip(idx.tolist(), tt.tolist())):
                out[:, k] = self._step(i)(tv)
        return out[:, 0] if ta.ndim == 0 else out


def _rms(v: list[float]) -> float:
    return math.sqrt(sum(x * x for x in v) / len(v))


def _solve_small(
    fun: Callable[..., Any], t0: float, t1: float, y0: list[float], t_eval: np.ndarray | None, rtol: list[float],
    atol: list[float], events: list[tuple[Callable[..., float], bool, float]], args: tuple, max_step: float,
    first_step: float | None = None, dense_output: bool = False,
) -> dict[str, Any]:
    """DOP853 on one system of floats; returns what :func:`integrate` reads from a solve_ivp result."""
    n = len(y0)
    step, dense_coeffs, interp = _dop853_code(n)
    rtol = [max(v, 100.0 * _EPS) for v in rtol]
    y = list(y0)
    f = [float(v) for v in fun(t0, y, *args)]
    nfev = 1
    t = t0
    # initial step (Hairer, Norsett, Wanner II.4; scipy.integrate._ivp.common.select_initial_step)
    span = t1 - t0
    if span == 0.0:
        h_abs = 0.0
    elif first_step is not None:
        h_abs = min(first_step, span, max_step)
    else:
        scale = [a + abs(v) * rt for a, v, rt in zip(atol, y, rtol)]
        d0 = _rms([v / s for v, s in zip(y, scale)])
        d1 = _rms([v / s for v, s in zip(f, scale)])
        h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
        h0 = min(h0, span)
        f1 = fun(t0 + h0, [v + h0 * d for v, d in zip(y, f)], *args)
        nfev += 1
        d2 = _rms([(a - b) / s for a, b, s in zip(f1, f, scale)]) / h0
        if d1 <= 1e-15 and d2 <= 1e-15:
            h1 = max(1e-6, h0 * 1e-3)
        else:
            h1 = (0.01 / max(d1, d2)) ** (1.0 / (DOP853.error_estimator_order + 1))
        h_abs = min(100.0 * h0, h1, span, max_step)
        if not (h_abs > 0.0):  # a NaN from the heuristic: start with the span and let the control shrink it
            h_abs = span
    g = [ev(t, y, *args) for ev, _, _ in events]
    t_events: list[list[float]] = [[] for _ in events]
    y_events: list[list[list[float]]] = [[] for _ in events]
    ts: list[float] = []
    ys: list[list[float]] = []
    if t_eval is None:
        ts.append(t)
        ys.append(y)
        te_list: list[float] = []
    else:
        te_list = t_eval.tolist()
    ti = 0
    if t_eval is not None:
        while ti < len(te_list) and te_list[ti] <= t0:
            if te_list[ti] == t0:
                ts.append(t0)
                ys.append(list(y))
            ti += 1
    status: int | None = None if span > 0.0 else 0
    message = "The solver successfully reached the end of the integration interval."
    rejected = False
    steps: list[list[Any]] = []  # the accepted steps, for the dense output
    while status is None:
        min_step = 10.0 * abs(math.nextafter(t, math.inf) - t)
        h_abs = min(max(h_abs, min_step), max_step)
        while True:
            if h_abs < min_step:
                status, message = -1, "Required step size is less than spacing between numbers."
                break
            t_new = t + h_abs
            if t_new > t1:
                t_new = t1
            h = t_new - t
            y_new, f_new, e5, e3, K = step(fun, t, y, f, h, args)
            nfev += 12
            y_new = [float(v) for v in y_new]
            f_new = [float(v) for v in f_new]
            scale = [a + max(abs(p), abs(q)) * rt for a, p, q, rt in zip(atol, y, y_new, rtol)]
            e5n = sum((e / s) ** 2 for e, s in zip(e5, scale))
            e3n = sum((e / s) ** 2 for e, s in zip(e3, scale))
            if e5n == 0.0 and e3n == 0.0:
                err = 0.0
            else:
                err = h * e5n / math.sqrt((e5n + 0.01 * e3n) * n)
            if err < 1.0:
                fac = _MAX_FACTOR if err == 0.0 else min(_MAX_FACTOR, _SAFETY * err ** _ERR_EXP)
                if rejected:
                    fac = min(1.0, fac)
                h_abs *= fac
                rejected = False
                break
            h_abs *= max(_MIN_FACTOR, _SAFETY * err ** _ERR_EXP) if err == err else _MIN_FACTOR
            rejected = True
        if status is not None:
            break
        t_old, y_old = t, y
        t, y, f = t_new, y_new, f_new
        sol: _DenseStep | None = None
        step_data = (t_old, h, y_old, y_new, K)

        def _dense(d: tuple = step_data) -> _DenseStep:
            nonlocal nfev
            nfev += 3
            return _DenseStep(d[0], d[1], d[2], dense_coeffs(fun, d[0], d[2], d[3], d[1], d[4], args), interp)

        if dense_output:
            steps.append([t_old, h, y_old, y_new, K, None])
        if events:
            g_new = [ev(t, y, *args) for ev, _, _ in events]
            active = []
            for e, ((_, _, direction), a, b) in enumerate(zip(events, g, g_new)):
                if crossed(a, b, direction):
                    active.append(e)
            if active:
                sol = _dense()
                if dense_output:
                    steps[-1][5] = sol
                roots = [brentq(lambda tt, e=e, d=sol: events[e][0](tt, d(tt), *args), t_old, t,
                                xtol=4 * _EPS, rtol=4 * _EPS) for e in active]
                hits = sorted(zip(roots, active))
                term = [k for k, (_, e) in enumerate(hits) if events[e][1]]
                if term:
                    hits = hits[: term[0] + 1]
                for rt, e in hits:
                    t_events[e].append(rt)
                    y_events[e].append(sol(rt))
                if term:
                    status = 1
                    t = hits[-1][0]
                    y = sol(t)
            g = g_new
        if t_eval is None:
            ts.append(t)
            ys.append(y)
        else:
            j = ti
            while j < len(te_list) and te_list[j] <= t:
                j += 1
            if j > ti:
                if sol is None:
                    sol = _dense()
                    if dense_output:
                        steps[-1][5] = sol
                for tt in te_list[ti:j]:
                    ts.append(tt)
                    ys.append(sol(tt))
                ti = j
        if status is None and t >= t1:
            status = 0
    return {
        "sol": _LazyDense(fun, args, dense_coeffs, interp, steps, list(y0)) if dense_output else None,
        "t": np.array(ts, dtype=float),
        "y": np.array(ys, dtype=float).reshape(-1, n).T,
        "t_events": [np.array(v, dtype=float) for v in t_events],
        "y_events": [np.array(v, dtype=float).reshape(-1, n) for v in y_events],
        "status": status, "message": message, "nfev": nfev, "last_step": h_abs,
    }


def integrate(
    fun: Callable[..., Any],
    t_span: tuple[float, float],
    y0: Any,
    *,
    t_eval: Any = None,
    rtol: float = 1e-10,
    atol: Any = 1e-12,
    method: str = "DOP853",
    dense_output: bool = False,
    events: Iterable[Event] = (),
    time_name: str = "t",
    fields: Callable[[np.ndarray, np.ndarray], Mapping[str, np.ndarray]] | None = None,
    args: tuple = (),
    max_step: float = np.inf,
    engine: str = "scipy",
    first_step: float | None = None,
) -> Solution:
    """Integrate ``dy/dt = fun(t, y)`` and return a :class:`Solution` with named arrays.

    Parameters
    ----------
    fun, t_span, y0, t_eval, rtol, atol, method, dense_output, args, max_step
        As in :func:`scipy.integrate.solve_ivp`.
    engine : {'scipy', 'python'}
        ``'scipy'``: :func:`scipy.integrate.solve_ivp`. ``'python'``: the same DOP853 (coefficients, error
        norm, step-size control, initial step, dense output on ``t_eval``, events located by ``brentq``) run
        on lists of floats, for small systems (a few states) where SciPy's per-step NumPy overhead dominates;
        ``fun`` and the events then receive ``y`` as a list of floats and ``fun`` may return any sequence.
        It integrates forward only, with ``method='DOP853'``; its dense output (``sol.sol(t)``, rows of the state
        for scalar or array ``t``, like SciPy's ``OdeSolution``) computes each step's interpolant the first time
        that step is asked for.
    first_step : float, optional
        Initial step size (default: SciPy's heuristic), e.g. the ``last_step`` of a run being continued.
    events : iterable of Event
        Named events; terminal ones end the run with ``status == 1`` and their message.
    time_name : str
        Attribute name of the time array in the result (``'t'`` or ``'tau'``).
    fields : callable, optional
        ``fields(t, y) -> {name: array}`` computed on the output grid (``y`` of shape ``(n_state, n_t)``).

    Returns
    -------
    Solution
    """
    if len(t_span) != 2:
        raise ValueError(f"t_span must be a pair (t0, t1), got {t_span!r}")
    t0, t1 = float(t_span[0]), float(t_span[1])
    if not (np.isfinite(t0) and np.isfinite(t1)):
        raise ValueError("t_span must be finite")
    y0a = np.asarray(y0, dtype=float)
    if not np.all(np.isfinite(y0a)):
        raise ValueError("the initial state y0 must be finite")
    evs = list(events)

    def _nonfinite(t: float, y: np.ndarray, *a: Any) -> float:
        return 1.0 if np.all(np.isfinite(y)) else -1.0

    # solve_ivp reads events' options from function attributes, which mypy does not model on a def
    _nonfinite.terminal = True  # type: ignore[attr-defined]  # solve_ivp's event attribute
    wrapped: list[Callable[..., float]] = []
    for ev in evs:
        def _f(t: float, y: np.ndarray, *a: Any, _ev: Event = ev) -> float:
            return _ev.fun(t, y, *a)

        _f.terminal = ev.terminal  # type: ignore[attr-defined]  # solve_ivp's event attribute
        _f.direction = ev.direction  # type: ignore[attr-defined]  # solve_ivp's event attribute
        wrapped.append(_f)
    wrapped.append(_nonfinite)

    if engine not in ("scipy", "python"):
        raise ValueError(f"engine must be 'scipy' or 'python', got {engine!r}")
    py = engine == "python"
    if py and (method != "DOP853" or t1 < t0):
        raise ValueError("engine='python' integrates forward with method='DOP853'")
    with np.errstate(all="ignore"):
        # solve_ivp loops forever when the right-hand side is NaN at the initial state (its step-size control
        # turns NaN): refuse that up front
        f0 = np.asarray(fun(t0, y0a.tolist() if py else y0a, *(args or ())), dtype=float)
    if not np.all(np.isfinite(f0)):
        raise ValueError(
            f"the right-hand side is not finite at the initial state (t = {t0!r}, y0 = {y0a!r}): check the "
            "model's parameters and any user-supplied function (e.g. a torque)"
        )
    if py:
        n = y0a.size
        atol_l = np.broadcast_to(np.asarray(atol, dtype=float), (n,)).tolist()
        te_arr = None if t_eval is None else np.asarray(t_eval, dtype=float)

        def _finite(t: float, y: list[float], *a: Any) -> float:
            return 1.0 if all(math.isfinite(v) for v in y) else -1.0

        ev_small = [(ev.fun, ev.terminal, ev.direction) for ev in evs] + [(_finite, True, 0.0)]
        with np.errstate(all="ignore"):
            rtol_l = np.broadcast_to(np.asarray(rtol, dtype=float), (n,)).tolist()
            out = _solve_small(fun, t0, t1, y0a.tolist(), te_arr, rtol_l, atol_l, ev_small, tuple(args or ()),
                               float(max_step), first_step, dense_output)
        res: Any = SimpleNamespace(**out)  # what integrate reads from a solve_ivp result
    else:
        with np.errstate(all="ignore"):
            res = solve_ivp(
                fun, (t0, t1), y0a, method=method, t_eval=t_eval, rtol=rtol, atol=atol,
                dense_output=dense_output, events=wrapped, args=args or None, max_step=max_step,
                **({} if first_step is None else {"first_step": first_step}),
            )
    t_events, y_events = {}, {}
    for i, ev in enumerate(evs):
        te_i, ye_i = np.asarray(res.t_events[i], dtype=float), np.asarray(res.y_events[i])
        if not py and te_i.size > 1:
            # solve_ivp counts a root that falls exactly on a step boundary in both steps (its rule is
            # g_old <= 0 <= g_new); one passage is one event, as :func:`crossed` decides for our integrators
            keep = np.concatenate(([True], np.diff(te_i) > 8 * np.finfo(float).eps * np.abs(te_i[1:])))
            te_i, ye_i = te_i[keep], ye_i[keep]
        t_events[ev.name], y_events[ev.name] = te_i, ye_i
    status = int(res.status)
    message = str(res.message)
    event = None
    t = np.asarray(res.t)
    y = np.asarray(res.y)
    if len(res.t_events[-1]) or (y.size and not np.all(np.isfinite(y[:, -1]))):
        status = -1
        tbad = res.t_events[-1][0] if len(res.t_events[-1]) else t[-1]
        message = f"the state became non-finite near {time_name} = {tbad:.6g}; integration stopped"
        keep = np.all(np.isfinite(y), axis=0)
        t, y = t[keep], y[:, keep]
    elif status == 1:
        for i, ev in enumerate(evs):
            if ev.terminal and len(res.t_events[i]):
                event = ev.name
                te = res.t_events[i][-1]
                message = f"stopped by event {ev.name!r} at {time_name} = {te:.6g}" + (
                    f": {ev.message}" if ev.message else ""
                )
                break
    data = dict(fields(t, y)) if fields is not None and t.size else {}
    sol = Solution(time_name, t, y, data, status, message, event, t_events, y_events,
                   res.sol if dense_output else None, int(res.nfev))
    sol.last_step = getattr(res, "last_step", None)
    return sol
