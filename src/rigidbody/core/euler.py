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


def _arr(x: Any, name: str) -> np.ndarray:
    try:
        a = np.asarray(x, dtype=float)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{name} must be real numbers, got {x!r}") from exc
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite")
    return a


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
    ps, th, ph = np.broadcast_arrays(_arr(psi, "psi"), _arr(theta, "theta"), _arr(phi, "phi"))
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
    Ra = _arr(R, "R")
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
    th, ph = _arr(theta, "theta"), _arr(phi, "phi")
    a, b, c = _arr(dpsi, "dpsi"), _arr(dtheta, "dtheta"), _arr(dphi, "dphi")
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
    th, ph = _arr(theta, "theta"), _arr(phi, "phi")
    pa, qa, ra = _arr(p, "p"), _arr(q, "q"), _arr(r, "r")
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


def quat_multiply(a: Any, b: Any) -> np.ndarray:
    r"""Hamilton product ``a ⊗ b`` of scalar-first quaternions.

    Parameters
    ----------
    a, b : array_like
        Quaternions ``(w, x, y, z)``, shape ``(..., 4)``, broadcast over the leading axes.

    Returns
    -------
    numpy.ndarray
        Shape ``(..., 4)``. With rotations, ``a ⊗ b`` applies ``b`` first (in the frame of ``a``).

    See Also
    --------
    quat_rate : the kinematics :math:`\dot q = \tfrac12 q\otimes(0, \omega)`.

    Examples
    --------
    Hamilton's rules :math:`ij = k`, :math:`ji = -k`:

    >>> from rigidbody.core.euler import quat_multiply
    >>> quat_multiply([0, 1, 0, 0], [0, 0, 1, 0])
    array([0., 0., 0., 1.])
    >>> quat_multiply([0, 0, 1, 0], [0, 1, 0, 0])
    array([ 0.,  0.,  0., -1.])
    """
    qa, qb = np.broadcast_arrays(_arr(a, "a"), _arr(b, "b"))
    w1, x1, y1, z1 = np.moveaxis(qa, -1, 0)
    w2, x2, y2, z2 = np.moveaxis(qb, -1, 0)
    return np.stack(
        [
            w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
            w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
            w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
        ],
        axis=-1,
    )


def quat_rate(q: Any, omega_body: Any) -> np.ndarray:
    r"""Quaternion kinematics :math:`\dot q = \tfrac12\,q\otimes(0, \omega)`.

    Parameters
    ----------
    q : array_like
        Attitude quaternion (body -> reference), shape ``(..., 4)``, scalar first.
    omega_body : array_like
        Angular velocity in **body** components ``(p, q, r)``, shape ``(..., 3)``.

    Returns
    -------
    numpy.ndarray
        :math:`\dot q`, shape ``(..., 4)``. Integrate it instead of the Euler angles: it has no
        singularity at :math:`\theta = 0, \pi`.

    See Also
    --------
    euler_rates : the same kinematics in Euler angles.
    quat_multiply : the product it uses.

    Examples
    --------
    A spin at the rate 2 about the body :math:`z` axis from the identity: :math:`\dot q = (0, 0, 0, 1)`,
    the derivative of :math:`(\cos t, 0, 0, \sin t)` at :math:`t = 0`:

    >>> from rigidbody.core.euler import quat_rate
    >>> quat_rate([1, 0, 0, 0], [0, 0, 2])
    array([0., 0., 0., 1.])
    """
    om = _arr(omega_body, "omega_body")
    zero = np.zeros((*om.shape[:-1], 1))
    return 0.5 * quat_multiply(q, np.concatenate([zero, om], axis=-1))


