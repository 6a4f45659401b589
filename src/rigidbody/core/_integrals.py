r"""Complete and incomplete elliptic integrals :math:`K, E, F, E(\phi)` in the modulus ``k`` or ``mc``.

Public in :mod:`rigidbody.core.elliptic`, whose docstring states their accuracy; this module holds their
implementation.
"""

from __future__ import annotations

import functools
from typing import Any

import numpy as np

from ._carlson import THIRD, rf_rd_dd
from ._modulus import ArrayLike, array_modulus, as_float_array, float_out, scalar_modulus
from ._periods import PI, complete_dd, dd_mul, dd_sqrt, fast_two_sum, two_prod, two_sum
from .kernel import ARRAY, SCALAR


@functools.lru_cache(maxsize=256)
def _complete_cached(mch: float, mcl: float) -> tuple[float, float]:
    """``(K, E)`` of one modulus, rounded once from their double-doubles (``K = inf``, ``E = 1`` at ``mc = 0``)."""
    if mch == 0.0:
        return float("inf"), 1.0
    kh, _, eh, _ = complete_dd(mch, mcl, SCALAR, with_e=True)
    return kh, eh


def complete(k: ArrayLike | None, mc: ArrayLike | None) -> tuple[Any, Any]:
    """``(K, E)`` of the modulus ``k`` (``m = k**2`` exactly) or of ``mc`` (see :func:`K`), floats or arrays."""
    mod = scalar_modulus(k, mc)
    if mod is not None:
        return _complete_cached(mod[1], mod[2])
    _, mch, mcl, _ = array_modulus(k, mc)
    mch, mcl = np.broadcast_arrays(mch, mcl)
    if mch.size and mch.min() == mch.max() and mcl.min() == mcl.max():
        ke = _complete_cached(float(mch.flat[0]), float(mcl.flat[0]))
        return float_out(np.full(mch.shape, ke[0])), float_out(np.full(mch.shape, ke[1]))
    kk, ee = np.full(mch.shape, np.inf), np.ones(mch.shape)
    pos = mch > 0.0
    kh, _, eh, _ = complete_dd(mch[pos], mcl[pos], ARRAY, with_e=True)
    kk[pos], ee[pos] = kh, eh
    return float_out(kk), float_out(ee)


# --------------------------------------------------------------------------------------------------
# complete and incomplete integrals
# --------------------------------------------------------------------------------------------------
def K(k: ArrayLike | None = None, *, mc: ArrayLike | None = None) -> Any:
    r"""Complete elliptic integral of the first kind :math:`K(k)=\int_0^{\pi/2}(1-k^2\sin^2\phi)^{-1/2}d\phi`.

    Parameters
    ----------
    k : array_like, optional
        Modulus in [0, 1].
    mc : array_like, optional
        Complementary parameter :math:`1-k^2` (more accurate near :math:`k=1`).

    Returns
    -------
    float or numpy.ndarray
        :math:`K`; ``inf`` at :math:`k = 1`.

    See Also
    --------
    E : the complete integral of the second kind.
    F : the incomplete integral, :math:`K(k) = F(\pi/2, k)`.
    jacobi : the Jacobi functions, of period :math:`4K`.

    References
    ----------
    NIST Digital Library of Mathematical Functions, §19.2(ii) (Legendre's integrals) and §19.12 (the
    asymptotic form :math:`K \approx \ln(4/k')` as :math:`k \to 1`).

    Examples
    --------
    >>> import math
    >>> from rigidbody.core.elliptic import K
    >>> print(f"{K(0.0):.12f}")  # pi/2
    1.570796326795

    The lemniscatic case :math:`k^2 = 1/2`, where :math:`K = \Gamma(1/4)^2/(4\sqrt\pi)`:

    >>> print(f"{K(math.sqrt(0.5)):.12f} {math.gamma(0.25)**2 / (4 * math.sqrt(math.pi)):.12f}")
    1.854074677301 1.854074677301

    Near the separatrix give ``mc = 1 - k**2``: :math:`K = \ln(4/k') + O(m_c\ln m_c)`, here
    :math:`k' = 10^{-6}`:

    >>> print(f"{K(mc=1e-12):.9f} {math.log(4e6):.9f}")
    15.201804919 15.201804919
    """
    return complete(k, mc)[0]


