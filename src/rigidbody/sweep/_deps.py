"""The sweeps' optional dependencies (xarray, zarr, dask, tqdm), imported only when called."""

from __future__ import annotations

import importlib
from typing import Any

_EXTRA = 'pip install "rigidbody[sweep]"'


def require(module: str) -> Any:
    """Import an optional dependency of the sweeps, or raise an ImportError saying how to install it."""
    try:
        return importlib.import_module(module)
    except ImportError as exc:
        raise ImportError(f"rigidbody.sweep needs {module!r}, an optional dependency: {_EXTRA}") from exc
