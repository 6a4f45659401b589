"""Benchmark: what rigidbody.sweep costs per point and what local processes and batching buy.

Ratios measured in one run (the machine's other load moves absolute times; ratios less so):

* overhead: a sweep of a trivial function (serial, and on local processes) against a plain Python loop
  over the same points (the baseline a user writes today); the results are identical (difference printed);
* a compute-bound function (``rigidbody.studies.averaging_error_euler_poinsot``, an averaged and a full
  Euler-Poinsot evolution per point, 0.03-0.7 s each): local processes against the serial sweep (the speed-up
  is bounded by the number of cores, less the second it takes to start the workers);
* a batched study (``rigidbody.studies.spin_end``: a chunk of points is one batch of averaged evolutions,
  about half a millisecond per point): the same comparison, where the workers' start is most of the cost;
* batching: ``rigidbody.sweep.gyrostat_stability`` (one vectorised ``gyrostat.stability_map`` call per
  chunk) against the same sweep calling ``gyrostat.stability`` point by point;
* memory: the bytes of the returned Dataset per point.

Run: python benchmarks/bench_sweep.py
"""

from __future__ import annotations

import os
import time
from functools import partial

import numpy as np

from rigidbody import gyrostat, studies
from rigidbody.sweep import gyrostat_stability, sweep
from rigidbody.sweep._executors import local_cpu_count


def trivial(a: float, b: float) -> dict[str, float]:
    return {"s": a + b, "p": a * b}


def stability_point(theta0: float, k2: float, *, sat: gyrostat.Satellite, R0: float) -> dict[str, float]:
    try:
        motion = gyrostat.stationary_motion(sat, R0, theta0, k2=k2)
    except ValueError:
        return {"code": -1.0}
    return {"code": float({"stable": 0, "unstable": 1, "undecided": 2}[gyrostat.stability(sat, motion).verdict])}


def timed(fun):
    t0 = time.perf_counter()
    out = fun()
    return time.perf_counter() - t0, out


def serial_vs_processes(label: str, func, grid: dict, output: str) -> None:
    """One sweep serially and on local processes: the speed-up, and whether the results are identical."""
    n = int(np.prod([len(v) for v in grid.values()]))
    t_ser, ds = timed(lambda: sweep(func, grid, executor="serial", progress=False))
    t_proc, dp = timed(lambda: sweep(func, grid, progress=False))
    same = bool(np.array_equal(ds[output].values, dp[output].values))
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"{label}, {n} points: serial {t_ser:.2f} s, local processes ({local_cpu_count()} workers) "
          f"{t_proc:.2f} s: speed-up {t_ser / t_proc:.2f}x; identical: {same}; load average {load:.1f} on "
          f"{os.cpu_count()} CPUs (other jobs take their share)")


def main() -> None:
    sweep(trivial, {"a": [0.0], "b": [0.0]}, executor="serial", progress=False)  # imports xarray once
    a, b = np.linspace(0.0, 1.0, 200), np.linspace(-1.0, 1.0, 100)  # 2e4 points
    n = a.size * b.size
    t_loop, loop = timed(lambda: np.array([[trivial(x, y)["s"] for y in b] for x in a]))
    t_ser, ds = timed(lambda: sweep(trivial, {"a": a, "b": b}, executor="serial", progress=False))
    t_proc, dp = timed(lambda: sweep(trivial, {"a": a, "b": b}, progress=False, chunk_size=1000))
    diff = max(float(np.max(np.abs(ds["s"].values - loop))), float(np.max(np.abs(dp["s"].values - loop))))
    print(f"trivial function, {n} points: plain loop {1e6 * t_loop / n:.1f} us/pt; sweep serial "
          f"{1e6 * t_ser / n:.1f} us/pt ({t_ser / t_loop:.1f}x the loop); local processes {1e6 * t_proc / n:.1f} "
          f"us/pt incl. worker start ({t_proc / t_loop:.1f}x); max |difference| = {diff:g}")
    print(f"memory of the Dataset: {ds.nbytes / n:.0f} bytes per point (2 float outputs + status + message)")

    serial_vs_processes("averaging_error_euler_poinsot (an averaged and a full evolution per point)",
                        studies.averaging_error_euler_poinsot,
                        {"eps": np.geomspace(0.01, 0.05, 6), "k2_0": np.linspace(0.1, 0.9, 6)}, "error")
    serial_vs_processes("spin_end (batched: one batch of averaged evolutions per chunk)", studies.spin_end,
                        {"r1": np.linspace(0.2, 2.4, 16), "r3": np.linspace(0.2, 2.4, 16)}, "regime")

    sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    g = {"theta0": np.linspace(-1.2, 1.2, 100), "k2": np.linspace(-0.05, 0.05, 50)}
    t_pp, dpp = timed(lambda: sweep(partial(stability_point, sat=sat, R0=1.0), g, executor="serial", progress=False))
    t_b, db = timed(lambda: sweep(partial(gyrostat_stability, sat=sat, R0=1.0), g, executor="serial",
                                  progress=False))
    agree = float(np.mean(dpp["code"].values == db["code"].values))
    print(f"gyrostat stability, 5000 points: batched chunks {t_b:.3f} s vs point by point {t_pp:.2f} s: "
          f"{t_pp / t_b:.0f}x; verdicts agree at {agree:.1%} of the points")


if __name__ == "__main__":
    main()
