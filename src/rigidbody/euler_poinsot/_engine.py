r"""The averaging engine: the mean effect of any torque over the Euler--Poinsot motion.

For a torque ``M = torque(omega, C, nu)`` (body components, see :mod:`._torques`) the averaged system of
the slow variables :math:`G, T, k^2` and the unit vector :math:`\mathbf n` of :math:`\mathbf G` (in the
orbital axes :math:`Ox_i`) is

.. math::
    \frac{d(G\mathbf n)}{d\tau} = \langle C\mathbf M\rangle,\qquad
    \frac{dT}{d\tau} = \langle\boldsymbol\omega\cdot\mathbf M\rangle,\qquad
    \frac{dk^2}{d\tau} = \frac{c\,\langle\dot P\rangle - k^2\langle\dot Q\rangle}{Q},

with :math:`P = 2Ta_1 - G^2`, :math:`Q = G^2 - 2Ta_3 = G^2(a_1-a_3)(a_2-a_3)/R`, :math:`c = (a_2-a_3)/(a_1-a_2)`
(so that :math:`k^2 = cP/Q` is (5)), :math:`\dot P = 2\sum_i(a_1-a_i)\omega_iM_i`,
:math:`\dot Q = 2\sum_i(a_i-a_3)\omega_iM_i`, and :math:`a = (A_1, A_2, A_3)` for the kind ``'max'``,
:math:`(A_3, A_2, A_1)` with the components relabelled for ``'min'``. Every term of :math:`\dot P` is
:math:`O(k)` or smaller on the motion, so :math:`dk^2` keeps its relative accuracy as :math:`k\to0`
(differentiating :math:`k^2(G, T)` would lose it to cancellation).

The mean :math:`\langle\cdot\rangle` is over the precession angle :math:`\psi` about :math:`\mathbf G`
(uniform, independent of the phase: no resonance), over one period :math:`4K` of the elliptic phase, and,
in the orbit-averaged limit :math:`\varepsilon = 0`, over the orbit (uniform in time: weight
:math:`(1+e\cos\nu)^{-2}` in the true anomaly). Each mean is the trapezoid rule on a uniform periodic grid
(spectrally convergent for smooth integrands; the elliptic-phase node count comes from
:func:`rigidbody.core.averaging.n_nodes`, i.e. from :math:`k`). The attitude on the grid is
:math:`C = Y R_3(\psi)\alpha_0(u)` with :math:`Y = (\mathbf y_1, \mathbf y_2, \mathbf n)` and
:math:`\alpha_0` the direction cosines of sec. 2 at :math:`\psi = 0`.

Error estimate: the grid of :math:`n` nodes per axis contains the grids of :math:`n/2` and :math:`n/4`
(every second and fourth node), so the means on them cost nothing more. With :math:`d_2 = |Q_{n/2} - Q_n|`,
:math:`d_1 = |Q_{n/4} - Q_{n/2}|` and :math:`r = d_2/d_1`, the error of :math:`Q_n` is estimated by
:math:`d_2` when :math:`r < 1/2` (it bounds :math:`|Q_n - Q|` whenever the errors at least halve per doubling,
or alternate in sign -- the erratic convergence of torques with kinks), by the geometric tail
:math:`d_2 r/(1-r)` for :math:`1/2 \le r < 0.9`, and by :math:`10\max(d_1, d_2)` when the differences do
not decrease; differences at the rounding level of the mean count as converged. For a smooth torque this
is pessimistic (the error of :math:`Q_n` is about :math:`d_2 r`): one doubling at the start of a run buys an
honest figure for torques that are not smooth. Node counts double along each axis over the tolerance (a budget).

Two checks that the nested differences cannot make. A torque that *jumps* (an eclipse, a switched torque)
gives means whose differences change by whole nodes, and often not at all: along an axis whose profile (the
quantities averaged over the other axes) keeps a step of the same size when the nodes double, and that step
stands out of the others, the estimate is at least :math:`V/n` (:math:`V` the variation of the profile;
Koksma's inequality bounds the error by :math:`V/2n`). And a feature that falls between *all* nested nodes
leaves them in agreement: the mean on the *dual* grid (shifted by half a step on every axis) is compared
with the grid's, the difference joins the estimate and refines every axis. What neither sees is a feature
narrower than the spacing of grid and dual together, :math:`\pi/n` per axis (from the start, 16 orbit
nodes: an eclipse shorter than 1/32 of the orbit).

The error reported (by :func:`adaptive`, hence by ``average_torque`` and a run's ``quad_error``) takes the
estimates from differences (nested and dual grids) times a safety factor of 4, the jump floors (bounds already)
as they are; the grids are chosen on the estimate itself. Where a torque is not smooth along two axes at once
(a kink or a switch on a curve across the precession angle and the phase) the means converge erratically and
the differences can fall short of the error: in about 2,000 reports for kinked and switched torques (random
directions, thresholds, states and tolerances) the true error reached 3.2 times the estimate (leaving out
features narrower than the grids' spacing, which no estimate sees).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core import averaging as avg
from ._grid import Grid, nu_nodes
from ._model import relabel
from ._protocol import TorqueSum, checked_closed_mean, evaluate, first_closed_mean
from ._state import Mean, State, amplitudes, frame

__all__ = ["TorqueAverage"]

#: quantities averaged on the grid: C M (3 components), omega . M, dP/dt, dQ/dt
_NQ = 6
#: the largest grid the adaptive refinement may use (points of (nu, psi, u)): 2^19 ~ 5e5 points, ~40 MB of C
_MAX_POINTS = 2**19
#: rounding level of a mean, relative to the mean absolute value of the integrand (8 units of 2.2e-16: the
#: products and sums that form each value, and the pairwise summation of the mean)
_ROUND = 8 * 2.2e-16
#: the reported error takes the estimates from differences times this factor (see the module docstring: erratic
#: convergence of torques that are not smooth along two axes; the largest ratio of true error to estimate found
#: was 3.2)
_SAFETY = 4.0


def _symmetric_phase(n: int, mc: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """sn, cn, dn on ``n`` (a multiple of 4) uniform nodes of 4K, exactly symmetric: the first quarter
    period from the core, the rest by sn(2K - s) = sn s, cn(2K - s) = -cn s, f(s + 2K) = (-sn, -cn, dn).
    Parts of a mean that are odd under these symmetries of the motion then cancel to rounding of the
    products, not of the Jacobi functions."""
    q = n // 4
    h = n // 2
    _, s2, c2, d2 = avg.phase_grid(n=h, mc=mc, period="2K")  # the first half of the nodes of 4K
    sn, cn, dn = np.empty(n), np.empty(n), np.empty(n)
    sn[:q + 1], cn[:q + 1], dn[:q + 1] = s2[:q + 1], c2[:q + 1], d2[:q + 1]
    sn[q + 1:h], cn[q + 1:h], dn[q + 1:h] = sn[q - 1:0:-1], -cn[q - 1:0:-1], dn[q - 1:0:-1]
    sn[h:], cn[h:], dn[h:] = -sn[:h], -cn[:h], dn[:h]
    return sn, cn, dn


def motion_nodes(st: State, n_u: int) -> tuple[np.ndarray, np.ndarray]:
    r"""Body angular velocity ``(n_u, 3)`` and direction cosines :math:`\alpha_0` ``(n_u, 3, 3)`` at
    :math:`\psi = 0` on ``n_u`` uniform nodes of the period :math:`4K` (the closed form of sec. 2)."""
    b = st.body
    k2, G, s = st.k2, st.G, st.sigma
    c_dn, c_sn, c_cn = amplitudes(st)
    sn, cn, dn = _symmetric_phase(n_u, st.mc)
    k = math.sqrt(k2)
    omega = np.empty((n_u, 3))
    w_dn, w_sn, w_cn = s * c_dn * dn, -s * k * c_sn * sn, k * c_cn * cn
    omega[:, 0], omega[:, 1], omega[:, 2] = relabel(st.kind, (w_dn, w_sn, w_cn))
    g = omega * b.A
    # alpha_0 = dcm(0, theta, phi): rows (cos phi, -sin phi, 0), (cos th sin phi, cos th cos phi, -sin th), g/G
    h = np.hypot(g[:, 0], g[:, 1])
    if h.min() > 0.0:
        sp, cp = g[:, 0] / h, g[:, 1] / h
    else:  # g along z3 (kind 'min' at k = 0): phi is undefined there, take phi = 0
        safe = np.where(h > 0.0, h, 1.0)
        sp, cp = np.where(h > 0.0, g[:, 0] / safe, 0.0), np.where(h > 0.0, g[:, 1] / safe, 1.0)
    ct, stt = g[:, 2] / G, h / G
    al = np.empty((n_u, 3, 3))
    al[:, 0, 0], al[:, 0, 1], al[:, 0, 2] = cp, -sp, 0.0
    al[:, 1, 0], al[:, 1, 1], al[:, 1, 2] = ct * sp, ct * cp, -stt
    al[:, 2, :] = g / G
    return omega, al


@functools.lru_cache(maxsize=64)
def _psi_trig(n_psi: int, dual: bool = False) -> tuple[np.ndarray, np.ndarray]:
    psi = (np.arange(n_psi) + (0.5 if dual else 0.0)) * (2.0 * math.pi / n_psi)
    c, s = np.cos(psi)[:, None], np.sin(psi)[:, None]
    c.setflags(write=False)
    s.setflags(write=False)
    return c, s


def torque_grid(torque: Any, st: State, grid: Grid, compact: bool = False, dual: bool = False,
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The torque at every node: ``M`` of shape ``(n_nu, n_psi, n_u, 3)`` (``n_nu = 1`` when nu is held),
    the orbit weights ``w``, and the body angular velocity ``(n_u, 3)`` and attitudes ``C`` ``(n_psi, n_u,
    3, 3)`` of the grid (C does not depend on nu).

    ``compact=True`` passes the torque arrays whose leading axes only broadcast against each other (omega
    ``(1, 1, n_u, 3)``, C ``(1, n_psi, n_u, 3, 3)``, nu ``(n_nu, 1, 1)``), so that a torque that does not
    depend on the attitude or on nu is evaluated once per phase node; :func:`adaptive` checks on the first
    grid that the torque gives the same values this way and otherwise passes full arrays.

    ``dual=True``: the grid shifted by half a step along every axis (the nodes of the grid of twice the
    nodes per axis that lie farthest from this grid's), for the check in :func:`adaptive`.
    """
    n_u = grid.n_u(st.mc)
    if dual:
        omega, al = motion_nodes(st, 2 * n_u)
        omega, al = omega[1::2], al[1::2]
    else:
        omega, al = motion_nodes(st, n_u)
    Y = frame(st.n)
    c, s = _psi_trig(grid.n_psi, dual)
    B = np.empty((grid.n_psi, 3, 3))  # Y R3(psi)
    B[:, :, 0] = Y[:, 0] * c + Y[:, 1] * s
    B[:, :, 1] = Y[:, 1] * c - Y[:, 0] * s
    B[:, :, 2] = Y[:, 2]
    C = B[:, None] @ al[None]  # (n_psi, n_u, 3, 3)
    if st.nu is None:
        nu, w = nu_nodes(st.orbit.e, grid.n_nu, dual)
    else:
        nu, w = np.array([st.nu]), np.ones(1)
    shape = (nu.size, grid.n_psi, n_u)
    if compact:
        M = evaluate(torque, omega[None, None], C[None], nu[:, None, None], (*shape, 3))
    else:
        M = evaluate(torque, np.broadcast_to(omega, (*shape, 3)), np.broadcast_to(C, (*shape, 3, 3)),
                     np.broadcast_to(nu[:, None, None], shape), (*shape, 3))
    return (M if M.shape == (*shape, 3) else np.broadcast_to(M, (*shape, 3))), w, omega, C


