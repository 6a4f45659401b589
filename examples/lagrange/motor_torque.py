"""
Beyond the paper: a motor torque
================================

A torque the paper did not print: theta-dependent equatorial drag plus an axial motor. Class (2.4) of
Akulenko, Leshchenko, Chernousko (1979): ``M1 = p f, M2 = q f`` with ``f = -a (1 + kappa cos theta)``,
``M3 = m0 - b r``. The general averaging engine (nutation mean of (2.7), then ``V`` of (2.13)) gives the slow
evolution; the full equations (1.1) check it, and ``r`` has the exact form
``m0/b + (r0 - m0/b) exp(-b tau / C)``. The top is the paper's (``A = 1.5, C = 1, mgl = 0.5``), spun with
``r0 = sqrt(3)`` and tilted by 60 degrees; ``a = 0.125, b = 0.1, kappa = 0.5, m0 = 0.15`` and the span
``tau in [0, 10]`` are our choices. The result draws itself (``avg.plot()``: the roots and the integrals
against ``tau``).
"""

import math

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import lagrange

top = lagrange.Top(A=1.5, C=1.0, mgl=0.5)
a, b, kappa, m0 = 0.125, 0.1, 0.5, 0.15
torque = lagrange.ProportionalTorque(
    f=lambda Gz, H, r, theta: -a * (1.0 + kappa * np.cos(theta)),
    M3=lambda Gz, H, r, theta: m0 - b * r + 0.0 * theta,
)
state0 = (0.0, 0.0, math.sqrt(3.0), 0.0, math.radians(60.0), 0.0)  # spun, tilted by 60 deg
Gz0, H0, r0 = lagrange.integrals(top, *state0[:5])
print("initial roots u1, u2, u3 =", np.round(lagrange.roots(top, Gz0, H0, r0), 6))

tau_end = 10.0
avg = lagrange.averaged(top, torque, (Gz0, H0, r0), (0.0, tau_end), tau_eval=np.linspace(0, tau_end, 11))
print(avg.message)
r_exact = m0 / b + (r0 - m0 / b) * np.exp(-b * avg.tau / top.C)
print("max |r - exact| along the averaged solution:", np.abs(avg.r - r_exact).max())

for eps in (0.02, 0.01):
    full = lagrange.simulate(top, torque, eps, state0, (0.0, tau_end / eps), t_eval=avg.tau / eps)
    err = max(np.abs(full.Gz - avg.Gz).max(), np.abs(full.H - avg.H).max(), np.abs(full.r - avg.r).max())
    print(f"eps = {eps}: max slow-variable error of the averaged solution = {err:.2e}")
print(" tau     u1        u2        u3        Gz        H         r")
for j in range(0, avg.tau.size, 2):
    print(f"{avg.tau[j]:4.1f} " + " ".join(f"{x:9.5f}" for x in (*avg.u[:, j], avg.Gz[j], avg.H[j], avg.r[j])))

axes = avg.plot()
axes[0].set_title("roots of (1.4) under the motor torque")
plt.show()
