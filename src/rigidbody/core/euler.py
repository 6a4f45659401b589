r"""3-1-3 Euler angles, direction cosines and quaternions.

Convention (used by all four papers)
------------------------------------
The reference frame :math:`OXYZ` is turned into the body frame :math:`Oxyz` by three rotations:
:math:`\psi` (precession) about :math:`Z`, :math:`\theta` (nutation) about the line of nodes, and
:math:`\varphi` (proper rotation) about the body axis :math:`z`:

.. math:: R = R_Z(\psi)\,R_X(\theta)\,R_Z(\varphi), \qquad x_{\rm ref} = R\,x_{\rm body}.

So ``R`` maps **body components to reference components**; its columns are the body axes written in
the reference frame, its rows the reference axes written in the body frame; the body symmetry axis is
``R[..., :, 2] = (sin θ sin ψ, -sin θ cos ψ, cos θ)`` and the reference :math:`Z` axis in body components
is ``R[..., 2, :] = (sin θ sin φ, sin θ cos φ, cos θ)``. It is SciPy's intrinsic
``Rotation.from_euler('ZXZ', [psi, theta, phi]).as_matrix()``.

Degenerate-angle rule
---------------------
At :math:`\sin\theta = 0` only :math:`\psi+\varphi` (:math:`\theta=0`) or :math:`\psi-\varphi`
(:math:`\theta=\pi`) is defined. :func:`angles` then returns :math:`\varphi = 0` and
:math:`\psi = \operatorname{atan2}(R_{21}, R_{11})` — no warning, no NaN. "Degenerate" means
:math:`\sqrt{R_{13}^2+R_{23}^2} \le 10^{-12}`; below that the split of the angle between
:math:`\psi` and :math:`\varphi` carries no information.

Quaternions are scalar-first, :math:`q = (w, x, y, z)`, and represent the same rotation as ``R``.
Angular velocity :math:`\omega` in **body** components (p, q, r) gives :math:`\dot q = \tfrac12 q\otimes(0,\omega)`.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ._quat import (
    dcm_from_quat,
    dcm_from_unit_quat,
    quat_from_dcm,
    quat_from_euler,
    quat_multiply,
    quat_rate,
    real_array,
)

__all__ = [
    "DEGENERATE_SIN_THETA",
    "angles",
    "body_rates",
    "dcm",
    "dcm_from_quat",
    "dcm_from_unit_quat",
    "euler_from_quat",
    "euler_rates",
    "quat_from_dcm",
    "quat_from_euler",
    "quat_multiply",
    "quat_rate",
    "skew",
]

#: Below this sin(theta) the angles are split by the degenerate-angle rule.
DEGENERATE_SIN_THETA = 1e-12

def _out(x: np.ndarray) -> Any:
    return float(x) if np.ndim(x) == 0 else x


def dcm(psi: Any, theta: Any, phi: Any) -> np.ndarray:
    r"""Direction-cosine matrix :math:`R = R_Z(\psi)R_X(\theta)R_Z(\varphi)` (body -> reference).

    Parameters
    ----------
    psi, theta, phi : array_like
        Precession, nutation and proper-rotation angles (radians), broadcast together.

    Returns
    -------
    numpy.ndarray
        Shape ``(..., 3, 3)``; ``x_ref = R @ x_body``.

    See Also
    --------
    angles : the inverse, the angles of a matrix.
    quat_from_euler : the same rotation as a quaternion.
    dcm_from_quat : the matrix of a quaternion.

    Examples
    --------
    >>> import numpy as np
    >>> from rigidbody.core.euler import dcm
    >>> R = dcm(0.3, 0.5, 0.7)
    >>> np.allclose(R @ R.T, np.eye(3), rtol=0, atol=1e-15)
    True

    The third column is the body symmetry axis :math:`(\sin\theta\sin\psi, -\sin\theta\cos\psi,
    \cos\theta)`, and ``R`` is SciPy's intrinsic z-x-z rotation:

    >>> np.allclose(R[:, 2], [np.sin(0.5) * np.sin(0.3), -np.sin(0.5) * np.cos(0.3), np.cos(0.5)], rtol=0, atol=1e-15)
    True
    >>> from scipy.spatial.transform import Rotation
    >>> np.allclose(R, Rotation.from_euler("ZXZ", [0.3, 0.5, 0.7]).as_matrix(), rtol=0, atol=1e-15)
    True
    """
    ps, th, ph = np.broadcast_arrays(real_array(psi, "psi"), real_array(theta, "theta"), real_array(phi, "phi"))
    c1, s1 = np.cos(ps), np.sin(ps)
    c2, s2 = np.cos(th), np.sin(th)
    c3, s3 = np.cos(ph), np.sin(ph)
    R = np.empty((*ps.shape, 3, 3))
    R[..., 0, 0] = c1 * c3 - s1 * c2 * s3
    R[..., 0, 1] = -c1 * s3 - s1 * c2 * c3
    R[..., 0, 2] = s1 * s2
    R[..., 1, 0] = s1 * c3 + c1 * c2 * s3
    R[..., 1, 1] = -s1 * s3 + c1 * c2 * c3
    R[..., 1, 2] = -c1 * s2
    R[..., 2, 0] = s2 * s3
    R[..., 2, 1] = s2 * c3
    R[..., 2, 2] = c2
    return R


def angles(R: Any) -> tuple[Any, Any, Any]:
    r"""Euler angles :math:`(\psi, \theta, \varphi)` of a direction-cosine matrix (inverse of :func:`dcm`).

    Parameters
    ----------
    R : array_like
        Shape ``(..., 3, 3)``, a rotation matrix (body -> reference).

    Returns
    -------
    psi, phi : float or numpy.ndarray
        In :math:`(-\pi, \pi]`.
    theta : float or numpy.ndarray
        In :math:`[0, \pi]`.

    Notes
    -----
    At :math:`\sin\theta \le 10^{-12}` the degenerate-angle rule applies: :math:`\varphi = 0`,
    :math:`\psi = \operatorname{atan2}(R_{21}, R_{11})`.

    See Also
    --------
    dcm : the inverse, the matrix of the angles.
    euler_from_quat : the angles of a quaternion.

    Examples
    --------
    >>> from rigidbody.core.euler import angles, dcm
    >>> print(*(f"{a:.12f}" for a in angles(dcm(0.3, 0.5, 0.7))))
    0.300000000000 0.500000000000 0.700000000000

    At :math:`\theta = 0` only :math:`\psi + \varphi` is defined: it is returned as :math:`\psi`:

    >>> angles(dcm(0.3, 0.0, 0.2))
    (0.5, 0.0, 0.0)
    """
    Ra = real_array(R, "R")
    if Ra.shape[-2:] != (3, 3):
        raise ValueError(f"R must have shape (..., 3, 3), got {Ra.shape}")
    r13, r23, r33 = Ra[..., 0, 2], Ra[..., 1, 2], Ra[..., 2, 2]
    r31, r32 = Ra[..., 2, 0], Ra[..., 2, 1]
    st = np.hypot(r13, r23)
    theta = np.arctan2(st, r33)
    deg = st <= DEGENERATE_SIN_THETA
    psi = np.where(deg, np.arctan2(Ra[..., 1, 0], Ra[..., 0, 0]), np.arctan2(r13, -r23))
    phi = np.where(deg, 0.0, np.arctan2(r31, r32))
    return _out(psi), _out(theta), _out(phi)


def body_rates(theta: Any, phi: Any, dpsi: Any, dtheta: Any, dphi: Any) -> tuple[Any, Any, Any]:
    r"""Body components of the angular velocity from Euler-angle rates (kinematic equations).

    .. math::
        p = \dot\psi\sin\theta\sin\varphi + \dot\theta\cos\varphi,\quad
        q = \dot\psi\sin\theta\cos\varphi - \dot\theta\sin\varphi,\quad
        r = \dot\psi\cos\theta + \dot\varphi

    (the kinematic part of Akulenko, Leshchenko & Chernousko (1.1)).

    Parameters
    ----------
    theta, phi : array_like
        Nutation and proper-rotation angles.
    dpsi, dtheta, dphi : array_like
        Euler-angle rates.

    Returns
    -------
    p, q, r : float or numpy.ndarray

    See Also
    --------
    euler_rates : the inverse.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`,
    eq. (1.1) (its kinematic part, inverted).

    Examples
    --------
    A pure precession at the rate 2: the angular velocity has the magnitude 2 and the components
    :math:`(0, 2\sin\theta, 2\cos\theta)` at :math:`\varphi = 0`:

    >>> import math
    >>> from rigidbody.core.euler import body_rates
    >>> p, q, r = body_rates(0.5, 0.0, 2.0, 0.0, 0.0)
    >>> print(p, f"{q:.12f} {2 * math.sin(0.5):.12f} {math.hypot(p, q, r):.12f}")
    0.0 0.958851077208 0.958851077208 2.000000000000
    """
    th, ph = real_array(theta, "theta"), real_array(phi, "phi")
    a, b, c = real_array(dpsi, "dpsi"), real_array(dtheta, "dtheta"), real_array(dphi, "dphi")
    st, sp, cp = np.sin(th), np.sin(ph), np.cos(ph)
    p = a * st * sp + b * cp
    q = a * st * cp - b * sp
    r = a * np.cos(th) + c
    return _out(p), _out(q), _out(r)


def euler_rates(theta: Any, phi: Any, p: Any, q: Any, r: Any) -> tuple[Any, Any, Any]:
    r"""Euler-angle rates from the body angular velocity (inverse kinematic equations).

    .. math::
        \dot\psi = \frac{p\sin\varphi + q\cos\varphi}{\sin\theta},\quad
        \dot\theta = p\cos\varphi - q\sin\varphi,\quad
        \dot\varphi = r - \dot\psi\cos\theta

    Parameters
    ----------
    theta, phi : array_like
        Nutation and proper-rotation angles.
    p, q, r : array_like
        Body components of the angular velocity.

    Returns
    -------
    dpsi, dtheta, dphi : float or numpy.ndarray

    Raises
    ------
    ValueError
        If :math:`\sin\theta = 0` anywhere (the rates of :math:`\psi` and :math:`\varphi` are undefined
        there; integrate in quaternions instead).

    See Also
    --------
    body_rates : the inverse.
    quat_rate : the kinematics without the singularity at :math:`\sin\theta = 0`.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`,
    eq. (1.1) (its kinematic part).

    Examples
    --------
    >>> from rigidbody.core.euler import body_rates, euler_rates
    >>> p, q, r = body_rates(0.5, 0.7, 0.3, -0.2, 1.1)
    >>> print(*(f"{x:.12f}" for x in euler_rates(0.5, 0.7, p, q, r)))
    0.300000000000 -0.200000000000 1.100000000000
    >>> euler_rates(0.0, 0.7, p, q, r)
    Traceback (most recent call last):
        ...
    ValueError: theta must not be 0 or pi (|sin theta| <= 1e-12): Euler-angle rates are singular there; ...
    """
    th, ph = real_array(theta, "theta"), real_array(phi, "phi")
    pa, qa, ra = real_array(p, "p"), real_array(q, "q"), real_array(r, "r")
    st = np.sin(th)
    if np.any(np.abs(st) <= DEGENERATE_SIN_THETA):
        raise ValueError(
            "theta must not be 0 or pi (|sin theta| <= 1e-12): Euler-angle rates are singular there; "
            "use quaternions (quat_rate) instead"
        )
    sp, cp = np.sin(ph), np.cos(ph)
    dpsi = (pa * sp + qa * cp) / st
    dtheta = pa * cp - qa * sp
    dphi = ra - dpsi * np.cos(th)
    return _out(dpsi), _out(dtheta), _out(dphi)

def euler_from_quat(q: Any) -> tuple[Any, Any, Any]:
    r"""3-1-3 Euler angles of a quaternion (through :func:`dcm_from_quat` and :func:`angles`).

    Parameters
    ----------
    q : array_like
        Shape ``(..., 4)``, scalar first.

    Returns
    -------
    psi, theta, phi : float or numpy.ndarray
        As :func:`angles`, including its degenerate-angle rule at :math:`\sin\theta = 0`.

    See Also
    --------
    quat_from_euler : the inverse.

    Examples
    --------
    >>> from rigidbody.core.euler import euler_from_quat, quat_from_euler
    >>> print(*(f"{a:.12f}" for a in euler_from_quat(quat_from_euler(0.3, 0.5, 0.7))))
    0.300000000000 0.500000000000 0.700000000000
    """
    return angles(dcm_from_quat(q))


def skew(v: Any) -> np.ndarray:
    """Cross-product matrix.

    Parameters
    ----------
    v : array_like
        Vectors, shape ``(..., 3)``.

    Returns
    -------
    numpy.ndarray
        Shape ``(..., 3, 3)`` with ``skew(v) @ w == np.cross(v, w)``.

    See Also
    --------
    quat_rate : the kinematics, a product with (0, omega).

    Examples
    --------
    >>> import numpy as np
    >>> from rigidbody.core.euler import skew
    >>> skew([1.0, 2.0, 3.0])
    array([[ 0., -3.,  2.],
           [ 3.,  0., -1.],
           [-2.,  1.,  0.]])
    >>> skew([1.0, 2.0, 3.0]) @ [4.0, 5.0, 6.0], np.cross([1.0, 2.0, 3.0], [4.0, 5.0, 6.0])
    (array([-3.,  6., -3.]), array([-3.,  6., -3.]))
    """
    va = real_array(v, "v")
    if va.shape[-1] != 3:
        raise ValueError(f"v must have shape (..., 3), got {va.shape}")
    x, y, z = np.moveaxis(va, -1, 0)
    S = np.zeros((*va.shape[:-1], 3, 3))
    S[..., 0, 1], S[..., 0, 2] = -z, y
    S[..., 1, 0], S[..., 1, 2] = z, -x
    S[..., 2, 0], S[..., 2, 1] = -y, x
    return S
