r"""Parameter studies built on :func:`rigidbody.sweep.sweep`: one point of each map, and what theory predicts.

Each ``*_point`` function computes one point of a map and returns a mapping of output names to floats, so
``sweep(func, grid)`` runs it over a grid (serially, on local processes or on a Dask cluster). A point
outside the domain of the study raises; the sweep records it (``status`` 1) and goes on.

*Where averaging holds* — the largest difference between the averaged and the full evolution of the slow
variables over a slow-time span, against the order the theory gives:

:func:`averaging_error_euler_poinsot` over :math:`(\varepsilon, k^2_0)`
    Rachinskaya's averaged system (9) with the true anomaly kept (:func:`rigidbody.euler_poinsot.averaged`)
    against the full equations (:func:`rigidbody.euler_poinsot.simulate`); order :math:`\varepsilon^2`
    (docs/euler_poinsot.md, "What the numbers show").
:func:`averaging_error_lagrange` over :math:`(\varepsilon, \theta_0)`
    the first approximation (2.15)/(3.4) of Akulenko, Leshchenko and Chernousko
    (:func:`rigidbody.lagrange.averaged`) against the full equations (1.1)
    (:func:`rigidbody.lagrange.simulate`); order :math:`\varepsilon`.
:func:`fitted_order`
    the exponent :math:`p` of ``error ~ C eps**p`` fitted along the ``eps`` axis.

*Where the spin ends* — :func:`spin_end`: the final regime of :math:`k^2` under the averaged equation (8)
over a plane of diagonal drag tensors. Only the decay rates :math:`a_i = I_{ii}/A_i` enter (8), and only
their ratios matter (the scale sets the unit of slow time), so the plane is ``r1 = a1/a2``,
``r3 = a3/a2``. With :math:`a_2 = 1`, (8) reads

.. math:: \frac{dk^2}{d\tau} = -2\left[(r_3 - 1)(k^2 - W) + (1 - r_1)\,k^2 E/K\right],\qquad W = 1 - E/K,

and three lines through ``(1, 1)`` organise the plane (derived here from (7)-(8); see docs/sweeps.md):

- :func:`chi_minus_3_line`, ``r3 = 2 r1 - 1``: there :math:`\chi = -3` in (7); the slope of (8) at
  :math:`k^2 = 0`, :math:`-(r_3 + 1 - 2r_1)`, vanishes: :math:`k^2 = 0` is stable above the line,
  unstable below;
- ``r3 = r1``: near :math:`k^2 = 1`, :math:`dk^2/d\tau \approx -2(r_3 - r_1)E/K`:
  below the line :math:`k^2` reaches the separatrix in finite time, above it is pushed back;
- :func:`equilibrium_line`, ``r3 = 1 + rho(k2_0) (r1 - 1)``: where ``k2_0`` itself is an equilibrium of
  (8) (:math:`\rho = k^2(E/K)/(k^2 - W)` falls from 2 at :math:`k^2 = 0` to 1 at :math:`k^2 = 1`, so an
  interior equilibrium exists exactly between the first two lines). Between the first two lines with
  ``r1 < 1`` it is unstable and this line splits the starts that end at 0 from those that reach the
  separatrix.

:func:`spin_end_predicted` gives the regime from the equilibria of (8) alone
(:func:`rigidbody.euler_poinsot.k2_equilibria`), the analytic counterpart of the integrated map.

The maps of the figures (``python -m rigidbody figures --only studies``) use the quick grids of
:data:`GRIDS`; the full grids are for a cluster (docs/sweeps.md says how).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from . import euler_poinsot as ep
from . import lagrange
from .core import elliptic
from .core.validate import real
from .sweep import batched

__all__ = [
    "GRIDS",
    "PAPER_BODY",
    "PAPER_DRAG_CASE1",
    "REGIMES",
    "averaging_error_euler_poinsot",
    "averaging_error_lagrange",
    "chi_minus_3_line",
    "drag_from_ratios",
    "equilibrium_line",
    "fitted_order",
    "spin_end",
    "spin_end_predicted",
]

#: Rachinskaya's body (section 3), nondimensional principal moments A1 > A2 > A3
PAPER_BODY = ep.Body(A1=3.2, A2=2.6, A3=1.67)
#: Rachinskaya's drag tensor of case 1 (section 3), its diagonal
PAPER_DRAG_CASE1 = (2.322, 1.31, 1.425)
#: codes of :func:`spin_end`'s ``regime``
REGIMES = {0: "k2 -> 0", 1: "k2 -> interior k*2", 2: "k2 -> 1 (separatrix)"}

#: the studies' grids: ``quick`` for the figures command (seconds on 2 cores), ``full`` for a cluster
GRIDS: dict[str, dict[str, dict[str, np.ndarray]]] = {
    "averaging_euler_poinsot": {
        "quick": {"eps": np.array([0.04, 0.02, 0.01]), "k2_0": 1.0 - np.array([0.9, 0.5, 0.2, 0.05, 0.01])},
        "full": {"eps": np.geomspace(0.0025, 0.08, 11), "k2_0": 1.0 - np.geomspace(0.95, 0.002, 40)},
    },
    "averaging_lagrange": {
        "quick": {"eps": np.array([0.04, 0.02, 0.01]), "theta0": np.radians([5.0, 30, 60, 90, 120, 150, 170])},
        "full": {"eps": np.geomspace(0.001, 0.08, 13), "theta0": np.radians(np.linspace(2.0, 178.0, 45))},
    },
    "spin_end": {
        "quick": {"r1": np.linspace(0.1, 2.5, 13), "r3": np.linspace(0.1, 2.5, 13)},
        "full": {"r1": np.linspace(0.05, 3.0, 120), "r3": np.linspace(0.05, 3.0, 120)},
    },
}


def _max_differences(a: Any, b: Any, names: tuple[str, ...]) -> dict[str, float]:
    return {n: float(np.max(np.abs(np.asarray(getattr(a, n)) - np.asarray(getattr(b, n))))) for n in names}


def _count(value: Any, name: str, low: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < low:
        raise ValueError(f"{name} must be an integer >= {low}, got {value!r}")
    return int(value)


def _ended(name: str, sol: Any) -> None:
    if sol.status != 0:
        raise RuntimeError(f"the {name} run ended early: {sol.message}")


def averaging_error_euler_poinsot(
    eps: float,
    k2_0: float,
    *,
    body: ep.Body = PAPER_BODY,
    I: Any = PAPER_DRAG_CASE1,
    tau_end: float = 0.5,
    n_out: int = 201,
    delta0: float = math.pi / 4,
    lam0: float = math.pi / 4,
) -> dict[str, float]:
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
    eps : float
        :math:`\varepsilon > 0`, the orbital rate in the section-3 scaling.
    k2_0 : float
        Initial modulus squared (5), in (0, 1).
    body : rigidbody.euler_poinsot.Body
        Default: the paper's body.
    I : array_like
        Drag tensor (3x3 or its diagonal); default the paper's case 1.
    tau_end : float
        End of the slow-time span, :math:`\tau = \varepsilon^2\tilde t`.
    n_out : int
        Number of comparison times (>= 2).
    delta0, lam0 : float
        Initial direction of :math:`\mathbf G` (radians).

    Returns
    -------
    dict
        ``G``, ``T``, ``k2``, ``delta``, ``lam``: the largest absolute differences; ``error``: the largest
        of those of ``G``, ``T``, ``k2`` (the slow variables of (9)).

    Raises
    ------
    ValueError
        For ``eps <= 0``, ``k2_0`` outside (0, 1), ``n_out < 2``, or a start where the rotation is not fast.
    RuntimeError
        If either run ends before ``tau_end`` (its message says why).
    """
    eps, k2_0 = real(eps, "eps"), real(k2_0, "k2_0")
    if eps <= 0.0:
        raise ValueError(f"eps must be > 0 (the full motion needs a finite spin), got {eps}")
    if not 0.0 < k2_0 < 1.0:
        raise ValueError(f"k2_0 must lie in (0, 1), got {k2_0}")
    n_out = _count(n_out, "n_out", 2)
    I_ = np.diag(np.asarray(I, dtype=float)) if np.ndim(I) == 1 else np.asarray(I, dtype=float)
    tau_end = real(tau_end, "tau_end")
    tau = np.linspace(0.0, tau_end, n_out)
    kw: dict[str, Any] = dict(k2_0=k2_0, delta0=delta0, lam0=lam0, tau_span=(0.0, tau_end), tau_eval=tau)
    avg = ep.averaged(body, I_, eps, **kw)
    full = ep.simulate(body, I_, eps, **kw)
    _ended("averaged", avg)
    _ended("full", full)
    out = _max_differences(full, avg, ("G", "T", "k2", "delta", "lam"))
    out["error"] = max(out["G"], out["T"], out["k2"])
    return out


