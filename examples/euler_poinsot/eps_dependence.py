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

Computed above with :func:`rigidbody.euler_poinsot.averaged`; drawn by
:func:`rigidbody.paperfigs.euler_poinsot.eps_dependence`.
"""

import math

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import euler_poinsot as ep
from rigidbody.paperfigs import euler_poinsot as figs

# the paper's satellite and its two drag tensors (section 3)
body = ep.Body(A1=3.2, A2=2.6, A3=1.67)
cases = {1: np.diag([2.322, 1.31, 1.425]), 2: np.diag([0.919, 5.228, 1.666])}
tau = np.linspace(0.0, 6.0, 3001)

sols = {}
print("case   eps   spin ratio at the start   max |delta - pi/4|   end")
for case, I in cases.items():
    sols[case] = {}
    for eps in (0.0, 0.01, 0.1, 0.3):
        # the theory needs a fast rotation, spin ratio > 1; below it, integrate anyway with the check off
        ratio = ep.spin_ratio(body, eps, 1.0, 0.99) if eps > 0 else math.inf
        sols[case][eps] = ep.averaged(body, I, eps, G0=1.0, k2_0=0.99, delta0=math.pi / 4, lam0=math.pi / 4,
                                      nu0=0.0, tau_span=(0.0, 6.0), tau_eval=tau,
                                      min_spin_ratio=1.0 if ratio > 1.0 else 0.0)
        s = sols[case][eps]
        print(f"{case:4d}  {eps:4g}  {ratio:23.3f}  {np.abs(s.delta - math.pi / 4).max():19.4f}   "
              f"{s.event or 'tau = 6'}")

fig = figs.eps_dependence(sols)
plt.show()
