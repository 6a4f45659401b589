"""
Fig. 1: the ball-and-rod structure
==================================

Krivtsov, *Description of the motion of an axisymmetric rigid body in a linearly viscous medium by
quasi-coordinates* (PMM 2000), section 2 and figure 1: a rigid structure of ``N`` equal balls on a circle of
radius ``a`` about the centre C of a rod AB, in the plane normal to it, and two more balls at A and B. If
each ball feels the drag ``f = -beta v`` (thin rods feel none), the total torque (2.1) about C is exactly the
paper's linearly viscous torque (1.1), ``M = -B omega``, with the transversely isotropic tensor
``B12 = beta (N a^2 / 2 + 2 b^2)``, ``B3 = beta N a^2`` (2.2); the inertia tensor (1.2) is transversely
isotropic too.

Choices (the paper draws the structure without numbers): ``N = 4``, ``a = 1``, half-length ``b = 1.5``, balls of
mass 1 and radius 0.3 (their own inertia included), ``beta = 0.1``. The title gives the resulting
``theta12, theta3, B12, B3`` and the regime of the axis: it contracts to a point when
``B12 / theta12 > B3 / theta3``.

Computed above with :func:`rigidbody.viscous.ball_and_rod`; drawn by
:func:`rigidbody.paperfigs.viscous.fig1_ball_and_rod`.
"""

import matplotlib.pyplot as plt

from rigidbody import viscous as vs
from rigidbody.paperfigs import viscous as figs

# N balls on a circle of radius a, two on the rod at +-b; each ball of mass 1, radius 0.3, drag -beta v
structure = dict(N=4, a=1.0, b=1.5, beta=0.1, mass=1.0, ball_radius=0.3)
body, medium = vs.ball_and_rod(**structure)  # the inertia (1.2) and drag (2.2) tensors
print(f"theta12 = {body.theta12:.4f}, theta3 = {body.theta3:.4f}, B12 = {medium.B12:.4f}, B3 = {medium.B3:.4f}")
rate12, rate3 = vs.decay_rates(body, medium)
print(f"decay rates B12/theta12 = {rate12:.4f}, B3/theta3 = {rate3:.4f} -> {vs.regime(body, medium)} spiral")

fig = figs.fig1_ball_and_rod(**structure)
plt.show()
