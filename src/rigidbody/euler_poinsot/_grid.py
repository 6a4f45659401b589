"""The node counts and the orbit nodes of the averaging engine (shared by :mod:`._engine` and :mod:`._lean`)."""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from ..core import averaging as avg

__all__ = ["Grid", "nu_nodes"]


@functools.lru_cache(maxsize=64)
def nu_nodes(e: float, n_nu: int, dual: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """True-anomaly nodes and time weights (sum 1) for the mean over one orbit of eccentricity ``e``
    (Kepler's law: dt is proportional to (1 + e cos nu)^-2 d nu). ``dual``: the nodes shifted by half a
    step. Cached; read-only arrays."""
    nu = (np.arange(n_nu) + (0.5 if dual else 0.0)) * (2.0 * math.pi / n_nu)
    w = (1.0 + e * np.cos(nu)) ** -2.0
    w /= w.sum()
    nu.setflags(write=False)
    w.setflags(write=False)
    return nu, w


@dataclass
class Grid:
    """Node counts of the engine: precession angle, elliptic phase (a multiple of the core's count), orbit."""

    n_psi: int = 8
    m_u: float = 1.0
    n_nu: int = 16

    def n_u(self, mc: float) -> int:
        n = round(self.m_u * avg.n_nodes(mc=mc, period="4K"))
        return max(4, n + (-n) % 4)
