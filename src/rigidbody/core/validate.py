"""Validation of user input, shared by all modules.

Every public function of the library rejects bad input with a ``TypeError`` (not a real number) or a
``ValueError`` (NaN, infinite, out of range) whose message names the parameter and the allowed range. What a
user's function returns (a torque, a field) is checked by :func:`returned`, whose errors name the function by
its repr and say what was expected.
"""

from __future__ import annotations

import functools
import math
import numbers
from typing import Any

import numpy as np

__all__ = ["RESULT_ERRORS", "ResultTypeError", "ResultValueError", "finite_array", "member_states", "positive",
           "real", "result_message", "returned", "span"]


def _as_float(value: Any, name: str) -> float:
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (numbers.Real, np.floating, np.integer)):
        raise TypeError(f"{name} must be a real number, got {type(value).__name__}")
    return float(value)


def _shown(value: Any) -> str:
    """A number as the messages show it: NumPy scalars like Python's (``nan``, not ``np.float64(nan)``), so that
    a batch member and the single call with the same value say the same."""
    return repr(float(value)) if isinstance(value, (np.floating, np.integer)) else repr(value)


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

    See Also
    --------
    positive : a finite float > 0.
    finite_array : an array of finite floats.

    Examples
    --------
    >>> from rigidbody.core.validate import real
    >>> real(3, "theta0")
    3.0
    >>> real(float("nan"), "theta0")
    Traceback (most recent call last):
        ...
    ValueError: theta0 must be finite, got nan
    >>> real(True, "theta0")
    Traceback (most recent call last):
        ...
    TypeError: theta0 must be a real number, got bool
    """
    v = _as_float(value, name)
    if not math.isfinite(v):
        raise ValueError(f"{name} must be finite, got {_shown(value)}")
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

    See Also
    --------
    real : a finite float of either sign.

    Examples
    --------
    >>> from rigidbody.core.validate import positive
    >>> positive(7e6, "R0")
    7000000.0
    >>> positive(0, "R0")
    Traceback (most recent call last):
        ...
    ValueError: R0 must be finite and > 0, got 0
    """
    v = _as_float(value, name)
    if not (math.isfinite(v) and v > 0.0):
        raise ValueError(f"{name} must be finite and > 0, got {_shown(value)}")
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

    See Also
    --------
    real : one finite float.

    Examples
    --------
    >>> from rigidbody.core.validate import span
    >>> span((0, 10), "t_span")
    (0.0, 10.0)
    >>> span((10, 0), "t_span")
    Traceback (most recent call last):
        ...
    ValueError: t_span must be finite with end >= start, got (10, 0)
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

    See Also
    --------
    real : one finite float.
    returned : the check of what a user's function returned.

    Examples
    --------
    >>> from rigidbody.core.validate import finite_array
    >>> finite_array([1, 0, 0], "n0")
    array([1., 0., 0.])
    >>> finite_array([1, 0, float("inf")], "n0")
    Traceback (most recent call last):
        ...
    ValueError: n0 must be finite, got [1, 0, inf]
    >>> finite_array([1j, 0, 0], "n0")
    Traceback (most recent call last):
        ...
    TypeError: n0 must be real numbers, got [1j, 0, 0]
    """
    a = _real_array(value, name)
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return a


def member_states(value: Any, names: tuple[str, ...], name: str) -> np.ndarray:
    """The start states of a run or a batch, given stacked or by components, as one array ``batch_shape + (k,)``.

    The library's batch convention: the batch shape of a call is the broadcast shape of its per-member inputs
    (NumPy's rules), ``()`` for a single run. A state of ``k`` components is given either

    * *by components*: a ``tuple`` or ``list`` of ``k`` entries (``names``), each a number or an array; they
      broadcast together (``(Gz0, H0, r0)`` with ``r0`` an array of 50 spins is a batch of 50), or
    * *stacked*: a NumPy array of shape ``batch_shape + (k,)``, one row per member.

    The type decides, so no value has two readings: an array is always stacked on its last axis, a tuple or
    list always holds the components. A list of ``k`` lists of ``k`` numbers (the nested-list form of ``k``
    stacked states, which the tuple rule would read transposed) is refused as ambiguous.

    Parameters
    ----------
    value : tuple, list or numpy.ndarray
        The user's input.
    names : tuple of str
        The components' names, in order (their count is ``k``).
    name : str
        Parameter name used in the error messages.

    Returns
    -------
    numpy.ndarray
        Float array of shape ``batch_shape + (k,)`` (not checked for finiteness: a run refuses a non-finite
        member with a status, a batch ends that member alone).

    Raises
    ------
    TypeError
        If an entry cannot be read as real numbers.
    ValueError
        For a tuple or list of another length than ``k``, components that do not broadcast, a stacked array
        whose last axis is not ``k``, an empty batch, or the ambiguous nested list.

    See Also
    --------
    finite_array : one array of finite numbers.

    Examples
    --------
    Components broadcast (one spin per member, the rest shared); an array is stacked on its last axis:

    >>> import numpy as np
    >>> from rigidbody.core.validate import member_states
    >>> member_states((0.5, 1.0, np.array([1.0, 2.0])), ("Gz", "H", "r"), "initial")
    array([[0.5, 1. , 1. ],
           [0.5, 1. , 2. ]])
    >>> member_states(np.array([[0.5, 1.0, 1.0]]), ("Gz", "H", "r"), "initial").shape
    (1, 3)
    >>> member_states((0.5, 1.0, 1.0), ("Gz", "H", "r"), "initial").shape  # one run: batch shape ()
    (3,)
    """
    k, listed = len(names), ", ".join(names)
    stacked = f"stacked states are a NumPy array of shape batch_shape + ({k},)"
    if isinstance(value, (tuple, list)):
        if len(value) != k:
            raise ValueError(f"{name} as a tuple or list holds the {k} components ({listed}), got {len(value)} "
                             f"entries; {stacked}")
        if all(isinstance(v, (tuple, list)) and len(v) == k for v in value):
            raise ValueError(f"{name} is ambiguous: a list of {k} lists of {k} numbers reads as the components "
                             f"({listed}) of {k} members or as {k} stacked states; pass np.asarray({name}) for "
                             f"stacked states or the components as arrays")
        parts = [_real_array(v, f"{name}[{i}] ({names[i]})") for i, v in enumerate(value)]
        try:
            out = np.stack(np.broadcast_arrays(*parts), axis=-1)
        except ValueError:
            raise ValueError(f"the components ({listed}) of {name} must broadcast together, got shapes "
                             f"{[p.shape for p in parts]}") from None
    else:
        out = _real_array(value, name)
        if out.ndim == 0 or out.shape[-1] != k:
            raise ValueError(f"{name} must be ({listed}) or an array of shape batch_shape + ({k},), got shape "
                             f"{out.shape}")
    if out.size == 0:
        raise ValueError(f"the batch of {name} is empty (shape {out.shape})")
    return out


def _real_array(value: Any, name: str) -> np.ndarray:
    """``value`` as a float array, finite or not (a ``TypeError`` naming ``name`` for what is not real numbers)."""
    if isinstance(value, (str, bytes)) or np.iscomplexobj(value):
        raise TypeError(f"{name} must be real numbers, got {value!r}")
    try:
        return np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be real numbers, got {value!r}") from None


class ResultTypeError(TypeError):
    """A user's function returned something that is not real numbers (None, complex numbers, text).

    See Also
    --------
    returned : the check that raises it.
    ResultValueError : real numbers of the wrong shape, or not finite.

    Examples
    --------
    It is a ``TypeError``, so ``except TypeError`` catches it:

    >>> import numpy as np
    >>> from rigidbody.core.validate import ResultTypeError, returned
    >>> def torque(t, y):
    ...     return None
    >>> try:
    ...     returned(torque(0.0, np.zeros(3)), torque, (3,), role="the torque")
    ... except TypeError as exc:
    ...     print(type(exc).__name__, isinstance(exc, ResultTypeError))
    ResultTypeError True
    """


class ResultValueError(ValueError):
    """A user's function returned real numbers of the wrong shape, or NaN or infinite values.

    See Also
    --------
    returned : the check that raises it.
    ResultTypeError : something that is not real numbers.

    Examples
    --------
    It is a ``ValueError``, so ``except ValueError`` catches it:

    >>> import numpy as np
    >>> from rigidbody.core.validate import ResultValueError, returned
    >>> def torque(t, y):
    ...     return np.array([0.0, np.nan, 0.0])
    >>> try:
    ...     returned(torque(0.0, np.zeros(3)), torque, (3,), role="the torque")
    ... except ValueError as exc:
    ...     print(type(exc).__name__, isinstance(exc, ResultValueError))
    ResultValueError True
    """


#: the errors of :func:`returned` (a run catches them to end with a status where a function misbehaves mid-way)
RESULT_ERRORS = (ResultTypeError, ResultValueError)


def returned(value: Any, fun: Any, shape: tuple[int, ...], *, role: str = "the function", finite: bool = True
             ) -> np.ndarray:
    """What a user's function returned, checked: a float array that broadcasts to ``shape``, finite.

    The one check of the output of a user's callable (a torque, a field): every code path that calls one
    passes its result through here. The common case (a float array of exactly ``shape``) costs one
    finiteness test.

    Parameters
    ----------
    value : object
        What the function returned.
    fun : callable
        The function (named by its repr in the messages).
    shape : tuple of int
        The shape expected (the leading axes of the arguments and the components, e.g. ``(..., 3)``); a
        result that broadcasts to it (a constant, compact leading axes) is accepted, a scalar is not.
    role : str
        What the function is, for the messages (``'the torque'``).
    finite : bool
        Whether to test for NaN and infinite values (a batch tests them per member itself).

    Returns
    -------
    numpy.ndarray
        ``value`` as a float array (the object itself when it already is one).

    Raises
    ------
    ResultTypeError
        (a ``TypeError``) for None, complex numbers, or anything that is not real numbers.
    ResultValueError
        (a ``ValueError``) for a scalar, a shape that does not broadcast to ``shape`` with the same last axis,
        or NaN or infinite values.

    See Also
    --------
    result_message : the message of the errors.
    RESULT_ERRORS : the two error classes, for an ``except`` clause.

    Examples
    --------
    A torque of the right shape passes (a list is converted), a constant broadcasts; a scalar is refused with
    a message that names the function:

    >>> import numpy as np
    >>> from rigidbody.core.validate import returned
    >>> def torque(t, y):
    ...     return [0.0, 0.0, -0.1 * y[2]]
    >>> returned(torque(0.0, np.ones(3)), torque, (3,), role="the torque")
    array([ 0. ,  0. , -0.1])
    >>> returned(np.array([[0.0, 0.0, 1.0]]), torque, (5, 3)).shape
    (1, 3)
    >>> returned(1.0, torque, (3,), role="the torque")
    Traceback (most recent call last):
        ...
    rigidbody.core.validate.ResultValueError: the torque <function torque at 0x...> returned a scalar (1.0); ...
    """
    if type(value) is np.ndarray and value.dtype == np.float64 and (value.shape == shape or _fits(value.shape, shape)):
        a = value  # the common cases: the shape itself, or the compact shape a vectorised function returns
    else:
        a = _result_array(value, fun, shape, role)
    if finite and not np.isfinite(a).all():
        raise ResultValueError(result_message(fun, shape, "non-finite values (NaN or inf)", role))
    return a


def result_message(fun: Any, shape: tuple[int, ...], problem: str, role: str = "the function") -> str:
    """The message of :func:`returned`: who returned what, and what was expected.

    Parameters
    ----------
    fun : callable
        The user's function (shown by its repr).
    shape : tuple of int
        The shape expected.
    problem : str
        What it returned instead.
    role : str
        What the function is (``'the torque'``).

    Returns
    -------
    str

    See Also
    --------
    returned : the check that raises with this message.

    Examples
    --------
    >>> from rigidbody.core.validate import result_message
    >>> print(result_message(abs, (10, 3), "complex numbers", role="the field"))
    the field <built-in function abs> returned complex numbers; expected finite real numbers of shape (..., 3), here
    (10, 3) (or broadcasting to it)
    """
    return (f"{role} {fun!r} returned {problem}; expected finite real numbers of shape (..., {shape[-1]}), here "
            f"{shape} (or broadcasting to it)")


def _result_array(value: Any, fun: Any, shape: tuple[int, ...], role: str) -> np.ndarray:
    if value is None:
        raise ResultTypeError(result_message(fun, shape, "None", role))
    if isinstance(value, (str, bytes)):
        raise ResultTypeError(result_message(fun, shape, f"text {value!r}", role))
    if np.iscomplexobj(value):
        raise ResultTypeError(result_message(fun, shape, "complex numbers", role))
    try:
        a = np.asarray(value)
    except (TypeError, ValueError):
        a = np.empty(0, dtype=object)
    if a.dtype.kind not in "fiu":
        what = f"{a.dtype.name} values" if a.dtype != object else f"a {type(value).__name__}"
        raise ResultTypeError(result_message(fun, shape, f"{what}, not real numbers", role))
    a = a.astype(float, copy=False)
    if a.ndim == 0:
        raise ResultValueError(result_message(fun, shape, f"a scalar ({float(a)!r})", role))
    if not _fits(a.shape, shape):
        raise ResultValueError(result_message(fun, shape, f"an array of shape {a.shape}", role))
    return a


@functools.lru_cache(maxsize=256)
def _fits(got: tuple[int, ...], shape: tuple[int, ...]) -> bool:
    """Whether an array of shape ``got`` (not a scalar) broadcasts to ``shape`` with the same last axis (cached: a
    run asks for the same pair of shapes at every step)."""
    try:
        return len(got) > 0 and got[-1] == shape[-1] and np.broadcast_shapes(got, shape) == shape
    except ValueError:
        return False
