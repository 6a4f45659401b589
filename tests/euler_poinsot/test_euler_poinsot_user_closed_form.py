r"""The torque protocol of rigidbody.euler_poinsot: a closed-form average is a capability the torque declares.

A torque class written here (no library file touched) that defines ``closed_mean`` gets the closed-form path of
``averaged_rates`` and ``averaged`` -- its ``__call__`` is never evaluated on a grid -- and the same class without
it gets the averaging engine. The torque is constant in the orbital axes, :math:`\mathbf M = C^T\mathbf m`
(body components of a fixed orbital vector :math:`\mathbf m`), which the catalogue does not have
(``ConstantTorque`` is constant in the body axes). Its average, derived here:

- :math:`C\mathbf M = \mathbf m` at every point of the motion, so :math:`\langle C\mathbf M\rangle = \mathbf m`;
- :math:`\boldsymbol\omega\cdot\mathbf M = (C\boldsymbol\omega)\cdot\mathbf m`, and the mean over the
  precession angle about :math:`\mathbf G` keeps only the component of :math:`C\boldsymbol\omega` along
  :math:`\mathbf n`, which is :math:`\boldsymbol\omega\cdot\mathbf G/G = 2T/G` exactly: :math:`\langle dT\rangle
  = (2T/G)\,\mathbf m\cdot\mathbf n`;
- :math:`k^2` is a function of :math:`2T/G^2` alone ((5): :math:`k^2 = c(2Ta_1 - G^2)/(G^2 - 2Ta_3)`), and
  :math:`d(T/G^2) = \dot T/G^2 - 2T\dot G/G^3` averages to :math:`(2T/G^3 - 2T/G^3)\,\mathbf m\cdot\mathbf n = 0`
  (:math:`\langle\dot G\rangle = \mathbf n\cdot\mathbf m`): :math:`\langle dk^2\rangle = 0`.

So the averaged run is solved exactly: :math:`G\mathbf n = G_0\mathbf n_0 + \mathbf m\tau`, :math:`k^2` constant.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rigidbody import euler_poinsot as ep

BODY = ep.Body(3.2, 2.6, 1.67)
M_ORB = np.array([0.12, -0.07, 0.05])
DELTA, LAM = 1.0, 0.3


class EngineOrbitFixed(ep.Torque):
    """A torque constant in the orbital axes, through the protocol's required part only: the engine averages it."""

    def __init__(self, m):
        self.m = np.asarray(m, dtype=float)
        self.calls = 0

    def __call__(self, omega, C, nu):
        self.calls += 1
        return np.einsum("...ji,j->...i", np.asarray(C, dtype=float), self.m)  # C^T m


class OwnClosedOrbitFixed(EngineOrbitFixed):
    """The same torque with its own closed form (the module docstring)."""

    def __init__(self, m):
        super().__init__(m)
        self.closed_calls = 0

    def closed_mean(self, st):
        self.closed_calls += 1
        mn = float(self.m @ st.n)
        return ep.Mean(self.m.copy(), 2.0 * st.T / st.G * mn, 0.0)


def rates_vector(r):
    return np.array([r["dG"], r["dT"], r["dk2"], r["ddelta"], r["dlam"]])


@pytest.mark.parametrize("kind", ["max", "min"])
@pytest.mark.parametrize("sigma", [1, -1])
@pytest.mark.parametrize("k2", [0.05, 0.6, 0.9])
@pytest.mark.parametrize("nu", [0.7, None])
def test_a_users_closed_form_is_used_and_agrees_with_the_engine(kind, sigma, k2, nu):
    # Slips caught: the closed-form path not taken for a user's class (calls > 0), the hook read under another
    # name, a closed form summed with the wrong frame or sign (differs from the engine), method='numerical' not
    # forcing the engine (closed_calls counted there, or calls == 0).
    own = OwnClosedOrbitFixed(M_ORB)
    closed = ep.averaged_rates(BODY, own, 1.2, k2, DELTA, LAM, nu, kind=kind, sigma=sigma)
    assert own.calls == 0 and own.closed_calls > 0
    used = own.closed_calls
    eng = ep.average_torque(BODY, own, 1.2, k2, DELTA, LAM, nu, kind=kind, sigma=sigma)
    assert own.calls > 0 and own.closed_calls == used
    assert eng.converged
    err = rates_vector(eng.error)
    # the engine's reported error bounds its distance from the exact average (its contract), plus the rounding
    # of means of O(0.1) terms, 1e-14, where the reported error is itself at rounding level
    assert np.all(np.abs(rates_vector(closed) - rates_vector(eng.rates)) <= err + 1e-14)
    # and the closed form is the one written above, not a library copy: dk2 = 0 and dG = m . n
    n = np.array([math.sin(DELTA) * math.cos(LAM), math.sin(DELTA) * math.sin(LAM), math.cos(DELTA)])
    assert closed["dk2"] == 0.0
    assert closed["dG"] == pytest.approx(float(M_ORB @ n), rel=1e-14, abs=1e-15)  # a dot product: rounding


