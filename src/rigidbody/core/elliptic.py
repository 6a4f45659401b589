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
* ``K`` is ``scipy.special.ellipk(k**2)`` (cephes forms :math:`1-m` itself, exactly for :math:`m\ge 1/2`) or
  ``ellipkm1(mc)``; ``E`` is ``scipy.special.ellipe(m)``, :math:`m = k^2` or :math:`1 - m_c`: 2 ulp from
  ``k``, 4 ulp from ``mc`` down to :math:`m_c = 10^{-20}` (``E`` is well conditioned in :math:`m_c`; Carlson's
  :math:`R_F - \frac{m}{3}R_D` loses ~50 ulp there to cancellation).
* ``F``, ``Einc`` use Carlson's symmetric integrals (``scipy.special.elliprf``/``elliprd``) written in
  ``mc``, accurate to a few ulp including :math:`m_c \to 0`.
* ``jacobi`` away from the separatrix (:math:`1-k^2 \ge 0.01` given ``k``, :math:`\ge 0.05` given ``mc``)
  calls ``scipy.special.ellipj`` on the argument as given and forms
  :math:`\operatorname{dn} = (m_c + m\operatorname{cn}^2)^{1/2}`, a sum of positives (SciPy's
  :math:`\operatorname{dn} = \operatorname{cn}/\cos(\varphi-\varphi_1)` loses relative accuracy where
  :math:`\operatorname{cn}\to 0`). Closer to the separatrix it sums the series in the complementary nome
  :math:`q_1 = e^{-\pi K/K'} \approx m_c/16` (Jacobi's imaginary transformation of the Fourier series; sums
  of positive hyperbolic terms, three of them for :math:`m_c \le 10^{-12}`) on the argument reduced in
  double-double arithmetic by the half period :math:`2K` and by :math:`u \mapsto K-u`
  (:math:`\operatorname{sn}(K-x)=\operatorname{cd}x`, :math:`\operatorname{cn}(K-x)=k'\operatorname{sd}x`,
  :math:`\operatorname{dn}(K-x)=k'\operatorname{nd}x`), with the period exact in ``mc``
  (``rigidbody.core._nome``). ``sn``, ``cn``, ``dn`` keep a relative accuracy of a few ulp down to
  :math:`m_c = 10^{-300}` and below (tested against mpmath at 1e-13), also where they are tiny (``dn``
  down to :math:`k' = \sqrt{m_c}`, ``cn`` and ``sn`` near their zeros at odd and even multiples :math:`nK`):
  there the relative error is :math:`n\delta/|u - nK|`, :math:`\delta` the error of the reduced argument per
  quarter period, ~1e-23 for :math:`m_c \le 10^{-8}` and below :math:`10^{-15}m_c` above (the float ``u``
  is taken as exact). This also avoids SciPy issue 8480 (``ellipj`` returns values up to 1e26 for
  :math:`1-m \le 10^{-9}`, :math:`u > K`).
* :math:`k = 1` exactly: :math:`\operatorname{sn}=\tanh u`, :math:`\operatorname{cn}=\operatorname{dn}
  =\operatorname{sech}u`, :math:`\operatorname{am}=\operatorname{gd}u`, :math:`K=\infty`, :math:`E=1`.

Cost: a Python float in gives a Python float out without array overhead (the right-hand sides of
integrators); on arrays away from the separatrix the functions cost what the SciPy calls cost plus a few
array operations, near it about what ``ellipj`` costs there (``benchmarks/bench_core.py``).

Invalid input (``k`` outside [0, 1], non-finite, non-numeric) raises instead of returning NaN.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from scipy import special

from . import kernel
from ._integrals import E, Einc, F, K
from ._modulus import ArrayLike, as_float_array, check_modulus, float_out, is_real_scalar, moduli
from ._nome import jacobi_near, nome, nome_cached

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

#: At and above this complementary parameter :func:`jacobi` calls ``scipy.special.ellipj`` on the argument
#: as given (no period reduction), with ``dn^2 = mc + m cn^2``; below it, the period-reduced evaluation with
#: the exact ``mc``. Given ``mc``, SciPy sees ``m = 1 - mc`` rounded by eps/2, a period wrong by ~eps/mc: the
#: functions move by ~1e-15 at mc = 0.05 and dn, through cn ~ sqrt(mc), by up to ~eps / mc^(3/2) relative;
#: given ``k``, ``m = k**2`` is the parameter itself and only SciPy's own rounding is left, a few ulp times
#: the number of periods (tests/core/test_elliptic.py::test_jacobi_from_mc_to_the_rounding_of_u).
_MC_JACOBI_FROM_MC = 5e-2
_MC_JACOBI_FROM_K = 1e-2
#: beyond this abs(u) SciPy's AGM phase 2^n a u overflows to NaN: such an argument (no digit of its phase is
#: left) is reduced by fmod(u, 4K) first; the near-separatrix route reduces every argument itself
_U_HUGE = 1e300

