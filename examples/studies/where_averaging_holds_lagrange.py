"""
Where averaging holds: the Lagrange top
=======================================

The largest difference between the first approximation (3.4) of Akulenko, Leshchenko and Chernousko (1979)
and the full equations (1.1) over tau in [0, 2], swept over (eps, theta0) with :func:`rigidbody.sweep.sweep`
(:func:`rigidbody.studies.averaging_error_lagrange`: the paper's top and linear drag (3.1), the top spun
about its axis with r0 = sqrt(3) as in section 3 and tilted by theta0, the swept choice). The theory's
order, eps, is drawn beside the measured error; the right panel shows error / eps.

The quick grid runs in seconds on local processes. For the full grid set ``SIZE = "full"`` and, to use a
Dask cluster, ``EXECUTOR`` to its scheduler address: that is the one line that changes. ``STORE`` keeps
finished chunks, so an interrupted run resumes where it stopped.

Drawn by :func:`rigidbody.paperfigs.studies.where_averaging_holds_lagrange`.
"""

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import studies
from rigidbody.paperfigs import studies as figs

SIZE = "quick"  # or "full"
EXECUTOR = None  # local processes; "serial"; or a Dask scheduler address such as "tcp://scheduler:8786"
STORE = None  # e.g. "averaging_lagrange.zarr" to keep finished chunks across runs

if __name__ == "__main__":  # the local worker processes are spawned and import this script
    ds = figs.study_data("averaging_lagrange", SIZE, executor=EXECUTOR, store=STORE)
    print(f"{ds.status.size} points, {int((ds.status != 0).sum())} failed")
    print("fitted order of the error along eps, per theta0:", np.round(studies.fitted_order(ds).values, 2))
    fig = figs.where_averaging_holds_lagrange(ds)
    plt.show()
