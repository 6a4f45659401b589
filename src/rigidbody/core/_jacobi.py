r"""The Jacobi functions of :mod:`rigidbody.core.elliptic`: the two routes, their constants, one point or arrays.

* :math:`m_c \ge 0.05`: theta series in the nome (``rigidbody.core._theta``);
* :math:`0 < m_c < 0.05`: hyperbolic series in the complementary nome (``rigidbody.core._nome``);
* :math:`m_c = 0`: :math:`\tanh`, :math:`\operatorname{sech}` and the Gudermannian.

Both series take the argument reduced by ``rigidbody.core._periods.reduce_half_period`` with :math:`K` as a
double-double. The modulus is exact as given: ``mc`` itself, or :math:`k` with :math:`m = k^2` and
:math:`m_c = 1 - k^2` formed exactly (``mc_of_k``), so the functions are those of the float inputs, without
the rounding of :math:`k^2` (which moves :math:`K`, and the zeros, by up to :math:`\varepsilon K/m_c`).
"""

from __future__ import annotations

import functools
import math
from typing import Any

import numpy as np

from ._nome import jacobi_near, nome
from ._periods import complete_dd
from ._theta import MC_THETA, jacobi_theta, jacobi_theta_float, theta_consts
from .kernel import ARRAY, SCALAR

__all__ = ["jacobi_arrays", "jacobi_scalar"]


def _consts(m: Any, mch: Any, mcl: Any, xp: Any, near: bool) -> tuple[Any, ...]:
    """The constants of one route (elementwise for arrays)."""
    if near:
        return nome(m, mch, xp, mcl) + complete_dd(mch, mcl, xp)
    return theta_consts(m, mch, mcl, xp)


@functools.lru_cache(maxsize=256)
def _consts_cached(m: float, mch: float, mcl: float) -> tuple[Any, ...]:
    """:func:`_consts` of one modulus in Python floats, cached (an integrator's right-hand side calls with the
    same modulus again and again; the constants cost about 30 us)."""
    return _consts(m, mch, mcl, SCALAR, mch < MC_THETA)


def _separatrix(u: Any, xp: Any) -> tuple[Any, Any, Any, Any]:
    """k = 1: sn = tanh, cn = dn = sech, am = gd (2 atan(tanh(u/2)))."""
    lib = np if xp.array else math
    e = lib.exp(-abs(u))
    sech = 2.0 * e / (1.0 + e * e)
    return lib.tanh(u), sech, sech, 2.0 * lib.atan(lib.tanh(0.5 * u))


def jacobi_scalar(u: float, m: float, mch: float, mcl: float, k: float) -> tuple[float, float, float, float]:
    """sn, cn, dn, am of one point in Python floats (``k = -1`` when the modulus is given by ``mc``)."""
    if mch == 0.0:
        return _separatrix(u, SCALAR)
    consts = _consts_cached(m, mch, mcl)
    if mch < MC_THETA:
        s, c, d, a = jacobi_near(u, m, mch, consts, (mch, mcl, k), SCALAR)
    else:
        s, c, d, a = jacobi_theta_float(u, consts, (mch, mcl, k))
    return float(s), float(c), float(d), float(a)


def jacobi_arrays(u: np.ndarray, m: np.ndarray, mch: np.ndarray, mcl: np.ndarray, k: np.ndarray
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """sn, cn, dn, am of 1-D arrays of one length (``k = -1`` where the modulus is given by ``mc``).

    One modulus for all points: its constants once (cached), broadcast; several: the constants elementwise.
    """
    if mch.size and mch.min() == mch.max() and mcl.min() == mcl.max() and k.min() == k.max():
        mc0, key = float(mch[0]), (float(mch[0]), float(mcl[0]), float(k[0]))
        if mc0 == 0.0:
            return _separatrix(u, ARRAY)
        consts = _consts_cached(float(m[0]), mc0, key[1])
        if mc0 < MC_THETA:
            return jacobi_near(u, float(m[0]), mc0, consts, key, ARRAY)
        return jacobi_theta(u, consts, key, ARRAY)
    out = tuple(np.empty_like(u) for _ in range(4))
    sep, near = mch == 0.0, (mch > 0.0) & (mch < MC_THETA)
    for sel, route in ((sep, "sep"), (near, "near"), (mch >= MC_THETA, "theta")):
        if not np.any(sel):
            continue
        us, ms, hs, ls, ks = u[sel], m[sel], mch[sel], mcl[sel], k[sel]
        if route == "sep":
            vals = _separatrix(us, ARRAY)
        elif route == "near":
            vals = jacobi_near(us, ms, hs, _consts(ms, hs, ls, ARRAY, True), (hs, ls, ks), ARRAY)
        else:
            vals = jacobi_theta(us, _consts(ms, hs, ls, ARRAY, False), (hs, ls, ks), ARRAY)
        for o, v in zip(out, vals):
            o[sel] = v
    return out  # type: ignore[return-value]
