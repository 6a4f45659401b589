"""How far is the orbit plane displaced?  kappa0(theta0) for several l/R (Stepanov 1968, (2.4)).

The paper: kappa0 is of order l^2/R^2 and largest at theta0 = pi/4.  Prints the peak position and height
for each l/R (the peak tends to pi/4 like (l/R)^2), the displacement for a real satellite, and plots
kappa0 / (l/R)^2 (the curves collapse).  Writes gyrostat_kappa0.png.
"""

import math

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import gyrostat

theta0 = np.linspace(-1.5, 1.5, 3001)
fig, ax = plt.subplots(figsize=(6, 4))
for lR in (0.05, 0.1, 0.2, 0.3):
    s = lR**2 * 3 / 3.0
    sat = gyrostat.Satellite(M=1.0, A1=1.2 * s, A2=1.0 * s, A3=0.8 * s)
    kappa0 = gyrostat.stability_map(sat, 1.0, theta0, k2=0.0).kappa0  # kappa0 does not depend on k2
    i = int(np.argmax(kappa0))
    print(f"l/R = {lR:4}: max kappa0 = {math.degrees(kappa0[i]):.4f} deg at theta0 = {theta0[i]:.4f} "
          f"(pi/4 = {math.pi / 4:.4f})")
    ax.plot(theta0, kappa0 / lR**2, label=f"l/R = {lR}")

si = gyrostat.Satellite(M=1000.0, A1=1200.0, A2=1000.0, A3=800.0, mu=3.986e14)
m = gyrostat.stationary_motion(si, 7.0e6, math.pi / 4, k2=0.0)
print(f"real satellite (l = {si.l:.2f} m, R0 = 7000 km): kappa0 = {m.kappa0:.3e} rad, "
      f"orbit plane displaced by {m.displacement * 1e9:.1f} nm")

ax.axvline(math.pi / 4, color="0.5", ls=":")
ax.set_xlabel("θ0 (rad)")
ax.set_ylabel("κ0 / (l/R)²")
ax.legend()
fig.tight_layout()
fig.savefig("gyrostat_kappa0.png", dpi=100)
