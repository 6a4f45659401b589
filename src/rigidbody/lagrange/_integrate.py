r"""Integrations: the averaged system (2.15) with sign switching, and the full equations (1.1)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..core import euler as _euler
from ..core.ode import Solution, integrate
from ..core.validate import positive, span
from ._avgrun import averaged
from ._top import Top, _check_top
from ._torques import Torque, check_torque

__all__ = ["averaged", "simulate"]


# ==================================================================================================
# full equations (1.1)
# ==================================================================================================
def simulate(
    top: Top,
    torque: Torque,
    eps: float,
    state0: tuple[float, float, float, float, float, float],
    t_span: tuple[float, float],
    t_eval: Any = None,
    *,
    rtol: float = 1e-10,
    atol: float = 1e-12,
    method: str = "DOP853",
    dense_output: bool = False,
) -> Solution:
    r"""Integrate the full equations of motion (1.1) with the perturbing torque ``eps M``.

    Inside, the attitude is a unit quaternion (scalar first, the rotation of
    :func:`rigidbody.core.euler.dcm`), so nothing breaks at ``theta = 0`` or ``pi``; the state is
    ``(p, q, r, q0, q1, q2, q3)``:

    .. math::
        Ap' + (C-A)qr = mgl\,\gamma_2 + \varepsilon M_1,\quad Aq' + (A-C)pr = -mgl\,\gamma_1 +
        \varepsilon M_2,\quad Cr' = \varepsilon M_3,\quad \dot{\mathbf q} = \tfrac12\mathbf q\otimes(0,\omega),

    with the upward vertical in body axes ``gamma = (sin th sin phi, sin th cos phi, cos th)``. Euler
    angles are derived output (:func:`rigidbody.core.euler.euler_from_quat`; at ``sin theta = 0``:
    ``phi = 0``).

    Parameters
    ----------
    top : Top
    torque : Torque
        Must implement ``body_moments`` (:class:`LinearDrag`, :class:`ProportionalTorque`,
        :class:`VerticalPlaneTorque`).
    eps : float
        Small parameter, ``eps >= 0``.
    state0 : (p, q, r, phi, theta, psi)
        Initial angular velocity (body components) and Euler angles (rad).
    t_span : (t0, t1)
        Time interval (fast time ``t``; ``tau = eps t``).
    t_eval : array_like, optional
    rtol, atol, method, dense_output
        As in :func:`scipy.integrate.solve_ivp`.

    Returns
    -------
    rigidbody.core.ode.Solution
        ``t``, ``tau``, ``p``, ``q``, ``r``, ``phi``, ``theta``, ``psi``, ``u`` (= cos theta), ``Gz``,
        ``H`` (first integrals (1.2) along the motion: the slow variables), ``quat`` (4, n).
    """
    top = _check_top(top)
    torque = check_torque(torque)
    if isinstance(eps, bool) or not isinstance(eps, (int, float, np.floating, np.integer)):
        raise TypeError(f"eps must be a real number, got {type(eps).__name__}")
    eps = float(eps)
    if not math.isfinite(eps) or eps < 0.0:
        raise ValueError(f"eps must be finite and >= 0, got {eps!r}")
    t0, t1 = span(t_span, "t_span")
    rtol, atol = positive(rtol, "rtol"), positive(atol, "atol")
    try:
        p0, q0, r0, phi0, th0, psi0 = (float(x) for x in state0)
    except (TypeError, ValueError):
        raise ValueError(f"state0 must be (p, q, r, phi, theta, psi), got {state0!r}") from None
    quat0 = _euler.quat_from_euler(psi0, th0, phi0)
    y0 = np.array([p0, q0, r0, *np.asarray(quat0, dtype=float)])
    A, C, mgl = top.A, top.C, top.mgl
    body = torque.body_moments
    if eps > 0.0:
        body(top, p0, q0, r0, 0.0, 0.0, 1.0)  # fail early (TypeError) for torques without body moments

    def rhs(t: float, y: np.ndarray) -> list[float]:
        p, q, r, w, x, yq, z = y
        g1 = 2.0 * (x * z - w * yq)
        g2 = 2.0 * (yq * z + w * x)
        g3 = 1.0 - 2.0 * (x * x + yq * yq)
        if eps != 0.0:
            M1, M2, M3 = body(top, p, q, r, g1, g2, g3)
        else:
            M1 = M2 = M3 = 0.0
        return [
            ((A - C) * q * r + mgl * g2 + eps * M1) / A,
            ((C - A) * p * r - mgl * g1 + eps * M2) / A,
            eps * M3 / C,
            0.5 * (-x * p - yq * q - z * r),
            0.5 * (w * p + yq * r - z * q),
            0.5 * (w * q + z * p - x * r),
            0.5 * (w * r + x * q - yq * p),
        ]

    def fields(t: np.ndarray, y: np.ndarray) -> dict[str, np.ndarray]:
        quat = y[3:7] / np.linalg.norm(y[3:7], axis=0)
        psi, theta, phi = _euler.euler_from_quat(quat.T)
        w, x, yq, z = quat
        g1 = 2.0 * (x * z - w * yq)
        g2 = 2.0 * (yq * z + w * x)
        g3 = 1.0 - 2.0 * (x * x + yq * yq)
        p, q, r = y[0], y[1], y[2]
        return {
            "tau": eps * t, "p": p, "q": q, "r": r,
            "phi": np.asarray(phi), "theta": np.asarray(theta), "psi": np.asarray(psi),
            "u": g3, "Gz": A * (p * g1 + q * g2) + C * r * g3,
            "H": 0.5 * (A * (p * p + q * q) + C * r * r) + mgl * g3,
            "quat": quat,
        }

    return integrate(rhs, (t0, t1), y0, t_eval=t_eval, rtol=rtol, atol=atol, method=method,
                     dense_output=dense_output, fields=fields, time_name="t")
