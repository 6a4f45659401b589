"""Validation of the initial state (n0, ndot0, Omega0) shared by simulate, axis_path and turn."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..core.validate import finite_array, real

__all__ = ["initial_state"]

_UNIT_TOL = 1e-10


def initial_state(n0: Any, ndot0: Any, Omega0: Any) -> tuple[np.ndarray, np.ndarray, float, float]:
    """Return ``(n0, ndot0, v0, Omega0)`` validated: ``|n0| = 1`` and ``ndot0 ⊥ n0`` to 1e-10.

    ``n0`` is renormalised (its norm may differ from 1 by rounding). ``ndot0`` must be perpendicular to
    ``n0`` up to rounding: ``|n0·ndot0| <= 1e-10 max(|ndot0|, |Omega0|)`` (relative to the body's rates,
    so the test does not depend on the unit of time; ``ndot0 = ω0×n0`` computed in floating point passes
    it). Within the tolerance the component along ``n0`` is removed; beyond it ``ValueError`` — the input
    is never silently projected.
    """
    n = finite_array(n0, "n0")
    nd = finite_array(ndot0, "ndot0")
    if n.shape != (3,):
        raise ValueError(f"n0 must be a 3-vector, got shape {n.shape}")
    if nd.shape != (3,):
        raise ValueError(f"ndot0 must be a 3-vector, got shape {nd.shape}")
    if isinstance(Omega0, np.ndarray) and Omega0.ndim == 0:
        Omega0 = Omega0.item()
    Om = real(Omega0, "Omega0")
    nn = math.sqrt(float(n @ n))
    if abs(nn - 1.0) > _UNIT_TOL:
        raise ValueError(f"n0 must be a unit vector (|n0| = 1 within {_UNIT_TOL}), got |n0| = {nn!r}")
    n = n / nn
    v0 = math.sqrt(float(nd @ nd))
    along = float(n @ nd)
    if abs(along) > _UNIT_TOL * max(v0, abs(Om)):
        raise ValueError(
            f"ndot0 must be perpendicular to n0 (|n0·ndot0| <= 1e-10 max(|ndot0|, |Omega0|)), got "
            f"n0·ndot0 = {along!r} with |ndot0| = {v0!r}"
        )
    nd = nd - along * n
    v0 = math.sqrt(float(nd @ nd))
    return n, nd, v0, Om


def perpendicular(n: np.ndarray) -> np.ndarray:
    """A unit vector perpendicular to the unit vector ``n`` (deterministic choice)."""
    i = int(np.argmin(np.abs(n)))
    e = np.zeros(3)
    e[i] = 1.0
    p = np.cross(n, e)
    return p / np.linalg.norm(p)
