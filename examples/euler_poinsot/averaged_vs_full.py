"""
Rachinskaya's example: chi, the k2 attractor, and averaged against full motion
==============================================================================

Rachinskaya, section 3: ``A = (3.2, 2.6, 1.67)`` and the two drag tensors of the paper. Prints ``chi`` of (7)
(printed -4.477 and 3.853) and the equilibria of ``k2`` under (8) with their stability; the orbit-averaged
evolution (9) from ``G(0) = 1, k2(0) = 0.99, delta(0) = lambda(0) = pi/4`` at a few ``tau``; then the error of
the averaged system (true anomaly kept) against the full equations (1), (3), (4) from ``k2(0) = 0.9`` over
``tau in [0, 0.5]``: it falls like ``eps^2``. Finally ``eps = 0.1`` is refused: the rotation started next to
the separatrix is not fast at that ``eps``. Prints only.
"""

import math

import numpy as np

from rigidbody import euler_poinsot as ep

body = ep.Body(A1=3.2, A2=2.6, A3=1.67)
cases = {"case 1": np.diag([2.322, 1.31, 1.425]), "case 2": np.diag([0.919, 5.228, 1.666])}

for name, I in cases.items():
    print(f"{name}: chi = {ep.chi(body, I):+.4f}, k2 equilibria (value, stability): {ep.k2_equilibria(body, I)}")
    sol = ep.averaged(body, I, eps=0.0, G0=1.0, k2_0=0.99, delta0=math.pi / 4, lam0=math.pi / 4,
                      tau_span=(0, 3), tau_eval=np.linspace(0, 3, 4))
    for row in zip(sol.tau, sol.G, sol.T, sol.k2, sol.delta, sol.lam):
        print("   tau = {:.1f}  G = {:.4f}  T = {:.4f}  k2 = {:.4f}  delta = {:.4f}  lambda = {:+.3f}".format(*row))

# averaged (9) with the true anomaly kept vs the full, unaveraged equations: the error shrinks like eps^2
I = cases["case 1"]
te = np.linspace(0, 0.5, 6)
for eps in (0.04, 0.02, 0.01):
    full = ep.simulate(body, I, eps, k2_0=0.9, tau_span=(0, 0.5), tau_eval=te)
    avg = ep.averaged(body, I, eps, k2_0=0.9, tau_span=(0, 0.5), tau_eval=te)
    print(f"eps = {eps:<5g} max |G_full - G_avg| = {np.abs(full.G - avg.G).max():.2e}   "
          f"max |k2_full - k2_avg| = {np.abs(full.k2 - avg.k2).max():.2e}")

# outside the theory: eps too large for the start near the separatrix
try:
    ep.averaged(body, I, eps=0.1)
except ValueError as exc:
    print("eps = 0.1:", exc)
