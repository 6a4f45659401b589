"""
Beyond the paper: the slow variables, case 1
=============================================

Rachinskaya's setup (section 3, ``A = (3.2, 2.6, 1.67)``, ``G(0) = 1``, ``k2(0) = 0.99``,
``delta(0) = lambda(0) = pi/4``, drag ``I = diag(2.322, 1.31, 1.425)``): the paper integrates the averaged
system (6)-(9) but plots only the hodograph. Here ``G, T, k2, delta, lambda`` against ``tau = eps^2 t`` for
the runs behind figures 1-3: the orbit-averaged limit ``eps = 0`` (dashed) and ``eps = 0.005`` with the true
anomaly kept (``nu0 = 0``), ``tau in [0, 6]`` (our choices; the paper states neither). ``G`` and ``T``
decrease strictly (6); ``k2`` follows (8): Case 1 (``chi < 0``): ``k2 = 0`` is unstable and ``k2`` decreases
towards the stable equilibrium ``k*^2 = 0.5206`` of (8) (dotted); at ``eps = 0.005`` the run ends at
``tau = 4.77`` (``slow_rotation``). With ``eps > 0`` ``delta`` oscillates with the orbital period, by
``O(eps)``, about its constant orbit-averaged value.

Drawn by :func:`rigidbody.paperfigs.euler_poinsot.slow_variables_case1`.
"""

import matplotlib.pyplot as plt

from rigidbody.paperfigs import euler_poinsot as figs

sols = figs.hodograph_data(1)
for eps, sol in sols.items():
    print(f"eps = {eps}: tau_end = {sol.tau[-1]:.3f}, G = {sol.G[-1]:.4f}, k2 = {sol.k2[-1]:.4f}")

fig = figs.slow_variables_case1(sols)
plt.show()
