r"""The averaged system (6)-(9) of Rachinskaya and its integrator.

Nondimensional form (section 3): :math:`\tilde G = G/G_0`, :math:`\tilde A_i = A_i\Omega_0/G_0`,
:math:`\varepsilon^2\tilde I = I/G_0`, the orbital rate is :math:`\varepsilon` in units of :math:`\Omega_0`,
slow time :math:`\tau = \varepsilon^2\tilde t` and true anomaly :math:`\nu = \tau/\varepsilon + \nu_0`.
In :math:`\tau` the system (9) is (6) with :math:`\omega_0 = 1` and :math:`I\to\tilde I`, so one set of
functions serves both forms: pass ``omega0`` and dimensional ``I`` for (6) in :math:`t`.

The closed forms of a drag tensor: coordinates, and what ``rtol`` means
-----------------------------------------------------------------------
With a drag tensor each segment of a run integrates (9) in :math:`(\ln G, \ln k^2, \delta, \lambda)` (plus
:math:`\nu` on an eccentric orbit; :math:`(\ln G, \ln k^2, \lambda)` in the orbit-averaged limit
:math:`\varepsilon = 0`, where :math:`\delta` is constant and :math:`\dot\lambda =
\tfrac34(1-e^2)^{-3/2}N^*\cos\delta_0/G`, :func:`precession_rate`) with the right-hand sides of
:mod:`._kernel`: ``rtol`` is the relative accuracy of :math:`G`, :math:`T`, :math:`k^2` however far they decay,
the angle equations (6) are regular at :math:`\sin\delta = 0` (the poles are fixed points of the
gravity-gradient average) and :math:`\lambda` is continuous by construction. DOP853 runs on Python floats
(``core.ode.integrate(engine='python')``) with the kernel's formulas folded into closures; its dense output is
computed for the steps that are sampled. A batch (array inputs, :mod:`._batch`) integrates the same equations
over members with :func:`rigidbody.core.batch.integrate_batch`.

Any torque
----------
With a torque object (``rigidbody.euler_poinsot.LinearDrag``, ..., or a plain function) the integrator evolves
:math:`(\ln G, \ln(k^2 + c), \mathbf n[, \nu])` (the direction of :math:`\mathbf G` as the angles
:math:`(\delta, \lambda)` or the unit vector :math:`\mathbf n`, see ``_integrate_kind``) with
:math:`d(G\mathbf n)/d\tau = \langle C\mathbf M\rangle` and the :math:`k^2` rate of :mod:`._engine` (DOP853 on
Python floats, as for a drag tensor: ``rtol`` is the relative accuracy of :math:`G` and :math:`k^2`, the direction
is held to ``rtol/10`` per step), the means from the closed forms of the torque's parts where they exist and from the
averaging engine otherwise (its grid chosen once, at the start). ``_integrate_kind`` integrates
one kind of motion from given :math:`(G, k^2, \mathbf n)`: a run that reaches the separatrix can be
restarted in the other kind with :math:`G`, :math:`T`, :math:`\mathbf n` continuous. With
:math:`\varepsilon > 0` the run checks the drift per Euler--Poinsot period (event) and the resonances
between the precession and the Euler--Poinsot frequency (predicted jumps, after the integration).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from typing import Any

import numpy as np
from scipy import special

from ..core import kernel as _kn
from ..core.ode import Event, Solution, integrate
from ..core.validate import RESULT_ERRORS, positive, real, span
from . import _kernel as _k
from ._engine import Averager, TorqueAverage, _Mean, _State, error_of, mean_of
from ._model import (
    K2_SPIN_CAP,
    Body,
    Orbit,
    _as_orbit,
    _check_body,
    _check_kind,
    _dk2,
    _drag_rates,
    _frame_y,
    _labels,
    _nstar,
    _nut_freq,
)
from ._protocol import Misfire
from ._resonance import resonance_crossings
from ._separatrix import K2_SWITCH, SeparatrixCrossing, _check_branch, _choose, _initial_kind, separatrix_crossing
from ._start import StartRules, check_start
from ._stops import stop_message
from ._torques import drag_as_torque, resolve

__all__ = ["average_torque", "averaged", "averaged_branches", "averaged_rates", "precession_rate"]


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
    """
    _check_body(body)
    _check_kind(kind)
    orb = _as_orbit(orbit)
    _check_method(method, "method")
    sigma = _check_sigma(sigma)
    what, tq = resolve(torque)
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
    if what == "drag" and method == "auto":
        return _rates_drag(body, tq, G, k2, delta, lam, nu, kind, orb, omega0)
    if what == "drag":
        tq = drag_as_torque(tq, body, orb, omega0)
    elif omega0 != 1.0:
        raise ValueError("omega0 applies to a drag tensor only: a torque object carries its own scale "
                         "(e.g. GravityGradient(body, orbit, omega0=...))")
    tq._check_setup(body, orb)
    if k2 >= 1.0:
        raise ValueError("k2 = 1 is the separatrix: the Euler-Poinsot period is infinite and a torque object "
                         "has no average there (the drag tensor's closed forms have a limit)")

    def L_y(d: float) -> np.ndarray:
        Y = _frame_y(d, lam)
        st = _State(body, kind, sigma, G, k2, Y[:, 2], nu, orb)
        return Y.T @ _once(tq, st, method)[0].L

    st = _State(body, kind, sigma, G, k2, _frame_y(delta, lam)[:, 2], nu, orb)
    mean, _, _ = _once(tq, st, method)
    L = _frame_y(delta, lam).T @ mean.L
    sd = math.sin(delta)
    if sd != 0.0:
        dlam = L[1] / (G * sd)
    elif abs(L[1]) > 1e-12 * max(1.0, float(np.abs(mean.L).max())):
        dlam = math.copysign(math.inf, L[1])
    else:  # the limit L2(delta)/sin(delta) along the meridian: a central difference, error O(h^2)
        h = 1e-5
        dlam = (L_y(h)[1] - L_y(-h)[1]) / (2.0 * math.sin(h) * G)
    return {"dG": float(L[2]), "dT": mean.dT, "dk2": mean.dk2, "ddelta": float(L[0] / G), "dlam": float(dlam)}


#: quadrature tolerance of the engine (relative to the size of the torque on the grid)
_TOL = 1e-13


def _once(tq: Any, st: _State, method: str, tol: float = _TOL) -> tuple[_Mean, _Mean, Any]:
    """Averages at one state with their error bound: closed forms where allowed, adaptive engine otherwise."""
    av = Averager(tq, method, tol)
    av.calibrate(st)
    total = _Mean(np.zeros(3), 0.0, 0.0)
    for p in av.closed:
        total = total + p._closed(st)
    err = _Mean(np.zeros(3), 0.0, 0.0)
    if av.first is not None:
        total = total + mean_of(av.first.mean, st)
        err = error_of(av.first.error, st)
    return total, err, av.first


def _check_method(method: Any, name: str) -> None:
    if method not in ("auto", "numerical"):
        raise ValueError(f"{name} must be 'auto' (closed forms where a torque has them) or 'numerical' (the "
                         f"averaging engine for every part), got {method!r}")


def _check_sigma(sigma: Any) -> int:
    if isinstance(sigma, bool) or sigma not in (1, -1):
        raise ValueError(f"sigma (sense of rotation) must be +1 or -1, got {sigma!r}")
    return int(sigma)


