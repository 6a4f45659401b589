"""
Fig. 2: the top tilted by 60 degrees
====================================

Akulenko, Leshchenko, Chernousko (PMM 1979), figure 2, case 2 of section 3: the same top and drag as in
figure 1 (``A = 1.5, C = 1, mgl = 0.5``, ``r0 = sqrt(3)``, ``a = 0.125, b = 0.1``), tilted by 60 degrees; the
initial roots of (1.4) are ``(0, 0.5, 2)``. The averaged system (3.4) in ``tau = eps t``; ``Gz, H, r`` by (2.8).

Choices the paper leaves open: ``tau in [0, 150]``, shown against ``tau`` and against ``xi = ln(1 + tau)``
(the paper's variable for cases 1 and 2). The figure also checks the paper's control: ``r`` against the
exact ``r0 exp(-b tau / C)`` of (3.3).

Computed above with :func:`rigidbody.lagrange.averaged`; drawn by
:func:`rigidbody.paperfigs.lagrange.fig2_case2_theta60`.
"""

import math

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import lagrange
from rigidbody.paperfigs import lagrange as figs

# the paper's top and its linear drag (3.1), M = -eps (a p, a q, b r)
top = lagrange.Top(A=1.5, C=1.0, mgl=0.5)
drag = lagrange.LinearDrag(a=0.125, b=0.1)

# spun about its axis with r0 = sqrt(3), tilted by theta0 = 60.0 degrees: (p, q, r, phi, theta, psi)
state0 = (0.0, 0.0, math.sqrt(3.0), 0.0, math.radians(60.0), 0.0)
Gz0, H0, r0 = lagrange.integrals(top, *state0[:5])  # the integrals (1.2)
print("initial roots of (1.4):", np.round(lagrange.roots(top, Gz0, H0, r0), 3), " paper: (0, 0.5, 2)")

# the averaged system (3.4) in the slow time tau = eps t (eps drops out), tau in [0, 150.0]
sol = lagrange.averaged(top, drag, (Gz0, H0, r0), (0.0, 150.0), tau_eval=np.linspace(0.0, 150.0, 1501))
print(sol.message)
print(" tau      u1        u2        u3        Gz         H         r")
for j in (0, 100, 300, 600, 1000, 1500):
    print(f"{sol.tau[j]:5.0f} " + " ".join(f"{x:9.5f}" for x in (*sol.u[:, j], sol.Gz[j], sol.H[j], sol.r[j])))

r_exact = r0 * np.exp(-drag.b * sol.tau / top.C)  # (3.3)
print(f"max |r - r0 exp(-b tau/C)| = {np.max(np.abs(sol.r - r_exact)):.1e}")
print("delta1 changes sign at tau =", sol.t_events["delta1_flip"])

fig = figs.fig2_case2_theta60(sol)
plt.show()
