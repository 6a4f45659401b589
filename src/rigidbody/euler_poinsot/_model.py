r"""Parameters of the problem and the algebra of the averaged system (Rachinskaya, eqs. (5)-(9)).

Here: the body, the drag tensor and the orbit as values, with their checks, and the labelling of the two kinds
of motion; the algebra of the slow variables :math:`(G, k^2)` is in :mod:`._algebra`, the integrators in
:mod:`._run` and :mod:`._full`.

Notation (the paper's): :math:`A_1 > A_2 > A_3` principal moments, :math:`I` the drag tensor in body
axes, :math:`G` the magnitude of the angular momentum, :math:`T` the kinetic energy, :math:`k^2` the
modulus of the Euler--Poinsot motion (5),

.. math:: W = 1 - E/K,\quad R = A_1(A_2-A_3) + A_3(A_1-A_2)k^2,\quad S = A_2-A_3+(A_1-A_2)k^2 .

Two kinds of Euler--Poinsot motion are distinguished by ``kind``:

``"max"``
    :math:`2TA_1 \ge G^2 > 2TA_2`: the angular momentum circulates about the axis of the largest moment
    :math:`A_1` (the paper's case, formula (5)).
``"min"``
    :math:`2TA_2 > G^2 \ge 2TA_3`: circulation about the axis of the smallest moment :math:`A_3`, with
    :math:`k^2 = (A_1-A_2)(G^2-2TA_3)/[(A_2-A_3)(2TA_1-G^2)]`. All formulas of this kind are those of
    ``"max"`` with the labels 1 and 3 exchanged (moments and drag coefficients); the tests check them
    against numerical averages independently.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy import special

from ..core.validate import real

__all__ = ["AXES", "KINDS", "Body", "Drag", "Orbit", "as_drag", "as_orbit", "check_body", "check_kind",
           "elliptic_ratios", "frame_y", "labelled", "relabel", "violates_triangle"]

KINDS = ("max", "min")


def check_kind(kind: str) -> None:
    if not isinstance(kind, str) or kind not in KINDS:
        raise ValueError(f"kind must be 'max' (rotation about the axis of A1) or 'min' (about A3), got {kind!r}")


def violates_triangle(A1: float, A2: float, A3: float) -> bool:
    """Whether the largest moment ``A1`` exceeds ``A2 + A3`` beyond rounding (no mass distribution has such moments)."""
    return bool(A1 > (A2 + A3) * (1.0 + 1e-12))


@dataclass(frozen=True)
class Body:
    """A triaxial rigid body (satellite) with principal moments ``A1 > A2 > A3 > 0``.

    Parameters
    ----------
    A1, A2, A3 : float
        Principal central moments of inertia about the body axes :math:`z_1, z_2, z_3` (the paper's
        :math:`A_i`; nondimensional :math:`\\tilde A_i = A_i\\Omega_0/G_0` in the section-3 scaling).
        The formulas (5)-(9) need the strict ordering ``A1 > A2 > A3`` (label the axes accordingly; a
        body with two equal moments is a :class:`SymmetricBody`) and a real body
        obeys the triangle inequality ``A1 <= A2 + A3``.

    Raises
    ------
    TypeError
        If a moment is not a real number.
    ValueError
        If a moment is not positive and finite, the ordering is violated or the triangle inequality fails.

    See Also
    --------
    Drag, Orbit : the other parameters of the problem.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, section 1 (:math:`A_1 > A_2 > A_3`) and section 3
    (the body of the numerical study).

    Examples
    --------
    The paper's body of section 3, and a body whose moments break the triangle inequality
    (:math:`A_1 = 3 > A_2 + A_3 = 2.5`), which no mass distribution has:

    >>> from rigidbody import euler_poinsot as ep
    >>> ep.Body(3.2, 2.6, 1.67).A.tolist()
    [3.2, 2.6, 1.67]
    >>> ep.Body(3.0, 1.5, 1.0)
    Traceback (most recent call last):
    ...
    ValueError: triangle inequality A1 <= A2 + A3 violated: A1=3.0 > A2 + A3=2.5
    """

    A1: float
    A2: float
    A3: float

    def __post_init__(self) -> None:
        vals = [real(getattr(self, n), n) for n in ("A1", "A2", "A3")]
        for n, v in zip(("A1", "A2", "A3"), vals):
            object.__setattr__(self, n, v)
            if v <= 0.0:
                raise ValueError(f"{n} must be positive, got {v!r}")
        A1, A2, A3 = vals
        if not (A1 > A2 > A3):
            raise ValueError(
                f"the moments must satisfy A1 > A2 > A3 (paper's labelling), got A1={A1}, A2={A2}, A3={A3}; "
                "relabel the axes (two equal moments: a SymmetricBody(A, C))"
            )
        if violates_triangle(A1, A2, A3):
            raise ValueError(f"triangle inequality A1 <= A2 + A3 violated: A1={A1} > A2 + A3={A2 + A3}")

    @property
    def A(self) -> np.ndarray:
        """The moments as an array ``[A1, A2, A3]``.

        Examples
        --------
        >>> from rigidbody import euler_poinsot as ep
        >>> ep.Body(3.2, 2.6, 1.67).A
        array([3.2 , 2.6 , 1.67])
        """
        return np.array([self.A1, self.A2, self.A3])


def check_body(body: Any) -> Body:
    if not isinstance(body, Body):
        raise TypeError(f"body must be a Body, got {type(body).__name__}")
    return body


def float_array(x: Any, name: str) -> np.ndarray:
    try:
        return np.asarray(x, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a real number or an array of them, got {x!r}") from None


def _as_matrix(I: Any) -> np.ndarray:
    if isinstance(I, Drag):
        return I.I
    try:
        M = np.asarray(I, dtype=float)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"I must be a 3x3 real matrix (drag tensor) or a Drag, got {I!r}") from exc
    if M.shape == (3,):
        M = np.diag(M)
    if M.shape != (3, 3):
        raise ValueError(f"I must be a 3x3 matrix (or the 3 diagonal entries), got shape {M.shape}")
    if not np.all(np.isfinite(M)):
        raise ValueError("I must be finite")
    return M


@dataclass(frozen=True)
class Drag:
    r"""Linear drag torque with a constant tensor :math:`I` in body axes.

    Sign convention: the torque is :math:`\mathbf L^r = -I\boldsymbol\omega` (body components), which
    dissipates energy, :math:`\dot T = -\boldsymbol\omega\cdot I\boldsymbol\omega < 0`, when the symmetric
    part of ``I`` is positive definite. This is the sign of the paper's formula (3); its text writes
    :math:`\mathbf L^r = I\omega` (see :ref:`errata-euler-poinsot`).

    Parameters
    ----------
    I : array_like
        A 3x3 matrix (any, off-diagonal entries allowed) or its 3 diagonal entries. The nondimensional
        :math:`\tilde I` of section 3 is :math:`I/(G_0\varepsilon^2)`.

    Raises
    ------
    ValueError
        If the shape is wrong, an entry is not finite or the symmetric part is not positive definite
        (the torque would not dissipate).

    See Also
    --------
    LinearDrag : the drag alone, as a torque object.
    chi, N_time, drag_rates : what the averaged system (6)-(8) takes of it.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, eq. (3) and :doc:`/errata` (its sign).

    Examples
    --------
    Off-diagonal entries are allowed but do not enter (6): an antisymmetric part leaves the averaged rates
    those of the diagonal. A tensor that would feed energy in is refused:

    >>> from rigidbody import euler_poinsot as ep
    >>> body = ep.Body(3.2, 2.6, 1.67)
    >>> drag = ep.Drag([[2.322, 0.5, 0.0], [-0.5, 1.31, 0.0], [0.0, 0.0, 1.425]])
    >>> drag.diag
    (2.322, 1.31, 1.425)
    >>> a = ep.averaged_rates(body, drag, 1.0, 0.5, 0.7, 0.3, None)
    >>> b = ep.averaged_rates(body, drag.diag, 1.0, 0.5, 0.7, 0.3, None)
    >>> print(f"{a['dG']:.6f} {b['dG']:.6f}")
    -0.665135 -0.665135
    >>> ep.Drag([1.0, 1.0, -1.0])
    Traceback (most recent call last):
    ...
    ValueError: I: the symmetric part of the drag tensor must be positive definite ...
    """

    I: Any = field()

    def __post_init__(self) -> None:
        M = _as_matrix(self.I)
        sym = 0.5 * (M + M.T)
        if np.linalg.eigvalsh(sym).min() <= 0.0:
            raise ValueError(
                "I: the symmetric part of the drag tensor must be positive definite (torque -I omega must "
                f"dissipate energy); eigenvalues {np.linalg.eigvalsh(sym)}"
            )
        M = M.copy()
        M.setflags(write=False)
        object.__setattr__(self, "I", M)

    @property
    def diag(self) -> tuple[float, float, float]:
        """The diagonal entries ``(I11, I22, I33)`` — the only ones the averaged system (6) keeps.

        Examples
        --------
        >>> from rigidbody import euler_poinsot as ep
        >>> ep.Drag([[2.322, 0.1, 0.0], [0.1, 1.31, 0.0], [0.0, 0.0, 1.425]]).diag
        (2.322, 1.31, 1.425)
        """
        return float(self.I[0, 0]), float(self.I[1, 1]), float(self.I[2, 2])

    def __hash__(self) -> int:
        return hash(self.I.tobytes())

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Drag) and bool(np.array_equal(self.I, other.I))

    def __repr__(self) -> str:
        # one line, and valid input: the 3 diagonal entries when I is diagonal, else the nested rows
        diagonal = not np.any(self.I - np.diag(np.diag(self.I)))
        return f"Drag(I={(np.diag(self.I) if diagonal else self.I).tolist()})"


def as_drag(I: Any) -> Drag:
    """Return ``I`` as a validated :class:`Drag` (accepts a Drag, a 3x3 matrix or 3 diagonal entries)."""
    return I if isinstance(I, Drag) else Drag(I)


@dataclass(frozen=True)
class Orbit:
    r"""The orbit of the centre of mass.

    Parameters
    ----------
    e : float
        Eccentricity in [0, 1). The paper's case is the circular orbit ``e = 0``. For ``e > 0`` the
        gravity-gradient torque carries the factor :math:`(1+e\cos\nu)^3/(1-e^2)^3` of (3) and the true
        anomaly obeys :math:`\dot\nu = \omega_0(1+e\cos\nu)^2/(1-e^2)^{3/2}` (Kepler's law; ``e = 0`` gives
        (2), :math:`\nu = \omega_0 t + \nu_0`), with :math:`\omega_0 = 2\pi/Q` the mean motion and the axis
        :math:`Ox_1` towards the pericentre.

    See Also
    --------
    GravityGradient : the torque that carries the orbit factor.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, eqs. (2), (3).

    Examples
    --------
    At the pericentre :math:`\nu = 0` the factor is :math:`(1+e)^3/(1-e^2)^3 = 1/(1-e)^3`, and the true
    anomaly runs at :math:`(1+e)^2/(1-e^2)^{3/2}` times the mean motion (:math:`1/0.729 = 1.371742` and
    :math:`1.21/0.99^{3/2} = 1.228380` for ``e = 0.1``):

    >>> from rigidbody import euler_poinsot as ep
    >>> orbit = ep.Orbit(e=0.1)
    >>> print(f"{orbit.factor(0.0):.6f} {orbit.nu_rate(0.0):.6f}")
    1.371742 1.228380
    """

    e: float = 0.0

    def __post_init__(self) -> None:
        e = real(self.e, "e")
        if not (0.0 <= e < 1.0):
            raise ValueError(f"e (eccentricity) must lie in [0, 1), got {e!r}")
        object.__setattr__(self, "e", e)

    def factor(self, nu: float) -> float:
        """The gravity-gradient factor :math:`(1+e\\cos\\nu)^3/(1-e^2)^3` of (3).

        Examples
        --------
        It is :math:`(a/r)^3`, :math:`a` the semi-major axis: :math:`1/(1+e)^3` at the apocentre.

        >>> import math
        >>> from rigidbody import euler_poinsot as ep
        >>> print(f"{ep.Orbit(e=0.1).factor(math.pi):.6f} {1 / 1.1**3:.6f}")
        0.751315 0.751315
        """
        e = self.e
        return (1.0 + e * math.cos(nu)) ** 3 / (1.0 - e * e) ** 3

    def nu_rate(self, nu: float) -> float:
        """:math:`\\dot\\nu/\\omega_0 = (1+e\\cos\\nu)^2/(1-e^2)^{3/2}`.

        Examples
        --------
        One turn of the true anomaly takes one orbital period, :math:`2\\pi` in units of :math:`1/\\omega_0`:

        >>> import math
        >>> from scipy.integrate import quad
        >>> from rigidbody import euler_poinsot as ep
        >>> orbit = ep.Orbit(e=0.3)
        >>> print(f"{quad(lambda nu: 1 / orbit.nu_rate(nu), 0, 2 * math.pi)[0]:.6f} {2 * math.pi:.6f}")
        6.283185 6.283185
        """
        e = self.e
        return (1.0 + e * math.cos(nu)) ** 2 / (1.0 - e * e) ** 1.5

    @property
    def mean_factor(self) -> float:
        """Orbit-period mean of ``factor * e_r e_r^T`` divided by diag(1/2, 1/2, 0): :math:`(1-e^2)^{-3/2}`.

        Examples
        --------
        The time mean of :meth:`factor` over the orbit (:math:`dt = d\\nu/\\dot\\nu`):

        >>> import math
        >>> from scipy.integrate import quad
        >>> from rigidbody import euler_poinsot as ep
        >>> orbit = ep.Orbit(e=0.3)
        >>> mean = quad(lambda nu: orbit.factor(nu) / orbit.nu_rate(nu), 0, 2 * math.pi)[0] / (2 * math.pi)
        >>> print(f"{mean:.6f} {orbit.mean_factor:.6f}")
        1.151961 1.151961
        """
        return (1.0 - self.e**2) ** -1.5


def as_orbit(orbit: Any) -> Orbit:
    if orbit is None:
        return Orbit()
    if isinstance(orbit, Orbit):
        return orbit
    raise TypeError(f"orbit must be an Orbit or None, got {type(orbit).__name__}")


# --------------------------------------------------------------------------------------------------
# elliptic ratios (scalar, stable in both limits)
# --------------------------------------------------------------------------------------------------
def elliptic_ratios(k2: float) -> tuple[float, float]:
    r"""Return :math:`E/K` and :math:`\langle\operatorname{sn}^2\rangle = (K-E)/(k^2K)` for :math:`0\le k^2\le1`.

    Uses Carlson's forms :math:`K = R_F(0, k'^2, 1)`, :math:`K - E = \tfrac{k^2}{3}R_D(0, k'^2, 1)`, so
    :math:`(K-E)/(k^2K) = R_D/(3R_F)` has no 0/0 at :math:`k\to0` (limit 1/2) and tends to 1 at the
    separatrix :math:`k\to1`, where :math:`E/K\to0`. (The same integrals as ``rigidbody.core.elliptic``;
    called directly here because these ratios sit inside ODE right-hand sides.)
    """
    mc = 1.0 - k2
    if mc <= 0.0:
        return 0.0, 1.0
    rf = float(special.elliprf(0.0, mc, 1.0))
    rd = float(special.elliprd(0.0, mc, 1.0))
    sn2 = rd / (3.0 * rf)
    return 1.0 - k2 * sn2, sn2


def frame_y(delta: float, lam: float) -> np.ndarray:
    """Columns y1, y2, y3 (the frame attached to G) in the orbital axes Ox_i."""
    sd, cd, sl, cl = math.sin(delta), math.cos(delta), math.sin(lam), math.cos(lam)
    return np.array([[cd * cl, -sl, sd * cl], [cd * sl, cl, sd * sl], [-sd, 0.0, cd]])


#: The body axes in the labelled order of each kind, in which the 'max'-kind formulas apply to both: the kind
#: 'min' exchanges the labels 1 and 3 (moments, drag coefficients, components of omega).
AXES: dict[str, tuple[int, int, int]] = {"max": (0, 1, 2), "min": (2, 1, 0)}


def relabel(kind: str, v: Any) -> tuple[Any, Any, Any]:
    """Three values in body order (``v[0], v[1], v[2]``) in the labelled order of ``kind``, and back (an
    involution)."""
    i, j, k = AXES[kind]
    return v[i], v[j], v[k]


def labelled(body: Body, kind: str, I: tuple[float, float, float] | None = None) -> Any:
    """Moments (and diagonal drag) in the order in which the 'max'-kind formulas apply."""
    A = relabel(kind, (body.A1, body.A2, body.A3))
    return A if I is None else (A, relabel(kind, I))
