"""The Python code of the documentation pages runs as written, in a fresh interpreter.

Every page of docs/ and docs/howto/ with a ```python block is collected (a block that is not Python, a shell
command or an excerpt, carries another language tag: ```bash, ```text).

The ```python blocks of a page form one session, run in order as one script (a later block uses the names of
an earlier one, as a reader typing them in would). A block with an ``if __name__ == "__main__":`` guard is a
script of its own (the page tells the reader to save it as a file: local worker processes import it), so it
runs alone, as a file. Each run is a real subprocess with a timeout, in an empty working directory.
"""

from __future__ import annotations

import importlib.util
import os
import re
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"
PAGES = [page for page in sorted([*DOCS.glob("*.md"), *(DOCS / "howto").glob("*.md")])
         if "```python" in page.read_text(encoding="utf-8")]
# the pages whose code writes a sweep store: zarr-python 3, installed by the sweep extra on Python >= 3.11 only
NEEDS_ZARR = {"sweeps.md", "howto/resume.md"}
GUARD = 'if __name__ == "__main__":'
# the longest session (the Euler-Poinsot theory page) takes ~7 s and the quickstart's sweep script ~10 s on a
# busy 2-core machine; a hang (a worker waiting forever) must fail the test, not stall the suite
TIMEOUT = 180


def python_blocks(text: str) -> list[str]:
    return re.findall(r"^```python\n(.*?)^```", text, flags=re.S | re.M)


def run_script(code: str, path: Path) -> subprocess.CompletedProcess[str]:
    path.write_text(code, encoding="utf-8")
    env = dict(os.environ, MPLBACKEND="Agg",
               PYTHONPATH=os.pathsep.join(p for p in (str(ROOT / "src"), os.environ.get("PYTHONPATH")) if p))
    result = subprocess.run([sys.executable, path.name], cwd=path.parent, env=env, capture_output=True,
                            text=True, timeout=TIMEOUT, check=False)
    assert result.returncode == 0, f"{path.name} failed:\n{result.stdout}\n{result.stderr}"
    return result


def _ids(pages: list[Path]) -> list[str]:
    return [str(p.relative_to(DOCS)) for p in pages]


@pytest.fixture(scope="module")
def outputs(tmp_path_factory: pytest.TempPathFactory) -> Callable[[Path, bool], list[str]]:
    """What a page's session (``guarded=False``) or each of its guarded scripts printed; each run once."""
    done: dict[tuple[Path, bool], list[str]] = {}

    def get(page: Path, guarded: bool) -> list[str]:
        if str(page.relative_to(DOCS)) in NEEDS_ZARR and importlib.util.find_spec("zarr") is None:
            pytest.skip("the page writes a sweep store, which needs zarr (the sweep extra, Python >= 3.11)")
        if (page, guarded) not in done:
            blocks = [b for b in python_blocks(page.read_text(encoding="utf-8")) if (GUARD in b) == guarded]
            codes = blocks if guarded else ["\n".join(blocks)] if blocks else []
            where = tmp_path_factory.mktemp(page.stem)
            done[page, guarded] = [run_script(code, where / f"script_{i}.py").stdout for i, code in enumerate(codes)]
        return done[page, guarded]

    return get


@pytest.mark.parametrize("page", PAGES, ids=_ids(PAGES))
def test_every_python_block_is_found(page: Path) -> None:
    text = page.read_text(encoding="utf-8")
    blocks = python_blocks(text)
    assert blocks, f"{page.name} has no Python block to run"
    # a fence the pattern missed (indented, or with options after the language) would go untested
    assert len(blocks) == len(re.findall(r"```python", text))


@pytest.mark.parametrize("page", PAGES, ids=_ids(PAGES))
def test_page_session_runs(page: Path, outputs: Callable[[Path, bool], list[str]]) -> None:
    outputs(page, False)  # run_script asserts a zero exit status


@pytest.mark.parametrize("page", PAGES, ids=_ids(PAGES))
def test_guarded_scripts_run_as_files(page: Path, outputs: Callable[[Path, bool], list[str]]) -> None:
    for out in outputs(page, True):
        assert out.strip(), "the guarded part did not run (nothing printed)"


def test_quickstart_prints_what_its_text_says(outputs: Callable[[Path, bool], list[str]]) -> None:
    (out,) = outputs(DOCS / "quickstart.md", False)
    # the roots of the cubic for the spun top tilted 60 deg: (0, 0.5, 2) in the Lagrange paper's table
    assert "roots: [0.  0.5 2. ]" in out
    # "agree to O(eps)": averaged and full Gz at tau = 2 differ by less than eps = 0.02 (the averaging
    # theorem's order with a constant of one; a wrong field or time compared would differ by O(1))
    averaged, full = map(float, re.search(r"averaged (\S+), full (\S+)", out).groups())
    assert abs(averaged - full) < 0.02
    # "n stays a unit vector" (to rounding: 50 samples of a closed form)
    assert float(re.search(r"largest \| \|n\| - 1 \|: (\S+)", out).group(1)) < 1e-12


def test_quickstart_sweep_fills_every_point(outputs: Callable[[Path, bool], list[str]]) -> None:
    (out,) = outputs(DOCS / "quickstart.md", True)
    assert "Dimensions:  (r1: 2, r3: 2)" in out
    # every point computed, none failed (xarray >= 2024 shows the size in bytes before the values)
    assert re.search(r"status\s+\(r1, r3\)\s+int64\s+(?:\S+B\s+)?0 0 0 0\n", out), out


def test_every_page_with_code_is_collected() -> None:
    # guards the collection above: the pages this suite promises to run are among those found (a glob that
    # missed docs/howto/ or the theory pages would pass vacuously)
    names = set(_ids(PAGES))
    assert {"quickstart.md", "sweeps.md", "euler_poinsot.md", "conventions.md", "howto/torque.md",
            "howto/dask.md", "howto/resume.md"} <= names
    assert NEEDS_ZARR <= names


def test_resume_recomputes_exactly_what_was_not_finished(outputs: Callable[[Path, bool], list[str]]) -> None:
    (out,) = outputs(DOCS / "howto" / "resume.md", False)
    # the function raises KeyboardInterrupt at its 7th call, so 6 of the 16 points finished (2 of them in the
    # chunk cut short): the rerun must compute the other 10, each once, and a third run none (a point whose
    # function raised is stored as done)
    assert "interrupted after 7 calls" in out
    assert "the rerun computed 10 points" in out
    assert "a third run computed 0 points" in out
    assert "is in use: another sweep is writing it" in out  # the lock refused the second sweep


def test_dask_howto_computes_every_point(outputs: Callable[[Path, bool], list[str]]) -> None:
    (out,) = outputs(DOCS / "howto" / "dask.md", True)
    assert "workers: 2" in out
    # spin_end raises at no point of this grid (positive ratios): every point has status 0 on the cluster
    assert "points with a non-zero status: 0" in out
