"""The amended potential W, the constraint chi (2.1), W1 = W + lambda chi and its gradient (2.2).

Coordinates (Stepanov 1968, section 2): ``x = (R, kappa, beta1, beta3, gamma1, gamma2)``; the
dependent direction cosines are ``beta2 = b2 * sqrt(1 - beta1^2 - beta3^2)`` and
``gamma3 = b3 * sqrt(1 - gamma1^2 - gamma2^2)`` with the square-root *branches* ``branch = (b2, b3)``,
each +1 or -1.  The branch is part of the state: a stationary motion with ``cos(theta0 + kappa0) < 0``
lives on ``b2 = -1``.
"""

from __future__ import annotations

from types import ModuleType
from typing import Any

import numpy as np

from ._model import Satellite

__all__ = ["amended_potential", "amended_potential_W", "chi", "gradient_W1"]


def _check_branch(branch: tuple[int, int]) -> tuple[int, int]:
    try:
        b2, b3 = branch
    except (TypeError, ValueError):
        raise TypeError("branch must be a pair (sign of beta2, sign of gamma3), each +1 or -1") from None
    if b2 not in (1, -1) or b3 not in (1, -1):
        raise ValueError(f"branch entries must be +1 or -1; got {branch!r}")
    return int(b2), int(b3)


def _check_domain(q: Any, name: str) -> None:
    """Real direction cosines need ``q = 1 - (sum of two squares) >= 0`` (complex/mpc input: not checked)."""
    a = np.asarray(q)
    if np.iscomplexobj(a):
        return
    try:
        bad = any(v < 0 for v in a.ravel()) if a.dtype == object else bool(np.any(a < 0))
    except TypeError:  # mpmath.mpc and the like (complex-step routes)
        return
    if bad:
        raise ValueError(f"{name} must be <= 1 (direction cosines): the point is outside the domain of W")


def _dependent(x: Any, branch: tuple[int, int], lib: ModuleType) -> tuple[Any, Any]:
    b2s, g3s = _check_branch(branch)
    _, _, b1, b3, g1, g2 = x
    qb, qg = 1 - b1 * b1 - b3 * b3, 1 - g1 * g1 - g2 * g2
    _check_domain(qb, "beta1^2 + beta3^2")
    _check_domain(qg, "gamma1^2 + gamma2^2")
    beta2 = b2s * lib.sqrt(qb)
    gamma3 = g3s * lib.sqrt(qg)
    return beta2, gamma3


def amended_potential_W(
    sat: Satellite, x: Any, *, k: float, branch: tuple[int, int] = (1, 1), lib: ModuleType = np
) -> Any:
    """The amended potential energy ``W = K^2 / (2 S) - U`` of section 2 (Routh function of sigma).

    ``K = k - k1 beta1 - k2 beta2 - k3 beta3``, ``S = M R^2 cos^2 kappa + sum A_i beta_i^2``,
    ``U = mu M / R - 3/2 mu R^-3 [sum A_i gamma_i^2 - (A1 + A2 + A3)/3]``.

    Parameters
    ----------
    sat : Satellite
    x : sequence of 6
        ``(R, kappa, beta1, beta3, gamma1, gamma2)``; scalars or broadcastable arrays.
    k : float
        Area constant (the integral of the cyclic coordinate sigma).
    branch : (int, int)
        Signs of ``beta2`` and ``gamma3``.
    lib : module
        Provides ``sqrt``, ``sin``, ``cos``: ``numpy`` (default; complex input gives the complex-step
        route), ``math`` or ``mpmath`` (extended precision).

    Returns
    -------
    scalar or ndarray
        ``W`` in units of energy, of the type ``lib`` produces.

    See Also
    --------
    amended_potential : ``W1 = W + lambda chi``.
    symmetric_potential : the W of section 3 in Euler angles.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, section 2.

    Examples
    --------
    Body axes along the orbital axes (``beta = (0, 1, 0)``, ``gamma = (0, 0, 1)``), the body of
    :class:`Satellite` at ``R = 1``: ``S = M + A2 = 1.01``, ``U = 1 - 3/2 (A3 - Abar) = 1.003``, so with
    ``k = 1.01`` the amended potential is ``W = 1.01/2 - 1.003 = -0.498``:

    >>> from rigidbody import gyrostat
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    >>> print(f"{gyrostat.amended_potential_W(sat, (1.0, 0.0, 0.0, 0.0, 0.0, 0.0), k=1.01):.12f}")
    -0.498000000000
    """
    R, kap, b1, b3, g1, g2 = x
    b2, g3 = _dependent(x, branch, lib)
    K = k - sat.k1 * b1 - sat.k2 * b2 - sat.k3 * b3
    ck = lib.cos(kap)
    S = sat.M * R * R * ck * ck + sat.A1 * b1 * b1 + sat.A2 * b2 * b2 + sat.A3 * b3 * b3
    Atr = sat.A1 + sat.A2 + sat.A3
    U = sat.mu * sat.M / R - 1.5 * sat.mu / R**3 * (
        sat.A1 * g1 * g1 + sat.A2 * g2 * g2 + sat.A3 * g3 * g3 - Atr / 3
    )
    return K * K / (2 * S) - U


