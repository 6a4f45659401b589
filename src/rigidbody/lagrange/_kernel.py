r"""Right-hand sides of the averaged system in coordinates whose error the integrator can control.

The averaged Lagrange top decays towards the hanging equilibrium: ``r``, ``Gz`` and the root gaps
``1 + u1``, ``1 + u2``, ``u3 - 1`` shrink by many orders while ``u1, u2 -> -1``. In the paper's variables
``(u1, u2, u3)`` (or in ``(Gz, H, r)``) a tolerance then controls only an absolute error: the small
quantities, and ``Gz``, ``r`` computed from the roots through (2.8), lose their relative accuracy. The
integrations therefore run in

* the **u chart** as ``(atanh u1, atanh u2, q)``: the two lower roots through their distances to the
  ends of ``[-1, 1]``, ``1 + u = 2/(1 + e^{-2x})``, ``1 - u = 2/(1 + e^{2x})``, so an absolute error in
  ``x`` is a relative error in either gap, and ``u3`` through ``q = tan(theta/2)``,
  ``theta = atan2(|Gz - C r|, |Gz + C r|)`` in ``[0, pi/2]``, which fixes ``u3 - 1`` relative to the lower gaps
  and passes smoothly through the branch point ``u3 = 1`` (where ``u3 - 1`` vanishes quadratically, a log
  coordinate would be singular); ``sin theta``, ``cos theta`` are rational in ``q``;
* the **GHr chart** as ``(ln S, psi, kappa)`` with ``Gz = S cos(pi psi)``, ``C r = S sin(pi psi)`` and
  ``kappa = K/S``, ``K = H + mgl - C r^2/2`` (the energy above the lowest state of the given spin, >= 0): the
  magnitude of ``(Gz, C r)`` on a log scale, its direction, and the energy in units of it; the branch points of
  (2.8) are ``psi`` = multiples of 1/4 (``r = 0`` or ``Gz^2 = C^2 r^2``), crossed smoothly.

The map (2.8) from the roots to ``(Gz, H, r)`` is evaluated without cancellation through the two products
``Pi+ = (1+u1)(1+u2)(1+u3) = (Gz + C r)^2/(2 A mgl)`` and ``Pi- = (1-u1)(1-u2)(u3-1) = (Gz - C r)^2/(2 A mgl)``
(the values ``-P(-1)``, ``-P(1)`` of the monic cubic (1.5); derived here from (1.6)), and the factor
``1/(1 - u_i^2)`` of the chart is cancelled analytically in ``V`` of (2.13).

Every function takes a namespace ``xp`` first: :data:`rigidbody.core.kernel.SCALAR` (``math``, for one run: a few
microseconds a call) or :data:`rigidbody.core.kernel.ARRAY` (NumPy, for a batch, elementwise over members), so one
formula serves both; ``<sn^2>`` comes from :func:`rigidbody.core.kernel.sn2_excess`.
"""

from __future__ import annotations

import math
from typing import Any

from ..core.kernel import ARRAY, SCALAR, sn2_excess

__all__ = ["ARRAY", "SCALAR", "cubic_spread", "double_root", "sn2_excess"]

_SQRT2 = math.sqrt(2.0)


# ---------------------------------------------------------------------------------------------------
# elementary pieces
# ---------------------------------------------------------------------------------------------------
def cubic_spread(xp: Any, s1: Any, s2: Any) -> Any:
    r"""The spread ``sqrt(s1^2 - 3 s2) = sqrt(((u1-u2)^2 + (u1-u3)^2 + (u2-u3)^2)/2)`` of the roots of (1.5) from
    their symmetric functions (1.6) (0 where the radicand is negative: one real root)."""
    return xp.sqrt(xp.maximum(s1 * s1 - 3.0 * s2, 0.0))


def double_root(s1: Any, spread: Any) -> Any:
    r"""The local maximum ``(s1 - sqrt(s1^2 - 3 s2))/3`` of the monic cubic (1.5), ``spread`` from
    :func:`cubic_spread`: the double root ``u1 = u2`` of a regular precession (Vieta's formulas (1.6))."""
    return (s1 - spread) / 3.0


