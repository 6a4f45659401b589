"""The catalogue's closed-form averages against an average over the Euler-Poinsot motion written here from
scratch in mpmath (nothing of the module is used for it): the motion from mpmath's Jacobi functions with its
parameters from the conservation laws, checked against Euler's equations by a numerical derivative; the
attitude any rotation whose third row is g/G, the precession angle averaged on a uniform grid; the period by
the trapezoid rule (periodic, analytic) doubled until converged; dk2 by the chain rule of (5) at 30 digits.
The torques are written here too, from their physics."""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest

from rigidbody import euler_poinsot as ep

A = (3.2, 2.6, 1.67)
BODY = ep.Body(*A)
G0, DELTA, LAM = 1.2, 1.0, 0.3


def cross(a, b):
    return mp.matrix([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def rows_with_third(e3):
    """A proper rotation whose third row is the unit vector e3."""
    ref = mp.matrix([1, 0, 0]) if abs(e3[0]) < 0.9 else mp.matrix([0, 1, 0])
    e1 = cross(ref, e3)
    e1 /= mp.sqrt(dot(e1, e1))
    e2 = cross(e3, e1)
    return mp.matrix([[e1[i] for i in range(3)], [e2[i] for i in range(3)], [e3[i] for i in range(3)]])


class Motion:
    """omega = (sigma p dn s, beta q sn s, r cn s) in labelled axes, s = rate t, modulus k2; p, q, r from G
    and T at s = 0 and s = K, the rate from one of Euler's equations, the sign beta from all three."""

    def __init__(self, G, k2, kind, sigma):
        self.Ab = [mp.mpf(x) for x in A]
        self.idx = (0, 1, 2) if kind == "max" else (2, 1, 0)
        a1, a2, a3 = (self.Ab[i] for i in self.idx)
        self.G, self.k2, self.sigma = mp.mpf(G), mp.mpf(k2), sigma
        G, k2 = self.G, self.k2
        twoT = G**2 * ((a2 - a3) + k2 * (a1 - a2)) / (a1 * (a2 - a3) + k2 * a3 * (a1 - a2))  # (5) solved for T
        self.T = twoT / 2
        p2, r2 = mp.lu_solve(mp.matrix([[a1**2, a3**2], [a1, a3]]), mp.matrix([G**2, twoT]))
        q2 = (twoT - a1 * p2 * (1 - k2)) / a2
        # the second conservation law at s = K: the modulus is the right one
        assert abs(a1**2 * p2 * (1 - k2) + a2**2 * q2 - G**2) < mp.mpf(10) ** (-25)
        self.p, self.q, self.r = mp.sqrt(p2), mp.sqrt(q2), mp.sqrt(r2)
        self.rate = abs((a1 - a2) * self.p * self.q / (a3 * self.r))
        self.K = mp.ellipk(k2)
        residuals = {}
        for beta in (1, -1):
            self.beta = beta
            residuals[beta] = self.residual()
        self.beta = min(residuals, key=residuals.get)
        assert residuals[self.beta] < mp.mpf(10) ** (-20)  # it solves Euler's equations

    def omega(self, s, order=0):
        """omega (order 0), d omega/dt (1) or d2 omega/dt2 (2) in body axes at phase s."""
        sn, cn, dn = (mp.ellipfun(f, s, m=self.k2) for f in ("sn", "cn", "dn"))
        k2 = self.k2
        f = [(dn, sn, cn),
             (-k2 * sn * cn, cn * dn, -sn * dn),
             (-k2 * dn * (cn**2 - sn**2), -sn * dn**2 - k2 * sn * cn**2, -cn * dn**2 + k2 * sn**2 * cn)][order]
        lab = [self.sigma * self.p * f[0], self.beta * self.q * f[1], self.r * f[2]]
        out = [mp.mpf(0)] * 3
        for j, i in enumerate(self.idx):
            out[i] = lab[j] * self.rate**order
        return mp.matrix(out)

    def residual(self):
        worst = mp.mpf(0)
        for s in (mp.mpf("0.3"), mp.mpf("1.7")):
            w = self.omega(s)
            dw = [mp.diff(lambda x, i=i: self.omega(x)[i], s) * self.rate for i in range(3)]
            g = mp.matrix([self.Ab[i] * w[i] for i in range(3)])
            rhs = cross(g, w)
            worst = max(worst, *(abs(self.Ab[i] * dw[i] - rhs[i]) for i in range(3)))
        return worst


def average(torque, G, k2, kind, sigma, nu, e=0.0, n_psi=8, n_nu=8, depends_on_nu=True):
    """dG, dT, dk2, ddelta, dlam of torque(w, dw, ddw, C, nu) -> body torque, averaged over the motion."""
    mot = Motion(G, k2, kind, sigma)
    dl, lm = mp.mpf(DELTA), mp.mpf(LAM)
    n = mp.matrix([mp.sin(dl) * mp.cos(lm), mp.sin(dl) * mp.sin(lm), mp.cos(dl)])
    Y = rows_with_third(n).T  # columns y1, y2, n
    Rs = [Y * mp.matrix([[mp.cos(x), -mp.sin(x), 0], [mp.sin(x), mp.cos(x), 0], [0, 0, 1]])
          for x in (2 * mp.pi * j / n_psi for j in range(n_psi))]
    if nu is None and depends_on_nu:
        nus = [2 * mp.pi * j / n_nu for j in range(n_nu)]
        ws = [(1 + e * mp.cos(x)) ** -2 for x in nus]  # Kepler's law: time weight of nu
        ws = [x / sum(ws) for x in ws]
    else:
        nus, ws = [mp.mpf(0) if nu is None else mp.mpf(nu)], [mp.mpf(1)]
    cache = {}

    def node(j, N):
        key = mp.mpf(j) / N
        if key not in cache:
            s = 4 * mot.K * key
            w, dw, ddw = (mot.omega(s, k) for k in range(3))
            g = mp.matrix([mot.Ab[i] * w[i] for i in range(3)])
            al = rows_with_third(g / mp.sqrt(dot(g, g)))
            acc = mp.matrix([0] * 4)
            for R in Rs:
                C = R * al
                for x, wt in zip(nus, ws):
                    M = torque(w, dw, ddw, C, x)
                    CM = C * M
                    acc += wt * mp.matrix([CM[0], CM[1], CM[2], dot(w, M)])
            cache[key] = acc / n_psi
        return cache[key]

    N, prev = 32, None
    while True:
        cur = sum((node(j, N) for j in range(N)), mp.matrix([0] * 4)) / N
        if prev is not None and max(abs(cur[i] - prev[i]) for i in range(4)) < mp.mpf(10) ** (-22):
            break
        assert N < 4096
        prev, N = cur, 2 * N
    L, dT = mp.matrix([cur[0], cur[1], cur[2]]), cur[3]
    dG = dot(L, n)
    a1, a2, a3 = (mot.Ab[i] for i in mot.idx)
    G, T = mot.G, mot.T
    P, Q = 2 * T * a1 - G**2, G**2 - 2 * T * a3
    dP, dQ = 2 * a1 * dT - 2 * G * dG, 2 * G * dG - 2 * a3 * dT
    dk2 = (a2 - a3) / (a1 - a2) * (dP * Q - P * dQ) / Q**2
    dn = (L - dG * n) / G
    e_d = mp.matrix([mp.cos(dl) * mp.cos(lm), mp.cos(dl) * mp.sin(lm), -mp.sin(dl)])
    e_l = mp.matrix([-mp.sin(lm), mp.cos(lm), 0])
    return {"dG": dG, "dT": dT, "dk2": dk2, "ddelta": dot(dn, e_d), "dlam": dot(dn, e_l) / mp.sin(dl)}


# --- the torques, from their physics ---------------------------------------------------------------
M0 = [0.3, -0.2, 0.5]
P_CAV = [[0.4, 0.1, 0.0], [0.1, 0.7, 0.05], [0.0, 0.05, 0.3]]
I_OFF = [[2.322, 0.3, -0.2], [0.1, 1.31, 0.4], [0.25, -0.15, 1.425]]
M_MAG, B_CONST = [0.5, -0.3, 0.2], [0.1, 0.4, -0.7]


def constant(w, dw, ddw, C, nu):
    return mp.matrix(M0)


def cavity(w, dw, ddw, C, nu):
    # the fluid's relative angular momentum K = -P dw; the body feels -(dK/dt + w x K)
    P = mp.matrix(P_CAV)
    return P * ddw + cross(w, P * dw)


def magnet_field(nu):
    return mp.matrix([0.3 * mp.cos(nu), 0.2 * mp.sin(2 * nu), mp.mpf("0.8")])


def magnet(field):
    def torque(w, dw, ddw, C, nu):
        return cross(mp.matrix(M_MAG), C.T * field(nu))  # m x B, B in body axes

    return torque


def gravity(w, dw, ddw, C, nu):
    rho = C.T * mp.matrix([mp.cos(nu), mp.sin(nu), 0])  # unit radius vector in body axes
    return 3 * cross(rho, mp.matrix([A[i] * rho[i] for i in range(3)]))


def drag(w, dw, ddw, C, nu):
    return -(mp.matrix(I_OFF) * w)


def field_np(nu):
    nu = np.asarray(nu, dtype=float)
    return np.stack([0.3 * np.cos(nu), 0.2 * np.sin(2 * nu), 0.8 + 0 * nu], axis=-1)


CASES = {  # name: (torque object, mp torque, depends on nu)
    "ConstantTorque": (ep.ConstantTorque(M0), constant, False),
    "ViscousCavity": (ep.ViscousCavity(BODY, P_CAV), cavity, False),
    "MagneticDipole": (ep.MagneticDipole(M_MAG, B_CONST), magnet(lambda nu: mp.matrix(B_CONST)), False),
    "MagneticDipole(B(nu))": (ep.MagneticDipole(M_MAG, field_np), magnet(magnet_field), True),
    "GravityGradient": (ep.GravityGradient(BODY), gravity, True),
    "LinearDrag": (ep.LinearDrag(I_OFF), drag, False),
}


def check(name, k2, kind, sigma, nu):
    obj, ref_torque, nu_dep = CASES[name]
    with mp.workdps(30):
        ref = {k: float(v) for k, v in average(ref_torque, G0, k2, kind, sigma, nu, depends_on_nu=nu_dep).items()}
    got = ep.averaged_rates(BODY, obj, G0, k2, DELTA, LAM, nu, kind=kind, sigma=sigma)
    # the mean torque (G ddelta, G sin(delta) dlam, dG): relative to its size; dT and dk2 each relative to
    # itself. The closed forms are exact: rounding of double precision, a few units of 1e-16, times the
    # cancellation of N* where the mean moment about G nearly equals the mean moment (5e-14 seen)
    Ly = lambda r: np.array([G0 * r["ddelta"], G0 * math.sin(DELTA) * r["dlam"], r["dG"]])  # noqa: E731
    size = np.abs(Ly(ref)).max()
    assert np.abs(Ly(got) - Ly(ref)).max() <= 1e-13 * size + 1e-15
    for key in ("dT", "dk2"):
        assert abs(got[key] - ref[key]) <= 1e-13 * abs(ref[key]) + 1e-15, key


@pytest.mark.parametrize(
    ("name", "k2", "kind", "sigma", "nu"),
    [
        ("ConstantTorque", 1 - 1e-6, "min", -1, 0.7),
        ("ViscousCavity", 1e-3, "max", 1, 0.7),
        ("ViscousCavity", 0.9, "min", -1, None),
        ("MagneticDipole", 0.5, "max", -1, 0.7),
        ("MagneticDipole(B(nu))", 0.5, "min", 1, None),
        ("GravityGradient", 0.5, "max", 1, 0.7),
        ("LinearDrag", 0.9, "min", 1, 0.7),
    ],
)
def test_closed_forms_equal_an_independent_mpmath_average(name, k2, kind, sigma, nu):
    check(name, k2, kind, sigma, nu)


@pytest.mark.slow
@pytest.mark.parametrize("name", list(CASES))
@pytest.mark.parametrize("kind", ["max", "min"])
@pytest.mark.parametrize("sigma", [1, -1])
@pytest.mark.parametrize("k2", [1e-8, 0.25, 0.9, 1 - 1e-8])
@pytest.mark.parametrize("nu", [0.7, None])
def test_closed_forms_equal_an_independent_mpmath_average_everywhere(name, kind, sigma, k2, nu):
    check(name, k2, kind, sigma, nu)
