"""Shared scalar validation: the error type and the parameter name reach the user."""

import math

import numpy as np
import pytest

from rigidbody.core.validate import finite_array, positive, real, span


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
