"""The family of stationary motions (2.3)-(2.4) with a displaced orbit plane (k1 = 0)."""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, replace

from ..core.validate import positive, real
from ._family import SINGULAR_TOL, check_fits, check_omega_sign, family_arrays, wrap_angle
from ._model import GyrostatWarning, Satellite

__all__ = ["StationaryMotion", "stationary_motion"]


@dataclass(frozen=True)
class StationaryMotion:
    r"""A stationary motion (2.3) of the family with a displaced orbit plane.

    Attributes
    ----------
    satellite : Satellite
        The satellite that realises the motion (its k1 = 0, k2, k3 are those of the motion).
    R0, theta0, kappa0, omega0 : float
        Orbit radius, tilt of x3 from the radius vector y3 in the plane Gy2y3, latitude of the
        centre of mass (the displacement of the orbit plane is ``R0 sin kappa0``), angular velocity
        of the orbital frame about zeta2.
    k2, k3 : float
        Gyrostatic momentum components (k1 = 0).
    k : float
        Area constant ``k = omega0 S0 + k2 beta2 + k3 beta3`` (``omega0 = K0 / S0``).
    lambda0 : float
        Lagrange multiplier ``M R0^2 omega0^2 sin kappa0``.
    S0 : float
    point : tuple of 6 floats
        ``(R, kappa, beta1, beta3, gamma1, gamma2)`` of (2.3).
    branch : (int, int)
        Signs of ``beta2 = cos(theta0 + kappa0)`` and ``gamma3 = cos(theta0)``.
    classical : bool
        True when kappa0 == 0 (theta0 = 0 or pi, or A2 == A3): the orbit plane passes through the
        attracting centre, the member shared with the kappa = 0 equilibria of Rumyantsev [1].

    See Also
    --------
    stationary_motion : the function that returns it.
    stability : its stability by Routh's method.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eqs. (2.3)-(2.4).

    Examples
    --------
    The direction cosines (2.3) satisfy the constraint (2.1), :math:`\beta\cdot\gamma = \sin\kappa_0`:

    >>> import math
    >>> from rigidbody import gyrostat
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    >>> m = gyrostat.stationary_motion(sat, 1.0, math.pi / 4, k2=0.0)
    >>> print(f"{sum(b * g for b, g in zip(m.beta, m.gamma)):.12f} {math.sin(m.kappa0):.12f}")
    0.002986547159 0.002986547159
    """

    satellite: Satellite
    R0: float
    theta0: float
    kappa0: float
    omega0: float
    k2: float
    k3: float
    k: float
    lambda0: float
    S0: float
    point: tuple[float, float, float, float, float, float]
    branch: tuple[int, int]
    classical: bool

    @property
    def k1(self) -> float:
        """The gyrostatic component along x1: 0 on the family (2.3).

        Examples
        --------
        >>> from rigidbody import gyrostat
        >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
        >>> gyrostat.stationary_motion(sat, 1.0, 0.3, k2=0.02).k1
        0.0
        """
        return 0.0

    @property
    def beta(self) -> tuple[float, float, float]:
        """Direction cosines of zeta2 (orbit normal) in the body axes (2.3).

        Examples
        --------
        ``(0, cos(theta0 + kappa0), sin(theta0 + kappa0))``, a unit vector:

        >>> import math
        >>> from rigidbody import gyrostat
        >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
        >>> print(f"{math.hypot(*gyrostat.stationary_motion(sat, 1.0, 0.3, k2=0.02).beta):.12f}")
        1.000000000000
        """
        t = self.theta0 + self.kappa0
        return (0.0, math.cos(t), math.sin(t))

    @property
    def gamma(self) -> tuple[float, float, float]:
        """Direction cosines of y3 (radius vector OG) in the body axes (2.3).

        Examples
        --------
        ``(0, -sin theta0, cos theta0)``:

        >>> import math
        >>> from rigidbody import gyrostat
        >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
        >>> print(*(f"{g:.6f}" for g in gyrostat.stationary_motion(sat, 1.0, math.pi / 4, k2=0.0).gamma))
        0.000000 -0.707107 0.707107
        """
        return (0.0, -math.sin(self.theta0), math.cos(self.theta0))

    @property
    def displacement(self) -> float:
        """Distance of the orbit plane from the attracting centre, ``R0 sin kappa0``.

        Examples
        --------
        Of order :math:`l^2/R_0` (section 2); here :math:`l = 0.1 R_0`:

        >>> import math
        >>> from rigidbody import gyrostat
        >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
        >>> m = gyrostat.stationary_motion(sat, 1.0, math.pi / 4, k2=0.0)
        >>> print(f"{m.displacement:.9f} {math.sin(m.kappa0):.9f}")
        0.002986547 0.002986547
        """
        return self.R0 * math.sin(self.kappa0)


