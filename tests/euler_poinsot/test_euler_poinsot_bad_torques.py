"""A torque that misbehaves is named, at every entry point, and one that turns bad part-way ends the run.

A user's torque that returned NaN or inf gave ``averaged_rates`` silent NaN rates; a wrong shape gave NumPy's
"operands could not be broadcast"; complex numbers lost their imaginary part; a scalar was broadcast to
``(s, s, s)``; None became NaN. Every entry must raise a TypeError/ValueError that names the torque (the
function's repr) and what was expected. A torque that is finite until some time and NaN after used to end
the run with "mc must lie in [0, 1] ... nan" or "Required step size is less than spacing"; the run must end
with status -1 and a message naming the torque and the time it turned bad.
"""

from __future__ import annotations

import re

import numpy as np
import pytest

from rigidbody import euler_poinsot as ep

BODY = ep.Body(3.2, 2.6, 1.67)
CASE1 = np.diag([2.322, 1.31, 1.425])


def drag(o, C, nu):
    return -np.asarray(o) @ CASE1.T


def returns_nan(o, C, nu):
    return np.full(np.shape(o), np.nan)


def returns_inf(o, C, nu):
    return drag(o, C, nu) + np.inf


def returns_none(o, C, nu):
    return None


def returns_two_components(o, C, nu):
    return drag(o, C, nu)[..., :2]


def returns_complex(o, C, nu):
    return drag(o, C, nu) * (1.0 + 0.5j)


def returns_scalar(o, C, nu):
    return 0.1


#: torque -> (exception, what the message says was wrong)
BAD = {
    returns_nan: (ValueError, "non-finite values"),
    returns_inf: (ValueError, "non-finite values"),
    returns_none: (TypeError, "returned None"),
    returns_two_components: (ValueError, r"an array of shape \(.*2,?\)"),
    returns_complex: (TypeError, "complex numbers"),
    returns_scalar: (ValueError, r"a scalar \(0\.1\)"),
}

#: every public entry that evaluates a torque: the engine (orbit-averaged and with nu held), the averaged runs
#: (engine path, and a sum with a closed-form part, whose bad part must be the one named), the full equations
ENTRIES = {
    "averaged_rates": lambda tq: ep.averaged_rates(BODY, tq, 1.0, 0.5, 0.7, 0.2, None),
    "averaged_rates_nu": lambda tq: ep.averaged_rates(BODY, tq, 1.0, 0.5, 0.7, 0.2, 0.3),
    "average_torque": lambda tq: ep.average_torque(BODY, tq, 1.0, 0.5, 0.7, 0.2, None),
    "averaged": lambda tq: ep.averaged(BODY, tq, 0.0, k2_0=0.5, tau_span=(0.0, 0.1)),
    "averaged_sum": lambda tq: ep.averaged(BODY, ep.GravityGradient(BODY) + tq, 0.02, k2_0=0.5,
                                           tau_span=(0.0, 0.1)),
    "simulate": lambda tq: ep.simulate(BODY, tq, 0.05, k2_0=0.5, tau_span=(0.0, 0.01)),
    "simulate_angles": lambda tq: ep.simulate(BODY, tq, 0.05, k2_0=0.5, tau_span=(0.0, 0.01),
                                              formulation="angles"),
    "separatrix_limits": lambda tq: ep.separatrix_limits(BODY, tq, 1.0, 0.7, 0.2, None),
}


@pytest.mark.parametrize("entry", list(ENTRIES))
@pytest.mark.parametrize("torque", list(BAD), ids=lambda f: f.__name__)
def test_a_bad_torque_is_named_with_what_was_expected(entry, torque):
    exc, what = BAD[torque]
    with pytest.raises(exc) as err:
        ENTRIES[entry](torque)
    msg = str(err.value)
    assert f"the torque {torque!r} returned" in msg  # the user's function, by its repr
    assert re.search(what, msg), msg
    assert "expected finite real numbers of shape (..., 3)" in msg


def test_the_field_of_a_magnet_is_checked_too():
    def field(nu):
        return np.stack([np.cos(nu), np.sin(nu), np.zeros_like(nu)], axis=-1) * 1j

    with pytest.raises(TypeError, match=re.escape(f"the field B {field!r} returned complex numbers")):
        ep.averaged_rates(BODY, ep.MagneticDipole([0.1, 0.2, 0.3], field), 1.0, 0.5, 0.7, 0.2, 0.3)


