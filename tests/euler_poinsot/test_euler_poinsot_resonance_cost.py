"""The resonance check of an averaged run: the crossings and predicted jumps against a per-crossing reference,
the Parseval bound of the resonant coefficients, and a cost that does not grow with the crossings near symmetry."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from scipy.optimize import brentq

from rigidbody import euler_poinsot as ep
from rigidbody.euler_poinsot import _resonance
from rigidbody.euler_poinsot._engine import State
from rigidbody.euler_poinsot._resonance import harmonic
from rigidbody.euler_poinsot._segment import rotation_number

BODY = ep.Body(3.2, 2.6, 1.67)
CASE2 = np.diag([0.919, 5.228, 1.666])
B2 = ep.Body(0.55, 0.35, 0.30)
NEAR = ep.Body(0.55, 0.3005727, 0.3005723)  # A2 - A3 = 4e-7: rotation number ~2000


def reference(sol, body, torque, eps, kind="max", sigma=1, nu0=0.0, n_grid=300, upto=None):
    """The resonance check one crossing at a time, as it was computed before the bound: the crossings of
    j rho = N (j = 1, 2) on a fine grid of the run's dense output (not the integrator's steps), each time by
    brentq, the rate of rho from averaged_rates, the period of the motion from EulerPoinsot and the coefficient
    from one harmonic at the crossing. ``upto``: only the crossings with these indices (in time order)."""
    t = np.linspace(sol.tau[0], sol.tau[-1], n_grid)
    rho = rotation_number(body, kind, np.clip(sol.sol(t)[1], 0.0, 0.99))  # the search stops at K2_SPIN_CAP = 0.99

    def k2_at(x):
        return min(max(float(sol.sol(x)[1]), 0.0), 1.0 - 1e-12)

    found = []
    for j in (1, 2):
        for i in range(n_grid - 1):
            lo, hi = sorted((j * rho[i], j * rho[i + 1]))
            for N in range(math.floor(lo) + 1, math.floor(hi) + 1):
                ts = brentq(lambda x, j=j, N=N: j * rotation_number(body, kind, k2_at(x)) - N, t[i], t[i + 1],
                            xtol=1e-13)
                found.append((ts, j, N))
    found.sort()
    out = []
    for k, (ts, j, N) in enumerate(found):
        if upto is not None and k not in upto:
            continue
        y = sol.sol(ts)
        G, k2, n = float(y[0]), float(y[1]), y[2:5] / np.linalg.norm(y[2:5])
        nu = nu0 + (ts - sol.tau[0]) / eps
        dk2 = ep.averaged_rates(body, torque, G, k2, math.acos(n[2]), math.atan2(n[1], n[0]), nu, kind=kind,
                                sigma=sigma)["dk2"]
        h = 1e-6 * k2
        rate = abs(j * (rotation_number(body, kind, k2 + h) - rotation_number(body, kind, k2 - h)) / (2 * h) * dk2)
        P = ep.EulerPoinsot(body, G, k2, kind, sigma).period
        st = State(body, kind, sigma, G, k2, n, nu, ep.Orbit(0.0))
        c = harmonic(torque, st, j, -N)
        amp = 2 * eps * math.sqrt(P / rate)
        par = complex(n @ c[0:3])
        jumps = [amp * abs(par) / G, amp * abs(complex(c[3])) / st.T, amp * np.linalg.norm(c[0:3] - par * n) / G]
        out.append({"tau": ts, "j": j, "m": -N, "jump": max(jumps), "jump_G": jumps[0], "jump_T": jumps[1],
                    "jump_n": jumps[2]})
    return out


def pairs(new, ref):
    """The two lists matched crossing by crossing (j = 1 at rho = N and j = 2 at 2N share a time: which comes
    first in the reference is rounding), after checking that they list the same crossings."""
    assert all(a["tau"] <= b["tau"] for a, b in itertools.pairwise(new))  # the run lists them in time order
    new, ref = (sorted(x, key=lambda r: (r["j"], r["m"], r["tau"])) for x in (new, ref))
    assert [(r["j"], r["m"]) for r in new] == [(r["j"], r["m"]) for r in ref]
    return zip(new, ref)


def assert_same_crossings(new, ref):
    for a, b in pairs(new, ref):
        # both root searches converge to ~1e-12 on the same dense output
        assert a["tau"] == pytest.approx(b["tau"], rel=0, abs=1e-9)
        for key in ("jump", "jump_G", "jump_T", "jump_n"):
            # the same coefficient at states 1e-12 apart and rates from the same means (closed forms or the
            # engine at quad_tol 1e-12): 1e-6 relative is loose; 1e-12 absolute covers the jumps of coefficients
            # that vanish (rounding of a 2-D FFT, ~1e-16 of the torque's effect, times amplitudes below 1)
            assert a[key] == pytest.approx(b[key], rel=1e-6, abs=1e-12), (a, b, key)


CASES = {
    # the paper's body, drag case 2 with gravity: k2 falls from 0.9 through rho = 5, 4, 3 (a jump of the
    # direction of G of 0.5 eps at rho = 3) and the half-integers of j = 2
    "paper case 2": (BODY, ep.LinearDrag(CASE2) + ep.GravityGradient(BODY), 0.02, dict(k2_0=0.9, tau_span=(0, 1))),
    # rotation about the axis of the smallest moment, a body-fixed torque (not odd in omega) and drag
    "constant torque, kind min": (B2, ep.ConstantTorque([0.05, 0.02, 0.1]) + ep.LinearDrag(np.diag([0.1, 0.2, 0.3])),
                                  0.02, dict(k2_0=0.5, kind="min", tau_span=(0, 1))),
}


@pytest.mark.parametrize("name", list(CASES))
def test_crossings_and_jumps_equal_the_per_crossing_reference(name):
    body, tq, eps, kw = CASES[name]
    sol = ep.averaged(body, tq, eps, **kw)
    assert sol.status == 0
    ref = reference(sol, body, tq, eps, kind=kw.get("kind", "max"))
    assert len(ref) >= 6  # the cases cross resonances, some with jumps well above rounding
    assert max(r["jump"] for r in ref) > 1e-6
    assert_same_crossings(sol.resonances, ref)
    assert not any(r["bound"] for r in sol.resonances)  # low orders: every coefficient computed


def test_a_slow_passage_stops_where_the_reference_predicts_a_large_jump():
    # The slow passage of test_euler_poinsot_engine_vs_full: k2 creeps through rho = 3. The reference, run on the
    # whole evolution (check off), finds the first crossing whose predicted jump exceeds resonance_tol; the checked
    # run must end there, having listed the same crossings up to it.
    def k2_star(i22):
        eq = ep.k2_equilibria(BODY, np.diag([2.322, i22, 1.425]))
        return next(k for k, s in eq if s == "stable" and k > 0)

    drag = 10.0 * np.diag([2.322, brentq(lambda x: k2_star(x) - 0.507, 1.31, 1.35), 1.425])
    c = -ep.drag_rates(BODY, drag, 1.0, 0.507)[0]

    def hold_G(omega, C, nu):
        return c * np.asarray(omega) * BODY.A

    tq = ep.LinearDrag(drag) + ep.GravityGradient(BODY) + hold_G
    kw = dict(k2_0=0.512, tau_span=(0, 1.5), drift_tol=None)
    free = ep.averaged(BODY, tq, 0.04, resonance_tol=None, **kw)
    ref = reference(free, BODY, tq, 0.04)
    first = next(k for k, r in enumerate(ref) if r["jump"] > 0.05)
    checked = ep.averaged(BODY, tq, 0.04, **kw)
    assert checked.status == 1 and checked.event == "resonance"
    cut = ref[first]["tau"]
    assert checked.tau[-1] == pytest.approx(cut, rel=0, abs=1e-9)  # root searches, as above
    # rho = 3 is also 2 rho = 6, at the same time: whether the reference's separate root search puts that one
    # before or after the cut is rounding; the run lists both
    assert_same_crossings(checked.resonances, [r for r in ref if r["tau"] <= cut + 1e-9])


def test_parseval_bound_equals_the_sum_over_all_orders():
    # sum_m |c_jm|^2 = <|W_j|^2> over the period (Parseval): the bound is the root of the right side, so the sum
    # of the squares of the coefficients computed one by one must equal its square. At k2 = 0.7 the
    # coefficients of this smooth torque fall below 1e-15 of the largest by |m| = 40, so the orders up to 45
    # hold all but rounding; both means are spectrally accurate: 1e-9 relative is loose.
    tq = ep.ViscousCavity(B2, [0.03, 0.19, 0.12]) + ep.GravityGradient(B2) + ep.ConstantTorque([0.1, -0.05, 0.2])
    for kind, sigma in (("max", 1), ("min", -1)):
        n = np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8])
        st = State(B2, kind, sigma, 1.3, 0.7, n, 0.4, ep.Orbit(0.0))
        bound = _resonance.harmonic_bound(tq, st)
        for j in (1, 2):
            c = np.array([harmonic(tq, st, j, m) for m in range(-45, 46)])
            par = c[:, 0:3] @ n
            sums = (np.sum(np.abs(par) ** 2) / st.G**2, np.sum(np.abs(c[:, 3]) ** 2) / st.T**2,
                    np.sum(np.abs(c[:, 0:3] - par[:, None] * n) ** 2) / st.G**2)
            assert sums[0] + sums[2] > 1e-6  # the harmonic j is there (a zero bound would pass trivially)
            for s, b in zip(sums, bound[j - 1]):
                assert s == pytest.approx(b**2, rel=1e-9, abs=1e-30)


def test_near_symmetric_cost_does_not_grow_with_the_crossings(monkeypatch):
    # Near A2 = A3 the rotation number is ~2000 and a run crosses one order per 3e-5 of tau; one coefficient per
    # crossing (a grid of 8 x 16000 nodes each) cost seconds over tau in [0, 0.002]. Counting the evaluations
    # (not the time): ten times the crossings, the same number of coefficients (none) and at most one bound per
    # node of the integrator (the ends of the steps that hold crossings).
    calls = {"harmonic": 0, "bound": 0}
    real_harmonic, real_bound = _resonance.harmonic, _resonance.harmonic_bound

    def counted_harmonic(*a):
        calls["harmonic"] += 1
        return real_harmonic(*a)

    def counted_bound(*a):
        calls["bound"] += 1
        return real_bound(*a)

    monkeypatch.setattr(_resonance, "harmonic", counted_harmonic)
    monkeypatch.setattr(_resonance, "harmonic_bound", counted_bound)
    tq = ep.ViscousCavity(NEAR, [0.03, 0.19, 0.12])
    seen = []
    for t1 in (0.002, 0.02):
        calls.update(harmonic=0, bound=0)
        sol = ep.averaged(NEAR, tq, 4e-4, k2_0=0.9, tau_span=(0, t1))  # output at the integrator's nodes
        assert sol.status == 0
        assert all(r["bound"] and r["jump"] * _resonance.MARGIN <= 0.05 for r in sol.resonances)
        assert calls["harmonic"] == 0 and 2 <= calls["bound"] <= sol.time.size <= 10
        seen.append(len(sol.resonances))
    assert seen[0] >= 50 and seen[1] >= 8 * seen[0]  # (rho falls by ~20 per 0.002 of tau)


def test_near_symmetric_bounds_hold_and_an_unproven_crossing_is_computed():
    # The bounded jumps (Parseval, at the ends of the step) must not be below the jumps of the coefficients the
    # reference computes at the crossings (the check trusts the bound times MARGIN; here it holds without).
    # And where a resonance_tol is too small for the bound to prove a crossing harmless, the run computes its
    # coefficient: then it agrees with the reference crossing by crossing.
    tq = ep.ViscousCavity(NEAR, [0.03, 0.19, 0.12])
    kw = dict(k2_0=0.9, tau_span=(0, 1e-4))
    sol = ep.averaged(NEAR, tq, 4e-4, **kw)
    assert sol.status == 0 and len(sol.resonances) >= 3 and all(r["bound"] for r in sol.resonances)
    ref = reference(sol, NEAR, tq, 4e-4, n_grid=20)
    for a, b in pairs(sol.resonances, ref):
        for key in ("jump_G", "jump_T", "jump_n"):
            assert b[key] <= a[key]
    # bounds ~1e-6 for j = 1: none proves harmless; this torque has no j = 2 harmonic (its effect C M is linear
    # in the attitude), bounds ~1e-22 there, which do
    strict = ep.averaged(NEAR, tq, 4e-4, resonance_tol=1e-8, **kw)
    assert strict.status == 0
    assert all(r["bound"] == (r["j"] == 2) for r in strict.resonances)
    assert_same_crossings([r for r in strict.resonances if r["j"] == 1], [r for r in ref if r["j"] == 1])
    assert all(b["jump"] <= a["jump"] for a, b in pairs(strict.resonances, ref) if a["j"] == 2)


def test_an_order_too_high_to_compute_whose_bound_exceeds_the_tolerance_ends_the_run(monkeypatch):
    # A2 - A3 = 4e-9: the rotation number is ~20000 and the coefficient of order 20000 would take a grid of
    # 8 x 160000 nodes. With a resonance_tol below the Parseval bound (~1e-8 here) nothing shows the crossing
    # harmless, so the run must end there with a status and a message that says so, and not compute it.
    calls = []
    real = _resonance.harmonic
    monkeypatch.setattr(_resonance, "harmonic", lambda *a: calls.append(a) or real(*a))
    body = ep.Body(0.55, 0.300000004, 0.3)
    tq = ep.ViscousCavity(body, [0.03, 0.19, 0.12])
    kw = dict(k2_0=0.9, tau_span=(0, 1e-5))
    sol = ep.averaged(body, tq, 2e-5, resonance_tol=1e-15, **kw)
    assert sol.status == 1 and sol.event == "resonance"
    assert "bound" in sol.message and "resonance_tol=None" in sol.message
    cut = max(sol.resonances, key=lambda r: r["jump"])
    assert cut["bound"] and cut["jump"] > 1e-15 and cut["rho"] > 10_000
    assert sol.tau[-1] == pytest.approx(cut["tau"], rel=0, abs=1e-12)  # the run ends at the crossing it lists
    assert calls == []
    free = ep.averaged(body, tq, 2e-5, **kw)  # the default tolerance: the bounds show every crossing harmless
    assert free.status == 0 and len(free.resonances) >= 3 and all(r["bound"] for r in free.resonances)
