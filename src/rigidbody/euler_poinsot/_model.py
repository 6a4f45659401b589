r"""Parameters of the problem and the algebra of the averaged system (Rachinskaya, eqs. (5)-(9)).

Everything here is a plain function of the body's moments of inertia, the drag tensor and the slow
variables :math:`(G, k^2)`; the integrators live in :mod:`._averaged` and :mod:`._full`.

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

__all__ = [
    "KINDS",
    "Body",
    "Drag",
    "N_star",
    "N_time",
    "Orbit",
    "T_from",
    "chi",
    "dk2_dtau",
    "drag_rates",
    "k2_equilibria",
    "k2_from",
    "kind_of",
    "spin_ratio",
]

KINDS = ("max", "min")


def _check_kind(kind: str) -> None:
    if not isinstance(kind, str) or kind not in KINDS:
        raise ValueError(f"kind must be 'max' (rotation about the axis of A1) or 'min' (about A3), got {kind!r}")


@dataclass(frozen=True)
class Body:
    """A triaxial rigid body (satellite) with principal moments ``A1 > A2 > A3 > 0``.

    Parameters
    ----------
    A1, A2, A3 : float
        Principal central moments of inertia about the body axes :math:`z_1, z_2, z_3` (the paper's
        :math:`A_i`; nondimensional :math:`\\tilde A_i = A_i\\Omega_0/G_0` in the section-3 scaling).
        The formulas (5)-(9) need the strict ordering ``A1 > A2 > A3`` (label the axes accordingly; a
        body with two equal moments is dynamically symmetric and outside this module) and a real body
        obeys the triangle inequality ``A1 <= A2 + A3``.

    Raises
    ------
    TypeError
        If a moment is not a real number.
    ValueError
        If a moment is not positive and finite, the ordering is violated or the triangle inequality fails.
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
                "relabel the axes (equal moments: a symmetric body, not covered by this module)"
            )
        if A1 > (A2 + A3) * (1.0 + 1e-12):
            raise ValueError(f"triangle inequality A1 <= A2 + A3 violated: A1={A1} > A2 + A3={A2 + A3}")

    @property
    def A(self) -> np.ndarray:
        """The moments as an array ``[A1, A2, A3]``."""
        return np.array([self.A1, self.A2, self.A3])


def _check_body(body: Any) -> Body:
    if not isinstance(body, Body):
        raise TypeError(f"body must be a Body, got {type(body).__name__}")
    return body


