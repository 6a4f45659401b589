"""Cost of the elliptic core against raw SciPy, and of a period average (run on demand).

Run: python benchmarks/bench_core.py
"""

import timeit

import numpy as np
from scipy import special

from rigidbody.core import averaging, elliptic


def _t(stmt, number):
    return min(timeit.repeat(stmt, number=number, repeat=5)) / number


def main() -> None:
    for n in (64, 100_000):
        u = np.linspace(0.0, 40.0, n)
        reps = 200 if n < 1000 else 5
        raw = _t(lambda u=u: special.ellipj(u, 0.81), reps)
        ours = _t(lambda u=u: elliptic.jacobi(u, 0.9), reps)
        near = _t(lambda u=u: elliptic.jacobi(u, mc=1e-12), reps)
        print(f"n={n:7d}: scipy ellipj {raw * 1e6:9.1f} us | jacobi(k=0.9) {ours * 1e6:9.1f} us "
              f"| jacobi(mc=1e-12, own AGM) {near * 1e6:9.1f} us")
    for mc in (0.5, 1e-4, 1e-10):
        nn = averaging.n_nodes(mc=mc)
        t = _t(lambda mc=mc: averaging.sn2_average(lambda x: x * x, -0.2, 0.7, mc=mc), 500)
        print(f"sn2_average at 1-k^2={mc:g}: {nn:4d} nodes, {t * 1e6:7.1f} us per call")


if __name__ == "__main__":
    main()
