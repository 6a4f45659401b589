"""
Fig. 5: projection on the orbit plane, case 2
=============================================

Rachinskaya, *Rapid rotation of a satellite in a resisting medium in a circular orbit*, figure 5.

The paper's setup (section 3): a body with ``A = (3.2, 2.6, 1.67)`` on a circular orbit, spinning fast
(``eps = omega0 / omega`` small), started with ``G(0) = 1``, ``k2(0) = 0.99`` (next to the separatrix of the
Euler-Poinsot motion), ``delta(0) = lambda(0) = pi/4`` (the angles of ``G`` from the orbit normal ``x3`` and
about it); gravity-gradient and drag torques (3), drag tensor ``I = diag(0.919, 5.228, 1.666)`` (case 2,
``chi > 0``). The averaged system (6)-(9) in the slow time ``tau = eps^2 t`` gives
``G, T, k2, delta, lambda``; the hodograph is the end of ``G = G n`` in the orbital axes ``Ox1x2x3``.

The figure: the hodograph projected on the orbit plane ``Ox1x2``; the paper draws it "at a larger scale", here
the right panel: the square drawn on the left, enlarged, holding the turns after the first one. The
``eps = 0.005`` run wiggles about the orbit-averaged one with the orbital period.

Choices the paper leaves open: ``eps``, the initial true anomaly and the end time. We draw the orbit-averaged
limit ``eps = 0`` (dashed) and ``eps = 0.005`` with the true anomaly kept (``nu0 = 0``), for
``tau in [0, 6]``.

Drawn by :func:`rigidbody.paperfigs.euler_poinsot.fig5_projection_case2`.
"""

import matplotlib.pyplot as plt
import numpy as np

from rigidbody.paperfigs import euler_poinsot as figs

sols = figs.hodograph_data(2)  # {eps: averaged Solution} for eps = 0 and 0.005
for eps, sol in sols.items():
    print(f"eps = {eps}: {(sol.lam[0] - sol.lam[-1]) / (2 * np.pi):.2f} turns, G from 1 to {sol.G[-1]:.4f}")

fig = figs.fig5_projection_case2(sols)
plt.show()
