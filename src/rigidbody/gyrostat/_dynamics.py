"""Full Newton-Euler equations of a gyrostat satellite in a central field (validation route).

The model behind the amended potential of section 2: translation of G under the force of the
second-order (MacCullagh) potential ``U = mu M / r - 3/2 mu r^-3 [e.I.e - tr I / 3]`` and rotation under
its torque, with a rotor of constant body-fixed momentum ``k``.  No use is made of W, (2.2) or (2.4): a
stationary motion found by Routh's method must be a relative equilibrium of these equations.

State (13): ``r`` (3, inertial, origin at the attracting centre O), ``v`` (3), quaternion ``q`` (4,
scalar first, body -> inertial), ``omega`` (3, body components).  Inertial axes: zeta1, zeta2, zeta3
of section 1 (zeta2 the axis of the orbital rotation).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..core.ode import Event, Solution, integrate
from ._model import Satellite
from ._stationary import StationaryMotion
from ._symmetric import SymmetricMotion

__all__ = ["initial_state", "simulate"]


def _dcm(q0: float, q1: float, q2: float, q3: float) -> tuple[float, ...]:
    return (
        1 - 2 * (q2 * q2 + q3 * q3), 2 * (q1 * q2 - q0 * q3), 2 * (q1 * q3 + q0 * q2),
        2 * (q1 * q2 + q0 * q3), 1 - 2 * (q1 * q1 + q3 * q3), 2 * (q2 * q3 - q0 * q1),
        2 * (q1 * q3 - q0 * q2), 2 * (q2 * q3 + q0 * q1), 1 - 2 * (q1 * q1 + q2 * q2),
    )


def _rhs(t: float, y: np.ndarray, M: float, A1: float, A2: float, A3: float, mu: float,
         k1: float, k2: float, k3: float) -> list[float]:
    x, yy, z, vx, vy, vz, q0, q1, q2, q3, w1, w2, w3 = y
    nq = math.sqrt(q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3)
    q0, q1, q2, q3 = q0 / nq, q1 / nq, q2 / nq, q3 / nq
    c11, c12, c13, c21, c22, c23, c31, c32, c33 = _dcm(q0, q1, q2, q3)
    r = math.sqrt(x * x + yy * yy + z * z)
    ex, ey, ez = x / r, yy / r, z / r
    # body components of e = r / |r|
    b1 = c11 * ex + c21 * ey + c31 * ez
    b2 = c12 * ex + c22 * ey + c32 * ez
    b3 = c13 * ex + c23 * ey + c33 * ez
    I1, I2, I3 = A1 * b1, A2 * b2, A3 * b3
    s = b1 * I1 + b2 * I2 + b3 * I3
    trI = A1 + A2 + A3
    # (I e - s e) in inertial components
    d1, d2, d3 = I1 - s * b1, I2 - s * b2, I3 - s * b3
    dx = c11 * d1 + c12 * d2 + c13 * d3
    dy = c21 * d1 + c22 * d2 + c23 * d3
    dz = c31 * d1 + c32 * d2 + c33 * d3
    r2, r4 = r * r, r**4
    f_rad = -mu * M / r2 - 1.5 * mu / r4 * (trI - 3 * s)
    fx = f_rad * ex - 3 * mu / r4 * dx
    fy = f_rad * ey - 3 * mu / r4 * dy
    fz = f_rad * ez - 3 * mu / r4 * dz
    g = 3 * mu / r**3
    T1 = g * (b2 * I3 - b3 * I2)
    T2 = g * (b3 * I1 - b1 * I3)
    T3 = g * (b1 * I2 - b2 * I1)
    h1, h2, h3 = A1 * w1 + k1, A2 * w2 + k2, A3 * w3 + k3
    dw1 = (T1 - (w2 * h3 - w3 * h2)) / A1
    dw2 = (T2 - (w3 * h1 - w1 * h3)) / A2
    dw3 = (T3 - (w1 * h2 - w2 * h1)) / A3
    dq0 = -0.5 * (q1 * w1 + q2 * w2 + q3 * w3)
    dq1 = 0.5 * (q0 * w1 + q2 * w3 - q3 * w2)
    dq2 = 0.5 * (q0 * w2 + q3 * w1 - q1 * w3)
    dq3 = 0.5 * (q0 * w3 + q1 * w2 - q2 * w1)
    return [vx, vy, vz, fx / M, fy / M, fz / M, dq0, dq1, dq2, dq3, dw1, dw2, dw3]


def _quat_from_columns(C: np.ndarray) -> np.ndarray:
    from ..core.euler import quat_from_dcm

    return np.asarray(quat_from_dcm(C), dtype=float)


def initial_state(sat: Satellite, motion: StationaryMotion | SymmetricMotion, *, sigma0: float = 0.0) -> np.ndarray:
    r"""The 13-state of the stationary motion at orbital angle ``sigma0``.

    G at ``R0 (cos k sin s, sin k, cos k cos s)``, velocity ``omega0 zeta2 x r``; body axes
    ``x1 = y1``, ``x2 = cos th y2 - sin th y3``, ``x3 = sin th y2 + cos th y3`` (so that beta, gamma are
    those of (2.3)); body angular velocity ``omega0 beta`` (plus, for (3.2), the spin about x3 fixed by
    ``c = A3 omega3 + k3``).

    The point (2.3) of the family (2.3)-(2.4), or the motion (3.2)-(3.3), as an initial state of the
    full Newton-Euler equations of :func:`simulate`.

    Parameters
    ----------
    sat : Satellite
        Supplies ``k3`` and ``A3`` for the spin of a :class:`SymmetricMotion` (unused otherwise).
    motion : StationaryMotion or SymmetricMotion
        The stationary motion (``R0, theta0, kappa0, omega0``, and ``c`` for (3.2)).
    sigma0 : float
        Orbital angle sigma of the centre of mass at the start (radians).

    Returns
    -------
    ndarray, shape (13,)
        ``(r, v, q, omega)``: position of G from the attracting centre and its velocity in the inertial
        axes zeta1, zeta2, zeta3 (3 + 3), the unit quaternion body -> inertial, scalar first (4), and the
        body components of the angular velocity (3); in the units of ``sat`` and ``motion``.

    See Also
    --------
    simulate : integrates the full equations from it.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eq. (2.3) and section 5.

    Examples
    --------
    G lies at the distance :math:`R_0` at the latitude :math:`\kappa_0` and moves on a circle of radius
    :math:`R_0\cos\kappa_0` at the rate :math:`\omega_0`:

    >>> import math
    >>> import numpy as np
    >>> from rigidbody import gyrostat
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    >>> m = gyrostat.stationary_motion(sat, 1.0, math.pi / 4, k2=0.0)
    >>> y0 = gyrostat.initial_state(m.satellite, m)
    >>> r, v = y0[:3], y0[3:6]
    >>> print(f"{np.linalg.norm(r):.12f} {r[1]:.12f} {math.sin(m.kappa0):.12f}")
    1.000000000000 0.002986547159 0.002986547159
    >>> print(f"{np.linalg.norm(v):.12f} {m.omega0 * math.cos(m.kappa0):.12f}")
    1.002247474429 1.002247474429
    """
    R0, kap, th, om = motion.R0, motion.kappa0, motion.theta0, motion.omega0
    ck, sk, cs, ss = math.cos(kap), math.sin(kap), math.cos(sigma0), math.sin(sigma0)
    y3 = np.array([ck * ss, sk, ck * cs])
    y1 = np.array([cs, 0.0, -ss])
    y2 = np.cross(y3, y1)
    x1 = y1
    x2 = math.cos(th) * y2 - math.sin(th) * y3
    x3 = math.sin(th) * y2 + math.cos(th) * y3
    C = np.column_stack([x1, x2, x3])
    r = R0 * y3
    v = om * np.cross([0.0, 1.0, 0.0], r)
    beta = C.T @ np.array([0.0, 1.0, 0.0])
    w = om * beta
    if isinstance(motion, SymmetricMotion):
        w3 = (motion.c - sat.k3) / sat.A3
        w = np.array([w[0], w[1], w3])
    return np.concatenate([r, v, _quat_from_columns(C), w])


def simulate(
    sat: Satellite,
    motion: StationaryMotion | SymmetricMotion | Any,
    t_span: tuple[float, float],
    *,
    dy0: Any = None,
    t_eval: Any = None,
    rtol: float = 1e-11,
    atol: float = 1e-13,
) -> Solution:
    r"""Integrate the full equations from a stationary motion (optionally perturbed by ``dy0``).

    Parameters
    ----------
    sat : Satellite
        Mass properties, mu and rotor momentum (for a :class:`StationaryMotion` use ``motion.satellite``,
        which carries its k2, k3).
    motion : StationaryMotion, SymmetricMotion or array of 13
        Start state (a motion is converted by :func:`initial_state`).
    dy0 : array of 13, optional
        Perturbation added to the state (the quaternion is renormalised in the right-hand side).

    Returns
    -------
    Solution
        Fields ``R``, ``kappa`` (latitude of G above the plane zeta3 zeta1), ``beta`` (3, n), ``gamma``
        (3, n): direction cosines of zeta2 and of OG in the body axes, as in section 2.
        A collision with the attracting centre (r < 1e-3 R0) ends the run (event ``'collision'``).

    See Also
    --------
    initial_state : the state of a stationary motion.
    rigidbody.plotting.plot_satellite_motion : the standard figure (``sol.plot()``).

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, sections 1-2 (the model behind W).

    Examples
    --------
    A motion found by Routh's method is a relative equilibrium of the full equations: over one orbit
    :math:`R`, :math:`\kappa` and the body components of OG stay at their values (2.3) to the integration
    tolerance:

    >>> import math
    >>> import numpy as np
    >>> from rigidbody import gyrostat
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    >>> m = gyrostat.stationary_motion(sat, 1.0, math.pi / 4, k2=0.0)
    >>> sol = gyrostat.simulate(m.satellite, m, (0.0, 2 * math.pi), t_eval=np.linspace(0.0, 2 * math.pi, 9))
    >>> bool(np.abs(sol.R - 1.0).max() < 1e-9 and np.abs(sol.kappa - m.kappa0).max() < 1e-9)
    True
    >>> bool(np.abs(sol.gamma - np.array(m.gamma)[:, None]).max() < 1e-9)
    True
    """
    y0 = initial_state(sat, motion) if isinstance(motion, (StationaryMotion, SymmetricMotion)) else np.asarray(
        motion, dtype=float)
    if y0.shape != (13,):
        raise ValueError(f"motion must be a stationary motion or a state of 13 numbers; got shape {y0.shape}")
    if dy0 is not None:
        y0 = y0 + np.asarray(dy0, dtype=float)
    r0 = float(np.linalg.norm(y0[:3]))
    args = (sat.M, sat.A1, sat.A2, sat.A3, sat.mu, sat.k1, sat.k2, sat.k3)

    def fields(t: np.ndarray, Y: np.ndarray) -> dict[str, np.ndarray]:
        r = Y[:3]
        R = np.linalg.norm(r, axis=0)
        q = Y[6:10] / np.linalg.norm(Y[6:10], axis=0)
        from ..core.euler import dcm_from_quat

        C = dcm_from_quat(q.T)  # (n, 3, 3), body -> inertial
        e = (r / R).T
        gamma = np.einsum("nij,ni->jn", C, e)
        beta = C[:, 1, :].T
        return {"R": R, "kappa": np.arcsin(np.clip(r[1] / R, -1, 1)), "beta": beta, "gamma": gamma}

    collision = Event(lambda t, y, *a: float(np.linalg.norm(y[:3])) - 1e-3 * r0, "collision", terminal=True,
                      message="G reached the attracting centre")
    return integrate(_rhs, t_span, y0, t_eval=t_eval, rtol=rtol, atol=atol, args=args, fields=fields,
                     events=(collision,))
