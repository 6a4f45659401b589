r"""The averaged evolution of one kind of motion with a torque object (restartable in the other kind).

The integrator evolves :math:`(\ln G, \ln(k^2 + c), \mathbf n[, \nu])` (the direction of :math:`\mathbf G` as the
angles :math:`(\delta, \lambda)` or the unit vector :math:`\mathbf n`, switched by charts) with
:math:`d(G\mathbf n)/d\tau = \langle C\mathbf M\rangle` and the :math:`k^2` rate of :mod:`._engine`; with
:math:`\varepsilon > 0` it checks the drift per Euler--Poinsot period (event) and the resonances between the
precession and the Euler--Poinsot frequency (predicted jumps, after the integration).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from typing import Any

import numpy as np
from scipy import special

from ..core.ode import Event, Solution
from ..core.validate import RESULT_ERRORS
from . import _kernel as _k
from ._engine import Averager
from ._model import Body, Orbit, labelled
from ._output import PiecewiseDense, finish_output, lam_unwrapped
from ._protocol import Misfire
from ._resonance import resonance_crossings
from ._spin import K2_SPIN_CAP, nutation_frequency
from ._state import Mean, State
from ._stops import drift_refusal, slow_drift, stop_message

__all__ = ["KindRun", "RunOptions", "Setup", "finish_kind", "rotation_number"]


# --------------------------------------------------------------------------------------------------
# any torque: the averaged evolution of one kind of motion (restartable in the other kind)
# --------------------------------------------------------------------------------------------------
@dataclass(kw_only=True)
class RunOptions:
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
        return {f.name: getattr(self, f.name) for f in fields(RunOptions)}


@dataclass(kw_only=True)
class Setup(RunOptions):
    """What a run with a torque object keeps fixed: the options, the averaged torque, where it stops."""

    averager: Averager
    k2_max: float
    spin_cap: float = K2_SPIN_CAP


@dataclass
class _Segment:
    """An averaged run in one kind of motion: its solution (rows G, k2, n[, nu] of the integrated state, and a dense
    output of the same rows) and how it was made."""

    res: Solution
    setup: Setup
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


def _state_of(setup: Setup, kind: str, sigma: int, tau: float, y: np.ndarray, tau0: float, nu0: float) -> State:
    eps = setup.eps
    k2 = min(max(float(y[1]), 0.0), 1.0 - 1e-15)
    n = np.asarray(y[2:5], dtype=float)
    if eps == 0.0:
        nu = None
    elif setup.orbit.e == 0.0:
        nu = (tau - tau0) / eps + nu0
    else:
        nu = float(y[5])
    return State(setup.body, kind, sigma, float(y[0]), k2, n / math.sqrt(float(n @ n)), nu, setup.orbit)


def _slow_drift(setup: Setup, st: State, m: Mean) -> float:
    r"""Relative change of the slow variables in one Euler--Poinsot period, :math:`\varepsilon^2P(\ldots)`."""
    freq = nutation_frequency(st.a, st.G, min(st.k2, setup.spin_cap))  # next to the separatrix: see K2_SPIN_CAP
    dG = float(st.n @ m.L)
    return slow_drift(setup.eps, freq, st.G, st.T, dG, m.dT, float(np.linalg.norm(m.L - dG * st.n)) / st.G)


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
        lam_all = lam_unwrapped(tt[order], yy[2:5][:, order], self.lam_start)
        pos = np.empty_like(order)
        pos[order] = np.arange(order.size)
        return lam_all[pos[steps.size:]]

    def lam_end(self) -> float:
        return float(self.lam(self.raw.time[-1:])[0])


def _k2_floor(rtol: float) -> float:
    """The c of the engine's coordinate ln(k2 + c): where the rounding of its dk2, ~10 eps_mach k (measured: 2e-12
    relative at k2 = 1e-8), is rtol of dk2 ~ k^2 relative, (10 eps_mach / (2 rtol))^2 (1.2e-10 at rtol 1e-10); the
    largest noise of d ln(k2 + c)/dtau, at k2 = c, is then about rtol."""
    return (10.0 * _k.RTOL_FLOOR / 100.0 / (2.0 * rtol)) ** 2


def _axisymmetric(av: Averager, st: State, tol: float = 1e-9) -> bool:
    """Whether the averaged torque is symmetric about the orbit normal x3 (turning G about x3 turns its mean
    torque alike and leaves dT, dk2 unchanged), probed at the state and at a generic direction, two angles each."""
    sd = math.sin(1.1)
    for n in (st.n, np.array([sd * math.cos(0.7), sd * math.sin(0.7), math.cos(1.1)])):
        m0 = av.mean(State(st.body, st.kind, st.sigma, st.G, st.k2, n, st.nu, st.orbit))
        size = float(np.abs(m0.L).max()) + abs(m0.dT) + abs(m0.dk2) + 1e-300
        for alpha in (1.0, 2.5):
            c, s = math.cos(alpha), math.sin(alpha)
            R = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
            m = av.mean(State(st.body, st.kind, st.sigma, st.G, st.k2, R @ n, st.nu, st.orbit))
            if (float(np.abs(m.L - R @ m0.L).max()) > tol * size or abs(m.dT - m0.dT) > tol * size
                    or abs(m.dk2 - m0.dk2) > tol * size):
                return False
    return True


def _mean_functions(setup: Setup, kind: str, sigma: int, z: float, c: float, tau0: float, nu0: float, inu: int,
                    misfire: Misfire) -> tuple[Any, Any]:
    """The averaged torque at a state of either chart of :class:`KindRun` (``mean_at``, on floats, the last
    call remembered) and as a (State, Mean) pair (``pair``, for the drift event)."""
    exp, sqrt, sin, cos = math.exp, math.sqrt, math.sin, math.cos
    eps, orb, body, av = setup.eps, setup.orbit, setup.body, setup.averager
    ecc = eps > 0.0 and orb.e != 0.0
    ie = 1.0 / eps if eps > 0.0 else 0.0
    k2_top = 1.0 - 1e-15

    def nu_of(tau: float, y: Any, i: int) -> float | None:
        if eps == 0.0:
            return None
        if ecc:
            return float(y[i])
        return (tau - tau0) * ie + nu0

    fast = av.fast(kind, sigma, eps > 0.0)  # the engine alone on floats, or None (closed forms: state objects)
    memo: list[Any] = [None, None, None, None]  # the last (chart, tau, y, means): the drift event reuses them

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
                m = av.mean(State(body, kind, sigma, G, k2, np.array([n1, n2, n3]), nu, orb))
                L1, L2, L3 = (float(v) for v in m.L)
                dT, dk2 = m.dT, m.dk2
        except RESULT_ERRORS as exc:  # NaN rates: the step fails here, the run ends with misfire's message
            misfire.note(tau, exc)
            L1 = L2 = L3 = dT = dk2 = math.nan
        out = (G, k2, n1, n2, n3, nu, L1, L2, L3, dT, dk2)
        memo[0], memo[1], memo[2], memo[3] = chart, tau, list(yl), out
        return out

    def pair(tau: float, y: Any, chart: str) -> tuple[State, Mean]:
        G, k2, n1, n2, n3, nu, L1, L2, L3, dT, dk2 = mean_at(tau, y, chart)
        return (State(body, kind, sigma, G, k2, np.array([n1, n2, n3]), nu, orb),
                Mean(np.array([L1, L2, L3]), dT, dk2))

    return mean_at, pair


class KindRun:
    """The averaged system of a torque object in one kind of motion, from (G0, k2_0, n0) at ``tau0`` (true anomaly
    ``nu0`` there, continuous lambda ``lam0``), integrated chart piece by chart piece: :meth:`piece` gives the
    next piece's right-hand side, start, tolerances and events, :meth:`add` takes its result, :meth:`switch` moves
    to the other chart at a chart event, :meth:`segment` joins the pieces. A crossing into the other kind restarts
    in a new one with G, T, n continuous (k2 from (5) of the other kind).

    As for a drag tensor (:mod:`._kernel`) the state is ``(ln G, ln k^2, delta, lambda[, nu])`` (``nu`` on an
    eccentric orbit with eps > 0): ``rtol`` is the relative accuracy of G and k^2 however far they decay, and
    lambda, a state, is continuous through any number of turns. ``d ln k^2/dtau = (dk^2/dtau)/k^2`` is finite as
    k -> 0 (the engine's dk^2 is O(k^2) there, without cancellation); a start at k^2 = 0 exactly stays there (an
    equilibrium of every averaged system: the phase-dependent part of the motion vanishes), carried by the factor
    z = 0. The polar angles are singular at the poles sin(delta) = 0, where a torque may turn G (the drag tensor's
    gravity gradient does not): there (sin(delta) < _SIN_OFF, until it exceeds _SIN_ON) the direction is the unit
    vector n instead. A start whose slow variables drift too fast for ``eps`` raises ValueError."""

    def __init__(self, setup: Setup, kind: str, sigma: int, tau0: float, G0: float, k2_0: float, n0: Any,
                 nu0: float, lam0: float) -> None:
        eps, orb, body = setup.eps, setup.orbit, setup.body
        self.setup, self.kind, self.sigma, self.tau0, self.nu0 = setup, kind, sigma, float(tau0), nu0
        self.ecc = ecc = eps > 0.0 and orb.e != 0.0
        av = setup.averager
        nn = np.asarray(n0, dtype=float)
        nn = nn / math.sqrt(float(nn @ nn))
        st0 = State(body, kind, sigma, G0, min(k2_0, 1.0 - 1e-15), nn, None if eps == 0.0 else nu0, orb)
        av.calibrate(st0)
        # k2 enters as s = ln(k2 + c): c = 0 with closed forms only (a start at k2 = 0 exactly then keeps z = 0); with
        # the engine, whose dk2 carries rounding ~eps_mach k (zero-mean O(k) products, see _engine) against a size
        # O(k^2), c = _k2_floor(rtol): the relative accuracy rtol of k2 down to where the engine has it, absolute below
        self.c = c = 0.0 if av.rest is None else _k2_floor(setup.rtol)
        self.z = z = 1.0 if k2_0 > 0.0 or c > 0.0 else 0.0
        ie = 1.0 / eps if eps > 0.0 else 0.0
        inu = 4  # index of nu in the angle chart's state (5 in the vector chart's)
        self.misfire = Misfire()  # a torque that misbehaves part-way ends the run with a status naming it
        mean_at, self.pair = _mean_functions(setup, kind, sigma, z, c, self.tau0, nu0, inu, self.misfire)
        self.rhs = dict(zip(("angles", "vector"), _rhs_pair(mean_at, z, c, orb, ie if ecc else None, inu)))
        y0: list[float] = [math.log(G0), math.log(k2_0 + c) if z else 0.0, *(float(v) for v in nn)]
        if ecc:
            y0.append(nu0)
        # the polar angles pay where G turns about x3: in the orbit-averaged limit of a torque symmetric about the
        # orbit normal (the gravity gradient, drag, ...) their rates do not depend on lambda, which drifts as one
        # smooth state however many turns it makes; elsewhere (a field fixed in space, the orbital motion resolved)
        # the unit vector follows the turns at least as cheaply (measured), so it is the chart throughout
        self.angles = eps == 0.0 and _axisymmetric(av, st0)
        self.chart = "angles" if self.angles and math.hypot(nn[0], nn[1]) >= _SIN_ON else "vector"
        if self.chart == "angles":
            y0[2:] = [math.acos(max(-1.0, min(1.0, float(nn[2])))), lam0]
        self.y0, self.lam_s = y0, lam0
        _check_drift(setup, st0, av)
        self.common_events = _common_events(setup, labelled(body, kind), z, c, ie)
        self.pieces: list[_Chart] = []

    def events(self) -> list[Event]:
        """The events of the current chart: the common stops, the drift per period, the chart switch."""
        setup, chart, pair = self.setup, self.chart, self.pair
        evs = list(self.common_events)
        if setup.eps > 0.0 and setup.drift_tol is not None:
            tol = setup.drift_tol

            def drift(t: float, y: Any) -> float:
                st, m = pair(t, y, chart)
                return _slow_drift(setup, st, m) - tol

            evs.append(Event(drift, "fast_drift", True, 1.0, stop_message("fast_drift", drift_tol=tol)))
        if chart == "angles":
            evs.append(Event(lambda t, y: math.sin(y[2]) - _SIN_OFF, "chart", True, -1.0))
        elif self.angles:
            evs.append(Event(lambda t, y: math.hypot(y[2], y[3]) / math.sqrt(y[2] ** 2 + y[3] ** 2 + y[4] ** 2)
                             - _SIN_ON, "chart", True, 1.0))
        return evs

    def piece(self) -> tuple[Any, list[float], Any, Any, list[Event]]:
        """The next chart piece: right-hand side (on floats), start, ``rtol``, ``atol`` and events (``rtol`` at the
        floor of solve_ivp's methods other than DOP853)."""
        rt: Any
        rt, at = _tolerances(self.setup.rtol, self.chart, self.ecc)
        if self.setup.method != "DOP853":
            rt = _k.RTOL_FLOOR
        return self.rhs[self.chart], self.y0, rt, at, self.events()

    def add(self, raw: Solution) -> bool:
        """Take a chart piece's result (a torque's failure named in its message); whether the segment goes on in
        the other chart (a chart event, below :data:`_MAX_CHARTS` pieces)."""
        self.misfire.settle(raw)
        self.pieces.append(_Chart(self.chart, raw, self.z, self.c, self.ecc, self.lam_s))
        return raw.event == "chart" and len(self.pieces) < _MAX_CHARTS

    def switch(self) -> None:
        """Continue in the other chart from the chart event."""
        self.chart, self.y0, _, self.lam_s = _switch(self.pieces[-1], self.ecc)

    def segment(self) -> _Segment:
        """The segment of this kind of motion, its chart pieces joined."""
        return _Segment(_join_charts(self.pieces), self.setup, self.kind, self.sigma, self.tau0, self.nu0, self.pieces)


def _rhs_pair(mean_at: Any, z: float, c: float, orb: Orbit, ie: float | None, inu: int) -> tuple[Any, Any]:
    """The right-hand sides in the angle chart ``(ln G, s, delta, lambda[, nu])`` and the vector chart
    ``(ln G, s, n[, nu])`` from ``mean_at``; ``ie`` = 1/eps on an eccentric orbit (nu a state), else None."""
    sin, cos = math.sin, math.cos

    def rhs_angles(tau: float, y: Any) -> list[float]:
        G, k2, _, _, _, _, L1, L2, L3, _, dk2 = mean_at(tau, y, "angles")
        d, la = y[2], y[3]
        sd, cd, sl, cl = sin(d), cos(d), sin(la), cos(la)
        iG = 1.0 / G
        out = [(sd * (cl * L1 + sl * L2) + cd * L3) * iG, dk2 / (k2 + c) if z else 0.0,
               (cd * (cl * L1 + sl * L2) - sd * L3) * iG, (cl * L2 - sl * L1) * iG / sd]
        if ie is not None:
            out.append(orb.nu_rate(float(y[inu])) * ie)
        return out

    def rhs_vector(tau: float, y: Any) -> list[float]:
        G, k2, n1, n2, n3, _, L1, L2, L3, _, dk2 = mean_at(tau, y, "vector")
        dG = n1 * L1 + n2 * L2 + n3 * L3
        iG = 1.0 / G
        out = [dG * iG, dk2 / (k2 + c) if z else 0.0, (L1 - dG * n1) * iG, (L2 - dG * n2) * iG,
               (L3 - dG * n3) * iG]
        if ie is not None:
            out.append(orb.nu_rate(float(y[inu + 1])) * ie)
        return out

    return rhs_angles, rhs_vector


def _check_drift(setup: Setup, st0: State, av: Averager) -> None:
    """Refuse a start where the slow variables change by more than ``drift_tol`` in one Euler--Poinsot period."""
    eps = setup.eps
    if eps > 0.0 and setup.drift_tol is not None and (d0 := _slow_drift(setup, st0, av.mean(st0))) > setup.drift_tol:
        raise ValueError(drift_refusal(eps, d0, setup.drift_tol))


def _common_events(setup: Setup, a: tuple[float, float, float], z: float, c: float, ie: float) -> list[Event]:
    """The stops of every chart: the separatrix (k2_max) and, with eps > 0, the rotation speed."""
    exp = math.exp
    lnk_stop = math.log(setup.k2_max + c)
    events = [
        Event((lambda t, y: y[1] - lnk_stop) if z else (lambda t, y: -1.0), "separatrix", True, 1.0,
              stop_message("separatrix", k2_max=setup.k2_max)),
    ]
    if setup.eps > 0.0:
        cap, ratio = setup.spin_cap, setup.min_spin_ratio
        events.append(Event(lambda t, y: nutation_frequency(a, exp(y[0]), min(max(z * exp(y[1]) - c, 0.0), cap)) * ie
                            - ratio, "slow_rotation", True, -1.0,
                            stop_message("slow_rotation", min_spin_ratio=ratio)))
    return events


def _switch(piece: _Chart, ecc: bool) -> tuple[str, list[float], float, float]:
    """The other chart at a chart event: its name, its state (the same G, k2, direction and nu), the time, and the
    continuous lambda there."""
    raw = piece.raw
    t_s = float(raw.t_events["chart"][-1])
    lam_s = piece.lam_end()
    yc = piece.common(raw.y[:, -1])
    n = yc[2:5]
    chart = "vector" if piece.chart == "angles" else "angles"
    y0 = [float(raw.y[0, -1]), float(raw.y[1, -1])]
    if chart == "angles":
        lam_n = math.atan2(n[1], n[0])
        lam_n += 2.0 * math.pi * round((lam_s - lam_n) / (2.0 * math.pi))  # the branch of the continuous lambda
        y0 += [math.acos(max(-1.0, min(1.0, float(n[2])))), lam_n]
    else:
        y0 += [float(v) for v in n]
    if ecc:
        y0.append(float(yc[5]))
    return chart, y0, t_s, lam_s


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
    dense = PiecewiseDense([p.raw.time[0] for p in pieces], [lambda t, p=p: p.common(p.raw.sol(t)) for p in pieces],
                            n_c)
    return Solution.build(producer="euler_poinsot.averaged", time_name=last.time_name, time=np.concatenate(times),
                          y=np.concatenate(ys, axis=1), status=status, message=message, event=event, t_events=te,
                          y_events=ye, dense=dense, nfev=sum(p.raw.nfev for p in pieces), last_step=last.last_step)


def rotation_number(body: Body, kind: str, k2: Any) -> Any:
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
    a1, a2, a3 = labelled(body, kind)
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
    body, kind, a = setup.body, seg.kind, labelled(setup.body, seg.kind)
    # within 1 - k2 < 0.01 of the separatrix the rotation number grows without bound (like the period) and the
    # passage there is the separatrix crossing's business, not a resonance's: the search stops at K2_SPIN_CAP
    return resonance_crossings(
        seg.res, lambda k2: rotation_number(body, kind, k2),
        lambda t, y: _state_of(setup, kind, seg.sigma, t, y, seg.tau0, seg.nu0),
        lambda G, k2: 2.0 * math.pi / nutation_frequency(a, G, k2), setup.averager, setup.eps,
        setup.resonance_tol, K2_SPIN_CAP)  # type: ignore[arg-type]  # called only with resonance_tol set


def _slow_fields(A: tuple[float, float, float], y: np.ndarray, nvec: Any, nu: Any) -> dict[str, np.ndarray]:
    """G, T (from (5) inverted, labelled moments A), k2, delta, n and nu of raw states y = (G, k2, ...)."""
    G = y[0]
    k2 = np.clip(y[1], 0.0, 1.0)
    n = nvec(y) if y.shape[1] else np.empty((3, 0))
    T = 0.5 * G**2 * _k.s_over_r(A, k2)
    return {"G": G, "T": T, "k2": k2, "delta": np.arccos(np.clip(n[2], -1.0, 1.0)), "n": n, "nu": nu}


def finish_kind(seg: _Segment, tau_eval: Any, lam0: float) -> Solution:
    """Output fields of a segment (G, T, k2, delta, lam, nu, n), the quadrature report and the resonance check."""
    setup, res = seg.setup, seg.res
    A = labelled(setup.body, seg.kind)
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
        out = _slow_fields(A, y, nvec, nu)
        out["kind"], out["sigma"] = np.full(tau.shape, seg.kind), np.full(tau.shape, seg.sigma)
        return out

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
        res = Solution.build(producer="euler_poinsot.averaged", time_name=res.time_name, time=tcut, y=ycut,
                             status=status, message=message, event=event, t_events=res.t_events,
                             y_events=res.y_events, dense=res.sol, nfev=res.nfev)
        resonances = [r for r in resonances if r["tau"] <= cut["tau"]]
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
    return finish_output(res, tau_eval, make_fields, lam0, nvec, lambda tau, y: seg.lam(tau),
                         producer="euler_poinsot.averaged", quad_error=qerr, resonances=resonances)


#: a slow state and its means in a torque object's right-hand side: G, k2, n1, n2, n3, nu, L1, L2, L3, dT, dk2
_Slow = tuple[float, float, float, float, float, Any, float, float, float, float, float]
