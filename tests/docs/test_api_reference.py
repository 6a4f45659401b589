"""Every public name of every module appears in the API reference (docs/api/*.rst).

The reference pages list names in autosummary blocks under a ``.. currentmodule::``; a name added to a
module's ``__all__`` and forgotten there fails here, so the site never silently lacks a public name.
"""

from __future__ import annotations

import importlib
import re
import types
from pathlib import Path

import pytest

API = Path(__file__).resolve().parents[2] / "docs" / "api"

# the public modules: each analysis, the plotting helpers, the figure registry and the paper-figure functions,
# and every core submodule
MODULES = [
    "rigidbody.gyrostat",
    "rigidbody.lagrange",
    "rigidbody.euler_poinsot",
    "rigidbody.viscous",
    "rigidbody.plotting",
    "rigidbody.paperfigs",
    "rigidbody.paperfigs.lagrange",
    "rigidbody.paperfigs.euler_poinsot",
    "rigidbody.paperfigs.gyrostat",
    "rigidbody.paperfigs.viscous",
    "rigidbody.paperfigs.studies",
    "rigidbody.sweep",
    "rigidbody.studies",
    "rigidbody.studies.explorer1",
] + [f"rigidbody.core.{name}" for name in importlib.import_module("rigidbody.core").__all__]


def documented() -> dict[str, set[str]]:
    """Names listed in autosummary blocks of docs/api/*.rst, by their ``currentmodule``."""
    names: dict[str, set[str]] = {}
    for page in sorted(API.glob("*.rst")):
        module = None
        in_summary = False
        for line in page.read_text(encoding="utf-8").splitlines():
            m = re.match(r"\.\. currentmodule:: (\S+)", line)
            if m:
                module, in_summary = m.group(1), False
                continue
            if line.startswith(".. autosummary::"):
                in_summary = True
                continue
            if in_summary and line.startswith("   ") and not line.strip().startswith(":"):
                if line.strip() and module is not None:
                    names.setdefault(module, set()).add(line.strip())
            elif in_summary and line.strip() and not line.startswith("   "):
                in_summary = False
    return names


@pytest.mark.parametrize("module_name", MODULES)
def test_every_public_name_is_in_the_api_reference(module_name: str) -> None:
    module = importlib.import_module(module_name)
    public = {
        name for name in module.__all__
        # submodules re-exported by a namespace are documented by their own names, not as entries
        if not isinstance(getattr(module, name), types.ModuleType)
    }
    missing = public - documented().get(module_name, set())
    assert not missing, f"{module_name}: add {sorted(missing)} to an autosummary block in docs/api/"


def test_reference_lists_no_name_that_does_not_exist() -> None:
    for module_name, names in documented().items():
        module = importlib.import_module(module_name)
        stale = {n for n in names if not hasattr(module, n)}
        assert not stale, f"docs/api lists {sorted(stale)} that {module_name} does not have"


def test_the_parser_sees_the_reference() -> None:
    # guards the two tests above against passing vacuously (a parser that finds nothing)
    names = documented()
    assert "Solution" in names["rigidbody.core.ode"]
    assert "averaged" in names["rigidbody.lagrange"]
