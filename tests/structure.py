"""Static measures of the package's shape, read from the source with ``ast`` (nothing is imported).

Used by ``tests/test_house_rules.py``; run as a script it prints the measures and the offenders:
``python tests/structure.py``.

- *imports*: every ``import`` / ``from ... import`` of a ``rigidbody`` module anywhere in a file (at its top or
  inside a function: a lazy import is an import too), resolved to the file it names;
- *layers*: core 1; gyrostat, lagrange, euler_poinsot, viscous 2; sweep 3; studies 4; plotting 5; paperfigs 6;
  the CLI (``__main__``) 7; the package ``__init__`` imports nothing of a higher layer either;
- *private names*: ``from .x import _name`` (or ``x._name``) where ``_name`` is defined in another file;
- *code lines* of a function: lines holding code, without its docstring, comments and blank lines.
"""

from __future__ import annotations

import ast
import sys
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src"
LAYERS = {"core": 1, "gyrostat": 2, "lagrange": 2, "euler_poinsot": 2, "viscous": 2, "sweep": 3, "studies": 4,
          "plotting": 5, "paperfigs": 6, "__main__": 7}


@dataclass
class Shape:
    files: dict[str, Path] = field(default_factory=dict)          # module name -> file
    imports: dict[str, set[str]] = field(default_factory=dict)    # module -> modules it imports
    private: list[str] = field(default_factory=list)              # "a.py imports _x from b"
    lines: dict[str, int] = field(default_factory=dict)           # module -> lines
    functions: dict[str, int] = field(default_factory=dict)       # "module.func" -> code lines
    parameters: dict[str, int] = field(default_factory=dict)      # public "module.func" -> parameters


def module_name(path: Path, src: Path = SRC) -> str:
    parts = list(path.relative_to(src).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def layer(module: str) -> int:
    parts = module.split(".")
    return LAYERS.get(parts[1], 0) if len(parts) > 1 else 0


def _resolve(module: str, is_pkg: bool, node: ast.ImportFrom) -> str:
    if not node.level:
        return node.module or ""
    base = module.split(".")
    base = base if is_pkg else base[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def _code_lines(fn: ast.FunctionDef | ast.AsyncFunctionDef, source: list[str]) -> int:
    body = fn.body
    if body and isinstance(body[0], ast.Expr) and isinstance(getattr(body[0], "value", None), ast.Constant):
        body = body[1:]  # the docstring
    if not body:
        return 0
    end = fn.end_lineno or fn.lineno
    skip: set[int] = set()
    for node in ast.walk(fn):  # docstrings of nested functions and classes
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)) and node.body:
            d = node.body[0]
            if isinstance(d, ast.Expr) and isinstance(d.value, ast.Constant) and isinstance(d.value.value, str):
                skip.update(range(d.lineno, (d.end_lineno or d.lineno) + 1))
    n = 0
    for no in range(body[0].lineno, end + 1):
        text = source[no - 1].strip()
        if text and no not in skip:  # comments count: a function is read with them
            n += 1
    return n


def _definitions(tree: ast.Module) -> set[str]:
    names = set()
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, (ast.Assign, ast.AnnAssign)):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            for t in targets:
                for n in ast.walk(t):
                    if isinstance(n, ast.Name):
                        names.add(n.id)
    return names


def _functions(tree: ast.Module) -> Iterator[tuple[str, ast.FunctionDef | ast.AsyncFunctionDef, bool]]:
    """(qualified name, node, public) of every function, methods and nested functions included."""
    def walk(node: ast.AST, prefix: str, public: bool) -> Iterator[tuple[str, ast.FunctionDef | ast.AsyncFunctionDef,
                                                                         bool]]:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef)):
                pub = public and (not child.name.startswith("_") or child.name == "__init__")
                yield prefix + child.name, child, pub
                yield from walk(child, prefix + child.name + ".", False)
            elif isinstance(child, ast.ClassDef):
                yield from walk(child, prefix + child.name + ".", public and not child.name.startswith("_"))
            else:
                yield from walk(child, prefix, public)
    yield from walk(tree, "", True)