def quantities(st: State, omega: np.ndarray, C: np.ndarray, M: np.ndarray) -> np.ndarray:
    """The six averaged quantities at the (psi, u) nodes for a torque ``M`` (n_psi, n_u, 3) already averaged
    over the orbit: C M (3), omega . M, dP/dt, dQ/dt; shape ``(n_psi, n_u, 6)``. All are linear in M with
    coefficients that do not depend on nu, so averaging M over nu first is exact."""
    V = np.empty((*M.shape[:-1], _NQ))
    V[..., 0:3] = (C @ M[..., None])[..., 0]
    OM = omega * M
    V[..., 3] = OM.sum(-1)
    a1, a2, a3 = st.a
    l1, l2, l3 = st.lab
    V[..., 4] = 2.0 * ((a1 - a2) * OM[..., l2] + (a1 - a3) * OM[..., l3])
    V[..., 5] = 2.0 * ((a1 - a3) * OM[..., l1] + (a2 - a3) * OM[..., l2])
    return V


def _nu_mean(M: np.ndarray, w: np.ndarray, step: int = 1) -> np.ndarray:
    if M.strides[0] == 0:  # the torque does not depend on nu (compact evaluation)
        return M[0]
    ws = w[::step]
    Ms = M[::step]
    return ((ws / ws.sum()) @ Ms.reshape(Ms.shape[0], -1)).reshape(Ms.shape[1:])


