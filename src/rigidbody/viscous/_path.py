"""The axis path on the unit sphere rebuilt from v(t) and k(t) alone (Darboux frame), and one turn
of the spiral with its solid angle (the solid-angle theorem, section 5)."""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core.ode import Event, integrate
from ._closed import as_scalar, curvature, quasi_coordinates, spiral_radius
from ._model import Body, Medium, check_body_medium
from ._state import initial_state

__all__ = ["Turn", "axis_path", "turn"]


class _Frame:
    """Darboux-frame equations in the compactified time ``u = 1 - exp(-γ t)``.

    ``dn/dt = v τ``, ``dτ/dt = -v n + w g``, ``dg/dt = -w τ`` with ``w = v k = (θ3/θ12) Ω``; only
    ``v`` and ``w`` enter, never ``k`` alone, so ``k → ∞`` is harmless. With ``d/du = d/dt / (γ (1-u))``
    the coefficients are ``cv(u) = (v0/γ) (1-u)^(a/γ - 1)``, ``cw(u) = (w0/γ) (1-u)^(b/γ - 1)``,
    ``a = B12/θ12``, ``b = B3/θ3``, ``γ = min(a, b)`` (``a`` if ``Ω0 = 0``): bounded on ``[0, 1]``.
    """

    def __init__(self, body: Body, medium: Medium, v0: float, Omega0: float) -> None:
        a = medium.B12 / body.theta12
        b = medium.B3 / body.theta3
        self.gamma = min(a, b) if Omega0 != 0.0 else a
        self.cv0 = v0 / self.gamma
        self.cw0 = body.theta3 / body.theta12 * Omega0 / self.gamma
        self.pv = a / self.gamma - 1.0
        self.pw = b / self.gamma - 1.0

    def u_of_t(self, t: np.ndarray) -> np.ndarray:
        return -np.expm1(-self.gamma * t)

    def t_of_u(self, u: float) -> float:
        return math.inf if u >= 1.0 else -math.log1p(-u) / self.gamma

    def coeffs(self, u: float) -> tuple[float, float]:
        x = 1.0 - u
        if x <= 0.0:
            x = 0.0
        cv = self.cv0 * (x**self.pv if self.pv != 0.0 else 1.0)
        # cw0 = 0 (Omega0 = 0, gamma = a) may come with pw < 0: no 0**negative at u = 1
        cw = self.cw0 * (x**self.pw if self.pw != 0.0 else 1.0) if self.cw0 != 0.0 else 0.0
        return cv, cw

    def rhs(self, u: float, y: np.ndarray) -> list[float]:
        n1, n2, n3, t1, t2, t3, g1, g2, g3 = y[:9]
        cv, cw = self.coeffs(u)
        return [
            cv * t1, cv * t2, cv * t3,
            -cv * n1 + cw * g1, -cv * n2 + cw * g2, -cv * n3 + cw * g3,
            -cw * t1, -cw * t2, -cw * t3,
        ]


def _initial_frame(n: np.ndarray, nd: np.ndarray, v0: float) -> np.ndarray:
    tau = nd / v0
    g = np.cross(n, tau)
    return np.concatenate([n, tau, g])


def _times(t_eval: Any) -> np.ndarray:
    t = np.atleast_1d(np.asarray(t_eval, dtype=float))
    if t.ndim != 1 or t.size == 0:
        raise ValueError("t_eval must be a non-empty 1-D array of times")
    if np.any(np.isnan(t)) or np.any(t < 0):
        raise ValueError("t_eval must hold times >= 0 (np.inf allowed: the end of the path)")
    return t


