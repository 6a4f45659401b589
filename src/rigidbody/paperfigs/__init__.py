"""Registry of the paper-figure builders behind ``python -m rigidbody figures``.

Each module adds a file ``rigidbody/paperfigs/<module>.py`` that registers one figure set::

    from rigidbody.paperfigs import register

    @register("lagrange", "Figs 1-3: the heavy top under linear drag (Akulenko et al. 1979)")
    def build(outdir: pathlib.Path) -> list[pathlib.Path]:
        ...  # compute with the public API, draw, save PNGs into outdir, return their paths

The builders live in the package (not in ``examples/``) so that the command works after a plain
``pip install .`` from any directory. Submodules are discovered automatically.
"""

from __future__ import annotations

import importlib
import pkgutil
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

__all__ = ["FigureSet", "discover", "register", "registry"]


@dataclass(frozen=True)
class FigureSet:
    """A registered figure set: its name, a one-line description and the builder."""

    name: str
    description: str
    build: Callable[[Path], list[Path]]


_REGISTRY: dict[str, FigureSet] = {}


def register(name: str, description: str) -> Callable[[Callable[[Path], list[Path]]], Callable[[Path], list[Path]]]:
    """Decorator registering ``build(outdir) -> list of written paths`` under ``name``."""

    def deco(func: Callable[[Path], list[Path]]) -> Callable[[Path], list[Path]]:
        _REGISTRY[name] = FigureSet(name, description, func)
        return func

    return deco


def discover() -> None:
    """Import every builder module in this package (each registers itself)."""
    for info in pkgutil.iter_modules(__path__):
        importlib.import_module(f"{__name__}.{info.name}")


def registry() -> dict[str, FigureSet]:
    """All registered figure sets, sorted by name (after :func:`discover`)."""
    discover()
    return dict(sorted(_REGISTRY.items()))
