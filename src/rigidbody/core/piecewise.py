"""A piecewise driver: the members of a problem run piece by piece, grouped by mode, on the two integrators.

A *problem* is a system whose run is made of pieces: a piece integrates one *mode* of the system (a kind of
motion, a chart, a state layout) until the end of the span or a terminal event; at some events the run goes on
in another mode from the state there (a separatrix crossing, a change of chart). One run is a batch of one
member. The driver (:func:`run_pieces`) runs the members round by round: a round groups the live members by
their mode, integrates a group of one on :func:`rigidbody.core.ode.integrate` (the scalar DOP853 on Python
floats; a single member costs many times more through the vectorised integrator) and a larger group together
on :func:`rigidbody.core.batch.integrate_batch`, hands the outcome to the problem to record, and then, member by
member, either ends the member with its piece's status and message or asks the problem what a terminal event
means (:meth:`PiecewiseProblem.on_event`: the next mode, or a stop with a status and a message). A member that
goes on starts its next piece with the step size its last one reached.

The driver owns the per-member records every run has (status, message, terminal event, final time, function
evaluations, the step to continue with, the mode and the start of the next piece); the problem owns its state,
its output and what its events mean.
"""

from __future__ import annotations

import math
from collections.abc import Hashable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, Protocol

import numpy as np

from .batch import integrate_batch, member_records
from .ode import Event, Solution, integrate
from .validate import RESULT_ERRORS

__all__ = ["Continue", "MemberRecords", "PieceEnd", "PieceSpec", "PiecewiseProblem", "Stop", "run_pieces"]


@dataclass
class PieceSpec:
    """What the integrator takes for one piece of a group of members.

    ``y0`` is a list of floats for a group of one (the scalar integrator: ``fun(t, y, *args)`` on floats) and an
    array of shape ``(m, n)`` for a group of ``m`` (``fun`` vectorised over members, as
    :func:`rigidbody.core.batch.integrate_batch` takes it). ``t_eval`` is the output grid (None: the integrator's
    steps, one member only); ``dense``: a dense output (one member only); ``method``: another
    :func:`scipy.integrate.solve_ivp` method for one member (a group uses DOP853).

    See Also
    --------
    PiecewiseProblem : its ``piece`` method returns one.
    run_pieces : the driver that integrates it.
    """

    fun: Any
    y0: Any
    rtol: Any
    atol: Any
    events: list[Event] = field(default_factory=list)
    args: tuple[Any, ...] = ()
    t_eval: Any = None
    dense: bool = False
    method: str = "DOP853"


@dataclass
class PieceEnd:
    """How a piece ended for each member of its group (index ``j`` in the group): status, message, terminal
    event, the time and raw state at the end, the state at each event, the step size reached and the function
    evaluations, read alike from a single-run and a batch :class:`Solution`.

    See Also
    --------
    PiecewiseProblem : its ``record`` and ``on_event`` methods receive one.
    """

    status: list[int]
    message: list[str]
    event: list[str | None]
    t_final: np.ndarray
    last_step: np.ndarray
    nfev: np.ndarray
    t_events: dict[str, list[np.ndarray]]
    y_events: dict[str, list[np.ndarray]]

    @classmethod
    def of(cls, sol: Solution, m: int, tau0: float, t1: float) -> PieceEnd:
        """The outcome of ``sol`` for its ``m`` members (``tau0``: the start of a single member's piece).

        Examples
        --------
        ``y' = 1`` from 0 stops at its terminal event ``y = 1/2``, at ``t = 1/2``:

        >>> from rigidbody.core.ode import Event, integrate
        >>> from rigidbody.core.piecewise import PieceEnd
        >>> half = Event(lambda t, y: y[0] - 0.5, "half", True, 1.0)
        >>> sol = integrate(lambda t, y: [1.0], (0.0, 2.0), [0.0], events=[half], engine="python")
        >>> end = PieceEnd.of(sol, 1, 0.0, 2.0)
        >>> print(end.status, end.event, [round(float(t), 12) for t in end.t_final])
        [1] ['half'] [0.5]
        """
        if not sol.batch_shape:  # the scalar integrator does not record t_final
            st, ev = int(sol.status), sol.event
            t_last = float(sol.time[-1]) if sol.time.size else tau0
            t_end = t1 if st == 0 else (float(sol.t_events[ev][-1]) if st == 1 and ev is not None else t_last)
            return cls([st], [str(sol.message)], [ev], np.array([t_end]),
                       np.array([math.nan if sol.last_step is None else float(sol.last_step)]),
                       np.array([int(sol.nfev)]), {k: [np.asarray(v)] for k, v in sol.t_events.items()},
                       {k: [np.asarray(v)] for k, v in sol.y_events.items()})
        return cls([int(s) for s in np.reshape(sol.status, m)], [str(s) for s in np.reshape(sol.message, m)],
                   list(np.reshape(sol.event, m)), np.asarray(sol.t_final, dtype=float).reshape(m),
                   np.asarray(sol.last_step, dtype=float).reshape(m), np.asarray(sol.nfev, dtype=int).reshape(m),
                   {k: list(np.reshape(v, m)) for k, v in sol.t_events.items()},
                   {k: list(np.reshape(v, m)) for k, v in sol.y_events.items()})

    def event_state(self, j: int, name: str) -> np.ndarray:
        """The raw state of member ``j`` at the last occurrence of event ``name``.

        Examples
        --------
        >>> from rigidbody.core.ode import Event, integrate
        >>> from rigidbody.core.piecewise import PieceEnd
        >>> half = Event(lambda t, y: y[0] - 0.5, "half", True, 1.0)
        >>> sol = integrate(lambda t, y: [1.0, 2.0], (0.0, 2.0), [0.0, 0.0], events=[half], engine="python")
        >>> print(PieceEnd.of(sol, 1, 0.0, 2.0).event_state(0, "half").round(12))  # y2 = 2 t = 1 there
        [0.5 1. ]
        """
        return np.asarray(self.y_events[name][j], dtype=float).reshape(-1, np.shape(self.y_events[name][j])[-1])[-1]


