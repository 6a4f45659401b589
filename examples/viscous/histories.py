"""
Beyond the paper: curvature, radius and quasi-coordinates against time
======================================================================

Krivtsov (PMM 2000) integrates the motion in the quasi-coordinates ``s`` (path length of the axis on the
sphere), ``xi`` (its total turning) and ``zeta`` (``d zeta / dt = Omega``) in closed form (5.1); the
curvature ``k`` is (4.5) and the radius of a turn ``R = 1/sqrt(1 + k^2)`` (5.2). The paper plots none of
them against time; here they are for the two spirals of figures 2 and 3 (same choices: ``theta12 = 2,
theta3 = 1``, ``Omega0 = 6``; contracting ``B12 = 0.4, B3 = 0.1, v0 = 2``; unwinding ``B12 = 0.1, B3 = 0.1,
v0 = 0.6``), ``t in [0, 80]``. ``s``, ``xi``, ``zeta`` tend to the finite limits that give the length of the
spiral, its total turning and the number of turns of the body about its axis.

Drawn by :func:`rigidbody.paperfigs.viscous.histories`.
"""

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import viscous as vs
from rigidbody.paperfigs import viscous as figs

data = {name: figs.figure_data(name) for name in figs.MEDIA}
for name in data:
    s_inf, xi_inf, zeta_inf = vs.limits(figs.BODY, figs.MEDIA[name], figs.OMEGA0, np.linalg.norm(figs.NDOT0[name]))
    print(f"{name}: s_inf = {s_inf:.4f}, xi_inf = {xi_inf:.4f}, zeta_inf / 2 pi = {zeta_inf / (2 * np.pi):.3f}")

fig = figs.histories(data)
plt.show()
