"""
Beyond the paper: stability maps for l/R = 0.1
==============================================

Stepanov (PMM 1968) gives the stationary motions (2.3)-(2.4) of a gyrostat satellite and the conditions
(2.5) of their stability by Routh's method, but no map. Here the verdicts in the plane
(``theta0``, ``k2 / (omega0 Abar)``) for the six orderings of principal moments proportional to
(1.2, 1.0, 0.8), with ``l / R = sqrt(Abar / M) / R0 = 0.1``: stable, unstable (odd degree of instability)
or undecided (even degree). The exact boundaries ``s2 = 0``, ``s3 = 0``, ``s1 = 0`` are black, those of
the restricted problem (the orbit through the centre, the classical approximation) dashed blue.

Choices (the paper has no map): units ``M = mu = R0 = 1``, ``omega0 > 0``, a 301 x 301 grid,
``theta0 in (-1.5, 1.5)``, ``k2 / (omega0 Abar) in (-6, 6)``.

Drawn by :func:`rigidbody.paperfigs.gyrostat.stability_maps_lr01`.
"""

import matplotlib.pyplot as plt
import numpy as np

from rigidbody.paperfigs import gyrostat as figs

for ratios in figs.orderings():
    mp = figs.map_data(0.1, ratios)["map"]
    share = {v: float(np.mean(mp.verdict == v)) for v in ("stable", "unstable", "undecided")}
    print(f"A1:A2:A3 = {ratios}: " + ", ".join(f"{k} {v:.1%}" for k, v in share.items()))

fig = figs.stability_maps_lr01()
plt.show()
