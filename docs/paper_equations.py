"""Sphinx extension: a labelled display equation carries the paper's number, read from its label.

The theory pages label each equation they take from a paper with the paper's number,
``$$ ... $$ (eq-lagrange-3-4)`` for (3.4) of the Lagrange paper, ``(eq-euler-poinsot-6)`` for (6) of
Rachinskaya's. Sphinx would number labelled equations (1), (2), ... in page order; this extension gives each
the number of its label instead, on the page (beside the equation, with its permalink) and in every
reference to it (``{eq}`eq-lagrange-3-4``` reads (3.4), from any page). A label that starts with ``eq-`` but
does not end in a number is reported (a warning, an error under ``-W``).
"""

from __future__ import annotations

import re
from typing import Any

from docutils import nodes
from sphinx.application import Sphinx
from sphinx.util import logging

logger = logging.getLogger(__name__)

# eq-<page>-<N> or eq-<page>-<N>-<M>, the page name in lower-case words joined by hyphens
LABEL = re.compile(r"eq-[a-z]+(?:-[a-z]+)*-(\d+)(?:-(\d+))?")


def paper_number(label: str) -> str | None:
    """The paper's equation number a label names ('3.4' for ``eq-lagrange-3-4``), None if it names none."""
    match = LABEL.fullmatch(label)
    if match is None:
        return None
    return ".".join(part for part in match.groups() if part)


def number_as_in_the_paper(app: Sphinx, doctree: nodes.document) -> None:
    """Give every labelled ``eq-`` equation of the page just read its paper's number."""
    equations = app.env.get_domain("math").data.setdefault("objects", {})
    for node in doctree.findall(nodes.math_block):
        label = node.get("label")
        if not label or not label.startswith("eq-"):
            continue
        number = paper_number(label)
        if number is None:
            logger.warning("equation label %r names no paper equation (expected eq-<page>-<N>[-<M>])", label,
                           location=node)
            continue
        node["number"] = number
        equations[label] = (app.env.docname, number)


def setup(app: Sphinx) -> dict[str, Any]:
    app.connect("doctree-read", number_as_in_the_paper)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
