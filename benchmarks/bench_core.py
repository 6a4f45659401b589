"""Cost of the elliptic core against raw SciPy, with the accuracy each side reaches (run on demand).

The raw SciPy side gets the parameter ``m = k**2`` ready made (``scipy.special.ellipk(m)``, ``ellipe(m)``,
``ellipj(u, m)``); the library side takes the modulus ``k`` (or ``mc``) and validates it.  Times are the
best of several interleaved repetitions; the ratios (library / SciPy) are what to read.  Accuracy: the
largest error against mpmath (40 digits) on a sample of the same inputs -- relative for K, E, dn,
absolute for sn, cn, am.

The integrators (``integrators``): the DOP853 on Python floats (``integrate(engine='python')``) against
``solve_ivp(method='DOP853')`` on the same system and tolerances (a 2-state pendulum with a terminal and a
non-terminal event and 401 output points; a 7-state chain of coupled pendulums; a single averaged run of
``lagrange`` and of ``euler_poinsot``, which run on it), and the vectorised DOP853
(``integrate_batch``) on one member and on 1000 members against a loop of the float integrator. CPU
seconds of this process, the best of a few repeats.

Run: python benchmarks/bench_core.py [elliptic] [integrators]   (both by default)
"""

from __future__ import annotations

import math
import sys
import time
from functools import partial

import mpmath
import numpy as np
from common import cpu_time
from scipy import special
from scipy.integrate import solve_ivp

from rigidbody.core import averaging, elliptic
from rigidbody.core.batch import integrate_batch
from rigidbody.core.ode import Event, integrate

N = 10**6
SAMPLE = 300


def best_times(fns: dict, repeat: int = 7, number: int = 1) -> dict:
    """Best wall time per call of each function, the functions interleaved (a noisy machine hits both)."""
    best = dict.fromkeys(fns, np.inf)
    for _ in range(repeat):
        for name, f in fns.items():
            t0 = time.perf_counter()
            for _ in range(number):
                f()
            best[name] = min(best[name], (time.perf_counter() - t0) / number)
    return best


def _mp_m(k=None, mc=None):
    return mpmath.mpf(k) ** 2 if mc is None else 1 - mpmath.mpf(mc)


def err_complete(fun, values, idx, m_of):
    """Max relative error of K or E on the sample."""
    ref = {"K": mpmath.ellipk, "E": mpmath.ellipe}
    out = {}
    with mpmath.workdps(40):
        for name, vals in values.items():
            r = np.array([float(ref[fun](m_of(i))) for i in idx])
            out[name] = float(np.max(np.abs(vals[idx] - r) / r))
    return out


def err_jacobi(results, u, idx, m_of):
    """Max absolute error of sn, cn, am and relative error of dn on the sample, per side."""
    out = {}
    with mpmath.workdps(40):
        refs = []
        for i in idx:
            m = m_of(i)
            x = mpmath.mpf(float(u[i]))
            refs.append([float(mpmath.ellipfun(f, x, m=m)) for f in ("sn", "cn", "dn")]
                        + [float(mpmath.ellipf(0, m) if x == 0 else _mp_am(x, m))])
        refs = np.array(refs)
    for name, (s, c, d, a) in results.items():
        out[name] = (float(np.max(np.abs(s[idx] - refs[:, 0]))), float(np.max(np.abs(c[idx] - refs[:, 1]))),
                     float(np.max(np.abs(d[idx] - refs[:, 2]) / refs[:, 2])),
                     float(np.max(np.abs(a[idx] - refs[:, 3]))))
    return out


def _mp_am(x, m):
    """am(x) continuous: the inverse of F, found from sn, cn and the period count."""
    K = mpmath.ellipk(m)
    j = mpmath.nint(x / (2 * K))
    s, c = mpmath.ellipfun("sn", x, m=m), mpmath.ellipfun("cn", x, m=m)
    par = 1 if int(j) % 2 == 0 else -1
    return j * mpmath.pi + mpmath.atan2(par * s, abs(par * c))


