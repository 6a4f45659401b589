"""Averaging engine (2.12)-(2.16), closed form (3.4), charts and sign switching, averaged vs full (1.1)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import integrate as spi

from rigidbody import lagrange as L
from rigidbody.core import elliptic as ell

TOP = L.Top(A=1.5, C=1.0, mgl=0.5)
DRAG = L.LinearDrag(a=0.125, b=0.1)


R0 = math.sqrt(3.0)


def spun(theta_deg, r0=R0):
    """The paper's initial states: spun about the axis, tilted by theta0."""
    return (0.0, 0.0, r0, 0.0, math.radians(theta_deg), 0.0)


# second torque example (not in the paper): theta-dependent equatorial drag and an axial motor,
# class (2.4): M1 = p f, M2 = q f, f = -a (1 + kappa cos theta); M3 = m0 - b r
KAPPA, M0 = 0.5, 0.15
MOTOR = L.ProportionalTorque(
    f=lambda Gz, H, r, th: -DRAG.a * (1.0 + KAPPA * np.cos(th)),
    M3=lambda Gz, H, r, th: M0 - DRAG.b * r + 0.0 * th,
)
# a class (2.5) torque: F = -c sin(theta) (a restoring torque in the vertical plane), no axial part
VPLANE = L.VerticalPlaneTorque(F=lambda Gz, H, r, th: -0.1 * np.sin(th))


@st.composite
def admissible(draw):
    u1 = draw(st.floats(-0.98, 0.9))
    u2 = draw(st.floats(u1 + 0.02, 0.99))
    u3 = draw(st.floats(1.01, 4.0))
    return u1, u2, u3, draw(st.sampled_from([-1.0, 1.0])), draw(st.sampled_from([-1.0, 1.0]))


# ---------------------------------------------------------------------------------- closed form (3.4)
@settings(max_examples=50, deadline=None)
@given(admissible())
def test_drag_closed_form_equals_engine(x):
    u1, u2, u3, d1, d2 = x
    closed = L.drag_rhs(TOP, DRAG, u1, u2, u3, d1, d2)
    engine = np.array(L.averaged_rhs(TOP, DRAG, u1, u2, u3, d1, d2, closed_form=False))
    # both exact up to the trapezoid error (1e-13 for sn^2 integrands) and the cancellation in
    # V = 1/((u1-u2)(u1-u3)) * [...]: relative 1e-10 of the largest component
    np.testing.assert_allclose(closed, engine, rtol=0, atol=1e-10 * np.abs(engine).max())


def test_nutation_mean_is_time_average():
    # <u> over a nutation period by adaptive quad in t of (1.3) vs the trapezoid rule vs v of (3.4)
    u1, u2, u3 = 0.1, 0.7, 1.8
    k2, mc = L.modulus(u1, u2, u3)
    Kk = ell.K(mc=mc)

    def u_t(s):
        return u1 + (u2 - u1) * ell.sn(s, mc=mc) ** 2

    quad = spi.quad(u_t, 0, 2 * Kk, epsabs=1e-15, epsrel=1e-13, limit=200)[0] / (2 * Kk)
    trap = L.nutation_mean(lambda u: u, u1, u2, u3)
    v = u3 - (u3 - u1) * ell.E(mc=mc) / Kk
    assert trap == pytest.approx(quad, abs=1e-13)  # quad to 1e-13, trapezoid spectrally to 1e-13
    assert v == pytest.approx(quad, abs=1e-13)
    # a non-polynomial integrand (1/(1+u)^2): still spectrally accurate with the default nodes
    g = spi.quad(lambda s: 1 / (1 + u_t(s)) ** 2, 0, 2 * Kk, epsabs=1e-15, epsrel=1e-13, limit=200)[0] / (2 * Kk)
    assert L.nutation_mean(lambda u: 1 / (1 + u) ** 2, u1, u2, u3) == pytest.approx(g, rel=1e-11, abs=0)


def _one_nutation_period(torque):
    """The unperturbed motion (eps = 0) from a fixed generic state over one nutation period 2K/alpha, sampled
    at 2001 points, for time averages of (2.1) (the torque enters only through the recorded state)."""
    state = (0.2, -0.3, 1.4, 0.3, 1.0, 0.0)
    Gz, H, r = L.integrals(TOP, *state[:5])
    u1, u2, u3 = L.roots(TOP, Gz, H, r)
    k2, mc = L.modulus(u1, u2, u3)
    T = 2 * ell.K(mc=mc) / L.nutation_frequency(TOP, u1, u3)
    t = np.linspace(0, T, 2001)
    f = L.simulate(TOP, torque, 0.0, state, (0, T), t_eval=t, rtol=1e-12, atol=1e-13)
    return Gz, H, r, u1, u2, u3, k2, mc, T, t, f


