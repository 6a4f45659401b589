"""Docstrings link the documentation pages instead of naming their files.

On the API pages a file path such as ``docs/euler_poinsot.md`` is dead text (an installed package has no docs/
folder); a cross-reference (``:doc:`/euler_poinsot```, ``:ref:`ep-any-torque```) renders as a link. Every
docstring of every module of the package is read (those of private modules too: their functions and classes are
the public names, re-exported), with the attribute comments ``#:`` that autodoc renders as docstrings.
"""

from __future__ import annotations

import doctest
import importlib
import pkgutil
import re
from pathlib import Path

import pytest

import rigidbody

MODULES = sorted(info.name for info in pkgutil.walk_packages(rigidbody.__path__, f"{rigidbody.__name__}."))
SRC = Path(rigidbody.__file__).resolve().parent
# "docs/" followed by a file name: a page (docs/sweeps.md), a notebook or an API source (docs/api/core.rst)
FILE_PATH = re.compile(r"docs/[\w./-]*\w\.(?:md|rst|ipynb|py)\b")


def docstrings(module_name: str) -> dict[str, str]:
    """The docstrings of the module and of everything defined in it (functions, classes, methods, properties)."""
    module = importlib.import_module(module_name)
    finder = doctest.DocTestFinder(exclude_empty=False)
    return {t.name: t.docstring or "" for t in finder.find(module, module_name)}


@pytest.mark.parametrize("module_name", MODULES)
def test_no_docstring_names_a_docs_file(module_name: str) -> None:
    found = {name: FILE_PATH.findall(doc) for name, doc in docstrings(module_name).items()}
    found = {name: paths for name, paths in found.items() if paths}
    assert not found, f"link the page (:doc:`/page` or :ref:`label`) instead of naming its file: {found}"


def test_no_attribute_comment_names_a_docs_file() -> None:
    bad = [f"{path.relative_to(SRC)}:{i}" for path in sorted(SRC.rglob("*.py"))
           for i, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1)
           if line.lstrip().startswith("#:") and FILE_PATH.search(line)]
    assert not bad, f"an attribute comment (#:, rendered by autodoc) names a docs file: {bad}"


def test_the_pattern_and_the_walk_see_what_they_must() -> None:
    # guards the tests above against passing vacuously: the pattern matches the paths once written, not the
    # links that replaced them; the walk reaches a private module's method docstrings
    assert FILE_PATH.findall('see ``docs/euler_poinsot.md``, "Any torque"') == ["docs/euler_poinsot.md"]
    assert FILE_PATH.search("(docs/sweeps.md says how)") and FILE_PATH.search("docs/api/core.rst")
    assert not FILE_PATH.search("see :doc:`/sweeps` and :ref:`ep-any-torque`")
    found = docstrings("rigidbody.euler_poinsot._protocol")
    assert "rigidbody.euler_poinsot._protocol.Torque.closed_mean" in found
    assert ":doc:`/euler_poinsot`" in found["rigidbody.euler_poinsot._protocol.Torque"]