@dataclass
class Continue:
    """A member goes on in ``mode`` from the time of its event (the problem has set its state there).

    See Also
    --------
    Stop : the other answer of :meth:`PiecewiseProblem.on_event`.
    """

    mode: Hashable


@dataclass
class Stop:
    """A member ends at time ``t`` with ``status``, ``message`` and terminal ``event``.

    See Also
    --------
    Continue : the other answer of :meth:`PiecewiseProblem.on_event`.
    """

    status: int
    message: str
    event: str | None
    t: float


class PiecewiseProblem(Protocol):
    """What :func:`run_pieces` asks of a problem.

    ``piece(mode, members, scalar)`` returns the :class:`PieceSpec` of the next piece of ``members`` (their
    indices; ``scalar``: one member on floats), each starting at ``starts[i]`` (given as ``tau``);
    ``record(mode, members, sol, end)`` stores the piece's output; ``on_event(mode, i, j, end)`` is called for a
    member ``i`` (``j`` in its group) whose piece ended on a terminal event named in :attr:`continues`, and
    returns :class:`Continue` or :class:`Stop`.

    See Also
    --------
    run_pieces : the driver (its Examples section has a whole problem).
    PieceSpec, PieceEnd : what a problem gives and receives.
    """

    continues: tuple[str, ...]

    def piece(self, mode: Any, members: list[int], scalar: bool, tau: np.ndarray) -> PieceSpec: ...

    def record(self, mode: Any, members: list[int], sol: Solution, end: PieceEnd) -> None: ...

    def on_event(self, mode: Any, i: int, j: int, end: PieceEnd) -> Continue | Stop: ...


@dataclass
class MemberRecords:
    """The per-member records of a piecewise run: ``status``, ``message``, ``event``, ``nfev``, ``t_final``
    (arrays of shape ``(B,)``, as :func:`rigidbody.core.batch.member_records` makes them), the mode of each
    member's next piece (None: ended), the start of that piece and the step size to start it with.

    See Also
    --------
    run_pieces : updates and returns them.
    rigidbody.core.batch.member_records : the arrays it starts from.
    """

    status: np.ndarray
    message: np.ndarray
    event: np.ndarray
    nfev: np.ndarray
    t_final: np.ndarray
    mode: list[Any]
    tau: np.ndarray
    hnext: np.ndarray

    @classmethod
    def start(cls, modes: Sequence[Any], t0: float, refused: Mapping[int, str] | None = None) -> MemberRecords:
        """Members starting at ``t0`` in ``modes``; ``refused``: index -> message of the members refused at the
        start (status -1, no mode).

        Examples
        --------
        >>> from rigidbody.core.piecewise import MemberRecords
        >>> rec = MemberRecords.start(["a", "b"], 0.0, refused={1: "b: refused"})
        >>> print(rec.mode, rec.message[1])
        ['a', None] b: refused
        """
        B = len(modes)
        status, message, event, nfev, t_final = member_records(B, t0)
        modes = list(modes)
        for i, msg in (refused or {}).items():
            message[i], modes[i] = msg, None
        return cls(status, message, event, nfev, t_final, modes, np.full(B, float(t0)), np.full(B, math.nan))

    def finish(self, i: int, status: int, message: str, event: str | None, t: float) -> None:
        self.status[i], self.message[i], self.event[i], self.t_final[i] = status, message, event, t
        self.mode[i] = None


def _groups(modes: list[Any]) -> dict[Any, list[int]]:
    """The live members by mode, in the order the modes first appear."""
    out: dict[Any, list[int]] = {}
    for i, m in enumerate(modes):
        if m is not None:
            out.setdefault(m, []).append(i)
    return out


