"""The examples in the core docstrings run and give what they say."""

import doctest

import pytest

from rigidbody.core import averaging, dop853, elliptic, euler, ode, quadform, validate


@pytest.mark.parametrize("module", [averaging, dop853, elliptic, euler, ode, quadform, validate])
def test_docstring_examples(module):
    result = doctest.testmod(module, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert result.failed == 0
