"""Closed forms of Krivtsov (2000): first integrals (3.3)-(3.5), curvature (4.5), quasi-coordinates (5.1)."""

from __future__ import annotations

import math
import numbers
from typing import Any

import numpy as np

from ..core.validate import real
from ._model import Body, Medium, check_body_medium

__all__ = [
    "F4",
    "Omega",
    "curvature",
    "f3",
    "limits",
    "omega2",
    "quasi_coordinates",
    "spiral_radius",
    "v",
]


def _time(t: Any) -> np.ndarray:
    try:
        arr = np.asarray(t, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(f"t must be a real number or an array of times >= 0, got {type(t).__name__}") from None
    if np.any(np.isnan(arr)) or np.any(arr < 0):
        raise ValueError("t must be >= 0 (t = inf is allowed and gives the limit t -> infinity)")
    return arr


def _out(x: np.ndarray) -> Any:
    return float(x) if np.ndim(x) == 0 else x


def as_scalar(x: Any) -> Any:
    """A 0-d array is accepted as the number it holds."""
    return x.item() if isinstance(x, np.ndarray) and x.ndim == 0 else x


def _Omega0(Omega0: Any) -> float:
    return real(as_scalar(Omega0), "Omega0")


def _v0(v0: Any) -> float:
    v0 = as_scalar(v0)
    if isinstance(v0, (bool, np.bool_)) or not isinstance(v0, (numbers.Real, np.floating, np.integer)):
        raise TypeError(f"v0 = |ndot0| must be a real number >= 0, got {type(v0).__name__}")
    val = float(v0)
    if not (math.isfinite(val) and val >= 0):
        raise ValueError(f"v0 = |ndot0| must be finite and >= 0, got {v0!r}")
    return val


def Omega(body: Body, medium: Medium, Omega0: float, t: Any) -> Any:
    """Spin ``Ω = ω·n``, eq. (3.3): ``Ω0 exp(-B3 t/θ3)``. Vectorised in ``t >= 0``.

    Parameters
    ----------
    body, medium : Body, Medium
    Omega0 : float
        Initial spin.
    t : array_like
        Times ``>= 0``.

    Returns
    -------
    float or ndarray

    See Also
    --------
    v : the speed of the axis tip.
    simulate : the full equations, whose ``Omega`` field this is.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, eq. (3.3).

    Examples
    --------
    After one e-folding time ``θ3/B3 = 10``:

    >>> import math
    >>> from rigidbody import viscous
    >>> body, medium = viscous.Body(theta12=2.0, theta3=1.0), viscous.Medium(B12=0.4, B3=0.1)
    >>> print(f"{viscous.Omega(body, medium, 6.0, 10.0):.12f} {6.0 / math.e:.12f}")
    2.207276647029 2.207276647029
    """
    check_body_medium(body, medium)
    tt = _time(t)
    return _out(_Omega0(Omega0) * np.exp(-(medium.B3 / body.theta3) * tt))


def v(body: Body, medium: Medium, v0: float, t: Any) -> Any:
    """Speed of the axis tip ``v = |ṅ|``, eqs. (3.3)-(3.4): ``v0 exp(-B12 t/θ12)``.

    Parameters
    ----------
    body, medium : Body, Medium
    v0 : float
        Initial speed ``|ndot0| >= 0``.
    t : array_like
        Times ``>= 0``.

    Returns
    -------
    float or ndarray

    See Also
    --------
    Omega : the spin.
    quasi_coordinates : its integral, the arc length ``s``.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, eqs. (3.3)-(3.4).

    Examples
    --------
    After one e-folding time ``θ12/B12 = 5``:

    >>> import math
    >>> from rigidbody import viscous
    >>> body, medium = viscous.Body(theta12=2.0, theta3=1.0), viscous.Medium(B12=0.4, B3=0.1)
    >>> print(f"{viscous.v(body, medium, 2.0, 5.0):.12f} {2.0 / math.e:.12f}")
    0.735758882343 0.735758882343
    """
    check_body_medium(body, medium)
    tt = _time(t)
    return _out(_v0(v0) * np.exp(-(medium.B12 / body.theta12) * tt))


def f3(body: Body, medium: Medium, Omega0: float, v0: float, t: Any) -> Any:
    """``f³ = n·(ṅ×n̈) = (θ3/θ12) Ω v²``, eq. (3.5).

    Parameters
    ----------
    body, medium : Body, Medium
    Omega0, v0 : float
        Initial spin and speed of the axis tip.
    t : array_like
        Times ``>= 0``.

    Returns
    -------
    float or ndarray

    See Also
    --------
    F4, omega2 : the other invariants of section 3.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, eq. (3.5).

    Examples
    --------
    At ``t = 0``: ``(1/2) 6 2² = 12``:

    >>> from rigidbody import viscous
    >>> body, medium = viscous.Body(theta12=2.0, theta3=1.0), viscous.Medium(B12=0.4, B3=0.1)
    >>> viscous.f3(body, medium, 6.0, 2.0, 0.0)
    12.0
    """
    om = np.asarray(Omega(body, medium, Omega0, t))
    vv = np.asarray(v(body, medium, v0, t))
    with np.errstate(over="ignore"):  # saturates to inf for absurdly large rates, like curvature
        return _out(body.theta3 / body.theta12 * om * vv * vv)


def F4(body: Body, medium: Medium, Omega0: float, v0: float, t: Any) -> Any:
    """``F⁴ = n̈·n̈ = f⁶/v² + v̇² + v⁴``, section 3 (after 3.6).

    Evaluated as ``(v θ3 Ω/θ12)² + (v B12/θ12)² + v⁴``, which is regular at ``v = 0``.

    Parameters
    ----------
    body, medium : Body, Medium
    Omega0, v0 : float
        Initial spin and speed of the axis tip.
    t : array_like
        Times ``>= 0``.

    Returns
    -------
    float or ndarray

    See Also
    --------
    f3, omega2 : the other invariants of section 3.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, section 3.

    Examples
    --------
    At ``t = 0``: ``(2 0.5 6)² + (2 0.2)² + 2⁴ = 36 + 0.16 + 16``:

    >>> from rigidbody import viscous
    >>> body, medium = viscous.Body(theta12=2.0, theta3=1.0), viscous.Medium(B12=0.4, B3=0.1)
    >>> print(f"{viscous.F4(body, medium, 6.0, 2.0, 0.0):.12f}")
    52.160000000000
    """
    om = np.asarray(Omega(body, medium, Omega0, t))
    vv = np.asarray(v(body, medium, v0, t))
    w = body.theta3 / body.theta12 * om
    a = medium.B12 / body.theta12
    with np.errstate(over="ignore", invalid="ignore"):  # saturates to inf for absurdly large rates
        return _out((vv * w) ** 2 + (vv * a) ** 2 + vv**4)


def omega2(body: Body, medium: Medium, Omega0: float, v0: float, t: Any) -> Any:
    """``ω·ω = v² + Ω²``, end of section 3.

    Parameters
    ----------
    body, medium : Body, Medium
    Omega0, v0 : float
        Initial spin and speed of the axis tip.
    t : array_like
        Times ``>= 0``.

    Returns
    -------
    float or ndarray

    See Also
    --------
    f3, F4 : the other invariants of section 3.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, section 3.

    Examples
    --------
    >>> from rigidbody import viscous
    >>> body, medium = viscous.Body(theta12=2.0, theta3=1.0), viscous.Medium(B12=0.4, B3=0.1)
    >>> viscous.omega2(body, medium, 6.0, 2.0, 0.0)  # 2² + 6²
    40.0
    """
    om = np.asarray(Omega(body, medium, Omega0, t))
    vv = np.asarray(v(body, medium, v0, t))
    with np.errstate(over="ignore"):  # saturates to inf for absurdly large rates
        return _out(vv * vv + om * om)


def _log_k(body: Body, medium: Medium, Omega0: float, v0: float, tt: np.ndarray) -> np.ndarray:
    """``log|k(t)|`` of (4.5); ``t = inf`` gives ``±inf`` (or the constant in Routh's case)."""
    lam = medium.B12 / body.theta12 - medium.B3 / body.theta3
    x0 = math.log(body.theta3 * abs(Omega0) / (body.theta12 * v0))
    if lam == 0.0:
        return np.full_like(tt, x0)
    return x0 + lam * tt


def curvature(body: Body, medium: Medium, Omega0: float, v0: float, t: Any) -> Any:
    """Spherical (geodesic) curvature of the axis path, eq. (4.5).

    ``k = (θ3 Ω0)/(θ12 v0) exp((B12/θ12 - B3/θ3) t)``, with the sign of ``Ω0``: ``k > 0`` turns the
    path counterclockwise seen from outside the sphere (towards ``g = n×τ``).

    Parameters
    ----------
    body, medium : Body, Medium
    Omega0 : float
        Initial spin ``Ω0 = ω0·n0``.
    v0 : float
        Initial speed of the axis tip ``|ṅ0| >= 0``.
    t : array_like
        Times ``>= 0``.

    Returns
    -------
    float or ndarray
        ``k(t)``. ``Ω0 = 0`` gives 0 (a great circle). ``v0 = 0`` with ``Ω0 != 0`` gives ``±inf``: the
        axis stands still (a circle of radius 0). Overflow for huge ``t`` saturates to ``±inf``.

    Raises
    ------
    ValueError
        ``v0 = 0`` and ``Ω0 = 0``: a body at rest has no path, its curvature is undefined.

    See Also
    --------
    spiral_radius : the radius (5.2) of the osculating circle.
    regime : the sign of the exponent.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, eqs. (4.3)-(4.5).

    Examples
    --------
    ``k0 = (1 · 6)/(2 · 2) = 1.5``, growing like ``exp((0.2 - 0.1) t)``: ``1.5 e`` at ``t = 10``:

    >>> import math
    >>> from rigidbody import viscous
    >>> body, medium = viscous.Body(theta12=2.0, theta3=1.0), viscous.Medium(B12=0.4, B3=0.1)
    >>> print(*(f"{k:.12f}" for k in viscous.curvature(body, medium, 6.0, 2.0, [0.0, 10.0])), f"{1.5 * math.e:.12f}")
    1.500000000000 4.077422742689 4.077422742689
    """
    check_body_medium(body, medium)
    tt = _time(t)
    Om0, vv0 = _Omega0(Omega0), _v0(v0)
    if vv0 == 0.0:
        if Om0 == 0.0:
            raise ValueError("curvature is undefined for a body at rest (v0 = 0 and Omega0 = 0)")
        return _out(np.full_like(tt, math.copysign(math.inf, Om0)))
    if Om0 == 0.0:
        return _out(np.zeros_like(tt))
    x = _log_k(body, medium, Om0, vv0, tt)
    with np.errstate(over="ignore"):
        return _out(math.copysign(1.0, Om0) * np.exp(x))


def spiral_radius(body: Body, medium: Medium, Omega0: float, v0: float, t: Any) -> Any:
    """Radius of a turn of the spiral, eq. (5.2): ``R = 1/K = 1/sqrt(1 + k²)``.

    ``R = sin ρ`` is the chordal radius of the osculating small circle (angular radius ``ρ``,
    ``cot ρ = |k|``). Computed in log form: finite for all ``t``; ``v0 = 0`` gives ``R = 0``.

    Parameters
    ----------
    body, medium : Body, Medium
    Omega0, v0 : float
        Initial spin and speed of the axis tip.
    t : array_like
        Times ``>= 0``.

    Returns
    -------
    float or ndarray

    See Also
    --------
    curvature : the curvature ``k`` it is computed from.
    turn : one turn of the spiral, whose solid angle is about ``2π(1 - sqrt(1 - R²))``.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, eq. (5.2).

    Examples
    --------
    With ``k0 = 1.5``: ``R0 = 1/sqrt(3.25)``; the contracting spiral shrinks to a point:

    >>> import math
    >>> from rigidbody import viscous
    >>> body, medium = viscous.Body(theta12=2.0, theta3=1.0), viscous.Medium(B12=0.4, B3=0.1)
    >>> print(*(f"{r:.12f}" for r in viscous.spiral_radius(body, medium, 6.0, 2.0, [0.0, math.inf])),
    ...       f"{1 / math.sqrt(3.25):.12f}")
    0.554700196225 0.000000000000 0.554700196225
    """
    check_body_medium(body, medium)
    tt = _time(t)
    Om0, vv0 = _Omega0(Omega0), _v0(v0)
    if vv0 == 0.0:
        if Om0 == 0.0:
            raise ValueError("spiral radius is undefined for a body at rest (v0 = 0 and Omega0 = 0)")
        return _out(np.zeros_like(tt))
    if Om0 == 0.0:
        return _out(np.ones_like(tt))
    x = _log_k(body, medium, Om0, vv0, tt)
    return _out(np.exp(-0.5 * np.logaddexp(0.0, 2.0 * x)))


def quasi_coordinates(body: Body, medium: Medium, Omega0: float, v0: float, t: Any) -> tuple[Any, Any, Any]:
    """Quasi-coordinates ``(s, ξ, ζ)``, eq. (5.1) in its verified form.

    ``ṡ = v``, ``ξ̇ = v k = (θ3/θ12) Ω``, ``ζ̇ = Ω``, all zero at ``t = 0``:

    * ``s = (θ12 v0/B12)(1 - exp(-B12 t/θ12))`` — arc length of the axis path;
    * ``ξ = (θ3² Ω0/(θ12 B3))(1 - exp(-B3 t/θ3))`` — turning angle of the path's tangent
      (printed with ``B12`` in the denominator: a misprint, see :doc:`/errata`);
    * ``ζ = (θ3 Ω0/B3)(1 - exp(-B3 t/θ3))`` — turning of the body about ``n`` relative to a
      parallel-transported frame.

    ``t = inf`` gives :func:`limits`.

    Parameters
    ----------
    body, medium : Body, Medium
    Omega0, v0 : float
        Initial spin and speed of the axis tip.
    t : array_like
        Times ``>= 0`` (``inf`` allowed).

    Returns
    -------
    s, xi, zeta : float or ndarray

    See Also
    --------
    limits : the values at ``t = inf``.
    simulate : the full equations, whose ``zeta`` field is ``ζ``.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, eq. (5.1) (corrected: see :doc:`/errata`).

    Examples
    --------
    Half of the arc length ``s∞ = θ12 v0/B12 = 10`` is run in ``ln 2 θ12/B12`` (here ``5 ln 2``):

    >>> import math
    >>> from rigidbody import viscous
    >>> body, medium = viscous.Body(theta12=2.0, theta3=1.0), viscous.Medium(B12=0.4, B3=0.1)
    >>> s, xi, zeta = viscous.quasi_coordinates(body, medium, 6.0, 2.0, 5 * math.log(2))
    >>> print(f"{s:.12f}")
    5.000000000000
    >>> viscous.quasi_coordinates(body, medium, 6.0, 2.0, math.inf)
    (10.0, 30.0, 60.0)
    """
    check_body_medium(body, medium)
    tt = _time(t)
    Om0, vv0 = _Omega0(Omega0), _v0(v0)
    a = medium.B12 / body.theta12
    b = medium.B3 / body.theta3
    e_a = -np.expm1(-a * tt)
    e_b = -np.expm1(-b * tt)
    s = vv0 / a * e_a
    zeta = Om0 / b * e_b
    xi = body.theta3 / body.theta12 * zeta
    return _out(s), _out(xi), _out(zeta)


def limits(body: Body, medium: Medium, Omega0: float, v0: float) -> tuple[float, float, float]:
    """Limits of (5.1) as ``t → ∞``: ``s∞ = θ12 v0/B12`` (length of the spiral),
    ``ξ∞ = θ3² Ω0/(θ12 B3)`` (total turning of the spiral), ``ζ∞ = θ3 Ω0/B3`` (total turn of the body
    about ``n`` relative to parallel transport).

    Parameters
    ----------
    body, medium : Body, Medium
    Omega0, v0 : float
        Initial spin and speed of the axis tip.

    Returns
    -------
    (float, float, float)
        ``(s∞, ξ∞, ζ∞)``.

    See Also
    --------
    quasi_coordinates : the quasi-coordinates at any time.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, eq. (5.1) (corrected: see :doc:`/errata`).

    Examples
    --------
    ``s∞ = 2 · 2/0.4``, ``ξ∞ = 1 · 6/(2 · 0.1)``, ``ζ∞ = 1 · 6/0.1``:

    >>> from rigidbody import viscous
    >>> body, medium = viscous.Body(theta12=2.0, theta3=1.0), viscous.Medium(B12=0.4, B3=0.1)
    >>> viscous.limits(body, medium, 6.0, 2.0)
    (10.0, 30.0, 60.0)
    """
    check_body_medium(body, medium)
    Om0, vv0 = _Omega0(Omega0), _v0(v0)
    s_inf = body.theta12 * vv0 / medium.B12
    zeta_inf = body.theta3 * Om0 / medium.B3
    xi_inf = body.theta3 / body.theta12 * zeta_inf
    return s_inf, xi_inf, zeta_inf