def E(k: ArrayLike | None = None, *, mc: ArrayLike | None = None) -> Any:
    r"""Complete elliptic integral of the second kind :math:`E(k)=\int_0^{\pi/2}(1-k^2\sin^2\phi)^{1/2}d\phi`.

    Parameters
    ----------
    k : array_like, optional
        Modulus in [0, 1].
    mc : array_like, optional
        Complementary parameter :math:`1-k^2`.

    Returns
    -------
    float or numpy.ndarray
        :math:`E`, with :math:`E(1) = 1`.

    See Also
    --------
    K : the complete integral of the first kind.
    Einc : the incomplete integral, :math:`E(k) = E(\pi/2, k)`.

    References
    ----------
    NIST Digital Library of Mathematical Functions, §19.2(ii) (Legendre's integrals) and §19.7(i)
    (Legendre's relation :math:`EK' + E'K - KK' = \pi/2`).

    Examples
    --------
    >>> import math
    >>> from rigidbody.core.elliptic import E, K
    >>> print(f"{E(0.0):.12f} {E(1.0):.12f}")  # pi/2 and 1
    1.570796326795 1.000000000000

    Legendre's relation at :math:`k = k' = 1/\sqrt2`, :math:`2EK - K^2 = \pi/2`:

    >>> k = math.sqrt(0.5)
    >>> print(f"{2 * E(k) * K(k) - K(k)**2:.12f} {math.pi / 2:.12f}")
    1.570796326795 1.570796326795
    """
    return complete(k, mc)[1]


def _add(a: tuple[Any, Any], b: tuple[Any, Any]) -> tuple[Any, Any]:
    s, e = two_sum(a[0], b[0])
    return fast_two_sum(s, e + (a[1] + b[1]))


def incomplete(phi: ArrayLike, k: ArrayLike | None, mc: ArrayLike | None, second: bool) -> Any:
    r""":math:`F(\phi, k)` or (``second``) :math:`E(\phi, k)`, rounded once from double-doubles.

    :math:`\phi = j\pi + \phi_r`, :math:`|\phi_r| \le \pi/2`, reduced with :math:`\pi` as a double-double;
    :math:`F = s R_F(c^2, \Delta^2, 1) + 2jK` and :math:`E = s R_F - \tfrac{m}{3}s^3 R_D(c^2, \Delta^2, 1) + 2jE`
    (DLMF 19.25.5, 19.25.7) with :math:`s, c = \sin\phi_r, \cos\phi_r` and
    :math:`\Delta^2 = c^2 + m_c s^2` (exact in :math:`m_c`), Carlson's integrals in double-double
    (``rigidbody.core._carlson``): what is left is the rounding of ``sin``, ``cos`` and of the result.
    """
    ph = as_float_array(phi, "phi")
    if not np.all(np.isfinite(ph)):
        raise ValueError("phi must be finite")
    parts = np.broadcast_arrays(ph, *array_modulus(k, mc))
    shape = parts[0].shape
    ph, _, mch, mcl, _ = (np.ascontiguousarray(p, dtype=float).ravel() for p in parts)
    if not ph.size:
        return np.empty(shape)
    j = np.rint(ph / np.pi)
    p, pe = two_prod(j, PI[0])
    rh, e = two_sum(ph, -p)
    rh, rl = two_sum(rh, e - pe - j * PI[1])
    sh, ch = np.sin(rh), np.cos(rh)
    s, c = sh + ch * rl, ch - sh * rl
    # s^2 + c^2 = 1 exactly: the smaller of s^2, c^2 from its own function, the larger as 1 less it (a
    # rounded sin beside a rounded cos would move phi by ulp(s)/c, which E(phi) feels near pi/2)
    near = abs(s) > abs(c)
    sm = np.where(near, c, s)
    a2 = two_prod(sm, sm)
    b2 = two_sum(1.0, -a2[0])
    b2 = fast_two_sum(b2[0], b2[1] - a2[1])
    s2 = tuple(np.where(near, b, a) for b, a in zip(b2, a2))
    c2 = tuple(np.where(near, a, b) for b, a in zip(b2, a2))
    root = dd_sqrt(s2[0], s2[1], np)
    sd = (np.where(near, np.copysign(root[0], s), s), np.where(near, np.copysign(root[1], s), 0.0))
    d2 = _add(c2, dd_mul(mch, mcl, *s2))
    sing = d2[0] == 0.0  # k = 1 and |phi_r| = pi/2: F infinite, E(phi_r) = sin(phi_r)
    one = np.ones_like(ph)
    x = (np.where(sing, 1.0, c2[0]), np.where(sing, 0.0, c2[1]))  # (k = 1, |phi_r| = pi/2: finite stand-ins)
    y = (np.where(sing, 1.0, d2[0]), np.where(sing, 0.0, d2[1]))
    ints = rf_rd_dd(x, y, (one, 0.0 * one), ARRAY, second)
    val = dd_mul(*sd, ints[0], ints[1])
    if second:
        mm = two_sum(1.0, -mch)
        mm = fast_two_sum(mm[0], mm[1] - mcl)
        t = dd_mul(*dd_mul(*dd_mul(*mm, *THIRD), *sd), *s2)
        t = dd_mul(*t, ints[2], ints[3])
        val = _add(val, (-t[0], -t[1]))
    out = val[0] + val[1]
    with np.errstate(invalid="ignore"):
        out = np.where(sing, s if second else np.copysign(np.inf, s), out)
        if np.any(j != 0):
            out = np.where(j != 0, out + 2.0 * j * _periods_dd(mch, mcl, second), out)
    return float_out(out.reshape(shape))