def elliptic_core() -> None:
    rng = np.random.default_rng(0)
    idx = rng.choice(N, SAMPLE, replace=False)
    print(f"elliptic core on {N:,} elements: library / raw SciPy (best of interleaved runs), max error vs mpmath")

    # ---- complete integrals, k uniform on [0, 0.999] (1 - k^2 >= 2e-3)
    k = rng.uniform(0.0, 0.999, N)
    m = k * k
    t = best_times({"ellipk": lambda: special.ellipk(m), "K": lambda: elliptic.K(k),
                    "ellipe": lambda: special.ellipe(m), "E": lambda: elliptic.E(k)})
    ek = err_complete("K", {"scipy": special.ellipk(m), "ours": elliptic.K(k)}, idx, lambda i: _mp_m(k[i]))
    ee = err_complete("E", {"scipy": special.ellipe(m), "ours": elliptic.E(k)}, idx, lambda i: _mp_m(k[i]))
    print(f"  K(k)  {t['K'] * 1e3:7.1f} ms vs ellipk(m) {t['ellipk'] * 1e3:7.1f} ms: {t['K'] / t['ellipk']:.2f}x"
          f"   rel. error: ours {ek['ours']:.1e}, scipy {ek['scipy']:.1e}")
    print(f"  E(k)  {t['E'] * 1e3:7.1f} ms vs ellipe(m) {t['ellipe'] * 1e3:7.1f} ms: {t['E'] / t['ellipe']:.2f}x"
          f"   rel. error: ours {ee['ours']:.1e}, scipy {ee['scipy']:.1e}")

    # ---- Jacobi functions, u uniform on [-40, 40], k uniform on [0, 0.99] (away from the separatrix)
    k = rng.uniform(0.0, 0.99, N)
    m = k * k
    u = rng.uniform(-40.0, 40.0, N)
    fns = {"ellipj": lambda: special.ellipj(u, m), "jacobi": lambda: elliptic.jacobi(u, k),
           "sn": lambda: elliptic.sn(u, k), "cn": lambda: elliptic.cn(u, k), "dn": lambda: elliptic.dn(u, k),
           "ellipj k=0.9": lambda: special.ellipj(u, 0.81), "jacobi k=0.9": lambda: elliptic.jacobi(u, 0.9)}
    t = best_times(fns, repeat=5)
    ej = err_jacobi({"ours": elliptic.jacobi(u, k), "scipy": special.ellipj(u, m)}, u, idx,
                    lambda i: _mp_m(k[i]))
    for name in ("jacobi", "sn", "cn", "dn"):
        print(f"  {name + '(u, k)':13s} {t[name] * 1e3:7.1f} ms vs ellipj(u, m) {t['ellipj'] * 1e3:7.1f} ms: "
              f"{t[name] / t['ellipj']:.2f}x")
    print(f"  jacobi(u, 0.9) {t['jacobi k=0.9'] * 1e3:6.1f} ms vs ellipj(u, 0.81) {t['ellipj k=0.9'] * 1e3:7.1f} ms: "
          f"{t['jacobi k=0.9'] / t['ellipj k=0.9']:.2f}x")
    for name, (es, ec, ed, ea) in ej.items():
        print(f"    error ({name:5s}): sn {es:.1e}, cn {ec:.1e} (abs), dn {ed:.1e} (rel), am {ea:.1e} (abs)")

    # ---- near the separatrix, mc = 1 - k^2 in [1e-12, 1e-3] given exactly; raw ellipj gets m = 1 - mc
    mc = 10.0 ** rng.uniform(-12, -3, N)
    u = rng.uniform(-1.0, 1.0, N) * 5 * elliptic.K(mc=mc)
    t = best_times({"ellipj": lambda: special.ellipj(u, 1 - mc), "jacobi": lambda: elliptic.jacobi(u, mc=mc)},
                   repeat=3)
    ej = err_jacobi({"ours": elliptic.jacobi(u, mc=mc), "scipy": special.ellipj(u, 1 - mc)}, u, idx,
                    lambda i: _mp_m(mc=mc[i]))
    print(f"  near the separatrix (1 - k^2 in [1e-12, 1e-3], |u| < 5K): jacobi(u, mc=mc) {t['jacobi'] * 1e3:.1f} ms "
          f"vs ellipj(u, 1 - mc) {t['ellipj'] * 1e3:.1f} ms: {t['jacobi'] / t['ellipj']:.2f}x")
    for name, (es, ec, ed, ea) in ej.items():
        print(f"    error ({name:5s}): sn {es:.1e}, cn {ec:.1e} (abs), dn {ed:.1e} (rel), am {ea:.1e} (abs)")

    # ---- incomplete integrals (SciPy: ellipkinc / ellipeinc), phi uniform on [-7, 7]
    k = rng.uniform(0.0, 0.999, N)
    m = k * k
    phi = rng.uniform(-7.0, 7.0, N)
    t = best_times({"ellipkinc": lambda: special.ellipkinc(phi, m), "F": lambda: elliptic.F(phi, k),
                    "ellipeinc": lambda: special.ellipeinc(phi, m), "Einc": lambda: elliptic.Einc(phi, k)}, repeat=3)
    with mpmath.workdps(40):
        rf = np.array([float(mpmath.ellipf(float(phi[i]), _mp_m(k[i]))) for i in idx])
        re = np.array([float(mpmath.ellipe(float(phi[i]), _mp_m(k[i]))) for i in idx])
    errs = {n: float(np.max(np.abs(v[idx] - r) / np.abs(r))) for n, v, r in (
        ("F", elliptic.F(phi, k), rf), ("ellipkinc", special.ellipkinc(phi, m), rf),
        ("Einc", elliptic.Einc(phi, k), re), ("ellipeinc", special.ellipeinc(phi, m), re))}
    print(f"  F(phi, k) {t['F'] * 1e3:.1f} ms vs ellipkinc {t['ellipkinc'] * 1e3:.1f} ms: "
          f"{t['F'] / t['ellipkinc']:.2f}x   rel. error: ours {errs['F']:.1e}, scipy {errs['ellipkinc']:.1e}")
    print(f"  Einc(phi, k) {t['Einc'] * 1e3:.1f} ms vs ellipeinc {t['ellipeinc'] * 1e3:.1f} ms: "
          f"{t['Einc'] / t['ellipeinc']:.2f}x   rel. error: ours {errs['Einc']:.1e}, scipy {errs['ellipeinc']:.1e}")

    # ---- scalar calls (Python float in, float out), as in the right-hand side of an integrator
    print("scalar calls (Python float in, float out), per call:")
    t = best_times({"ellipk": lambda: special.ellipk(0.81), "K": lambda: elliptic.K(0.9),
                    "ellipe": lambda: special.ellipe(0.81), "E": lambda: elliptic.E(0.9),
                    "ellipj": lambda: special.ellipj(1.3, 0.81), "jacobi": lambda: elliptic.jacobi(1.3, 0.9),
                    "jacobi mc": lambda: elliptic.jacobi(1.3, mc=0.19),
                    "jacobi near": lambda: elliptic.jacobi(11.3, mc=1e-6),
                    "jacobi sep": lambda: elliptic.jacobi(11.3, mc=1e-12)}, repeat=5, number=2000)
    us = {n: v * 1e6 for n, v in t.items()}
    print(f"  K(0.9) {us['K']:.2f} us vs ellipk {us['ellipk']:.2f} us ({us['K'] / us['ellipk']:.1f}x); "
          f"E(0.9) {us['E']:.2f} us vs ellipe {us['ellipe']:.2f} us ({us['E'] / us['ellipe']:.1f}x)")
    print(f"  jacobi(1.3, 0.9) {us['jacobi']:.2f} us, jacobi(1.3, mc=0.19) {us['jacobi mc']:.2f} us vs ellipj "
          f"{us['ellipj']:.2f} us ({us['jacobi'] / us['ellipj']:.1f}x); near the separatrix jacobi(11.3, mc=1e-6) "
          f"{us['jacobi near']:.1f} us, mc=1e-12 (complementary-nome series) {us['jacobi sep']:.1f} us")

    print("period averages (core.averaging):")
    for mcv in (0.5, 1e-4, 1e-10):
        nn = averaging.n_nodes(mc=mcv)
        t = best_times({"avg": lambda mcv=mcv: averaging.sn2_average(lambda x: x * x, -0.2, 0.7, mc=mcv)},
                       repeat=5, number=200)
        print(f"  sn2_average at 1-k^2={mcv:g}: {nn:4d} nodes, {t['avg'] * 1e6:7.1f} us per call")


