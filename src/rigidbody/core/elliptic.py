r"""Jacobi elliptic functions and elliptic integrals in the **modulus** ``k``.

The papers write :math:`\operatorname{sn}(u, k)`, :math:`K(k)`, :math:`E(k)` with the modulus ``k``;
SciPy uses the *parameter* :math:`m = k^2` (``scipy.special.ellipj(u, m)``, ``ellipk(m)``). This module is
the one place where that conversion happens: every other module calls these functions with ``k``.

Near the separatrix (:math:`k \to 1`) the number :math:`m = k^2` stored as a double has lost the digits of
:math:`m_c = 1 - k^2` that fix the period :math:`4K \approx 4\ln(4/k')`. Every function therefore also
accepts the complementary parameter ``mc`` (keyword); pass it whenever you have it. When both ``k`` and
``mc`` are given they must agree to 1e-12.

Accuracy
--------
* ``K``, ``E``, ``F``, ``Einc`` use Carlson's symmetric integrals (``scipy.special.elliprf``/``elliprd``)
  written in ``mc``, accurate to a few ulp including :math:`m_c \to 0`.
* ``jacobi`` reduces the argument by the period :math:`4K` and by the symmetries
  :math:`u \mapsto 2K-u` and :math:`u \mapsto K-u` (the latter through
  :math:`\operatorname{sn}(K-x)=\operatorname{cd}x`, :math:`\operatorname{cn}(K-x)=k'\operatorname{sd}x`,
  :math:`\operatorname{dn}(K-x)=k'\operatorname{nd}x`) to :math:`0\le x\le K/2`, where it evaluates the
  descending-Landen/AGM scheme itself with :math:`b_0 = \sqrt{m_c}` (exact in ``mc``) when
  :math:`m_c \le 10^{-9}` and ``scipy.special.ellipj`` otherwise. This avoids SciPy issue 8480
  (``ellipj`` returns values up to 1e26 for :math:`1-m \le 10^{-9}`, :math:`u > K`).
* :math:`k = 1` exactly: :math:`\operatorname{sn}=\tanh u`, :math:`\operatorname{cn}=\operatorname{dn}
  =\operatorname{sech}u`, :math:`\operatorname{am}=\operatorname{gd}u`, :math:`K=\infty`, :math:`E=1`.

Invalid input (``k`` outside [0, 1], non-finite, non-numeric) raises instead of returning NaN.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy import special

__all__ = [
    "E",
    "Einc",
    "F",
    "K",
    "am",
    "check_modulus",
    "cn",
    "dn",
    "jacobi",
    "sn",
]

ArrayLike = Any

#: Below this complementary parameter the AGM is run with the exact ``mc`` instead of SciPy's ``ellipj``
#: (cephes switches to a first-order expansion in ``mc`` at 1e-10, see the module docstring).
_MC_OWN_AGM = 1e-9


def _out(x: np.ndarray) -> Any:
    """Scalar in, Python float out; arrays stay arrays."""
    return float(x) if np.ndim(x) == 0 else x


def _as_float_array(x: ArrayLike, name: str) -> np.ndarray:
    try:
        a = np.asarray(x, dtype=float)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{name} must be a real number or an array of real numbers, got {x!r}") from exc
    return a


def check_modulus(k: ArrayLike, name: str = "k") -> np.ndarray:
    """Validate a modulus (or complementary parameter) and return it as a float array.

    Parameters
    ----------
    k : array_like
        Values that must lie in the closed interval [0, 1] and be finite.
    name : str
        Parameter name used in the error message.

    Returns
    -------
    numpy.ndarray
        ``k`` as a float array.

    Raises
    ------
    TypeError
        If ``k`` is not numeric.
    ValueError
        If any value is NaN or lies outside [0, 1].
    """
    a = _as_float_array(k, name)
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite and in [0, 1]; got a non-finite value")
    if np.any(a < 0.0) or np.any(a > 1.0):
        bad = a[(a < 0.0) | (a > 1.0)].ravel()[0]
        raise ValueError(f"{name} must lie in [0, 1] (modulus convention, m = k**2); got {bad!r}")
    return a


def _m_mc(k: ArrayLike | None, mc: ArrayLike | None) -> tuple[np.ndarray, np.ndarray]:
    """Return the parameter ``m = k**2`` and its complement ``mc = 1 - m`` (validated)."""
    if k is None and mc is None:
        raise TypeError("give the modulus k or the complementary parameter mc = 1 - k**2")
    if mc is not None:
        mca = check_modulus(mc, "mc")
        if k is not None:
            ka = check_modulus(k, "k")
            if np.any(np.abs(ka * ka + mca - 1.0) > 1e-12):
                raise ValueError("k and mc are inconsistent: k**2 + mc must equal 1 (to 1e-12)")
            m = ka * ka
        else:
            m = 1.0 - mca
        return m, mca
    ka = check_modulus(k, "k")
    m = ka * ka
    return m, 1.0 - m


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
    """
    _, mca = _m_mc(k, mc)
    return _out(special.ellipkm1(mca))


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
    """
    m, mca = _m_mc(k, mc)
    # E = R_F(0, mc, 1) - m/3 R_D(0, mc, 1); both terms diverge at mc = 0, where E = 1.
    safe = np.where(mca > 0.0, mca, 1.0)
    val = special.elliprf(0.0, safe, 1.0) - m / 3.0 * special.elliprd(0.0, safe, 1.0)
    return _out(np.where(mca > 0.0, val, 1.0))


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
    """
    ph = _as_float_array(phi, "phi")
    m, mca = _m_mc(k, mc)
    ph, m, mca = np.broadcast_arrays(ph, m, mca)
    j, phr = _reduce_phi(ph)
    s, c = np.sin(phr), np.cos(phr)
    c2 = c * c
    delta2 = c2 + mca * s * s  # 1 - m sin^2, exact in mc
    with np.errstate(divide="ignore", invalid="ignore"):
        val = s * special.elliprf(c2, delta2, 1.0)
        kk = special.ellipkm1(mca)
        val = np.where(j != 0, val + 2.0 * j * kk, val)
    # k = 1, |phi| = pi/2 exactly: R_F(0, 0, 1) = inf -> F = +-inf (correct); no NaN can arise otherwise.
    return _out(val)


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
    """
    ph = _as_float_array(phi, "phi")
    m, mca = _m_mc(k, mc)
    ph, m, mca = np.broadcast_arrays(ph, m, mca)
    j, phr = _reduce_phi(ph)
    s, c = np.sin(phr), np.cos(phr)
    c2 = c * c
    delta2 = c2 + mca * s * s
    sing = (mca == 0.0) & (c2 == 0.0)  # R_F and R_D both diverge; E(+-pi/2, 1) = +-1
    c2s = np.where(sing, 1.0, c2)
    d2s = np.where(sing, 1.0, delta2)
    val = s * special.elliprf(c2s, d2s, 1.0) - m / 3.0 * s**3 * special.elliprd(c2s, d2s, 1.0)
    val = np.where(sing, s, val)
    safe = np.where(mca > 0.0, mca, 1.0)
    ecomp = np.where(
        mca > 0.0, special.elliprf(0.0, safe, 1.0) - m / 3.0 * special.elliprd(0.0, safe, 1.0), 1.0
    )
    val = val + 2.0 * j * ecomp
    return _out(val)


# --------------------------------------------------------------------------------------------------
# Jacobi functions
# --------------------------------------------------------------------------------------------------
def _agm_jacobi(x: np.ndarray, m: np.ndarray, mca: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """sn, cn, dn by the descending Landen (AGM) scheme with b0 = sqrt(mc) exact; for 0 <= x <= K/2."""
    a = np.ones_like(x)
    b = np.sqrt(mca)
    c = np.sqrt(m)
    A = [a]
    C = [c]
    for _ in range(80):
        if np.all(np.abs(C[-1]) <= 1e-17 * A[-1]):
            break
        a_new = 0.5 * (a + b)
        c_new = 0.5 * (a - b)
        b = np.sqrt(a * b)
        a = a_new
        A.append(a)
        C.append(c_new)
    n = len(A) - 1
    phi = (2.0**n) * A[-1] * x
    for i in range(n, 0, -1):
        phi = 0.5 * (np.arcsin(C[i] * np.sin(phi) / A[i]) + phi)
    snv = np.sin(phi)
    cnv = np.cos(phi)
    dnv = np.sqrt(mca + m * cnv * cnv)  # dn^2 = mc + m cn^2: a sum of positives, no cancellation
    return snv, cnv, dnv


def _jacobi_base(x: np.ndarray, m: np.ndarray, mca: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """sn, cn, dn for 0 <= x <= K/2 (finite K)."""
    snv = np.empty_like(x)
    cnv = np.empty_like(x)
    dnv = np.empty_like(x)
    own = mca <= _MC_OWN_AGM
    if np.any(~own):
        s_, c_, d_, _ = special.ellipj(x[~own], m[~own])
        snv[~own], cnv[~own], dnv[~own] = s_, c_, d_
    if np.any(own):
        s_, c_, d_ = _agm_jacobi(x[own], m[own], mca[own])
        snv[own], cnv[own], dnv[own] = s_, c_, d_
    return snv, cnv, dnv


def _sech(u: np.ndarray) -> np.ndarray:
    e = np.exp(-np.abs(u))
    return 2.0 * e / (1.0 + e * e)


def jacobi(u: ArrayLike, k: ArrayLike | None = None, *, mc: ArrayLike | None = None) -> tuple[Any, Any, Any, Any]:
    r"""Jacobi elliptic functions :math:`\operatorname{sn}, \operatorname{cn}, \operatorname{dn}` and the amplitude.

    Parameters
    ----------
    u : array_like
        Argument (any real value; reduced by the period internally).
    k : array_like, optional
        Modulus in [0, 1] (the papers' convention; SciPy's parameter is :math:`m = k^2`).
    mc : array_like, optional
        Complementary parameter :math:`1-k^2`; pass it near the separatrix.

    Returns
    -------
    sn, cn, dn, am : float or numpy.ndarray
        Broadcast to the common shape of the inputs. ``am`` is continuous and increasing in ``u``
        (:math:`\operatorname{am}(u+2K)=\operatorname{am}(u)+\pi`).

    Examples
    --------
    >>> from rigidbody.core.elliptic import jacobi
    >>> s, c, d, a = jacobi(0.3, 0.5)
    >>> abs(s**2 + c**2 - 1) < 1e-15 and abs(d**2 + 0.25 * s**2 - 1) < 1e-15
    True
    """
    ua = _as_float_array(u, "u")
    if not np.all(np.isfinite(ua)):
        raise ValueError("u must be finite")
    m, mca = _m_mc(k, mc)
    ua, m, mca = np.broadcast_arrays(ua, m, mca)
    shape = ua.shape
    ua, m, mca = ua.ravel(), m.ravel(), mca.ravel()
    snv = np.empty_like(ua)
    cnv = np.empty_like(ua)
    dnv = np.empty_like(ua)
    amv = np.empty_like(ua)

    sep = mca == 0.0
    if np.any(sep):
        us = ua[sep]
        snv[sep] = np.tanh(us)
        cnv[sep] = dnv[sep] = _sech(us)
        amv[sep] = 2.0 * np.arctan(np.tanh(0.5 * us))
    per = ~sep
    if np.any(per):
        up, mp, mcp = ua[per], m[per], mca[per]
        kk = special.ellipkm1(mcp)
        kp = np.sqrt(mcp)
        # 1) reduce by the period 4K:  ur in [-2K, 2K]
        ur = up - 4.0 * kk * np.round(up / (4.0 * kk))
        sgn = np.where(ur < 0.0, -1.0, 1.0)
        a = np.abs(ur)
        # 2) u -> 2K - u  (sn, dn even about K; cn odd)
        far = a > kk
        csgn = np.where(far, -1.0, 1.0)
        a = np.where(far, 2.0 * kk - a, a)
        a = np.clip(a, 0.0, kk)
        # 3) u -> K - u for the upper half of [0, K]
        upper = a > 0.5 * kk
        x = np.where(upper, kk - a, a)
        s0, c0, d0 = _jacobi_base(x, mp, mcp)
        s1 = np.where(upper, c0 / d0, s0)
        c1 = np.where(upper, kp * s0 / d0, c0)
        d1 = np.where(upper, kp / d0, d0)
        snp = sgn * s1
        cnp = csgn * c1
        snv[per], cnv[per], dnv[per] = snp, cnp, d1
        # amplitude: am(u) = j*pi + am(u - 2jK), |u - 2jK| <= K where cn >= 0
        j = np.round(up / (2.0 * kk))
        par = np.where(np.mod(j, 2.0) == 0.0, 1.0, -1.0)
        amv[per] = j * np.pi + np.arctan2(par * snp, np.abs(par * cnp) * 1.0)
    out = tuple(_out(v.reshape(shape)) for v in (snv, cnv, dnv, amv))
    return out


_JACOBI_PARAMS = """
    Parameters
    ----------
    u : array_like
        Argument (any real value; reduced by the period internally).
    k : array_like, optional
        Modulus in [0, 1] (SciPy's parameter is ``m = k**2``).
    mc : array_like, optional
        Complementary parameter ``1 - k**2``; pass it near the separatrix.

    Returns
    -------
    float or numpy.ndarray
        Broadcast over the inputs; see :func:`jacobi` for the accuracy and the conventions.
    """


def _jacobi_doc(func: Any) -> Any:
    """Append the shared Parameters/Returns sections to a single-function Jacobi docstring."""
    func.__doc__ = (func.__doc__ or "").rstrip() + "\n" + _JACOBI_PARAMS
    return func


@_jacobi_doc
def sn(u: ArrayLike, k: ArrayLike | None = None, *, mc: ArrayLike | None = None) -> Any:
    """Jacobi ``sn(u, k)`` in the modulus ``k``.

    """
    return jacobi(u, k, mc=mc)[0]


@_jacobi_doc
def cn(u: ArrayLike, k: ArrayLike | None = None, *, mc: ArrayLike | None = None) -> Any:
    """Jacobi ``cn(u, k)`` in the modulus ``k``.

    """
    return jacobi(u, k, mc=mc)[1]


@_jacobi_doc
def dn(u: ArrayLike, k: ArrayLike | None = None, *, mc: ArrayLike | None = None) -> Any:
    """Jacobi ``dn(u, k)`` in the modulus ``k``.

    """
    return jacobi(u, k, mc=mc)[2]


@_jacobi_doc
def am(u: ArrayLike, k: ArrayLike | None = None, *, mc: ArrayLike | None = None) -> Any:
    """Jacobi amplitude ``am(u, k)``, continuous and increasing in ``u`` in the modulus ``k``.

    """
    return jacobi(u, k, mc=mc)[3]
