"""
Beyond the paper: the slow variables, case 2
=============================================

Rachinskaya's setup (section 3, ``A = (3.2, 2.6, 1.67)``, ``G(0) = 1``, ``k2(0) = 0.99``,
``delta(0) = lambda(0) = pi/4``, drag ``I = diag(0.919, 5.228, 1.666)``): the paper integrates the averaged
system (6)-(9) but plots only the hodograph. Here ``G, T, k2, delta, lambda`` against ``tau = eps^2 t`` for
the runs behind figures 4-6: the orbit-averaged limit ``eps = 0`` (dashed) and ``eps = 0.005`` with the true
anomaly kept (``nu0 = 0``), ``tau in [0, 6]`` (our choices; the paper states neither). ``G`` and ``T``
decrease strictly (6); ``k2`` follows (8): Case 2 (``chi > 0``): ``k2 -> 0`` (dotted: its stable equilibrium),
the rotation tends to the axis of the largest moment. With ``eps > 0`` ``delta`` oscillates with the orbital
period, by ``O(eps)``, about its constant orbit-averaged value.

Drawn by :func:`rigidbody.paperfigs.euler_poinsot.slow_variables_case2`.
"""

import matplotlib.pyplot as plt

from rigidbody.paperfigs import euler_poinsot as figs

sols = figs.hodograph_data(2)
for eps, sol in sols.items():
    print(f"eps = {eps}: tau_end = {sol.tau[-1]:.3f}, G = {sol.G[-1]:.4f}, k2 = {sol.k2[-1]:.4f}")

fig = figs.slow_variables_case2(sols)
plt.show()
