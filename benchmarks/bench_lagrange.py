"""Benchmarks for rigidbody.lagrange (run on demand: ``python benchmarks/bench_lagrange.py``).

1. Averaged (3.4) vs full equations (1.1) at equal slow-variable accuracy, eps = 1e-3, tau in [0, 5],
   case 2 of the paper (theta0 = 60 deg). The accuracy of the averaged solution is its O(eps) distance from a
   tight full reference; the full integration is then run with the loosest rtol that is as accurate.
2. Cost of one averaged right-hand side: closed form (3.4) vs the general engine (nutation mean + V).
"""

from __future__ import annotations

import time
import timeit

import numpy as np

from rigidbody import lagrange as L

TOP, DRAG = L.PAPER_TOP, L.PAPER_DRAG


def slow_err(a, b):
    return max(np.abs(a.Gz - b.Gz).max(), np.abs(a.H - b.H).max(), np.abs(a.r - b.r).max())


def bench_averaged_vs_full(eps: float = 1e-3, tau_end: float = 5.0) -> None:
    state = L.paper_initial_state(2)
    ini = L.integrals(TOP, *state[:5])
    tau = np.linspace(0.0, tau_end, 201)
    t0 = time.perf_counter()
    ref = L.simulate(TOP, DRAG, eps, state, (0, tau_end / eps), t_eval=tau / eps, rtol=1e-12, atol=1e-13)
    t_ref = time.perf_counter() - t0
    t0 = time.perf_counter()
    avg = L.averaged(TOP, DRAG, ini, (0, tau_end), tau_eval=tau)
    t_avg = time.perf_counter() - t0
    e_avg = slow_err(avg, ref)
    print(f"eps = {eps:g}, tau in [0, {tau_end:g}]: full reference (rtol 1e-12) {t_ref:.2f} s, "
          f"nfev {ref.nfev}")
    print(f"averaged (3.4): {t_avg * 1e3:.1f} ms, slow-variable error vs reference {e_avg:.2e} (O(eps))")
    best = None
    for rtol in (1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8):
        t0 = time.perf_counter()
        f = L.simulate(TOP, DRAG, eps, state, (0, tau_end / eps), t_eval=tau / eps, rtol=rtol, atol=rtol * 1e-2)
        tf = time.perf_counter() - t0
        e = slow_err(f, ref)
        print(f"  full rtol {rtol:.0e}: {tf:.3f} s, error {e:.2e}")
        if e <= e_avg and best is None:
            best = (rtol, tf)
    if best is not None:
        print(f"equal accuracy: full (rtol {best[0]:.0e}) {best[1]:.3f} s vs averaged {t_avg:.4f} s -> "
              f"ratio {best[1] / t_avg:.0f}x")


def bench_rhs() -> None:
    u = (0.0, 0.5, 2.0)
    n = 2000
    tc = timeit.timeit(lambda: L.averaged_rhs(TOP, DRAG, *u, -1.0, 1.0), number=n) / n
    te = timeit.timeit(lambda: L.averaged_rhs(TOP, DRAG, *u, -1.0, 1.0, closed_form=False), number=n) / n
    print(f"averaged right-hand side: closed form (3.4) {tc * 1e6:.1f} us, general engine {te * 1e6:.1f} us "
          f"(ratio {te / tc:.1f})")


if __name__ == "__main__":
    bench_rhs()
    bench_averaged_vs_full()
