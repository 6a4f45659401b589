r"""The torque protocol: the base class, a plain function as a torque, sums, and the one evaluation.

Every evaluation of a torque in the module (the averaging engine and its lean mean, the separatrix averages,
the full equations, single and batch) goes through :func:`evaluate`, which passes what a torque that may run
the user's code returned through :func:`rigidbody.core.validate.returned`: a torque that returns None, complex
numbers, a scalar, a wrong shape, NaN or infinities is named (by its repr, or its function's) with what was
expected. The catalogue torques that call no user function (they declare ``_broadcasts``) are trusted: their
output is not checked, so the engine's cost is unchanged for them. A run whose torque misbehaves part-way
notes it in a :class:`Misfire` and ends with a status and a message naming the torque and the time.

See :mod:`._torques` for the protocol itself and the catalogue.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from ..core.ode import Solution
from ..core.validate import returned
from ._state import Mean, State
from ._stops import stop_message

__all__ = ["FunctionTorque", "Misfire", "Torque", "TorqueSum", "as_torque", "checked_closed_mean", "evaluate",
           "first_closed_mean"]

#: what a torque is called in the messages of :func:`rigidbody.core.validate.returned`
ROLE = "the torque"


class Torque:
    r"""Base class of the torque objects: ``torque(omega, C, nu) -> M``, body components of shape ``(..., 3)``
    (see :doc:`/euler_poinsot`, "The protocol").

    Subclasses implement ``__call__(omega, C, nu)``; they may also declare a closed-form average and the setup
    they were built for, by overriding the two hooks below. Adding two torques (or a torque and a plain
    function) gives a :class:`TorqueSum`, whose parts each take their own path.

    See Also
    --------
    LinearDrag, GravityGradient, ConstantTorque, ViscousCavity, MagneticDipole : the catalogue.
    average_torque : the engine that averages any torque.

    Notes
    -----
    The two hooks a subclass may override:

    ``closed_mean(st) -> Mean or None``
        The torque's average over the Euler--Poinsot motion in closed form at the slow state ``st`` (a
        :class:`State`: ``body``, ``kind`` ('max' or 'min'), ``sigma`` (+1 or -1), ``G``, ``k2``, ``mc`` =
        :math:`1-k^2`, ``n`` (the unit vector of :math:`\mathbf G` in the orbital axes), ``nu`` (the true
        anomaly held during the average, or None in the orbit-averaged limit :math:`\varepsilon = 0`, where
        the average is also over the orbit) and ``orbit``). It returns a :class:`Mean` with ``L`` =
        :math:`\langle C\mathbf M\rangle`, the mean torque in the orbital axes, shape (3,) (that is
        :math:`d(G\mathbf n)/d\tau`), ``dT`` = :math:`\langle\boldsymbol\omega\cdot\mathbf M\rangle`
        (:math:`dT/d\tau`) and ``dk2`` (:math:`dk^2/d\tau`), in the units of ``__call__`` (the section-3
        scaling divided by :math:`\varepsilon^2`, slow time :math:`\tau`); the mean is over the precession
        angle, the period of the phase (and the orbit for ``nu=None``), as the averaging engine takes it.
        Returning None (the default) sends the torque to the averaging engine, which evaluates ``__call__``
        on grids of the motion. The path is chosen at the first state of each kind of motion of a run: a
        torque that returns a Mean there must return one at every state of that kind (None later is a
        ``TypeError`` naming the torque). ``averaging='numerical'`` of :func:`averaged` (``method='numerical'``
        of :func:`averaged_rates`) skips the hook (how a closed form is tested against the engine).
    ``check_setup(body, orbit) -> None``
        Called at the start of a run (and of :func:`averaged_rates`, :func:`separatrix_crossing`, ...): raise
        a ``ValueError`` if the run's :class:`Body` or :class:`Orbit` differs from those the torque was built
        for (as :class:`GravityGradient` does). The default accepts any.

    Examples
    --------
    A torque of one's own: the engine averages it over the Euler--Poinsot motion. This one is
    :math:`-0.5\boldsymbol\omega`, an isotropic drag, so its averages are those of the closed form (6):

    >>> import numpy as np
    >>> from rigidbody import euler_poinsot as ep
    >>> class Damper(ep.Torque):
    ...     def __call__(self, omega, C, nu):
    ...         return -0.5 * np.asarray(omega)
    >>> body = ep.Body(3.2, 2.6, 1.67)
    >>> r = ep.averaged_rates(body, Damper(), 1.0, 0.4, 0.7, 0.3, None)
    >>> dG, dT = ep.drag_rates(body, [0.5, 0.5, 0.5], 1.0, 0.4)
    >>> print(f"{r['dG']:.6f} {dG:.6f} {r['dT']:.6f} {dT:.6f}")
    -0.173241 -0.173241 -0.062377 -0.062377
    """

    #: whether ``__call__`` broadcasts the leading axes of its arguments (declared by the catalogue torques that
    #: call no user function; tested): the engine then passes compact arguments at once, other torques it
    #: checks first, on its first grid; and :func:`evaluate` trusts their output (only a class that declares
    #: it itself: a user's subclass is checked)
    _broadcasts: ClassVar[bool] = False

    def __call__(self, omega: Any, C: Any, nu: Any) -> np.ndarray:
        raise NotImplementedError

    def __add__(self, other: Any) -> TorqueSum:
        return TorqueSum((*self.parts(), *as_torque(other, "other").parts()))

    def __radd__(self, other: Any) -> TorqueSum:
        return TorqueSum((*as_torque(other, "other").parts(), *self.parts()))

    def parts(self) -> tuple[Torque, ...]:
        """The torques this one is the sum of (itself for a single torque).

        Examples
        --------
        >>> from rigidbody import euler_poinsot as ep
        >>> body = ep.Body(3.2, 2.6, 1.67)
        >>> drag = ep.LinearDrag([1.0, 1.0, 1.0])
        >>> drag.parts() == (drag,)
        True
        >>> [type(p).__name__ for p in (drag + ep.GravityGradient(body)).parts()]
        ['LinearDrag', 'GravityGradient']
        """
        return (self,)

    def check_setup(self, body: Any, orbit: Any) -> None:
        """Refuse a run whose body or orbit differs from the one this torque was built for (by default: none).

        Examples
        --------
        :class:`GravityGradient` is built from a body's moments and refuses another body:

        >>> from rigidbody import euler_poinsot as ep
        >>> gg = ep.GravityGradient(ep.Body(3.2, 2.6, 1.67))
        >>> gg.check_setup(ep.Body(3.2, 2.6, 1.67), ep.Orbit())   # the same body: accepted
        >>> try:
        ...     gg.check_setup(ep.Body(3.0, 2.0, 1.5), ep.Orbit())
        ... except ValueError:
        ...     print("refused")
        refused
        """

    def closed_mean(self, st: State) -> Mean | None:
        """The closed-form average at the slow state ``st``, or None when the torque has none (by default: the
        averaging engine is used).

        Examples
        --------
        The linear drag's closed form agrees with the engine's average of the same torque:

        >>> import numpy as np
        >>> from rigidbody import euler_poinsot as ep
        >>> body, drag = ep.Body(3.2, 2.6, 1.67), ep.LinearDrag([2.322, 1.31, 1.425])
        >>> delta, lam = 0.7, 0.3
        >>> n = np.array([np.sin(delta) * np.cos(lam), np.sin(delta) * np.sin(lam), np.cos(delta)])
        >>> st = ep.State(body, "max", 1, 1.0, 0.5, n, None, ep.Orbit())
        >>> mean = drag.closed_mean(st)
        >>> engine = ep.average_torque(body, drag, 1.0, 0.5, delta, lam, None)
        >>> print(f"{mean.dT:.9f} {engine.rates['dT']:.9f} {mean.dk2:.9f} {engine.rates['dk2']:.9f}")
        -0.235227252 -0.235227252 0.001881235 0.001881235
        >>> ep.Torque().closed_mean(st) is None   # the base class: no closed form, the engine averages
        True
        """
        return None


def as_torque(value: Any, name: str = "torque") -> Torque:
    """``value`` as a :class:`Torque`: a torque object is returned as is, a plain callable is wrapped."""
    if isinstance(value, Torque):
        return value
    if callable(value):
        return FunctionTorque(value)
    raise TypeError(
        f"{name} must be a torque object or a callable torque(omega, C, nu) -> M, got {type(value).__name__}"
    )


@dataclass(frozen=True)
class FunctionTorque(Torque):
    """A plain function ``fun(omega, C, nu) -> M`` used as a torque object (what ``as_torque`` wraps).

    Calling it returns the function's value checked by :func:`evaluate` (finite real components of shape
    ``(..., 3)``; otherwise a ``TypeError``/``ValueError`` naming the function).

    See Also
    --------
    Torque : the protocol it implements.

    Examples
    --------
    A function that returns the wrong shape is named in the error:

    >>> import numpy as np
    >>> from rigidbody import euler_poinsot as ep
    >>> def wrong(omega, C, nu):
    ...     return np.zeros(2)
    >>> try:
    ...     ep.FunctionTorque(wrong)(np.ones(3), np.eye(3), 0.0)
    ... except ValueError as exc:
    ...     print(exc)
    the torque <function wrong at 0x...> returned an array of shape (2,); expected finite real numbers of shape
    (..., 3), here (3,) (or broadcasting to it)
    """

    fun: Callable[..., Any]

    def __post_init__(self) -> None:
        if not callable(self.fun):
            raise TypeError(f"fun must be callable (omega, C, nu) -> M, got {type(self.fun).__name__}")

    def __call__(self, omega: Any, C: Any, nu: Any) -> np.ndarray:
        return evaluate(self, omega, C, nu)


@dataclass(frozen=True)
class TorqueSum(Torque):
    """The sum of torques (what ``a + b`` returns); nested sums are flattened.

    See Also
    --------
    Torque : ``a + b`` of two torques.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, eqs. (3), (6) (drag plus gravity gradient).

    Examples
    --------
    Rachinskaya's perturbation as a sum of two catalogue torques has the averages of (6), which
    :func:`averaged_rates` evaluates from the drag tensor alone:

    >>> from rigidbody import euler_poinsot as ep
    >>> body, I = ep.Body(3.2, 2.6, 1.67), [2.322, 1.31, 1.425]
    >>> both = ep.LinearDrag(I) + ep.GravityGradient(body)
    >>> type(both).__name__, len(both.terms)
    ('TorqueSum', 2)
    >>> a = ep.averaged_rates(body, both, 1.0, 0.5, 0.7, 0.3, 0.2)
    >>> b = ep.averaged_rates(body, I, 1.0, 0.5, 0.7, 0.3, 0.2)
    >>> print(f"{a['ddelta']:.6f} {b['ddelta']:.6f} {a['dlam']:.6f} {b['dlam']:.6f}")
    -0.121774 -0.121774 -1.440931 -1.440931
    """

    terms: tuple[Torque, ...]

    def __post_init__(self) -> None:
        flat: list[Torque] = []
        for t in self.terms:
            flat.extend(as_torque(t, "terms").parts())
        if not flat:
            raise ValueError("terms: a TorqueSum needs at least one torque")
        object.__setattr__(self, "terms", tuple(flat))

    def parts(self) -> tuple[Torque, ...]:
        return self.terms

    def __iter__(self) -> Iterator[Torque]:
        return iter(self.terms)

    def __call__(self, omega: Any, C: Any, nu: Any) -> np.ndarray:
        return evaluate(self, omega, C, nu)

    def check_setup(self, body: Any, orbit: Any) -> None:
        for t in self.terms:
            t.check_setup(body, orbit)


def first_closed_mean(part: Torque, st: State) -> Mean | None:
    """``part.closed_mean(st)`` at the first state of a kind of motion, where the path is chosen (None sends the
    part to the engine), checked whole: a :class:`Mean` of finite numbers with ``L`` of shape (3,), or None; a
    ``TypeError``/``ValueError`` naming the part otherwise."""
    m = part.closed_mean(st)
    if m is None:
        return None
    m = checked_closed_mean(part, st, m)
    if np.shape(m.L) != (3,) or not np.all(np.isfinite(m.L)) or not (math.isfinite(m.dT) and math.isfinite(m.dk2)):
        raise ValueError(f"{part!r}.closed_mean must return a Mean of finite numbers with L of shape (3,) "
                         f"(<C M> in the orbital axes), got {m!r}")
    return m


def checked_closed_mean(part: Torque, st: State, m: Any = None) -> Mean:
    """``part.closed_mean(st)`` (or its value ``m``) at a later state of a kind of motion whose path is the closed
    form: a :class:`Mean` (only its type is checked, the right-hand sides call this at every step); None or
    another type is a ``TypeError`` naming the part."""
    if m is None:
        m = part.closed_mean(st)
    if m is None:
        raise TypeError(f"{part!r}.closed_mean returned None at k2 = {st.k2} (kind {st.kind!r}) after a Mean at "
                        "the first state of this kind of motion: return a Mean at every state of a kind of motion, "
                        "or None at every one to have the averaging engine average the torque")
    if not isinstance(m, Mean):
        raise TypeError(f"{part!r}.closed_mean must return a Mean or None, got {type(m).__name__}")
    return m


def evaluate(torque: Any, omega: Any, C: Any, nu: Any, shape: tuple[int, ...] | None = None, *,
             finite: bool = True) -> np.ndarray:
    """The torque at ``(omega, C, nu)``, each part's output checked (the one evaluation of the module).

    Parameters
    ----------
    torque : Torque or callable
        A torque object (its parts are evaluated and added) or a plain function.
    omega, C, nu
        The arguments of the protocol.
    shape : tuple of int, optional
        The shape of the torque expected, ``leading + (3,)`` (default: the broadcast of the arguments' leading
        axes); a part's output must broadcast to it.
    finite : bool
        Whether NaN and infinite values are refused (a batch finds them per member itself).

    Returns
    -------
    numpy.ndarray
        Body components, of ``shape`` or broadcastable to it.

    Raises
    ------
    rigidbody.core.validate.ResultTypeError, rigidbody.core.validate.ResultValueError
        (a ``TypeError``, a ``ValueError``) naming the part that misbehaved and what was expected.
    """
    if shape is None:
        shape = (*np.broadcast_shapes(np.shape(omega)[:-1], np.shape(C)[:-2], np.shape(nu)), 3)
    out: Any = None
    for p in torque.parts() if isinstance(torque, Torque) else (torque,):
        if type(p) is FunctionTorque:  # the user's function itself: named in the messages
            M = returned(p.fun(omega, C, nu), p.fun, shape, role=ROLE, finite=finite)
        elif type(p).__dict__.get("_broadcasts", False):  # a catalogue torque that calls no user function
            M = p(omega, C, nu)
        else:
            M = returned(p(omega, C, nu), p, shape, role=ROLE, finite=finite)
        out = M if out is None else out + M
    return out  # an array: a torque has at least one part


class Misfire:
    """Where a run's torque misbehaved (:func:`evaluate` refused its output): the right-hand side notes it and
    returns NaN, the integrator's step then shrinks onto the time where the torque turns bad and fails there,
    and :meth:`settle` gives that failure the message naming the torque and the time."""

    def __init__(self) -> None:
        self.t = math.nan
        self.why = ""

    def note(self, t: float, exc: Exception) -> None:
        """Note a refused evaluation at time ``t`` (the latest counts: the failing steps close in on it)."""
        self.t, self.why = float(t), str(exc)

    def settle(self, sol: Solution) -> Solution:
        """``sol`` with the message naming the torque and the time if it failed (status -1) where the torque
        misbehaved (at or after its last time: a refused trial point the integrator then went past is not the
        cause)."""
        if self.why and sol.status == -1 and (sol.time.size == 0 or self.t >= float(sol.time[-1])):
            sol.message = stop_message("torque", tau=self.t, why=self.why)
        return sol
