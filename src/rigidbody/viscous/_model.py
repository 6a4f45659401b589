"""Body, medium and the ball-and-rod model of Krivtsov (2000), eqs. (1.1), (1.2) and section 2."""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass
from typing import Literal

import numpy as np

from ..core.validate import positive

__all__ = ["Body", "Medium", "ball_and_rod", "decay_rates", "regime"]

Regime = Literal["contracting", "unwinding", "circle"]


@dataclass(frozen=True)
class Body:
    """Axisymmetric rigid body, eq. (1.2): ``θ = θ12 (E - nn) + θ3 nn``.

    Parameters
    ----------
    theta12 : float
        Equatorial moment of inertia, > 0.
    theta3 : float
        Polar moment of inertia (about the symmetry axis ``n``), ``0 < θ3 <= 2 θ12``
        (triangle inequality of the principal moments; equality is a flat body).

    See Also
    --------
    Medium : the viscous torque.
    ball_and_rod : the body and medium of the paper's model (fig. 1).

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, eq. (1.2).

    Examples
    --------
    >>> from rigidbody import viscous
    >>> viscous.Body(theta12=2.0, theta3=1.0)
    Body(theta12=2.0, theta3=1.0)
    >>> viscous.Body(theta12=1.0, theta3=3.0)
    Traceback (most recent call last):
        ...
    ValueError: theta3 must satisfy theta3 <= 2*theta12 (triangle inequality), got theta3=3.0, theta12=1.0: ...
    """

    theta12: float
    theta3: float

    def __post_init__(self) -> None:
        t12 = positive(self.theta12, "theta12")
        t3 = positive(self.theta3, "theta3")
        if t3 > 2.0 * t12 * (1.0 + 1e-14):
            raise ValueError(
                f"theta3 must satisfy theta3 <= 2*theta12 (triangle inequality), got theta3={t3!r}, "
                f"theta12={t12!r}: no rigid body has these moments"
            )
        object.__setattr__(self, "theta12", t12)
        object.__setattr__(self, "theta3", t3)


@dataclass(frozen=True)
class Medium:
    """Linearly viscous torque, eq. (1.1): ``M = -B·ω``, ``B = B12 (E - nn) + B3 nn``.

    Parameters
    ----------
    B12 : float
        Equatorial viscosity coefficient, > 0.
    B3 : float
        Axial viscosity coefficient, > 0.

    See Also
    --------
    Body : the moments of inertia.
    regime : the kind of path the pair gives.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, eq. (1.1).

    Examples
    --------
    >>> from rigidbody import viscous
    >>> viscous.Medium(B12=0.4, B3=0.1)
    Medium(B12=0.4, B3=0.1)
    >>> viscous.Medium(B12=0.4, B3=-0.1)
    Traceback (most recent call last):
        ...
    ValueError: B3 must be finite and > 0, got -0.1
    """

    B12: float
    B3: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "B12", positive(self.B12, "B12"))
        object.__setattr__(self, "B3", positive(self.B3, "B3"))


def check_body_medium(body: Body, medium: Medium) -> None:
    """Refuse a body or a medium of the wrong type (TypeError naming which)."""
    if not isinstance(body, Body):
        raise TypeError(f"body must be a viscous.Body, got {type(body).__name__}")
    if not isinstance(medium, Medium):
        raise TypeError(f"medium must be a viscous.Medium, got {type(medium).__name__}")


def decay_rates(body: Body, medium: Medium) -> tuple[float, float]:
    """Return ``(B12/θ12, B3/θ3)``: the decay rates of ``v`` and ``Ω``, eq. (3.3).

    Parameters
    ----------
    body, medium : Body, Medium

    Returns
    -------
    (float, float)

    See Also
    --------
    v, Omega : the decays themselves.
    regime : the comparison of the two rates.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, eqs. (3.3)-(3.4).

    Examples
    --------
    >>> from rigidbody import viscous
    >>> body, medium = viscous.Body(theta12=2.0, theta3=1.0), viscous.Medium(B12=0.4, B3=0.1)
    >>> viscous.decay_rates(body, medium)
    (0.2, 0.1)
    """
    check_body_medium(body, medium)
    return medium.B12 / body.theta12, medium.B3 / body.theta3


