r"""The complete integrals :math:`K` and :math:`E` in double-double arithmetic, by the arithmetic-geometric mean.

The Jacobi functions reduce their argument by the half period :math:`2K`; near a zero of
:math:`\operatorname{sn}` or :math:`\operatorname{cn}` the reduced argument is small and keeps its relative
accuracy only if :math:`K` is known far beyond double precision. Here :math:`K = \pi / (2M(1, k'))`
(Abramowitz & Stegun 17.6.1), the mean :math:`M` run in double-double arithmetic from
:math:`k' = \sqrt{m_c}`, itself a double-double from the complementary parameter given as a double-double
(``mc`` exactly, or :math:`1 - k^2` formed exactly from ``k``). The iteration stops once
:math:`t = (a - b)/(a + b) < 2^{-27}` and ends with :math:`M = \tfrac{a+b}2 (1 - t^2/4 - 5t^4/64)`, the
expansion of :math:`\pi / (2K(t)) = M(1 + t, 1 - t)`: :math:`K` to about :math:`2^{-104}` relative.
:math:`E = K(1 - \sum_{n\ge0} 2^{n-1}c_n^2)` (A&S 17.6.3-4) with :math:`c_0 = k`,
:math:`c_{n+1} = c_n^2 / (4a_{n+1})` (no cancellation), the sum in double-double as well: near
:math:`k = 1` the bracket is about :math:`1/K` and loses :math:`\log_2 K` bits, which the second double keeps.

The functions take a namespace ``xp`` of :mod:`rigidbody.core.kernel` (``SCALAR`` or ``ARRAY``): one code for
a Python float and for arrays, elementwise.
"""

from __future__ import annotations

import decimal
import functools
import math
from typing import Any

import numpy as np

__all__ = [
    "FIX",
    "FIX_FAST",
    "HALF_PI",
    "PI",
    "T_FAST",
    "agm_dd",
    "agm_steps",
    "complete_dd",
    "dd_div",
    "dd_mul",
    "dd_sqrt",
    "fast_two_sum",
    "k_triple",
    "mc_of_k",
    "reduce_half_period",
    "reduce_phase",
    "times_int",
    "two_prod",
    "two_sum",
    "with_parity",
]


def _dd_const(d: decimal.Decimal) -> tuple[float, float]:
    hi = float(d)
    return hi, float(d - decimal.Decimal(hi))


with decimal.localcontext() as _ctx:
    _ctx.prec = 50
    #: pi as a double-double (40 digits of a Machin-type formula would do; the digits are spelled out)
    _PI_D = decimal.Decimal("3.14159265358979323846264338327950288419716939937510")
    PI = _dd_const(_PI_D)
    HALF_PI = _dd_const(_PI_D / 2)


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


def times_int(j: Any, b: Any, xp: Any) -> tuple[Any, Any]:
    """:func:`two_prod` of an integer-valued ``j`` and ``b``: below ``2^26`` ``j`` needs no splitting (its
    products with the halves of ``b`` are exact)."""
    if not (np.max(np.abs(j), initial=0.0) if xp.array else abs(j)) < 2.0**26:
        return two_prod(j, b)
    p = j * b
    cb = 134217729.0 * b
    bh = cb - (cb - b)
    return p, (j * bh - p) + j * (b - bh)


def fast_two_sum(a: Any, b: Any) -> tuple[Any, Any]:
    """``s + e = a + b`` exactly when ``|a| >= |b|`` (or ``a = 0``)."""
    s = a + b
    return s, b - (s - a)


def _square(a: Any) -> tuple[Any, Any]:
    """``p + e = a^2`` exactly (:func:`two_prod` with one split)."""
    p = a * a
    ca = 134217729.0 * a
    ah = ca - (ca - a)
    al = a - ah
    return p, ((ah * ah - p) + 2.0 * ah * al) + al * al


def dd_mul(ah: Any, al: Any, bh: Any, bl: Any) -> tuple[Any, Any]:
    """The product of two double-doubles (relative error about ``2^-104``)."""
    p, pe = two_prod(ah, bh)
    return fast_two_sum(p, pe + (ah * bl + al * bh))


