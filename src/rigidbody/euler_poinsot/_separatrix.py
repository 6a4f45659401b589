r"""The separatrix of the Euler--Poinsot motion and the passage through it.

On the sphere :math:`|\mathbf g| = G` of body components of the angular momentum the separatrix
:math:`G^2 = 2TA_2` is two great circles through the saddles :math:`\pm G\mathbf e_2` (rotation about the
intermediate axis). They cut the sphere into four *regions*, one per kind of motion and sense of
rotation: ``("max", s)`` (circulation about :math:`s\,\mathbf e_1`, :math:`g_1` of sign :math:`s`) and
``("min", s)`` (about :math:`s\,\mathbf e_3`). The four half circles between the saddles are the *arcs*
:math:`(s_1, s_3)`, :math:`s_i = \pm1` the signs of :math:`g_1, g_3` on them. Arc :math:`(s_1, s_3)`
separates the regions ``("max", s1)`` and ``("min", s3)``; the flow runs along it from
:math:`+\mathbf e_2` to :math:`-\mathbf e_2` when :math:`s_1s_3 = 1` and back when :math:`s_1s_3 = -1`.

Motion on an arc (from Euler's equations; the :math:`k\to1` limit of section 2, sn → tanh, cn, dn → sech):

.. math::
    \mathbf g = \big(s_1c_1\operatorname{sech}\lambda t,\ -s_1s_3G\tanh\lambda t,\
    s_3c_3\operatorname{sech}\lambda t\big),\qquad
    c_1 = G\sqrt{\frac{A_1(A_2-A_3)}{A_2(A_1-A_3)}},\ c_3 = G\sqrt{\frac{A_3(A_1-A_2)}{A_2(A_1-A_3)}},
    \ \lambda = G\sqrt{\frac{(A_1-A_2)(A_2-A_3)}{A_1A_2^2A_3}} .

Slow drift along the separatrix
-------------------------------
With a torque :math:`\mathbf L` (body components) the energy measured from the separatrix,
:math:`h = T - G^2/(2A_2)` (:math:`h < 0` in the ``"max"`` regions, :math:`> 0` in the ``"min"``
ones), changes at the rate :math:`\dot h = (\boldsymbol\omega - \mathbf g/A_2)\cdot\mathbf L`, which vanishes
at the saddles. Its integral along an arc (with the torque averaged over the precession angle
:math:`\psi` about :math:`\mathbf G`, and over the orbit when ``nu`` is None) is finite:

.. math:: \Theta_{s_1s_3} = \int_{-\infty}^{\infty}\langle\dot h\rangle_\psi\,dt
          = \frac1\lambda\int_{-\pi/2}^{\pi/2}\Big\langle s_1c_1\Big(\frac1{A_1}-\frac1{A_2}\Big)L_1
          + s_3c_3\Big(\frac1{A_3}-\frac1{A_2}\Big)L_3\Big\rangle_\psi dx,

(substitution :math:`\tanh\lambda t = \sin x`), computed by Gauss--Legendre quadrature in :math:`x`.
A region's *loop drift* is the sum over its two arcs: the change of :math:`h` per revolution of a motion
close to the separatrix. The averaged rate of :math:`h` there is the loop drift over the period,
:math:`\to 0` like :math:`1/K(k)`, so :math:`k^2` reaches 1 in finite time when the loop drift points to
the separatrix.

Capture probabilities
---------------------
A motion that reaches the separatrix from region :math:`R_0` follows the arcs; at each saddle it
continues along the next arc of the region on whose side it is (the sign of :math:`h` there), and along
each arc :math:`h` changes by :math:`\Theta` of that arc. The phase at which the crossing happens is fast
and, over an ensemble of initial states, uniformly distributed in :math:`h` over one loop drift
(Liouville). Following the interval of :math:`h` through this piecewise translation until each piece is
in a region whose loop drift points away from the separatrix gives the probability of capture into each
region. With two boundary arcs of positive flux this is the classical ratio of the fluxes
(:math:`\Theta_1/(\Theta_1+\Theta_2)`); on the four-arc network of the rigid body a motion can also pass
into a region that does not keep it (its loop drift points to the separatrix) and leave it again, which
the interval bookkeeping follows. The bookkeeping is derived here; the probabilistic description of
separatrix crossing in the Euler--Poinsot problem is that of J. Bao and A. Neishtadt, "Separatrix
crossing in rotation of a body with changing geometry of masses" (arXiv:1712.05357, 2017); the
equivalence of the usual definitions of the probability is shown by A. Neishtadt and A. Okunev, "On the
phase change for perturbations of Hamiltonian systems with separatrix crossing" (arXiv:2003.05828, 2020).

Assumptions: the torque is averaged over :math:`\psi` on each arc. That is exact for torques that depend
on the body's angular velocity only (a constant body-fixed torque, linear drag); for torques that depend on
the attitude about :math:`\mathbf G` (gravity gradient, magnetic) the drift of a single passage depends on
the precession phase at that passage, and the probabilities computed from the averaged drifts are the
leading approximation only.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..core import euler
from ..core.validate import real
from ._boundary import as_torque
from ._engine import nu_nodes
from ._model import Body, Orbit, as_orbit, check_body
from ._protocol import evaluate
from ._regions import ARCS, REGIONS, Arc, Region, check_arc, check_region, next_arc, region_arcs
from ._state import frame

__all__ = ["ARCS", "K2_SWITCH", "REGIONS", "Separatrix", "SeparatrixCrossing", "momenta_at", "orbit_nodes",
           "psi_average", "separatrix_crossing", "separatrix_setup"]


TorqueFn = Callable[[np.ndarray, np.ndarray, np.ndarray], Any]


@dataclass(frozen=True)
class Separatrix:
    r"""The separatrix motions :math:`G^2 = 2TA_2` of a triaxial body, in hyperbolic functions.

    Parameters
    ----------
    body : Body
    G : float
        Magnitude of the angular momentum (> 0).

    See Also
    --------
    EulerPoinsot : the motions on either side, of which it is the limit :math:`k\to1`.
    separatrix_crossing : the drifts along its arcs and the capture probabilities.
    separatrix_limits : the averaged rates at the separatrix.

    Notes
    -----
    ``g(t, arc)`` is the motion along the arc ``(s1, s3)`` (see the module docstring), at the middle of
    the arc (``g2 = 0``) at ``t = 0``; it tends to the saddle :math:`\mp s_1s_3G\mathbf e_2` as
    :math:`t\to\pm\infty`. It is the limit :math:`k\to1` of :class:`EulerPoinsot` of either kind: the
    ``"max"`` motion with ``sigma = s1`` runs along ``(s1, +1)`` and then ``(s1, -1)``, the ``"min"``
    motion with ``sigma = s3`` along ``(+1, s3)`` and then ``(-1, s3)``.

    Examples
    --------
    >>> from rigidbody.euler_poinsot import Body, Separatrix
    >>> sep = Separatrix(Body(3.2, 2.6, 1.67), G=1.0)
    >>> g = sep.g(0.7, (1, -1))
    >>> bool(abs((g**2).sum() - 1.0) < 1e-14), bool(abs(0.5 * (g**2 / sep.body.A).sum() - sep.T) < 1e-14)
    (True, True)
    """

    body: Body
    G: float

    def __post_init__(self) -> None:
        check_body(self.body)
        G = real(self.G, "G")
        if G <= 0:
            raise ValueError(f"G must be positive, got {G}")
        object.__setattr__(self, "G", G)

    @property
    def T(self) -> float:
        r"""Kinetic energy on the separatrix, :math:`G^2/(2A_2)`.

        Examples
        --------
        The energy of the Euler--Poinsot motion at :math:`k^2 = 1` (the inverse of (5), :func:`T_from`), and
        :math:`1/(2\cdot2.6)` by hand:

        >>> from rigidbody import euler_poinsot as ep
        >>> body = ep.Body(3.2, 2.6, 1.67)
        >>> print(f"{ep.Separatrix(body, 1.0).T:.6f} {ep.T_from(body, 1.0, 1.0):.6f} {1 / 5.2:.6f}")
        0.192308 0.192308 0.192308
        """
        return self.G**2 / (2.0 * self.body.A2)

    @property
    def rate(self) -> float:
        r""":math:`\lambda = G\sqrt{(A_1-A_2)(A_2-A_3)/(A_1A_2^2A_3)}`: the exponent of the saddles.

        Examples
        --------
        On an arc :math:`g_2 = -s_1s_3G\tanh(\lambda t)`, so at its middle :math:`\dot g_2 = -s_1s_3G\lambda`;
        Euler's equation :math:`\dot{\mathbf g} = \mathbf g\times\boldsymbol\omega` gives
        :math:`\dot g_2 = g_3\omega_1 - g_1\omega_3` there:

        >>> from rigidbody import euler_poinsot as ep
        >>> sep = ep.Separatrix(ep.Body(3.2, 2.6, 1.67), 1.0)
        >>> g, w = sep.g(0.0, (1, 1)), sep.omega(0.0, (1, 1))
        >>> print(f"{sep.rate:.6f} {-(g[2] * w[0] - g[0] * w[2]) / sep.G:.6f}")
        0.124283 0.124283
        """
        A1, A2, A3 = self.body.A1, self.body.A2, self.body.A3
        return self.G * math.sqrt((A1 - A2) * (A2 - A3) / (A1 * A2 * A2 * A3))

    @property
    def amplitudes(self) -> tuple[float, float]:
        r""":math:`(c_1, c_3)`, the largest :math:`|g_1|` and :math:`|g_3|` on the separatrix.

        Examples
        --------
        Both are reached at the middle of an arc (:math:`g_2 = 0`), where :math:`c_1^2 + c_3^2 = G^2` and the
        energy is that of the separatrix, :math:`c_1^2/A_1 + c_3^2/A_3 = 2T = G^2/A_2`:

        >>> from rigidbody import euler_poinsot as ep
        >>> c1, c3 = ep.Separatrix(ep.Body(3.2, 2.6, 1.67), 1.0).amplitudes
        >>> print(f"{c1**2 + c3**2:.6f} {c1**2 / 3.2 + c3**2 / 1.67:.6f} {1 / 2.6:.6f}")
        1.000000 0.384615 0.384615
        """
        A1, A2, A3 = self.body.A1, self.body.A2, self.body.A3
        c1 = self.G * math.sqrt(A1 * (A2 - A3) / (A2 * (A1 - A3)))
        c3 = self.G * math.sqrt(A3 * (A1 - A2) / (A2 * (A1 - A3)))
        return c1, c3

    def g(self, t: Any, arc: Any) -> np.ndarray:
        r"""Body components of the angular momentum on the arc ``(s1, s3)``, shape ``(3, *t.shape)``.

        Parameters
        ----------
        t : array_like
            Time from the middle of the arc.
        arc : (int, int)
            Signs ``(s1, s3)`` of :math:`g_1, g_3` on the arc.

        Examples
        --------
        The motion leaves one saddle and tends to the other, :math:`\mp s_1s_3G\mathbf e_2` as
        :math:`t\to\pm\infty` (at :math:`\lambda t = \pm25`, :math:`\operatorname{sech} = 3\cdot10^{-11}`):

        >>> import numpy as np
        >>> from rigidbody import euler_poinsot as ep
        >>> sep = ep.Separatrix(ep.Body(3.2, 2.6, 1.67), 1.0)
        >>> t = 25.0 / sep.rate
        >>> (np.round(sep.g(np.array([-t, t]), (1, -1)), 9) + 0.0).T.tolist()
        [[0.0, -1.0, 0.0], [0.0, 1.0, 0.0]]
        """
        a = check_arc(arc)
        u = self.rate * np.asarray(t, dtype=float)
        return momenta_at(self, np.arctan(np.sinh(u)), a)  # gd(u): sin x = tanh u, cos x = sech u

    def omega(self, t: Any, arc: Any) -> np.ndarray:
        r"""Body angular velocity on the arc ``(s1, s3)``, shape ``(3, *t.shape)``.

        Examples
        --------
        It obeys Euler's equations :math:`A\dot{\boldsymbol\omega} = A\boldsymbol\omega\times\boldsymbol\omega`:
        a central difference with :math:`h = 10^{-4}` errs by :math:`h^2|\dddot{\boldsymbol\omega}|/6 \approx
        10^{-12}` (and :math:`10^{-16}/h` of rounding), far below the bound :math:`10^{-9}`:

        >>> import numpy as np
        >>> from rigidbody import euler_poinsot as ep
        >>> body = ep.Body(3.2, 2.6, 1.67)
        >>> sep, h = ep.Separatrix(body, 1.0), 1e-4
        >>> w = sep.omega(3.0, (-1, 1))
        >>> dw = (sep.omega(3.0 + h, (-1, 1)) - sep.omega(3.0 - h, (-1, 1))) / (2 * h)
        >>> bool(np.abs(dw - np.cross(body.A * w, w) / body.A).max() < 1e-9)
        True
        """
        g = self.g(t, arc)
        return g / self.body.A.reshape((3,) + (1,) * (g.ndim - 1))


def momenta_at(sep: Separatrix, x: np.ndarray, arc: Arc) -> np.ndarray:
    """Body angular momentum at the points ``sin x = tanh(rate t)`` of an arc, shape ``(3, *x.shape)``."""
    s1, s3 = arc
    c1, c3 = sep.amplitudes
    cx = np.cos(x)
    return np.stack([s1 * c1 * cx, -s1 * s3 * sep.G * np.sin(x), s3 * c3 * cx])


# --------------------------------------------------------------------------------------------------
# the perturbation: a torque callable (omega, C, nu) -> M, vectorised over leading axes
# --------------------------------------------------------------------------------------------------
def _torque_fn(torque: Any, body: Body, orbit: Orbit) -> TorqueFn:
    """The whole perturbation as a torque object: a drag tensor means drag plus the gravity-gradient torque."""
    tq, _ = as_torque(torque, body, orbit)
    tq.check_setup(body, orbit)
    return tq


def orbit_nodes(nu: float | None, orbit: Orbit, n_nu: int) -> tuple[np.ndarray, np.ndarray]:
    """True anomalies and weights: ``nu`` itself, or the time mean over one orbit (Kepler's law)."""
    if nu is not None:
        return np.array([nu]), np.array([1.0])
    return nu_nodes(orbit.e, n_nu)


def _unit_n(delta: Any, lam: Any) -> np.ndarray:
    d, la = real(delta, "delta"), real(lam, "lam")
    if not (0.0 <= d <= math.pi):
        raise ValueError(f"delta (polar angle of G from x3) must lie in [0, pi], got {d}")
    return np.array([math.sin(d) * math.cos(la), math.sin(d) * math.sin(la), math.cos(d)])


def psi_average(body: Body, torque: TorqueFn, g: np.ndarray, n: np.ndarray, nus: np.ndarray,
                wnu: np.ndarray, n_psi: int) -> tuple[np.ndarray, np.ndarray]:
    """Torque at body momenta ``g`` (3, m), averaged over psi (and the orbit nodes).

    Returns the mean body torque (3, m) and the mean torque in the orbital axes (3, m).
    """
    G = np.linalg.norm(g, axis=0)
    theta = np.arccos(np.clip(g[2] / G, -1.0, 1.0))
    phi = np.arctan2(g[0], g[1])
    psi = np.arange(n_psi) * (2.0 * math.pi / n_psi)
    alpha = euler.dcm(psi[:, None], theta[None, :], phi[None, :])  # (n_psi, m, 3, 3): body -> Oy
    C = np.einsum("ij,...jk->...ik", frame(n), alpha)  # body -> Ox
    omega = np.broadcast_to((g / body.A[:, None]).T, C.shape[:-1])
    Lb = np.zeros((3, g.shape[1]))
    Lo = np.zeros((3, g.shape[1]))
    for nu, w in zip(nus, wnu):
        M = evaluate(torque, omega, C, np.full(C.shape[:-2], nu), omega.shape)
        if M.shape != omega.shape:
            M = np.broadcast_to(M, omega.shape)
        Lb += w * M.mean(axis=0).T
        Lo += w * np.einsum("...ij,...j->...i", C, M).mean(axis=0).T
    return Lb, Lo


def _check_nodes(n: Any, name: str, minimum: int) -> int:
    if isinstance(n, (bool, np.bool_)) or not isinstance(n, (int, np.integer)) or n < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}, got {n!r}")
    return int(n)


