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

from ._periods import reduce_half_period, two_prod, two_sum, with_parity
from .kernel import SCALAR

__all__ = ["jacobi_near", "ln_dd", "n_terms", "nome", "nome_cached"]


def _lib(xp: Any) -> Any:
    """The module whose ``exp, expm1, log1p, sqrt, fmod, frexp`` act on ``xp``'s values."""
    return np if xp.array else math


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


def nome(m: Any, mc: Any, xp: Any, mcl: Any = 0.0) -> tuple[Any, Any, Any, Any, Any]:
    r"""The complementary nome and what the series need, for :math:`0 < m_c \le 0.05`.

    ``mcl`` is the low part of :math:`m_c` given as a double-double (``1 - k^2`` from ``k``): :math:`q_1`
    and :math:`\ln(1/q_1)` are proportional to :math:`m_c` and :math:`-\ln m_c` to first order, so it
    enters as the factor :math:`1 + m_{c,lo}/m_c` (the series' quarter period then matches :math:`K` of the
    exact :math:`m_c`, not of its rounding).

    Returns
    -------
    tuple
        ``(P_hi, P_lo, q, eps, c0)``: :math:`P = \ln(1/q_1) = 2Y` as a double-double, :math:`q_1`,
        :math:`\vartheta_3(q_1)^2 = 1 + \varepsilon` and :math:`c_0 - 1`, :math:`c_0 = (1 + q^2 + q^6 + q^{12})^2`.
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
    rel = mcl / mc
    q = lam * (1.0 + corr) * (1.0 + rel)
    # ln(1/q1) = 4 ln 2 - ln mc + ln(1 - (1-k)/2) + 2 ln(1 - (1-sqrt k)/2) - ln(1 + 2 lam^4 + ...)
    small = lib.log1p(-0.5 * omk) + 2.0 * lib.log1p(-0.5 * omsk) - lib.log1p(corr)
    lh, ll = ln_dd(mc, xp)
    ph, pl = two_sum(_LN16[0], -lh)
    ph, pl = two_sum(ph, pl + (_LN16[1] - ll + small - rel))
    q2 = q * q
    q4 = q2 * q2
    q6 = q4 * q2
    t = 2.0 * (q + q4 + q4 * q4 * q)  # theta3 - 1
    c = q2 + q6 + q6 * q6
    return ph, pl, q, t * (2.0 + t), c * (2.0 + c)


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


def _tails(xh: Any, lnq: Any, q: Any, xp: Any) -> tuple[Any, Any, Any, Any]:
    """The sums of the series after their first terms at ``x ~ xh`` (``-tiny <= x <= ln(1/q)/4``), with D, S, N
    divided by ``e^x / 2``: ``(e^-2x, D - (1 + e^-2x)/(1 + q), S/(1 - e^-2x) - 1/(1 - q), N)``. Each term falls
    by ``e1 = q e^{2x} <= sqrt(q) <= 0.06``: these are small beside the first terms, and a relative error of
    a few ulp in them is below an ulp of the whole."""
    lib = _lib(xp)
    ex2 = lib.exp(-2.0 * xh)
    ex4 = ex2 * ex2
    e1 = lib.exp(lnq + 2.0 * xh)  # q e^{2x} <= sqrt(q)
    nt = n_terms(float(np.max(e1)) if xp.array else e1)
    # S's terms q^n e^{2nx} (1 - e^{-(4n+2)x}) = e1^n (1 - e^-2x) g_n, g_n = sum_{i<=2n} ex2^i
    d_tail, s_tail, n_sum = 0.0, 0.0, 0.0
    en, g, qn, p, ex2n = 1.0, 1.0, 1.0, 1.0, 1.0  # e1^n, g_n, q^n, ex2^(2n), ex2^n
    for _ in range(nt):
        en, qn, ex2n = en * e1, qn * q, ex2n * ex2
        g = g + p * ex2 + p * ex4
        p = p * ex4
        q2n = qn * qn
        d_tail = d_tail + en * (1.0 + p * ex2) / (1.0 + q2n * q)
        s_tail = s_tail + en * g / (1.0 - q2n * q)
        n_sum = n_sum + (en + qn * ex2n) / (1.0 + q2n)
    return ex2, d_tail, s_tail, n_sum


def jacobi_near(u: Any, m: Any, mc: Any, consts: tuple[Any, ...], key: tuple[Any, Any, Any], xp: Any
                ) -> tuple[Any, Any, Any, Any]:
    """sn, cn, dn, am for ``0 < mc < 0.05``.

    ``consts = nome(m, mc, xp) + (K_hi, K_lo)`` (:math:`K` as a double-double,
    ``rigidbody.core._periods.complete_dd``), ``key`` the modulus exactly (see
    ``rigidbody.core._periods.reduce_half_period``, which reduces ``u`` by the half period :math:`2K`).
    A few ulp of relative accuracy, also where cn and dn are tiny.
    """
    ph, _, q, eps, c0m, kh, kl = consts
    j, sgn, upper, vh, vl = reduce_half_period(u, kh, kl, key, xp)
    # the series' variable x = v / theta3^2 = v - v eps / (1 + eps), as a double-double
    f = eps / (1.0 + eps)
    xh, xl = two_sum(vh, -(vh * f))
    xl = xl + vl * (1.0 - f)
    ex2, d_tail, s_tail, n_sum = _tails(xh, -ph, q, xp)
    lib = _lib(xp)
    # With tau = (1 + q) D_tail / (1 + e^-2x), N2 = 2N and a = c0 (1 + q) - 1, the series give (the shared
    # factors cancelled) sn = tanh x (1 + q)(1/(1 - q) + S_tail) / (1 + tau), cn = sech x (1 + a) / (1 + tau),
    # dn = cn (1 + N2) / (1 + eps) below K/2, and beyond it cd = (1 + eps)/(1 + N2),
    # k' sd = k' sinh x (1 + eps)(1/(1 - q) + S_tail) / (c0 (1 + N2)),
    # k' nd = k' cosh x (1 + eps)(1 + tau) / ((1 + a)(1 + N2)). Each is base (1 + w), w formed from the small
    # quantities: one rounding on top of the error of tanh, cosh or sinh.
    tau = (1.0 + q) * d_tail / (1.0 + ex2)
    n2 = 2.0 * n_sum
    a = c0m + q * (1.0 + c0m)
    g = q / (1.0 - q)
    st = s_tail * (1.0 + q)
    lo_d = (a + n2 + a * n2) - (tau + eps + tau * eps)  # dn: (1 + a)(1 + N2) - (1 + tau)(1 + eps)
    w_up_s = (eps - n2) / (1.0 + n2)
    w_up_c = ((eps + g + s_tail + eps * (g + s_tail)) - (c0m + n2 + c0m * n2)) / ((1.0 + c0m) * (1.0 + n2))
    w_up_d = -lo_d / ((1.0 + a) * (1.0 + n2))
    w_lo_s = (2.0 * g + st - tau) / (1.0 + tau)
    w_lo_c = (a - tau) / (1.0 + tau)
    w_lo_d = lo_d / ((1.0 + tau) * (1.0 + eps))
    ch, sh = lib.cosh(xh), lib.sinh(xh)
    ch, sh = ch + xl * sh, sh + xl * ch  # first order in the low part of x
    th, sech = sh / ch, 1.0 / ch
    th = xp.where(xh < 0.5, lib.tanh(xh) + xl * (sech * sech), th)  # (tanh near 0, where sh / ch is ~1 ulp)
    kp = lib.sqrt(mc)
    bs = xp.where(upper, 1.0, th)
    bc = xp.where(upper, kp * sh, sech)
    bd = xp.where(upper, kp * ch, sech)
    sn = bs + bs * xp.where(upper, w_up_s, w_lo_s)
    cn = bc + bc * xp.where(upper, w_up_c, w_lo_c)
    dn = bd + bd * xp.where(upper, w_up_d, w_lo_d)
    return with_parity(j, sgn * sn, cn, dn, xp)