def dd_div(ah: Any, al: Any, bh: Any, bl: Any) -> tuple[Any, Any]:
    """The quotient of two double-doubles (one correction of the double quotient)."""
    q = ah / bh
    p, pe = two_prod(q, bh)
    return fast_two_sum(q, (((ah - p) - pe) + al - q * bl) / bh)


def dd_sqrt(ah: Any, al: Any, lib: Any) -> tuple[Any, Any]:
    """The square root of a double-double ``a >= 0`` (one Newton correction of the double root)."""
    s = lib.sqrt(ah)
    p, pe = _square(s)
    if lib is math:
        return (s, 0.0) if s == 0.0 else fast_two_sum(s, (((ah - p) - pe) + al) / (2.0 * s))
    with np.errstate(divide="ignore", invalid="ignore"):  # (the root of 0 is 0, 0)
        return fast_two_sum(s, np.where(s == 0.0, 0.0, (((ah - p) - pe) + al) / (2.0 * s)))


def mc_of_k(k: Any) -> tuple[Any, Any]:
    """``1 - k**2`` as a double-double, exact (``k`` in [0, 1])."""
    p, pe = two_prod(k, k)
    s, se = two_sum(1.0, -p)
    return fast_two_sum(s, se - pe)


#: stop the mean once t = (a - b)/(a + b) is below this: the t^6 term of the closing expansion is < 2^-165
_T_STOP = 2.0**-27


def _agm_step(st: tuple[Any, ...], weight: float, with_e: bool, lib: Any) -> tuple[Any, ...]:
    """One step of the mean on the state ``(a, b, c_n^2, S)`` (each a double-double: eight entries)."""
    ah, al, bh, bl, c2h, c2l, sh, sl = st
    nh, nl = fast_two_sum(ah, bh)  # (a >= b)
    nh, nl = fast_two_sum(nh, nl + (al + bl))
    nh, nl = 0.5 * nh, 0.5 * nl  # a_{n+1}
    # b_{n+1} = sqrt(a b): the double root of the product, corrected by (a b - s^2) / (2 s) with a b and s^2
    # exact (a, b > 0 here)
    p, pe = two_prod(ah, bh)
    s = lib.sqrt(p)
    r, re = _square(s)
    bh, bl = fast_two_sum(s, (((p - r) - re) + (pe + (ah * bl + al * bh))) / (2.0 * s))
    if with_e:  # c_{n+1}^2 = (c_n^2 / (4 a_{n+1}))^2, S += 2^n c_{n+1}^2
        c2h, c2l = dd_div(c2h, c2l, 4.0 * nh, 4.0 * nl)
        c2h, c2l = dd_mul(c2h, c2l, c2h, c2l)
        sh, se = two_sum(sh, weight * c2h)
        sl = sl + (se + weight * c2l)
    return nh, nl, bh, bl, c2h, c2l, sh, sl


def _agm_close(st: tuple[Any, ...], t: Any, weight: float) -> tuple[Any, Any, Any, Any]:
    """``(M_hi, M_lo, S_hi, S_lo)`` from a state with ``t < _T_STOP``: the mean closed by the expansion of
    M(1 + t, 1 - t), the sum by the next term c_{N+1} = (a_N - b_N)/2 = t M (later ones below 2^-108)."""
    ah, al, bh, bl, _, _, sh, sl = st
    mh, ml = two_sum(ah, bh)
    mh, ml = fast_two_sum(0.5 * mh, 0.5 * (ml + al + bl))
    x = t * t  # M(1 + t, 1 - t) = 1 - x/4 - 5x^2/64 - 11x^3/256 - ...: to x^7, the rest below 2^-104 for t < 2^-7
    mh, ml = fast_two_sum(mh, ml - mh * (x * (0.25 + x * (0.078125 + x * (0.04296875 + x * (
        0.02862548828125 + x * (0.0210418701171875 + x * (0.016425132751464844 + x * 0.013351678848266602))))))))
    sh, se = two_sum(sh, 2.0 * weight * (t * mh) ** 2)
    return mh, ml, sh, sl + se


