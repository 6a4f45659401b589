r"""Jacobi elliptic functions and elliptic integrals in the **modulus** ``k``.

The papers write :math:`\operatorname{sn}(u, k)`, :math:`K(k)`, :math:`E(k)` with the modulus ``k``;
SciPy uses the *parameter* :math:`m = k^2` (``scipy.special.ellipj(u, m)``, ``ellipk(m)``). This module is
the one place where that conversion happens: every other module calls these functions with ``k``.

The inputs are taken as exact: the functions are those of the float ``u`` and of the modulus as given, ``k``
(with :math:`m = k^2` and :math:`m_c = 1 - k^2` formed exactly, not rounded) or the complementary
parameter ``mc`` (keyword). Near the separatrix (:math:`k \to 1`) a double ``k`` close to 1 carries
:math:`m_c = 1 - k^2` only to its own spacing; pass ``mc`` whenever you have it. When both ``k`` and ``mc``
are given they must agree to 1e-12, and ``mc`` rules.

Accuracy
--------
Against mpmath at 50 digits and more (``tests/core/test_elliptic_ulps.py``; the table of the documentation
page *Elliptic functions: accuracy and cost*):

* ``sn``, ``cn``, ``dn``, ``am``: within 8 ulp of the exact value everywhere, measured at most 4: any
  :math:`0 \le m \le 1`, :math:`1 - m` down to :math:`10^{-300}`, ``u`` of either sign, near the zeros of
  ``sn`` and ``cn`` (the float nearest to :math:`nK` included). The argument is reduced by the half period
  :math:`2K`, with :math:`K` a double-double (the arithmetic-geometric mean in double-double arithmetic,
  ``rigidbody.core._periods``), and within about :math:`2^{-45}K` of a multiple of :math:`K` by :math:`K` to
  :math:`2^{-160}`, so that the distance to a zero keeps its digits; beyond :math:`K/2` the functions are
  evaluated at :math:`v = K - |r|` (:math:`\operatorname{sn}(K - v) = \operatorname{cd}v`,
  :math:`\operatorname{cn}(K - v) = k'\operatorname{sd}v`, :math:`\operatorname{dn}(K - v) =
  k'\operatorname{nd}v`). For :math:`m_c \ge 0.05` theta series in the nome :math:`q \le 0.18`
  (``rigidbody.core._theta``), below it series of positive hyperbolic terms in the complementary nome
  :math:`q_1 \approx m_c/16` (``rigidbody.core._nome``); each function is a sine, cosine or hyperbolic
  function times :math:`1 + w`, :math:`w` small, so a few roundings in all. Beyond :math:`|u| = 2^{40}K`
  the reduced argument loses digits as :math:`u` grows (no digit of the phase is left at :math:`2^{53}K`).
* ``K``, ``E``: rounded once from double-doubles (the same mean; :math:`E` by Legendre's sum
  :math:`1 - E/K = \sum 2^{n-1}c_n^2`): 0.5 ulp.
* ``F``, ``Einc``: Carlson's :math:`R_F`, :math:`R_D` in double-double (``rigidbody.core._carlson``) at
  :math:`\phi` reduced by :math:`\pi` as a double-double: within 2 ulp, measured 1.6.
* :math:`k = 1` exactly: :math:`\operatorname{sn}=\tanh u`, :math:`\operatorname{cn}=\operatorname{dn}
  =\operatorname{sech}u`, :math:`\operatorname{am}=\operatorname{gd}u`, :math:`K=\infty`, :math:`E=1`.

Cost: a Python float in gives a Python float out, at about 4-6 us a call (the right-hand sides of
integrators; the constants of a modulus are cached). Arrays are evaluated in blocks that stay in the cache:
with one modulus ``jacobi`` costs 0.4 times ``scipy.special.ellipj`` on :math:`10^6` arguments, with a modulus
per element 0.9 times (the double-double mean per element, closed early and completed near the zeros).
``benchmarks/bench_elliptic.py`` measures both sides.

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
    if mc is None:  # (1 - k^2 formed block by block)
        moduli(k, None)
        parts = np.broadcast_arrays(ua, np.asarray(k, dtype=float))
    else:
        _, mca, _ = moduli(k, mc)
        parts = np.broadcast_arrays(ua, mca)
    u_f, mods = (np.ascontiguousarray(p).ravel() for p in parts)
    s, c, d, a = (float_out(o.reshape(parts[0].shape)) for o in jacobi_arrays(u_f, mods, mc is None))
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
