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
from collections.abc import Callable
from typing import Any

import numpy as np

from ._modulus import of_k
from ._nome import jacobi_near, nome
from ._periods import complete_dd
from ._theta import MC_THETA, jacobi_theta, jacobi_theta_float, theta_consts
from .kernel import ARRAY, SCALAR

__all__ = ["BLOCK", "blockwise", "jacobi_arrays", "jacobi_scalar"]


def _consts(m: Any, mch: Any, mcl: Any, xp: Any, near: bool, early: bool = False) -> tuple[Any, ...]:
    """The constants of one route (elementwise for arrays; ``early``: the theta route's mean closed early)."""
    if near:
        return nome(m, mch, xp, mcl) + complete_dd(mch, mcl, xp)
    return theta_consts(m, mch, mcl, xp, early)


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


#: the block of elements the array evaluation takes at a time: its few dozen temporaries (128 KB each) then
#: stay in the cache, several times faster per operation than arrays of megabytes, and the Python cost of an
#: operation (about a microsecond) stays a small part of its work
BLOCK = 2**14


def blockwise(f: Callable[..., tuple[Any, ...]], arrays: tuple[np.ndarray, ...], nout: int
              ) -> tuple[np.ndarray, ...]:
    """``f(*arrays)`` (elementwise, ``nout`` arrays out) block by block over 1-D arrays of one length."""
    n = arrays[0].size
    if n <= BLOCK:
        return tuple(f(*arrays))
    out = tuple(np.empty(n) for _ in range(nout))
    for i in range(0, n, BLOCK):
        for o, v in zip(out, f(*(a[i:i + BLOCK] for a in arrays))):
            o[i:i + BLOCK] = v
    return out


def _moduli(mod: np.ndarray, by_k: bool) -> tuple[np.ndarray, ...]:
    """``(m, mc_hi, mc_lo, k)`` of a block of moduli ``k`` (``by_k``) or complementary parameters."""
    if by_k:
        return of_k(mod)
    return 1.0 - mod, mod, np.zeros_like(mod), np.full_like(mod, -1.0)


def _theta_filled(u: np.ndarray, mod: np.ndarray, theta: np.ndarray, by_k: bool) -> tuple[Any, ...]:
    """The theta route on a block with the mean closed early (am NaN where that is not enough), its other
    members at k = 3/4 or mc = 1/2 (their values are replaced afterwards)."""
    filled = mod.copy()
    filled[~theta] = 0.75 if by_k else 0.5
    m, mch, mcl, k = _moduli(filled, by_k)
    return jacobi_theta(u, _consts(m, mch, mcl, ARRAY, False, early=True), (mch, mcl, k), ARRAY)


def _route(u: np.ndarray, mod: np.ndarray, by_k: bool, near: bool) -> tuple[Any, ...]:
    """sn, cn, dn, am of a block on one route, a modulus per element."""
    m, mch, mcl, k = _moduli(mod, by_k)
    consts = _consts(m, mch, mcl, ARRAY, near)
    if near:
        return jacobi_near(u, m, mch, consts, (mch, mcl, k), ARRAY)
    return jacobi_theta(u, consts, (mch, mcl, k), ARRAY)


def jacobi_arrays(u: np.ndarray, mod: np.ndarray, by_k: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """sn, cn, dn, am of 1-D arrays of one length: the argument and the modulus ``k`` (``by_k``) or the
    complementary parameter ``mc`` (valid).

    One modulus for all points: its constants once (cached), broadcast; several: the constants elementwise,
    each route on its members (gathered, so that a route with a few members costs a few blocks), or, where
    the theta route has most members, on the whole array. Everything block by block (:func:`blockwise`).
    """
    if mod.size and mod.min() == mod.max():
        m, mch, mcl, k = (float(x[0]) for x in _moduli(mod[:1], by_k))
        if mch == 0.0:
            return blockwise(lambda x: _separatrix(x, ARRAY), (u,), 4)  # type: ignore[return-value]
        consts, key = _consts_cached(m, mch, mcl), (mch, mcl, k)
        if mch < MC_THETA:
            return blockwise(lambda x: jacobi_near(x, m, mch, consts, key, ARRAY), (u,), 4)  # type: ignore[return-value]
        return blockwise(lambda x: jacobi_theta(x, consts, key, ARRAY), (u,), 4)  # type: ignore[return-value]
    # the routes (1 - k^2 rounded: both series hold a little beyond their boundary mc = 0.05)
    mc = 1.0 - mod * mod if by_k else mod
    theta = mc >= MC_THETA
    routes: list[tuple[np.ndarray, str]] = [(mod == 1.0 if by_k else mod == 0.0, "sep")]
    routes.append((~theta & ~routes[0][0], "near"))
    if 2 * np.count_nonzero(theta) >= u.size:  # mostly theta: no gathering of arguments nor scattering of values
        out = list(blockwise(lambda x, y, z: _theta_filled(x, y, z, by_k), (u, mod, theta), 4))
        routes.append((theta & np.isnan(out[3]), "theta"))  # (near the zeros: again with the full mean)
    else:
        out = [np.empty_like(u) for _ in range(4)]
        routes.append((theta, "theta"))
    vals: tuple[Any, ...]
    for sel, route in routes:
        idx = np.flatnonzero(sel)
        if not idx.size:
            continue
        if route == "sep":
            vals = _separatrix(u[idx], ARRAY)
        else:
            vals = blockwise(functools.partial(_route, by_k=by_k, near=route == "near"), (u[idx], mod[idx]), 4)
        for o, v in zip(out, vals):
            o[idx] = v
    return out[0], out[1], out[2], out[3]
