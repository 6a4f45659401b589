"""
Fig. 2: the top tilted by 60 degrees
====================================

Akulenko, Leshchenko, Chernousko (PMM 1979), figure 2, case 2 of section 3: the same top and drag as in
figure 1 (``A = 1.5, C = 1, mgl = 0.5``, ``r0 = sqrt(3)``, ``a = 0.125, b = 0.1``), tilted by 60 degrees; the
initial roots of (1.4) are ``(0, 0.5, 2)``. The averaged system (3.4) in ``tau = eps t``; ``Gz, H, r`` by (2.8).

Choices the paper leaves open: ``tau in [0, 150]``, shown against ``tau`` and against ``xi = ln(1 + tau)``
(the paper's variable for cases 1 and 2). The figure also checks the paper's control: ``r`` against the
exact ``r0 exp(-b tau / C)`` of (3.3).

Drawn by :func:`rigidbody.paperfigs.lagrange.fig2_case2_theta60`.
"""

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import lagrange
from rigidbody.paperfigs import lagrange as figs

sol = lagrange.paper_solution(2)
r_exact = np.sqrt(3.0) * np.exp(-lagrange.PAPER_DRAG.b * sol.tau / lagrange.PAPER_TOP.C)
print(sol.message)
print(f"max |r - r0 exp(-b tau/C)| = {np.max(np.abs(sol.r - r_exact)):.1e}")
print("delta1 changes sign at tau =", sol.t_events["delta1_flip"])

fig = figs.fig2_case2_theta60(sol)
plt.show()
