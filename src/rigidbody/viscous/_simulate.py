"""Full simulation of eq. (1.2), ``(θ·ω)˙ = -B·ω``, with the attitude as a quaternion."""

from __future__ import annotations

import math
from typing import Any, Literal

import numpy as np

from ..core import euler
from ..core.ode import Solution, integrate
from ._model import Body, Medium, check_body_medium
from ._state import initial_state, perpendicular

__all__ = ["axial_rotation", "simulate"]


def _initial_attitude(n0: np.ndarray, ndot0: np.ndarray, v0: float, attitude0: Any) -> np.ndarray:
    if attitude0 is None:
        e1 = ndot0 / v0 if v0 > 0 else perpendicular(n0)
        e2 = np.cross(n0, e1)
        R = np.column_stack([e1, e2, n0])
        return euler.quat_from_dcm(R)
    q = np.asarray(attitude0, dtype=float)
    if q.shape != (4,) or not np.all(np.isfinite(q)):
        raise ValueError("attitude0 must be a finite scalar-first quaternion (w, x, y, z)")
    nq = float(np.linalg.norm(q))
    if abs(nq - 1.0) > 1e-10:
        raise ValueError(f"attitude0 must be a unit quaternion, got norm {nq!r}")
    q = q / nq
    R = euler.dcm_from_quat(q)
    if np.linalg.norm(R[:, 2] - n0) > 1e-10:
        raise ValueError("attitude0 must put the body z axis on n0 (R(attitude0)[:, 2] == n0)")
    return q


def _cartesian_problem(body: Body, medium: Medium, q0: Any, wb0: np.ndarray) -> tuple[list[float], Any, Any, Any, Any]:
    """Euler's equations in body rates (p, q, r) with the quaternion: start, right-hand side and read-outs."""
    t1 = t2 = body.theta12
    t3 = body.theta3
    b1 = b2 = medium.B12
    B3 = medium.B3
    y0 = [*q0, *wb0, 0.0]

    def rhs(t: float, y: np.ndarray) -> list[float]:
        qw, qx, qy, qz, p, q, r, _ = y
        return [
            -0.5 * (qx * p + qy * q + qz * r),
            0.5 * (qw * p + qy * r - qz * q),
            0.5 * (qw * q + qz * p - qx * r),
            0.5 * (qw * r + qx * q - qy * p),
            ((t2 - t3) * q * r - b1 * p) / t1,
            ((t3 - t1) * r * p - b2 * q) / t2,
            ((t1 - t2) * p * q - B3 * r) / t3,
            r,
        ]

    def body_rates(y: np.ndarray) -> np.ndarray:
        return np.array(y[4:7])

    def speed(y: np.ndarray) -> np.ndarray:
        return np.hypot(y[4], y[5])

    def curv(y: np.ndarray) -> np.ndarray | None:
        return None

    return y0, rhs, body_rates, speed, curv