def regime(body: Body, medium: Medium, rtol: float = 1e-12) -> Regime:
    """Classify the path of the symmetry axis, section 4 after eq. (4.5).

    Parameters
    ----------
    body, medium : Body, Medium
    rtol : float
        Relative tolerance for the equality ``B12/θ12 = B3/θ3`` (Routh's case, eq. 1.3).

    Returns
    -------
    {'contracting', 'unwinding', 'circle'}
        ``B12/θ12 > B3/θ3``: k → ∞, a spiral contracting to a point (fig. 2);
        ``B12/θ12 < B3/θ3``: k → 0, a spiral unwinding to a great circle (fig. 3);
        equal within ``rtol``: a circle, ``K = K0 exp(-αt)``.

    See Also
    --------
    decay_rates : the two rates compared.
    curvature : the curvature (4.5), whose exponent is their difference.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, eqs. (1.3), (4.5) and section 4.

    Examples
    --------
    >>> from rigidbody import viscous
    >>> body = viscous.Body(theta12=2.0, theta3=1.0)
    >>> [viscous.regime(body, viscous.Medium(B12=b12, B3=0.1)) for b12 in (0.4, 0.1, 0.2)]
    ['contracting', 'unwinding', 'circle']
    """
    if not (isinstance(rtol, numbers.Real) and 0.0 <= rtol < 1.0):
        raise ValueError(f"rtol must be in [0, 1), got {rtol!r}")
    a, b = decay_rates(body, medium)
    if abs(a - b) <= rtol * max(a, b):
        return "circle"
    return "contracting" if a > b else "unwinding"


