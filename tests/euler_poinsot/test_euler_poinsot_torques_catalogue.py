"""The catalogue beyond the paper's two torques: each closed-form average against the averaging engine,
plus the physics each one must show (dissipation, the major-axis rule, precession about the field)."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from rigidbody import euler_poinsot as ep
from rigidbody.euler_poinsot._catalogue import _sn4_mean

BODY = ep.Body(3.2, 2.6, 1.67)
DELTA, LAM = 1.0, 0.3


def turning_field(nu):
    nu = np.asarray(nu, dtype=float)
    return np.stack([0.3 * np.cos(nu), 0.2 * np.sin(2 * nu), 0.8 + 0 * nu], axis=-1)


CATALOGUE = {
    "ConstantTorque": ep.ConstantTorque([0.3, -0.2, 0.5]),
    "ViscousCavity": ep.ViscousCavity(BODY, [[0.4, 0.1, 0.0], [0.1, 0.7, 0.05], [0.0, 0.05, 0.3]]),
    "MagneticDipole": ep.MagneticDipole([0.5, -0.3, 0.2], [0.1, 0.4, -0.7]),
    "MagneticDipole(B(nu))": ep.MagneticDipole([0.5, -0.3, 0.2], turning_field),
}


def L_y(r, G=1.2):
    """The averaged torque in the frame of G: (G ddelta, G sin(delta) dlam, dG)."""
    return np.array([G * r["ddelta"], G * math.sin(DELTA) * r["dlam"], r["dG"]])


@pytest.mark.parametrize("name", list(CATALOGUE))
@pytest.mark.parametrize("kind", ["max", "min"])
@pytest.mark.parametrize("sigma", [1, -1])
@pytest.mark.parametrize("k2", [1e-8, 1e-3, 0.15, 0.25, 0.9, 1 - 1e-6])
@pytest.mark.parametrize("nu", [0.7, None])
def test_catalogue_closed_forms_equal_the_engine(name, kind, sigma, k2, nu):
    tq = CATALOGUE[name]
    closed = ep.averaged_rates(BODY, tq, 1.2, k2, DELTA, LAM, nu, kind=kind, sigma=sigma)
    eng = ep.average_torque(BODY, tq, 1.2, k2, DELTA, LAM, nu, kind=kind, sigma=sigma)
    assert eng.converged
    Lc, Le = L_y(closed), L_y(eng.rates)
    # the engine is exact to rounding for these smooth torques: 1e-12 relative to each average, plus the
    # rounding of a mean of O(1) terms (the torques here are of order 1), 1e-14, where an average is exactly
    # zero or tends to zero at the separatrix (the mean of dn is pi/2K -> 0)
    assert np.abs(Le - Lc).max() <= 1e-12 * np.abs(Lc).max() + 1e-14
    for key in ("dT", "dk2"):
        assert abs(eng.rates[key] - closed[key]) <= 1e-12 * abs(closed[key]) + 1e-14, key


def test_mean_of_sn4_is_stable_on_both_sides_of_the_switch():
    # series below k2 = 0.2, recurrence above: both against mpmath's quadrature of sin^4/Delta over K
    mpmath.mp.dps = 30
    for k2 in (0.0, 1e-12, 1e-6, 0.1, 0.19999, 0.2, 0.20001, 0.5, 0.99, 1 - 1e-9):
        m = mpmath.mpf(k2)

        def density(p, m=m):
            return mpmath.sin(p) ** 4 / mpmath.sqrt(1 - m * mpmath.sin(p) ** 2)

        I2 = mpmath.quad(density, [0, mpmath.pi / 2])
        ref = float(I2 / mpmath.ellipk(m))
        # double rounding of the formulas: a few units of 1e-16
        assert _sn4_mean(k2) == pytest.approx(ref, rel=2e-15, abs=0), k2


def test_constant_torque_acts_through_the_mean_of_the_body_angular_momentum():
    # independent route: <g> over the closed-form motion (EulerPoinsot.nodes), only its component along
    # the axis of rotation is non-zero; <C M0> = n (<g> . M0)/G, <omega . M0> = <omega> . M0
    M0 = np.array([0.3, -0.2, 0.5])
    for kind, axis in (("max", 0), ("min", 2)):
        for sigma in (1, -1):
            m = ep.EulerPoinsot(BODY, 1.2, 0.6, kind, sigma)
            _, g = m.nodes()
            gbar = g.mean(axis=1)
            assert np.abs(np.delete(gbar, axis)).max() < 1e-14
            r = ep.averaged_rates(BODY, ep.ConstantTorque(M0), 1.2, 0.6, DELTA, LAM, 0.4, kind=kind, sigma=sigma)
            assert r["dG"] == pytest.approx(gbar @ M0 / 1.2, rel=1e-13, abs=0)
            assert r["dT"] == pytest.approx((gbar / BODY.A) @ M0, rel=1e-13, abs=0)
            assert abs(r["ddelta"]) < 1e-15 and abs(r["dlam"]) < 1e-15  # along G only (rounding of n -> Oy)


@pytest.mark.parametrize("kind", ["max", "min"])
def test_viscous_cavity_dissipates_and_drives_towards_the_major_axis(kind):
    # A highly viscous fluid is internal: G is conserved on average, T decreases; hence G^2/2T grows and
    # k2 moves towards rotation about the axis of the largest moment: k2 -> 0 for 'max', k2 -> 1 (the
    # separatrix, then the other kind) for 'min' -- the flat spin of Explorer 1.
    tq = ep.ViscousCavity(BODY, [1.0, 2.0, 0.5])
    for k2 in np.linspace(0.01, 0.99, 25):
        r = ep.averaged_rates(BODY, tq, 1.0, k2, DELTA, LAM, None, kind=kind)
        assert r["dG"] == 0.0 and r["dT"] < 0
        assert (r["dk2"] < 0) if kind == "max" else (r["dk2"] > 0)


def test_magnet_precesses_G_about_the_field():
    B = np.array([0.1, 0.4, -0.7])
    tq = ep.MagneticDipole([0.5, -0.3, 0.2], B)
    for sigma in (1, -1):
        t = ep.average_torque(BODY, tq, 1.2, 0.6, DELTA, LAM, 0.4, sigma=sigma)
        n = np.array([math.sin(DELTA) * math.cos(LAM), math.sin(DELTA) * math.sin(LAM), math.cos(DELTA)])
        # dn is perpendicular to n and to B: a rotation about B (G, T and k2 unchanged)
        assert abs(t.dn @ n) < 1e-14 and abs(t.dn @ B) < 1e-14
        assert abs(t.rates["dG"]) < 1e-14 and abs(t.rates["dT"]) < 1e-14 and abs(t.rates["dk2"]) < 1e-14
    # ... in the opposite sense for the opposite rotation
    d1 = ep.average_torque(BODY, tq, 1.2, 0.6, DELTA, LAM, 0.4, sigma=1).dn
    d2 = ep.average_torque(BODY, tq, 1.2, 0.6, DELTA, LAM, 0.4, sigma=-1).dn
    np.testing.assert_allclose(d1, -d2, rtol=0, atol=1e-14)


@pytest.mark.parametrize("e", [0.3, 0.7])
@pytest.mark.parametrize("kind", ["max", "min"])
def test_magnet_on_an_eccentric_orbit_feels_the_time_mean_of_the_field(e, kind):
    # nu averaged: the field turning with the orbit, B(nu) = (0.3 cos nu, 0.2 sin 2nu, 0.8), acts through its
    # mean over time, in which nu is weighted by Kepler's law: <cos nu> = -e, <sin 2nu> = 0 (derived here:
    # dM = (1 - e^2)^(3/2) (1 + e cos nu)^-2 dnu, and the integral of cos nu dM over the orbit is -2 pi e),
    # i.e. the constant field (-0.3 e, 0, 0.8) -- not the mean over nu, (0, 0, 0.8)
    orb = ep.Orbit(e)
    m = [0.5, -0.3, 0.2]
    turning = ep.MagneticDipole(m, turning_field)
    const = ep.MagneticDipole(m, [-0.3 * e, 0.0, 0.8])
    ref = L_y(ep.averaged_rates(BODY, const, 1.2, 0.6, DELTA, LAM, None, kind=kind, orbit=orb))
    closed = L_y(ep.averaged_rates(BODY, turning, 1.2, 0.6, DELTA, LAM, None, kind=kind, orbit=orb))
    eng = L_y(ep.average_torque(BODY, turning, 1.2, 0.6, DELTA, LAM, None, kind=kind, orbit=orb).rates)
    # the field's orbit mean by 256 (closed form) or the engine's nodes, both spectrally accurate: rounding
    assert np.abs(closed - ref).max() <= 1e-13 * np.abs(ref).max()
    assert np.abs(eng - ref).max() <= 1e-12 * np.abs(ref).max()


@pytest.mark.parametrize(
    ("call", "exc", "match"),
    [
        (lambda: ep.ConstantTorque([1.0, 2.0]), ValueError, "shape"),
        (lambda: ep.ConstantTorque([1.0, np.nan, 0.0]), ValueError, "finite"),
        (lambda: ep.ConstantTorque("abc"), TypeError, "M"),
        (lambda: ep.ViscousCavity(BODY, [[1, 2, 0], [0, 1, 0], [0, 0, 1]]), ValueError, "symmetric"),
        (lambda: ep.ViscousCavity(BODY, [1.0, -2.0, 1.0]), ValueError, "semi-definite"),
        (lambda: ep.ViscousCavity((3, 2, 1), [1.0, 1.0, 1.0]), TypeError, "Body"),
        (lambda: ep.MagneticDipole([1.0, 0.0, 0.0], [1.0, 0.0]), ValueError, "B"),
        (lambda: ep.MagneticDipole([1.0, math.inf, 0.0], [1.0, 0.0, 0.0]), ValueError, "m"),
        (lambda: ep.averaged(BODY, ep.ViscousCavity(ep.Body(3, 2, 1.5), [1, 1, 1]), 0.0), ValueError, "Body"),
    ],
)
def test_bad_catalogue_input_is_named(call, exc, match):
    with pytest.raises(exc, match=match):
        call()
