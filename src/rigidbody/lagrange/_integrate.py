r"""Integrations: the averaged system (2.15) with sign switching, and the full equations (1.1)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..core import euler as _euler
from ..core.ode import Event, Solution, integrate
from ..core.validate import positive, span
from ._averaging import (
    V_matrix,
    averaged_slow_rates,
    drag_rhs,
)
from ._top import Top, _check_top, deltas, from_roots, root_radical, roots, vieta
from ._torques import LinearDrag, Torque, check_torque

__all__ = ["averaged", "simulate"]

_CHARTS = ("auto", "u", "GHr")
#: spread of the three roots below which they count as a triple root u1 = u2 = u3 = 1 (there the roots are
#: only (machine eps)^(1/3)-conditioned and the nutation period diverges)
_TRIPLE_TOL = 1e-3


def _s13(u1: float, u2: float, u3: float) -> float:
    return u1 + u2 + u3 + u1 * u2 * u3


def _closeness(u1: float, u2: float, u3: float, d1: float) -> tuple[float, float]:
    """(b1, b2): b1 = |Gz^2 - C^2r^2|/(Gz^2 + C^2r^2) = R/(s1+s3); b2 = C^2 r^2/(Gz^2 + C^2 r^2)."""
    s13 = _s13(u1, u2, u3)
    if s13 <= 0.0:
        return 0.0, 0.0
    R = float(root_radical(u1, u2, u3))
    return R / s13, 0.5 * (s13 - d1 * R) / s13


def _double_root(top: Top, Gz: float, H: float, r: float) -> tuple[float, float]:
    """``(c, s1)``: the local maximum ``c = (s1 - (s1^2 - 3 s2)^{1/2})/3`` of the cubic (1.6) (the double root
    of a regular precession; smooth in (Gz, H, r), not clipped to [-1, 1]); ValueError if there is none."""
    if not (math.isfinite(Gz) and math.isfinite(H) and math.isfinite(r)):
        raise ValueError("Gz, H, r must be finite")
    s1, s2, _ = vieta(top, Gz, H, r)
    disc = s1 * s1 - 3.0 * s2
    if disc < 0.0:
        raise ValueError(f"(Gz, H, r) = ({Gz!r}, {H!r}, {r!r}): the cubic (1.5) has one real root")
    return (s1 - math.sqrt(disc)) / 3.0, s1


def _roots_or_double(top: Top, Gz: float, H: float, r: float) -> tuple[float, float, float]:
    """Roots of (1.5); a state a hair outside the admissible set next to its regular-precession boundary
    (Runge-Kutta stages and accepted steps along a solution that runs on that curved boundary: the hanging or
    the sleeping top) gets the double root at the local maximum of the cubic, ``u1 = u2 = c``."""
    try:
        return roots(top, Gz, H, r)
    except ValueError:
        c, s1 = _double_root(top, Gz, H, r)
        c = min(max(c, -1.0), 1.0)
        return c, c, max(s1 - 2.0 * c, 1.0)


def averaged(
    top: Top,
    torque: Torque,
    initial: tuple[float, float, float],
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

    Parameters
    ----------
    top : Top
    torque : Torque
        :class:`LinearDrag` (closed form (3.4) by default) or any admissible torque (general engine).
    initial : (Gz, H, r)
        Initial slow variables (1.2).
    tau_span : (tau0, tau1)
        Slow-time interval.
    tau_eval : array_like, optional
        Output times (default: the solver's steps).
    rtol, atol, method
        Passed to :func:`scipy.integrate.solve_ivp`.
    n : int, optional
        Trapezoid nodes per nutation period for the general engine.
    chart : {'auto', 'u', 'GHr'}
        ``'auto'``: ``u`` chart with switching (default); ``'u'``: ``u`` chart only (a near-branch-point
        state ends the run, event ``'branch_point'``); ``'GHr'``: averaged (2.7) in (Gz, H, r) throughout.
    closed_form : bool, optional
        Use (3.4) for :class:`LinearDrag` (default) or force the general engine (``False``).
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
        ``'chart_switch'``, and the terminal event).
    """
    top = _check_top(top)
    torque = check_torque(torque)
    t0, t1 = span(tau_span, "tau_span")
    if chart not in _CHARTS:
        raise ValueError(f"chart must be one of {_CHARTS}, got {chart!r}")
    degenerate_tol = positive(degenerate_tol, "degenerate_tol")
    switch_tol = positive(switch_tol, "switch_tol")
    if degenerate_tol >= 1.0:
        raise ValueError(f"degenerate_tol must lie in (0, 1) (a ratio of root gaps), got {degenerate_tol!r}")
    if switch_tol >= 0.5:
        raise ValueError(f"switch_tol must lie in (0, 0.5) (the chart is left at 2 switch_tol), got {switch_tol!r}")
    rtol, atol = positive(rtol, "rtol"), positive(atol, "atol")
    if isinstance(max_segments, bool) or not isinstance(max_segments, (int, np.integer)) or max_segments < 1:
        raise ValueError(f"max_segments must be an integer >= 1, got {max_segments!r}")
    try:
        Gz0, H0, r0 = (float(x) for x in initial)
    except (TypeError, ValueError):
        raise ValueError(f"initial must be (Gz, H, r), got {initial!r}") from None
    if closed_form is None:
        closed_form = isinstance(torque, LinearDrag)
    if closed_form and not isinstance(torque, LinearDrag):
        raise TypeError("closed_form=True is available for LinearDrag only (3.4)")
    drag = torque if isinstance(torque, LinearDrag) else None
    te_all = None if tau_eval is None else np.asarray(tau_eval, dtype=float)
    if te_all is not None and te_all.size and (te_all.min() < t0 or te_all.max() > t1):
        raise ValueError("tau_eval must lie within tau_span")

    u_init = roots(top, Gz0, H0, r0)
    d1, d2 = deltas(top, Gz0, r0)

    # ---- right-hand sides ------------------------------------------------------------------------
    def rhs_u(tau: float, y: np.ndarray, d1: float, d2: float) -> np.ndarray:
        # Runge-Kutta stages may step slightly outside the admissible box near a branch point (the field
        # behaves like sqrt(u3 - 1) there); evaluate at the nearest admissible point.
        u1 = min(max(float(y[0]), -1.0), 1.0)
        u2 = min(max(float(y[1]), -1.0), 1.0)
        u3 = max(float(y[2]), 1.0)
        if not (u1 < u2 < u3):
            return np.full(3, np.nan)
        if drag is not None and closed_form:
            return drag_rhs(top, drag, u1, u2, u3, d1, d2)
        Gz, H, r = from_roots(top, u1, u2, u3, d1, d2)
        Fm = averaged_slow_rates(top, torque, Gz, H, r, (u1, u2, u3), n=n)
        return V_matrix(top, u1, u2, u3, Gz, r) @ np.array(Fm)

    def rhs_g(tau: float, y: np.ndarray) -> np.ndarray:
        Gz, H, r = float(y[0]), float(y[1]), float(y[2])
        try:  # roots from the cubic inside: a nearly double pair is handled smoothly there
            return np.array(averaged_slow_rates(top, torque, Gz, H, r, n=n))
        except ValueError:
            pass
        # Runge-Kutta stages leave the admissible set by O(h^2) when the solution runs along its boundary (a
        # regular precession, e.g. the hanging or the sleeping top: the boundary is curved in (Gz, H, r));
        # extend the field continuously by the value at the double root, the local maximum of the cubic
        try:
            c, _ = _double_root(top, Gz, H, r)
        except ValueError:
            return np.full(3, np.nan)
        F = torque.slow_rates(top, Gz, H, r, np.array([c]))
        return np.array([float(np.mean(F[0])), float(np.mean(F[1])), float(np.mean(F[2]))])

    # ---- events ----------------------------------------------------------------------------------
    def ev_deg(tau: float, y: np.ndarray, *a: Any) -> float:
        return float((y[1] - y[0]) / (y[2] - y[0])) - degenerate_tol

    def ev_sep(tau: float, y: np.ndarray, *a: Any) -> float:
        return float((y[2] - y[1]) / (y[2] - y[0])) - degenerate_tol

    def ev_branch(tau: float, y: np.ndarray, d1: float, d2: float) -> float:
        b1, b2 = _closeness(float(y[0]), float(y[1]), float(y[2]), d1)
        return min(b1, b2) - switch_tol

    def ev_sep_g(tau: float, y: np.ndarray) -> float:
        try:
            u1, u2, u3 = _roots_or_double(top, float(y[0]), float(y[1]), float(y[2]))
        except ValueError:
            return -1.0
        if u3 - u1 <= 0.0:
            return -1.0
        return (u3 - u2) / (u3 - u1) - degenerate_tol

    def ev_triple(tau: float, y: np.ndarray) -> float:
        # root spread sqrt(s1^2 - 3 s2) = sqrt(((u1-u2)^2 + (u1-u3)^2 + (u2-u3)^2)/2), smooth in (Gz, H, r)
        s1, s2, _ = vieta(top, float(y[0]), float(y[1]), float(y[2]))
        return math.sqrt(max(s1 * s1 - 3.0 * s2, 0.0)) - _TRIPLE_TOL

    # sign-change events of Gz^2 - C^2 r^2 and r; a value that is zero to integration accuracy (identically
    # zero for a non-spinning top, r = 0, or a planar pendulum, Gz = r = 0; integration noise for a sleeping
    # or hanging top, Gz = +-C r, where both branches of (2.8) coincide) counts as positive, so that it does
    # not report flips at every step; a genuine crossing is located to that relative accuracy (1e-10)
    def ev_w(tau: float, y: np.ndarray) -> float:
        g2, c2 = float(y[0] * y[0]), float((top.C * y[2]) ** 2)
        w = g2 - c2
        return w if abs(w) > 1e-10 * (g2 + c2) else 1e-300

    def ev_r(tau: float, y: np.ndarray) -> float:
        return float(y[2]) if y[2] != 0.0 else 1e-300

    def ev_leave(tau: float, y: np.ndarray) -> float:
        s = float(y[0] * y[0] + (top.C * y[2]) ** 2)
        if s == 0.0:
            return -1.0
        b1 = abs(float(y[0] * y[0] - (top.C * y[2]) ** 2)) / s
        b2 = float((top.C * y[2]) ** 2) / s
        return min(b1, b2) - 2.0 * switch_tol

    msg_deg = ("u2 - u1 reached degenerate_tol (u3 - u1): regular precession, the determinant "
               "(u1-u2)(u1-u3)(u2-u3) of (2.10) vanishes")
    msg_sep = ("u3 - u2 reached degenerate_tol (u3 - u1): sleeping top / separatrix k -> 1, the nutation "
               "period is infinite")
    msg_triple = (f"the roots of (1.5) merge, u1 = u2 = u3 = 1 (spread below {_TRIPLE_TOL:g}): a sleeping top at its "
                  "stability limit C^2 r^2 = 4 A mgl, the nutation period is infinite")
    msg_branch = ("Gz^2 - C^2 r^2 or r is near zero: a sign delta1/delta2 of (2.8) may change; use "
                  "chart='auto' to continue through it")

    # ---- segment loop ----------------------------------------------------------------------------
    taus: list[np.ndarray] = []
    Us: list[np.ndarray] = []
    Gs: list[np.ndarray] = []
    D1s: list[np.ndarray] = []
    D2s: list[np.ndarray] = []
    CHs: list[np.ndarray] = []
    t_events: dict[str, list[float]] = {"delta1_flip": [], "delta2_flip": [], "chart_switch": []}
    status, message, event, nfev = 0, "the end of tau_span was reached", None, 0

    cur = "GHr" if chart == "GHr" else "u"
    tau = t0
    ystate: np.ndarray
    if cur == "u":
        ystate = np.array(u_init, dtype=float)
        b1, b2 = _closeness(*u_init, d1)
        if chart == "auto" and min(b1, b2) < switch_tol:
            cur = "GHr"
        elif min(b1, b2) <= switch_tol:
            raise ValueError(
                "chart='u': the initial state is within switch_tol of a branch point of (2.8) "
                f"(|Gz^2 - C^2 r^2| or C^2 r^2 is {min(b1, b2):.3g} of Gz^2 + C^2 r^2 <= switch_tol = "
                f"{switch_tol:g}), where a sign delta1/delta2 may change; use chart='auto' or 'GHr', or a smaller "
                "switch_tol"
            )
        if chart == "auto" and (u_init[1] - u_init[0]) <= degenerate_tol * (u_init[2] - u_init[0]):
            cur = "GHr"  # a regular precession: (2.10) is singular, the (2.7)-averaged chart is not
    if cur == "GHr":
        ystate = np.array([Gz0, H0, r0])
    u1i, u2i, u3i = u_init
    if (u2i - u1i) <= degenerate_tol * (u3i - u1i) and cur == "u":
        raise ValueError(
            "chart='u': the initial state is (numerically) a regular precession, u1 = u2: the averaged system "
            "in (u1, u2, u3) is singular there (determinant of (2.10)); use chart='auto' or 'GHr'"
        )
    if (u3i - u2i) <= degenerate_tol * (u3i - u1i):
        raise ValueError("the initial state is a sleeping top on the separatrix (u2 = u3 = 1): "
                         "infinite nutation period, no average")
    if ev_triple(t0, np.array([Gz0, H0, r0])) <= 0.0:
        raise ValueError(f"the initial state has a (nearly) triple root u1 = u2 = u3 = 1 (root spread below "
                         f"{_TRIPLE_TOL:g}): a sleeping top at its stability limit C^2 r^2 = 4 A mgl, infinite "
                         "nutation period, no average")

    last_out = -math.inf
    for _ in range(max_segments):
        tev = None
        if te_all is not None:
            tev = te_all[(te_all >= tau) & (te_all > last_out)]
        if cur == "u":
            evs = [Event(ev_deg, "u1_eq_u2", True, -1.0, msg_deg),
                   Event(ev_sep, "separatrix", True, -1.0, msg_sep)]
            if chart in ("auto", "u"):
                evs.append(Event(ev_branch, "branch_point", True, -1.0, msg_branch))
            sol = integrate(rhs_u, (tau, t1), ystate, t_eval=tev, rtol=rtol, atol=atol, method=method,
                            events=evs, time_name="tau", args=(d1, d2))
            nfev += sol.nfev
            tt, yy = sol.tau, sol.y
            if tt.size:
                G = np.array(from_roots(top, yy[0], yy[1], yy[2], d1, d2))
                taus.append(tt)
                Us.append(yy)
                Gs.append(G.reshape(3, -1))
                D1s.append(np.full(tt.size, d1))
                D2s.append(np.full(tt.size, d2))
                CHs.append(np.zeros(tt.size))
                last_out = tt[-1]
            if sol.status == 1 and sol.event == "branch_point" and chart == "auto":
                te = float(sol.t_events["branch_point"][-1])
                ye = sol.y_events["branch_point"][-1]
                tau = te
                ystate = np.array(from_roots(top, ye[0], ye[1], ye[2], d1, d2), dtype=float)
                cur = "GHr"
                t_events["chart_switch"].append(te)
                continue
            status, message, event = sol.status, sol.message, sol.event
            if sol.event is not None:
                t_events[sol.event] = list(sol.t_events[sol.event])
            break
        # ---- chart GHr ----
        evs = [Event(ev_w, "delta1_flip", False, 0.0), Event(ev_r, "delta2_flip", False, 0.0),
               Event(ev_sep_g, "separatrix", True, -1.0, msg_sep),
               Event(ev_triple, "triple_root", True, -1.0, msg_triple)]
        if chart == "auto":
            evs.append(Event(ev_leave, "leave_branch", True, 1.0))
        sol = integrate(rhs_g, (tau, t1), ystate, t_eval=tev, rtol=rtol, atol=atol, method=method,
                        events=evs, time_name="tau")
        nfev += sol.nfev
        t_events["delta1_flip"].extend(sol.t_events["delta1_flip"].tolist())
        t_events["delta2_flip"].extend(sol.t_events["delta2_flip"].tolist())
        tt, yy = sol.tau, sol.y
        if tt.size:
            U = np.array([_roots_or_double(top, *yy[:, j]) for j in range(tt.size)]).T
            dd = np.array(deltas(top, yy[0], yy[2])).reshape(2, -1)
            taus.append(tt)
            Us.append(U)
            Gs.append(yy)
            D1s.append(dd[0])
            D2s.append(dd[1])
            CHs.append(np.ones(tt.size))
            last_out = tt[-1]
        if sol.status == 1 and sol.event == "leave_branch":
            te = float(sol.t_events["leave_branch"][-1])
            ye = sol.y_events["leave_branch"][-1]
            tau = te
            ystate = np.array(_roots_or_double(top, *ye), dtype=float)
            d1, d2 = deltas(top, ye[0], ye[2])
            cur = "u"
            t_events["chart_switch"].append(te)
            if (ystate[1] - ystate[0]) <= degenerate_tol * (ystate[2] - ystate[0]):
                status, event = 1, "u1_eq_u2"
                message = f"stopped by event 'u1_eq_u2' at tau = {te:.6g}: {msg_deg}"
                break
            continue
        status, message, event = sol.status, sol.message, sol.event
        if sol.event is not None:
            t_events[sol.event] = list(sol.t_events[sol.event])
        break
    else:
        status, message = -1, f"more than max_segments={max_segments} chart switches (chattering)"

    if taus:
        tau_a = np.concatenate(taus)
        U_a = np.concatenate(Us, axis=1)
        G_a = np.concatenate(Gs, axis=1)
        d1_a, d2_a, ch_a = np.concatenate(D1s), np.concatenate(D2s), np.concatenate(CHs)
        # drop duplicated switching points (kept once, from the later segment)
        keep = np.append(np.diff(tau_a) > 0.0, True)
        tau_a, U_a, G_a = tau_a[keep], U_a[:, keep], G_a[:, keep]
        d1_a, d2_a, ch_a = d1_a[keep], d2_a[keep], ch_a[keep]
    else:
        tau_a = np.empty(0)
        U_a = G_a = np.empty((3, 0))
        d1_a = d2_a = ch_a = np.empty(0)
    k2 = np.where(U_a[2] > U_a[0], (U_a[1] - U_a[0]) / np.where(U_a[2] > U_a[0], U_a[2] - U_a[0], 1.0), 0.0)
    data = {
        "u": U_a, "u1": U_a[0], "u2": U_a[1], "u3": U_a[2],
        "Gz": G_a[0], "H": G_a[1], "r": G_a[2], "k2": k2,
        "delta1": d1_a, "delta2": d2_a, "chart": ch_a,
    }
    tev_out = {k: np.asarray(v, dtype=float) for k, v in t_events.items()}
    return Solution("tau", tau_a, U_a, data, int(status), message, event, tev_out, {}, None, nfev)


