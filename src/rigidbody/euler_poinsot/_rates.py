"""The averaged rates at one state: (6) for a drag tensor, the mean effect of any torque, the precession rate."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..core.validate import positive, real
from ._algebra import dk2_labelled, drag_rates_labelled, nstar_labelled
from ._boundary import as_torque
from ._checks import check_averaging, check_sigma
from ._engine import Averager, TorqueAverage, error_of, mean_of
from ._model import Body, Orbit, as_orbit, check_body, check_kind, frame_y, labelled
from ._state import Mean, State

__all__ = ["average_torque", "averaged_rates", "direction_rates", "precession_rate"]


def averaged_rates(
    body: Body,
    torque: Any,
    G: float,
    k2: float,
    delta: float,
    lam: float,
    nu: float | None,
    *,
    kind: str = "max",
    orbit: Orbit | None = None,
    omega0: float = 1.0,
    sigma: int = 1,
    method: str = "auto",
) -> dict[str, float]:
    r"""Right-hand sides of the averaged system (6) (dimensional) or (9) (per :math:`\tau`, ``omega0=1``).

    Parameters
    ----------
    body : Body
    torque : array_like, Drag, torque object or callable
        A drag tensor (3x3, its diagonal, or a :class:`Drag`; only its diagonal enters (6)): Rachinskaya's
        drag *plus* the gravity-gradient torque, the closed forms (6). A torque object or a plain callable
        ``torque(omega, C, nu) -> M`` (see :class:`Torque`) is the whole perturbation: its averages come from
        the closed forms of its parts where they have them, from the averaging engine otherwise
        (:func:`average_torque`).
    G, k2, delta, lam : float
        Slow variables.
    nu : float or None
        True anomaly; ``None`` gives the orbit-averaged limit (:math:`\varepsilon \to 0`).
    kind : {'max', 'min'}
        Kind of Euler--Poinsot motion ('max' is the paper's).
    orbit : Orbit, optional
        Eccentric orbits multiply the gravity terms by :math:`(1+e\cos\nu)^3/(1-e^2)^3`.
    omega0 : float
        Orbital mean motion (1 in the nondimensional form (9)). Only for a drag tensor: a torque object
        carries its own scale (e.g. ``GravityGradient(..., omega0=...)``).
    sigma : {+1, -1}
        Sense of rotation of the Euler--Poinsot motion (sign of :math:`g_1` for 'max', :math:`g_3` for 'min').
        The averages of torques that are not odd in :math:`\boldsymbol\omega` depend on it (a constant
        body-fixed torque, a magnet); those of the paper's two torques do not.
    method : {'auto', 'numerical'}
        ``'numerical'`` uses the engine for every part, also where a closed form exists (for checks).

    Returns
    -------
    dict
        ``dG``, ``dT``, ``dk2``, ``ddelta``, ``dlam``. For a drag tensor the :math:`\lambda` equation is
        evaluated as :math:`\beta_1\beta_3/\sin\delta = \cos^2(\nu-\lambda)\cos\delta`, which is finite at
        :math:`\sin\delta = 0` (where :math:`\lambda` itself is undefined: the integrator evolves the unit
        vector of :math:`\mathbf G` instead). For a torque object ``dlam`` is :math:`L_2/(G\sin\delta)`; at
        :math:`\sin\delta = 0` its limit along the meridian :math:`\lambda` when :math:`L_2 = 0` there,
        :math:`\pm\infty` otherwise (use :func:`average_torque` for the regular :math:`d\mathbf n/d\tau`).

    Raises
    ------
    TypeError
        If ``body`` is not a :class:`Body`, a number is not real or ``torque`` is neither a drag tensor nor
        a callable; or the torque returns None, complex numbers or anything but real numbers (the message
        names it).
    ValueError
        If ``G <= 0``, ``k2`` is outside [0, 1], ``nu`` is not finite, ``omega0 <= 0`` (or not 1 with a
        torque object), ``sigma`` is not +1 or -1, ``method`` or ``kind`` is unknown, or a torque object
        was built for another body or orbit; or the torque returns a scalar, a shape other than ``(..., 3)``,
        NaN or infinities (the message names it and what was expected).

    See Also
    --------
    averaged : integrates these right-hand sides.
    average_torque : the engine, with its error estimate.
    symmetric_rates : the rates of a body with two equal moments (their limit).
    drag_rates, dk2_dtau, precession_rate : the closed forms of the paper's case.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, eqs. (6), (8), (9).

    Examples
    --------
    The paper's case (a drag tensor: drag plus gravity gradient): the gravity gradient leaves :math:`G`,
    :math:`T` and :math:`k^2` unchanged on average, so those rates are the drag's of (6) and (8), and with
    :math:`\nu` averaged out (``nu=None``) :math:`\lambda` turns at the :func:`precession_rate`:

    >>> from rigidbody import euler_poinsot as ep
    >>> body, I = ep.Body(3.2, 2.6, 1.67), [2.322, 1.31, 1.425]
    >>> r = ep.averaged_rates(body, I, 1.0, 0.5, 0.7, 0.3, None)
    >>> dG, dT = ep.drag_rates(body, I, 1.0, 0.5)
    >>> print(f"{r['dG']:.6f} {dG:.6f} {r['dk2']:.6f} {ep.dk2_dtau(body, I, 0.5):.6f}")
    -0.665135 -0.665135 0.001881 0.001881
    >>> print(f"{r['dlam']:.6f} {ep.precession_rate(body, 1.0, 0.5, 0.7):.6f}")
    -0.727719 -0.727719
    """
    check_body(body)
    check_kind(kind)
    orb = as_orbit(orbit)
    check_averaging(method, "method")
    sigma = check_sigma(sigma)
    G = real(G, "G")
    if G <= 0:
        raise ValueError(f"G must be positive, got {G}")
    k2 = real(k2, "k2")
    if not (0.0 <= k2 <= 1.0):
        raise ValueError(f"k2 must lie in [0, 1], got {k2}")
    delta, lam = real(delta, "delta"), real(lam, "lam")
    omega0 = real(omega0, "omega0")
    if omega0 <= 0:
        raise ValueError(f"omega0 (orbital mean motion) must be positive, got {omega0}")
    if nu is not None:
        nu = real(nu, "nu")
    tq, drag = as_torque(torque, body, orb, omega0)
    if drag is not None and method == "auto":
        return _rates_drag(body, drag, G, k2, delta, lam, nu, kind, orb, omega0)
    if drag is None and omega0 != 1.0:
        raise ValueError("omega0 applies to a drag tensor only: a torque object carries its own scale "
                         "(e.g. GravityGradient(body, orbit, omega0=...))")
    tq.check_setup(body, orb)
    if k2 >= 1.0:
        raise ValueError("k2 = 1 is the separatrix: the Euler-Poinsot period is infinite and a torque object "
                         "has no average there (the drag tensor's closed forms have a limit)")

    def L_at(d: float) -> np.ndarray:
        return _once(tq, State(body, kind, sigma, G, k2, frame_y(d, lam)[:, 2], nu, orb), method)[0].L

    mean, _, _ = _once(tq, State(body, kind, sigma, G, k2, frame_y(delta, lam)[:, 2], nu, orb), method)
    dG, ddelta, dlam = direction_rates(mean.L, G, delta, lam, L_at)
    return {"dG": dG, "dT": mean.dT, "dk2": mean.dk2, "ddelta": ddelta, "dlam": dlam}


def direction_rates(L: np.ndarray, G: float, delta: float, lam: float, L_at: Any) -> tuple[float, float, float]:
    r"""``dG``, ``ddelta``, ``dlam`` of the mean torque ``L`` (orbital axes) at the direction ``(delta, lam)`` of G:
    its components in the frame of G, :math:`(L_1/G, L_2/(G\sin\delta))` and :math:`L_3`. At a pole
    (:math:`\sin\delta = 0`) ``dlam`` is infinite where :math:`L_2 \ne 0`, else the limit along the meridian
    :math:`\lambda`, by a central difference of ``L_at(delta)`` (the mean torque at another polar angle; error
    :math:`O(h^2)`)."""
    Ly = frame_y(delta, lam).T @ L
    sd = math.sin(delta)
    if sd != 0.0:
        dlam = Ly[1] / (G * sd)
    elif abs(Ly[1]) > 1e-12 * max(1.0, float(np.abs(L).max())):
        dlam = math.copysign(math.inf, Ly[1])
    else:  # the limit L2(delta)/sin(delta) along the meridian: a central difference, error O(h^2)
        h = 1e-5
        dlam = ((frame_y(h, lam).T @ L_at(h))[1] - (frame_y(-h, lam).T @ L_at(-h))[1]) / (2.0 * math.sin(h) * G)
    return float(Ly[2]), float(Ly[0] / G), float(dlam)


#: quadrature tolerance of the engine (relative to the size of the torque on the grid)
_TOL = 1e-13


def _once(tq: Any, st: State, method: str, tol: float = _TOL) -> tuple[Mean, Mean, Any]:
    """Averages at one state with their error bound: closed forms where allowed, adaptive engine otherwise."""
    av = Averager(tq, method, tol)
    av.calibrate(st)
    total = av.closed_sum(st)
    err = Mean(np.zeros(3), 0.0, 0.0)
    if av.first is not None:
        total = total + mean_of(av.first.mean, st)
        err = error_of(av.first.error, st)
    return total, err, av.first


def _rates_drag(body: Body, drag: Any, G: float, k2: float, delta: float, lam: float, nu: float | None,
                kind: str, orb: Orbit, omega0: float) -> dict[str, float]:
    """The closed forms (6) for a drag tensor (drag plus gravity gradient)."""
    A, Id = labelled(body, kind, drag.diag)
    dG, dT = drag_rates_labelled(A, Id, G, k2)
    dk2 = dk2_labelled(A, Id, k2)
    Ns = nstar_labelled(A, k2)
    sd, cd = math.sin(delta), math.cos(delta)
    w2 = omega0 * omega0
    if nu is None:
        ddelta = 0.0
        dlam = 0.75 * w2 * orb.mean_factor * Ns * cd / G
    else:
        f = orb.factor(nu)
        b2 = math.sin(nu - lam)
        b3 = math.cos(nu - lam) * sd
        ddelta = -1.5 * w2 * f * b2 * b3 * Ns / G
        # beta1*beta3/sin(delta) = cos^2(nu - lam) cos(delta): regular at sin(delta) = 0
        dlam = 1.5 * w2 * f * math.cos(nu - lam) ** 2 * cd * Ns / G
    return {"dG": dG, "dT": dT, "dk2": dk2, "ddelta": ddelta, "dlam": dlam}


def average_torque(
    body: Body,
    torque: Any,
    G: float,
    k2: float,
    delta: float,
    lam: float,
    nu: float | None,
    *,
    kind: str = "max",
    sigma: int = 1,
    orbit: Orbit | None = None,
    tol: float = _TOL,
) -> TorqueAverage:
    r"""The averaging engine: the mean effect of any torque over the Euler--Poinsot motion, with its error.

    Averages the torque over the precession angle :math:`\psi` about :math:`\mathbf G` (uniformly: no
    resonance between :math:`\dot\psi` and the Euler--Poinsot frequency is assumed), over one period of the
    elliptic phase and, for ``nu=None`` (the orbit-averaged limit :math:`\varepsilon = 0`), over the orbit;
    then forms the averaged rates as in (6): :math:`d(G\mathbf n)/d\tau = \langle C\mathbf M\rangle`,
    :math:`dT/d\tau = \langle\boldsymbol\omega\cdot\mathbf M\rangle` and :math:`dk^2/d\tau` from the
    derivative of (5). Every mean is the trapezoid rule on a uniform grid (spectrally convergent for smooth
    torques; the node count of the elliptic phase comes from :math:`k`); node counts are doubled until the
    estimated error (from the grids of half and a quarter of the nodes, which the grid contains) is below
    ``tol`` times the size of the torque, or a node budget is spent. For torques with kinks or jumps
    (a shadow, ``max(0, cos)``) the convergence is algebraic and the estimate says so. The closed forms of
    the catalogue are *not* used here (:func:`averaged_rates` uses them).

    Parameters
    ----------
    body : Body
    torque : array_like, Drag, torque object or callable
        As in :func:`averaged_rates` (a drag tensor means :class:`LinearDrag` plus :class:`GravityGradient`).
    G, k2, delta, lam, nu
        Slow state, as in :func:`averaged_rates` (``k2`` in [0, 1)).
    kind : {'max', 'min'}
    sigma : {+1, -1}
        Sense of rotation of the Euler--Poinsot motion.
    orbit : Orbit, optional
    tol : float
        Relative tolerance of the quadrature (> 0; default 1e-13).

    Returns
    -------
    TorqueAverage
        ``rates`` (as :func:`averaged_rates`), ``error`` (estimated absolute errors of the rates), ``L``,
        ``dn``, ``nodes``, ``converged``, ``convergence``.

    See Also
    --------
    averaged_rates : the rates, from the closed forms where a torque has them.
    Torque : the protocol of the torque averaged.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, section 2 (the averaging over the Euler--Poinsot motion)
    and eq. (6).

    Examples
    --------
    >>> import numpy as np
    >>> from rigidbody import euler_poinsot as ep
    >>> body = ep.Body(3.2, 2.6, 1.67)
    >>> tq = ep.LinearDrag(np.diag([2.322, 1.31, 1.425]))
    >>> r = ep.average_torque(body, tq, 1.0, 0.9, 0.7, 0.2, None)
    >>> closed = ep.averaged_rates(body, tq, 1.0, 0.9, 0.7, 0.2, None)
    >>> bool(abs(r.rates["dk2"] - closed["dk2"]) < 1e-12), r.converged
    (True, True)
    """
    check_body(body)
    check_kind(kind)
    orb = as_orbit(orbit)
    sigma = check_sigma(sigma)
    tol = positive(tol, "tol")
    tq, _ = as_torque(torque, body, orb)
    tq.check_setup(body, orb)
    G, k2 = real(G, "G"), real(k2, "k2")
    if G <= 0:
        raise ValueError(f"G must be positive, got {G}")
    if not (0.0 <= k2 < 1.0):
        raise ValueError(f"k2 must lie in [0, 1) (k2 = 1 is the separatrix), got {k2}")
    delta, lam = real(delta, "delta"), real(lam, "lam")
    if nu is not None:
        nu = real(nu, "nu")
    Y = frame_y(delta, lam)
    st = State(body, kind, sigma, G, k2, Y[:, 2], nu, orb)
    mean, err, q = _once(tq, st, "numerical", tol)
    L, eL = Y.T @ mean.L, float(np.linalg.norm(err.L))
    sd = math.sin(delta)
    rates = {"dG": float(L[2]), "dT": mean.dT, "dk2": mean.dk2, "ddelta": float(L[0] / G),
             "dlam": float(L[1] / (G * sd)) if sd != 0.0 else math.copysign(math.inf, L[1])}
    error = {"dG": eL, "dT": err.dT, "dk2": err.dk2, "ddelta": eL / G, "dlam": eL / (G * abs(sd)) if sd else math.inf}
    dn = (mean.L - L[2] * Y[:, 2]) / G
    return TorqueAverage(rates, error, mean.L, dn, (q.grid.n_psi, q.grid.n_u(st.mc), q.grid.n_nu),
                         q.converged, q.convergence)


def precession_rate(body: Body, G: float, k2: float, delta: float, *, kind: str = "max",
                    orbit: Orbit | None = None, omega0: float = 1.0) -> float:
    r"""Orbit-averaged precession rate :math:`\dot\lambda = \tfrac{3\omega_0^2}{4G}(1-e^2)^{-3/2}N^*(k)\cos\delta`.

    The :math:`\varepsilon\to0` limit of the :math:`\lambda` equation of (6)/(9) (averaged over
    :math:`\nu`); in that limit :math:`\dot\delta = 0`.

    Parameters
    ----------
    body : Body
    G : float
        Magnitude of the angular momentum (> 0).
    k2 : float
        Modulus squared of the Euler--Poinsot motion (5), in :math:`[0, 1]`; enters through :math:`N^*`
        (:func:`~rigidbody.euler_poinsot.N_star`).
    delta : float
        Polar angle of :math:`\mathbf G` from the orbit normal :math:`x_3` (radians).
    kind : {'max', 'min'}
        Kind of Euler--Poinsot motion ('max' is the paper's).
    orbit : Orbit, optional
        Eccentric orbits give the factor :math:`(1-e^2)^{-3/2}` (default: the paper's circular orbit).
    omega0 : float
        Orbital mean motion (> 0). The default 1 gives :math:`d\lambda/d\tau` of the nondimensional form
        (9) (``G`` and the moments in the section-3 scaling); pass the dimensional :math:`\omega_0` (with
        dimensional ``G`` and moments) for :math:`d\lambda/dt` of (6).

    Returns
    -------
    float
        :math:`\dot\lambda` in rad per unit :math:`\tau` (``omega0=1``) or per unit :math:`t`.

    Raises
    ------
    TypeError
        If ``body`` is not a :class:`Body`, ``orbit`` is not an :class:`Orbit` or a number is not real.
    ValueError
        If ``kind`` is unknown, a number is not finite, ``G <= 0``, ``omega0 <= 0`` or ``k2`` is outside
        :math:`[0, 1]`.

    See Also
    --------
    N_star : the factor of the body's moments.
    averaged_rates : all the rates, at a given :math:`\nu` too.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, eqs. (6), (9).

    Examples
    --------
    The formula with :func:`N_star`, and the eccentric orbit's factor :math:`(1-e^2)^{-3/2}`
    (:math:`0.99^{-3/2} = 1.015190` for ``e = 0.1``):

    >>> import math
    >>> from rigidbody import euler_poinsot as ep
    >>> body = ep.Body(3.2, 2.6, 1.67)
    >>> rate = ep.precession_rate(body, 1.0, 0.5, 0.7)
    >>> print(f"{rate:.6f} {0.75 * ep.N_star(body, 0.5) * math.cos(0.7):.6f}")
    -0.727719 -0.727719
    >>> print(f"{ep.precession_rate(body, 1.0, 0.5, 0.7, orbit=ep.Orbit(0.1)) / rate:.6f}")
    1.015190
    """
    check_body(body)
    check_kind(kind)
    orb = as_orbit(orbit)
    G, k2, delta, omega0 = real(G, "G"), real(k2, "k2"), real(delta, "delta"), real(omega0, "omega0")
    if G <= 0:
        raise ValueError(f"G must be positive, got {G}")
    if not (0.0 <= k2 <= 1.0):
        raise ValueError(f"k2 must lie in [0, 1], got {k2}")
    if omega0 <= 0:
        raise ValueError(f"omega0 (orbital mean motion) must be positive, got {omega0}")
    return 0.75 * omega0**2 * orb.mean_factor * nstar_labelled(labelled(body, kind), k2) * math.cos(delta) / G
