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
    eq = ", ".join(f"{k:.4f} ({kind})" for k, kind in ep.k2_equilibria(body, I))
    print(f"{name}: chi (7) = {ep.chi(body, I):+.4f}; equilibria of k2 under (8): {eq}")
    sol = ep.averaged(body, I, eps=0.0, G0=1.0, k2_0=0.99, delta0=math.pi / 4, lam0=math.pi / 4,
                      tau_span=(0, 3), tau_eval=np.linspace(0, 3, 7))
    print("   tau     G        T        k2      delta    lambda")
    for row in zip(sol.tau, sol.G, sol.T, sol.k2, sol.delta, sol.lam):
        print("   {:3.1f}  {:.4f}  {:.5f}  {:.4f}  {:.4f}  {:+8.3f}".format(*row))

# the averaged system (9) with the true anomaly kept against the full, unaveraged equations (1), (3), (4)
# from k2 = 0.9, tau in [0, 0.5]: the difference shrinks like eps^2
I = cases["case 1"]
te = np.linspace(0, 0.5, 6)
print("\ncase 1 from k2 = 0.9, averaged against full over tau in [0, 0.5]:")
print("  eps   max |G_full - G_avg|   / eps^2   max |k2_full - k2_avg|   / eps^2")
for eps in (0.04, 0.02, 0.01):
    full = ep.simulate(body, I, eps, k2_0=0.9, tau_span=(0, 0.5), tau_eval=te)
    avg = ep.averaged(body, I, eps, k2_0=0.9, tau_span=(0, 0.5), tau_eval=te)
    dG, dk2 = np.abs(full.G - avg.G).max(), np.abs(full.k2 - avg.k2).max()
    print(f"{eps:5g}  {dG:20.2e}  {dG / eps**2:8.2f}  {dk2:22.2e}  {dk2 / eps**2:8.2f}")

# outside the theory: eps too large for the start near the separatrix
try:
    ep.averaged(body, I, eps=0.1)
except ValueError as exc:
    print("\neps = 0.1:", exc)
