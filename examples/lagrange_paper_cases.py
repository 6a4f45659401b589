"""The three cases of Akulenko, Leshchenko, Chernousko (1979), Sec. 3: the table and the slow evolution.

Writes figs 1-3 to ./lagrange_figs (same builder as ``python -m rigidbody figures --only lagrange``).
"""

import math
from pathlib import Path

import numpy as np

from rigidbody import lagrange
from rigidbody.paperfigs.lagrange import build

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
          f"u -> {np.round(sol.u[:, -1], 5)}, delta1 flips at {sol.t_events['delta1_flip']}, "
          f"max |r - r0 exp(-b tau/C)| = {r_err:.1e}")

print(build(Path("lagrange_figs")))
