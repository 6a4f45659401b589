r"""Carlson's symmetric integrals :math:`R_F` and :math:`R_D` in double-double arithmetic (the incomplete
integrals of :mod:`rigidbody.core.elliptic` to an ulp).

Carlson's duplication (B. C. Carlson, "Numerical computation of real or complex elliptic integrals", Numer.
Algorithms 10, 1995; DLMF 19.36(i)): with :math:`\lambda = \sqrt{xy} + \sqrt{yz} + \sqrt{zx}`, the
integrals are unchanged by :math:`(x, y, z) \to ((x + \lambda)/4, (y + \lambda)/4, (z + \lambda)/4)`
(:math:`R_D` gains :math:`3/(\sqrt z (z + \lambda))` per step), and the deviations
:math:`X = 1 - x/A` shrink by 4 per step. The steps run in double-double until every deviation is below
:math:`2^{-18}`, and the series of DLMF 19.36.1-2 to fifth order closes them (the sixth-order terms are
below :math:`2^{-108}`). ``SciPy``'s ``elliprf`` is a few ulp off (2.4 measured), which with the roundings of
its arguments made :math:`F` 3 ulp off; here the arguments are double-doubles as well.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

import numpy as np

from ._periods import dd_div, dd_mul, dd_sqrt, fast_two_sum, two_sum

__all__ = ["FIFTH", "THIRD", "rf_rd_dd"]

#: 1/3 and 1/5 as double-doubles
THIRD = (1.0 / 3.0, float(Fraction(1, 3) - Fraction(1.0 / 3.0)))
FIFTH = (0.2, float(Fraction(1, 5) - Fraction(0.2)))

_DEV_STOP = 2.0**-18


def _add(ah: Any, al: Any, bh: Any, bl: Any) -> tuple[Any, Any]:
    s, e = two_sum(ah, bh)
    return fast_two_sum(s, e + (al + bl))


def rf_rd_dd(x: tuple[Any, Any], y: tuple[Any, Any], z: tuple[Any, Any], xp: Any, with_rd: bool
             ) -> tuple[Any, ...]:
    r""":math:`R_F(x, y, z)` (and :math:`R_D(x, y, z)` with ``with_rd``) as double-doubles.

    Parameters
    ----------
    x, y, z : tuple
        Double-doubles ``(hi, lo)``, non-negative, at most one zero (for :math:`R_D`, ``z > 0``); floats with
        ``SCALAR``, arrays of one shape with ``ARRAY``.
    xp : SCALAR or ARRAY
        The namespace (``rigidbody.core.kernel``).
    with_rd : bool
        Also compute :math:`R_D`.

    Returns
    -------
    tuple
        ``(RF_hi, RF_lo)`` or ``(RF_hi, RF_lo, RD_hi, RD_lo)``.
    """
    lib = np if xp.array else math
    (xh, xl), (yh, yl), (zh, zl) = x, y, z
    acc_h, acc_l, scale = 0.0 * xh, 0.0 * xh, 1.0  # R_D: 3 sum 4^-n / (sqrt z_n (z_n + lambda_n))
    for _ in range(60):
        ah = (xh + yh + (3.0 if with_rd else 1.0) * zh) / (5.0 if with_rd else 3.0)
        dev = xp.maximum(xp.maximum(abs(ah - xh), abs(ah - yh)), abs(ah - zh)) / ah
        if (float(np.max(dev)) if xp.array else dev) <= _DEV_STOP:
            break
        sx, sy, sz = dd_sqrt(xh, xl, lib), dd_sqrt(yh, yl, lib), dd_sqrt(zh, zl, lib)
        lam = _add(*dd_mul(*sx, *sy), *dd_mul(*sz, *_add(*sx, *sy)))
        if with_rd:
            t = dd_div(3.0 * scale, 0.0, *dd_mul(*sz, *_add(zh, zl, *lam)))
            acc_h, acc_l = _add(acc_h, acc_l, *t)
        scale *= 0.25
        xh, xl = _add(xh, xl, *lam)
        yh, yl = _add(yh, yl, *lam)
        zh, zl = _add(zh, zl, *lam)
        xh, xl, yh, yl, zh, zl = (0.25 * v for v in (xh, xl, yh, yl, zh, zl))
    return _close(xh, xl, yh, yl, zh, zl, xp, with_rd, (acc_h, acc_l, scale))


def _close(xh: Any, xl: Any, yh: Any, yl: Any, zh: Any, zl: Any, xp: Any, with_rd: bool,
           rd_acc: tuple[Any, Any, float]) -> tuple[Any, ...]:
    """The series of DLMF 19.36.1 (and 19.36.2) at the last point of the duplication."""
    lib = np if xp.array else math
    sh, sl = _add(*_add(xh, xl, yh, yl), zh, zl)
    a_f = dd_mul(sh, sl, *THIRD)
    dx = ((a_f[0] - xh) + (a_f[1] - xl)) / a_f[0]
    dy = ((a_f[0] - yh) + (a_f[1] - yl)) / a_f[0]
    dz = -dx - dy
    e2, e3 = dx * dy - dz * dz, dx * dy * dz
    small = -e2 / 10.0 + e3 / 14.0 + e2 * e2 / 24.0 - 3.0 * e2 * e3 / 44.0
    root = dd_sqrt(*a_f, lib)
    rh, rl = dd_div(1.0, 0.0, *root)
    rf = fast_two_sum(rh, rl + rh * small)
    if not with_rd:
        return rf
    acc_h, acc_l, scale = rd_acc
    a_d = dd_mul(*_add(*_add(xh, xl, yh, yl), 3.0 * zh, 3.0 * zl), *FIFTH)
    dx = ((a_d[0] - xh) + (a_d[1] - xl)) / a_d[0]
    dy = ((a_d[0] - yh) + (a_d[1] - yl)) / a_d[0]
    dz = -(dx + dy) / 3.0
    xy, z2 = dx * dy, dz * dz
    e2, e3 = xy - 6.0 * z2, (3.0 * xy - 8.0 * z2) * dz
    e4, e5 = 3.0 * (xy - z2) * z2, xy * z2 * dz
    small = (-3.0 * e2 / 14.0 + e3 / 6.0 + 9.0 * e2 * e2 / 88.0 - 3.0 * e4 / 22.0 - 9.0 * e2 * e3 / 52.0
             + 3.0 * e5 / 26.0)
    root = dd_sqrt(*a_d, lib)
    tail = dd_div(scale, 0.0, *dd_mul(*a_d, *root))  # 4^-N A^(-3/2)
    tail = fast_two_sum(tail[0], tail[1] + tail[0] * small)
    return (*rf, *_add(acc_h, acc_l, *tail))
