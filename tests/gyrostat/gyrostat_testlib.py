"""Shared helpers for the gyrostat tests: random parameter sets and extended-precision derivatives.

mpmath is the independent route: W1 is evaluated at 50 significant digits and differentiated
numerically (mpmath.diff), so the result shares no algebra with the printed closed forms and does not
suffer the float64 cancellation of SI units (W ~ mu M / R ~ 1e11 next to attitude terms ~ 1e-3).
"""

from __future__ import annotations

import math

import mpmath
import numpy as np

from rigidbody import gyrostat

DPS = 50


def random_body(rng: np.random.Generator, l_over_R: float, *, R0: float = 1.0, M: float = 1.0,
                mu: float = 1.0) -> gyrostat.Satellite:
    """A random triaxial body (triangle inequalities hold) with sqrt(Abar/M) = l_over_R * R0."""
    while True:
        a = rng.uniform(0.3, 1.0, 3)
        if all(a[i] <= a[(i + 1) % 3] + a[(i + 2) % 3] for i in range(3)):
            break
    a = a / a.mean() * M * (l_over_R * R0) ** 2
    return gyrostat.Satellite(M=M, A1=float(a[0]), A2=float(a[1]), A3=float(a[2]), mu=mu)


def mp_derivatives(f, x, order: int):
    """Gradient (order 1) or Hessian (order 2) of f at x by mpmath.diff at DPS digits."""
    n = len(x)
    with mpmath.workdps(DPS):
        xm = [mpmath.mpf(v) for v in x]
        if order == 1:
            out = np.empty(n)
            for i in range(n):
                nn = tuple(1 if j == i else 0 for j in range(n))
                out[i] = float(mpmath.diff(f, xm, nn))
            return out
        H = np.empty((n, n))
        for i in range(n):
            for j in range(i, n):
                nn = [0] * n
                nn[i] += 1
                nn[j] += 1
                H[i, j] = H[j, i] = float(mpmath.diff(f, xm, tuple(nn)))
        return H


def mp_W1(sat: gyrostat.Satellite, m: gyrostat.StationaryMotion):
    """W1 of motion m as an mpmath function of the 6 coordinates."""

    def f(*x):
        return gyrostat.amended_potential(sat, x, k=mpmath.mpf(m.k), lam=mpmath.mpf(m.lambda0),
                                          branch=m.branch, lib=mpmath)

    return f


def mp_W1_lambda(sat: gyrostat.Satellite, m: gyrostat.StationaryMotion):
    """W1 as an mpmath function of the 6 coordinates and lambda (for the section-4 Jacobian)."""

    def f(*x):
        return gyrostat.amended_potential(sat, x[:6], k=mpmath.mpf(m.k), lam=x[6], branch=m.branch, lib=mpmath)

    return f


def row_scale(H: np.ndarray) -> np.ndarray:
    """sqrt(D_i D_j) with D_i the max-norm of row i: the scale an inertia count sees after equilibration."""
    D = np.max(np.abs(H), axis=1)
    return np.sqrt(np.outer(D, D))


def motion_cases(seed: int = 2024):
    """Random (sat, motion) pairs covering l/R from 1e-3 to 0.3, both omega signs, all four branches."""
    rng = np.random.default_rng(seed)
    cases = []
    # principal branch, random tilt
    for l_R in (1e-3, 0.05, 0.2, 0.3):
        sat = random_body(rng, l_R)
        th = float(rng.uniform(-1.3, 1.3))
        k2 = float(rng.uniform(-3, 3)) * sat.Abar
        cases.append((sat, gyrostat.stationary_motion(sat, 1.0, th, k2=k2, omega_sign=int(rng.choice([-1, 1])))))
    # beta2 < 0 and gamma3 < 0: theta0 in (pi/2, pi) and (-pi, -pi/2)
    for th in (2.2, -2.5):
        sat = random_body(rng, 0.2)
        cases.append((sat, gyrostat.stationary_motion(sat, 1.0, th, k2=0.7 * sat.Abar)))
    # mixed branches need kappa0 > |pi/2 - theta0|, i.e. 3 (A2 - A3) / (M R0^2) > 1: a very large body
    # (l/R ~ 0.6); theta0 = pi/2 -+ 0.05 gives branches (-1, +1) and (+1, -1)
    sat = gyrostat.Satellite(M=1.0, A1=0.45, A2=0.5, A3=0.1)
    for th in (math.pi / 2 - 0.05, math.pi / 2 + 0.05):
        cases.append((sat, gyrostat.stationary_motion(sat, 1.0, th, k3=0.05)))
    # SI: a real satellite
    si = gyrostat.Satellite(M=1000.0, A1=1200.0, A2=1000.0, A3=800.0, mu=3.986e14)
    cases.append((si, gyrostat.stationary_motion(si, 7e6, math.pi / 4, k2=1.0)))
    cases.append((si, gyrostat.stationary_motion(si, 7e6, -0.3, k3=-2.0, omega_sign=-1)))
    return cases


