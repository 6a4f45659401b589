"""Shared scalar validation: the error type and the parameter name reach the user."""

import math

import numpy as np
import pytest

from rigidbody.core.validate import (
    RESULT_ERRORS,
    ResultTypeError,
    ResultValueError,
    finite_array,
    positive,
    real,
    returned,
    span,
)


def test_real_accepts_numpy_scalars_and_rejects_bad_input():
    assert real(np.float32(1.5), "x") == 1.5
    assert real(np.int64(3), "x") == 3.0
    with pytest.raises(TypeError, match="alpha must be a real number"):
        real("1.0", "alpha")
    with pytest.raises(TypeError, match="alpha"):
        real(True, "alpha")
    with pytest.raises(ValueError, match="beta must be finite"):
        real(math.nan, "beta")


@pytest.mark.parametrize("bad", [0.0, -1.0, math.inf])
def test_positive(bad):
    with pytest.raises(ValueError, match="mass must be finite and > 0"):
        positive(bad, "mass")
    assert positive(2, "mass") == 2.0


def test_span():
    assert span((0, 1.5), "t_span") == (0.0, 1.5)
    with pytest.raises(ValueError, match="t_span must be finite with end >= start"):
        span((1.0, 0.0), "t_span")
    with pytest.raises(ValueError, match="t_span must be a pair"):
        span(3.0, "t_span")


def test_finite_array():
    np.testing.assert_array_equal(finite_array([1, 2.5], "u"), [1.0, 2.5])
    with pytest.raises(TypeError, match="Gz must be real numbers"):
        finite_array("a", "Gz")
    with pytest.raises(TypeError, match="Gz"):
        finite_array([1 + 2j], "Gz")
    with pytest.raises(ValueError, match="H must be finite"):
        finite_array([0.0, math.inf], "H")


def test_real_shows_numpy_scalars_as_numbers():
    # a batch member (a NumPy scalar) and the single call (a float) must say the same
    with pytest.raises(ValueError) as a:
        real(np.float64("nan"), "k2_0")
    with pytest.raises(ValueError) as b:
        real(math.nan, "k2_0")
    assert str(a.value) == str(b.value) == "k2_0 must be finite, got nan"


def _torque(o):
    return o


@pytest.mark.parametrize(
    ("value", "exc", "what"),
    [
        (None, ResultTypeError, "returned None"),
        (np.ones((4, 3)) * 1j, ResultTypeError, "complex numbers"),
        ([[1 + 0j, 2, 3]], ResultTypeError, "complex numbers"),
        ("abc", ResultTypeError, "text 'abc'"),
        (np.ones((4, 3), dtype=bool), ResultTypeError, "bool values"),
        ({"a": 1}, ResultTypeError, "a dict"),
        (0.5, ResultValueError, r"a scalar \(0.5\)"),
        (np.zeros((4, 2)), ResultValueError, r"an array of shape \(4, 2\)"),
        (np.zeros((5, 3)), ResultValueError, r"an array of shape \(5, 3\)"),
        (np.full((4, 3), np.nan), ResultValueError, "non-finite values"),
        ([0.0, np.inf, 0.0], ResultValueError, "non-finite values"),
    ],
)
def test_returned_names_the_function_and_what_was_wrong(value, exc, what):
    with pytest.raises(exc, match=what) as err:
        returned(value, _torque, (4, 3), role="the torque")
    msg = str(err.value)
    assert msg.startswith(f"the torque {_torque!r} returned ")
    assert "expected finite real numbers of shape (..., 3), here (4, 3)" in msg
    assert isinstance(err.value, RESULT_ERRORS)


def test_returned_accepts_what_broadcasts_and_converts_to_float():
    a = np.arange(12.0).reshape(4, 3)
    assert returned(a, _torque, (4, 3)) is a  # the common case: the array itself
    np.testing.assert_array_equal(returned([1, 2, 3], _torque, (4, 3)), [1.0, 2.0, 3.0])  # a constant
    assert returned(np.ones((1, 3), dtype=np.float32), _torque, (4, 3)).dtype == np.float64
    # a batch tests finiteness per member itself
    assert np.isnan(returned(np.full((4, 3), np.nan), _torque, (4, 3), finite=False)).all()
    with pytest.raises(ResultValueError, match="shape"):
        returned(np.full((4, 2), np.nan), _torque, (4, 3), finite=False)
