"""The gallery (examples/) and the figure registry (python -m rigidbody figures) list the same figures.

Every figure registered in :mod:`rigidbody.paperfigs` has the script ``examples/<set>/<name>.py`` that calls
the same function, and every paper-figure script (``fig<N>_<slug>.py``) is registered: a figure is drawn by
one piece of code, reachable from both. A figure's script shows its computation: it calls the public
computing functions of its analysis (``averaged``, ``simulate``, ``axis_path``, ...) itself and hands their
results to the drawing function, and what it draws is what the command draws. Every script has the
reStructuredText title sphinx-gallery needs, imports only public modules, and runs on its own.
"""

from __future__ import annotations

import ast
import inspect
import os
import runpy
import subprocess
import sys
from pathlib import Path
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
import pytest

from rigidbody.paperfigs import PAPER_FIGURE, registry

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
SCRIPTS = sorted(EXAMPLES.rglob("*.py"))


def _paper_scripts() -> set[str]:
    return {f"{p.parent.name}/{p.stem}" for p in SCRIPTS if PAPER_FIGURE.match(p.stem)}


def test_registry_and_gallery_list_the_same_paper_figures() -> None:
    registered = {f"{s}/{f}" for s, fs in registry().items() for f in fs.paper_figures}
    assert registered == _paper_scripts()
    # guard against a vacuous pass: the papers' 1 + 3 + 6 + 5 figures
    assert len(registered) == 15
    # every figure set has a gallery folder named after it, and its computing functions listed below
    assert set(registry()) == set(COMPUTING) == {p.parent.name for p in SCRIPTS} - {"core"}


# the public functions of each set's analysis that compute what a figure shows (not its case: Body, Top, ...)
COMPUTING = {
    "lagrange": ("rigidbody.lagrange", {"averaged", "simulate"}),
    "euler_poinsot": ("rigidbody.euler_poinsot", {"averaged", "simulate", "averaged_branches", "average_torque",
                                                  "averaged_rates"}),
    "gyrostat": ("rigidbody.gyrostat", {"stationary_motion", "symmetric_stationary_motion", "stability",
                                        "stability_map", "normalized_stability_map", "symmetric_stability_map"}),
    "viscous": ("rigidbody.viscous", {"ball_and_rod", "axis_path", "simulate", "turn", "quasi_coordinates"}),
    "studies": ("rigidbody.studies", {"evaluate"}),
}


def _calls(tree: ast.AST, module: str) -> list[ast.Call]:
    """The calls in ``tree`` of functions of ``module``, however it is imported (``from rigidbody import
    lagrange``, ``import rigidbody.lagrange as lg``, ``from rigidbody.lagrange import averaged``)."""
    parent, _, leaf = module.rpartition(".")
    aliases, direct = set(), {}
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.module == parent:
            aliases |= {a.asname or a.name for a in node.names if a.name == leaf}
        elif isinstance(node, ast.ImportFrom) and node.module == module:
            direct |= {(a.asname or a.name): a.name for a in node.names}
        elif isinstance(node, ast.Import):
            aliases |= {a.asname for a in node.names if a.name == module and a.asname}
    out = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.Call):
            continue
        f = node.func
        if isinstance(f, ast.Attribute) and isinstance(f.value, ast.Name) and f.value.id in aliases:
            out.append(node)
        elif isinstance(f, ast.Name) and f.id in direct:
            out.append(node)
    return out


def _called_name(call: ast.Call) -> str:
    return call.func.attr if isinstance(call.func, ast.Attribute) else call.func.id  # type: ignore[attr-defined]


def test_call_finder_sees_every_form_of_import() -> None:
    # guards the next test against passing or failing for the way a script imports its analysis
    src = ("import rigidbody.lagrange as lg\nfrom rigidbody import lagrange\nfrom rigidbody.lagrange import simulate\n"
           "from rigidbody.paperfigs import lagrange as figs\n"
           "lg.averaged(1)\nlagrange.Top(2)\nsimulate(3)\nfigs.averaged(4)\nnp.averaged(5)\n")
    found = [_called_name(c) for c in _calls(ast.parse(src), "rigidbody.lagrange")]
    assert sorted(found) == ["Top", "averaged", "simulate"]


