"""Benchmark: stability maps of the motions (2.3) (Stepanov 1968) against a straightforward NumPy baseline.

The baseline (:func:`baseline_codes`) is what one writes by hand from the paper: the closed-form family
(2.4), the second derivatives of W1 exactly as printed after (2.4), the a_ij of (2.5), and the verdict rule
of the library -- 'stable' when the constrained second variation is positive definite (all five leading
minors s1, s2, s2 a11, s2 (a11 a22 - a12^2), s2 s3 positive), 'unstable' when its degree is odd (s2 s3 < 0),
'undecided' otherwise, 'invalid' where no motion exists or the chart is singular -- vectorised over full
(meshgrid) arrays.

Accuracy: the verdicts of both sides are compared with the same formulas evaluated at 50 digits (mpmath)
on every point where the two disagree (up to a sample of them), over a grid, scattered points, and points
next to the boundaries s2 = 0 and s3 = 0.  Times are the best of interleaved repetitions.

Run: python benchmarks/bench_gyrostat.py
"""

from __future__ import annotations

import math
import time

import mpmath
import numpy as np

from rigidbody import gyrostat

SINGULAR_TOL = 1e-6  # the library's |cos| threshold of a singular chart


def timed(fun, repeat=3):
    best = np.inf
    out = None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fun()
        best = min(best, time.perf_counter() - t0)
    return best, out


def timed_pair(f, g, repeat=7):
    """Best times of f and g, interleaved (a busy machine slows both alike), and their last results."""
    best = [np.inf, np.inf]
    out = [None, None]
    for _ in range(repeat):
        for i, fun in enumerate((f, g)):
            t0 = time.perf_counter()
            out[i] = fun()
            best[i] = min(best[i], time.perf_counter() - t0)
    return best, out


def baseline_codes(sat, R0, th, k2, lib=np):
    """Verdict codes (0 stable, 1 unstable, 2 undecided, -1 invalid) and s1, s2, s3 from the printed formulas.

    ``lib=np`` on arrays; ``lib=mpmath`` on scalars (the 50-digit reference of the same formulas).
    """
    M, A1, A2, A3, mu = sat.M, sat.A1, sat.A2, sat.A3, sat.mu
    if lib is mpmath:
        M, A1, A2, A3, mu, R0, th, k2 = (mpmath.mpf(v) for v in (M, A1, A2, A3, mu, R0, th, k2))
    sin, cos, sqrt, arctan = lib.sin, lib.cos, lib.sqrt, (lib.atan if lib is mpmath else lib.arctan)
    n0 = mu / R0**3
    st, ct = sin(th), cos(th)
    # (2.4): omega0^2 cos^2 kappa0 = n2; sin 2 kappa0 = 3 (A2 - A3) n0 sin 2 theta0 / (M R0^2 omega0^2)
    n2 = n0 * (1 - 9 / (2 * M * R0**2) * ((A2 - A3) * st**2 + (2 * A3 - A1 - A2) / 3))
    kap = arctan(3 * (A2 - A3) * n0 * st * ct / (M * R0**2 * n2))
    ck, sk = cos(kap), sin(kap)
    om = sqrt(n2) / ck
    sp, cp = sin(th + kap), cos(th + kap)
    S0 = M * R0**2 * ck**2 + A2 * cp**2 + A3 * sp**2
    L = M * R0**2 * om**2 * sk
    s2k = 2 * sk * ck
    Q = M * R0**2 * s2k / (2 * cp) - (A2 - A3) * sp
    # second derivatives of W1 at (2.3), as printed
    RR = (4 * M * R0**2 * ck**2 - S0) / S0 * M * om**2 * ck**2 - 2 * M * n0 \
        + 18 * mu / R0**5 * ((A2 - A3) * st**2 + (2 * A3 - A1 - A2) / 3)
    kk = M * R0**2 / S0 * om**2 * (S0 * ck**2 + M * R0**2 * s2k**2)
    b1b1 = L * st / cp + (A2 - A1) * om**2 + om * k2 / cp
    b3b3 = L * st / cp**3 + (A2 - A3) * om**2 + om * k2 / cp**3 + om**2 / S0 * Q**2
    g1g1 = -L * sp / ct + 3 * n0 * (A1 - A3)
    g2g2 = -L * sp / ct**3 + 3 * n0 * (A2 - A3)
    Rk = -(2 * M * R0**2 * ck**2 - S0) / S0 * M * R0 * om**2 * s2k
    Rb3 = 2 * M * R0 * om**2 * ck**2 / S0 * Q
    kb3 = -M * R0**2 * om**2 * s2k / S0 * Q
    Rg2 = 9 * mu * (A2 - A3) * st / R0**4
    b1g1 = L
    b3g2 = -M * R0**2 * om**2 * sk**2 / (ct * cp)
    # (2.5)
    q = ct / cp
    a11 = RR
    a22 = kk + ct**2 * g2g2
    a33 = b3b3 + q**2 * g2g2 - 2 * q * b3g2
    a12 = Rk + ct * Rg2
    a13 = Rb3 - q * Rg2
    a23 = kb3 - ct * q * g2g2 + ct * b3g2
    s1 = g1g1
    s2 = g1g1 * b1b1 - b1g1**2
    C = a11 * a22 - a12**2
    s3 = a11 * (a22 * a33 - a23**2) - a12 * (a12 * a33 - a23 * a13) + a13 * (a12 * a23 - a22 * a13)
    if lib is mpmath:
        if not (n2 > 0 and abs(ct) > SINGULAR_TOL and abs(cp) > SINGULAR_TOL):
            return -1, s1, s2, s3
        if s1 > 0 and s2 > 0 and a11 > 0 and C > 0 and s3 > 0:
            return 0, s1, s2, s3
        return (1 if s2 * s3 < 0 else 2), s1, s2, s3
    code = np.where((s1 > 0) & (s2 > 0) & (a11 > 0) & (C > 0) & (s3 > 0), 0, np.where(s2 * s3 < 0, 1, 2))
    code[~((n2 > 0) & (np.abs(ct) > SINGULAR_TOL) & (np.abs(cp) > SINGULAR_TOL))] = -1
    return code, s1, s2, s3


