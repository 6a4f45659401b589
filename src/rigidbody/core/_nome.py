r"""Jacobi functions near the separatrix by the complementary nome (the near route of ``core.elliptic``).

With the complementary nome :math:`q_1 = e^{-\pi K/K'}` (:math:`q_1 \approx m_c/16 \to 0` as
:math:`k \to 1`), Jacobi's imaginary transformation turns the Fourier series of the functions of modulus
:math:`k'` (DLMF 22.11.1-3) into sums of positive hyperbolic terms. With :math:`u = \vartheta_3(q_1)^2\,y`
and :math:`q = q_1`,

.. math::
    \operatorname{cn}u = \frac{c_0}{D},\quad \operatorname{sn}u = \frac{S}{D},\quad
    \operatorname{dn}u = \frac{c_0}{\vartheta_3^2}\frac{N}{D},\qquad c_0 = (1 + q^2 + q^6 + q^{12} + \dots)^2,

    D = \sum_{n\ge0}\frac{q^n\cosh(2n+1)y}{1 + q^{2n+1}},\quad
    S = \sum_{n\ge0}\frac{q^n\sinh(2n+1)y}{1 - q^{2n+1}},\quad
    N = 1 + 4\sum_{n\ge1}\frac{q^n\cosh 2ny}{1 + q^{2n}},

and the quarter period is :math:`K = \vartheta_3^2 Y`, :math:`Y = \tfrac12\ln(1/q_1)`. On
:math:`0 \le y \le Y/2` the terms fall like :math:`q^{n/2}` (three terms for :math:`m_c \le 10^{-12}`) and
every sum is of positive terms: a few ulp of relative accuracy where :math:`\operatorname{cn}` and
:math:`\operatorname{dn}` are as small as :math:`m_c^{1/4}`. Beyond :math:`Y/2` the shift
:math:`\operatorname{sn}(K-v) = \operatorname{cd}v`, :math:`\operatorname{cn}(K-v) = k'\operatorname{sd}v`,
:math:`\operatorname{dn}(K-v) = k'\operatorname{nd}v` brings the argument back.

The argument is reduced in double-double arithmetic (:math:`y = u/\vartheta_3^2`, then :math:`y - 2Yj`, then
:math:`Y - |y|`), so that the distance to a zero of :math:`\operatorname{cn}` at an odd multiple of
:math:`K` keeps its relative accuracy: :math:`2Y = \ln(1/q_1) = \ln 16 - \ln m_c + O(m_c)` is carried to
~1e-22 absolute for :math:`m_c \le 10^{-12}` (:math:`\ln m_c` by a table and a short series, with
:math:`m_c` given exactly), to ~1e-17 at :math:`m_c = 0.05` (the rounding of the :math:`O(m_c)` terms).

The functions take a namespace ``xp`` of :mod:`rigidbody.core.kernel` (``SCALAR`` for one Python float,
``ARRAY`` for arrays, elementwise), so one code serves the scalar fast path and arrays.
"""

from __future__ import annotations

import decimal
import functools
import math
from typing import Any

import numpy as np

from .kernel import SCALAR

__all__ = ["jacobi_near", "ln_dd", "n_terms", "nome", "nome_cached", "two_prod", "two_sum"]


def _lib(xp: Any) -> Any:
    """The module whose ``exp, expm1, log1p, sqrt, fmod, frexp`` act on ``xp``'s values."""
    return np if xp.array else math


def two_sum(a: Any, b: Any) -> tuple[Any, Any]:
    """``s + e = a + b`` exactly with ``s = fl(a + b)`` (Knuth's TwoSum)."""
    s = a + b
    bb = s - a
    return s, (a - (s - bb)) + (b - bb)


def two_prod(a: Any, b: Any) -> tuple[Any, Any]:
    """``p + e = a b`` exactly with ``p = fl(a b)`` (Dekker's splitting; for ``|a|, |b| < 1e290``)."""
    p = a * b
    ca, cb = 134217729.0 * a, 134217729.0 * b
    ah, bh = ca - (ca - a), cb - (cb - b)
    al, bl = a - ah, b - bh
    return p, ((ah * bh - p) + ah * bl + al * bh) + al * bl


def _dd(d: decimal.Decimal) -> tuple[float, float]:
    hi = float(d)
    return hi, float(d - decimal.Decimal(hi))


with decimal.localcontext() as _ctx:
    _ctx.prec = 40
    #: ln 2 split so that ``e * _LN2_HI`` is exact for every binary exponent ``e`` of a double
    _LN2_HI = math.ldexp(math.floor(math.ldexp(math.log(2.0), 40)), -40)
    _LN2_LO = float(decimal.Decimal(2).ln() - decimal.Decimal(_LN2_HI))
    _LN16 = _dd(decimal.Decimal(16).ln())
    #: ln(j/64) for j = 45..91 as double-doubles (zeros below 45, never used), as a list for Python floats
    #: and as arrays
    _LNTAB = [(0.0, 0.0)] * 45 + [_dd((decimal.Decimal(j) / 64).ln()) for j in range(45, 92)]
    _LNTAB_HI, _LNTAB_LO = np.array([v[0] for v in _LNTAB]), np.array([v[1] for v in _LNTAB])


