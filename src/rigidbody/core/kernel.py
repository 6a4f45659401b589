r"""One formula for a single run and for a batch: math namespaces, and elliptic means without cancellation.

The right-hand sides of the averaged systems are written once, as functions that take a namespace ``xp``
first: :data:`SCALAR` (the ``math`` module's functions, for one run integrated on Python floats: a few
microseconds a call) or :data:`ARRAY` (NumPy's ufuncs, elementwise over the members of a batch). The
same code then serves :func:`rigidbody.core.ode.integrate` and :func:`rigidbody.core.batch.integrate_batch`.

:func:`sn2_excess` and :func:`elliptic_ratios` give the period means of the Jacobi functions that the
averaged equations of the analyses need, :math:`\langle\operatorname{sn}^2\rangle = (K - E)/(k^2K)` and
:math:`E/K`, by the arithmetic-geometric mean: exact in the complementary parameter :math:`m_c = 1 - k^2`
and free of the cancellation of :math:`(K - E)/k^2` at small :math:`k`.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from scipy.special import ellipe as _ellipe
from scipy.special import ellipk as _ellipk

__all__ = ["ARRAY", "SCALAR", "elliptic_ratios", "sn2_excess"]


class _Scalar:
    """``math`` functions under the names the kernels use (callers turn ``ZeroDivisionError``,
    ``OverflowError`` and ``ValueError`` of a state outside the functions' domain into NaN)."""

    sqrt = staticmethod(math.sqrt)
    exp = staticmethod(math.exp)
    expm1 = staticmethod(math.expm1)
    log = staticmethod(math.log)
    sinh = staticmethod(math.sinh)
    cosh = staticmethod(math.cosh)
    tanh = staticmethod(math.tanh)
    sin = staticmethod(math.sin)
    cos = staticmethod(math.cos)
    acos = staticmethod(math.acos)
    atan2 = staticmethod(math.atan2)
    copysign = staticmethod(math.copysign)
    abs = staticmethod(abs)
    minimum = staticmethod(min)
    maximum = staticmethod(max)
    nan = math.nan
    array = False

    @staticmethod
    def where(c: Any, a: Any, b: Any) -> Any:
        return a if c else b

    @staticmethod
    def any(c: Any) -> bool:
        return bool(c)

    @staticmethod
    def rint(x: float) -> float:
        return float(round(x)) if math.isfinite(x) else x

    @staticmethod
    def clip(x: float, lo: float, hi: float) -> float:
        return lo if x < lo else hi if x > hi else x


class _Array:
    """NumPy ufuncs under the same names (elementwise over batch members)."""

    sqrt = staticmethod(np.sqrt)
    exp = staticmethod(np.exp)
    expm1 = staticmethod(np.expm1)
    log = staticmethod(np.log)
    sinh = staticmethod(np.sinh)
    cosh = staticmethod(np.cosh)
    tanh = staticmethod(np.tanh)
    sin = staticmethod(np.sin)
    cos = staticmethod(np.cos)
    acos = staticmethod(np.arccos)
    atan2 = staticmethod(np.arctan2)
    copysign = staticmethod(np.copysign)
    abs = staticmethod(np.abs)
    minimum = staticmethod(np.minimum)
    maximum = staticmethod(np.maximum)
    where = staticmethod(np.where)
    any = staticmethod(np.any)
    rint = staticmethod(np.rint)
    clip = staticmethod(np.clip)
    nan = np.nan
    array = True


#: the ``math`` namespace: one state of Python floats
SCALAR = _Scalar()
#: the NumPy namespace: arrays of members, elementwise
ARRAY = _Array()


def sn2_excess(xp: Any, k2: Any, mc: Any) -> Any:
    r"""``<sn^2> - 1/2`` over a period, ``(1 - E/K)/k^2 - 1/2``, without cancellation for small ``k``.

    By the arithmetic-geometric mean (``a0 = 1, b0 = sqrt(mc), c0 = k``, ``c_{n+1} = c_n^2/(4 a_{n+1})``),
    ``1 - E/K = sum_{n>=0} 2^{n-1} c_n^2`` (Abramowitz & Stegun 17.6.3-17.6.4); with ``q_n = c_n^2/k^2`` the
    sum divided by ``k^2`` is ``1/2 + sum_{n>=1} 2^{n-1} q_n``, every term positive. Exact in ``mc``.

    Parameters
    ----------
    xp : SCALAR or ARRAY
        The namespace: floats or arrays (elementwise).
    k2, mc : float or numpy.ndarray
        :math:`k^2` and :math:`m_c = 1 - k^2` (``mc > 0``; pass ``mc`` itself where it is known better than
        ``1 - k2``).

    Returns
    -------
    float or numpy.ndarray
        :math:`\langle\operatorname{sn}^2\rangle - 1/2`, in :math:`[0, 1/2)`.

    See Also
    --------
    elliptic_ratios : :math:`E/K` and :math:`\langle\operatorname{sn}^2\rangle` from it.

    References
    ----------
    M. Abramowitz, I. A. Stegun, Handbook of Mathematical Functions (1964), 17.6.3-17.6.4.

    Examples
    --------
    For small :math:`k` the series of :math:`K` and :math:`E` give :math:`E/K = 1 - k^2/2 - k^4/16 - k^6/32
    - \dots`, so :math:`\langle\operatorname{sn}^2\rangle - 1/2 = k^2/16 + k^4/32 + O(k^6)`: at
    :math:`k^2 = 2\cdot10^{-8}` the difference :math:`(1 - E/K)/k^2 - 1/2` would lose 8 digits to cancellation,
    the AGM sum keeps them all:

    >>> from rigidbody.core.kernel import SCALAR, sn2_excess
    >>> m = 2e-8
    >>> print(f"{sn2_excess(SCALAR, m, 1 - m):.10e} {m / 16 + m**2 / 32:.10e}")
    1.2500000125e-09 1.2500000125e-09

    Where nothing cancels it agrees with SciPy's integrals:

    >>> from scipy.special import ellipe, ellipk
    >>> print(f"{sn2_excess(SCALAR, 0.5, 0.5):.12f} {(1 - ellipe(0.5) / ellipk(0.5)) / 0.5 - 0.5:.12f}")
    0.043053418956 0.043053418956
    """
    a = 1.0
    b = xp.sqrt(mc)
    q = 1.0  # q_n = c_n^2/k^2
    p = 1.0  # 2^(n-1)
    total = 0.0
    if xp.array:
        # the AGM converges quadratically: with c_1 = k^2/(2(1 + k')) <= 1/2 and c_{n+1} = c_n^2/(4 a_{n+1}),
        # a_{n+1} >= sqrt(mc), the iterations needed for the terms to drop below 1e-17 follow from the smallest
        # complementary parameter of the batch
        mcmin = max(float(np.min(mc)), 0.0) if np.size(mc) else 1.0
        c, n_it = (1.0 - mcmin) / (2.0 * (1.0 + math.sqrt(mcmin))), 1
        while c * c > 1e-17 and n_it < 40:
            c, n_it = c * c / (4.0 * max(math.sqrt(mcmin), 1e-300)) if c > 0.0 else 0.0, n_it + 1
    else:
        n_it = 40
    for _ in range(n_it):
        a, b = 0.5 * (a + b), xp.sqrt(a * b)
        q = q * q * k2 / (16.0 * a * a)
        term = p * q
        total = total + term
        if not xp.array and term <= 1e-17 * (0.5 + total):
            break
        p *= 2.0
    return total


#: the smallest complementary parameter the AGM of :func:`elliptic_ratios` is run with (closer to the
#: separatrix the ratios are their limits E/K = 0, <sn^2> = 1 to within 1/ln(4/sqrt(mc)) ~ 1/690)
_MC_FLOOR = 1e-300


def elliptic_ratios(xp: Any, k2: Any) -> tuple[Any, Any]:
    r""":math:`E/K` and :math:`\langle\operatorname{sn}^2\rangle = (K - E)/(k^2 K)` for :math:`0 \le k^2 \le 1`.

    :math:`\langle\operatorname{sn}^2\rangle` by :func:`sn2_excess` (limit 1/2 at :math:`k \to 0` without
    cancellation), :math:`E/K = 1 - k^2\langle\operatorname{sn}^2\rangle`. On floats with :math:`k^2 \ge 0.1`,
    where :math:`K - E` does not cancel (at most a digit), SciPy's ``ellipk``/``ellipe`` instead: a third of the
    cost of the AGM loop in Python, the same values to a few ulp. At and beyond the separatrix
    (:math:`k^2 \ge 1`) the limits :math:`E/K = 0`, :math:`\langle\operatorname{sn}^2\rangle = 1`, below 0
    those of :math:`k = 0` (the right-hand sides of integrators meet such values in trial stages).

    Parameters
    ----------
    xp : SCALAR or ARRAY
    k2 : float or numpy.ndarray

    Returns
    -------
    (E/K, <sn^2>) : floats or arrays

    See Also
    --------
    sn2_excess : :math:`\langle\operatorname{sn}^2\rangle - 1/2` without cancellation.
    rigidbody.core.averaging.jacobi_average : period means of any function of sn, cn, dn.

    Examples
    --------
    The limits :math:`k = 0` (:math:`E = K = \pi/2`, :math:`\langle\sin^2\rangle = 1/2`) and :math:`k = 1`
    (:math:`K = \infty`, :math:`\langle\tanh^2\rangle = 1`), and one value between, on floats and on arrays:

    >>> import numpy as np
    >>> from rigidbody.core.kernel import ARRAY, SCALAR, elliptic_ratios
    >>> elliptic_ratios(SCALAR, 0.0), elliptic_ratios(SCALAR, 1.0)
    ((1.0, 0.5), (0.0, 1.0))
    >>> ek, s = elliptic_ratios(ARRAY, np.array([0.0, 0.5, 1.0]))
    >>> print(*(f"{x:.9f}" for x in ek), "|", *(f"{x:.9f}" for x in s))
    1.000000000 0.728473291 0.000000000 | 0.500000000 0.543053419 1.000000000
    >>> from rigidbody.core.elliptic import E, K
    >>> print(f"{E(np.sqrt(0.5)) / K(np.sqrt(0.5)):.9f} {(1 - 0.728473291) / 0.5:.9f}")
    0.728473291 0.543053418
    """
    if not xp.array:
        if k2 >= 1.0:
            return 0.0, 1.0
        if k2 <= 0.0:
            return 1.0, 0.5
        if k2 >= 0.1:
            ek = float(_ellipe(k2)) / float(_ellipk(k2))
            return ek, (1.0 - ek) / k2
        s = 0.5 + sn2_excess(xp, k2, 1.0 - k2)
        return 1.0 - k2 * s, s
    k2c = np.clip(k2, 0.0, 1.0)
    mc = np.maximum(1.0 - k2c, _MC_FLOOR)
    s = 0.5 + sn2_excess(xp, k2c, mc)
    s = np.where(k2c >= 1.0, 1.0, s)
    return 1.0 - k2c * s, s