def test_engine_rates_are_time_averages_of_2_1():
    # <F> of the corrected (2.7) vs the time average of (2.1) evaluated on the unperturbed full motion
    Gz, H, r, u1, u2, u3, k2, mc, T, t, f = _one_nutation_period(MOTOR)
    g1, g2 = np.sin(f.theta) * np.sin(f.phi), np.sin(f.theta) * np.cos(f.phi)
    fac = -DRAG.a * (1 + KAPPA * np.cos(f.theta))
    M1, M2, M3 = f.p * fac, f.q * fac, M0 - DRAG.b * f.r
    dGz = M1 * g1 + M2 * g2 + M3 * np.cos(f.theta)  # (2.1): vertical component of the torque
    dH = M1 * f.p + M2 * f.q + M3 * f.r
    avg = [spi.simpson(x, x=t) / T for x in (dGz, dH, M3 / TOP.C)]
    got = L.averaged_slow_rates(TOP, MOTOR, Gz, H, r)
    # Simpson on 2000 intervals of a smooth periodic integrand (h^4 ~ 1e-13 relative) + rtol 1e-12
    np.testing.assert_allclose(got, avg, atol=1e-9)


def test_averaged_rhs_general_torque_is_jacobian_times_mean():
    # U = d u/d(Gz,H,r) . <F>: the engine's V (2.13) against finite differences of the roots
    Gz, H, r = L.integrals(TOP, 0.1, 0.3, 1.2, 0.2, 0.9)
    u = L.roots(TOP, Gz, H, r)
    d1, d2 = L.deltas(TOP, Gz, r)
    Fm = np.array(L.averaged_slow_rates(TOP, VPLANE, Gz, H, r))
    h = 1e-6
    dirv = Fm / np.linalg.norm(Fm)
    up = np.array(L.roots(TOP, *(np.array([Gz, H, r]) + h * dirv)))
    um = np.array(L.roots(TOP, *(np.array([Gz, H, r]) - h * dirv)))
    fd = (up - um) / (2 * h) * np.linalg.norm(Fm)
    U = np.array(L.averaged_rhs(TOP, VPLANE, *u, d1, d2))
    np.testing.assert_allclose(U, fd, atol=1e-7 * np.abs(U).max())  # central differences: O(h^2) + 1e-16/h


# -------------------------------------------------------------------------------------- integrations
@pytest.mark.parametrize("torque", [MOTOR, VPLANE], ids=["motor", "vertical-plane"])
def test_u_chart_agrees_with_GHr_chart(torque):
    ini = L.integrals(TOP, *spun(60)[:5])
    tau = np.linspace(0, 5, 11)
    a = L.averaged(TOP, torque, ini, (0, 5), tau_eval=tau, chart="u")
    b = L.averaged(TOP, torque, ini, (0, 5), tau_eval=tau, chart="GHr")
    assert a.status == 0 and b.status == 0, (a.message, b.message)
    # the same averaged system in two sets of variables, rtol 1e-12 each
    for name in ("Gz", "H", "r"):
        np.testing.assert_allclose(getattr(a, name), getattr(b, name), atol=1e-9)
    np.testing.assert_allclose(a.u, b.u, atol=1e-8)


def test_motor_spin_is_exact():
    # r' = eps (m0 - b r)/C holds exactly in (1.1): r = m0/b + (r0 - m0/b) exp(-b tau / C)
    ini = L.integrals(TOP, *spun(60)[:5])
    s = L.averaged(TOP, MOTOR, ini, (0, 10), tau_eval=np.linspace(0, 10, 21))
    r_exact = M0 / DRAG.b + (math.sqrt(3) - M0 / DRAG.b) * np.exp(-DRAG.b * s.tau / TOP.C)
    np.testing.assert_allclose(s.r, r_exact, atol=1e-9)  # integrator rtol 1e-12 through the u chart


