r"""A body with two equal principal moments (the axisymmetric satellite, the sphere): :class:`SymmetricBody` and the
algebra of its torque-free motion, the regular precession.

Body axes: :math:`z_1, z_2` transverse (moment :math:`A`), :math:`z_3` the symmetry axis (moment :math:`C`); the
sphere is :math:`A = C`. With :math:`\mathbf G` of magnitude :math:`G` at the nutation angle :math:`\theta` from
:math:`z_3` (:math:`c = \cos\theta`), the body components are
:math:`\mathbf g = G(\sin\theta\sin\varphi, \sin\theta\cos\varphi, \cos\theta)` and

.. math::
    \boldsymbol\omega = (g_1/A, g_2/A, g_3/C),\qquad
    2T = G^2\Bigl(\frac{1-c^2}{A} + \frac{c^2}{C}\Bigr),\qquad
    \dot\psi = G/A,\qquad \dot\varphi = Gc\Bigl(\frac1C - \frac1A\Bigr)

(:math:`\psi` the precession angle about :math:`\mathbf G`, :math:`\varphi` the azimuth of :math:`\mathbf G` in the
body about :math:`z_3`, turning opposite to the body's proper rotation). The attitude (body -> orbital axes) is
:math:`C = Y R_3(\psi) R_1(\theta) R_3(\varphi)` with :math:`Y = (\mathbf y_1, \mathbf y_2, \mathbf n)` of
:func:`._model.frame_y`. Under a torque :math:`\mathbf M` (body components) the symmetry-axis component obeys
:math:`\dot g_3 = M_3` exactly (the gyroscopic term :math:`(\mathbf g\times\boldsymbol\omega)_3` vanishes when
:math:`A_1 = A_2`), so :math:`\dot c = (M_3 - c\,\mathbf M\cdot\mathbf g/G)/G`: the slow variables
:math:`(G\mathbf n, c)` have no separatrix (:math:`c` passes 0, the spin about a transverse axis, smoothly).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, TypeGuard

import numpy as np

from ..core import euler
from ..core.validate import real
from ._model import Body

__all__ = ["SymmetricBody", "attitude", "check_any_body", "cos_theta_of", "energy", "is_symmetric", "kind_fields",
           "momentum_body", "omega_body"]


@dataclass(frozen=True)
class SymmetricBody:
    r"""A rigid body with two equal principal moments: the axisymmetric satellite (and the sphere, ``A = C``).

    Parameters
    ----------
    A : float
        The transverse moment (about the body axes :math:`z_1, z_2`).
    C : float
        The moment about the symmetry axis :math:`z_3` (the paper's scaling, as :class:`Body`). A real body has
        :math:`C \le 2A` (the triangle inequality).

    Raises
    ------
    TypeError
        If a moment is not a real number.
    ValueError
        If a moment is not positive and finite or ``C > 2 A``.

    See Also
    --------
    Body : the triaxial body (:math:`A_1 > A_2 > A_3`).
    averaged : its averaged evolution over the regular precession (``theta0`` the initial nutation angle).

    Notes
    -----
    The torque-free motion is the regular precession: :math:`\mathbf G` fixed, the body turning about it at
    :math:`G/A` and about its own axis, which keeps the nutation angle :math:`\theta` to :math:`\mathbf G`. The
    averaged evolution averages over both angles (no resonance between them); the sphere (``A = C``) has no
    proper rotation to average over, and its averaged evolution keeps the direction of :math:`\mathbf G` in the
    body as a slow variable (see :func:`averaged`).

    Examples
    --------
    A prolate body (spin axis of the least moment, as Explorer 1) and an oblate one (LAGEOS); their kinetic energy
    at the nutation angle :math:`\theta` lies between :math:`G^2/2A` and :math:`G^2/2C`:

    >>> from rigidbody import euler_poinsot as ep
    >>> body = ep.SymmetricBody(A=2.0, C=1.0)
    >>> body.shape, body.A.tolist()
    ('prolate', [2.0, 2.0, 1.0])
    >>> ep.SymmetricBody(A=1.0, C=1.04).shape
    'oblate'
    >>> ep.SymmetricBody(A=1.0, C=2.5)
    Traceback (most recent call last):
    ...
    ValueError: triangle inequality C <= 2 A violated: C=2.5 > 2 A=2.0
    """

    transverse: float
    axial: float

    def __init__(self, A: float, C: float) -> None:
        vals = {"A": real(A, "A"), "C": real(C, "C")}
        for name, v in vals.items():
            if not (0.0 < v < math.inf):
                raise ValueError(f"{name} must be positive and finite, got {v!r}")
        if vals["C"] > 2.0 * vals["A"] * (1.0 + 1e-12):
            raise ValueError(f"triangle inequality C <= 2 A violated: C={vals['C']} > 2 A={2.0 * vals['A']}")
        object.__setattr__(self, "transverse", vals["A"])
        object.__setattr__(self, "axial", vals["C"])

    def __repr__(self) -> str:
        return f"SymmetricBody(A={self.transverse!r}, C={self.axial!r})"

    @property
    def A(self) -> np.ndarray:
        """The principal moments in body order ``[A, A, C]`` (the symmetry axis third).

        Examples
        --------
        >>> from rigidbody import euler_poinsot as ep
        >>> ep.SymmetricBody(3.0, 5.0).A
        array([3., 3., 5.])
        """
        return np.array([self.transverse, self.transverse, self.axial])

    @property
    def A1(self) -> float:
        """The moment about :math:`z_1` (the transverse one; ``A1``, ``A2``, ``A3`` in body order, as :class:`Body`'s
        attributes, for the torques built from a body's moments).

        Examples
        --------
        >>> from rigidbody import euler_poinsot as ep
        >>> b = ep.SymmetricBody(3.0, 5.0)
        >>> b.A1, b.A2, b.A3
        (3.0, 3.0, 5.0)
        """
        return self.transverse

    @property
    def A2(self) -> float:
        """The moment about :math:`z_2` (the transverse one).

        Examples
        --------
        >>> from rigidbody import euler_poinsot as ep
        >>> ep.SymmetricBody(3.0, 5.0).A2
        3.0
        """
        return self.transverse

    @property
    def A3(self) -> float:
        """The moment about the symmetry axis :math:`z_3`.

        Examples
        --------
        >>> from rigidbody import euler_poinsot as ep
        >>> ep.SymmetricBody(3.0, 5.0).A3
        5.0
        """
        return self.axial

    @property
    def shape(self) -> str:
        """``'oblate'`` (``C > A``: the symmetry axis of the largest moment), ``'prolate'`` (``C < A``) or
        ``'sphere'``.

        Examples
        --------
        >>> from rigidbody import euler_poinsot as ep
        >>> ep.SymmetricBody(3.0, 3.0).shape
        'sphere'
        """
        return "oblate" if self.axial > self.transverse else "prolate" if self.axial < self.transverse else "sphere"


def check_any_body(body: Any) -> Any:
    """``body`` if it is a :class:`Body` or a :class:`SymmetricBody`, a ``TypeError`` otherwise."""
    if not isinstance(body, (Body, SymmetricBody)):
        raise TypeError(f"body must be a Body or a SymmetricBody, got {type(body).__name__}")
    return body


def is_symmetric(body: Any) -> TypeGuard[SymmetricBody]:
    """Whether ``body`` is a :class:`SymmetricBody` (the runs' one test of which system to integrate)."""
    return isinstance(body, SymmetricBody)


def energy(body: SymmetricBody, G: Any, c: Any) -> Any:
    """The kinetic energy at ``G`` and ``c = cos(theta)``."""
    return 0.5 * G * G * ((1.0 - c * c) / body.transverse + c * c / body.axial)


def cos_theta_of(body: SymmetricBody, G: float, T: float, sigma: int) -> float:
    """``cos(theta)`` (sign ``sigma``) from ``G`` and the energy ``T`` (a ``ValueError`` for a ``T`` outside the
    range the body allows at this ``G``)."""
    A, C = body.transverse, body.axial
    lo, hi = sorted((0.5 * G * G / A, 0.5 * G * G / C))
    if not (lo * (1.0 - 1e-14) <= T <= hi * (1.0 + 1e-14)):
        raise ValueError(f"T0 must lie between G0^2/2A and G0^2/2C for this body ([{lo!r}, {hi!r}]), got {T!r}")
    if A == C:
        raise ValueError("the sphere's energy does not fix the nutation angle: give theta0")
    c2 = (2.0 * T / (G * G) - 1.0 / A) / (1.0 / C - 1.0 / A)
    return sigma * math.sqrt(min(max(c2, 0.0), 1.0))


def kind_fields(body: SymmetricBody, c: Any) -> dict[str, np.ndarray]:
    """The triaxial fields a symmetric body's result carries at the nutation cosines ``c`` (the limits of a
    near-symmetric body's): ``k2`` 0, ``kind`` ``'max'`` (oblate, the sphere) or ``'min'`` (prolate), ``sigma`` the
    sign of ``c`` (+1 at 0)."""
    c = np.asarray(c, dtype=float)
    return {"k2": np.zeros(c.shape), "kind": np.full(c.shape, "max" if body.axial >= body.transverse else "min"),
            "sigma": np.where(c < 0.0, -1, 1)}


def momentum_body(G: float, theta: float, phi: Any) -> np.ndarray:
    r"""The body components of G at the nutation angle ``theta`` and the body azimuths ``phi`` (shape
    ``np.shape(phi) + (3,)``): :math:`G(\sin\theta\sin\varphi, \sin\theta\cos\varphi, \cos\theta)`."""
    phi = np.asarray(phi, dtype=float)
    s = math.sin(theta)
    return G * np.stack([s * np.sin(phi), s * np.cos(phi), np.full_like(phi, math.cos(theta))], axis=-1)


def omega_body(body: SymmetricBody, g: np.ndarray) -> np.ndarray:
    """The angular velocity of body components ``g`` of G (shape ``(..., 3)``)."""
    return g / body.A


def attitude(Y: np.ndarray, psi: np.ndarray, theta: float, phi: np.ndarray) -> np.ndarray:
    r""":math:`C = Y R_3(\psi) R_1(\theta) R_3(\varphi)` on the grid ``psi[:, None], phi[None, :]``: shape
    ``(n_psi, n_phi, 3, 3)``."""
    R = euler.dcm(psi[:, None], theta, phi[None, :])
    return np.einsum("ij,...jk->...ik", Y, R)