def ball_and_rod(
    N: int = 4,
    a: float = 1.0,
    b: float = 0.5,
    beta: float = 0.1,
    mass: float = 1.0,
    *,
    ball_radius: float = 0.0,
    rod_mass: float = 0.0,
    spoke_mass: float = 0.0,
) -> tuple[Body, Medium]:
    """The physical model of fig. 1: balls on a circle and on the axis, each with drag ``-βv``.

    ``N`` equal balls lie on a circle of radius ``a`` about the centre ``C`` in the plane normal to the
    rod ``AB``; two more sit on the rod at ``±b``. Section 2, eq. (2.2) and the result after it:
    ``B12 = β (N a²/2 + 2 b²)``, ``B3 = β N a²``.

    Parameters
    ----------
    N : int
        Number of balls on the circle, ``N >= 3`` (N = 2 is not transversely isotropic).
    a, b : float
        Circle radius (> 0) and half-length of the rod (>= 0).
    beta : float
        Viscous coefficient of one ball, > 0.
    mass : float
        Mass of one ball, > 0.
    ball_radius : float, optional
        Radius of a (solid, homogeneous) ball; its own inertia ``(2/5) m r²`` is added. Drag is
        still ``-βv`` (no viscous torque on a spinning ball), as in the paper. Balls may touch but not
        overlap: ``ball_radius <= min(a sin(π/N), b, sqrt(a² + b²)/2)``, else ``ValueError``.
    rod_mass : float, optional
        Mass of the thin axial rod AB (length ``2b``): adds ``rod_mass b²/3`` to ``θ12``.
    spoke_mass : float, optional
        Mass of each of the ``N`` thin spokes from C to the balls: adds ``N m_s a²/6`` to ``θ12``
        and ``N m_s a²/3`` to ``θ3``.

    Returns
    -------
    (Body, Medium)

    Notes
    -----
    With point balls and massless rods ``B = (β/m) θ`` exactly: Routh's circle. With ball radius
    only, the spiral contracts iff ``b² > N a²/4``; rod mass pushes towards unwinding. This verdict
    depends on the paper's drag model: adding the Stokes rotational drag of each ball,
    ``(4/3) β r²`` to ``B12`` and ``B3``, reverses it (see :doc:`/viscous`).

    See Also
    --------
    regime : the kind of path of the body in the medium.
    rigidbody.plotting.ball_and_rod_sketch : draws the structure.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, section 2, eq. (2.2).

    Examples
    --------
    ``N = 4`` point balls on a circle of radius 1, rod half-length 0.5: ``B12 = 0.1 (4/2 + 2 0.25) = 0.25``,
    ``B3 = 0.1 4 = 0.4``, and ``θ = (m/β) B``: Routh's circle. Solid balls of radius 0.3 tip the balance, by
    ``b² > N a²/4``:

    >>> from rigidbody import viscous
    >>> body, medium = viscous.ball_and_rod(4, 1.0, 0.5, beta=0.1, mass=1.0)
    >>> body, medium, viscous.regime(body, medium)
    (Body(theta12=2.5, theta3=4.0), Medium(B12=0.25, B3=0.4), 'circle')
    >>> [viscous.regime(*viscous.ball_and_rod(4, 1.0, b, ball_radius=0.3)) for b in (1.5, 0.5)]
    ['contracting', 'unwinding']
    """
    if isinstance(N, bool) or not isinstance(N, numbers.Integral):
        raise TypeError(f"N must be an int >= 3, got {type(N).__name__}")
    N = int(N)
    if N < 3:
        raise ValueError(f"N must be >= 3 (N balls on a circle; N = 2 is not axisymmetric), got {N}")
    a = positive(a, "a")
    if isinstance(b, (bool, np.bool_)) or not isinstance(b, (numbers.Real, np.floating, np.integer)):
        raise TypeError(f"b must be a real number >= 0, got {type(b).__name__}")
    if not (math.isfinite(b) and b >= 0):
        raise ValueError(f"b must be finite and >= 0, got {b!r}")
    beta = positive(beta, "beta")
    m = positive(mass, "mass")
    for name, val in (("ball_radius", ball_radius), ("rod_mass", rod_mass), ("spoke_mass", spoke_mass)):
        if isinstance(val, (bool, np.bool_)) or not isinstance(val, (numbers.Real, np.floating, np.integer)):
            raise TypeError(f"{name} must be a real number >= 0, got {type(val).__name__}")
        if not (math.isfinite(val) and val >= 0):
            raise ValueError(f"{name} must be finite and >= 0, got {val!r}")
    b = float(b)
    rb = float(ball_radius)
    if rb > 0.0:
        # the balls are solid: centres at least 2 r apart (touching allowed; a relative 1e-12 of slack for
        # rounding). Neighbours on the circle: chord 2 a sin(pi/N); the two axial balls: 2 b; an axial and a
        # circle ball: sqrt(a^2 + b^2).
        gaps = (
            ("neighbouring balls on the circle (2 a sin(pi/N))", 2.0 * a * math.sin(math.pi / N)),
            ("the two balls on the rod (2 b)", 2.0 * b),
            ("a ball on the rod and one on the circle (sqrt(a^2 + b^2))", math.hypot(a, b)),
        )
        for what, dist in gaps:
            if dist < 2.0 * rb * (1.0 - 1e-12):
                raise ValueError(
                    f"ball_radius = {rb!r} makes the balls overlap: the distance between {what} is {dist!r} "
                    f"< 2 ball_radius; need ball_radius <= {0.5 * dist!r} for a = {a!r}, b = {b!r}, N = {N}"
                )
    medium = Medium(B12=beta * (N * a * a / 2.0 + 2.0 * b * b), B3=beta * N * a * a)
    iso = (N + 2) * 0.4 * m * ball_radius**2
    theta12 = m * (N * a * a / 2.0 + 2.0 * b * b) + iso + rod_mass * b * b / 3.0 + N * spoke_mass * a * a / 6.0
    theta3 = m * N * a * a + iso + N * spoke_mass * a * a / 3.0
    return Body(theta12=theta12, theta3=theta3), medium
