"""
Where averaging holds: the Euler--Poinsot module
================================================

The largest difference between Rachinskaya's averaged system (9) (true anomaly kept) and the full equations
(1), (3), (4) over tau in [0, 0.5], over a grid of (eps, k2_0)
(:func:`rigidbody.studies.averaging_error_euler_poinsot`: the paper's body and drag case 1, G0 = 1,
delta0 = lam0 = pi/4, nu0 = 0, initial phase u0 = psi0 = 0 — our choices). The theory's order, eps^2, is
drawn beside the measured error; the right panel shows error / eps^2, which stays O(1) away from the
separatrix and grows towards it (the period grows like ln(1/(1 - k^2))).

The quick grid runs in seconds in this process (:func:`rigidbody.studies.evaluate`: the points of each eps
integrated as batches; the base install suffices). For the full grid set ``SIZE = "full"`` and ``SWEEP`` to
run it with :func:`rigidbody.sweep.sweep` (the ``sweep`` extra): on a Dask cluster with its scheduler
address, with a ``store`` that keeps finished chunks, so an interrupted run resumes where it stopped.

Computed above with :func:`rigidbody.studies.evaluate` (or :func:`rigidbody.sweep.sweep`); drawn by
:func:`rigidbody.paperfigs.studies.where_averaging_holds_euler_poinsot`.
"""

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import studies
from rigidbody.paperfigs import studies as figs
from rigidbody.sweep import sweep

SIZE = "quick"  # or "full"
# {}: in this process; or sweep it, e.g. {"executor": "tcp://scheduler:8786", "store": "averaging_euler_poinsot.zarr"}
SWEEP: dict = {}

if __name__ == "__main__":  # a sweep's local worker processes are spawned and import this script
    grid = studies.GRIDS["averaging_euler_poinsot"][SIZE]  # the values of each parameter of the study
    # in this process (the points integrated as batches), or swept on workers: the same numbers
    if SWEEP:
        ds = sweep(studies.averaging_error_euler_poinsot, grid, **SWEEP)
    else:
        ds = studies.evaluate(studies.averaging_error_euler_poinsot, grid)
    # the exponent p of error ~ eps^p at each distance from the separatrix (theory: 2)
    for k2_0, p in zip(studies.grid_values(ds, "k2_0"), np.asarray(studies.fitted_order(ds))):
        print(f"1 - k2_0 = {1 - k2_0:.3g}: p = {p:.2f}")
    failed = studies.grid_values(ds, "message")[studies.grid_values(ds, "status") != 0]
    print(f"{failed.size} point(s) failed:", *failed, sep="\n  ")
    fig = figs.where_averaging_holds_euler_poinsot(ds)
    plt.show()
