r"""The unperturbed Lagrange top: first integrals, the cubic Q(u), its roots and the maps (1.6)/(2.8).

Akulenko, Leshchenko, Chernousko (1979), "Perturbed motions of a rigid body close to the Lagrange
case", PMM 43(5). Equation numbers refer to that paper.

Conventions: 3-1-3 Euler angles (psi, theta, phi) as in :mod:`rigidbody.core.euler`; the body z axis is
the symmetry axis; the centre of mass is at distance l on +z, so the potential energy is
``mgl cos(theta)`` (theta = 0: the top stands upright above the pivot).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core.validate import finite_array

__all__ = [
    "Top",
    "cubic_coefficients",
    "deltas",
    "from_roots",
    "integrals",
    "root_radical",
    "roots",
    "vieta",
]


@dataclass(frozen=True)
class Top:
    r"""A heavy dynamically symmetric top with a fixed point (the Lagrange case).

    Parameters
    ----------
    A : float
        Equatorial moment of inertia about the fixed point O, ``A > 0``.
    C : float
        Axial moment of inertia about O, ``C > 0``.
    mgl : float
        Weight times the distance from O to the centre of mass, ``mgl > 0`` (the centre of mass
        lies on the positive symmetry axis).

    Raises
    ------
    TypeError
        If a parameter is not a real number.
    ValueError
        If a parameter is not finite and positive, or ``C > 2A``.

    See Also
    --------
    integrals : the first integrals (1.2) of its motion.
    roots : the roots of the cubic (1.5) they determine.

    Notes
    -----
    Units are arbitrary but consistent; the paper's figures use ``A = 1.5, C = 1, mgl = 0.5``.
    ``C <= 2A`` is required: the moments of inertia of a real body about any point obey the triangle
    inequality (``2A - C = 2 * integral of z^2 dm >= 0`` on the symmetry axis), so ``C > 2A`` is no
    rigid body.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, eq. (1.1).

    Examples
    --------
    The paper's top (section 3); a body with ``C > 2A`` is refused:

    >>> from rigidbody import lagrange
    >>> top = lagrange.Top(A=1.5, C=1.0, mgl=0.5)
    >>> top == lagrange.PAPER_TOP
    True
    >>> lagrange.Top(A=1.0, C=3.0, mgl=0.5)
    Traceback (most recent call last):
        ...
    ValueError: Top.C must satisfy C <= 2A ...
    """

    A: float
    C: float
    mgl: float

    def __post_init__(self) -> None:
        for name in ("A", "C", "mgl"):
            val = getattr(self, name)
            if isinstance(val, bool) or not isinstance(val, (int, float, np.floating, np.integer)):
                raise TypeError(f"Top.{name} must be a real number, got {type(val).__name__}")
            if not math.isfinite(float(val)) or float(val) <= 0.0:
                raise ValueError(f"Top.{name} must be finite and > 0, got {val!r}")
            object.__setattr__(self, name, float(val))
        if self.C > 2.0 * self.A:
            raise ValueError(
                f"Top.C must satisfy C <= 2A (triangle inequality of the moments of inertia of a real "
                f"body), got A={self.A!r}, C={self.C!r}"
            )


def check_top(top: Any) -> Top:
    if not isinstance(top, Top):
        raise TypeError(f"top must be a lagrange.Top, got {type(top).__name__}")
    return top


def integrals(top: Top, p: Any, q: Any, r: Any, phi: Any, theta: Any) -> tuple[Any, Any, Any]:
    r"""First integrals (1.2) of the Lagrange top.

    .. math::
        G_z = A\sin\theta(p\sin\varphi + q\cos\varphi) + Cr\cos\theta,\quad
        H = \tfrac12[A(p^2+q^2) + Cr^2] + mgl\cos\theta,\quad r.

    Parameters
    ----------
    top : Top
    p, q, r : float or array_like
        Body components of the angular velocity.
    phi, theta : float or array_like
        Proper rotation and nutation angles (rad).

    Returns
    -------
    Gz, H, r
        Vertical component of the angular momentum, total energy, axial spin (broadcast arrays,
        or floats for scalar input).

    See Also
    --------
    roots : the roots of the cubic (1.5) from these integrals.
    vieta : their symmetric functions (1.6).

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, eq. (1.2).

    Examples
    --------
    The paper's case 2 (spun about the axis, ``r = sqrt(3)``, tilted by 60 degrees): ``Gz = C r cos 60° =
    sqrt(3)/2`` and ``H = C r²/2 + mgl cos 60° = 3/2 + 1/4``:

    >>> from rigidbody import lagrange
    >>> Gz, H, r = lagrange.integrals(lagrange.PAPER_TOP, *lagrange.paper_initial_state(2)[:5])
    >>> print(f"{Gz:.6f} {H:.6f} {r:.6f}")
    0.866025 1.750000 1.732051
    """
    top = check_top(top)
    names = ("p", "q", "r", "phi", "theta")
    p, q, r, phi, theta = (finite_array(x, name) for x, name in zip((p, q, r, phi, theta), names))
    try:
        np.broadcast_shapes(*(x.shape for x in (p, q, r, phi, theta)))
    except ValueError:
        shapes = ", ".join(f"{n} {x.shape}" for n, x in zip(names, (p, q, r, phi, theta)))
        raise ValueError(f"p, q, r, phi, theta must broadcast to one shape, got {shapes}") from None
    st, ct = np.sin(theta), np.cos(theta)
    Gz = top.A * st * (p * np.sin(phi) + q * np.cos(phi)) + top.C * r * ct
    H = 0.5 * (top.A * (p * p + q * q) + top.C * r * r) + top.mgl * ct
    out = np.broadcast_arrays(Gz, H, r)
    if all(np.ndim(x) == 0 for x in out):
        return float(Gz), float(H), float(r)
    return np.array(out[0]), np.array(out[1]), np.array(out[2])


def vieta(top: Top, Gz: Any, H: Any, r: Any) -> tuple[Any, Any, Any]:
    r"""Right-hand sides of (1.6): the elementary symmetric functions of the roots.

    Returns ``(s1, s2, s3) = (u1+u2+u3, u1u2+u1u3+u2u3, u1u2u3)`` as functions of (Gz, H, r):

    .. math::
        s_1 = \frac{H}{mgl} - \frac{Cr^2}{2mgl} + \frac{C^2r^2}{2Amgl},\quad
        s_2 = \frac{G_zCr}{Amgl} - 1,\quad
        s_3 = -\frac{H}{mgl} + \frac{Cr^2}{2mgl} + \frac{G_z^2}{2Amgl}.

    See Also
    --------
    roots : the roots themselves.
    cubic_coefficients : the same cubic in monomial form.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, eq. (1.6).

    Examples
    --------
    For case 2 the paper's table gives the roots ``(0, 0.5, 2)``, whose symmetric functions are
    ``(2.5, 1, 0)``:

    >>> from rigidbody import lagrange
    >>> top = lagrange.PAPER_TOP
    >>> s = lagrange.vieta(top, *lagrange.integrals(top, *lagrange.paper_initial_state(2)[:5]))
    >>> print(" ".join(f"{round(x, 6) + 0.0:.6f}" for x in s))  # + 0.0: no "-0"
    2.500000 1.000000 0.000000
    """
    A, C, mgl = top.A, top.C, top.mgl
    s1 = H / mgl - C * r * r / (2 * mgl) + C * C * r * r / (2 * A * mgl)
    s2 = Gz * C * r / (A * mgl) - 1.0
    s3 = -H / mgl + C * r * r / (2 * mgl) + Gz * Gz / (2 * A * mgl)
    return s1, s2, s3


def cubic_coefficients(top: Top, Gz: float, H: float, r: float) -> tuple[float, float, float, float]:
    r"""Coefficients ``(c3, c2, c1, c0)`` of the cubic Q(u) of (1.5), highest power first.

    ``Q(u) = (2 mgl / A) (u - u1)(u - u2)(u - u3)``; ``u'^2 = Q(u)`` along the motion (u = cos theta).
    The coefficients follow from the symmetric functions (1.6) (:func:`vieta`).

    Parameters
    ----------
    top : Top
    Gz, H, r : float
        The first integrals (1.2): vertical component of the angular momentum, total energy and axial
        spin (units of ``A``, ``mgl`` and time consistent with ``top``).

    Returns
    -------
    c3, c2, c1, c0 : float
        ``c3 = 2mgl/A``, ``c2 = -c3 s1``, ``c1 = c3 s2``, ``c0 = -c3 s3``, so that
        ``Q(u) = c3 u^3 + c2 u^2 + c1 u + c0`` (units of 1/time^2, as ``u'^2``).

    See Also
    --------
    vieta : the symmetric functions of the roots (1.6).
    roots : the roots.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, eq. (1.5).

    Examples
    --------
    Case 2 has a root at ``u = 0`` (paper's table ``(0, 0.5, 2)``), so the constant coefficient vanishes:

    >>> from rigidbody import lagrange
    >>> top = lagrange.PAPER_TOP
    >>> c = lagrange.cubic_coefficients(top, *lagrange.integrals(top, *lagrange.paper_initial_state(2)[:5]))
    >>> print(f"{round(c[-1], 6) + 0.0:.6f}")  # + 0.0: no "-0"
    0.000000
    """
    s1, s2, s3 = vieta(top, Gz, H, r)
    f = 2.0 * top.mgl / top.A
    return f, -f * s1, f * s2, -f * s3


def _monic(u: float, s1: float, s2: float, s3: float) -> float:
    return ((u - s1) * u + s2) * u - s3


def _newton_polish(u: float, s1: float, s2: float, s3: float, lo: float, hi: float) -> float:
    """Two safeguarded Newton steps on the monic cubic (only accepted if they stay in [lo, hi])."""
    for _ in range(2):
        f = _monic(u, s1, s2, s3)
        d = (3.0 * u - 2.0 * s1) * u + s2
        if d == 0.0 or f == 0.0:
            break
        un = u - f / d
        if not (lo <= un <= hi) or abs(_monic(un, s1, s2, s3)) >= abs(f):
            break
        u = un
    return u


def _bisect(s1: float, s2: float, s3: float, lo: float, hi: float, increasing: bool) -> float:
    """Root of the monic cubic in [lo, hi] where it is monotone with the given sense (bisection to ulp)."""
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            break
        f = _monic(mid, s1, s2, s3)
        if f == 0.0:
            return mid
        if (f > 0.0) == increasing:
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


def _roots_scalar(top: Top, Gz: float, H: float, r: float) -> tuple[float, float, float]:
    s1, s2, s3 = vieta(top, Gz, H, r)
    scale = 1.0 + abs(s1) + abs(s2) + abs(s3)
    tol = 64.0 * np.finfo(float).eps * scale
    # P(u) = u^3 - s1 u^2 + s2 u - s3 satisfies P(1) = -(Gz - Cr)^2/(2 A mgl) <= 0,
    # P(-1) = -(Gz + Cr)^2/(2 A mgl) <= 0 and P(cos theta) = A u'^2 / (2 mgl) >= 0 on a real motion.
    disc = s1 * s1 - 3.0 * s2  # critical points of P: (s1 -+ sqrt(disc)) / 3
    if disc < 0.0:
        raise ValueError(
            f"(Gz, H, r) = ({Gz!r}, {H!r}, {r!r}) is not attainable: the cubic (1.5) has one real root"
        )
    sq = math.sqrt(disc)
    c_lo = (s1 - sq) / 3.0  # local maximum of P
    c_hi = (s1 + sq) / 3.0  # local minimum of P
    um = min(max(c_lo, -1.0), 1.0)
    pmax = _monic(um, s1, s2, s3)
    if -1e-9 * scale <= pmax < 0.0 and -1.0 < c_lo < 1.0:
        # just outside the admissible set, at the regular-precession boundary (a double root at the local
        # maximum of the cubic): an integrator's stage may land here; project onto the boundary
        return c_lo, c_lo, max(s1 - 2.0 * c_lo, 1.0)
    if pmax < -tol:
        raise ValueError(
            f"(Gz, H, r) = ({Gz!r}, {H!r}, {r!r}) is not attainable by a real top: Q(u) < 0 on [-1, 1] "
            "(energy H too low for the given Gz and r)"
        )
    if H - 0.5 * top.C * r * r < -top.mgl * (1.0 + 1e-9 * scale):  # same slack as the projection above
        raise ValueError(
            f"(Gz, H, r) = ({Gz!r}, {H!r}, {r!r}) is not attainable: H must be >= C r^2/2 - mgl "
            "(kinetic energy of the axial spin plus the lowest potential energy)"
        )
    # u3: the largest root, in [max(1, c_hi), s1 + 2] (u1 + u2 >= -2); P increasing there.
    lo3 = max(1.0, c_hi)
    hi3 = max(lo3, s1 + 2.0)
    if _monic(lo3, s1, s2, s3) >= 0.0:
        u3 = lo3
    else:
        while _monic(hi3, s1, s2, s3) < 0.0:  # guard against rounding in s1 + 2
            hi3 = hi3 + 1.0 + abs(hi3)
        u3 = _bisect(s1, s2, s3, lo3, hi3, True)
        u3 = _newton_polish(u3, s1, s2, s3, lo3, hi3)
    # deflate: u1 + u2 = s1 - u3, u1 u2 = s3 / u3 (u3 >= 1 > 0)
    m = 0.5 * (s1 - u3)
    prod = s3 / u3
    d2 = m * m - prod  # = ((u2 - u1)/2)^2, the ill-conditioned part near regular precession
    half = math.sqrt(d2) if d2 > 0.0 else 0.0
    if half > 1e-4 * (1.0 + abs(m)):
        # distinct roots: refine each inside its bracket around the local maximum of P
        u1 = m - half
        u2 = m + half
        lo1, hi1 = -1.0, min(um, 1.0)
        if lo1 <= u1 <= hi1 and _monic(lo1, s1, s2, s3) <= 0.0 <= _monic(hi1, s1, s2, s3):
            u1 = _newton_polish(_bisect(s1, s2, s3, lo1, hi1, True), s1, s2, s3, lo1, hi1)
        lo2, hi2 = max(um, -1.0), 1.0
        if lo2 <= u2 <= hi2 and _monic(hi2, s1, s2, s3) <= 0.0 <= _monic(lo2, s1, s2, s3):
            u2 = _newton_polish(_bisect(s1, s2, s3, lo2, hi2, False), s1, s2, s3, lo2, hi2)
    else:
        u1 = m - half
        u2 = m + half
    if u1 < -1.0 - 1e-6 or u2 > 1.0 + 1e-6:
        raise ValueError(
            f"(Gz, H, r) = ({Gz!r}, {H!r}, {r!r}) is not attainable by a real top: the cubic (1.5) has no "
            f"pair of roots in [-1, 1] (got {u1!r}, {u2!r})"
        )
    # enforce the admissible ordering -1 <= u1 <= u2 <= 1 <= u3 against rounding (1.5)
    u1 = min(max(u1, -1.0), 1.0)
    u2 = min(max(u2, u1), 1.0)
    u3 = max(u3, 1.0)
    return u1, u2, u3


def roots(top: Top, Gz: Any, H: Any, r: Any) -> tuple[Any, Any, Any]:
    r"""Roots ``u1 <= u2 <= 1 <= u3`` of the cubic Q(u) (1.5) from the integrals (Gz, H, r).

    The largest root is found by bisection on its bracket ``[max(1, c+), s1 + 2]`` (c+ the local
    minimum of the cubic) and Newton-polished; ``u1, u2`` follow by deflation with Vieta (1.6),
    so a nearly double pair (regular precession, ``u1 ~ u2``; sleeping top, ``u2 ~ 1 ~ u3``) costs no
    accuracy beyond the inherent ``sqrt(machine eps)`` conditioning of a double root. Results are
    clipped to the admissible ranges ``-1 <= u1 <= u2 <= 1 <= u3`` of (1.5).

    Parameters
    ----------
    top : Top
    Gz, H, r : float or array_like
        First integrals (1.2).

    Returns
    -------
    u1, u2, u3 : float or numpy.ndarray

    Raises
    ------
    ValueError
        If (Gz, H, r) is not attainable by a real motion (Q(u) < 0 on all of [-1, 1]).

    See Also
    --------
    integrals : the integrals (1.2) from a state.
    from_roots : the inverse map (2.8).
    vieta : the symmetric functions (1.6).

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, eqs. (1.5)-(1.6).

    Examples
    --------
    The paper's table of initial roots for case 2 is ``(0, 0.5, 2)``:

    >>> from rigidbody import lagrange
    >>> top = lagrange.PAPER_TOP
    >>> u = lagrange.roots(top, *lagrange.integrals(top, *lagrange.paper_initial_state(2)[:5]))
    >>> print(" ".join(f"{round(x, 6) + 0.0:.6f}" for x in u))  # + 0.0: no "-0"
    0.000000 0.500000 2.000000
    """
    top = check_top(top)
    Gz, H, r = np.broadcast_arrays(*(finite_array(x, name) for x, name in zip((Gz, H, r), ("Gz", "H", "r"))))
    if Gz.ndim == 0:
        return _roots_scalar(top, float(Gz), float(H), float(r))
    out = np.empty((3, Gz.size))
    for i in range(Gz.size):
        out[:, i] = _roots_scalar(top, float(Gz.flat[i]), float(H.flat[i]), float(r.flat[i]))
    return out[0].reshape(Gz.shape), out[1].reshape(Gz.shape), out[2].reshape(Gz.shape)


def _check_delta(d: Any, name: str) -> Any:
    da = np.asarray(d, dtype=float)
    if not np.all((da == 1.0) | (da == -1.0)):
        raise ValueError(f"{name} must be +1 or -1, got {d!r}")
    return da


def root_radical(u1: Any, u2: Any, u3: Any) -> Any:
    r"""``R = [(1 - u1^2)(1 - u2^2)(u3^2 - 1)]^{1/2}`` of (2.8) (negative factors from rounding clipped).

    ``R^2 = (s1 + s3)^2 - (1 + s2)^2`` with the symmetric functions (1.6), and ``Gz^2 - C^2 r^2 = 2Amgl delta1 R``.

    Parameters
    ----------
    u1, u2, u3 : float or array_like
        Roots of the cubic (1.5), ``-1 <= u1 <= u2 <= 1 <= u3`` (dimensionless, ``u = cos theta``);
        broadcast together.

    Returns
    -------
    float or numpy.ndarray
        The radical ``R >= 0`` (dimensionless).

    See Also
    --------
    from_roots : where ``R`` enters (2.8).

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, eq. (2.8).

    Examples
    --------
    For case 2's roots ``(0, 0.5, 2)``: ``R² = 1 · 0.75 · 3 = 2.25``:

    >>> from rigidbody import lagrange
    >>> print(f"{lagrange.root_radical(0.0, 0.5, 2.0):.6f}")
    1.500000
    """
    f = np.maximum(1.0 - u1 * u1, 0.0) * np.maximum(1.0 - u2 * u2, 0.0) * np.maximum(u3 * u3 - 1.0, 0.0)
    return np.sqrt(f)


def from_roots(
    top: Top, u1: Any, u2: Any, u3: Any, delta1: Any = -1, delta2: Any = 1
) -> tuple[Any, Any, Any]:
    r"""The integrals (Gz, H, r) from the roots, formula (2.8).

    .. math::
        G_z &= (Amgl)^{1/2}(s_1 + s_3 + \delta_1R)^{1/2}\,\delta_2\,\mathrm{sign}(1+s_2),\\
        H &= \tfrac12 mgl[s_1(1+A/C) + (\delta_1R - s_3)(1-A/C)],\\
        r &= \delta_2 C^{-1}(Amgl)^{1/2}(s_1+s_3-\delta_1R)^{1/2},

    with ``s1 = u1+u2+u3``, ``s2 = u1u2+u1u3+u2u3``, ``s3 = u1u2u3``,
    ``R = [(1-u1^2)(1-u2^2)(u3^2-1)]^{1/2}``, ``delta1 = sign(Gz^2 - C^2 r^2)``, ``delta2 = sign r``.
    (2.8) is verified: it inverts (1.6) exactly, since ``Gz^2 + C^2r^2 = 2Amgl(s1+s3)``,
    ``Gz C r = Amgl(1+s2)`` and ``(s1+s3)^2 - (1+s2)^2 = R^2``.

    Parameters
    ----------
    top : Top
    u1, u2, u3 : float or array_like
        Roots with ``-1 <= u1 <= u2 <= 1 <= u3``.
    delta1, delta2 : {+1, -1}
        The signs of (2.8). The paper's figure cases (a top spun about its axis) have ``delta1 = -1``.

    Returns
    -------
    Gz, H, r

    See Also
    --------
    roots : the inverse map.
    deltas : the signs that select the branch.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, eq. (2.8).

    Examples
    --------
    From case 2's tabulated roots ``(0, 0.5, 2)`` back to its integrals ``(sqrt(3)/2, 7/4, sqrt(3))``:

    >>> from rigidbody import lagrange
    >>> top = lagrange.PAPER_TOP
    >>> Gz, H, r = lagrange.from_roots(top, 0.0, 0.5, 2.0, delta1=-1, delta2=1)
    >>> print(f"{Gz:.6f} {H:.6f} {r:.6f}")
    0.866025 1.750000 1.732051
    """
    top = check_top(top)
    if all(isinstance(x, (float, int)) for x in (u1, u2, u3, delta1, delta2)):
        return _from_roots_scalar(top, float(u1), float(u2), float(u3), float(delta1), float(delta2))
    u1, u2, u3 = (finite_array(x, name) for x, name in zip((u1, u2, u3), ("u1", "u2", "u3")))
    d1 = _check_delta(delta1, "delta1")
    d2 = _check_delta(delta2, "delta2")
    tol = 1e-12
    if np.any(u1 < -1.0 - tol) or np.any(u1 > u2 + tol) or np.any(u2 > 1.0 + tol) or np.any(u3 < 1.0 - tol):
        raise ValueError(
            "roots must satisfy -1 <= u1 <= u2 <= 1 <= u3 (1.5); got "
            f"u1={u1!r}, u2={u2!r}, u3={u3!r}"
        )
    A, C, mgl = top.A, top.C, top.mgl
    s1 = u1 + u2 + u3
    s2 = u1 * u2 + u1 * u3 + u2 * u3
    s3 = u1 * u2 * u3
    R = root_radical(u1, u2, u3)
    g_arg = s1 + s3 + d1 * R
    r_arg = s1 + s3 - d1 * R
    amg = math.sqrt(A * mgl)
    Gz = amg * np.sqrt(np.maximum(g_arg, 0.0)) * d2 * np.where(1.0 + s2 >= 0.0, 1.0, -1.0)
    H = 0.5 * mgl * (s1 * (1.0 + A / C) + (d1 * R - s3) * (1.0 - A / C))
    r = d2 * amg / C * np.sqrt(np.maximum(r_arg, 0.0))
    if np.ndim(Gz) == 0 and np.ndim(H) == 0 and np.ndim(r) == 0:
        return float(Gz), float(H), float(r)
    Gz, H, r = np.broadcast_arrays(Gz, H, r)
    return np.array(Gz), np.array(H), np.array(r)


def _from_roots_scalar(top: Top, u1: float, u2: float, u3: float, d1: float, d2: float) -> tuple[float, float, float]:
    """Math-scalar version of :func:`from_roots` (same formulas (2.8); used inside right-hand sides)."""
    if d1 not in (1.0, -1.0):
        raise ValueError(f"delta1 must be +1 or -1, got {d1!r}")
    if d2 not in (1.0, -1.0):
        raise ValueError(f"delta2 must be +1 or -1, got {d2!r}")
    tol = 1e-12
    if not (math.isfinite(u1) and math.isfinite(u2) and math.isfinite(u3)):
        raise ValueError(f"u1, u2, u3 must be finite, got u1={u1!r}, u2={u2!r}, u3={u3!r}")
    if u1 < -1.0 - tol or u1 > u2 + tol or u2 > 1.0 + tol or u3 < 1.0 - tol:
        raise ValueError(
            f"roots must satisfy -1 <= u1 <= u2 <= 1 <= u3 (1.5); got u1={u1!r}, u2={u2!r}, u3={u3!r}"
        )
    A, C, mgl = top.A, top.C, top.mgl
    s1 = u1 + u2 + u3
    s2 = u1 * u2 + u1 * u3 + u2 * u3
    s3 = u1 * u2 * u3
    R = math.sqrt(max(1.0 - u1 * u1, 0.0) * max(1.0 - u2 * u2, 0.0) * max(u3 * u3 - 1.0, 0.0))
    amg = math.sqrt(A * mgl)
    Gz = amg * math.sqrt(max(s1 + s3 + d1 * R, 0.0)) * d2 * (1.0 if 1.0 + s2 >= 0.0 else -1.0)
    H = 0.5 * mgl * (s1 * (1.0 + A / C) + (d1 * R - s3) * (1.0 - A / C))
    r = d2 * amg / C * math.sqrt(max(s1 + s3 - d1 * R, 0.0))
    return Gz, H, r


def deltas(top: Top, Gz: Any, r: Any) -> tuple[Any, Any]:
    r"""The signs ``delta1 = sign(Gz^2 - C^2 r^2)`` and ``delta2 = sign r`` of (2.8).

    Zero is mapped to +1 (both branches of (2.8) coincide there).

    Parameters
    ----------
    top : Top
        Only its axial moment ``C`` enters.
    Gz : float or array_like
        Vertical component of the angular momentum (1.2).
    r : float or array_like
        Axial spin (1.2), the projection of the angular velocity on the symmetry axis.

    Returns
    -------
    delta1, delta2 : float or numpy.ndarray
        Each +1 or -1; floats for scalar input, else arrays broadcast from ``Gz`` and ``r``.

    See Also
    --------
    from_roots : which takes these signs.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, eq. (2.8).

    Examples
    --------
    For case 2, ``Gz = sqrt(3)/2 < C r = sqrt(3)`` and ``r > 0``, so ``delta1 = -1``, ``delta2 = +1``:

    >>> from rigidbody import lagrange
    >>> top = lagrange.PAPER_TOP
    >>> Gz, H, r = lagrange.integrals(top, *lagrange.paper_initial_state(2)[:5])
    >>> lagrange.deltas(top, Gz, r)
    (-1.0, 1.0)
    """
    w = np.asarray(Gz, dtype=float) ** 2 - (top.C * np.asarray(r, dtype=float)) ** 2
    d1 = np.where(w >= 0.0, 1.0, -1.0)
    d2 = np.where(np.asarray(r, dtype=float) >= 0.0, 1.0, -1.0)
    if np.ndim(d1) == 0 and np.ndim(d2) == 0:
        return float(d1), float(d2)
    return d1, d2