def quat_from_euler(psi: Any, theta: Any, phi: Any) -> np.ndarray:
    r"""Scalar-first unit quaternion of the rotation :func:`dcm`.

    Parameters
    ----------
    psi, theta, phi : array_like
        3-1-3 Euler angles (radians), broadcast together.

    Returns
    -------
    numpy.ndarray
        Shape ``(..., 4)``, ``(w, x, y, z)``; the sign is not normalised (``w`` may be negative).

    See Also
    --------
    euler_from_quat : the inverse.
    dcm : the same rotation as a matrix.

    Examples
    --------
    A quarter turn about :math:`Z` is :math:`(\cos\frac\pi4, 0, 0, \sin\frac\pi4)`:

    >>> import numpy as np
    >>> from rigidbody.core.euler import dcm, dcm_from_quat, quat_from_euler
    >>> print(np.round(quat_from_euler(np.pi / 2, 0.0, 0.0), 6))
    [0.707107 0.       0.       0.707107]
    >>> np.allclose(dcm_from_quat(quat_from_euler(0.3, 0.5, 0.7)), dcm(0.3, 0.5, 0.7), rtol=0, atol=1e-15)
    True
    """
    ps, th, ph = np.broadcast_arrays(_arr(psi, "psi"), _arr(theta, "theta"), _arr(phi, "phi"))
    ch = np.cos(0.5 * th)
    sh = np.sin(0.5 * th)
    sp = 0.5 * (ps + ph)
    dm = 0.5 * (ps - ph)
    return np.stack([ch * np.cos(sp), sh * np.cos(dm), sh * np.sin(dm), ch * np.sin(sp)], axis=-1)


def dcm_from_quat(q: Any) -> np.ndarray:
    """Rotation matrix (body -> reference) of a quaternion.

    Parameters
    ----------
    q : array_like
        Shape ``(..., 4)``, scalar first; normalised before use (it must be non-zero).

    Returns
    -------
    numpy.ndarray
        Shape ``(..., 3, 3)``, the same convention as :func:`dcm`.

    Raises
    ------
    ValueError
        If the shape is not ``(..., 4)`` or a quaternion is zero.

    See Also
    --------
    dcm_from_unit_quat : the same from the components of a unit quaternion, unchecked.
    quat_from_dcm : the inverse.

    Examples
    --------
    >>> from rigidbody.core.euler import dcm_from_quat
    >>> dcm_from_quat([2.0, 0.0, 0.0, 0.0])  # normalised first: the identity
    array([[1., 0., 0.],
           [0., 1., 0.],
           [0., 0., 1.]])
    """
    qa = _arr(q, "q")
    if qa.shape[-1] != 4:
        raise ValueError(f"q must have shape (..., 4), got {qa.shape}")
    nrm = np.linalg.norm(qa, axis=-1, keepdims=True)
    if np.any(nrm == 0.0):
        raise ValueError("q must be non-zero")
    return dcm_from_unit_quat(*np.moveaxis(qa / nrm, -1, 0))


def dcm_from_unit_quat(w: Any, x: Any, y: Any, z: Any) -> np.ndarray:
    """Direction cosine matrix (body -> reference) of a unit quaternion given by its components.

    The rotation of :func:`dcm_from_quat` without its checks and normalisation, for right-hand sides that
    hold the quaternion as separate state rows.

    Parameters
    ----------
    w, x, y, z : float or array_like
        Components of a unit quaternion (scalar part first), arrays of one shape.

    Returns
    -------
    numpy.ndarray
        Shape ``(..., 3, 3)``: ``x_ref = R @ x_body``.

    See Also
    --------
    dcm_from_quat : the checked version (any shape ``(..., 4)``, normalised).

    Examples
    --------
    A quarter turn about :math:`z` takes the body :math:`x` axis to the reference :math:`y` axis:

    >>> import numpy as np
    >>> from rigidbody.core.euler import dcm_from_unit_quat
    >>> c = np.sqrt(0.5)
    >>> R = dcm_from_unit_quat(c, 0.0, 0.0, c)
    >>> np.allclose(R @ [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], rtol=0, atol=1e-15)
    True
    """
    R = np.empty((*np.shape(w), 3, 3))
    R[..., 0, 0] = 1 - 2 * (y * y + z * z)
    R[..., 0, 1] = 2 * (x * y - w * z)
    R[..., 0, 2] = 2 * (x * z + w * y)
    R[..., 1, 0] = 2 * (x * y + w * z)
    R[..., 1, 1] = 1 - 2 * (x * x + z * z)
    R[..., 1, 2] = 2 * (y * z - w * x)
    R[..., 2, 0] = 2 * (x * z - w * y)
    R[..., 2, 1] = 2 * (y * z + w * x)
    R[..., 2, 2] = 1 - 2 * (x * x + y * y)
    return R


