r"""The unperturbed Lagrange motion in closed form: u(t) (1.3)-(1.4) and phi(t), psi(t) by (1.7)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..core import elliptic as _ell
from ..core.ode import Solution, integrate
from ._averaging import modulus
from ._top import Top, check_top, integrals, roots

__all__ = ["lagrange_motion", "nutation_frequency"]


def nutation_frequency(top: Top, u1: float, u3: float) -> float:
    r"""``alpha = [mgl (u3 - u1) / (2A)]^{1/2}`` of (1.3); the nutation period is ``2K(k)/alpha``.

    ``u = u1 + (u2 - u1) sn^2(alpha t + beta, k)`` (1.3), with ``k^2`` from (1.4) (:func:`modulus`).

    Parameters
    ----------
    top : Top
        Only ``A`` and ``mgl`` enter.
    u1, u3 : float
        Smallest and largest roots of the cubic (1.5), ``u1 <= u3`` (dimensionless).

    Returns
    -------
    float
        The frequency ``alpha`` of the elliptic phase, in 1/time (units of ``top``: ``(mgl/A)^{1/2}``).

    Raises
    ------
    ValueError
        If ``u3 < u1`` (negative radicand, from :func:`math.sqrt`).

    See Also
    --------
    modulus : the modulus ``k`` of the same phase (1.4).
    lagrange_motion : the motion (1.3) it paces.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, eq. (1.3).

    Examples
    --------
    Case 2's roots ``(0, 0.5, 2)`` with ``mgl = 0.5``, ``A = 1.5``: ``alpha = (0.5 · 2 / 3)^{1/2} =
    1/sqrt(3)``:

    >>> from rigidbody import lagrange
    >>> print(f"{lagrange.nutation_frequency(lagrange.PAPER_TOP, 0.0, 2.0):.6f}")
    0.577350
    """
    return math.sqrt(top.mgl * (u3 - u1) / (2.0 * top.A))


def lagrange_motion(
    top: Top,
    state0: tuple[float, float, float, float, float, float],
    t: Any,
    *,
    rtol: float = 1e-12,
    atol: float = 1e-12,
) -> Solution:
    r"""The unperturbed (eps = 0) Lagrange motion from an initial state, by the paper's formulas.

    ``u = cos(theta) = u1 + (u2 - u1) sn^2(alpha t + beta, k)`` (1.3)-(1.4) with the phase ``beta`` fixed
    by ``u(0) = cos(theta0)`` and the sign of ``u'(0) = -sin(theta0) theta'(0)``; then ``psi``, ``phi`` by
    the quadratures (1.7)

    .. math:: \dot\psi = \frac{G_z - Cru}{A(1-u^2)},\qquad \dot\varphi = r - u\dot\psi,

    integrated along the closed-form ``u(t)`` (high-order ODE quadrature, tolerance ``rtol``).

    Parameters
    ----------
    top : Top
    state0 : (p, q, r, phi, theta, psi)
        Initial state; ``0 < theta0 < pi`` is required for psi, phi (Euler angles are singular at the
        poles) and the motion must not reach ``u = +-1`` (``Gz = +-C r``; a ``ValueError`` is raised).
    t : array_like
        Increasing output times starting at 0 or later.

    Returns
    -------
    rigidbody.core.ode.Solution
        ``t``, ``u``, ``theta``, ``phi``, ``psi``, and the constants as attributes of ``fields``:
        ``u1, u2, u3, k2, alpha, beta`` (scalars, stored as 0-d arrays).

    See Also
    --------
    simulate : the full equations (1.1), with a torque.
    roots : the turning points ``u1, u2`` of the nutation.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, eqs. (1.3)-(1.4), (1.7).

    Examples
    --------
    The nutation of case 2 runs between the roots ``u1 = 0`` and ``u2 = 0.5`` of the paper's table
    (``u = cos theta``: the axis swings between 90 and 60 degrees):

    >>> import numpy as np
    >>> from rigidbody import lagrange
    >>> sol = lagrange.lagrange_motion(lagrange.PAPER_TOP, lagrange.paper_initial_state(2),
    ...                                np.linspace(0.0, 20.0, 2001))
    >>> print(f"{round(sol.u.min(), 6) + 0.0:.6f} {sol.u.max():.6f}")  # + 0.0: no "-0"
    0.000000 0.500000
    """
    top = check_top(top)
    p0, q0, r0, phi0, th0, psi0 = (float(x) for x in state0)
    if not 0.0 < th0 < math.pi:
        raise ValueError(f"theta0 must lie in (0, pi) for the Euler-angle quadratures (1.7), got {th0!r}")
    t = np.asarray(t, dtype=float)
    if t.ndim != 1 or t.size == 0 or np.any(np.diff(t) <= 0) or t[0] < 0:
        raise ValueError("t must be a non-empty increasing 1-D array of times >= 0")
    Gz, H, r = integrals(top, p0, q0, r0, phi0, th0)
    u1, u2, u3 = roots(top, Gz, H, r)
    if u1 <= -1.0 + 1e-12 or u2 >= 1.0 - 1e-12:
        # Q(-1) = -(Gz + Cr)^2/A^2 = 0 or Q(1) = -(Gz - Cr)^2/A^2 = 0: a turning point at a pole
        pole = "pi" if u1 <= -1.0 + 1e-12 else "0"
        raise ValueError(
            f"the motion reaches theta = {pole} (u1 = -1 or u2 = 1, i.e. Gz = -+C r): the Euler angles "
            "psi, phi of (1.7) are singular there; use simulate (quaternion attitude) instead"
        )
    k2, mc = modulus(u1, u2, u3)
    alpha = nutation_frequency(top, u1, u3)
    u0 = math.cos(th0)
    dtheta0 = p0 * math.cos(phi0) - q0 * math.sin(phi0)
    du0 = -math.sin(th0) * dtheta0
    if u2 > u1:
        x = min(max((u0 - u1) / (u2 - u1), 0.0), 1.0)
        beta = float(_ell.F(math.asin(math.sqrt(x)), mc=mc))
        if du0 < 0.0:
            beta = -beta
    else:
        beta = 0.0
    mc_ = max(mc, 0.0)

    def u_of(tt: Any) -> Any:
        snv = np.asarray(_ell.sn(alpha * np.asarray(tt) + beta, mc=mc_))
        return u1 + (u2 - u1) * snv * snv

    A, C = top.A, top.C

    def rhs(tt: float, y: np.ndarray) -> list[float]:
        u = float(u_of(tt))
        dpsi = (Gz - C * r * u) / (A * (1.0 - u * u))
        return [dpsi, r - u * dpsi]

    sol = integrate(rhs, (0.0, float(t[-1])), [psi0, phi0], t_eval=t if t[0] == 0.0 else np.r_[0.0, t],
                    rtol=rtol, atol=atol)
    psi, phi = sol.y[0], sol.y[1]
    tt = sol.t
    if t[0] != 0.0:
        psi, phi, tt = psi[1:], phi[1:], tt[1:]
    u = u_of(tt)
    data = {
        "u": u, "theta": np.arccos(np.clip(u, -1.0, 1.0)), "psi": psi, "phi": phi,
        "u1": np.asarray(u1), "u2": np.asarray(u2), "u3": np.asarray(u3), "k2": np.asarray(k2),
        "alpha": np.asarray(alpha), "beta": np.asarray(beta),
        "Gz": np.asarray(Gz), "H": np.asarray(H), "r": np.asarray(r),
    }
    return Solution.build(producer="lagrange.lagrange_motion", time_name="t", time=tt, y=np.vstack([psi, phi]),
                          status=sol.status, message=sol.message, fields=data, event=sol.event, t_events=sol.t_events,
                          y_events=sol.y_events, nfev=sol.nfev)
