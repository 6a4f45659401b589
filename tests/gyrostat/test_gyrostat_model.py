"""Input validation, singular places and the classical member of the family."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from rigidbody import gyrostat


def test_satellite_validation():
    with pytest.raises(ValueError, match="M must be finite and > 0"):
        gyrostat.Satellite(M=0.0, A1=1, A2=1, A3=1)
    with pytest.raises(ValueError, match="A2"):
        gyrostat.Satellite(M=1.0, A1=1, A2=-1, A3=1)
    with pytest.raises(ValueError, match="triangle inequality"):
        gyrostat.Satellite(M=1.0, A1=3, A2=1, A3=1)
    with pytest.raises(TypeError, match="k2 must be a real number"):
        gyrostat.Satellite(M=1.0, A1=1, A2=1, A3=1, k2="x")
    with pytest.raises(ValueError, match="mu"):
        gyrostat.Satellite(M=1.0, A1=1, A2=1, A3=1, mu=math.inf)
    sat = gyrostat.Satellite(M=2.0, A1=2.0, A2=1.0, A3=1.0)  # flat body: equality allowed
    assert math.isclose(sat.l, math.sqrt(4 / 3 / 2))
    with pytest.raises(AttributeError):
        sat.M = 3.0  # frozen


def test_stationary_motion_argument_errors():
    sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    with pytest.raises(TypeError, match="exactly one"):
        gyrostat.stationary_motion(sat, 1.0, 0.3)
    with pytest.raises(TypeError, match="exactly one"):
        gyrostat.stationary_motion(sat, 1.0, 0.3, k2=0.0, k3=0.0)
    with pytest.raises(ValueError, match="R0"):
        gyrostat.stationary_motion(sat, -1.0, 0.3, k2=0.0)
    with pytest.raises(ValueError, match="omega_sign"):
        gyrostat.stationary_motion(sat, 1.0, 0.3, k2=0.0, omega_sign=2)
    with pytest.raises(ValueError, match="k1 = 0"):
        gyrostat.stationary_motion(gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008, k1=0.1), 1.0, 0.3, k2=0)
    with pytest.raises(TypeError, match="Satellite"):
        gyrostat.stationary_motion("sat", 1.0, 0.3, k2=0)


def test_no_motion_for_a_too_large_body():
    # omega0^2 cos^2 kappa0 = mu/R0^3 {1 - 9/(2 M R0^2)[(A2 - A3) sin^2 th + (2 A3 - A1 - A2)/3]} <= 0
    # a rod along x1 (A2 = A3) of rms radius sqrt(0.705) < R0 = 1: it fits, but 4.5 [...] = 1.035 > 1
    sat = gyrostat.Satellite(M=1.0, A1=0.01, A2=0.7, A3=0.7)
    with pytest.raises(ValueError, match="too large"):
        gyrostat.stationary_motion(sat, 1.0, 0.3, k2=0.0)
    assert gyrostat.stability_map(sat, 1.0, np.array([0.3, 1.0]), k2=0.0).verdict.tolist() == ["invalid"] * 2


@pytest.mark.parametrize("R0", [0.1, 0.8, 0.8396])  # rms radius sqrt(0.705) = 0.83964
def test_body_that_does_not_fit_inside_its_orbit_is_rejected(R0):
    """rms radius sqrt((A1 + A2 + A3)/(2 M)) >= R0: some mass lies at least R0 from G, where the
    second-order potential of section 2 describes no real body (the old code returned a 'motion' with
    k3 ~ 1e11 for an SI body of size 1 m at R0 = 0.1 m)."""
    sat = gyrostat.Satellite(M=1.0, A1=0.01, A2=0.7, A3=0.7)
    with pytest.raises(ValueError, match=r"R0 = .* must exceed the rms radius"):
        gyrostat.stationary_motion(sat, R0, 0.3, k2=0.0)
    with pytest.raises(ValueError, match="rms radius"):
        gyrostat.exact_boundaries(sat, R0, np.array([0.3]))
    with pytest.raises(ValueError, match="rms radius"):
        gyrostat.normalized_stability_map(sat, R0, np.array([0.3]), np.array([0.1]))
    assert np.all(gyrostat.stability_map(sat, R0, np.array([0.3, 1.0]), k2=0.0).code == -1)
    sym = gyrostat.Satellite(M=1.0, A1=0.5, A2=0.5, A3=0.41)  # rms radius sqrt(0.705)
    with pytest.raises(ValueError, match="rms radius"):
        gyrostat.symmetric_stationary_motion(sym, R0, 0.3)
    assert np.all(gyrostat.symmetric_stability_map(sym, R0, np.array([0.3, 1.0])).code == -1)
    # just outside the rms radius the motion is computed
    gyrostat.symmetric_stationary_motion(sym, 1.0, 0.3)


def test_singular_places():
    sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    # theta0 = 0: the classical kappa0 = 0 member; k2 free, k3 = 0
    m = gyrostat.stationary_motion(sat, 1.0, 0.0, k2=0.004)
    assert m.classical and m.kappa0 == 0.0 and m.k3 == 0.0
    assert gyrostat.stability(m.satellite, m).verdict in ("stable", "unstable", "undecided")
    with pytest.raises(ValueError, match="give k2 instead"):
        gyrostat.stationary_motion(sat, 1.0, 0.0, k3=0.0)
    with pytest.raises(ValueError, match="requires k3 = 0"):
        gyrostat.stationary_motion(sat, 1.0, 0.0, k3=0.01)
    with pytest.warns(gyrostat.GyrostatWarning, match="ill-conditioned"):
        gyrostat.stationary_motion(sat, 1.0, 1e-9, k3=0.01)
    # theta0 + kappa0 -> pi/2 with k2 given: k3 diverges
    th = math.pi / 2 - 1e-8
    with pytest.warns(gyrostat.GyrostatWarning, match="ill-conditioned"):
        m = gyrostat.stationary_motion(sat, 1.0, th, k2=0.001)
    with pytest.raises(ValueError, match="singular"):
        gyrostat.stability(m.satellite, m)
    # theta0 is reduced to (-pi, pi]
    m1 = gyrostat.stationary_motion(sat, 1.0, 0.3 + 2 * math.pi, k2=0.001)
    m2 = gyrostat.stationary_motion(sat, 1.0, 0.3, k2=0.001)
    assert math.isclose(m1.theta0, m2.theta0) and math.isclose(m1.k3, m2.k3, rel_tol=1e-12)


def test_motion_geometry_and_omega_sign():
    sat = gyrostat.Satellite(M=1.0, A1=0.03, A2=0.02, A3=0.012)
    m = gyrostat.stationary_motion(sat, 1.0, 0.6, k2=0.01)
    b, g = np.array(m.beta), np.array(m.gamma)
    assert np.isclose(b @ b, 1) and np.isclose(g @ g, 1)
    assert np.isclose(b @ g, math.sin(m.kappa0))  # (2.1)
    assert math.isclose(m.displacement, math.sin(m.kappa0))
    mn = gyrostat.stationary_motion(sat, 1.0, 0.6, k2=0.01, omega_sign=-1)
    assert mn.omega0 == -m.omega0 and mn.kappa0 == m.kappa0
    # reversing omega0 and the rotor momentum together is the time-reversed motion: same k3 up to sign
    mr = gyrostat.stationary_motion(sat, 1.0, 0.6, k2=-0.01, omega_sign=-1)
    assert math.isclose(mr.k3, -m.k3, rel_tol=1e-12)
    with pytest.raises(TypeError, match="StationaryMotion"):
        gyrostat.stability(sat, "m")
    with pytest.raises(ValueError, match="differs"):
        gyrostat.stability(gyrostat.Satellite(M=2.0, A1=0.03, A2=0.02, A3=0.012), m)


def test_map_marks_singular_places_invalid_without_warnings():
    sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.009)
    th = np.array([-math.pi, -math.pi / 2, 0.0, 1e-300, math.pi / 2, math.pi, 0.3])
    a = gyrostat.stability_map(sat, 1.0, th, k2=np.array([0.0, 1e-3]))
    # cos theta0 = 0: the chart is singular
    assert np.all(a.code[[1, 4]] == -1) and np.all(a.code[[0, 2, 3, 5, 6]] >= 0)
    b = gyrostat.stability_map(sat, 1.0, th, k3=np.array([0.0, 1e-3]))
    # with k3 given, theta0 = 0, pi (and 1e-300) leave k2 undetermined / ill-conditioned
    assert np.all(b.code[:6] == -1) and np.all(b.code[6] >= 0)


def test_map_input_errors_name_the_parameters():
    sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    th, k2 = np.linspace(-1, 1, 5), np.linspace(-0.01, 0.01, 4)
    with pytest.raises(ValueError, match=r"theta0 \(5,\), k2 \(4,\)"):
        gyrostat.stability_map(sat, 1.0, th, k2=k2, grid=False)
    with pytest.raises(TypeError, match="theta0 must be a real number"):
        gyrostat.stability_map(sat, 1.0, "a", k2=0.0)
    assert gyrostat.stability_map(sat, 1.0, np.array([]), k2=k2).code.shape == (0, 4)
    sym = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.012, A3=0.008)
    with pytest.raises(ValueError, match=r"theta0 \(2,\), A3 \(3,\)"):
        gyrostat.symmetric_stability_map(sym, 1.0, np.array([0.2, 0.3]), A3=np.array([0.01, 0.02, 0.03]), grid=False)
    with pytest.raises(TypeError, match="A3 must be a real number"):
        gyrostat.symmetric_stability_map(sym, 1.0, np.array([0.2, 0.3]), A3="big")


def test_potential_outside_the_domain_of_the_direction_cosines():
    """beta1^2 + beta3^2 > 1 (or gamma1^2 + gamma2^2 > 1) has no real beta2 (gamma3): a clear error, not a
    NaN with a RuntimeWarning from sqrt (nor math's 'math domain error', nor a silent mpmath complex)."""
    import mpmath

    sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008, k2=0.01)
    for lib in (np, math, mpmath):
        with pytest.raises(ValueError, match=r"beta1\^2 \+ beta3\^2 must be <= 1"):
            gyrostat.amended_potential(sat, (1.0, 0.0, 0.8, 0.8, 0.0, 0.0), k=1.0, lam=0.1, lib=lib)
        with pytest.raises(ValueError, match=r"gamma1\^2 \+ gamma2\^2 must be <= 1"):
            gyrostat.chi((1.0, 0.0, 0.0, 0.0, 0.8, -0.8), lib=lib)
    with pytest.raises(ValueError, match="beta1"):
        gyrostat.gradient_W1(sat, (1.0, 0.0, np.array([0.1, 0.99]), 0.5, 0.0, 0.0), k=1.0, lam=0.1)
    # complex-step input is not checked (its real part is inside the domain here)
    z = gyrostat.amended_potential(sat, (1.0, 0.0, 0.1 + 1e-30j, 0.5, 0.0, 0.0), k=1.0, lam=0.1)
    assert np.isfinite(z.real) and z.imag != 0.0