def averaging_error_lagrange(
    eps: float,
    theta0: float,
    *,
    top: lagrange.Top = lagrange.PAPER_TOP,
    torque: lagrange.Torque = lagrange.PAPER_DRAG,
    r0: float = lagrange.PAPER_R0,
    tau_end: float = 2.0,
    n_out: int = 201,
) -> dict[str, float]:
    r"""Largest difference between the averaged (2.15)/(3.4) and the full motion (1.1) of the top.

    The top starts spun about its axis (``p = q = 0``, ``r = r0``) and tilted by ``theta0``: the paper's
    section-3 initial states with the tilt free. The slow variables ``Gz, H, r`` (the first integrals
    (1.2), which the torque changes slowly) of the full motion are compared with the averaged ones at
    ``n_out`` equally spaced slow times :math:`\tau = \varepsilon t`. First-order averaging predicts
    :math:`O(\varepsilon)` over :math:`\tau = O(1)`.

    Parameters
    ----------
    eps : float
        :math:`\varepsilon > 0`.
    theta0 : float
        Initial nutation angle (radians), in (0, pi).
    top : rigidbody.lagrange.Top
    torque : rigidbody.lagrange.Torque
        Default: the paper's top and linear drag (3.1).
    r0 : float
        Initial axial spin (default the paper's ``sqrt(3)``).
    tau_end : float
        End of the slow-time span.
    n_out : int
        Number of comparison times (>= 2).

    Returns
    -------
    dict
        ``Gz``, ``H``, ``r``: the largest absolute differences; ``error``: the largest of the three.

    Raises
    ------
    ValueError
        For ``eps <= 0``, ``theta0`` outside (0, pi) or ``n_out < 2``.
    RuntimeError
        If either run ends before ``tau_end`` (its message says why).
    """
    eps, theta0 = real(eps, "eps"), real(theta0, "theta0")
    if eps <= 0.0:
        raise ValueError(f"eps must be > 0 (the full motion needs a finite nutation period), got {eps}")
    if not 0.0 < theta0 < math.pi:
        raise ValueError(f"theta0 must lie in (0, pi), got {theta0}")
    n_out = _count(n_out, "n_out", 2)
    tau_end = real(tau_end, "tau_end")
    tau = np.linspace(0.0, tau_end, n_out)
    state0 = (0.0, 0.0, float(r0), 0.0, theta0, 0.0)
    avg = lagrange.averaged(top, torque, lagrange.integrals(top, *state0[:5]), (0.0, tau_end), tau_eval=tau)
    full = lagrange.simulate(top, torque, eps, state0, (0.0, tau_end / eps), t_eval=tau / eps)
    _ended("averaged", avg)
    _ended("full", full)
    out = _max_differences(full, avg, ("Gz", "H", "r"))
    out["error"] = max(out.values())
    return out


