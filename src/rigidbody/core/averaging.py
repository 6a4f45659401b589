r"""Period averages over motions written in Jacobi elliptic functions.

The averaged equations of all the papers need means over one period of smooth functions of
:math:`\operatorname{sn}, \operatorname{cn}, \operatorname{dn}` of a phase :math:`s = \alpha t`. The
integrands are analytic and periodic in :math:`s`, so the trapezoid rule on a uniform grid of the phase
converges geometrically (spectrally): for a function analytic in the strip :math:`|\operatorname{Im}s| < a`
with period :math:`P`, the error of :math:`n` nodes is :math:`O(e^{-2\pi a n / P})`. The Jacobi functions
have poles at :math:`s = iK'`, so :math:`a = K'` and for :math:`P = 2K` the error is
:math:`O(e^{-\pi K' n/K})`. :func:`n_nodes` uses this estimate: near the separatrix
(:math:`1-k^2=10^{-10}`, :math:`K\approx 12.9`, :math:`K'\approx\pi/2`) about a hundred nodes per
:math:`2K` give 1e-13. A user function with singularities of its own closer to the real axis (e.g.
:math:`1/(1-u^2)` with :math:`u` near :math:`\pm1`) needs more nodes: pass ``n``.

``quad`` is never used here: these functions sit inside ODE right-hand sides.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
from scipy import special

from .elliptic import jacobi, m_mc

__all__ = ["jacobi_average", "n_nodes", "phase_grid", "sn2_average"]

#: below this complementary parameter phase_grid uses the careful, period-reduced jacobi()
_MC_FAST = 1e-3

#: ln(1/1e-13) = 30 plus the log of the prefactor: the Fourier coefficients of sn^2 decay like m q^m (a double
#: pole), so the aliasing error of N nodes is ~ N pi^2/(k K)^2 q^N, up to e^7 times q^N here. Calibrated in
#: tests/core/test_averaging.py::test_default_nodes_reach_1e-13_over_the_whole_range.
_LOG_TOL = 40.0


def _period_factor(period: str) -> float:
    if period == "2K":
        return 1.0
    if period == "4K":
        return 2.0
    raise ValueError(f"period must be '2K' or '4K', got {period!r}")


def _scalar_mc(k: Any, mc: Any) -> float:
    """Validated complementary parameter of a scalar modulus (cheap: these run inside ODE right-hand sides)."""
    if mc is not None and k is None and isinstance(mc, (float, int)) and not isinstance(mc, bool):
        mcf = float(mc)
        if not (0.0 <= mcf <= 1.0):  # also rejects NaN
            raise ValueError(f"mc must lie in [0, 1] (mc = 1 - k**2); got {mc!r}")
        return mcf
    _, mca = m_mc(k, mc)
    if np.ndim(mca) != 0:
        raise ValueError("period averages take a scalar modulus (one state per call)")
    return float(mca)


def n_nodes(k: float | None = None, *, mc: float | None = None, period: str = "2K") -> int:
    r"""Number of trapezoid nodes per period that averages ``sn``-type integrands to ~1e-13.

    Parameters
    ----------
    k : float, optional
        Modulus in [0, 1).
    mc : float, optional
        Complementary parameter :math:`1-k^2` (in (0, 1]).
    period : {'2K', '4K'}
        The averaging period in the phase :math:`s`.

    Returns
    -------
    int
        :math:`n \ge 16`, a multiple of 4, from :math:`e^{-\pi K' n/K} \le 10^{-13}` per :math:`2K`.

    See Also
    --------
    phase_grid : the nodes and the Jacobi functions there.

    References
    ----------
    L. N. Trefethen, J. A. C. Weideman, "The exponentially convergent trapezoidal rule", SIAM Review 56(3),
    385-458 (2014) (periodic integrands analytic in a strip).

    Examples
    --------
    The count is :math:`40K/(\pi K')` per :math:`2K`, rounded up to a multiple of 4, at least 16. Away from
    the separatrix that is the floor (:math:`40K/(\pi K') \approx 10` at :math:`k^2 = 1/4`); at
    :math:`1 - k^2 = 10^{-10}`, :math:`K \approx \ln(4\cdot10^5) = 12.90` and :math:`K' \approx \pi/2`
    give :math:`104.6 \to 108` (twice as many per :math:`4K`):

    >>> from rigidbody.core.averaging import n_nodes
    >>> n_nodes(0.5), n_nodes(mc=1e-10), n_nodes(mc=1e-10, period="4K")
    (16, 108, 212)
    """
    mcf = _scalar_mc(k, mc)
    if mcf == 0.0:
        raise ValueError("the period is infinite at k = 1 (separatrix): no period average exists")
    kk = float(special.ellipkm1(mcf))
    kkp = float(special.ellipkm1(1.0 - mcf))  # K' = K(k'): parameter of k' is mc, its complement is m
    n = _LOG_TOL * kk / (math.pi * kkp) * _period_factor(period)
    n = max(16, math.ceil(n))
    return n + (-n) % 4


def phase_grid(
    k: float | None = None,
    n: int | None = None,
    *,
    mc: float | None = None,
    period: str = "4K",
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    r"""Uniform nodes of the phase over one period and the Jacobi functions there.

    Parameters
    ----------
    k : float, optional
        Modulus in [0, 1).
    n : int, optional
        Number of nodes (default :func:`n_nodes`).
    mc : float, optional
        Complementary parameter :math:`1-k^2`.
    period : {'4K', '2K'}
        Period covered by the nodes :math:`s_j = jP/n`, :math:`j = 0..n-1`.

    Returns
    -------
    s, sn, cn, dn : numpy.ndarray
        Arrays of length ``n``.

    See Also
    --------
    jacobi_average : the mean of a function over these nodes.
    n_nodes : the default number of nodes.

    Examples
    --------
    At :math:`k = 0` the period :math:`4K` is :math:`2\pi` and ``sn`` is the sine:

    >>> import numpy as np
    >>> from rigidbody.core.averaging import phase_grid
    >>> s, sn, cn, dn = phase_grid(0.0, 8)
    >>> print(f"{s[1]:.12f} {np.pi / 4:.12f}", np.allclose(sn, np.sin(s), rtol=0, atol=1e-15))
    0.785398163397 0.785398163397 True
    """
    mcf = _scalar_mc(k, mc)
    if mcf == 0.0:
        raise ValueError("the period is infinite at k = 1 (separatrix): no period average exists")
    if n is None:
        n = n_nodes(mc=mcf, period=period)
    if not isinstance(n, (int, np.integer)) or n < 2:
        raise ValueError(f"n must be an integer >= 2, got {n!r}")
    kk = float(special.ellipkm1(mcf))
    p = kk * 2.0 * _period_factor(period)
    s = np.arange(n) * (p / n)
    if mcf >= _MC_FAST:
        # fast path: SciPy's ellipj on the whole period. Cephes forms sqrt(1 - m) from m, losing ~eps/mc
        # relative (2e-12 at mc = 1e-6, found by tests/core/test_averaging.py); for mc >= 1e-3 the loss is
        # < 1e-15. Below, the period-reduced jacobi() with the exact mc. Checked in test_phase_grid_agrees_...
        snv, cnv, dnv, _ = special.ellipj(s, 1.0 - mcf)
    else:
        snv, cnv, dnv, _ = jacobi(s, mc=mcf)
    return s, snv, cnv, dnv


def jacobi_average(
    f: Callable[[np.ndarray, np.ndarray, np.ndarray], Any],
    k: float | None = None,
    *,
    mc: float | None = None,
    n: int | None = None,
    period: str = "4K",
) -> Any:
    r"""Mean over one period of :math:`f(\operatorname{sn}s, \operatorname{cn}s, \operatorname{dn}s)`.

    Parameters
    ----------
    f : callable
        ``f(sn, cn, dn)`` vectorised over 1-D arrays of nodes; it may return an array of shape
        ``(..., n)``: the mean is taken over the last axis.
    k, mc : float
        Modulus or complementary parameter.
    n : int, optional
        Nodes per period (default :func:`n_nodes` for the period).
    period : {'4K', '2K'}
        Use '4K' unless ``f`` is known to have period 2K (e.g. even in sn and cn jointly).

    Returns
    -------
    float or numpy.ndarray
        The period mean.

    See Also
    --------
    sn2_average : the mean over a motion :math:`u = u_1 + (u_2 - u_1)\operatorname{sn}^2`.
    phase_grid : the nodes.
    rigidbody.core.kernel.elliptic_ratios : the means of :math:`\operatorname{sn}^2` and
        :math:`\operatorname{dn}^2` in closed form.

    References
    ----------
    L. N. Trefethen, J. A. C. Weideman, "The exponentially convergent trapezoidal rule", SIAM Review 56(3),
    385-458 (2014) (periodic integrands analytic in a strip).

    Examples
    --------
    The closed forms :math:`\langle\operatorname{sn}^2\rangle = (1 - E/K)/k^2` and
    :math:`\langle\operatorname{dn}^2\rangle = E/K` (:math:`\int_0^K\operatorname{dn}^2 = E`: Jacobi's epsilon function,
    NIST DLMF §22.16(ii)):

    >>> from rigidbody.core.averaging import jacobi_average
    >>> from rigidbody.core.elliptic import E, K
    >>> k = 0.8
    >>> abs(jacobi_average(lambda s, c, d: s**2, k) - (1 - E(k) / K(k)) / k**2) < 1e-14
    True
    >>> print(f"{jacobi_average(lambda s, c, d: d**2, k):.12f} {E(k) / K(k):.12f}")
    0.639677324894 0.639677324894
    """
    _, snv, cnv, dnv = phase_grid(k, n, mc=mc, period=period)
    vals = np.asarray(f(snv, cnv, dnv), dtype=float)
    res = vals.mean(axis=-1)
    return float(res) if np.ndim(res) == 0 else res


def sn2_average(
    g: Callable[[np.ndarray], Any],
    u1: float,
    u2: float,
    k: float | None = None,
    *,
    mc: float | None = None,
    n: int | None = None,
) -> Any:
    r"""Mean over one period of :math:`g(u)` for :math:`u = u_1 + (u_2-u_1)\operatorname{sn}^2(s, k)`.

    This is the time average over one oscillation of motions such as the nutation of the Lagrange top
    (:math:`u = \cos\theta`, Akulenko et al. (1.3)), where :math:`s = \alpha t` and the period in
    :math:`s` is :math:`2K`.

    Parameters
    ----------
    g : callable
        Vectorised function of ``u``; may return ``(..., n)`` arrays (mean over the last axis).
    u1, u2 : float
        The turning points.
    k, mc : float
        Modulus or complementary parameter of the motion.
    n : int, optional
        Nodes per period 2K (default :func:`n_nodes`).

    Returns
    -------
    float or numpy.ndarray
        The period mean.

    See Also
    --------
    jacobi_average : the mean of any function of sn, cn, dn.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`,
    eqs. (1.3)-(1.4).

    Examples
    --------
    The mean of :math:`u` itself is :math:`u_1 + (u_2 - u_1)(1 - E/K)/k^2`:

    >>> from rigidbody.core.averaging import sn2_average
    >>> from rigidbody.core.elliptic import E, K
    >>> u1, u2, k = -0.3, 0.6, 0.8
    >>> print(f"{sn2_average(lambda u: u, u1, u2, k):.12f} {u1 + (u2 - u1) * (1 - E(k) / K(k)) / k**2:.12f}")
    0.206703761868 0.206703761868
    """
    _, snv, _, _ = phase_grid(k, n, mc=mc, period="2K")
    u = u1 + (u2 - u1) * snv * snv
    vals = np.asarray(g(u), dtype=float)
    res = vals.mean(axis=-1)
    return float(res) if np.ndim(res) == 0 else res