def lean_mean(torque: Any, st: State, grid: Grid, compact: bool = False) -> np.ndarray:
    """The six means on one grid, no error estimate (the integrators' right-hand sides): only the means of
    C M and of the products omega_i M_i are formed (the rest is linear in them)."""
    M, w, omega, C = torque_grid(torque, st, grid, compact)
    Mn = _nu_mean(M, w)
    N = Mn.shape[0] * Mn.shape[1]
    out = np.empty(_NQ)
    out[0:3] = np.einsum("puij,puj->i", C, Mn) / N
    om = np.einsum("ui,pui->i", omega, Mn) / N  # <omega_i M_i>
    a1, a2, a3 = st.a
    l1, l2, l3 = st.lab
    out[3] = om.sum()
    out[4] = 2.0 * ((a1 - a2) * om[l2] + (a1 - a3) * om[l3])
    out[5] = 2.0 * ((a1 - a3) * om[l1] + (a2 - a3) * om[l2])
    return out


def _sub(V: np.ndarray, axis: int, step: int) -> np.ndarray:
    """Mean on every ``step``-th node along ``axis`` (0: psi, 1: u) of a (psi, u, 6) array."""
    return V[::step].mean(axis=(0, 1)) if axis == 0 else V[:, ::step].mean(axis=(0, 1))


