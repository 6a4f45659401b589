"""
Where averaging holds
=====================

The largest difference between the averaged and the full evolution of the slow variables, swept over the
small parameter and the initial state with :func:`rigidbody.sweep.sweep`:

* Euler--Poinsot module (Rachinskaya): the averaged system (9) with the true anomaly kept against the full
  equations over tau in [0, 0.5], over (eps, k2_0); the theory's order is eps^2;
* Lagrange top (Akulenko, Leshchenko, Chernousko 1979): the first approximation (3.4) against the full
  equations (1.1) over tau in [0, 2], over (eps, theta0); the theory's order is eps.

The quick grids run in seconds on local processes. For the full grids (440 and 585 full simulations,
the smallest eps costing seconds each) set ``SIZE = "full"`` and, to use a Dask cluster, ``EXECUTOR`` to its
scheduler address: that is the one line that changes. ``STORE`` keeps finished chunks, so an interrupted
run resumes where it stopped. Writes study_averaging.png in the current directory.
"""

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import studies
from rigidbody.plotting import studies as sp
from rigidbody.sweep import sweep

SIZE = "quick"  # or "full"
EXECUTOR = None  # local processes; "serial"; or a Dask scheduler address such as "tcp://scheduler:8786"
STORE = None  # e.g. "averaging_{name}.zarr" to keep finished chunks across runs

if __name__ == "__main__":  # the local worker processes are spawned and import this script
    cases = (
        ("averaging_euler_poinsot", studies.averaging_error_euler_poinsot, 2.0),
        ("averaging_lagrange", studies.averaging_error_lagrange, 1.0),
    )
    fig, axes = plt.subplots(2, 2, figsize=(12, 9))
    for row, (name, func, order) in zip(axes, cases):
        store = STORE.format(name=name) if STORE else None
        ds = sweep(func, studies.GRIDS[name][SIZE], executor=EXECUTOR, store=store)
        failed = ds.message.values[ds.status.values != 0]
        print(f"{name}: {int(ds.status.size)} points, {failed.size} failed", *set(failed), sep="\n  ")
        print("  fitted order of the error along eps:", np.round(studies.fitted_order(ds).values, 2))
        if name == "averaging_euler_poinsot":  # the distance to the separatrix on a log axis
            ds = ds.assign_coords(k2_0=1.0 - ds.k2_0).rename(k2_0="one_minus_k2_0")
            label, ylog = "1 - k2_0", True
        else:
            ds = ds.assign_coords(theta0=np.degrees(ds.theta0)).rename(theta0="theta0_deg")
            label, ylog = "theta0 (deg)", False
        sp.averaging_error_plot(ds, order, ax=row[0], label=label)
        sp.scaled_error_map(ds, order, ax=row[1], ylog=ylog)
        row[0].set_title(name.replace("_", " "))
    fig.tight_layout()
    fig.savefig("study_averaging.png", dpi=100)
