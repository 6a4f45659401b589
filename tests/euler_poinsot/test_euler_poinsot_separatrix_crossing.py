"""Passing the separatrix: the averaged evolution against the full equations next to it and through it."""

from __future__ import annotations

import numpy as np
import pytest

from rigidbody import euler_poinsot as ep

BODY = ep.Body(3.2, 2.6, 1.67)
CASE1 = np.diag([2.322, 1.31, 1.425])


def near_separatrix_errors(eps, mc, phases, span=0.2):
    """Max over phases and time of |full - averaged| for G, T, k2, lambda, from k2_0 = 1 - mc (case 1, 'max')."""
    te = np.linspace(0, span, 21)
    a = ep.averaged(BODY, CASE1, eps, k2_0=1 - mc, tau_span=(0, span), tau_eval=te, min_spin_ratio=0, k2_max=1.0)
    K = ep.EulerPoinsot(BODY, 1.0, 1 - mc, mc=mc).K
    errs, crossed = [], 0
    for u0 in np.linspace(0, 4 * K, phases, endpoint=False):
        s = ep.simulate(BODY, CASE1, eps, k2_0=1 - mc, tau_span=(0, span), tau_eval=te, u0=u0, min_spin_ratio=0,
                        k2_max=None)
        assert s.status == 0
        crossed += s.t_events["separatrix"].size > 0
        errs.append([np.abs(getattr(s, f) - getattr(a, f)).max() for f in ("G", "T", "k2", "lam")])
    return np.max(errs, axis=0) / eps**2, crossed


def test_averaging_error_next_to_the_separatrix_does_not_grow_with_the_period():
    # Case 1 from the separatrix side (k2 decreases away from it). At 1 - k2 = 1e-8 the period is 4.2 times
    # that at 1 - k2 = 0.1, and the osculating motion of every run crosses the separatrix back and forth
    # (its energy oscillates by O(eps^2) around the averaged one, more than the distance to the separatrix).
    # The error of the slow variables stays second order with the same constant: the oscillating part of the
    # torque's effect is concentrated on the passages along the separatrix arcs (the rest of the period is
    # spent next to the saddles, where the torque equals its mean), so it is bounded by the arc drifts, not
    # by the period. Measured (eps = 0.02, 8 phases): G 5.7 / 5.7 eps^2, T 1.9 / 2.1, k2 11 / 10, lambda
    # 6.5 / 9.1 (1 - k2 = 0.1 / 1e-8); at eps = 0.01 the same within 10 %.
    P = [ep.EulerPoinsot(BODY, 1.0, 1 - mc, mc=mc).period for mc in (0.1, 1e-8)]
    assert P[1] / P[0] > 4
    far, c_far = near_separatrix_errors(0.02, 0.1, 4)
    near, c_near = near_separatrix_errors(0.02, 1e-8, 4)
    assert c_far == 0 and c_near == 4
    assert np.all(far[:3] < [8, 3, 15]) and np.all(near[:3] < [8, 3, 15])
    # no growth like the period (x 4.2) in G, T, k2; lambda grows by at most 2 (measured 1.4): its rate goes
    # with N*(k2), whose slope in k2 is infinite at the separatrix, so the O(eps^2) error of k2 weighs more
    assert np.all(near[:3] < 1.5 * far[:3]) and near[3] < 2 * far[3]


# ------------------------------------------------------------------ averaged through the separatrix vs full
I_DISS = np.diag([0.1, 0.1, 1.0])  # drag mostly on the minor axis: a minor-axis spin decays to the separatrix
START = dict(kind="min", k2_0=0.6, delta0=1.0, lam0=0.3, min_spin_ratio=0, k2_max=None)  # through the separatrix


def crossing_errors(eps, tau1=1.6):
    """Averaged (9) through the separatrix against the full equations (drag tensor + gravity gradient)."""
    te = np.linspace(0, tau1, 33)
    a = ep.averaged(BODY, I_DISS, eps, tau_span=(0, tau1), tau_eval=te, **START)
    s = ep.simulate(BODY, I_DISS, eps, tau_span=(0, tau1), tau_eval=te, **START)
    assert a.status == 0 and s.status == 0 and len(a.crossings) == 1
    tc = a.crossings[0]["tau"]
    assert a.t_events["separatrix"] == pytest.approx([tc], abs=0)
    # the osculating energy oscillates by O(eps^2) about the averaged one: the full motion crosses G^2 = 2 T A2
    # a few times within one period of the separatrix passage; its crossing time is the mean of that burst
    burst = s.t_events["separatrix"]
    # the burst lasts O(eps^2 ln(1/eps)) (the period next to the separatrix; measured 23, 12, 1.6 times that)
    assert burst.size >= 1 and burst[-1] - burst[0] < 40 * eps**2 * np.log(1 / eps)
    out = {"tc": abs(burst.mean() - tc), "kinds": np.array_equal(a.kind, s.kind)}
    for name, sel in (("before", te < tc), ("after", te > tc)):
        assert sel.sum() >= 8
        out[name] = {f: np.abs(getattr(s, f) - getattr(a, f))[sel].max() / eps**2 for f in ("G", "T", "delta", "lam")}
    return out


