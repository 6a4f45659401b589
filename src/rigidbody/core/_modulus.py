"""The arguments of the elliptic functions: the modulus ``k`` or the complementary parameter ``mc``.

The checks and conversions behind :mod:`rigidbody.core.elliptic` (where ``check_modulus`` is public), shared
by its integrals (``rigidbody.core._integrals``) and its Jacobi functions.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ._periods import mc_of_k

ArrayLike = Any


def float_out(x: np.ndarray) -> Any:
    """Scalar in, Python float out; arrays stay arrays."""
    return float(x) if np.ndim(x) == 0 else x


def is_real_scalar(x: Any) -> bool:
    """A Python float or int (the scalar fast paths; anything else takes the general route)."""
    t = type(x)
    return t is float or t is int


def as_float_array(x: ArrayLike, name: str) -> np.ndarray:
    """``x`` as a float array (TypeError naming ``name`` if it is not real numbers); its range is not checked."""
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

    See Also
    --------
    rigidbody.core.validate.finite_array : the check of an array of any real values.

    Examples
    --------
    >>> from rigidbody.core.elliptic import check_modulus
    >>> check_modulus([0.0, 0.5, 1.0])
    array([0. , 0.5, 1. ])
    >>> check_modulus(1.2, "k0")
    Traceback (most recent call last):
        ...
    ValueError: k0 must lie in [0, 1] (modulus convention, m = k**2); got ...1.2...
    """
    a = as_float_array(k, name)
    modulus_range(a, name)
    return a


def modulus_range(a: np.ndarray, name: str) -> tuple[float, float]:
    """``(min, max)`` of a modulus array after checking it lies in [0, 1] (two reductions; NaN propagates
    through both, so one comparison catches it).  ``(1.0, 0.0)`` for an empty array."""
    if a.size == 0:
        return 1.0, 0.0
    lo, hi = a.min(), a.max()
    if lo >= 0.0 and hi <= 1.0:
        return float(lo), float(hi)
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite and in [0, 1]; got a non-finite value")
    bad = a[(a < 0.0) | (a > 1.0)].ravel()[0]
    raise ValueError(f"{name} must lie in [0, 1] (modulus convention, m = k**2); got {bad!r}")


def moduli(k: ArrayLike | None, mc: ArrayLike | None) -> tuple[np.ndarray, np.ndarray, float]:
    """The parameter ``m = k**2``, its complement ``mc = 1 - m`` (validated) and the smallest ``mc``."""
    if mc is None:
        if k is None:
            raise TypeError("give the modulus k or the complementary parameter mc = 1 - k**2")
        ka = as_float_array(k, "k")
        _, hi = modulus_range(ka, "k")
        m = ka * ka
        return m, 1.0 - m, 1.0 - hi * hi
    mca = as_float_array(mc, "mc")
    lo, _ = modulus_range(mca, "mc")
    if k is None:
        return 1.0 - mca, mca, lo
    ka = as_float_array(k, "k")
    modulus_range(ka, "k")
    m = ka * ka
    if np.any(np.abs(m + mca - 1.0) > 1e-12):
        raise ValueError("k and mc are inconsistent: k**2 + mc must equal 1 (to 1e-12)")
    return m, mca, lo


def scalar_modulus(k: ArrayLike | None, mc: ArrayLike | None) -> tuple[float, float, float, float] | None:
    """``(m, mc_hi, mc_lo, k)`` of a valid modulus given as one Python float or int (``k = -1`` when given by
    ``mc``), else None."""
    if mc is None:
        if is_real_scalar(k) and 0.0 <= k <= 1.0:  # type: ignore[operator]  # k is a float or int here
            kf = float(k)  # type: ignore[arg-type]  # k is a float or int here
            return (kf * kf, *mc_of_k(kf), kf)
    elif k is None and is_real_scalar(mc) and 0.0 <= mc <= 1.0:
        mcf = float(mc)
        return 1.0 - mcf, mcf, 0.0, -1.0
    return None


def array_modulus(k: ArrayLike | None, mc: ArrayLike | None) -> tuple[np.ndarray, ...]:
    """``(m, mc_hi, mc_lo, k)`` as arrays (validated; ``k = -1`` where the modulus is given by ``mc``, which
    then rules when both are given)."""
    if mc is None:
        moduli(k, None)
        return of_k(np.asarray(k, dtype=float))
    _, mca, _ = moduli(k, mc)
    return 1.0 - mca, mca, np.zeros_like(mca), np.full_like(mca, -1.0)


def of_k(k: np.ndarray) -> tuple[np.ndarray, ...]:
    """``(m, mc_hi, mc_lo, k)`` of a valid modulus array ``k`` (``1 - k^2`` exactly, as a double-double)."""
    return (k * k, *mc_of_k(k), k)
