"""
Write your own torque: spin-up thrusters against the drag
=========================================================

A torque is any callable ``torque(omega, C, nu) -> M``: the body components of the angular velocity
``omega`` (shape ``(..., 3)``), the direction cosines ``C`` from the body to the orbital axes and the true
anomaly ``nu``; it returns the body components of the torque, shape ``(..., 3)`` (see the theory page, "Any
torque"). :func:`rigidbody.euler_poinsot.averaged` averages it over the Euler--Poinsot motion (its engine
where no closed form is known) and :func:`rigidbody.euler_poinsot.simulate` integrates it in the full
equations; it adds to the catalogue's torques with ``+``.

Here the torque models a pair of tangential thrusters (or a motor working against a momentum wheel) that
push with a constant torque ``M0 = 0.3`` about the body axis of the largest moment ``A1``: the spin-up of a
spin-stabilised satellite. Its average does not vanish: it pushes ``G`` along itself at the rate
``dG/dtau = a1 w1 M0 / G`` (``w1`` the mean of ``omega1`` over the Euler--Poinsot motion), so the run with it
differs visibly from the run without it. The satellite and the drag are those of Rachinskaya's case 2
(``A = (3.2, 2.6, 1.67)``, ``I = diag(0.919, 5.228, 1.666)``, ``chi > 0``), with the gravity gradient; without
the thrusters the drag brakes the rotation, ``G -> 0``; with them the rotation settles about the axis of the
largest moment (``k2 -> 0``, ``omega1 = G / A1``) where the thrust balances the drag ``-I11 omega1``:
``G -> A1 M0 / I11``. Choices: ``M0 = 0.3``, ``G0 = 1``, ``k2_0 = 0.9``, ``delta0 = lambda0 = pi/4``, ``nu0 = 0``,
``tau`` in ``[0, 15]`` for the orbit-averaged runs (``eps = 0``) and ``[0, 0.5]`` for the check against the full
equations at ``eps = 0.02`` and ``0.01``.

The averaging engine reproduces the catalogue's closed form for a constant torque
(:class:`rigidbody.euler_poinsot.ConstantTorque`), and the full equations reproduce the averaged run to
``O(eps^2)``: printed below.
"""

import math

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import euler_poinsot as ep

body = ep.Body(A1=3.2, A2=2.6, A3=1.67)
I = np.diag([0.919, 5.228, 1.666])  # Rachinskaya's drag tensor, case 2
paper = ep.LinearDrag(I) + ep.GravityGradient(body)  # the paper's torques (the same as passing I itself)
M0 = 0.3


def thrusters(omega, C, nu):
    """A constant torque M0 about the body axis z1 of the largest moment, whatever the attitude and orbit."""
    return np.zeros(np.shape(omega)) + np.array([M0, 0.0, 0.0])  # the shape of omega: (..., 3)


# 1. the averaged rates at one slow state: the engine (no closed form given) against the closed form
state = dict(G=1.0, k2=0.9, delta=0.7, lam=0.2, nu=None)  # nu=None: averaged over the orbit too
engine = ep.average_torque(body, thrusters, **state)
closed = ep.averaged_rates(body, ep.ConstantTorque([M0, 0.0, 0.0]), **state)
print("rate     engine (the function)   closed form (ConstantTorque)")
for key in ("dG", "dT", "dk2"):
    print(f"{key:5}  {engine.rates[key]:+22.15f}  {closed[key]:+22.15f}")

# 2. the orbit-averaged evolution (eps = 0) without and with the thrusters
start = dict(G0=1.0, k2_0=0.9, delta0=math.pi / 4, lam0=math.pi / 4, nu0=0.0)
tau = np.linspace(0.0, 15.0, 751)
without = ep.averaged(body, paper, 0.0, tau_span=(0.0, 15.0), tau_eval=tau, **start)
with_thrust = ep.averaged(body, paper + thrusters, 0.0, tau_span=(0.0, 15.0), tau_eval=tau, **start)
G_star = body.A1 * M0 / I[0, 0]  # thrust M0 = drag I11 omega1 with omega1 = G / A1
print(f"\nG -> A1 M0 / I11 = {G_star:.4f} predicted with the thrusters")
print("  tau   G without   G with  k2 without    k2 with")
for j in range(0, tau.size, 125):
    row = (without.G[j], with_thrust.G[j], without.k2[j], with_thrust.k2[j])
    print(f"{tau[j]:5.1f}  " + "  ".join(f"{x:9.4f}" for x in row))

# 3. the full equations with the same function: the averaged run is right to O(eps^2)
print("\n  eps    max |G_full - G_avg|   / eps^2   (tau in [0, 0.5], with the thrusters)")
te = np.linspace(0.0, 0.5, 11)
for eps in (0.02, 0.01):
    full = ep.simulate(body, paper + thrusters, eps, tau_span=(0.0, 0.5), tau_eval=te, **start)
    avg = ep.averaged(body, paper + thrusters, eps, tau_span=(0.0, 0.5), tau_eval=te, **start)
    err = np.abs(full.G - avg.G).max()
    print(f"{eps:5g}  {err:20.2e}  {err / eps**2:8.2f}")

fig, axes = plt.subplots(1, 3, figsize=(13.0, 3.8))
for sol, color, label in ((without, "k", "paper's drag and gravity gradient"),
                          (with_thrust, "tab:red", f"... + thrusters, M0 = {M0} about z1")):
    for ax, name in zip(axes, ("G", "T", "k2")):
        ax.plot(sol.tau, getattr(sol, name), color=color, label=label)
axes[0].axhline(G_star, color="tab:red", ls=":", lw=1.0, label="A1 M0 / I11 (thrust = drag)")
for ax, ylabel in zip(axes, ("$G$", "$T$", "$k^2$")):
    ax.set_xlabel(r"$\tau$")
    ax.set_ylabel(ylabel)
    ax.grid(alpha=0.3)
axes[0].legend(fontsize=8)
fig.suptitle("A torque written as a function: spin-up thrusters against the drag (orbit-averaged, eps = 0)")
fig.tight_layout()
plt.show()