def sincospi(xp: Any, x: Any) -> tuple[Any, Any]:
    """``(sin(pi x), cos(pi x))``, exact zeros at the multiples of 1/2 (``r = 0`` stays exactly 0)."""
    n = xp.rint(2.0 * x)
    f = math.pi * (x - 0.5 * n)
    s, c = xp.sin(f), xp.cos(f)
    k = n % 4
    sin_ = xp.where(k == 0, s, xp.where(k == 1, c, xp.where(k == 2, -s, -c)))
    cos_ = xp.where(k == 0, c, xp.where(k == 1, -s, xp.where(k == 2, -c, s)))
    return sin_, cos_


# ---------------------------------------------------------------------------------------------------
# the u chart
# ---------------------------------------------------------------------------------------------------
def _side(xp: Any, x: Any) -> tuple[Any, Any, Any, Any]:
    """``u = tanh x``, its gaps ``1 + u = 2/(1 + E)``, ``1 - u = 2E/(1 + E)`` and ``E = e^{-2x}`` (the gaps to a
    few ulp; ``u`` itself only absolutely near 0, where that is all it needs)."""
    E = xp.exp(-2.0 * x)
    w = 2.0 / (1.0 + E)
    return 0.5 * w * (1.0 - E), w, w * E, E


def _trig_q(q: Any) -> tuple[Any, Any]:
    """``(sin theta, cos theta)`` of ``q = tan(theta/2)``."""
    t = 1.0 / (1.0 + q * q)
    return 2.0 * q * t, (1.0 - q) * (1.0 + q) * t


def _gap3(w1: Any, z1: Any, w2: Any, z2: Any, q: Any) -> Any:
    """``u3 - 1 = 2 T w1 w2/(z1 z2 - T w1 w2)``, ``T = tan^2 theta = 4 q^2/(1 - q^2)^2`` (from ``Pi-/Pi+``)."""
    q2 = q * q
    ww = 4.0 * q2 * w1 * w2
    return 2.0 * ww / (z1 * z2 * (1.0 - q2) ** 2 - ww)


def _d21(xp: Any, x1: Any, x2: Any, w1: Any, w2: Any, E2: Any) -> Any:
    """``u2 - u1 = tanh x2 - tanh x1 = (1+u1)(1+u2) e^{-2 x2} (e^{2(x2 - x1)} - 1)/2``, exact for nearly equal
    roots."""
    return 0.5 * w1 * w2 * E2 * xp.expm1(2.0 * (x2 - x1))


def gaps_to_x(xp: Any, w1: Any, z1: Any, w2: Any, z2: Any) -> tuple[Any, Any]:
    """``atanh u`` of the two lower roots from their gaps ``1 + u_i``, ``1 - u_i``."""
    return 0.5 * xp.log(w1 / z1), 0.5 * xp.log(w2 / z2)


class UState:
    """Everything the u-chart right-hand sides need at one state (attributes; scalars or arrays)."""

    __slots__ = ("Cr", "Gz", "H", "K", "Sm", "Sp", "c", "cth", "d1", "d21", "d31", "d32", "gm", "gp", "k2", "mc",
                 "pim", "pip", "q", "r", "sth", "u1", "u2", "u3", "w1", "w2", "z1", "z2")

    Cr: Any
    Gz: Any
    H: Any
    K: Any
    Sm: Any
    Sp: Any
    c: Any
    cth: Any
    d1: Any
    d21: Any
    d31: Any
    d32: Any
    gm: Any
    gp: Any
    k2: Any
    mc: Any
    pim: Any
    pip: Any
    q: Any
    r: Any
    sth: Any
    u1: Any
    u2: Any
    u3: Any
    w1: Any
    w2: Any
    z1: Any
    z2: Any


