"""The eddy-current torque and the geomagnetic dipole field: the closed-form averages against the averaging engine
and against a quadrature written here (another construction of the motion and the attitude, the orbit in mean
anomaly), the dissipation, the sphere's exponential spin-down, averaged against full runs, and the field against
the dipole formula in inertial axes."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
from scipy import special

from rigidbody import euler_poinsot as ep
from rigidbody.euler_poinsot._eddy import omega_moments, sn4_mean

BODIES = [ep.Body(3.2, 2.6, 1.67), ep.Body(1.0, 0.8, 0.5), ep.Body(2.0, 1.9, 0.3)]
P_GENERAL = np.array([[0.4, 0.1, -0.05], [0.1, 0.7, 0.08], [-0.05, 0.08, 0.3]])
TENSORS = {"isotropic": 0.3, "general": P_GENERAL}
ECC = 0.2
R_ORBIT = 1.25 * ep.IGRF_RADIUS


def dipole(orbit):
    """The IGRF dipole on an inclined orbit, in units of |g10| (order-one numbers)."""
    return ep.DipoleField(1.0, 0.4, R_ORBIT, orbit, scale=1.0 / abs(ep.IGRF13_G10))


def field_of(name, orbit):
    return np.array([0.1, 0.4, -0.7]) if name == "constant" else dipole(orbit)


# (k2, nu, e): held and orbit-averaged, circular and eccentric, near and far from the separatrix
STATES = [(0.3, 0.7, 0.0), (0.9, None, ECC), (0.05, 2.5, ECC), (0.6, None, 0.0)]
G, DELTA, LAM = 1.2, 1.0, 0.3


def n_of(delta, lam):
    return np.array([math.sin(delta) * math.cos(lam), math.sin(delta) * math.sin(lam), math.cos(delta)])


# --------------------------------------------------------------------------------------------------
# an independent quadrature of the averages
# --------------------------------------------------------------------------------------------------
def completed(v, a):
    """A rotation matrix (rows) whose third row is the unit vector ``v``, by Gram-Schmidt from the vector ``a``."""
    r1 = a - (v @ a)[..., None] * v
    r1 = r1 / np.linalg.norm(r1, axis=-1, keepdims=True)
    return np.stack([r1, np.cross(v, r1), v], axis=-2)


def motion(body, G, k2, kind, sigma, n_u):
    """Body angular velocity on n_u uniform phase nodes of a period, from the energy and the amplitudes of the
    Euler-Poinsot motion written out here (Landau-Lifshitz sec. 37) and SciPy's Jacobi functions."""
    idx = (0, 1, 2) if kind == "max" else (2, 1, 0)
    a1, a2, a3 = (body.A[i] for i in idx)
    T = G**2 * ((a2 - a3) + k2 * (a1 - a2)) / (2.0 * (a1 * (a2 - a3) + k2 * a3 * (a1 - a2)))
    w1 = math.sqrt((G**2 - 2 * T * a3) / (a1 * (a1 - a3)))
    w2 = math.sqrt((2 * T * a1 - G**2) / (a2 * (a1 - a2)))
    w3 = math.sqrt((2 * T * a1 - G**2) / (a3 * (a1 - a3)))
    K = special.ellipk(k2)
    u = np.arange(n_u) * (4 * K / n_u)
    sn, cn, dn, _ = special.ellipj(u, k2)
    omega = np.empty((n_u, 3))
    omega[:, idx[0]], omega[:, idx[1]], omega[:, idx[2]] = sigma * w1 * dn, -sigma * w2 * sn, w3 * cn
    return omega, T, (a1, a2, a3), idx


def orbit_nodes(nu, e, n_nu):
    """The held true anomaly, or uniform mean-anomaly nodes of the orbit (Kepler's equation by Newton)."""
    if nu is not None:
        return np.array([nu])
    Mn = np.arange(n_nu) * (2 * math.pi / n_nu)
    E = Mn.copy()
    for _ in range(50):
        E = E - (E - e * np.sin(E) - Mn) / (1 - e * np.cos(E))
    return 2 * np.arctan2(math.sqrt(1 + e) * np.sin(E / 2), math.sqrt(1 - e) * np.cos(E / 2))


def pairwise_mean(X):
    """The mean over every node of ``X`` (..., 3), by NumPy's pairwise summation along a contiguous axis (a
    reduction over several strided axes would add the ~1e5 terms one by one, with errors ~1e-12)."""
    Y = np.ascontiguousarray(X.reshape(-1, X.shape[-1]).T)
    return Y.sum(axis=1) / Y.shape[1]


