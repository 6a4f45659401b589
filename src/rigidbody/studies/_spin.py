r"""Where the spin ends: the final regime of :math:`k^2` under the averaged equation (8) over a plane of
diagonal drag tensors, and the lines of the plane derived from (7)-(8)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .. import euler_poinsot as ep
from ..core import elliptic
from ..core.validate import real
from ..sweep import RAISED, batched
from ._common import PAPER_BODY, call_errors, checked, k2_start

__all__ = ["REGIMES", "chi_minus_3_line", "drag_from_ratios", "equilibrium_line", "spin_end", "spin_end_predicted"]

#: codes of :func:`spin_end`'s ``regime``
REGIMES = {0: "k2 -> 0", 1: "k2 -> interior k*2", 2: "k2 -> 1 (separatrix)"}


def _ratios(r1: Any, r3: Any) -> tuple[np.ndarray, np.ndarray]:
    rule = "be > 0 (a drag dissipates)"
    return checked(r1, "r1", lambda a: a > 0.0, rule), checked(r3, "r3", lambda a: a > 0.0, rule)


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

    See Also
    --------
    spin_end : the study that uses it.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, eq. (7).

    Examples
    --------
    Equal ratios give equal decay rates ``I_ii / A_i = 1``: ``I`` is the body's inertia tensor
    ``diag(3.2, 2.6, 1.67)``:

    >>> import numpy as np
    >>> from rigidbody import studies
    >>> np.diag(studies.drag_from_ratios(1.0, 1.0))
    array([3.2 , 2.6 , 1.67])
    """
    r1, r3 = (float(v) for v in _ratios(real(r1, "r1"), real(r3, "r3")))
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
        Arrays ``r1``, ``r3`` (the points of a grid for :func:`evaluate`, or a chunk of a sweep: the function
        is marked :func:`rigidbody.sweep.batched`) give arrays, integrated as one batch (a drag tensor per
        point), with ``status`` (1 where the point's single call would raise, its outputs NaN) and ``message``
        (that exception) per point.

    See Also
    --------
    spin_end_predicted : the same regime from the equilibria of (8), without integration.
    drag_from_ratios : the drag tensor of a point.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, eqs. (7)-(9).

    Examples
    --------
    By (7), ``chi = (2 a2 - a1 - a3)/(a3 - a1)``: for the ratios ``(1, 2)`` it is ``-1`` and ``k2`` decays to
    0 (regime 0), for ``(2, 1)`` it is ``+1`` and ``k2`` reaches the separatrix (regime 2), as the
    equilibria of (8) predict:

    >>> from rigidbody import studies
    >>> a, b = studies.spin_end(1.0, 2.0), studies.spin_end(2.0, 1.0)
    >>> print(f"{a['chi']:.6f} {a['regime']:.0f} {b['chi']:.6f} {b['regime']:.0f}")
    -1.000000 0 1.000000 2
    >>> studies.spin_end_predicted(1.0, 2.0), studies.spin_end_predicted(2.0, 1.0)
    (0, 2)
    """
    k2_0 = float(k2_start(real(k2_0, "k2_0")))
    if np.ndim(r1) or np.ndim(r3):
        return _spin_end_batch(r1, r3, body, k2_0, real(tau_end, "tau_end"), real(k2_zero, "k2_zero"), rtol)
    I = drag_from_ratios(r1, r3, body)
    sol = ep.averaged(body, I, 0.0, k2_0=k2_0, tau_span=(0.0, real(tau_end, "tau_end")), rtol=rtol, atol=1e-10,
                      k2_max=1.0 - 1e-6)  # the default stop next to the separatrix, stated
    if sol.status == -1:
        raise RuntimeError(sol.message)
    k2_end = float(sol.k2[-1])
    regime = 2 if sol.event == "separatrix" else (0 if k2_end < k2_zero else 1)
    chi = float(ep.chi(body, I)) if r3 != r1 else math.nan
    return {"regime": float(regime), "k2_end": k2_end, "tau_end": float(sol.tau[-1]), "chi": chi}


def _spin_end_batch(r1: Any, r3: Any, body: ep.Body, k2_0: float, tau_end: float, k2_zero: float,
                    rtol: float) -> dict[str, Any]:
    """:func:`spin_end` over arrays of points: one batch of averaged evolutions (a drag tensor per point)."""
    r1, r3 = np.broadcast_arrays(*_ratios(r1, r3))
    shape = r1.shape
    r1, r3 = r1.reshape(-1), r3.reshape(-1)
    I = np.zeros((r1.size, 3, 3))
    I[:, 0, 0], I[:, 1, 1], I[:, 2, 2] = r1 * body.A1, body.A2, r3 * body.A3
    sol = ep.averaged(body, I, 0.0, k2_0=k2_0, tau_span=(0.0, tau_end), tau_eval=[0.0, tau_end], rtol=rtol,
                      atol=1e-10, k2_max=1.0 - 1e-6)
    k2_end = np.asarray(sol.y_final)[:, 1]  # k2 where each run ended
    regime = np.where(sol.event == "separatrix", 2.0, np.where(k2_end < k2_zero, 0.0, 1.0))
    # chi of (7) from the decay-rate ratios: (2 a2 - a1 - a3)/(a3 - a1), a2 = 1
    with np.errstate(divide="ignore", invalid="ignore"):
        chi = np.where(r3 != r1, (2.0 - r1 - r3) / (r3 - r1), np.nan)
    # the single call raises for a run that failed (status -1), or that its start refused (a ValueError)
    message = call_errors(sol, np.asarray(sol.status).reshape(-1) < 0, "G")
    status = np.where(message == "", 0, RAISED)
    out = {"regime": regime, "k2_end": k2_end, "tau_end": np.asarray(sol.t_final, dtype=float), "chi": chi}
    out = {k: np.where(status == 0, v, np.nan).reshape(shape) for k, v in out.items()}
    return {**out, "status": status.reshape(shape), "message": message.reshape(shape)}


def spin_end_predicted(r1: float, r3: float, *, body: ep.Body = PAPER_BODY, k2_0: float = 0.5) -> int:
    r"""The final regime of :math:`k^2` from the equilibria of (8) alone (no integration).

    :math:`k^2` obeys the autonomous scalar equation (8), so from ``k2_0`` it moves monotonically to the
    nearest equilibrium in the direction of the flow (:func:`rigidbody.euler_poinsot.k2_equilibria`),
    or to the separatrix when there is none on that side and the flow points up.

    Returns
    -------
    int
        0, 1 or 2 as in :data:`REGIMES`.

    See Also
    --------
    spin_end : the integrated regime.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, eq. (8).

    Examples
    --------
    By (7), the ratios ``(1, 2)`` give ``chi = -1`` and ``k2`` decays to 0 (regime 0);
    swapping the ratios gives ``chi = +1`` and the separatrix (regime 2), as :func:`spin_end` finds by
    integration:

    >>> from rigidbody import studies
    >>> studies.spin_end_predicted(1.0, 2.0), studies.spin_end_predicted(2.0, 1.0)
    (0, 2)
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

    See Also
    --------
    equilibrium_line : the other boundary of the spin-end map.
    spin_end : the map these lines bound.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, eqs. (7)-(8).

    Examples
    --------
    With ``a2 = 1``, ``chi = -3`` means ``a3 = 2 a1 - 1``:

    >>> import numpy as np
    >>> from rigidbody import studies
    >>> studies.chi_minus_3_line(np.array([1.0, 2.0]))
    array([1., 3.])
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

    See Also
    --------
    chi_minus_3_line : the other boundary of the spin-end map.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, eq. (8).

    Examples
    --------
    Every such line passes through ``(1, 1)`` (equal decay rates: (8) vanishes for any ``k2``):

    >>> import numpy as np
    >>> from rigidbody import studies
    >>> print(f"{studies.equilibrium_line(np.array([1.0]), 0.5)[0]:.6f}")
    1.000000
    """
    k2_0 = float(k2_start(real(k2_0, "k2_0")))
    return 1.0 + _rho(k2_0) * (np.asarray(r1, dtype=float) - 1.0)

