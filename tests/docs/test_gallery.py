"""The gallery (examples/) and the figure registry (python -m rigidbody figures) list the same figures.

Every figure registered in :mod:`rigidbody.paperfigs` has the script ``examples/<set>/<name>.py`` that calls
the same function, and every paper-figure script (``fig<N>_<slug>.py``) is registered: a figure is drawn by
one piece of code, reachable from both. Every script has the reStructuredText title sphinx-gallery needs,
imports only public modules, and runs on its own.
"""

from __future__ import annotations

import ast
import os
import subprocess
import sys
from pathlib import Path

import pytest

from rigidbody.paperfigs import PAPER_FIGURE, registry

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
SCRIPTS = sorted(EXAMPLES.rglob("*.py"))
# every figure set has a gallery folder named after it
SETS = ("lagrange", "euler_poinsot", "gyrostat", "viscous", "studies")


def _paper_scripts() -> set[str]:
    return {f"{p.parent.name}/{p.stem}" for p in SCRIPTS if PAPER_FIGURE.match(p.stem)}


def test_registry_and_gallery_list_the_same_paper_figures() -> None:
    registered = {f"{s}/{f}" for s, fs in registry().items() for f in fs.paper_figures}
    assert registered == _paper_scripts()
    # guard against a vacuous pass: the papers' 1 + 3 + 6 + 5 figures
    assert len(registered) == 15


@pytest.mark.parametrize("set_name", SETS)
def test_every_registered_figure_has_a_script_calling_its_function(set_name: str) -> None:
    fs = registry()[set_name]
    for name, func in fs.figures.items():
        path = EXAMPLES / set_name / f"{name}.py"
        assert path.exists(), f"{set_name}/{name} is registered but examples/{set_name}/{name}.py is missing"
        tree = ast.parse(path.read_text(encoding="utf-8"))
        called = {node.func.attr for node in ast.walk(tree)
                  if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)}
        assert func.__name__ in called, f"examples/{set_name}/{name}.py does not call {func.__name__}"
        imported = {node.module for node in ast.walk(tree) if isinstance(node, ast.ImportFrom)}
        assert "rigidbody.paperfigs" in imported or f"rigidbody.paperfigs.{set_name}" in imported


@pytest.mark.parametrize("path", SCRIPTS, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_script_has_a_title_and_imports_only_public_modules(path: Path) -> None:
    doc = ast.get_docstring(ast.parse(path.read_text(encoding="utf-8")), clean=False)
    assert doc, "a gallery script starts with a docstring"
    lines = doc.strip("\n").splitlines()
    assert len(lines) >= 3 and set(lines[1]) == {"="} and len(lines[1]) >= len(lines[0]), (
        "the docstring starts with a reStructuredText title (a line underlined with '=')")
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        modules = ([node.module or ""] if isinstance(node, ast.ImportFrom)
                   else [a.name for a in node.names] if isinstance(node, ast.Import) else [])
        for module in modules:
            if module.split(".")[0] == "rigidbody":
                assert not any(part.startswith("_") for part in module.split(".")), f"private import {module}"


def test_every_gallery_folder_has_a_header() -> None:
    for folder in {p.parent for p in SCRIPTS}:
        assert (folder / "README.rst").exists() or (folder / "GALLERY_HEADER.rst").exists(), folder


def _run(path: Path, cwd: Path) -> subprocess.CompletedProcess:
    env = dict(os.environ, MPLBACKEND="Agg")
    return subprocess.run([sys.executable, str(path)], cwd=cwd, env=env, capture_output=True, text=True, timeout=300)


# one quick script per paper in the default run (the docs build runs them all; `-m slow` runs them all here)
QUICK = ["lagrange/fig3_case3_theta170.py", "euler_poinsot/fig4_hodograph_case2.py", "gyrostat/fig1_dumbbell.py",
         "viscous/fig4_turn_contracting.py"]


@pytest.mark.parametrize("name", QUICK)
def test_script_runs_on_its_own_and_writes_nothing(name: str, tmp_path: Path) -> None:
    out = _run(EXAMPLES / name, tmp_path)
    assert out.returncode == 0, out.stderr
    assert list(tmp_path.iterdir()) == []


@pytest.mark.slow
@pytest.mark.parametrize("path", SCRIPTS, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_every_script_runs_on_its_own(path: Path, tmp_path: Path) -> None:
    out = _run(path, tmp_path)
    assert out.returncode == 0, out.stderr