def _figure_scripts() -> list[tuple[str, str]]:
    return [(s, f) for s, fs in registry().items() for f in fs.figures]


@pytest.mark.parametrize(("set_name", "name"), _figure_scripts(), ids=lambda x: x)
def test_figure_script_computes_with_the_analysis_and_hands_the_result_to_the_drawing(set_name: str,
                                                                                       name: str) -> None:
    """The page of a figure shows the computation: a call of a public computing function of its analysis
    (not a figure module's data helper), and the drawing function given data when it takes any."""
    tree = ast.parse((EXAMPLES / set_name / f"{name}.py").read_text(encoding="utf-8"))
    module, computing = COMPUTING[set_name]
    called = {_called_name(c) for c in _calls(tree, module)}
    assert called & computing, (f"examples/{set_name}/{name}.py computes nothing with {module} itself "
                                f"(none of {sorted(computing)})")
    func = registry()[set_name].figures[name]
    draws = [c for c in _calls(tree, f"rigidbody.paperfigs.{set_name}") if _called_name(c) == func.__name__]
    assert draws, f"examples/{set_name}/{name}.py does not draw with {func.__name__}"
    if inspect.signature(func).parameters:
        assert all(c.args or c.keywords for c in draws), f"{func.__name__} is called without the script's data"


def _shown(fig: Any) -> list[Any]:
    """What a figure shows: its texts and the data of its lines, collections and images, axes by axes."""
    out: list[Any] = [fig.get_suptitle()]
    for ax in fig.axes:
        out += [ax.get_title(), ax.get_xlabel(), ax.get_ylabel(), *(t.get_text() for t in ax.texts)]
        for line in ax.get_lines():
            out.append(np.asarray(line.get_data_3d() if hasattr(line, "get_data_3d") else line.get_xydata(), float))
        for coll in ax.collections:
            out.append(np.asarray(coll.get_offsets(), float))
            if coll.get_array() is not None:
                out.append(np.asarray(coll.get_array(), float))
    return out


def _run_in_process(path: Path) -> list[Any]:
    """Run a gallery script as sphinx-gallery does (as ``__main__``, in this process); its open figures."""
    plt.close("all")
    runpy.run_path(str(path), run_name="__main__")
    figs = [plt.figure(n) for n in plt.get_fignums()]
    return figs


def _paper_first(items: list[tuple[str, str]]) -> list[Any]:
    # the paper's figures in the default run (a second each); the other figures with -m slow
    return [pytest.param(s, f, marks=() if PAPER_FIGURE.match(f) else pytest.mark.slow) for s, f in items]


@pytest.mark.parametrize(("set_name", "name"), _paper_first(_figure_scripts()), ids=lambda x: x)
def test_figure_script_runs_and_draws_what_the_figures_command_draws(set_name: str, name: str) -> None:
    """One source for each figure: the script's literal case and calls give the figure of the command."""
    try:
        (shown,) = _run_in_process(EXAMPLES / set_name / f"{name}.py")
        script = _shown(shown)
        plt.close("all")
        command = _shown(registry()[set_name].figures[name]())
    finally:
        plt.close("all")
    assert len(script) == len(command) and len(script) > 3, "not the same artists (or an empty figure)"
    assert any(isinstance(x, np.ndarray) and x.size > 1 for x in script), "a figure without data"
    for a, b in zip(script, command):
        if isinstance(a, str):
            assert a == b
        else:
            # the same public calls on the same numbers: equal up to a regrouping of the same arithmetic
            # (1e-9); any of the cases' parameters differing (given to 3 or more digits) moves them by far more
            assert a.shape == b.shape
            np.testing.assert_allclose(a, b, rtol=1e-9, atol=1e-12)


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


# two quick scripts in a fresh interpreter in the default run (every figure script runs in this process above;
# the docs build runs them all; `-m slow` runs them all here)
QUICK = ["lagrange/fig3_case3_theta170.py", "viscous/fig4_turn_contracting.py"]


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
