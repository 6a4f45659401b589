"""Dynamically symmetric satellite (section 3): A1 = A2, k1 = k2 = 0, W(R, kappa, theta, psi)."""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from types import ModuleType
from typing import Any

import numpy as np

from ..core.validate import positive, real
from ._family import SINGULAR_TOL, check_fits, check_omega_sign, wrap_angle
from ._model import GyrostatWarning, Satellite

__all__ = [
    "SymmetricMotion",
    "gradient_W_sym",
    "hessian_W_sym",
    "symmetric_family_arrays",
    "symmetric_potential",
    "symmetric_stationary_motion",
]


SYM_COORDS = ("R", "kappa", "theta", "psi")


def check_symmetric(sat: Satellite) -> None:
    """Reject a satellite outside section 3 (TypeError if not a Satellite; ValueError unless A1 = A2, k1 = k2 = 0)."""
    if not isinstance(sat, Satellite):
        raise TypeError(f"sat must be a Satellite; got {type(sat).__name__}")
    if sat.A1 != sat.A2:
        raise ValueError(f"section 3 requires A1 == A2 (dynamic symmetry); got A1={sat.A1!r}, A2={sat.A2!r}")
    if sat.k1 != 0.0 or sat.k2 != 0.0:
        raise ValueError(f"section 3 requires k1 = k2 = 0; got k1={sat.k1!r}, k2={sat.k2!r}")


def symmetric_potential(
    sat: Satellite, x: Any, *, k: float, c: float, lib: ModuleType = np
) -> Any:
    r"""Amended potential of section 3, ``W(R, kappa, theta, psi) = K^2 / (2 S1) - U``.

    ``K = k - c beta3``, ``S1 = M R^2 cos^2 kappa + A1 (1 - beta3^2)``,
    ``beta3 = cos theta sin kappa - sin theta cos psi cos kappa``,
    ``U = mu M / R + mu R^-3 (A1 - A3)(1 - 3/2 sin^2 theta)``.  ``c`` is the constant of the cyclic
    integral of phi (k3 enters it additively).  ``lib``: numpy (default), math or mpmath.

    Its stationary points are given by (3.1); the motion (3.2)-(3.3) is one of them, and its second
    derivative in psi there is (3.4).

    Parameters
    ----------
    sat : Satellite
        Supplies ``M, A1, A3, mu`` (any consistent units); the section-3 setting is ``A1 = A2``,
        ``k1 = k2 = 0`` (not checked here).
    x : sequence of 4
        ``(R, kappa, theta, psi)``: orbit radius (length), latitude of the centre of mass and the 3-1-3
        Euler angles theta, psi of the body relative to the orbital frame (radians); scalars or
        broadcastable arrays.
    k : float
        Area constant (the integral of the cyclic coordinate sigma), an angular momentum.
    c : float
        Constant of the cyclic integral of phi, an angular momentum (``A3 omega3 + k3``).
    lib : module
        Provides ``sin``, ``cos``: ``numpy`` (default), ``math`` or ``mpmath`` (extended precision).

    Returns
    -------
    scalar or ndarray
        ``W`` in units of energy, of the type ``lib`` produces.

    See Also
    --------
    gradient_W_sym, hessian_W_sym : its derivatives in closed form.
    amended_potential_W : the W of section 2 (any body).

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, section 3.

    Examples
    --------
    At :math:`\kappa = \theta = 0` (so :math:`\beta_3 = 0`) with :math:`k = c = 0`:
    :math:`W = -U = -(\mu M/R + \mu R^{-3}(A_1 - A_3)) = -1.004` for the body below at :math:`R = 1`:

    >>> import math
    >>> from rigidbody import gyrostat
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.01, A2=0.01, A3=0.006)
    >>> print(f"{gyrostat.symmetric_potential(sat, (1.0, 0.0, 0.0, math.pi), k=0.0, c=0.0):.12f}")
    -1.004000000000
    """
    R, kap, th, ps = x
    b = lib.cos(th) * lib.sin(kap) - lib.sin(th) * lib.cos(ps) * lib.cos(kap)
    K = k - c * b
    S1 = sat.M * R * R * lib.cos(kap) ** 2 + sat.A1 * (1 - b * b)
    st = lib.sin(th)
    U = sat.mu * sat.M / R + sat.mu / R**3 * (sat.A1 - sat.A3) * (1 - 1.5 * st * st)
    return K * K / (2 * S1) - U