@pytest.mark.parametrize("bad", [5, 0, 0.5, True, np.True_])
def test_omega_sign_is_plus_or_minus_one_everywhere(bad):
    """omega_sign multiplies omega0: symmetric_stability_map and exact_boundaries silently returned
    5 omega0 for omega_sign=5."""
    sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    sym = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.012, A3=0.008)
    th = np.array([0.3, 0.5])
    calls = [
        lambda: gyrostat.stationary_motion(sat, 1.0, 0.3, k2=0.0, omega_sign=bad),
        lambda: gyrostat.stability_map(sat, 1.0, th, k2=0.0, omega_sign=bad),
        lambda: gyrostat.exact_boundaries(sat, 1.0, th, omega_sign=bad),
        lambda: gyrostat.normalized_stability_map(sat, 1.0, th, np.array([0.1]), omega_sign=bad),
        lambda: gyrostat.symmetric_stationary_motion(sym, 1.0, 0.3, omega_sign=bad),
        lambda: gyrostat.symmetric_stability_map(sym, 1.0, th, omega_sign=bad),
    ]
    for call in calls:
        with pytest.raises(ValueError, match="omega_sign must be"):
            call()


@pytest.mark.parametrize("th", [1e-12, -3e-9, 1e-5, 0.3])
def test_small_tilts_are_not_rounded_by_the_angle_reduction(th):
    """theta0 in (-pi, pi] is used as given: the reduction (theta + pi) mod 2 pi - pi used to round it to the
    ulp of pi (theta0 = 1e-12 became 1.00009e-12, and kappa0 ~ theta0 with it).  kappa0 is checked against
    tan kappa0 = 3/2 (A2 - A3) n0 sin 2 theta0 / (M R0^2 n^2) at 50 digits (relative rounding only)."""
    import mpmath

    sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    m = gyrostat.stationary_motion(sat, 1.0, th, k2=0.001)
    assert m.theta0 == th
    with mpmath.workdps(50):
        A1, A2, A3, t = (mpmath.mpf(v) for v in (sat.A1, sat.A2, sat.A3, th))
        n2 = 1 - mpmath.mpf(9) / 2 * ((A2 - A3) * mpmath.sin(t) ** 2 + (2 * A3 - A1 - A2) / 3)
        kap = float(mpmath.atan(mpmath.mpf(3) / 2 * (A2 - A3) * mpmath.sin(2 * t) / n2))
    assert math.isclose(m.kappa0, kap, rel_tol=1e-14)
    sym = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.012, A3=0.008)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", gyrostat.GyrostatWarning)  # near the Euler chart's singular line
        assert gyrostat.symmetric_stationary_motion(sym, 1.0, th).theta0 == th
    # angles outside (-pi, pi] are still reduced
    assert math.isclose(gyrostat.stationary_motion(sat, 1.0, th + 2 * math.pi, k2=0.001).theta0, th,
                        abs_tol=1e-15)


def test_second_variation_helpers_check_the_body():
    """hessian_W1 / constrained_second_variation with another body silently mixed the two."""
    sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    m = gyrostat.stationary_motion(sat, 1.0, 0.3, k2=0.001)
    other = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.009)
    for f in (gyrostat.hessian_W1, gyrostat.constrained_second_variation, gyrostat.stability):
        with pytest.raises(ValueError, match=r"sat\.A3 differs"):
            f(other, m)
    with pytest.raises(TypeError, match="StationaryMotion"):
        gyrostat.hessian_W1(sat, "motion")
