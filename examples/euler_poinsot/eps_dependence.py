"""
Beyond the paper: how the picture depends on eps
================================================

Rachinskaya's setup (section 3) for both drag tensors, integrated by the averaged system (9) with the true
anomaly kept, for ``eps = 0`` (orbit-averaged), 0.01, 0.1 and 0.3; ``nu0 = 0``, ``tau in [0, 6]`` (our choices;
the paper states neither ``eps`` nor the span). Left: ``delta(tau)``; middle: the projection of the hodograph on
the orbit plane ``Ox1x2``; right: the side view along ``x3`` (distance from the axis against the height),
where a constant ``delta`` is a straight line.

``eps = 0.1`` and ``0.3`` are outside the theory: the rotation started next to the separatrix is then not fast
compared with the orbit (``ep.spin_ratio < 1``), and they are integrated with the check switched off
(``min_spin_ratio=0``). Only there does ``delta`` drift and the spiral bend as the paper describes; within the
theory ``cos delta`` is an adiabatic invariant (see the theory page).

Drawn by :func:`rigidbody.paperfigs.euler_poinsot.eps_dependence`.
"""

import matplotlib.pyplot as plt

from rigidbody import euler_poinsot as ep
from rigidbody.paperfigs import euler_poinsot as figs

body = ep.Body(A1=3.2, A2=2.6, A3=1.67)
for eps in (0.01, 0.1, 0.3):
    print(f"eps = {eps}: spin ratio at the start = {ep.spin_ratio(body, eps, 1.0, 0.99):.3f} (> 1 needed)")

fig = figs.eps_dependence()
plt.show()
