r"""The averaging engine's mean on a fixed grid, for the right-hand sides of the averaged evolution.

:func:`._engine.lean_mean` computes the six means of a torque (``<C M>``, ``<omega.M>``, ``<dP/dt>``,
``<dQ/dt>``) on the grid an integration chose at its start, from a :class:`._engine.State`. An averaged run
asks for it at every right-hand side (tens of thousands of times with the true anomaly resolved), on grids of
a few hundred nodes where NumPy's cost per operation, not per node, decides. :class:`LeanMean` gives the same
numbers (to rounding; tested) with what does not change along a run done once (the node tables of the
elliptic phase per node count, the rotations by the precession angle, the orbit nodes and weights, the index
tables of the contractions) and the rest in fewer array operations:

* the Jacobi functions on the first quarter period only (SciPy's ``ellipj``, or the period-reduced
  :func:`rigidbody.core.elliptic.jacobi` within ``1e-3`` of the separatrix, as
  :func:`rigidbody.core.averaging.phase_grid`), extended to the period by the exact symmetries of the
  motion in one gather (as :func:`._engine._symmetric_phase`);
* the attitudes :math:`C = Y R_3(\psi)\alpha_0(u)` of the whole grid as one matrix product
  (:math:`(Y R_3(\psi_p))` stacked over :math:`\psi` times :math:`\alpha_0` stacked over the phase);
* the means as small matrix products: ``<C M>`` contracted over the phase with :math:`\alpha_0` first, then
  with :math:`Y R_3(\psi)`; ``<omega_i M_i>`` as the diagonal of a 3x3 product; the orbit mean (``eps = 0``)
  as one product with Kepler's weights.

It takes the slow state as floats, so the integrators need not build a state object per right-hand side.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from scipy import special

from ..core import averaging as avg
from ..core.elliptic import jacobi
from ._grid import Grid, nu_nodes
from ._model import AXES, Body, Orbit, labelled, relabel
from ._protocol import evaluate

__all__ = ["LeanMean"]


def n_phase(grid: Grid, K: float, mc: float) -> int:
    """``grid.n_u(mc)`` from :math:`K` already computed (the node count of :func:`rigidbody.core.averaging.n_nodes`
    for the period 4K, times ``grid.m_u``, a multiple of 4)."""
    kkp = float(special.ellipkm1(1.0 - mc))
    n = max(16, math.ceil(avg._LOG_TOL * K / (math.pi * kkp) * 2.0))
    n += (-n) % 4
    n = round(grid.m_u * n)
    return max(4, n + (-n) % 4)


class _Tables:
    """What depends on the phase node count ``n_u`` only: the gather from the quarter period to the period
    (index and sign of sn, cn, dn; rows in the body order of omega), buffers, the diagonal positions of
    ``omega_i M_i``."""

    def __init__(self, n_u: int, perm: tuple[int, int, int]) -> None:
        q, h = n_u // 4, n_u // 2
        idx = np.empty(n_u, dtype=np.intp)
        sgn = np.ones((3, n_u))  # rows sn, cn, dn
        for i in range(n_u):
            k, s = i % h, (1.0 if i < h else -1.0)
            if k <= q:  # sn(2K + s) = -sn s, cn(2K + s) = -cn s, dn(2K + s) = dn s
                idx[i], sgn[0, i], sgn[1, i] = k, s, s
            else:  # sn(2K - s) = sn s, cn(2K - s) = -cn s
                idx[i], sgn[0, i], sgn[1, i] = h - k, s, -s
        self.n_u, self.q = n_u, q
        self.flat = (np.array(perm)[:, None] * (q + 1) + idx[None, :]).ravel()  # into E.ravel(), body rows
        self.sign = sgn[list(perm)]
        self.s = np.arange(q + 1, dtype=float)
        self.E = np.empty((3, q + 1))
        self.junk = np.empty(q + 1)
        self.AT = np.zeros((3, n_u, 3))  # alpha_0 as [k, u, j]; AT[0, :, 2] stays 0


class LeanMean:
    r"""The six means of ``torque`` on a fixed grid at slow states given as floats (see the module docstring).

    Parameters
    ----------
    torque : callable
        ``torque(omega, C, nu) -> M`` (the part of the perturbation the engine averages).
    body : Body
    kind : {'max', 'min'}
    sigma : {+1, -1}
    grid : Grid
        The node counts (the integrator's lean grid).
    compact : bool
        Whether the torque may be called with broadcastable leading axes (:func:`._engine.adaptive` decides).
    orbit : Orbit
    held : bool
        True when the true anomaly is a number (``eps > 0``), False for the mean over the orbit.
    """

    def __init__(self, torque: Any, body: Body, kind: str, sigma: int, grid: Grid, compact: bool, orbit: Orbit,
                 held: bool) -> None:
        self.torque, self.kind, self.sigma, self.grid = torque, kind, sigma, grid
        self.compact, self.held = compact, held
        self.a = labelled(body, kind)
        self.lab = AXES[kind]
        # omega in body order from the rows (sn, cn, dn): 'max' (dn, sn, cn), 'min' (cn, sn, dn)
        self.perm = (2, 0, 1) if kind == "max" else (1, 0, 2)
        self.A = body.A[:, None]
        n_psi = grid.n_psi
        psi = np.arange(n_psi) * (2.0 * math.pi / n_psi)
        c, s = np.cos(psi), np.sin(psi)
        R3 = np.zeros((3, n_psi, 3))  # [m, p, k] = R3(psi_p)[m, k]
        R3[0, :, 0], R3[0, :, 1], R3[1, :, 0], R3[1, :, 1], R3[2, :, 2] = c, -s, s, c, 1.0
        self.R3 = R3.reshape(3, 3 * n_psi)
        if held:
            self.nu: Any = None
            self.w: Any = None
        else:
            nu, w = nu_nodes(orbit.e, grid.n_nu)
            self.nu, self.w = nu[:, None, None], w
        self.nu_buf = np.empty((1, 1, 1))  # the held true anomaly, as the torque receives it
        self.n_nu = 1 if held else grid.n_nu
        a1, a2, a3 = self.a
        self.R0, self.R1 = a1 * (a2 - a3), a3 * (a1 - a2)
        self.q_dn, self.q_sn, self.q_cn = (a2 - a3) / a1, (a1 - a3) / a2, (a1 - a2) / a3
        self.coef = np.empty((3, 1))
        self.tables: dict[int, _Tables] = {}

    def _phase(self, k2: float) -> tuple[_Tables, np.ndarray]:
        """The node tables and the body components of omega at G = 1, shape (3, n_u)."""
        mc = 1.0 - k2
        K = float(special.ellipkm1(mc))
        n_u = n_phase(self.grid, K, mc)
        t = self.tables.get(n_u)
        if t is None:
            t = self.tables[n_u] = _Tables(n_u, self.perm)
        E = t.E
        if mc >= avg._MC_FAST:
            special.ellipj(t.s * (4.0 * K / n_u), 1.0 - mc, out=(E[0], E[1], E[2], t.junk))
        else:  # next to the separatrix: the period-reduced Jacobi functions with the exact mc (as phase_grid)
            sn, cn, dn, _ = jacobi(t.s * (4.0 * K / n_u), mc=mc)
            E[0], E[1], E[2] = sn, cn, dn
        R = self.R0 + self.R1 * k2
        k, sg = math.sqrt(k2), self.sigma
        c_dn, c_sn = sg * math.sqrt(self.q_dn / R), -sg * k * math.sqrt(self.q_sn / R)
        c_cn = k * math.sqrt(self.q_cn / R)
        coef = self.coef
        coef[0, 0], coef[1, 0], coef[2, 0] = relabel(self.kind, (c_dn, c_sn, c_cn))
        W = E.ravel()[t.flat].reshape(3, n_u)
        W *= t.sign
        W *= coef
        return t, W

    def __call__(self, G: float, k2: float, n1: float, n2: float, n3: float, nu: float | None
                 ) -> tuple[float, float, float, float, float, float]:
        """``(<C M>_1, <C M>_2, <C M>_3, <omega.M>, <dP/dt>, <dQ/dt>)`` at the slow state (``n`` a unit vector)."""
        t, W = self._phase(k2)
        n_u, n_psi = t.n_u, self.grid.n_psi
        # alpha_0 = dcm(0, theta, phi) of the unit vector g/G in body axes: rows (cos phi, -sin phi, 0),
        # (cos th sin phi, cos th cos phi, -sin th), g/G; with AT[k, u, j] = alpha_0[u, k, j]
        gam = W * self.A
        h = np.hypot(gam[0], gam[1])
        AT = t.AT
        if h.min() > 0.0:
            sp, cp = gam[:2] / h
        else:  # g along z3 (kind 'min' at k = 0): phi is undefined there, take phi = 0 (as motion_nodes)
            safe = np.where(h > 0.0, h, 1.0)
            sp, cp = np.where(h > 0.0, gam[0] / safe, 0.0), np.where(h > 0.0, gam[1] / safe, 1.0)
        AT[0, :, 0] = cp
        np.negative(sp, out=AT[0, :, 1])
        np.multiply(gam[2], sp, out=AT[1, :, 0])
        np.multiply(gam[2], cp, out=AT[1, :, 1])
        np.negative(h, out=AT[1, :, 2])
        AT[2] = gam.T
        # Y = (y1, y2, n) of frame(n): y2 in the orbit plane off the poles
        hh = math.hypot(n1, n2)
        cl, sl = (n1 / hh, n2 / hh) if hh > 1e-300 else (1.0, 0.0)
        Y = np.array([[n3 * cl, -sl, n1], [n3 * sl, cl, n2], [-hh, 0.0, n3]])
        B = (Y @ self.R3).reshape(3, n_psi, 3)  # [i, p, k] = (Y R3(psi_p))[i, k]
        A2 = AT.reshape(3, 3 * n_u)
        Cg = B.transpose(1, 0, 2).reshape(3 * n_psi, 3) @ A2  # [(p, i), (u, j)]
        C = Cg.reshape(n_psi, 3, n_u, 3).transpose(0, 2, 1, 3)
        omega = W.T * G
        shape = (self.n_nu, n_psi, n_u, 3)
        if self.held:
            nu_a = self.nu_buf
            nu_a[0, 0, 0] = nu
        else:
            nu_a = self.nu
        if self.compact:
            M = evaluate(self.torque, omega[None, None], C[None], nu_a, shape)
        else:
            M = evaluate(self.torque, np.broadcast_to(omega, shape), np.broadcast_to(C, (*shape, 3)),
                         np.broadcast_to(nu_a, shape[:3]), shape)
        if M.shape != shape:
            M = np.broadcast_to(M, shape)
        if self.held:
            Mf = M.reshape(n_psi, 3 * n_u)
        else:  # the mean over the orbit first (the six quantities are linear in M, their coefficients free of nu)
            Mf = (self.w @ M.reshape(self.n_nu, -1)).reshape(n_psi, 3 * n_u)
        N = n_psi * n_u
        # <C M>_i = sum_p,k (Y R3(psi_p))[i, k] sum_u,j alpha_0(u)[k, j] M[p, u, j]: two small matrix products
        X = Mf @ A2.T  # [p, k]
        L = (B.reshape(3, 3 * n_psi) @ X.ravel()) / N
        # <omega_i M_i> = G sum_u W[i, u] sum_p M[p, u, i]: the diagonal of a 3x3 product
        om = (W @ Mf.sum(axis=0).reshape(n_u, 3)).diagonal() * (G / N)
        o = (float(om[0]), float(om[1]), float(om[2]))
        l1, l2, l3 = self.lab
        a1, a2, a3 = self.a
        return (float(L[0]), float(L[1]), float(L[2]), o[0] + o[1] + o[2],
                2.0 * ((a1 - a2) * o[l2] + (a1 - a3) * o[l3]), 2.0 * ((a1 - a3) * o[l1] + (a2 - a3) * o[l2]))

    def rates(self, G: float, k2: float, n1: float, n2: float, n3: float, nu: float | None
              ) -> tuple[float, float, float, float, float]:
        """``(L1, L2, L3, dT, dk2)``: the mean torque in orbital axes and the rates of :math:`T` and :math:`k^2`
        (as :func:`._engine.mean_of` from the six means)."""
        q = self(G, k2, n1, n2, n3, nu)
        a1, a2, a3 = self.a
        Q = G * G * (a1 - a3) * (a2 - a3) / (self.R0 + self.R1 * k2)
        return q[0], q[1], q[2], q[3], ((a2 - a3) / (a1 - a2) * q[4] - k2 * q[5]) / Q
