"""Helpers shared by the viscous test files."""

import numpy as np


def initial(seed=1, v0=0.4):
    """A random unit axis n0 and an initial axis velocity ndot0 perpendicular to it, |ndot0| = v0."""
    rng = np.random.default_rng(seed)
    n0 = rng.normal(size=3)
    n0 /= np.linalg.norm(n0)
    d = np.cross(n0, rng.normal(size=3))
    return n0, v0 * d / np.linalg.norm(d)