@pytest.mark.parametrize("kind", ["max", "min"])
def test_the_same_torque_without_a_closed_form_gets_the_engine(kind):
    # Slips caught: a torque without closed_mean sent down the closed path (AttributeError, or no evaluations),
    # the base class's default closed_mean not returning None.
    eng_tq = EngineOrbitFixed(M_ORB)
    auto = ep.averaged_rates(BODY, eng_tq, 1.2, 0.6, DELTA, LAM, None, kind=kind)
    assert eng_tq.calls > 0
    ref = ep.average_torque(BODY, EngineOrbitFixed(M_ORB), 1.2, 0.6, DELTA, LAM, None, kind=kind)
    closed = ep.averaged_rates(BODY, OwnClosedOrbitFixed(M_ORB), 1.2, 0.6, DELTA, LAM, None, kind=kind)
    # within the engine's reported error (plus rounding, as above)
    assert np.all(np.abs(rates_vector(auto) - rates_vector(closed)) <= rates_vector(ref.error) + 1e-14)


def exact_run(tau, G0, n0):
    """G n = G0 n0 + m tau, k2 constant (the module docstring)."""
    g = G0 * n0[:, None] + M_ORB[:, None] * tau[None, :]
    G = np.linalg.norm(g, axis=0)
    return G, g / G


def test_averaged_runs_with_and_without_the_closed_form_agree_with_the_exact_solution():
    # Slips caught: a run with a user's closed form evaluating the torque on grids (calls > 0), a run of either
    # path drifting from the exact solution (a wrong frame of L, a dk2 that is not zero).
    G0, k2_0, tau = 1.0, 0.4, np.linspace(0.0, 2.0, 9)
    n0 = np.array([math.sin(DELTA) * math.cos(LAM), math.sin(DELTA) * math.sin(LAM), math.cos(DELTA)])
    G_ex, n_ex = exact_run(tau, G0, n0)
    own, eng_tq = OwnClosedOrbitFixed(M_ORB), EngineOrbitFixed(M_ORB)
    runs = {}
    for name, tq in (("closed", own), ("engine", eng_tq)):
        sol = ep.averaged(BODY, tq, 0.0, G0=G0, k2_0=k2_0, delta0=DELTA, lam0=LAM, tau_span=(0.0, 2.0),
                          tau_eval=tau, rtol=1e-10, atol=1e-12)
        assert sol.status == 0, sol.message
        runs[name] = sol
        # the integrator's tolerance rtol = 1e-10 over 2 time units of a smooth, non-stiff system: a 1e-8
        # global error is a 100x margin; the engine's averages are exact to rounding for this smooth torque
        assert np.abs(sol.G - G_ex).max() <= 1e-8
        assert np.abs(np.asarray(sol.n) - n_ex).max() <= 1e-8
        assert np.abs(np.asarray(sol.k2) - k2_0).max() <= 1e-8
    assert own.calls == 0 and own.closed_calls > 0
    assert eng_tq.calls > 0
    # the two runs agree to the sum of their distances from the exact solution (each <= 1e-8 above)
    assert np.abs(runs["closed"].G - runs["engine"].G).max() <= 2e-8


class FlakyClosedForm(OwnClosedOrbitFixed):
    """A closed form that stops giving one part-way through a kind of motion (a contract breach)."""

    def closed_mean(self, st):
        return None if self.closed_calls > 3 else super().closed_mean(st)


class WrongShapeClosedForm(OwnClosedOrbitFixed):
    def closed_mean(self, st):
        return ep.Mean(np.zeros(2), 0.0, 0.0)


def test_a_closed_mean_that_breaks_the_contract_is_named():
    # Slips caught: None after a Mean within a kind of motion or a Mean of the wrong shape reaching the
    # integrator (an obscure TypeError/broadcast error, or silent garbage) instead of an error naming the torque.
    with pytest.raises(TypeError, match=r"FlakyClosedForm.*closed_mean returned None"):
        ep.averaged(BODY, FlakyClosedForm(M_ORB), 0.0, k2_0=0.4, tau_span=(0.0, 1.0))
    with pytest.raises(ValueError, match=r"WrongShapeClosedForm.*closed_mean must return a Mean"):
        ep.averaged_rates(BODY, WrongShapeClosedForm(M_ORB), 1.2, 0.4, DELTA, LAM, None)


class BuiltForOneBody(EngineOrbitFixed):
    def check_setup(self, body, orbit):
        if body != BODY:
            raise ValueError(f"{self!r} was built for {BODY!r}")


def test_a_users_check_setup_refuses_another_body():
    # Slip caught: the public check_setup hook not called at a run's start (the run would go on).
    other = ep.Body(3.0, 2.5, 1.6)
    with pytest.raises(ValueError, match="was built for"):
        ep.averaged(other, BuiltForOneBody(M_ORB), 0.0, k2_0=0.4, tau_span=(0.0, 1.0))
    with pytest.raises(ValueError, match="was built for"):
        ep.averaged_rates(other, BuiltForOneBody(M_ORB), 1.2, 0.4, DELTA, LAM, None)