def axis_path(
    body: Body,
    medium: Medium,
    n0: Any,
    ndot0: Any,
    Omega0: float,
    t_eval: Any,
    *,
    rtol: float = 1e-12,
    atol: float = 1e-14,
    frame: bool = False,
) -> Any:
    """Rebuild the path ``n(t)`` of the symmetry axis from ``v(t)`` (3.4) and ``k(t)`` (4.5) alone.

    Integrates the Darboux frame ``(n, τ, g = n×τ)`` of a curve on the unit sphere,
    ``n' = τ, τ' = -n + k g, g' = -k τ`` (``'`` = d/ds, ``k = n·(n'×n'')`` of eq. 4.3), written in time
    with ``ds/dt = v`` and ``v k = (θ3/θ12) Ω``, in the compactified time ``u = 1 - exp(-γt)``,
    ``γ = min(B12/θ12, B3/θ3)``: the right-hand side stays bounded as ``k → ∞`` and ``t → ∞``
    (``u → 1``; the path has the finite length ``s∞``). No dynamics is integrated.

    Parameters
    ----------
    body, medium : Body, Medium
    n0, ndot0, Omega0
        Initial axis, its velocity (⊥ ``n0``) and spin, as in :func:`simulate`; only the initial point
        ``n0``, tangent ``ndot0/|ndot0|``, ``v0 = |ndot0|`` and ``Ω0`` are used.
    t_eval : array_like
        Times ``>= 0`` (any order; ``np.inf`` gives the end point of the path).
    rtol, atol : float
        DOP853 tolerances in ``u``; the defaults give ~1e-12 rad.
    frame : bool
        Also return ``τ`` and ``g``.

    Returns
    -------
    n : ndarray, shape (3, len(t_eval))
        Or ``(n, tau, g)`` if ``frame``. ``v0 = 0``: the axis is fixed, ``n = n0`` (``τ, g`` are NaN).

    See Also
    --------
    simulate : the same path from the full equations of motion.
    turn : one turn of the spiral.
    rigidbody.plotting.sphere_path : draws the path on the unit sphere.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, eqs. (3.4), (4.3)-(4.5).

    Examples
    --------
    Without spin (``Ω0 = 0``, ``k = 0``) the axis runs along a great circle and stops after the arc
    ``s∞ = θ12 v0/B12``, here ``π/2``; half of it is run by ``t = ln 2 θ12/B12``:

    >>> import math
    >>> import numpy as np
    >>> from rigidbody import viscous
    >>> body, medium = viscous.Body(theta12=2.0, theta3=1.0), viscous.Medium(B12=0.4, B3=0.1)
    >>> n = viscous.axis_path(body, medium, [1, 0, 0], [0, 0.1 * math.pi, 0], 0.0, [5 * math.log(2), np.inf])
    >>> print(np.round(n, 8) + 0.0)  # + 0.0: no -0.0
    [[0.70710678 0.        ]
     [0.70710678 1.        ]
     [0.         0.        ]]
    """
    check_body_medium(body, medium)
    n, nd, v0, Om0 = initial_state(n0, ndot0, Omega0)
    t = _times(t_eval)
    if v0 == 0.0:
        nn = np.repeat(n[:, None], t.size, axis=1)
        if frame:
            nan = np.full_like(nn, np.nan)
            return nn, nan, nan.copy()
        return nn
    fr = _Frame(body, medium, v0, Om0)
    us, inverse = np.unique(fr.u_of_t(t), return_inverse=True)  # sorted, without repeats
    y0 = _initial_frame(n, nd, v0)
    if us[-1] > 0.0:
        sol = integrate(fr.rhs, (0.0, float(us[-1])), y0, t_eval=us, rtol=rtol, atol=atol, time_name="u")
        if not sol.success:
            raise RuntimeError(f"axis_path: integration failed: {sol.message}")
        out = sol.y[:, inverse.ravel()]
    else:
        out = np.repeat(y0[:, None], t.size, axis=1)
    if frame:
        return out[0:3], out[3:6], out[6:9]
    return out[0:3]


_R_MIN = 1e-7  # smallest osculating radius (5.2) of a turn that `turn` resolves to ~1e-9 relative


