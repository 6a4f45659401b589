"""CITATION.cff agrees with the package metadata and with the references page of the site."""

from __future__ import annotations

import re
from pathlib import Path

import yaml  # PyYAML comes with jupytext (the test extra)

ROOT = Path(__file__).resolve().parents[2]


def _citation() -> dict:
    return yaml.safe_load((ROOT / "CITATION.cff").read_text(encoding="utf-8"))


def test_citation_names_the_released_version_and_licence() -> None:
    pyproject = (ROOT / "pyproject.toml").read_text(encoding="utf-8")  # (tomllib only from Python 3.11)
    cff = _citation()
    assert cff["cff-version"] == "1.2.0"
    assert f'\nversion = "{cff["version"]}"\n' in pyproject
    assert f'license = {{ text = "{cff["license"]}" }}' in pyproject
    assert f'\nRepository = "{cff["repository-code"]}"\n' in pyproject


def test_cited_papers_are_those_of_the_references_page() -> None:
    page = " ".join((ROOT / "docs" / "references.md").read_text(encoding="utf-8").split())
    papers = _citation()["references"]
    assert len(papers) == 4
    for paper in papers:
        assert f'"{paper["title"]}"' in page, paper["title"]
        for author in paper["authors"]:
            assert re.search(rf"{re.escape(author['given-names'])} {author['family-names']}\b", page)
        if "volume" in paper:
            assert f"**{paper['volume']}**" in page
            assert f"({paper['year']})" in page
