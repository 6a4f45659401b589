"""Benchmarks for rigidbody.lagrange (run on demand: ``python benchmarks/bench_lagrange.py``).

Every comparison is at equal accuracy, measured against a tight reference (never the tolerance), with the
accuracy of each side printed beside the ratio. Times are CPU seconds of this process (the minimum of a few
repeats), so other load on the machine disturbs them less; ratios come from one run.

1. ``lagrange.averaged`` (paper case 2, tau in [0, 100], rtol 1e-10, 101 output points) against a
   straightforward SciPy implementation of the same averaged system written here: (2.7) for linear drag (3.1)
   in (Gz, H, r), the cubic's roots by the trigonometric formula, ``scipy.special.ellipk/ellipe``, a
   ``math``-scalar right-hand side, ``solve_ivp(method='DOP853')`` with a pure relative tolerance (atol = 0).
   The error of either is the largest relative error, over the output grid, of Gz, r and the energy above
   the hanging state H + mgl; the reference is the baseline at rtol 1e-13 (its r agrees with the exact
   r0 exp(-b tau/C) of (3.3) to ~1e-13). The baseline's time at the project's error is interpolated
   (log-log) between its runs over a sweep of rtol.
2. A batch of 1000 averaged evolutions (random tilts 20-160 deg and spins 1-2.5, the paper's top and drag,
   tau in [0, 100], rtol 1e-10) against a loop of the single calls; and a batch of 100 full simulations
   (eps random in [0.01, 0.05], t in [0, 50]) against its loop. Both sides give the same numbers (printed).
3. Full equations (1.1) against the averaged system, eps = 1e-3, tau in [0, 5], case 2: each side at the
   loosest rtol whose own error (against its rtol-1e-12 reference) is below a tenth of their O(eps)
   difference, so that the run resolves the difference it is compared by.

Lines starting with ``RATIO`` are collected by ``benchmarks/run_all.py``.
"""

from __future__ import annotations

import math
import time

import numpy as np
from common import BASELINE_RTOLS, cpu_time, time_at_accuracy
from scipy.integrate import solve_ivp
from scipy.special import ellipe, ellipk

from rigidbody import lagrange as L

TOP, DRAG = L.PAPER_TOP, L.PAPER_DRAG
A, C, MGL = TOP.A, TOP.C, TOP.mgl
a_, b_ = DRAG.a, DRAG.b




# ------------------------------------------------------------------------------ the straightforward baseline
def baseline_rhs(t, y):
    Gz, H, r = y
    s1 = H / MGL - C * r * r / (2 * MGL) + C * C * r * r / (2 * A * MGL)
    s2 = Gz * C * r / (A * MGL) - 1.0
    s3 = -H / MGL + C * r * r / (2 * MGL) + Gz * Gz / (2 * A * MGL)
    p = s2 - s1 * s1 / 3.0
    q = -2.0 * s1**3 / 27.0 + s1 * s2 / 3.0 - s3
    m = 2.0 * math.sqrt(max(-p / 3.0, 0.0))
    th = math.acos(max(-1.0, min(1.0, 3.0 * q / (p * m)))) / 3.0
    u1, u2, u3 = sorted(m * math.cos(th - 2.0 * math.pi * k / 3.0) + s1 / 3.0 for k in range(3))
    k2 = (u2 - u1) / (u3 - u1)
    v = u3 - (u3 - u1) * ellipe(k2) / ellipk(k2)
    return [-a_ * (Gz - C * r * v) / A - b_ * r * v, -a_ * (2.0 * (H - MGL * v) - C * r * r) / A - b_ * r * r,
            -b_ * r / C]


def baseline(ini, T, te, rtol):
    return solve_ivp(baseline_rhs, (0.0, T), ini, method="DOP853", rtol=rtol, atol=0.0, t_eval=te)


def rel_errors(Gz, H, r, ref):
    """Largest relative errors of Gz, r and H + mgl over the grid."""
    return (float(np.max(np.abs(Gz / ref[0] - 1))), float(np.max(np.abs(r / ref[2] - 1))),
            float(np.max(np.abs((H + MGL) / (ref[1] + MGL) - 1))))


