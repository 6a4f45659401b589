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

Computed above with :func:`rigidbody.viscous.quasi_coordinates`, :func:`rigidbody.viscous.curvature`
and :func:`rigidbody.viscous.spiral_radius`; drawn by
:func:`rigidbody.paperfigs.viscous.histories`.
"""

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import viscous as vs
from rigidbody.paperfigs import viscous as figs

body, Omega0 = vs.Body(theta12=2.0, theta3=1.0), 6.0
spirals = {"contracting": (vs.Medium(B12=0.4, B3=0.1), 2.0), "unwinding": (vs.Medium(B12=0.1, B3=0.1), 0.6)}
t = np.linspace(0.0, 80.0, 801)
data = {}
print("spiral        s_inf    xi_inf   zeta_inf / 2 pi")
for name, (medium, v0) in spirals.items():
    s, xi, zeta = vs.quasi_coordinates(body, medium, Omega0, v0, t)  # (5.1)
    k = vs.curvature(body, medium, Omega0, v0, t)  # (4.5)
    R = vs.spiral_radius(body, medium, Omega0, v0, t)  # (5.2)
    data[name] = {"t": t, "k": k, "R": R, "s": s, "xi": xi, "zeta": zeta}
    s_inf, xi_inf, zeta_inf = vs.limits(body, medium, Omega0, v0)
    print(f"{name:12} {s_inf:7.4f}  {xi_inf:8.4f}  {zeta_inf / (2 * np.pi):10.3f}")

fig = figs.histories(data)
plt.show()