def decode_u(xp: Any, A: float, C: float, mgl: float, x1: Any, x2: Any, q: Any, d1: Any, d2: Any) -> UState:
    """Roots, gaps and (Gz, H, r) by (2.8) at the u-chart point ``(x1, x2, q)`` with signs ``delta1, delta2``.

    ``tan^2 theta = Pi-/Pi+ = (1-u1)(1-u2)(u3-1)/((1+u1)(1+u2)(1+u3))`` gives
    ``u3 - 1 = 2 T w1 w2/(z1 z2 - T w1 w2)`` (``T = tan^2 theta``, ``w = 1 + u``, ``z = 1 - u``).
    """
    s = UState()
    u1, w1, z1, _ = _side(xp, x1)
    u2, w2, z2, E2 = _side(xp, x2)
    sn, cs = _trig_q(q)
    c = _gap3(w1, z1, w2, z2, q)
    s.sth, s.cth, s.q = sn, cs, q
    s.u1, s.w1, s.z1, s.u2, s.w2, s.z2, s.c, s.u3 = u1, w1, z1, u2, w2, z2, c, 1.0 + c
    s.d21 = _d21(xp, x1, x2, w1, w2, E2)
    s.d32 = c + z2
    s.d31 = c + z1
    s.k2 = s.d21 / s.d31
    s.mc = s.d32 / s.d31
    pip = w1 * w2 * (2.0 + c)
    pim = z1 * z2 * c
    s.pip, s.pim = pip, pim
    amg2 = 2.0 * A * mgl
    Sp = xp.sqrt(amg2 * pip)  # |Gz + C r|
    # |Gz - C r| = Sp tan(theta), signed with q: the chart continues smoothly through the branch point q = 0
    # (where Gz - C r changes sign and delta1 flips), so that a step reaching past it stays accurate up to it
    Sm = Sp * 2.0 * q / ((1.0 - q) * (1.0 + q))
    s.Sp, s.Sm = Sp, Sm
    # the signs of Gz +- C r by (2.8): delta1 = -1: (delta2, -delta2); delta1 = +1: both sign(Gz) =
    # delta2 sign(1 + s2), 1 + s2 = (Pi+ - Pi-)/2
    sgp = xp.where(d1 < 0.0, d2, xp.where(pip >= pim, d2, -d2))
    s.gp = sgp * Sp  # Gz + C r
    s.gm = (sgp * d1) * Sm  # Gz - C r
    s.d1 = d1
    Gz = 0.5 * (s.gp + s.gm)
    Cr = 0.5 * (s.gp - s.gm)
    s.Gz, s.Cr, s.r = Gz, Cr, Cr / C
    # K = H + mgl - C r^2/2 = mgl (u1 + u2 + u3 + 1) - C^2 r^2/(2A)  (from s1 of (1.6))
    s.K = mgl * (w1 + w2 + c) - Cr * Cr / (2.0 * A)
    s.H = s.K - mgl + Cr * Cr / (2.0 * C)
    return s


def drag_means(xp: Any, A: float, C: float, mgl: float, a: float, b: float, s: UState) -> tuple[Any, Any, Any]:
    r"""The averaged (2.7) for linear drag (3.1), ``<F> = F(v)``, ``v = <u>`` (F is linear in ``u``).

    ``v = u1 + (u2 - u1) <sn^2>``; ``F1 = -a (Gz - C r v)/A - b r v``, ``F2 = -2a (K - mgl (1 + v))/A - b r^2``
    with ``K - mgl(1 + v) = <A (p^2 + q^2)/2> >= 0``, ``F3 = -b r/C`` ((3.1) in (2.3), (2.7)).
    """
    sx = sn2_excess(xp, s.k2, s.mc)
    lo = s.d21 * (0.5 + sx)  # v - u1
    hi = s.d21 * (0.5 - sx)  # u2 - v
    v = s.u1 + lo
    onepv = s.w1 + lo  # 1 + v
    onemv = s.z2 + hi  # 1 - v
    gv = 0.5 * (s.gp * onemv + s.gm * onepv)  # Gz - C r v, exact at v = -1 and v = +1
    kin = mgl * (s.w1 + s.c + hi) - s.Cr * s.Cr / (2.0 * A)  # K - mgl (1 + v)
    r = s.r
    F1 = -a * gv / A - b * r * v
    F2 = -2.0 * a * kin / A - b * r * r
    F3 = -b * r / C
    return F1, F2, F3