def simulate(
    body: Body,
    medium: Medium,
    n0: Any,
    ndot0: Any,
    Omega0: float,
    t_span: tuple[float, float],
    t_eval: Any = None,
    *,
    attitude0: Any = None,
    formulation: Literal["polar", "cartesian"] = "polar",
    rtol: float = 1e-12,
    atol: float = 1e-14,
    dense_output: bool = False,
) -> Solution:
    """Integrate the full equation of motion (1.2) ``(θ·ω)˙ = -B·ω`` of an axisymmetric body.

    Euler's equations in body axes, ``θ = diag(θ12, θ12, θ3)``, ``B = diag(B12, B12, B3)``, body ``z``
    along the symmetry axis ``n``, with the attitude quaternion ``q̇ = q⊗(0, ω)/2`` (scalar first,
    ``x_ref = R(q) x_body``). None of the closed forms (3.3)-(5.1) is used.

    Parameters
    ----------
    body, medium : Body, Medium
    n0 : array_like, shape (3,)
        Initial unit symmetry axis.
    ndot0 : array_like, shape (3,)
        Initial velocity of the axis tip, perpendicular to ``n0`` (``v0 = |ndot0|``).
    Omega0 : float
        Initial spin ``Ω0 = ω0·n0``. Then ``ω0 = n0×ndot0 + Ω0 n0``.
    t_span : (float, float)
        Integration interval.
    t_eval : array_like, optional
        Output times (default: the solver's steps).
    attitude0 : array_like, shape (4,), optional
        Initial attitude quaternion; its body ``z`` axis must be ``n0``. Default: body ``x`` along
        ``ndot0`` (or any perpendicular if ``v0 = 0``).
    formulation : {'polar', 'cartesian'}
        ``'polar'`` (default) integrates ``p + iq = exp(λ + iμ)`` and ``r = ±exp(ρ)`` — Euler's
        right-hand sides divided by the magnitude — so ``v, Ω, k`` keep their *relative* accuracy over
        any number of e-folding times. ``'cartesian'`` integrates ``(p, q, r)`` (a cross-check).
    rtol, atol : float
        DOP853 tolerances; with the defaults the states agree with the closed forms to ~1e-11.
    dense_output : bool
        Keep the dense interpolant (``sim.sol``) of the raw state.

    Returns
    -------
    Solution
        ``sim.t``; ``sim.n``, ``sim.ndot``, ``sim.omega`` (inertial components), ``sim.omega_body``
        — all shape ``(3, nt)``; ``sim.attitude`` (4, nt) unit quaternions; ``sim.Omega = ω·n``;
        ``sim.v = |ṅ|``; ``sim.k = (θ3/θ12) Ω/v`` (``±inf`` where ``v = 0``; NaN only for a body
        at rest, ``v0 = Ω0 = 0``, whose path has no curvature); ``sim.zeta``, the
        body's turning angle about ``n`` (∫ ω·n dt, the quasi-coordinate ζ); ``sim.quat_norm_error``.

    See Also
    --------
    axis_path : the axis path from the closed forms alone.
    v, curvature, quasi_coordinates : the closed forms the result obeys.
    rigidbody.plotting.plot_axis_path : the standard figure (``sim.plot()``).

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, eqs. (1.1)-(1.2).

    Examples
    --------
    The full equations reproduce the closed forms (3.4), (4.5) and (5.1):

    >>> import numpy as np
    >>> from rigidbody import viscous
    >>> body, medium = viscous.Body(theta12=2.0, theta3=1.0), viscous.Medium(B12=0.4, B3=0.1)
    >>> sim = viscous.simulate(body, medium, [1, 0, 0], [0, 2, 0], 6.0, (0.0, 10.0), t_eval=np.linspace(0, 10, 11))
    >>> np.allclose(sim.v, viscous.v(body, medium, 2.0, sim.t), rtol=1e-10, atol=0)
    True
    >>> np.allclose(sim.k, viscous.curvature(body, medium, 6.0, 2.0, sim.t), rtol=1e-10, atol=0)
    True
    >>> np.allclose(sim.zeta, viscous.quasi_coordinates(body, medium, 6.0, 2.0, sim.t)[2], rtol=0, atol=1e-10)
    True
    """
    check_body_medium(body, medium)
    n, nd, v0, Om0 = initial_state(n0, ndot0, Omega0)
    if formulation not in ("polar", "cartesian"):
        raise ValueError(f"formulation must be 'polar' or 'cartesian', got {formulation!r}")
    q0 = _initial_attitude(n, nd, v0, attitude0)
    R0 = euler.dcm_from_quat(q0)
    omega0 = np.cross(n, nd) + Om0 * n
    wb0 = R0.T @ omega0
    t12, t3 = body.theta12, body.theta3
    B12, B3 = medium.B12, medium.B3
    # Euler's equations written for a general body theta = diag(t1, t2, t3), B = diag(b1, b2, b3)
    t1 = t2 = t12
    b1 = b2 = B12

    if formulation == "polar":
        has_w = v0 > 0.0
        has_r = Om0 != 0.0
        sr = math.copysign(1.0, Om0)
        lam0 = math.log(math.hypot(wb0[0], wb0[1])) if has_w else 0.0
        mu0 = math.atan2(wb0[1], wb0[0]) if has_w else 0.0
        rho0 = math.log(abs(wb0[2])) if has_r else 0.0
        y0 = [*q0, lam0, mu0, rho0, 0.0]

        def rhs(t: float, y: np.ndarray) -> list[float]:
            qw, qx, qy, qz, lam, mu, rho, _ = y
            c, s = math.cos(mu), math.sin(mu)
            E = math.exp(lam) if has_w else 0.0
            r = sr * math.exp(rho) if has_r else 0.0
            p, q = E * c, E * s
            # Euler's equations divided by E = |p + iq|:  dP = pdot/E, dQ = qdot/E
            dP = ((t2 - t3) * s * r - b1 * c) / t1
            dQ = ((t3 - t1) * c * r - b2 * s) / t2
            dlam = c * dP + s * dQ
            dmu = c * dQ - s * dP
            # Euler's third equation divided by r: ((t1 - t2) p q / r - B3)/t3; t1 = t2 for the
            # axisymmetric body, so the first term vanishes identically (and would be 0/0 once r underflows)
            drho = -B3 / t3 if has_r else 0.0
            return [
                -0.5 * (qx * p + qy * q + qz * r),
                0.5 * (qw * p + qy * r - qz * q),
                0.5 * (qw * q + qz * p - qx * r),
                0.5 * (qw * r + qx * q - qy * p),
                dlam if has_w else 0.0,
                dmu if has_w else 0.0,
                drho,
                r,
            ]

        def body_rates(y: np.ndarray) -> np.ndarray:
            E = np.exp(y[4]) if has_w else np.zeros_like(y[4])
            r = sr * np.exp(y[6]) if has_r else np.zeros_like(y[6])
            return np.array([E * np.cos(y[5]), E * np.sin(y[5]), r])

        def speed(y: np.ndarray) -> np.ndarray:
            return np.exp(y[4]) if has_w else np.zeros_like(y[4])

        def curv(y: np.ndarray) -> np.ndarray | None:
            # k = (t3/t12) r/|p + iq| from the logarithms: right even when v and Omega both underflow
            if not (has_w and has_r):
                return None
            with np.errstate(over="ignore"):
                return sr * np.exp(math.log(t3 / t12) + y[6] - y[4])

    else:
        y0, rhs, body_rates, speed, curv = _cartesian_problem(body, medium, q0, wb0)

    def fields(t: np.ndarray, y: np.ndarray) -> dict[str, np.ndarray]:
        q = y[0:4]
        qn = np.linalg.norm(q, axis=0)
        qu = q / qn
        R = euler.dcm_from_quat(qu.T)  # (nt, 3, 3)
        wb = body_rates(y)
        w_ref = np.einsum("tij,jt->it", R, wb)
        n_ref = R[:, :, 2].T
        vv = speed(y)
        Om = wb[2]
        k = curv(y)
        if k is None:
            with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
                k = np.where(vv > 0, t3 / t12 * Om / np.where(vv > 0, vv, 1.0), np.copysign(np.inf, Om))
        if not (v0 > 0 or Om0 != 0):
            k = np.full_like(vv, np.nan)
        return {
            "n": n_ref,
            "ndot": np.cross(w_ref, n_ref, axis=0),
            "omega": w_ref,
            "omega_body": wb,
            "attitude": qu,
            "Omega": Om,
            "v": vv,
            "k": k,
            "zeta": y[7],
            "quat_norm_error": qn - 1.0,
        }

    return integrate(rhs, t_span, y0, t_eval=t_eval, rtol=rtol, atol=atol, method="DOP853",
                     dense_output=dense_output, fields=fields)