_ellipk = special.ellipk
_ellipj = special.ellipj


def m_mc(k: ArrayLike | None, mc: ArrayLike | None) -> tuple[np.ndarray, np.ndarray]:
    """Return the parameter ``m = k**2`` and its complement ``mc = 1 - m`` (validated)."""
    m, mca, _ = moduli(k, mc)
    return m, mca


# --------------------------------------------------------------------------------------------------
# Jacobi functions
# --------------------------------------------------------------------------------------------------
def _sech(u: np.ndarray) -> np.ndarray:
    e = np.exp(-np.abs(u))
    return 2.0 * e / (1.0 + e * e)


def _jacobi_reduced(ua: np.ndarray, m: np.ndarray, mca: np.ndarray
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """sn, cn, dn, am of 1-D arrays near the separatrix (mc <= 0.05; mc = 0: the hyperbolic limits)."""
    out = tuple(np.empty_like(ua) for _ in range(4))
    sep = mca == 0.0
    if np.any(sep):
        us = ua[sep]
        for o, v in zip(out, (np.tanh(us), _sech(us), _sech(us), 2.0 * np.arctan(np.tanh(0.5 * us)))):
            o[sep] = v
    per = ~sep
    if np.any(per):
        up, mp, mcp = ua[per], m[per], mca[per]
        if mcp.size > 1 and mcp.min() == mcp.max():  # one modulus: its constants once
            mp, mcp = mp[:1], mcp[:1]
        for o, v in zip(out, jacobi_near(up, mp, mcp, nome(mp, mcp, kernel.ARRAY), kernel.ARRAY)):
            o[per] = v
    return out  # type: ignore[return-value]


def _jacobi_reduced_scalar(u: float, m: float, mc: float) -> tuple[float, float, float, float]:
    """:func:`_jacobi_reduced` for one point in Python floats (the array route costs ~100 us per call)."""
    if mc == 0.0:
        e = math.exp(-abs(u))
        sech = 2.0 * e / (1.0 + e * e)
        return math.tanh(u), sech, sech, 2.0 * math.atan(math.tanh(0.5 * u))
    s, c, d, a = jacobi_near(u, m, mc, nome_cached(m, mc), kernel.SCALAR)
    return float(s), float(c), float(d), float(a)


def jacobi(u: ArrayLike, k: ArrayLike | None = None, *, mc: ArrayLike | None = None) -> tuple[Any, Any, Any, Any]:
    r"""Jacobi elliptic functions :math:`\operatorname{sn}, \operatorname{cn}, \operatorname{dn}` and the amplitude.

    Parameters
    ----------
    u : array_like
        Argument (any finite real value).
    k : array_like, optional
        Modulus in [0, 1] (the papers' convention; SciPy's parameter is :math:`m = k^2`).
    mc : array_like, optional
        Complementary parameter :math:`1-k^2`; pass it near the separatrix.

    Returns
    -------
    sn, cn, dn, am : float or numpy.ndarray
        Broadcast to the common shape of the inputs. ``am`` is continuous and increasing in ``u``
        (:math:`\operatorname{am}(u+2K)=\operatorname{am}(u)+\pi`).

    See Also
    --------
    sn, cn, dn, am : the four functions one at a time.
    K : the quarter period.
    rigidbody.core.averaging.jacobi_average : period means of functions of sn, cn, dn.

    References
    ----------
    NIST Digital Library of Mathematical Functions, §22.2 (definitions), §22.5 (special values and the limits
    :math:`k \to 0, 1`), §22.6(i) (:math:`\operatorname{sn}^2 + \operatorname{cn}^2 = 1`,
    :math:`k^2\operatorname{sn}^2 + \operatorname{dn}^2 = 1`) and §22.16(i) (the amplitude).

    Examples
    --------
    >>> import math
    >>> from rigidbody.core.elliptic import K, jacobi
    >>> s, c, d, a = jacobi(0.3, 0.5)
    >>> abs(s**2 + c**2 - 1) < 1e-15 and abs(d**2 + 0.25 * s**2 - 1) < 1e-15
    True

    At the quarter period :math:`\operatorname{sn} = 1`, :math:`\operatorname{dn} = k' = \sqrt{1 - k^2}`,
    :math:`\operatorname{am} = \pi/2`:

    >>> s, c, d, a = jacobi(K(0.6), 0.6)
    >>> print(f"{s:.12f} {d:.12f} {a:.12f}")
    1.000000000000 0.800000000000 1.570796326795

    The limits: circular functions at :math:`k = 0`, hyperbolic at :math:`k = 1`:

    >>> print(*(f"{x:.12f}" for x in jacobi(1.0, 0.0)))  # sin 1, cos 1, 1, 1
    0.841470984808 0.540302305868 1.000000000000 1.000000000000
    >>> print(*(f"{x:.12f}" for x in jacobi(1.0, 1.0)[:2]), f"{math.tanh(1.0):.12f} {1 / math.cosh(1.0):.12f}")
    0.761594155956 0.648054273664 0.761594155956 0.648054273664
    """
    if is_real_scalar(u) and abs(u) <= _U_HUGE:  # scalar fast path (right-hand sides of integrators)
        mcf, mf, fast = -1.0, 0.0, _MC_JACOBI_FROM_K
        if mc is None:
            if is_real_scalar(k) and 0.0 <= k <= 1.0:  # type: ignore[operator]  # k is a float or int here
                mf = k * k  # type: ignore[operator]
                mcf = 1.0 - mf
        elif k is None and is_real_scalar(mc) and 0.0 <= mc <= 1.0:
            mcf = float(mc)
            mf, fast = 1.0 - mcf, _MC_JACOBI_FROM_MC
        if mcf >= fast:
            s, c, _, a = _ellipj(u, mf)
            return float(s), float(c), math.sqrt(mcf + mf * (c * c)), float(a)
        if mcf >= 0.0:
            return _jacobi_reduced_scalar(float(u), mf, mcf)
    ua = as_float_array(u, "u")
    umax = np.max(np.abs(ua)) if ua.size else 0.0
    if not umax <= _U_HUGE and not np.all(np.isfinite(ua)):
        raise ValueError("u must be finite")
    m, mca, mc_min = moduli(k, mc)
    fast = _MC_JACOBI_FROM_K if mc is None else _MC_JACOBI_FROM_MC
    if mc_min >= fast and umax <= _U_HUGE:  # SciPy directly, dn^2 = mc + m cn^2 (see _MC_JACOBI_FROM_K)
        s, c, _, a = _ellipj(ua, m)
        return float_out(s), float_out(c), float_out(np.sqrt(mca + m * (c * c))), float_out(a)
    ua, m, mca = np.broadcast_arrays(ua, m, mca)
    shape = ua.shape
    ua, m, mca = ua.ravel(), m.ravel(), mca.ravel()
    near = mca < fast
    if np.all(near):
        out = _jacobi_reduced(ua, m, mca)
    else:
        out = (np.empty_like(ua), np.empty_like(ua), np.empty_like(ua), np.empty_like(ua))
        far = ~near
        uf = ua[far]
        if umax > _U_HUGE:
            uf = np.where(np.abs(uf) > _U_HUGE, np.fmod(uf, 4.0 * _ellipk(m[far])), uf)
        s, c, _, a = _ellipj(uf, m[far])
        for o, v in zip(out, (s, c, np.sqrt(mca[far] + m[far] * (c * c)), a)):
            o[far] = v
        for o, v in zip(out, _jacobi_reduced(ua[near], m[near], mca[near])):
            o[near] = v
    return float_out(out[0].reshape(shape)), float_out(out[1].reshape(shape)), float_out(out[2].reshape(shape)), \
        float_out(out[3].reshape(shape))


_JACOBI_PARAMS = """
    Parameters
    ----------
    u : array_like
        Argument (any finite real value).
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
    """Insert the shared Parameters/Returns sections after the summary line of a single-function Jacobi
    docstring (before its See Also and Examples)."""
    summary, _, rest = (func.__doc__ or "").partition("\n\n")
    func.__doc__ = summary + "\n" + _JACOBI_PARAMS + "\n" + rest
    return func


@_jacobi_doc
def sn(u: ArrayLike, k: ArrayLike | None = None, *, mc: ArrayLike | None = None) -> Any:
    r"""Jacobi ``sn(u, k)`` in the modulus ``k``.

    See Also
    --------
    cn, dn, am : the other functions of the same argument.
    jacobi : all four at once (one evaluation).

    References
    ----------
    NIST Digital Library of Mathematical Functions, §22.2, §22.5 and §22.6(i).

    Examples
    --------
    >>> import math
    >>> from rigidbody.core.elliptic import K, sn
    >>> print(f"{sn(K(0.6), 0.6):.12f}")  # sn(K) = 1
    1.000000000000
    >>> print(f"{sn(0.5, 0.0):.12f} {math.sin(0.5):.12f}")  # k = 0: sin
    0.479425538604 0.479425538604
    >>> print(f"{sn(0.5, 1.0):.12f} {math.tanh(0.5):.12f}")  # k = 1: tanh
    0.462117157260 0.462117157260
    """
    return jacobi(u, k, mc=mc)[0]


@_jacobi_doc
def cn(u: ArrayLike, k: ArrayLike | None = None, *, mc: ArrayLike | None = None) -> Any:
    r"""Jacobi ``cn(u, k)`` in the modulus ``k``.

    See Also
    --------
    sn, dn, am : the other functions of the same argument.
    jacobi : all four at once (one evaluation).

    References
    ----------
    NIST Digital Library of Mathematical Functions, §22.2, §22.5 and §22.6(i).

    Examples
    --------
    >>> from rigidbody.core.elliptic import K, cn, sn
    >>> print(f"{cn(2 * K(0.6), 0.6):.12f}")  # cn(2K) = -1
    -1.000000000000
    >>> print(f"{sn(0.8, 0.6)**2 + cn(0.8, 0.6)**2:.12f}")
    1.000000000000
    """
    return jacobi(u, k, mc=mc)[1]


@_jacobi_doc
def dn(u: ArrayLike, k: ArrayLike | None = None, *, mc: ArrayLike | None = None) -> Any:
    r"""Jacobi ``dn(u, k)`` in the modulus ``k``.

    See Also
    --------
    sn, cn, am : the other functions of the same argument.
    jacobi : all four at once (one evaluation).

    References
    ----------
    NIST Digital Library of Mathematical Functions, §22.2, §22.5 and §22.6(i).

    Examples
    --------
    >>> from rigidbody.core.elliptic import K, dn, sn
    >>> print(f"{dn(K(0.6), 0.6):.12f}")  # dn(K) = k' = sqrt(1 - k**2)
    0.800000000000
    >>> print(f"{0.36 * sn(0.8, 0.6)**2 + dn(0.8, 0.6)**2:.12f}")  # k**2 sn**2 + dn**2 = 1
    1.000000000000

    Near the separatrix give ``mc``: ``dn`` keeps its relative accuracy where it is tiny,
    :math:`\operatorname{dn}(K) = k' = 10^{-8}` here:

    >>> print(f"{dn(K(mc=1e-16), mc=1e-16):.12e}")
    1.000000000000e-08
    """
    return jacobi(u, k, mc=mc)[2]


@_jacobi_doc
def am(u: ArrayLike, k: ArrayLike | None = None, *, mc: ArrayLike | None = None) -> Any:
    r"""Jacobi amplitude ``am(u, k)``, continuous and increasing in ``u`` in the modulus ``k``.

    See Also
    --------
    F : the inverse function, :math:`F(\operatorname{am}(u, k), k) = u`.
    sn, cn, dn : :math:`\sin\operatorname{am}`, :math:`\cos\operatorname{am}` and
        :math:`\sqrt{1 - k^2\sin^2\operatorname{am}}`.

    References
    ----------
    NIST Digital Library of Mathematical Functions, §22.16(i).

    Examples
    --------
    >>> import math
    >>> from rigidbody.core.elliptic import K, am
    >>> print(f"{am(3 * K(0.6), 0.6):.12f} {3 * math.pi / 2:.12f}")  # am(u + 2K) = am(u) + pi
    4.712388980385 4.712388980385
    >>> print(f"{am(1.0, 1.0):.12f} {2 * math.atan(math.tanh(0.5)):.12f}")  # k = 1: the Gudermannian
    0.865769483240 0.865769483240
    """
    return jacobi(u, k, mc=mc)[3]