# ------------------------------------------------------------------------------------------------ integrators
def pendulum(t, y):
    return [y[1], -math.sin(y[0])]


def chain(t, y):
    """Seven pendulums coupled to their neighbours by springs (a 7-state first-order system: angles only, each
    driven by its neighbours' differences, so that every state enters every few stages)."""
    return [-math.sin(y[i]) + 0.3 * ((y[i - 1] if i else 0.0) - 2.0 * y[i] + (y[i + 1] if i < 6 else 0.0))
            + 0.1 * math.cos(t) for i in range(7)]


PEND_EVENTS = [Event(lambda t, y: y[0], "zero", terminal=False),
               Event(lambda t, y: y[1] - 1.7, "fast", terminal=True, direction=1.0)]  # beyond the top speed 1.68


def _scalar_case(name: str, fun, span, y0, kw: dict) -> None:
    """The float integrator against solve_ivp on one system."""
    wrapped = []
    for ev in kw.get("events", ()):
        def g(t, y, ev=ev):
            return ev.fun(t, y)
        g.terminal, g.direction = ev.terminal, ev.direction
        wrapped.append(g)
    skw = dict(t_eval=kw.get("t_eval"), events=wrapped or None)
    ours = partial(integrate, fun, span, y0, rtol=1e-10, atol=1e-12, engine="python", **kw)
    t_py = cpu_time(ours, repeat=5)
    t_sp = cpu_time(partial(solve_ivp, fun, span, y0, method="DOP853", rtol=1e-10, atol=1e-12, **skw), repeat=3)
    run = ours()
    print(f"  integrate(engine='python') {name}: {t_py * 1e3:.2f} ms ({run.nfev} evaluations, "
          f"{t_py / run.nfev * 1e6:.2f} us each) vs solve_ivp {t_sp * 1e3:.2f} ms")
    print(f"RATIO integrate(engine='python') vs solve_ivp, {name}: {t_sp / t_py:.2f}x faster")


