r"""Complete and incomplete elliptic integrals :math:`K, E, F, E(\phi)` in the modulus ``k`` or ``mc``.

Public in :mod:`rigidbody.core.elliptic`, whose docstring states their accuracy; this module holds their
implementation.
"""

from __future__ import annotations

import functools
from typing import Any

import numpy as np
from scipy import special

from ._modulus import ArrayLike, array_modulus, as_float_array, float_out, moduli, scalar_modulus
from ._periods import complete_dd
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


def _reduce_phi(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """phi = j*pi + phr with |phr| <= pi/2."""
    j = np.round(phi / np.pi)
    return j, phi - j * np.pi


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
    ph = as_float_array(phi, "phi")
    _, mca, _ = moduli(k, mc)
    j, phr = _reduce_phi(ph)
    s, c = np.sin(phr), np.cos(phr)
    c2 = c * c
    delta2 = c2 + mca * (s * s)  # 1 - m sin^2, exact in mc
    with np.errstate(divide="ignore", invalid="ignore"):
        val = s * special.elliprf(c2, delta2, 1.0)
        if np.any(j != 0):  # (only there: 0 * K = NaN at k = 1)
            val = np.where(j != 0, val + 2.0 * j * complete(k, mc)[0], val)
    # k = 1, |phi| = pi/2 exactly: R_F(0, 0, 1) = inf -> F = +-inf (correct); no NaN can arise otherwise.
    return float_out(val)


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
    ph = as_float_array(phi, "phi")
    m, mca, _ = moduli(k, mc)
    j, phr = _reduce_phi(ph)
    s, c = np.sin(phr), np.cos(phr)
    c2 = c * c
    delta2 = c2 + mca * (s * s)
    sing = (mca == 0.0) & (c2 == 0.0)  # R_F and R_D both diverge; E(+-pi/2, 1) = +-1
    if np.any(sing):
        c2 = np.where(sing, 1.0, c2)
        delta2 = np.where(sing, 1.0, delta2)
    val = s * special.elliprf(c2, delta2, 1.0) - m / 3.0 * s**3 * special.elliprd(c2, delta2, 1.0)
    if np.any(sing):
        val = np.where(sing, s, val)
    if np.any(j != 0):
        val = val + 2.0 * j * complete(k, mc)[1]
    return float_out(val)