def _axis_error(n: int, means: tuple[np.ndarray, ...], noise: np.ndarray) -> tuple[Any, Any, Any]:
    """(error estimate of the full grid, of the half grid, of the quarter grid) along one axis, per
    quantity, from the means on the full, half and quarter grids. ``noise`` is the rounding level of a mean:
    differences below twice it are convergence to rounding."""
    if n == 1:
        return np.zeros(_NQ), np.zeros(_NQ), np.zeros(_NQ)
    m1, m2 = means[0], means[1]
    d2 = np.abs(m2 - m1)
    if n % 4:
        est = np.where(d2 <= 2.0 * noise, noise, 10.0 * d2)
        return est, np.full(_NQ, np.inf), np.full(_NQ, np.inf)
    d1 = np.abs(means[2] - m2)
    with np.errstate(divide="ignore", invalid="ignore"):
        r = d2 / d1
        tail = d2 * r / (1.0 - r)
    est = np.where(
        d2 <= 2.0 * noise, noise,  # the half grid already agrees to rounding
        np.where(
            d1 <= 2.0 * noise, 10.0 * d2,  # the quarter grid agreed but the full one does not: do not trust
            np.where(r < 0.5, d2, np.where(r < 0.9, tail, 10.0 * np.maximum(d1, d2))),
        ),
    )
    est = np.maximum(est, noise)
    return est, d2 + est, d1 + d2 + est


@dataclass
class Quadrature:
    """Means of the six quantities with their estimated errors and the grid that produced them."""

    mean: np.ndarray
    error: np.ndarray
    scale: np.ndarray
    grid: Grid
    lean: Grid
    converged: bool
    convergence: dict[str, float]
    compact: bool


