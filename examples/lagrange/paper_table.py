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

top, drag = lagrange.PAPER_TOP, lagrange.PAPER_DRAG
print("case theta0   u1      u2      u3     (paper)")
for case, th in lagrange.PAPER_CASES.items():
    Gz, H, r = lagrange.integrals(top, *lagrange.paper_initial_state(case)[:5])
    u = lagrange.roots(top, Gz, H, r)
    print(f"{case:4d} {th:5.0f}  " + " ".join(f"{x:7.3f}" for x in u), " ", lagrange.PAPER_TABLE[case])

for case in (1, 2, 3):
    sol = lagrange.paper_solution(case)
    r_err = np.abs(sol.r - math.sqrt(3) * np.exp(-drag.b * sol.tau / top.C)).max()
    print(f"case {case}: tau_end = {sol.tau[-1]:g}, H -> {sol.H[-1]:.6f}, Gz -> {sol.Gz[-1]:.2e}, "
          f"u -> {np.round(sol.u[:, -1], 5)}, max |r - r0 exp(-b tau/C)| = {r_err:.1e}")
