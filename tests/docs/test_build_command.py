"""CI builds the documentation with the command CONTRIBUTING.md gives, verbatim and with warnings as errors."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_ci_runs_the_contributing_docs_command_verbatim() -> None:
    commands = re.findall(r"`(python -m pip install \"\.\[docs\]\" && python -m sphinx [^`]*)`",
                          (ROOT / "CONTRIBUTING.md").read_text(encoding="utf-8"))
    assert len(commands) == 1, "CONTRIBUTING.md gives one docs build command"
    command = commands[0]
    assert " -W " in command and "--keep-going" in command  # warnings are errors, all of them reported
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8").splitlines()
    assert command in ci
    # after the tests and mypy
    assert ci.index(command) > max(i for i, line in enumerate(ci) if "pytest" in line or "mypy" in line)


def test_the_build_needs_no_network() -> None:
    conf = (ROOT / "docs" / "conf.py").read_text(encoding="utf-8")
    assert "intersphinx" not in conf