def chi(x: Any, *, branch: tuple[int, int] = (1, 1), lib: ModuleType = np) -> Any:
    """The constraint (2.1): ``chi = beta1 gamma1 + beta2 gamma2 + beta3 gamma3 - sin(kappa)``.

    ``beta . gamma = cos(angle between zeta2 and OG) = sin(kappa)``: the geometric tie between the
    attitude coordinates and the latitude of the centre of mass (section 2).

    Parameters
    ----------
    x : sequence of 6
        ``(R, kappa, beta1, beta3, gamma1, gamma2)``; scalars or broadcastable arrays (``kappa`` in radians,
        direction cosines dimensionless; ``R`` does not enter).
    branch : (int, int)
        Signs of ``beta2`` and ``gamma3`` (each +1 or -1).
    lib : module
        Provides ``sqrt``, ``sin``: ``numpy`` (default; complex input gives the complex-step route),
        ``math`` or ``mpmath`` (extended precision).

    Returns
    -------
    scalar or ndarray
        The dimensionless value of chi (0 on the constraint), of the type ``lib`` produces.

    Raises
    ------
    TypeError
        If ``branch`` is not a pair.
    ValueError
        If a ``branch`` entry is not +1 or -1, or a real point has ``beta1^2 + beta3^2 > 1`` or
        ``gamma1^2 + gamma2^2 > 1`` (no real ``beta2`` or ``gamma3``).

    See Also
    --------
    constraint_gradient : its gradient at a motion (2.3).

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eq. (2.1).

    Examples
    --------
    With ``beta = (0, 1, 0)`` and ``gamma = (0, 0, 1)`` orthogonal, ``chi = -sin(kappa)``; on a motion (2.3) it
    vanishes:

    >>> import math
    >>> from rigidbody import gyrostat
    >>> print(f"{gyrostat.chi((1.0, 0.1, 0.0, 0.0, 0.0, 0.0)):.12f} {-math.sin(0.1):.12f}")
    -0.099833416647 -0.099833416647
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    >>> m = gyrostat.stationary_motion(sat, 1.0, 0.3, k2=0.02)
    >>> bool(abs(gyrostat.chi(m.point, branch=m.branch)) < 1e-15)
    True
    """
    _, kap, b1, b3, g1, g2 = x
    b2, g3 = _dependent(x, branch, lib)
    return b1 * g1 + b2 * g2 + b3 * g3 - lib.sin(kap)


def amended_potential(
    sat: Satellite,
    x: Any,
    *,
    k: float,
    lam: float,
    branch: tuple[int, int] = (1, 1),
    lib: ModuleType = np,
) -> Any:
    """``W1 = W + lambda chi`` (section 2), the function whose stationary points are the motions.

    See :func:`amended_potential_W` for the parameters; ``lam`` is the Lagrange multiplier.
    ``chi`` is the constraint (2.1); the first derivatives of W1 are (2.2) (:func:`gradient_W1`) and its
    stationary points with ``chi = 0`` include the family (2.3)-(2.4), where ``lam = lambda0``.

    Parameters
    ----------
    sat : Satellite
        Mass properties, ``mu`` and gyrostatic momentum ``k1, k2, k3`` (any consistent units, e.g. SI or
        nondimensional ``M = mu = R0 = 1``).
    x : sequence of 6
        ``(R, kappa, beta1, beta3, gamma1, gamma2)``; scalars or broadcastable arrays (``R`` a length,
        ``kappa`` in radians, the direction cosines dimensionless).
    k : float
        Area constant (the integral of the cyclic coordinate sigma), an angular momentum.
    lam : float
        Lagrange multiplier of the constraint (2.1), an energy (``lambda0 = M R0^2 omega0^2 sin kappa0`` at
        (2.3)).
    branch : (int, int)
        Signs of ``beta2`` and ``gamma3``.
    lib : module
        ``numpy`` (default; complex input gives the complex-step route), ``math`` or ``mpmath``.

    Returns
    -------
    scalar or ndarray
        ``W1`` in units of energy, of the type ``lib`` produces.

    Raises
    ------
    TypeError
        If ``branch`` is not a pair.
    ValueError
        If a ``branch`` entry is not +1 or -1, or a real point has ``beta1^2 + beta3^2 > 1`` or
        ``gamma1^2 + gamma2^2 > 1``.

    See Also
    --------
    gradient_W1 : its first derivatives (2.2).
    hessian_W1 : its second derivatives at a motion.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, section 2, eqs. (2.1)-(2.2).

    Examples
    --------
    A motion (2.3) is a stationary point of W1 (its complex-step gradient vanishes), and there ``chi = 0``,
    so ``W1 = W``:

    >>> import math
    >>> import numpy as np
    >>> from rigidbody import gyrostat
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    >>> m = gyrostat.stationary_motion(sat, 1.0, 0.3, k2=0.02)
    >>> from rigidbody.core.quadform import gradient_cs
    >>> def W1(x):
    ...     return gyrostat.amended_potential(m.satellite, x, k=m.k, lam=m.lambda0, branch=m.branch)
    >>> bool(np.abs(gradient_cs(W1, m.point)).max() < 1e-14)
    True
    >>> W = gyrostat.amended_potential_W(m.satellite, m.point, k=m.k, branch=m.branch)
    >>> print(f"{W1(m.point):.12f} {W:.12f}")
    -0.493678922608 -0.493678922608
    """
    return amended_potential_W(sat, x, k=k, branch=branch, lib=lib) + lam * chi(x, branch=branch, lib=lib)


