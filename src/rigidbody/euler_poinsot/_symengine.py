r"""The mean effect of any torque over the regular precession of a body with two equal moments, and the averaged
rates of its slow variables.

The torque-free motion of a :class:`SymmetricBody` (:mod:`._symbody`) turns the body about :math:`\mathbf G` (the
precession angle :math:`\psi`, at :math:`G/A`) and about its symmetry axis (the azimuth :math:`\varphi` of
:math:`\mathbf G` in the body, at :math:`Gc(1/C - 1/A)`). The averaged system takes the means over both angles
(uniform, independent: no resonance between them) and, in the orbit-averaged limit, over the orbit (Kepler's
weights, :func:`._grid.nu_nodes`):

.. math::
    \frac{d(G\mathbf n)}{d\tau} = \langle C\mathbf M\rangle,\qquad
    \frac{d\theta}{d\tau} = \frac{c\,\langle M_\varphi\rangle - s\,\langle M_3\rangle}{G},\qquad
    \frac{dT}{d\tau} = \langle\boldsymbol\omega\cdot\mathbf M\rangle

(:math:`c = \cos\theta`, :math:`s = \sin\theta`, :math:`M_\varphi = M_1\sin\varphi + M_2\cos\varphi` the body
torque along the transverse direction of :math:`\mathbf G`): it is :math:`\dot c = (M_3 - c\,\mathbf M\cdot
\hat{\mathbf g})/G` divided by :math:`-s`, written without the division, so that it holds on the axis (:math:`s = 0`)
too, where a spin about the symmetry axis decays or grows smoothly.

The sphere (:math:`A = C`) has no proper rotation: :math:`\varphi` stands still, the mean is over :math:`\psi`
alone and the direction :math:`\hat{\mathbf g}` of :math:`\mathbf G` in the body is a slow variable,
:math:`d\hat{\mathbf g}/d\tau = (\langle\mathbf M\rangle - \hat{\mathbf g}(\hat{\mathbf g}\cdot\langle\mathbf M
\rangle))/G` (:math:`\boldsymbol\omega\parallel\mathbf G`, so :math:`d\mathbf g/dt = \mathbf M` in the body).

Each mean is the trapezoid rule on a uniform periodic grid (exact for trigonometric polynomials of degree below
the node count, spectrally convergent for smooth torques). The grid is chosen once per run, at its start: the node
counts double until the mean on the grid and on its every second node agree to ``quad_tol`` relative to the mean
size of the torque; that difference is the reported error estimate (pessimistic for smooth torques: the error of
the finer mean is far smaller).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ._grid import nu_nodes
from ._model import Orbit, frame_y
from ._protocol import evaluate
from ._symbody import SymmetricBody, attitude, momentum_body

__all__ = ["SymGrid", "SymMean", "choose_grid", "phase_invariant", "sym_mean", "sym_rates"]

#: the largest grid (points of nu, psi, phi) the choice of grid may use
_MAX_POINTS = 2**19
#: rounding level of a mean relative to the mean size of the torque
_ROUND = 8 * 2.2e-16


@dataclass(frozen=True)
class SymGrid:
    """Node counts: precession angle, body azimuth (1 for the sphere: it is a slow variable), orbit (1: held)."""

    n_psi: int
    n_phi: int
    n_nu: int


@dataclass(frozen=True)
class SymMean:
    """The means at one slow state: ``L`` = <C M> (orbital axes), ``Mb`` = <M> (body axes), ``dT`` = <omega.M>,
    ``Mphi`` = <M1 sin(phi) + M2 cos(phi)> (the body torque along the transverse direction of G), ``scale`` the mean
    size of the torque, ``error`` the estimate of the quadrature error of ``L``, ``Mb``, ``dT`` (absolute, the
    largest)."""

    L: np.ndarray
    Mb: np.ndarray
    dT: float
    Mphi: float
    scale: float
    error: float


def _nodes(n: int) -> np.ndarray:
    return np.arange(n) * (2.0 * math.pi / n)


def _values(torque: Any, body: SymmetricBody, grid: SymGrid, G: float, gb: np.ndarray, n: np.ndarray,
            nu: float | None, orbit: Orbit) -> tuple[np.ndarray, np.ndarray]:
    """The averaged quantities at every node (shape ``(n_nu, n_psi, n_phi, 8)``: C M, M, omega.M, M_phi) and the node
    weights (same leading shape, sum 1)."""
    if grid.n_phi == 1:  # the sphere: the body azimuth of G is a slow variable
        theta = math.atan2(math.hypot(float(gb[0]), float(gb[1])), float(gb[2]))
        phi = np.array([math.atan2(float(gb[0]), float(gb[1]))])
    else:  # gb = (0, sin theta, cos theta), theta signed (past the axis: the same motion, phi shifted by pi)
        theta = math.atan2(float(gb[1]), float(gb[2]))
        phi = _nodes(grid.n_phi)
    Y = frame_y(math.acos(max(-1.0, min(1.0, float(n[2])))), math.atan2(float(n[1]), float(n[0])))
    C = attitude(Y, _nodes(grid.n_psi), theta, phi)[None]  # (1, n_psi, n_phi, 3, 3)
    g = momentum_body(G, theta, phi)  # (n_phi, 3)
    omega = (g / body.A)[None, None]  # (1, 1, n_phi, 3)
    if nu is None:
        nus, w_nu = nu_nodes(orbit.e, grid.n_nu)
        nu_arr: Any = nus[:, None, None]
    else:
        nu_arr, w_nu = float(nu), np.ones(1)
    shape = (w_nu.size, grid.n_psi, grid.n_phi, 3)
    M = np.broadcast_to(evaluate(torque, omega, C, nu_arr, shape), shape)
    Q = np.empty((*shape[:-1], 8))
    Q[..., 0:3] = np.einsum("...ij,...j->...i", C, M)
    Q[..., 3:6] = M
    Q[..., 6] = np.einsum("...i,...i->...", np.broadcast_to(omega, shape), M)
    Q[..., 7] = M[..., 0] * np.sin(phi) + M[..., 1] * np.cos(phi)
    w = np.broadcast_to(w_nu[:, None, None] / (grid.n_psi * grid.n_phi), shape[:-1])
    return Q, w


def _mean(Q: np.ndarray, w: np.ndarray) -> np.ndarray:
    return np.einsum("abcq,abc->q", Q, w)


def _coarse(Q: np.ndarray, w: np.ndarray) -> np.ndarray:
    """The mean on every second node of each averaged axis (weights renormalised)."""
    sl = tuple(slice(None, None, 2) if m > 1 else slice(None) for m in Q.shape[:-1])
    wc = w[sl]
    return np.einsum("abcq,abc->q", Q[sl], wc / wc.sum())


def sym_mean(torque: Any, body: SymmetricBody, grid: SymGrid, G: float, gb: np.ndarray, n: np.ndarray,
             nu: float | None, orbit: Orbit, estimate: bool = False) -> SymMean:
    """The means on ``grid`` at the slow state (``gb`` the unit vector of G in the body, ``n`` in the orbital axes;
    ``nu`` None: over the orbit); ``estimate``: with the error estimate (the coarse grid's difference)."""
    Q, w = _values(torque, body, grid, G, gb, n, nu, orbit)
    m = _mean(Q, w)
    scale = float(np.einsum("abc,abc->", np.linalg.norm(Q[..., 3:6], axis=-1), w))
    err = float(np.abs(_coarse(Q, w) - m)[:6].max()) if estimate else math.nan
    return SymMean(m[0:3], m[3:6], float(m[6]), float(m[7]), scale, err)


def choose_grid(torque: Any, body: SymmetricBody, G: float, gb: np.ndarray, n: np.ndarray, nu: float | None,
                orbit: Orbit, tol: float) -> tuple[SymGrid, SymMean]:
    """The smallest grid (node counts doubling from 16 per angle, 32 over the orbit) on which the mean and that of
    every second node agree to ``tol`` relative to the torque's size (or to rounding), with the mean there."""
    sphere = body.shape == "sphere"
    j = 0
    while True:
        k = 16 * 2**j
        grid = SymGrid(k, 1 if sphere else k, 2 * k if nu is None else 1)
        m = sym_mean(torque, body, grid, G, gb, n, nu, orbit, estimate=True)
        last = 2 * grid.n_psi * grid.n_phi * grid.n_nu > _MAX_POINTS
        if m.error <= max(tol, _ROUND) * m.scale or last:
            return grid, m
        j += 1


def phase_invariant(torque: Any, body: SymmetricBody, grid: SymGrid, G: float, n: np.ndarray, nu: float | None,
                    orbit: Orbit) -> bool:
    """Whether the torque's means over psi (and the orbit) do not depend on the body azimuth phi (a torque
    symmetric about the symmetry axis: the gravity gradient, an axial magnet, an isotropic drag, ...), tried at
    the nutation angle of 1 rad: then the averaging needs no fast proper rotation."""
    th = 1.0
    gb = np.array([0.0, math.sin(th), math.cos(th)])
    Q, w = _values(torque, body, SymGrid(grid.n_psi, max(grid.n_phi, 8), grid.n_nu), G, gb, n, nu, orbit)
    # the mean over nu and psi at each phi of what the rates take: <C M>, M3, omega.M, M_phi (the transverse body
    # components of M turn with phi even for a torque symmetric about z3; only their phi-mean, unused, would differ)
    per_phi = np.einsum("abcq,ab->cq", Q[..., [0, 1, 2, 5, 6, 7]], w[:, :, 0] * Q.shape[2])
    scale = float(np.abs(Q[..., 3:6]).max()) or 1.0
    return bool(np.abs(per_phi - per_phi.mean(axis=0)).max() <= 1e3 * 2.2e-16 * scale)


def sym_rates(body: SymmetricBody, m: SymMean, G: float, gb: np.ndarray, n: np.ndarray) -> dict[str, Any]:
    """The averaged rates from the means: ``dG``, ``dn`` (3), ``dT``, and ``dtheta`` (the symmetric body, ``gb`` =
    (0, sin theta, cos theta)) or ``dgb`` (3, the sphere)."""
    Ln = float(n @ m.L)
    out: dict[str, Any] = {"dG": Ln, "dn": (m.L - n * Ln) / G, "dT": m.dT}
    if body.shape == "sphere":
        out["dgb"] = (m.Mb - gb * float(gb @ m.Mb)) / G
    else:
        out["dtheta"] = (float(gb[2]) * m.Mphi - float(gb[1]) * float(m.Mb[2])) / G
    return out
