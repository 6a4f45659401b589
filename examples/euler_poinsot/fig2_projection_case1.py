"""
Fig. 2: projection on the orbit plane, case 1
=============================================

Rachinskaya, *Rapid rotation of a satellite in a resisting medium in a circular orbit*, figure 2.

The paper's setup (section 3): a body with ``A = (3.2, 2.6, 1.67)`` on a circular orbit, spinning fast
(``eps = omega0 / omega`` small), started with ``G(0) = 1``, ``k2(0) = 0.99`` (next to the separatrix of the
Euler-Poinsot motion), ``delta(0) = lambda(0) = pi/4`` (the angles of ``G`` from the orbit normal ``x3`` and
about it); gravity-gradient and drag torques (3), drag tensor ``I = diag(2.322, 1.31, 1.425)`` (case 1,
``chi < 0``). The averaged system (6)-(9) in the slow time ``tau = eps^2 t`` gives
``G, T, k2, delta, lambda``; the hodograph is the end of ``G = G n`` in the orbital axes ``Ox1x2x3``.

The figure: the hodograph projected on the orbit plane ``Ox1x2``; the paper draws it "at a larger scale", here
the right panel: the square drawn on the left, enlarged, holding the turns after the first one. The
``eps = 0.005`` run wiggles about the orbit-averaged one with the orbital period.

Choices the paper leaves open: ``eps``, the initial true anomaly and the end time. We draw the orbit-averaged
limit ``eps = 0`` (dashed) and ``eps = 0.005`` with the true anomaly kept (``nu0 = 0``), for
``tau in [0, 6]``; at ``eps = 0.005`` the run ends at ``tau = 4.77`` where the decaying rotation is no longer
fast (``event == 'slow_rotation'``).

Computed above with :func:`rigidbody.euler_poinsot.averaged`; drawn by
:func:`rigidbody.paperfigs.euler_poinsot.fig2_projection_case1`.
"""

import math

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import euler_poinsot as ep
from rigidbody.paperfigs import euler_poinsot as figs

# the paper's satellite (principal moments of inertia) and the drag tensor of case 1 (chi < 0)
body = ep.Body(A1=3.2, A2=2.6, A3=1.67)
I = np.diag([2.322, 1.31, 1.425])

# the averaged system (9) in the slow time tau = eps^2 t from the paper's initial state, for the
# orbit-averaged limit eps = 0 and for eps = 0.005 with the true anomaly kept (nu0 = 0)
tau = np.linspace(0.0, 6.0, 3001)
sols = {eps: ep.averaged(body, I, eps, G0=1.0, k2_0=0.99, delta0=math.pi / 4, lam0=math.pi / 4, nu0=0.0,
                         tau_span=(0.0, 6.0), tau_eval=tau)
        for eps in (0.0, 0.005)}

# the spiral in the orbit plane: turns of lambda and the shrinking |G|
print("  eps    tau_end   turns of lambda   G from 1 to   end")
for eps, sol in sols.items():
    turns = (sol.lam[0] - sol.lam[-1]) / (2 * np.pi)
    print(f"{eps:5g}  {sol.tau[-1]:8.3f}  {turns:16.2f}  {sol.G[-1]:12.4f}   {sol.event or 'end of the span'}")

fig = figs.fig2_projection_case1(sols)
plt.show()
