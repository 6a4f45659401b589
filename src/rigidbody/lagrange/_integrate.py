r"""Integrations: the averaged system (2.15) with sign switching, and the full equations (1.1)."""

from __future__ import annotations

from typing import Any

import numpy as np

from ..core import euler as _euler
from ..core.batch import integrate_batch
from ..core.ode import Solution, integrate
from ..core.validate import member_states, positive, span
from ._avgrun import averaged
from ._top import Top, check_top
from ._torques import Torque, check_torque

__all__ = ["averaged", "simulate"]


# ==================================================================================================
# full equations (1.1)
# ==================================================================================================
def _gamma(w: Any, x: Any, yq: Any, z: Any) -> tuple[Any, Any, Any]:
    """The upward vertical in body axes from the attitude quaternion (floats or arrays)."""
    return 2.0 * (x * z - w * yq), 2.0 * (yq * z + w * x), 1.0 - 2.0 * (x * x + yq * yq)


def _full_rates(top: Top, eps: Any, y: Any, M: tuple[Any, Any, Any]) -> list[Any]:
    """Right-hand side of (1.1) with the quaternion kinematics, for one state (floats) or a batch (arrays)."""
    A, C, mgl = top.A, top.C, top.mgl
    p, q, r, w, x, yq, z = y
    g1, g2, _ = _gamma(w, x, yq, z)
    return [
        ((A - C) * q * r + mgl * g2 + eps * M[0]) / A,
        ((C - A) * p * r - mgl * g1 + eps * M[1]) / A,
        eps * M[2] / C,
        0.5 * (-x * p - yq * q - z * r),
        0.5 * (w * p + yq * r - z * q),
        0.5 * (w * q + z * p - x * r),
        0.5 * (w * r + x * q - yq * p),
    ]


def _full_fields(top: Top, eps: Any, t: np.ndarray, y: np.ndarray) -> dict[str, np.ndarray]:
    """Output of :func:`simulate` from states ``y`` of shape ``(..., 7, n_t)``."""
    A, C, mgl = top.A, top.C, top.mgl
    quat = y[..., 3:7, :] / np.linalg.norm(y[..., 3:7, :], axis=-2, keepdims=True)
    psi, theta, phi = _euler.euler_from_quat(np.moveaxis(quat, -2, -1))
    w, x, yq, z = (quat[..., i, :] for i in range(4))
    g1, g2, g3 = _gamma(w, x, yq, z)
    p, q, r = y[..., 0, :], y[..., 1, :], y[..., 2, :]
    return {
        "tau": np.asarray(eps)[..., None] * t if np.ndim(eps) else eps * t, "p": p, "q": q, "r": r,
        "phi": np.asarray(phi), "theta": np.asarray(theta), "psi": np.asarray(psi),
        "u": g3, "Gz": A * (p * g1 + q * g2) + C * r * g3,
        "H": 0.5 * (A * (p * p + q * q) + C * r * r) + mgl * g3,
        "quat": quat,
    }


