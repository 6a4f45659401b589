"""Stability of the motions (3.2) of a dynamically symmetric satellite (section 3), one motion at a time."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core.quadform import inertia, leading_minors
from ._model import Satellite
from ._secondvar import VERDICTS, verdict_codes
from ._symmetric import SymmetricMotion, check_symmetric, hessian_W_sym

__all__ = ["SymmetricStability", "W_thetatheta_stable"]


def W_thetatheta_stable(M: Any, A1: Any, A3: Any, mu: Any, R0: Any, theta0: Any, kappa0: Any, omega0: Any,
                        c: Any) -> Any:
    r"""``d^2 W / d theta^2`` at (3.2) in a form without cancellation (vectorised).

    With ``b = beta3 = sin(theta0 + kappa0)``, ``S10 = M R0^2 cos^2 kappa0 + A1 cos^2(theta0 + kappa0)``:
    ``W_thth = f_bb cos^2(theta0 + kappa0) - f_b b - U_thth`` with ``f_bb = (c - 2 A1 omega0 b)^2 / S10 +
    A1 omega0^2``.  Eliminating ``f_b = omega0 (A1 omega0 b - c)`` by the third equation (3.1) (the first
    relation (3.3)) and using ``cos 2 theta + sin theta cos theta tan(theta + kappa) =
    (cos^3 theta cos kappa + sin^3 theta sin kappa) / cos(theta + kappa)`` gives

        W_thth = [(c - 2 A1 omega0 b)^2 / S10 + A1 omega0^2] cos^2(theta0 + kappa0)
                 + 3 mu R0^-3 (A1 - A3) (cos^3 theta0 cos kappa0 + sin^3 theta0 sin kappa0) / cos(theta0 + kappa0).

    The chain-rule value adds terms of order ``mu R0^-3 (A1 - A3)`` that cancel near theta0 = +-pi/2, where
    the true value is O(l^2/R^2) of them: in SI units float64 kept no correct digit within ~1e-7 of pi/2.

    Parameters
    ----------
    M, A1, A3, mu : array_like
        Mass, equatorial (``A1 = A2``) and axial moments of inertia, gravitational parameter (any
        consistent units, as in :class:`Satellite`).
    R0 : array_like
        Orbit radius of the motion (3.2).
    theta0, kappa0 : array_like
        Nutation angle and latitude of the centre of mass at (3.2) (radians).
    omega0 : array_like
        Angular velocity of the orbital frame, (3.3).
    c : array_like
        Constant of the cyclic integral of phi, (3.3) (an angular momentum).

    Returns
    -------
    ndarray or numpy scalar
        ``d^2 W / d theta^2`` at (3.2), in units of energy, broadcast over the inputs (``inf``/``nan``
        where ``cos(theta0 + kappa0) = 0``).

    See Also
    --------
    hessian_W_sym : the chain-rule Hessian.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eqs. (3.1)-(3.3).

    Examples
    --------
    Away from :math:`\theta_0 = \pm\pi/2` (no cancellation) it equals the chain-rule entry:

    >>> import math
    >>> import numpy as np
    >>> from rigidbody import gyrostat
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.01, A2=0.01, A3=0.006)
    >>> ms = gyrostat.symmetric_stationary_motion(sat, 1.0, math.pi / 4)
    >>> Wtt = gyrostat.W_thetatheta_stable(1.0, 0.01, 0.006, 1.0, 1.0, ms.theta0, ms.kappa0, ms.omega0, ms.c)
    >>> print(f"{Wtt:.12f} {gyrostat.hessian_W_sym(sat, ms.point, k=ms.k, c=ms.c)[2, 2]:.12f}")
    0.011028359030 0.011028359030
    """
    with np.errstate(divide="ignore", invalid="ignore"):
        M, A1, A3, mu, R0, th, kap, om, c = (
            np.asarray(v, dtype=float) for v in (M, A1, A3, mu, R0, theta0, kappa0, omega0, c))
        ct, st, ck, sk = np.cos(th), np.sin(th), np.cos(kap), np.sin(kap)
        cp, b = ct * ck - st * sk, st * ck + ct * sk
        S = M * R0**2 * ck**2 + A1 * cp**2
        return (((c - 2 * A1 * om * b) ** 2 / S + A1 * om**2) * cp**2
                + 3 * mu / R0**3 * (A1 - A3) * (ct**3 * ck + st**3 * sk) / cp)


def W_psipsi_34(sat: Satellite, R0: Any, theta0: Any, kappa0: Any) -> Any:
    r"""The paper's (3.4): ``3 mu R0^-3 (A1 - A3) sin^2 theta0 cos theta0 cos kappa0 / cos(theta0 + kappa0)``.

    ``d^2 W / d psi^2`` at the motion (3.2) (``psi = pi``); the paper's sufficient condition is (3.4) > 0.

    Parameters
    ----------
    sat : Satellite
        Supplies ``A1, A3, mu`` (any consistent units).
    R0 : array_like
        Orbit radius of the motion (3.2).
    theta0, kappa0 : array_like
        Nutation angle and latitude of the centre of mass at (3.2) (radians).

    Returns
    -------
    ndarray or numpy scalar
        ``W_psipsi`` in units of energy, broadcast over the inputs (``inf``/``nan`` where
        ``cos(theta0 + kappa0) = 0``).

    See Also
    --------
    hessian_W_sym : the whole second variation.
    symmetric_stability_map : the verdicts from it.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eq. (3.4).

    Examples
    --------
    For :math:`|\theta_0| < \pi/2` (3.4) > 0 reduces to :math:`A_1 > A_3` (section 3):

    >>> import math
    >>> from rigidbody import gyrostat
    >>> for A3 in (0.006, 0.012):
    ...     sat = gyrostat.Satellite(M=1.0, A1=0.01, A2=0.01, A3=A3)
    ...     ms = gyrostat.symmetric_stationary_motion(sat, 1.0, 0.5)
    ...     print(A3, bool(gyrostat.W_psipsi_34(sat, 1.0, ms.theta0, ms.kappa0) > 0))
    0.006 True
    0.012 False
    """
    with np.errstate(divide="ignore", invalid="ignore"):
        return (3 * sat.mu / np.asarray(R0, dtype=float) ** 3 * (sat.A1 - sat.A3) * np.sin(theta0) ** 2
                * np.cos(theta0) * np.cos(kappa0) / np.cos(np.asarray(theta0) + kappa0))


@dataclass(frozen=True)
class SymmetricStability:
    r"""Stability of a motion (3.2) from the full 4x4 second variation of W(R, kappa, theta, psi).

    Attributes
    ----------
    hessian : ndarray (4, 4)
        Second derivatives of W at (3.2), order (R, kappa, theta, psi); the theta-theta entry from the
        cancellation-free :func:`W_thetatheta_stable`, the others by the chain rule.
    minors : ndarray (4,)
        Its leading principal minors.
    W_psipsi : float
        The (3.4) entry; the psi row decouples (W_Rpsi = W_kappapsi = W_thetapsi = 0 at psi = pi).
    Delta : float
        Determinant of the (R, kappa, theta) block (section 4: the Jacobian of (3.1) is W_psipsi * Delta).
    degree, nullity, verdict :
        As for :class:`Stability`.
    paper_condition : bool
        The paper's sufficient condition (3.4) ``W_psipsi > 0``.
    jacobian : float
        ``det hessian`` = Jacobian of the system (3.1).
    unconditionally_stable : bool

    See Also
    --------
    stability : the function that returns it.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eq. (3.4) and section 4.

    Examples
    --------
    The Jacobian of (3.1) is :math:`W_{\psi\psi}\Delta` (section 4):

    >>> import math
    >>> import numpy as np
    >>> from rigidbody import gyrostat
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.01, A2=0.01, A3=0.006)
    >>> ms = gyrostat.symmetric_stationary_motion(sat, 1.0, math.pi / 4)
    >>> st = gyrostat.stability(sat, ms)
    >>> print(st.verdict, st.paper_condition, f"{st.jacobian:.8e} {st.W_psipsi * st.Delta:.8e}")
    stable True 6.36976918e-05 6.36976918e-05
    """

    hessian: np.ndarray
    minors: np.ndarray
    W_psipsi: float
    Delta: float
    degree: int
    nullity: int
    verdict: str
    paper_condition: bool
    jacobian: float
    unconditionally_stable: bool

    @property
    def s1(self) -> float:
        """The first leading minor of the second variation, ``W_RR``.

        Examples
        --------
        >>> import math
        >>> import numpy as np
        >>> from rigidbody import gyrostat
        >>> sat = gyrostat.Satellite(M=1.0, A1=0.01, A2=0.01, A3=0.006)
        >>> ms = gyrostat.symmetric_stationary_motion(sat, 1.0, math.pi / 4)
        >>> st = gyrostat.stability(sat, ms)
        >>> print(f"{st.s1:.9f} {st.hessian[0, 0]:.9f}")
        0.977276722 0.977276722
        """
        return float(self.minors[0])

    @property
    def s2(self) -> float:
        """The second leading minor, the determinant of the (R, kappa) block.

        Examples
        --------
        >>> import math
        >>> import numpy as np
        >>> from rigidbody import gyrostat
        >>> sat = gyrostat.Satellite(M=1.0, A1=0.01, A2=0.01, A3=0.006)
        >>> ms = gyrostat.symmetric_stationary_motion(sat, 1.0, math.pi / 4)
        >>> st = gyrostat.stability(sat, ms)
        >>> print(f"{st.s2:.9f} {np.linalg.det(st.hessian[:2, :2]):.9f}")
        0.990969494 0.990969494
        """
        return float(self.minors[1])

    @property
    def s3(self) -> float:
        """The third leading minor, the determinant of the (R, kappa, theta) block, :attr:`Delta`.

        Examples
        --------
        >>> import math
        >>> import numpy as np
        >>> from rigidbody import gyrostat
        >>> sat = gyrostat.Satellite(M=1.0, A1=0.01, A2=0.01, A3=0.006)
        >>> ms = gyrostat.symmetric_stationary_motion(sat, 1.0, math.pi / 4)
        >>> st = gyrostat.stability(sat, ms)
        >>> print(f"{st.s3:.9f} {st.Delta:.9f}")
        0.010552775 0.010552775
        """
        return float(self.minors[2])


def stability_symmetric(sat: Satellite, m: SymmetricMotion, *, rtol: float = 1e-12) -> SymmetricStability:
    check_symmetric(sat)
    for name in ("M", "A1", "A3", "mu"):
        if getattr(sat, name) != getattr(m.satellite, name):
            raise ValueError(f"sat.{name} differs from the satellite the motion was computed for")
    H = hessian_W_sym(sat, m.point, k=m.k, c=m.c)
    H[2, 2] = W_thetatheta_stable(sat.M, sat.A1, sat.A3, sat.mu, m.R0, m.theta0, m.kappa0, m.omega0, m.c)
    # the psi row/column vanish identically off the diagonal at psi = pi (sin psi = 0)
    H[3, :3] = 0.0
    H[:3, 3] = 0.0
    _, n_neg, n_zero = inertia(H, rtol=rtol)
    code = int(verdict_codes(np.asarray(n_neg), np.asarray(n_zero)))
    minors = leading_minors(H)
    Delta = float(leading_minors(H[:3, :3])[-1])
    jac = float(minors[-1])
    return SymmetricStability(
        hessian=H, minors=minors, W_psipsi=float(H[3, 3]), Delta=Delta, degree=int(n_neg), nullity=int(n_zero),
        verdict=VERDICTS[code], paper_condition=bool(H[3, 3] > 0), jacobian=jac,
        unconditionally_stable=(code == 0 and jac != 0.0),
    )