def separatrix_setup(body: Any, torque: Any, G: Any, delta: Any, lam: Any, nu: Any, orbit: Any, n_x: Any, n_psi: Any,
                     n_nu: Any) -> tuple[Separatrix, TorqueFn, np.ndarray, float | None, Orbit, tuple[int, int, int]]:
    check_body(body)
    orb = as_orbit(orbit)
    sep = Separatrix(body, G)
    n = _unit_n(delta, lam)
    nu_ = None if nu is None else real(nu, "nu")
    nodes = (_check_nodes(n_x, "n_x", 4), _check_nodes(n_psi, "n_psi", 2), _check_nodes(n_nu, "n_nu", 2))
    return sep, _torque_fn(torque, body, orb), n, nu_, orb, nodes


def _arc_drifts(sep: Separatrix, torque: TorqueFn, n: np.ndarray, nus: np.ndarray, wnu: np.ndarray,
                n_x: int, n_psi: int) -> dict[Arc, float]:
    body = sep.body
    A1, A2, A3 = body.A1, body.A2, body.A3
    c1, c3 = sep.amplitudes
    x, w = np.polynomial.legendre.leggauss(n_x)
    x = 0.5 * math.pi * x
    w = 0.5 * math.pi * w
    out: dict[Arc, float] = {}
    for arc in ARCS:
        s1, s3 = arc
        Lb, _ = psi_average(body, torque, momenta_at(sep, x, arc), n, nus, wnu, n_psi)
        integrand = s1 * c1 * (1.0 / A1 - 1.0 / A2) * Lb[0] + s3 * c3 * (1.0 / A3 - 1.0 / A2) * Lb[2]
        out[arc] = float(w @ integrand) / sep.rate
    return out