@dataclass(frozen=True)
class Turn:
    """One turn of the spiral and the solid-angle theorem ``Δφ = χ + Δζ`` (section 5).

    Attributes
    ----------
    t1, t2 : float
        Start and end of the turn.
    centre : ndarray (3,)
        The osculating centre ``c1 = sgn(k)(k n + g)/sqrt(1+k²)`` at ``t1`` about which the turn is
        counted.
    chi : float
        Signed solid angle enclosed by the turn closed with the meridian arc through ``c1`` (exact,
        from the path geometry: ``∫ c1·(n×dn)/(1 + c1·n)``); positive counterclockwise seen from outside.
    chi_approx, chi_approx_start, chi_approx_end : float
        The paper's ``sgn(k) 2π(1 - sqrt(1 - R²))`` with ``R`` of (5.2) at mid-turn ``(t1+t2)/2``, at
        ``t1`` and at ``t2``. Relative error: ~``λT`` with ``R`` at the start or end,
        second order in ``T`` at mid-turn (measured ``≈ -(0.14 B12/θ12 + 0.08 B3/θ3) λ T²``),
        ``λ = B12/θ12 - B3/θ3``, ``T = t2 - t1``; exact for the circle.
    R1, R_mid, R2 : float
        Spiral radius (5.2) at ``t1``, ``(t1+t2)/2`` and ``t2``.
    dzeta : float
        ``ζ(t2) - ζ(t1)`` from (5.1).
    dphi : float
        ``χ + Δζ``: the body's axial turn over the turn (not reduced modulo 2π).
    n : ndarray (3, m)
        Samples of the axis path over the turn (for plots).

    See Also
    --------
    turn : the function that returns it.
    rigidbody.plotting.turn_solid_angle : draws it.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, section 5, eq. (5.2).

    Examples
    --------
    The solid-angle theorem ``Δφ = χ + Δζ``: the body's turn about its axis in absolute space, which
    :func:`axial_rotation` measures on the attitudes of the full simulation (modulo 2π):

    >>> import math
    >>> from rigidbody import viscous
    >>> body, medium = viscous.Body(theta12=2.0, theta3=1.0), viscous.Medium(B12=0.4, B3=0.1)
    >>> tr = viscous.turn(body, medium, [1, 0, 0], [0, 2, 0], 6.0)
    >>> sim = viscous.simulate(body, medium, [1, 0, 0], [0, 2, 0], 6.0, (0.0, tr.t2), t_eval=[0.0, tr.t2])
    >>> dphi = viscous.axial_rotation(sim.attitude[:, 0], sim.attitude[:, -1])
    >>> print(f"{dphi:.9f} {math.remainder(tr.chi + tr.dzeta, 2 * math.pi):.9f}")
    -0.906193936 -0.906193936
    """

    t1: float
    t2: float
    centre: np.ndarray
    chi: float
    chi_approx: float
    chi_approx_start: float
    chi_approx_end: float
    R1: float
    R_mid: float
    R2: float
    dzeta: float
    dphi: float
    n: np.ndarray