#: where the theta route of arrays with a modulus per element closes its mean (two steps fewer than at
#: ``_T_STOP`` for mc >= 0.05): the closing expansion in doubles, x = t^2 rounded, leaves M to about 2^-66
#: relative; ``reduce_phase`` then holds its 2^-55 of zeta where zeta >= (2|j| + 2) 2^-11 pi/2 (the phase
#: |u| M <= (|j| + 1) pi), and the arguments are evaluated again with the full mean where zeta is below
#: (2|j| + 2) FIX_FAST pi/2 (about 1 % of random arguments)
T_FAST = 2.0**-7
FIX_FAST = 2.0**-10


@functools.lru_cache(maxsize=64)
def agm_steps(mc: float, stop: float = _T_STOP) -> int:
    """The steps of the mean from ``(1, sqrt(mc))`` until ``t = (a - b)/(a + b) < _T_STOP`` (the most of any
    larger ``mc``: the mean of ``(1, k')`` converges the faster the larger ``k'``), in doubles: the
    double-double ``t`` differs from it by about 1e-16, which moves the stop only where ``t`` is within 1e-8
    of ``_T_STOP`` relative, and the closing expansion is as good there."""
    a, b, n = 1.0, math.sqrt(mc), 0
    while (a - b) / (a + b) >= stop and n < 64:
        a, b, n = 0.5 * (a + b), math.sqrt(a * b), n + 1
    return n


def agm_dd(mch: Any, mcl: Any, xp: Any, with_e: bool = False, stop: float = _T_STOP) -> tuple[Any, ...]:
    r"""The mean :math:`M(1, k') = \pi/(2K)` as a double-double, for :math:`0 < m_c \le 1`.

    Parameters
    ----------
    mch, mcl : float or numpy.ndarray
        The complementary parameter :math:`m_c = 1 - k^2` as a double-double (``mcl = 0`` for a double);
        floats with ``SCALAR``, 1-D arrays with ``ARRAY``.
    xp : SCALAR or ARRAY
        The namespace (``rigidbody.core.kernel``).
    with_e : bool
        Also return the sum :math:`1 - E/K` as a double-double.
    stop : float
        For arrays, close the mean once :math:`t < ` ``stop`` (default ``2^-27``: :math:`M` to about
        :math:`2^{-104}`; :data:`T_FAST`: about :math:`2^{-66}`).

    Returns
    -------
    tuple
        ``(M_hi, M_lo)``, or ``(M_hi, M_lo, S_hi, S_lo)`` with :math:`S = 1 - E/K`.
    """
    lib = np if xp.array else math
    # k' = sqrt(mc), scaled by an even power of 2 below 2^-900 (the low parts of the products of tiny numbers
    # are subnormal below about 2^-969)
    if (np.min(mch, initial=1.0) if xp.array else mch) < 2.0**-900:
        n = lib.frexp(mch)[1] // 2
        bh, bl = dd_sqrt(lib.ldexp(mch, -2 * n), lib.ldexp(mcl, -2 * n), lib)
        bh, bl = lib.ldexp(bh, n), lib.ldexp(bl, n)
    else:
        bh, bl = dd_sqrt(mch, mcl, lib)
    c2h, c2l = two_sum(1.0, -mch)
    c2h, c2l = fast_two_sum(c2h, c2l - mcl)  # c_0^2 = m; the sum S = 1 - E/K = sum 2^(n-1) c_n^2
    st = (1.0 + 0.0 * bh, 0.0 * bh, bh, bl, c2h, c2l, 0.5 * c2h, 0.5 * c2l)
    weight = 0.5
    if xp.array:  # (arrays) the steps the smallest mc needs, for all: a step on a converged member keeps its
        # mean, and costs less than testing and gathering members (from 3 steps at mc = 1/2 to 11 at 1e-300)
        steps = agm_steps(float(np.min(mch)) if np.size(mch) else 1.0, stop)
        if not with_e and steps:  # the first step in closed form: a_1 = (1 + k')/2, b_1 = sqrt(k')
            ah, al = fast_two_sum(1.0, bh)
            st = (0.5 * ah, 0.5 * (al + bl), *dd_sqrt(bh, bl, lib), c2h, c2l, c2h, c2l)
            weight, steps = 1.0, steps - 1
        for _ in range(steps):
            weight *= 2.0
            st = _agm_step(st, weight, with_e, lib)
        t = ((st[0] - st[2]) + (st[1] - st[3])) / (st[0] + st[2])
        res = _agm_close(st, t, weight)
    else:
        for _ in range(64):
            t = ((st[0] - st[2]) + (st[1] - st[3])) / (st[0] + st[2])
            if t < _T_STOP:
                res = _agm_close(st, t, weight)
                break
            weight *= 2.0
            st = _agm_step(st, weight, with_e, lib)
    return res if with_e else res[:2]


