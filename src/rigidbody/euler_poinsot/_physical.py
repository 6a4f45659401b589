r"""The torque-free motion of any rigid body from a physical state (inertia tensor, body angular velocity,
attitude), in closed form.

The principal moments are sorted :math:`A_1 \ge A_2 \ge A_3` (the paper's order; the principal axes, a proper
rotation of the user's body axes, are kept). The motion circulates about a *rotation axis*: :math:`z_1` when
:math:`G^2 > 2TA_2` (kind ``'max'``), :math:`z_3` when :math:`G^2 < 2TA_2` (``'min'``). In the right-handed
*labelled* frame :math:`(l_1, l_2, l_3)` = :math:`(z_1, z_2, z_3)` for ``'max'``, :math:`(z_3, z_2, -z_1)` for
``'min'``, with moments :math:`(a_1, a_2, a_3)`, :math:`p = |a_1 - a_2|`, :math:`q = |a_1 - a_3|`,
:math:`r = |a_2 - a_3|`, :math:`E_1 = |2Ta_1 - G^2| = a_2p\omega_2^2 + a_3q\omega_3^2`,
:math:`E_3 = |G^2 - 2Ta_3| = a_1q\omega_1^2 + a_2r\omega_2^2` (sums of positive terms: no cancellation), Landau's
solution (Mechanics, sec. 37) reads

.. math::
    \omega_1 = s_1c_1\operatorname{dn}u,\ \omega_2 = -\eta s_1s_3c_2\operatorname{sn}u,\
    \omega_3 = s_3c_3\operatorname{cn}u,\quad u = \lambda t + u_0,\quad
    c_1^2 = \frac{E_3}{a_1q},\ c_2^2 = \frac{E_1}{a_2p},\ c_3^2 = \frac{E_1}{a_3q},\
    \lambda^2 = \frac{pE_3}{a_1a_2a_3},\ m = \frac{rE_1}{pE_3},

:math:`\eta = \operatorname{sign}(a_1 - a_3)`, :math:`s_1 = \operatorname{sign}\omega_1(0)`, :math:`s_3 = 1`
(the separatrix: :math:`\operatorname{sign}\omega_3(0)`), and
:math:`1 - m = q(pa_1\omega_1^2 - ra_3\omega_3^2)/(pE_3)` (the distance from the separatrix, formed once). These
hold for every body with :math:`p > 0`: two equal moments give :math:`r = 0`, :math:`m = 0` (regular
precession), the separatrix :math:`m = 1` (hyperbolic functions). With :math:`l_3` as the polar axis of 3-1-3
angles about :math:`\mathbf G` (never reached by :math:`\mathbf G`),
:math:`\dot\psi = G/a_3 - \eta Gq/(a_1a_3(1 - n\operatorname{sn}^2u))`, :math:`n = -a_3E_1/(a_1E_3) \le 0`,
integrated in closed form by :mod:`._precession`. A state whose angular velocity is an eigenvector of the
inertia tensor (rest, the sphere, a spin about a principal axis of a symmetric body's equal moments, the spin
about the intermediate axis exactly on the separatrix, a spin about a principal axis) is a permanent rotation,
exact to rounding.
"""

from __future__ import annotations

import functools
import math
from typing import Any

import numpy as np
from scipy.spatial.transform import Rotation

from ..core import elliptic as ell
from ..core import euler
from ..core.validate import finite_array
from ._model import KINDS, Body, violates_triangle
from ._precession import elliptic_f, elliptic_pi

__all__ = ["FreeMotion", "as_attitude", "principal_axes"]

#: Relative asymmetry of a tensor still read as symmetric (rounding of a tensor computed in another frame).
SYMMETRY_RTOL = 1e-12


