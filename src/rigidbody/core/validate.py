"""Validation of scalar user input, shared by all modules.

Every public function of the library rejects bad input with a ``TypeError`` (not a real number) or a
``ValueError`` (NaN, infinite, out of range) whose message names the parameter and the allowed range.
"""

from __future__ import annotations

import math
import numbers
from typing import Any

import numpy as np

__all__ = ["finite_array", "positive", "real", "span"]


def _as_float(value: Any, name: str) -> float:
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (numbers.Real, np.floating, np.integer)):
        raise TypeError(f"{name} must be a real number, got {type(value).__name__}")
    return float(value)


def real(value: Any, name: str) -> float:
    """Return ``value`` as a finite float.

    Parameters
    ----------
    value : object
        The user's input.
    name : str
        Parameter name used in the error message.

    Returns
    -------
    float

    Raises
    ------
    TypeError
        If ``value`` is not a real number (``bool`` is rejected too).
    ValueError
        If ``value`` is NaN or infinite.
    """
    v = _as_float(value, name)
    if not math.isfinite(v):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return v


def positive(value: Any, name: str) -> float:
    """Return ``value`` as a finite float > 0.

    Parameters
    ----------
    value : object
        The user's input.
    name : str
        Parameter name used in the error message.

    Returns
    -------
    float

    Raises
    ------
    TypeError
        If ``value`` is not a real number.
    ValueError
        If ``value`` is not finite or not > 0.
    """
    v = _as_float(value, name)
    if not (math.isfinite(v) and v > 0.0):
        raise ValueError(f"{name} must be finite and > 0, got {value!r}")
    return v


def span(value: Any, name: str) -> tuple[float, float]:
    """Return an integration span ``(start, end)`` of finite floats with ``end >= start``.

    Parameters
    ----------
    value : sequence of two numbers
        The user's span.
    name : str
        Parameter name used in the error message (``'t_span'``, ``'tau_span'``).

    Returns
    -------
    tuple of float

    Raises
    ------
    ValueError
        If it is not a pair of finite numbers with ``end >= start``.
    """
    try:
        a, b = (float(x) for x in value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a pair of finite numbers (start, end), got {value!r}") from None
    if not (math.isfinite(a) and math.isfinite(b)) or b < a:
        raise ValueError(f"{name} must be finite with end >= start, got {value!r}")
    return a, b


def finite_array(value: Any, name: str) -> np.ndarray:
    """Return ``value`` as a float array with only finite entries.

    Parameters
    ----------
    value : array_like
        The user's input.
    name : str
        Parameter name used in the error message.

    Returns
    -------
    numpy.ndarray

    Raises
    ------
    TypeError
        If ``value`` cannot be read as real numbers (strings, objects, complex numbers).
    ValueError
        If any entry is NaN or infinite.
    """
    if isinstance(value, (str, bytes)) or np.iscomplexobj(value):
        raise TypeError(f"{name} must be real numbers, got {value!r}")
    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be real numbers, got {value!r}") from None
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return a