def _captures(region: Region, loop: float, scale: float) -> bool:
    """A region keeps the motions that enter it when its loop drift points away from the separatrix (into h of its
    sign)."""
    return region.h_sign * loop > 1e-12 * scale


def _propagate(drifts: dict[Arc, float], source: Region, first: int = 0, max_steps: int = 200, floor: float = 0.0
               ) -> tuple[dict[Region, float], float, bool]:
    """Capture probabilities from ``source`` by following the interval of h through the arc network.

    Drifts below ``floor`` in absolute value count as zero (a torque without effect on the separatrix).
    """
    scale = max(abs(v) for v in drifts.values())
    if scale <= floor:
        return dict.fromkeys(REGIONS, 0.0), 0.0, False
    loops = {r: sum(drifts[a] for a in region_arcs(r)) for r in REGIONS}
    source = Region(*source)
    a0 = region_arcs(source)[first]
    loop = loops[source]
    probs = dict.fromkeys(REGIONS, 0.0)
    if scale == 0.0 or not -source.h_sign * loop > 1e-12 * scale:
        return probs, 0.0, False  # the source region does not approach the separatrix: nothing crosses
    p1, p2 = drifts[a0], loop
    if not source.about_a1:  # h > 0; crossing in this loop iff h + min(p1, p2) <= 0
        m = min(p1, p2)
        pieces = [(a0, -m - abs(loop), -m)]
    else:  # h < 0; crossing iff h + max(p1, p2) >= 0
        m = max(p1, p2)
        pieces = [(a0, -m, -m + loop)]
    total = abs(loop)
    for _ in range(max_steps):
        new: list[tuple[Arc, float, float]] = []
        for arc, lo, hi in pieces:
            lo, hi = lo + drifts[arc], hi + drifts[arc]
            parts = [(lo, min(hi, 0.0)), (max(lo, 0.0), hi)]
            for plo, phi_ in parts:
                if phi_ - plo <= 0.0:
                    continue
                h_side = -1.0 if phi_ <= 0.0 else 1.0
                region = Region.beside(arc, h_side)
                nxt = next_arc(arc, h_side)
                q1, q2 = drifts[nxt], loops[region]
                if _captures(region, q2, scale) and (
                    (region.about_a1 and phi_ + max(q1, q2) < 0.0)
                    or (not region.about_a1 and plo + min(q1, q2) > 0.0)
                ):
                    probs[region] += (phi_ - plo) / total
                    continue
                new.append((nxt, plo, phi_))
        pieces = new
        if not pieces:
            break
    undetermined = max(0.0, 1.0 - sum(probs.values()))
    return probs, undetermined, True


