"""What a reader of the built site sees: formulas as written, no internal file names, no script from a CDN.

A real Sphinx build of a few pages (``build_site`` of ``tests/docs/conftest.py``: the site's own configuration
less what needs the whole tree, warnings as errors; a few seconds).
"""

from __future__ import annotations

import html
import re
from collections.abc import Callable
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"
PAGES = ["errata", "references"]
# the papers' OCR text files are named <three digits>_<16 hex digits>.txt (or shortened, 001_…): a reader
# has no such file
OCR_NAME = re.compile(r"\b\d{3}_(?:[0-9a-f]{6,}|…)")
CDN = re.compile(r"cdn\.jsdelivr|cdnjs|unpkg\.com|mathjax@|polyfill\.io|cdn\.mathjax")


@pytest.fixture(scope="module")
def site(build_site: Callable[[dict[str, str]], Path]) -> Path:
    return build_site({page: (DOCS / f"{page}.md").read_text(encoding="utf-8") for page in PAGES})


def display_math_of_source(page: str) -> list[str]:
    """The $$...$$ formulas of a page's Markdown source, whitespace collapsed."""
    text = (DOCS / f"{page}.md").read_text(encoding="utf-8")
    return [" ".join(m.split()) for m in re.findall(r"\$\$(.+?)\$\$", text, flags=re.S)]


def display_math_of_html(page_html: str) -> list[str]:
    """The display formulas of a built page (MathJax input between \\[ and \\]), whitespace collapsed."""
    blocks = re.findall(r'<div class="math notranslate nohighlight">\s*\\\[(.*?)\\\]\s*</div>', page_html, re.S)
    return [" ".join(html.unescape(b).split()) for b in blocks]


def visible_text(page_html: str, *, prose_only: bool = True) -> str:
    """The text of the page's article, tags stripped; with ``prose_only``, code and math removed."""
    body = page_html[page_html.index('<article role="main"'):]
    body = re.sub(r"<(script|style)\b.*?</\1>", " ", body, flags=re.S)
    if prose_only:
        body = re.sub(r"<(code|pre)\b.*?</\1>", " ", body, flags=re.S)
        body = re.sub(r'<(div|span) class="math notranslate nohighlight">.*?</\1>', " ", body, flags=re.S)
    return html.unescape(re.sub(r"<[^>]+>", "", body))


def test_errata_formulas_are_rendered_as_written(site: Path) -> None:
    source = display_math_of_source("errata")
    built = display_math_of_html((site / "errata.html").read_text(encoding="utf-8"))
    assert source, "the errata page has no display formula"
    assert built == source


def test_corrected_F1_of_the_lagrange_paper_keeps_both_terms(site: Path) -> None:
    # the printed (2.7) dropped sin(theta); the page once lost the '+' of the corrected form to a list bullet
    built = display_math_of_html((site / "errata.html").read_text(encoding="utf-8"))
    assert r"F_1 = M_1^* \sin\theta + M_3^* \cos\theta" in built
    assert r"F_1 = M_1^* + M_3^* \cos\theta ." in built


@pytest.mark.parametrize("page", PAGES)
def test_no_markup_left_in_the_prose(site: Path, page: str) -> None:
    # a code span broken across lines leaves its backticks in the text (and a '+ ' line start makes a bullet)
    text = visible_text((site / f"{page}.html").read_text(encoding="utf-8"))
    assert "`" not in text
    assert "$" not in text


def test_reference_labels_resolve(site: Path) -> None:
    errata = (site / "errata.html").read_text(encoding="utf-8")
    references = (site / "references.html").read_text(encoding="utf-8")
    labels = set(re.findall(r'href="references\.html#(ref-[a-z0-9-]+)"', errata))
    assert {"ref-stepanov-1968", "ref-alc-1979", "ref-rachinskaya", "ref-krivtsov-2000"} <= labels
    for label in labels:
        assert f'id="{label}"' in references


@pytest.mark.parametrize("page", [*PAGES, "index"])
def test_no_internal_file_names_in_the_built_pages(site: Path, page: str) -> None:
    text = visible_text((site / f"{page}.html").read_text(encoding="utf-8"), prose_only=False)
    assert not OCR_NAME.search(text)


def test_mathjax_comes_with_the_site(site: Path) -> None:
    pages = sorted(site.glob("*.html"))
    assert pages
    for page in pages:
        assert not CDN.search(page.read_text(encoding="utf-8")), f"{page.name} loads a script from a CDN"
    errata = (site / "errata.html").read_text(encoding="utf-8")
    (src,) = re.findall(r'<script defer="defer" src="(_static/mathjax/[^"?]+)', errata)
    assert (site / src).is_file()
    # CommonHTML output draws with these web fonts; without them a formula shows as boxes offline
    assert (site / "_static/mathjax/output/chtml/fonts/woff-v2/MathJax_Main-Regular.woff").is_file()


SOURCES = [*DOCS.rglob("*.md"), *DOCS.rglob("*.rst"), *(ROOT / "examples").rglob("*.py"), *(ROOT / "src").rglob("*.py"),
           ROOT / "README.md", ROOT / "CITATION.cff"]


def test_no_internal_file_names_in_what_the_site_shows() -> None:
    # pages, gallery scripts and docstrings all end up on the site: cite the paper instead
    found = {str(p.relative_to(ROOT)): OCR_NAME.findall(p.read_text(encoding="utf-8"))
             for p in SOURCES if "_build" not in p.parts and "auto_examples" not in p.parts}
    assert not {path: names for path, names in found.items() if names}