def reference_mean(body, torque, k2, kind, sigma, n, nu, e, n_u=256, n_psi=8, n_nu=64):
    """<C M>, dT, dk2 by the tensor-product trapezoid rule over (nu, psi, u): exact over psi (the integrands are
    trigonometric polynomials of degree <= 3 in psi), geometric over the phase and the mean anomaly."""
    omega, T, (a1, a2, a3), idx = motion(body, G, k2, kind, sigma, n_u)
    g = omega * body.A
    R0 = completed(g / G, np.array([0.3, 1.0, -0.2]))  # body -> frame of G, (n_u, 3, 3)
    F = completed(n, np.array([1.0, -0.4, 0.5])).T  # columns y1, y2, n
    psi = np.arange(n_psi) * (2 * math.pi / n_psi)
    c, s = np.cos(psi), np.sin(psi)
    Rz = np.zeros((n_psi, 3, 3))
    Rz[:, 0, 0], Rz[:, 0, 1], Rz[:, 1, 0], Rz[:, 1, 1], Rz[:, 2, 2] = c, -s, s, c, 1.0
    C = F @ Rz[:, None] @ R0[None]  # (n_psi, n_u, 3, 3)
    nus = orbit_nodes(nu, e, n_nu)
    M = torque(omega[None, None], C[None], nus[:, None, None])  # (n_nu, n_psi, n_u, 3)
    L = pairwise_mean((C[None] @ M[..., None])[..., 0])
    OM = pairwise_mean(omega * M)
    A = np.array([a1, a2, a3])
    OM = OM[list(idx)]  # labelled
    dP, dQ = 2 * ((a1 - A) * OM).sum(), 2 * ((A - a3) * OM).sum()
    Pv, Qv = 2 * T * a1 - G**2, G**2 - 2 * T * a3
    cc = (a2 - a3) / (a1 - a2)
    assert cc * Pv / Qv == pytest.approx(k2, rel=1e-13, abs=1e-15)  # the motion's T is that of k2: (5)
    return L, OM.sum(), (cc * dP - k2 * dQ) / Qv


@pytest.mark.parametrize("body", BODIES, ids=["case", "flat", "prolate"])
@pytest.mark.parametrize("tensor", list(TENSORS))
@pytest.mark.parametrize("kind", ["max", "min"])
@pytest.mark.parametrize("field_name", ["constant", "dipole"])
def test_closed_form_equals_an_independent_quadrature(body, tensor, kind, field_name):
    for j, (k2, nu, e) in enumerate(STATES):
        orbit = ep.Orbit(e)
        tq = ep.EddyCurrent(TENSORS[tensor], field_of(field_name, orbit))
        sigma = 1 if j % 2 else -1
        n = n_of(DELTA, LAM + 0.5 * j)
        st = ep.State(body, kind, sigma, G, k2, n, nu, orbit)
        m = tq.closed_mean(st)
        L, dT, dk2 = reference_mean(body, tq, k2, kind, sigma, n, nu, e)
        # the reference converges to rounding: twice the nodes along every axis moves it by < 1e-14 (checked on
        # the first state); both routes round at a few 1e-16 of the O(1) terms they add (measured: L and dT agree
        # to 3e-15), and dk2 = (c dP - k2 dQ)/Q loses a factor c = (a2 - a3)/(a1 - a2) (16 for the prolate body)
        # to cancellation (measured 1e-13). 1e-12 keeps a margin of 10 there and catches any wrong term (a slip
        # in one coefficient moves a rate by > 1e-4 here)
        if j == 0:
            L2, dT2, dk22 = reference_mean(body, tq, k2, kind, sigma, n, nu, e, 512, 16, 128)
            assert np.abs(L2 - L).max() < 1e-14 and abs(dT2 - dT) < 1e-14 and abs(dk22 - dk2) < 1e-14
        scale = np.abs(L).max()
        assert np.abs(m.L - L).max() <= 1e-12 * scale, (k2, nu, m.L, L)
        assert m.dT == pytest.approx(dT, rel=1e-12, abs=0), (k2, nu)
        assert m.dk2 == pytest.approx(dk2, rel=1e-12, abs=1e-15), (k2, nu)