@dataclass(frozen=True)
class SeparatrixCrossing:
    r"""What happens when a motion reaches the separatrix: drifts along the arcs and capture probabilities.

    Attributes
    ----------
    source : (str, int)
        The region ``(kind, sigma)`` the motion comes from.
    drifts : dict
        Arc ``(s1, s3)`` -> :math:`\Theta`, the change of :math:`h = T - G^2/(2A_2)` along one passage of the
        arc, per unit torque time: in the section-3 scaling the change is :math:`\varepsilon^2\Theta` (the
        torque acts in :math:`\tau = \varepsilon^2\tilde t`); with a dimensional torque :math:`\Theta` is the
        change itself.
    loop_drifts : dict
        Region -> the sum of the drifts of its two arcs: the change of :math:`h` per revolution close to the
        separatrix. A ``"max"`` region approaches the separatrix when it is positive, a ``"min"`` region when
        it is negative.
    probabilities : dict
        Region -> probability that the motion ends in it (each region whose loop drift points away from the
        separatrix; 0 for the others). They sum to ``1 - undetermined``.
    undetermined : float
        Measure of crossing phases the arc bookkeeping could not settle (e.g. all drifts zero); 0 normally.
    crosses : bool
        Whether motions of the source region reach the separatrix at all (its loop drift points to it).
    quad_error : float
        Estimated quadrature error of the drifts (difference to the half-node rule).

    See Also
    --------
    separatrix_crossing : computes it.
    averaged_branches : averaged runs through the separatrix into each region.
    Separatrix : the motions along the arcs.

    Examples
    --------
    The drag is odd in :math:`\boldsymbol\omega`: both senses of rotation tie (the tie goes to ``sigma = +1``):

    >>> from rigidbody import euler_poinsot as ep
    >>> c = ep.separatrix_crossing(ep.Body(3.2, 2.6, 1.67), [3.0, 2.0, 1.0], 1.0, 0.7, 0.3, None, ("max", 1))
    >>> c.capturing, round(c.probabilities[("min", -1)], 9), c.most_probable()
    ((('min', 1), ('min', -1)), 0.5, ('min', 1))
    """

    source: Region
    drifts: dict[Arc, float] = field(repr=False)
    loop_drifts: dict[Region, float]
    probabilities: dict[Region, float]
    undetermined: float
    crosses: bool
    quad_error: float = field(repr=False)

    @property
    def capturing(self) -> tuple[Region, ...]:
        r"""The regions that keep the motions entering them (loop drift away from the separatrix).

        Examples
        --------
        For the drag :math:`I = \mathrm{diag}(3, 2, 1)`, :math:`I_{11}/A_1 - I_{33}/A_3 > 0`: next to the separatrix
        (8) drives :math:`k^2` up on the ``'max'`` side and, the labels 1 and 3 exchanged, down on the ``'min'``
        side (:func:`k2_equilibria`), so the two ``'min'`` regions keep the motions and the ``'max'`` ones do not:

        >>> from rigidbody import euler_poinsot as ep
        >>> print(f"{3.0 / 3.2 - 1.0 / 1.67:.3f}")
        0.339
        >>> c = ep.separatrix_crossing(ep.Body(3.2, 2.6, 1.67), [3.0, 2.0, 1.0], 1.0, 0.7, 0.3, None, ("max", 1))
        >>> c.capturing
        (('min', 1), ('min', -1))
        """
        scale = max(abs(v) for v in self.drifts.values()) if self.drifts else 0.0
        return tuple(r for r in REGIONS if _captures(r, self.loop_drifts[r], scale))

    def most_probable(self) -> Region:
        r"""The region of largest capture probability (ties: ``sigma = +1`` first, then ``'max'``).

        Examples
        --------
        The drag is odd in :math:`\boldsymbol\omega`: the two senses of rotation are mirror images and tie, and
        the tie goes to ``sigma = +1``. Motions of a region that moves away from the separatrix (``'min'`` for
        this drag, see ``capturing``) do not reach it:

        >>> from rigidbody import euler_poinsot as ep
        >>> body, I = ep.Body(3.2, 2.6, 1.67), [3.0, 2.0, 1.0]
        >>> ep.separatrix_crossing(body, I, 1.0, 0.7, 0.3, None, ("max", 1)).most_probable()
        ('min', 1)
        >>> ep.separatrix_crossing(body, I, 1.0, 0.7, 0.3, None, ("min", 1)).most_probable()
        Traceback (most recent call last):
        ...
        ValueError: motions of ('min', 1) do not cross the separatrix: no capture
        """
        if not self.crosses:
            raise ValueError(f"motions of {self.source} do not cross the separatrix: no capture")
        return max(REGIONS, key=lambda r: (round(self.probabilities[r], 12), r.sigma, r.about_a1))