def symmetric_derivatives(
    M: Any, A1: Any, A3: Any, mu: Any, k: Any, c: Any, R: Any, kap: Any, th: Any, ps: Any
) -> tuple[Any, Any]:
    """Gradient (4,) and Hessian (4, 4) of W by the chain rule W = f(R, kappa, b(kappa, theta, psi)) - U."""
    ck, sk, ct, st, cps, sps = np.cos(kap), np.sin(kap), np.cos(th), np.sin(th), np.cos(ps), np.sin(ps)
    b = ct * sk - st * cps * ck
    # derivatives of b w.r.t. (kappa, theta, psi)
    bk = ct * ck + st * cps * sk
    bt = -st * sk - ct * cps * ck
    bp = st * sps * ck
    bkk, btt = -b, -b
    bpp = st * cps * ck
    bkt = -st * ck + ct * cps * sk
    bkp = -st * sps * sk
    btp = ct * sps * ck
    K = k - c * b
    S = M * R**2 * ck**2 + A1 * (1 - b**2)
    # y = (R, kappa, b): first and second derivatives of K and S
    Ky = [0 * b, 0 * b, -c + 0 * b]
    Sy = [2 * M * R * ck**2, -M * R**2 * 2 * sk * ck, -2 * A1 * b]
    Syy = [
        [2 * M * ck**2, -2 * M * R * 2 * sk * ck, 0 * b],
        [-2 * M * R * 2 * sk * ck, -2 * M * R**2 * (ck**2 - sk**2), 0 * b],
        [0 * b, 0 * b, -2 * A1 + 0 * b],
    ]
    fy = [K * Ky[i] / S - K**2 * Sy[i] / (2 * S**2) for i in range(3)]
    fyy = [
        [
            Ky[i] * Ky[j] / S - K * (Ky[i] * Sy[j] + Ky[j] * Sy[i]) / S**2
            - K**2 * Syy[i][j] / (2 * S**2) + K**2 * Sy[i] * Sy[j] / S**3
            for j in range(3)
        ]
        for i in range(3)
    ]
    # Jacobian dy/dx, x = (R, kappa, theta, psi)
    z = 0 * b
    J = [[1 + z, z, z, z], [z, 1 + z, z, z], [z, bk, bt, bp]]
    bxx = [[z, z, z, z], [z, bkk, bkt, bkp], [z, bkt, btt, btp], [z, bkp, btp, bpp]]
    # U(R, theta)
    d = A1 - A3
    g = 1 - 1.5 * st**2
    U_R = -mu * M / R**2 - 3 * mu / R**4 * d * g
    U_t = -1.5 * mu / R**3 * d * 2 * st * ct
    U_RR = 2 * mu * M / R**3 + 12 * mu / R**5 * d * g
    U_Rt = 4.5 * mu / R**4 * d * 2 * st * ct
    U_tt = -3 * mu / R**3 * d * (ct**2 - st**2)
    Ux = [U_R, z, U_t, z]
    Uxx = [[U_RR, z, U_Rt, z], [z, z, z, z], [U_Rt, z, U_tt, z], [z, z, z, z]]
    grad = [sum(fy[i] * J[i][p] for i in range(3)) - Ux[p] for p in range(4)]
    hess = [
        [
            sum(J[i][p] * fyy[i][j] * J[j][q] for i in range(3) for j in range(3))
            + fy[2] * bxx[p][q] - Uxx[p][q]
            for q in range(4)
        ]
        for p in range(4)
    ]
    G = np.stack(np.broadcast_arrays(*grad), axis=-1)
    H = np.stack([np.stack(np.broadcast_arrays(*row), axis=-1) for row in hess], axis=-2)
    return G, H


