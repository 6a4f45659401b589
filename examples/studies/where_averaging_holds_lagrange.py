"""
Where averaging holds: the Lagrange top
=======================================

The largest difference between the first approximation (3.4) of Akulenko, Leshchenko and Chernousko (1979)
and the full equations (1.1) over tau in [0, 2], over a grid of (eps, theta0)
(:func:`rigidbody.studies.averaging_error_lagrange`: the paper's top and linear drag (3.1), the top spun
about its axis with r0 = sqrt(3) as in section 3 and tilted by theta0, the swept choice). The theory's
order, eps, is drawn beside the measured error; the right panel shows error / eps.

The quick grid runs in seconds in this process (:func:`rigidbody.studies.evaluate`: the points of each eps
integrated as batches; the base install suffices). For the full grid set ``SIZE = "full"`` and ``SWEEP`` to
run it with :func:`rigidbody.sweep.sweep` (the ``sweep`` extra): on a Dask cluster with its scheduler
address, with a ``store`` that keeps finished chunks, so an interrupted run resumes where it stopped.

Computed above with :func:`rigidbody.studies.evaluate` (or :func:`rigidbody.sweep.sweep`); drawn by
:func:`rigidbody.paperfigs.studies.where_averaging_holds_lagrange`.
"""

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import studies
from rigidbody.paperfigs import studies as figs
from rigidbody.sweep import sweep

SIZE = "quick"  # or "full"
# {}: in this process; or sweep it, e.g. {"executor": "tcp://scheduler:8786", "store": "averaging_lagrange.zarr"}
SWEEP: dict = {}

if __name__ == "__main__":  # a sweep's local worker processes are spawned and import this script
    grid = studies.GRIDS["averaging_lagrange"][SIZE]  # the values of each parameter of the study
    # in this process (the points integrated as batches), or swept on workers: the same numbers
    if SWEEP:
        ds = sweep(studies.averaging_error_lagrange, grid, **SWEEP)
    else:
        ds = studies.evaluate(studies.averaging_error_lagrange, grid)
    # error / eps at the smallest eps and the fitted exponent (theory: 1), per initial tilt
    eps, theta0 = studies.grid_values(ds, "eps"), studies.grid_values(ds, "theta0")
    scaled = studies.grid_values(ds, "error", ("theta0", "eps"))[:, np.argmin(eps)] / eps.min()
    print("theta0 (deg)  error/eps  p")
    for row in zip(np.degrees(theta0), scaled, np.asarray(studies.fitted_order(ds))):
        print("{:12.0f}  {:9.2e}  {:.2f}".format(*row))
    fig = figs.where_averaging_holds_lagrange(ds)
    plt.show()