class MPMotion:
    """The motion (2.3)-(2.4) recomputed at DPS digits from the same float inputs (R0, theta0, k2/k3).

    Needed in SI units: some second derivatives of W1 (e.g. W_g2g2 = G - lambda0 beta3 / gamma3^3) are
    O(l^2/R^2) differences of their terms, so evaluating them at the float64-rounded point (lambda0,
    kappa0 rounded to 1e-16) would change them at the 1e-16 (R/l)^2 level.
    """

    def __init__(self, m: gyrostat.StationaryMotion, *, given: str = "k2"):
        sat = m.satellite
        with mpmath.workdps(DPS):
            M, A1, A2, A3, mu = (mpmath.mpf(v) for v in (sat.M, sat.A1, sat.A2, sat.A3, sat.mu))
            R0, th = mpmath.mpf(m.R0), mpmath.mpf(m.theta0)
            n0 = mu / R0**3
            n2 = n0 * (1 - mpmath.mpf(9) / (2 * M * R0**2) * ((A2 - A3) * mpmath.sin(th) ** 2 + (2 * A3 - A1 - A2) / 3))
            kap = mpmath.atan(mpmath.mpf(3) / 2 * (A2 - A3) * n0 * mpmath.sin(2 * th) / (M * R0**2 * n2))
            om = mpmath.sign(m.omega0) * mpmath.sqrt(n2) / mpmath.cos(kap)
            sp, cp = mpmath.sin(th + kap), mpmath.cos(th + kap)
            rest = om**2 * (A2 - A3) * sp * cp + mpmath.mpf(3) / 2 * n0 * (A2 - A3) * mpmath.sin(2 * th)
            if given == "k2":
                k2 = mpmath.mpf(m.k2)
                k3 = (om * k2 * sp + rest) / (om * cp)
            else:
                k3 = mpmath.mpf(m.k3)
                k2 = (om * k3 * cp - rest) / (om * sp)
            S0 = M * R0**2 * mpmath.cos(kap) ** 2 + A2 * cp**2 + A3 * sp**2
            self.k = om * S0 + k2 * cp + k3 * sp
            self.lam = M * R0**2 * om**2 * mpmath.sin(kap)
            self.point = [R0, kap, mpmath.mpf(0), sp, mpmath.mpf(0), -mpmath.sin(th)]
            self.k2, self.k3, self.kappa0, self.omega0, self.theta0 = k2, k3, kap, om, th
            self.M, self.A1, self.A2, self.A3, self.mu = M, A1, A2, A3, mu
        self.branch = m.branch

    def W1(self, *x):
        b2s, g3s = self.branch
        R, kap, b1, b3, g1, g2 = x
        b2 = b2s * mpmath.sqrt(1 - b1**2 - b3**2)
        g3 = g3s * mpmath.sqrt(1 - g1**2 - g2**2)
        K = self.k - self.k2 * b2 - self.k3 * b3
        S = self.M * R**2 * mpmath.cos(kap) ** 2 + self.A1 * b1**2 + self.A2 * b2**2 + self.A3 * b3**2
        U = self.mu * self.M / R - mpmath.mpf(3) / 2 * self.mu / R**3 * (
            self.A1 * g1**2 + self.A2 * g2**2 + self.A3 * g3**2 - (self.A1 + self.A2 + self.A3) / 3)
        chi = b1 * g1 + b2 * g2 + b3 * g3 - mpmath.sin(kap)
        return K**2 / (2 * S) - U + self.lam * chi

    def hessian(self, *, as_mp: bool = False):
        """The 6x6 Hessian of W1 at the motion: float64 (default) or an mpmath matrix at DPS digits."""
        n = 6
        with mpmath.workdps(DPS):
            H = mpmath.matrix(n, n)
            for i in range(n):
                for j in range(i, n):
                    nn = [0] * n
                    nn[i] += 1
                    nn[j] += 1
                    H[i, j] = H[j, i] = mpmath.diff(self.W1, self.point, tuple(nn))
        if as_mp:
            return H
        return np.array([[float(H[i, j]) for j in range(n)] for i in range(n)])

    def constrained_form(self):
        """delta^2 W1 on the tangent space of chi = 0 (2.1), at DPS digits, in the order
        (gamma1, beta1, R, kappa, beta3): delta gamma2 = cos th delta kappa - cos th / cos(th + ka) delta beta3
        eliminated with the 50-digit kappa0 (an mpmath matrix, 5x5)."""
        H = self.hessian(as_mp=True)
        with mpmath.workdps(DPS):
            ct, cp = mpmath.cos(self.theta0), mpmath.cos(self.theta0 + self.kappa0)
            T = mpmath.zeros(6, 5)
            T[4, 0] = 1  # gamma1
            T[2, 1] = 1  # beta1
            T[0, 2] = 1  # R
            T[1, 3] = 1  # kappa
            T[5, 3] = ct
            T[3, 4] = 1  # beta3
            T[5, 4] = -ct / cp
            return T.T * H * T