def _integrate(problem: PiecewiseProblem, mode: Any, members: list[int], rec: MemberRecords, t1: float,
               strict: bool) -> tuple[Solution, PieceEnd] | None:
    """One piece of a group: the scalar integrator for one member, the vectorised one for more. A single
    member's ``ValueError`` at its start (the problem refuses its state, a user's function fails there, a
    right-hand side not finite there) raises for a single run (``strict``) and ends the member with status -1
    and the message in a batch."""
    if len(members) == 1:
        i = members[0]
        tau = float(rec.tau[i])
        h = float(rec.hnext[i])
        try:
            spec = problem.piece(mode, members, True, rec.tau[members])
            py = spec.method == "DOP853"
            sol = integrate(spec.fun, (tau, t1), spec.y0, t_eval=spec.t_eval, rtol=spec.rtol, atol=spec.atol,
                            method=spec.method, dense_output=spec.dense, events=spec.events, time_name="tau",
                            args=spec.args, engine="python" if py else "scipy",
                            first_step=None if (math.isnan(h) or not py) else h)
        except (ValueError, *RESULT_ERRORS) as exc:
            if strict:
                raise
            rec.finish(i, -1, str(exc), None, tau)
            return None
        return sol, PieceEnd.of(sol, 1, tau, t1)
    idx = np.array(members)
    spec = problem.piece(mode, members, False, rec.tau[idx])
    sol = integrate_batch(spec.fun, (rec.tau[idx], t1), spec.y0, t_eval=spec.t_eval, rtol=spec.rtol, atol=spec.atol,
                          events=spec.events, args=spec.args, time_name="tau", first_step=rec.hnext[idx])
    return sol, PieceEnd.of(sol, idx.size, 0.0, t1)


def run_pieces(problem: PiecewiseProblem, rec: MemberRecords, t1: float, *, strict: bool = False) -> MemberRecords:
    """Run every member of ``problem`` to its end, round by round.

    Parameters
    ----------
    problem : PiecewiseProblem
        The system: its pieces, their output, what its events mean.
    rec : MemberRecords
        The members' modes and starts (:meth:`MemberRecords.start`); updated in place and returned.
    t1 : float
        The end of the span.
    strict : bool
        A single run: an error at a piece's start raises instead of ending the member.

    Returns
    -------
    MemberRecords
        Each member's status (0 end of the span, 1 a terminal event, -1 a failure), message, terminal event,
        final time and function evaluations.

    See Also
    --------
    PiecewiseProblem : what a problem provides.
    rigidbody.core.ode.integrate, rigidbody.core.batch.integrate_batch : the two integrators it chooses between.

    Examples
    --------
    ``y' = 1`` from 0, the mode ``'up'`` until ``y = 1``, then ``'down'`` (``y' = -1``) to the end ``t = 1.5``:

    >>> import numpy as np
    >>> from rigidbody.core.ode import Event
    >>> from rigidbody.core.piecewise import Continue, MemberRecords, PieceSpec, run_pieces
    >>> class Tent:
    ...     continues = ("top",)
    ...     def piece(self, mode, members, scalar, tau):
    ...         s = 1.0 if mode == "up" else -1.0
    ...         top = Event(lambda t, y: y[0] - 1.0, "top", True, 1.0) if mode == "up" else Event(
    ...             lambda t, y: -1.0, "top")
    ...         return PieceSpec(lambda t, y: [s], [self.y], 1e-10, 1e-12, [top])
    ...     def record(self, mode, members, sol, end):
    ...         self.y = float(sol.y[0, -1])
    ...     def on_event(self, mode, i, j, end):
    ...         return Continue("down")
    >>> tent = Tent(); tent.y = 0.0
    >>> rec = run_pieces(tent, MemberRecords.start(["up"], 0.0), 1.5)
    >>> print(rec.status[0], f"{tent.y:.6f}")
    0 0.500000
    """
    while True:
        groups = _groups(rec.mode)
        if not groups:
            return rec
        for mode, members in groups.items():
            got = _integrate(problem, mode, members, rec, t1, strict)
            if got is None:
                continue
            sol, end = got
            problem.record(mode, members, sol, end)
            for j, i in enumerate(members):
                rec.nfev[i] += int(end.nfev[j])
                rec.hnext[i] = end.last_step[j]
                st, ev = end.status[j], end.event[j]
                if st == 1 and ev in problem.continues:
                    nxt = problem.on_event(mode, i, j, end)
                    if isinstance(nxt, Continue):
                        rec.mode[i], rec.tau[i] = nxt.mode, float(end.t_final[j])
                        continue
                    rec.finish(i, nxt.status, nxt.message, nxt.event, nxt.t)
                    continue
                rec.finish(i, st, end.message[j], ev, float(end.t_final[j]))
