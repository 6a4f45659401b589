r"""Parameter studies at scale: a function over a grid, on local processes or a Dask cluster.

:func:`sweep` evaluates ``func(**point)`` over the outer product of a grid and returns an
``xarray.Dataset`` (one dimension per grid name, one variable per output, a ``status`` and ``message``
per point). The same call runs in-process (``executor='serial'``), on local worker processes (the
default: no server to start) or on a Dask cluster (a ``distributed.Client`` or a scheduler address);
with ``store=PATH`` the points are written to a Zarr store as their chunks complete and an interrupted
sweep resumes where it stopped, computing only the points not finished.

:func:`batched`
    marks a function that takes a whole chunk (1-D arrays) per call.
:func:`load`
    the Dataset of a store as it stands (while a sweep writes it, or after an interruption).
:func:`gyrostat_stability`
    a batched wrapper of :func:`rigidbody.gyrostat.stability_map`.
:func:`euler_poinsot_averaged`, :func:`lagrange_averaged`
    batched wrappers of the averaged evolutions (:func:`rigidbody.euler_poinsot.averaged`,
    :func:`rigidbody.lagrange.averaged`): a chunk of points is one batch integration.

Needs the optional dependencies: ``pip install "rigidbody[sweep]"`` (xarray, zarr, dask[distributed],
tqdm). ``import rigidbody`` does not import any of them. See :doc:`/sweeps`.
"""

from ._api import load, sweep
from ._results import NOT_COMPUTED, OK, RAISED
from ._run import batched
from ._wrappers import RUN_FAILED, euler_poinsot_averaged, gyrostat_stability, lagrange_averaged

__all__ = ["NOT_COMPUTED", "OK", "RAISED", "RUN_FAILED", "batched", "euler_poinsot_averaged", "gyrostat_stability",
           "lagrange_averaged", "load", "sweep"]
