"""The API pages of functions and classes end with "Examples using X": the gallery scripts that call them.

sphinx-gallery writes, per ``rigidbody`` name an example calls, an ``<name>.examples`` file of thumbnails into
``backreferences_dir``; the autosummary templates of ``docs/_templates`` include it on the name's page. This
test is static and cheap: it reads the configuration and renders the templates the way autosummary looks them
up (project templates first, Sphinx's own as fallback). Whether the thumbnails really appear needs the full
build with the gallery executed (minutes, far over the default run's budget): CI builds the site with the
command of CONTRIBUTING.md, where a missing ``.examples`` file is an include warning and so an error.
"""

from __future__ import annotations

import runpy
from pathlib import Path
from typing import Any

import pytest
import sphinx
from jinja2.sandbox import SandboxedEnvironment
from sphinx.util import rst
from sphinx.util.template import SphinxTemplateLoader

DOCS = Path(__file__).resolve().parents[2] / "docs"


@pytest.fixture(scope="module")
def conf() -> dict[str, Any]:
    return runpy.run_path(str(DOCS / "conf.py"))


def _render(conf: dict[str, Any], objtype: str, module: str, objname: str) -> str:
    """The autosummary page of ``module.objname``, with the template autosummary picks for ``objtype``."""
    system = [Path(sphinx.__file__).parent / "ext" / "autosummary" / "templates"]
    env = SandboxedEnvironment(loader=SphinxTemplateLoader(str(DOCS), conf["templates_path"], system))
    env.filters["escape"] = rst.escape
    env.filters["underline"] = lambda text, line="=": f"{text}\n{line * len(text)}"
    context = dict(fullname=f"{module}.{objname}", module=module, objname=objname, name=objname,
                   objtype=objtype, methods=["plot"], attributes=["t"], _=lambda s: s)
    # autosummary's lookup: the template named after the object type, else base.rst (which has no include)
    name = f"autosummary/{objtype}.rst"
    return env.get_or_select_template([name, "autosummary/base.rst"]).render(context)


def test_the_gallery_records_which_examples_use_each_rigidbody_name(conf: dict[str, Any]) -> None:
    sg = conf["sphinx_gallery_conf"]
    # sphinx-gallery keeps a name when ``module.startswith(doc_module)``: a str or a tuple of prefixes
    assert "rigidbody" in sg["doc_module"]
    assert sg["backreferences_dir"], "no backreferences_dir: sphinx-gallery writes no .examples files"
    assert "sphinx_gallery.gen_gallery" in conf["extensions"]
    assert "sphinx.ext.autodoc" in conf["extensions"]  # its docstring event makes the empty .examples files


@pytest.mark.parametrize(("objtype", "module", "objname"), [
    ("function", "rigidbody.euler_poinsot", "averaged"),
    ("class", "rigidbody.lagrange", "Top"),
])
def test_the_api_page_includes_the_examples_that_use_the_name(conf: dict[str, Any], objtype: str, module: str,
                                                              objname: str) -> None:
    page = _render(conf, objtype, module, objname)
    backrefs = conf["sphinx_gallery_conf"]["backreferences_dir"].strip("/")
    include = f".. include:: /{backrefs}/{module}.{objname}.examples"
    # unindented: the file starts with a section heading, which is an error inside a directive's body
    assert include in page.splitlines(), f"the {objtype} template does not include {include!r}:\n{page}"
    # the page still documents the object itself
    assert f".. auto{objtype}:: {objname}" in page