def test_a_constant_torque_may_return_its_three_components():
    # the one rule: a result that broadcasts to (..., 3) is a torque (a constant (3,)), a scalar is not
    def const(o, C, nu):
        return np.array([0.0, 0.0, 0.2])

    a = ep.averaged_rates(BODY, const, 1.0, 0.5, 0.7, 0.2, None)
    b = ep.averaged_rates(BODY, ep.ConstantTorque([0.0, 0.0, 0.2]), 1.0, 0.5, 0.7, 0.2, None, method="numerical")
    for k in a:  # the same quadrature of the same torque
        assert a[k] == pytest.approx(b[k], rel=0, abs=1e-14), k


# ---- a torque that turns bad part-way ---------------------------------------------------------------
NU1 = 4.0


def late(o, C, nu):
    """Linear drag while nu <= NU1, NaN after."""
    return np.where(np.asarray(nu)[..., None] > NU1, np.nan, drag(o, C, nu))


#: runs in which the true anomaly nu = tau/eps + nu0 (nu0 = 0) reaches NU1 at tau = NU1 eps = 0.2
PARTWAY = {
    "simulate": lambda: ep.simulate(BODY, late, 0.05, k2_0=0.5, tau_span=(0.0, 0.5)),
    "simulate_angles": lambda: ep.simulate(BODY, late, 0.05, k2_0=0.5, tau_span=(0.0, 0.5), formulation="angles"),
    "averaged": lambda: ep.averaged(BODY, late, 0.05, k2_0=0.5, tau_span=(0.0, 0.5)),
    "averaged_sum": lambda: ep.averaged(BODY, ep.GravityGradient(BODY) + late, 0.05, k2_0=0.5, tau_span=(0.0, 0.5)),
}


@pytest.mark.parametrize("run", list(PARTWAY))
def test_a_torque_that_turns_nan_part_way_ends_the_run_with_a_status_naming_it(run):
    sol = PARTWAY[run]()
    assert sol.status == -1
    assert sol.message.startswith("at tau = 0.2: ") and f"the torque {late!r} returned non-finite" in sol.message
    # the failing steps close in on the time the torque turns bad (to the spacing of floats) before the run ends
    assert sol.tau[-1] == pytest.approx(NU1 * 0.05, rel=0, abs=1e-9)
    assert np.all(np.isfinite(sol.G))


def test_a_torque_that_turns_nan_below_some_G_ends_the_orbit_averaged_run_there():
    # eps = 0: the torque is NaN once the decaying G falls below 0.8; the run must end with the torque named,
    # at the state where G = 0.8 (the failing steps shrink onto it: G to ~1e-15, well within 1e-9)
    def weak(o, C, nu):
        o = np.asarray(o)
        G = np.linalg.norm(o * BODY.A, axis=-1)
        return np.where((G < 0.8)[..., None], np.nan, drag(o, C, nu))

    sol = ep.averaged(BODY, weak, 0.0, k2_0=0.5, tau_span=(0.0, 3.0))
    assert sol.status == -1 and f"the torque {weak!r} returned non-finite" in sol.message
    assert sol.G[-1] == pytest.approx(0.8, rel=0, abs=1e-9)
    when = re.match(r"at tau = (\S+): ", sol.message)
    assert when and float(when.group(1)) == pytest.approx(sol.tau[-1], rel=1e-5, abs=0)  # printed to 6 digits


def test_in_a_batch_only_the_members_whose_torque_turns_bad_end_that_way():
    # nu0 = -10 keeps nu <= 0 over the span: that member runs to the end
    sol = ep.simulate(BODY, late, 0.05, k2_0=0.5, nu0=np.array([0.0, -10.0]), tau_span=(0.0, 0.3),
                      min_spin_ratio=0.0)
    one = ep.simulate(BODY, late, 0.05, k2_0=0.5, nu0=0.0, tau_span=(0.0, 0.3), min_spin_ratio=0.0)
    assert sol.status.tolist() == [-1, 0]
    assert sol.message[0] == one.message  # the single call's message
    assert sol.t_final[0] == pytest.approx(NU1 * 0.05, rel=0, abs=1e-9)  # as the single run's (see above)
    # the averaged batch of torque objects runs member by member: the single call's message as well
    av = ep.averaged(BODY, late, 0.05, k2_0=0.5, nu0=np.array([0.0, -10.0]), tau_span=(0.0, 0.3))
    assert av.status.tolist() == [-1, 0]
    assert av.message[0] == ep.averaged(BODY, late, 0.05, k2_0=0.5, tau_span=(0.0, 0.3)).message
