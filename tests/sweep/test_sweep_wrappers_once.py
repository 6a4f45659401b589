"""The batched wrappers integrate a chunk once: the work of a call equals that of the one batch call it makes.

The measure is the number of times the torque is evaluated (a plain function torque that counts its calls):
a wrapper that runs the chunk twice (once as a single run, then again as a batch of one, as
``euler_poinsot_averaged`` did for an all-scalar chunk) evaluates it about twice as often as the one call.
"""

from __future__ import annotations

import math

import numpy as np

from rigidbody import euler_poinsot as ep
from rigidbody import lagrange as L
from rigidbody.sweep import euler_poinsot_averaged, lagrange_averaged

BODY = ep.Body(A1=3.2, A2=2.6, A3=1.67)
RATES = np.array([0.3, 0.2, 0.1])


class Counted:
    """A drag-like torque ``-rates * omega`` (the engine averages it) that counts its evaluations."""

    def __init__(self) -> None:
        self.calls = 0

    def __call__(self, omega, C, nu):
        self.calls += 1
        return -RATES * omega


def test_euler_poinsot_wrapper_integrates_an_all_scalar_call_once():
    # Slip caught: the wrapper ran an all-scalar chunk as a single run, found no batch shape and ran it again
    # as a batch of one (about twice the evaluations). The reference is the batch-of-one call the wrapper
    # makes; the same call twice costs exactly twice, so 1.5 separates one call from two with margin.
    wrapped, direct = Counted(), Counted()
    out = euler_poinsot_averaged(body=BODY, torque=wrapped, G0=1.0, k2_0=0.5, tau_span=(0.0, 0.5))
    sol = ep.averaged(BODY, direct, np.atleast_1d(0.0), 1.0, 0.5, math.pi / 4, math.pi / 4, (0.0, 0.5), [0.5])
    assert direct.calls > 0 and wrapped.calls < 1.5 * direct.calls, (wrapped.calls, direct.calls)
    # and it returns that call's result, one row per point (the same computation: agreement to rounding)
    assert out["G"].shape == (1,)
    np.testing.assert_allclose(out["G"], sol.G[:, -1], rtol=1e-12, atol=0)


def test_lagrange_wrapper_passes_the_components_straight_through():
    # the grid's arrays as the components of initial: a (3,) chunk of spins with Gz0, H0 shared; the linear
    # drag keeps r = r0 exp(-b tau / C) exactly (3.3), so each point's spin at tau = 2 is known in closed form
    # (tolerance: the integrator's rtol 1e-10 relative on r, with a factor 10 of margin)
    Gz, H, r = L.integrals(L.PAPER_TOP, 0.0, 0.0, 1.7, 0.0, math.radians(70.0))
    r0 = r * np.array([0.9, 1.0, 1.02])
    out = lagrange_averaged(top=L.PAPER_TOP, torque=L.PAPER_DRAG, Gz0=Gz, H0=H, r0=r0, tau_span=(0.0, 2.0),
                            rtol=1e-10)
    exact = r0 * np.exp(-L.PAPER_DRAG.b * 2.0 / L.PAPER_TOP.C)
    np.testing.assert_allclose(out["r"], exact, rtol=1e-9, atol=0)
    assert list(out["status"]) == [0, 0, 0]
