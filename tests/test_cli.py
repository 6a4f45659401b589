"""The figures command and the registry."""

import subprocess
import sys
import textwrap

import pytest

import rigidbody
from rigidbody import paperfigs
from rigidbody.paperfigs import PAPER_FIGURE, registry


def _run(args, cwd):
    return subprocess.run([sys.executable, "-m", "rigidbody", "figures", *args], cwd=cwd, capture_output=True,
                          text=True, timeout=300)


def test_version():
    assert isinstance(rigidbody.__version__, str) and rigidbody.__version__


def test_figures_list_runs_from_any_directory(tmp_path):
    out = _run(["--list"], tmp_path)
    assert out.returncode == 0, out.stderr
    for name, fs in registry().items():
        assert name in out.stdout
        for fig in fs.figures:
            assert f"{name}/{fig}" in out.stdout


def test_paper_figures_of_every_set_are_numbered_once_from_1():
    # the four papers: Stepanov's one figure, Lagrange figs 1-3, Rachinskaya figs 1-6, Krivtsov figs 1-5
    expected = {"gyrostat": 1, "lagrange": 3, "euler_poinsot": 6, "viscous": 5}
    reg = registry()
    for name, count in expected.items():
        numbers = [int(PAPER_FIGURE.match(f)["number"]) for f in reg[name].paper_figures]
        assert numbers == list(range(1, count + 1)), name


def test_only_one_figure_writes_exactly_that_file(tmp_path):
    out = _run(["--only", "lagrange/fig3_case3_theta170", "--out", str(tmp_path)], tmp_path)
    assert out.returncode == 0, out.stderr
    written = sorted(p.relative_to(tmp_path).as_posix() for p in tmp_path.rglob("*.png"))
    assert written == ["lagrange/fig3_case3_theta170.png"]


def test_unknown_figure_set_is_an_error(tmp_path):
    out = _run(["--only", "nope", "--out", str(tmp_path)], tmp_path)
    assert out.returncode == 2
    assert "unknown figure set" in out.stderr


def test_unknown_figure_is_an_error_naming_the_set_s_figures(tmp_path):
    out = _run(["--only", "lagrange/fig9_nope", "--out", str(tmp_path)], tmp_path)
    assert out.returncode == 2
    assert "unknown figure lagrange/fig9_nope" in out.stderr and "fig1_case1_theta5" in out.stderr


def test_register_figures_refuses_bad_names_and_a_figure_number_twice():
    def draw():  # never called
        raise AssertionError

    with pytest.raises(ValueError, match="lower case"):
        paperfigs.register_figures("test_only", "x", {"Fig1_bad": draw})
    with pytest.raises(ValueError, match="figure 2 of 'test_only' is registered twice"):
        paperfigs.register_figures("test_only", "x", {"fig2_a": draw, "fig2_b": draw})
    assert "test_only" not in registry()


def test_a_builder_registered_by_decorator_still_works(tmp_path):
    calls = []

    @paperfigs.register("test_decorated", "x")
    def build(outdir):
        calls.append(outdir)
        return []

    try:
        fs = registry()["test_decorated"]
        assert fs.figures == {} and fs.paper_figures == ()
        assert fs.build(tmp_path) == [] and calls == [tmp_path]
        with pytest.raises(ValueError, match="no individually named figures"):
            fs.build(tmp_path, only=["a"])
    finally:
        paperfigs._REGISTRY.pop("test_decorated")


# the optional dependencies (the sweep extra); the base install is numpy, scipy, matplotlib
EXTRAS = ("xarray", "dask", "distributed", "zarr", "tqdm")

# runs in a fresh interpreter: an import finder refuses the extras before anything is imported, then the figures
# command draws the studies set. The grids are cut to two values per axis to keep the test light (which modules
# a figure imports does not depend on the size of its grid).
_BASE_INSTALL = textwrap.dedent("""
    import sys

    tried = []

    class NotInstalled:
        def find_spec(self, name, path=None, target=None):
            if name.split(".")[0] in {extras!r}:
                tried.append(name)
                raise ImportError(f"No module named {{name!r}} (blocked: not in the base install)")
            return None

    sys.meta_path.insert(0, NotInstalled())
    import numpy as np
    from rigidbody import studies
    from rigidbody.__main__ import main

    studies.GRIDS["averaging_euler_poinsot"]["quick"] = {{"eps": np.array([0.08, 0.04]), "k2_0": np.array([0.5, 0.9])}}
    studies.GRIDS["averaging_lagrange"]["quick"] = {{"eps": np.array([0.08, 0.04]), "theta0": np.array([0.5, 1.5])}}
    studies.GRIDS["spin_end"]["quick"] = {{"r1": np.linspace(0.2, 2.4, 5), "r3": np.linspace(0.2, 2.4, 5)}}
    code = main(["figures", "--only", "studies", "--out", sys.argv[1]])
    imported = sorted({{m.split(".")[0] for m in sys.modules}} & set({extras!r}))
    print("tried to import:", sorted(set(tried)), "imported:", imported)
    sys.exit(code)
""")


def test_study_figures_need_no_optional_dependency(tmp_path):
    # the README's first command must work after a plain `pip install .`: no figure may need the sweep extra
    code = _BASE_INSTALL.format(extras=EXTRAS)
    out = subprocess.run([sys.executable, "-c", code, str(tmp_path)], cwd=tmp_path, capture_output=True, text=True,
                         timeout=300)
    assert out.returncode == 0, out.stdout + out.stderr
    assert "tried to import: [] imported: []" in out.stdout, out.stdout
    written = sorted(p.relative_to(tmp_path).as_posix() for p in tmp_path.rglob("*.png"))
    assert written == sorted(f"studies/{name}.png" for name in registry()["studies"].figures)
    assert all(p.stat().st_size > 10_000 for p in tmp_path.rglob("*.png"))  # drawn, not empty canvases
