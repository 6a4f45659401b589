"""Averaged vs full equations, and numerical vs closed-form averaging: costs at equal accuracy.

Run on demand: python benchmarks/bench_euler_poinsot.py

1. For eps = 0.01 and 0.005 (paper's body, drag case 1, k2(0) = 0.9, tau in [0, 0.5]) the averaged system (9)
   has an error ~eps^2 against the full motion (the averaging error). The full equations can be integrated
   loosely and still be that accurate: we pick the loosest rtol in 1e-4 ... 1e-10 whose full solution stays
   within that error of a tight (rtol 1e-11) reference, and compare wall times. Also printed: the cost of the
   orbit-averaged limit (eps = 0).
2. The averaging engine against the closed forms: the paper's case 1 from its own start (k2 = 0.99,
   delta = lambda = pi/4) to tau = 3, eps = 0 (orbit-averaged) and eps = 0.005, integrated with the closed
   forms (9) (the drag tensor: the paper's code path), with the same closed forms through the torque objects
   (the vector form every torque uses) and with the engine for every part (averaging="numerical"). The
   accuracy of each is its largest difference in G, T, k2, delta, lambda from a closed-form run at
   rtol 1e-13; timings are the best of several interleaved runs (the machine may be shared). Target: the
   numerical evolution costs at most 20 times the closed-form one.
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


def engine_vs_closed() -> None:
    setup = dict(G0=1.0, k2_0=0.99, delta0=np.pi / 4, lam0=np.pi / 4, tau_span=(0.0, 3.0))
    objs = ep.LinearDrag(I) + ep.GravityGradient(BODY)
    te = np.linspace(0.0, 3.0, 31)
    for eps, repeat in ((0.0, 7), (0.005, 2)):
        ref = ep.averaged(BODY, I, eps, tau_eval=te, rtol=1e-13, atol=1e-15, **setup)
        runs = {
            "closed forms (9), paper's path": dict(torque=I),
            "closed forms, torque objects": dict(torque=objs),
            "engine (averaging='numerical')": dict(torque=I, averaging="numerical"),
        }
        best = {k: np.inf for k in runs}
        out = {}
        for _ in range(repeat):
            for name, kw in runs.items():
                kw = dict(kw)
                tq = kw.pop("torque")
                t0 = time.perf_counter()
                out[name] = ep.averaged(BODY, tq, eps, tau_eval=te, **kw, **setup)
                best[name] = min(best[name], time.perf_counter() - t0)
        print(f"paper's case 1 to tau = 3, eps = {eps:g}:")
        for name, sol in out.items():
            extra = f", quadrature error {sol.quad_error:.1e}" if name.startswith("engine") else ""
            print(f"   {name:32s} {best[name] * 1e3:8.1f} ms, nfev = {sol.nfev:6d}, "
                  f"accuracy {err(sol, ref):.1e}{extra}")
        t_num = best["engine (averaging='numerical')"]
        t_paper = best["closed forms (9), paper's path"]
        print(f"   cost ratio engine / closed forms (9) = {t_num / t_paper:.1f} "
              f"(target <= 20); engine / closed forms in the same formulation = "
              f"{t_num / best['closed forms, torque objects']:.1f}")


if __name__ == "__main__":
    main()
    engine_vs_closed()
