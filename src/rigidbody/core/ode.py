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
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

__all__ = ["Event", "Solution", "integrate"]


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

    fun: Callable[..., float]
    name: str
    terminal: bool = True
    direction: float = 0.0
    message: str = ""


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
) -> Solution:
    """Integrate ``dy/dt = fun(t, y)`` and return a :class:`Solution` with named arrays.

    Parameters
    ----------
    fun, t_span, y0, t_eval, rtol, atol, method, dense_output, args, max_step
        As in :func:`scipy.integrate.solve_ivp`.
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

    with np.errstate(all="ignore"):
        # solve_ivp loops forever when the right-hand side is NaN at the initial state (its step-size control
        # turns NaN): refuse that up front
        f0 = np.asarray(fun(t0, y0a, *(args or ())), dtype=float)
    if not np.all(np.isfinite(f0)):
        raise ValueError(
            f"the right-hand side is not finite at the initial state (t = {t0!r}, y0 = {y0a!r}): check the "
            "model's parameters and any user-supplied function (e.g. a torque)"
        )
    with np.errstate(all="ignore"):
        res = solve_ivp(
            fun, (t0, t1), y0a, method=method, t_eval=t_eval, rtol=rtol, atol=atol,
            dense_output=dense_output, events=wrapped, args=args or None, max_step=max_step,
        )
    t_events = {ev.name: np.asarray(res.t_events[i]) for i, ev in enumerate(evs)}
    y_events = {ev.name: np.asarray(res.y_events[i]) for i, ev in enumerate(evs)}
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
    return Solution(time_name, t, y, data, status, message, event, t_events, y_events,
                    res.sol if dense_output else None, int(res.nfev))
