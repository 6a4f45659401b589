"""
Beyond the paper: stability maps for l/R = 0.2
==============================================

Stepanov (PMM 1968) gives the stationary motions (2.3)-(2.4) of a gyrostat satellite and the conditions
(2.5) of their stability by Routh's method, but no map. Here the verdicts in the plane
(``theta0``, ``k2 / (omega0 Abar)``) for the six orderings of principal moments proportional to
(1.2, 1.0, 0.8), with ``l / R = sqrt(Abar / M) / R0 = 0.2``: stable, unstable (odd degree of instability)
or undecided (even degree). The exact boundaries ``s2 = 0``, ``s3 = 0``, ``s1 = 0`` are black, those of
the restricted problem (the orbit through the centre, the classical approximation) dashed blue.

Choices (the paper has no map): units ``M = mu = R0 = 1``, ``omega0 > 0``, a 301 x 301 grid,
``theta0 in (-1.5, 1.5)``, ``k2 / (omega0 Abar) in (-6, 6)``.

Computed above with :func:`rigidbody.gyrostat.normalized_stability_map`; drawn by
:func:`rigidbody.paperfigs.gyrostat.stability_maps_lr02`.
"""

import itertools

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import gyrostat
from rigidbody.paperfigs import gyrostat as figs

l_over_R = 0.2
theta0 = np.linspace(-1.5, 1.5, 301)
u = np.linspace(-6.0, 6.0, 301)  # k2 / (omega0 Abar)
maps = {}
print("A1 : A2 : A3        stable  unstable  undecided")
for ratios in sorted(set(itertools.permutations((1.2, 1.0, 0.8))), reverse=True):
    # moments in these ratios with sqrt(Abar / M) = l/R (M = mu = R0 = 1)
    s = l_over_R**2 * 3 / sum(ratios)
    sat = gyrostat.Satellite(M=1.0, A1=ratios[0] * s, A2=ratios[1] * s, A3=ratios[2] * s)
    maps[ratios] = gyrostat.normalized_stability_map(sat, 1.0, theta0, u)  # (StabilityMap, boundaries)
    verdict = maps[ratios][0].verdict
    print(f"{ratios!s:18}" + "".join(f"{np.mean(verdict == v):9.1%}" for v in ("stable", "unstable", "undecided")))

fig = figs.stability_maps_lr02(maps)
plt.show()