def principal_axes(inertia: Any) -> tuple[np.ndarray, np.ndarray]:
    """Principal moments ``A1 >= A2 >= A3`` and the principal axes (columns, a proper rotation) in body axes.

    ``inertia``: three principal moments (any order; the body axes are principal) or a symmetric
    positive-definite 3x3 tensor. Refused with a ``ValueError`` naming ``inertia``: another shape, asymmetry
    beyond ``SYMMETRY_RTOL``, a moment <= 0, the triangle inequality violated.
    """
    J = finite_array(inertia, "inertia")
    if J.shape == (3, 3) and np.count_nonzero(J - np.diag(np.diag(J))) == 0:
        J = np.diag(J).copy()  # a diagonal tensor: the body axes are principal, kept exactly
    if J.shape == (3,):
        order = np.argsort(-J, kind="stable")
        A, P = J[order], np.eye(3)[:, order]
    elif J.shape == (3, 3):
        scale = float(np.abs(J).max())
        if float(np.abs(J - J.T).max()) > SYMMETRY_RTOL * scale:
            raise ValueError(f"inertia must be a symmetric 3x3 tensor, got {J.tolist()}")
        w, V = np.linalg.eigh(0.5 * (J + J.T))
        A, P = w[::-1].copy(), V[:, ::-1].copy()
    else:
        raise ValueError(f"inertia must be three principal moments or a 3x3 tensor, got shape {J.shape}")
    if not A[2] > 0.0:
        raise ValueError(f"inertia must be positive definite, got principal moments {A.tolist()}")
    if violates_triangle(A[0], A[1], A[2]):
        raise ValueError(f"inertia violates the triangle inequality A1 <= A2 + A3 (no rigid body has these "
                         f"principal moments): {A.tolist()}")
    if np.linalg.det(P) < 0.0:
        P[:, 2] = -P[:, 2]
    return A, P


def as_attitude(attitude: Any) -> Rotation:
    """``attitude`` (body -> inertial) as a SciPy ``Rotation``: a ``Rotation``, a quaternion (scalar last) or a
    direction cosine matrix; ``None`` is the identity."""
    if attitude is None:
        return Rotation.identity()
    if isinstance(attitude, Rotation):
        if not attitude.single:
            raise ValueError("attitude must be a single rotation, got a stack of rotations")
        return attitude
    a = finite_array(attitude, "attitude")
    if a.shape == (4,):
        if not np.linalg.norm(a) > 0.0:
            raise ValueError("attitude: a quaternion must not be zero")
        return Rotation.from_quat(a)
    if a.shape == (3, 3):
        if float(np.abs(a @ a.T - np.eye(3)).max()) > 1e-9 or np.linalg.det(a) < 0.0:
            raise ValueError(f"attitude must be a proper rotation matrix (orthonormal, det +1), got {a.tolist()}")
        return Rotation.from_matrix(a)
    raise ValueError(f"attitude must be a Rotation, a quaternion (x, y, z, w) or a 3x3 matrix, got shape {a.shape}")


def _basis_to_g(g: np.ndarray) -> np.ndarray:
    r""":math:`R_X(\theta)R_Z(\varphi)` of the unit vectors ``g`` (shape (N, 3), third component the polar one):
    the rotation that takes ``g`` to :math:`e_3`, rows :math:`(g_2/\rho, -g_1/\rho, 0)`,
    :math:`(g_3g_1/\rho, g_3g_2/\rho, -\rho)`, :math:`g`; :math:`\rho = \sqrt{g_1^2 + g_2^2} > 0`."""
    g = g / np.linalg.norm(g, axis=-1, keepdims=True)
    g1, g2, g3 = g[:, 0], g[:, 1], g[:, 2]
    rho = np.hypot(g1, g2)
    zero = np.zeros_like(rho)
    return np.stack([np.stack([g2 / rho, -g1 / rho, zero], -1),
                     np.stack([g3 * g1 / rho, g3 * g2 / rho, -rho], -1), g], -2)


def _turn(omega: np.ndarray, t: np.ndarray) -> Rotation:
    """The turns by ``|omega| t`` about ``omega`` (body axes), from the half-angle's sine and cosine (SciPy's
    ``from_rotvec`` loses ~1e-14 at 20 rad)."""
    rate = float(np.linalg.norm(omega))
    if rate == 0.0:
        return Rotation.identity(len(t))
    half = 0.5 * rate * t
    return Rotation.from_quat(np.column_stack([np.sin(half)[:, None] * (omega / rate), np.cos(half)]))


