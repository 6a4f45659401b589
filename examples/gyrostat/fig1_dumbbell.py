"""
The paper's figure: a spinning dumbbell whose orbit plane misses the centre
===========================================================================

Stepanov, *On stationary motions of a gyrostat satellite* (PMM 1968), section 5 and its one figure. In the
stationary motions (2.3) of a satellite in a central Newtonian field the centre of mass G moves on a circle
whose plane is displaced from the attracting centre O by ``R0 sin kappa0``: the y2 component of the gravity
forces, ``(3/2) mu R0^-4 (A2 - A3) sin 2 theta0``, is not zero when the satellite is tilted. The paper shows
it on a spinning dumbbell.

Our dumbbell (the paper draws it without numbers): two equal balls, total mass ``M = 1``, at ``arm = 0.3 R0``
from G on a light rod (``A1 = A2 = M arm^2``, ``A3 = 0.01 A1`` for the rod), its axis tilted by
``theta0 = pi/4`` from the radius vector (``mu = R0 = 1``). It is the symmetric gyrostat of section 3: the
stationary motion (3.2)-(3.3) and its stability, by the full second variation and by the paper's condition
(3.4). The figure is to scale: with a realistic ``l/R`` the displacement would be invisible (printed below).

Computed above with :func:`rigidbody.gyrostat.symmetric_stationary_motion` and
:func:`rigidbody.gyrostat.stability`; drawn by
:func:`rigidbody.paperfigs.gyrostat.fig1_dumbbell`.
"""

import math

import matplotlib.pyplot as plt

from rigidbody import gyrostat
from rigidbody.paperfigs import gyrostat as figs

# two equal balls (total mass M = 1) at arm = 0.3 R0 from G on a light rod; units mu = R0 = 1
arm = 0.3
sat = gyrostat.Satellite(M=1.0, A1=arm**2, A2=arm**2, A3=0.01 * arm**2)

# the stationary motion (3.2)-(3.3) with the axis tilted by theta0 = pi/4, and its stability
ms = gyrostat.symmetric_stationary_motion(sat, 1.0, math.pi / 4)
st = gyrostat.stability(sat, ms)
print(f"kappa0 = {math.degrees(ms.kappa0):.3f} deg, omega0 = {ms.omega0:.5f}, c = {ms.c:.5f}, k = {ms.k:.5f}")
print(f"displacement of the orbit plane R0 sin kappa0 = {ms.displacement:.4f} R0")
print(f"W_psipsi (3.4) = {st.W_psipsi:.3e}, degree = {st.degree}, verdict = {st.verdict}, "
      f"unconditionally stable: {st.unconditionally_stable}")

# the same for a real satellite (l = 1 m, R0 = 7000 km): the displacement is invisible
real = gyrostat.Satellite(M=1000.0, A1=1200.0, A2=1000.0, A3=800.0, mu=3.986e14)
m = gyrostat.stationary_motion(real, 7.0e6, math.pi / 4, k2=0.0)
print(f"a real satellite (l = {real.l:.2f} m, R0 = 7000 km): displaced by {m.displacement * 1e9:.1f} nm")

fig = figs.fig1_dumbbell(sat, ms)
plt.show()