def check_crossing(eps):
    r = crossing_errors(eps)
    assert r["kinds"]  # the kind of motion agrees at every output time
    for side in ("before", "after"):
        # first-order averaging: O(eps^2) for the slow variables over tau ~ 1 (measured G 3.8-4.2, T 1.3-1.6,
        # delta 6.4-8.8, lambda 2.3-9.9 eps^2 at eps = 0.04, 0.02, 0.01): no loss of order across the crossing
        e = r[side]
        assert e["G"] < 8 and e["T"] < 3 and e["delta"] < 15 and e["lam"] < 20, (side, e)
    # the crossing time: the averaged energy's error O(eps^2) over its rate ~ 1/period ~ 1/ln(1/eps) next to the
    # separatrix gives O(eps^2 ln(1/eps)) (measured 3.3, 1.0, 4.1 eps^2 ln(1/eps) at eps = 0.04, 0.02, 0.01)
    assert r["tc"] < 10 * eps**2 * np.log(1 / eps), r["tc"]
    return r


@pytest.mark.parametrize("eps", [0.04, 0.02])
def test_averaged_crossing_against_the_full_motion(eps):
    check_crossing(eps)


@pytest.mark.slow
@pytest.mark.parametrize("eps", [0.01, 0.005])
def test_averaged_crossing_against_the_full_motion_small_eps(eps):
    check_crossing(eps)


def dissipation(kappa):
    """Removes kinetic energy at constant |G| (on average like internal dissipation): M perpendicular to g."""
    A = BODY.A

    def torque(omega, C, nu):
        g = omega * A
        return -kappa * (omega - (omega * g).sum(-1, keepdims=True) * g / (g * g).sum(-1, keepdims=True))

    return torque


@pytest.mark.parametrize("eps", [0.05, 0.025])
def test_averaged_crossing_with_the_engine_against_the_full_motion(eps):
    # a plain-function torque (no closed form: the averaging engine) through the separatrix, from 'min' to
    # 'max' at constant G: T before and after, and the crossing time, against simulate
    te = np.linspace(0, 3, 31)
    kw = dict(kind="min", k2_0=0.2, delta0=1.0, lam0=0.3, tau_span=(0, 3), tau_eval=te, k2_max=None)
    a = ep.averaged(BODY, dissipation(3.0), eps, **kw)
    s = ep.simulate(BODY, dissipation(3.0), eps, **kw)
    assert a.status == 0 and s.status == 0 and a.quad_error < 1e-10
    c = a.crossings[0]
    assert c["source"] == ("min", 1) and c["region"][0] == "max"
    # an odd torque: the two senses beyond are equally likely
    assert c["probabilities"][("max", 1)] == pytest.approx(0.5, abs=1e-12)
    assert np.array_equal(a.kind, s.kind)
    # G is conserved by the torque exactly and by the averaged system to the integrator's tolerance
    assert a.G == pytest.approx(1.0, abs=1e-9) and s.G == pytest.approx(1.0, abs=1e-8)
    # T: O(eps^2) (measured 0.15-0.24 eps^2 on both sides); crossing time O(eps^2 ln(1/eps)) (9, 3.8 eps^2)
    assert np.abs(a.T - s.T).max() < 1.0 * eps**2
    assert abs(s.t_events["separatrix"].mean() - c["tau"]) < 10 * eps**2 * np.log(1 / eps)


# ------------------------------------------------------------------------------- branches and statuses
M0 = np.array([0.4, 0.0, -0.5])


def constant(omega, C, nu):
    return np.zeros(np.shape(omega)) + M0


CONST = dict(kind="min", k2_0=0.55, delta0=1.0, lam0=0.3, tau_span=(0, 2.0), k2_max=None)


