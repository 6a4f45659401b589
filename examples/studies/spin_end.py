"""
Where the spin ends
===================

The final regime of k^2 (the modulus of the Euler--Poinsot motion) under Rachinskaya's averaged equation
(8) over a plane of diagonal drag tensors (:func:`rigidbody.studies.spin_end`, one batch of averaged
evolutions). Only the decay rates a_i = I_ii / A_i enter (8), and only their ratios
r1 = a1/a2, r3 = a3/a2. From k2_0 = 0.5 (our choice), k^2 tends to 0 (blue), to an interior equilibrium
k*^2 (green) or to the separatrix k^2 = 1 (red). The lines: chi = -3 of (7) (k^2 = 0 changes stability),
r3 = r1 (the separatrix changes from repelling to attracting) and, between them for r1 < 1, the line where
k2_0 itself is an equilibrium (derived from (8)). The paper's drag cases 1 and 2 are marked. Cells next to
the chi = -3 line are decided slowly (the rate of (8) at k^2 = 0 vanishes there), so a finite run may call a
slow approach to 0 an interior equilibrium. The right panel shows the interior equilibrium reached.

The full grid (120 x 120 drag tensors, one batch) runs in a few seconds in this process
(:func:`rigidbody.studies.evaluate`; the base install suffices), fine enough that the boundaries between the
regimes are lines; ``SIZE = "quick"`` (13 x 13) is for a first look. Set ``SWEEP`` to sweep it with
:func:`rigidbody.sweep.sweep` (the ``sweep`` extra), e.g. on a Dask scheduler's address.

Computed above with :func:`rigidbody.studies.evaluate` (or :func:`rigidbody.sweep.sweep`); drawn by
:func:`rigidbody.paperfigs.studies.spin_end`.
"""

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import studies
from rigidbody.paperfigs import studies as figs
from rigidbody.sweep import sweep

SIZE = "full"  # or "quick"
SWEEP: dict = {}  # in this process; or e.g. {"executor": "tcp://scheduler:8786"} (rigidbody.sweep)

if __name__ == "__main__":  # a sweep's local worker processes are spawned and import this script
    grid = studies.GRIDS["spin_end"][SIZE]  # the values of each parameter of the study
    # in this process (the points integrated as batches), or swept on workers: the same numbers
    if SWEEP:
        ds = sweep(studies.spin_end, grid, **SWEEP)
    else:
        ds = studies.evaluate(studies.spin_end, grid)
    regime = studies.grid_values(ds, "regime", ("r1", "r3"))
    # the equilibria of (8) alone (root finding, about 5 ms a point) on every 6th row and column of the grid
    step = 6 if SIZE == "full" else 1
    r1s, r3s = studies.grid_values(ds, "r1")[::step], studies.grid_values(ds, "r3")[::step]
    predicted = np.array([[studies.spin_end_predicted(a, b, k2_0=figs.K2_0) for b in r3s] for a in r1s])
    agree = float(np.mean(predicted == regime[::step, ::step]))
    print(f"{regime.size} drag tensors; at {predicted.size} of them the integration ends where the equilibria "
          f"of (8) say for {agree:.0%}")
    for code, text in studies.REGIMES.items():
        print(f"  {text}: {int((regime == code).sum())}")
    fig = figs.spin_end(ds)
    plt.show()
