"""
Any torque: a viscous cavity, a magnet and the gravity gradient
===============================================================

Rachinskaya's satellite (``A = (3.2, 2.6, 1.67)``) without the paper's drag: a cavity filled with a highly
viscous fluid dissipates energy at constant ``G`` (``ViscousCavity``), a permanent magnet along the axis of
the largest moment sits in a field along the orbit normal (``MagneticDipole``; the field of an aligned
dipole on an equatorial circular orbit), and the gravity gradient acts as in the paper. A plain function
adds a body-fixed torque along the same axis that acts only in sunlight (``|nu - pi| > 0.6``), a torque
with jumps and without a closed form: the averaging engine handles it.

The averaged evolution (closed forms where the catalogue has them, the engine for the rest) is drawn with
the full equations at ``eps = 0.04`` and ``0.02`` (their difference shrinks like ``eps^2``), and the
orbit-averaged limit ``eps = 0`` (black), where the engine also averages over the orbit: there the jump of
the sunlit torque makes its quadrature converge only to first order in the orbit nodes, which the run
reports (``quad_error``); with ``eps > 0`` the true anomaly is held in the average and the jump is one in
time, stepped over by the integrator. Choices: start ``k2 = 0.9`` (rotation about the axis of the largest
moment), ``delta = lambda = pi/4``, ``nu0 = 0``, ``tau`` in ``[0, 0.5]``. The cavity drives ``k2`` to 0 (the
major-axis rule), the magnet and the gravity gradient turn ``G`` about the orbit normal, the sunlit torque
spins the body up in steps. See ``docs/euler_poinsot.md``, "Any torque".
"""

import math

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import euler_poinsot as ep
from rigidbody.plotting import slow_variables

body = ep.Body(3.2, 2.6, 1.67)


def sunlit_push(omega, C, nu):
    """0.3 along the body axis z1 while the satellite is in sunlight (|nu - pi| > 0.6), 0 in the shadow."""
    lit = np.abs(np.mod(nu, 2 * np.pi) - np.pi) > 0.6
    return np.zeros(np.shape(omega)) + np.asarray(lit, dtype=float)[..., None] * [0.3, 0.0, 0.0]


torque = (ep.ViscousCavity(body, [10.0, 17.5, 7.5]) + ep.MagneticDipole([0.3, 0.0, 0.0], [0.0, 0.0, -1.0])
          + ep.GravityGradient(body) + sunlit_push)
start = dict(G0=1.0, k2_0=0.9, delta0=math.pi / 4, lam0=math.pi / 4, nu0=0.0, tau_span=(0.0, 0.5))
tau = np.linspace(0.0, 0.5, 201)

limit = ep.averaged(body, torque, 0.0, tau_eval=tau, quad_tol=1e-3, **start)
print(f"eps = 0 (orbit-averaged): {limit.message}")
print(f"   quadrature error of the engine along the run {limit.quad_error:.1e} (relative; the sunlit torque jumps)")
axes = slow_variables(limit, color="k", lw=1.0, label="averaged, eps = 0")
for eps, color in ((0.04, "tab:blue"), (0.02, "tab:orange")):
    avg = ep.averaged(body, torque, eps, tau_eval=tau, quad_tol=1e-6, **start)
    full = ep.simulate(body, torque, eps, tau_eval=tau, **start)
    err = max(np.abs(full.G - avg.G).max(), np.abs(full.k2 - avg.k2).max(),
              np.linalg.norm(full.n - avg.n, axis=0).max())
    print(f"eps = {eps}: {avg.message}")
    print(f"   quadrature error {avg.quad_error:.1e}; largest averaged-vs-full difference of G, k2, n "
          f"{err:.2e} = {err / eps**2:.1f} eps^2")
    big = [r for r in avg.resonances if r["jump"] > 1e-6]
    print(f"   resonance crossings with a predicted jump > 1e-6: {[(round(r['tau'], 3), r['rho']) for r in big]}")
    axes = slow_variables(full, axes=axes, color=color, lw=0.6, alpha=0.6, label=f"full, eps = {eps}")
    slow_variables(avg, axes=axes, color=color, ls="--", lw=1.5, label=f"averaged, eps = {eps}")

axes[0].set_title("viscous cavity + magnet + gravity gradient + sunlit push")
plt.tight_layout()
plt.show()