def reference_codes(sat, R0, th, k2):
    """The verdicts of the printed formulas evaluated at 50 digits (scalar loop)."""
    with mpmath.workdps(50):
        return np.array([baseline_codes(sat, R0, float(t), float(k), lib=mpmath)[0] for t, k in zip(th, k2)])


def accuracy(sat, R0, th, k2, ours, base, sample=200):
    """Against the printed formulas at 50 digits, on the points where the two sides disagree (all of them, or
    a sample scaled up to all): wrong verdicts of the library (a 'stable' or 'unstable' the reference
    contradicts), library points called 'undecided' because an eigenvalue is zero to its threshold rtol =
    1e-12 (degenerate by its rule; the reference, without a threshold, is nondegenerate there), and wrong
    verdicts of the baseline."""
    diff = np.flatnonzero(ours != base)
    rng = np.random.default_rng(0)
    pick = rng.choice(diff, min(sample, diff.size), replace=False) if diff.size else diff
    ref = reference_codes(sat, R0, th[pick], k2[pick])
    scale = diff.size / max(pick.size, 1)
    wrong = (ours[pick] != ref) & (ours[pick] != 2)
    within = (ours[pick] == 2) & (ref != 2)
    return (diff.size, round(float(np.sum(wrong)) * scale), round(float(np.sum(within)) * scale),
            round(float(np.sum(base[pick] != ref)) * scale))


def compare(label, sat, R0, library_call):
    """Time the library call and the baseline on the same points; print the ratio and the accuracies."""
    mp = library_call()
    TH, K2 = np.broadcast_arrays(mp.params["theta0"], mp.params["k2"])
    TH, K2 = np.ascontiguousarray(TH), np.ascontiguousarray(K2)
    with np.errstate(all="ignore"):
        (t_lib, t_base), (mp, (base, _, _, _)) = timed_pair(library_call, lambda: baseline_codes(sat, R0, TH, K2))
    ours = np.asarray(mp.code)
    nd, wrong_ours, zero_ours, wrong_base = accuracy(sat, R0, TH.ravel(), K2.ravel(), ours.ravel(), base.ravel())
    counts = {v: int(np.sum(ours == c)) for c, v in ((0, "stable"), (1, "unstable"), (2, "undecided"), (-1, "invalid"))}
    print(f"{label}: stability_map {t_lib:.3f} s, baseline {t_base:.3f} s -> baseline/library = "
          f"{t_base / t_lib:.2f}x  ({ours.size:,} points, {counts})")
    print(f"    verdicts differ at {nd} points; against the printed formulas at 50 digits: library wrong {wrong_ours} "
          f"(undecided as degenerate to rtol {zero_ours}), baseline wrong {wrong_base}")


def main() -> None:
    sat = gyrostat.Satellite(M=1000.0, A1=1200.0, A2=1000.0, A3=800.0, mu=3.986e14)
    R0 = 7.0e6
    n0 = math.sqrt(sat.mu / R0**3)
    theta0 = np.linspace(-1.5, 1.5, 1000)
    k2 = np.linspace(-4.0, 4.0, 1000) * sat.Abar * n0
    compare("grid 1000 x 1000 (theta0, k2), SI", sat, R0, lambda: gyrostat.stability_map(sat, R0, theta0, k2=k2))
    rng = np.random.default_rng(1)
    th_r = rng.uniform(-1.5, 1.5, 10**6)
    k2_r = rng.uniform(-4.0, 4.0, 10**6) * sat.Abar * n0
    compare("10^6 scattered points (grid=False), SI", sat, R0,
            lambda: gyrostat.stability_map(sat, R0, th_r, k2=k2_r, grid=False))
    # next to the boundaries s2 = 0 and s3 = 0 (k2 within 1e-10 .. 1e-6 relative): where float64 decides
    th_b = rng.uniform(-1.4, 1.4, 10**5)
    b = gyrostat.exact_boundaries(sat, R0, th_b)
    kb = np.where(rng.random(th_b.size) < 0.5, b["k2_s2"], b["k2_s3"])
    ok = np.isfinite(kb)
    th_b, kb = th_b[ok], kb[ok] * (1 + rng.choice([-1, 1], ok.sum()) * 10 ** rng.uniform(-10, -6, ok.sum()))
    compare(f"{th_b.size:,} points next to s2 = 0 or s3 = 0 (grid=False), SI", sat, R0,
            lambda: gyrostat.stability_map(sat, R0, th_b, k2=kb, grid=False))

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
