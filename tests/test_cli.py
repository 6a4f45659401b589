"""The figures command and the registry."""

import subprocess
import sys

import rigidbody
from rigidbody.paperfigs import registry


def test_version():
    assert isinstance(rigidbody.__version__, str) and rigidbody.__version__


def test_figures_list_runs_from_any_directory(tmp_path):
    out = subprocess.run([sys.executable, "-m", "rigidbody", "figures", "--list"], cwd=tmp_path,
                         capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    for name in registry():
        assert name in out.stdout


def test_unknown_figure_set_is_an_error(tmp_path):
    out = subprocess.run([sys.executable, "-m", "rigidbody", "figures", "--only", "nope", "--out", str(tmp_path)],
                         cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert out.returncode == 2
    assert "unknown figure set" in out.stderr
