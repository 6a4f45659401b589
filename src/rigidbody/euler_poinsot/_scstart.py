r"""A spacecraft's start as the paper's nondimensional problem: :class:`PaperStart` and :func:`paper_start`, which
reads it from the torque-free motion of the spacecraft's state relative to the orbital axes (a triaxial body in the
paper's variables, a body with two equal moments as a :class:`SymmetricBody`)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.spatial.transform import Rotation

from ._full import initial_state
from ._kepler import KeplerOrbit
from ._model import Body, Orbit, frame_y
from ._physical import SYMMETRY_RTOL, FreeMotion
from ._symbody import SymmetricBody
from ._symfull import symmetric_start

__all__ = ["PaperStart", "angles_of", "paper_start", "symmetry_axes"]


@dataclass(frozen=True, eq=False)
class PaperStart:
    r"""A spacecraft's start as the paper's nondimensional problem (built by :attr:`Spacecraft.paper`).

    The arguments of :func:`averaged`/:func:`simulate` (``body, eps, G0, k2_0, delta0, lam0, nu0``, ``kind``,
    ``sigma``, ``orbit``, ``u0``, ``psi0``) and the scales that lead back to SI units.

    Attributes
    ----------
    body : Body or SymmetricBody
        :math:`\tilde A_i = A_i\Omega_0/G_0` (principal moments, :math:`A_1 > A_2 > A_3`; a
        :class:`SymmetricBody` when two moments are equal to 1e-12 relative, its symmetry axis third).
    eps : float
        :math:`n/\Omega_0`.
    G0, k2_0, kind, sigma : float, float, str, int
        :math:`\tilde G_0 = 1`, the modulus squared, ``'max'``/``'min'``, the sense of rotation (a
        :class:`SymmetricBody`: 0, ``'max'`` oblate or ``'min'`` prolate, the sign of :math:`\cos\theta_0`).
    delta0, lam0 : float
        Polar angle and azimuth of :math:`\mathbf G` in the orbital axes :math:`Ox_i` (rad).
    u0, psi0, nu0 : float
        Elliptic phase (a :class:`SymmetricBody`: the azimuth :math:`\varphi_0` of :math:`\mathbf G` in the
        body), precession angle about :math:`\mathbf G` (see :func:`initial_state`) and true anomaly.
    orbit : Orbit
        The paper's orbit (its eccentricity).
    Omega0, G_unit : float
        The units: :math:`\Omega_0 = |\boldsymbol\omega(0)|` (rad/s), :math:`G_0 = |\mathbf G(0)|` (N m s).
    axes : numpy.ndarray
        The principal axes (columns) in the user's body axes (a :class:`SymmetricBody`: its axes, the symmetry
        axis third).
    to_inertial : scipy.spatial.transform.Rotation
        :math:`Ox_i` -> the user's inertial frame.
    theta0 : float or None
        A :class:`SymmetricBody`'s nutation angle of :math:`\mathbf G` from its symmetry axis (None otherwise).

    See Also
    --------
    Spacecraft : builds it (``Spacecraft.paper``).
    averaged, simulate : the functions its arguments are for.

    Examples
    --------
    The paper's moments are the physical ones in units of :math:`G_0/\Omega_0`, and a torque of
    ``torque_unit`` N m is 1 in the module's equations:

    >>> from rigidbody.euler_poinsot import KeplerOrbit, Spacecraft
    >>> p = Spacecraft([12.0, 10.0, 7.0], [0.0, 0.0, 0.1], orbit=KeplerOrbit(mean_motion=1e-3)).paper
    >>> A = (p.body.A1, p.body.A2, p.body.A3)
    >>> print(", ".join(f"{a:.6f}" for a in A), f"eps = {p.eps:.6f}", p.kind, p.k2_0)
    1.714286, 1.428571, 1.000000 eps = 0.010000 min 0.0
    >>> print(f"{p.torque_unit:.1e} N m, {p.tau_per_second:.1e} per second")
    7.0e-06 N m, 1.0e-05 per second
    """

    body: Body | SymmetricBody
    eps: float
    G0: float
    k2_0: float
    kind: str
    sigma: int
    delta0: float
    lam0: float
    u0: float
    psi0: float
    nu0: float
    orbit: Orbit
    Omega0: float
    G_unit: float
    axes: np.ndarray
    to_inertial: Rotation
    theta0: float | None = None

    @property
    def tau_per_second(self) -> float:
        r""":math:`d\tau/dt = \varepsilon^2\Omega_0` (1/s).

        Examples
        --------
        A spin of 0.1 rad/s on an orbit of mean motion 0.001 rad/s (:math:`\varepsilon = 0.01`): one unit of the
        slow time is :math:`1/(10^{-4}\cdot 0.1)` s, a little under 28 hours:

        >>> from rigidbody.euler_poinsot import KeplerOrbit, Spacecraft
        >>> p = Spacecraft([12.0, 10.0, 7.0], [0.1, 0.0, 0.0], orbit=KeplerOrbit(mean_motion=1e-3)).paper
        >>> print(f"{1.0 / p.tau_per_second / 3600.0:.4f} h")
        27.7778 h
        """
        return self.eps**2 * self.Omega0

    @property
    def torque_unit(self) -> float:
        r"""The torque (N m) that is 1 in the module's scaling: :math:`G_0\varepsilon^2\Omega_0`.

        Examples
        --------
        It changes :math:`G` by :math:`G_0` in one unit of the slow time (:math:`d\tilde G/d\tau = 1`):

        >>> from rigidbody.euler_poinsot import KeplerOrbit, Spacecraft
        >>> p = Spacecraft([12.0, 10.0, 7.0], [0.1, 0.0, 0.0], orbit=KeplerOrbit(mean_motion=1e-3)).paper
        >>> print(f"{p.torque_unit / p.tau_per_second:.6f} N m s = G0 = {p.G_unit:.6f} N m s")
        1.200000 N m s = G0 = 1.200000 N m s
        """
        return self.G_unit * self.eps**2 * self.Omega0

    def physical(self, g: Any, R: Any) -> tuple[np.ndarray, Rotation]:
        r"""The angular velocity (rad/s, user's body axes) and the attitude (body -> inertial) of the paper's
        body components :math:`\tilde{\mathbf g}` (shape ``(..., 3)``) and attitudes ``R`` (principal axes ->
        :math:`Ox_i`, a ``Rotation``).

        Examples
        --------
        The paper's :math:`\tilde{\mathbf g} = (1, 0, 0)` along the axis of the largest moment, in the user's
        units: a spin of :math:`G_0/A_1` rad/s about the axis of :math:`A_1`, here the user's first axis:

        >>> from scipy.spatial.transform import Rotation
        >>> from rigidbody.euler_poinsot import KeplerOrbit, Spacecraft
        >>> p = Spacecraft([12.0, 10.0, 7.0], [0.1, 0.0, 0.0], orbit=KeplerOrbit(mean_motion=1e-3)).paper
        >>> omega, R = p.physical([1.0, 0.0, 0.0], Rotation.identity())
        >>> print([f"{w:.6f}" for w in omega], f"{p.G_unit / 12.0:.6f}")
        ['0.100000', '0.000000', '0.000000'] 0.100000
        """
        A = np.array([self.body.A1, self.body.A2, self.body.A3])
        omega = self.Omega0 * (np.asarray(g, dtype=float) / A) @ self.axes.T
        return omega, self.to_inertial * R * Rotation.from_matrix(self.axes.T)

    def state(self) -> tuple[np.ndarray, Rotation]:
        """The physical state the paper's start describes: the angular velocity (rad/s, user's body axes) and the
        attitude (body -> inertial), through :func:`initial_state` (the start of :func:`simulate`).

        Examples
        --------
        The round trip physical -> paper -> physical gives the state back to rounding:

        >>> import numpy as np
        >>> from scipy.spatial.transform import Rotation
        >>> from rigidbody.euler_poinsot import KeplerOrbit, Spacecraft
        >>> R = Rotation.from_euler("zyx", [0.3, -1.0, 2.0])
        >>> sc = Spacecraft([12.0, 10.0, 7.0], [0.03, -0.08, 0.05], R, orbit=KeplerOrbit(altitude=700e3))
        >>> omega, attitude = sc.paper.state()
        >>> print(np.abs(omega - [0.03, -0.08, 0.05]).max() < 1e-15, (attitude * R.inv()).magnitude() < 1e-13)
        True True
        """
        if isinstance(self.body, SymmetricBody):
            assert self.theta0 is not None
            st = symmetric_start(self.body, self.G0, self.theta0, self.delta0, self.lam0, self.u0, self.psi0)
            return self.physical(st["g"], Rotation.from_matrix(st["R"]))
        st = initial_state(self.body, self.G0, self.k2_0, self.delta0, self.lam0, kind=self.kind, u0=self.u0,
                           psi0=self.psi0, sigma=self.sigma)
        return self.physical(st["g"], Rotation.from_matrix(st["R"]))


def angles_of(n: np.ndarray) -> tuple[float, float]:
    """Polar angle from x3 and azimuth of the unit vector ``n`` (azimuth 0 at a pole)."""
    return math.atan2(math.hypot(n[0], n[1]), n[2]), math.atan2(n[1], n[0])


def _refusal(motion: FreeMotion) -> str:
    """Why the paper's problem cannot start from this motion, and what to do."""
    A = ", ".join(f"{a:.17g}" for a in motion.moments)
    if motion.kind == "rest":
        return "the body is at rest (G = 0): the paper's scaling takes |G(0)| as the unit of angular momentum"
    if motion.kind == "separatrix":
        return ("the state lies exactly on the separatrix (G^2 = 2 T A2, k^2 = 1), where the paper's variables "
                "(k^2 < 1, a kind of motion) are undefined: start next to it (the torque-free motion on it is "
                "EulerPoinsot.from_state)")
    raise AssertionError(f"a paper's start exists for the moments ({A}) in the kind {motion.kind!r}")


