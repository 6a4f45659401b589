r"""Perturbing torques admissible for averaging over the nutation angle (Akulenko et al. 1979, Sec. 2).

A torque ``eps M`` is admissible when the combinations (2.2)

.. math::
    M_1\sin\varphi + M_2\cos\varphi = M_1^*,\quad M_1p + M_2q = M_2^*,\quad M_3 = M_3^*

depend on the fast variables only through the nutation angle theta. The slow variables then obey (2.7)

.. math::
    G_z' = \varepsilon F_1,\ F_1 = M_1^*\sin\theta + M_3^*\cos\theta;\quad
    H' = \varepsilon F_2,\ F_2 = M_2^* + M_3^* r;\quad r' = \varepsilon F_3,\ F_3 = M_3^*/C.

(The paper prints ``F1 = M1* + M3* cos(theta)``: the factor ``sin(theta)`` of (2.1) was dropped; see
:ref:`errata-lagrange`.)

The protocol
------------
Every torque object accepted by :func:`rigidbody.lagrange.averaged` and
:func:`rigidbody.lagrange.simulate` is a :class:`Torque`:

``slow_rates(top, Gz, H, r, u) -> (F1, F2, F3)``
    the right-hand sides (2.7) at fixed slow variables for an array ``u = cos(theta)`` of nutation
    states (vectorised over ``u``). This is all the averaging engine needs.
``body_moments(top, p, q, r, g1, g2, g3) -> (M1, M2, M3)``
    the body components of ``M`` at a full state, with ``(g1, g2, g3) = (sin th sin phi,
    sin th cos phi, cos th)`` the upward vertical in body axes (direction cosines). Needed only by
    :func:`simulate`; scalars in, floats out.
``body_moments_batch(top, p, q, r, g1, g2, g3) -> (M1, M2, M3)`` (optional)
    the same for arrays of batch members (a batch :func:`simulate` calls ``body_moments`` member by member
    for a torque without it); the ready-made classes have it, their user functions then receive arrays.
``closed_means(xp, top, s) -> (<F1>, <F2>, <F3>)`` (optional)
    the nutation means of (2.7) in closed form, the capability of a torque that has one (:class:`LinearDrag`:
    (3.4)); the base class returns None and the averaging engine (a trapezoid rule over the nutation period on
    ``slow_rates``) is used. ``s`` is the state of the chart being integrated, with attributes ``Gz, H, r``,
    ``Cr`` (``C r``), the roots ``u1 <= u2 <= u3``, ``k2`` and ``mc = 1 - k2``; ``xp`` is
    :data:`rigidbody.core.kernel.SCALAR` (``s`` holds floats, one run) or :data:`~rigidbody.core.kernel.ARRAY`
    (``s`` holds arrays of batch members; the means must be computed elementwise). A subclass that defines it
    gets the closed form by default in :func:`averaged` and :func:`averaged_rhs` (``closed_form=False``
    forces the engine); :func:`has_closed_form` tells whether a torque has one.

Ready-made classes: :class:`ProportionalTorque` (class (2.4): ``M1 = p f, M2 = q f, M3 = M3*``),
:class:`VerticalPlaneTorque` (class (2.5): ``M1 = F sin phi, M2 = F cos phi, M3 = M3*``),
:class:`StarTorque` (the functions ``M1*, M2*, M3*`` of (2.2) given directly; averaging only) and
:class:`LinearDrag` (3.1), which also carries the closed-form averaged system (3.4).
User functions ``f, F, M3`` take ``(Gz, H, r, theta)`` as in (2.6) (``theta`` may be an array).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from . import _kernel as _k
from ._top import Top

__all__ = [
    "LinearDrag",
    "ProportionalTorque",
    "StarTorque",
    "Torque",
    "VerticalPlaneTorque",
    "check_torque",
    "has_closed_form",
]

SlowFunction = Callable[[Any, Any, Any, Any], Any]


def _sin_theta(u: np.ndarray) -> np.ndarray:
    return np.sqrt(np.maximum(1.0 - u * u, 0.0))


def _theta(u: np.ndarray) -> np.ndarray:
    return np.arccos(np.clip(u, -1.0, 1.0))


def _body_slow(top: Top, p: Any, q: Any, r: Any, g1: Any, g2: Any, g3: Any) -> tuple[Any, Any, Any]:
    """(Gz, H, theta) of a full state (floats, or arrays of batch members): Gz = K . gamma, H by (1.2)."""
    Gz = top.A * (p * g1 + q * g2) + top.C * r * g3
    H = 0.5 * (top.A * (p * p + q * q) + top.C * r * r) + top.mgl * g3
    if np.ndim(g3):
        return Gz, H, np.arccos(np.clip(g3, -1.0, 1.0))
    return Gz, H, math.acos(min(1.0, max(-1.0, g3)))


class Torque:
    """Base class of admissible perturbing torques (see the module docstring for the protocol).

    See Also
    --------
    ProportionalTorque, VerticalPlaneTorque, StarTorque, LinearDrag : the torques of the paper.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, eqs. (2.2)-(2.7).

    Examples
    --------
    A torque gives the averaged system the rates F1, F2, F3 of (2.7) of ``(Gz, H, r)`` at ``cos theta = u``.
    An axial torque ``M3 = -b r`` turns the vertical momentum at ``M3 u``, does work ``M3 r`` and spins down
    at ``M3 / C``; averaged over case 2's nutation it gives the rates of the :class:`StarTorque` example,
    ``dH/dtau = -b r² = -0.3`` and ``dr/dtau = -0.1 sqrt(3)``:

    >>> import numpy as np
    >>> from rigidbody import lagrange
    >>> class Axial(lagrange.Torque):
    ...     def slow_rates(self, top, Gz, H, r, u):
    ...         M3 = -0.1 * r + np.zeros_like(u)
    ...         return M3 * u, M3 * r, M3 / top.C
    >>> top = lagrange.PAPER_TOP
    >>> Gz, H, r = lagrange.integrals(top, *lagrange.paper_initial_state(2)[:5])
    >>> dGz, dH, dr = lagrange.averaged_slow_rates(top, Axial(), Gz, H, r)
    >>> print(f"{dH:.6f} {dr:.6f}")
    -0.300000 -0.173205
    """

    def slow_rates(self, top: Top, Gz: float, H: float, r: float, u: np.ndarray) -> tuple[np.ndarray, ...]:
        """The (corrected) right-hand sides F1, F2, F3 of (2.7) at ``cos(theta) = u``.

        Examples
        --------
        For the linear drag (3.1) at ``phi = 0``, (2.2) gives ``M1* = -a q``, ``M2* = -a (p² + q²)`` and
        ``M3* = -b r``, so ``F1 = -a q sin(theta) - b r cos(theta)``, ``F2 = M2* + M3* r``, ``F3 = M3*/C``:

        >>> import numpy as np
        >>> from rigidbody import lagrange
        >>> top, (a, b) = lagrange.Top(A=1.5, C=1.0, mgl=0.5), (0.125, 0.1)
        >>> p, q, r, theta = 0.3, 0.2, 1.7, 1.0
        >>> Gz, H, r = lagrange.integrals(top, p, q, r, 0.0, theta)
        >>> F = lagrange.LinearDrag(a, b).slow_rates(top, Gz, H, r, np.cos(theta))
        >>> print(" ".join(f"{x:.9f}" for x in F))
        -0.112888167 -0.305250000 -0.170000000
        >>> print(f"{-a * q * np.sin(theta) - b * r * np.cos(theta):.9f} {-a * (p*p + q*q) - b * r * r:.9f}")
        -0.112888167 -0.305250000
        """
        raise NotImplementedError

    def body_moments(
        self, top: Top, p: float, q: float, r: float, g1: float, g2: float, g3: float
    ) -> tuple[float, float, float]:
        """Body components (M1, M2, M3) of the torque at a full state (for :func:`simulate`).

        ``(g1, g2, g3)`` is the upward vertical in body axes. A torque given by its averaged combinations only
        (the base class, :class:`StarTorque`) has none and raises a ``TypeError``.

        Examples
        --------
        >>> from rigidbody import lagrange
        >>> top = lagrange.Top(A=1.5, C=1.0, mgl=0.5)
        >>> M = lagrange.LinearDrag(a=0.125, b=0.1).body_moments(top, 0.4, 0.2, 2.0, 0.0, 0.6, 0.8)
        >>> print(" ".join(f"{m:.6f}" for m in M))   # (-a p, -a q, -b r)
        -0.050000 -0.025000 -0.200000
        """
        raise TypeError(
            f"{type(self).__name__} defines only the averaged combinations (2.2); "
            "the full equations (1.1) need body moments: use ProportionalTorque or VerticalPlaneTorque"
        )

    def closed_means(self, xp: Any, top: Top, s: Any) -> tuple[Any, Any, Any] | None:
        """The nutation means ``<F1>, <F2>, <F3>`` of (2.7) in closed form at the chart state ``s`` (see the
        module docstring), or None: this torque has none and the averaging engine is used.

        Examples
        --------
        The linear drag has the closed form (3.4), which agrees with the engine's quadrature (the rates of the
        roots ``u1, u2, u3``):

        >>> from rigidbody import lagrange
        >>> top, drag = lagrange.PAPER_TOP, lagrange.PAPER_DRAG
        >>> closed = lagrange.averaged_rhs(top, drag, 0.0, 0.5, 2.0)
        >>> engine = lagrange.averaged_rhs(top, drag, 0.0, 0.5, 2.0, closed_form=False)
        >>> print(" ".join(f"{a:.9f}" for a in closed)); print(" ".join(f"{b:.9f}" for b in engine))
        -0.051796079 -0.040169934 -0.348203921
        -0.051796079 -0.040169934 -0.348203921
        """
        return None


def _check_callable(f: Any, name: str) -> None:
    if not callable(f):
        raise TypeError(f"{name} must be a callable (Gz, H, r, theta) -> value, got {type(f).__name__}")


def _zero(Gz: float, H: float, r: float, theta: Any) -> Any:
    return 0.0 * np.asarray(theta, dtype=float)


def _axial(M3: Any, name: str) -> Any:
    """The optional axial function of a torque class: validated, or identically zero when None."""
    if M3 is None:
        return _zero
    _check_callable(M3, name)
    return M3


class ProportionalTorque(Torque):
    r"""Torque of class (2.4): ``M1 = p f, M2 = q f, M3 = M3*`` with ``f, M3*`` functions of (Gz, H, r, theta).

    Then, by (2.3), ``M1* sin(theta) = f (Gz - C r u)/A`` and ``M2* = f [2(H - mgl u) - C r^2]/A``.

    Parameters
    ----------
    f : callable (Gz, H, r, theta) -> float or array
        The common factor of the equatorial components (2.4), (2.6).
    M3 : callable (Gz, H, r, theta) -> float or array, optional
        The axial component ``M3*`` (default 0).

    See Also
    --------
    LinearDrag : its member ``f = -a``, ``M3* = -b r`` (3.1), with a closed form.
    VerticalPlaneTorque, StarTorque : the other torque classes.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, eqs. (2.4), (2.6).

    Examples
    --------
    With ``f = -a`` and ``M3* = -b r`` it is the linear drag (3.1), so its averaged system, found by
    quadrature, is the closed form (3.4):

    >>> from rigidbody import lagrange
    >>> top, drag = lagrange.PAPER_TOP, lagrange.PAPER_DRAG
    >>> torque = lagrange.ProportionalTorque(lambda Gz, H, r, theta: -0.125 + 0 * theta,
    ...                                      lambda Gz, H, r, theta: -0.1 * r + 0 * theta)
    >>> quadrature = lagrange.averaged_rhs(top, torque, 0.0, 0.5, 2.0)
    >>> closed = lagrange.drag_rhs(top, drag, 0.0, 0.5, 2.0)
    >>> print(" ".join(f"{a:.6f}" for a in quadrature))
    -0.051796 -0.040170 -0.348204
    >>> print(" ".join(f"{b:.6f}" for b in closed))
    -0.051796 -0.040170 -0.348204
    """

    def __init__(self, f: SlowFunction, M3: SlowFunction | None = None) -> None:
        _check_callable(f, "f")
        self.f = f
        self.M3 = _axial(M3, "M3")

    def slow_rates(self, top: Top, Gz: float, H: float, r: float, u: np.ndarray) -> tuple[np.ndarray, ...]:
        u = np.asarray(u, dtype=float)
        th = _theta(u)
        f = np.asarray(self.f(Gz, H, r, th), dtype=float)
        m3 = np.asarray(self.M3(Gz, H, r, th), dtype=float)
        F1 = f * (Gz - top.C * r * u) / top.A + m3 * u
        F2 = f * (2.0 * (H - top.mgl * u) - top.C * r * r) / top.A + m3 * r
        F3 = m3 / top.C
        return np.broadcast_arrays(F1, F2, F3 * np.ones_like(u))

    def body_moments(
        self, top: Top, p: float, q: float, r: float, g1: float, g2: float, g3: float
    ) -> tuple[float, float, float]:
        Gz, H, th = _body_slow(top, p, q, r, g1, g2, g3)
        f = float(self.f(Gz, H, r, th))
        return p * f, q * f, float(self.M3(Gz, H, r, th))

    def body_moments_batch(
        self, top: Top, p: np.ndarray, q: np.ndarray, r: np.ndarray, g1: np.ndarray, g2: np.ndarray, g3: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """:meth:`body_moments` for arrays of batch members.

        Examples
        --------
        >>> import numpy as np
        >>> from rigidbody import lagrange
        >>> torque = lagrange.ProportionalTorque(lambda Gz, H, r, theta: -0.5 + 0 * theta)   # f = -0.5, M3 = 0
        >>> M1, M2, M3 = torque.body_moments_batch(lagrange.PAPER_TOP, np.array([0.2, 0.4]), np.array([0.1, 0.3]),
        ...                                        np.ones(2), np.zeros(2), np.full(2, 0.6), np.full(2, 0.8))
        >>> M1, M2, M3   # (p f, q f, 0) per member
        (array([-0.1, -0.2]), array([-0.05, -0.15]), array([0., 0.]))
        """
        Gz, H, th = _body_slow(top, p, q, r, g1, g2, g3)
        f = np.asarray(self.f(Gz, H, r, th), dtype=float)
        return p * f, q * f, np.broadcast_to(np.asarray(self.M3(Gz, H, r, th), dtype=float), p.shape)


class VerticalPlaneTorque(Torque):
    r"""Torque of class (2.5): ``M1 = F sin(phi), M2 = F cos(phi), M3 = M3*``.

    The equatorial part is directed along the projection of the vertical on the equatorial plane
    (body components ``(sin phi, cos phi, 0)``). By (2.3), ``M1* = F`` and
    ``M2* = F (Gz - C r u)/(A sin theta)``.

    Parameters
    ----------
    F : callable (Gz, H, r, theta) -> float or array
    M3 : callable (Gz, H, r, theta) -> float or array, optional (default 0)

    See Also
    --------
    ProportionalTorque, StarTorque : the other torque classes.

    Notes
    -----
    At ``sin(theta) = 0`` the direction (sin phi, cos phi) is undefined; :meth:`body_moments` then
    uses ``F = 0`` for the equatorial part (the torque is discontinuous there unless ``F -> 0``).

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, eq. (2.5).

    Examples
    --------
    A purely axial torque ``M3* = -b r`` (``F = 0``) does work ``M3 r = -b r²``, so in case 2
    (``r² = 3``, ``b = 0.1``) ``dH/dtau = -0.3`` and ``dr/dtau = -b r / C = -0.1 sqrt(3)``:

    >>> from rigidbody import lagrange
    >>> top = lagrange.PAPER_TOP
    >>> Gz, H, r = lagrange.integrals(top, *lagrange.paper_initial_state(2)[:5])
    >>> torque = lagrange.VerticalPlaneTorque(lambda Gz, H, r, theta: 0 * theta,
    ...                                       lambda Gz, H, r, theta: -0.1 * r + 0 * theta)
    >>> dGz, dH, dr = lagrange.averaged_slow_rates(top, torque, Gz, H, r)
    >>> print(f"{dH:.6f} {dr:.6f}")
    -0.300000 -0.173205
    """

    def __init__(self, F: SlowFunction, M3: SlowFunction | None = None) -> None:
        _check_callable(F, "F")
        self.F = F
        self.M3 = _axial(M3, "M3")

    def slow_rates(self, top: Top, Gz: float, H: float, r: float, u: np.ndarray) -> tuple[np.ndarray, ...]:
        u = np.asarray(u, dtype=float)
        th = _theta(u)
        st = _sin_theta(u)
        Fv = np.asarray(self.F(Gz, H, r, th), dtype=float)
        m3 = np.asarray(self.M3(Gz, H, r, th), dtype=float)
        num = Gz - top.C * r * u
        ratio = np.divide(num, top.A * st, out=np.zeros(np.broadcast(num, st).shape), where=st > 0.0)
        F1 = Fv * st + m3 * u
        F2 = Fv * ratio + m3 * r
        F3 = m3 / top.C
        return np.broadcast_arrays(F1, F2, F3 * np.ones_like(u))

    def body_moments(
        self, top: Top, p: float, q: float, r: float, g1: float, g2: float, g3: float
    ) -> tuple[float, float, float]:
        Gz, H, th = _body_slow(top, p, q, r, g1, g2, g3)
        st = math.hypot(g1, g2)
        m3 = float(self.M3(Gz, H, r, th))
        if st == 0.0:
            return 0.0, 0.0, m3
        Fv = float(self.F(Gz, H, r, th))
        return Fv * g1 / st, Fv * g2 / st, m3

    def body_moments_batch(
        self, top: Top, p: np.ndarray, q: np.ndarray, r: np.ndarray, g1: np.ndarray, g2: np.ndarray, g3: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """:meth:`body_moments` for arrays of batch members (the equatorial part 0 where ``sin theta = 0``).

        Examples
        --------
        The equatorial part ``F`` along the projection of the vertical, ``(g1, g2)/sin(theta)``, and none for
        the member whose axis is vertical:

        >>> import numpy as np
        >>> from rigidbody import lagrange
        >>> torque = lagrange.VerticalPlaneTorque(lambda Gz, H, r, theta: 0.5 + 0 * theta)   # F = 0.5, M3 = 0
        >>> M1, M2, M3 = torque.body_moments_batch(lagrange.PAPER_TOP, np.zeros(2), np.zeros(2), np.ones(2),
        ...                                        np.array([0.36, 0.0]), np.array([0.48, 0.0]), np.array([0.8, 1.0]))
        >>> np.round(M1, 12), np.round(M2, 12)
        (array([0.3, 0. ]), array([0.4, 0. ]))
        """
        Gz, H, th = _body_slow(top, p, q, r, g1, g2, g3)
        st = np.hypot(g1, g2)
        m3 = np.broadcast_to(np.asarray(self.M3(Gz, H, r, th), dtype=float), p.shape)
        Fv = np.asarray(self.F(Gz, H, r, th), dtype=float) / np.where(st > 0.0, st, 1.0)
        Fv = np.where(st > 0.0, Fv, 0.0)
        return Fv * g1, Fv * g2, m3


class StarTorque(Torque):
    r"""A torque given directly by the functions ``M1*, M2*, M3*`` of (2.2) (averaging only).

    Parameters
    ----------
    M1s, M2s, M3s : callable (Gz, H, r, theta) -> float or array
        ``M1* = M1 sin(phi) + M2 cos(phi)``, ``M2* = M1 p + M2 q``, ``M3* = M3``.

    See Also
    --------
    ProportionalTorque, VerticalPlaneTorque : torque classes that also give body moments for :func:`simulate`.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, eq. (2.2).

    Examples
    --------
    A purely axial torque ``M3* = -b r`` does work ``M3 r = -b r²``: in case 2 (``r² = 3``,
    ``b = 0.1``) ``dH/dtau = -0.3`` and ``dr/dtau = -b r / C = -0.1 sqrt(3)``:

    >>> from rigidbody import lagrange
    >>> top = lagrange.PAPER_TOP
    >>> Gz, H, r = lagrange.integrals(top, *lagrange.paper_initial_state(2)[:5])
    >>> zero = lambda Gz, H, r, theta: 0 * theta
    >>> torque = lagrange.StarTorque(zero, zero, lambda Gz, H, r, theta: -0.1 * r + 0 * theta)
    >>> dGz, dH, dr = lagrange.averaged_slow_rates(top, torque, Gz, H, r)
    >>> print(f"{dH:.6f} {dr:.6f}")
    -0.300000 -0.173205
    """

    def __init__(self, M1s: SlowFunction, M2s: SlowFunction, M3s: SlowFunction | None = None) -> None:
        _check_callable(M1s, "M1s")
        _check_callable(M2s, "M2s")
        self.M1s, self.M2s = M1s, M2s
        self.M3s = _axial(M3s, "M3s")

    def slow_rates(self, top: Top, Gz: float, H: float, r: float, u: np.ndarray) -> tuple[np.ndarray, ...]:
        u = np.asarray(u, dtype=float)
        th = _theta(u)
        m1 = np.asarray(self.M1s(Gz, H, r, th), dtype=float)
        m2 = np.asarray(self.M2s(Gz, H, r, th), dtype=float)
        m3 = np.asarray(self.M3s(Gz, H, r, th), dtype=float)
        F1 = m1 * _sin_theta(u) + m3 * u
        F2 = m2 + m3 * r
        F3 = m3 / top.C
        return np.broadcast_arrays(F1, F2, F3 * np.ones_like(u))


@dataclass(frozen=True)
class LinearDrag(Torque):
    r"""Linear dissipative torque (3.1): ``M1 = -a p, M2 = -a q, M3 = -b r`` with ``a, b > 0``.

    A special case of class (2.4) (``f = -a``, ``M3* = -b r``). Its averaged system has the closed
    form (3.4) (:func:`rigidbody.lagrange.drag_rhs`), and ``r = r0 exp(-eps b t / C)`` exactly (3.3).

    Parameters
    ----------
    a : float
        Equatorial damping coefficient, ``a >= 0``.
    b : float
        Axial damping coefficient, ``b >= 0``.

    See Also
    --------
    ProportionalTorque : the class (2.4) it belongs to.
    drag_rhs : its closed-form averaged system (3.4).

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, eqs. (3.1)-(3.4).

    Examples
    --------
    The axial spin decays as ``r = r0 exp(-b tau / C)`` (3.3): ``dr/dtau = -b r / C = -0.1 sqrt(3)``
    for the paper's case 2:

    >>> from rigidbody import lagrange
    >>> top = lagrange.PAPER_TOP
    >>> Gz, H, r = lagrange.integrals(top, *lagrange.paper_initial_state(2)[:5])
    >>> rates = lagrange.averaged_slow_rates(top, lagrange.LinearDrag(a=0.125, b=0.1), Gz, H, r)
    >>> print(f"{rates[2]:.6f}")
    -0.173205
    """

    a: float
    b: float

    def __post_init__(self) -> None:
        for name in ("a", "b"):
            val = getattr(self, name)
            if isinstance(val, bool) or not isinstance(val, (int, float, np.floating, np.integer)):
                raise TypeError(f"LinearDrag.{name} must be a real number, got {type(val).__name__}")
            if not math.isfinite(float(val)) or float(val) < 0.0:
                raise ValueError(f"LinearDrag.{name} must be finite and >= 0, got {val!r}")
            object.__setattr__(self, name, float(val))

    def slow_rates(self, top: Top, Gz: float, H: float, r: float, u: np.ndarray) -> tuple[np.ndarray, ...]:
        u = np.asarray(u, dtype=float)
        a, b = self.a, self.b
        F1 = -a * (Gz - top.C * r * u) / top.A - b * r * u
        F2 = -a * (2.0 * (H - top.mgl * u) - top.C * r * r) / top.A - b * r * r
        F3 = -b * r / top.C
        return np.broadcast_arrays(F1, F2, F3 * np.ones_like(u))

    def closed_means(self, xp: Any, top: Top, s: Any) -> tuple[Any, Any, Any]:
        """(3.4): ``<F> = F(<u>)`` (``F`` is linear in ``u``), evaluated without cancellation from the u chart's
        gaps (:func:`rigidbody.lagrange._kernel.drag_means`) or the GHr chart's root pair (``drag_means_g``).

        Examples
        --------
        ``F3 = -b r/C`` does not depend on the nutation, so its mean is itself (the spin decays as in (3.3)):

        >>> from rigidbody import lagrange
        >>> top, drag = lagrange.PAPER_TOP, lagrange.PAPER_DRAG
        >>> Gz, H, r = lagrange.from_roots(top, 0.0, 0.5, 2.0)
        >>> print(f"{lagrange.averaged_slow_rates(top, drag, Gz, H, r)[2]:.9f} {-drag.b * r / top.C:.9f}")
        -0.173205081 -0.173205081
        """
        if isinstance(s, _k.UState):
            return _k.drag_means(xp, top.A, top.C, top.mgl, self.a, self.b, s)
        return _k.drag_means_g(xp, top.A, top.C, top.mgl, self.a, self.b, s)

    def body_moments(
        self, top: Top, p: float, q: float, r: float, g1: float, g2: float, g3: float
    ) -> tuple[float, float, float]:
        return -self.a * p, -self.a * q, -self.b * r

    def body_moments_batch(
        self, top: Top, p: np.ndarray, q: np.ndarray, r: np.ndarray, g1: np.ndarray, g2: np.ndarray, g3: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """:meth:`body_moments` for arrays of batch members.

        Examples
        --------
        >>> import numpy as np
        >>> from rigidbody import lagrange
        >>> M = lagrange.LinearDrag(a=0.125, b=0.1).body_moments_batch(
        ...     lagrange.PAPER_TOP, np.array([0.4, 0.8]), np.array([0.2, 0.0]), np.array([2.0, 1.0]), *np.zeros((3, 2)))
        >>> np.round(M, 12)   # (-a p, -a q, -b r) per member
        array([[-0.05 , -0.1  ],
               [-0.025, -0.   ],
               [-0.2  , -0.1  ]])
        """
        return -self.a * p, -self.a * q, -self.b * r


def check_torque(torque: Any, name: str = "torque") -> Torque:
    """Validate a torque argument (anything implementing :meth:`Torque.slow_rates`)."""
    if not callable(getattr(torque, "slow_rates", None)):
        raise TypeError(
            f"{name} must implement slow_rates(top, Gz, H, r, u) (see rigidbody.lagrange.Torque), "
            f"got {type(torque).__name__}"
        )
    return torque


def has_closed_form(torque: Any) -> bool:
    """Whether ``torque`` declares a closed-form average (a ``closed_means`` of its own, see :class:`Torque`).

    See Also
    --------
    averaged_rhs : which uses the closed form when there is one.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, eq. (3.4).

    Examples
    --------
    The linear drag (3.1) has the closed form (3.4); a general torque of class (2.4) has none:

    >>> from rigidbody import lagrange
    >>> lagrange.has_closed_form(lagrange.PAPER_DRAG)
    True
    >>> lagrange.has_closed_form(lagrange.ProportionalTorque(lambda Gz, H, r, theta: -0.125 + 0 * theta))
    False
    """
    hook = getattr(type(torque), "closed_means", None)
    return callable(hook) and hook is not Torque.closed_means


def closed_form_choice(torque: Any, closed_form: bool | None) -> bool:
    """The rule of the ``closed_form`` option: default the torque's capability, ``True`` only for a torque that
    has a closed form (TypeError naming the torque otherwise), ``False`` the engine."""
    has = has_closed_form(torque)
    if closed_form is None:
        return has
    if closed_form and not has:
        raise TypeError(f"closed_form=True needs a torque with a closed-form average (a closed_means method, see "
                        f"rigidbody.lagrange.Torque); {type(torque).__name__} has none")
    return bool(closed_form)