def test_branches_of_a_torque_whose_two_senses_differ():
    # a constant body-fixed torque braking the spin about the minor axis, pushing about the major one: from
    # ('min', 1) the motion ends as ('max', 1) with p = 0.464 or as ('min', -1), the spin reversed, with 0.536
    # (test_euler_poinsot_separatrix.py checks these numbers against ensembles of full runs)
    a = ep.averaged(BODY, constant, 0.0, **CONST)
    assert a.status == 0 and len(a.crossings) == 1
    c = a.crossings[0]
    p = {r: v for r, v in c["probabilities"].items() if v > 0}
    assert p == pytest.approx({("max", 1): 0.4642, ("min", -1): 0.5358}, abs=1e-4)
    assert c["region"] == ("min", -1) and a.kind[-1] == "min" and a.sigma[-1] == -1  # 'likely'
    # the same probabilities from separatrix_crossing at the crossing state
    n = c["n"]
    d = ep.separatrix_crossing(BODY, constant, c["G"], np.arccos(n[2]), np.arctan2(n[1], n[0]), None, ("min", 1))
    assert d.probabilities == pytest.approx(c["probabilities"], abs=1e-12)
    # forcing the other branch: spin-up about the major axis (the torque's component along it), G grows
    b = ep.averaged(BODY, constant, 0.0, branch=("max", 1), **CONST)
    assert b.status == 0 and b.kind[-1] == "max" and b.sigma[-1] == 1 and b.G[-1] > b.G[b.tau < c["tau"]][-1]
    # before the crossing both runs are the same
    assert np.array_equal(a.G[a.tau < c["tau"]], b.G[b.tau < c["tau"]])
    # a branch of probability 0 ends the run at the crossing with a status, not a stall
    z = ep.averaged(BODY, constant, 0.0, branch=("max", -1), **CONST)
    assert z.status == 1 and z.event == "separatrix" and "not entered" in z.message
    assert z.tau[-1] == pytest.approx(c["tau"], abs=1e-9)
    # every branch at once
    both = ep.averaged_branches(BODY, constant, 0.0, **CONST)
    assert set(both) == {("max", 1), ("min", -1)}
    assert both[("max", 1)].G[-1] == pytest.approx(b.G[-1], abs=1e-12)
    # a random branch is one of them
    r = ep.averaged(BODY, constant, 0.0, branch="random", seed=3, **CONST)
    assert (r.kind[-1], r.sigma[-1]) in both


def test_a_separatrix_that_attracts_from_both_sides_ends_the_run_with_a_status():
    # a torque that pushes the energy towards the separatrix from both sides and vanishes on it: no region
    # keeps the motions that arrive; the averaged run must stop there (not stall, not pick a side)
    A2 = BODY.A2

    def attract(omega, C, nu):
        g = omega * BODY.A
        h = 0.5 * (g * omega).sum(-1, keepdims=True) - (g * g).sum(-1, keepdims=True) / (2 * A2)
        return -5.0 * np.tanh(h / 1e-3) * (omega - g / A2)

    for kind in ("min", "max"):
        a = ep.averaged(BODY, attract, 0.0, kind=kind, k2_0=0.5, tau_span=(0, 30), k2_max=None)
        assert a.status == 1 and a.event == "separatrix" and "attracts from both sides" in a.message
        assert a.tau[-1] < 5 and a.k2[-1] == pytest.approx(1.0, abs=1e-8)
    # the full motion indeed goes to the separatrix and stays on it (eps = 0.05, tau in [0, 6]). How often it
    # then crosses it is decided by rounding (1 - k2 is ~1e-14 there: 67 crossings at one SIMD level of NumPy's
    # elementary functions, 42 at another), so no count is asserted. The attraction is exponential: the largest
    # 1 - k2 over each unit of tau falls by a factor ~400 from one unit to the next (6.7e-6, 1.6e-8, 4.5e-11 on
    # [1, 2], [2, 3], [3, 4]); a factor 10 per unit and 1e-9 after tau = 4 leave 1.5 and 4 decades of margin
    tt = np.linspace(0, 6, 121)
    s = ep.simulate(BODY, attract, 0.05, kind="min", k2_0=0.5, tau_span=(0, 6), tau_eval=tt, k2_max=None)
    gap = 1 - s.k2
    assert s.status == 0 and gap[tt >= 4].max() < 1e-9
    env = [gap[(tt >= j) & (tt <= j + 1)].max() for j in (1, 2, 3)]
    assert env[1] < env[0] / 10 and env[2] < env[1] / 10
    # one passage is one event: no crossing is listed twice (a root on a step boundary was counted in both steps)
    te = s.t_events["separatrix"]
    assert np.all(np.diff(te) > 0)


