"""
A minor-axis spin decays through the separatrix into a major-axis spin
======================================================================

A rigid body conserves its angular momentum G and loses kinetic energy T to internal dissipation; a spin
about the axis of its *smallest* moment has the most energy for its G, so it decays, reaches the separatrix
``G^2 = 2 T A2`` and ends as a spin about the axis of its *largest* moment, the state of least energy. This
is the mechanism behind the flat spin of Explorer 1 (1958); Explorer itself had two equal transverse moments,
for which the separatrix degenerates (the example ``explorer1`` runs it with its own numbers). A triaxial
body shows the passage itself, with its capture into one of two senses of the final spin.

Here the body of Rachinskaya's example, ``A = (3.2, 2.6, 1.67)``, loses energy at constant ``|G|`` through
a torque written as a plain function, ``M = -kappa (omega - (omega.g) g / G^2)`` (perpendicular to G: it
removes the part of the angular velocity across G, as internal damping does on average; its effect on the
direction of G averages out). ``kappa = 3``, ``eps = 0.05``, start ``('min', +1)`` with ``k2 = 0.05``, no
gravity: our choices, for a figure whose fast motion is still visible. The full equations
(:func:`rigidbody.euler_poinsot.simulate`) against the averaged ones (:func:`rigidbody.euler_poinsot.averaged`),
both asked to go through the separatrix (``k2_max=None``), after which they continue about the major axis.
The torque is odd in omega, so both senses of the final spin are equally likely; which one the full run takes
depends on its fast phase at the crossing, and the averaged run is continued in the same one (``branch``).

Left: the energy relative to the separatrix, ``2 T A2 / G^2``; middle: the body components of G/G along the
minor (``g3``) and major (``g1``) axes, with the range the averaged motion sweeps; right: the path of G in the
body seen along the intermediate axis, the separatrix dashed. Drawn by
:func:`rigidbody.plotting.separatrix_passage`.
"""

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import euler_poinsot as ep
from rigidbody.plotting import separatrix_passage

body = ep.Body(A1=3.2, A2=2.6, A3=1.67)
KAPPA, EPS, TAU = 3.0, 0.05, (0.0, 4.0)


def dissipation(omega, C, nu):
    """Removes kinetic energy at constant |G|: minus kappa times the part of omega across G."""
    g = omega * body.A
    return -KAPPA * (omega - (omega * g).sum(-1, keepdims=True) * g / (g * g).sum(-1, keepdims=True))


start = dict(kind="min", k2_0=0.05, delta0=1.0, lam0=0.3, tau_span=TAU, k2_max=None)  # go through
full = ep.simulate(body, dissipation, EPS, tau_eval=np.linspace(*TAU, 4001), **start)
branch = (str(full.kind[-1]), int(full.sigma[-1]))  # the sense the full run ends in
avg = ep.averaged(body, dissipation, EPS, tau_eval=np.linspace(*TAU, 401), branch=branch, **start)

crossing = avg.crossings[0]
print(f"averaged: crosses the separatrix at tau = {crossing['tau']:.4f}, from {crossing['source']} to "
      f"{crossing['region']}; capture probabilities {crossing['probabilities']}")
print(f"full:     G^2 = 2 T A2 crossed at tau = {np.round(full.t_events['separatrix'], 4)}; ends as "
      f"{(str(full.kind[-1]), int(full.sigma[-1]))}")
print(f"T at the end: full {full.T[-1]:.5f}, averaged {avg.T[-1]:.5f}; pure major-axis spin G^2/(2 A1) = "
      f"{1 / (2 * body.A1):.5f}")

fig, axes = plt.subplots(1, 3, figsize=(13.0, 4.0), gridspec_kw={"width_ratios": [1.2, 1.2, 1.0]})
separatrix_passage(body, full, avg, axes=axes)
fig.suptitle("A minor-axis spin losing energy at constant G: through the separatrix into a major-axis spin")
fig.tight_layout()
plt.show()
