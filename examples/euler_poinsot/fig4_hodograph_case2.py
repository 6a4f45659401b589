"""
Fig. 4: the hodograph of the angular momentum, case 2
=====================================================

Rachinskaya, *Rapid rotation of a satellite in a resisting medium in a circular orbit*, figure 4.

The paper's setup (section 3): a body with ``A = (3.2, 2.6, 1.67)`` on a circular orbit, spinning fast
(``eps = omega0 / omega`` small), started with ``G(0) = 1``, ``k2(0) = 0.99`` (next to the separatrix of the
Euler-Poinsot motion), ``delta(0) = lambda(0) = pi/4`` (the angles of ``G`` from the orbit normal ``x3`` and
about it); gravity-gradient and drag torques (3), drag tensor ``I = diag(0.919, 5.228, 1.666)`` (case 2,
``chi > 0``). The averaged system (6)-(9) in the slow time ``tau = eps^2 t`` gives
``G, T, k2, delta, lambda``; the hodograph is the end of ``G = G n`` in the orbital axes ``Ox1x2x3``.

The figure: the hodograph in 3-D, with the orbit normal ``x3`` in grey and equal scales on the three axes. The
paper reads it as ``G``, decreasing, tending to a limiting position in the orbit plane; within the theory
(``eps`` small) ``delta`` stays at ``pi/4`` up to ``O(eps)`` oscillations and ``G`` spirals to the origin
along the cone ``delta = pi/4`` about ``x3`` (see the theory page and the ``eps`` dependence figure for where
the paper's picture comes from).

Choices the paper leaves open: ``eps``, the initial true anomaly and the end time. We draw the orbit-averaged
limit ``eps = 0`` (dashed) and ``eps = 0.005`` with the true anomaly kept (``nu0 = 0``), for
``tau in [0, 6]``.

Computed above with :func:`rigidbody.euler_poinsot.averaged`; drawn by
:func:`rigidbody.paperfigs.euler_poinsot.fig4_hodograph_case2`.
"""

import math

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import euler_poinsot as ep
from rigidbody.paperfigs import euler_poinsot as figs

# the paper's satellite (principal moments of inertia) and the drag tensor of case 2 (chi > 0)
body = ep.Body(A1=3.2, A2=2.6, A3=1.67)
I = np.diag([0.919, 5.228, 1.666])

# the averaged system (9) in the slow time tau = eps^2 t from the paper's initial state, for the
# orbit-averaged limit eps = 0 and for eps = 0.005 with the true anomaly kept (nu0 = 0)
tau = np.linspace(0.0, 6.0, 3001)
sols = {eps: ep.averaged(body, I, eps, G0=1.0, k2_0=0.99, delta0=math.pi / 4, lam0=math.pi / 4, nu0=0.0,
                         tau_span=(0.0, 6.0), tau_eval=tau)
        for eps in (0.0, 0.005)}

print(f"chi (7) = {ep.chi(body, I):.4f}; equilibria of k2 under (8): {ep.k2_equilibria(body, I)}")
print(f"eps = 0.005: ends at tau = {sols[0.005].tau[-1]:.3f} ({sols[0.005].event or 'end of the span'})")
# on the cone delta = pi/4 about the orbit normal |G| shrinks; with eps > 0 delta wiggles by O(eps)
print("  tau   G (eps = 0)  delta (eps = 0)   G (eps = 0.005)  delta (eps = 0.005)")
for j in range(0, tau.size, 500):
    cells = [f"{s.G[j]:11.4f}  {s.delta[j]:15.4f}" if j < s.tau.size else f"{'(ended)':>28}" for s in sols.values()]
    print(f"{tau[j]:5.1f}  " + "   ".join(cells))

fig = figs.fig4_hodograph_case2(sols)
plt.show()