def test_output_of_a_run_through_the_separatrix():
    te = np.linspace(0, 1.6, 17)
    T0 = ep.T_from(BODY, 1.0, 0.6, "min")
    a = ep.averaged(BODY, I_DISS, 0.02, T0=T0, tau_span=(0, 1.6), tau_eval=te, delta0=1.0, lam0=0.3,
                    min_spin_ratio=0, k2_max=None)
    b = ep.averaged(BODY, I_DISS, 0.02, tau_span=(0, 1.6), **START)  # solver steps
    tc = a.crossings[0]["tau"]
    assert np.array_equal(a.tau, te) and a.T[0] == pytest.approx(T0, abs=1e-14)
    assert list(a.kind) == ["min" if t < tc else "max" for t in te]
    tc = b.crossings[0]["tau"]
    # G, T and n continuous across the crossing (T jumps by O(1e-9) at the switch); lambda unwrapped
    for f in ("G", "T", "lam"):
        v = getattr(b, f)
        jump = np.abs(np.diff(v)).max()
        assert jump < 0.05, f  # solver steps; a 2 pi slip of lambda or a jump of G, T would show
    i = np.searchsorted(b.tau, tc)
    assert b.tau[i] == tc and b.tau[i - 1] < tc
    # the solver's steps: the crossing time closes the segment before it, the next step is on the other side
    assert b.k2[i] == pytest.approx(1.0, abs=2e-9) and b.kind[i] == "min" and b.kind[i + 1] == "max"
    # raw state rows G, k2, n and a dense output that reproduces the fields
    assert a.y.shape == (5, te.size)
    mid = 0.5 * (te[5] + te[6])
    np.testing.assert_allclose(a.sol(te[12]), a.y[:, 12], rtol=1e-12, atol=1e-14)
    assert a.sol(mid).shape == (5,)
    # the stop (the default): the run ends next to the separatrix
    c = ep.averaged(BODY, I_DISS, 0.02, tau_span=(0, 1.6), **{**START, "k2_max": 1 - 1e-6})
    assert c.status == 1 and c.event == "separatrix" and c.tau[-1] < tc


def test_separatrix_passage_example_data():
    # the data behind examples/euler_poinsot/separatrix_passage.py (the script itself is run): a minor-axis spin that
    # loses energy at constant G crosses into a major-axis spin, averaged and full alike
    import runpy
    from pathlib import Path

    import matplotlib

    matplotlib.use("Agg")
    script = Path(__file__).resolve().parents[2] / "examples" / "euler_poinsot" / "separatrix_passage.py"
    g = runpy.run_path(str(script), run_name="__main__")
    full, avg, eps, body = g["full"], g["avg"], g["EPS"], g["body"]
    assert full.status == 0 and avg.status == 0
    assert (full.kind[0], avg.kind[0]) == ("min", "min") and (full.kind[-1], avg.kind[-1]) == ("max", "max")
    c = avg.crossings[0]
    assert c["source"] == ("min", 1) and c["region"] == (full.kind[-1], full.sigma[-1])
    # the crossing time and the final energy agree to the averaging's O(eps^2) (ln(1/eps) for the time):
    # measured 0.028 = 11 eps^2 and 1.2e-4 = 0.05 eps^2
    assert abs(full.t_events["separatrix"].mean() - c["tau"]) < 10 * eps**2 * np.log(1 / eps)
    assert abs(full.T[-1] - avg.T[-1]) < 0.2 * eps**2
    # on the way to the major-axis spin: T between the separatrix value and the pure spin's G^2/(2 A1)
    assert 1 / (2 * body.A1) < avg.T[-1] < 1 / (2 * body.A2)
    g["plt"].close("all")


def test_starts_on_the_separatrix_are_refused_naming_k2_0():
    # through the separatrix (k2_max=None) a start within 1e-9 of it has no kind of motion to start in; with
    # the default stop, a start beyond k2_max = 1 - 1e-6 is refused as before
    with pytest.raises(ValueError, match="k2_0"):
        ep.averaged(BODY, CASE1, 0.0, k2_0=1 - 1e-10, k2_max=None)
    with pytest.raises(ValueError, match="k2_0"):
        ep.averaged(BODY, CASE1, 0.0, k2_0=1 - 1e-7)
    assert ep.averaged(BODY, CASE1, 0.0, k2_0=1 - 1e-7, k2_max=None, tau_span=(0, 0.1)).status == 0


def test_a_run_without_a_crossing_lists_none():
    a = ep.averaged(BODY, CASE1, 0.0, k2_0=0.5, tau_span=(0, 0.1), k2_max=None)
    assert a.crossings == [] and a.t_events["separatrix"].size == 0
