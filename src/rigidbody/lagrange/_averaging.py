r"""Averaging over the nutation period in the slow variables (u1, u2, u3) (Akulenko et al. 1979, Sec. 2-3).

The first-approximation system (2.15)-(2.16) is ``u_i' = U_i(u1, u2, u3)`` in the slow time
``tau = eps t``. Since the matrix ``V_ij`` of (2.12)-(2.13) depends on the slow variables only,

.. math:: U_i = \sum_j V_{ij}(u_1,u_2,u_3)\,\langle F_j\rangle,

where ``<F_j>`` is the mean of the right-hand sides (2.7) over one nutation period,
``u = cos(theta) = u1 + (u2 - u1) sn^2(s, k)``, ``s = alpha t + beta`` (1.3), (2.14). The mean is a
trapezoid rule on a uniform grid of the phase ``s`` over ``2K`` (spectrally convergent,
:func:`rigidbody.core.averaging.sn2_average`), never ``quad``.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..core import averaging as _avg
from ..core import elliptic as _ell
from . import _kernel as _k
from ._top import Top, check_top, from_roots, roots, vieta
from ._torques import LinearDrag, Torque, check_torque, closed_form_choice

#: width u2 - u1 (relative to max(u3 - u1, 1)) below which a pair of roots of the cubic counts as double
_NEAR_DOUBLE = 1e-6

__all__ = [
    "V_matrix",
    "averaged_rhs",
    "averaged_slow_rates",
    "drag_rhs",
    "modulus",
    "nutation_mean",
]


def modulus(u1: Any, u2: Any, u3: Any) -> tuple[Any, Any]:
    r"""``k^2 = (u2 - u1)/(u3 - u1)`` (1.4) and its complement ``mc = (u3 - u2)/(u3 - u1)``.

    ``mc`` is formed from the root differences, not as ``1 - k^2``, so that it keeps its digits near
    the separatrix (sleeping top, ``u2 -> u3 = 1``).

    Parameters
    ----------
    u1, u2, u3 : float or array_like
        Roots of the cubic (1.5), ``-1 <= u1 <= u2 <= 1 <= u3`` with ``u1 < u3`` (dimensionless,
        ``u = cos theta``).

    Returns
    -------
    k2, mc : float or numpy.ndarray
        The squared modulus ``k^2`` of the nutation (1.3)-(1.4) and its complement, both in ``[0, 1]``
        for admissible roots.

    See Also
    --------
    nutation_frequency : the frequency of the same elliptic phase (1.3).

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, eq. (1.4).

    Examples
    --------
    Case 2's roots ``(0, 0.5, 2)`` (paper's table): ``k² = 0.5/2``, ``mc = 1.5/2``:

    >>> from rigidbody import lagrange
    >>> k2, mc = lagrange.modulus(0.0, 0.5, 2.0)
    >>> print(f"{k2:.6f} {mc:.6f}")
    0.250000 0.750000
    """
    d = u3 - u1
    return (u2 - u1) / d, (u3 - u2) / d


def _grid_u(u1: float, u2: float, u3: float, n: int | None) -> np.ndarray:
    k2, mc = modulus(u1, u2, u3)
    mc = min(max(mc, 0.0), 1.0)
    if mc == 0.0:
        raise ValueError("u2 = u3: the nutation period is infinite (separatrix), no average exists")
    _, snv, _, _ = _avg.phase_grid(None, n, mc=mc, period="2K")
    return u1 + (u2 - u1) * snv * snv


def nutation_mean(g: Any, u1: float, u2: float, u3: float, n: int | None = None) -> Any:
    r"""Mean of ``g(u)`` over one period of the nutation (1.3): ``u = u1 + (u2-u1) sn^2(alpha t + beta, k)``.

    Parameters
    ----------
    g : callable
        Vectorised in ``u``; may return ``(..., n)`` arrays (mean over the last axis).
    u1, u2, u3 : float
        Roots of (1.5).
    n : int, optional
        Nodes of the trapezoid rule per period ``2K`` (default
        :func:`rigidbody.core.averaging.n_nodes`, 1e-13 for ``sn^2``-type integrands).

    See Also
    --------
    averaged_slow_rates : the means of the rates (2.7) it forms.
    modulus : the modulus of the nutation.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, eqs. (1.3), (2.7).

    Examples
    --------
    Over the nutation (1.3), ``u = u1 + (u2 - u1) sn²``, whose mean is ``u1 + (u2 - u1)(1 - E/K)/k²``;
    for case 2's roots ``(0, 0.5, 2)``, ``k² = 1/4``:

    >>> from scipy.special import ellipe, ellipk
    >>> from rigidbody import lagrange
    >>> print(f"{lagrange.nutation_mean(lambda u: u, 0.0, 0.5, 2.0):.6f}")
    0.258980
    >>> print(f"{0.5 * (1 - ellipe(0.25) / ellipk(0.25)) / 0.25:.6f}")
    0.258980
    """
    u = _grid_u(u1, u2, u3, n)
    res = np.asarray(g(u), dtype=float).mean(axis=-1)
    return float(res) if np.ndim(res) == 0 else res


def averaged_slow_rates(
    top: Top, torque: Torque, Gz: float, H: float, r: float, u123: tuple[float, float, float] | None = None,
    n: int | None = None,
) -> tuple[float, float, float]:
    r"""The averaged right-hand sides ``<F1>, <F2>, <F3>`` of (2.7) for (Gz, H, r).

    This is the averaged system in the original slow variables,
    ``Gz' = <F1>, H' = <F2>, r' = <F3>`` (slow time), the route the paper prescribes for following the
    signs ``delta1, delta2`` of (2.8).

    Parameters
    ----------
    top, torque
    Gz, H, r : float
    u123 : tuple, optional
        The roots of (1.5) if already known (else computed by :func:`roots`).
    n : int, optional
        Trapezoid nodes per nutation period.

    See Also
    --------
    averaged_rhs : the same rates carried to the roots by (2.12)-(2.13).
    V_matrix : the map between the two.

    Notes
    -----
    When the roots come from the cubic (``u123`` not given) and the pair is nearly double,
    ``u2 - u1 <= 1e-6 max(u3 - u1, 1)`` (close to a regular precession, e.g. a sleeping top), the mean is
    ``F`` at the double root, taken as the local maximum ``(s1 - (s1^2 - 3 s2)^{1/2})/3`` of the cubic
    (1.6): that is smooth in (Gz, H, r), while ``u1, u2`` themselves carry ``sqrt(machine eps)``
    rounding noise there, which would stall a tight integrator. The error is ``O((u2 - u1)^2)``.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, eq. (2.7).

    Examples
    --------
    Under the linear drag (3.1) the spin decays as ``r0 exp(-b tau / C)`` (3.3): ``dr/dtau = -b r / C =
    -0.1 sqrt(3)`` in case 2:

    >>> from rigidbody import lagrange
    >>> top = lagrange.PAPER_TOP
    >>> Gz, H, r = lagrange.integrals(top, *lagrange.paper_initial_state(2)[:5])
    >>> dGz, dH, dr = lagrange.averaged_slow_rates(top, lagrange.PAPER_DRAG, Gz, H, r)
    >>> print(f"{dr:.6f}")
    -0.173205
    """
    if u123 is None:
        u1, u2, u3 = roots(top, Gz, H, r)
        near_double = u2 - u1 <= _NEAR_DOUBLE * max(u3 - u1, 1.0)
    else:
        u1, u2, u3 = u123
        near_double = False
    if near_double:
        s1, s2, _ = vieta(top, Gz, H, r)
        c_lo = _k.double_root(s1, _k.cubic_spread(_k.SCALAR, s1, s2))
        u = np.array([c_lo])  # not clipped to [-1, 1]: keeps the field smooth across a pole (rounding only)
    elif u2 - u1 <= 0.0:
        # regular precession: the nutation is frozen at u = u1 = u2, the mean is the value there
        u = np.array([0.5 * (u1 + u2)])
    else:
        u = _grid_u(u1, u2, u3, n)
    F = torque.slow_rates(top, Gz, H, r, u)
    return float(np.mean(F[0])), float(np.mean(F[1])), float(np.mean(F[2]))


def V_matrix(top: Top, u1: Any, u2: Any, u3: Any, Gz: Any, r: Any) -> np.ndarray:
    r"""The matrix ``V_ij`` of (2.12)-(2.13): ``u_i' = eps sum_j V_ij F_j``.

    .. math::
        V_{11} = \frac{G_z - Cru_1}{Amgl\,D_1},\quad V_{12} = \frac{u_1^2-1}{mgl\,D_1},\quad
        V_{13} = \frac{C}{mgl\,D_1}\Big[\Big(\frac CA - 1\Big)ru_1^2 - \frac{G_z}{A}u_1 + r\Big],

    ``D_1 = (u1 - u2)(u1 - u3)``; rows 2, 3 by cyclic permutation of the indices of ``u``.
    (Verified: ``V = d(u1,u2,u3)/d(Gz,H,r)``, the inverse Jacobian of (1.6).)

    Returns
    -------
    numpy.ndarray
        Shape ``(3, 3, ...)``.

    Raises
    ------
    ValueError
        Unless ``u1 < u2 < u3`` (the determinant of (2.10) vanishes otherwise).

    See Also
    --------
    averaged_slow_rates : the rates F it maps.
    averaged_rhs : the product V F.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, eqs. (2.12)-(2.13).

    Examples
    --------
    ``V`` maps the averaged rates of ``(Gz, H, r)`` to those of the roots: for the drag of case 2 the
    product is the closed form (3.4):

    >>> import numpy as np
    >>> from rigidbody import lagrange
    >>> top = lagrange.PAPER_TOP
    >>> Gz, H, r = lagrange.integrals(top, *lagrange.paper_initial_state(2)[:5])
    >>> V = lagrange.V_matrix(top, 0.0, 0.5, 2.0, Gz, r)
    >>> F = lagrange.averaged_slow_rates(top, lagrange.PAPER_DRAG, Gz, H, r)
    >>> print(" ".join(f"{x:.6f}" for x in V @ np.array(F)))
    -0.051796 -0.040170 -0.348204
    >>> print(" ".join(f"{x:.6f}" for x in lagrange.drag_rhs(top, lagrange.PAPER_DRAG, 0.0, 0.5, 2.0)))
    -0.051796 -0.040170 -0.348204
    """
    top = check_top(top)
    _check_roots(u1, u2, u3)
    A, C, mgl = top.A, top.C, top.mgl
    us = [np.asarray(x, dtype=float) for x in (u1, u2, u3)]
    rows = []
    for i in range(3):
        ui, uj, uk = us[i], us[(i + 1) % 3], us[(i + 2) % 3]
        D = (ui - uj) * (ui - uk)
        rows.append([
            (Gz - C * r * ui) / (A * mgl * D),
            (ui * ui - 1.0) / (mgl * D),
            C / (mgl * D) * ((C / A - 1.0) * r * ui * ui - Gz / A * ui + r),
        ])
    return np.array(rows, dtype=float)


def _check_roots(u1: Any, u2: Any, u3: Any) -> None:
    if not np.all((np.asarray(u1) < np.asarray(u2)) & (np.asarray(u2) < np.asarray(u3))):
        raise ValueError(
            "the averaged system (2.15) needs distinct roots u1 < u2 < u3 (the determinant of (2.10) is "
            f"(u1-u2)(u1-u3)(u2-u3)); got u1={u1!r}, u2={u2!r}, u3={u3!r}"
        )


def averaged_rhs(
    top: Top,
    torque: Torque,
    u1: float,
    u2: float,
    u3: float,
    delta1: float = -1.0,
    delta2: float = 1.0,
    *,
    n: int | None = None,
    closed_form: bool | None = None,
) -> tuple[float, float, float]:
    r"""Right-hand side ``(U1, U2, U3)`` of the averaged system (2.15)-(2.16).

    General engine: ``U = V <F>`` with (2.13) and the nutation mean of (2.7) (corrected ``F1``).

    Parameters
    ----------
    top : Top
    torque : Torque
        Any admissible torque (see :mod:`rigidbody.lagrange`); one with a closed-form average (``closed_means``:
        :class:`LinearDrag`, the printed (3.4)) uses it unless ``closed_form=False``.
    u1, u2, u3 : float
        Slow variables, ``-1 <= u1 < u2 <= 1 <= u3``, ``u2 < u3``.
    delta1, delta2 : {-1, +1}
        Signs of (2.8).
    n : int, optional
        Trapezoid nodes per nutation period.
    closed_form : bool, optional
        Force (``True``) or forbid (``False``) the closed form; default: closed form when available.

    Returns
    -------
    U1, U2, U3 : float

    See Also
    --------
    drag_rhs : the closed form (3.4) for the linear drag.
    averaged : integrates this system.
    has_closed_form : whether a torque supplies a closed form.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, eqs. (2.15)-(2.16).

    Examples
    --------
    For the drag (3.1) the quadrature route (``closed_form=False``) and the closed form (3.4) agree;
    case 2's roots ``(0, 0.5, 2)``:

    >>> from rigidbody import lagrange
    >>> top, drag = lagrange.PAPER_TOP, lagrange.PAPER_DRAG
    >>> by_quadrature = lagrange.averaged_rhs(top, drag, 0.0, 0.5, 2.0, closed_form=False)
    >>> closed = lagrange.averaged_rhs(top, drag, 0.0, 0.5, 2.0, closed_form=True)
    >>> print(" ".join(f"{x:.6f}" for x in by_quadrature))
    -0.051796 -0.040170 -0.348204
    >>> print(" ".join(f"{x:.6f}" for x in closed))
    -0.051796 -0.040170 -0.348204
    """
    top = check_top(top)
    torque = check_torque(torque)
    _check_roots(u1, u2, u3)
    closed = closed_form_choice(torque, closed_form)
    if closed and type(torque) is LinearDrag:  # the printed (3.4)
        out = drag_rhs(top, torque, u1, u2, u3, delta1, delta2)
        return float(out[0]), float(out[1]), float(out[2])
    Gz, H, r = from_roots(top, u1, u2, u3, delta1, delta2)
    if closed:  # the torque's own closed form, at the state decoded as the GHr chart does
        g = _k.decode_g(_k.SCALAR, top.A, top.C, top.mgl, *_k.slow_to_polar(_k.SCALAR, top.C, Gz, H, r, top.mgl))
        Fm = torque.closed_means(_k.SCALAR, top, g)
    else:
        Fm = averaged_slow_rates(top, torque, Gz, H, r, (u1, u2, u3), n=n)
    V = V_matrix(top, u1, u2, u3, Gz, r)
    U = V @ np.array(Fm)
    return float(U[0]), float(U[1]), float(U[2])


def drag_rhs(
    top: Top, drag: LinearDrag, u1: Any, u2: Any, u3: Any, delta1: Any = -1.0, delta2: Any = 1.0
) -> np.ndarray:
    r"""Closed-form averaged system (3.4) for linear drag (3.1), vectorised over states.

    .. math::
        u_1' = -\frac{1}{mgl(u_1-u_2)(u_1-u_3)}\Big[b\frac CA r^2u_1^2 - a\frac CA r^2(u_1^2-1)
        - 2\frac aA mgl(u_1^2-1)v + 2\frac aA H(u_1^2-1) - \frac CA\Big(b - a\frac CA\Big)r^2u_1v \\
        - \frac CA\Big(\frac aA + \frac bC\Big)G_zru_1 + \frac a{A^2}G_z^2
        + \frac1A\Big(b - a\frac CA\Big)G_zrv\Big],

    ``v = u3 - (u3 - u1) E(k)/K(k)`` (= the nutation mean of ``u``), the same ``v`` in all three
    equations; ``u2', u3'`` by cyclic permutation of the indices of ``u``; (Gz, H, r) from (2.8). The
    printed form (002 OCR) is verified against the general engine (tests/lagrange, test name
    ``test_drag_closed_form_equals_engine``).

    Returns
    -------
    numpy.ndarray
        Shape ``(3, ...)``.

    Raises
    ------
    ValueError
        Unless ``u1 < u2 < u3`` (regular precession ``u1 = u2`` and the separatrix ``u2 = u3`` are
        singular points of (3.4)).

    See Also
    --------
    averaged_rhs : the general averaged system (2.15)-(2.16).
    LinearDrag : the torque (3.1).

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, eq. (3.4).

    Examples
    --------
    Vieta (1.6) and ``r = r0 exp(-b tau/C)`` (3.3) fix one combination of the rates: the rates of the
    roots sum to ``ds1/dtau``, which :func:`vieta` applied to the slow rates (2.7) gives as well. In case 2:

    >>> from rigidbody import lagrange
    >>> top = lagrange.PAPER_TOP
    >>> Gz, H, r = lagrange.integrals(top, *lagrange.paper_initial_state(2)[:5])
    >>> du = lagrange.drag_rhs(top, lagrange.PAPER_DRAG, 0.0, 0.5, 2.0)
    >>> dGz, dH, dr = lagrange.averaged_slow_rates(top, lagrange.PAPER_DRAG, Gz, H, r)
    >>> ds1 = dH / top.mgl - top.C * r * dr / top.mgl + top.C**2 * r * dr / (top.A * top.mgl)
    >>> print(f"{sum(du):.6f} {ds1:.6f}")
    -0.440170 -0.440170
    """
    A, C, mgl = top.A, top.C, top.mgl
    a, b = drag.a, drag.b
    scalar = all(isinstance(x, (float, int)) for x in (u1, u2, u3, delta1, delta2))
    if scalar:
        if not (u1 < u2 < u3):
            _check_roots(u1, u2, u3)
    else:
        u1, u2, u3 = (np.asarray(x, dtype=float) for x in (u1, u2, u3))
        _check_roots(u1, u2, u3)
    Gz, H, r = from_roots(top, u1, u2, u3, delta1, delta2)
    _, mc = modulus(u1, u2, u3)
    v = u3 - (u3 - u1) * _ell.E(mc=mc) / _ell.K(mc=mc)
    us = (u1, u2, u3)
    out = []
    for i in range(3):
        ui, uj, uk = us[i], us[(i + 1) % 3], us[(i + 2) % 3]
        bracket = (
            b * C / A * r * r * ui * ui
            - a * C / A * r * r * (ui * ui - 1.0)
            - 2.0 * a / A * mgl * (ui * ui - 1.0) * v
            + 2.0 * a / A * H * (ui * ui - 1.0)
            - C / A * (b - a * C / A) * r * r * ui * v
            - C / A * (a / A + b / C) * Gz * r * ui
            + a / (A * A) * Gz * Gz
            + 1.0 / A * (b - a * C / A) * Gz * r * v
        )
        out.append(-bracket / (mgl * (ui - uj) * (ui - uk)))
    return np.array(out)
