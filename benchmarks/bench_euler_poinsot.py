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
3. ``euler_poinsot.averaged`` against a straightforward SciPy implementation of the same averaged system (9)
   written here (the baseline): the paper's variables (G, k2, delta, lambda) with (6)-(8) as printed
   (chi and N of (7), E/K and (K - E)/(K k^2) from ``scipy.special.ellipk/ellipe``), a ``math``-scalar
   right-hand side, ``solve_ivp(method='DOP853')`` with a pure relative tolerance (atol = 0). Paper case 1
   from its own start (k2 = 0.99, delta = lambda = pi/4), tau in [0, 3], 31 output times, rtol 1e-10, at
   eps = 0 and eps = 0.005. The error of either is the largest over the grid of the relative errors of G, T,
   k2 and the errors of delta, lambda (radians); the reference is the baseline at rtol 1e-13. The baseline's
   time at the project's error is interpolated (log-log) over a sweep of its rtol.
4. A batch of 10^4 averaged evolutions (paper body and drag case 1, random k2(0) in [0.05, 0.95], delta(0) in
   [0, pi], lambda(0) in [0, 2 pi], eps = 0, tau in [0, 3], 31 output times) against the loop of single calls;
   and a batch of 100 full simulations (random eps in [0.03, 0.05], k2(0), phases; tau in [0, 0.3]) against its
   loop. Both sides give the same numbers (difference printed).
5. The resonance check near symmetry: ``averaged(Body(0.55, 0.3005727, 0.3005723), ViscousCavity(body, [0.03,
   0.19, 0.12]), 4e-4, k2_0=0.9, tau_span=(0, 0.002))`` (rotation number ~2000: the run crosses about 60
   resonances of orders ~2000 and ~4000) against the same on the generic body ``Body(0.55, 0.35, 0.30)`` (none
   crossed). Target: at most 5 times. Also printed: each run with the check off (``resonance_tol=None``).

