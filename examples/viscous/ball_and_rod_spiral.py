"""
Where does the symmetry axis go? The ball-and-rod structure in a viscous medium
===============================================================================

Krivtsov (PMM 2000): the structure of figure 1 (``N = 4`` balls of mass 1 and radius 0.3 on a circle of
radius ``a = 1``, rod half-length ``b = 1.5``, ``beta = 0.1``; our choices), spun with ``Omega0 = 8`` about its
axis ``n0 = e_z`` and tipped with ``dn/dt = (0.5, 0, 0)``. Prints its regime, the closed-form limits (5.1)
(length of the spiral, total turning, turns of the body about its axis), one turn with the solid-angle
theorem, and the agreement of the path reconstructed from ``v(t), k(t)`` with the full simulation; the
simulation result draws its standard figure, the axis path on the sphere (``sim.plot()``).
"""

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import viscous as vs

body, medium = vs.ball_and_rod(N=4, a=1.0, b=1.5, beta=0.1, mass=1.0, ball_radius=0.3)
print(body, medium, vs.regime(body, medium))

n0 = np.array([0.0, 0.0, 1.0])
ndot0 = np.array([0.5, 0.0, 0.0])   # initial velocity of the axis tip (perpendicular to n0)
Omega0 = 8.0                          # initial spin about the axis
v0 = np.linalg.norm(ndot0)

s_inf, xi_inf, zeta_inf = vs.limits(body, medium, Omega0, v0)
print(f"spiral length s_inf = {s_inf:.4f}, total turning xi_inf = {xi_inf:.4f} rad, "
      f"body turns about n: zeta_inf/2pi = {zeta_inf / (2 * np.pi):.3f}")

tr = vs.turn(body, medium, n0, ndot0, Omega0, t1=0.0)
print(f"first turn: t in [0, {tr.t2:.4f}], chi = {tr.chi:.6f} (cap approximation {tr.chi_approx:.6f}), "
      f"axial turn dphi = chi + dzeta = {tr.dphi:.6f}")

t = np.linspace(0.0, 80.0, 3000)
n = vs.axis_path(body, medium, n0, ndot0, Omega0, t)   # from v(t), k(t) alone
sim = vs.simulate(body, medium, n0, ndot0, Omega0, (0.0, 80.0), t_eval=t)
print("max |n_path - n_sim| =", np.max(np.linalg.norm(n - sim.n, axis=0)))

ax = sim.plot()
ax.set_title(f"{vs.regime(body, medium)} spiral of the ball-and-rod structure")
plt.show()