def fitted_order(ds: Any, var: str = "error", over: str = "eps") -> Any:
    r"""The exponent :math:`p` of ``var ~ C over**p``: least squares in log-log along the ``over`` axis.

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep's result (points that failed, NaN, are left out of each fit).
    var, over : str
        The variable and the grid dimension.

    Returns
    -------
    xarray.DataArray
        One exponent for each point of the other dimensions (NaN where fewer than two points are left).
    """
    import xarray as xr

    x = np.log(ds[over])

    def fit(y: np.ndarray) -> float:
        ok = np.isfinite(y) & (y > 0)
        if ok.sum() < 2:
            return math.nan
        return float(np.polyfit(x.values[ok], np.log(y[ok]), 1)[0])

    return xr.apply_ufunc(fit, ds[var], input_core_dims=[[over]], vectorize=True)


def drag_from_ratios(r1: float, r3: float, body: ep.Body = PAPER_BODY) -> np.ndarray:
    r"""The diagonal drag tensor with decay-rate ratios ``a1/a2 = r1``, ``a3/a2 = r3`` and :math:`a_2 = 1`.

    :math:`a_i = I_{ii}/A_i`, so :math:`I = \mathrm{diag}(r_1 A_1,\ A_2,\ r_3 A_3)`.

    Parameters
    ----------
    r1, r3 : float
        Positive ratios of the decay rates.
    body : rigidbody.euler_poinsot.Body

    Returns
    -------
    numpy.ndarray
        The 3x3 tensor.
    """
    r1, r3 = real(r1, "r1"), real(r3, "r3")
    if r1 <= 0.0 or r3 <= 0.0:
        raise ValueError(f"r1 and r3 must be > 0 (a drag dissipates), got r1={r1}, r3={r3}")
    return np.diag([r1 * body.A1, body.A2, r3 * body.A3])


