"""The gyrostat satellite (Stepanov 1968, section 1)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..core.validate import positive, real

__all__ = ["GyrostatWarning", "Satellite"]


class GyrostatWarning(UserWarning):
    """Raised (as a warning) near the singular places of the stationary family or of its chart."""


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
        """Mean principal moment ``(A1 + A2 + A3) / 3``."""
        return (self.A1 + self.A2 + self.A3) / 3.0

    @property
    def l(self) -> float:  # noqa: E743 - the paper's name for the size
        """Characteristic size ``sqrt(Abar / M)``."""
        return math.sqrt(self.Abar / self.M)

    @property
    def symmetric(self) -> bool:
        """True when A1 == A2 (dynamically symmetric about x3, section 3)."""
        return self.A1 == self.A2