def gradient_W1(
    sat: Satellite, x: Any, *, k: float, lam: float, branch: tuple[int, int] = (1, 1)
) -> np.ndarray:
    """The first derivatives (2.2) of ``W1`` (closed form, valid at any point, not only stationary).

    Parameters
    ----------
    sat : Satellite
        Mass properties, ``mu`` and gyrostatic momentum ``k1, k2, k3``.
    x : sequence of 6
        ``(R, kappa, beta1, beta3, gamma1, gamma2)``; scalars or broadcastable arrays.
    k : float
        Area constant.
    lam : float
        Lagrange multiplier of the constraint (2.1).
    branch : (int, int)
        Signs of ``beta2`` and ``gamma3``.

    Returns
    -------
    ndarray, shape (6, ...)
        ``dW1/dR, dW1/dkappa, dW1/dbeta1, dW1/dbeta3, dW1/dgamma1, dW1/dgamma2``.

    See Also
    --------
    amended_potential : ``W1`` itself.
    hessian_W1 : the second derivatives at a motion (2.3).

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eq. (2.2).

    Examples
    --------
    The closed form agrees with the complex-step derivative of :func:`amended_potential` at any point, and
    (2.2) vanishes at a motion (2.3):

    >>> import math
    >>> import numpy as np
    >>> from rigidbody import gyrostat
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    >>> m = gyrostat.stationary_motion(sat, 1.0, 0.3, k2=0.02)
    >>> from rigidbody.core.quadform import gradient_cs
    >>> x = (1.1, 0.05, 0.1, 0.2, 0.1, -0.3)
    >>> g_cs = gradient_cs(lambda z: gyrostat.amended_potential(sat, z, k=1.0, lam=0.01), x)
    >>> np.allclose(gyrostat.gradient_W1(sat, x, k=1.0, lam=0.01), g_cs, rtol=0, atol=1e-14)
    True
    >>> g = gyrostat.gradient_W1(m.satellite, m.point, k=m.k, lam=m.lambda0, branch=m.branch)
    >>> bool(np.abs(g).max() < 1e-14)
    True
    """
    R, kap, b1, b3, g1, g2 = (np.asarray(v, dtype=float) for v in x)
    b2, g3 = _dependent((R, kap, b1, b3, g1, g2), branch, np)
    M, A1, A2, A3, mu = sat.M, sat.A1, sat.A2, sat.A3, sat.mu
    K = k - sat.k1 * b1 - sat.k2 * b2 - sat.k3 * b3
    ck = np.cos(kap)
    S = M * R**2 * ck**2 + A1 * b1**2 + A2 * b2**2 + A3 * b3**2
    KS, KS2 = K / S, (K / S) ** 2
    dR = (
        -KS2 * M * R * ck**2
        + M * mu / R**2
        - 4.5 * mu / R**4 * ((A1 - A3) * g1**2 + (A2 - A3) * g2**2 + (2 * A3 - A1 - A2) / 3)
    )
    dk = KS2 * M * R**2 * np.sin(kap) * ck - lam * ck
    db1 = KS * (-sat.k1 + sat.k2 * b1 / b2) - KS2 * (A1 - A2) * b1 + lam * (g1 - g2 * b1 / b2)
    db3 = KS * (-sat.k3 + sat.k2 * b3 / b2) - KS2 * (A3 - A2) * b3 + lam * (g3 - g2 * b3 / b2)
    dg1 = 3 * mu / R**3 * (A1 - A3) * g1 + lam * (b1 - b3 * g1 / g3)
    dg2 = 3 * mu / R**3 * (A2 - A3) * g2 + lam * (b2 - b3 * g2 / g3)
    return np.stack(np.broadcast_arrays(dR, dk, db1, db3, dg1, dg2))
