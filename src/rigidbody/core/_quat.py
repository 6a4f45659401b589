r"""Scalar-first quaternions :math:`q = (w, x, y, z)`: products, kinematics and conversions to and from the
direction-cosine matrix and the 3-1-3 Euler angles of :mod:`rigidbody.core.euler`.

The functions are public in :mod:`rigidbody.core.euler` (listed in its ``__all__``), where the convention
is stated; this module holds their implementation and the array check the Euler-angle functions share.
"""

from __future__ import annotations

from typing import Any

import numpy as np


def real_array(x: Any, name: str) -> np.ndarray:
    """Return ``x`` as a float array, checked real and finite (the array check of the Euler-angle functions).

    A TypeError names the parameter ``name`` if ``x`` is not real numbers, a ValueError if an entry is NaN
    or infinite.
    """
    try:
        a = np.asarray(x, dtype=float)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{name} must be real numbers, got {x!r}") from exc
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite")
    return a


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
    qa, qb = np.broadcast_arrays(real_array(a, "a"), real_array(b, "b"))
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
    om = real_array(omega_body, "omega_body")
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
    ps, th, ph = np.broadcast_arrays(real_array(psi, "psi"), real_array(theta, "theta"), real_array(phi, "phi"))
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
    qa = real_array(q, "q")
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
    Ra = real_array(R, "R")
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