def _max_slow_error(torque, theta_deg, eps, tau_end):
    state = spun(theta_deg)
    f = L.simulate(TOP, torque, eps, state, (0, tau_end / eps), rtol=1e-10, atol=1e-12)
    s = L.averaged(TOP, torque, L.integrals(TOP, *state[:5]), (0, tau_end), tau_eval=f.tau)
    assert f.status == 0 and s.status == 0
    return max(np.abs(f.Gz - s.Gz).max(), np.abs(f.H - s.H).max(), np.abs(f.r - s.r).max())


def test_averaged_vs_full_error_is_order_eps():
    # the averaging theorem checked: max |slow(full) - slow(averaged)| over tau in [0, 5] ~ c eps
    eps = np.array([0.04, 0.02, 0.01])
    err = np.array([_max_slow_error(DRAG, 60, e, 5.0) for e in eps])
    order = np.polyfit(np.log(eps), np.log(err), 1)[0]
    assert 0.8 <= order <= 1.3, (err, order)
    # and the constant is moderate: the nutation-scale oscillation of the slow variables,
    # ~ (variation of F2 over a nutation, 2 a mgl (u2 - u1)/A ~ 0.04) x period (~5.8) / (2 pi) ~ 0.04
    assert err[-1] < 0.1 * eps[-1], err


@pytest.mark.slow
def test_averaged_vs_full_error_is_order_eps_small_eps():
    eps = np.array([0.01, 0.005, 0.0025])
    for th in (5, 60, 170):
        err = np.array([_max_slow_error(DRAG, th, e, 5.0) for e in eps])
        order = np.polyfit(np.log(eps), np.log(err), 1)[0]
        assert 0.8 <= order <= 1.3, (th, err, order)


def test_second_torque_averaged_vs_full():
    # the general engine on a torque the paper did not print: error halves with eps (O(eps) theorem)
    e1 = _max_slow_error(MOTOR, 60, 0.02, 3.0)
    e2 = _max_slow_error(MOTOR, 60, 0.01, 3.0)
    assert e2 < 0.03
    assert 1.6 < e1 / e2 < 2.5, (e1, e2)  # ratio 2 for an O(eps) error; the band allows O(eps^2) terms


def test_vertical_plane_torque_averaged_vs_full():
    e1 = _max_slow_error(VPLANE, 60, 0.02, 3.0)
    e2 = _max_slow_error(VPLANE, 60, 0.01, 3.0)
    assert e2 < 0.03
    assert 1.6 < e1 / e2 < 2.5, (e1, e2)


def test_delta1_changes_sign_and_full_equations_agree():
    # case 1 of the paper (theta0 = 5 deg): Gz^2 - C^2 r^2 < 0 at first, and the drag makes it cross
    # zero (u3 touches 1) near tau ~ 1.59; the run starts in the GHr chart (|Gz^2 - C^2 r^2| is only 0.4%
    # of Gz^2 + C^2 r^2), flips delta1 and returns to the paper's (u1, u2, u3) chart with delta1 = +1 at
    # tau ~ 4.1: the span [0, 6] checks that continuation too
    state = spun(5)
    ini = L.integrals(TOP, *state[:5])
    s = L.averaged(TOP, DRAG, ini, (0, 6), tau_eval=np.linspace(0, 6, 61))
    assert s.status == 0
    flips = s.t_events["delta1_flip"]
    assert flips.size == 1
    assert s.delta1[0] == -1 and s.delta1[-1] == 1
    assert s.chart[-1] == 0 and s.t_events["chart_switch"][-1] < 5  # back in the u chart after the crossing
    err = []
    for eps in (0.02, 0.01):
        f = L.simulate(TOP, DRAG, eps, state, (0, 6 / eps), rtol=1e-10, atol=1e-12)
        w = f.Gz**2 - (TOP.C * f.r) ** 2
        cross = f.tau[np.argmax(w > 0)]
        assert w[0] < 0 and np.all(w[f.tau > cross + 0.05] > 0)
        # the sign change of the real motion at the averaged one's time to O(eps) (slope of w ~ 1)
        assert abs(cross - flips[0]) < 3 * eps
        sa = L.averaged(TOP, DRAG, ini, (0, 6), tau_eval=f.tau)
        assert sa.chart[-1] == 0
        err.append(max(np.abs(f.Gz - sa.Gz).max(), np.abs(f.H - sa.H).max(), np.abs(f.r - sa.r).max()))
    # O(eps) averaging error; the constant is the nutation-scale oscillation of the slow variables,
    # ~ (variation of F over a nutation) x period / (2 pi) ~ 0.04 for these parameters
    assert err[1] < 0.1 * 0.01, err
    assert 1.6 < err[0] / err[1] < 2.5, err  # ratio 2 for O(eps): a wrong continuation leaves an O(1) floor


