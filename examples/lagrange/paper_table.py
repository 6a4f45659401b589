"""
The paper's table and the end states of its three cases
=======================================================

Akulenko, Leshchenko, Chernousko (PMM 1979), section 3: the initial roots ``u1, u2, u3`` of the cubic (1.4)
for the top ``A = 1.5, C = 1, mgl = 0.5`` spun with ``r0 = sqrt(3)`` and tilted by 5, 60 and 170 degrees
(the printed table), and where the averaged system (3.4) under the drag ``a = 0.125, b = 0.1`` takes each
case: ``H -> -mgl``, ``Gz -> 0``, ``u -> (-1, -1, 1)``, with the paper's check ``r = r0 exp(-b tau / C)`` (3.3).
Spans (not in the paper): ``tau in [0, 150]`` for cases 1, 2 and ``[0, 60]`` for case 3. Prints only; the
figures are the next scripts.
"""

import math

import numpy as np

from rigidbody import lagrange

top = lagrange.Top(A=1.5, C=1.0, mgl=0.5)
drag = lagrange.LinearDrag(a=0.125, b=0.1)
r0 = math.sqrt(3.0)
# tilt theta0 (degrees) -> the roots printed in the paper's table, and the span (our choice)
cases = {5.0: ((0.913, 0.996, 1.087), 150.0), 60.0: ((0.0, 0.5, 2.0), 150.0), 170.0: ((-0.992, -0.985, 2.992), 60.0)}

print("theta0  roots of (1.4): u1, u2, u3    | printed in the paper")
sols = {}
for th, (printed, tau_end) in cases.items():
    Gz, H, r = lagrange.integrals(top, 0.0, 0.0, r0, 0.0, math.radians(th))  # spun about the axis, tilted
    u = lagrange.roots(top, Gz, H, r)
    print(f"{th:6.0f}  " + "".join(f"{x:9.5f} " for x in u) + " |" + "".join(f"{x:8.3f}" for x in printed))
    sols[th] = lagrange.averaged(top, drag, (Gz, H, r), (0.0, tau_end), tau_eval=np.linspace(0.0, tau_end, 1501))

print("\nwhere (3.4) takes each case: H -> -mgl = -0.5, Gz -> 0, u -> (-1, -1, 1); r exactly r0 exp(-b tau/C) (3.3)")
print("theta0  tau_end       H          Gz        u1        u2        u3    max |r - r0 exp(-b tau/C)|")
for th, sol in sols.items():
    r_err = np.abs(sol.r - r0 * np.exp(-drag.b * sol.tau / top.C)).max()
    u_end = "".join(f"{x:10.5f}" for x in sol.u[:, -1])
    print(f"{th:6.0f}  {sol.tau[-1]:7.0f}  {sol.H[-1]:10.6f}  {sol.Gz[-1]:+.2e}{u_end}  {r_err:12.1e}")
