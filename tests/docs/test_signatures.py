"""Default values read on the API pages as they were written: ``delta0=pi / 4``, not ``0.7853981633974483``.

docs/conf.py keeps the source text of defaults (``autodoc_preserve_defaults``), so the text in the source is what
a reader sees. Every function and method of the package is read (ast, nothing imported): a default may not be a
float literal with more digits than a person types, nor a module-qualified constant (``math.pi / 4``): write
``pi / 4`` with ``from math import pi``.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

SRC = Path(__file__).resolve().parents[2] / "src" / "rigidbody"
UNREADABLE = re.compile(r"\d\.\d{9,}|\b(?:np|numpy|math)\.(?:pi|e)\b")


def defaults(path: Path) -> list[tuple[str, str]]:
    """``(where, default's source text)`` of every parameter default of the file's functions."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    found = []
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            for d in [*node.args.defaults, *(k for k in node.args.kw_defaults if k is not None)]:
                found.append((f"{path.relative_to(SRC)}:{d.lineno} {node.name}", ast.unparse(d)))
    return found


def test_defaults_are_written_readably() -> None:
    bad = [(where, text) for path in sorted(SRC.rglob("*.py")) for where, text in defaults(path)
           if UNREADABLE.search(text)]
    assert not bad, f"write these defaults as a reader would (pi / 4 with from math import pi): {bad}"


def test_the_pattern_and_the_reader_see_what_they_must() -> None:
    # guards the test above against passing vacuously
    assert UNREADABLE.search("0.7853981633974483") and UNREADABLE.search("math.pi / 4")
    assert UNREADABLE.search("np.pi / 4")
    assert not UNREADABLE.search("pi / 4") and not UNREADABLE.search("1e-12") and not UNREADABLE.search("0.125")
    texts = dict(defaults(SRC / "euler_poinsot" / "_averaged.py")).values()
    assert "pi / 4" in texts
