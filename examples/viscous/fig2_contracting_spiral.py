"""
Fig. 2: the contracting spiral
==============================

Krivtsov (PMM 2000), figure 2: the path of the symmetry axis ``n`` on the unit sphere. Its speed
``v = v0 exp(-B12 t / theta12)`` and spin ``Omega = Omega0 exp(-B3 t / theta3)`` (3.3) give the geodesic
curvature ``k = theta3 Omega / (theta12 v)`` (4.5), so the path is a spiral of radius ``R = 1/sqrt(1 + k^2)``
(5.2). The curvature grows without bound (``B12/theta12 > B3/theta3``): the spiral, of finite length
``s_inf``, contracts to a point, the ``x`` at its centre. It is seen from that limit point.

Choices (the paper prints no numbers): ``theta12 = 2, theta3 = 1``, ``B12 = 0.4, B3 = 0.1``, ``Omega0 = 6``,
``n0 = e_x``, ``v0 = 2`` (``k0 = 1.5, R0 = 0.55``). The path is reconstructed from ``v(t)`` and ``k(t)`` alone
(:func:`rigidbody.viscous.axis_path`, checked against the full simulation in the tests) from ``t = 0`` to
``t = inf``; the far side of the sphere is dashed.

Computed above with :func:`rigidbody.viscous.axis_path`; drawn by
:func:`rigidbody.paperfigs.viscous.fig2_contracting_spiral`.
"""

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import viscous as vs
from rigidbody.paperfigs import viscous as figs

body = vs.Body(theta12=2.0, theta3=1.0)
medium = vs.Medium(B12=0.4, B3=0.1)
n0, ndot0, Omega0 = [1.0, 0.0, 0.0], [0.0, 2.0, 0.0], 6.0  # axis, its velocity (v0 = 2.0), spin
s_inf, xi_inf, zeta_inf = vs.limits(body, medium, Omega0, 2.0)
print(f"regime: {vs.regime(body, medium)}; length s_inf = {s_inf:.4f}, total turning xi_inf = {xi_inf:.4f} rad")
print("    t     curvature k (4.5)   radius R (5.2)")
for t in (0.0, 5.0, 10.0, 20.0, 40.0, 80.0):
    k, R = vs.curvature(body, medium, Omega0, 2.0, t), vs.spiral_radius(body, medium, Omega0, 2.0, t)
    print(f"{t:5.0f}  {k:18.4f}  {R:15.4f}")

# the path from t = 0 to t = inf, rebuilt from v(t) and k(t), on times uniform in the compactified time
# u = 1 - exp(-gamma t) of the reconstruction (dense where the path turns fast)
gamma = min(vs.decay_rates(body, medium))
u = np.linspace(0.0, 1.0 - np.exp(-gamma * 200.0), 4000)
t = np.append(-np.log1p(-u) / gamma, np.inf)
n = vs.axis_path(body, medium, n0, ndot0, Omega0, t)
print("the limit point n(inf) =", np.round(n[:, -1], 5))

fig = figs.fig2_contracting_spiral(n)  # seen from its limit point
plt.show()

