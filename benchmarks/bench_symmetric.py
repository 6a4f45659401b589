"""A body with two equal moments: the averaged system over the regular precession against the full motion
integrated by SciPy, at equal accuracy.

Run on demand: python benchmarks/bench_symmetric.py

A prolate body ``SymmetricBody(2, 1)`` under an axisymmetric drag and the gravity gradient on a circular orbit,
eps = 0.01, from the nutation angle 0.8 rad, over two orbits (tau in [0, 4 pi eps]; about 150 spin turns). The
straightforward SciPy version is the full motion written here (Euler's equations with a quaternion,
``solve_ivp(method='DOP853')``, the torque from its physics); its reference run is at rtol 1e-12. The error of
either side is the largest difference in G, cos(theta) and the direction of G from that reference after whole
orbits (where the orbital oscillation of the osculating variables returns to its start): the averaging error,
O(eps^2), for ``euler_poinsot.averaged``. The full motion's time at that accuracy is interpolated (log-log)
over a sweep of its rtol.

Times are CPU seconds of this process (the best of a few repeats); the ratio comes from one run. The line
starting with ``RATIO`` is collected by ``benchmarks/run_all.py``.
"""

from __future__ import annotations

import math

import numpy as np
from common import cpu_time, time_at_accuracy
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation

from rigidbody import euler_poinsot as ep

BODY = ep.SymmetricBody(2.0, 1.0)
DRAG = np.diag([0.1, 0.1, 0.3])
EPS, TH0, DELTA0, LAM0, NU0 = 0.01, 0.8, 1.0, 0.3, 0.2
TAU1 = 2 * 2 * math.pi * EPS  # two orbits
N_OUT = 3  # the start and the ends of the two orbits


def full(rtol: float) -> np.ndarray:
    """G, cos(theta) and the direction of G (rows: output times) of the full motion at ``rtol``."""
    n0 = np.array([math.sin(DELTA0) * math.cos(LAM0), math.sin(DELTA0) * math.sin(LAM0), math.cos(DELTA0)])
    Y = np.array([[math.cos(DELTA0) * math.cos(LAM0), -math.sin(LAM0), n0[0]],
                  [math.cos(DELTA0) * math.sin(LAM0), math.cos(LAM0), n0[1]], [-math.sin(DELTA0), 0.0, n0[2]]])
    R0 = Y @ Rotation.from_euler("ZXZ", [0.0, TH0, 0.0]).as_matrix()
    A = BODY.A

    def rhs(t, y):
        g, (x, yq, z, s) = y[:3], y[3:] / np.linalg.norm(y[3:])
        w = g / A
        nu = NU0 + EPS * t
        R = Rotation.from_quat([x, yq, z, s]).as_matrix()
        rho = R.T @ np.array([math.cos(nu), math.sin(nu), 0.0])
        M = 3.0 * np.cross(rho, A * rho) - DRAG @ w
        dq = 0.5 * np.array([s * w[0] + yq * w[2] - z * w[1], s * w[1] + z * w[0] - x * w[2],
                             s * w[2] + x * w[1] - yq * w[0], -(x * w[0] + yq * w[1] + z * w[2])])
        return np.concatenate([np.cross(g, w) + EPS**2 * M, dq])

    t_out = np.linspace(0.0, TAU1 / EPS**2, N_OUT)
    sol = solve_ivp(rhs, (0.0, t_out[-1]), np.concatenate([R0.T @ n0, Rotation.from_matrix(R0).as_quat()]),
                    method="DOP853", rtol=rtol, atol=rtol * 1e-2, t_eval=t_out)
    out = []
    for k in range(N_OUT):
        g, R = sol.y[:3, k], Rotation.from_quat(sol.y[3:, k]).as_matrix()
        G = np.linalg.norm(g)
        out.append(np.concatenate([[G, g[2] / G], R @ g / G]))
    return np.array(out)


def averaged() -> np.ndarray:
    tq = ep.LinearDrag(DRAG) + ep.GravityGradient(BODY)
    s = ep.averaged(BODY, tq, EPS, theta0=TH0, delta0=DELTA0, lam0=LAM0, nu0=NU0, tau_span=(0.0, TAU1),
                    tau_eval=np.linspace(0.0, TAU1, N_OUT), rtol=1e-10)
    return np.column_stack([s.G, np.cos(s.theta), s.n.T])


def main() -> None:
    ref = full(1e-12)
    avg = averaged()
    e_avg = float(np.abs(avg - ref).max())
    t_avg = cpu_time(averaged, repeat=3)
    print(f"euler_poinsot.averaged (SymmetricBody), eps {EPS:g}, two orbits: {t_avg * 1e3:.1f} ms, error {e_avg:.1e} "
          f"(the averaging error, O(eps^2) = {EPS**2:.0e})")
    runs = []
    for rtol in (1e-4, 1e-5, 1e-6, 1e-7, 1e-8):
        e = float(np.abs(full(rtol) - ref).max())
        t = cpu_time(lambda rtol=rtol: full(rtol), repeat=1)
        runs.append((e, t))
        print(f"  full motion (SciPy DOP853) rtol {rtol:g}: {t * 1e3:.1f} ms, error {e:.1e}")
    t_full, note = time_at_accuracy(e_avg, runs)
    print(f"RATIO full motion (SciPy) / euler_poinsot.averaged for a SymmetricBody at equal accuracy "
          f"({e_avg:.1e} both): {t_full / t_avg:.1f}x{note}")


if __name__ == "__main__":
    main()