def u_chart_rates(
    xp: Any, A: float, C: float, mgl: float, s: UState, F1: Any, F2: Any, F3: Any
) -> tuple[Any, Any, Any]:
    r"""``dx/dtau`` of the u chart from the averaged slow rates ``<F>``: ``u_i' = sum_j V_ij <F_j>`` (2.12)-(2.13).

    ``V_i1 = N1_i/(A mgl D_i)``, ``V_i2 = (u_i^2 - 1)/(mgl D_i)``, ``V_i3 = C N3_i/(mgl D_i)`` with
    ``N1_i = Gz - C r u_i``, ``N3_i = (C/A - 1) r u_i^2 - Gz u_i/A + r``, ``D_i = (u_i - u_j)(u_i - u_k)``;
    ``N1, N3`` are written through their values at ``u = -1`` and ``u = +1`` (``Gz + C r`` and ``Gz - C r``,
    small near the ends where the chart divides by ``1 - u^2``), and the factor ``u_i^2 - 1`` of ``V_i2``
    cancels the chart's ``1/(1 - u_i^2)``.
    """
    # N1 = Gz - C r u = ((Gz + C r)(1 - u) + (Gz - C r)(1 + u))/2 and N3, the quadratic through its values
    # (Gz + C r)/A at u = -1 and -(Gz - C r)/A at u = +1: N3 = ((Gz + C r)(1 - u) - (Gz - C r)(1 + u))/(2A)
    # - (C/A - 1) r (1 + u)(1 - u); both exact at either end of the range of u
    kr = (C / A - 1.0) * s.r
    gp, gm = s.gp, s.gm
    iA = 1.0 / A
    CF3 = C * F3
    out = []
    for w, z in ((s.w1, s.z1), (s.w2, s.z2)):
        N1 = 0.5 * (gp * z + gm * w)
        N3 = (0.5 * iA) * (gp * z - gm * w) - kr * w * z
        out.append((N1 * F1 * iA + N3 * CF3) / (w * z))
    dx1 = (out[0] - F2) / (mgl * s.d21 * s.d31)
    dx2 = (out[1] - F2) / (-mgl * s.d21 * s.d32)
    # tan(theta) = Sm/Sp with Gz + C r = sgp Sp, Gz - C r = sgp delta1 Sm: d Sp = sgp (F1 + C F3),
    # d Sm = sgp delta1 (F1 - C F3); dq = (1 + q^2) dtheta/2
    sgp = xp.copysign(1.0, gp)
    dth = sgp * (s.Sp * s.d1 * (F1 - CF3) - s.Sm * (F1 + CF3)) / (s.Sp * s.Sp + s.Sm * s.Sm)
    return dx1, dx2, 0.5 * (1.0 + s.q * s.q) * dth


# ---------------------------------------------------------------------------------------------------
# the GHr chart (log-polar in the (Gz, C r) plane)
# ---------------------------------------------------------------------------------------------------
class GState:
    """Slow variables and roots at a GHr-chart point (attributes; scalars or arrays)."""

    __slots__ = ("Cr", "Gz", "H", "K", "S", "cs", "d21", "gm", "gp", "half", "inside", "k2", "mc", "msum", "ok", "r",
                 "s1", "s2", "s3", "sn", "spread", "u1", "u2", "u3")

    Cr: Any
    Gz: Any
    H: Any
    K: Any
    S: Any
    cs: Any
    d21: Any
    gm: Any
    gp: Any
    half: Any
    inside: Any
    k2: Any
    mc: Any
    msum: Any
    ok: Any
    r: Any
    s1: Any
    s2: Any
    s3: Any
    sn: Any
    spread: Any
    u1: Any
    u2: Any
    u3: Any


