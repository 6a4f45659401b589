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

Computed above with :func:`rigidbody.euler_poinsot.averaged`; drawn by
:func:`rigidbody.paperfigs.euler_poinsot.slow_variables_case1`.
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

print("  eps    tau_end     G        T        k2      delta   end")
for eps, sol in sols.items():
    print(f"{eps:5g}  {sol.tau[-1]:8.3f}  {sol.G[-1]:.4f}  {sol.T[-1]:.5f}  {sol.k2[-1]:.4f}  {sol.delta[-1]:.4f}   "
          f"{sol.event or 'end of the span'}")
print("stable equilibria of k2 under (8):", [k for k, kind in ep.k2_equilibria(body, I) if kind == "stable"])

fig = figs.slow_variables_case1(sols)
plt.show()
