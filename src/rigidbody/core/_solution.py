"""The result type of every integration (:class:`Solution`) and the named events that end runs (:class:`Event`);
both are re-exported by :mod:`rigidbody.core.ode`, where users find them."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from . import _display

__all__ = ["OPTIONAL_FIELDS", "Event", "Solution"]


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

    See Also
    --------
    integrate, rigidbody.core.batch.integrate_batch : the integrators that take events.

    Examples
    --------
    ``y = exp(-t)`` falls to one half at ``t = ln 2``; the terminal event ends the run there (status 1):

    >>> import math
    >>> from rigidbody.core.ode import Event, integrate
    >>> half = Event(lambda t, y: y[0] - 0.5, "half", message="y fell to one half")
    >>> sol = integrate(lambda t, y: [-y[0]], (0.0, 5.0), [1.0], events=[half])
    >>> print(sol.status, sol.event, f"{sol.t_events['half'][0]:.9f} {math.log(2.0):.9f}")
    1 half 0.693147181 0.693147181
    """

    fun: Callable[..., Any]
    name: str
    terminal: bool = True
    direction: float = 0.0
    message: str = ""


def _empty_lists(batch_shape: tuple[int, ...]) -> Any:
    """``[]`` for a single run, an object array of empty lists (one per member) for a batch."""
    if not batch_shape:
        return []
    out = np.empty(batch_shape, dtype=object)
    for i in np.ndindex(*batch_shape):
        out[i] = []
    return out


#: The optional fields of a result that only some producers record (those of a separatrix-crossing averaged run):
#: name -> the default of a result that does not record it, as a function of ``batch_shape``
OPTIONAL_FIELDS: dict[str, Callable[[tuple[int, ...]], Any]] = {
    "crossings": _empty_lists,
    "quad_error": lambda shape: np.zeros(shape) if shape else 0.0,
    "resonances": _empty_lists,
}


