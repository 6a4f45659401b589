r"""The public entry of the averaged system (2.15): validation, then :mod:`._avgproblem` (a problem for the
piecewise driver :func:`rigidbody.core.piecewise.run_pieces`).

The two charts of :func:`averaged` (the paper's roots ``u`` and the original slow variables ``(Gz, H, r)``)
are integrated in the coordinates of :mod:`rigidbody.lagrange._kernel` (the roots through their log-gaps,
``(Gz, C r)`` in log-polar form), with absolute error control on those coordinates, i.e. relative error
control on every decaying quantity. One run is a batch of one: the same driver runs a group of one member on
the scalar integrator and a larger group on the vectorised one.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..core.ode import Solution
from ..core.validate import member_states
from ._avgproblem import run_members
from ._avgsetup import ChartSetup, check_options
from ._top import Top, check_top
from ._torques import Torque, check_torque

__all__ = ["averaged"]


# ==================================================================================================
# public entry
# ==================================================================================================
def averaged(
    top: Top,
    torque: Torque,
    initial: Any,
    tau_span: tuple[float, float],
    tau_eval: Any = None,
    *,
    rtol: float = 1e-12,
    atol: float = 1e-14,
    method: str = "DOP853",
    n: int | None = None,
    chart: str = "auto",
    closed_form: bool | None = None,
    degenerate_tol: float = 1e-8,
    switch_tol: float = 1e-2,
    max_segments: int = 200,
) -> Solution:
    r"""Integrate the averaged first-approximation system (2.15)-(2.16) in the slow time ``tau = eps t``.

    The state is ``(u1, u2, u3)`` (the paper's variables; chart ``'u'``). The signs ``delta1 =
    sign(Gz^2 - C^2 r^2)`` and ``delta2 = sign r`` of (2.8) are taken from the initial (Gz, H, r). Where
    one of them may change (``Gz^2 - C^2 r^2`` or ``r`` near zero, i.e. ``R`` or the radicand of ``r``
    in (2.8) near zero, where the map (2.8) has a square-root branch point), the integration continues,
    as the paper prescribes, with the averaged original system (2.7) in (Gz, H, r) (chart ``'GHr'``; the
    roots are recomputed from the cubic (1.5)); sign changes are recorded as events ``'delta1_flip'``,
    ``'delta2_flip'``, and the integration returns to the ``u`` chart with the new signs once clear of
    the branch point. Switching happens at ``|Gz^2-C^2r^2| / (Gz^2+C^2r^2) < switch_tol`` (or the same
    for ``C^2 r^2``) and back at twice that (hysteresis).

    A start at a regular precession (``u1 = u2``, where (2.10) is singular) is integrated in the ``GHr``
    chart by ``chart='auto'`` (and refused by ``chart='u'``). Degenerate states reached during the
    integration end it with ``status = 1`` and a message: ``u2 - u1 <
    degenerate_tol (u3 - u1)`` (regular precession; the determinant of (2.10) vanishes, event
    ``'u1_eq_u2'``), ``u3 - u2 < degenerate_tol (u3 - u1)`` (sleeping top / separatrix, infinite
    nutation period, event ``'separatrix'``) and, in the ``GHr`` chart, a triple root ``u1 = u2 = u3 = 1``
    (root spread below 1e-3: a fast sleeping top slowed down to ``C^2 r^2 = 4 A mgl``, event
    ``'triple_root'``).

    A batch of initial states (components of ``initial`` that are arrays, or a stacked array of shape
    ``batch_shape + (3,)``) is integrated together, each member with its own charts, signs, events and status
    (see Notes).

    Parameters
    ----------
    top : Top
    torque : Torque
        Any admissible torque: one with a closed-form average (``closed_means``, e.g. :class:`LinearDrag`,
        (3.4)) uses it by default, the others the general engine.
    initial : tuple (Gz0, H0, r0) or numpy.ndarray of shape ``batch_shape + (3,)``
        Initial slow variables (1.2). By components: a tuple or list of three numbers or arrays that broadcast
        together (as :func:`integrals` returns them for arrays of states); stacked: an array with one row
        ``(Gz, H, r)`` per member. The batch shape is the components' broadcast shape (the array's shape less
        its last axis), ``()`` for one run.
    tau_span : (tau0, tau1)
        Slow-time interval.
    tau_eval : array_like, optional
        Output times (default: the solver's steps for one run, 101 uniform points for a batch).
    rtol : float
        Relative accuracy of every slow variable (see Notes).
    atol : float
        Absolute accuracy of ``(Gz, H, r)`` where ``Gz = r = 0`` (a top with no angular momentum about the
        vertical and no spin, the only states with no relative scale).
    method : str
        ``'DOP853'`` (default) or another :func:`scipy.integrate.solve_ivp` method for one run; a batch always
        uses DOP853.
    n : int, optional
        Trapezoid nodes per nutation period for the general engine.
    chart : {'auto', 'u', 'GHr'}
        ``'auto'``: ``u`` chart with switching (default); ``'u'``: ``u`` chart only (a near-branch-point
        state ends the run, event ``'branch_point'``); ``'GHr'``: averaged (2.7) in (Gz, H, r) throughout.
    closed_form : bool, optional
        Use the torque's closed-form average (its ``closed_means``; :class:`LinearDrag`: (3.4)) where it has one
        (default), or force the general engine (``False``); ``True`` for a torque without one is a TypeError.
    degenerate_tol, switch_tol : float
        Thresholds described above.
    max_segments : int
        Maximum number of chart segments (guards against chattering).

    Returns
    -------
    rigidbody.core.ode.Solution
        Fields ``tau``, ``u`` (shape (3, n)), ``u1, u2, u3``, ``Gz``, ``H``, ``r``, ``k2``, ``delta1``,
        ``delta2``, ``chart`` (0 for ``u``, 1 for ``GHr``), and ``status`` (0 end reached, 1 a terminal
        degenerate event, -1 failure), ``message``, ``t_events`` (``'delta1_flip'``, ``'delta2_flip'``,
        ``'chart_switch'``, and the terminal event). For a batch every field has shape
        ``batch_shape + (len(tau_eval),)`` (``u``: ``batch_shape + (3, len(tau_eval))``), NaN after a
        member's end, and ``status``, ``message``, ``event`` are per member; ``sol[i]`` is member ``i``.

    See Also
    --------
    simulate : the full equations (1.1) it approximates.
    averaged_rhs : its right-hand side (2.15)-(2.16).
    paper_solution : the paper's cases.

    Notes
    -----
    *What the tolerance controls.* The slow variables of a decaying top (``r``, ``Gz``, the energy above
    the hanging state ``H + mgl``, the gaps ``1 + u1``, ``1 + u2``, ``u3 - 1``) shrink by many orders. The u
    chart is therefore integrated in ``(atanh u1, atanh u2, q)``, ``q = tan(theta/2)``,
    ``tan theta = |Gz - C r|/|Gz + C r|``, and the GHr chart in ``(ln S, psi, kappa)`` with ``S`` the length
    of ``(Gz, C r)``, ``pi psi`` its direction and ``kappa = (H + mgl - C r^2/2)/S``, both with absolute
    error control ``rtol`` on these coordinates: ``rtol`` is then the relative local accuracy of every root
    gap, of ``S`` (hence of ``Gz`` and ``r`` away from their zeros) and of the energy, however far they decay.
    In the u chart ``r`` and ``Gz`` follow from the roots by (2.8), evaluated without cancellation; the
    smaller of ``|Gz|``, ``|C r|`` inherits the gaps' error times their ratio (at most ``1/switch_tol``
    before the chart switches). ``atol`` is used only where no relative scale exists (``Gz = r = 0``).

    *Batches.* The batch convention of the library (:func:`rigidbody.core.validate.member_states`): the batch
    shape is the broadcast shape of the per-member inputs, here the components of ``initial``. The type
    decides how ``initial`` is read, so no value has two readings: an array is stacked on its last axis (the
    form of earlier versions, kept), a tuple or list holds the three components (the form of the per-member
    arguments of :func:`rigidbody.euler_poinsot.averaged`); a list of three lists of three numbers, which
    could be either, is refused. ``top``, ``torque`` and the options are shared by all members. Members in the
    same chart are integrated together by :func:`rigidbody.core.batch.integrate_batch` (vectorised right-hand
    sides for :class:`LinearDrag`; the general engine evaluates its nutation means member by member); a member
    that needs the other chart continues in a follow-up batch of that chart from its switching point.
    Every member equals its single run within the tolerance.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`,
    eqs. (2.15)-(2.16), (3.3)-(3.4).

    Examples
    --------
    Case 2 under the drag (3.1): the roots start at the paper's table ``(0, 0.5, 2)`` and the spin
    follows ``r = r0 exp(-b tau / C)`` (3.3), ``sqrt(3)/e`` at ``tau = 10``:

    >>> import math
    >>> from rigidbody import lagrange
    >>> top = lagrange.PAPER_TOP
    >>> initial = lagrange.integrals(top, *lagrange.paper_initial_state(2)[:5])
    >>> sol = lagrange.averaged(top, lagrange.PAPER_DRAG, initial, (0.0, 10.0))
    >>> print(f"{sol.u2[0]:.6f} {sol.u3[0]:.6f}")
    0.500000 2.000000
    >>> print(f"{sol.r[-1]:.6f} {math.sqrt(3) / math.e:.6f}")
    0.637186 0.637186
    """
    top = check_top(top)
    torque = check_torque(torque)
    t0, t1, degenerate_tol, switch_tol, rtol, atol = check_options(
        tau_span, chart, degenerate_tol, switch_tol, rtol, atol, max_segments)
    st = ChartSetup(top, torque, rtol, atol, n, chart, closed_form, degenerate_tol, switch_tol)
    te_all = None if tau_eval is None else np.atleast_1d(np.asarray(tau_eval, dtype=float))
    if te_all is not None and te_all.size and (te_all.min() < t0 or te_all.max() > t1):
        raise ValueError("tau_eval must lie within tau_span")
    ini = member_states(initial, ("Gz", "H", "r"), "initial")
    batch_shape = ini.shape[:-1]
    if batch_shape:
        te = np.linspace(t0, t1, 101) if te_all is None else te_all
        return run_members(st, ini.reshape(-1, 3), batch_shape, t0, t1, te, "DOP853", max_segments)
    return run_members(st, ini.reshape(1, 3), (), t0, t1, te_all, method, max_segments)