def spiral(t, y, a, w):
    return np.stack([-a * y[:, 0] + w * y[:, 1], -w * y[:, 0] - a * y[:, 1]], axis=1)


def spiral_one(t, y, a, w):
    return [-a * y[0] + w * y[1], -w * y[0] - a * y[1]]


def _loop(a, w, tb, n_loop):
    ev = [Event(lambda t, y, a, w: y[0] - 0.05, "small", terminal=True, direction=-1.0)]
    return [integrate(spiral_one, (0.0, 30.0), [1.0, 0.0], t_eval=tb, args=(a[i], w[i]), events=ev, engine="python")
            for i in range(n_loop)]


def _batch_case(B: int, rng) -> None:
    """integrate_batch on B members against a loop of the float integrator (at most 50 runs, scaled)."""
    a, w = rng.uniform(0.05, 0.2, B), rng.uniform(0.5, 3.0, B)
    tb = np.linspace(0.0, 30.0, 61)
    ev = [Event(lambda t, y, a, w: y[:, 0] - 0.05, "small", terminal=True, direction=-1.0)]
    t_b = cpu_time(partial(integrate_batch, spiral, (0.0, 30.0), np.tile([1.0, 0.0], (B, 1)), t_eval=tb,
                           args=(a, w), events=ev), repeat=3)
    n_loop = min(B, 50)
    t_l = cpu_time(partial(_loop, a, w, tb, n_loop), repeat=3) * B / n_loop
    print(f"  integrate_batch, {B} member(s), spiral with a terminal event: {t_b * 1e3:.2f} ms vs a loop of "
          f"integrate(engine='python') {t_l * 1e3:.2f} ms")
    print(f"RATIO integrate_batch of {B} vs a loop of integrate(engine='python'): {t_l / t_b:.2f}x")


def integrators() -> None:
    print("integrators: CPU time per run (best of repeats)")
    _scalar_case("pendulum, 2 states, 2 events, 401 samples", pendulum, (0.0, 200.0), [2.0, 0.0],
                 dict(t_eval=np.linspace(0.0, 200.0, 401), events=PEND_EVENTS))
    _scalar_case("coupled chain, 7 states", chain, (0.0, 100.0), [0.1 * (i + 1) for i in range(7)], {})

    from rigidbody import euler_poinsot as ep
    from rigidbody import lagrange as lg

    t_lg = cpu_time(partial(lg.paper_solution, 2, n_out=101, tau_end=100.0), repeat=5)
    print(f"  lagrange.paper_solution(2), tau in [0, 100] (one averaged run on floats): {t_lg * 1e3:.2f} ms")
    t_ep = cpu_time(partial(ep.averaged, ep.Body(3.2, 2.6, 1.67), np.diag([2.322, 1.31, 1.425]), 0.0, G0=1.0,
                            k2_0=0.9, delta0=math.pi / 4, lam0=math.pi / 4, tau_span=(0.0, 30.0)), repeat=5)
    print(f"  euler_poinsot.averaged closed forms, tau in [0, 30] (one run on floats): {t_ep * 1e3:.2f} ms")
    rng = np.random.default_rng(0)
    for B in (1, 1000):
        _batch_case(B, rng)


def main(argv: list[str]) -> None:
    parts = argv or ["elliptic", "integrators"]
    if "elliptic" in parts:
        elliptic_core()
    if "integrators" in parts:
        integrators()


if __name__ == "__main__":
    main(sys.argv[1:])
