"""Averaged vs full equations: cost at equal accuracy (run on demand: python benchmarks/bench_euler_poinsot.py).

For eps = 0.01 and 0.005 (paper's body, drag case 1, k2(0) = 0.9, tau in [0, 0.5]) the averaged system (9)
has an error ~eps^2 against the full motion (the averaging error). The full equations can be integrated
loosely and still be that accurate: we pick the loosest rtol in 1e-4 ... 1e-10 whose full solution stays
within that error of a tight (rtol 1e-11) reference, and compare wall times. Also printed: the cost of the
orbit-averaged limit (eps = 0).
"""

from __future__ import annotations

import time

import numpy as np

from rigidbody import euler_poinsot as ep

BODY = ep.Body(3.2, 2.6, 1.67)
I = np.diag([2.322, 1.31, 1.425])
KW = dict(k2_0=0.9, tau_span=(0.0, 0.5))
FIELDS = ("G", "T", "k2", "delta", "lam")


def timed(f, *a, repeat=3, **kw):
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = f(*a, **kw)
        best = min(best, time.perf_counter() - t0)
    return out, best


def err(a, b):
    return max(np.abs(getattr(a, f) - getattr(b, f)).max() for f in FIELDS)


def main() -> None:
    te = np.linspace(0, 0.5, 11)
    lim, t_lim = timed(ep.averaged, BODY, I, 0.0, tau_eval=te, **KW)
    print(f"orbit-averaged limit (eps = 0): {t_lim * 1e3:.1f} ms, nfev = {lim.nfev}")
    for eps in (0.01, 0.005):
        ref = ep.simulate(BODY, I, eps, tau_eval=te, rtol=1e-11, atol=1e-13, **KW)
        avg, t_avg = timed(ep.averaged, BODY, I, eps, tau_eval=te, **KW)
        target = err(avg, ref)  # the accuracy the averaged answer has
        chosen = None
        for rtol in (1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10):
            full, t_full = timed(ep.simulate, BODY, I, eps, tau_eval=te, rtol=rtol, atol=rtol * 1e-2,
                                 repeat=1, **KW)
            if full.status == 0 and err(full, ref) <= target:
                chosen = (rtol, t_full, full.nfev, err(full, ref))
                break
        print(f"eps = {eps:g}: averaged (9) error vs full = {target:.2e}, {t_avg * 1e3:.1f} ms, nfev = {avg.nfev}")
        if chosen is None:
            print("   full: no rtol in 1e-4..1e-10 reached that accuracy")
            continue
        rtol, t_full, nfev, e = chosen
        print(f"   full at equal accuracy: rtol = {rtol:g}, error {e:.2e}, {t_full * 1e3:.1f} ms, nfev = {nfev}")
        print(f"   cost ratio full / averaged = {t_full / t_avg:.1f} (time), {nfev / avg.nfev:.1f} (nfev); "
              f"full / limit = {t_full / t_lim:.0f}")


if __name__ == "__main__":
    main()
