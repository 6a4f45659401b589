"""
Fig. 4: one turn of the contracting spiral and its solid angle
==============================================================

Krivtsov (PMM 2000), figure 4 and section 5: the axial turn of the body while the axis ``n`` runs once
round the spiral follows from the solid-angle theorem, ``Delta phi = chi + Delta zeta``, with ``Delta zeta``
the increment of the quasi-coordinate ``zeta`` (5.1) over the turn and ``chi`` the solid angle the turn
bounds (filled); for dense turns ``chi ~ 2 pi (1 - sqrt(1 - R^2))`` with the radius ``R`` of (5.2).

Choices (the paper prints no numbers; as in figures 2-3): ``theta12 = 2, theta3 = 1``, ``B12 = 0.4, B3 = 0.1``,
``Omega0 = 6``, ``n0 = e_x``, ``v0 = 2``. A turn starts at ``t1 = 0`` about the osculating centre of the
path there and ends when the azimuth about it has advanced by ``2 pi`` (:func:`rigidbody.viscous.turn`);
the dotted arc closes it along the meridian through the centre. The title gives ``chi``, its cap
approximation and ``Delta zeta``.

Computed above with :func:`rigidbody.viscous.turn`; drawn by
:func:`rigidbody.paperfigs.viscous.fig4_turn_contracting`.
"""

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import viscous as vs
from rigidbody.paperfigs import viscous as figs

body = vs.Body(theta12=2.0, theta3=1.0)
medium = vs.Medium(B12=0.4, B3=0.1)
n0, ndot0, Omega0 = [1.0, 0.0, 0.0], [0.0, 2.0, 0.0], 6.0  # axis, its velocity (v0 = 2.0), spin

# one turn from t1 = 0, its solid angle chi and the axial turn Delta phi = chi + Delta zeta
tr = vs.turn(body, medium, n0, ndot0, Omega0, 0.0)
print(f"turn: t in [0, {tr.t2:.4f}], radius R from {tr.R1:.4f} to {tr.R2:.4f}")
print(f"chi = {tr.chi:.6f}, cap approximation 2 pi (1 - sqrt(1 - R^2)) at mid-turn {tr.chi_approx:.6f} "
      f"(relative difference {abs(tr.chi_approx / tr.chi - 1):.1e})")
print(f"Delta zeta = {tr.dzeta:.4f}, axial turn Delta phi = {tr.dphi:.4f} = {tr.dphi / (2 * np.pi):.3f} turns")

fig = figs.fig4_turn_contracting(tr)
plt.show()
