"""
Beyond the paper: the symmetric gyrostat, verdicts over (theta0, A3/A1)
=======================================================================

Stepanov (PMM 1968), section 3: for a symmetric satellite (``A1 = A2``) the stationary motions (3.2)-(3.3)
exist for any tilt ``theta0``, and the paper's condition (3.4), ``W_psipsi > 0`` iff ``A1 > A3``, decides
their stability. Here the verdicts of the full second variation of the amended potential over ``theta0``
and ``A3 / A1``, with the boundary ``A3 = A1`` where (3.4) changes sign and the line ``3 A3 = 4 A1`` above
which the paper's instability claim for ``A3 > A1`` no longer follows (even degree: undecided; see the
errata).

Choices: ``l/R = 0.1`` (``A1 = 0.01``, ``M = mu = R0 = 1``), ``theta0 in (-3.1, 3.1)``,
``A3 / A1 in (0.05, 2)``. Near ``cos theta0 = 0`` the ``O(l^2/R^2)`` terms decide, and ``sin theta0 = 0`` is
singular for this chart (grey).

Computed above with :func:`rigidbody.gyrostat.symmetric_stability_map`; drawn by
:func:`rigidbody.paperfigs.gyrostat.symmetric_map`.
"""

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import gyrostat
from rigidbody.paperfigs import gyrostat as figs

# a symmetric satellite with l/R = 0.1 (A1 = A2 = M l^2, M = mu = R0 = 1); A3 / A1 is varied
theta0 = np.linspace(-3.1, 3.1, 311)
ratio = np.linspace(0.05, 2.0, 196)
A1 = 0.1**2
sat = gyrostat.Satellite(M=1.0, A1=A1, A2=A1, A3=A1)
sm = gyrostat.symmetric_stability_map(sat, 1.0, theta0, A3=ratio * A1)  # (3.2)-(3.3), full second variation
for verdict in ("stable", "unstable", "undecided"):
    print(f"{verdict:10}: {np.mean(sm.verdict == verdict):6.1%} of the grid")

fig = figs.symmetric_map(sm)
plt.show()
