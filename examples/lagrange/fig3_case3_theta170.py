"""
Fig. 3: the top tilted by 170 degrees
=====================================

Akulenko, Leshchenko, Chernousko (PMM 1979), figure 3, case 3 of section 3: the same top and drag as in
figures 1-2, started almost hanging (tilted by 170 degrees); initial roots ``(-0.992, -0.985, 2.992)``. Here
``Gz`` increases to 0 (it decreases in cases 1 and 2), as the paper states. Averaged system (3.4) in
``tau = eps t``; ``Gz, H, r`` by (2.8).

Choices the paper leaves open: ``tau in [0, 60]`` (the evolution is fast; the paper used ``tau`` here, not
``xi``).

Computed above with :func:`rigidbody.lagrange.averaged`; drawn by
:func:`rigidbody.paperfigs.lagrange.fig3_case3_theta170`.
"""

import math

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import lagrange
from rigidbody.paperfigs import lagrange as figs

# the paper's top and its linear drag (3.1), M = -eps (a p, a q, b r)
top = lagrange.Top(A=1.5, C=1.0, mgl=0.5)
drag = lagrange.LinearDrag(a=0.125, b=0.1)

# spun about its axis with r0 = sqrt(3), tilted by theta0 = 170.0 degrees: (p, q, r, phi, theta, psi)
state0 = (0.0, 0.0, math.sqrt(3.0), 0.0, math.radians(170.0), 0.0)
Gz0, H0, r0 = lagrange.integrals(top, *state0[:5])  # the integrals (1.2)
print("initial roots of (1.4):", np.round(lagrange.roots(top, Gz0, H0, r0), 3), " paper: (-0.992, -0.985, 2.992)")

# the averaged system (3.4) in the slow time tau = eps t (eps drops out), tau in [0, 60.0]
sol = lagrange.averaged(top, drag, (Gz0, H0, r0), (0.0, 60.0), tau_eval=np.linspace(0.0, 60.0, 1501))
print(sol.message)
print(" tau      u1        u2        u3        Gz         H         r")
for j in range(0, 1501, 250):
    print(f"{sol.tau[j]:5.0f} " + " ".join(f"{x:9.5f}" for x in (*sol.u[:, j], sol.Gz[j], sol.H[j], sol.r[j])))

print(f"Gz from {sol.Gz[0]:.4f} to {sol.Gz[-1]:.2e}; monotone increase: {bool(np.all(np.diff(sol.Gz) >= 0))}")

fig = figs.fig3_case3_theta170(sol)
plt.show()