def _rates_drag(body: Body, drag: Any, G: float, k2: float, delta: float, lam: float, nu: float | None,
                kind: str, orb: Orbit, omega0: float) -> dict[str, float]:
    """The closed forms (6) for a drag tensor (drag plus gravity gradient)."""
    A, Id = _labels(body, kind, drag.diag)
    dG, dT = _drag_rates(A, Id, G, k2)
    dk2 = _dk2(A, Id, k2)
    Ns = _nstar(A, k2)
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
    _check_body(body)
    _check_kind(kind)
    orb = _as_orbit(orbit)
    sigma = _check_sigma(sigma)
    tol = positive(tol, "tol")
    what, tq = resolve(torque)
    if what == "drag":
        tq = drag_as_torque(tq, body, orb)
    tq._check_setup(body, orb)
    G, k2 = real(G, "G"), real(k2, "k2")
    if G <= 0:
        raise ValueError(f"G must be positive, got {G}")
    if not (0.0 <= k2 < 1.0):
        raise ValueError(f"k2 must lie in [0, 1) (k2 = 1 is the separatrix), got {k2}")
    delta, lam = real(delta, "delta"), real(lam, "lam")
    if nu is not None:
        nu = real(nu, "nu")
    Y = _frame_y(delta, lam)
    st = _State(body, kind, sigma, G, k2, Y[:, 2], nu, orb)
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
    """
    _check_body(body)
    _check_kind(kind)
    orb = _as_orbit(orbit)
    G, k2, delta, omega0 = real(G, "G"), real(k2, "k2"), real(delta, "delta"), real(omega0, "omega0")
    if G <= 0:
        raise ValueError(f"G must be positive, got {G}")
    if not (0.0 <= k2 <= 1.0):
        raise ValueError(f"k2 must lie in [0, 1], got {k2}")
    if omega0 <= 0:
        raise ValueError(f"omega0 (orbital mean motion) must be positive, got {omega0}")
    return 0.75 * omega0**2 * orb.mean_factor * _nstar(_labels(body, kind), k2) * math.cos(delta) / G


def _unit(delta: float, lam: float) -> tuple[float, float, float]:
    return (math.sin(delta) * math.cos(lam), math.sin(delta) * math.sin(lam), math.cos(delta))


def _lam_unwrapped(tau_fine: np.ndarray, n_fine: np.ndarray, lam0: float) -> np.ndarray:
    lam = np.unwrap(np.arctan2(n_fine[1], n_fine[0]))
    # choose the branch of the initial value given by the user
    return lam + 2.0 * math.pi * round((lam0 - lam[0]) / (2.0 * math.pi))


def _finish(
    res: Solution,
    tau_eval: Any,
    make_fields: Any,
    lam0: float,
    nvec: Any,
    lam_direct: Any = None,
) -> Solution:
    """Evaluate on tau_eval (through dense output) and unwrap lambda along the solver's own steps.

    ``lam_direct(tau, y)``, when given, returns the continuous lambda at the output times (from the state itself).
    """
    tau_steps = res.time
    y_steps = res.y
    if lam_direct is not None:
        if tau_eval is None:
            tau_out, y_out = tau_steps, y_steps
        else:
            te = np.asarray(tau_eval, dtype=float)
            tau_out = te[(te >= tau_steps[0]) & (te <= tau_steps[-1])] if tau_steps.size else te[:0]
            y_out = res.sol(tau_out) if tau_out.size else np.empty((y_steps.shape[0], 0))
        lam = lam_direct(tau_out, y_out)
    elif tau_eval is None:
        tau_out, y_out = tau_steps, y_steps
        lam = _lam_unwrapped(tau_steps, nvec(y_steps), lam0)
    else:
        te = np.asarray(tau_eval, dtype=float)
        te = te[(te >= tau_steps[0]) & (te <= tau_steps[-1])] if tau_steps.size else te[:0]
        if te.size:
            y_out = res.sol(te)
            tt = np.concatenate([tau_steps, te])
            order = np.argsort(tt, kind="stable")
            yy = np.concatenate([y_steps, y_out], axis=1)[:, order]
            lam_all = _lam_unwrapped(tt[order], nvec(yy), lam0)
            pos = np.empty_like(order)
            pos[order] = np.arange(order.size)
            lam = lam_all[pos[tau_steps.size:]]
        else:
            y_out = np.empty((y_steps.shape[0], 0))
            lam = np.empty(0)
        tau_out = te
    data = make_fields(tau_out, y_out)
    data["lam"] = lam
    return Solution(res.time_name, tau_out, y_out, data, res.status, res.message, res.event,
                    res.t_events, res.y_events, res.sol, res.nfev)


def _check_tau_eval(tau_eval: Any, tau_span: Any) -> None:
    """tau_eval must be finite, sorted and inside tau_span (points beyond an early stop are dropped)."""
    if tau_eval is None:
        return
    try:
        te = np.asarray(tau_eval, dtype=float).ravel()
    except (TypeError, ValueError):
        raise TypeError(f"tau_eval must be an array of real numbers, got {tau_eval!r}") from None
    a, b = span(tau_span, "tau_span")
    if not np.all(np.isfinite(te)):
        raise ValueError("tau_eval must be finite")
    if np.any(np.diff(te) < 0):
        raise ValueError("tau_eval must be sorted (increasing)")
    if te.size and (te[0] < a or te[-1] > b):
        raise ValueError(f"tau_eval must lie within tau_span = {tuple(tau_span)!r}, got [{te[0]}, {te[-1]}]")


def _check_tol(rtol: Any, atol: Any) -> None:
    positive(rtol, "rtol")
    if real(atol, "atol") < 0:
        raise ValueError(f"atol must be >= 0, got {atol}")


def averaged(
    body: Body,
    torque: Any,
    eps: Any,
    G0: Any = 1.0,
    k2_0: Any = None,
    delta0: Any = math.pi / 4,
    lam0: Any = math.pi / 4,
    tau_span: tuple[float, float] = (0.0, 3.0),
    tau_eval: Any = None,
    nu0: Any = 0.0,
    *,
    kind: str | None = None,
    T0: Any = None,
    orbit: Orbit | None = None,
    rtol: float = 1e-10,
    atol: float = 1e-12,
    method: str = "DOP853",
    k2_max: float | None = 1.0 - 1e-6,
    min_spin_ratio: float = 1.0,
    sigma: int = 1,
    averaging: str = "auto",
    quad_tol: float = 1e-12,
    drift_tol: float | None = 0.5,
    resonance_tol: float | None = 0.05,
    branch: Any = "likely",
    seed: Any = None,
) -> Solution:
    r"""Integrate the nondimensional averaged system (9) in the slow time :math:`\tau = \varepsilon^2\tilde t`.

    Parameters
    ----------
    body : Body
        Nondimensional moments :math:`\tilde A_i`.
    torque : array_like, Drag, torque object or callable
        A nondimensional drag tensor :math:`\tilde I` (3x3, its diagonal or a :class:`Drag`; only the
        diagonal enters (9)): Rachinskaya's drag *plus* the gravity-gradient torque, integrated with the
        closed forms (9); an array of shape ``batch_shape + (3, 3)`` gives each member of a batch its own
        tensor. A torque object (:class:`LinearDrag`, :class:`GravityGradient`, ... and sums) or a
        plain callable ``torque(omega, C, nu) -> M`` is the whole perturbation: the averaged system is then
        :math:`d(G\mathbf n)/d\tau = \langle C\mathbf M\rangle`, :math:`dT/d\tau = \langle\boldsymbol\omega
        \cdot\mathbf M\rangle` with the means from the closed forms of the parts that have them and from the
        averaging engine otherwise (see :func:`average_torque` and ``docs/euler_poinsot.md``, "Any torque").
    eps : float or array_like
        :math:`\varepsilon`, the orbital rate in units of :math:`\Omega_0`; the true anomaly is
        :math:`\nu = \tau/\varepsilon + \nu_0` (Kepler's law for an eccentric ``orbit``). ``eps = 0`` gives
        the orbit-averaged limit (the gravity terms averaged over :math:`\nu`).
    G0, k2_0, delta0, lam0 : float or array_like
        Initial :math:`\tilde G`, :math:`k^2` (in [0, 1); default 0.99), :math:`\delta`, :math:`\lambda`
        (radians).
    tau_span : (float, float)
    tau_eval : array_like, optional
        Output times (default: the solver's steps; for a batch 101 times over ``tau_span``).
    nu0 : float or array_like
        Initial true anomaly.
    kind : {'max', 'min'}
        Initial kind of Euler--Poinsot motion ('max': about the axis of :math:`A_1`, the paper's case;
        the default).
    T0 : float or array_like, optional
        The initial kinetic energy instead of ``k2_0`` and ``kind``: any :math:`T_0` in
        :math:`[G_0^2/(2A_1), G_0^2/(2A_3)]` off the separatrix (the kind follows from :func:`kind_of`).
    orbit : Orbit, optional
        Default circular.
    rtol, atol, method
        With a drag tensor ``rtol`` is the relative accuracy of :math:`G`, :math:`T` and :math:`k^2` however far
        they decay (the closed forms are integrated in :math:`\ln G`, :math:`\ln k^2` with absolute control
        ``rtol``) and the angles are held to ``rtol/10`` radians per step (:math:`\lambda` relatively beyond a
        radian); ``atol`` is then not used. With a torque object the state is :math:`(\ln G, \ln k^2, \mathbf n)`
        with the same meaning of ``rtol`` for :math:`G`, :math:`T`, :math:`k^2`, and the unit vector :math:`\mathbf n`
        of :math:`\mathbf G` held to ``rtol/10`` per step; ``atol`` is not used either.
        ``method``: ``'DOP853'`` (default; run on Python floats) or another
        :func:`scipy.integrate.solve_ivp` method (one run only: a batch uses DOP853).
    k2_max : float or None
        The run ends (status 1, event ``'separatrix'``) when :math:`k^2` reaches this value (default
        :math:`1 - 10^{-6}`: at :math:`k^2 = 1` the period of the Euler--Poinsot motion is infinite). ``None``:
        the evolution goes on through the separatrix into the other kind of motion (see ``branch``), with
        :math:`G`, :math:`T` and :math:`\mathbf n` continuous; the averaged rates have finite limits there
        (:func:`separatrix_limits`).
    min_spin_ratio : float
        The run ends (event ``'slow_rotation'``) when the rotation is no longer fast: when
        :func:`spin_ratio` (frequency :math:`2\pi/P` of the Euler--Poinsot motion over the orbital rate
        :math:`\varepsilon`) falls to this value (``eps > 0`` only; a start below it raises ``ValueError``;
        pass 0 to switch the check off, e.g. to show where the theory fails). In a run through the separatrix
        (``k2_max=None``) the ratio is taken at :math:`\min(k^2, 0.99)`: the momentary infinite period of the
        crossing itself does not end it.
    sigma : {+1, -1}
        Sense of rotation of the Euler--Poinsot motion (torque objects; the drag tensor's averages do not
        depend on it).
    averaging : {'auto', 'numerical'}
        For a torque object (or, with ``'numerical'``, a drag tensor): ``'numerical'`` uses the averaging
        engine for every part, also where a closed form exists (for checks and benchmarks).
    quad_tol : float
        Relative tolerance of the engine's quadrature, to which its grid is chosen at the start.
        ``sol.quad_error`` reports the estimated error of the averages at the first and last states.
    drift_tol : float or None
        Torque objects, ``eps > 0``: the run ends (event ``'fast_drift'``) when the slow variables change
        by more than this fraction in one Euler--Poinsot period,
        :math:`\varepsilon^2P(|\dot G|/G + |\dot T|/T + |\dot{\mathbf n}|)`: then there is no separation of
        time scales and the averaging does not hold. ``None`` switches the check off.
    resonance_tol : float or None
        Torque objects, ``eps > 0``: where the rotation number :math:`\rho = \langle\dot\psi\rangle P/2\pi`
        crosses a resonance :math:`j\rho = -m` (:math:`j = 1, 2`) the averaging over :math:`\psi` and the
        phase does not hold; the passage changes the slow variables by the jump
        :math:`2|c_{jm}|\varepsilon\sqrt{P/|j\dot\rho|}` (:math:`c_{jm}` the resonant harmonic of the
        torque's effect), which is computed and listed in ``sol.resonances``. A jump larger than this
        (relative to :math:`G`, :math:`T`; radians for the direction) ends the run there (event
        ``'resonance'``): the passage is too slow (a capture into resonance is possible). ``None`` switches
        the check off.
    branch : 'likely', 'random', (str, int) or sequence of them
        Where the motion goes at a separatrix crossing: beyond the separatrix there are motions of either
        kind and sense, ``(kind, sigma)``, and which one the body enters depends on the fast phase at the
        crossing; :func:`separatrix_crossing` gives their capture probabilities. ``'likely'`` (default)
        continues in the most probable one (ties: ``sigma = +1``, then ``'max'``), ``'random'`` draws it
        (``seed``), a region ``('max', -1)`` forces it, a list of regions forces one per crossing (then
        ``'likely'``). A forced region of probability 0 (its drift points back to the separatrix) ends the
        run there with status 1, event ``'separatrix'``; so does a separatrix that no region leaves (it
        attracts from all sides). :func:`averaged_branches` runs every branch of the first crossing.
    seed : int or numpy.random.Generator, optional
        Random source for ``branch='random'``.

    Returns
    -------
    Solution
        ``sol.tau``, ``sol.G``, ``sol.T``, ``sol.k2``, ``sol.delta`` (in [0, pi]), ``sol.lam`` (continuous,
        unwrapped), ``sol.nu`` (the true anomaly; constant ``nu0`` when ``eps = 0``, where it is averaged
        out), ``sol.n`` (unit vector of G in :math:`Ox_i`, shape (3, n)), ``sol.kind`` and ``sol.sigma``
        (the kind of motion and its sense at every output time; ``k2`` is the modulus of that kind),
        ``sol.status`` (0 end reached, 1 an event ended the run, -1 failure: e.g. a torque that turns non-finite
        part-way, named in the message with the time), ``sol.message`` (for an event: what ended the run and the
        option that relaxes it), ``sol.event``
        (``'separatrix'``, ``'slow_rotation'`` or None; with a torque object also ``'fast_drift'`` and
        ``'resonance'``). ``sol.t_events['separatrix']`` holds the times of the separatrix crossings and
        ``sol.crossings`` one dict per crossing: ``tau``, ``source`` and ``region`` (the regions
        ``(kind, sigma)`` before and after), ``probabilities`` (capture probability of each region) and
        ``drifts`` (see :class:`SeparatrixCrossing`). A run that crossed the separatrix has as raw state
        ``sol.y`` the rows ``G, k2, n1, n2, n3`` (and a piecewise dense output ``sol.sol``).
        With a torque object the result also has ``sol.quad_error`` (the estimated quadrature error of the
        engine's averages on the run's grid: the largest of those of the mean torque
        :math:`\langle C\mathbf M\rangle`, of :math:`dT/d\tau` times :math:`G/T` and of :math:`dk^2/d\tau`
        times :math:`G`, relative to the size of the averaged torque, at the first and the last state of each
        segment; 0 when only closed forms are used),
        ``sol.resonances`` (the resonance crossings with their predicted jumps: dicts with
        ``tau``, ``j``, ``m``, ``rho``, ``jump``, ``jump_G``, ``jump_T``, ``jump_n``, ``bound``: True where the
        jumps are upper bounds, for high orders shown harmless without computing their coefficient), ``sol.kind``
        and ``sol.sigma``.

        For a batch every field has shape ``batch_shape + (len(tau_eval),)`` (``n``: ``batch_shape + (3, n_t)``),
        NaN after a member's end; ``status``, ``message``, ``event`` and ``crossings`` are per member; ``sol[i]``
        is member ``i`` as a single-run result.

    Notes
    -----
    *Batches.* Arrays for ``eps``, ``G0``, ``k2_0`` (or ``T0``), ``delta0``, ``lam0``, ``nu0`` (and a batch of
    drag tensors) broadcast to one batch shape; the body, the orbit, ``tau_span``, ``kind``, ``sigma`` and the
    options are shared. With a drag tensor the members are integrated together
    (:func:`rigidbody.core.batch.integrate_batch`, the closed forms vectorised over members, per-member step
    control and events), round by round: a member that reaches the separatrix in a run through it
    (``k2_max=None``) crosses as its single run does and continues in the next round in the other kind of
    motion. A member whose start the single call refuses gets ``status = -1`` and that call's message; the
    others go on. A torque object made of :class:`LinearDrag` parts and the :class:`GravityGradient` of the run
    (the drag tensor's meaning) runs the same vectorised closed forms; any other torque object (or
    ``averaging='numerical'``) runs its members one by one through the single call (the engine's quadrature
    adapts to each state). Every member equals its single call within
    the tolerance; with ``branch='random'`` the members draw from one generator seeded by ``seed``.

    Examples
    --------
    >>> import numpy as np
    >>> from rigidbody import euler_poinsot as ep
    >>> body = ep.Body(3.2, 2.6, 1.67)
    >>> sol = ep.averaged(body, np.diag([2.322, 1.31, 1.425]), 0.0, tau_span=(0, 3), tau_eval=[0, 3])
    >>> bool(sol.G[-1] < sol.G[0]), sol.status
    (True, 0)
    """
    from . import _batch

    if _batch.is_batch(eps, G0, k2_0, delta0, lam0, nu0, T0) or _batch.drag_batch(torque) is not None:
        opts = dict(kind=kind, T0=T0, orbit=orbit, rtol=rtol, atol=atol, method=method, k2_max=k2_max,
                    min_spin_ratio=min_spin_ratio, sigma=sigma, averaging=averaging, quad_tol=quad_tol,
                    drift_tol=drift_tol, resonance_tol=resonance_tol, branch=branch, seed=seed)
        return _batch.averaged_batch(body, torque, eps, G0, k2_0, delta0, lam0, tau_span, tau_eval, nu0, opts,
                                     averaged)
    _check_body(body)
    k2_0, kind = _initial_kind(body, real(G0, "G0"), k2_0, kind, T0)
    span(tau_span, "tau_span")
    _check_tau_eval(tau_eval, tau_span)
    _check_tol(rtol, atol)
    orb = _as_orbit(orbit)
    _check_method(averaging, "averaging")
    sigma = _check_sigma(sigma)
    quad_tol = positive(quad_tol, "quad_tol")
    drift_tol = None if drift_tol is None else positive(drift_tol, "drift_tol")
    resonance_tol = None if resonance_tol is None else positive(resonance_tol, "resonance_tol")
    branch = _check_branch(branch)
    what, tq = resolve(torque)
    through = k2_max is None
    k2_stop = K2_SWITCH if through else real(k2_max, "k2_max")
    min_spin_ratio = real(min_spin_ratio, "min_spin_ratio")
    rules = StartRules(body, None if through else k2_stop, min_spin_ratio)
    eps, G0, k2_0, delta0, lam0, nu0 = check_start(rules, kind, eps, G0, k2_0, delta0, lam0, nu0)
    region0 = (kind, sigma)
    gen = _Generic(torque=tq if what == "torque" else drag_as_torque(tq, body, orb), averaging=averaging,
                   quad_tol=quad_tol, body=body, eps=eps, orbit=orb, nu0=nu0, rtol=rtol, atol=atol, method=method,
                   min_spin_ratio=min_spin_ratio, drift_tol=drift_tol, resonance_tol=resonance_tol)
    if what == "drag" and averaging != "numerical":
        gen.drag = tq  # the closed forms (9) of the paper; the torque object serves the crossings
    else:
        gen.torque._check_setup(body, orb)
    gen.spin_cap = K2_SPIN_CAP if through else 1.0
    # the true anomaly at the start: nu = tau/eps + nu0 on a circular orbit (as the drag tensor's closed forms and
    # simulate take it, also when tau_span starts after 0); on an eccentric orbit nu is a state starting at nu0
    nu_start = nu0 + float(tau_span[0]) / eps if eps > 0.0 and orb.e == 0.0 else nu0
    first = gen.piece(region0, tau_span, G0, k2_0, np.array(_unit(delta0, lam0)), nu_start, lam0, k2_stop)
    rng = np.random.default_rng(seed) if branch == "random" else None  # the only branch rule that draws
    return _through(first, gen, tau_span, tau_eval, through, branch, rng)


# --------------------------------------------------------------------------------------------------
# any torque: the averaged evolution of one kind of motion (restartable in the other kind)
# --------------------------------------------------------------------------------------------------
@dataclass(kw_only=True)
class _RunOptions:
    """The options of :func:`averaged` that every segment of a run shares."""

    body: Body
    eps: float
    orbit: Orbit
    nu0: float
    rtol: float
    atol: float
    method: str
    min_spin_ratio: float
    drift_tol: float | None
    resonance_tol: float | None

    def options(self) -> dict[str, Any]:
        return {f.name: getattr(self, f.name) for f in fields(_RunOptions)}


@dataclass(kw_only=True)
class _Setup(_RunOptions):
    """What a run with a torque object keeps fixed: the options, the averaged torque, where it stops."""

    averager: Averager
    k2_max: float
    spin_cap: float = K2_SPIN_CAP


@dataclass
class _Segment:
    """An averaged run in one kind of motion: its solution (rows G, k2, n[, nu] of the integrated state, and a dense
    output of the same rows) and how it was made."""

    res: Solution
    setup: _Setup
    kind: str
    sigma: int
    tau0: float
    nu0: float
    charts: list[_Chart]

    def lam(self, tau: np.ndarray) -> np.ndarray:
        """The continuous lambda at sorted times within the segment, from the chart pieces."""
        starts = np.array([p.raw.time[0] for p in self.charts])
        idx = np.clip(np.searchsorted(starts, tau, side="right") - 1, 0, len(self.charts) - 1)
        out = np.empty(tau.shape)
        for i in np.unique(idx).tolist():
            sel = idx == i
            out[sel] = self.charts[i].lam(tau[sel])
        return out


def _state_of(setup: _Setup, kind: str, sigma: int, tau: float, y: np.ndarray, tau0: float, nu0: float) -> _State:
    eps = setup.eps
    k2 = min(max(float(y[1]), 0.0), 1.0 - 1e-15)
    n = np.asarray(y[2:5], dtype=float)
    if eps == 0.0:
        nu = None
    elif setup.orbit.e == 0.0:
        nu = (tau - tau0) / eps + nu0
    else:
        nu = float(y[5])
    return _State(setup.body, kind, sigma, float(y[0]), k2, n / math.sqrt(float(n @ n)), nu, setup.orbit)


def _slow_drift(setup: _Setup, st: _State, m: _Mean) -> float:
    r"""Relative change of the slow variables in one Euler--Poinsot period, :math:`\varepsilon^2P(\ldots)`."""
    freq = _nut_freq(st.a, st.G, min(st.k2, setup.spin_cap))  # next to the separatrix: see K2_SPIN_CAP
    if freq <= 0.0:
        return math.inf
    dG = float(st.n @ m.L)
    dn = float(np.linalg.norm(m.L - dG * st.n)) / st.G
    return setup.eps**2 * (2.0 * math.pi / freq) * (abs(dG) / st.G + abs(m.dT) / st.T + dn)


#: chart switches of the direction of G (torque objects): the polar angles (delta, lambda) about x3 while
#: sin(delta) >= _SIN_OFF, the unit vector n near the poles (where lambda is undefined) until sin(delta) > _SIN_ON
_SIN_OFF, _SIN_ON = 0.1, 0.2
#: a run whose direction changes chart more often than this ends with a status (it hovers at a chart boundary)
_MAX_CHARTS = 10_000


def _tolerances(rtol: float, chart: str, ecc: bool) -> tuple[list[float], list[float]]:
    """Per-component ``(rtol, atol)`` of a chart's state: ``ln G`` and ``ln k^2`` absolutely to ``rtol`` (a relative
    error of G and k^2 however far they decay); the angles, or the components of the unit vector n (an error of n
    is an angle), absolutely to ``ANGLE_FACTOR * rtol``, lambda and nu also relatively to ``rtol`` (beyond a radian)
    -- the tolerances of a drag-tensor run (:func:`._kernel.tolerances`)."""
    r, a = float(rtol), _k.ANGLE_FACTOR * float(rtol)
    if chart == "angles":  # ln G, ln k2, delta, lambda[, nu]
        rt, at = [_k.RTOL_FLOOR, _k.RTOL_FLOOR, _k.RTOL_FLOOR, r], [r, r, a, a]
    else:  # ln G, ln k2, n1, n2, n3[, nu]
        rt, at = [_k.RTOL_FLOOR] * 5, [r, r, a, a, a]
    if ecc:
        rt.append(r)
        at.append(a)
    return rt, at


@dataclass
class _Chart:
    """One piece of a segment integrated in one chart of the direction of G: ``'angles'`` (state ln G, ln k2,
    delta, lambda[, nu]) or ``'vector'`` (ln G, ln k2, n1, n2, n3[, nu]); ``lam_start`` is the continuous lambda
    at its start."""

    chart: str
    raw: Solution
    z: float
    c: float
    ecc: bool
    lam_start: float

    @property
    def n_common(self) -> int:
        return 6 if self.ecc else 5

    def common(self, y: Any) -> np.ndarray:
        """Rows G, k2, n (unit)[, nu] of raw states (columns, or one state)."""
        y = np.asarray(y, dtype=float)
        if self.chart == "angles":
            sd = np.sin(y[2])
            n = [sd * np.cos(y[3]), sd * np.sin(y[3]), np.cos(y[2])]
            rest = [y[4]] if self.ecc else []
        else:
            n = list(y[2:5] / np.sqrt((y[2:5] ** 2).sum(axis=0)))
            rest = [y[5]] if self.ecc else []
        return np.array([np.exp(y[0]), np.clip(self.z * np.exp(y[1]) - self.c, 0.0, 1.0), *n, *rest])

    def lam(self, tau: np.ndarray) -> np.ndarray:
        """The continuous lambda at sorted times within the piece: a state of the angle chart; in the vector chart
        unwrapped from n along the solver's steps and the times asked for, from ``lam_start``."""
        raw = self.raw
        if tau.size == 0:
            return np.empty(0)
        if self.chart == "angles":
            return np.asarray(raw.sol(tau), dtype=float)[3].reshape(tau.shape)
        steps = raw.time
        tt = np.concatenate([steps, tau])
        order = np.argsort(tt, kind="stable")
        yy = np.concatenate([raw.y, np.asarray(raw.sol(tau), dtype=float).reshape(raw.y.shape[0], -1)], axis=1)
        lam_all = _lam_unwrapped(tt[order], yy[2:5][:, order], self.lam_start)
        pos = np.empty_like(order)
        pos[order] = np.arange(order.size)
        return lam_all[pos[steps.size:]]

    def lam_end(self) -> float:
        return float(self.lam(self.raw.time[-1:])[0])


#: a slow state and its means in a torque object's right-hand side: G, k2, n1, n2, n3, nu, L1, L2, L3, dT, dk2
_Slow = tuple[float, float, float, float, float, Any, float, float, float, float, float]


def _k2_floor(rtol: float) -> float:
    """The c of the engine's coordinate ln(k2 + c): where the rounding of its dk2, ~10 eps_mach k (measured: 2e-12
    relative at k2 = 1e-8), is rtol of dk2 ~ k^2 relative, (10 eps_mach / (2 rtol))^2 (1.2e-10 at rtol 1e-10); the
    largest noise of d ln(k2 + c)/dtau, at k2 = c, is then about rtol."""
    return (10.0 * _k.RTOL_FLOOR / 100.0 / (2.0 * rtol)) ** 2


def _axisymmetric(av: Averager, st: _State, tol: float = 1e-9) -> bool:
    """Whether the averaged torque is symmetric about the orbit normal x3 (turning G about x3 turns its mean
    torque alike and leaves dT, dk2 unchanged), probed at the state and at a generic direction, two angles each."""
    sd = math.sin(1.1)
    for n in (st.n, np.array([sd * math.cos(0.7), sd * math.sin(0.7), math.cos(1.1)])):
        m0 = av.mean(_State(st.body, st.kind, st.sigma, st.G, st.k2, n, st.nu, st.orbit))
        size = float(np.abs(m0.L).max()) + abs(m0.dT) + abs(m0.dk2) + 1e-300
        for alpha in (1.0, 2.5):
            c, s = math.cos(alpha), math.sin(alpha)
            R = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
            m = av.mean(_State(st.body, st.kind, st.sigma, st.G, st.k2, R @ n, st.nu, st.orbit))
            if (float(np.abs(m.L - R @ m0.L).max()) > tol * size or abs(m.dT - m0.dT) > tol * size
                    or abs(m.dk2 - m0.dk2) > tol * size):
                return False
    return True


def _integrate_kind(setup: _Setup, kind: str, sigma: int, tau_span: Any, G0: float, k2_0: float,
                    n0: Any, nu0: float, lam0: float, first_step: float | None = None) -> _Segment:
    """Integrate the averaged system of a torque object in one kind of motion from (G0, k2_0, n0) at the
    start of ``tau_span`` (true anomaly ``nu0`` there, continuous lambda ``lam0``). A crossing into the other kind
    restarts here with G, T, n continuous (k2 from (5) of the other kind).

    As for a drag tensor (:mod:`._kernel`) the state is ``(ln G, ln k^2, delta, lambda[, nu])`` (``nu`` on an
    eccentric orbit with eps > 0): ``rtol`` is the relative accuracy of G and k^2 however far they decay, and
    lambda, a state, is continuous through any number of turns. ``d ln k^2/dtau = (dk^2/dtau)/k^2`` is finite as
    k -> 0 (the engine's dk^2 is O(k^2) there, without cancellation); a start at k^2 = 0 exactly stays there (an
    equilibrium of every averaged system: the phase-dependent part of the motion vanishes), carried by the factor
    z = 0. The polar angles are singular at the poles sin(delta) = 0, where a torque may turn G (the drag tensor's
    gravity gradient does not): there (sin(delta) < _SIN_OFF, until it exceeds _SIN_ON) the direction is the unit
    vector n instead. With ``method='DOP853'`` DOP853 runs on Python floats (``engine='python'``), its dense output
    computed lazily."""
    tau0, t1 = float(tau_span[0]), float(tau_span[1])
    eps, orb, body = setup.eps, setup.orbit, setup.body
    ecc = eps > 0.0 and orb.e != 0.0
    av = setup.averager
    nn = np.asarray(n0, dtype=float)
    nn = nn / math.sqrt(float(nn @ nn))
    st0 = _State(body, kind, sigma, G0, min(k2_0, 1.0 - 1e-15), nn, None if eps == 0.0 else nu0, orb)
    av.calibrate(st0)
    # k2 enters as s = ln(k2 + c): c = 0 with closed forms only (a start at k2 = 0 exactly then keeps z = 0); with the
    # engine, whose dk2 carries rounding ~eps_mach k (zero-mean O(k) products, see _engine) against a size O(k^2),
    # c = _k2_floor(rtol): the relative accuracy rtol of k2 down to where the engine has it, absolute below
    c = 0.0 if av.rest is None else _k2_floor(setup.rtol)
    z = 1.0 if k2_0 > 0.0 or c > 0.0 else 0.0
    a = _labels(body, kind)
    exp, sqrt, sin, cos = math.exp, math.sqrt, math.sin, math.cos
    ie = 1.0 / eps if eps > 0.0 else 0.0
    k2_top = 1.0 - 1e-15
    inu = 4  # index of nu in the angle chart's state (5 in the vector chart's)

    def nu_of(tau: float, y: Any, i: int) -> float | None:
        if eps == 0.0:
            return None
        if ecc:
            return float(y[i])
        return (tau - tau0) * ie + nu0

    fast = av.fast(kind, sigma, eps > 0.0)  # the engine alone on floats, or None (closed forms: state objects)
    memo: list[Any] = [None, None, None, None]  # the last (chart, tau, y, means): the drift event reuses them
    misfire = Misfire()  # a torque that misbehaves part-way ends the run with a status naming it

    def mean_at(tau: float, y: Any, chart: str) -> _Slow:
        """(G, k2, n1, n2, n3, nu, L1, L2, L3, dT, dk2) at a state of the chart."""
        yl = y if isinstance(y, list) else list(y)
        if memo[1] == tau and memo[0] == chart and memo[2] == yl:
            return memo[3]  # the cached tuple
        G = exp(yl[0])
        k2 = z * exp(yl[1]) - c
        k2 = (k2 if k2 < k2_top else k2_top) if k2 > 0.0 else 0.0
        if chart == "angles":
            sd = sin(yl[2])
            n1, n2, n3 = sd * cos(yl[3]), sd * sin(yl[3]), cos(yl[2])
            nu = nu_of(tau, yl, inu)
        else:
            r = sqrt(yl[2] * yl[2] + yl[3] * yl[3] + yl[4] * yl[4])
            n1, n2, n3 = yl[2] / r, yl[3] / r, yl[4] / r
            nu = nu_of(tau, yl, inu + 1)
        try:
            if fast is not None:
                L1, L2, L3, dT, dk2 = fast(G, k2, n1, n2, n3, nu)
            else:
                m = av.mean(_State(body, kind, sigma, G, k2, np.array([n1, n2, n3]), nu, orb))
                L1, L2, L3 = (float(v) for v in m.L)
                dT, dk2 = m.dT, m.dk2
        except RESULT_ERRORS as exc:  # NaN rates: the step fails here, the run ends with misfire's message
            misfire.note(tau, exc)
            L1 = L2 = L3 = dT = dk2 = math.nan
        out = (G, k2, n1, n2, n3, nu, L1, L2, L3, dT, dk2)
        memo[0], memo[1], memo[2], memo[3] = chart, tau, list(yl), out
        return out

    def pair(tau: float, y: Any, chart: str) -> tuple[_State, _Mean]:
        G, k2, n1, n2, n3, nu, L1, L2, L3, dT, dk2 = mean_at(tau, y, chart)
        return (_State(body, kind, sigma, G, k2, np.array([n1, n2, n3]), nu, orb),
                _Mean(np.array([L1, L2, L3]), dT, dk2))

    def rhs_angles(tau: float, y: Any) -> list[float]:
        G, k2, _, _, _, _, L1, L2, L3, _, dk2 = mean_at(tau, y, "angles")
        d, la = y[2], y[3]
        sd, cd, sl, cl = sin(d), cos(d), sin(la), cos(la)
        iG = 1.0 / G
        out = [(sd * (cl * L1 + sl * L2) + cd * L3) * iG, dk2 / (k2 + c) if z else 0.0,
               (cd * (cl * L1 + sl * L2) - sd * L3) * iG, (cl * L2 - sl * L1) * iG / sd]
        if ecc:
            out.append(orb.nu_rate(float(y[inu])) * ie)
        return out

    def rhs_vector(tau: float, y: Any) -> list[float]:
        G, k2, n1, n2, n3, _, L1, L2, L3, _, dk2 = mean_at(tau, y, "vector")
        dG = n1 * L1 + n2 * L2 + n3 * L3
        iG = 1.0 / G
        out = [dG * iG, dk2 / (k2 + c) if z else 0.0, (L1 - dG * n1) * iG, (L2 - dG * n2) * iG,
               (L3 - dG * n3) * iG]
        if ecc:
            out.append(orb.nu_rate(float(y[inu + 1])) * ie)
        return out

    y0: list[float] = [math.log(G0), math.log(k2_0 + c) if z else 0.0, *(float(v) for v in nn)]
    if ecc:
        y0.append(nu0)
    # the polar angles pay where G turns about x3: in the orbit-averaged limit of a torque symmetric about the orbit
    # normal (the gravity gradient, drag, ...) their rates do not depend on lambda, which drifts as one smooth
    # state however many turns it makes; elsewhere (a field fixed in space, the orbital motion resolved) the unit
    # vector follows the turns at least as cheaply (measured), so it is the chart throughout
    angles = eps == 0.0 and _axisymmetric(av, st0)
    chart = "angles" if angles and math.hypot(nn[0], nn[1]) >= _SIN_ON else "vector"
    if chart == "angles":
        y0[2:] = [math.acos(max(-1.0, min(1.0, float(nn[2])))), lam0]
    if eps > 0.0 and setup.drift_tol is not None and (d0 := _slow_drift(setup, st0, av.mean(st0))) > setup.drift_tol:
        raise ValueError(
            f"the torque is too strong for eps = {eps:g} at this state: the slow variables change by {d0:.3g} of "
            f"themselves in one Euler-Poinsot period (> drift_tol = {setup.drift_tol:g}); the averaging needs a "
            "separation of time scales. Lower eps or the torque, or pass drift_tol=None to integrate anyway"
        )

    lnk_stop = math.log(setup.k2_max + c)
    common_events = [
        Event((lambda t, y: y[1] - lnk_stop) if z else (lambda t, y: -1.0), "separatrix", True, 1.0,
              stop_message("separatrix", k2_max=setup.k2_max)),
    ]
    if eps > 0.0:
        cap, ratio = setup.spin_cap, setup.min_spin_ratio
        common_events.append(Event(lambda t, y: _nut_freq(a, exp(y[0]), min(max(z * exp(y[1]) - c, 0.0), cap)) * ie
                                   - ratio,
                                   "slow_rotation", True, -1.0, stop_message("slow_rotation", min_spin_ratio=ratio)))

    def chart_events(chart: str) -> list[Event]:
        evs = list(common_events)
        if eps > 0.0 and setup.drift_tol is not None:
            tol = setup.drift_tol

            def drift(t: float, y: Any) -> float:
                st, m = pair(t, y, chart)
                return _slow_drift(setup, st, m) - tol

            evs.append(Event(drift, "fast_drift", True, 1.0, stop_message("fast_drift", drift_tol=tol)))
        if chart == "angles":
            evs.append(Event(lambda t, y: sin(y[2]) - _SIN_OFF, "chart", True, -1.0))
        elif angles:
            evs.append(Event(lambda t, y: math.hypot(y[2], y[3]) / sqrt(y[2] ** 2 + y[3] ** 2 + y[4] ** 2) - _SIN_ON,
                             "chart", True, 1.0))
        return evs

    py = setup.method == "DOP853"
    pieces: list[_Chart] = []
    lam_s, t_s, step = lam0, tau0, first_step
    while True:
        rt: Any
        rt, at = _tolerances(setup.rtol, chart, ecc)
        raw = integrate(rhs_angles if chart == "angles" else rhs_vector, (t_s, t1), y0,
                        rtol=rt if py else _k.RTOL_FLOOR, atol=at, method=setup.method, dense_output=True,
                        events=chart_events(chart), time_name="tau", engine="python" if py else "scipy",
                        first_step=step if py else None)
        misfire.settle(raw)
        piece = _Chart(chart, raw, z, c, ecc, lam_s)
        pieces.append(piece)
        if raw.event != "chart" or len(pieces) >= _MAX_CHARTS:
            break
        # switch charts at the event: the same G, k2, direction (and nu), lambda continuous
        t_s = float(raw.t_events["chart"][-1])
        lam_s = piece.lam_end()
        yc = piece.common(raw.y[:, -1])
        n = yc[2:5]
        chart = "vector" if chart == "angles" else "angles"
        y0 = [float(raw.y[0, -1]), float(raw.y[1, -1])]
        if chart == "angles":
            lam_n = math.atan2(n[1], n[0])
            lam_n += 2.0 * math.pi * round((lam_s - lam_n) / (2.0 * math.pi))  # the branch of the continuous lambda
            y0 += [math.acos(max(-1.0, min(1.0, float(n[2])))), lam_n]
        else:
            y0 += [float(v) for v in n]
        if ecc:
            y0.append(float(yc[5]))
        step = raw.last_step if py else None
    return _Segment(_join_charts(pieces), setup, kind, sigma, tau0, nu0, pieces)


def _join_charts(pieces: list[_Chart]) -> Solution:
    """One Solution (rows G, k2, n[, nu]) from the chart pieces of a segment: their steps, events (the chart
    switches left out), status and message of the last, the total nfev, a piecewise dense output."""
    last = pieces[-1].raw
    times, ys = [], []
    for i, p in enumerate(pieces):
        t, y = p.raw.time, p.raw.y
        if i:  # the first point of a later piece is the last of its predecessor
            t, y = t[1:], y[:, 1:]
        times.append(t)
        ys.append(p.common(y) if t.size else np.empty((p.n_common, 0)))
    t_events: dict[str, list[float]] = {}
    y_events: dict[str, list[np.ndarray]] = {}
    for p in pieces:
        for k, v in p.raw.t_events.items():
            if k == "chart":
                continue
            t_events.setdefault(k, []).extend(np.asarray(v, dtype=float).tolist())
            yv = p.raw.y_events[k]
            y_events.setdefault(k, []).extend([p.common(row) for row in np.asarray(yv, dtype=float)])
    n_c = pieces[0].n_common
    te = {k: np.array(v, dtype=float) for k, v in t_events.items()}
    ye = {k: (np.array(v, dtype=float).reshape(-1, n_c)) for k, v in y_events.items()}
    status, message, event = last.status, last.message, last.event
    if event == "chart":  # only after _MAX_CHARTS switches
        status, event = -1, None
        message = (f"the direction of G changed charts {len(pieces)} times (it hovers at sin(delta) = "
                   f"{_SIN_OFF:g}..{_SIN_ON:g}); integration stopped")
    dense = _PiecewiseDense([p.raw.time[0] for p in pieces], [lambda t, p=p: p.common(p.raw.sol(t)) for p in pieces],
                            n_c)
    res = Solution(last.time_name, np.concatenate(times), np.concatenate(ys, axis=1), {}, status, message, event, te,
                   ye, dense, sum(p.raw.nfev for p in pieces))
    res.last_step = last.last_step
    return res


def _rho(body: Body, kind: str, k2: Any) -> Any:
    r"""Rotation number :math:`\rho = \langle\dot\psi\rangle P/2\pi` of the Euler--Poinsot motion (independent of G
    and sigma), vectorised over ``k2`` in [0, 1).

    With :math:`\dot\psi = G(2T - g_3^2/A_3)/(G^2 - g_3^2)` (body axes; :math:`g_3 = A_3k c_{cn}\operatorname{cn}u`
    for 'max', :math:`A_3 c_{dn}\operatorname{dn}u` for 'min') the mean over a period is a complete elliptic
    integral of the third kind, :math:`\langle 1/(\alpha+\beta\operatorname{sn}^2)\rangle = \Pi(-\beta/\alpha|k^2)/
    (K\alpha)`; in the labelled moments :math:`a_i` (derived here; checked against the spectral mean of
    :meth:`EulerPoinsot.psi_rate_mean` in the tests):

    'max': :math:`\langle\dot\psi\rangle/G = [1 - (a_1-a_3)\Pi(n|k^2)/(a_1K)]/a_3`,
    :math:`n = -k^2a_3(a_1-a_2)/(a_1(a_2-a_3))`; 'min': :math:`\langle\dot\psi\rangle/G = [1 + (a_1-a_3)
    \Pi(n|k^2)/(a_3K)]/a_1`, :math:`n = -a_1(a_2-a_3)/(a_3(a_1-a_2))`; :math:`P = 4K/\dot u`. Carlson's forms
    :math:`K = R_F(0, k'^2, 1)`, :math:`\Pi = K + \tfrac n3R_J(0, k'^2, 1, 1-n)` (DLMF 19.25.14).
    """
    a1, a2, a3 = _labels(body, kind)
    k2 = np.asarray(k2, dtype=float)
    mc = 1.0 - k2
    R = a1 * (a2 - a3) + a3 * (a1 - a2) * k2
    rate = np.sqrt((a1 - a2) * (a1 - a3) * (a2 - a3) / (a1 * a2 * a3 * R))  # du/dt at G = 1
    K = special.elliprf(0.0, mc, 1.0)
    if kind == "max":
        n = -k2 * a3 * (a1 - a2) / (a1 * (a2 - a3))
        Pi = K + n / 3.0 * special.elliprj(0.0, mc, 1.0, 1.0 - n)
        mean = (K - (a1 - a3) / a1 * Pi) / a3  # <dpsi/dt> K at G = 1
    else:
        n = -a1 * (a2 - a3) / (a3 * (a1 - a2))
        Pi = K + n / 3.0 * special.elliprj(0.0, mc, 1.0, 1.0 - n)
        mean = (K + (a1 - a3) / a3 * Pi) / a1
    out = 2.0 * mean / (math.pi * rate)
    return float(out) if out.ndim == 0 else out


def _resonances(seg: _Segment) -> list[dict[str, float]]:
    """Resonance crossings j rho = N (j = 1, 2) along a segment with eps > 0, with their predicted jumps."""
    setup = seg.setup
    body, kind, a = setup.body, seg.kind, _labels(setup.body, seg.kind)
    # within 1 - k2 < 0.01 of the separatrix the rotation number grows without bound (like the period) and the
    # passage there is the separatrix crossing's business, not a resonance's: the search stops at K2_SPIN_CAP
    return resonance_crossings(
        seg.res, lambda k2: _rho(body, kind, k2),
        lambda t, y: _state_of(setup, kind, seg.sigma, t, y, seg.tau0, seg.nu0),
        lambda G, k2: 2.0 * math.pi / _nut_freq(a, G, k2), setup.averager, setup.eps,
        setup.resonance_tol, K2_SPIN_CAP)  # type: ignore[arg-type]  # called only with resonance_tol set


def _slow_fields(A: tuple[float, float, float], y: np.ndarray, nvec: Any, nu: Any) -> dict[str, np.ndarray]:
    """G, T (from (5) inverted, labelled moments A), k2, delta, n and nu of raw states y = (G, k2, ...)."""
    G = y[0]
    k2 = np.clip(y[1], 0.0, 1.0)
    n = nvec(y) if y.shape[1] else np.empty((3, 0))
    T = 0.5 * G**2 * _k.s_over_r(A, k2)
    return {"G": G, "T": T, "k2": k2, "delta": np.arccos(np.clip(n[2], -1.0, 1.0)), "n": n, "nu": nu}


def _finish_kind(seg: _Segment, tau_eval: Any, lam0: float) -> Solution:
    """Output fields of a segment (G, T, k2, delta, lam, nu, n), the quadrature report and the resonance check."""
    setup, res = seg.setup, seg.res
    A = _labels(setup.body, seg.kind)
    eps = setup.eps

    def nvec(y: np.ndarray) -> np.ndarray:
        n = y[2:5]
        return n / np.linalg.norm(n, axis=0)

    def make_fields(tau: np.ndarray, y: np.ndarray) -> dict[str, np.ndarray]:
        if eps == 0.0:
            nu = np.full_like(tau, seg.nu0)
        elif setup.orbit.e == 0.0:
            nu = (tau - seg.tau0) / eps + seg.nu0
        else:
            nu = y[5]
        return _slow_fields(A, y, nvec, nu)

    resonances = _resonances(seg) if eps > 0.0 and setup.resonance_tol is not None else []
    status, message, event = res.status, res.message, res.event
    cut = next((r for r in resonances if r["jump"] > setup.resonance_tol), None)  # type: ignore[operator]  # tol set
    if cut is not None:
        keep = res.time <= cut["tau"]
        tcut = np.append(res.time[keep], cut["tau"])
        ycut = np.column_stack([res.y[:, keep], res.sol(cut["tau"])])
        status, event = 1, "resonance"
        # an order too high to compute its coefficient, and a bound that does not show it harmless
        message = stop_message("resonance_bound" if cut["bound"] else "resonance", tau=cut["tau"], rho=cut["rho"],
                               jump=cut["jump"], resonance_tol=setup.resonance_tol)
        res = Solution(res.time_name, tcut, ycut, {}, status, message, event, res.t_events, res.y_events,
                       res.sol, res.nfev)
        resonances = [r for r in resonances if r["tau"] <= cut["tau"]]
    out = _finish(res, tau_eval, make_fields, lam0, nvec, lambda tau, y: seg.lam(tau))
    # the quadrature error along the run (relative to the size of the averaged torque), at the first and the
    # last state (each estimate costs a few right-hand sides on the calibration grid)
    qerr = 0.0
    if setup.averager.rest is not None and res.time.size:
        for t in np.unique([res.time[0], res.time[-1]]):
            st = _state_of(setup, seg.kind, seg.sigma, float(t), res.sol(t), seg.tau0, seg.nu0)
            try:
                m, e = setup.averager.report(st)
            except RESULT_ERRORS:  # the torque turned bad at the end (the run's status says so): no estimate
                qerr = math.nan
                break
            # every rate in torque units: <C M> itself, dT/dtau times G/T, dk2/dtau times G
            GT = st.G / max(st.T, 1e-300)
            size = float(np.abs(m.L).max()) + abs(m.dT) * GT + 1e-300
            qerr = max(qerr, max(float(np.abs(e.L).max()), abs(e.dT) * GT, abs(e.dk2) * st.G) / size)
    data = {f: getattr(out, f) for f in out.fields}
    data["kind"] = np.full(out.time.shape, seg.kind)
    data["sigma"] = np.full(out.time.shape, seg.sigma)
    return _with(out, data, {"quad_error": qerr, "resonances": resonances})


def _with(sol: Solution, data: dict[str, Any], extra: dict[str, Any]) -> Solution:
    """A Solution with extra scalar attributes (kept out of the array fields)."""
    new = Solution(sol.time_name, sol.time, sol.y, data, sol.status, sol.message, sol.event, sol.t_events,
                   sol.y_events, sol.sol, sol.nfev)
    for k, v in extra.items():
        setattr(new, k, v)
    return new


# --------------------------------------------------------------------------------------------------
# through the separatrix: segments of one kind of motion joined at the crossings
# --------------------------------------------------------------------------------------------------
#: a run that crosses the separatrix more often than this ends with a status (the averaged motion stalls there)
_MAX_CROSSINGS = 50


@dataclass
class _Piece:
    """One segment of an averaged run: its raw result, its region (kind, sigma), how to evaluate its output
    fields at given times (``finish(tau_eval, lam_start)``), its state as rows G, k2, n (``common(y)``), and
    the lambda it starts from."""

    res: Solution
    region: tuple[str, int]
    finish: Any
    common: Any
    lam_start: float


@dataclass(kw_only=True)
class _Generic(_RunOptions):
    """What the segments after a crossing share: the whole perturbation as a torque object and the options
    of :func:`averaged`. The segments use the averaging engine (closed forms of the parts that have them)."""

    torque: Any
    averaging: str
    quad_tol: float

    def __post_init__(self) -> None:
        self.averager = Averager(self.torque, self.averaging, self.quad_tol)
        self.drag: Any = None  # a drag tensor run: its segments use the closed forms (9) of the paper
        # the rotation-speed check takes the period at min(k2, spin_cap): K2_SPIN_CAP in a run through the
        # separatrix (its momentary infinite period must not end the run), 1 (no cap) in a run that stops there
        self.spin_cap = K2_SPIN_CAP

    def setup(self, k2_stop: float) -> _Setup:
        return _Setup(**self.options(), averager=self.averager, k2_max=k2_stop, spin_cap=self.spin_cap)

    def piece(self, region: tuple[str, int], tau_span: Any, G: float, k2: float, n: np.ndarray, nu0: float,
              lam_s: float, k2_stop: float, first_step: float | None = None) -> _Piece:
        if self.drag is not None:
            return _drag_piece(self, self.drag, region, tau_span, G, k2, n, nu0, lam_s, k2_stop, first_step)
        seg = _integrate_kind(self.setup(k2_stop), region[0], region[1], tau_span, G, k2, n, nu0, lam_s,
                              first_step)

        def finish(te: Any, lam: float) -> Solution:
            return _finish_kind(seg, te, lam)

        def common(y: np.ndarray) -> np.ndarray:
            return np.vstack([y[0], y[1], y[2:5] / np.linalg.norm(y[2:5], axis=0)])

        return _Piece(seg.res, region, finish, common, lam_s)

    def crossing(self, G: float, delta: float, lam: float, nu: float | None, source: tuple[str, int]
                 ) -> SeparatrixCrossing:
        return separatrix_crossing(self.body, self.torque, G, delta, lam, nu, source, orbit=self.orbit)

    def dk2_at(self, region: tuple[str, int], G: float, n: np.ndarray, nu: float | None) -> float:
        """The averaged dk2/dtau of ``region`` at the switch next to the separatrix."""
        if self.drag is not None:
            A, Id = _labels(self.body, region[0], self.drag.diag)
            return _dk2(A, Id, K2_SWITCH)
        st = _State(self.body, region[0], region[1], G, K2_SWITCH, n, nu, self.orbit)
        self.averager.calibrate(st)
        return float(self.averager.mean(st).dk2)


class _PiecewiseDense:
    """Dense output of a run made of pieces (segments through the separatrix, charts of a segment): ``n_rows`` rows
    (G, k2, n[, nu]) at any times, from the piece that starts last before each; ``parts[i](t)`` evaluates piece i
    at an array of its times."""

    def __init__(self, starts: list[float], parts: list[Any], n_rows: int) -> None:
        self.starts = np.array(starts, dtype=float)
        self.parts = parts
        self.n_rows = n_rows

    def __call__(self, t: Any) -> np.ndarray:
        tt = np.atleast_1d(np.asarray(t, dtype=float))
        out = np.empty((self.n_rows, tt.size))
        idx = np.clip(np.searchsorted(self.starts, tt, side="right") - 1, 0, len(self.parts) - 1)
        for i in np.unique(idx).tolist():
            sel = idx == i
            out[:, sel] = self.parts[i](tt[sel])
        return out[:, 0] if np.ndim(t) == 0 else out


def _through(first: _Piece, gen: _Generic, tau_span: Any, tau_eval: Any, through: bool, branch: Any,
             rng: np.random.Generator | None) -> Solution:
    """Continue an averaged run across the separatrix as often as it reaches it, then assemble the output."""
    t1 = float(tau_span[1])
    pieces = [first]
    crossings: list[dict[str, Any]] = []
    stop = ""
    cur = first
    while through and cur.res.status == 1 and cur.res.event == "separatrix":
        tc = float(cur.res.t_events["separatrix"][-1])
        at = cur.finish(np.array([tc]), cur.lam_start)
        G, n = float(at.G[0]), np.asarray(at.n[:, 0], dtype=float)
        delta, lam = float(at.delta[0]), float(at.lam[0])
        nu = float(at.nu[0]) if gen.eps > 0.0 else None
        c = gen.crossing(G, delta, lam, nu, cur.region)
        region, why = _choose(c, branch, len(crossings), rng)
        if region is not None and gen.dk2_at(region, G, n, nu) >= 0.0:
            why = stop_message("attracts", region=region)
            region = None
        crossings.append({"tau": tc, "source": cur.region, "region": region, "probabilities": dict(c.probabilities),
                          "drifts": dict(c.drifts), "G": G, "n": n})
        if region is None:
            stop = why
            break
        if len(crossings) > _MAX_CROSSINGS or (len(crossings) > 1 and tc <= crossings[-2]["tau"]):
            stop = stop_message("stall", n=len(crossings), tau=tc)
            break
        # a segment that starts next to the separatrix starts with the step its predecessor ended with: there
        # the rates' logarithmic singularity can fool the initial-step heuristic into a step whose error
        # estimate is too optimistic (1e-7 instead of 1e-10 relative in G, measured)
        cur = gen.piece(region, (tc, t1), G, K2_SWITCH, n, nu if nu is not None else gen.nu0, lam, K2_SWITCH,
                        first_step=cur.res.last_step)
        pieces.append(cur)
    if len(pieces) == 1 and not crossings:
        sol: Solution = first.finish(tau_eval, first.lam_start)
        sol.crossings = []  # type: ignore[attr-defined]  # an extra attribute of this result: no crossing
        return sol
    return _assemble(pieces, crossings, stop, tau_eval)


def _assemble(pieces: list[_Piece], crossings: list[dict[str, Any]], stop: str, tau_eval: Any) -> Solution:
    """One Solution from the segments: fields at the requested times (each from its segment's dense output),
    lambda continuous, the kind and sense at every time, the crossings as events."""
    outs: list[Solution] = []
    last = len(pieces) - 1
    for i, p in enumerate(pieces):
        a, b = float(p.res.time[0]), float(p.res.time[-1])
        if tau_eval is None:
            te = p.res.time if i == 0 else p.res.time[1:]
        else:
            t = np.asarray(tau_eval, dtype=float)
            te = t[(t >= a) & ((t <= b) if i == last else (t < b))]
        outs.append(p.finish(te, p.lam_start))
    names = [f for f in outs[-1].fields if all(f in o.fields for o in outs)]
    data = {f: np.concatenate([np.asarray(getattr(o, f)) for o in outs], axis=-1) for f in names}
    tau = np.concatenate([o.time for o in outs])
    y = np.vstack([data["G"], data["k2"], data["n"]])
    res = pieces[-1].res
    status, message, event = res.status, res.message, res.event
    if stop:
        tc = crossings[-1]["tau"]
        status, event = 1, "separatrix"
        message = stop_message("crossing", tau=tc, why=stop)
    t_events = dict(res.t_events)
    y_events = dict(res.y_events)
    t_events["separatrix"] = np.array([c["tau"] for c in crossings])
    y_events["separatrix"] = (np.array([[c["G"], K2_SWITCH, *c["n"]] for c in crossings]) if crossings
                              else np.empty((0, 5)))
    dense = _PiecewiseDense([p.res.time[0] for p in pieces], [lambda t, p=p: p.common(p.res.sol(t)) for p in pieces],
                            5)
    sol = Solution(res.time_name, tau, y, data, status, message, event, t_events, y_events, dense,
                   sum(p.res.nfev for p in pieces))
    sol.crossings = crossings  # type: ignore[attr-defined]  # an extra attribute of this result
    qerr = [getattr(o, "quad_error", 0.0) for o in outs]
    sol.quad_error = max(qerr)  # type: ignore[attr-defined]  # an extra attribute of this result
    sol.resonances = [r for o in outs for r in getattr(o, "resonances", [])]  # type: ignore[attr-defined]
    return sol


def averaged_branches(*args: Any, **kwargs: Any) -> dict[tuple[str, int], Solution]:
    r"""Every branch of the first separatrix crossing of an averaged run.

    Runs :func:`averaged` with the same arguments (``branch`` excepted) and, at its first separatrix crossing,
    continues once in each region ``(kind, sigma)`` of positive capture probability (later crossings take
    the most probable branch).

    Parameters
    ----------
    *args, **kwargs
        As for :func:`averaged`, without ``branch``.

    Returns
    -------
    dict
        Region -> Solution; each Solution's ``crossings[0]['probabilities'][region]`` is the probability of
        that branch. A run that does not cross the separatrix gives one entry, its initial region.
    """
    if "branch" in kwargs:
        raise TypeError("averaged_branches runs every branch: do not pass branch")
    first = averaged(*args, **kwargs)
    if not getattr(first, "crossings", None):
        return {(str(first.kind[0]), int(first.sigma[0])): first} if first.tau.size else {}
    c = first.crossings
    out: dict[tuple[str, int], Solution] = {}
    for region, p in c[0]["probabilities"].items():
        if p > 0.0:
            out[region] = first if region == c[0]["region"] else averaged(*args, branch=[region], **kwargs)
    return out

def _drag_piece(gen: _Generic, drag: Any, region: tuple[str, int], tau_span: Any, G0: float, k2_0: float,
                n0: np.ndarray, nu_start: float, lam0: float, k2_stop: float, first_step: float | None = None
                ) -> _Piece:
    """A segment of the paper's averaged system (9) (drag tensor plus gravity gradient, closed forms), integrated
    in ``(ln G, ln k^2, [delta,] lambda[, nu])`` (:mod:`._kernel`: relative accuracy of the decaying variables,
    lambda continuous) by DOP853 on Python floats; its dense output is computed where it is asked for."""
    SC = _kn.SCALAR
    delta0 = math.acos(max(-1.0, min(1.0, float(n0[2]))))
    body, orb, eps, kind, sigma = gen.body, gen.orbit, gen.eps, region[0], region[1]
    A, Id = _labels(body, kind, drag.diag)
    g1, g2, g3, c3, c1 = _k.DragCoefficients(A, Id).args()
    nu0 = gen.nu0  # circular orbit: nu = tau / eps + nu0 with the run's nu0
    e = orb.e
    limit = eps == 0.0
    y0, z_a = _k.initial_state(eps, G0, k2_0, delta0, lam0, nu_start, e)
    z = float(z_a)
    hl = 0.75 * orb.mean_factor * math.cos(delta0)
    ie = 0.0 if limit else 1.0 / eps
    rhs = _k.scalar_rhs(A, (g1, g2, g3, c3, c1), z, e, limit, hl, ie, nu0)

    lnk_stop = math.log(k2_stop)
    events = [Event((lambda t, y: y[1] - lnk_stop) if z > 0.0 else (lambda t, y: -1.0), "separatrix", True, 1.0,
                    stop_message("separatrix", k2_max=k2_stop))]
    if not limit:
        cap, r = gen.spin_cap, gen.min_spin_ratio
        events.append(Event(lambda t, y: _k.nut_freq(SC, A, math.exp(y[0]), min(z * math.exp(y[1]), cap)) * ie - r,
                            "slow_rotation", True, -1.0, stop_message("slow_rotation", min_spin_ratio=r)))
    rt: Any
    rt, at = _k.tolerances(gen.rtol, y0.size)
    py = gen.method == "DOP853"
    res = integrate(rhs, tau_span, y0, rtol=rt if py else _k.RTOL_FLOOR, atol=at, method=gen.method,
                    dense_output=True, events=events, time_name="tau", engine="python" if py else "scipy",
                    first_step=first_step if py else None)
    def common(y: np.ndarray) -> np.ndarray:
        f = _k.fields(A, e, np.zeros(np.shape(y)[-1]), y, z, limit, delta0, nu0, ie)
        return np.vstack([f["G"], f["k2"], f["n"]])

    def make_fields(tau: np.ndarray, y: np.ndarray) -> dict[str, np.ndarray]:
        out = _k.fields(A, e, tau, y, z, limit, delta0, nu0, ie)
        out["kind"], out["sigma"] = np.full(tau.shape, kind), np.full(tau.shape, sigma)
        return out

    def finish(te: Any, lam_s: float) -> Solution:
        # the fields on te (the solver's steps by default) from the dense output; lambda is a state (continuous by
        # construction); the raw rows become G, k2, n like every run's
        steps = res.time
        if te is None:
            tau, y = steps, res.y
        else:
            tt = np.asarray(te, dtype=float)
            tau = tt[(tt >= steps[0]) & (tt <= steps[-1])] if steps.size else tt[:0]
            y = res.sol(tau) if tau.size else np.empty((res.y.shape[0], 0))
        f = make_fields(tau, y)
        out = Solution(res.time_name, tau, np.vstack([f["G"], f["k2"], f["n"]]), f, res.status, res.message,
                       res.event, res.t_events, res.y_events, lambda t: common(res.sol(t)), res.nfev)
        out.last_step = res.last_step
        return out

    return _Piece(res, region, finish, common, lam0)
