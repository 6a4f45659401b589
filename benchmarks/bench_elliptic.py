"""Jacobi functions and elliptic integrals: accuracy in ulp against mpmath and cost against SciPy (on demand).

Accuracy: the largest error, in ulp of the exact value (mpmath, 50 digits, more for tiny ``mc``), of
``rigidbody.core.elliptic`` and of ``scipy.special`` on seeded samples of four regions -- ``u`` uniform over
+-10 K for the parameter m in [0, 0.95] (from ``k``), the same for 1 - m log-uniform down to 1e-300 (from
``mc``), ``u`` within 1e-15..1e-3 relative of a multiple n K (|n| <= 10) and the float nearest to n K -- and
K, E, F, E(phi) on random moduli. SciPy gets ``m`` itself (``ellipj(u, m)``, ``ellipk(m)``...): for it the
exact value is taken at its own float ``m``, so each side is judged on its own inputs.

Cost: CPU time per element on 10^6 arguments, the library against ``scipy.special.ellipj`` (best of
interleaved repeats), with one modulus for all elements (a motion: u = omega t) and with a modulus per
element; and per call on one Python float. Ratios (library / SciPy) are printed as ``RATIO`` lines.

Run: python benchmarks/bench_elliptic.py [--sample N]
"""

from __future__ import annotations

import math
import os
import sys

import mpmath as mp
import numpy as np
from common import cpu_time
from scipy import special

from rigidbody.core import elliptic as ell

N = 10**6


def ulps(got: float, ref: mp.mpf) -> float:
    """``|got - ref|`` in ulp of ``ref`` (0 where both are 0)."""
    if ref == 0:
        return 0.0 if got == 0 else math.inf
    return float(abs(mp.mpf(float(got)) - ref) / mp.ldexp(1, int(mp.floor(mp.log(abs(ref), 2))) - 52))


def exact_jacobi(u: float, m: mp.mpf) -> tuple[list, mp.mpf]:
    """sn, cn, dn, am and K at the float ``u`` for the parameter ``m`` (an mpf at the working precision)."""
    kk = mp.ellipk(m)
    uu = mp.mpf(u)
    s, c, d = (mp.ellipfun(name, uu, m=m) for name in ("sn", "cn", "dn"))
    j = mp.nint(uu / (2 * kk))
    sign = -1 if j % 2 else 1
    return [s, c, d, j * mp.pi + mp.atan2(sign * s, sign * c)], kk


def region_points(rng: np.random.Generator, n: int, region: str) -> list[tuple[float, float]]:
    """``(u, mc)`` points of a region (mc as the library receives it; SciPy gets m = 1 - mc)."""
    out = []
    while len(out) < n:
        mc = float(10.0 ** rng.uniform(-300, math.log10(0.05))) if region == "m near 1" else \
            float(1.0 - rng.uniform(0.0, 0.95))
        with mp.workdps(60 - min(0, math.floor(math.log10(mc)))):
            kk = mp.ellipk(1 - mp.mpf(mc))
        jn = int(rng.integers(-10, 11))
        if region in ("m in [0, 0.95]", "m near 1"):
            u = float(rng.uniform(-10, 10) * kk)
        elif region == "near zeros":
            u = float(jn * kk * (1 + 10.0 ** rng.uniform(-15, -3) * rng.choice([-1, 1])))
        else:
            u = float(jn * kk)
        if u != 0.0:
            out.append((u, mc))
    return out


def jacobi_accuracy(n: int) -> None:
    rng = np.random.default_rng(2026)
    print(f"Jacobi functions: max error in ulp against mpmath, {n} points per region")
    print(f"{'region':<22}{'side':<8}{'sn':>10}{'cn':>10}{'dn':>10}{'am':>10}")
    for region in ("m in [0, 0.95]", "m near 1", "near zeros", "nearest float to nK"):
        pts = region_points(rng, n, region)
        u = np.array([p[0] for p in pts])
        mc = np.array([p[1] for p in pts])
        ours = ell.jacobi(u, mc=mc)
        theirs = special.ellipj(u, 1.0 - mc)
        worst = {"ours": np.zeros(4), "scipy": np.zeros(4)}
        bad = {side: sum(int(not np.all(np.isfinite([v[i] for v in vals]))) for i in range(len(pts)))
               for side, vals in (("ours", ours), ("scipy", theirs))}
        for i, (ui, mci) in enumerate(pts):
            with mp.workdps(60 - min(0, math.floor(math.log10(mci)))):
                ref, _ = exact_jacobi(ui, 1 - mp.mpf(mci))
                ref_sc, _ = exact_jacobi(ui, mp.mpf(float(1.0 - mci)))
            # (fmax: a NaN of SciPy's is counted apart, not as the maximum)
            worst["ours"] = np.fmax(worst["ours"], [ulps(ours[t][i], ref[t]) for t in range(4)])
            worst["scipy"] = np.fmax(worst["scipy"], [ulps(theirs[t][i], ref_sc[t]) for t in range(4)])
        for side, w in worst.items():
            note = f"   ({bad[side]} points not finite)" if bad[side] else ""
            print(f"{region:<22}{side:<8}" + "".join(f"{x:>10.3g}" for x in w) + note)


