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

Computed above with :func:`rigidbody.lagrange.averaged`; drawn by
:func:`rigidbody.paperfigs.lagrange.fig1_case1_theta5`.
"""

import math

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import lagrange
from rigidbody.paperfigs import lagrange as figs

# the paper's top and its linear drag (3.1), M = -eps (a p, a q, b r)
top = lagrange.Top(A=1.5, C=1.0, mgl=0.5)
drag = lagrange.LinearDrag(a=0.125, b=0.1)

# spun about its axis with r0 = sqrt(3), tilted by theta0 = 5.0 degrees: (p, q, r, phi, theta, psi)
state0 = (0.0, 0.0, math.sqrt(3.0), 0.0, math.radians(5.0), 0.0)
Gz0, H0, r0 = lagrange.integrals(top, *state0[:5])  # the integrals (1.2)
print("initial roots of (1.4):", np.round(lagrange.roots(top, Gz0, H0, r0), 3), " paper: (0.913, 0.996, 1.087)")

# the averaged system (3.4) in the slow time tau = eps t (eps drops out), tau in [0, 150.0]
sol = lagrange.averaged(top, drag, (Gz0, H0, r0), (0.0, 150.0), tau_eval=np.linspace(0.0, 150.0, 1501))
print(sol.message)
print(" tau      u1        u2        u3        Gz         H         r")
for j in (0, 100, 300, 600, 1000, 1500):
    print(f"{sol.tau[j]:5.0f} " + " ".join(f"{x:9.5f}" for x in (*sol.u[:, j], sol.Gz[j], sol.H[j], sol.r[j])))

print(f"H -> {sol.H[-1]:.6f} (-mgl = -0.5), u -> {np.round(sol.u[:, -1], 5)} (the top ends hanging down)")

fig = figs.fig1_case1_theta5(sol)
plt.show()