def quat_from_dcm(R: Any) -> np.ndarray:
    r"""Scalar-first unit quaternion of a rotation matrix, by Shepperd's stable method.

    Parameters
    ----------
    R : array_like
        Rotation matrices (body -> reference), shape ``(..., 3, 3)``.

    Returns
    -------
    numpy.ndarray
        Shape ``(..., 4)``, normalised, with ``w >= 0``.

    See Also
    --------
    dcm_from_quat : the inverse (up to the sign of the quaternion).

    References
    ----------
    S. W. Shepperd, "Quaternion from rotation matrix", Journal of Guidance and Control 1(3), 223-224 (1978).

    Examples
    --------
    The turn by :math:`2\pi/3` about :math:`(1, 1, 1)/\sqrt3` permutes the axes; its quaternion is
    :math:`(\cos\frac\pi3, \sin\frac\pi3(1, 1, 1)/\sqrt3) = (1, 1, 1, 1)/2`:

    >>> from rigidbody.core.euler import dcm_from_quat, quat_from_dcm
    >>> quat_from_dcm([[0, 0, 1], [1, 0, 0], [0, 1, 0]])
    array([0.5, 0.5, 0.5, 0.5])

    ``q`` and ``-q`` are the same rotation; the one with ``w >= 0`` is returned:

    >>> quat_from_dcm(dcm_from_quat([-0.5, 0.5, 0.5, 0.5]))
    array([ 0.5, -0.5, -0.5, -0.5])
    """
    Ra = _arr(R, "R")
    if Ra.shape[-2:] != (3, 3):
        raise ValueError(f"R must have shape (..., 3, 3), got {Ra.shape}")
    tr = Ra[..., 0, 0] + Ra[..., 1, 1] + Ra[..., 2, 2]
    diag = np.stack([tr, Ra[..., 0, 0], Ra[..., 1, 1], Ra[..., 2, 2]], axis=-1)
    choice = np.argmax(diag, axis=-1)
    q = np.empty((*tr.shape, 4))
    # four candidate formulas; pick the one with the largest pivot
    cands = []
    w = np.sqrt(np.maximum(1 + tr, 0.0)) / 2
    ws = np.where(w == 0, 1.0, w)
    cands.append(
        np.stack([w, (Ra[..., 2, 1] - Ra[..., 1, 2]) / (4 * ws), (Ra[..., 0, 2] - Ra[..., 2, 0]) / (4 * ws),
                  (Ra[..., 1, 0] - Ra[..., 0, 1]) / (4 * ws)], axis=-1)
    )
    for i in range(3):
        j, k = (i + 1) % 3, (i + 2) % 3
        v = np.sqrt(np.maximum(1 + 2 * Ra[..., i, i] - tr, 0.0)) / 2
        vs = np.where(v == 0, 1.0, v)
        comp = np.empty((*tr.shape, 4))
        comp[..., 0] = (Ra[..., k, j] - Ra[..., j, k]) / (4 * vs)
        comp[..., 1 + i] = v
        comp[..., 1 + j] = (Ra[..., j, i] + Ra[..., i, j]) / (4 * vs)
        comp[..., 1 + k] = (Ra[..., k, i] + Ra[..., i, k]) / (4 * vs)
        cands.append(comp)
    stacked = np.stack(cands, axis=0)
    q = np.take_along_axis(stacked, choice[None, ..., None], axis=0)[0]
    q = np.where(q[..., :1] < 0, -q, q)
    return q / np.linalg.norm(q, axis=-1, keepdims=True)


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
    va = _arr(v, "v")
    if va.shape[-1] != 3:
        raise ValueError(f"v must have shape (..., 3), got {va.shape}")
    x, y, z = np.moveaxis(va, -1, 0)
    S = np.zeros((*va.shape[:-1], 3, 3))
    S[..., 0, 1], S[..., 0, 2] = -z, y
    S[..., 1, 0], S[..., 1, 2] = z, -x
    S[..., 2, 0], S[..., 2, 1] = -y, x
    return S