def stationary_motion(
    sat: Satellite,
    R0: float,
    theta0: float,
    *,
    k2: float | None = None,
    k3: float | None = None,
    omega_sign: int = 1,
) -> StationaryMotion:
    r"""The stationary motion (2.3) for given R0, theta0 and one gyrostatic component (2.4).

    Closed form, no root finding (see :func:`family_arrays`): ``kappa0`` from ``tan kappa0``,
    ``omega0`` from the second relation (2.4), the missing gyrostatic component from the first.

    Parameters
    ----------
    sat : Satellite
        Mass, moments of inertia and mu are used; ``sat.k1`` must be 0 (the family needs k1 = 0);
        ``sat.k2``/``sat.k3`` are ignored (the motion fixes them).
    R0 : float
        Orbit radius (> 0).
    theta0 : float
        Tilt angle (radians), reduced to (-pi, pi].
    k2, k3 : float
        Exactly one of them; the other is computed.
    omega_sign : {+1, -1}
        Sign of omega0.

    Returns
    -------
    StationaryMotion

    Raises
    ------
    ValueError
        ``R0`` does not exceed the rms radius ``sqrt((A1 + A2 + A3) / (2 M))`` of the body (it does not fit
        inside its orbit, see :func:`check_fits`).
        No motion of the family exists: ``omega0^2 cos^2 kappa0 <= 0`` (body too large for R0), the
        denominator ``cos(theta0 + kappa0)`` vanishes when k2 is given, or ``sin(theta0 + kappa0)``
        vanishes when k3 is given (theta0 = 0 or pi: the classical kappa = 0 member, where k3 must be
        0 and k2 is free -- pass k2 instead).

    Warns
    -----
    GyrostatWarning
        Near those places (abs(cos) or abs(sin) < 1e-6): the computed component is ill-conditioned.

    See Also
    --------
    stability : the verdict of Routh's method for the motion.
    stability_map : verdicts over arrays of parameters.
    symmetric_stationary_motion : the motions (3.2) of a dynamically symmetric satellite.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eqs. (2.3)-(2.4).

    Examples
    --------
    The classical member :math:`\theta_0 = 0` (orbit plane through the centre): by the second relation
    (2.4) :math:`\omega_0^2 = \mu R_0^{-3}\{1 - \frac{9}{2MR_0^2}\frac{2A_3 - A_1 - A_2}{3}\} = 1.009`:

    >>> import math
    >>> from rigidbody import gyrostat
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    >>> m = gyrostat.stationary_motion(sat, 1.0, 0.0, k2=0.0)
    >>> print(m.kappa0, m.classical, f"{m.omega0:.12f} {math.sqrt(1.009):.12f}")
    0.0 True 1.004489920308 1.004489920308

    Tilted by :math:`\theta_0 = \pi/4` the orbit plane is displaced: the second relation gives
    :math:`\omega_0^2\cos^2\kappa_0 = 1 - \frac92[\frac{A_2 - A_3}{2} + \frac{2A_3 - A_1 - A_2}{3}] = 1.0045`,
    the third divided by the second :math:`\tan\kappa_0 = \frac32(A_2 - A_3)\sin2\theta_0/1.0045`:

    >>> m = gyrostat.stationary_motion(sat, 1.0, math.pi / 4, k2=0.0)
    >>> print(f"{m.kappa0:.12f} {math.atan(1.5 * 0.002 / 1.0045):.12f}")
    0.002986551598 0.002986551598
    >>> print(f"{m.omega0 * math.cos(m.kappa0):.12f} {math.sqrt(1.0045):.12f}")
    1.002247474429 1.002247474429
    """
    if not isinstance(sat, Satellite):
        raise TypeError(f"sat must be a Satellite; got {type(sat).__name__}")
    if sat.k1 != 0.0:
        raise ValueError(f"the family (2.3) requires k1 = 0; sat.k1 = {sat.k1!r}")
    R0 = positive(R0, "R0")
    check_fits(sat, R0)
    theta0 = float(wrap_angle(real(theta0, "theta0")))
    omega_sign = check_omega_sign(omega_sign)
    if (k2 is None) == (k3 is None):
        raise TypeError("give exactly one of k2 and k3 (the other is computed from (2.4))")
    if k2 is not None:
        k2 = real(k2, "k2")
    if k3 is not None:
        k3 = real(k3, "k3")
    f = family_arrays(sat.M, sat.A1, sat.A2, sat.A3, sat.mu, R0, theta0, k2=k2, k3=k3, omega_sign=omega_sign)
    if not f["n2"] > 0:
        raise ValueError(
            "no stationary motion: omega0^2 cos^2 kappa0 = mu/R0^3 {1 - 9/(2 M R0^2)[...]} <= 0 (2.4); "
            f"the body is too large for R0 = {R0!r} (l/R0 = {sat.l / R0:.3g})"
        )
    sp, cp = float(f["sin_tk"]), float(f["cos_tk"])
    kappa0 = float(f["kappa0"])
    if k3 is None:
        if cp == 0.0:
            raise ValueError(
                "cos(theta0 + kappa0) = 0: with k2 given, (2.4) has no solution for k3 (it diverges); "
                "give k3 instead"
            )
        if abs(cp) < SINGULAR_TOL:
            warnings.warn(
                f"|cos(theta0 + kappa0)| = {abs(cp):.2e}: k3 from (2.4) is ill-conditioned near "
                "theta0 + kappa0 = +-pi/2", GyrostatWarning, stacklevel=2,
            )
    else:
        if sp == 0.0:
            if k3 == 0.0:
                raise ValueError(
                    "theta0 + kappa0 = 0 or pi (the classical kappa0 = 0 equilibrium with axes along the "
                    "orbital axes): k2 is not determined by k3 = 0 here; give k2 instead"
                )
            raise ValueError(
                "theta0 + kappa0 = 0 or pi: (2.4) requires k3 = 0 there (no motion with "
                f"k3 = {k3!r}); give k2 instead"
            )
        if abs(sp) < SINGULAR_TOL:
            warnings.warn(
                f"|sin(theta0 + kappa0)| = {abs(sp):.2e}: k2 from (2.4) is ill-conditioned near the "
                "classical member theta0 = 0 (or pi)", GyrostatWarning, stacklevel=2,
            )
    k2v, k3v = float(f["k2"]), float(f["k3"])
    b2s = 1 if cp >= 0 else -1
    g3s = 1 if math.cos(theta0) >= 0 else -1
    point = (R0, kappa0, 0.0, sp, 0.0, -math.sin(theta0))
    return StationaryMotion(
        satellite=replace(sat, k1=0.0, k2=k2v, k3=k3v),
        R0=R0, theta0=theta0, kappa0=kappa0, omega0=float(f["omega0"]), k2=k2v, k3=k3v,
        k=float(f["k"]), lambda0=float(f["lambda0"]), S0=float(f["S0"]), point=point,
        branch=(b2s, g3s), classical=(kappa0 == 0.0),
    )