def integrals_accuracy(n: int) -> None:
    rng = np.random.default_rng(2027)
    k = rng.uniform(0, 1, n)
    phi = rng.uniform(-7, 7, n)
    m = k * k
    rows = {"K": (ell.K(k), special.ellipk(m), lambda i, mm: mp.ellipk(mm)),
            "E": (ell.E(k), special.ellipe(m), lambda i, mm: mp.ellipe(mm)),
            "F": (ell.F(phi, k), special.ellipkinc(phi, m), lambda i, mm: mp.ellipf(phi[i], mm)),
            "E(phi)": (ell.Einc(phi, k), special.ellipeinc(phi, m), lambda i, mm: mp.ellipe(phi[i], mm))}
    print(f"\ncomplete and incomplete integrals: max error in ulp against mpmath, {n} random k (phi in +-7)")
    with mp.workdps(50):
        for name, (ours, theirs, ref) in rows.items():
            w_ours = max(ulps(ours[i], ref(i, mp.mpf(k[i]) ** 2)) for i in range(n))
            w_sc = max(ulps(theirs[i], ref(i, mp.mpf(float(m[i])))) for i in range(n))
            print(f"{name:<8} ours {w_ours:8.3g}   scipy {w_sc:8.3g}")


def cost() -> None:
    print(f"\nmachine load (1, 5, 15 min): {' '.join(f'{x:.1f}' for x in os.getloadavg())} on {os.cpu_count()} cores")
    rng = np.random.default_rng(2028)
    k0 = math.sqrt(0.7)
    u = rng.uniform(-10, 10, N) * ell.K(k0)
    ks = np.sqrt(rng.uniform(0, 0.999, N))
    ms = ks * ks
    print(f"\ncost on {N:,} elements (CPU seconds, best of interleaved repeats)")
    for label, ours, theirs in (("one modulus", lambda: ell.jacobi(u, k0), lambda: special.ellipj(u, 0.7)),
                                ("a modulus per element", lambda: ell.jacobi(u, ks), lambda: special.ellipj(u, ms))):
        t_ours, t_sc = math.inf, math.inf
        for _ in range(3):
            t_ours = min(t_ours, cpu_time(ours, repeat=1))
            t_sc = min(t_sc, cpu_time(theirs, repeat=1))
        print(f"{label:<24} library {t_ours:7.3f} s  scipy.special.ellipj {t_sc:7.3f} s")
        print(f"RATIO jacobi / ellipj, {label}: {t_ours / t_sc:.2f}")
    # each argument the float nearest to n K of its own modulus: the reduction recomputes the distance with
    # K to 2^-160 (an integer mean per modulus), the worst case per element
    n0 = 10**4
    kz = np.sqrt(rng.uniform(0, 0.999, n0))
    uz = rng.integers(1, 11, n0) * ell.K(kz)
    t_ours = min(cpu_time(lambda: ell.jacobi(uz, kz), repeat=1) for _ in range(3))
    t_sc = min(cpu_time(lambda: special.ellipj(uz, kz * kz), repeat=1) for _ in range(3))
    print(f"{'at n K, a modulus each':<24} library {t_ours / n0 * 1e6:7.2f} us  scipy.special.ellipj "
          f"{t_sc / n0 * 1e6:7.3f} us an element")
    print(f"RATIO jacobi / ellipj, at n K with a modulus each: {t_ours / t_sc:.0f}")
    one = cpu_time(lambda: ell.jacobi(1.3, 0.6), repeat=5, number=20000)
    sc = cpu_time(lambda: special.ellipj(1.3, 0.36), repeat=5, number=20000)
    print(f"one Python float: library {one * 1e6:.2f} us a call, scipy.special.ellipj {sc * 1e6:.2f} us")
    print(f"RATIO jacobi / ellipj, one float: {one / sc:.2f}")


def main(argv: list[str]) -> None:
    n = int(argv[argv.index("--sample") + 1]) if "--sample" in argv else 100
    jacobi_accuracy(n)
    integrals_accuracy(n)
    cost()


if __name__ == "__main__":
    main(sys.argv[1:])
