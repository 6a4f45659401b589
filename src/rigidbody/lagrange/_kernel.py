r"""Right-hand sides of the averaged system in coordinates whose error the integrator can control.

The averaged Lagrange top decays towards the hanging equilibrium: ``r``, ``Gz`` and the root gaps
``1 + u1``, ``1 + u2``, ``u3 - 1`` shrink by many orders while ``u1, u2 -> -1``. In the paper's variables
``(u1, u2, u3)`` (or in ``(Gz, H, r)``) a tolerance then controls only an absolute error: the small
quantities, and ``Gz``, ``r`` computed from the roots through (2.8), lose their relative accuracy. The
integrations therefore run in

* the **u chart** as ``(atanh u1, atanh u2, theta)``: the two lower roots through their distances to the
  ends of ``[-1, 1]``, ``1 + u = 2/(1 + e^{-2x})``, ``1 - u = 2/(1 + e^{2x})``, so an absolute error in
  ``x`` is a relative error in either gap, and ``u3`` through ``theta = atan2(|Gz - C r|, |Gz + C r|)``, which
  fixes ``u3 - 1`` relative to the lower gaps and passes smoothly through the branch point ``u3 = 1``
  (where ``u3 - 1`` vanishes quadratically, a log coordinate would be singular);
* the **GHr chart** as ``(ln S, psi, H)`` with ``Gz = S cos(pi psi)``, ``C r = S sin(pi psi)``: the
  magnitude of ``(Gz, C r)`` on a log scale and its direction; the branch points of (2.8) are
  ``psi`` = multiples of 1/4 (``r = 0`` or ``Gz^2 = C^2 r^2``), crossed smoothly.

The map (2.8) from the roots to ``(Gz, H, r)`` is evaluated without cancellation through the two products
``Pi+ = (1+u1)(1+u2)(1+u3) = (Gz + C r)^2/(2 A mgl)`` and ``Pi- = (1-u1)(1-u2)(u3-1) = (Gz - C r)^2/(2 A mgl)``
(the values ``-P(-1)``, ``-P(1)`` of the monic cubic (1.5); derived here from (1.6)), and the factor
``1/(1 - u_i^2)`` of the chart is cancelled analytically in ``V`` of (2.13).

Every function takes a namespace ``xp`` first: :data:`SCALAR` (``math``, for one run: a few microseconds a
call) or :data:`ARRAY` (NumPy, for a batch, elementwise over members), so one formula serves both.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

__all__ = ["ARRAY", "SCALAR"]

_SQRT2 = math.sqrt(2.0)


class _Scalar:
    """``math`` functions under the names the kernels use (callers turn ``ZeroDivisionError``,
    ``OverflowError`` and ``ValueError`` of a state outside the functions' domain into NaN)."""

    sqrt = staticmethod(math.sqrt)
    exp = staticmethod(math.exp)
    log = staticmethod(math.log)
    sinh = staticmethod(math.sinh)
    sin = staticmethod(math.sin)
    cos = staticmethod(math.cos)
    acos = staticmethod(math.acos)
    abs = staticmethod(abs)
    minimum = staticmethod(min)
    maximum = staticmethod(max)
    nan = math.nan
    array = False

    @staticmethod
    def where(c: Any, a: Any, b: Any) -> Any:
        return a if c else b

    @staticmethod
    def any(c: Any) -> bool:
        return bool(c)

    @staticmethod
    def rint(x: float) -> float:
        return float(round(x)) if math.isfinite(x) else x

    @staticmethod
    def clip(x: float, lo: float, hi: float) -> float:
        return lo if x < lo else hi if x > hi else x


class _Array:
    """NumPy ufuncs under the same names (elementwise over batch members)."""

    sqrt = staticmethod(np.sqrt)
    exp = staticmethod(np.exp)
    log = staticmethod(np.log)
    sinh = staticmethod(np.sinh)
    sin = staticmethod(np.sin)
    cos = staticmethod(np.cos)
    acos = staticmethod(np.arccos)
    abs = staticmethod(np.abs)
    minimum = staticmethod(np.minimum)
    maximum = staticmethod(np.maximum)
    where = staticmethod(np.where)
    any = staticmethod(np.any)
    rint = staticmethod(np.rint)
    clip = staticmethod(np.clip)
    nan = np.nan
    array = True


SCALAR = _Scalar()
ARRAY = _Array()


# ---------------------------------------------------------------------------------------------------
# elementary pieces
# ---------------------------------------------------------------------------------------------------
def sincospi(xp: Any, x: Any) -> tuple[Any, Any]:
    """``(sin(pi x), cos(pi x))``, exact zeros at the multiples of 1/2 (``r = 0`` stays exactly 0)."""
    n = xp.rint(2.0 * x)
    f = math.pi * (x - 0.5 * n)
    s, c = xp.sin(f), xp.cos(f)
    k = n % 4
    sin_ = xp.where(k == 0, s, xp.where(k == 1, c, xp.where(k == 2, -s, -c)))
    cos_ = xp.where(k == 0, c, xp.where(k == 1, -s, xp.where(k == 2, -c, s)))
    return sin_, cos_


def sn2_excess(xp: Any, k2: Any, mc: Any) -> Any:
    r"""``<sn^2> - 1/2`` over a period, ``(1 - E/K)/k^2 - 1/2``, without cancellation for small ``k``.

    By the arithmetic-geometric mean (``a0 = 1, b0 = sqrt(mc), c0 = k``, ``c_{n+1} = c_n^2/(4 a_{n+1})``),
    ``1 - E/K = sum_{n>=0} 2^{n-1} c_n^2`` (Abramowitz & Stegun 17.6.3-17.6.4); with ``q_n = c_n^2/k^2`` the
    sum divided by ``k^2`` is ``1/2 + sum_{n>=1} 2^{n-1} q_n``, every term positive. Exact in ``mc``.
    """
    a = 1.0 + 0.0 * mc
    b = xp.sqrt(mc)
    q = 1.0 + 0.0 * k2
    c2 = k2
    p = 0.5
    total = 0.0 * k2
    for _ in range(40):
        a_new = 0.5 * (a + b)
        b = xp.sqrt(a * b)
        a = a_new
        q = q * c2 / (16.0 * a * a)
        c2 = c2 * c2 / (16.0 * a * a)
        p *= 2.0
        term = p * q
        total = total + term
        if not xp.any(term > 1e-17 * (0.5 + total)):
            break
    return total


# ---------------------------------------------------------------------------------------------------
# the u chart
# ---------------------------------------------------------------------------------------------------
def _side(xp: Any, x: Any) -> tuple[Any, Any, Any, Any]:
    """``u = tanh x`` and its gaps ``1 + u``, ``1 - u``, plus ``t = exp(-2|x|)``."""
    t = xp.exp(-2.0 * xp.abs(x))
    big = 2.0 / (1.0 + t)
    small = 2.0 * t / (1.0 + t)
    pos = x >= 0.0
    w = xp.where(pos, big, small)
    z = xp.where(pos, small, big)
    u = xp.where(pos, 1.0, -1.0) * (1.0 - t) / (1.0 + t)
    return u, w, z, t


def gaps_to_x(xp: Any, w1: Any, z1: Any, w2: Any, z2: Any) -> tuple[Any, Any]:
    """``atanh u`` of the two lower roots from their gaps ``1 + u_i``, ``1 - u_i``."""
    return 0.5 * xp.log(w1 / z1), 0.5 * xp.log(w2 / z2)


class UState:
    """Everything the u-chart right-hand sides need at one state (attributes; scalars or arrays)."""

    __slots__ = ("Cr", "Gz", "H", "K", "Sm", "Sp", "c", "cth", "d21", "d31", "d32", "gm", "gp", "k2", "mc", "pim",
                 "pip", "r", "sth", "u1", "u2", "u3", "w1", "w2", "z1", "z2")

    Cr: Any
    Gz: Any
    H: Any
    K: Any
    Sm: Any
    Sp: Any
    c: Any
    cth: Any
    d21: Any
    d31: Any
    d32: Any
    gm: Any
    gp: Any
    k2: Any
    mc: Any
    pim: Any
    pip: Any
    r: Any
    sth: Any
    u1: Any
    u2: Any
    u3: Any
    w1: Any
    w2: Any
    z1: Any
    z2: Any


def decode_u(xp: Any, A: float, C: float, mgl: float, x1: Any, x2: Any, th: Any, d1: Any, d2: Any) -> UState:
    """Roots, gaps and (Gz, H, r) by (2.8) at the u-chart point ``(x1, x2, theta)`` with signs ``delta1, delta2``.

    ``tan^2 theta = Pi-/Pi+ = (1-u1)(1-u2)(u3-1)/((1+u1)(1+u2)(1+u3))`` gives
    ``u3 - 1 = 2 T w1 w2/(z1 z2 - T w1 w2)`` (``T = tan^2 theta``, ``w = 1 + u``, ``z = 1 - u``).
    """
    s = UState()
    u1, w1, z1, t1 = _side(xp, x1)
    u2, w2, z2, t2 = _side(xp, x2)
    sn, cs = xp.sin(th), xp.cos(th)
    ww = w1 * w2 * sn * sn
    c = 2.0 * ww / (z1 * z2 * cs * cs - ww)
    s.sth, s.cth = sn, cs
    s.u1, s.w1, s.z1, s.u2, s.w2, s.z2, s.c, s.u3 = u1, w1, z1, u2, w2, z2, c, 1.0 + c
    # u2 - u1 = tanh x2 - tanh x1 = sinh(x2 - x1)/(cosh x1 cosh x2), exact for nearly equal roots
    s.d21 = 4.0 * xp.sinh(x2 - x1) * xp.exp(-(xp.abs(x1) + xp.abs(x2))) / ((1.0 + t1) * (1.0 + t2))
    s.d32 = c + z2
    s.d31 = c + z1
    s.k2 = s.d21 / s.d31
    s.mc = s.d32 / s.d31
    pip = w1 * w2 * (2.0 + c)
    pim = z1 * z2 * c
    s.pip, s.pim = pip, pim
    amg2 = 2.0 * A * mgl
    Sp = xp.sqrt(amg2 * pip)  # |Gz + C r|
    Sm = xp.sqrt(amg2 * pim)  # |Gz - C r|
    s.Sp, s.Sm = Sp, Sm
    sg = xp.where(pip >= pim, d2, -d2)
    neg = d1 < 0.0
    Gz = xp.where(neg, d2 * (Sp - Sm), sg * (Sp + Sm)) * 0.5
    Cr = xp.where(neg, d2 * (Sp + Sm), sg * (Sp - Sm)) * 0.5
    s.gp = xp.where(neg, d2, sg) * Sp  # Gz + C r
    s.gm = xp.where(neg, -d2, sg) * Sm  # Gz - C r
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
    gv = xp.where(v <= 0.0, s.gp - s.Cr * onepv, s.gm + s.Cr * onemv)  # Gz - C r v
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
    ``N1, N3`` are expanded about the nearer end of the range of ``u_i`` (they vanish with ``Gz +- C r`` there),
    and the factor ``u_i^2 - 1`` of ``V_i2`` cancels the chart's ``1/(1 - u_i^2)``.
    """
    kA = C / A - 1.0
    Gz, Cr, r = s.Gz, s.Cr, s.r
    gp, gm = s.gp, s.gm
    out = []
    for u, w, z in ((s.u1, s.w1, s.z1), (s.u2, s.w2, s.z2)):
        lower = u <= 0.0
        N1 = xp.where(lower, gp - Cr * w, gm + Cr * z)
        N3 = xp.where(lower, gp / A - w * (2.0 * kA * r + Gz / A) + kA * r * w * w,
                      -gm / A + z * (Gz / A - 2.0 * kA * r) + kA * r * z * z)
        out.append((N1 * F1 / A + C * N3 * F3) / (w * z))
    dx1 = (out[0] - F2) / (mgl * s.d21 * s.d31)
    dx2 = (out[1] - F2) / (-mgl * s.d21 * s.d32)
    # theta = atan2(|Gz - C r|, |Gz + C r|): d|Gz +- C r| = sign(Gz +- C r) (F1 +- C F3)
    sgp = xp.where(gp >= 0.0, 1.0, -1.0)
    sgm = xp.where(gm >= 0.0, 1.0, -1.0)
    CF3 = C * F3
    dth = (s.Sp * sgm * (F1 - CF3) - s.Sm * sgp * (F1 + CF3)) / (s.Sp * s.Sp + s.Sm * s.Sm)
    return dx1, dx2, dth


# ---------------------------------------------------------------------------------------------------
# the GHr chart (log-polar in the (Gz, C r) plane)
# ---------------------------------------------------------------------------------------------------
class GState:
    """Slow variables and roots at a GHr-chart point (attributes; scalars or arrays)."""

    __slots__ = ("Cr", "Gz", "H", "K", "S", "cs", "d21", "gm", "gp", "half", "k2", "mc", "msum", "ok", "r", "s1",
                 "s2", "s3", "sn", "spread", "u1", "u2", "u3")

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


def decode_g(xp: Any, A: float, C: float, mgl: float, sigma: Any, psi: Any, H: Any) -> GState:
    """(Gz, H, r) and the roots of (1.5) at ``(ln S, psi, H)``.

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
    g.Gz, g.Cr, g.r, g.H = Gz, Cr, Cr / C, H
    g.gp = _SQRT2 * S * sq  # Gz + C r
    g.gm = _SQRT2 * S * cq  # Gz - C r
    K = H + mgl - Cr * Cr / (2.0 * C)
    g.K = K
    amg = A * mgl
    s1 = K / mgl - 1.0 + Cr * Cr / (2.0 * amg)
    s2 = Gz * Cr / amg - 1.0
    s3 = (g.gp * g.gp + g.gm * g.gm) / (4.0 * amg) - s1
    g.s1, g.s2, g.s3 = s1, s2, s3
    disc = s1 * s1 - 3.0 * s2
    g.ok = disc >= 0.0
    sqd = xp.sqrt(xp.maximum(disc, 0.0))
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
    c_lo = (s1 - sqd) / 3.0  # local maximum of the cubic: the double root of a regular precession
    inside = h2 > 0.0
    half = xp.sqrt(xp.maximum(h2, 0.0))
    g.msum = xp.where(inside, msum, c_lo)
    g.half = half
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
    """``d(ln S, psi, H)/dtau`` from ``<F>``: ``S^2 = Gz^2 + C^2 r^2``, ``pi psi = atan2(C r, Gz)``."""
    CF3 = C * F3
    dsig = (g.cs * F1 + g.sn * CF3) / g.S
    dpsi = (g.cs * CF3 - g.sn * F1) / (math.pi * g.S)
    return dsig, dpsi, F2


def slow_to_polar(xp: Any, C: float, Gz: Any, H: Any, r: Any) -> tuple[Any, Any, Any]:
    """``(ln S, psi, H)`` of ``(Gz, H, r)`` (``S > 0``)."""
    Cr = C * r
    S = xp.sqrt(Gz * Gz + Cr * Cr)
    psi = np.arctan2(Cr, Gz) / math.pi if xp.array else math.atan2(Cr, Gz) / math.pi
    return xp.log(S), psi, H


# ---------------------------------------------------------------------------------------------------
# one-run fast path: the u chart under linear drag as one math-scalar function
# ---------------------------------------------------------------------------------------------------
def u_drag_rates_scalar_factory(
    A: float, C: float, mgl: float, a: float, b: float
) -> Callable[[float, float, float, float, float], tuple[float, float, float]]:
    """``f(x1, x2, theta, delta1, delta2) -> d(x1, x2, theta)/dtau`` of the u chart under linear drag.

    :func:`decode_u`, :func:`drag_means` and :func:`u_chart_rates` fused for floats: the same formulas,
    evaluated with ``math``, branches instead of selections and the parameters' combinations computed once
    (tests compare the two).
    """
    sqrt, exp, sin, cos, sinh = math.sqrt, math.exp, math.sin, math.cos, math.sinh
    amg2 = 2.0 * A * mgl
    iA, iC, i2A = 1.0 / A, 1.0 / C, 0.5 / A
    kA = C / A - 1.0
    aA, bC = a / A, b / C
    two_a_A = 2.0 * a / A

    def rates(x1: float, x2: float, th: float, d1: float, d2: float) -> tuple[float, float, float]:
        ax1 = x1 if x1 >= 0.0 else -x1
        ax2 = x2 if x2 >= 0.0 else -x2
        t1 = exp(-2.0 * ax1)
        t2 = exp(-2.0 * ax2)
        i1 = 1.0 / (1.0 + t1)
        i2 = 1.0 / (1.0 + t2)
        if x1 >= 0.0:
            w1, z1, u1 = 2.0 * i1, 2.0 * t1 * i1, (1.0 - t1) * i1
        else:
            w1, z1, u1 = 2.0 * t1 * i1, 2.0 * i1, (t1 - 1.0) * i1
        if x2 >= 0.0:
            w2, z2, u2 = 2.0 * i2, 2.0 * t2 * i2, (1.0 - t2) * i2
        else:
            w2, z2, u2 = 2.0 * t2 * i2, 2.0 * i2, (t2 - 1.0) * i2
        sn = sin(th)
        cs = cos(th)
        ww = w1 * w2 * sn * sn
        c = 2.0 * ww / (z1 * z2 * cs * cs - ww)
        d21 = 4.0 * sinh(x2 - x1) * exp(-(ax1 + ax2)) * i1 * i2
        d32 = c + z2
        d31 = c + z1
        pip = w1 * w2 * (2.0 + c)
        pim = z1 * z2 * c
        Sp = sqrt(amg2 * pip)
        Sm = sqrt(amg2 * pim)
        if d1 < 0.0:
            gp, gm = d2 * Sp, -d2 * Sm
        elif pip >= pim:
            gp, gm = d2 * Sp, d2 * Sm
        else:
            gp, gm = -d2 * Sp, -d2 * Sm
        Gz = 0.5 * (gp + gm)
        Cr = 0.5 * (gp - gm)
        r = Cr * iC
        # <sn^2> - 1/2 by the AGM series (sn2_excess)
        aa, bb, q, cc, p, sx = 1.0, sqrt(d32 / d31), 1.0, d21 / d31, 1.0, 0.0
        while True:
            aa, bb = 0.5 * (aa + bb), sqrt(aa * bb)
            f = cc / (16.0 * aa * aa)
            q *= f
            cc *= f
            pq = p * q
            sx += pq
            if pq <= 1e-17 * (0.5 + sx):
                break
            p *= 2.0
        lo = d21 * (0.5 + sx)
        hi = d21 * (0.5 - sx)
        v = u1 + lo
        gv = gp - Cr * (w1 + lo) if v <= 0.0 else gm + Cr * (z2 + hi)
        brv = b * r
        F1 = -aA * gv - brv * v
        F2 = -two_a_A * (mgl * (w1 + c + hi) - Cr * Cr * i2A) - brv * r
        CF3 = -bC * Cr
        GA = Gz * iA
        kr = kA * r
        if u1 <= 0.0:
            N1 = gp - Cr * w1
            N3 = gp * iA - w1 * (2.0 * kr + GA) + kr * w1 * w1
        else:
            N1 = gm + Cr * z1
            N3 = -gm * iA + z1 * (GA - 2.0 * kr) + kr * z1 * z1
        P1 = (N1 * F1 * iA + N3 * CF3) / (w1 * z1)
        if u2 <= 0.0:
            N1 = gp - Cr * w2
            N3 = gp * iA - w2 * (2.0 * kr + GA) + kr * w2 * w2
        else:
            N1 = gm + Cr * z2
            N3 = -gm * iA + z2 * (GA - 2.0 * kr) + kr * z2 * z2
        P2 = (N1 * F1 * iA + N3 * CF3) / (w2 * z2)
        sgm = 1.0 if gm >= 0.0 else -1.0
        sgp = 1.0 if gp >= 0.0 else -1.0
        dth = (Sp * (F1 - CF3) * sgm - Sm * (F1 + CF3) * sgp) / (Sp * Sp + Sm * Sm)
        md = mgl * d21
        return (P1 - F2) / (md * d31), (F2 - P2) / (md * d32), dth

    return rates


def u_event_values_scalar(x1: float, x2: float, th: float, d1: float) -> tuple[float, float, float]:
    """``(k^2, mc, min(b1, b2))`` at a u-chart point: the modulus (1.4), its complement and the distance from
    the branch points of (2.8), ``b1 = |Gz^2 - C^2 r^2|/(Gz^2 + C^2 r^2) = sin 2 theta`` and
    ``b2 = C^2 r^2/(Gz^2 + C^2 r^2) = (1 - delta1 sin 2 theta)/2`` (from ``tan theta = |Gz - C r|/|Gz + C r|``)."""
    ax1 = x1 if x1 >= 0.0 else -x1
    ax2 = x2 if x2 >= 0.0 else -x2
    t1 = math.exp(-2.0 * ax1)
    t2 = math.exp(-2.0 * ax2)
    i1 = 1.0 / (1.0 + t1)
    i2 = 1.0 / (1.0 + t2)
    w1, z1 = (2.0 * i1, 2.0 * t1 * i1) if x1 >= 0.0 else (2.0 * t1 * i1, 2.0 * i1)
    w2, z2 = (2.0 * i2, 2.0 * t2 * i2) if x2 >= 0.0 else (2.0 * t2 * i2, 2.0 * i2)
    sn, cs = math.sin(th), math.cos(th)
    ww = w1 * w2 * sn * sn
    c = 2.0 * ww / (z1 * z2 * cs * cs - ww)
    d21 = 4.0 * math.sinh(x2 - x1) * math.exp(-(ax1 + ax2)) * i1 * i2
    d31 = c + z1
    b1 = 2.0 * sn * cs
    return d21 / d31, (c + z2) / d31, min(b1, 0.5 * (1.0 - d1 * b1))