def bench_vs_baseline(T: float = 100.0, rtol: float = 1e-10) -> None:
    ini = L.integrals(TOP, *L.paper_initial_state(2)[:5])
    te = np.linspace(0.0, T, 101)
    ref = baseline(ini, T, te, 1e-13).y
    r_exact = L.PAPER_R0 * np.exp(-b_ * te / C)
    ours_ref = L.averaged(TOP, DRAG, ini, (0.0, T), tau_eval=te, rtol=1e-13)
    print(f"reference (baseline, rtol 1e-13): r vs exact (3.3) {np.max(np.abs(ref[2] / r_exact - 1)):.1e}; "
          f"project at rtol 1e-13 vs reference {max(rel_errors(ours_ref.Gz, ours_ref.H, ours_ref.r, ref)):.1e}")
    L.averaged(TOP, DRAG, ini, (0.0, T), tau_eval=te, rtol=rtol)  # warm-up (the stepper's code is generated once)
    s = L.averaged(TOP, DRAG, ini, (0.0, T), tau_eval=te, rtol=rtol)
    e_p = rel_errors(s.Gz, s.H, s.r, ref)
    t_p = cpu_time(lambda: L.averaged(TOP, DRAG, ini, (0.0, T), tau_eval=te, rtol=rtol), repeat=7, number=3)
    print(f"lagrange.averaged, rtol {rtol:g}: {t_p * 1e3:.2f} ms, nfev {s.nfev}, relative errors Gz {e_p[0]:.1e}, "
          f"r {e_p[1]:.1e}, H + mgl {e_p[2]:.1e}")
    runs = []
    for rt in BASELINE_RTOLS:
        sb = baseline(ini, T, te, rt)
        e_b = max(rel_errors(*sb.y, ref))
        t_b = cpu_time(lambda rt=rt: baseline(ini, T, te, rt), repeat=5, number=3)
        runs.append((e_b, t_b))
        print(f"  baseline rtol {rt:g}: {t_b * 1e3:.2f} ms, nfev {sb.nfev}, largest relative error {e_b:.1e}")
    target = max(e_p)
    t_eq, note = time_at_accuracy(target, runs)
    print(f"RATIO lagrange.averaged vs straightforward SciPy (case 2, tau in [0, {T:g}], rtol {rtol:g}): "
          f"{t_eq / t_p:.2f}x at equal accuracy (project error {target:.1e}, baseline interpolated to the same; "
          f"baseline at rtol {rtol:g}: error {runs[3][0]:.1e}, {runs[3][1] / t_p:.2f}x the project's time){note}")


# ------------------------------------------------------------------------------------------------- batches
def bench_batch(B: int = 1000, T: float = 100.0) -> None:
    rng = np.random.default_rng(0)
    th = rng.uniform(math.radians(20.0), math.radians(160.0), B)
    r0 = rng.uniform(1.0, 2.5, B)
    ini = np.array(L.integrals(TOP, 0 * th, 0 * th, r0, 0 * th, th)).T
    te = np.linspace(0.0, T, 41)
    L.averaged(TOP, DRAG, ini[:4], (0.0, T), tau_eval=te, rtol=1e-10)  # warm-up
    t0 = time.process_time()
    b = L.averaged(TOP, DRAG, ini, (0.0, T), tau_eval=te, rtol=1e-10)
    t_b = time.process_time() - t0
    t0 = time.process_time()
    loop = [L.averaged(TOP, DRAG, ini[i], (0.0, T), tau_eval=te, rtol=1e-10) for i in range(B)]
    t_l = time.process_time() - t0
    diff = max(float(np.max(np.abs(b.r[i] / loop[i].r - 1))) for i in range(B))
    print(f"RATIO lagrange.averaged batch of {B} vs loop (tau in [0, {T:g}], rtol 1e-10): {t_l / t_b:.1f}x "
          f"({t_b:.2f} s vs {t_l:.2f} s; statuses {np.bincount(b.status + 1).tolist()} for -1/0/1; largest relative "
          f"batch-loop difference in r {diff:.1e})")
    n = 100
    st = np.zeros((n, 6))
    st[:, 2] = rng.uniform(1.0, 2.5, n)
    st[:, 4] = rng.uniform(0.3, 2.8, n)
    eps = rng.uniform(0.01, 0.05, n)
    tt = np.linspace(0.0, 50.0, 21)
    t0 = time.process_time()
    bs = L.simulate(TOP, DRAG, eps, st, (0.0, 50.0), t_eval=tt)
    t_b = time.process_time() - t0
    t0 = time.process_time()
    loop = [L.simulate(TOP, DRAG, float(eps[i]), tuple(st[i]), (0.0, 50.0), t_eval=tt) for i in range(n)]
    t_l = time.process_time() - t0
    diff = max(float(np.max(np.abs(bs.Gz[i] - loop[i].Gz))) for i in range(n))
    print(f"RATIO lagrange.simulate batch of {n} vs loop (t in [0, 50], rtol 1e-10): {t_l / t_b:.1f}x "
          f"({t_b:.2f} s vs {t_l:.2f} s; largest batch-loop difference in Gz {diff:.1e})")


