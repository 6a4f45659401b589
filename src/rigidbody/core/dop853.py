"""The numerics of the DOP853 method, once, for both integrators of :mod:`rigidbody.core`.

:func:`rigidbody.core.ode.integrate` with ``engine='python'`` (one small system on Python floats) and
:func:`rigidbody.core.batch.integrate_batch` (many systems, vectorised over the members) run the same method
as :func:`scipy.integrate.solve_ivp` with ``method='DOP853'``; what they share lives here:

* the coefficients: the explicit Runge-Kutta pair of order 8(5,3) of Dormand and Prince with Hairer's
  coefficients, its error estimators and its 7th-order dense output, read from
  :class:`scipy.integrate.DOP853` (:data:`A`, :data:`B`, :data:`C`, :data:`E3`, :data:`E5`, :data:`D`,
  :data:`A_EXTRA`, :data:`C_EXTRA`);
* the error norm (:func:`error_norm`) and the step-size controller (:func:`step_factor`), SciPy's;
* the initial step (:func:`trial_step`, :func:`initial_step`: Hairer, Norsett and Wanner, II.4, as
  ``scipy.integrate._ivp.common.select_initial_step``);
* the event rules: when an event function crossed zero over a step (:func:`crossed`) and which of the roots
  found in one step count and where the step ends (:func:`settle_events`).

The functions take a namespace ``xp`` first (:data:`rigidbody.core.kernel.SCALAR` for floats,
:data:`rigidbody.core.kernel.ARRAY` for arrays of members, elementwise) and use only its ``minimum``,
``maximum``, ``where`` and ``sqrt``, so one definition serves both integrators. They are written so that
every branch is safe to evaluate on floats (``xp.where`` on floats evaluates both of its values).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy.integrate import DOP853

__all__ = [
    "A_EXTRA",
    "C_EXTRA",
    "E3",
    "E5",
    "EPS",
    "ERROR_EXPONENT",
    "ERROR_ORDER",
    "MAX_FACTOR",
    "MIN_FACTOR",
    "MIN_STEP_SPACINGS",
    "N_STAGES",
    "ROOT_TOL",
    "RTOL_FLOOR",
    "SAFETY",
    "A",
    "B",
    "C",
    "D",
    "crossed",
    "error_norm",
    "initial_step",
    "settle_events",
    "step_factor",
    "trial_step",
]


def _frozen(a: Any) -> np.ndarray:
    out = np.array(a, dtype=float)
    out.setflags(write=False)
    return out


#: number of stages of a step (the 13th evaluation, at the step's end, is the first stage of the next)
N_STAGES: int = DOP853.n_stages
#: Runge-Kutta matrix, shape (12, 12) (row ``s``: the weights of stages ``0`` to ``s - 1``)
A: np.ndarray = _frozen(DOP853.A)
#: weights of the 8th-order solution, shape (12,)
B: np.ndarray = _frozen(DOP853.B)
#: stage times as fractions of the step, shape (12,)
C: np.ndarray = _frozen(DOP853.C)
#: weights of the 3rd-order error estimator over the 12 stages and the step's end, shape (13,)
E3: np.ndarray = _frozen(DOP853.E3)
#: weights of the 5th-order error estimator, shape (13,)
E5: np.ndarray = _frozen(DOP853.E5)
#: the dense output's coefficients over the 16 stages, shape (4, 16)
D: np.ndarray = _frozen(DOP853.D)
#: Runge-Kutta matrix of the three extra stages of the dense output, shape (3, 16)
A_EXTRA: np.ndarray = _frozen(DOP853.A_EXTRA)
#: times of the three extra stages as fractions of the step, shape (3,)
C_EXTRA: np.ndarray = _frozen(DOP853.C_EXTRA)
#: order of the error estimate (7: the local error is O(h^8))
ERROR_ORDER: int = DOP853.error_estimator_order
#: the controller's exponent, -1/(ERROR_ORDER + 1)
ERROR_EXPONENT: float = -1.0 / (ERROR_ORDER + 1)
#: SciPy's step-size controller (``scipy/integrate/_ivp/rk.py``): safety factor and limits of the change
SAFETY, MIN_FACTOR, MAX_FACTOR = 0.9, 0.2, 10.0
#: machine epsilon of float64
EPS: float = float(np.finfo(float).eps)
#: SciPy's floor of the relative tolerance
RTOL_FLOOR: float = 100.0 * EPS
#: a step shorter than this many spacings of floating-point numbers at ``t`` fails (SciPy's rule)
MIN_STEP_SPACINGS: float = 10.0
#: relative and absolute tolerance of an event's root in time (SciPy's ``brentq`` settings for events)
ROOT_TOL: float = 4.0 * EPS

# below this error the controller's factor is MAX_FACTOR anyway (SAFETY * err**ERROR_EXPONENT >= 16 > 10): the
# floor keeps 0 ** negative out of the float evaluation without changing any factor
_ERR_FLOOR = 1e-10
_TINY = float(np.finfo(float).smallest_subnormal)


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

    See Also
    --------
    settle_events : which roots of a step count and where the step ends.
    rigidbody.core.ode.integrate : the single-run integrator that applies the rule.

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


def error_norm(xp: Any, h: Any, e5n: Any, e3n: Any, n: int) -> Any:
    """SciPy's scaled error of a DOP853 step, from the squared norms of its two error estimates.

    Parameters
    ----------
    xp : SCALAR or ARRAY
        The namespace (:mod:`rigidbody.core.kernel`).
    h : float or ndarray
        The step size.
    e5n, e3n : float or ndarray
        ``sum((e / scale)**2)`` over the components of the 5th- and the 3rd-order estimates ``E5 @ K``,
        ``E3 @ K``, with ``scale = atol + rtol * max(|y_old|, |y_new|)``.
    n : int
        Number of components.

    Returns
    -------
    float or ndarray
        ``h * e5n / sqrt((e5n + 0.01 * e3n) * n)``, 0 where both estimates vanish; a step is accepted where it
        is below 1. NaN where an estimate is not finite.

    See Also
    --------
    step_factor : the step-size change it decides.

    Examples
    --------
    Without a 3rd-order estimate (``e3n = 0``) the error is ``h (e5n / n)**(1/2)``, here ``0.1 · 1``:

    >>> from rigidbody.core import dop853
    >>> from rigidbody.core.kernel import SCALAR
    >>> print(f"{dop853.error_norm(SCALAR, 0.1, 3.0, 0.0, 3):.6f}")
    0.100000
    """
    return h * e5n / xp.sqrt(xp.maximum(e5n + 0.01 * e3n, _TINY) * n)


def step_factor(xp: Any, err: Any, after_rejection: Any) -> Any:
    """The factor by which the step size changes after a step of scaled error ``err`` (SciPy's controller).

    Parameters
    ----------
    xp : SCALAR or ARRAY
        The namespace.
    err : float or ndarray
        :func:`error_norm` of the step (accepted where ``err < 1``).
    after_rejection : bool or ndarray of bool
        Whether the step attempted before this one was rejected: then an accepted step does not grow the size.

    Returns
    -------
    float or ndarray
        Accepted: ``min(MAX_FACTOR, SAFETY * err**ERROR_EXPONENT)`` (``MAX_FACTOR`` for ``err == 0``; at most 1
        after a rejection). Rejected: ``max(MIN_FACTOR, SAFETY * err**ERROR_EXPONENT)``, ``MIN_FACTOR`` for a
        NaN error.

    See Also
    --------
    error_norm : the error it takes.

    Examples
    --------
    At ``err = 1`` the factor is the safety factor ``0.9``; an error-free step grows by ``MAX_FACTOR = 10``;
    after a rejection an accepted step does not grow (``min(1, 0.9 · 0.5**(-1/8)) = 0.98...``):

    >>> from rigidbody.core import dop853
    >>> from rigidbody.core.kernel import SCALAR
    >>> print(dop853.step_factor(SCALAR, 1.0, False), dop853.step_factor(SCALAR, 0.0, False))
    0.9 10.0
    >>> print(f"{dop853.step_factor(SCALAR, 0.5, True):.6f} {min(1.0, 0.9 * 0.5 ** (-1 / 8)):.6f}")
    0.981457 0.981457
    """
    f = SAFETY * xp.maximum(err, _ERR_FLOOR) ** ERROR_EXPONENT  # NaN for a NaN error
    grow = xp.minimum(xp.where(after_rejection, 1.0, MAX_FACTOR), f)
    shrink = xp.maximum(MIN_FACTOR, xp.where(f == f, f, MIN_FACTOR))
    return xp.where(err < 1.0, grow, shrink)


def trial_step(xp: Any, d0: Any, d1: Any, span: Any) -> Any:
    """The trial step ``h0`` of the initial-step heuristic (Hairer, Norsett, Wanner II.4).

    Parameters
    ----------
    xp : SCALAR or ARRAY
        The namespace.
    d0, d1 : float or ndarray
        RMS norms of the initial state and of its derivative, each component divided by
        ``atol + rtol * |y0|``.
    span : float or ndarray
        Length of the time span.

    Returns
    -------
    float or ndarray
        ``0.01 * d0 / d1`` (``1e-6`` where either norm is below ``1e-5``), at most ``span``.

    See Also
    --------
    initial_step : the first step it leads to.

    Examples
    --------
    ``0.01 · 1 / 10``; and ``1e-6`` for a state of norm below ``1e-5``:

    >>> from rigidbody.core import dop853
    >>> from rigidbody.core.kernel import SCALAR
    >>> print(dop853.trial_step(SCALAR, 1.0, 10.0, 5.0), dop853.trial_step(SCALAR, 1e-6, 10.0, 5.0))
    0.001 1e-06
    """
    return xp.minimum(xp.where((d0 < 1e-5) | (d1 < 1e-5), 1e-6, 0.01 * d0 / xp.maximum(d1, 1e-5)), span)


def initial_step(xp: Any, h0: Any, d1: Any, d2: Any, span: Any, max_step: float) -> Any:
    """The first step size of a run from the heuristic's norms (Hairer, Norsett, Wanner II.4, as SciPy).

    Parameters
    ----------
    xp : SCALAR or ARRAY
        The namespace.
    h0 : float or ndarray
        :func:`trial_step`.
    d1 : float or ndarray
        Scaled RMS norm of the initial derivative ``f0``.
    d2 : float or ndarray
        Scaled RMS norm of ``(f(t0 + h0, y0 + h0 f0) - f0) / h0``, an estimate of the second derivative.
    span : float or ndarray
        Length of the time span.
    max_step : float
        Largest step size.

    Returns
    -------
    float or ndarray
        ``min(100 h0, (0.01 / max(d1, d2))**(1/8), span, max_step)``, with ``max(1e-6, 1e-3 h0)`` for the middle
        term where both norms are below 1e-15; the span where the heuristic gives no positive step (a
        non-finite trial derivative): the step-size control then shrinks it.

    See Also
    --------
    trial_step : the trial step ``h0``.

    Examples
    --------
    With ``d1 = d2 = 1`` the order-based step ``0.01**(1/8) = 0.56`` exceeds ``100 h0 = 0.1``, which is taken:

    >>> from rigidbody.core import dop853
    >>> from rigidbody.core.kernel import SCALAR
    >>> print(f"{dop853.initial_step(SCALAR, 0.001, 1.0, 1.0, 5.0, float('inf')):.6f}")
    0.100000
    """
    h1 = xp.where((d1 <= 1e-15) & (d2 <= 1e-15), xp.maximum(1e-6, h0 * 1e-3),
                  (0.01 / xp.maximum(xp.maximum(d1, d2), 1e-15)) ** (1.0 / (ERROR_ORDER + 1)))
    h = xp.minimum(xp.minimum(100.0 * h0, h1), xp.minimum(span, max_step))
    return xp.where((h > 0.0) & (d2 == d2), h, span)


def settle_events(xp: Any, roots: list[Any], terminal: list[bool], t_end: Any) -> tuple[Any, Any, list[Any]]:
    """Where a step ends and which of the event roots found in it count.

    The step ends at the earliest root of a terminal event (the first event listed on a tie), or at ``t_end``.
    A root counts if it lies before that time, or at it when its event is the one that ends the step or is
    not terminal.

    Parameters
    ----------
    xp : SCALAR or ARRAY
        The namespace.
    roots : list of float or ndarray
        Per event, its root in this step (NaN where the event did not cross zero).
    terminal : list of bool
        Per event, whether it is terminal.
    t_end : float or ndarray
        The end of the step.

    Returns
    -------
    t_stop : float or ndarray
        Where the step ends.
    stop : int or ndarray
        Index of the event that ends the step, -1 where none does.
    counted : list of bool or ndarray of bool
        Per event, whether its root counts.

    See Also
    --------
    crossed : when an event function has crossed zero within a step.
    rigidbody.core.batch.integrate_batch : the vectorised integrator that applies it.

    Examples
    --------
    A terminal event (index 0) at ``0.3`` ends the step there; a non-terminal root at ``0.2`` (before it) counts, the
    one that did not cross (NaN) does not:

    >>> from rigidbody.core import dop853
    >>> from rigidbody.core.kernel import SCALAR
    >>> dop853.settle_events(SCALAR, [0.3, 0.2], [True, False], 1.0)
    (0.3, 0, [True, True])
    >>> dop853.settle_events(SCALAR, [0.3, float("nan")], [True, False], 1.0)
    (0.3, 0, [True, False])
    """
    t_stop, stop = t_end, xp.where(t_end == t_end, -1, -1)
    for j, (r, term) in enumerate(zip(roots, terminal)):
        if term:
            earlier = r < t_stop  # False for NaN: no root
            t_stop = xp.where(earlier, r, t_stop)
            stop = xp.where(earlier, j, stop)
    counted = [(r < t_stop) | ((r == t_stop) & ((stop == j) | (not term)))
               for j, (r, term) in enumerate(zip(roots, terminal))]
    return t_stop, stop, counted
