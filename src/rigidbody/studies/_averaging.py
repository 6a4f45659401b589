r"""Where averaging holds: the largest difference between the averaged and the full evolution of the slow
variables, one point or a batch of points."""

from __future__ import annotations

import math
from collections.abc import Callable
from math import pi
from typing import Any

import numpy as np

from .. import euler_poinsot as ep
from .. import lagrange
from ..core.validate import real
from ..sweep import RAISED
from ._common import PAPER_BODY, PAPER_DRAG_CASE1, call_errors, checked, first_errors, k2_start

__all__ = ["averaging_error_euler_poinsot", "averaging_error_lagrange"]

#: the start of a single call's RuntimeError for a run that did not reach the end of its span
_EARLY = "the {} run ended early: "


def _count(value: Any, name: str, low: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < low:
        raise ValueError(f"{name} must be an integer >= {low}, got {value!r}")
    return int(value)


def _ended(name: str, sol: Any) -> None:
    if sol.status != 0:
        raise RuntimeError(_EARLY.format(name) + str(sol.message))


def _differences(full: Any, avg: Any, names: tuple[str, ...], slow: tuple[str, ...]) -> dict[str, Any]:
    """The largest absolute differences over the output times (the last axis) and ``error``, the largest of
    those of the ``slow`` variables."""
    out = {n: np.max(np.abs(np.asarray(getattr(full, n)) - np.asarray(getattr(avg, n))), axis=-1) for n in names}
    out["error"] = np.max([out[n] for n in slow], axis=0)
    return out


def _by_eps(eps: np.ndarray, runs: Callable[[float, np.ndarray], tuple[Any, Any]], names: tuple[str, ...],
            slow: tuple[str, ...], field: str) -> dict[str, np.ndarray]:
    """The differences over arrays of points (flat), one batch of averaged and one of full runs per value of
    ``eps`` (``runs(eps, index) -> (averaged, full)``), with a status and message per point: 1 and the
    exception where the point's single call raises (its outputs NaN)."""
    out = {k: np.full(eps.size, np.nan) for k in (*names, "error")}
    message = np.full(eps.size, "", dtype=object)
    for e in np.unique(eps):
        idx = np.nonzero(eps == e)[0]
        avg, full = runs(float(e), idx)
        errors = [call_errors(sol, np.asarray(sol.status).reshape(-1) != 0, field, _EARLY.format(name))
                  for name, sol in (("averaged", avg), ("full", full))]
        message[idx] = first_errors(*errors)
        for k, v in _differences(full, avg, names, slow).items():
            out[k][idx] = v
    status = np.where(message == "", 0, RAISED)
    for v in out.values():
        v[status != 0] = np.nan
    return {**out, "status": status, "message": message}


def _reshaped(out: dict[str, np.ndarray], shape: tuple[int, ...]) -> dict[str, np.ndarray]:
    return {k: v.reshape(shape) for k, v in out.items()}


_EP_FIELDS = ("G", "T", "k2", "delta", "lam")


def averaging_error_euler_poinsot(
    eps: Any,
    k2_0: Any,
    *,
    body: ep.Body = PAPER_BODY,
    I: Any = PAPER_DRAG_CASE1,
    tau_end: float = 0.5,
    n_out: int = 201,
    delta0: Any = pi / 4,
    lam0: Any = pi / 4,
) -> dict[str, Any]:
    r"""Largest difference between the averaged (9) and the full motion over :math:`\tau \in [0, \tau_{end}]`.

    Both start from the same slow variables (:math:`G_0 = 1`, ``k2_0``, ``delta0``, ``lam0``, true anomaly
    0, kind 'max'); the full motion at the phase ``u0 = psi0 = 0`` of the Euler--Poinsot motion
    (:func:`rigidbody.euler_poinsot.initial_state`). The differences are taken at ``n_out`` equally spaced
    slow times (enough of them that the maximum of the oscillating difference does not depend on where
    the samples fall: with 11 the fitted order scatters by 0.3). The theory (averaging over the
    Euler--Poinsot motion with :math:`\nu` kept) predicts
    :math:`O(\varepsilon^2)` over :math:`\tau = O(1)`; the averaging needs the rotation to be fast, which
    fails near the separatrix (the Euler--Poinsot period grows like :math:`\ln(1/(1-k^2))`): there the
    full run is refused (``ValueError`` from :func:`rigidbody.euler_poinsot.simulate`).

    Parameters
    ----------
    eps : float or array_like
        :math:`\varepsilon > 0`, the orbital rate in the section-3 scaling.
    k2_0 : float or array_like
        Initial modulus squared (5), in (0, 1).
    body : rigidbody.euler_poinsot.Body
        Default: the paper's body.
    I : array_like
        Drag tensor (3x3 or its diagonal); default the paper's case 1.
    tau_end : float
        End of the slow-time span, :math:`\tau = \varepsilon^2\tilde t`.
    n_out : int
        Number of comparison times (>= 2).
    delta0, lam0 : float or array_like
        Initial direction of :math:`\mathbf G` (radians).

    Returns
    -------
    dict
        ``G``, ``T``, ``k2``, ``delta``, ``lam``: the largest absolute differences; ``error``: the largest
        of those of ``G``, ``T``, ``k2`` (the slow variables of (9)). Arrays ``eps``, ``k2_0``, ``delta0``,
        ``lam0`` (broadcast together, e.g. the points of a grid for :func:`evaluate`) give arrays: the points
        of each value of ``eps`` integrated as one batch of averaged and one of full runs, each member equal to
        its single run within the integrators' tolerance; with ``status`` (1 where the point's single call
        raises, its outputs NaN) and ``message`` (that exception, ``'Type: text'``) per point.

    Raises
    ------
    ValueError
        For ``eps <= 0``, ``k2_0`` outside (0, 1), ``n_out < 2``, or (a single point) a start where the
        rotation is not fast.
    RuntimeError
        (A single point) if either run ends before ``tau_end`` (its message says why).

    See Also
    --------
    averaging_error_lagrange : the same study for the top.
    fitted_order : the order of the error in ``eps``.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, eq. (9).

    Examples
    --------
    The averaged motion approaches the full one as ``eps -> 0`` (Bogolyubov's averaging theorem on slow
    times of order 1): the error is below ``eps`` and smaller for the smaller ``eps``:

    >>> import numpy as np
    >>> from rigidbody import studies
    >>> out = studies.averaging_error_euler_poinsot(np.array([0.04, 0.02]), 0.5, tau_end=0.1, n_out=11)
    >>> bool(out["error"][0] < 0.04 and out["error"][1] < out["error"][0])
    True
    """
    E = checked(eps, "eps", lambda a: a > 0.0, "be > 0 (the full motion needs a finite spin)")
    K = k2_start(k2_0)
    n_out = _count(n_out, "n_out", 2)
    I_ = np.diag(np.asarray(I, dtype=float)) if np.ndim(I) == 1 else np.asarray(I, dtype=float)
    tau_end = real(tau_end, "tau_end")
    tau = np.linspace(0.0, tau_end, n_out)
    if np.ndim(delta0) or np.ndim(lam0) or E.ndim or K.ndim:
        arrays = np.broadcast_arrays(E, K, np.asarray(delta0, dtype=float), np.asarray(lam0, dtype=float))
        e_, k_, d_, l_ = (a.reshape(-1) for a in arrays)

        def runs(e: float, i: np.ndarray) -> tuple[Any, Any]:
            kw: dict[str, Any] = dict(k2_0=k_[i], delta0=d_[i], lam0=l_[i], tau_span=(0.0, tau_end), tau_eval=tau)
            return ep.averaged(body, I_, e, **kw), ep.simulate(body, I_, e, **kw)

        return _reshaped(_by_eps(e_, runs, _EP_FIELDS, ("G", "T", "k2"), "G"), arrays[0].shape)
    kw: dict[str, Any] = dict(k2_0=float(K), delta0=delta0, lam0=lam0, tau_span=(0.0, tau_end), tau_eval=tau)
    avg = ep.averaged(body, I_, float(E), **kw)
    full = ep.simulate(body, I_, float(E), **kw)
    _ended("averaged", avg)
    _ended("full", full)
    return {k: float(v) for k, v in _differences(full, avg, _EP_FIELDS, ("G", "T", "k2")).items()}


def averaging_error_lagrange(
    eps: Any,
    theta0: Any,
    *,
    top: lagrange.Top = lagrange.PAPER_TOP,
    torque: lagrange.Torque = lagrange.PAPER_DRAG,
    r0: Any = lagrange.PAPER_R0,
    tau_end: float = 2.0,
    n_out: int = 201,
) -> dict[str, Any]:
    r"""Largest difference between the averaged (2.15)/(3.4) and the full motion (1.1) of the top.

    The top starts spun about its axis (``p = q = 0``, ``r = r0``) and tilted by ``theta0``: the paper's
    section-3 initial states with the tilt free. The slow variables ``Gz, H, r`` (the first integrals
    (1.2), which the torque changes slowly) of the full motion are compared with the averaged ones at
    ``n_out`` equally spaced slow times :math:`\tau = \varepsilon t`. First-order averaging predicts
    :math:`O(\varepsilon)` over :math:`\tau = O(1)`.

    Parameters
    ----------
    eps : float or array_like
        :math:`\varepsilon > 0`.
    theta0 : float or array_like
        Initial nutation angle (radians), in (0, pi).
    top : rigidbody.lagrange.Top
    torque : rigidbody.lagrange.Torque
        Default: the paper's top and linear drag (3.1).
    r0 : float or array_like
        Initial axial spin (default the paper's ``sqrt(3)``).
    tau_end : float
        End of the slow-time span.
    n_out : int
        Number of comparison times (>= 2).

    Returns
    -------
    dict
        ``Gz``, ``H``, ``r``: the largest absolute differences; ``error``: the largest of the three. Arrays
        ``eps``, ``theta0``, ``r0`` (broadcast together) give arrays: the points of each value of ``eps``
        integrated as one batch of averaged and one of full runs, each member equal to its single run within
        the integrators' tolerance; with ``status`` and ``message`` per point as for
        :func:`averaging_error_euler_poinsot`.

    Raises
    ------
    ValueError
        For ``eps <= 0``, ``theta0`` outside (0, pi) or ``n_out < 2``.
    RuntimeError
        (A single point) if either run ends before ``tau_end`` (its message says why).

    See Also
    --------
    averaging_error_euler_poinsot : the same study for the satellite.
    fitted_order : the order of the error in ``eps``.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`,
    eqs. (1.1), (2.15), (3.3)-(3.4).

    Examples
    --------
    The first approximation errs by ``O(eps)`` on slow times of order 1: halving ``eps`` halves the error
    (ratio about 2); the spin ``r`` agrees to rounding, both motions following ``r0 exp(-b tau / C)`` (3.3):

    >>> import numpy as np
    >>> from rigidbody import studies
    >>> out = studies.averaging_error_lagrange(np.array([0.02, 0.01]), 1.0, tau_end=0.5, n_out=11)
    >>> print(f"{out['error'][0] / out['error'][1]:.1f}")
    2.0
    >>> bool(np.all(out["r"] < 1e-10))
    True
    """
    E = checked(eps, "eps", lambda a: a > 0.0, "be > 0 (the full motion needs a finite nutation period)")
    TH = checked(theta0, "theta0", lambda a: (a > 0.0) & (a < math.pi), "lie in (0, pi)")
    n_out = _count(n_out, "n_out", 2)
    tau_end = real(tau_end, "tau_end")
    tau = np.linspace(0.0, tau_end, n_out)
    names = ("Gz", "H", "r")
    if np.ndim(r0) or E.ndim or TH.ndim:
        arrays = np.broadcast_arrays(E, TH, np.asarray(r0, dtype=float))
        e_, th_, r_ = (a.reshape(-1) for a in arrays)

        def runs(e: float, i: np.ndarray) -> tuple[Any, Any]:
            state0 = np.zeros((i.size, 6))
            state0[:, 2], state0[:, 4] = r_[i], th_[i]
            initial = lagrange.integrals(top, 0.0, 0.0, r_[i], 0.0, th_[i])  # the components (Gz0, H0, r0)
            avg = lagrange.averaged(top, torque, initial, (0.0, tau_end), tau_eval=tau)
            return avg, lagrange.simulate(top, torque, e, state0, (0.0, tau_end / e), t_eval=tau / e)

        return _reshaped(_by_eps(e_, runs, names, names, "Gz"), arrays[0].shape)
    eps, state0 = float(E), (0.0, 0.0, float(r0), 0.0, float(TH), 0.0)
    avg = lagrange.averaged(top, torque, lagrange.integrals(top, *state0[:5]), (0.0, tau_end), tau_eval=tau)
    full = lagrange.simulate(top, torque, eps, state0, (0.0, tau_end / eps), t_eval=tau / eps)
    _ended("averaged", avg)
    _ended("full", full)
    return {k: float(v) for k, v in _differences(full, avg, names, names).items()}