def measure(src: Path = SRC) -> Shape:
    shape = Shape()
    trees = {}
    for path in sorted((src / "rigidbody").rglob("*.py")):
        mod = module_name(path, src)
        shape.files[mod] = path
        text = path.read_text()
        trees[mod] = (ast.parse(text), text.splitlines(), path.name == "__init__.py")
    defined = {mod: _definitions(t) for mod, (t, _, _) in trees.items()}
    for mod, (tree, source, is_pkg) in trees.items():
        shape.lines[mod] = len(source) + 1  # counted as the house counts: the line after the last newline too
        deps: set[str] = set()
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                deps.update(a.name for a in node.names if a.name.startswith("rigidbody"))
            elif isinstance(node, ast.ImportFrom):
                target = _resolve(mod, is_pkg, node)
                if not target.startswith("rigidbody"):
                    continue
                for a in node.names:
                    sub = f"{target}.{a.name}"
                    if sub in shape.files or sub in trees:
                        deps.add(sub)  # "from . import module"
                    else:
                        deps.add(target)
                        if a.name.startswith("_") and not a.name.startswith("__") and a.name in defined.get(target, ()):
                            shape.private.append(f"{mod} imports {a.name} from {target}")
        shape.imports[mod] = {d for d in deps if d in trees and d != mod}
    exported = _exported(trees)
    for mod, (tree, source, is_pkg) in trees.items():
        visible = is_pkg or not mod.split(".")[-1].startswith("_")
        for name, fn, public in _functions(tree):
            q = f"{mod}.{name}"
            shape.functions[q] = _code_lines(fn, source)
            if public and (visible or name.split(".")[0] in exported.get(mod, ())):
                a = fn.args
                n = len(a.posonlyargs) + len(a.args) + len(a.kwonlyargs) + bool(a.vararg) + bool(a.kwarg)
                if a.args and a.args[0].arg in ("self", "cls"):
                    n -= 1
                shape.parameters[q] = n
    return shape


def _exported(trees: dict[str, tuple[ast.Module, list[str], bool]]) -> dict[str, set[str]]:
    """Names of a private module that a package re-exports (``from ._x import name``): module -> names."""
    out: dict[str, set[str]] = {}
    for mod, (tree, _, is_pkg) in trees.items():
        if not is_pkg:
            continue
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and node.level:
                target = _resolve(mod, True, node)
                out.setdefault(target, set()).update(a.name for a in node.names)
    return out


def public_parameters(shape: Shape) -> dict[str, int]:
    """Parameters of the functions a user reaches: those re-exported by a package's ``__all__`` included."""
    return shape.parameters


def cycles(shape: Shape) -> list[list[str]]:
    """The strongly connected components of more than one file (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out: list[list[str]] = []
    sys.setrecursionlimit(10_000)

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in shape.imports.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(shape.imports):
        if v not in index:
            visit(v)
    return out


def upward(shape: Shape) -> list[str]:
    return [f"{a} (layer {layer(a)}) imports {b} (layer {layer(b)})"
            for a, deps in sorted(shape.imports.items()) for b in sorted(deps)
            if layer(a) and layer(b) > layer(a)]


def report(shape: Shape) -> dict[str, object]:
    big = max(shape.lines.items(), key=lambda kv: kv[1])
    longest = max(shape.functions.items(), key=lambda kv: kv[1])
    params = max(shape.parameters.items(), key=lambda kv: kv[1])
    return {"import cycles": cycles(shape), "upward imports": upward(shape),
            "private names across files": len(shape.private), "largest file": big,
            "longest function": longest, "most parameters (public)": params}


if __name__ == "__main__":
    s = measure()
    for k, v in report(s).items():
        print(f"{k}: {v}")
    print("files over 600 lines:", sorted((n, m) for m, n in s.lines.items() if n > 600)[::-1])
    print("functions over 100 code lines:", sorted((n, f) for f, n in s.functions.items() if n > 100)[::-1])
    print("public functions over 15 parameters:", sorted((n, f) for f, n in s.parameters.items() if n > 15)[::-1])
    print("private names:", *s.private[:200], sep="\n  ")
