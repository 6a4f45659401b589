r"""The averaged system (6)-(9) of Rachinskaya and its integrator.

Nondimensional form (section 3): :math:`\tilde G = G/G_0`, :math:`\tilde A_i = A_i\Omega_0/G_0`,
:math:`\varepsilon^2\tilde I = I/G_0`, the orbital rate is :math:`\varepsilon` in units of :math:`\Omega_0`,
slow time :math:`\tau = \varepsilon^2\tilde t` and true anomaly :math:`\nu = \tau/\varepsilon + \nu_0`.
In :math:`\tau` the system (9) is (6) with :math:`\omega_0 = 1` and :math:`I\to\tilde I`, so one set of
functions serves both forms: pass ``omega0`` and dimensional ``I`` for (6) in :math:`t`.

Formulation that does not break at :math:`\sin\delta = 0`
--------------------------------------------------------
Instead of :math:`(\delta, \lambda)` the integrator evolves the unit vector
:math:`\mathbf n = (\sin\delta\cos\lambda, \sin\delta\sin\lambda, \cos\delta)` of :math:`\mathbf G` in the
orbital axes :math:`Ox_i`. The two angle equations of (6) are the components along :math:`y_1, y_2` of

.. math:: \frac{d\mathbf n}{dt} = \frac{3\omega_0^2}{2G}f(\nu)N^*(\mathbf e_r\cdot\mathbf n)\,
          (\mathbf n\times\mathbf e_r),\qquad \mathbf e_r = (\cos\nu, \sin\nu, 0),

(:math:`\beta_i = \mathbf e_r\cdot\mathbf y_i`, :math:`f = 1` on a circular orbit), which is regular
everywhere. :math:`\delta = \arccos n_3` and :math:`\lambda = \operatorname{atan2}(n_2, n_1)` are derived
output, :math:`\lambda` unwrapped along the solver's steps.

Orbit-averaged limit (:math:`\varepsilon = 0`)
---------------------------------------------
Averaging also over :math:`\nu` (:math:`\langle f\,\mathbf e_r\mathbf e_r^T\rangle = (1-e^2)^{-3/2}
\operatorname{diag}(1/2, 1/2, 0)`) gives :math:`d\mathbf n/dt = -\tfrac{3\omega_0^2}{4G}(1-e^2)^{-3/2}N^*n_3\,
(\mathbf n\times\mathbf e_3)`: :math:`\delta` is constant and :math:`\dot\lambda =
\tfrac{3\omega_0^2}{4G}(1-e^2)^{-3/2}N^*\cos\delta` (:func:`precession_rate`). The integrator then
evolves :math:`(G, k^2, \Lambda)` with :math:`\dot\Lambda = \tfrac34(1-e^2)^{-3/2}N^*/G` and
:math:`\lambda = \lambda_0 + \Lambda\cos\delta_0`: as :math:`G \to 0` the precession accelerates like
:math:`1/G`, and a smooth :math:`\Lambda` costs no extra steps where resolving the turns of
:math:`\mathbf n` would.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..core.ode import Event, Solution, integrate
from ..core.validate import positive, real, span
from ._model import (
    Body,
    Orbit,
    _as_orbit,
    _check_body,
    _check_kind,
    _dk2,
    _drag_rates,
    _labels,
    _nstar,
    _nut_freq,
    _S_over_R,
    as_drag,
)

__all__ = ["averaged", "averaged_rates", "precession_rate"]


def averaged_rates(
    body: Body,
    I: Any,
    G: float,
    k2: float,
    delta: float,
    lam: float,
    nu: float | None,
    *,
    kind: str = "max",
    orbit: Orbit | None = None,
    omega0: float = 1.0,
) -> dict[str, float]:
    r"""Right-hand sides of the averaged system (6) (dimensional) or (9) (per :math:`\tau`, ``omega0=1``).

    Parameters
    ----------
    body : Body
    I : array_like or Drag
        Drag tensor (only its diagonal enters (6)).
    G, k2, delta, lam : float
        Slow variables.
    nu : float or None
        True anomaly; ``None`` gives the orbit-averaged limit (:math:`\varepsilon \to 0`).
    kind : {'max', 'min'}
        Kind of Euler--Poinsot motion ('max' is the paper's).
    orbit : Orbit, optional
        Eccentric orbits multiply the gravity terms by :math:`(1+e\cos\nu)^3/(1-e^2)^3`.
    omega0 : float
        Orbital mean motion (1 in the nondimensional form (9)).

    Returns
    -------
    dict
        ``dG``, ``dT``, ``dk2``, ``ddelta``, ``dlam``. The :math:`\lambda` equation is evaluated as
        :math:`\beta_1\beta_3/\sin\delta = \cos^2(\nu-\lambda)\cos\delta`, which is finite at
        :math:`\sin\delta = 0` (where :math:`\lambda` itself is undefined: the integrator evolves the unit
        vector of :math:`\mathbf G` instead).
    """
    _check_body(body)
    _check_kind(kind)
    orb = _as_orbit(orbit)
    A, Id = _labels(body, kind, as_drag(I).diag)
    G = real(G, "G")
    if G <= 0:
        raise ValueError(f"G must be positive, got {G}")
    k2 = real(k2, "k2")
    if not (0.0 <= k2 <= 1.0):
        raise ValueError(f"k2 must lie in [0, 1], got {k2}")
    dG, dT = _drag_rates(A, Id, G, k2)
    dk2 = _dk2(A, Id, k2)
    Ns = _nstar(A, k2)
    sd, cd = math.sin(real(delta, "delta")), math.cos(delta)
    lam = real(lam, "lam")
    omega0 = real(omega0, "omega0")
    if omega0 <= 0:
        raise ValueError(f"omega0 (orbital mean motion) must be positive, got {omega0}")
    w2 = omega0 * omega0
    if nu is None:
        ddelta = 0.0
        dlam = 0.75 * w2 * orb.mean_factor * Ns * cd / G
    else:
        nu = real(nu, "nu")
        f = orb.factor(nu)
        b2 = math.sin(nu - lam)
        b3 = math.cos(nu - lam) * sd
        ddelta = -1.5 * w2 * f * b2 * b3 * Ns / G
        # beta1*beta3/sin(delta) = cos^2(nu - lam) cos(delta): regular at sin(delta) = 0
        dlam = 1.5 * w2 * f * math.cos(nu - lam) ** 2 * cd * Ns / G
    return {"dG": dG, "dT": dT, "dk2": dk2, "ddelta": ddelta, "dlam": dlam}


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


def _slow_msg(r: float) -> str:
    return (f"the rotation is no longer fast: (2 pi / Euler-Poinsot period) / omega0 fell to {r:g}; "
            "the averaging over the Euler-Poinsot motion (eps << 1) no longer holds")


def _check_spin(A: tuple[float, float, float], G0: float, k2_0: float, eps: float, r: float) -> None:
    r = real(r, "min_spin_ratio")
    if eps > 0 and r > 0 and _nut_freq(A, G0, k2_0) / eps <= r:
        raise ValueError(
            f"eps = {eps:g} is too large for this state: the Euler-Poinsot frequency over the orbital rate is "
            f"{_nut_freq(A, G0, k2_0) / eps:.3g} <= min_spin_ratio = {r:g} (the rotation is not fast); lower "
            "eps, or pass min_spin_ratio=0 to integrate anyway outside the theory"
        )


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

    ``lam_direct(y)``, when given, returns the continuous lambda from the state itself.
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
        lam = lam_direct(y_out)
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


def _validate_common(body: Any, eps: Any, G0: Any, k2_0: Any, delta0: Any, lam0: Any,
                     tau_span: Any, nu0: Any) -> tuple[float, float, float, float, float, float]:
    _check_body(body)
    eps = real(eps, "eps")
    if eps < 0:
        raise ValueError(f"eps must be >= 0 (eps = omega0/omega), got {eps}")
    G0 = real(G0, "G0")
    if G0 <= 0:
        raise ValueError(f"G0 must be positive, got {G0}")
    k2_0 = real(k2_0, "k2_0")
    if not (0.0 <= k2_0 < 1.0):
        raise ValueError(f"k2_0 must lie in [0, 1) (k2 = 1 is the separatrix), got {k2_0}")
    delta0 = real(delta0, "delta0")
    if not (0.0 <= delta0 <= math.pi):
        raise ValueError(f"delta0 (polar angle of G from x3) must lie in [0, pi], got {delta0}")
    lam0 = real(lam0, "lam0")
    nu0 = real(nu0, "nu0")
    span(tau_span, "tau_span")
    return eps, G0, k2_0, delta0, lam0, nu0


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
    I: Any,
    eps: float,
    G0: float = 1.0,
    k2_0: float = 0.99,
    delta0: float = math.pi / 4,
    lam0: float = math.pi / 4,
    tau_span: tuple[float, float] = (0.0, 3.0),
    tau_eval: Any = None,
    nu0: float = 0.0,
    *,
    kind: str = "max",
    orbit: Orbit | None = None,
    rtol: float = 1e-10,
    atol: float = 1e-12,
    method: str = "DOP853",
    k2_max: float = 1.0 - 1e-6,
    min_spin_ratio: float = 1.0,
) -> Solution:
    r"""Integrate the nondimensional averaged system (9) in the slow time :math:`\tau = \varepsilon^2\tilde t`.

    Parameters
    ----------
    body : Body
        Nondimensional moments :math:`\tilde A_i`.
    I : array_like or Drag
        Nondimensional drag tensor :math:`\tilde I` (3x3; only the diagonal enters (9)).
    eps : float
        :math:`\varepsilon`, the orbital rate in units of :math:`\Omega_0`; the true anomaly is
        :math:`\nu = \tau/\varepsilon + \nu_0` (Kepler's law for an eccentric ``orbit``). ``eps = 0`` gives
        the orbit-averaged limit (the gravity terms averaged over :math:`\nu`).
    G0, k2_0, delta0, lam0 : float
        Initial :math:`\tilde G`, :math:`k^2` (in [0, 1)), :math:`\delta`, :math:`\lambda` (radians).
    tau_span : (float, float)
    tau_eval : array_like, optional
        Output times (default: the solver's steps).
    nu0 : float
        Initial true anomaly.
    kind : {'max', 'min'}
        Kind of Euler--Poinsot motion ('max': about the axis of :math:`A_1`, the paper's case).
    orbit : Orbit, optional
        Default circular.
    rtol, atol, method
        Passed to the solver (``rigidbody.core.ode.integrate``).
    k2_max : float
        The run ends (status 1, event ``'separatrix'``) when :math:`k^2` reaches this value: at
        :math:`k^2 = 1` the period of the Euler--Poinsot motion is infinite and (6) does not hold.
    min_spin_ratio : float
        The run ends (event ``'slow_rotation'``) when the rotation is no longer fast: when
        :func:`spin_ratio` (frequency :math:`2\pi/P` of the Euler--Poinsot motion over the orbital rate
        :math:`\varepsilon`) falls to this value (``eps > 0`` only; a start below it raises ``ValueError``;
        pass 0 to switch the check off, e.g. to show where the theory fails).

    Returns
    -------
    Solution
        ``sol.tau``, ``sol.G``, ``sol.T``, ``sol.k2``, ``sol.delta`` (in [0, pi]), ``sol.lam`` (continuous,
        unwrapped), ``sol.nu`` (the true anomaly; constant ``nu0`` when ``eps = 0``, where it is averaged
        out), ``sol.n`` (unit vector of G in :math:`Ox_i`, shape (3, n)), ``sol.status`` (0 end reached,
        1 an event ended the run, -1 failure), ``sol.message``, ``sol.event`` (``'separatrix'``,
        ``'slow_rotation'`` or None).

    Examples
    --------
    >>> import numpy as np
    >>> from rigidbody import euler_poinsot as ep
    >>> body = ep.Body(3.2, 2.6, 1.67)
    >>> sol = ep.averaged(body, np.diag([2.322, 1.31, 1.425]), 0.0, tau_span=(0, 3), tau_eval=[0, 3])
    >>> bool(sol.G[-1] < sol.G[0]), sol.status
    (True, 0)
    """
    eps, G0, k2_0, delta0, lam0, nu0 = _validate_common(body, eps, G0, k2_0, delta0, lam0, tau_span, nu0)
    _check_tau_eval(tau_eval, tau_span)
    _check_tol(rtol, atol)
    _check_kind(kind)
    orb = _as_orbit(orbit)
    drag = as_drag(I)
    A, Id = _labels(body, kind, drag.diag)
    k2_max = real(k2_max, "k2_max")
    if not (k2_0 < k2_max <= 1.0):
        raise ValueError(f"k2_max (the separatrix stop) must lie in (k2_0, 1] = ({k2_0}, 1], got {k2_max}: "
                         "raise k2_max or start further from the separatrix")
    _check_spin(A, G0, k2_0, eps, min_spin_ratio)
    circular = orb.e == 0.0
    mf = orb.mean_factor
    inv_eps = 1.0 / eps if eps > 0 else 0.0

    def grav(G: float, k2: float, n1: float, n2: float, n3: float, nu: float) -> tuple[float, float, float]:
        Ns = _nstar(A, k2)
        cn, sn = math.cos(nu), math.sin(nu)
        c = 1.5 * orb.factor(nu) * Ns * (cn * n1 + sn * n2) / G
        return -c * n3 * sn, c * n3 * cn, c * (n1 * sn - n2 * cn)

    def rhs_limit(tau: float, y: np.ndarray) -> list[float]:
        # eps = 0: delta is constant and lambda = lam0 + cos(delta0) * Lambda, dLambda = (3/4) mf N*/G
        G, k2 = y[0], y[1]
        k2c = 0.0 if k2 < 0.0 else (1.0 if k2 > 1.0 else k2)
        dG, _ = _drag_rates(A, Id, G, k2c)
        return [dG, _dk2(A, Id, k2c), 0.75 * mf * _nstar(A, k2c) / G]

    def rhs(tau: float, y: np.ndarray) -> list[float]:
        G, k2, n1, n2, n3 = y[0], y[1], y[2], y[3], y[4]
        k2c = 0.0 if k2 < 0.0 else (1.0 if k2 > 1.0 else k2)
        nrm = math.sqrt(n1 * n1 + n2 * n2 + n3 * n3)
        n1, n2, n3 = n1 / nrm, n2 / nrm, n3 / nrm
        dG, _ = _drag_rates(A, Id, G, k2c)
        dk2 = _dk2(A, Id, k2c)
        if eps > 0.0 and not circular:
            nu = y[5]
            d1, d2, d3 = grav(G, k2c, n1, n2, n3, nu)
            return [dG, dk2, d1, d2, d3, inv_eps * orb.nu_rate(nu)]
        nu = tau * inv_eps + nu0
        d1, d2, d3 = grav(G, k2c, n1, n2, n3, nu)
        return [dG, dk2, d1, d2, d3]

    n0 = _unit(delta0, lam0)
    y0 = [G0, k2_0, *n0] if eps > 0.0 else [G0, k2_0, 0.0]
    if eps > 0.0 and not circular:
        y0.append(nu0)
    cd0, sd0 = math.cos(delta0), math.sin(delta0)
    events = [
        Event(lambda t, y: y[1] - k2_max, "separatrix", True, 1.0,
              f"k2 reached {k2_max:g}: the Euler-Poinsot motion approaches the separatrix 2T A2 = G^2, "
              "where the averaging (6) does not hold"),
    ]
    if eps > 0.0:
        events.append(
            Event(lambda t, y: _nut_freq(A, y[0], min(max(y[1], 0.0), 1.0)) / eps - min_spin_ratio,
                  "slow_rotation", True, -1.0, _slow_msg(min_spin_ratio))
        )
    res = integrate(rhs if eps > 0.0 else rhs_limit, tau_span, y0, rtol=rtol, atol=atol, method=method,
                    dense_output=True, events=events, time_name="tau")

    def lam_limit(y: np.ndarray) -> np.ndarray:
        return lam0 + cd0 * y[2]

    def nvec(y: np.ndarray) -> np.ndarray:
        if eps == 0.0:
            lam = lam_limit(y)
            return np.array([sd0 * np.cos(lam), sd0 * np.sin(lam), np.full_like(lam, cd0)])
        n = y[2:5]
        return n / np.linalg.norm(n, axis=0)

    def make_fields(tau: np.ndarray, y: np.ndarray) -> dict[str, np.ndarray]:
        G = y[0]
        k2 = np.clip(y[1], 0.0, 1.0)
        n = nvec(y) if y.shape[1] else np.empty((3, 0))
        T = 0.5 * G**2 * np.array([_S_over_R(A, float(x)) for x in k2])
        if eps > 0.0 and not circular:
            nu = y[5]
        else:
            nu = tau * inv_eps + nu0 if eps > 0 else np.full_like(tau, nu0)
        return {"G": G, "T": T, "k2": k2, "delta": np.arccos(np.clip(n[2], -1.0, 1.0)), "n": n, "nu": nu}

    return _finish(res, tau_eval, make_fields, lam0, nvec, lam_limit if eps == 0.0 else None)
