"""The theory pages typeset their equations, number them as in the papers and link the API they name.

Rules checked on the Markdown sources of the theory pages (``docs/<module>.md`` of the four papers and
``docs/conventions.md``):

* **No math in code spans.** A code span is for code, and the project's code is ASCII: a code span (or a
  role's title, which renders as code) holding a Greek letter, a super- or subscript, a mathematical operator
  or symbol (``² ∂ − · × ± √ ≤ ⟨ ‖``, a combining accent as in ``ω̇``) is a formula in monospace Unicode
  and must be written in dollar math instead.
* **No inline formula split into a list.** A line of a paragraph that starts with ``+ ``, ``- `` or ``* `` is
  a list item to Markdown; inside an open ``$...$`` it cuts the formula in two (and drops the sign).
* **An equation is found by its paper number.** Every equation number a paper's page cites — ``(N.M)`` in
  its prose (``(N)`` on the Euler–Poinsot page, whose paper numbers its equations 1–9), or a reference
  ``{eq}`eq-<page>-N-M``` — is the label of a display equation on that page, ``$$ ... $$ (eq-<page>-N-M)``;
  the labels of a page carry its name. ``conventions.md`` has no paper: it cites equations only as ``{eq}``
  references to a label of a paper's page.
* **The API the pages name is linked, and every link resolves.** Each ``{func}``/``{class}``/... role names
  an object that exists and has a page in the API reference (``docs/api/*.rst``, autosummary); a name of the
  page's module in plain backticks (outside headings and code blocks) would be a missing link.

A Sphinx build of these pages (``build_site`` of ``tests/docs/conftest.py``: warnings as errors, without the
API pages, the gallery and the notebooks; a few seconds) checks that each labelled equation shows its paper's
number and each reference reads the same.
"""

from __future__ import annotations

import html
import importlib
import re
from collections.abc import Callable
from pathlib import Path
from types import ModuleType
from typing import Any

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"
PAPER_PAGES = ["gyrostat", "lagrange", "euler_poinsot", "viscous"]
PAGES = [*PAPER_PAGES, "conventions"]

# characters of formulas, not of code: Greek, combining accents, super/subscripts, ², ³, ¹, ±, ·, ×, ½,
# mathematical operators, ‖, ⟨ ⟩
MATH_CHARS = re.compile("[\u0370-\u03ff\u0300-\u036f\u2070-\u209f\u00b2\u00b3\u00b9\u00b1\u00b7\u00d7\u00bd"
                        "\u2200-\u22ff\u2016\u27e8\u27e9]")
FENCE = re.compile(r"^(```|~~~).*?^\1", re.S | re.M)
DISPLAY = re.compile(r"^[ \t]*\$\$\n(.*?)\n[ \t]*\$\$(?: \((eq-[\w-]+)\))?$", re.S | re.M)
ROLE = re.compile(r"\{(?:py:)?(func|class|meth|attr|data|mod|obj|exc|eq)\}`([^`]+)`")
CODE = re.compile(r"`([^`\n]+)`")
INLINE_MATH = re.compile(r"\$[^$]+\$")


def source(page: str) -> str:
    return (DOCS / f"{page}.md").read_text(encoding="utf-8")


def label_prefix(page: str) -> str:
    return "eq-" + page.replace("_", "-") + "-"


def number_of(label: str) -> str:
    """'3.4' for ``eq-lagrange-3-4``, '6' for ``eq-euler-poinsot-6``."""
    match = re.fullmatch(r"eq-[a-z-]+?-(\d+(?:-\d+)?)", label)
    assert match, f"{label} names no equation number"
    return match.group(1).replace("-", ".")


def prose(text: str) -> str:
    """The text outside code blocks and display math, with roles, code spans and inline math removed."""
    text = DISPLAY.sub(" ", FENCE.sub(" ", text))
    return INLINE_MATH.sub(" ", CODE.sub(" ", ROLE.sub(" ", text)))


def labels(text: str) -> list[str]:
    return [label for _, label in DISPLAY.findall(FENCE.sub(" ", text)) if label]


@pytest.mark.parametrize("page", PAGES)
def test_no_formula_in_code_spans(page: str) -> None:
    text = DISPLAY.sub(" ", FENCE.sub(" ", source(page)))
    titles = [content for _, content in ROLE.findall(text)]
    spans = CODE.findall(ROLE.sub(" ", text))
    assert not [span for span in [*spans, *titles] if MATH_CHARS.search(span)]


@pytest.mark.parametrize("page", PAGES)
def test_no_inline_formula_broken_by_a_list_marker(page: str) -> None:
    broken = []
    for paragraph in re.split(r"\n\s*\n", DISPLAY.sub(" ", FENCE.sub(" ", source(page)))):
        dollars = 0
        for line in paragraph.split("\n"):
            if dollars % 2 and re.match(r"\s*[-+*] ", line):
                broken.append(line)
            dollars += line.count("$")
    assert not broken