def _float_array(x: Any, name: str) -> np.ndarray:
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
    :math:`\mathbf L^r = I\omega` (see ``docs/errata.md``).

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
        """The diagonal entries ``(I11, I22, I33)`` — the only ones the averaged system (6) keeps."""
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
    """

    e: float = 0.0

    def __post_init__(self) -> None:
        e = real(self.e, "e")
        if not (0.0 <= e < 1.0):
            raise ValueError(f"e (eccentricity) must lie in [0, 1), got {e!r}")
        object.__setattr__(self, "e", e)

    def factor(self, nu: float) -> float:
        """The gravity-gradient factor :math:`(1+e\\cos\\nu)^3/(1-e^2)^3` of (3)."""
        e = self.e
        return (1.0 + e * math.cos(nu)) ** 3 / (1.0 - e * e) ** 3

    def nu_rate(self, nu: float) -> float:
        """:math:`\\dot\\nu/\\omega_0 = (1+e\\cos\\nu)^2/(1-e^2)^{3/2}`."""
        e = self.e
        return (1.0 + e * math.cos(nu)) ** 2 / (1.0 - e * e) ** 1.5

    @property
    def mean_factor(self) -> float:
        """Orbit-period mean of ``factor * e_r e_r^T`` divided by diag(1/2, 1/2, 0): :math:`(1-e^2)^{-3/2}`."""
        return (1.0 - self.e**2) ** -1.5


def _as_orbit(orbit: Any) -> Orbit:
    if orbit is None:
        return Orbit()
    if isinstance(orbit, Orbit):
        return orbit
    raise TypeError(f"orbit must be an Orbit or None, got {type(orbit).__name__}")


# --------------------------------------------------------------------------------------------------
# elliptic ratios (scalar, stable in both limits)
# --------------------------------------------------------------------------------------------------
def _ratios(k2: float) -> tuple[float, float]:
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


def _frame_y(delta: float, lam: float) -> np.ndarray:
    """Columns y1, y2, y3 (the frame attached to G) in the orbital axes Ox_i."""
    sd, cd, sl, cl = math.sin(delta), math.cos(delta), math.sin(lam), math.cos(lam)
    return np.array([[cd * cl, -sl, sd * cl], [cd * sl, cl, sd * sl], [-sd, 0.0, cd]])


def _labels(body: Body, kind: str, I: tuple[float, float, float] | None = None) -> Any:
    """Moments (and diagonal drag) in the order in which the 'max'-kind formulas apply."""
    if kind == "max":
        A = (body.A1, body.A2, body.A3)
        return A if I is None else (A, I)
    A = (body.A3, body.A2, body.A1)
    return A if I is None else (A, (I[2], I[1], I[0]))


def _S_over_R(A: tuple[float, float, float], k2: float) -> float:
    A1, A2, A3 = A
    return (A2 - A3 + (A1 - A2) * k2) / (A1 * (A2 - A3) + A3 * (A1 - A2) * k2)


# --------------------------------------------------------------------------------------------------
# public algebra
# --------------------------------------------------------------------------------------------------
def k2_from(body: Body, G: Any, T: Any, kind: str = "max") -> Any:
    r"""Modulus :math:`k^2` of the Euler--Poinsot motion from :math:`G` and :math:`T`, formula (5).

    .. math:: k^2 = \frac{(A_2-A_3)(2TA_1-G^2)}{(A_1-A_2)(G^2-2TA_3)}\quad(\text{kind 'max'}),\qquad
              k^2 = \frac{(A_1-A_2)(G^2-2TA_3)}{(A_2-A_3)(2TA_1-G^2)}\quad(\text{kind 'min'}).

    Parameters
    ----------
    body : Body
    G, T : array_like
        Angular-momentum magnitude (> 0) and kinetic energy (> 0); broadcast together.
    kind : {'max', 'min'}

    Returns
    -------
    float or numpy.ndarray
        :math:`k^2 \in [0, 1]`.

    Raises
    ------
    ValueError
        If :math:`G^2/2T` lies outside :math:`[A_3, A_1]` (no rigid-body state) or on the other side of the
        separatrix :math:`G^2 = 2TA_2` than ``kind`` says (use :func:`kind_of`).
    """
    _check_body(body)
    _check_kind(kind)
    G_ = _float_array(G, "G")
    T_ = _float_array(T, "T")
    if np.any(~np.isfinite(G_)) or np.any(G_ <= 0):
        raise ValueError("G must be positive and finite")
    if np.any(~np.isfinite(T_)) or np.any(T_ <= 0):
        raise ValueError("T must be positive and finite")
    A1, A2, A3 = body.A1, body.A2, body.A3
    D = G_**2 / (2.0 * T_)
    tol = 1e-12 * A1
    if np.any(D > A1 + tol) or np.any(D < A3 - tol):
        raise ValueError(f"G**2/(2T) must lie in [A3, A1] = [{A3}, {A1}] for a rigid body")
    if kind == "max":
        if np.any(D < A2 - tol):
            raise ValueError("G**2 < 2T A2: the state circulates about the axis of A3, use kind='min'")
        num = (A2 - A3) * (A1 - D)
        den = (A1 - A2) * (D - A3)
    else:
        if np.any(D > A2 + tol):
            raise ValueError("G**2 > 2T A2: the state circulates about the axis of A1, use kind='max'")
        num = (A1 - A2) * (D - A3)
        den = (A2 - A3) * (A1 - D)
    k2 = np.clip(num / den, 0.0, 1.0)
    return float(k2) if np.ndim(k2) == 0 else k2


def T_from(body: Body, G: Any, k2: Any, kind: str = "max") -> Any:
    r"""Kinetic energy from :math:`G` and :math:`k^2`: the inverse of (5).

    .. math:: 2T = G^2\,\frac{S}{R} = G^2\,\frac{A_2-A_3+(A_1-A_2)k^2}{A_1(A_2-A_3)+A_3(A_1-A_2)k^2}
              \quad(\text{kind 'max'; labels 1}\leftrightarrow 3\text{ for 'min'}).

    Parameters
    ----------
    body : Body
    G : array_like
        Angular-momentum magnitude (> 0).
    k2 : array_like
        Modulus squared in [0, 1].
    kind : {'max', 'min'}

    Returns
    -------
    float or numpy.ndarray
    """
    _check_body(body)
    _check_kind(kind)
    G_ = _float_array(G, "G")
    k2_ = _float_array(k2, "k2")
    if np.any(~np.isfinite(G_)) or np.any(G_ <= 0):
        raise ValueError("G must be positive and finite")
    if np.any(~np.isfinite(k2_)) or np.any(k2_ < 0) or np.any(k2_ > 1):
        raise ValueError("k2 must lie in [0, 1]")
    A1, A2, A3 = _labels(body, kind)
    T = 0.5 * G_**2 * (A2 - A3 + (A1 - A2) * k2_) / (A1 * (A2 - A3) + A3 * (A1 - A2) * k2_)
    return float(T) if np.ndim(T) == 0 else T


def kind_of(body: Body, G: float, T: float) -> str:
    """'max', 'min' or 'separatrix' for a state (G, T) (compares :math:`G^2` with :math:`2TA_2`).

    The two kinds of Euler--Poinsot motion of section 2: ``'max'`` (:math:`2TA_1 \\ge G^2 > 2TA_2`, the
    domain of formula (5)) and ``'min'`` (:math:`2TA_2 > G^2 \\ge 2TA_3`).

    Parameters
    ----------
    body : Body
    G : float
        Magnitude of the angular momentum (> 0).
    T : float
        Kinetic energy (> 0), in units consistent with ``G`` and the moments (dimensional, or the
        nondimensional :math:`\\tilde G, \\tilde T` of section 3).

    Returns
    -------
    {'max', 'min', 'separatrix'}
        ``'separatrix'`` only when :math:`G^2 = 2TA_2` exactly.

    Raises
    ------
    TypeError
        If ``body`` is not a :class:`Body` or ``G``, ``T`` is not a real number.
    ValueError
        If ``G`` or ``T`` is not positive, or :math:`G^2/2T` lies outside :math:`[A_3, A_1]` (no rigid-body
        state has it).
    """
    _check_body(body)
    G, T = real(G, "G"), real(T, "T")
    if G <= 0 or T <= 0:
        raise ValueError(f"G and T must be positive, got G={G}, T={T}")
    D = G**2 / (2.0 * T)
    tol = 1e-12 * body.A1
    if D > body.A1 + tol or D < body.A3 - tol:
        raise ValueError(f"G**2/(2T) = {D:g} must lie in [A3, A1] = [{body.A3}, {body.A1}] for a rigid body")
    if D > body.A2:
        return "max"
    if D < body.A2:
        return "min"
    return "separatrix"


def chi(body: Body, I: Any) -> float:
    r"""The parameter :math:`\chi` of the :math:`k^2` equation (7).

    .. math:: \chi = \frac{2I_{22}A_1A_3 - I_{11}A_2A_3 - I_{33}A_1A_2}{(I_{33}A_1 - I_{11}A_3)A_2}.

    Only the diagonal of ``I`` enters. For the paper's two drag cases this gives -4.4743 and 3.8523
    (printed: -4.477 and 3.853; see ``docs/euler_poinsot.md``).

    Parameters
    ----------
    body : Body
    I : array_like or Drag
        Drag tensor in body axes (3x3, or its 3 diagonal entries); only its diagonal enters.

    Returns
    -------
    float
        :math:`\chi` (dimensionless: a ratio of drag-times-moment products, the same for the dimensional
        :math:`I, A_i` and the nondimensional :math:`\tilde I, \tilde A_i` of section 3). The slope of (8)
        at :math:`k^2 = 0` is :math:`(-3-\chi)/(2N)`: for :math:`N > 0` (:func:`N_time`) that equilibrium
        is stable iff :math:`\chi > -3`.

    Raises
    ------
    TypeError
        If ``body`` is not a :class:`Body` or ``I`` is not a real matrix.
    ValueError
        If ``I`` has the wrong shape, is not finite or its symmetric part is not positive definite (see
        :class:`Drag`); or if :math:`I_{33}A_1 = I_{11}A_3` (then :math:`N = \infty` and :math:`\chi` is
        undefined; the :math:`k^2` equation itself stays finite: use :func:`dk2_dtau`).
    """
    _check_body(body)
    I11, I22, I33 = as_drag(I).diag
    A1, A2, A3 = body.A1, body.A2, body.A3
    den = (I33 * A1 - I11 * A3) * A2
    if den == 0.0:
        raise ValueError("chi is undefined for I33*A1 == I11*A3 (N infinite); use dk2_dtau")
    return (2 * I22 * A1 * A3 - I11 * A2 * A3 - I33 * A1 * A2) / den


def N_time(body: Body, I: Any) -> float:
    r"""The time scale :math:`N = A_1A_3/(I_{33}A_1 - I_{11}A_3)` of (7) (:math:`\xi = (t-t_*)/N`).

    Parameters
    ----------
    body : Body
    I : array_like or Drag
        Drag tensor in body axes (3x3, or its 3 diagonal entries); only :math:`I_{11}, I_{33}` enter.

    Returns
    -------
    float
        :math:`N` in units of time: dimensional :math:`t` for the dimensional :math:`I`, or :math:`\tau`
        for the nondimensional :math:`\tilde I = I/(G_0\varepsilon^2)` of section 3. Negative when
        :math:`I_{33}A_1 < I_{11}A_3`.

    Raises
    ------
    TypeError
        If ``body`` is not a :class:`Body` or ``I`` is not a real matrix.
    ValueError
        If ``I`` is not a valid drag tensor (see :class:`Drag`), or :math:`I_{33}A_1 = I_{11}A_3` (then
        :math:`N` is infinite).
    """
    _check_body(body)
    I11, _, I33 = as_drag(I).diag
    den = I33 * body.A1 - I11 * body.A3
    if den == 0.0:
        raise ValueError("N is infinite for I33*A1 == I11*A3")
    return body.A1 * body.A3 / den


def _dk2(A: tuple[float, float, float], I: tuple[float, float, float], k2: float) -> float:
    A1, A2, A3 = A
    I11, I22, I33 = I
    ek, sn2 = _ratios(k2)
    W = k2 * sn2
    # (8) rewritten: c(1-chi) = 2(I33/A3 - I22/A2), c(1+chi) = 2(I22/A2 - I11/A1), c = 1/N
    return -2.0 * (I33 / A3 - I22 / A2) * (k2 - W) - 2.0 * (I22 / A2 - I11 / A1) * k2 * ek


def dk2_dtau(body: Body, I: Any, k2: float, kind: str = "max") -> float:
    r"""Right-hand side of the :math:`k^2` equation (8) (dimensional :math:`t`, or :math:`\tau` with :math:`\tilde I`).

    Implemented in the equivalent form

    .. math:: \frac{dk^2}{dt} = -2\Big(\frac{I_{33}}{A_3}-\frac{I_{22}}{A_2}\Big)(k^2-W)
              - 2\Big(\frac{I_{22}}{A_2}-\frac{I_{11}}{A_1}\Big)k^2\frac{E}{K},

    which equals :math:`N^{-1}\{(1-\chi)(1-k^2)-[(1-\chi)+(1+\chi)k^2]E/K\}` (since
    :math:`(1-\chi)/N = 2(I_{33}/A_3 - I_{22}/A_2)`, :math:`(1+\chi)/N = 2(I_{22}/A_2 - I_{11}/A_1)`) but
    stays finite when :math:`I_{33}A_1 = I_{11}A_3` and has no 0/0 at :math:`k \to 0` (both terms are
    :math:`O(k^2)`). For ``kind='min'`` the labels 1 and 3 are exchanged.

    Parameters
    ----------
    body : Body
    I : array_like or Drag
        Drag tensor in body axes (3x3, or its 3 diagonal entries); only its diagonal enters (8).
        Dimensional :math:`I` gives :math:`dk^2/dt`; the nondimensional :math:`\tilde I = I/(G_0\varepsilon^2)`
        (with :math:`\tilde A_i = A_i\Omega_0/G_0`) gives :math:`dk^2/d\tau` of (9).
    k2 : float
        Modulus squared of the Euler--Poinsot motion (5), in :math:`[0, 1]`.
    kind : {'max', 'min'}
        Kind of Euler--Poinsot motion ('max' is the paper's).

    Returns
    -------
    float
        :math:`dk^2/dt` (or :math:`dk^2/d\tau`); independent of :math:`G`.

    Raises
    ------
    TypeError
        If ``body`` is not a :class:`Body`, ``k2`` is not a real number or ``I`` is not a real matrix.
    ValueError
        If ``kind`` is unknown, ``k2`` is outside :math:`[0, 1]` or ``I`` is not a valid drag tensor (see
        :class:`Drag`).
    """
    _check_body(body)
    _check_kind(kind)
    k2f = real(k2, "k2")
    if not (0.0 <= k2f <= 1.0):
        raise ValueError(f"k2 must lie in [0, 1], got {k2f}")
    A, Id = _labels(body, kind, as_drag(I).diag)
    return _dk2(A, Id, k2f)


def _drag_rates(
    A: tuple[float, float, float], I: tuple[float, float, float], G: float, k2: float
) -> tuple[float, float]:
    """(dG/dt, dT/dt) of (6) in 'max' labelling."""
    A1, A2, A3 = A
    I11, I22, I33 = I
    ek, sn2 = _ratios(k2)
    W = k2 * sn2
    R = A1 * (A2 - A3) + A3 * (A1 - A2) * k2
    # <g_i^2>/G^2 over the Euler-Poinsot motion: (A2-A3)(1-W)/R, (A1-A3)W/R, (A1-A2)(k2-W)/R
    m1 = (A2 - A3) * ek / R
    m2 = (A1 - A3) * W / R
    m3 = (A1 - A2) * (k2 - W) / R
    dG = -G * (I11 * m1 + I22 * m2 + I33 * m3)
    dT = -G * G * (I11 * m1 / A1 + I22 * m2 / A2 + I33 * m3 / A3)
    return dG, dT


def drag_rates(body: Body, I: Any, G: float, k2: float, kind: str = "max") -> tuple[float, float]:
    r"""The averaged drag terms :math:`(dG/dt, dT/dt)` of (6).

    .. math:: \frac{dG}{dt} = -\frac{G}{R}\{I_{22}(A_1-A_3)W + I_{11}(A_2-A_3)(1-W) + I_{33}(A_1-A_2)(k^2-W)\},

    and :math:`dT/dt` as printed in (6), evaluated in the equivalent form
    :math:`dT/dt = -(G^2/R)\{I_{11}(A_2-A_3)(1-W)/A_1 + I_{22}(A_1-A_3)W/A_2 + I_{33}(A_1-A_2)(k^2-W)/A_3\}`
    (the same expression after :math:`2T = G^2S/R`; the tests compare both with numerical averages of
    :math:`-\boldsymbol\omega\cdot I\boldsymbol\omega`). The gravity-gradient torque does not change
    :math:`G` and :math:`T` on average. Only the diagonal of ``I`` enters.

    Returns
    -------
    dG, dT : float
        Per unit dimensional time :math:`t` (or per :math:`\tau` with the nondimensional :math:`\tilde I`).
    """
    _check_body(body)
    _check_kind(kind)
    A, Id = _labels(body, kind, as_drag(I).diag)
    G, k2 = real(G, "G"), real(k2, "k2")
    if G <= 0 or not (0.0 <= k2 <= 1.0):
        raise ValueError(f"need G > 0 and k2 in [0, 1], got G={G}, k2={k2}")
    return _drag_rates(A, Id, G, k2)


def _nstar(A: tuple[float, float, float], k2: float) -> float:
    A1, A2, A3 = A
    _, sn2 = _ratios(k2)
    R = A1 * (A2 - A3) + A3 * (A1 - A2) * k2
    fac = k2 * (A1 - A2) * (A1 - A3) / R  # = 2 A1 T / G^2 - 1, without cancellation
    return A2 + A3 - 2.0 * A1 + 3.0 * fac * (A3 + (A2 - A3) * sn2)


def N_star(body: Body, k2: Any, kind: str = "max") -> Any:
    r""":math:`N^*` of (6): :math:`N^* = A_2+A_3-2A_1+3(2A_1T/G^2-1)[A_3+(A_2-A_3)(K-E)/(Kk^2)]`.

    A function of :math:`k^2` only (:math:`2A_1T/G^2 - 1 = k^2(A_1-A_2)(A_1-A_3)/R`). Physically
    :math:`N^* = A_1+A_2+A_3-3\langle J_{GG}\rangle`, where :math:`J_{GG}` is the moment of inertia
    about the direction of :math:`\mathbf G` averaged over the Euler--Poinsot motion. It drives the
    gravity-gradient equations for :math:`\delta, \lambda` in (6) and (9) (:func:`precession_rate`).

    Parameters
    ----------
    body : Body
    k2 : float or array_like
        Modulus squared of the Euler--Poinsot motion (5), in :math:`[0, 1]`.
    kind : {'max', 'min'}
        Kind of Euler--Poinsot motion ('max' is the paper's; labels 1 and 3 exchanged for 'min').

    Returns
    -------
    float or numpy.ndarray
        :math:`N^*`, in the units of the moments :math:`A_i` (dimensional, or :math:`\tilde A_i` of
        section 3); a float for scalar ``k2``.

    Raises
    ------
    TypeError
        If ``body`` is not a :class:`Body` or ``k2`` is not real.
    ValueError
        If ``kind`` is unknown or ``k2`` is not finite and in :math:`[0, 1]`.
    """
    _check_body(body)
    _check_kind(kind)
    A = _labels(body, kind)
    k2a = _float_array(k2, "k2")
    if np.any(~np.isfinite(k2a)) or np.any(k2a < 0) or np.any(k2a > 1):
        raise ValueError("k2 must lie in [0, 1]")
    out = np.vectorize(lambda x: _nstar(A, float(x)))(k2a)
    return float(out) if np.ndim(out) == 0 else out


def k2_equilibria(body: Body, I: Any, kind: str = "max", n_grid: int = 2001) -> list[tuple[float, str]]:
    r"""Equilibria of the :math:`k^2` equation (8) in :math:`[0, 1)` and their stability.

    :math:`k^2 = 0` is always an equilibrium; its linearisation is
    :math:`dk^2/dt \approx -(I_{33}/A_3 + I_{22}/A_2 - 2I_{11}/A_1)\,k^2 = N^{-1}\tfrac{-3-\chi}{2}k^2`.
    Interior roots are bracketed on a grid and refined with Brent's method. Near :math:`k^2=1` the right-hand
    side has the sign of :math:`-(I_{33}/A_3 - I_{11}/A_1)`: when that is positive, :math:`k^2` reaches the
    separatrix in finite time.

    Parameters
    ----------
    body : Body
    I : array_like or Drag
        Drag tensor (only its diagonal enters (8)).
    kind : {'max', 'min'}
    n_grid : int
        Points of the uniform grid in :math:`[0, 1]` on which sign changes are bracketed (>= 4); two
        roots closer than its spacing can be missed.

    Returns
    -------
    list of (k2, 'stable' | 'unstable' | 'neutral')
    """
    from scipy.optimize import brentq

    _check_body(body)
    _check_kind(kind)
    if isinstance(n_grid, (bool, np.bool_)) or not isinstance(n_grid, (int, np.integer)) or n_grid < 4:
        raise ValueError(f"n_grid must be an integer >= 4 (grid on which roots are bracketed), got {n_grid!r}")
    A, Id = _labels(body, kind, as_drag(I).diag)
    out: list[tuple[float, str]] = []
    slope0 = -(Id[2] / A[2] + Id[1] / A[1] - 2.0 * Id[0] / A[0])
    out.append((0.0, "stable" if slope0 < 0 else ("unstable" if slope0 > 0 else "neutral")))
    xs = np.linspace(0.0, 1.0, n_grid)[1:-1]
    fs = np.array([_dk2(A, Id, float(x)) for x in xs])
    for i in range(len(xs) - 1):
        if fs[i] == 0.0 or fs[i] * fs[i + 1] < 0:
            r = brentq(lambda x: _dk2(A, Id, x), xs[i], xs[i + 1], xtol=1e-15, rtol=1e-14)
            stab = "stable" if fs[i] > 0 or fs[i + 1] < 0 else "unstable"
            out.append((float(r), stab))
    return out


#: The rotation-speed check (``min_spin_ratio``) takes the period at ``min(k2, K2_SPIN_CAP)``: next to the
#: separatrix the period grows without bound (like ln(1/(1 - k^2))) while the body still turns fast (about the
#: intermediate axis, at rate G/A2); the momentary infinite period of a passage must not end a run. At
#: k^2 = 0.99 the period is about 2.4 times that at k = 0.
K2_SPIN_CAP = 0.99


def _nut_freq(A: tuple[float, float, float], G: float, k2: float) -> float:
    r"""Angular frequency :math:`2\pi/P = \pi\dot u/(2K)` of the Euler--Poinsot motion (labelled moments)."""
    A1, A2, A3 = A
    mc = 1.0 - k2
    if mc <= 0.0:
        return 0.0
    R = A1 * (A2 - A3) + A3 * (A1 - A2) * k2
    rate = G * math.sqrt((A1 - A2) * (A1 - A3) * (A2 - A3) / (A1 * A2 * A3 * R))
    return math.pi * rate / (2.0 * float(special.elliprf(0.0, mc, 1.0)))


def spin_ratio(body: Body, eps: float, G: float, k2: float, kind: str = "max") -> float:
    r"""How fast the rotation is compared with the orbit: :math:`(2\pi/P)/\omega_0`.

    :math:`P = 4K/\dot u` is the period of the Euler--Poinsot motion (the slowest fast oscillation; it
    grows without bound at the separatrix) and :math:`\omega_0 = \varepsilon` in the section-3 scaling
    (dimensional use: pass :math:`\omega_0` as ``eps``). The averaging needs this ratio to be large; the
    integrators stop when it falls to ``min_spin_ratio``.

    The period follows from the closed-form Euler--Poinsot motion of section 2 with the modulus (5),
    :math:`\dot u = G\sqrt{(A_1-A_2)(A_1-A_3)(A_2-A_3)/(A_1A_2A_3R)}` (labels 1 and 3 exchanged for
    ``kind='min'``).

    Parameters
    ----------
    body : Body
    eps : float
        Orbital rate in the section-3 scaling, :math:`\tilde\omega_0 = \varepsilon` (> 0); or the
        dimensional mean motion :math:`\omega_0` with dimensional ``G`` and moments.
    G : float
        Magnitude of the angular momentum (> 0; :math:`\tilde G` in the section-3 scaling).
    k2 : float
        Modulus squared of the Euler--Poinsot motion (5), in :math:`[0, 1]`.
    kind : {'max', 'min'}
        Kind of Euler--Poinsot motion ('max' is the paper's).

    Returns
    -------
    float
        The dimensionless ratio :math:`(2\pi/P)/\omega_0` (0 at the separatrix :math:`k^2 = 1`).

    Raises
    ------
    TypeError
        If ``body`` is not a :class:`Body` or ``eps``, ``G``, ``k2`` is not a real number.
    ValueError
        If ``kind`` is unknown, ``eps <= 0``, ``G <= 0`` or ``k2`` is outside :math:`[0, 1]`.
    """
    _check_body(body)
    _check_kind(kind)
    eps = real(eps, "eps")
    if eps <= 0:
        raise ValueError("eps must be positive")
    G, k2 = real(G, "G"), real(k2, "k2")
    if G <= 0:
        raise ValueError(f"G must be positive, got {G}")
    if not (0.0 <= k2 <= 1.0):
        raise ValueError(f"k2 must lie in [0, 1], got {k2}")
    return _nut_freq(_labels(body, kind), G, k2) / eps
