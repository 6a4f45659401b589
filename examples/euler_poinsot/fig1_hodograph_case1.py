"""
Fig. 1: the hodograph of the angular momentum, case 1
=====================================================

Rachinskaya, *Rapid rotation of a satellite in a resisting medium in a circular orbit*, figure 1.

The paper's setup (section 3): a body with ``A = (3.2, 2.6, 1.67)`` on a circular orbit, spinning fast
(``eps = omega0 / omega`` small), started with ``G(0) = 1``, ``k2(0) = 0.99`` (next to the separatrix of the
Euler-Poinsot motion), ``delta(0) = lambda(0) = pi/4`` (the angles of ``G`` from the orbit normal ``x3`` and
about it); gravity-gradient and drag torques (3), drag tensor ``I = diag(2.322, 1.31, 1.425)`` (case 1,
``chi < 0``). The averaged system (6)-(9) in the slow time ``tau = eps^2 t`` gives
``G, T, k2, delta, lambda``; the hodograph is the end of ``G = G n`` in the orbital axes ``Ox1x2x3``.

The figure: the hodograph in 3-D, with the orbit normal ``x3`` in grey and equal scales on the three axes. The
paper reads it as ``G``, decreasing, tending to a limiting position in the orbit plane; within the theory
(``eps`` small) ``delta`` stays at ``pi/4`` up to ``O(eps)`` oscillations and ``G`` spirals to the origin
along the cone ``delta = pi/4`` about ``x3`` (see the theory page and the ``eps`` dependence figure for where
the paper's picture comes from).

Choices the paper leaves open: ``eps``, the initial true anomaly and the end time. We draw the orbit-averaged
limit ``eps = 0`` (dashed) and ``eps = 0.005`` with the true anomaly kept (``nu0 = 0``), for
``tau in [0, 6]``; at ``eps = 0.005`` the run ends at ``tau = 4.77`` where the decaying rotation is no longer
fast (``event == 'slow_rotation'``).

Drawn by :func:`rigidbody.paperfigs.euler_poinsot.fig1_hodograph_case1`.
"""

import matplotlib.pyplot as plt

from rigidbody import euler_poinsot as ep
from rigidbody.paperfigs import euler_poinsot as figs

sols = figs.hodograph_data(1)  # {eps: averaged Solution} for eps = 0 and 0.005
body = ep.Body(A1=3.2, A2=2.6, A3=1.67)
print("chi (7) =", round(ep.chi(body, figs.CASES[1]), 4), " k2 equilibria (8):", ep.k2_equilibria(body, figs.CASES[1]))

fig = figs.fig1_hodograph_case1(sols)
plt.show()
