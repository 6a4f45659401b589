"""House rules that a reader cannot see from one test: checked over the whole test tree."""

import re
from pathlib import Path

TESTS = Path(__file__).resolve().parent


def test_relative_tolerances_are_not_silently_absolute():
    # pytest.approx(x, rel=r) keeps the default abs=1e-12: for |x| < 1e-12/r the relative bound is vacuous.
    # Every rel-only approx must say abs= explicitly (abs=0 for a purely relative bound).
    offenders = []
    for path in TESTS.rglob("*.py"):
        for no, line in enumerate(path.read_text().splitlines(), 1):
            if re.search(r"approx\(.*\brel=", line) and "abs=" not in line:
                offenders.append(f"{path.relative_to(TESTS)}:{no}")
    assert not offenders, "rel= without abs= in pytest.approx: " + ", ".join(offenders)