def gradient_W_sym(sat: Satellite, x: Any, *, k: float, c: float) -> np.ndarray:
    """Gradient (3.1) of the section-3 W at ``x = (R, kappa, theta, psi)`` (shape (..., 4)).

    Closed form by the chain rule through ``beta3``, valid at any point; it vanishes at the motion
    (3.2)-(3.3).

    Parameters
    ----------
    sat : Satellite
        Supplies ``M, A1, A3, mu`` (any consistent units; ``A1 = A2`` is assumed, not checked).
    x : sequence of 4
        ``(R, kappa, theta, psi)``: length and angles in radians; scalars or broadcastable arrays.
    k : float
        Area constant, an angular momentum.
    c : float
        Constant of the cyclic integral of phi, an angular momentum.

    Returns
    -------
    ndarray, shape (..., 4)
        ``(dW/dR, dW/dkappa, dW/dtheta, dW/dpsi)``: energy per length for R, energy for the angles.

    See Also
    --------
    symmetric_potential : W itself.
    hessian_W_sym : the second derivatives.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eq. (3.1).

    Examples
    --------
    It vanishes at the motion (3.2), and agrees with the complex-step derivative of W anywhere:

    >>> import math
    >>> import numpy as np
    >>> from rigidbody import gyrostat
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.01, A2=0.01, A3=0.006)
    >>> ms = gyrostat.symmetric_stationary_motion(sat, 1.0, math.pi / 4)
    >>> bool(np.abs(gyrostat.gradient_W_sym(sat, ms.point, k=ms.k, c=ms.c)).max() < 1e-14)
    True
    >>> from rigidbody.core.quadform import gradient_cs
    >>> x = (1.1, 0.05, 0.7, 2.0)
    >>> g_cs = gradient_cs(lambda z: gyrostat.symmetric_potential(sat, z, k=1.0, c=0.01), x)
    >>> np.allclose(gyrostat.gradient_W_sym(sat, x, k=1.0, c=0.01), g_cs, rtol=0, atol=1e-14)
    True
    """
    R, kap, th, ps = (np.asarray(v, dtype=float) for v in x)
    return symmetric_derivatives(sat.M, sat.A1, sat.A3, sat.mu, k, c, R, kap, th, ps)[0]


def hessian_W_sym(sat: Satellite, x: Any, *, k: float, c: float) -> np.ndarray:
    """Hessian of the section-3 W at ``x = (R, kappa, theta, psi)`` (shape (..., 4, 4)), chain rule.

    Valid at any point.  At a motion (3.2) near theta0 = +-pi/2 its theta-theta entry is a difference of
    terms that cancel to O(l^2/R^2) (no correct digit in SI units within ~1e-7 of pi/2): the verdicts
    (:class:`SymmetricStability`) use :func:`W_thetatheta_stable` for that entry instead. At (3.2)
    (``psi = pi``) the psi row decouples and its diagonal entry is (3.4) (:func:`W_psipsi_34`).

    Parameters
    ----------
    sat : Satellite
        Supplies ``M, A1, A3, mu`` (any consistent units; ``A1 = A2`` is assumed, not checked).
    x : sequence of 4
        ``(R, kappa, theta, psi)``: length and angles in radians; scalars or broadcastable arrays.
    k : float
        Area constant, an angular momentum.
    c : float
        Constant of the cyclic integral of phi, an angular momentum.

    Returns
    -------
    ndarray, shape (..., 4, 4)
        Symmetric second derivatives of W in the order :data:`SYM_COORDS` ``(R, kappa, theta, psi)``:
        energy/length^2 for ``W_RR``, energy/length for the rest of the R row, energy otherwise.

    See Also
    --------
    W_psipsi_34 : the psi-psi entry at (3.2), printed as (3.4).
    W_thetatheta_stable : the theta-theta entry at (3.2) without cancellation.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eqs. (3.1)-(3.4).

    Examples
    --------
    At the motion (3.2) the psi row decouples and its diagonal entry is the paper's (3.4):

    >>> import math
    >>> import numpy as np
    >>> from rigidbody import gyrostat
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.01, A2=0.01, A3=0.006)
    >>> ms = gyrostat.symmetric_stationary_motion(sat, 1.0, math.pi / 4)
    >>> H = gyrostat.hessian_W_sym(sat, ms.point, k=ms.k, c=ms.c)
    >>> bool(np.abs(H[3, :3]).max() < 1e-15)
    True
    >>> print(f"{H[3, 3]:.12f} {gyrostat.W_psipsi_34(sat, 1.0, ms.theta0, ms.kappa0):.12f}")
    0.006036108325 0.006036108325
    """
    R, kap, th, ps = (np.asarray(v, dtype=float) for v in x)
    return symmetric_derivatives(sat.M, sat.A1, sat.A3, sat.mu, k, c, R, kap, th, ps)[1]