@pytest.mark.parametrize("page", PAPER_PAGES)
def test_cited_equation_numbers_are_labelled_displays_of_the_page(page: str) -> None:
    text = source(page)
    defined = labels(text)
    prefix = label_prefix(page)
    assert defined, "the page displays no labelled equation"
    assert all(label.startswith(prefix) for label in defined)
    assert len(set(defined)) == len(defined)
    number = r"\((\d)\)" if page == "euler_poinsot" else r"\((\d+\.\d+)\)"
    cited = {prefix + n.replace(".", "-") for n in re.findall(number, prose(text))}
    cited |= {target for role, target in ROLE.findall(text) if role == "eq"}
    assert cited, "the page cites no equation"
    assert not sorted(cited - set(defined))


def test_conventions_cites_equations_by_links_to_the_papers_pages() -> None:
    text = source("conventions")
    assert not re.findall(r"\(\d+\.\d+\)", prose(text))
    targets = [target for role, target in ROLE.findall(text) if role == "eq"]
    assert targets
    for target in targets:
        page = next(p for p in PAPER_PAGES if target.startswith(label_prefix(p)))
        assert target in labels(source(page))


def documented() -> tuple[set[str], set[str]]:
    """The objects that have a page in the API reference (autosummary entries) and the documented modules."""
    objects, modules = set(), set()
    for rst in (DOCS / "api").glob("*.rst"):
        module = ""
        for line in rst.read_text(encoding="utf-8").splitlines():
            if match := re.match(r"\.\. (?:py:)?currentmodule:: (\S+)", line):
                module = match.group(1)
            elif match := re.match(r"\.\. automodule:: (\S+)", line):
                modules.add(match.group(1))
            elif module and (match := re.fullmatch(r"   (~?[\w.]+)", line)):
                objects.add(f"{module}.{match.group(1).lstrip('~')}")
    return objects, modules


def resolve(name: str) -> Any:
    """The object a dotted name refers to, importing the longest module prefix."""
    parts = name.split(".")
    for i in range(len(parts), 0, -1):
        try:
            obj: Any = importlib.import_module(".".join(parts[:i]))
        except ImportError:
            continue
        for attr in parts[i:]:
            obj = getattr(obj, attr)
        return obj
    raise ImportError(name)


@pytest.mark.parametrize("page", PAGES)
def test_api_links_resolve_to_documented_objects(page: str) -> None:
    text = source(page)
    current = re.search(r"^```\{py:currentmodule\} (\S+)$", text, re.M)
    objects, modules = documented()
    unresolved = []
    for role, content in ROLE.findall(text):
        if role == "eq":
            continue
        target = re.sub(r"^.*<(.+)>$", r"\1", content, flags=re.S).lstrip("~")
        if current and not target.startswith("rigidbody."):
            target = f"{current.group(1)}.{target}"
        resolve(target)  # raises when the object does not exist
        if target not in (modules if role == "mod" else objects):
            unresolved.append(target)
    assert not unresolved, "named objects without a page in docs/api"


@pytest.mark.parametrize("page", PAPER_PAGES)
def test_api_names_in_plain_backticks_are_links(page: str) -> None:
    module: ModuleType = importlib.import_module(f"rigidbody.{page}")
    body = "\n".join(line for line in FENCE.sub(" ", source(page)).splitlines() if not line.startswith("#"))
    spans = CODE.findall(ROLE.sub(" ", body))
    named = [s for s in spans if re.sub(r"^(ep|lagrange|viscous|gyrostat)\.|\(\)$", "", s) in module.__all__]
    assert not named


@pytest.fixture(scope="module")
def site(build_site: Callable[[dict[str, str]], Path]) -> Path:
    pages = {page: source(page) for page in [*PAGES, "errata", "references"]}
    # the other pages they link to ({doc}`name` or {doc}`text <name>`) as one-line stubs: their content (the
    # sweeps page's gallery figures, the how-tos) is not what this test builds
    linked = {m.split("<")[-1].rstrip(">").strip("/") for t in pages.values()
              for m in re.findall(r"\{doc\}`([^`]+)`", t)}
    return build_site({**pages, **{name: f"# {name}\n" for name in sorted(linked - set(pages))}})


@pytest.mark.parametrize("page", PAPER_PAGES)
def test_built_equations_show_the_papers_numbers(site: Path, page: str) -> None:
    built = html.unescape((site / f"{page}.html").read_text(encoding="utf-8"))
    shown = dict(re.findall(r'id="equation-(eq-[\w-]+)">\s*<span class="eqno">\(([\d.]+)\)', built))
    assert shown == {label: number_of(label) for label in labels(source(page))}


@pytest.mark.parametrize("page", PAGES)
def test_built_equation_references_read_the_papers_numbers(site: Path, page: str) -> None:
    built = html.unescape((site / f"{page}.html").read_text(encoding="utf-8"))
    refs = re.findall(r'<a class="reference internal" href="[\w.]*#equation-(eq-[\w-]+)">\(([\d.]+)\)</a>', built)
    expected = [target for role, target in ROLE.findall(source(page)) if role == "eq"]
    assert sorted(label for label, _ in refs) == sorted(expected)
    assert all(number == number_of(label) for label, number in refs)
