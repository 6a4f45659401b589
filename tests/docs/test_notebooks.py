"""The tutorial notebooks (docs/notebooks/*.md, MyST text notebooks stored without outputs) execute.

Each is read with jupytext and run top to bottom in a real Jupyter kernel by nbclient; an exception in
any cell fails the test with the cell and the traceback. The docs build executes them again (MyST-NB).
"""

from __future__ import annotations

from pathlib import Path

import jupytext
import nbclient
import pytest

NOTEBOOKS = sorted((Path(__file__).resolve().parents[2] / "docs" / "notebooks").glob("*.md"))


def test_there_is_one_tutorial_per_analysis_module() -> None:
    assert {p.stem for p in NOTEBOOKS} == {"gyrostat", "lagrange", "euler_poinsot", "viscous"}


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_notebook_executes(path: Path, tmp_path: Path) -> None:
    nb = jupytext.read(path)
    assert not any(c.get("outputs") for c in nb.cells if c.cell_type == "code"), "stored with outputs"
    # run in a scratch directory so a notebook that writes files leaves nothing in the repository
    nbclient.NotebookClient(nb, timeout=300, kernel_name="python3",
                            resources={"metadata": {"path": str(tmp_path)}}).execute()
    images = [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])
              if "image/png" in o.get("data", {})]
    assert images, "a tutorial draws at least one figure inline"
    # the workflow of the tutorials: a result object is inspected through its HTML display
    html = [o["data"]["text/html"] for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])
            if "text/html" in o.get("data", {})]
    assert any("rigidbody-solution" in h for h in html), "a tutorial shows a result's HTML display"
