"""The rules of the run options that the averaged runs and the full equations share (single and batch)."""

from __future__ import annotations

from typing import Any

import numpy as np

from ..core.validate import positive, real, span

__all__ = ["check_averaging", "check_sigma", "check_tau_eval", "check_tol"]


def check_averaging(method: Any, name: str) -> None:
    if method not in ("auto", "numerical"):
        raise ValueError(f"{name} must be 'auto' (closed forms where a torque has them) or 'numerical' (the "
                         f"averaging engine for every part), got {method!r}")


def check_sigma(sigma: Any) -> int:
    if isinstance(sigma, bool) or sigma not in (1, -1):
        raise ValueError(f"sigma (sense of rotation) must be +1 or -1, got {sigma!r}")
    return int(sigma)


def check_tau_eval(tau_eval: Any, tau_span: Any) -> None:
    """tau_eval must be finite, sorted and inside tau_span (points beyond an early stop are dropped)."""
    if tau_eval is None:
        return
    try:
        te = np.asarray(tau_eval, dtype=float).ravel()
    except (TypeError, ValueError):
        raise TypeError(f"tau_eval must be an array of real numbers, got {tau_eval!r}") from None
    a, b = span(tau_span, "tau_span")
    if not np.all(np.isfinite(te)):
        raise ValueError("tau_eval must be finite")
    if np.any(np.diff(te) < 0):
        raise ValueError("tau_eval must be sorted (increasing)")
    if te.size and (te[0] < a or te[-1] > b):
        raise ValueError(f"tau_eval must lie within tau_span = {tuple(tau_span)!r}, got [{te[0]}, {te[-1]}]")


def check_tol(rtol: Any, atol: Any) -> None:
    positive(rtol, "rtol")
    if real(atol, "atol") < 0:
        raise ValueError(f"atol must be >= 0, got {atol}")