def turn(
    body: Body,
    medium: Medium,
    n0: Any,
    ndot0: Any,
    Omega0: float,
    t1: float = 0.0,
    *,
    rtol: float = 1e-12,
    atol: float = 1e-14,
    samples: int = 400,
    centre: Any = None,
) -> Turn:
    """One turn of the axis spiral starting at ``t1``, its solid angle and the axial rotation.

    Definition of a turn: the centre is the osculating centre ``c1`` of the path at ``t1``; the turn ends
    at the first ``t2 > t1`` at which the azimuth of ``n`` about ``c1`` has advanced by ``2π`` (sense of
    ``k``), i.e. ``n`` is back on the half great circle from ``c1`` through ``n(t1)``. The loop is
    closed by the arc of that meridian from ``n(t2)`` to ``n(t1)``. Then the solid-angle theorem
    (Zhuravlev) gives the body's axial turn in absolute space ``Δφ = χ + Δζ``; the paper's approximation
    is ``χ ≈ 2π(1 - sqrt(1 - R²))``, ``R`` from (5.2).

    Parameters
    ----------
    body, medium, n0, ndot0, Omega0
        As in :func:`axis_path`.
    t1 : float
        Start of the turn, ``>= 0``.
    rtol, atol : float
        Tolerances of the path integration.
    samples : int
        Number of path samples returned in ``Turn.n``.
    centre : array_like (3,), optional
        Unit vector about which the azimuth is counted (default: the osculating centre at ``t1``). When
        the spiral changes fast (``|λ|T`` not small) the path may never circle the osculating centre;
        the limit point ``axis_path(..., np.inf)`` of a contracting spiral is then a better centre.

    Returns
    -------
    Turn

    Raises
    ------
    ValueError
        If the path has no complete turn after ``t1`` (``Ω0 = 0``, ``v0 = 0``, or the remaining total
        turning of the spiral is too small), or the turn is too small to resolve (``R(t1) < 1e-7``: its
        relative accuracy would be ~``rtol/R``; use the cap formula).

    See Also
    --------
    Turn : the result.
    axis_path : the path itself.
    spiral_radius : the radius (5.2) in the cap formula.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, section 5, eqs. (5.1)-(5.2).

    Examples
    --------
    In Routh's case ``B12/θ12 = B3/θ3`` the path is a small circle of chordal radius ``R = 1/sqrt(1 + k²)``,
    ``k = 1.5``: a turn is the arc ``s = 2πR``, run in ``t2 = -(θ12/B12) ln(1 - 2πR B12/(θ12 v0))``, and its solid
    angle is the cap ``2π(1 - sqrt(1 - R²))`` exactly:

    >>> import math
    >>> from rigidbody import viscous
    >>> body, medium = viscous.Body(theta12=2.0, theta3=1.0), viscous.Medium(B12=0.2, B3=0.1)
    >>> tr = viscous.turn(body, medium, [1, 0, 0], [0, 2, 0], 6.0)
    >>> R = 1 / math.sqrt(1 + 1.5**2)
    >>> print(f"{tr.t2:.9f} {-10 * math.log(1 - 2 * math.pi * R * 0.1 / 2):.9f}")
    1.914804188 1.914804188
    >>> print(f"{tr.chi:.9f} {tr.chi_approx:.9f} {2 * math.pi * (1 - math.sqrt(1 - R**2)):.9f}")
    1.055259123 1.055259123 1.055259123
    """
    check_body_medium(body, medium)
    n, nd, v0, Om0 = initial_state(n0, ndot0, Omega0)
    t1 = as_scalar(t1)
    if isinstance(t1, (bool, np.bool_)) or not isinstance(t1, (numbers.Real, np.floating, np.integer)):
        raise TypeError(f"t1 must be a real number >= 0, got {type(t1).__name__}")
    t1 = float(t1)
    if not (math.isfinite(t1) and t1 >= 0.0):
        raise ValueError(f"t1 must be finite and >= 0, got {t1!r}")
    if isinstance(samples, (bool, np.bool_)) or not isinstance(samples, (numbers.Integral, np.integer)) or samples < 2:
        raise ValueError(f"samples must be an int >= 2, got {samples!r}")
    if v0 == 0.0 or Om0 == 0.0:
        raise ValueError("no turn: the path is a point (v0 = 0) or a great-circle arc (Omega0 = 0)")
    fr = _Frame(body, medium, v0, Om0)
    n1, tau1, g1 = (x[:, 0] for x in axis_path(body, medium, n, nd, Om0, [t1], rtol=rtol, atol=atol, frame=True))
    sg = 1.0 if Om0 > 0 else -1.0
    R1 = float(spiral_radius(body, medium, Om0, v0, t1))
    if R1 < _R_MIN:
        # the turn is integrated in absolute coordinates on the unit sphere: its relative accuracy is
        # ~rtol/R and the cost grows like 1/R (R = 4e-10 took minutes and lost 4 digits)
        raise ValueError(
            f"the turn from t1 = {t1} is too small to resolve on the unit sphere: R = {R1:.3g} < {_R_MIN:g}; its "
            f"solid angle is the cap 2*pi*(1 - sqrt(1 - R^2)) ~ pi R^2 = {math.pi * R1 * R1:.3g} (relative O(lambda T))"
        )
    # c1 = sgn(k)(k n + g)/sqrt(1+k^2) = cos(rho) n + sgn(k) sin(rho) g, sin(rho) = R (5.2): regular as |k| -> inf
    cosr = math.sqrt(1.0 - R1 * R1) if R1 < 0.5 else abs(float(curvature(body, medium, Om0, v0, t1))) * R1
    if centre is None:
        c = cosr * n1 + sg * R1 * g1
    else:
        c = np.asarray(centre, dtype=float)
        if c.shape != (3,) or not np.all(np.isfinite(c)) or abs(np.linalg.norm(c) - 1.0) > 1e-10:
            raise ValueError("centre must be a finite unit 3-vector")
        if abs(float(c @ n1)) > 1.0 - 1e-12:
            raise ValueError("centre must differ from +-n(t1)")
    c = c / np.linalg.norm(c)
    c1, c2, c3 = c

    def rhs(u: float, y: np.ndarray) -> list[float]:
        d = fr.rhs(u, y)
        n_1, n_2, n_3 = y[0], y[1], y[2]
        dn1, dn2, dn3 = d[0], d[1], d[2]
        cn = c1 * n_1 + c2 * n_2 + c3 * n_3
        # c·(n×dn)
        cx = c1 * (n_2 * dn3 - n_3 * dn2) + c2 * (n_3 * dn1 - n_1 * dn3) + c3 * (n_1 * dn2 - n_2 * dn1)
        # sin^2 of the distance from the centre as |c×n|^2: no cancellation near the centre (1 - cn^2 has)
        s2 = (c2 * n_3 - c3 * n_2) ** 2 + (c3 * n_1 - c1 * n_3) ** 2 + (c1 * n_2 - c2 * n_1) ** 2
        dalpha = cx / s2
        dchi = cx / (1.0 + cn)
        return [*d, dalpha, dchi]

    ev = Event(lambda u, y: y[9] - sg * 2.0 * math.pi, "turn_end", terminal=True,
               message="the azimuth about the centre advanced by 2*pi")
    def near_centre(u: float, y: np.ndarray) -> float:
        # |c×n|^2 - 1e-12: the axis within 1e-6 rad of the centre (azimuth undefined) or of its antipode
        return (c2 * y[2] - c3 * y[1]) ** 2 + (c3 * y[0] - c1 * y[2]) ** 2 + (c1 * y[1] - c2 * y[0]) ** 2 - 1e-12

    centre_ev = Event(near_centre, "through_centre", terminal=True,
                      message="the path reaches the centre (or its antipode): the azimuth about it is undefined")
    u1 = float(fr.u_of_t(np.asarray(t1)))
    y0 = [*n1, *tau1, *g1, 0.0, 0.0]
    sol = integrate(rhs, (u1, 1.0), y0, rtol=rtol, atol=atol, events=[ev, centre_ev], dense_output=True,
                    time_name="u")
    if sol.event == "through_centre" or not sol.success:
        raise ValueError(f"turn from t1 = {t1} is undefined: {sol.message}")
    if sol.event != "turn_end":
        raise ValueError(
            f"no complete turn of the spiral after t1 = {t1}: the azimuth of n about the centre only reaches "
            f"{sol.y[9, -1]:.6g} rad (the remaining total turning is too small, or the spiral changes too fast to "
            "circle the osculating centre: try centre=axis_path(..., np.inf) for a contracting spiral)"
        )
    u2 = float(sol.t_events["turn_end"][0])
    y2 = sol.y_events["turn_end"][0]
    t2 = fr.t_of_u(u2)
    chi = float(y2[10])
    R2 = float(spiral_radius(body, medium, Om0, v0, t2))
    Rm = float(spiral_radius(body, medium, Om0, v0, 0.5 * (t1 + t2)))

    def cap(R: float) -> float:
        # 1 - sqrt(1 - R^2) written without cancellation (tiny turns: R^2 below the rounding of 1)
        return sg * 2.0 * math.pi * R * R / (1.0 + math.sqrt(max(0.0, 1.0 - R * R)))

    z = quasi_coordinates(body, medium, Om0, v0, np.array([t1, t2]))[2]
    dzeta = float(z[1] - z[0])
    us = np.linspace(u1, u2, samples)
    nn = sol.sol(us)[0:3]
    return Turn(
        t1=t1, t2=t2, centre=c, chi=chi,
        chi_approx=cap(Rm), chi_approx_start=cap(R1), chi_approx_end=cap(R2),
        R1=R1, R_mid=Rm, R2=R2, dzeta=dzeta, dphi=chi + dzeta, n=nn,
    )
