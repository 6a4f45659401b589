"""Benchmark: a 1000 x 1000 stability map of the motions (2.3) (Stepanov 1968) for a real satellite in SI
units, and the scalar API for comparison.

Run: python benchmarks/bench_gyrostat.py
"""

from __future__ import annotations

import math
import time

import numpy as np

from rigidbody import gyrostat


def timed(fun, repeat=3):
    best = np.inf
    out = None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fun()
        best = min(best, time.perf_counter() - t0)
    return best, out


def main() -> None:
    sat = gyrostat.Satellite(M=1000.0, A1=1200.0, A2=1000.0, A3=800.0, mu=3.986e14)
    R0 = 7.0e6
    n0 = math.sqrt(sat.mu / R0**3)
    theta0 = np.linspace(-1.5, 1.5, 1000)
    k2 = np.linspace(-4.0, 4.0, 1000) * sat.Abar * n0
    t, mp = timed(lambda: gyrostat.stability_map(sat, R0, theta0, k2=k2))
    names = ((0, "stable"), (1, "unstable"), (2, "undecided"), (-1, "invalid"))
    counts = {v: int(np.sum(mp.code == c)) for c, v in names}
    print(f"stability_map 1000 x 1000 (SI units): {t:.2f} s  ({1e6 / t:,.0f} points/s)  {counts}")

    t, _ = timed(lambda: gyrostat.normalized_stability_map(sat, R0, theta0, np.linspace(-6, 6, 1000)))
    print(f"normalized_stability_map 1000 x 1000: {t:.2f} s")

    sym = gyrostat.Satellite(M=1000.0, A1=1200.0, A2=1200.0, A3=800.0, mu=3.986e14)
    t, _ = timed(lambda: gyrostat.symmetric_stability_map(sym, R0, np.linspace(0.01, 3.1, 1000),
                                                          A3=np.linspace(100.0, 2400.0, 1000)))
    print(f"symmetric_stability_map 1000 x 1000 (full 4x4 second variation): {t:.2f} s")

    def scalar(n=2000):
        rng = np.random.default_rng(0)
        for th, k in zip(rng.uniform(-1.5, 1.5, n), rng.uniform(-4, 4, n) * sat.Abar * n0):
            m = gyrostat.stationary_motion(sat, R0, float(th), k2=float(k))
            gyrostat.stability(m.satellite, m)

    t, _ = timed(scalar, repeat=1)
    print(f"scalar stationary_motion + stability: {t / 2000 * 1e6:.0f} us per point")


if __name__ == "__main__":
    main()
