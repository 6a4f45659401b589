"""
Fig. 3: the unwinding spiral
============================

Krivtsov (PMM 2000), figure 3: the path of the symmetry axis ``n`` on the unit sphere. Its speed
``v = v0 exp(-B12 t / theta12)`` and spin ``Omega = Omega0 exp(-B3 t / theta3)`` (3.3) give the geodesic
curvature ``k = theta3 Omega / (theta12 v)`` (4.5), so the path is a spiral of radius ``R = 1/sqrt(1 + k^2)``
(5.2). The curvature decays (``B12/theta12 < B3/theta3``): the spiral unwinds towards a great circle of the
sphere; it is seen from the pole of that circle.

Choices (the paper prints no numbers): ``theta12 = 2, theta3 = 1``, ``B12 = 0.1, B3 = 0.1``, ``Omega0 = 6``,
``n0 = e_x``, ``v0 = 0.6`` (``k0 = 5, R0 = 0.2``). The path is reconstructed from ``v(t)`` and ``k(t)`` alone
(:func:`rigidbody.viscous.axis_path`, checked against the full simulation in the tests) from ``t = 0`` to
``t = inf``; the far side of the sphere is dashed.

Drawn by :func:`rigidbody.paperfigs.viscous.fig3_unwinding_spiral`.
"""

import matplotlib.pyplot as plt

from rigidbody import viscous as vs
from rigidbody.paperfigs import viscous as figs

data = figs.figure_data("unwinding")  # the path n(t) and the closed-form k, R, s, xi, zeta
s_inf, xi_inf, zeta_inf = vs.limits(figs.BODY, figs.MEDIA["unwinding"], figs.OMEGA0, 0.6)
print(f"regime: {vs.regime(figs.BODY, figs.MEDIA['unwinding'])}; length s_inf = {s_inf:.4f}, "
      f"total turning xi_inf = {xi_inf:.4f} rad, R from {data['R'][0]:.3f} to {data['R'][-1]:.3f}")

fig = figs.fig3_unwinding_spiral(data)
plt.show()