def symmetric_family_arrays(
    M: Any, A1: Any, A3: Any, mu: Any, R0: Any, theta0: Any, omega_sign: Any = 1
) -> dict[str, np.ndarray]:
    """Vectorised solution (3.2)-(3.3): kappa0, omega0, c, k (k via omega0 = K0 / S10)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        M, A1, A3, mu, R0, th = (np.asarray(v, dtype=float) for v in (M, A1, A3, mu, R0, theta0))
        n0 = mu / R0**3
        st, ct = np.sin(th), np.cos(th)
        s2t = 2 * st * ct
        n2 = n0 * (1 + 3 * (A1 - A3) / (M * R0**2) * (1 - 1.5 * st**2))
        exists = n2 > 0
        n2p = np.where(exists, n2, np.nan)
        kap = np.arctan(1.5 * (A1 - A3) * n0 * s2t / (M * R0**2 * n2p))
        om = np.asarray(omega_sign, dtype=float) * np.sqrt(n2p) / np.cos(kap)
        # sin, cos of theta0 + kappa0 by the addition formulas: cos(th + kap) evaluated after rounding the
        # sum th + kap loses relative accuracy near theta0 = +-pi/2 (kappa0 ~ 1e-14 in SI units)
        ck, sk = np.cos(kap), np.sin(kap)
        sp, cp = st * ck + ct * sk, ct * ck - st * sk
        ok = cp != 0
        c = np.where(ok, (0.5 * A1 * om**2 * 2 * sp * cp + 1.5 * n0 * (A1 - A3) * s2t) / (om * np.where(ok, cp, 1)),
                     np.nan)
        S10 = M * R0**2 * np.cos(kap) ** 2 + A1 * cp**2
        k = om * S10 + c * sp
    return {"theta0": th + 0 * om, "n2": n2 + 0 * om, "kappa0": kap, "omega0": om, "c": c, "k": k,
            "S10": S10, "exists": exists & ok, "sin_t": st + 0 * om, "cos_tk": cp}


@dataclass(frozen=True)
class SymmetricMotion:
    """Stationary motion (3.2) of a dynamically symmetric gyrostat: a regular precession in Koenig axes.

    Attributes
    ----------
    satellite : Satellite
    R0, theta0, kappa0, omega0 : float
        As in (3.2)-(3.3); psi0 = pi.
    c : float
        Constant of the cyclic integral of phi (k3 is included in it).
    k : float
        Area constant, ``omega0 S10 + c beta3``.
    S10 : float
    point : (R0, kappa0, theta0, pi)

    See Also
    --------
    symmetric_stationary_motion : the function that returns it.
    StationaryMotion : the motions (2.3) of a triaxial satellite.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eqs. (3.2)-(3.3).

    Examples
    --------
    >>> import math
    >>> import numpy as np
    >>> from rigidbody import gyrostat
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.01, A2=0.01, A3=0.006)
    >>> ms = gyrostat.symmetric_stationary_motion(sat, 1.0, math.pi / 4)
    >>> ms.point == (ms.R0, ms.kappa0, ms.theta0, math.pi)
    True
    """

    satellite: Satellite
    R0: float
    theta0: float
    kappa0: float
    omega0: float
    c: float
    k: float
    S10: float
    point: tuple[float, float, float, float]

    @property
    def psi0(self) -> float:
        """The precession angle of (3.2), pi.

        Examples
        --------
        >>> import math
        >>> import numpy as np
        >>> from rigidbody import gyrostat
        >>> sat = gyrostat.Satellite(M=1.0, A1=0.01, A2=0.01, A3=0.006)
        >>> ms = gyrostat.symmetric_stationary_motion(sat, 1.0, math.pi / 4)
        >>> ms.psi0 == math.pi
        True
        """
        return math.pi

    @property
    def displacement(self) -> float:
        """Distance of the orbit plane from the attracting centre, ``R0 sin kappa0``.

        Examples
        --------
        >>> import math
        >>> import numpy as np
        >>> from rigidbody import gyrostat
        >>> sat = gyrostat.Satellite(M=1.0, A1=0.01, A2=0.01, A3=0.006)
        >>> ms = gyrostat.symmetric_stationary_motion(sat, 1.0, math.pi / 4)
        >>> print(f"{ms.displacement:.12f} {math.sin(ms.kappa0):.12f}")
        0.005981946808 0.005981946808
        """
        return self.R0 * math.sin(self.kappa0)


def symmetric_stationary_motion(
    sat: Satellite, R0: float, theta0: float, *, omega_sign: int = 1
) -> SymmetricMotion:
    r"""The stationary motion (3.2) with relations (3.3), closed form.

    Parameters
    ----------
    sat : Satellite
        Must have A1 == A2 and k1 = k2 = 0 (``sat.k3`` is irrelevant: it enters c additively).
    R0 : float
    theta0 : float
        Nutation angle of x3 from y3 (radians), reduced to (-pi, pi]; theta0 = 0 or pi (x3 along
        the radius vector) is the singular line of the Euler chart and is rejected.
    omega_sign : {+1, -1}

    Returns
    -------
    SymmetricMotion

    Raises
    ------
    ValueError
        Non-symmetric satellite, R0 not above the rms radius of the body (see
        :func:`stationary_motion`), sin theta0 = 0, cos(theta0 + kappa0) = 0 (c undefined) or no motion
        (``omega0^2 cos^2 kappa0 <= 0``).

    See Also
    --------
    stability : its verdict from the full second variation.
    symmetric_stability_map : verdicts over arrays of parameters.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eqs. (3.2)-(3.3).

    Examples
    --------
    The second relation (3.3) at :math:`\theta_0 = \pi/4`:
    :math:`\omega_0^2\cos^2\kappa_0 = \mu R_0^{-3}[1 + \frac{3(A_1 - A_3)}{MR_0^2}(1 - \frac32\sin^2\theta_0)]
    = 1.003`, and the third divided by it :math:`\tan\kappa_0 = \frac32(A_1 - A_3)\sin2\theta_0/1.003`:

    >>> import math
    >>> import numpy as np
    >>> from rigidbody import gyrostat
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.01, A2=0.01, A3=0.006)
    >>> ms = gyrostat.symmetric_stationary_motion(sat, 1.0, math.pi / 4)
    >>> print(f"{ms.omega0**2 * math.cos(ms.kappa0)**2:.12f}")
    1.003000000000
    >>> print(f"{ms.kappa0:.12f} {math.atan(1.5 * 0.004 / 1.003):.12f}")
    0.005981982484 0.005981982484
    """
    check_symmetric(sat)
    R0 = positive(R0, "R0")
    check_fits(sat, R0)
    theta0 = float(wrap_angle(real(theta0, "theta0")))
    omega_sign = check_omega_sign(omega_sign)
    if math.sin(theta0) == 0.0:
        raise ValueError(
            "theta0 = 0 or pi: x3 along the radius vector is the singular line of the Euler angles "
            "(theta, psi) of section 3 (the kappa = 0 equilibrium of Rumyantsev [1]); choose theta0 != 0, pi"
        )
    f = symmetric_family_arrays(sat.M, sat.A1, sat.A3, sat.mu, R0, theta0, omega_sign)
    if not f["n2"] > 0:
        raise ValueError("no stationary motion: omega0^2 cos^2 kappa0 <= 0 in (3.3); the body is too large for R0")
    cp = float(f["cos_tk"])
    if cp == 0.0:
        raise ValueError("cos(theta0 + kappa0) = 0: the constant c of (3.3) is undefined")
    if abs(cp) < SINGULAR_TOL or abs(math.sin(theta0)) < SINGULAR_TOL:
        warnings.warn("theta0 is near a singular place of (3.3) or of the Euler chart", GyrostatWarning, stacklevel=2)
    kap = float(f["kappa0"])
    return SymmetricMotion(
        satellite=sat, R0=R0, theta0=theta0, kappa0=kap, omega0=float(f["omega0"]), c=float(f["c"]),
        k=float(f["k"]), S10=float(f["S10"]), point=(R0, kap, theta0, math.pi),
    )
