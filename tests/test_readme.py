"""The README's promises: CI runs its test command verbatim; its Python example runs."""

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _bash_blocks():
    return re.findall(r"```bash\n(.*?)```", (ROOT / "README.md").read_text(), flags=re.S)


def test_ci_runs_the_readme_test_command_verbatim():
    blocks = [b.strip() for b in _bash_blocks()]
    assert len(blocks) == 2, "the README gives exactly two set-up-and-run commands"
    test_cmd = [b for b in blocks if "pytest" in b]
    assert len(test_cmd) == 1
    ci = (ROOT / ".ci" / "run").read_text().splitlines()
    assert test_cmd[0] in ci


def test_readme_python_example_runs():
    code = re.findall(r"```python\n(.*?)```", (ROOT / "README.md").read_text(), flags=re.S)
    assert code
    namespace: dict = {}
    for block in code:  # later blocks may use names (np) from earlier ones, as in a notebook
        exec(compile(block, "README.md", "exec"), namespace)
