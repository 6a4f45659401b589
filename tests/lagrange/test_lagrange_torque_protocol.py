"""The torque protocol of rigidbody.lagrange: a closed-form average is a capability the torque declares.

A torque class written here (no library file touched) that defines ``closed_means`` gets the closed-form path of
``averaged`` and ``averaged_rhs`` -- the averaging engine never calls its ``slow_rates`` -- and one without it
gets the engine. The references are independent of the library's kernels: the exact spin r = r0 exp(-b tau/C) of
linear drag (3.3), and the nutation mean of u written here from the complete elliptic integrals,
<u> = u3 - (u3 - u1) E(k)/K(k) (the v of (3.4)), instead of the kernel's <sn^2> series.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.special import ellipe, ellipk

from rigidbody import lagrange as L

TOP, DRAG, R0 = L.PAPER_TOP, L.PAPER_DRAG, L.PAPER_R0
A, C, MGL = TOP.A, TOP.C, TOP.mgl


def drag_rates(top, a, b, Gz, H, r, u):
    """(2.7) for linear drag (3.1) at cos(theta) = u (linear in u)."""
    F1 = -a * (Gz - top.C * r * u) / top.A - b * r * u
    F2 = -a * (2.0 * (H - top.mgl * u) - top.C * r * r) / top.A - b * r * r
    F3 = -b * r / top.C + 0.0 * u
    return F1, F2, F3


class EngineDrag(L.Torque):
    """Linear drag through the protocol's required part only: the engine averages it."""

    def __init__(self, a, b):
        self.a, self.b = a, b
        self.engine_calls = 0

    def slow_rates(self, top, Gz, H, r, u):
        self.engine_calls += 1
        return np.broadcast_arrays(*drag_rates(top, self.a, self.b, Gz, H, r, np.asarray(u, dtype=float)))


class OwnClosedDrag(EngineDrag):
    """Linear drag with a closed form of its own: F(<u>), <u> = u3 - (u3 - u1) E(k)/K(k)."""

    def __init__(self, a, b):
        super().__init__(a, b)
        self.closed_calls = 0

    def closed_means(self, xp, top, s):
        self.closed_calls += 1
        v = s.u3 - (s.u3 - s.u1) * ellipe(s.k2) / ellipk(s.k2)
        return drag_rates(top, self.a, self.b, s.Gz, s.H, s.r, v)


def spun(theta_deg, r0=R0):
    return L.integrals(TOP, 0.0, 0.0, r0, 0.0, math.radians(theta_deg))


def test_has_closed_form_is_declared_by_the_class():
    # Slip caught: a capability read from the class name (isinstance LinearDrag) instead of the hook
    assert L.has_closed_form(DRAG) and L.has_closed_form(OwnClosedDrag(1.0, 1.0))
    assert not L.has_closed_form(EngineDrag(1.0, 1.0))
    assert not L.has_closed_form(L.ProportionalTorque(f=lambda G, H, r, th: 0.0 * th))


