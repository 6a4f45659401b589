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
from types import SimpleNamespace
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

from ._scalar import solve_small
from ._solution import OPTIONAL_FIELDS, Event, Solution
from .dop853 import crossed

__all__ = ["OPTIONAL_FIELDS", "Event", "Solution", "crossed", "integrate"]


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

    See Also
    --------
    rigidbody.core.batch.integrate_batch : many independent systems at once.
    Event : a named event.
    Solution : the result.

    Examples
    --------
    ``dy/dt = -y`` from ``y(0) = 1`` reaches ``1/e`` at ``t = 1``; the named field ``x`` is the state:

    >>> import math
    >>> from rigidbody.core.ode import integrate
    >>> sol = integrate(lambda t, y: [-y[0]], (0.0, 1.0), [1.0], fields=lambda t, y: {"x": y[0]})
    >>> print(f"{sol.x[-1]:.9f} {math.exp(-1.0):.9f}")
    0.367879441 0.367879441
    >>> sol.status
    0
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
            out = solve_small(fun, t0, t1, y0a.tolist(), te_arr, rtol_l, atol_l, ev_small, tuple(args or ()),
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
    if y.ndim != 2:  # solve_ivp returns y of shape (0,) when no output time was reached (an empty t_eval)
        y = y.reshape(y0a.size, t.size)
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
    return Solution.build(producer="core.ode.integrate", time=t, y=y, status=status, message=message, fields=data,
                          event=event, t_events=t_events, y_events=y_events, dense=res.sol if dense_output else None,
                          nfev=int(res.nfev), time_name=time_name, last_step=getattr(res, "last_step", None))