def simulate(
    top: Top,
    torque: Torque,
    eps: Any,
    state0: Any,
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

    A batch (components of ``state0`` or ``eps`` that are arrays; the batch shape is their broadcast shape, the
    convention of :func:`averaged`) is integrated together by :func:`rigidbody.core.batch.integrate_batch` on a
    common ``t_eval`` (default: 101 uniform points); each member equals its single run within the tolerance.

    Parameters
    ----------
    top : Top
    torque : Torque
        Must implement ``body_moments`` (:class:`LinearDrag`, :class:`ProportionalTorque`,
        :class:`VerticalPlaneTorque`). In a batch their user functions receive arrays of members.
    eps : float or array_like
        Small parameter, ``eps >= 0`` (per member in a batch).
    state0 : tuple (p, q, r, phi, theta, psi) or numpy.ndarray of shape ``batch_shape + (6,)``
        Initial angular velocity (body components) and Euler angles (rad): by components, a tuple or list of
        six numbers or arrays that broadcast together (and with ``eps``), or stacked, an array with one row per
        member (see :func:`rigidbody.core.validate.member_states`: the type decides).
    t_span : (t0, t1)
        Time interval (fast time ``t``; ``tau = eps t``).
    t_eval : array_like, optional
    rtol, atol, method, dense_output
        As in :func:`scipy.integrate.solve_ivp` (a batch always uses DOP853, without dense output).

    Returns
    -------
    rigidbody.core.ode.Solution
        ``t``, ``tau``, ``p``, ``q``, ``r``, ``phi``, ``theta``, ``psi``, ``u`` (= cos theta), ``Gz``,
        ``H`` (first integrals (1.2) along the motion: the slow variables), ``quat`` (4, n); for a batch each
        with the leading ``batch_shape`` and per-member ``status``, ``message``.

    See Also
    --------
    averaged : the averaged system (2.15) in slow time.
    lagrange_motion : the unperturbed motion (``eps = 0``).

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, eqs. (1.1), (3.1), (3.3).

    Examples
    --------
    For a symmetric top the axial Euler equation is ``C dr/dt = eps M3 = -eps b r``, so under the drag
    (3.1) the full motion keeps ``r = r0 exp(-eps b t / C)`` (3.3) exactly; case 2 with ``eps = 0.01`` to
    ``t = 10`` gives ``sqrt(3) exp(-0.01)``:

    >>> import math
    >>> from rigidbody import lagrange
    >>> state0 = lagrange.paper_initial_state(2)
    >>> sol = lagrange.simulate(lagrange.PAPER_TOP, lagrange.PAPER_DRAG, 0.01, state0, (0.0, 10.0))
    >>> print(f"{sol.r[-1]:.6f} {math.sqrt(3) * math.exp(-0.01):.6f}")
    1.714817 1.714817
    """
    top = check_top(top)
    torque = check_torque(torque)
    t0, t1 = span(t_span, "t_span")
    rtol, atol = positive(rtol, "rtol"), positive(atol, "atol")
    eps_a = _check_eps(eps)
    st0 = member_states(state0, ("p", "q", "r", "phi", "theta", "psi"), "state0")
    if eps_a.ndim or st0.ndim > 1:
        return _simulate_batch(top, torque, eps_a, st0, t0, t1, t_eval, rtol, atol)
    eps = float(eps_a)
    p0, q0, r0, phi0, th0, psi0 = (float(x) for x in st0)
    quat0 = _euler.quat_from_euler(psi0, th0, phi0)
    y0 = np.array([p0, q0, r0, *np.asarray(quat0, dtype=float)])
    body = torque.body_moments
    if eps > 0.0:
        body(top, p0, q0, r0, 0.0, 0.0, 1.0)  # fail early (TypeError) for torques without body moments
    zero = (0.0, 0.0, 0.0)

    def rhs(t: float, y: np.ndarray) -> list[float]:
        if eps != 0.0:
            M = body(top, y[0], y[1], y[2], *_gamma(y[3], y[4], y[5], y[6]))
        else:
            M = zero
        return _full_rates(top, eps, y, M)

    return integrate(rhs, (t0, t1), y0, t_eval=t_eval, rtol=rtol, atol=atol, method=method,
                     dense_output=dense_output, fields=lambda t, y: _full_fields(top, eps, t, y), time_name="t")


def _check_eps(eps: Any) -> np.ndarray:
    if isinstance(eps, (bool, np.bool_)) or (np.ndim(eps) == 0 and not isinstance(
            eps, (int, float, np.floating, np.integer))):
        raise TypeError(f"eps must be a real number, got {type(eps).__name__}")
    try:
        e = np.asarray(eps, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(f"eps must be real numbers, got {eps!r}") from None
    if not np.all(np.isfinite(e)) or np.any(e < 0.0):
        raise ValueError(f"eps must be finite and >= 0, got {eps!r}")
    return e


def _simulate_batch(top: Top, torque: Torque, eps: np.ndarray, st: np.ndarray, t0: float, t1: float, t_eval: Any,
                    rtol: float, atol: float) -> Solution:
    """The batch branch of :func:`simulate`: start states ``st`` of shape ``batch_shape + (6,)``."""
    try:
        batch_shape = np.broadcast_shapes(st.shape[:-1], eps.shape)
    except ValueError:
        raise ValueError(f"eps of shape {eps.shape} does not broadcast against the batch shape "
                         f"{st.shape[:-1]} of state0") from None
    st = np.broadcast_to(st, (*batch_shape, 6)).reshape(-1, 6)
    E = np.broadcast_to(eps, batch_shape).reshape(-1).copy()
    quat0 = np.asarray(_euler.quat_from_euler(st[:, 5], st[:, 4], st[:, 3]), dtype=float).reshape(-1, 4)
    y0 = np.concatenate([st[:, :3], quat0], axis=1).reshape((*batch_shape, 7))
    if np.any(E > 0.0):
        torque.body_moments(top, float(st[0, 0]), float(st[0, 1]), float(st[0, 2]), 0.0, 0.0, 1.0)  # fail early

    def rhs(t: np.ndarray, y: np.ndarray, e: np.ndarray) -> np.ndarray:
        p, q, r, w, x, yq, z = y.T
        g1, g2, g3 = _gamma(w, x, yq, z)
        M = _body_moments_batch(torque, top, p, q, r, g1, g2, g3)
        return np.stack(_full_rates(top, e, (p, q, r, w, x, yq, z), M), axis=1)

    te = np.linspace(t0, t1, 101) if t_eval is None else np.asarray(t_eval, dtype=float)
    return integrate_batch(rhs, (t0, t1), y0, t_eval=te, rtol=rtol, atol=atol, args=(E,), time_name="t",
                           fields=lambda t, y: _full_fields(top, E, t, y))


def _body_moments_batch(torque: Torque, top: Top, p: np.ndarray, q: np.ndarray, r: np.ndarray, g1: np.ndarray,
                        g2: np.ndarray, g3: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Body moments of a torque for arrays of members: the torque's own vectorised form where it has one
    (``body_moments_batch``), else member by member."""
    fast = getattr(torque, "body_moments_batch", None)
    if fast is not None:
        return fast(top, p, q, r, g1, g2, g3)
    out = np.array([torque.body_moments(top, *(float(v[i]) for v in (p, q, r, g1, g2, g3))) for i in range(p.size)])
    return out[:, 0], out[:, 1], out[:, 2]
