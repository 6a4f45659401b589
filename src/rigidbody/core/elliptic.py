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

from ._integrals import E, Einc, F, K
from ._jacobi import jacobi_arrays, jacobi_scalar
from ._modulus import (
    ArrayLike,
    array_modulus,
    as_float_array,
    check_modulus,
    float_out,
    is_real_scalar,
    moduli,
    scalar_modulus,
)

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

def m_mc(k: ArrayLike | None, mc: ArrayLike | None) -> tuple[np.ndarray, np.ndarray]:
    """Return the parameter ``m = k**2`` and its complement ``mc = 1 - m`` (validated)."""
    m, mca, _ = moduli(k, mc)
    return m, mca


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
    if is_real_scalar(u) and math.isfinite(u):
        mod = scalar_modulus(k, mc)
        if mod is not None:  # one point in Python floats (right-hand sides of integrators)
            return jacobi_scalar(float(u), *mod)
    ua = as_float_array(u, "u")
    if ua.size and not np.all(np.isfinite(ua)):
        raise ValueError("u must be finite")
    parts = np.broadcast_arrays(ua, *array_modulus(k, mc))
    shape = parts[0].shape
    out = jacobi_arrays(*(np.ascontiguousarray(p).ravel() for p in parts))
    s, c, d, a = (float_out(np.asarray(o).reshape(shape)) for o in out)
    return s, c, d, a


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