# ==================================================================================================
# full equations (1.1)
# ==================================================================================================
def simulate(
    top: Top,
    torque: Torque,
    eps: float,
    state0: tuple[float, float, float, float, float, float],
    t_span: tuple[float, float],
    t_eval: Any = None,
    *,
    rtol: float = 1e-10,
    atol: float = 1e-12,
    method: str = "DOP853",
    dense_output: bool = False,
) -> Solution:
    r"""Integrate the full equations of motion (1.1) with the perturbing torque ``eps M``.

    Inside, the attitude is a unit quaternion (scalar first, the rotation of
    :func:`rigidbody.core.euler.dcm`), so nothing breaks at ``theta = 0`` or ``pi``; the state is
    ``(p, q, r, q0, q1, q2, q3)``:

    .. math::
        Ap' + (C-A)qr = mgl\,\gamma_2 + \varepsilon M_1,\quad Aq' + (A-C)pr = -mgl\,\gamma_1 +
        \varepsilon M_2,\quad Cr' = \varepsilon M_3,\quad \dot{\mathbf q} = \tfrac12\mathbf q\otimes(0,\omega),

    with the upward vertical in body axes ``gamma = (sin th sin phi, sin th cos phi, cos th)``. Euler
    angles are derived output (:func:`rigidbody.core.euler.euler_from_quat`; at ``sin theta = 0``:
    ``phi = 0``).

    Parameters
    ----------
    top : Top
    torque : Torque
        Must implement ``body_moments`` (:class:`LinearDrag`, :class:`ProportionalTorque`,
        :class:`VerticalPlaneTorque`).
    eps : float
        Small parameter, ``eps >= 0``.
    state0 : (p, q, r, phi, theta, psi)
        Initial angular velocity (body components) and Euler angles (rad).
    t_span : (t0, t1)
        Time interval (fast time ``t``; ``tau = eps t``).
    t_eval : array_like, optional
    rtol, atol, method, dense_output
        As in :func:`scipy.integrate.solve_ivp`.

    Returns
    -------
    rigidbody.core.ode.Solution
        ``t``, ``tau``, ``p``, ``q``, ``r``, ``phi``, ``theta``, ``psi``, ``u`` (= cos theta), ``Gz``,
        ``H`` (first integrals (1.2) along the motion: the slow variables), ``quat`` (4, n).
    """
    top = _check_top(top)
    torque = check_torque(torque)
    if isinstance(eps, bool) or not isinstance(eps, (int, float, np.floating, np.integer)):
        raise TypeError(f"eps must be a real number, got {type(eps).__name__}")
    eps = float(eps)
    if not math.isfinite(eps) or eps < 0.0:
        raise ValueError(f"eps must be finite and >= 0, got {eps!r}")
    t0, t1 = span(t_span, "t_span")
    rtol, atol = positive(rtol, "rtol"), positive(atol, "atol")
    try:
        p0, q0, r0, phi0, th0, psi0 = (float(x) for x in state0)
    except (TypeError, ValueError):
        raise ValueError(f"state0 must be (p, q, r, phi, theta, psi), got {state0!r}") from None
    quat0 = _euler.quat_from_euler(psi0, th0, phi0)
    y0 = np.array([p0, q0, r0, *np.asarray(quat0, dtype=float)])
    A, C, mgl = top.A, top.C, top.mgl
    body = torque.body_moments
    if eps > 0.0:
        body(top, p0, q0, r0, 0.0, 0.0, 1.0)  # fail early (TypeError) for torques without body moments

    def rhs(t: float, y: np.ndarray) -> list[float]:
        p, q, r, w, x, yq, z = y
        g1 = 2.0 * (x * z - w * yq)
        g2 = 2.0 * (yq * z + w * x)
        g3 = 1.0 - 2.0 * (x * x + yq * yq)
        if eps != 0.0:
            M1, M2, M3 = body(top, p, q, r, g1, g2, g3)
        else:
            M1 = M2 = M3 = 0.0
        return [
            ((A - C) * q * r + mgl * g2 + eps * M1) / A,
            ((C - A) * p * r - mgl * g1 + eps * M2) / A,
            eps * M3 / C,
            0.5 * (-x * p - yq * q - z * r),
            0.5 * (w * p + yq * r - z * q),
            0.5 * (w * q + z * p - x * r),
            0.5 * (w * r + x * q - yq * p),
        ]

    def fields(t: np.ndarray, y: np.ndarray) -> dict[str, np.ndarray]:
        quat = y[3:7] / np.linalg.norm(y[3:7], axis=0)
        psi, theta, phi = _euler.euler_from_quat(quat.T)
        w, x, yq, z = quat
        g1 = 2.0 * (x * z - w * yq)
        g2 = 2.0 * (yq * z + w * x)
        g3 = 1.0 - 2.0 * (x * x + yq * yq)
        p, q, r = y[0], y[1], y[2]
        return {
            "tau": eps * t, "p": p, "q": q, "r": r,
            "phi": np.asarray(phi), "theta": np.asarray(theta), "psi": np.asarray(psi),
            "u": g3, "Gz": A * (p * g1 + q * g2) + C * r * g3,
            "H": 0.5 * (A * (p * p + q * q) + C * r * r) + mgl * g3,
            "quat": quat,
        }

    return integrate(rhs, (t0, t1), y0, t_eval=t_eval, rtol=rtol, atol=atol, method=method,
                     dense_output=dense_output, fields=fields, time_name="t")