def test_u_chart_alone_stops_at_the_branch_point():
    ini = L.integrals(TOP, *spun(60)[:5])
    s = L.averaged(TOP, DRAG, ini, (0, 40), chart="u")
    assert s.status == 1 and s.event == "branch_point"
    assert "delta1/delta2" in s.message
    assert np.all(np.isfinite(s.u))
    # case 1 starts next to the branch point (|Gz^2 - C^2 r^2| is 0.4% of Gz^2 + C^2 r^2): the u chart alone
    # is refused there (it used to integrate through the branch point with the wrong sign and then fail
    # inside from_roots)
    ini1 = L.integrals(TOP, *spun(5)[:5])
    with pytest.raises(ValueError, match="branch point"):
        L.averaged(TOP, DRAG, ini1, (0, 6), chart="u")
    s = L.averaged(TOP, DRAG, ini1, (0, 1), chart="u", switch_tol=1e-3)  # allowed with a smaller threshold
    assert s.status == 0 and np.all(s.u[2] > 1.0)


def test_degenerate_state_ends_with_clear_status():
    # case 3 tends to a regular precession about the lower position (u2 - u1 -> 0): with a loose
    # threshold the degenerate event fires early, ending the run with status 1 and no NaN
    ini = L.integrals(TOP, *spun(170)[:5])
    s = L.averaged(TOP, DRAG, ini, (0, 100), degenerate_tol=1e-3)
    assert s.status == 1 and s.event == "u1_eq_u2"
    assert "regular precession" in s.message and "(2.10)" in s.message
    assert s.k2[-1] == pytest.approx(1e-3, rel=1e-3, abs=0)
    assert np.all(np.isfinite(s.u)) and s.tau[-1] < 100


def test_initial_regular_precession_runs_in_the_GHr_chart():
    # steady precession (theta' = 0, A cos(th) psi'^2 - C r psi' + mgl = 0): u1 = u2, (2.10) is singular;
    # 'auto' integrates the (2.7)-averaged system instead (smooth there), 'u' refuses
    th, r = 0.7, 3.0
    cth, sth = math.cos(th), math.sin(th)
    dpsi = (TOP.C * r - math.sqrt((TOP.C * r) ** 2 - 4 * TOP.A * cth * TOP.mgl)) / (2 * TOP.A * cth)
    state = (dpsi * sth * math.sin(0.4), dpsi * sth * math.cos(0.4), r, 0.4, th, 0.0)
    ini = L.integrals(TOP, *state[:5])
    with pytest.raises(ValueError, match="regular precession"):
        L.averaged(TOP, DRAG, ini, (0, 1), chart="u")
    err = []
    for eps in (0.02, 0.01):
        f = L.simulate(TOP, DRAG, eps, state, (0, 2 / eps), rtol=1e-10, atol=1e-12)
        s = L.averaged(TOP, DRAG, ini, (0, 2), tau_eval=f.tau)
        assert s.status == 0 and np.all(s.chart == 1) and np.all(np.isfinite(s.Gz))
        b = L.averaged(TOP, DRAG, ini, (0, 2), tau_eval=f.tau, chart="GHr")
        np.testing.assert_array_equal(s.H, b.H)  # 'auto' is the GHr chart throughout here
        err.append(max(np.abs(f.Gz - s.Gz).max(), np.abs(f.H - s.H).max(), np.abs(f.r - s.r).max()))
    # against the full equations (1.1): the O(eps) part of the averaging error is the nutation-scale
    # oscillation of the slow variables, proportional to the nutation amplitude u2 - u1 = 0 here; the drag
    # excites a nutation of amplitude O(eps) only, so the error is O(eps^2): ratio 4 when eps halves
    assert err[1] < 0.01 * 0.01, err
    assert 3.0 < err[0] / err[1] < 5.0, err


