"""
Fig. 6: the view along the spiral axis, case 2
==============================================

Rachinskaya, *Rapid rotation of a satellite in a resisting medium in a circular orbit*, figure 6.

The paper's setup (section 3): a body with ``A = (3.2, 2.6, 1.67)`` on a circular orbit, spinning fast
(``eps = omega0 / omega`` small), started with ``G(0) = 1``, ``k2(0) = 0.99`` (next to the separatrix of the
Euler-Poinsot motion), ``delta(0) = lambda(0) = pi/4`` (the angles of ``G`` from the orbit normal ``x3`` and
about it); gravity-gradient and drag torques (3), drag tensor ``I = diag(0.919, 5.228, 1.666)`` (case 2,
``chi > 0``). The averaged system (6)-(9) in the slow time ``tau = eps^2 t`` gives
``G, T, k2, delta, lambda``; the hodograph is the end of ``G = G n`` in the orbital axes ``Ox1x2x3``.

The figure: "the hodograph along the spiral axis", read both ways. Left: looking down the axis (the projection
on the plane normal to it), inner turns enlarged. Right: the spiral laid along its axis, distance from the
axis against the height along it, where a spiral on a cone about a straight axis is a straight line through
the origin. The axis is that of the cone fitted to the ``eps = 0.005`` run
(:func:`rigidbody.plotting.spiral_axis`); within the theory it is ``x3`` to ``O(eps)`` and does not bend (the
paper reports a bent axis, see the ``eps`` dependence figure).

Choices the paper leaves open: ``eps``, the initial true anomaly and the end time. We draw the orbit-averaged
limit ``eps = 0`` (dashed) and ``eps = 0.005`` with the true anomaly kept (``nu0 = 0``), for
``tau in [0, 6]``.

Computed above with :func:`rigidbody.euler_poinsot.averaged`; drawn by
:func:`rigidbody.paperfigs.euler_poinsot.fig6_spiral_axis_case2` (the axis by
:func:`rigidbody.plotting.spiral_axis`).
"""

import math

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import euler_poinsot as ep
from rigidbody import plotting
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

# the axis of the cone fitted to the eps = 0.005 run (within the theory: x3, up to O(eps))
axis = plotting.spiral_axis(sols[0.005])
print("spiral axis:", np.round(axis, 5), f" {np.degrees(np.arccos(axis[2])):.3f} deg from x3")

fig = figs.fig6_spiral_axis_case2(sols)
plt.show()