def _rot_z(psi: np.ndarray) -> np.ndarray:
    c, s, o, i = np.cos(psi), np.sin(psi), np.zeros_like(psi), np.ones_like(psi)
    return np.stack([np.stack([c, -s, o], -1), np.stack([s, c, o], -1), np.stack([o, o, i], -1)], -2)


#: The labelled frame of each kind (columns in principal axes): (z1, z2, z3) for 'max', (z3, z2, -z1) for 'min'.
_LABELLED = {"max": np.eye(3), "min": np.array([[0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]])}


class FreeMotion:
    r"""The torque-free motion of a rigid body from its physical state (built by :meth:`EulerPoinsot.from_state`).

    Every body the triangle inequality allows: triaxial, two equal moments (regular precession), the sphere;
    every state: both kinds, exactly on the separatrix (the asymptotic motion in hyperbolic functions, or the
    permanent spin about the intermediate axis), at rest. :class:`Body` stays strict (:math:`A_1 > A_2 > A_3`,
    the paper's formulas (5)-(9) need it): this class carries its own representation, the sorted moments
    ``moments``, the principal axes ``axes`` and Landau's solution in a labelled frame (module docstring of
    ``rigidbody.euler_poinsot._physical``), valid for equal moments too.

    Attributes
    ----------
    moments : numpy.ndarray
        Principal moments ``A1 >= A2 >= A3`` (the paper's order).
    axes : numpy.ndarray
        The principal axes as columns in the user's body axes (a proper rotation): principal components
        of a body vector ``v`` are ``axes.T @ v``.
    G, T : float
        Magnitude of the angular momentum and kinetic energy (the user's units).
    kind : str
        ``'max'`` (:math:`G^2 > 2TA_2`), ``'min'`` (:math:`G^2 < 2TA_2`), ``'separatrix'`` (:math:`G^2 = 2TA_2`,
        not a sphere), ``'sphere'`` or ``'rest'`` (:math:`G = 0`).
    k2, mc : float
        The modulus squared (:math:`0` for two equal moments, :math:`1` on the separatrix) and :math:`1 - k^2`.
    sigma : int
        Sense of rotation: sign of :math:`g_1` (``'max'``, ``'separatrix'``) or :math:`g_3` (``'min'``).
    phase : float
        The paper's initial elliptic argument :math:`u_0` (:meth:`EulerPoinsot.omega`'s ``u0``).
    rate : float
        :math:`\dot u` (0 for a permanent rotation).
    frame : numpy.ndarray
        The paper's frame :math:`Oy_i` (columns in inertial axes, :math:`y_3 \parallel \mathbf G`) in which the
        3-1-3 angles of :meth:`EulerPoinsot.angles` with ``psi0 = 0`` give the attitude of the principal axes.
    momentum : numpy.ndarray
        The angular momentum in inertial axes (constant).
    paper : EulerPoinsot or None
        The paper's motion (``Body(*moments), G, k2, kind, sigma``) for a triaxial body in ``'max'`` or ``'min'``.
    uniform : bool
        Whether the motion is a permanent rotation (the angular velocity an eigenvector of the inertia).

    See Also
    --------
    EulerPoinsot : the paper's torque-free motion in its own variables.
    Spacecraft : the same start state on an orbit, with torques, in SI units.

    Examples
    --------
    An axisymmetric satellite (two equal moments) precesses regularly: the symmetry-axis rate stays, the
    transverse rate turns at :math:`\Omega = (A_t - A_s)\omega_s/A_t` in body axes:

    >>> import numpy as np
    >>> from rigidbody.euler_poinsot import EulerPoinsot
    >>> m = EulerPoinsot.from_state([2.0, 2.0, 1.5], [0.3, 0.0, 1.0])
    >>> m.kind, m.k2, m.paper is None
    ('min', 0.0, True)
    >>> Omega = (2.0 - 1.5) * 1.0 / 2.0
    >>> t = 2.0
    >>> bool(np.allclose(m.omega(t), [0.3 * np.cos(Omega * t), -0.3 * np.sin(Omega * t), 1.0], rtol=0, atol=1e-15))
    True
    """

    def __init__(self, inertia: Any, omega: Any, attitude: Any = None, paper: Any = None) -> None:
        A, P = principal_axes(inertia)
        w_user = finite_array(omega, "omega")
        if w_user.shape != (3,):
            raise ValueError(f"omega must be the body angular velocity, shape (3,), got shape {w_user.shape}")
        R0 = as_attitude(attitude)
        w = P.T @ w_user
        g = A * w
        self.moments, self.axes, self.attitude0, self.omega0 = A, P, R0, w_user
        self.G, self.T = float(np.linalg.norm(g)), 0.5 * float(np.dot(g, w))
        self.momentum = R0.apply(P @ g)
        sep = A[0] * (A[0] - A[1]) * w[0] ** 2 - A[2] * (A[1] - A[2]) * w[2] ** 2
        self.uniform = len(set(A[w != 0.0].tolist())) <= 1  # omega an eigenvector of the inertia
        self.kind = ("rest" if self.G == 0.0 else "sphere" if A[0] == A[2] else
                     "max" if sep > 0.0 else "min" if sep < 0.0 else "separatrix")
        self.k2, self.mc, self.sigma, self.phase, self.rate = 0.0, 1.0, 1, 0.0, 0.0
        if self.uniform:
            self.k2, self.mc = (1.0, 0.0) if self.kind == "separatrix" else (0.0, 1.0)
            self.sigma = -1 if w[2 if self.kind == "min" else 0] < 0.0 else 1
        else:
            self._solution(A, w)
        self._paper_class, self._g = paper, g

    def _solution(self, A: np.ndarray, w: np.ndarray) -> None:
        """Landau's solution in the labelled frame of the kind ('max' labels on the separatrix)."""
        L = _LABELLED["min" if self.kind == "min" else "max"]
        a, wl = np.abs(L.T) @ A, L.T @ w
        p, q, r = abs(a[0] - a[1]), abs(a[0] - a[2]), abs(a[1] - a[2])
        E1 = a[1] * p * wl[1] ** 2 + a[2] * q * wl[2] ** 2
        E3 = a[0] * q * wl[0] ** 2 + a[1] * r * wl[1] ** 2
        on_sep = self.kind == "separatrix"
        self.mc = 0.0 if on_sep else float(q * (p * a[0] * wl[0] ** 2 - r * a[2] * wl[2] ** 2) / (p * E3))
        self.k2 = 1.0 if on_sep else float(min(r * E1 / (p * E3), 1.0))
        self._eta = 1.0 if a[0] > a[2] else -1.0
        s1, s3 = (1.0 if wl[0] > 0.0 else -1.0), (-1.0 if on_sep and wl[2] < 0.0 else 1.0)
        self._signs = (s1, -self._eta * s1 * s3, s3)
        # sqrt(E1) as a hypot: E1 underflows for a state within 1e-154 of the rotation axis
        sn0, cn0 = -self._eta * s1 * s3 * wl[1] * math.sqrt(a[1] * p), s3 * wl[2] * math.sqrt(a[2] * q)
        root_E1 = math.hypot(sn0, cn0)
        self._amp = (math.sqrt(E3 / (a[0] * q)), root_E1 / math.sqrt(a[1] * p), root_E1 / math.sqrt(a[2] * q))
        self.rate = math.sqrt(p * E3 / (a[0] * a[1] * a[2]))
        self._u0 = elliptic_f(sn0, cn0, self.mc)
        # sn, cn, dn of u0 from the state itself (exact to rounding, unlike sn(F(phi0)))
        self._jac0 = (sn0 / root_E1, cn0 / root_E1, abs(wl[0]) * math.sqrt(a[0] * q / E3))
        self._n = -a[2] * E1 / (a[0] * E3)
        self._cpsi = self._eta * self.G * q / (a[0] * a[2])
        self._a, self._L = a, L
        self.sigma = int(s1)
        K = float(ell.K(mc=self.mc)) if self.mc > 0.0 else math.inf
        self.phase = self._u0 if self.kind != "min" else math.remainder(self._u0 + 2.0 * K, 4.0 * K)
        self._F = self.attitude0.as_matrix() @ self.axes @ L @ _basis_to_g(self._a * self._omega_l(np.zeros(1)))[0].T

    def _jacobi(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        r""":math:`\operatorname{sn}, \operatorname{cn}, \operatorname{dn}` of :math:`u_0 + \lambda t`: by the addition
        theorem (DLMF 22.8.1-3) from those of :math:`u_0` where its denominator :math:`1 - m s_0^2 s^2 \ge 1/2`
        (so that ``t = 0`` gives the state back to rounding), directly elsewhere (no cancellation near the
        separatrix)."""
        sv, cv, dv, _ = ell.jacobi(self.rate * t, mc=self.mc)
        s0, c0, d0 = self._jac0
        den = 1.0 - self.k2 * s0 * s0 * sv * sv
        add = ((s0 * cv * dv + sv * c0 * d0) / den, (c0 * cv - s0 * sv * d0 * dv) / den,
               (d0 * dv - self.k2 * s0 * sv * c0 * cv) / den)
        if np.all(den >= 0.5):
            return add
        sn, cn, dn, _ = ell.jacobi(self.rate * t + self._u0, mc=self.mc)
        good = den >= 0.5
        return np.where(good, add[0], sn), np.where(good, add[1], cn), np.where(good, add[2], dn)

    def _omega_l(self, t: np.ndarray) -> np.ndarray:
        """Angular velocity in the labelled frame, shape ``t.shape + (3,)``."""
        sn, cn, dn = self._jacobi(t)
        (s1, s2, s3), (c1, c2, c3) = self._signs, self._amp
        return np.stack([s1 * c1 * np.asarray(dn), s2 * c2 * np.asarray(sn), s3 * c3 * np.asarray(cn)], -1)

    @functools.cached_property
    def paper(self) -> Any:
        """The paper's :class:`EulerPoinsot` (triaxial body, kind ``'max'`` or ``'min'``), else ``None``."""
        A = self.moments
        if self._paper_class is None or self.kind not in KINDS or not A[0] > A[1] > A[2]:
            return None
        body = Body(float(A[0]), float(A[1]), float(A[2]))
        return self._paper_class(body, self.G, self.k2, self.kind, self.sigma, mc=self.mc)

    @functools.cached_property
    def frame(self) -> np.ndarray:
        """:math:`Oy_i` in inertial axes: the attitude of the principal axes times the inverse of the paper's
        3-1-3 angles at ``t = 0`` (``psi = 0``)."""
        if self.paper is not None:
            _, theta, phi = self.paper.angles(0.0, self.phase)
        else:
            g = self._g
            theta, phi = math.atan2(math.hypot(g[0], g[1]), g[2]), math.atan2(g[0], g[1])
        return np.asarray(self.attitude0.as_matrix() @ self.axes @ euler.dcm(0.0, theta, phi).T)

    def __repr__(self) -> str:
        m = ", ".join(f"{a:.6g}" for a in self.moments)
        return (f"<FreeMotion moments=({m}) G={self.G:.6g} T={self.T:.6g} kind={self.kind!r} k2={self.k2:.6g} "
                f"sigma={self.sigma:+d}>")

    @property
    def period(self) -> float:
        r"""Period of the body angular velocity, :math:`4K/\dot u` (``inf`` on the separatrix, 0 for a permanent
        rotation).

        Examples
        --------
        After one period the body angular velocity is back where it started:

        >>> import numpy as np
        >>> from rigidbody import euler_poinsot as ep
        >>> f = ep.EulerPoinsot.from_state(np.diag([2.0, 1.5, 1.0]), [0.3, 0.2, 1.0])
        >>> bool(np.allclose(f.omega(f.period), [0.3, 0.2, 1.0], rtol=0.0, atol=1e-14))
        True
        """
        if self.uniform:
            return 0.0
        return 4.0 * float(ell.K(mc=self.mc)) / self.rate if self.mc > 0.0 else math.inf

    def psi(self, t: Any) -> np.ndarray:
        r"""The precession angle about :math:`\mathbf G` of the labelled polar axis :math:`l_3`, from 0 at ``t = 0``
        (closed form, :mod:`._precession`).

        Examples
        --------
        The rate against Landau's :math:`\dot\psi = G(A_1\omega_1^2 + A_2\omega_2^2)/(A_1^2\omega_1^2 +
        A_2^2\omega_2^2)` (polar axis :math:`A_3` for ``'max'``), by a central difference:

        >>> import numpy as np
        >>> from rigidbody import euler_poinsot as ep
        >>> f = ep.EulerPoinsot.from_state(np.diag([2.0, 1.5, 1.0]), [1.0, 0.2, 0.3])
        >>> w, A = f.axes.T @ f.omega(1.0), f.moments
        >>> landau = f.G * (A[0] * w[0]**2 + A[1] * w[1]**2) / (A[0]**2 * w[0]**2 + A[1]**2 * w[1]**2)
        >>> rate = (f.psi(1.0 + 1e-4) - f.psi(1.0 - 1e-4)) / 2e-4  # truncation h**2/6 |psi'''| ~ 1e-9
        >>> print(f.kind, abs(rate - landau) < 1e-8)
        max True
        """
        t = finite_array(t, "t")
        if self.uniform:
            raise ValueError("psi is not defined for a permanent rotation (kind "
                             f"{self.kind!r}): use rotation(t)")
        u, u0 = self.rate * t + self._u0, self._u0
        span = elliptic_pi(u, self._n, self.mc, *self._jacobi(t)) - elliptic_pi(u0, self._n, self.mc, *self._jac0)
        return np.asarray(self.G / self._a[2] * t - self._cpsi / self.rate * span)

    def omega(self, t: Any) -> np.ndarray:
        r"""Angular velocity in the user's body axes at times ``t`` (units of 1/omega), shape ``t.shape + (3,)``.

        Examples
        --------
        The kinetic energy :math:`\frac12\boldsymbol\omega\cdot I\boldsymbol\omega` stays at its start value:

        >>> import numpy as np
        >>> from rigidbody import euler_poinsot as ep
        >>> I = np.array([[2.0, 0.1, 0.0], [0.1, 1.5, 0.0], [0.0, 0.0, 1.0]])
        >>> w = ep.EulerPoinsot.from_state(I, [0.3, 0.2, 1.0]).omega(np.linspace(0.0, 20.0, 5))
        >>> print(np.round(0.5 * np.einsum("ti,ij,tj->t", w, I, w), 12))
        [0.626 0.626 0.626 0.626 0.626]
        """
        t = finite_array(t, "t")
        if self.uniform:
            return np.broadcast_to(self.omega0, (*t.shape, 3)).copy()
        return np.asarray(self._omega_l(t) @ (self.axes @ self._L).T)

    def rotation(self, t: Any) -> Rotation:
        r"""Attitude (body -> inertial) at times ``t``: one ``Rotation`` for a scalar ``t``, else a stack over the
        flattened ``t``.

        Examples
        --------
        The body's angular momentum :math:`I\boldsymbol\omega` turned to the inertial axes is the same vector
        at every time:

        >>> import numpy as np
        >>> from rigidbody import euler_poinsot as ep
        >>> I = np.diag([2.0, 1.5, 1.0])
        >>> f = ep.EulerPoinsot.from_state(I, [0.3, 0.2, 1.0])
        >>> t = np.linspace(0.0, 20.0, 5)
        >>> print(np.round(f.rotation(t).apply(f.omega(t) @ I), 12))
        [[0.6 0.3 1. ]
         [0.6 0.3 1. ]
         [0.6 0.3 1. ]
         [0.6 0.3 1. ]
         [0.6 0.3 1. ]]
        """
        t = finite_array(t, "t")
        flat = t.reshape(-1)
        if self.uniform:
            R = self.attitude0 * _turn(self.omega0, flat)
        else:
            B = _basis_to_g(self._a * self._omega_l(flat))
            M = self._F @ _rot_z(self.psi(flat)) @ B @ (self.axes @ self._L).T
            R = Rotation.from_matrix(M)
        return R[0] if t.ndim == 0 else R