def test_averaged_rejects_bad_input():
    ini = L.integrals(TOP, *spun(60)[:5])
    with pytest.raises(ValueError, match="tau_span"):
        L.averaged(TOP, DRAG, ini, (1, 0))
    with pytest.raises(TypeError, match="torque"):
        L.averaged(TOP, "drag", ini, (0, 1))
    with pytest.raises(TypeError, match="closed_form"):
        L.averaged(TOP, MOTOR, ini, (0, 1), closed_form=True)
    with pytest.raises(ValueError, match="chart"):
        L.averaged(TOP, DRAG, ini, (0, 1), chart="xyz")
    with pytest.raises(ValueError, match="distinct roots"):
        L.averaged_rhs(TOP, DRAG, 0.3, 0.3, 2.0)
    for kw, name in [(dict(degenerate_tol=2.0), "degenerate_tol"), (dict(switch_tol=0.7), "switch_tol"),
                     (dict(max_segments=0), "max_segments"), (dict(rtol=-1.0), "rtol"), (dict(atol=0.0), "atol")]:
        with pytest.raises(ValueError, match=name):
            L.averaged(TOP, DRAG, ini, (0, 1), **kw)
    with pytest.raises(ValueError, match="rtol"):
        L.simulate(TOP, DRAG, 0.1, spun(60), (0, 1), rtol=-1.0)


def test_non_finite_user_torque_is_refused_not_a_hang():
    # a torque that is NaN at the initial state used to hang solve_ivp (its step-size control turns NaN)
    bad = L.ProportionalTorque(f=lambda Gz, H, r, th: np.nan * th)
    ini = L.integrals(TOP, *spun(60)[:5])
    for chart in ("auto", "GHr"):
        with pytest.raises(ValueError, match="not finite at the initial state"):
            L.averaged(TOP, bad, ini, (0, 1), chart=chart)
    with pytest.raises(ValueError, match="not finite at the initial state"):
        L.simulate(TOP, bad, 0.1, spun(60), (0, 1))


def test_printed_F1_of_2_7_lacks_sin_theta():
    # (2.7) prints F1 = M1* + M3* cos(theta); (2.1) gives Gz' = eps[(M1 sin phi + M2 cos phi) sin theta
    # + M3 cos theta], i.e. F1 = M1* sin(theta) + M3* cos(theta). Decide with the time average of the
    # vertical torque component on a real (unperturbed) motion, for the class (2.5) torque VPLANE.
    Gz, H, r, u1, u2, u3, _, mc, T, t, f = _one_nutation_period(VPLANE)
    Fv = -0.1 * np.sin(f.theta)
    M1, M2 = Fv * np.sin(f.phi), Fv * np.cos(f.phi)
    gam1, gam2 = np.sin(f.theta) * np.sin(f.phi), np.sin(f.theta) * np.cos(f.phi)
    true_mean = spi.simpson(M1 * gam1 + M2 * gam2, x=t) / T  # vertical component of the torque
    printed_mean = spi.simpson(M1 * np.sin(f.phi) + M2 * np.cos(f.phi), x=t) / T  # <M1*> (M3 = 0)
    ours = L.averaged_slow_rates(TOP, VPLANE, Gz, H, r)[0]
    assert ours == pytest.approx(true_mean, abs=1e-9)  # Simpson h^4 + rtol 1e-12
    assert abs(printed_mean - true_mean) > 100 * 1e-9  # the printed form is off by far more than that


def test_spin_reversal_flips_delta2_and_matches_full_equations():
    # a reversing axial motor, M3 = -0.3 - b r: r crosses zero (delta2 = sign r flips) at
    # tau* = (C/b) ln((r0 + 3)/3) ~ 4.56 (exact, from r' = (-0.3 - 0.1 r)/C); delta1 flips before that
    rev = L.ProportionalTorque(f=lambda G, H, r, th: -0.125 + 0 * th, M3=lambda G, H, r, th: -0.3 - 0.1 * r + 0 * th)
    state = spun(60)
    ini = L.integrals(TOP, *state[:5])
    tau = np.linspace(0, 8, 33)
    a = L.averaged(TOP, rev, ini, (0, 8), tau_eval=tau)
    assert a.status == 0, a.message
    t_star = TOP.C / 0.1 * math.log((R0 + 3.0) / 3.0)
    assert a.t_events["delta2_flip"] == pytest.approx([t_star], abs=1e-8)  # event location, rtol 1e-12
    assert a.t_events["delta1_flip"].size >= 1
    assert a.delta2[0] == 1 and a.delta2[-1] == -1
    b = L.averaged(TOP, rev, ini, (0, 8), tau_eval=tau, chart="GHr")
    for name in ("Gz", "H", "r"):  # the chart-switching run equals the (2.7)-averaged run
        np.testing.assert_allclose(getattr(a, name), getattr(b, name), atol=1e-9)
    eps = 0.01
    f = L.simulate(TOP, rev, eps, state, (0, 8 / eps), t_eval=tau / eps)
    err = max(np.abs(f.Gz - a.Gz).max(), np.abs(f.H - a.H).max(), np.abs(f.r - a.r).max())
    assert err < 0.5 * eps  # O(eps) averaging error (constant ~0.1 here)


