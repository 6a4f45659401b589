r"""The charts of the averaged system (2.15) of the problem :mod:`._avgproblem`.

A chart gives, for one member (scalar functions on floats, for :func:`rigidbody.core.ode.integrate`) and for a
group of members (vectorised functions, for :func:`rigidbody.core.batch.integrate_batch`), the same things:
its start from the slow state ``(Gz, H, r)``, its right-hand side, its events, its tolerances, its output
fields and the slow state at the event that hands a member over to the other chart. The charts:

* :class:`UChart`: the paper's roots in ``(atanh u1, atanh u2, q)``; it hands over at a branch point of (2.8);
* :class:`PolarChart`: averaged (2.7) in ``(ln S, psi - n, kappa)``, ``n`` the integer nearest ``psi`` at the
  segment's start (so that ``psi - n`` is small when ``r`` is and its relative control keeps ``r``'s relative
  accuracy); it records the sign flips of ``delta1``, ``delta2`` and hands back once clear of the branch point;
* :class:`PlainChart`: averaged (2.7) in plain ``(Gz, H, r)`` for ``Gz = r = 0`` (no direction in the
  ``(Gz, C r)`` plane); one member at a time.

A stage outside a chart's domain (overflow, a root order violated, the engine refusing a state) gets NaN
rates, so that the integrator rejects the step.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from ..core.ode import Event
from . import _kernel as _k
from ._avgsetup import (
    FLIP_NOISE,
    MSG_BRANCH,
    MSG_DEG,
    MSG_SEP,
    MSG_TRIPLE,
    RTOL_FLOOR,
    ChartSetup,
    roots_or_double,
    spread_event,
)
from ._top import deltas

__all__ = ["Chart", "PlainChart", "PolarChart", "UChart"]

_SC, _AX = _k.SCALAR, _k.ARRAY
_NAN3 = (math.nan, math.nan, math.nan)
_MATH_ERRORS = (ZeroDivisionError, OverflowError, ValueError)


def _cached(fn: Callable[..., tuple[Any, ...]], scalar: bool, size: int, nargs: int) -> Callable[..., tuple[Any, ...]]:
    """``fn(t, y, *args)`` (``nargs`` arguments, 1 or 2) evaluated once per state: the integrators call a chart's
    events in turn on the same state, and one decoding serves them all. Scalar states are keyed by value (a
    state outside the chart's domain gets NaN), arrays by identity (the cache holds them, so their ids cannot be
    reused while cached). The signatures are spelled out: forwarding ``*args`` would cost more than the cache
    saves on one run."""
    cache: list[Any] = [None, None, None]
    nan = (math.nan,) * size

    def scalar_get(key: tuple[Any, ...], t: Any, y: Any, *args: Any) -> tuple[Any, ...]:
        try:
            cache[2] = fn(t, y, *args)
        except _MATH_ERRORS:
            cache[2] = nan
        cache[0] = key
        return cache[2]

    def array_get(t: Any, y: Any, *args: Any) -> tuple[Any, ...]:
        cache[:] = [t, y, fn(t, y, *args)]
        return cache[2]

    if scalar and nargs == 1:
        def get1(t: Any, y: Any, a: Any) -> tuple[Any, ...]:
            key = (y[0], y[1], y[2], a)
            return cache[2] if cache[0] == key else scalar_get(key, t, y, a)

        return get1
    if scalar:
        def get2(t: Any, y: Any, a: Any, b: Any) -> tuple[Any, ...]:
            key = (y[0], y[1], y[2], a, b)
            return cache[2] if cache[0] == key else scalar_get(key, t, y, a, b)

        return get2

    def get_array(t: Any, y: Any, *args: Any) -> tuple[Any, ...]:
        return cache[2] if cache[0] is t and cache[1] is y else array_get(t, y, *args)

    return get_array


def _event(values: Callable[..., tuple[Any, ...]], k: int, nargs: int, name: str, terminal: bool, direction: float,
           message: str = "") -> Event:
    """The ``k``-th of the cached event values as an :class:`Event` of ``nargs`` (1 or 2) arguments."""
    if nargs == 1:
        def ev1(t: Any, y: Any, a: Any) -> Any:
            return values(t, y, a)[k]

        return Event(ev1, name, terminal, direction, message)

    def ev2(t: Any, y: Any, a: Any, b: Any) -> Any:
        return values(t, y, a, b)[k]

    return Event(ev2, name, terminal, direction, message)


class Chart:
    """What the problem asks of a chart (see the module's docstring); subclasses fill it in."""

    #: value of the output field ``chart``
    code = 0.0
    #: the terminal event that hands a member over to the other chart
    switch = ""
    #: non-terminal events whose times are recorded for every member
    recorded: tuple[str, ...] = ()
    #: whether a group of members can be integrated together
    vector = True

    def __init__(self, st: ChartSetup) -> None:
        self.st = st
        self._built: dict[bool, tuple[Callable[..., Any], list[Event]]] = {}

    def functions(self, scalar: bool) -> tuple[Callable[..., Any], list[Event]]:
        """The right-hand side and the events, on floats (``scalar``) or on arrays of members (built once)."""
        if scalar not in self._built:
            self._built[scalar] = self._functions(scalar)
        return self._built[scalar]

    def _functions(self, scalar: bool) -> tuple[Callable[..., Any], list[Event]]:
        raise NotImplementedError

    def start(self, xp: Any, Gz: Any, H: Any, r: Any, d1: Any, d2: Any) -> tuple[Any, tuple[Any, ...]]:
        """The chart's coordinates (shape ``(3,)`` or ``(m, 3)``) and the per-member arguments."""
        raise NotImplementedError

    def tolerances(self, y0: np.ndarray, engine: str) -> tuple[Any, Any]:
        """``(rtol, atol)`` for the start ``y0`` (shape ``(3,)`` or ``(m, 3)``)."""
        return RTOL_FLOOR, self.st.rtol

    def fields(self, y: np.ndarray, args: tuple[Any, ...]) -> dict[str, np.ndarray]:
        """The output fields of states ``y`` of shape ``(3, n)`` or ``(m, 3, n)``."""
        raise NotImplementedError

    def exit_state(self, xp: Any, y: tuple[Any, Any, Any], args: tuple[Any, ...]) -> tuple[Any, Any, Any]:
        """(Gz, H, r) at the switching state(s) of chart coordinates ``y``: floats (``xp`` SCALAR) or arrays over
        members (``xp`` ARRAY; ``args`` for those members)."""
        raise NotImplementedError


class UChart(Chart):
    """The paper's roots, ``(atanh u1, atanh u2, q)``; signs ``delta1, delta2`` ride along as arguments."""

    code = 0.0
    switch = "branch_point"

    def _functions(self, scalar: bool) -> tuple[Callable[..., Any], list[Event]]:
        st = self.st
        if scalar:
            kd, drag_rates, chart_rates = st.kd, _k.u_drag_rates, st.rhs_x

            def rhs(tau: Any, y: Any, d1: Any, d2: Any) -> Any:
                x1, x2, th = y
                if not x1 < x2:
                    return _NAN3
                try:
                    if kd is not None:
                        return drag_rates(_SC, kd, x1, x2, th, d1, d2)
                    return chart_rates(_SC, x1, x2, th, d1, d2)
                except _MATH_ERRORS:
                    return _NAN3

            values = _cached(lambda t, y, d1, d2: st.u_events(_SC, y[0], y[1], y[2], d1), True, 3, 2)
        else:
            def rhs(tau: Any, y: Any, d1: Any, d2: Any) -> Any:
                x1, x2, th = y[:, 0], y[:, 1], y[:, 2]
                d = np.stack(st.rhs_x(_AX, x1, x2, th, d1, d2), axis=1)
                bad = ~(x1 < x2)
                if bad.any():
                    d[bad] = np.nan
                return d

            values = _cached(lambda t, y, d1, d2: st.u_events(_AX, y[:, 0], y[:, 1], y[:, 2], d1), False, 3, 2)
        evs = [_event(values, 0, 2, "u1_eq_u2", True, -1.0, MSG_DEG),
               _event(values, 1, 2, "separatrix", True, -1.0, MSG_SEP)]
        if st.chart in ("auto", "u"):
            evs.append(_event(values, 2, 2, "branch_point", True, -1.0, MSG_BRANCH))
        return rhs, evs

    def start(self, xp: Any, Gz: Any, H: Any, r: Any, d1: Any, d2: Any) -> tuple[Any, tuple[Any, ...]]:
        x = self.st.slow_to_x(xp, Gz, H, r, *self.st.roots_g(xp, Gz, H, r))
        return (np.array(x) if xp is _SC else np.stack(x, axis=1)), (d1, d2)

    def tolerances(self, y0: np.ndarray, engine: str) -> tuple[Any, Any]:
        return RTOL_FLOOR, (np.full(3, self.st.rtol) if y0.ndim == 1 else self.st.rtol)

    def fields(self, y: np.ndarray, args: tuple[Any, ...]) -> dict[str, np.ndarray]:
        f = self.st.fields_x(y, *args)
        f["chart"] = np.zeros(np.shape(f["Gz"]))
        return f

    def exit_state(self, xp: Any, y: tuple[Any, Any, Any], args: tuple[Any, ...]) -> tuple[Any, Any, Any]:
        st = self.st
        s = _k.decode_u(xp, st.A, st.C, st.mgl, *y, *args)
        return s.Gz, s.H, s.r


class PolarChart(Chart):
    """Averaged (2.7) in ``(ln S, psi - n, kappa)``; the offset ``n`` rides along as an argument."""

    code = 1.0
    switch = "leave_branch"
    recorded = ("delta1_flip", "delta2_flip")

    def _functions(self, scalar: bool) -> tuple[Callable[..., Any], list[Event]]:
        st = self.st
        xp = _SC if scalar else _AX

        def cols(y: Any) -> tuple[Any, Any, Any]:
            return (y[0], y[1], y[2]) if scalar else (y[:, 0], y[:, 1], y[:, 2])

        if scalar:
            def rhs(tau: Any, y: Any, n_off: Any) -> Any:
                sig, psi, kap = y
                try:
                    return list(st.rhs_p(_SC, sig, psi + n_off, kap))
                except _MATH_ERRORS:
                    return _NAN3
        else:
            def rhs(tau: Any, y: Any, n_off: Any) -> Any:
                return np.stack(st.rhs_p(_AX, y[:, 0], y[:, 1] + n_off, y[:, 2]), axis=1)

        if scalar:
            def ev_w(t: Any, y: Any, n_off: Any) -> Any:
                return st.ev_w(_SC, y[1] + n_off)

            def ev_r(t: Any, y: Any, n_off: Any) -> Any:
                return st.ev_r(_SC, y[1] + n_off)

            def ev_leave(t: Any, y: Any, n_off: Any) -> Any:
                return st.ev_leave(_SC, y[1] + n_off)
        else:
            def ev_w(t: Any, y: Any, n_off: Any) -> Any:
                return st.ev_w(_AX, y[:, 1] + n_off)

            def ev_r(t: Any, y: Any, n_off: Any) -> Any:
                return st.ev_r(_AX, y[:, 1] + n_off)

            def ev_leave(t: Any, y: Any, n_off: Any) -> Any:
                return st.ev_leave(_AX, y[:, 1] + n_off)

        def roots(t: Any, y: Any, n_off: Any) -> tuple[Any, ...]:
            sig, psi, kap = cols(y)
            return st.ev_roots_g(xp, sig, psi + n_off, kap)

        rt = _cached(roots, scalar, 2, 1)
        evs = [Event(ev_w, "delta1_flip", False, 0.0), Event(ev_r, "delta2_flip", False, 0.0),
               _event(rt, 0, 1, "separatrix", True, -1.0, MSG_SEP),
               _event(rt, 1, 1, "triple_root", True, -1.0, MSG_TRIPLE)]
        if st.chart == "auto":
            evs.append(Event(ev_leave, "leave_branch", True, 1.0))
        return rhs, evs

    def start(self, xp: Any, Gz: Any, H: Any, r: Any, d1: Any, d2: Any) -> tuple[Any, tuple[Any, ...]]:
        sig, psi, kap = _k.slow_to_polar(xp, self.st.C, Gz, H, r, self.st.mgl)
        n_off = xp.rint(psi)
        y = (sig, psi - n_off, kap)
        return (np.array(y, dtype=float) if xp is _SC else np.stack(y, axis=1)), (n_off,)

    def tolerances(self, y0: np.ndarray, engine: str) -> tuple[Any, Any]:
        return self.st.polar_tolerances(y0[..., 2], engine)

    def fields(self, y: np.ndarray, args: tuple[Any, ...]) -> dict[str, np.ndarray]:
        off = np.zeros(y.shape[:-1])
        off[..., 1] = args[0]
        f = self.st.fields_p(y + off[..., None])
        f["chart"] = np.ones(np.shape(f["Gz"]))
        return f

    def exit_state(self, xp: Any, y: tuple[Any, Any, Any], args: tuple[Any, ...]) -> tuple[Any, Any, Any]:
        st = self.st
        g = _k.decode_g(xp, st.A, st.C, st.mgl, y[0], y[1] + args[0], y[2])
        return g.Gz, g.H, g.r


class PlainChart(PolarChart):
    """Averaged (2.7) in plain ``(Gz, H, r)``, for a segment starting at ``Gz = r = 0``; one member at a time."""

    vector = False

    def _functions(self, scalar: bool) -> tuple[Callable[..., Any], list[Event]]:
        st, C = self.st, self.st.C

        def rhs(tau: float, y: Any) -> list[float]:
            return list(st.engine_ghr(float(y[0]), float(y[1]), float(y[2])))

        def ev_w(tau: float, y: Any) -> float:
            g2, c2 = float(y[0] * y[0]), float((C * y[2]) ** 2)
            w = g2 - c2
            return w if abs(w) > FLIP_NOISE * (g2 + c2) else 1e-300

        def ev_r(tau: float, y: Any) -> float:
            return float(y[2]) if y[2] != 0.0 else 1e-300

        def ev_sep(tau: float, y: Any) -> float:
            try:
                u1, u2, u3 = roots_or_double(st.top, float(y[0]), float(y[1]), float(y[2]))
            except ValueError:
                return -1.0
            return (u3 - u2) / (u3 - u1) - st.deg if u3 - u1 > 0.0 else -1.0

        def ev_triple(tau: float, y: Any) -> float:
            return spread_event(st.top, float(y[0]), float(y[1]), float(y[2]))

        def ev_leave(tau: float, y: Any) -> float:
            s = float(y[0] * y[0] + (C * y[2]) ** 2)
            if s == 0.0:
                return -1.0
            return min(abs(float(y[0] * y[0] - (C * y[2]) ** 2)) / s, float((C * y[2]) ** 2) / s) - 2.0 * st.sw

        evs = [Event(ev_w, "delta1_flip", False, 0.0), Event(ev_r, "delta2_flip", False, 0.0),
               Event(ev_sep, "separatrix", True, -1.0, MSG_SEP),
               Event(ev_triple, "triple_root", True, -1.0, MSG_TRIPLE)]
        if st.chart == "auto":
            evs.append(Event(ev_leave, "leave_branch", True, 1.0))
        return rhs, evs

    def start(self, xp: Any, Gz: Any, H: Any, r: Any, d1: Any, d2: Any) -> tuple[Any, tuple[Any, ...]]:
        return np.array([Gz, H, r], dtype=float), ()

    def tolerances(self, y0: np.ndarray, engine: str) -> tuple[Any, Any]:
        return self.st.rtol, self.st.atol

    def fields(self, y: np.ndarray, args: tuple[Any, ...]) -> dict[str, np.ndarray]:
        U = np.array([roots_or_double(self.st.top, *y[:, j]) for j in range(y.shape[1])]).reshape(-1, 3).T
        dd = np.array(deltas(self.st.top, y[0], y[2])).reshape(2, -1)
        d31 = U[2] - U[0]
        return {"u1": U[0], "u2": U[1], "u3": U[2], "Gz": y[0], "H": y[1], "r": y[2],
                "k2": np.where(d31 > 0, (U[1] - U[0]) / np.where(d31 > 0, d31, 1.0), 0.0),
                "delta1": dd[0], "delta2": dd[1], "chart": np.ones(y.shape[1])}

    def exit_state(self, xp: Any, y: tuple[Any, Any, Any], args: tuple[Any, ...]) -> tuple[Any, Any, Any]:
        return y