def ln_dd(x: Any, xp: Any) -> tuple[Any, Any]:
    """``ln x`` (``x > 0`` finite, subnormals included) as a double-double, to ~1e-22 absolute.

    ``x = f 2^e`` with ``f = (j/64)(1 + r)``, ``|r| < 0.012``: ``e ln 2`` and ``ln(j/64)`` from double-double
    constants, ``ln(1 + r)`` by its series with ``r`` (to its own rounding, carried) and ``r^2/2`` exact.
    """
    lib = _lib(xp)
    f, e = lib.frexp(x)
    low = f < 0.7071067811865476
    f, e = xp.where(low, 2.0 * f, f), xp.where(low, e - 1, e) * 1.0
    j = xp.rint(64.0 * f)
    f0 = j / 64.0
    d = f - f0  # exact (Sterbenz)
    r = d / f0
    p, pe = two_prod(r, f0)
    r_lo = ((d - p) - pe) / f0  # d / f0 = r + r_lo
    r2, r2e = two_prod(r, r)
    tail = r2 * r * (1 / 3 + r * (-1 / 4 + r * (1 / 5 + r * (-1 / 6 + r * (1 / 7 + r * (-1 / 8 + r * (
        1 / 9 + r * (-1 / 10 + r * (1 / 11 + r * (-1 / 12))))))))))  # r^3/3 - r^4/4 + ...; r^13/13 < 3e-26
    if xp.array:
        ji = j.astype(np.intp)
        t_hi, t_lo = _LNTAB_HI[ji], _LNTAB_LO[ji]
    else:
        t_hi, t_lo = _LNTAB[int(j)]
    h, lo = two_sum(e * _LN2_HI, t_hi)
    h, lo2 = two_sum(h, r)
    h, lo3 = two_sum(h, -0.5 * r2)
    lo = lo + lo2 + lo3 + (e * _LN2_LO + t_lo + (tail - 0.5 * r2e + r_lo * (1.0 - r)))
    return two_sum(h, lo)


def nome(m: Any, mc: Any, xp: Any) -> tuple[Any, Any, Any, Any, Any]:
    r"""The complementary nome and what the series need, for :math:`0 < m_c \le 0.05`.

    Returns
    -------
    tuple
        ``(P_hi, P_lo, q, eps, c0)``: :math:`P = \ln(1/q_1) = 2Y` as a double-double, :math:`q_1`,
        :math:`\vartheta_3(q_1)^2 = 1 + \varepsilon` and :math:`c_0 = (1 + q^2 + q^6 + q^{12})^2`.
    """
    lib = _lib(xp)
    k = lib.sqrt(m)
    sk = lib.sqrt(k)
    omk = mc / (1.0 + k)  # 1 - k
    omsk = omk / (1.0 + sk)  # 1 - sqrt(k)
    # the nome series of the modulus k' (Abramowitz & Stegun ch. 17): q1 = lam + 2 lam^5 + 15 lam^9 +
    # 150 lam^13 + ..., lam = (1 - sqrt k) / (2 (1 + sqrt k)) <= 3.3e-3 here, so lam^13 is below 1e-28 of q1
    lam = 0.5 * omsk / (1.0 + sk)
    l4 = (lam * lam) ** 2
    corr = l4 * (2.0 + l4 * (15.0 + 150.0 * l4))
    q = lam * (1.0 + corr)
    # ln(1/q1) = 4 ln 2 - ln mc + ln(1 - (1-k)/2) + 2 ln(1 - (1-sqrt k)/2) - ln(1 + 2 lam^4 + ...)
    small = lib.log1p(-0.5 * omk) + 2.0 * lib.log1p(-0.5 * omsk) - lib.log1p(corr)
    lh, ll = ln_dd(mc, xp)
    ph, pl = two_sum(_LN16[0], -lh)
    ph, pl = two_sum(ph, pl + (_LN16[1] - ll + small))
    t = 2.0 * (q + q**4 + q**9)  # theta3 - 1
    return ph, pl, q, t * (2.0 + t), (1.0 + q * q + q**6 + q**12) ** 2


def n_terms(e1: float) -> int:
    """Terms after the first the series need where ``q e^{2x} <= e1``: the n-th is below ``e1^n`` of the first
    (``e1 <= sqrt(q1)`` on the reduced range), ``e1^(N+1) < 2^-56``."""
    if e1 <= 0.0:
        return 0
    return max(0, math.ceil(56.0 / -math.log2(e1)) - 1)


@functools.lru_cache(maxsize=64)
def nome_cached(m: float, mc: float) -> tuple[float, float, float, float, float]:
    """:func:`nome` of one modulus in Python floats, cached (an integrator's right-hand side calls with the
    same modulus again and again)."""
    return nome(m, mc, SCALAR)


