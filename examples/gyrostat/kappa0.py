"""
Beyond the paper: how far is the orbit plane displaced?
=======================================================

Stepanov (PMM 1968), (2.4): the latitude ``kappa0`` of the centre of mass above the plane through the
attracting centre, for the stationary motions (2.3). The paper states that ``kappa0`` is of order
``l^2 / R^2`` and largest at ``theta0 = pi/4``. Left: ``kappa0(theta0)`` for ``l/R = 0.05, 0.1, 0.2, 0.3``;
right: ``kappa0 / (l/R)^2``: the curves collapse, and their maxima (dots) tend to ``pi/4`` as ``l/R -> 0``.

Choices: principal moments in the ratio 1.2 : 1.0 : 0.8, units ``M = mu = R0 = 1``, ``k2 = 0`` (``kappa0``
does not depend on ``k2``), ``theta0 in (-1.5, 1.5)``.

Drawn by :func:`rigidbody.paperfigs.gyrostat.kappa0`.
"""

import math

import matplotlib.pyplot as plt
import numpy as np

from rigidbody.paperfigs import gyrostat as figs

for lR, kappa in figs.kappa_data().items():
    i = int(np.argmax(kappa))
    print(f"l/R = {lR:4}: max kappa0 = {math.degrees(kappa[i]):.4f} deg at theta0 = {figs.THETA[i]:.2f} "
          f"(pi/4 = {math.pi / 4:.4f}), kappa0 / (l/R)^2 = {kappa[i] / lR**2:.4f}")

fig = figs.kappa0()
plt.show()
