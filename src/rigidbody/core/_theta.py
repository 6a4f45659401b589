r"""Jacobi functions away from the separatrix (:math:`m_c \ge 0.05`) by theta series in the nome.

With the nome :math:`q = e^{-\pi K'/K}` (:math:`q \le 0.18` here) and :math:`\zeta = \pi v/(2K)`, the theta
functions (DLMF 20.2.1-4, divided by :math:`2q^{1/4}` for :math:`\vartheta_1, \vartheta_2`) are

.. math::
    S = \sum_{n\ge0}(-1)^n q^{n(n+1)}\sin(2n+1)\zeta,\quad C = \sum_{n\ge0}q^{n(n+1)}\cos(2n+1)\zeta,\quad
    D = \vartheta_4(\zeta),\quad N = \vartheta_3(\zeta),

and DLMF 22.2.4-6 with the constants fixed by :math:`\operatorname{sn}(K) = \operatorname{cn}(0) =
\operatorname{dn}(0) = 1` give, for :math:`0 \le v \le K/2` (with :math:`T_1 = C(0)`, :math:`T_3 = N(0)`,
:math:`T_4 = D(0)`),

.. math::
    \operatorname{sn}v = \frac{T_3}{T_1}\frac{S}{D},\quad \operatorname{cn}v = \frac{T_4}{T_1}\frac{C}{D},\quad
    \operatorname{dn}v = \frac{T_4}{T_3}\frac{N}{D},\qquad
    \operatorname{sn}(K-v) = \frac{T_3}{T_1}\frac{C}{N},\quad \operatorname{cn}(K-v) = \frac{T_4}{T_1}\frac{S}{N},
    \quad \operatorname{dn}(K-v) = \frac{T_4}{T_3}\frac{D}{N}

(the second three are :math:`\operatorname{cd}v`, :math:`k'\operatorname{sd}v`, :math:`k'\operatorname{nd}v`
with :math:`k' = (T_4/T_3)^2`). On :math:`0 \le \zeta \le \pi/4` every factor is a sum whose first term
dominates: :math:`S/\sin\zeta`, :math:`C/\cos\zeta`, :math:`D` and :math:`N` are :math:`1 + ` polynomials in
:math:`x = \cos 2\zeta` with coefficients of order :math:`q^2`, :math:`q^2`, :math:`q` and :math:`q` (the
Dirichlet kernel :math:`\sin(2n+1)\zeta / \sin\zeta = 1 + 2\sum_{j\le n}\cos 2j\zeta` and Chebyshev's
:math:`\cos 2j\zeta = T_j(x)`), truncated after :math:`q^{20}` and :math:`q^{16}` (the first omitted terms,
:math:`q^{30}` and :math:`q^{25}`, are below :math:`2^{-60}` at :math:`q = 0.18`). Each function is a ratio of two
such factors times a constant: a few roundings, so a few ulp relative, near the zeros included.

The argument is reduced in double-double arithmetic by the half period :math:`2K`, and by :math:`v = K - |r|`
beyond :math:`K/2`, with :math:`K = \pi/(2M)` from the double-double mean ``rigidbody.core._periods.agm_dd``
(about :math:`2^{-104}` relative); :math:`\zeta = vM` is carried as a double-double into :math:`\sin` and
:math:`\cos`. Arrays reduce the phase :math:`uM` by :math:`\pi` instead (``reduce_phase``: the same
:math:`\zeta`, without the division that forms :math:`K`), with a modulus per element from a mean closed two
steps early (:math:`M` to about :math:`2^{-66}`: the relative error of :math:`\zeta` stays below
:math:`2^{-55}` down to :math:`\zeta = (2|j| + 2)2^{-11}\pi/2`; below :math:`(2|j| + 2)2^{-10}\pi/2`, about one
random argument in a hundred, am is NaN and the caller evaluates again with the full mean). The relative error near a
zero :math:`nK` is a few ulp plus :math:`n\,\delta_K / |u - nK|`, :math:`\delta_K \approx 2^{-104}K` the
error of the period (the argument ``u`` is taken as exact).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ._periods import (
    FIX,
    FIX_FAST,
    HALF_PI,
    PI,
    T_FAST,
    agm_dd,
    dd_div,
    dd_mul,
    reduce_phase,
    two_prod,
    two_sum,
    with_parity,
)
from .kernel import SCALAR

__all__ = ["MC_THETA", "jacobi_theta", "jacobi_theta_float", "theta_consts"]

#: the smallest complementary parameter of this route (q = 0.179 there); below it ``rigidbody.core._nome``
MC_THETA = 0.05
#: the nome series in lambda^4 (A&S 17.3.21; OEIS A002103): q = lambda (1 + 2 l^4 + 15 l^8 + ...), the
#: 11th term (9481557398 l^40) is below 2^-66 of the first at lambda = 0.179 (mc = 0.05): far below the
#: rounding of q, which enters the functions through coefficients of order q
_NOME_COEFFS = (1.0, 2.0, 15.0, 150.0, 1707.0, 20910.0, 268616.0, 3567400.0, 48555069.0, 673458874.0)


def theta_consts(m: Any, mch: Any, mcl: Any, xp: Any, early: bool = False) -> tuple[Any, ...]:
    r"""What :func:`jacobi_theta` needs of one modulus (elementwise for arrays), :math:`m_c \ge 0.05`.

    Returns
    -------
    tuple
        ``(K_hi, K_lo, M_hi, M_lo, cs, cc, cd, cs - 1, cc - 1, sig, dlt, m, early)``: :math:`K` and
        :math:`M = \pi/(2K)` as double-doubles (for arrays :math:`K` as a double, ``K_lo = 0``, since they
        reduce the phase by :math:`M`, and :math:`M` from the mean closed early, about :math:`2^{-66}`
        relative: ``early`` is true), the constants :math:`T_3/T_1, T_4/T_1, T_4/T_3`, the first two less one
        (formed without cancellation) and the coefficients (of :math:`x^0 \dots x^4`) of :math:`S/\sin\zeta - 1` and
        :math:`D - 1` (:math:`C/\cos\zeta - 1` and :math:`N - 1` are the same polynomials at :math:`-x`:
        :math:`\zeta \to \pi/2 - \zeta`).
    """
    lib = np if xp.array else math
    mh, ml = agm_dd(mch, mcl, xp, stop=T_FAST) if early else agm_dd(mch, mcl, xp)  # (early: arrays only)
    # (arrays reduce the phase by the mean, ``reduce_phase``, and need K only to its double)
    kh, kl = (HALF_PI[0] / mh, 0.0 * mh) if xp.array else dd_div(HALF_PI[0], HALF_PI[1], mh, ml)
    kp = lib.sqrt(mch)
    skp = lib.sqrt(kp)
    lam = m / (2.0 * (1.0 + kp) * (1.0 + skp) ** 2)  # (1 - sqrt k') / (2 (1 + sqrt k')), no cancellation
    l4 = (lam * lam) ** 2
    acc = 0.0 * lam
    for c in _NOME_COEFFS[:0:-1]:
        acc = (acc + c) * l4
    q = lam + lam * acc
    q2 = q * q
    q4 = q2 * q2
    q6, q9 = q4 * q2, q4 * q4 * q
    q12 = q6 * q6
    q16 = q12 * q4
    q20 = q16 * q4
    t1m = q2 + q6 + q12 + q20  # T1 - 1
    t3m = 2.0 * (q + q4 + q9 + q16)  # T3 - 1
    t4m = 2.0 * (q4 + q16 - q - q9)  # T4 - 1
    t1, t3, t4 = 1.0 + t1m, 1.0 + t3m, 1.0 + t4m
    sig = (-q2 - q6 + q12 + q20, -2.0 * q2 + 2.0 * q6 + 4.0 * q12 - 4.0 * q20, 4.0 * q6 - 4.0 * q12 - 12.0 * q20,
           -8.0 * q12 + 8.0 * q20, 16.0 * q20)
    dlt = (-2.0 * q4 + 2.0 * q16, -2.0 * q + 6.0 * q9, 4.0 * q4 - 16.0 * q16, -8.0 * q9, 16.0 * q16)
    cd = skp  # T4 / T3 = sqrt(k') (from mc itself: two roundings)
    return kh, kl, mh, ml, t3 / t1, t4 / t1, cd, (t3m - t1m) / t1, (t4m - t1m) / t1, sig, dlt, m, early and xp.array


def _poly(c: tuple[Any, ...], x: Any) -> Any:
    """``c[0] + c[1] x + ... + c[4] x^4`` (Horner)."""
    return c[0] + x * (c[1] + x * (c[2] + x * (c[3] + x * c[4])))


def _assemble(consts: tuple[Any, ...], sgn: Any, bases: tuple[Any, Any], polys: tuple[Any, Any, Any, Any]
              ) -> tuple[Any, Any, Any]:
    """sn, cn, dn of the reduced argument from the bases (sin, cos swapped beyond K/2) and the polynomials
    (P of sn's base, of cn's base, of the denominator, of dn's numerator): lower, sn = cs S/D, cn = cc C/D;
    upper, sn = cs C/N, cn = cc S/N. Each is base (1 + w) with w = ((A - 1) + A P - Q) / (1 + Q) small: one
    rounding on top of the error of sin or cos."""
    cs, cc, cd, cs1, cc1 = consts[4:9]
    (bs, bc), (ps, pc, pd, pn) = bases, polys
    den = 1.0 + pd
    return (sgn * (bs + bs * ((cs1 + cs * ps - pd) / den)), bc + bc * ((cc1 + cc * pc - pd) / den),
            cd * (1.0 + (pn - pd) / den))


#: below this sn^2 (lower branch) cn and dn are taken from sn: their error is then at most a tenth of sn's
#: (|d cn / cn| = sn^2/cn^2 |d sn / sn|, as much for dn) plus a rounding, and cn(0) = dn(0) = 1 exactly
_SN2_SMALL = 0.1


def _from_sn(sn: Any, cn: Any, dn: Any, m: Any, small: Any, xp: Any) -> tuple[Any, Any]:
    """cn = sqrt((1 - sn)(1 + sn)), dn = sqrt(1 - m sn^2) where ``small``, else cn, dn as they are."""
    if not xp.array:
        return (math.sqrt((1.0 - sn) * (1.0 + sn)), math.sqrt(1.0 - m * (sn * sn))) if small else (cn, dn)
    with np.errstate(invalid="ignore"):  # (where |sn| rounds above 1 the root is NaN, and not taken)
        return np.where(small, np.sqrt((1.0 - sn) * (1.0 + sn)), cn), np.where(small, np.sqrt(1.0 - m * (sn * sn)), dn)


def _zeta(vh: Any, vl: Any, consts: tuple[Any, ...], lib: Any) -> tuple[Any, Any, Any]:
    """sin and cos of zeta = pi v / (2K) (v a double-double) and x = cos 2 zeta."""
    return _sincos(*dd_mul(vh, vl, consts[2], consts[3]), lib)


def _sincos(zh: Any, zl: Any, lib: Any) -> tuple[Any, Any, Any]:
    """sin and cos of zeta (a double-double) and x = cos 2 zeta."""
    sz, cz = lib.sin(zh), lib.cos(zh)
    s, c = sz + cz * zl, cz - sz * zl
    return s, c, 1.0 - 2.0 * (s * s)


def jacobi_theta(u: Any, consts: tuple[Any, ...], key: tuple[Any, Any, Any], xp: Any) -> tuple[Any, Any, Any, Any]:
    """sn, cn, dn, am for ``mc >= MC_THETA`` (``consts = theta_consts(...)``, ``key`` the modulus exactly: see
    ``rigidbody.core._periods.reduce_half_period``), ``u`` finite; arrays (any ``xp``). With the constants of
    a mean closed early (``theta_consts(..., early=True)``, arrays) am is NaN where zeta is below
    ``(2|j| + 2) FIX_FAST pi/2``: those points are to be evaluated again with the full mean."""
    sig, dlt = consts[9:11]
    j, sgn, upper, zh, zl = reduce_phase(u, consts[2], consts[3], key, xp)
    s, c, x = _sincos(zh, zl, np if xp.array else math)
    # beyond K/2 the roles of sin and cos, and of x and -x, swap: one flip of x, the polynomials at +-x from
    # their even and odd parts
    w = xp.where
    x = w(upper, -x, x)
    x2 = x * x
    se, so = sig[0] + x2 * (sig[2] + x2 * sig[4]), x * (sig[1] + x2 * sig[3])
    de, do = dlt[0] + x2 * (dlt[2] + x2 * dlt[4]), x * (dlt[1] + x2 * dlt[3])
    sn, cn, dn = _assemble(consts, sgn, (w(upper, c, s), w(upper, s, c)), (se + so, se - so, de + do, de - do))
    cn, dn = _from_sn(sn, cn, dn, consts[11], ~upper & (sn * sn < _SN2_SMALL), xp)
    out = with_parity(j, sn, cn, dn, xp)
    if consts[12]:  # the mean closed early: am is NaN where zeta is too small for it, the caller's mark to redo
        redo = abs(zh) < (2.0 * abs(j) + 2.0) * (FIX_FAST * HALF_PI[0])
        return out[0], out[1], out[2], np.where(redo, np.nan, out[3])
    return out


def jacobi_theta_float(u: float, consts: tuple[Any, ...], key: tuple[float, float, float]
                       ) -> tuple[float, float, float, float]:
    """:func:`jacobi_theta` for one Python float, written with branches (the right-hand sides of integrators
    call it: twice as fast as the namespace form)."""
    kh, kl = consts[0], consts[1]
    if not abs(u) <= 2.0**30 * kh:  # (far periods and the near-zero fix-up: the general reduction)
        return jacobi_theta(u, consts, key, SCALAR)
    j = float(round(u / (2.0 * kh)))
    p, pe = two_prod(j, 2.0 * kh)
    rh, e = two_sum(u, -p)
    rh, rl = two_sum(rh, e - pe - j * (2.0 * kl))
    sgn = -1.0 if rh < 0.0 else 1.0
    ah, al = sgn * rh, sgn * rl
    upper = ah > 0.5 * kh
    vh, vl = two_sum(kh - ah, kl - al) if upper else (ah, al)
    if abs(vh) < (2.0 * abs(j) + 2.0) * FIX * kh:
        return jacobi_theta(u, consts, key, SCALAR)
    s, c, x = _zeta(vh, vl, consts, math)
    sig, dlt = consts[9:11]
    ps, pc, pd, pn = _poly(sig, x), _poly(sig, -x), _poly(dlt, x), _poly(dlt, -x)
    if upper:
        sn, cn, dn = _assemble(consts, sgn, (c, s), (pc, ps, pn, pd))
    else:
        sn, cn, dn = _assemble(consts, sgn, (s, c), (ps, pc, pd, pn))
        if sn * sn < _SN2_SMALL:
            cn, dn = _from_sn(sn, cn, dn, consts[11], True, SCALAR)
    if j == 0.0:
        return sn, cn, dn, math.atan2(sn, cn)
    p, pe = two_prod(j, PI[0])
    am = p + ((pe + j * PI[1]) + math.atan2(sn, cn))
    return (sn, cn, dn, am) if j % 2.0 == 0.0 else (-sn, -cn, dn, am)