@batched
def spin_end(
    r1: float,
    r3: float,
    *,
    body: ep.Body = PAPER_BODY,
    k2_0: float = 0.5,
    tau_end: float = 100.0,
    k2_zero: float = 1e-3,
    rtol: float = 1e-6,
) -> dict[str, float]:
    r"""Final regime of :math:`k^2` for the drag tensor of decay-rate ratios ``r1 = a1/a2``, ``r3 = a3/a2``.

    Integrates the orbit-averaged system (9) (``eps = 0``, :func:`rigidbody.euler_poinsot.averaged`) from
    ``k2_0`` with :func:`drag_from_ratios` (:math:`a_2 = 1` sets the unit of slow time) until
    ``tau_end`` or until :math:`k^2` reaches the separatrix, and classifies the end: ``regime`` 2 if the
    separatrix was reached, 0 if :math:`k^2` fell below ``k2_zero``, else 1 (an interior equilibrium
    :math:`k_*^2` of (8)). Near the :math:`\chi = -3` line the approach to :math:`k^2 = 0` (or to a small
    :math:`k_*^2`) is slow, its rate :math:`-(r_3 + 1 - 2r_1)` vanishing there: within about
    :math:`\ln(k^2_0/k^2_{zero})/\tau_{end}` of the line a finite run cannot tell 0 from 1.

    Parameters
    ----------
    r1, r3 : float
        Positive ratios of the decay rates :math:`a_i = I_{ii}/A_i`.
    body : rigidbody.euler_poinsot.Body
    k2_0 : float
        Initial modulus squared, in (0, 1).
    tau_end : float
        End of the slow-time span (in units of :math:`1/a_2`).
    k2_zero : float
        Below this, :math:`k^2` counts as having reached 0.
    rtol : float
        Relative tolerance of the integration (the classification needs few digits of :math:`k^2`, whose
        equation is smooth; the cost is set by the precession angle, which grows like :math:`1/G` as
        :math:`G` decays).

    Returns
    -------
    dict
        ``regime`` (see :data:`REGIMES`), ``k2_end`` (the last :math:`k^2`), ``tau_end`` (when the run
        ended), ``chi`` (:math:`\chi` of (7); NaN where its denominator :math:`a_3 - a_1` vanishes).
        Arrays ``r1``, ``r3`` (a chunk of a sweep: the function is marked :func:`rigidbody.sweep.batched`)
        give arrays, integrated as one batch (a drag tensor per point), with the sweep's ``status`` (1 where
        the point's single call would raise) and ``message`` per point.
    """
    k2_0 = real(k2_0, "k2_0")
    if not 0.0 < k2_0 < 1.0:
        raise ValueError(f"k2_0 must lie in (0, 1), got {k2_0}")
    if np.ndim(r1) or np.ndim(r3):
        return _spin_end_batch(np.asarray(r1, dtype=float), np.asarray(r3, dtype=float), body, k2_0,
                               real(tau_end, "tau_end"), real(k2_zero, "k2_zero"), rtol)
    I = drag_from_ratios(r1, r3, body)
    sol = ep.averaged(body, I, 0.0, k2_0=k2_0, tau_span=(0.0, real(tau_end, "tau_end")), rtol=rtol, atol=1e-10,
                      k2_max=1.0 - 1e-6)  # the default stop next to the separatrix, stated
    if sol.status == -1:
        raise RuntimeError(sol.message)
    k2_end = float(sol.k2[-1])
    regime = 2 if sol.event == "separatrix" else (0 if k2_end < k2_zero else 1)
    chi = float(ep.chi(body, I)) if r3 != r1 else math.nan
    return {"regime": float(regime), "k2_end": k2_end, "tau_end": float(sol.tau[-1]), "chi": chi}


def _failed(sol: Any) -> tuple[np.ndarray, list[str]]:
    """The sweep's status (1: the point's single call would have raised) and messages of a batch: a member
    refused at its start (the ValueError of its single call) or failed later (a RuntimeError here)."""
    st = np.asarray(sol.status).reshape(-1)
    started = np.isfinite(np.asarray(sol.G).reshape(st.size, -1)[:, 0])
    msg = [str(m) for m in np.asarray(sol.message, dtype=object).reshape(-1)]
    out = [("" if s >= 0 else (f"RuntimeError: {m}" if ok else f"ValueError: {m}"))
           for s, ok, m in zip(st, started, msg)]
    return np.where(st >= 0, 0, 1), out


