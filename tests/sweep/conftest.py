"""Shared fixtures of the sweep tests: the helper module and one real Dask cluster per session.

The helper functions live in ``sweep_testlib`` (importable here: the suite uses --import-mode=importlib).
They are registered with cloudpickle to travel by value, so worker processes need not import the test tree.
"""

import sys
from pathlib import Path

import pytest

_here = str(Path(__file__).resolve().parent)
if _here not in sys.path:
    sys.path.insert(0, _here)

import cloudpickle  # noqa: E402 - the sweep extra (installed by the test extra) brings it with dask
import sweep_testlib  # noqa: E402

cloudpickle.register_pickle_by_value(sweep_testlib)


@pytest.fixture(scope="session")
def cluster():
    """A real distributed.LocalCluster: two single-threaded worker processes on this machine (no mock).

    The dashboard gets a free port (":0"): with ``dashboard_address=None`` distributed still tries 8787 and
    warns (an error under our warning filter) when another cluster on the machine holds it. The scheduler
    runs a task whose worker died once more (``allowed-failures`` 1; Dask's default is 3): a point that kills
    every worker then costs four deaths and restarts, not eight."""
    import dask
    import distributed

    with dask.config.set({"distributed.scheduler.allowed-failures": 1}), distributed.LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0", host="127.0.0.1") as lc:
        yield lc


@pytest.fixture
def client(cluster):
    import distributed

    with distributed.Client(cluster, set_as_default=False) as c:
        yield c
