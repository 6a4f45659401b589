"""
Fig. 1: the top tilted by 5 degrees
===================================

Akulenko, Leshchenko, Chernousko, *Perturbed motions of a rigid body close to the Lagrange case* (PMM 1979),
figure 1, case 1 of section 3.

A heavy symmetric top, ``A = 1.5, C = 1, mgl = 0.5``, spun about its axis with ``r0 = sqrt(3)`` and tilted by
``theta0 = 5`` degrees, under the linear drag (3.1) ``M = -eps (a p, a q, b r)`` with ``a = 0.125, b = 0.1``.
The slow variables are the roots ``u1 <= u2 <= u3`` of the cubic (1.4) built from the integrals
``Gz, H, r`` (1.2); the averaged system (2.15), for this drag in closed form (3.4), is integrated in the slow
time ``tau = eps t`` (``eps`` itself drops out). ``Gz, H, r`` follow from the roots by (2.8). The paper's
statements: ``H`` decreases to ``-mgl``, ``Gz`` to 0, ``u1, u2 -> -1`` and ``u3 -> 1`` (the top ends hanging
down); ``r = r0 exp(-b tau / C)`` exactly (3.3).

Choices the paper leaves open: the span, ``tau in [0, 150]``; since case 1 evolves slowly the paper changed
the variable to ``xi = ln(1 + tau)``, so the figure shows both abscissas (bottom row: ``xi``). Dotted
verticals: the sign change of ``delta1`` in (2.8).

Drawn by :func:`rigidbody.paperfigs.lagrange.fig1_case1_theta5`.
"""

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import lagrange
from rigidbody.paperfigs import lagrange as figs

sol = lagrange.paper_solution(1)  # (3.4) from the paper's initial state, tau in [0, 150]
print(sol.message)
print("initial roots:", np.round(sol.u[:, 0], 3), " paper:", lagrange.PAPER_TABLE[1])
print(f"at tau = {sol.tau[-1]:g}: u = {np.round(sol.u[:, -1], 5)}, H = {sol.H[-1]:.6f} (-mgl = -0.5)")

fig = figs.fig1_case1_theta5(sol)
plt.show()