def test_sleeping_tops():
    # fast sleeping top (C^2 r^2 > 4 A mgl): u1 = u2 = 1 < u3; the auto chart starts in (Gz, H, r)
    # (R = 0 is a branch point of (2.8)) and the top keeps sleeping while r decays exactly by (3.3)
    ini = L.integrals(TOP, 0.0, 0.0, 3.0, 0.0, 0.0)
    s = L.averaged(TOP, DRAG, ini, (0, 5), tau_eval=np.linspace(0, 5, 6))
    assert s.status == 0 and np.all(s.chart == 1)
    np.testing.assert_allclose(s.r, 3.0 * np.exp(-DRAG.b * s.tau / TOP.C), rtol=1e-10)  # rtol 1e-12
    # sleeping: Gz = C r (angular momentum along the vertical axis), u1 = u2 = 1 to root conditioning
    np.testing.assert_allclose(s.Gz, TOP.C * s.r, rtol=1e-9)
    assert np.all(s.u1 > 1 - 1e-7)
    # slow sleeping top: u2 = u3 = 1 is the separatrix (infinite nutation period): refused clearly
    with pytest.raises(ValueError, match="separatrix"):
        L.averaged(TOP, DRAG, L.integrals(TOP, 0.0, 0.0, 1.0, 0.0, 0.0), (0, 5))


def test_hanging_spinning_top_theta0_pi():
    # theta0 = pi exactly, spun about its axis: p = q = 0, gamma = (0, 0, -1) is an exact solution of (1.1)
    # under drag with r = r0 exp(-b tau / C), so Gz = -C r and H = C r^2/2 - mgl (u1 = u2 = -1: a regular
    # precession at the lower pole and a branch point of (2.8), Gz + C r = 0)
    r0 = 1.7
    ini = L.integrals(TOP, 0.0, 0.0, r0, 0.0, math.pi)
    s = L.averaged(TOP, DRAG, ini, (0, 10), tau_eval=np.linspace(0, 10, 11))
    assert s.status == 0, s.message
    # a smooth 3-state system over 10 time units needs a few hundred evaluations at rtol 1e-12; Runge-Kutta
    # stages leave the admissible set here (its boundary is curved) and a NaN/ValueError there used to cost
    # ~2 million (100 s) -- a deterministic work count, not a timing
    assert s.nfev < 5000, s.nfev
    r = r0 * np.exp(-DRAG.b * s.tau / TOP.C)
    # global error of an rtol-1e-12 integration over ~100 steps
    np.testing.assert_allclose(s.r, r, rtol=1e-9)
    np.testing.assert_allclose(s.Gz, -TOP.C * r, rtol=1e-9)
    np.testing.assert_allclose(s.H, 0.5 * TOP.C * r**2 - TOP.mgl, rtol=1e-9)
    assert np.all(s.u1 < -1 + 1e-7) and np.all(s.u2 < -1 + 1e-7)  # double root at -1: sqrt(eps)-conditioned
    f = L.simulate(TOP, DRAG, 0.1, (0.0, 0.0, r0, 0.0, math.pi, 0.0), (0, 100), t_eval=s.tau / 0.1)
    assert f.status == 0 and np.all(f.theta == math.pi)  # the full motion stays at the pole too


