"""The paper's figure: a spinning dumbbell whose circular orbit plane misses the attracting centre.

A symmetric gyrostat (section 3, A1 = A2) made of two equal balls at arm a = 0.3 R0 on a light rod, its
axis tilted by theta0 = pi/4 from the radius vector.  Prints the stationary motion (3.2)-(3.3) and its
stability (full second variation and the paper's (3.4)); draws it to scale.  Writes gyrostat_dumbbell.png.
"""

import math

import matplotlib.pyplot as plt

from rigidbody import gyrostat
from rigidbody.plotting import gyrostat as pg

arm = 0.3
A1 = 1.0 * arm**2  # two balls of mass 1/2 at +-arm: A1 = A2 = M arm^2; the rod gives a small A3
sat = gyrostat.Satellite(M=1.0, A1=A1, A2=A1, A3=0.01 * A1)
ms = gyrostat.symmetric_stationary_motion(sat, R0=1.0, theta0=math.pi / 4)
st = gyrostat.stability(sat, ms)
print(f"kappa0 = {math.degrees(ms.kappa0):.3f} deg, omega0 = {ms.omega0:.5f}, c = {ms.c:.5f}, k = {ms.k:.5f}")
print(f"displacement of the orbit plane R0 sin kappa0 = {ms.displacement:.4f} R0")
print(f"W_psipsi (3.4) = {st.W_psipsi:.3e}, degree = {st.degree}, verdict = {st.verdict}, "
      f"unconditionally stable: {st.unconditionally_stable}")

fig, ax = plt.subplots(figsize=(8, 5))
pg.dumbbell_side_view(ms.R0, ms.kappa0, ms.theta0, arm, ax, elevation_deg=8.0)
fig.savefig("gyrostat_dumbbell.png", dpi=100, bbox_inches="tight")
