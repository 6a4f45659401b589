"""The gyrostat satellite (Stepanov 1968, section 1)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..core.validate import positive, real

__all__ = ["GyrostatWarning", "Satellite"]


class GyrostatWarning(UserWarning):
    r"""Raised (as a warning) near the singular places of the stationary family or of its chart.

    See Also
    --------
    stationary_motion, symmetric_stationary_motion : the functions that warn.

    Examples
    --------
    With ``k3`` given, ``k2`` of (2.4) divides by :math:`\sin(\theta_0 + \kappa_0)`, which is tiny next to the
    classical member :math:`\theta_0 = 0`:

    >>> import warnings
    >>> from rigidbody import gyrostat
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     m = gyrostat.stationary_motion(sat, 1.0, 1e-8, k3=1e-3)
    >>> print(caught[0].category.__name__, caught[0].message)
    GyrostatWarning |sin(theta0 + kappa0)| = 1.01e-08: k2 from (2.4) is ill-conditioned near the classical member
    theta0 = 0 (or pi)
    """


@dataclass(frozen=True)
class Satellite:
    """A gyrostat satellite in a central Newtonian field.

    Parameters
    ----------
    M : float
        Mass (> 0).
    A1, A2, A3 : float
        Principal central moments of inertia about the body axes x1, x2, x3 (> 0, each at most the
        sum of the other two: the triangle inequalities of a real body).
    mu : float
        Gravitational parameter of the attracting centre (> 0); 1 in nondimensional units.
    k1, k2, k3 : float
        Constant projections of the gyrostatic momentum (rotor angular momentum) on x1, x2, x3.

    Notes
    -----
    Any consistent units: SI (kg, kg m^2, m^3/s^2, kg m^2/s) or nondimensional (M = mu = 1,
    lengths in units of the orbit radius).  The characteristic size of the body is
    ``l = sqrt(Abar / M)`` with ``Abar = (A1 + A2 + A3) / 3`` (property :attr:`l`).

    See Also
    --------
    stationary_motion : the motions (2.3) of such a satellite.
    symmetric_stationary_motion : the motions (3.2) of a dynamically symmetric one.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, section 1.

    Examples
    --------
    A nondimensional body (``M = mu = 1``, lengths in units of the orbit radius) of size ``l/R0 = 0.1``:

    >>> from rigidbody import gyrostat
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    >>> sat
    Satellite(M=1.0, A1=0.012, A2=0.01, A3=0.008, mu=1.0, k1=0.0, k2=0.0, k3=0.0)
    >>> gyrostat.Satellite(M=1.0, A1=0.03, A2=0.01, A3=0.01)
    Traceback (most recent call last):
        ...
    ValueError: A1 = 0.03 violates the triangle inequality A1 <= sum of the other two (0.02)
    """

    M: float
    A1: float
    A2: float
    A3: float
    mu: float = 1.0
    k1: float = 0.0
    k2: float = 0.0
    k3: float = 0.0

    def __post_init__(self) -> None:
        for name in ("M", "A1", "A2", "A3", "mu"):
            object.__setattr__(self, name, positive(getattr(self, name), name))
        for name in ("k1", "k2", "k3"):
            object.__setattr__(self, name, real(getattr(self, name), name))
        A = (self.A1, self.A2, self.A3)
        for i, name in enumerate(("A1", "A2", "A3")):
            others = A[(i + 1) % 3] + A[(i + 2) % 3]
            if A[i] > others * (1.0 + 1e-12):
                raise ValueError(
                    f"{name} = {A[i]!r} violates the triangle inequality {name} <= sum of the other two "
                    f"({others!r})"
                )

    @property
    def Abar(self) -> float:
        """Mean principal moment ``(A1 + A2 + A3) / 3``.

        Examples
        --------
        >>> from rigidbody import gyrostat
        >>> print(f"{gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008).Abar:.12f}")
        0.010000000000
        """
        return (self.A1 + self.A2 + self.A3) / 3.0

    @property
    def l(self) -> float:  # noqa: E743 - the paper's name for the size
        """Characteristic size ``sqrt(Abar / M)``.

        Examples
        --------
        >>> from rigidbody import gyrostat
        >>> print(f"{gyrostat.Satellite(M=2.0, A1=3.0, A2=2.0, A3=1.0).l:.12f}")  # sqrt(2 / 2)
        1.000000000000
        """
        return math.sqrt(self.Abar / self.M)

    @property
    def symmetric(self) -> bool:
        """True when A1 == A2 (dynamically symmetric about x3, section 3).

        Examples
        --------
        >>> from rigidbody import gyrostat
        >>> gyrostat.Satellite(M=1.0, A1=0.01, A2=0.01, A3=0.006).symmetric
        True
        """
        return self.A1 == self.A2
