"""Shared by the documentation tests: a real Sphinx build of a few pages with the site's own configuration.

The build runs in a subprocess with warnings as errors, with ``docs/conf.py`` less what needs the whole tree
(the gallery, the API pages, notebook execution); a few pages take a few seconds. The complete site is built
by CI with the command of CONTRIBUTING.md.
"""

from __future__ import annotations

import os
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"

CONF = """\
import runpy

globals().update({{k: v for k, v in runpy.run_path({conf!r}).items() if not k.startswith("__")}})
extensions = [e for e in extensions if e not in {{"sphinx_gallery.gen_gallery", "sphinx.ext.autosummary",
                                               "sphinx.ext.autodoc", "numpydoc", "sphinx.ext.viewcode"}}]
del sphinx_gallery_conf
nb_execution_mode = "off"
"""


@pytest.fixture(scope="session")
def build_site(tmp_path_factory: pytest.TempPathFactory) -> Callable[[dict[str, str]], Path]:
    """A function that builds pages ``{name: Markdown text}`` (under one toctree) and returns the HTML folder."""

    def build(pages: dict[str, str]) -> Path:
        src = tmp_path_factory.mktemp("src")
        out = tmp_path_factory.mktemp("html")
        (src / "conf.py").write_text(CONF.format(conf=str(DOCS / "conf.py")), encoding="utf-8")
        toctree = "\n".join(pages)
        (src / "index.md").write_text(f"# Pages\n\n```{{toctree}}\n{toctree}\n```\n", encoding="utf-8")
        for name, text in pages.items():
            (src / f"{name}.md").parent.mkdir(parents=True, exist_ok=True)  # a page in a folder: howto/...
            (src / f"{name}.md").write_text(text, encoding="utf-8")
        env = dict(os.environ,
                   PYTHONPATH=os.pathsep.join(p for p in (str(ROOT / "src"), os.environ.get("PYTHONPATH")) if p))
        result = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html",
                                 str(src), str(out)], env=env, capture_output=True, text=True, timeout=300,
                                check=False)
        assert result.returncode == 0, f"the Sphinx build failed:\n{result.stdout}\n{result.stderr}"
        return out

    return build