def complete_dd(mch: Any, mcl: Any, xp: Any, with_e: bool = False) -> tuple[Any, ...]:
    r""":math:`K` (and :math:`E` with ``with_e``) as double-doubles, ``(K_hi, K_lo[, E_hi, E_lo])``, for
    :math:`0 < m_c \le 1` (the arguments as in :func:`agm_dd`)."""
    mean = agm_dd(mch, mcl, xp, with_e)
    kh, kl = dd_div(HALF_PI[0], HALF_PI[1], mean[0], mean[1])
    if not with_e:
        return kh, kl
    eh, el = two_sum(1.0, -mean[2])
    eh, el = fast_two_sum(eh, el - mean[3])
    return (kh, kl, *dd_mul(kh, kl, eh, el))


def _atan_inv(x: int, bits: int) -> int:
    """``atan(1/x) 2^bits`` (``x >= 2``) by its alternating series in integers (truncated: a few units low)."""
    term = (1 << bits) // x
    total, n, sign = term, 1, -1
    while term:
        term //= x * x
        n += 2
        total += sign * (term // n)
        sign = -sign
    return total


#: pi 2^_PI_BITS as an integer (Machin's formula, 16 guard bits)
_PI_BITS = 320
_PI_INT = (16 * _atan_inv(5, _PI_BITS + 16) - 4 * _atan_inv(239, _PI_BITS + 16)) >> 16


@functools.lru_cache(maxsize=256)
def k_triple(mch: float, mcl: float, k: float) -> tuple[float, float, float]:
    """:math:`K` of ``mc = mch + mcl`` (exactly), or of the modulus ``k`` if ``k >= 0`` (``mc = 1 - k^2``
    exactly), as three doubles, to about ``2^-160`` relative.

    The mean in fixed-point integer arithmetic, 200 bits (and half the binary exponent of ``mc`` more, for
    the root of a tiny ``mc``), with integer square roots (about 10 microseconds; cached): what the reduction
    of an argument within about ``2^-45 K`` of a multiple of ``K`` needs, where the double-double ``K``
    leaves the distance with too few digits.
    """
    if k >= 0.0:
        n, d = k.as_integer_ratio()
        num, den = d * d - n * n, d * d
    else:
        (n1, d1), (n2, d2) = mch.as_integer_ratio(), mcl.as_integer_ratio()
        den = max(d1, d2)  # (powers of 2)
        num = n1 * (den // d1) + n2 * (den // d2)
    p = 200 + max(0, (den.bit_length() - num.bit_length()) // 2 + 1)
    a, b = 1 << p, math.isqrt((num << (2 * p)) // den)  # 1 and k' = sqrt(mc), times 2^p
    while a - b > 4:  # (then the next mean is within 2^-p of a and b: the error of the roots is a few units)
        a, b = (a + b) >> 1, math.isqrt(a * b)
    rn, rd = (_PI_INT << (p + 200)) // ((a + b) << _PI_BITS), 1 << 200  # K = pi / (2M), M = (a + b)/2
    out = []
    for _ in range(3):  # the double nearest to the rest, three times
        x = rn / rd
        xn, xd = x.as_integer_ratio()
        out.append(x)
        rn, rd = rn * xd - xn * rd, rd * xd
    return out[0], out[1], out[2]


#: the reduced argument v (the distance to a multiple n K, n <= 2|j| + 1) is recomputed with the triple K
#: where |v| < (2|j| + 2) FIX K: the double-double K is within 2^-103 K (measured 6e-32 K), so that elsewhere
#: the error n 2^-103 K of v is below 2^-55 of it; within, the triple K leaves about 2^-100 of v
FIX = 2.0**-48


def _distance(u: Any, n: Any, k3: tuple[Any, Any, Any]) -> Any:
    """``u - n K`` for ``K = k3[0] + k3[1] + k3[2]`` where it is small (a double: its relative error about eps^2)."""
    p1, e1 = two_prod(n, k3[0])
    p2, e2 = two_prod(n, k3[1])
    h, lo = two_sum(u, -p1)
    h, lo2 = two_sum(h, -e1)
    h, lo3 = two_sum(h, -p2)
    return h + (lo + lo2 + lo3 - e2 - n * k3[2])


def reduce_half_period(u: Any, kh: Any, kl: Any, key: tuple[Any, Any, Any], xp: Any) -> tuple[Any, ...]:
    r"""Reduce ``u`` by the half period: :math:`u = 2jK + r`, :math:`|r| \le K`, and the argument of the series.

    Parameters
    ----------
    u : float or numpy.ndarray
        The argument (finite).
    kh, kl : float or numpy.ndarray
        :math:`K` as a double-double.
    key : tuple
        ``(mch, mcl, k)``: the modulus exactly, for :func:`k_triple`.
    xp : SCALAR or ARRAY
        The namespace.

    Returns
    -------
    tuple
        ``(j, sgn, upper, v_hi, v_lo)``: ``sgn`` the sign of ``r``; ``upper`` where :math:`|r| > K/2`, and then
        :math:`v = K - |r|`, else :math:`v = |r|`, as a double-double, to :math:`2^{-55}` of itself: where it is
        below :math:`(2|j| + 2)\,2^{-48}K` (near a zero of sn or cn) it is recomputed from :math:`K` to about
        :math:`2^{-160}` (:func:`k_triple`, a fraction of a millisecond the first time for a modulus), about
        :math:`2^{-100}` of itself for :math:`|j| < 2^{40}`.
    """
    lib = np if xp.array else math
    big = abs(u) > 2.0**50 * kh
    if xp.any(big):  # no digit of the phase is left: reduce by the double 4K first (exact)
        u = xp.where(big, lib.fmod(u, 4.0 * kh), u)
    j = xp.rint(u / (2.0 * kh))
    p, pe = times_int(j, 2.0 * kh, xp)
    rh, e = two_sum(u, -p)
    rh, rl = two_sum(rh, e - pe - j * (2.0 * kl))
    sgn = xp.copysign(1.0, rh)
    ah, al = sgn * rh, sgn * rl
    upper = ah > 0.5 * kh
    vh, vl = two_sum(kh - ah, kl - al)  # K - |r|: the first difference exact where it is used (Sterbenz)
    vh, vl = xp.where(upper, vh, ah), xp.where(upper, vl, al)
    fix = abs(vh) < (2.0 * abs(j) + 2.0) * FIX * kh
    if not xp.any(fix):
        return j, sgn, upper, vh, vl
    idx, v = _near_zero(u, j, sgn, upper, fix, key, xp)
    if not xp.array:
        return j, sgn, upper, v, 0.0
    vh, vl = vh.copy(), vl.copy()
    vh[idx], vl[idx] = v, 0.0
    return j, sgn, upper, vh, vl


def _near_zero(u: Any, j: Any, sgn: Any, upper: Any, fix: Any, key: tuple[Any, Any, Any], xp: Any
               ) -> tuple[Any, Any]:
    """``(idx, v)``: the reduced argument ``v`` recomputed with the triple ``K`` (:func:`k_triple`) where
    ``fix`` (at the indices ``idx`` of arrays; ``idx = None`` for a Python float)."""
    sign = xp.where(upper, -sgn, sgn)  # v = sign (u - n K), n = 2j (+ sgn where upper)
    if not xp.array:
        return None, sign * _distance(u, j * 2.0 + (sgn if upper else 0.0), k_triple(*map(float, key)))
    idx = np.flatnonzero(fix)
    keys = zip(*(np.broadcast_to(v, np.shape(u))[idx].tolist() for v in key))
    trip = np.array([k_triple(*kk) for kk in keys]).reshape(-1, 3)
    n = 2.0 * j[idx] + np.where(upper[idx], sgn[idx], 0.0)
    return idx, sign[idx] * _distance(u[idx], n, (trip[:, 0], trip[:, 1], trip[:, 2]))


def reduce_phase(u: Any, mh: Any, ml: Any, key: tuple[Any, Any, Any], xp: Any) -> tuple[Any, ...]:
    r"""Reduce the phase :math:`\phi = \pi u/(2K) = uM`: :math:`\phi = j\pi + \rho`, :math:`|\rho| \le \pi/2`,
    and the argument :math:`\zeta = \pi v/(2K)` of the theta series, without forming :math:`K`.

    The same reduction as :func:`reduce_half_period` (``r = 2\rho K/\pi``), on the mean
    :math:`M = \pi/(2K)` (a double-double, about :math:`2^{-104}` relative) instead of :math:`K`: the error
    of :math:`\phi` is about :math:`|\phi|\,2^{-103}`, that of :math:`v` was :math:`|2j|\,2^{-103}K`; where
    :math:`\zeta < (2|j| + 2)\,2^{-48}\pi/2` (:math:`v < (2|j| + 2)\,2^{-48}K`, near a zero of sn or cn)
    :math:`v` is recomputed from :math:`K` to about :math:`2^{-160}` (:func:`k_triple`) and multiplied by
    :math:`M`.

    Returns
    -------
    tuple
        ``(j, sgn, upper, zeta_hi, zeta_lo)``: ``sgn`` the sign of :math:`\rho`; ``upper`` where
        :math:`|\rho| > \pi/4`, and then :math:`\zeta = \pi/2 - |\rho|`, else :math:`\zeta = |\rho|`.
    """
    lib = np if xp.array else math
    big = abs(u) * mh > 2.0**50 * HALF_PI[0]
    if xp.any(big):  # no digit of the phase is left: reduce by the double 4K first (exact)
        u = xp.where(big, lib.fmod(u, 4.0 * (HALF_PI[0] / mh)), u)
    ph, pe = two_prod(u, mh)
    ph, pl = fast_two_sum(ph, pe + u * ml)
    j = xp.rint(ph / PI[0])
    p, pe = times_int(j, PI[0], xp)
    rh, e = two_sum(ph, -p)
    rh, rl = two_sum(rh, e + ((pl - pe) - j * PI[1]))
    sgn = xp.copysign(1.0, rh)
    ah, al = sgn * rh, sgn * rl
    upper = ah > 0.5 * HALF_PI[0]
    zh, zl = two_sum(HALF_PI[0] - ah, HALF_PI[1] - al)  # pi/2 - |rho|: the first difference exact where used
    zh, zl = xp.where(upper, zh, ah), xp.where(upper, zl, al)
    fix = abs(zh) < (2.0 * abs(j) + 2.0) * (FIX * HALF_PI[0])
    if not xp.any(fix):
        return j, sgn, upper, zh, zl
    idx, v = _near_zero(u, j, sgn, upper, fix, key, xp)
    if not xp.array:
        return (j, sgn, upper, *dd_mul(v, 0.0, mh, ml))
    zh, zl = zh.copy(), zl.copy()
    zh[idx], zl[idx] = dd_mul(v, 0.0, np.broadcast_to(mh, np.shape(u))[idx], np.broadcast_to(ml, np.shape(u))[idx])
    return j, sgn, upper, zh, zl


def with_parity(j: Any, sn: Any, cn: Any, dn: Any, xp: Any) -> tuple[Any, Any, Any, Any]:
    r"""sn, cn, dn, am at :math:`u = 2jK + r` from sn, cn, dn at ``r``: :math:`(-1)^j` on sn and cn,
    :math:`\operatorname{am} = j\pi + \operatorname{atan2}(\operatorname{sn} r, \operatorname{cn} r)`.
    A value an ulp outside the functions' range (:math:`|\operatorname{sn}|, |\operatorname{cn}|,
    \operatorname{dn} \le 1`: sn rounds to :math:`1 + 2^{-52}` next to the separatrix with some CPUs' sinh, cosh)
    is set on the bound, which is nearer the exact value."""
    sn = xp.where(sn > 1.0, 1.0, xp.where(sn < -1.0, -1.0, sn))
    cn = xp.where(cn > 1.0, 1.0, xp.where(cn < -1.0, -1.0, cn))
    dn = xp.where(dn > 1.0, 1.0, dn)
    par = 1.0 - 4.0 * abs(0.5 * j - xp.rint(0.5 * j))  # (-1)^j (j an integer below 2^52)
    p, pe = times_int(j, PI[0], xp)
    p, pe = fast_two_sum(p, pe + j * PI[1])
    return par * sn, par * cn, dn, p + (pe + xp.atan2(sn, cn))