def _series(x: Any, lnq: Any, q: Any, eps: Any, c0: Any, xp: Any) -> tuple[Any, Any, Any]:
    """sn, cn, dn at ``u = theta3^2 x`` for ``-tiny <= x <= ln(1/q)/4`` (every sum of positive terms)."""
    lib = _lib(xp)
    ex = lib.exp(-x)
    ex2 = ex * ex
    ex4 = ex2 * ex2
    em = -lib.expm1(-2.0 * x)  # 1 - e^{-2x}
    e1 = lib.exp(lnq + 2.0 * x)  # q e^{2x} <= sqrt(q)
    nt = n_terms(float(np.max(e1)) if xp.array else e1)
    # D, S, N divided by e^x / 2; S's terms q^n e^{2nx} (1 - e^{-(4n+2)x}) = e1^n em g_n, g_n = sum_{i<=2n} ex2^i
    d_sum = (1.0 + ex2) / (1.0 + q)
    s_sum = 1.0 / (1.0 - q)
    n_sum = 0.0
    en, g, qn, p, ex2n = 1.0, 1.0, 1.0, 1.0, 1.0  # e1^n, g_n, q^n, ex2^(2n), ex2^n
    for _ in range(nt):
        en, qn, ex2n = en * e1, qn * q, ex2n * ex2
        g = g + p * ex2 + p * ex4
        p = p * ex4
        q2n = qn * qn
        d_sum = d_sum + en * (1.0 + p * ex2) / (1.0 + q2n * q)
        s_sum = s_sum + en * g / (1.0 - q2n * q)
        n_sum = n_sum + (en + qn * ex2n) / (1.0 + q2n)
    cn = 2.0 * c0 * ex / d_sum
    return em * s_sum / d_sum, cn, cn * (1.0 + 2.0 * n_sum) / (1.0 + eps)


def jacobi_near(u: Any, m: Any, mc: Any, consts: tuple[Any, Any, Any, Any, Any], xp: Any
                ) -> tuple[Any, Any, Any, Any]:
    """sn, cn, dn, am for ``0 < mc <= 0.05`` (``consts = nome(m, mc, xp)``).

    Relative accuracy a few ulp, also where cn and dn are tiny, when the argument is farther from an odd
    multiple of K than ~1e-22 (mc <= 1e-12) to ~1e-17 (mc = 0.05) times the number of the multiple divided
    by the target accuracy; any finite ``u`` gives finite values (beyond ``|u| = 2^53`` no digit of the phase
    is left).
    """
    ph, pl, q, eps, c0 = consts
    # y = u / theta3^2 = u - u eps / (1 + eps) in double-double
    yh, yl = two_sum(u, -(u * eps / (1.0 + eps)))
    # y = j P + r, |r| <= P/2 (P = 2Y: the half period 2K); fmod is exact, j exact below 2^53
    r0 = _lib(xp).fmod(yh, ph)
    j = xp.rint((yh - r0) / ph)
    rh, rl = two_sum(r0, xp.where(abs(yh) < 2.0**53, yl - j * pl, 0.0))
    s = xp.where(rh > 0.5 * ph, 1.0, xp.where(rh < -0.5 * ph, -1.0, 0.0))
    rh, rl2 = two_sum(rh, -s * ph)
    rl = rl + rl2 - s * pl
    j = j + s
    sgn = xp.where(rh < 0.0, -1.0, 1.0)
    ah, al = sgn * rh, sgn * rl  # |r|
    upper = ah > 0.25 * ph
    vh, vl = two_sum(0.5 * ph - ah, 0.5 * pl - al)  # Y - |r| (the first difference exact: Sterbenz)
    xh, xl = two_sum(xp.where(upper, vh, ah), xp.where(upper, vl, al))
    s0, c0_, d0 = _series(xh, -ph, q, eps, c0, xp)
    # first order in the low part of the argument: sn' = cn dn, cn' = -sn dn, dn' = -m sn cn
    du = xl * (1.0 + eps)
    s0, c0_, d0 = s0 + c0_ * d0 * du, c0_ - s0 * d0 * du, d0 - m * s0 * c0_ * du
    # below K/2 where sn^2 < 1/2, cn = sqrt((1 - sn)(1 + sn)) and dn = sqrt(1 - m sn^2) carry at most the
    # error of sn (|d cn| <= |sn/cn| |d sn| <= |d sn|, and as much for dn) plus a rounding, and never exceed
    # 1: the products of the series gather a few ulp, which showed as cn = dn = 1 + 2 ulp at u ~ 1e-9 K.
    # (Above K/2 the results are ratios of these, whose shared factors cancel: kept as they are.)
    lib, small = _lib(xp), (s0 * s0 < 0.5) & (ah <= 0.25 * ph)  # not upper
    c0_ = xp.where(small, lib.sqrt((1.0 - s0) * (1.0 + s0)), c0_)
    d0 = xp.where(small, lib.sqrt(1.0 - m * s0 * s0), d0)
    kp = _lib(xp).sqrt(mc)
    s1 = xp.where(upper, c0_ / d0, s0)
    c1 = xp.where(upper, kp * s0 / d0, c0_)
    d1 = xp.where(upper, kp / d0, d0)
    par = xp.where(_lib(xp).fmod(j, 2.0) == 0.0, 1.0, -1.0)
    return par * sgn * s1, par * c1, d1, j * math.pi + xp.atan2(sgn * s1, c1)
