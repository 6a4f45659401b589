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

Drawn by :func:`rigidbody.paperfigs.viscous.fig2_contracting_spiral`.
"""

import matplotlib.pyplot as plt

from rigidbody import viscous as vs
from rigidbody.paperfigs import viscous as figs

data = figs.figure_data("contracting")  # the path n(t) and the closed-form k, R, s, xi, zeta
s_inf, xi_inf, zeta_inf = vs.limits(figs.BODY, figs.MEDIA["contracting"], figs.OMEGA0, 2)
print(f"regime: {vs.regime(figs.BODY, figs.MEDIA['contracting'])}; length s_inf = {s_inf:.4f}, "
      f"total turning xi_inf = {xi_inf:.4f} rad, R from {data['R'][0]:.3f} to {data['R'][-1]:.3f}")

fig = figs.fig2_contracting_spiral(data)
plt.show()