def decode_g(xp: Any, A: float, C: float, mgl: float, sigma: Any, psi: Any, kap: Any) -> GState:
    """(Gz, H, r) and the roots of (1.5) at ``(ln S, psi, kappa)``, ``kappa = K/S``, ``K = H + mgl - C r^2/2``.

    The largest root ``u3`` (simple) by two Newton steps from the trigonometric formula; ``u1 + u2`` and
    ``u1 u2`` by (1.6). A point a hair outside the admissible set next to a regular precession (Runge-Kutta
    stages along a boundary solution) gets the double root at the local maximum of the cubic, ``u1 = u2``
    (``ok`` is False where the cubic has a single real root).
    """
    g = GState()
    S = xp.exp(sigma)
    sn, cs = sincospi(xp, psi)
    sq, cq = sincospi(xp, psi + 0.25)
    g.S, g.sn, g.cs = S, sn, cs
    Gz = S * cs
    Cr = S * sn
    K = kap * S
    H = K - mgl + Cr * Cr / (2.0 * C)
    g.Gz, g.Cr, g.r, g.H, g.K = Gz, Cr, Cr / C, H, K
    g.gp = _SQRT2 * S * sq  # Gz + C r
    g.gm = _SQRT2 * S * cq  # Gz - C r
    amg = A * mgl
    s1 = K / mgl - 1.0 + Cr * Cr / (2.0 * amg)
    s2 = Gz * Cr / amg - 1.0
    s3 = (g.gp * g.gp + g.gm * g.gm) / (4.0 * amg) - s1
    g.s1, g.s2, g.s3 = s1, s2, s3
    disc = s1 * s1 - 3.0 * s2
    g.ok = disc >= 0.0
    sqd = cubic_spread(xp, s1, s2)
    g.spread = sqd
    # depressed cubic t^3 + p t + q, u = t + s1/3; its largest root 2 sqrt(-p/3) cos(acos(...)/3)
    p = -disc / 3.0
    q = -2.0 * s1 * s1 * s1 / 27.0 + s1 * s2 / 3.0 - s3
    m = 2.0 * sqd / 3.0  # = 2 sqrt(-p/3)
    arg = xp.where(m > 0.0, 3.0 * q / (p * m + (m == 0.0)), 0.0)
    u3 = m * xp.cos(xp.acos(xp.clip(arg, -1.0, 1.0)) / 3.0) + s1 / 3.0
    for _ in range(2):
        f = ((u3 - s1) * u3 + s2) * u3 - s3
        d = (3.0 * u3 - 2.0 * s1) * u3 + s2
        u3 = xp.where(d != 0.0, u3 - f / xp.where(d != 0.0, d, 1.0), u3)
    u3 = xp.maximum(u3, 1.0)
    msum = 0.5 * (s1 - u3)  # (u1 + u2)/2
    h2 = msum * msum - s3 / u3  # ((u2 - u1)/2)^2
    c_lo = double_root(s1, sqd)  # local maximum of the cubic: the double root of a regular precession
    inside = h2 > 0.0
    half = xp.sqrt(xp.maximum(h2, 0.0))
    g.msum = xp.where(inside, msum, c_lo)
    g.half = half
    g.inside = inside
    u1 = g.msum - half
    u2 = g.msum + half
    g.u1 = xp.clip(u1, -1.0, 1.0)
    g.u2 = xp.clip(u2, -1.0, 1.0)
    g.u3 = u3
    d31 = u3 - g.u1
    g.d21 = g.u2 - g.u1
    g.k2 = g.d21 / xp.where(d31 > 0.0, d31, 1.0)
    g.mc = (u3 - g.u2) / xp.where(d31 > 0.0, d31, 1.0)
    return g


def drag_means_g(xp: Any, A: float, C: float, mgl: float, a: float, b: float, g: GState) -> tuple[Any, Any, Any]:
    """:func:`drag_means` at a GHr-chart point: ``v = (u1 + u2)/2 + (u2 - u1)(<sn^2> - 1/2)``, smooth at a
    double root (the ``sqrt(eps)`` rounding of ``u2 - u1`` there is multiplied by ``k^2/16``)."""
    sx = sn2_excess(xp, g.k2, xp.maximum(g.mc, 1e-300))
    v = g.msum + 2.0 * g.half * sx  # not clipped to [-1, 1]: smooth across a pole (rounding only)
    r = g.r
    F1 = -a * (g.Gz - g.Cr * v) / A - b * r * v
    F2 = -a * (2.0 * (g.H - mgl * v) - g.Cr * r) / A - b * r * r
    F3 = -b * r / C
    return F1, F2, F3


def g_chart_rates(xp: Any, C: float, g: GState, F1: Any, F2: Any, F3: Any) -> tuple[Any, Any, Any]:
    """``d(ln S, psi, kappa)/dtau`` from ``<F>``: ``S^2 = Gz^2 + C^2 r^2``, ``pi psi = atan2(C r, Gz)``,
    ``kappa = K/S`` with ``K' = H' - C r r' = F2 - C r F3``."""
    CF3 = C * F3
    dsig = (g.cs * F1 + g.sn * CF3) / g.S
    dpsi = (g.cs * CF3 - g.sn * F1) / (math.pi * g.S)
    dkap = (F2 - g.Cr * F3) / g.S - (g.K / g.S) * dsig
    return dsig, dpsi, dkap


def slow_to_polar(xp: Any, C: float, Gz: Any, H: Any, r: Any, mgl: float) -> tuple[Any, Any, Any]:
    """``(ln S, psi, kappa)`` of ``(Gz, H, r)`` (``S > 0``)."""
    Cr = C * r
    S = xp.sqrt(Gz * Gz + Cr * Cr)
    return xp.log(S), xp.atan2(Cr, Gz) / math.pi, (H + mgl - Cr * Cr / (2.0 * C)) / S