def adaptive(torque: Any, st: State, tol: float, grid: Grid | None = None, refine: bool = True,
             compact: bool | None = None) -> Quadrature:
    """Mean of the six quantities with an error estimate; the grid is doubled along axes until ``tol``."""
    g = Grid() if grid is None else Grid(grid.n_psi, grid.m_u, grid.n_nu)
    if st.nu is not None:
        g.n_nu = 1
    first: Any = None  # the first grid's evaluation, when the check below made it
    if compact is None:  # may the torque be called with broadcastable (not equal) leading axes?
        first = torque_grid(torque, st, g)
        try:
            small = torque_grid(torque, st, g, compact=True)
            compact = bool(np.array_equal(small[0], first[0]))
            if compact:
                first = small
        except (ValueError, TypeError, IndexError):
            compact = False
    while True:
        M, w, omega, C = first if first is not None else torque_grid(torque, st, g, compact)
        first = None
        steps = (1, 2, 4) if g.n_nu >= 4 and g.n_nu % 4 == 0 else ((1, 2) if g.n_nu % 2 == 0 else (1,))
        Vs = [quantities(st, omega, C, _nu_mean(M, w, k)) for k in steps]
        V = Vs[0]
        m = V.mean(axis=(0, 1))
        S = _scale(np.abs(quantities(st, np.abs(omega), np.abs(C), np.tensordot(w, np.abs(M), axes=(0, 0)))))
        noise = _ROUND * S
        per_axis = {
            "nu": (g.n_nu, tuple(v.mean(axis=(0, 1)) for v in Vs)),
            "psi": (g.n_psi, (m, _sub(V, 0, 2), _sub(V, 0, 4) if g.n_psi % 4 == 0 else m)),
            "u": (V.shape[1], (m, _sub(V, 1, 2), _sub(V, 1, 4))),
        }
        errs = {k: _axis_error(n, ms, noise) for k, (n, ms) in per_axis.items()}
        diffs = {k: e[0] for k, e in errs.items()}  # the estimates from the nested differences alone
        for k, prof in _profiles(st, omega, C, M, w, V).items():
            floor = _jump_floor(prof)
            e, e_half, e_quarter = errs[k]
            errs[k] = (np.maximum(e, floor), e_half + 2.0 * floor, e_quarter + 4.0 * floor)
        err = sum(e[0] for e in errs.values())
        ok = bool(np.all(err <= tol * S))
        bad = [k for k, e in errs.items() if np.any(e[0] > tol * S / 3.0)]
        npts = M.shape[0] * M.shape[1] * M.shape[2]
        if ok or not refine or not bad or npts * 2 ** len(bad) > _MAX_POINTS:
            # The nested grids share their nodes: a feature of the torque that falls between all of them (an
            # eclipse shorter than the orbit step, a shadow between the nodes) leaves them in agreement. The
            # dual grid, shifted by half a step on every axis, samples between: its disagreement with this
            # grid is added to the estimate, and refines every axis while the budget allows.
            Md, wd, omd, Cd = torque_grid(torque, st, g, compact, dual=True)
            dual = np.abs(quantities(st, omd, Cd, _nu_mean(Md, wd)).mean(axis=(0, 1)) - m)
            dual = np.where(dual <= 2.0 * noise, 0.0, dual)
            err = np.maximum(err, dual)
            ok = bool(np.all(err <= tol * S))
            bad = [k for k, (n, _) in per_axis.items() if n > 1]
            if ok or not refine or np.all(dual <= tol * S / 3.0) or npts * 2 ** len(bad) > _MAX_POINTS:
                break
        for k in bad:
            if k == "nu":
                g.n_nu *= 2
            elif k == "psi":
                g.n_psi *= 2
            else:
                g.m_u *= 2.0
    lean = Grid(g.n_psi, g.m_u, g.n_nu)
    for k, (_, e_half, e_quarter) in errs.items():
        # the coarsest of the nested grids whose estimate meets the tolerance: half the nodes, and along the
        # orbit (which starts from 16 nodes to see short shadows) a quarter; not along psi and the phase, whose
        # needs change along a run with k2 and G (a quarter of the phase nodes chosen at the start left 6e-6
        # at the end of the any-torque example, half of them 3e-9)
        half = np.all(e_half + dual <= tol * S / 3.0)
        f = (4 if k == "nu" and np.all(e_quarter + dual <= tol * S / 3.0) else 2) if half else 1
        if k == "nu":
            lean.n_nu = max(lean.n_nu // f, min(lean.n_nu, 2))
        elif k == "psi":
            lean.n_psi = max(lean.n_psi // f, min(lean.n_psi, 2))
        else:
            lean.m_u /= f
    conv = {}
    for k, (n, ms) in per_axis.items():
        if n >= 4 and n % 4 == 0:
            d2 = float(np.max(np.abs(ms[1] - ms[0]) / S))
            d1 = float(np.max(np.abs(ms[2] - ms[1]) / S))
            conv[k] = d2 / d1 if d1 > 0 else 0.0
    # reported: the estimates from differences (nested grids, dual grid) times the safety factor, the jump floors
    # (bounds already) as they are
    report = np.maximum(sum(np.maximum(_SAFETY * diffs[k], e[0]) for k, e in errs.items()), _SAFETY * dual)
    return Quadrature(m, report, S, g, lean, ok, conv, compact)


#: ratio of the largest steps of a profile on the grid and on the half grid above which it jumps
_JUMP = 0.85
#: ... and the ratio of the largest step to the median step above which that step is a jump
_ISOLATED = 5.0


def _profiles(st: State, omega: np.ndarray, C: np.ndarray, M: np.ndarray, w: np.ndarray, V: np.ndarray,
              ) -> dict[str, np.ndarray]:
    """The six quantities along each axis, averaged over the other axes (``(n, 6)`` per axis; along nu
    times ``n w``, so that their plain mean is the weighted one)."""
    out = {"psi": V.mean(axis=1), "u": V.mean(axis=0)}
    if M.shape[0] > 1 and M.strides[0] != 0:
        N = M.shape[1] * M.shape[2]
        P = np.empty((M.shape[0], _NQ))
        K = M.shape[0]
        # sum over p, u, j of C[p, u, i, j] M[k, p, u, j]: one matrix product
        P[:, 0:3] = (np.ascontiguousarray(M).reshape(K, -1) @ C.transpose(0, 1, 3, 2).reshape(-1, 3)) / N
        om = (M.sum(axis=1) * omega).sum(axis=1) / N  # <omega_i M_i> at each nu
        a1, a2, a3 = st.a
        l1, l2, l3 = st.lab
        P[:, 3] = om.sum(axis=1)
        P[:, 4] = 2.0 * ((a1 - a2) * om[:, l2] + (a1 - a3) * om[:, l3])
        P[:, 5] = 2.0 * ((a1 - a3) * om[:, l1] + (a2 - a3) * om[:, l2])
        out["nu"] = P * (w.size * w)[:, None]
    return out


def _jump_floor(P: np.ndarray) -> np.ndarray:
    r"""A floor for the error of the mean of a profile ``P`` (``(n, 6)``, periodic) that jumps.

    The largest step between neighbouring nodes of a smooth profile halves when the nodes double (a harmonic
    of m periods over n nodes: the ratio is 1/(2 cos(pi m/n)), below 0.85 for m < 0.28 n, if the half grid
    does not alias it), and it is of the size of its neighbours; a jump keeps its size and stands out. Where
    the largest step on the grid is more than 0.85 of that on the half grid and 5 times the median step,
    the mean is bounded as for any function of bounded variation, :math:`|E_n| \le V/2n` (the total
    variation :math:`V` over the period, from the steps: Koksma's inequality with the discrepancy
    :math:`1/2n` of the uniform grid), and ``V/n`` is returned; zero elsewhere. The differences of nested
    grids do not bound the error of a jump: its nodes inside change by whole numbers, and often not at all.
    """
    n = P.shape[0]
    if n < 8 or n % 2:
        return np.zeros(_NQ)
    step = np.abs(np.diff(P, axis=0, append=P[:1]))  # periodic: the last step closes the period
    h = P[::2]
    step2 = np.abs(np.diff(h, axis=0, append=h[:1])).max(axis=0)
    top = step.max(axis=0)
    mid = np.partition(step, (n // 2 - 1, n // 2), axis=0)  # the median of an even number of steps
    median = 0.5 * (mid[n // 2 - 1] + mid[n // 2])
    jump = (top > _JUMP * step2) & (top > _ISOLATED * median)
    return np.where(jump, step.sum(axis=0) / n, 0.0)


def _scale(Vabs: np.ndarray) -> np.ndarray:
    """Size of each quantity on the grid: the mean of its absolute terms (one scale for the 3 of C M)."""
    S = Vabs.mean(axis=(0, 1))
    S[0:3] = S[0:3].max()
    return S + 1e-300


def mean_of(q: np.ndarray, st: State) -> Mean:
    """The averaged effect (L, dT, dk2) from the six means."""
    a1, a2, a3 = st.a
    c = (a2 - a3) / (a1 - a2)
    dk2 = (c * q[4] - st.k2 * q[5]) / st.Q
    return Mean(np.array(q[0:3]), float(q[3]), float(dk2))


def error_of(e: np.ndarray, st: State) -> Mean:
    """Error bounds on (L, dT, dk2) from those of the six means (triangle inequality)."""
    a1, a2, a3 = st.a
    c = abs((a2 - a3) / (a1 - a2))
    return Mean(np.array(e[0:3]), float(e[3]), float((c * e[4] + st.k2 * e[5]) / abs(st.Q)))


@dataclass(frozen=True)
class TorqueAverage:
    r"""The averaged effect of a torque at one slow state, as computed by the engine (:func:`average_torque`).

    Attributes
    ----------
    rates : dict
        ``dG``, ``dT``, ``dk2``, ``ddelta``, ``dlam`` (as :func:`averaged_rates`).
    error : dict
        Estimated absolute quadrature error of each rate (same keys).
    L : numpy.ndarray
        The mean torque :math:`\langle C\mathbf M\rangle` in the orbital axes, shape (3,).
    dn : numpy.ndarray
        :math:`d\mathbf n/d\tau` of the unit vector of :math:`\mathbf G` in the orbital axes (regular at
        :math:`\sin\delta = 0`, where ``dlam`` is not).
    nodes : tuple of int
        ``(n_psi, n_u, n_nu)`` of the grid used (``n_nu = 1`` when :math:`\nu` is held).
    converged : bool
        Whether the estimated errors met the tolerance (relative to the torque's size) within the node budget.
    convergence : dict
        The last ratio :math:`d_2/d_1` of successive differences per axis (``'psi'``, ``'u'``, ``'nu'``):
        near 0 for spectral convergence, about :math:`2^{-p}` for algebraic convergence of order :math:`p`.

    See Also
    --------
    average_torque : computes it.
    averaged_rates : the same rates (closed forms where a torque has them), without an error estimate.
    Mean : what a torque's own closed form gives.

    Examples
    --------
    The paper's drag: the engine's rate is that of the closed form (6), -0.665135 (:func:`drag_rates`):

    >>> from rigidbody.euler_poinsot import Body, LinearDrag, average_torque
    >>> a = average_torque(Body(3.2, 2.6, 1.67), LinearDrag([2.322, 1.31, 1.425]), 1.0, 0.5, 0.7, 0.3, None)
    >>> print(f"{a.rates['dG']:.6f}", a.converged)
    -0.665135 True
    """

    rates: dict[str, float]
    error: dict[str, float]
    L: np.ndarray
    dn: np.ndarray
    nodes: tuple[int, int, int]
    converged: bool
    convergence: dict[str, float]


def _sum_of(parts: list[Any]) -> Any:
    return parts[0] if len(parts) == 1 else TorqueSum(tuple(parts))


class Averager:
    """Averages of one torque at slow states: the closed forms of its parts where they have them (unless
    ``method='numerical'``), the engine for the rest. ``calibrate`` chooses the engine's grid at a state
    (adaptively, to ``tol``); ``mean`` then evaluates on that grid (the integrators' right-hand sides);
    ``report`` re-estimates the quadrature error at a state on that grid. Not yet calibrated, ``mean`` and
    ``report`` calibrate at the state they are given."""

    def __init__(self, torque: Any, method: str, tol: float) -> None:
        self.parts = list(torque.parts())
        self.torque = _sum_of(self.parts)
        self.method = method
        self.tol = tol
        self.closed: list[Any] = []
        self.rest: Any = None
        self.grid: Grid | None = None
        self.first: Quadrature | None = None
        self.lean: Any = None
        self.first_state: State | None = None
        self.calibrated = False

    def calibrate(self, st: State) -> None:
        self.calibrated = True
        closed: list[Any] = []
        rest: list[Any] = []
        for p in self.parts:
            ok = self.method != "numerical" and first_closed_mean(p, st) is not None
            (closed if ok else rest).append(p)
        self.closed = closed
        self.rest = _sum_of(rest) if rest else None
        if self.rest is not None:
            compact = True if all(getattr(p, "_broadcasts", False) for p in rest) else None
            self.first = adaptive(self.rest, st, self.tol, compact=compact)
            self.first_state = st
            self.grid = self.first.lean
            from ._lean import LeanMean  # the same means on this grid, what does not change along a run done once

            self.lean = LeanMean(self.rest, st.body, st.kind, st.sigma, self.grid, self.first.compact, st.orbit,
                                 st.nu is not None)

    def mean(self, st: State) -> Mean:
        if not self.calibrated:
            self.calibrate(st)
        total: Mean | None = None
        for p in self.closed:
            m = checked_closed_mean(p, st)
            total = m if total is None else total + m
        if self.rest is not None:
            assert self.grid is not None
            assert self.first is not None
            lm = self.lean
            if (lm is not None and lm.kind == st.kind and lm.sigma == st.sigma and lm.held == (st.nu is not None)
                    and st.mc == 1.0 - st.k2):
                q = np.array(lm(st.G, st.k2, *(float(x) for x in st.n), st.nu))
            else:
                q = lean_mean(self.rest, st, self.grid, self.first.compact)
            m = mean_of(q, st)
            total = m if total is None else total + m
        assert total is not None
        return total

    def fast(self, kind: str, sigma: int, held: bool) -> Any:
        """The engine's :meth:`._lean.LeanMean.rates` when the whole torque goes through the engine on the grid of the
        last calibration for this kind, sense and true-anomaly mode (the right-hand sides then skip the state
        objects), else None."""
        lm = self.lean
        if self.closed or lm is None or lm.kind != kind or lm.sigma != sigma or lm.held != held:
            return None
        return lm.rates

    def closed_sum(self, st: State) -> Mean:
        """The sum of the closed-form parts' means at ``st`` (zero when every part goes through the engine)."""
        total = Mean(np.zeros(3), 0.0, 0.0)
        for p in self.closed:
            total = total + checked_closed_mean(p, st)
        return total

    def report(self, st: State) -> tuple[Mean, Mean]:
        """(mean on the integrators' grid, a bound on its quadrature error) at a state. The bound is
        |lean - fine| + (estimated error of the fine, calibration grid): the triangle inequality. Closed
        forms count as exact."""
        if not self.calibrated:
            self.calibrate(st)
        total = self.closed_sum(st)
        err = Mean(np.zeros(3), 0.0, 0.0)
        if self.rest is not None:
            assert self.first is not None and self.grid is not None
            s0 = self.first_state
            if s0 is not None and _same_state(s0, st):  # the calibration's own estimate on that grid
                q = self.first
            else:
                q = adaptive(self.rest, st, self.tol, grid=self.first.grid, refine=False, compact=self.first.compact)
            lm = self.lean
            if lm is not None and lm.kind == st.kind and lm.sigma == st.sigma and lm.held == (st.nu is not None):
                lean = np.array(lm(st.G, st.k2, *(float(x) for x in st.n), st.nu))
            else:
                lean = lean_mean(self.rest, st, self.grid, self.first.compact)
            total = total + mean_of(lean, st)
            err = error_of(np.abs(lean - q.mean) + q.error, st)
        return total, err


def _same_state(a: State, b: State, rel: float = 1e-12) -> bool:
    """Whether two slow states agree to ``rel`` (the start of a run, and the calibration state it came from)."""
    return (a.kind == b.kind and a.sigma == b.sigma and a.body is b.body and a.orbit == b.orbit
            and (a.nu is None) == (b.nu is None)
            and (a.nu is None or b.nu is None or abs(a.nu - b.nu) <= rel * (1.0 + abs(b.nu)))
            and abs(a.G - b.G) <= rel * abs(b.G) and abs(a.k2 - b.k2) <= rel
            and float(np.abs(np.asarray(a.n) - np.asarray(b.n)).max()) <= rel)