def test_fast_sleeping_top_slows_down_to_its_stability_limit():
    # on the sleeping manifold the roots are 1, 1, u* = C^2 r^2/(2 A mgl) - 1 (test_sleeping_top_roots) and
    # r = r0 exp(-b tau / C) exactly, so the root spread u* - 1 reaches the triple-root threshold 1e-3 at
    # tau_e = (C/b) ln(r0 / r_e), r_e = sqrt(2 A mgl (2 + 1e-3)) / C. The run must stop there with a clear
    # status (it used to end with status -1, "Required step size is less than spacing between numbers":
    # the sqrt(eps) rounding noise of the double root u1 = u2 = 1 stalled the rtol-1e-12 integrator).
    r0 = 3.0
    ini = L.integrals(TOP, 0.0, 0.0, r0, 0.0, 0.0)
    s = L.averaged(TOP, DRAG, ini, (0, 10))
    assert s.status == 1 and s.event == "triple_root", s.message
    assert s.nfev < 5000, s.nfev  # smooth field: a few hundred evaluations (see the hanging top)
    assert "C^2 r^2 = 4 A mgl" in s.message
    r_e = math.sqrt(2 * TOP.A * TOP.mgl * (2 + 1e-3)) / TOP.C
    tau_e = TOP.C / DRAG.b * math.log(r0 / r_e)
    assert s.tau[-1] == pytest.approx(tau_e, abs=1e-6)  # event location; the spread is smooth in (Gz, H, r)
    np.testing.assert_allclose(s.Gz, TOP.C * s.r, rtol=1e-9)  # still sleeping: Gz = C r (rtol 1e-12 drift)
    assert not s.t_events["delta1_flip"].size  # rounding noise of Gz^2 - C^2 r^2 = 0 is no sign change
    # starting at (or within the threshold of) the triple root is refused
    with pytest.raises(ValueError, match="triple root"):
        L.averaged(TOP, DRAG, L.integrals(TOP, 0.0, 0.0, 1.0001 * math.sqrt(3), 0.0, 0.0), (0, 1))


def test_non_spinning_top_against_full_equations():
    # r = 0 (delta2 = sign r at its boundary) with a conical motion: no spurious sign-change events (r and
    # Gz^2 - C^2 r^2 vanish or stay of one sign identically), r stays 0, and the run agrees with (1.1)
    state = (0.3, 0.2, 0.0, 0.0, math.radians(60), 0.0)
    ini = L.integrals(TOP, *state[:5])
    err = []
    for eps in (0.02, 0.01):
        f = L.simulate(TOP, DRAG, eps, state, (0, 5 / eps), rtol=1e-10, atol=1e-12)
        s = L.averaged(TOP, DRAG, ini, (0, 5), tau_eval=f.tau)
        assert s.status == 0, s.message
        assert not s.t_events["delta1_flip"].size and not s.t_events["delta2_flip"].size
        assert np.all(s.r == 0.0) and np.all(f.r == 0.0)
        err.append(max(np.abs(f.Gz - s.Gz).max(), np.abs(f.H - s.H).max()))
    assert err[1] < 0.5 * 0.01  # O(eps) averaging error
    assert 1.6 < err[0] / err[1] < 2.5, err  # ratio 2 for an O(eps) error; the band allows O(eps^2) terms
    # the planar pendulum (Gz = r = 0 identically) has no events either
    p = L.averaged(TOP, DRAG, L.integrals(TOP, 0.0, 0.0, 0.0, 0.0, 1.0), (0, 5))
    assert p.status == 0 and not p.t_events["delta1_flip"].size and not p.t_events["delta2_flip"].size


@pytest.mark.slow
@pytest.mark.parametrize("case_theta", [5, 60, 170])
def test_paper_cases_long_span_against_full(case_theta):
    # over tau in [0, 30] (through the delta1 crossings of cases 1, 2) the averaged solution stays
    # O(eps) close to the full motion; halving eps halves the error
    e1 = _max_slow_error(DRAG, case_theta, 0.01, 30.0)
    e2 = _max_slow_error(DRAG, case_theta, 0.005, 30.0)
    assert e2 < 0.05
    assert 1.6 < e1 / e2 < 2.5, (e1, e2)


def test_torque_functions_must_be_callable():
    def f(Gz, H, r, th):
        return -0.1

    for make in (
        lambda: L.ProportionalTorque(f, M3=3.0),
        lambda: L.VerticalPlaneTorque(f, M3="M3"),
        lambda: L.StarTorque(f, f, M3s=1),
    ):
        with pytest.raises(TypeError, match=r"M3s? must be a callable"):
            make()
    with pytest.raises(TypeError, match="f must be a callable"):
        L.ProportionalTorque(0.5)
    assert L.ProportionalTorque(f).M3(0.0, 0.0, 0.0, 0.3) == 0.0  # default axial part is zero