# ---------------------------------------------------------------------------------------------------
# the u chart under linear drag in one function (the hot path of single runs and batches)
# ---------------------------------------------------------------------------------------------------
def drag_constants(A: float, C: float, mgl: float, a: float, b: float) -> tuple[float, ...]:
    """The parameter combinations :func:`u_drag_rates` uses, computed once per run."""
    return (2.0 * A * mgl, 1.0 / A, 1.0 / C, 0.5 / A, C / A - 1.0, a / A, b / C, 2.0 * a / A, mgl, b)


def u_drag_rates(xp: Any, k: tuple[float, ...], x1: Any, x2: Any, q: Any, d1: Any, d2: Any) -> tuple[Any, Any, Any]:
    """``d(x1, x2, theta)/dtau`` of the u chart under linear drag: :func:`decode_u`, :func:`drag_means` and
    :func:`u_chart_rates` in one pass, computing only what the rates need (tests compare the two routes).

    ``k`` is :func:`drag_constants`; works on floats (``xp = SCALAR``) and on arrays of members (``ARRAY``).
    """
    amg2, iA, iC, i2A, kA, aA, bC, two_a_A, mgl, b = k
    E1 = xp.exp(-2.0 * x1)
    E2 = xp.exp(-2.0 * x2)
    w1 = 2.0 / (1.0 + E1)
    w2 = 2.0 / (1.0 + E2)
    z1 = w1 * E1
    z2 = w2 * E2
    c = _gap3(w1, z1, w2, z2, q)
    d21 = _d21(xp, x1, x2, w1, w2, E2)
    d32 = c + z2
    d31 = c + z1
    pip = w1 * w2 * (2.0 + c)
    pim = z1 * z2 * c
    Sp = xp.sqrt(amg2 * pip)
    Sm = Sp * 2.0 * q / ((1.0 - q) * (1.0 + q))  # |Gz - C r|, signed with q (see decode_u)
    sgp = xp.where((d1 < 0.0) | (pip >= pim), d2, -d2)
    gp = sgp * Sp
    gm = sgp * d1 * Sm
    Cr = 0.5 * (gp - gm)
    r = Cr * iC
    sx = sn2_excess(xp, d21 / d31, d32 / d31)
    lo = d21 * (0.5 + sx)
    hi = d21 * (0.5 - sx)
    v = 0.5 * w1 * (1.0 - E1) + lo
    brv = b * r
    F1 = -aA * 0.5 * (gp * (z2 + hi) + gm * (w1 + lo)) - brv * v
    F2 = -two_a_A * (mgl * (w1 + c + hi) - Cr * Cr * i2A) - brv * r
    CF3 = -bC * Cr
    kr = kA * r
    F1A = F1 * iA
    P1 = (0.5 * (gp * z1 + gm * w1) * F1A + (i2A * (gp * z1 - gm * w1) - kr * w1 * z1) * CF3) / (w1 * z1)
    P2 = (0.5 * (gp * z2 + gm * w2) * F1A + (i2A * (gp * z2 - gm * w2) - kr * w2 * z2) * CF3) / (w2 * z2)
    dth = sgp * (Sp * d1 * (F1 - CF3) - Sm * (F1 + CF3)) / (Sp * Sp + Sm * Sm)
    md = mgl * d21
    return (P1 - F2) / (md * d31), (F2 - P2) / (md * d32), 0.5 * (1.0 + q * q) * dth


def u_event_values(xp: Any, x1: Any, x2: Any, q: Any, d1: Any) -> tuple[Any, Any, Any]:
    """``(k^2, mc, min(b1, b2))`` at a u-chart point: the modulus (1.4), its complement and the distance from
    the branch points of (2.8), ``b1 = |Gz^2 - C^2 r^2|/(Gz^2 + C^2 r^2) = sin 2 theta`` and
    ``b2 = C^2 r^2/(Gz^2 + C^2 r^2) = (1 - delta1 sin 2 theta)/2`` (from ``tan theta = |Gz - C r|/|Gz + C r|``)."""
    _, w1, z1, _ = _side(xp, x1)
    _, w2, z2, E2 = _side(xp, x2)
    c = _gap3(w1, z1, w2, z2, q)
    d31 = c + z1
    q2 = q * q
    b1 = 4.0 * q * (1.0 - q2) / (1.0 + q2) ** 2  # sin 2 theta
    return _d21(xp, x1, x2, w1, w2, E2) / d31, (c + z2) / d31, xp.minimum(b1, 0.5 * (1.0 - d1 * b1))