# ------------------------------------------------------------------------------------- full vs averaged
def slow_err(a, b) -> float:
    return max(np.abs(a.Gz - b.Gz).max(), np.abs(a.H - b.H).max(), np.abs(a.r - b.r).max())


def bench_averaged_vs_full(eps: float = 1e-3, tau_end: float = 5.0) -> None:
    state = L.paper_initial_state(2)
    ini = L.integrals(TOP, *state[:5])
    tau = np.linspace(0.0, tau_end, 201)
    t0 = time.process_time()
    full_ref = L.simulate(TOP, DRAG, eps, state, (0, tau_end / eps), t_eval=tau / eps, rtol=1e-12, atol=1e-13)
    t_ref = time.process_time() - t0
    avg_ref = L.averaged(TOP, DRAG, ini, (0, tau_end), tau_eval=tau, rtol=1e-12)
    d = slow_err(full_ref, avg_ref)
    print(f"eps = {eps:g}, tau in [0, {tau_end:g}]: O(eps) difference full - averaged = {d:.2e} (full reference "
          f"rtol 1e-12: {t_ref:.1f} s, nfev {full_ref.nfev})")
    goal = 0.1 * d
    full = None
    for rtol in (1e-5, 1e-6, 1e-7, 1e-8, 1e-9):
        t0 = time.process_time()
        f = L.simulate(TOP, DRAG, eps, state, (0, tau_end / eps), t_eval=tau / eps, rtol=rtol, atol=rtol * 1e-2)
        tf = time.process_time() - t0
        e = slow_err(f, full_ref)
        print(f"  full rtol {rtol:.0e}: {tf:.3f} s, own error {e:.2e}")
        if e <= goal:
            full = (rtol, tf, e)
            break
    avg = None
    for rtol in (1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-10):
        s = L.averaged(TOP, DRAG, ini, (0, tau_end), tau_eval=tau, rtol=rtol)
        e = slow_err(s, avg_ref)
        if e <= goal:
            ta = cpu_time(lambda rtol=rtol: L.averaged(TOP, DRAG, ini, (0, tau_end), tau_eval=tau, rtol=rtol),
                          repeat=7, number=3)
            avg = (rtol, ta, e)
            print(f"  averaged rtol {rtol:.0e}: {ta * 1e3:.2f} ms, own error {e:.2e}")
            break
    if full is None or avg is None:
        print("  no tolerance in the sweep resolved the difference")
        return
    print(f"RATIO lagrange.simulate vs lagrange.averaged (eps {eps:g}, tau in [0, {tau_end:g}], each resolving the "
          f"O(eps) difference {d:.1e} to a tenth): {full[1] / avg[1]:.0f}x (full rtol {full[0]:.0e} error "
          f"{full[2]:.1e}; averaged rtol {avg[0]:.0e} error {avg[2]:.1e})")


if __name__ == "__main__":
    bench_vs_baseline()
    bench_batch()
    bench_averaged_vs_full()
