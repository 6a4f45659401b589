"""Benchmark: the axis path from the closed forms v(t), k(t) (viscous.axis_path, 9-state frame equations in
the compactified time u) against the full simulation (viscous.simulate, Euler + quaternion), for the same
accuracy of n(t).

Run: python benchmarks/bench_viscous.py
Reference: the two routes at rtol = 1e-13 agree to ~1e-12; the error of each run is measured against the
reference of the OTHER route, so neither is judged by itself.
"""

from __future__ import annotations

import time

import numpy as np

from rigidbody import viscous as vs


def timed(fun, repeat=5):
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fun()
        best = min(best, time.perf_counter() - t0)
    return best, out


BODY = vs.Body(2.0, 1.0)
N0 = np.array([0.0, 0.6, 0.8])
ND0 = np.array([0.5, 0.0, 0.0])
OMEGA0 = 4.0


def run_case(name: str, medium: vs.Medium, T: float = 100.0) -> None:
    t = np.linspace(0.0, T, 1001)

    def path(rtol: float, atol: float) -> np.ndarray:
        return vs.axis_path(BODY, medium, N0, ND0, OMEGA0, t, rtol=rtol, atol=atol)

    def sim(rtol: float, atol: float) -> np.ndarray:
        return vs.simulate(BODY, medium, N0, ND0, OMEGA0, (0.0, T), t_eval=t, rtol=rtol, atol=atol).n

    def closed() -> tuple:
        return (vs.curvature(BODY, medium, OMEGA0, 0.5, t), vs.spiral_radius(BODY, medium, OMEGA0, 0.5, t),
                vs.quasi_coordinates(BODY, medium, OMEGA0, 0.5, t))

    ref_path, ref_sim = path(1e-13, 1e-15), sim(1e-13, 1e-15)
    agree = np.max(np.linalg.norm(ref_path - ref_sim, axis=0))
    print(f"\n{name}: t in [0, {T}], 1001 output times; reference routes agree to {agree:.1e}")
    print(f"{'rtol':>8} | {'axis_path err':>13} {'ms':>7} | {'simulate err':>12} {'ms':>7} | speed-up")
    for rtol in (1e-6, 1e-8, 1e-10, 1e-12):
        tp, n_p = timed(lambda rtol=rtol: path(rtol, rtol * 1e-2))
        ts, n_s = timed(lambda rtol=rtol: sim(rtol, rtol * 1e-2))
        ep = np.max(np.linalg.norm(n_p - ref_sim, axis=0))
        es = np.max(np.linalg.norm(n_s - ref_path, axis=0))
        print(f"{rtol:8.0e} | {ep:13.1e} {1e3 * tp:7.2f} | {es:12.1e} {1e3 * ts:7.2f} | {ts / tp:5.1f}x")
    tc, _ = timed(closed)
    print(f"closed forms k, R, s, xi, zeta on 1001 times: {1e3 * tc:.3f} ms")


def main() -> None:
    run_case("contracting", vs.Medium(0.4, 0.1))
    run_case("unwinding", vs.Medium(0.1, 0.1))


if __name__ == "__main__":
    main()