def _spin_end_batch(r1: np.ndarray, r3: np.ndarray, body: ep.Body, k2_0: float, tau_end: float, k2_zero: float,
                    rtol: float) -> dict[str, Any]:
    """:func:`spin_end` over arrays of points: one batch of averaged evolutions (a drag tensor per point)."""
    r1, r3 = np.broadcast_arrays(r1, r3)
    shape = r1.shape
    r1, r3 = r1.reshape(-1), r3.reshape(-1)
    if np.any(~(r1 > 0.0)) or np.any(~(r3 > 0.0)):
        raise ValueError("r1 and r3 must be > 0 (a drag dissipates)")
    I = np.zeros((r1.size, 3, 3))
    I[:, 0, 0], I[:, 1, 1], I[:, 2, 2] = r1 * body.A1, body.A2, r3 * body.A3
    sol = ep.averaged(body, I, 0.0, k2_0=k2_0, tau_span=(0.0, tau_end), tau_eval=[0.0, tau_end], rtol=rtol,
                      atol=1e-10, k2_max=1.0 - 1e-6)
    k2_end = np.asarray(sol.y_final)[:, 1]  # k2 where each run ended
    regime = np.where(sol.event == "separatrix", 2.0, np.where(k2_end < k2_zero, 0.0, 1.0))
    # chi of (7) from the decay-rate ratios: (2 a2 - a1 - a3)/(a3 - a1), a2 = 1
    with np.errstate(divide="ignore", invalid="ignore"):
        chi = np.where(r3 != r1, (2.0 - r1 - r3) / (r3 - r1), np.nan)
    status, message = _failed(sol)
    out = {"regime": regime, "k2_end": k2_end, "tau_end": np.asarray(sol.t_final, dtype=float), "chi": chi}
    out = {k: v.reshape(shape) for k, v in out.items()}
    return {**out, "status": status.reshape(shape), "message": np.array(message, dtype=object).reshape(shape)}


def spin_end_predicted(r1: float, r3: float, *, body: ep.Body = PAPER_BODY, k2_0: float = 0.5) -> int:
    r"""The final regime of :math:`k^2` from the equilibria of (8) alone (no integration).

    :math:`k^2` obeys the autonomous scalar equation (8), so from ``k2_0`` it moves monotonically to the
    nearest equilibrium in the direction of the flow (:func:`rigidbody.euler_poinsot.k2_equilibria`),
    or to the separatrix when there is none on that side and the flow points up.

    Returns
    -------
    int
        0, 1 or 2 as in :data:`REGIMES`.
    """
    I = drag_from_ratios(r1, r3, body)
    rate = ep.dk2_dtau(body, I, real(k2_0, "k2_0"))
    roots = [k for k, _ in ep.k2_equilibria(body, I)]
    if rate > 0:
        return 1 if any(k > k2_0 for k in roots) else 2
    if rate == 0:
        return 1
    return 0 if max(k for k in roots if k < k2_0) == 0.0 else 1


def chi_minus_3_line(r1: Any) -> np.ndarray:
    r"""The line :math:`\chi = -3` of the analysis of (8) in the plane (``r1``, ``r3``): ``r3 = 2 r1 - 1``.

    From (7), :math:`\chi = (2a_2 - a_1 - a_3)/(a_3 - a_1)`, so :math:`\chi = -3` where
    :math:`a_2 + a_3 = 2a_1`: the slope of (8) at :math:`k^2 = 0` vanishes and :math:`k^2 = 0` changes
    stability.

    Parameters
    ----------
    r1 : array_like

    Returns
    -------
    numpy.ndarray
        ``r3`` on the line.
    """
    return 2.0 * np.asarray(r1, dtype=float) - 1.0


def _rho(k2: float) -> float:
    k = math.sqrt(k2)
    e_over_k = float(elliptic.E(k) / elliptic.K(k))
    return k2 * e_over_k / (k2 - 1.0 + e_over_k)


def equilibrium_line(r1: Any, k2_0: float) -> np.ndarray:
    r"""The line through ``(1, 1)`` where ``k2_0`` is an equilibrium of (8): ``r3 = 1 + rho (r1 - 1)``.

    :math:`\rho(k^2) = k^2 (E/K) / (k^2 - W)`, :math:`W = 1 - E/K` (derived from (8) with :math:`a_2 = 1`:
    the right-hand side vanishes where :math:`(r_3 - 1)(k^2 - W) = (r_1 - 1)k^2E/K`).

    Parameters
    ----------
    r1 : array_like
    k2_0 : float
        In (0, 1).

    Returns
    -------
    numpy.ndarray
        ``r3`` on the line.
    """
    k2_0 = real(k2_0, "k2_0")
    if not 0.0 < k2_0 < 1.0:
        raise ValueError(f"k2_0 must lie in (0, 1), got {k2_0}")
    return 1.0 + _rho(k2_0) * (np.asarray(r1, dtype=float) - 1.0)

