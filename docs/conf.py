"""Sphinx configuration of the rigidbody documentation.

Build (no network needed): ``python -m pip install ".[docs]" && python -m sphinx -W --keep-going -b html docs
docs/_build/html``. MyST-NB reads the Markdown pages and executes the tutorial notebooks, numpydoc renders
the docstrings, autosummary writes one page per public name, sphinx-gallery runs ``examples/``. The site
needs no network to read either: MathJax is served from the site itself (``_static/mathjax``, copied there
by ``sphinx-mathjax-offline``), not from a CDN.
"""

from __future__ import annotations

import sys
from pathlib import Path

import rigidbody

sys.path.insert(0, str(Path(__file__).resolve().parent))  # gallery_order.py, paper_equations.py

project = "rigidbody"
author = "rigidbody developers"
copyright = "the rigidbody developers"
release = rigidbody.__version__
version = release

extensions = [
    "myst_nb",
    "numpydoc",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx-mathjax-offline",  # MathJax 3 and its fonts copied into the site: equations render offline
    "sphinx.ext.viewcode",  # [source] links: a gallery figure's function leads to the code that draws it
    "sphinx_gallery.gen_gallery",
    "paper_equations",  # docs/paper_equations.py: $$ ... $$ (eq-lagrange-3-4) is numbered (3.4), as in the paper
]

source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}
root_doc = "index"
# sphinx-gallery writes a notebook, a copy of the script and a zip beside each page (in every section):
# only its .rst pages are sources
exclude_patterns = ["_build", "auto_examples/**.ipynb", "auto_examples/**.py", "auto_examples/**.zip",
                    "**.md5", "**.codeobj.json", "**.cost.json", "**sg_execution_times.rst"]

# MyST: $...$ and $$...$$ math as in the theory pages, definition lists, heading anchors for cross links
myst_enable_extensions = ["dollarmath", "amsmath", "deflist", "colon_fence"]
myst_heading_anchors = 3
myst_dmath_double_inline = True

# MathJax from the site's own _static folder (the files sphinx-mathjax-offline copies), never from a CDN
mathjax_path = "mathjax/tex-chtml.js"

# MyST-NB: the tutorials are stored without outputs and executed on every build; an error fails the build
nb_execution_mode = "force"
nb_execution_raise_on_error = True
nb_execution_timeout = 300
nb_merge_streams = True
# no notebook shows widgets: no RequireJS or widget bundle from a CDN on the notebook pages
nb_ipywidgets_js: dict[str, dict[str, str]] = {}

# autosummary / autodoc / numpydoc; the function and class page templates add the gallery back-links
templates_path = ["_templates"]
autosummary_generate = True
autosummary_imported_members = True
autodoc_typehints = "none"  # numpydoc's Parameters sections carry the types
# signatures show defaults as written in the source (``delta0=pi / 4``, not ``delta0=0.7853981633974483``)
autodoc_preserve_defaults = True
# a class page documents its methods, properties and fields, so the Methods and Attributes tables of the
# autosummary class template link to them (the API pages' automodule directives say :no-members:)
autodoc_default_options = {"members": True, "undoc-members": True}
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
numpydoc_validation_checks: set[str] = set()

# sphinx-gallery: every script in examples/ is run and gets a page with its figures; one section per paper
# (in the order of the theory pages), the paper's figures first in each
sphinx_gallery_conf = {
    "examples_dirs": ["../examples"],
    "gallery_dirs": ["auto_examples"],
    "filename_pattern": r".*\.py$",
    "ignore_pattern": r"__init__\.py",
    "download_all_examples": False,
    "remove_config_comments": True,
    "subsection_order": ["../examples/gyrostat", "../examples/lagrange", "../examples/euler_poinsot",
                         "../examples/viscous", "*", "../examples/core"],
    "within_subsection_order": "gallery_order.PaperFiguresFirst",
    "matplotlib_animations": False,
    "image_scrapers": ("matplotlib",),
    "reference_url": {},
    "show_memory": False,
    "abort_on_example_error": True,
    "only_warn_on_example_error": False,
    # "Examples using X" on the API pages: each example's calls of rigidbody names are listed, per name, in
    # an ``<name>.examples`` file beside the autosummary pages; _templates/autosummary/{function,class}.rst
    # include it (empty for a name no example calls)
    "doc_module": ("rigidbody",),
    "backreferences_dir": "api/generated",
}

html_theme = "furo"
html_title = f"rigidbody {release}"
html_static_path: list[str] = []