def _periods_dd(mch: np.ndarray, mcl: np.ndarray, second: bool) -> np.ndarray:
    """K (or E) rounded from its double-double, elementwise (inf or 1 where mc = 0)."""
    pos = mch > 0.0
    v = complete_dd(np.where(pos, mch, 1.0), np.where(pos, mcl, 0.0), ARRAY, with_e=second)
    return np.where(pos, (v[2] + v[3]) if second else (v[0] + v[1]), 1.0 if second else np.inf)


def F(phi: ArrayLike, k: ArrayLike | None = None, *, mc: ArrayLike | None = None) -> Any:
    r"""Incomplete elliptic integral of the first kind :math:`F(\phi,k)=\int_0^\phi(1-k^2\sin^2t)^{-1/2}dt`.

    Valid for any real :math:`\phi` (quasi-periodicity :math:`F(\phi+j\pi)=F(\phi)+2jK`).

    Parameters
    ----------
    phi : array_like
        Amplitude (radians).
    k : array_like, optional
        Modulus in [0, 1].
    mc : array_like, optional
        Complementary parameter :math:`1-k^2`.

    Returns
    -------
    float or numpy.ndarray
        :math:`F(\phi, k)`; infinite at :math:`k=1`, :math:`|\phi|\ge\pi/2`.

    See Also
    --------
    K : the complete integral, :math:`F(\pi/2, k)`.
    Einc : the incomplete integral of the second kind.
    am : the inverse function, :math:`\operatorname{am}(F(\phi, k), k) = \phi`.

    References
    ----------
    NIST Digital Library of Mathematical Functions, §19.2(ii) (Legendre's integrals) and §19.25(i) (the
    same in Carlson's :math:`R_F`).

    Examples
    --------
    >>> import math
    >>> from rigidbody.core.elliptic import F, K, am
    >>> print(f"{F(0.7, 0.0):.12f}")  # k = 0: F = phi
    0.700000000000
    >>> print(f"{F(1.0, 1.0):.12f} {math.atanh(math.sin(1.0)):.12f}")  # k = 1: the inverse Gudermannian
    1.226191170884 1.226191170884
    >>> print(f"{F(math.pi / 2, 0.6):.12f} {K(0.6):.12f}")  # F(pi/2, k) = K(k)
    1.750753802916 1.750753802916
    >>> print(f"{am(F(1.0, 0.6), 0.6):.12f}")
    1.000000000000
    """
    return incomplete(phi, k, mc, second=False)


def Einc(phi: ArrayLike, k: ArrayLike | None = None, *, mc: ArrayLike | None = None) -> Any:
    r"""Incomplete elliptic integral of the second kind :math:`E(\phi,k)=\int_0^\phi(1-k^2\sin^2t)^{1/2}dt`.

    Valid for any real :math:`\phi` (:math:`E(\phi+j\pi)=E(\phi)+2jE`).

    Parameters
    ----------
    phi : array_like
        Amplitude (radians).
    k : array_like, optional
        Modulus in [0, 1].
    mc : array_like, optional
        Complementary parameter :math:`1-k^2`.

    Returns
    -------
    float or numpy.ndarray
        :math:`E(\phi, k)`.

    See Also
    --------
    E : the complete integral, :math:`E(\pi/2, k)`.
    F : the incomplete integral of the first kind.

    References
    ----------
    NIST Digital Library of Mathematical Functions, §19.2(ii) (Legendre's integrals) and §19.25(i) (the
    same in Carlson's :math:`R_F`, :math:`R_D`).

    Examples
    --------
    >>> import math
    >>> from rigidbody.core.elliptic import E, Einc
    >>> print(f"{Einc(1.0, 1.0):.12f} {math.sin(1.0):.12f}")  # k = 1: E(phi, 1) = sin(phi)
    0.841470984808 0.841470984808
    >>> print(f"{Einc(math.pi / 2, 0.6):.12f} {E(0.6):.12f}")
    1.418083394449 1.418083394449
    >>> print(f"{Einc(math.pi + 0.3, 0.6) - Einc(0.3, 0.6):.12f} {2 * E(0.6):.12f}")  # one period: 2E
    2.836166788897 2.836166788897
    """
    return incomplete(phi, k, mc, second=True)