def separatrix_crossing(
    body: Body,
    torque: Any,
    G: float,
    delta: float,
    lam: float,
    nu: float | None,
    source: Any,
    *,
    orbit: Orbit | None = None,
    n_x: int = 48,
    n_psi: int = 16,
    n_nu: int = 32,
) -> SeparatrixCrossing:
    r"""Drifts along the separatrix arcs and the capture probabilities of a motion crossing it.

    Parameters
    ----------
    body : Body
    torque : callable or array_like or Drag
        ``torque(omega, C, nu) -> M`` (body components; ``omega`` of shape ``(..., 3)``, ``C`` body ->
        orbital axes of shape ``(..., 3, 3)``, ``nu`` of shape ``(...)``), the whole perturbation in the
        section-3 scaling; or a drag tensor (then the perturbation is the paper's drag plus the
        gravity-gradient torque (3)).
    G : float
        Magnitude of the angular momentum at the crossing (> 0).
    delta, lam : float
        Direction of :math:`\mathbf G` in the orbital axes (polar angle from :math:`x_3`, azimuth).
    nu : float or None
        True anomaly at the crossing (held fixed: the crossing takes a few rotations); ``None`` averages
        over the orbit (the ``eps = 0`` limit).
    source : (str, int)
        The region ``(kind, sigma)`` the motion comes from.
    orbit : Orbit, optional
        For the orbit average (``nu=None``) and the drag-tensor form (gravity factor).
    n_x, n_psi, n_nu : int
        Gauss--Legendre nodes along an arc, trapezoid nodes in :math:`\psi` and in the mean anomaly.

    Returns
    -------
    SeparatrixCrossing
        ``probabilities`` maps each region ``(kind, sigma)`` to its capture probability.

    See Also
    --------
    SeparatrixCrossing : its result.
    separatrix_limits : the averaged rates as the separatrix is approached.
    averaged : continues a run through the separatrix in a region chosen with these probabilities.
    averaged_branches : runs each region.

    Examples
    --------
    A constant body-fixed torque that brakes a spin about the minor axis and pushes about the major one:

    >>> import numpy as np
    >>> from rigidbody.euler_poinsot import Body, separatrix_crossing
    >>> M0 = np.array([0.4, 0.0, -0.5])
    >>> c = separatrix_crossing(Body(3.2, 2.6, 1.67), lambda w, C, nu: np.broadcast_to(M0, w.shape),
    ...                         1.0, 0.5, 0.0, 0.0, ("min", 1))
    >>> {r: round(p, 3) for r, p in c.probabilities.items() if p > 0}
    {('max', 1): 0.464, ('min', -1): 0.536}
    """
    sep, fn, n, nu_, orb, nodes = separatrix_setup(body, torque, G, delta, lam, nu, orbit, n_x, n_psi, n_nu)
    n_x, n_psi, n_nu = nodes
    src = check_region(source, "source")
    nus, wnu = orbit_nodes(nu_, orb, n_nu)
    drifts = _arc_drifts(sep, fn, n, nus, wnu, n_x, n_psi)
    nus2, wnu2 = orbit_nodes(nu_, orb, max(2, n_nu // 2))
    coarse = _arc_drifts(sep, fn, n, nus2, wnu2, max(4, n_x // 2), max(2, n_psi // 2))
    err = max(abs(drifts[a] - coarse[a]) for a in ARCS)
    # drifts below 1e-12 of the separatrix energy per passage time count as zero: a torque that does not act on
    # the separatrix (then no region keeps the motions reaching it: it attracts from all sides)
    probs, und, crosses = _propagate(drifts, src, floor=1e-12 * sep.T / sep.rate)
    loops = {r: sum(drifts[a] for a in region_arcs(r)) for r in REGIONS}
    return SeparatrixCrossing(src, drifts, loops, probs, und, crosses, err)


# --------------------------------------------------------------------------------------------------
# what the integrators need: initial states on either side, the switch at the separatrix, the branch
# --------------------------------------------------------------------------------------------------
#: The averaged integration switches to the other side of the separatrix when k^2 reaches this value; the
#: new kind of motion starts at the same k^2 with G and n continuous (T jumps by O(1e-9) relative: the two
#: sides at 1 - k^2 = 1e-9 are that close in energy), and the time skipped is below 1e-7.
K2_SWITCH = 1.0 - 1e-9


