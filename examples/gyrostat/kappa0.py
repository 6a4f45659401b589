"""
Beyond the paper: how far is the orbit plane displaced?
=======================================================

Stepanov (PMM 1968), (2.4): the latitude ``kappa0`` of the centre of mass above the plane through the
attracting centre, for the stationary motions (2.3). The paper states that ``kappa0`` is of order
``l^2 / R^2`` and largest at ``theta0 = pi/4``. Left: ``kappa0(theta0)`` for ``l/R = 0.05, 0.1, 0.2, 0.3``;
right: ``kappa0 / (l/R)^2``: the curves collapse, and their maxima (dots) tend to ``pi/4`` as ``l/R -> 0``.

Choices: principal moments in the ratio 1.2 : 1.0 : 0.8, units ``M = mu = R0 = 1``, ``k2 = 0`` (``kappa0``
does not depend on ``k2``), ``theta0 in (-1.5, 1.5)``.

Computed above with :func:`rigidbody.gyrostat.stability_map`; drawn by
:func:`rigidbody.paperfigs.gyrostat.kappa0`.
"""

import math

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import gyrostat
from rigidbody.paperfigs import gyrostat as figs

theta0 = np.linspace(-1.5, 1.5, 301)
kappa = {}
print(" l/R   max kappa0 (deg)  at theta0   kappa0 / (l/R)^2")
for lR in (0.05, 0.1, 0.2, 0.3):
    # moments in the ratio 1.2 : 1.0 : 0.8 with their mean Abar = M l^2 (M = mu = R0 = 1)
    sat = gyrostat.Satellite(M=1.0, A1=1.2 * lR**2, A2=1.0 * lR**2, A3=0.8 * lR**2)
    kappa[lR] = gyrostat.stability_map(sat, 1.0, theta0, k2=0.0).kappa0  # (2.4); it does not depend on k2
    i = int(np.argmax(kappa[lR]))
    print(f"{lR:4}  {math.degrees(kappa[lR][i]):16.4f}  {theta0[i]:9.2f}  {kappa[lR][i] / lR**2:16.4f}")
print(f"(pi/4 = {math.pi / 4:.4f})")

fig = figs.kappa0(kappa)
plt.show()