def symmetry_axes(A: np.ndarray) -> tuple[float, float, list[int]] | None:
    """For sorted principal moments ``A`` with two equal to ``SYMMETRY_RTOL`` relative (the rounding of a tensor
    computed in other axes): the transverse and axial moments and the principal axes that are z1, z2, z3 of the
    :class:`SymmetricBody` (a cyclic order: a proper rotation); None for a triaxial body."""
    tol = SYMMETRY_RTOL * float(A[0])
    if A[0] - A[2] <= tol:  # the sphere: its moments made exactly equal
        return float(np.mean(A)), float(np.mean(A)), [0, 1, 2]
    if A[0] - A[1] <= tol:  # A1 = A2 (the sphere too): the symmetry axis is that of A3
        return 0.5 * float(A[0] + A[1]), float(A[2]), [0, 1, 2]
    if A[1] - A[2] <= tol:  # A2 = A3: the symmetry axis is that of A1
        return 0.5 * float(A[1] + A[2]), float(A[0]), [1, 2, 0]
    return None


def paper_start(m: FreeMotion, orbit: KeplerOrbit) -> PaperStart:
    """The paper's start of the torque-free motion ``m`` (the state relative to the orbital axes) on ``orbit``; a
    ``ValueError`` for a state the paper's problem does not describe (at rest, exactly on a triaxial separatrix)."""
    if m.kind == "rest":
        raise ValueError(f"Spacecraft: {_refusal(m)}")
    Omega0 = float(np.linalg.norm(m.omega0))
    sym = symmetry_axes(m.moments)
    if sym is None:
        ep = m.paper
        if ep is None:
            raise ValueError(f"Spacecraft: {_refusal(m)}")
        A = m.moments * (Omega0 / m.G)
        F = m.frame  # Oy_i in Ox_i
        delta, lam = angles_of(F[:, 2])
        Rz = frame_y(delta, lam).T @ F
        return PaperStart(Body(float(A[0]), float(A[1]), float(A[2])), orbit.n / Omega0, 1.0, m.k2, m.kind, m.sigma,
                          delta, lam, m.phase, math.atan2(Rz[1, 0], Rz[0, 0]), orbit.nu0, orbit.paper, Omega0, m.G,
                          m.axes, orbit.to_inertial())
    At, C, order = sym
    Q = m.axes[:, order]  # z1, z2, z3 of the symmetric body in the user's body axes
    body = SymmetricBody(At * Omega0 / m.G, C * Omega0 / m.G)
    g = Q.T @ (m.axes @ (m.moments * (m.axes.T @ m.omega0)))  # G in the symmetric body's axes
    g = g / np.linalg.norm(g)
    theta = math.atan2(math.hypot(g[0], g[1]), g[2])
    phi = math.atan2(g[0], g[1])
    R = m.attitude0.as_matrix() @ Q  # the symmetric body's axes -> the orbital axes
    n = R @ g
    delta, lam = angles_of(n)
    # R = Y R3(psi) R1(theta) R3(phi): R3(psi) = Y^T R R3(phi)^T R1(theta)^T
    R3 = frame_y(delta, lam).T @ R @ Rotation.from_euler("XZ", [theta, phi]).as_matrix().T
    kind = "max" if body.axial >= body.transverse else "min"
    return PaperStart(body, orbit.n / Omega0, 1.0, 0.0, kind, -1 if g[2] < 0.0 else 1, delta, lam, phi,
                      math.atan2(R3[1, 0], R3[0, 0]), orbit.nu0, orbit.paper, Omega0, m.G, Q, orbit.to_inertial(),
                      theta)
