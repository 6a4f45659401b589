"""rigidbody.sweep on a real Dask cluster (distributed.LocalCluster, two worker processes; no mock)."""

from __future__ import annotations

import signal
from functools import partial

import sweep_testlib as lib
import xarray as xr
from sweep_checks import GRID, quiet, reference, resume, run_python, same_results, wait_for_calls

from rigidbody.sweep import sweep


def test_client_and_scheduler_address_give_the_serial_and_processes_dataset(client, cluster):
    ref = sweep(lib.poly, GRID, executor="serial", progress=False, chunk_size=4)
    on_client = sweep(lib.poly, GRID, executor=client, progress=False, chunk_size=4)
    on_address = sweep(lib.poly, GRID, executor=cluster.scheduler_address, progress=False, chunk_size=4)
    on_processes = sweep(lib.poly, GRID, progress=False, chunk_size=4, max_workers=2)
    for ds in (on_client, on_address, on_processes):
        xr.testing.assert_identical(ds, ref)
    assert ref["s"].shape == (8, 3) and int((ref.status != 0).sum()) == 1  # the failing point, recorded


def test_batched_chunks_on_the_cluster(client):
    ref = sweep(lib.poly_batched, GRID, executor="serial", progress=False, chunk_size=6)
    xr.testing.assert_identical(sweep(lib.poly_batched, GRID, executor=client, progress=False, chunk_size=6), ref)


def test_a_killed_dask_worker_loses_nothing(client, tmp_path):
    # the worker process running a = 4 ends; the nanny restarts it and the scheduler runs the task again
    calls = tmp_path / "calls"
    calls.mkdir()
    f = partial(lib.counted, calls_dir=str(calls), kill_at=4.0)
    ds = sweep(f, GRID, executor=client, progress=False, chunk_size=3)
    same_results(ds, reference())
    assert (tmp_path / "killed.0").exists()


def test_an_interrupted_dask_client_resumes_from_its_store(client, cluster, tmp_path):
    calls = tmp_path / "calls"
    calls.mkdir()
    store = tmp_path / "s.zarr"
    code = (
        "import cloudpickle, sweep_testlib as lib\n"
        "from functools import partial\n"
        "from rigidbody.sweep import sweep\n"
        "import numpy as np\n"
        "cloudpickle.register_pickle_by_value(lib)\n"
        f"sweep(partial(lib.counted, calls_dir={str(calls)!r}, delay=0.05), "
        "{'a': np.arange(8.0), 'b': np.array([0.0, -1.0, 0.5])}, "
        f"store={str(store)!r}, progress=False, chunk_size=3, executor={cluster.scheduler_address!r})\n"
    )
    # each call held to >= 0.2 s: the 15 points left after the 9th call need >= 1.5 s on the two workers, so
    # the Ctrl-C below lands before the sweep can finish, also on a loaded machine
    lib.hold(calls)
    proc = run_python(code)
    wait_for_calls(calls, 9, proc)
    proc.send_signal(signal.SIGINT)  # Ctrl-C in the client
    _, err = proc.communicate(timeout=60)
    assert proc.returncode != 0 and "KeyboardInterrupt" in err
    quiet(calls)
    lib.hold(calls, on=False)
    # on Dask a task is the unit of recovery (its worker may be on another machine: no journal of its points):
    # the resumed run computes exactly the points the store does not hold
    resume(store, calls, partial(lib.counted, calls_dir=str(calls), delay=0.05), executor=client,
            stored_only=True)
