"""
Where averaging holds: the Euler--Poinsot module
================================================

The largest difference between Rachinskaya's averaged system (9) (true anomaly kept) and the full equations
(1), (3), (4) over tau in [0, 0.5], swept over (eps, k2_0) with :func:`rigidbody.sweep.sweep`
(:func:`rigidbody.studies.averaging_error_euler_poinsot`: the paper's body and drag case 1, G0 = 1,
delta0 = lam0 = pi/4, nu0 = 0, initial phase u0 = psi0 = 0 — our choices). The theory's order, eps^2, is
drawn beside the measured error; the right panel shows error / eps^2, which stays O(1) away from the
separatrix and grows towards it (the period grows like ln(1/(1 - k^2))).

The quick grid runs in seconds on local processes. For the full grid set ``SIZE = "full"`` and, to use a
Dask cluster, ``EXECUTOR`` to its scheduler address: that is the one line that changes. ``STORE`` keeps
finished chunks, so an interrupted run resumes where it stopped.

Drawn by :func:`rigidbody.paperfigs.studies.where_averaging_holds_euler_poinsot`.
"""

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import studies
from rigidbody.paperfigs import studies as figs

SIZE = "quick"  # or "full"
EXECUTOR = None  # local processes; "serial"; or a Dask scheduler address such as "tcp://scheduler:8786"
STORE = None  # e.g. "averaging_euler_poinsot.zarr" to keep finished chunks across runs

if __name__ == "__main__":  # the local worker processes are spawned and import this script
    ds = figs.study_data("averaging_euler_poinsot", SIZE, executor=EXECUTOR, store=STORE)
    print(f"{ds.status.size} points, {int((ds.status != 0).sum())} failed")
    print("fitted order of the error along eps, per k2_0:", np.round(studies.fitted_order(ds).values, 2))
    fig = figs.where_averaging_holds_euler_poinsot(ds)
    plt.show()