Times are CPU seconds of this process (the minimum of a few repeats where stated); ratios come from one run.
Lines starting with ``RATIO`` are collected by ``benchmarks/run_all.py``.
"""

from __future__ import annotations

import math
import time

import numpy as np
from common import BASELINE_RTOLS, cpu_time, time_at_accuracy
from scipy.integrate import solve_ivp
from scipy.special import ellipe, ellipk

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


# ------------------------------------------------------------------------------ the straightforward baseline
A1, A2, A3 = BODY.A1, BODY.A2, BODY.A3
I11, I22, I33 = float(I[0, 0]), float(I[1, 1]), float(I[2, 2])
N_7 = A1 * A3 / (I33 * A1 - I11 * A3)  # N and chi of (7)
CHI = (2 * I22 * A1 * A3 - I11 * A2 * A3 - I33 * A1 * A2) / ((I33 * A1 - I11 * A3) * A2)


def baseline_parts(k2: float) -> tuple[float, float, float]:
    """dG/G and dk2/dtau of (6)-(8) as printed, and N* of (6)."""
    K, E = float(ellipk(k2)), float(ellipe(k2))
    W = 1.0 - E / K
    R = A1 * (A2 - A3) + A3 * (A1 - A2) * k2
    dGG = -(I22 * (A1 - A3) * W + I11 * (A2 - A3) * (1.0 - W) + I33 * (A1 - A2) * (k2 - W)) / R
    dk2 = ((1.0 - CHI) * (1.0 - k2) - ((1.0 - CHI) + (1.0 + CHI) * k2) * E / K) / N_7
    Ns = A2 + A3 - 2.0 * A1 + 3.0 * (k2 * (A1 - A2) * (A1 - A3) / R) * (A3 + (A2 - A3) * (K - E) / (K * k2))
    return dGG, dk2, Ns


def baseline(eps: float, y0: list[float], T: float, te: np.ndarray, rtol: float):
    """(9) in (G, k2, delta, lambda); eps = 0: delta constant, the orbit-averaged lambda equation."""
    if eps == 0.0:
        def rhs(t, y):
            G, k2, d, lam = y
            dGG, dk2, Ns = baseline_parts(k2)
            return [dGG * G, dk2, 0.0, 0.75 * Ns * math.cos(d) / G]
    else:
        def rhs(t, y):
            G, k2, d, lam = y
            dGG, dk2, Ns = baseline_parts(k2)
            x = t / eps - lam
            b1, b2, b3 = math.cos(d) * math.cos(x), math.sin(x), math.sin(d) * math.cos(x)
            return [dGG * G, dk2, -1.5 * b2 * b3 * Ns / G, 1.5 * b1 * b3 * Ns / (G * math.sin(d))]
    return solve_ivp(rhs, (0.0, T), y0, method="DOP853", rtol=rtol, atol=0.0, t_eval=te)




def errors(G, T, k2, delta, lam, ref) -> float:
    """Largest relative error of G, T, k2 and error of delta, lambda (radians) over the grid."""
    G_r, k2_r, d_r, l_r = ref
    T_r = ep.T_from(BODY, G_r, k2_r)
    return float(max(np.max(np.abs(G / G_r - 1)), np.max(np.abs(T / T_r - 1)), np.max(np.abs(k2 / k2_r - 1)),
                     np.max(np.abs(delta - d_r)), np.max(np.abs(lam - l_r))))


def bench_vs_baseline(eps: float, T: float = 3.0, rtol: float = 1e-10) -> None:
    te = np.linspace(0.0, T, 31)
    y0 = [1.0, 0.99, math.pi / 4, math.pi / 4]
    ref = baseline(eps, y0, T, te, 1e-13).y
    kw = dict(k2_0=0.99, delta0=math.pi / 4, lam0=math.pi / 4, tau_span=(0.0, T), tau_eval=te, rtol=rtol)
    ep.averaged(BODY, I, eps, **kw)  # warm-up
    s = ep.averaged(BODY, I, eps, **kw)
    e_p = errors(s.G, s.T, s.k2, s.delta, s.lam, ref)
    t_p = cpu_time(lambda: ep.averaged(BODY, I, eps, **kw), repeat=5, number=3 if eps == 0 else 1)
    print(f"euler_poinsot.averaged, eps = {eps:g}, rtol {rtol:g}: {t_p * 1e3:.2f} ms, nfev {s.nfev}, error {e_p:.1e}")
    runs = []
    for rt in BASELINE_RTOLS:
        sb = baseline(eps, y0, T, te, rt)
        G, k2, d, lam = sb.y
        e_b = errors(G, ep.T_from(BODY, G, k2), k2, d, lam, ref)
        t_b = cpu_time(lambda rt=rt: baseline(eps, y0, T, te, rt), repeat=3, number=3 if eps == 0 else 1)
        runs.append((e_b, t_b))
        print(f"  baseline rtol {rt:g}: {t_b * 1e3:.2f} ms, nfev {sb.nfev}, error {e_b:.1e}")
    t_eq, note = time_at_accuracy(e_p, runs)
    print(f"RATIO euler_poinsot.averaged vs straightforward SciPy (case 1, eps {eps:g}, tau in [0, {T:g}], rtol "
          f"{rtol:g}): {t_eq / t_p:.2f}x at equal accuracy (project error {e_p:.1e}, baseline interpolated to the "
          f"same; baseline at rtol {rtol:g}: error {runs[3][0]:.1e}, {runs[3][1] / t_p:.2f}x the project's time)"
          f"{note}")


# ------------------------------------------------------------------------------------------------- batches
def bench_batch(B: int = 10_000, T: float = 3.0) -> None:
    rng = np.random.default_rng(0)
    k2 = rng.uniform(0.05, 0.95, B)
    d0 = rng.uniform(0.0, math.pi, B)
    l0 = rng.uniform(0.0, 2.0 * math.pi, B)
    te = np.linspace(0.0, T, 31)
    kw = dict(tau_span=(0.0, T), tau_eval=te)
    ep.averaged(BODY, I, 0.0, 1.0, k2[:4], d0[:4], l0[:4], **kw)  # warm-up
    t0 = time.process_time()
    b = ep.averaged(BODY, I, 0.0, 1.0, k2, d0, l0, **kw)
    t_b = time.process_time() - t0
    t0 = time.process_time()
    loop = [ep.averaged(BODY, I, 0.0, 1.0, float(k2[i]), float(d0[i]), float(l0[i]), **kw) for i in range(B)]
    t_l = time.process_time() - t0
    dG = max(float(np.max(np.abs(b.G[i] / loop[i].G - 1))) for i in range(B))
    dl = max(float(np.max(np.abs(b.lam[i] - loop[i].lam))) for i in range(B))
    print(f"RATIO euler_poinsot.averaged batch of {B} vs loop (case 1, eps 0, tau in [0, {T:g}], rtol 1e-10): "
          f"{t_l / t_b:.1f}x ({t_b:.2f} s vs {t_l:.2f} s; statuses {np.bincount(b.status + 1).tolist()} for "
          f"-1/0/1; largest batch-loop difference: relative in G {dG:.1e}, lambda {dl:.1e} rad)")
    # full equations: an ensemble of 100 full runs (random phases and slow states, eps in [0.03, 0.05])
    n = 100
    eps = rng.uniform(0.03, 0.05, n)
    k2s = rng.uniform(0.1, 0.9, n)
    u0 = rng.uniform(0.0, 4.0, n)
    tt = np.linspace(0.0, 0.3, 7)
    kw = dict(tau_span=(0.0, 0.3), tau_eval=tt)
    t0 = time.process_time()
    bs = ep.simulate(BODY, I, eps, 1.0, k2s, 0.7, 0.3, u0=u0, **kw)
    t_b = time.process_time() - t0
    t0 = time.process_time()
    loop = [ep.simulate(BODY, I, float(eps[i]), 1.0, float(k2s[i]), 0.7, 0.3, u0=float(u0[i]), **kw) for i in range(n)]
    t_l = time.process_time() - t0
    diff = max(float(np.max(np.abs(bs.G[i] - loop[i].G))) for i in range(n))
    print(f"RATIO euler_poinsot.simulate batch of {n} vs loop (eps in [0.03, 0.05], tau in [0, 0.3], rtol 1e-10): "
          f"{t_l / t_b:.1f}x ({t_b:.2f} s vs {t_l:.2f} s; largest batch-loop difference in G {diff:.1e})")


# ---------------------------------------------------------------------------------------------- resonances
def bench_resonances(t1: float = 0.002) -> None:
    eps, kw = 4e-4, dict(k2_0=0.9, tau_span=(0.0, t1))
    times = {}
    for name, body in (("generic", ep.Body(0.55, 0.35, 0.30)), ("near-symmetric", ep.Body(0.55, 0.3005727, 0.3005723))):
        tq = ep.ViscousCavity(body, [0.03, 0.19, 0.12])
        sol = ep.averaged(body, tq, eps, **kw)
        times[name] = cpu_time(lambda body=body, tq=tq: ep.averaged(body, tq, eps, **kw), repeat=5, number=3)
        off = cpu_time(lambda body=body, tq=tq: ep.averaged(body, tq, eps, resonance_tol=None, **kw), repeat=5,
                       number=3)
        bounded = sum(r["bound"] for r in sol.resonances)
        print(f"resonance check, {name} body {body}: {times[name] * 1e3:.2f} ms ({off * 1e3:.2f} ms with the check "
              f"off), {len(sol.resonances)} crossings ({bounded} bounded, {len(sol.resonances) - bounded} computed)")
    print(f"RATIO euler_poinsot.averaged near-symmetric vs generic body (ViscousCavity, eps 4e-4, tau in [0, {t1:g}]): "
          f"{times['near-symmetric'] / times['generic']:.2f}x (target <= 5)")


if __name__ == "__main__":
    main()
    engine_vs_closed()
    bench_vs_baseline(0.0)
    bench_vs_baseline(0.005)
    bench_batch()
    bench_resonances()
