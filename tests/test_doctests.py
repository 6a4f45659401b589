"""The examples in the docstrings run and print what they say, in every module of the package.

The modules are found by walking the package (the private implementation modules included: the public
functions are defined there), so an example added anywhere is collected without a list to update. The
examples print rounded numbers and identities, never the last bits of a float, so they hold on every
machine. Matplotlib draws off-screen (tests/conftest.py); the figures a module's examples open are closed
after it.
"""

from __future__ import annotations

import doctest
import importlib
import pkgutil

import matplotlib.pyplot as plt
import pytest

import rigidbody

MODULES = sorted(info.name for info in pkgutil.walk_packages(rigidbody.__path__, f"{rigidbody.__name__}."))
FLAGS = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE


def examples(module_name: str) -> list[doctest.DocTest]:
    """The docstring examples defined in the module (not those of names it imports)."""
    module = importlib.import_module(module_name)
    return [t for t in doctest.DocTestFinder(exclude_empty=True).find(module, module_name) if t.examples]


@pytest.mark.parametrize("module_name", MODULES)
def test_docstring_examples(module_name: str) -> None:
    report: list[str] = []
    runner = doctest.DocTestRunner(optionflags=FLAGS)
    try:
        for test in examples(module_name):
            runner.run(test, out=report.append)
    finally:
        plt.close("all")
    assert runner.failures == 0, "".join(report)


def test_the_walk_finds_the_examples() -> None:
    # guards the test above against passing vacuously (a walk that finds no module or no example)
    assert {"rigidbody.core.elliptic", "rigidbody.gyrostat._model", "rigidbody.paperfigs.viscous"} <= set(MODULES)
    assert examples("rigidbody.core.elliptic")