def axial_rotation(q1: Any, q2: Any) -> float:
    """Turn of the body about its axis between attitudes ``q1`` and ``q2`` (solid-angle theorem).

    The body ``x`` axis at ``q2`` is carried back to ``n1`` by the shortest rotation taking ``n2`` to
    ``n1`` (i.e. parallel transport along the great-circle arc that closes the path) and its angle
    from the body ``x`` axis at ``q1`` is measured about ``n1`` (right-handed), in ``(-π, π]``.

    Parameters
    ----------
    q1, q2 : array_like, shape (4,)
        Scalar-first unit attitude quaternions (body ``z`` = symmetry axis), e.g. columns of
        ``sim.attitude``; a norm differing from 1 by more than 1e-6 raises ``ValueError``.

    Returns
    -------
    float
        ``Δφ`` modulo ``2π``. Equal to ``χ + Δζ`` (mod 2π) by the solid-angle theorem.

    See Also
    --------
    turn : ``χ`` and ``Δζ`` of one turn of the spiral (see :class:`Turn` for the theorem checked).

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, section 5.

    Examples
    --------
    Two attitudes with the same axis, turned by 0.5 rad about it:

    >>> import math
    >>> from rigidbody import viscous
    >>> q2 = [math.cos(0.25), 0.0, 0.0, math.sin(0.25)]
    >>> print(f"{viscous.axial_rotation([1.0, 0.0, 0.0, 0.0], q2):.12f}")
    0.500000000000
    """
    qs = []
    for name, q in (("q1", q1), ("q2", q2)):
        qa = np.asarray(q, dtype=float)
        if qa.shape != (4,) or not np.all(np.isfinite(qa)):
            raise ValueError(f"{name} must be a finite scalar-first quaternion of shape (4,), got {q!r}")
        nq = float(np.linalg.norm(qa))
        if abs(nq - 1.0) > 1e-6:
            raise ValueError(f"{name} must be a unit quaternion (|{name}| = 1 within 1e-6), got norm {nq!r}")
        qs.append(qa / nq)
    R1 = euler.dcm_from_quat(qs[0])
    R2 = euler.dcm_from_quat(qs[1])
    n1, n2 = R1[:, 2], R2[:, 2]
    e1, e2 = R1[:, 0], R2[:, 0]
    c = float(n2 @ n1)
    if c <= -1.0 + 1e-12:
        raise ValueError("axial_rotation: the two axes are antipodal; the closing great-circle arc is undefined")
    ax = np.cross(n2, n1)
    # Rodrigues for the rotation taking n2 to n1 about ax (|ax| = sin angle), applied to e2
    e2t = e2 * c + np.cross(ax, e2) + ax * (ax @ e2) / (1.0 + c)
    return float(math.atan2(n1 @ np.cross(e1, e2t), e1 @ e2t))