@pytest.mark.parametrize("tensor", list(TENSORS))
@pytest.mark.parametrize("kind", ["max", "min"])
@pytest.mark.parametrize("sigma", [1, -1])
@pytest.mark.parametrize("k2", [1e-8, 0.25, 0.95, 1 - 1e-6])
def test_closed_form_equals_the_engine(tensor, kind, sigma, k2):
    for body, (nu, e) in zip(BODIES, [(0.7, 0.0), (None, ECC), (None, 0.0)]):
        orbit = ep.Orbit(e)
        tq = ep.EddyCurrent(TENSORS[tensor], dipole(orbit))
        kw = dict(kind=kind, sigma=sigma, orbit=orbit)
        closed = ep.averaged_rates(body, tq, G, k2, DELTA, LAM, nu, **kw)
        eng = ep.averaged_rates(body, tq, G, k2, DELTA, LAM, nu, method="numerical", **kw)
        # the engine converges to its tolerance 1e-12 of the torque's size (O(1) here); dk2 tends to zero with
        # k2 (it is O(k2)), and the engine forms it from means of O(1) terms: the floor 1e-14 covers that
        for key in closed:
            assert closed[key] == pytest.approx(eng[key], rel=1e-12, abs=1e-14), (key, body)


# --------------------------------------------------------------------------------------------------
# the torque itself
# --------------------------------------------------------------------------------------------------
def random_rotations(rng, n):
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    w, x, y, z = q.T
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], -1),
        np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], -1),
        np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], -1)], -2)


def test_torque_dissipates_and_has_the_power_of_its_definition():
    rng = np.random.default_rng(21)
    for _ in range(20):
        X = rng.normal(size=(3, 3))
        P = X @ X.T * rng.uniform(0.1, 3)  # positive semi-definite
        if _ % 4 == 0:
            P = np.outer(X[0], X[0])  # rank one: a thin plate or a loop
        omega, C, B = rng.normal(size=(50, 3)), random_rotations(rng, 50), rng.normal(size=3)
        M = ep.EddyCurrent(P, B)(omega, C, 0.0)
        b = np.einsum("nij,i->nj", C, B)
        wb = np.cross(omega, b)
        power = np.einsum("ni,ni->n", omega, M)
        # omega . M = -(omega x b) . P (omega x b) to rounding, and never positive
        assert np.allclose(power, -np.einsum("ni,ij,nj->n", wb, P, wb), rtol=1e-12, atol=1e-12)
        assert power.max() <= 1e-12 * np.abs(power).max()
        # the definition written out: (P (omega x b)) x b, with P acting on the column vector
        assert np.allclose(M, np.cross(wb @ P.T, b), rtol=1e-13, atol=1e-13)


def test_the_averaged_energy_never_grows():
    # <omega . M> <= 0 at every state, both kinds, any field
    rng = np.random.default_rng(5)
    for _ in range(30):
        X = rng.normal(size=(3, 3))
        tq = ep.EddyCurrent(X @ X.T, rng.normal(size=3))
        n = rng.normal(size=3)
        st = ep.State(BODIES[_ % 3], ("max", "min")[_ % 2], 1, 1.0, rng.uniform(0, 0.99), n / np.linalg.norm(n),
                      0.0, ep.Orbit())
        assert tq.closed_mean(st).dT <= 0.0


