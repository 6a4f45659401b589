"""Stability maps of a gyrostat satellite's stationary motions (Stepanov 1968, (2.3)-(2.5)).

For each ordering of the principal moments (proportional to 1.2, 1.0, 0.8) and l/R = 0.1, 0.2: verdicts in
the plane (theta0, k2 / (omega0 Abar)) with the exact boundaries s2 = 0, s3 = 0, s1 = 0 (black) and the
restricted-problem ones (blue, dashed) overlaid.  Writes gyrostat_maps_lR*.png in the current directory.
"""

import itertools

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import gyrostat
from rigidbody.plotting import gyrostat as pg

theta0 = np.linspace(-1.5, 1.5, 301)
u = np.linspace(-4.0, 4.0, 301)  # k2 / (omega0 Abar)

for lR in (0.1, 0.2):
    fig, axes = plt.subplots(2, 3, figsize=(13, 8), sharex=True, sharey=True)
    for ax, r in zip(axes.ravel(), sorted(set(itertools.permutations((1.2, 1.0, 0.8))), reverse=True)):
        s = lR**2 * 3 / sum(r)  # nondimensional: M = mu = R0 = 1, sqrt(Abar / M) = l/R
        sat = gyrostat.Satellite(M=1.0, A1=r[0] * s, A2=r[1] * s, A3=r[2] * s)
        _, mp, _ = pg.normalized_map_plot(sat, 1.0, theta0, u, ax, legend=(ax is axes[0, 0]))
        ax.set_title(f"A1:A2:A3 = {r[0]}:{r[1]}:{r[2]}")
        frac = {v: float(np.mean(mp.verdict == v)) for v in ("stable", "unstable", "undecided")}
        print(f"l/R = {lR}, A = {r}: " + ", ".join(f"{k} {v:.1%}" for k, v in frac.items()))
    for ax in axes.ravel():
        ax.label_outer()
    fig.tight_layout()
    fig.savefig(f"gyrostat_maps_lR{lR:g}.png", dpi=100)
    plt.close(fig)
