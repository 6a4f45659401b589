"""
Fig. 3: the top tilted by 170 degrees
=====================================

Akulenko, Leshchenko, Chernousko (PMM 1979), figure 3, case 3 of section 3: the same top and drag as in
figures 1-2, started almost hanging (tilted by 170 degrees); initial roots ``(-0.992, -0.985, 2.992)``. Here
``Gz`` increases to 0 (it decreases in cases 1 and 2), as the paper states. Averaged system (3.4) in
``tau = eps t``; ``Gz, H, r`` by (2.8).

Choices the paper leaves open: ``tau in [0, 60]`` (the evolution is fast; the paper used ``tau`` here, not
``xi``).

Drawn by :func:`rigidbody.paperfigs.lagrange.fig3_case3_theta170`.
"""

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import lagrange
from rigidbody.paperfigs import lagrange as figs

sol = lagrange.paper_solution(3)
print(sol.message)
print(f"Gz from {sol.Gz[0]:.4f} to {sol.Gz[-1]:.2e}; monotone increase: {bool(np.all(np.diff(sol.Gz) >= 0))}")

fig = figs.fig3_case3_theta170(sol)
plt.show()
