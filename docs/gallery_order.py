"""Order of the gallery scripts within a section (sphinx-gallery ``within_subsection_order``).

The paper's figures first, by figure number (``fig2_...`` before ``fig10_...``), then the other scripts by
file name. Referred to by name in ``conf.py`` so that Sphinx can cache the configuration.
"""

from __future__ import annotations

import re
from pathlib import Path


class PaperFiguresFirst:
    """Sort key: ``fig<N>_*.py`` by ``N``, then the other scripts alphabetically."""

    def __init__(self, src_dir: str | Path) -> None:
        self.src_dir = src_dir

    def __call__(self, filename: str | Path) -> tuple[int, int, str]:
        name = Path(filename).name
        m = re.match(r"fig(\d+)_", name)
        return (0, int(m.group(1)), name) if m else (1, 0, name)

    def __repr__(self) -> str:
        return f"<{type(self).__name__}>"