def test_a_users_closed_form_is_used_in_both_charts_and_in_a_batch():
    # Slip caught: the drivers take the closed form only for LinearDrag (the user's torque then goes to the
    # engine, engine_calls > 0), or only in one chart. Paper case 2 switches to the GHr chart near tau = 26
    # and back: tau in [0, 40] passes through both. r = r0 exp(-b tau/C) exactly (3.3): F3 does not depend on
    # u, so any averaging gives it; the runs' global error at rtol 1e-10 is ~1e-9 relative (margin 10x).
    ini = L.integrals(TOP, *L.paper_initial_state(2)[:5])
    te = np.linspace(0.0, 40.0, 41)
    own = OwnClosedDrag(DRAG.a, DRAG.b)
    s = L.averaged(TOP, own, ini, (0.0, 40.0), tau_eval=te, rtol=1e-10)
    assert s.status == 0 and own.engine_calls == 0 and own.closed_calls > 0
    assert s.t_events["chart_switch"].size == 2  # both charts used
    r_exact = ini[2] * np.exp(-DRAG.b * te / C)
    np.testing.assert_allclose(s.r, r_exact, rtol=1e-8, atol=0)
    # the same closed form as the library's LinearDrag (another formula for <u>, the fused u-chart pass): equal
    # to the runs' global errors (1e-9 relative on rtol 1e-10 runs; H relative to its scale mgl near its zero)
    ref = L.averaged(TOP, DRAG, ini, (0.0, 40.0), tau_eval=te, rtol=1e-10)
    np.testing.assert_allclose(s.Gz, ref.Gz, rtol=1e-8, atol=1e-8 * np.abs(ref.Gz).max())
    np.testing.assert_allclose(s.H, ref.H, rtol=0, atol=1e-8 * max(np.abs(ref.H).max(), MGL))
    # a batch evaluates the hook on arrays of members (xp = ARRAY), still never the engine
    own_b = OwnClosedDrag(DRAG.a, DRAG.b)
    ini_b = np.array([spun(60.0), spun(120.0), spun(40.0, 2.0)])
    b = L.averaged(TOP, own_b, ini_b, (0.0, 20.0), tau_eval=te[:21], rtol=1e-10)
    assert np.all(b.status == 0) and own_b.engine_calls == 0 and own_b.closed_calls > 0
    np.testing.assert_allclose(b.r, ini_b[:, 2:3] * np.exp(-DRAG.b * te[:21] / C), rtol=1e-8, atol=0)


def test_a_torque_without_a_closed_form_gets_the_engine():
    # Slip caught: a torque without closed_means sent to a closed-form path (AttributeError / wrong rates), or
    # closed_form=True accepted for it. The engine's trapezoid rule converges spectrally: its averages of the
    # drag equal the closed form to ~1e-13, so the runs agree to their global errors (1e-9 relative).
    ini = spun(60.0)
    te = np.linspace(0.0, 10.0, 11)
    eng = EngineDrag(DRAG.a, DRAG.b)
    s = L.averaged(TOP, eng, ini, (0.0, 10.0), tau_eval=te, rtol=1e-10)
    assert s.status == 0 and eng.engine_calls > 0
    ref = L.averaged(TOP, DRAG, ini, (0.0, 10.0), tau_eval=te, rtol=1e-10)
    np.testing.assert_allclose(s.Gz, ref.Gz, rtol=1e-8, atol=1e-8 * np.abs(ref.Gz).max())
    with pytest.raises(TypeError, match=r"closed_means.*EngineDrag"):
        L.averaged(TOP, eng, ini, (0.0, 1.0), closed_form=True)
    with pytest.raises(TypeError, match=r"closed_means.*EngineDrag"):
        L.averaged_rhs(TOP, eng, -0.5, 0.2, 1.5, closed_form=True)
    # closed_form=False forces the engine on a torque that has a closed form
    own = OwnClosedDrag(DRAG.a, DRAG.b)
    L.averaged(TOP, own, ini, (0.0, 1.0), rtol=1e-8, closed_form=False)
    assert own.engine_calls > 0 and own.closed_calls == 0


@pytest.mark.parametrize("u", [(-0.5, 0.2, 1.5), (-0.9, -0.3, 1.1), (0.1, 0.6, 2.0)])
@pytest.mark.parametrize("d", [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0)])
def test_averaged_rhs_takes_a_users_closed_form(u, d):
    # Slip caught: averaged_rhs sending a user's closed form to the engine or to the printed (3.4) of LinearDrag
    # only. Against the printed (3.4) (drag_rhs): the two differ by rounding in <u> and in the map (2.8), a
    # few 1e-14 of the rates' scale; 1e-10 leaves margin for the (1 - u^2) factors near the poles.
    own = OwnClosedDrag(DRAG.a, DRAG.b)
    got = np.array(L.averaged_rhs(TOP, own, *u, *d))
    ref = np.array(L.averaged_rhs(TOP, DRAG, *u, *d))
    assert own.engine_calls == 0 and own.closed_calls == 1
    np.testing.assert_allclose(got, ref, rtol=1e-10, atol=1e-10 * np.abs(ref).max())