@pytest.mark.parametrize(("P", "match"), [
    ([[1.0, 0.2, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], "symmetric"),
    ([1.0, -0.5, 1.0], "positive semi-definite"),
    (-1.0, "positive semi-definite"),
    ([[1.0, 2.0]], "3x3"),
    ([1.0, math.nan, 1.0], "finite"),
])
def test_bad_tensors_are_refused(P, match):
    with pytest.raises(ValueError, match=match):
        ep.EddyCurrent(P, [0.0, 0.0, 1.0])


def test_bad_fields_are_refused():
    with pytest.raises(TypeError, match="B must be"):
        ep.EddyCurrent(1.0, "north")
    with pytest.raises(ValueError, match="B must be 3 finite"):
        ep.EddyCurrent(1.0, [1.0, 2.0])
    with pytest.raises(TypeError, match="P must be"):
        ep.EddyCurrent("big", [1.0, 0.0, 0.0])
    tq = ep.EddyCurrent(1.0, lambda nu: np.zeros(2))  # a field of the wrong shape is named
    with pytest.raises(ValueError, match="the field B"):
        tq(np.ones(3), np.eye(3), 0.0)


def test_a_dipole_field_for_another_orbit_is_refused():
    tq = ep.EddyCurrent(1.0, dipole(ep.Orbit(ECC)))
    with pytest.raises(ValueError, match="built for"):
        ep.averaged_rates(BODIES[0], tq, 1.0, 0.3, 1.0, 0.3, None)


# --------------------------------------------------------------------------------------------------
# dynamics
# --------------------------------------------------------------------------------------------------
def test_a_near_sphere_spins_down_across_the_field_at_the_rate_p_B2_over_A():
    # For a sphere (moment A) with P = p I in a constant field, M = -p b x (omega x b): the spin across the
    # field decays as exp(-p B^2 t / A) and the spin along it stays. A triaxial body within 0.2 % of a sphere
    # must show both with A between A3 and A1 (the averaged rate is p B^2 2T/G^2, 2T/G^2 between 1/A1 and 1/A3)
    body = ep.Body(1.002, 1.001, 1.0)
    p, B = 0.4, np.array([0.0, 0.6, 0.8])  # |B| = 1
    tau = np.linspace(0.0, 2.0, 5)
    sol = ep.averaged(body, ep.EddyCurrent(p, B), 0.0, G0=1.0, k2_0=0.5, delta0=1.1, lam0=0.2,
                      tau_span=(0.0, 2.0), tau_eval=tau, solver=ep.Solver(rtol=1e-11, atol=1e-13))
    assert sol.status == 0, sol.message
    Gv = sol.G * sol.n  # (3, len(tau))
    along = B @ Gv
    across = np.linalg.norm(Gv - np.outer(B, along), axis=0)
    # the component along B is constant to the integrator's tolerance (1e-11 relative, over a few steps)
    assert np.abs(along - along[0]).max() < 1e-9
    rate = -np.log(across[1:] / across[0]) / (p * tau[1:])
    assert np.all(rate > 1 / 1.002 - 1e-9) and np.all(rate < 1 / 1.0 + 1e-9), rate


def errors(torque, eps, tau1=0.3, k2_0=0.8, orbit=None):
    """Largest difference full - averaged over tau in [0, tau1] of G, T, k2 and the direction n of G."""
    te = np.linspace(0, tau1, 7)
    kw = dict(k2_0=k2_0, tau_span=(0, tau1), tau_eval=te, delta0=1.0, lam0=0.3, nu0=0.5, orbit=orbit)
    s = ep.simulate(BODIES[0], torque, eps, **kw)
    a = ep.averaged(BODIES[0], torque, eps, **kw)
    assert s.status == 0 and a.status == 0, (s.message, a.message)
    err = [np.abs(getattr(s, f) - getattr(a, f)).max() for f in ("G", "T", "k2")]
    return max(*err, np.linalg.norm(s.n - a.n, axis=0).max())


def test_averaged_follows_the_full_motion():
    # first-order averaging of an O(eps^2) torque with nu explicit: the slow variables of the full motion
    # follow the averaged ones to O(eps^2) over tau = O(1) (as for the catalogue's torques); two eps
    orbit = ep.Orbit(ECC)
    tq = ep.EddyCurrent(P_GENERAL * 2.0, dipole(orbit))
    e1, e2 = errors(tq, 0.04, orbit=orbit), errors(tq, 0.02, orbit=orbit)
    assert math.log2(e1 / e2) > 1.6, (e1, e2)
    assert e2 < 20 * 0.02**2  # an O(1) constant, as in test_euler_poinsot_engine_vs_full (measured 13.9)


# --------------------------------------------------------------------------------------------------
# the field
# --------------------------------------------------------------------------------------------------
def R1(x):
    c, s = math.cos(x), math.sin(x)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def R3(x):
    c, s = math.cos(x), math.sin(x)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


@pytest.mark.parametrize("node", [0.0, 1.3])
def test_dipole_field_is_the_dipole_formula_in_inertial_axes(node):
    # inertial axes (z the Earth's axis), the orbit by its elements: perifocal -> inertial R3(node) R1(i) R3(argp);
    # the dipole of moment m = g10 a^3 4 pi/mu0 z: B = (mu0/4 pi r^3) (3 (m . rh) rh - m); back into orbital axes
    i, argp, a, e = 1.1, 0.7, 1.4 * ep.IGRF_RADIUS, 0.15
    f = ep.DipoleField(i, argp, a, ep.Orbit(e))
    Q = R3(node) @ R1(i) @ R3(argp)
    for nu in np.linspace(0, 2 * math.pi, 9):
        r = a * (1 - e * e) / (1 + e * math.cos(nu))
        rh = Q @ np.array([math.cos(nu), math.sin(nu), 0.0])
        m = ep.IGRF13_G10 * ep.IGRF_RADIUS**3 * np.array([0.0, 0.0, 1.0])
        B = (3 * (m @ rh) * rh - m) / r**3
        # two routes through a few rotations and powers: rounding, 1e-13 of |g10| leaves a factor of 100
        assert np.allclose(Q.T @ B, f(nu), rtol=1e-13, atol=1e-13 * abs(ep.IGRF13_G10))
    # vectorised over nu: the same numbers element by element (the same operations: to the last bit, 1e-15)
    nus = np.linspace(0, 6, 12).reshape(3, 4)
    assert f(nus).shape == (3, 4, 3)
    assert np.allclose(f(nus)[1, 2], f(nus[1, 2]), rtol=1e-15, atol=0)


def test_dipole_field_strength():
    # the IGRF-13 g10 (2020): 29404.8 nT at the equator on the reference sphere, 1/8 of it at two radii
    f = ep.DipoleField(0.0, 0.0, 2 * ep.IGRF_RADIUS, scale=1e9)
    # an equatorial orbit: |B| = |g10| (aE/r)^3 exactly, up to the rounding of a few products (1e-14)
    assert np.linalg.norm(f(0.3)) == pytest.approx(29404.8 / 8, rel=1e-14, abs=0)


def test_dipole_field_refuses_bad_orbits():
    with pytest.raises(ValueError, match="inclination"):
        ep.DipoleField(4.0, 0.0, 1e7)
    with pytest.raises(ValueError, match="in metres"):
        ep.DipoleField(1.0, 0.0, 7000.0)  # kilometres by mistake
    with pytest.raises(ValueError, match="scale"):
        ep.DipoleField(1.0, 0.0, 1e7, scale=0.0)


# --------------------------------------------------------------------------------------------------
# the elliptic means
# --------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("k2", [0.0, 1e-12, 1e-9, 1e-8, 2e-8, 1e-6, 0.1, 0.5, 0.99, 1 - 1e-9])
def test_mean_of_sn4_against_mpmath(k2):
    # <sn^4> = int_0^{pi/2} sin^4/Delta / K; below k2 = 1e-8 the series branch, above the AGM one: both to a few
    # roundings (the terms are positive), 4e-16 relative
    mpmath.mp.dps = 30
    m = mpmath.mpf(k2)
    ref = mpmath.quad(lambda p: mpmath.sin(p) ** 4 / mpmath.sqrt(1 - m * mpmath.sin(p) ** 2), [0, mpmath.pi / 2])
    ref = float(ref / mpmath.ellipk(m))
    assert sn4_mean(k2, float(1 - m)) == pytest.approx(ref, rel=4e-16, abs=0)


@pytest.mark.parametrize("kind", ["max", "min"])
@pytest.mark.parametrize("k2", [1e-6, 0.4, 0.97])
def test_moments_of_the_angular_velocity(kind, k2):
    # every entry of the second and fourth moments (also those the eddy torque's averages do not use) against
    # the trapezoid rule over SciPy's Jacobi functions (converged: 1024 nodes; 1e-13 of the largest entry)
    body = BODIES[1]
    st = ep.State(body, kind, -1, G, k2, n_of(DELTA, LAM), 0.0, ep.Orbit())
    m2, m4 = omega_moments(st)
    omega, *_ = motion(body, G, k2, kind, -1, 1024)
    r2 = np.einsum("ni,nj->ij", omega, omega) / len(omega)
    r4 = np.einsum("ni,nj,nk,nl->ijkl", omega, omega, omega, omega) / len(omega)
    assert np.abs(m2 - r2).max() <= 1e-13 * np.abs(r2).max()
    assert np.abs(m4 - r4).max() <= 1e-13 * np.abs(r4).max()


def test_orbit_mean_of_a_field_that_is_no_polynomial_in_nu():
    # a field with a pole near the real axis (at nu = pi +- 0.2i): the trapezoid rule converges like exp(-0.2 n),
    # so the orbit mean of B B^T needs 256-512 nodes, three doublings of the first 64; against the mean in time
    # written here, uniform in the mean anomaly (4096 nodes: converged to rounding)
    def field(nu):
        nu = np.asarray(nu, dtype=float)
        return np.stack([np.exp(np.cos(nu)), 0.1 / (1.02 + np.cos(nu)), 0.5 + 0 * nu], axis=-1)

    e = 0.3
    tq = ep.EddyCurrent(1.0, field)
    B = field(orbit_nodes(None, e, 4096))
    ref = B.T @ B / len(B)
    # both sums round at ~1e-16 of the largest entry; the doubling stops at an agreement of 4e-15
    assert np.abs(tq.field_square(None, e) - ref).max() <= 1e-14 * np.abs(ref).max()
