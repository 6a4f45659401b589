r"""The averaged rates of a body with two equal moments at one slow state: :func:`symmetric_rates`."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..core.validate import positive, real
from ._boundary import as_torque
from ._model import Orbit, as_orbit
from ._output import unit_of_angles
from ._rates import direction_rates
from ._symbody import SymmetricBody
from ._symengine import choose_grid, sym_mean, sym_rates

__all__ = ["symmetric_rates"]


def symmetric_rates(body: SymmetricBody, torque: Any, G: float, theta: float, delta: float, lam: float,
                    nu: float | None, *, orbit: Orbit | None = None, quad_tol: float = 1e-12) -> dict[str, float]:
    r"""Right-hand sides of the averaged system of a body with two equal moments (the mean over its regular
    precession), per unit of the slow time :math:`\tau`.

    Parameters
    ----------
    body : SymmetricBody
    torque : array_like, Drag, torque object or callable
        As in :func:`averaged` (a drag tensor means linear drag plus the gravity gradient).
    G, theta, delta, lam : float
        The slow variables: :math:`G > 0`, the nutation angle of :math:`\mathbf G` from the symmetry axis (in
        :math:`[0, \pi]`; for the sphere the angle of :math:`\mathbf G` from the body axis :math:`z_3`, with
        :math:`\mathbf G` in the plane of :math:`z_2, z_3`), the polar angle and azimuth of :math:`\mathbf G` in the
        orbital axes.
    nu : float or None
        True anomaly; ``None`` gives the orbit-averaged limit.
    orbit : Orbit, optional
        Default circular.
    quad_tol : float
        Relative tolerance to which the quadrature's grid is chosen.

    Returns
    -------
    dict
        ``dG``, ``dT``, ``dtheta``, ``ddelta``, ``dlam`` and ``quad_error`` (the estimated error of the means,
        relative to the torque's size). ``ddelta`` and ``dlam`` as in :func:`averaged_rates` (at a pole ``dlam`` is
        infinite where :math:`\mathbf n` moves off it, else its limit along the meridian). ``dtheta`` is
        :math:`(\cos\theta\,\langle M_\varphi\rangle - \sin\theta\,\langle M_3\rangle)/G`, finite on the axis
        too; for the sphere the rate of the angle of :math:`\mathbf G` from :math:`z_3` in the body.

    Raises
    ------
    TypeError
        If ``body`` is not a :class:`SymmetricBody`, a number is not real or ``torque`` is not a torque.
    ValueError
        If ``G <= 0``, ``theta`` or ``delta`` is outside :math:`[0, \pi]`, or the torque misbehaves (named).

    See Also
    --------
    averaged : integrates these rates (``theta0`` for a :class:`SymmetricBody`).
    averaged_rates : the rates of a triaxial :class:`Body`, whose limits these are.

    Examples
    --------
    An axisymmetric drag on a prolate body: the axial component of :math:`\mathbf G` decays at :math:`I_3/C`, the
    transverse one at :math:`I_1/A`, so :math:`\tan\theta` grows at :math:`I_3/C - I_1/A = 0.25` and
    :math:`\dot\theta = 0.25\sin\theta\cos\theta`:

    >>> import math
    >>> from rigidbody import euler_poinsot as ep
    >>> r = ep.symmetric_rates(ep.SymmetricBody(2.0, 1.0), ep.LinearDrag([0.1, 0.1, 0.3]), 1.0, 1.0, 0.5, 0.0, None)
    >>> print(f"{r['dtheta']:.12f} {0.25 * math.sin(1.0) * math.cos(1.0):.12f}")
    0.113662178353 0.113662178353
    """
    if not isinstance(body, SymmetricBody):
        raise TypeError(f"body must be a SymmetricBody, got {type(body).__name__}")
    G, theta, delta, lam = real(G, "G"), real(theta, "theta"), real(delta, "delta"), real(lam, "lam")
    if G <= 0.0:
        raise ValueError(f"G must be positive, got {G}")
    for name, v in (("theta", theta), ("delta", delta)):
        if not 0.0 <= v <= math.pi:
            raise ValueError(f"{name} must lie in [0, pi], got {v}")
    nu = None if nu is None else real(nu, "nu")
    orb = as_orbit(orbit)
    tq, _ = as_torque(torque, body, orb)
    tq.check_setup(body, orb)
    gb = np.array([0.0, math.sin(theta), math.cos(theta)])
    tol = positive(quad_tol, "quad_tol")
    grid, m = choose_grid(tq, body, G, gb, np.array(unit_of_angles(delta, lam)), nu, orb, tol)

    def L_at(d: float) -> np.ndarray:  # the mean torque at another polar angle of G (the limit at a pole)
        return sym_mean(tq, body, grid, G, gb, np.array(unit_of_angles(d, lam)), nu, orb).L

    dG, ddelta, dlam = direction_rates(m.L, G, delta, lam, L_at)
    r = sym_rates(body, m, G, gb, np.array(unit_of_angles(delta, lam)))
    if "dgb" in r:  # the sphere: the angle of G from z3 in the body
        st, dc = math.sin(theta), float(r["dgb"][2])
        dtheta = -dc / st if st > 0.0 else (0.0 if dc == 0.0 else math.inf)
    else:
        dtheta = float(r["dtheta"])
    return {"dG": dG, "dT": float(r["dT"]), "dtheta": float(dtheta), "ddelta": ddelta, "dlam": dlam,
            "quad_error": m.error / m.scale if m.scale > 0.0 else 0.0}