class Solution:
    """Result of an integration: named arrays plus SciPy's status, for one run or a batch of runs.

    A single run (``batch_shape == ()``) has the time array of shape ``(n_t,)``, scalar fields of shape
    ``(n_t,)``, vector fields of shape ``(k, n_t)``, ``y`` of shape ``(n_state, n_t)`` and a scalar
    ``status``, ``message`` and ``event``. A batch run (:func:`rigidbody.core.batch.integrate_batch` and the
    batch calls of the analyses) has a leading ``batch_shape`` on every field and on ``y``, the common output
    grid as ``time``, per-member ``status`` (int array), ``message`` and ``event`` (object arrays),
    ``success`` (bool array) and NaN in a member's samples after its end; ``sol[i]`` (or
    :meth:`member`) is the single-run view of member ``i``, with the member's entries of the per-member
    fields below.

    A producer builds its result by keywords with :meth:`build` (``Solution.build(producer=
    "euler_poinsot.averaged", time=tau, y=y, status=0, message=..., fields={...}, crossings=[...])``); the
    positional form ``Solution(time_name, time, y, data, status, message, event, t_events, y_events, sol,
    nfev, *, batch_shape=(), producer=None, **optional)`` is kept for the producers not yet converted.

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
        -1 failure, 0 end of the span reached, 1 a terminal event (per member for a batch: an int array of
        shape ``batch_shape``).
    message : str or numpy.ndarray
        What ended the run and, for a failure or a stop, how to go on (per member: an object array).
    success : bool or numpy.ndarray
        ``status >= 0``.
    event : str or None, or numpy.ndarray
        Name of the terminal event that ended the run (per member for a batch: an object array, None for a
        member that no event ended).
    t_events : dict
        Event name -> times at which it occurred (for a batch: an object array of per-member arrays).
    y_events : dict
        Event name -> states at those times (likewise).
    sol : callable or None
        Dense output of the raw state when requested (single runs only): ``sol(t)`` gives the state's rows at
        a scalar or an array of times, like SciPy's ``OdeSolution``.
    nfev : int or numpy.ndarray
        Number of right-hand-side evaluations (per member for a batch).
    producer : str or None
        The function that produced the result (``'core.ode.integrate'``, ``'core.batch.integrate_batch'``,
        ``'euler_poinsot.averaged'``, ...); None where the producer does not record itself.
    t_final, y_final : float and numpy.ndarray, or arrays
        The time at which the run ended (the end of the span, a terminal event, a failure) and the raw state
        there; per member for a batch. Default None (not recorded).
    last_step : float or numpy.ndarray or None
        The step size the integrator would have taken next, to continue a run (``first_step`` of the next
        segment); per member for a batch. Default None (not recorded, e.g. ``solve_ivp`` runs).
    crossings : list of dict
        Separatrix crossings of an averaged run (time, regions, capture probabilities, ...); for a batch an
        object array of per-member lists. Default: empty (no crossing, or a producer that crosses none).
    quad_error : float or numpy.ndarray
        The largest error estimate of the numerical period averages the run used (per member for a batch).
        Default 0.0 (closed forms, or no averaging).
    resonances : list
        Resonances met on the way (per member for a batch: an object array of lists). Default: empty.

    See Also
    --------
    integrate, rigidbody.core.batch.integrate_batch : the integrators that return it.
    Solution.build : how a producer makes one.

    Notes
    -----
    :data:`OPTIONAL_FIELDS` declares the last three with their defaults; a result that does not record one
    gives its default when asked. :meth:`plot` draws with the module named by :attr:`plot_backend`.

    Examples
    --------
    ``dy/dt = -k y`` for ``k = 1, 2`` in one batch: member ``i`` ends at ``exp(-k_i)``, and ``sol[i]`` is its
    single-run view:

    >>> import numpy as np
    >>> from rigidbody.core.batch import integrate_batch
    >>> k = np.array([1.0, 2.0])
    >>> sol = integrate_batch(lambda t, y, k: -k[:, None] * y, (0.0, 1.0), np.ones((2, 1)), args=(k,))
    >>> sol.batch_shape, sol.y.shape
    ((2,), (2, 1, 101))
    >>> print(f"{sol[1].y[0, -1]:.9f} {np.exp(-2.0):.9f}")
    0.135335283 0.135335283
    """

    #: The module whose ``plot_solution(sol, ax=None, **kwargs)`` draws a result: looked up by name when
    #: :meth:`plot` is called (as pandas finds its plotting backend), so :mod:`rigidbody.core` imports nothing
    #: above it. Set it (on the class, or on one result) to draw results with other code.
    plot_backend: ClassVar[str] = "rigidbody.plotting"

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
        producer: str | None = None,
        **optional: Any,
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
        self.producer = producer
        self.t_final = optional.pop("t_final", None)
        self.y_final = optional.pop("y_final", None)
        self.last_step: Any = optional.pop("last_step", None)
        unknown = sorted(set(optional) - set(OPTIONAL_FIELDS))
        if unknown:
            raise TypeError(f"Solution got unknown field(s) {unknown}; the optional fields are t_final, y_final, "
                            f"last_step and {sorted(OPTIONAL_FIELDS)}")
        # kept in the instance's dict (a result that does not record one gives the default: __getattr__)
        self.__dict__.update(optional)

    @classmethod
    def build(
        cls,
        *,
        producer: str,
        time: Any,
        y: Any,
        status: Any,
        message: Any,
        fields: Mapping[str, Any] | None = None,
        event: Any = None,
        t_events: Mapping[str, Any] | None = None,
        y_events: Mapping[str, Any] | None = None,
        dense: Any = None,
        nfev: Any = 0,
        time_name: str = "t",
        **optional: Any,
    ) -> Solution:
        """A result built by keywords: what every producer records, and the optional fields it has.

        Parameters
        ----------
        producer : str
            The function that produced it (``'euler_poinsot.averaged'``).
        time : array_like
            The output times, shape ``(n_t,)``.
        y : array_like
            The raw state, shape ``batch_shape + (n_state, n_t)``.
        status : int or array_like of int
            -1 failure, 0 end of the span, 1 a terminal event; its shape is the batch shape (``()`` for one
            run).
        message : str or array_like of str
            Per member for a batch.
        fields : mapping of str to array_like, optional
            The named arrays (each ``batch_shape + (..., n_t)``).
        event : str or None, or array_like, optional
            The terminal event that ended the run (per member for a batch; default None: none).
        t_events, y_events : mapping, optional
            Event name -> times, states (for a batch: object arrays of per-member arrays).
        dense : callable, optional
            Dense output of the raw state (single runs).
        nfev : int or array_like of int
            Right-hand-side evaluations (per member for a batch).
        time_name : str
            ``'t'`` or ``'tau'``.
        **optional
            ``t_final``, ``y_final``, ``last_step`` and the fields of :data:`OPTIONAL_FIELDS` (``crossings``,
            ``quad_error``, ``resonances``); those not given take their defaults (see the class).

        Returns
        -------
        Solution

        Raises
        ------
        TypeError
            For a producer that is not a non-empty string, or an unknown optional field.
        ValueError
            For a ``y``, ``message``, ``event`` or ``nfev`` whose shape does not fit the batch shape and ``time``.

        See Also
        --------
        integrate : which builds its result this way.

        Examples
        --------
        A one-field result whose fields are attributes:

        >>> import numpy as np
        >>> from rigidbody.core.ode import Solution
        >>> sol = Solution.build(producer="demo", time=np.linspace(0.0, 1.0, 3), y=np.zeros((1, 3)), status=0,
        ...                      message="done", fields={"x": np.array([1.0, 2.0, 3.0])})
        >>> print(sol.producer, sol.status, sol.x[-1])
        demo 0 3.0
        """
        if not isinstance(producer, str) or not producer:
            raise TypeError(f"producer must name the function that made the result (a non-empty str), got "
                            f"{producer!r}")
        batch_shape = tuple(np.shape(status))
        t = np.asarray(time, dtype=float)
        ya = np.asarray(y)
        if t.ndim != 1 or ya.ndim != len(batch_shape) + 2 or ya.shape[:len(batch_shape)] != batch_shape \
                or ya.shape[-1] != t.size:
            raise ValueError(f"y must have shape batch_shape + (n_state, n_t) = {batch_shape} + (n_state, {t.size})"
                             f" for time of shape {t.shape}, got {ya.shape}")
        if batch_shape:
            event = np.full(batch_shape, None, dtype=object) if event is None else event
            for name, value in (("message", message), ("event", event), ("nfev", nfev)):
                if np.shape(value) != batch_shape:
                    raise ValueError(f"{name} must have one entry per member, shape {batch_shape}, got shape "
                                     f"{np.shape(value)}")
        return cls(time_name, t, ya, dict(fields or {}), status, message, event, dict(t_events or {}),
                   dict(y_events or {}), dense, nfev, batch_shape=batch_shape, producer=producer, **optional)

    def __getattr__(self, name: str) -> Any:
        if name == self.__dict__.get("time_name"):
            return self.__dict__["time"]
        data = self.__dict__.get("_data", {})
        if name in data:
            return data[name]
        if name in OPTIONAL_FIELDS and "batch_shape" in self.__dict__:
            value = OPTIONAL_FIELDS[name](self.batch_shape)  # not recorded: the declared default
            self.__dict__[name] = value
            return value
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

        See Also
        --------
        Solution.to_xarray : all members at once, as a Dataset.

        Examples
        --------
        The last member of a batch of ``dy/dt = -k y`` (``k = 2``) ends at ``exp(-2)``:

        >>> import numpy as np
        >>> from rigidbody.core.batch import integrate_batch
        >>> k = np.array([1.0, 2.0])
        >>> sol = integrate_batch(lambda t, y, k: -k[:, None] * y, (0.0, 1.0), np.ones((2, 1)), args=(k,))
        >>> last = sol.member(-1)
        >>> last.batch_shape, last.status
        ((), 0)
        >>> print(f"{last.y[0, -1]:.9f} {np.exp(-2.0):.9f}")
        0.135335283 0.135335283
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
        names = ("t_final", "y_final", "last_step", *(f for f in OPTIONAL_FIELDS if f in self.__dict__))
        optional = {f: self._member_value(getattr(self, f), idx) for f in names}
        return Solution(self.time_name, self.time[keep], y[..., keep], data, int(self.status[idx]),
                        str(self.message[idx]), self.event[idx], t_events, y_events, None, int(nfev),
                        producer=self.producer, **optional)

    def _member_value(self, value: Any, idx: tuple[int, ...]) -> Any:
        """A member's entry of a per-member field (an array with the batch's leading shape), else the value."""
        if isinstance(value, np.ndarray) and value.shape[:len(self.batch_shape)] == self.batch_shape:
            entry = value[idx]
            return entry.item() if isinstance(entry, np.generic) else entry
        return value

    def __bool__(self) -> bool:
        return True

    def __len__(self) -> int:
        if not self.batch_shape:
            raise TypeError("a single run has no members (len() is defined for batch solutions)")
        return self.batch_shape[0]

    def __dir__(self) -> list[str]:
        return sorted(set(super().__dir__()) | set(self._data) | set(OPTIONAL_FIELDS) | {self.time_name})

    def _repr_html_(self) -> str:
        return _display.solution_html(self)

    def plot(self, ax: Any = None, *, backend: str | None = None, **kwargs: Any) -> Any:
        """Draw the module's standard figure; returns the Axes it drew on.

        Parameters
        ----------
        ax : Axes or array of Axes, optional
            Where to draw (new ones by default).
        backend : str, optional
            The module whose ``plot_solution(sol, ax, **kwargs)`` draws (default :attr:`plot_backend`,
            ``'rigidbody.plotting'``: :func:`rigidbody.plotting.plot_solution`), imported when called.
        **kwargs
            Passed to the drawing function.

        Returns
        -------
        Axes or numpy.ndarray of Axes

        Examples
        --------
        An averaged run of the Lagrange top draws its roots and its slow variables; given those Axes back, a
        second result is drawn over the first:

        >>> import numpy as np
        >>> from rigidbody import lagrange
        >>> top, drag = lagrange.Top(A=1.5, C=1.0, mgl=0.5), lagrange.LinearDrag(a=0.125, b=0.1)
        >>> start = lagrange.integrals(top, 0.0, 0.0, 3**0.5, 0.0, np.pi / 3)
        >>> axes = lagrange.averaged(top, drag, start, (0.0, 10.0)).plot()
        >>> [ax.get_ylabel() for ax in axes]
        ['roots of Q(u)', 'slow variables']
        >>> _ = lagrange.averaged(top, drag, start, (0.0, 5.0)).plot(axes)
        >>> [ax.get_lines()[0].get_label() for ax in axes], [len(ax.get_lines()) for ax in axes]
        (['$u_1$', '$G_z$'], [10, 8])
        """
        return _display.plot_solution(self, ax, backend=self.plot_backend if backend is None else backend,
                                      **kwargs)

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

        See Also
        --------
        Solution.member : one member as a single-run Solution.

        Examples
        --------
        A batch of ``dy/dt = -k y`` with the batch axis named by its ``k``: at ``t = 1`` the field ``x`` is
        ``exp(-k)``:

        >>> import numpy as np
        >>> from rigidbody.core.batch import integrate_batch
        >>> k = np.array([1.0, 2.0])
        >>> sol = integrate_batch(lambda t, y, k: -k[:, None] * y, (0.0, 1.0), np.ones((2, 1)), args=(k,),
        ...                       t_eval=np.linspace(0.0, 1.0, 3), fields=lambda t, y: {"x": y[..., 0, :]})
        >>> ds = sol.to_xarray(batch_dims={"k": k})
        >>> dict(ds["x"].sizes)
        {'k': 2, 't': 3}
        >>> print(f"{float(ds['x'].sel(k=2.0, t=1.0)):.9f} {np.exp(-2.0):.9f}")
        0.135335283 0.135335283
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
