r"""The averaged system (2.15) integrated through its charts: one run, or a batch of runs together.

The two charts of :func:`averaged` (the paper's roots ``u`` and the original slow variables ``(Gz, H, r)``)
are integrated in the coordinates of :mod:`rigidbody.lagrange._kernel` (the roots through their log-gaps,
``(Gz, C r)`` in log-polar form), with absolute error control on those coordinates, i.e. relative error
control on every decaying quantity. A single run uses :func:`rigidbody.core.ode.integrate` with
``math``-scalar right-hand sides; a batch runs :func:`rigidbody.core.batch.integrate_batch` chart by chart
(the members in the u chart together, then those in the GHr chart, ...), each member switching charts,
flipping signs and ending on its own events.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from ..core.ode import Event, Solution, integrate
from ..core.validate import positive, span
from . import _kernel as _k
from ._averaging import averaged_slow_rates
from ._top import Top, _check_top, deltas, roots, vieta
from ._torques import LinearDrag, Torque, check_torque

__all__ = ["averaged"]

_CHARTS = ("auto", "u", "GHr")
#: spread of the three roots below which they count as a triple root u1 = u2 = u3 = 1 (there the roots are
#: only (machine eps)^(1/3)-conditioned and the nutation period diverges)
_TRIPLE_TOL = 1e-3
#: the smallest rtol SciPy accepts without a warning; the charts' coordinates are controlled through atol
_RTOL_FLOOR = 100.0 * np.finfo(float).eps
#: kappa = K/S below which the GHr chart's absolute tolerance on kappa stops shrinking with it (K -> 0 only
#: for a top hanging at rest about its spin, where K = 0 exactly stays 0)
_KAPPA_FLOOR = 1e-2
#: |psi - n| below which the GHr chart controls psi absolutely (relative accuracy of r down to r ~ 1e-3 S)
_PSI_FLOOR = 1e-3
#: a sign-change function below this fraction of its scale counts as zero (no flip): integration noise
_FLIP_NOISE = 1e-10

# the stops of an averaged run; each names the option that relaxes it where one does
_MSG_DEG = ("u2 - u1 reached degenerate_tol (u3 - u1): regular precession, the determinant "
            "(u1-u2)(u1-u3)(u2-u3) of (2.10) vanishes; pass chart='GHr' to go on through it (the (2.7)-averaged "
            "system is regular there), or a smaller degenerate_tol to stop later")
_MSG_SEP = ("u3 - u2 reached degenerate_tol (u3 - u1): sleeping top / separatrix k -> 1, the nutation "
            "period is infinite and the averaging does not hold; a smaller degenerate_tol goes closer to it")
_MSG_TRIPLE = (f"the roots of (1.5) merge, u1 = u2 = u3 = 1 (spread below {_TRIPLE_TOL:g}): a sleeping top at "
               "its stability limit C^2 r^2 = 4 A mgl, the nutation period is infinite")
_MSG_BRANCH = ("Gz^2 - C^2 r^2 or r is near zero: a sign delta1/delta2 of (2.8) may change; use "
               "chart='auto' to continue through it")
_MSG_END = "the end of tau_span was reached"


def _per_member(fn: Callable[..., tuple[float, float, float]], *cols: Any) -> tuple[Any, Any, Any]:
    """The general engine's means ``fn(*floats)`` member by member on arrays of states. A member whose state
    lies outside the chart's domain (a Runge-Kutta stage past a root collision, NaN coordinates: the engine
    raises) gets NaN rates, so that its step is rejected, as the single run's right-hand side rejects it."""
    out = np.full((3, *np.shape(cols[0])), np.nan)
    for i in range(out.shape[1]):
        try:
            out[:, i] = fn(*(float(c[i]) for c in cols))
        except (ZeroDivisionError, OverflowError, ValueError):
            pass
    return out[0], out[1], out[2]


# ==================================================================================================
# problem set-up shared by single and batch runs
# ==================================================================================================
class _Setup:
    """Validated options and the charts' right-hand sides and events (scalar and vectorised)."""

    def __init__(self, top: Top, torque: Torque, rtol: float, atol: float, n: int | None, chart: str,
                 closed_form: bool | None, degenerate_tol: float, switch_tol: float) -> None:
        self.top = top
        self.torque = torque
        self.A, self.C, self.mgl = top.A, top.C, top.mgl
        if closed_form is None:
            closed_form = isinstance(torque, LinearDrag)
        if closed_form and not isinstance(torque, LinearDrag):
            raise TypeError("closed_form=True is available for LinearDrag only (3.4)")
        self.drag = torque if (closed_form and isinstance(torque, LinearDrag)) else None
        self.kd = None if self.drag is None else _k.drag_constants(self.A, self.C, self.mgl, self.drag.a,
                                                                    self.drag.b)
        self.rtol, self.atol, self.n, self.chart = rtol, atol, n, chart
        self.deg, self.sw = degenerate_tol, switch_tol

    # ---- slow variables <-> chart coordinates ------------------------------------------------------
    def slow_to_x(self, xp: Any, Gz: Any, H: Any, r: Any, u1: Any, u2: Any, u3: Any) -> tuple[Any, Any, Any]:
        """u-chart coordinates of (Gz, H, r) with roots ``u1 < u2 < u3`` (absolute accuracy), the small gaps
        refined by (1.6): ``(1+u1)(1+u2)(1+u3) = (Gz + C r)^2/(2 A mgl)``, ``(1-u1)(1-u2)(u3-1) = (Gz - C r)^2/
        (2 A mgl)`` and ``(1+u1) + (1+u2) + (u3-1) = K/mgl + C^2 r^2/(2 A mgl)``."""
        A, C, mgl = self.A, self.C, self.mgl
        Cr = C * r
        amg2 = 2.0 * A * mgl
        pip = (Gz + Cr) ** 2 / amg2
        pim = (Gz - Cr) ** 2 / amg2
        w1, w2, z1, z2, c = 1.0 + u1, 1.0 + u2, 1.0 - u1, 1.0 - u2, u3 - 1.0
        by_c = (z2 >= c) & (z1 * z2 > 0.0)  # u3 - 1 is the smaller gap: from the product
        c, z2 = (xp.where(by_c, pim / xp.where(by_c, z1 * z2, 1.0), c),
                 xp.where(~by_c & (c > 0.0), pim / (z1 * xp.where(c > 0.0, c, 1.0)), z2))
        # both lower roots near -1: their sum and product by (1.6); otherwise 1 + u1 from the product
        K = H + mgl - Cr * Cr / (2.0 * C)
        ssum = K / mgl + Cr * Cr / (2.0 * A * mgl) - c
        prod = pip / (2.0 + c)
        big = 0.5 * ssum + xp.sqrt(xp.maximum(0.25 * ssum * ssum - prod, 0.0))
        pair = (w2 < 0.25) & (big > 0.0)
        w1 = xp.where(pair, prod / xp.where(pair, big, 1.0),
                      xp.where(w2 > 0.0, pip / (xp.where(w2 > 0.0, w2, 1.0) * (2.0 + c)), w1))
        w2 = xp.where(pair, big, w2)
        # q = tan(theta/2), tan theta = |Gz - C r|/|Gz + C r|
        Sp, Sm = xp.abs(Gz + Cr), xp.abs(Gz - Cr)
        q = Sm / (xp.sqrt(Sp * Sp + Sm * Sm) + Sp)
        return 0.5 * xp.log(w1 / z1), 0.5 * xp.log(w2 / z2), q

    # ---- right-hand sides --------------------------------------------------------------------------
    def means_u(self, xp: Any, s: _k.UState) -> tuple[Any, Any, Any]:
        if self.drag is not None:
            return _k.drag_means(xp, self.A, self.C, self.mgl, self.drag.a, self.drag.b, s)
        if xp.array:
            return _per_member(lambda Gz, H, r, u1, u2, u3: averaged_slow_rates(
                self.top, self.torque, Gz, H, r, (u1, u2, u3), n=self.n), s.Gz, s.H, s.r, s.u1, s.u2, s.u3)
        return averaged_slow_rates(self.top, self.torque, s.Gz, s.H, s.r, (s.u1, s.u2, s.u3), n=self.n)

    def means_g(self, xp: Any, g: _k.GState) -> tuple[Any, Any, Any]:
        if self.drag is not None:
            return _k.drag_means_g(xp, self.A, self.C, self.mgl, self.drag.a, self.drag.b, g)
        if xp.array:
            return _per_member(self.engine_ghr, g.Gz, g.H, g.r)
        F = self.engine_ghr(g.Gz, g.H, g.r)
        return F[0], F[1], F[2]

    def engine_ghr(self, Gz: float, H: float, r: float) -> tuple[float, float, float]:
        """Averaged (2.7) by the general engine; a state a hair outside the admissible set (Runge-Kutta stages
        along a regular precession) gets the value at the double root, the local maximum of the cubic."""
        top, torque = self.top, self.torque
        try:  # roots from the cubic inside: a nearly double pair is handled smoothly there
            return averaged_slow_rates(top, torque, Gz, H, r, n=self.n)
        except ValueError:
            pass
        s1, s2, _ = vieta(top, Gz, H, r)
        disc = s1 * s1 - 3.0 * s2
        if not (math.isfinite(disc) and disc >= 0.0):
            return math.nan, math.nan, math.nan
        c = (s1 - math.sqrt(disc)) / 3.0
        F = torque.slow_rates(top, Gz, H, r, np.array([c]))
        return float(np.mean(F[0])), float(np.mean(F[1])), float(np.mean(F[2]))

    def rhs_x(self, xp: Any, x1: Any, x2: Any, x3: Any, d1: Any, d2: Any) -> tuple[Any, Any, Any]:
        if self.kd is not None:
            return _k.u_drag_rates(xp, self.kd, x1, x2, x3, d1, d2)
        s = _k.decode_u(xp, self.A, self.C, self.mgl, x1, x2, x3, d1, d2)
        F = self.means_u(xp, s)
        return _k.u_chart_rates(xp, self.A, self.C, self.mgl, s, *F)

    def rhs_p(self, xp: Any, sig: Any, psi: Any, kap: Any) -> tuple[Any, Any, Any]:
        g = _k.decode_g(xp, self.A, self.C, self.mgl, sig, psi, kap)
        F = self.means_g(xp, g)
        d = _k.g_chart_rates(xp, self.C, g, *F)
        if xp.array:
            bad = ~g.ok
            return tuple(np.where(bad, np.nan, v) for v in d)  # type: ignore[return-value]  # 3 arrays
        return d if g.ok else (math.nan, math.nan, math.nan)

    def roots_g(self, xp: Any, Gz: Any, H: Any, r: Any) -> tuple[Any, Any, Any]:
        """Roots of (1.5) at (Gz, H, r) with ``Gz^2 + C^2 r^2 > 0`` by :func:`_kernel.decode_g` (the largest by
        Newton from the trigonometric formula, the pair by (1.6)); the chart switches of one run and of a batch
        use this same routine."""
        g = _k.decode_g(xp, self.A, self.C, self.mgl, *_k.slow_to_polar(xp, self.C, Gz, H, r, self.mgl))
        return g.u1, g.u2, g.u3

    def polar_tolerances(self, kap0: float, engine: str) -> tuple[Any, np.ndarray]:
        """``(rtol, atol)`` of the GHr chart's ``(ln S, psi - n, kappa)``: ``ln S`` absolutely (``rtol`` is the
        relative accuracy of ``S``), ``psi - n`` relatively down to 1e-3 (so ``sin(pi psi)``, hence ``r`` near
        its zero, keeps its relative accuracy), ``kappa`` absolutely on its own scale (``rtol`` relative accuracy
        of the energy ``K``). SciPy's solvers take one ``rtol``: there ``psi`` is controlled absolutely."""
        atol = np.array([self.rtol, self.rtol * _PSI_FLOOR, self.rtol * max(abs(kap0), _KAPPA_FLOOR)])
        if engine == "python":
            return np.array([_RTOL_FLOOR, self.rtol, _RTOL_FLOOR]), atol
        atol[1] = self.rtol / math.pi
        return _RTOL_FLOOR, atol

    def u_events(self, xp: Any, x1: Any, x2: Any, th: Any, d1: Any) -> tuple[Any, Any, Any]:
        """The u-chart events: ``k^2 - degenerate_tol`` (regular precession), ``mc - degenerate_tol``
        (separatrix), ``min(b1, b2) - switch_tol`` (branch point of (2.8))."""
        k2, mc, b = _k.u_event_values(xp, x1, x2, th, d1)
        return k2 - self.deg, mc - self.deg, b - self.sw

    def ev_w(self, xp: Any, psi: Any) -> Any:
        # sign changes of Gz^2 - C^2 r^2 = S^2 cos(2 pi psi); a value that is zero to integration accuracy (a
        # sleeping or hanging top, Gz = +-C r) counts as positive, so that noise reports no flips: the event is
        # cos(2 pi psi) + 1e-10, continuous, located where Gz^2 - C^2 r^2 = -1e-10 S^2
        _, w = _k.sincospi(xp, 2.0 * psi)
        return w + _FLIP_NOISE

    def ev_r(self, xp: Any, psi: Any) -> Any:
        s, _ = _k.sincospi(xp, psi)
        return xp.where(s != 0.0, s, 1e-300)

    def ev_roots_g(self, xp: Any, sig: Any, psi: Any, kap: Any) -> tuple[Any, Any]:
        """The separatrix event ``mc - degenerate_tol`` and the triple-root event (root spread
        ``sqrt(s1^2 - 3 s2) = sqrt(((u1-u2)^2 + (u1-u3)^2 + (u2-u3)^2)/2)`` minus 1e-3, smooth in (Gz, H, r))."""
        g = _k.decode_g(xp, self.A, self.C, self.mgl, sig, psi, kap)
        return xp.where(g.u3 - g.u1 > 0.0, g.mc - self.deg, -1.0), g.spread - _TRIPLE_TOL

    def ev_leave(self, xp: Any, psi: Any) -> Any:
        s, _ = _k.sincospi(xp, psi)
        _, w = _k.sincospi(xp, 2.0 * psi)
        return xp.minimum(xp.abs(w), s * s) - 2.0 * self.sw

    # ---- output fields on a grid -------------------------------------------------------------------
    def fields_x(self, X: np.ndarray, d1: Any, d2: Any) -> dict[str, np.ndarray]:
        with np.errstate(all="ignore"):
            s = _k.decode_u(_k.ARRAY, self.A, self.C, self.mgl, X[..., 0, :], X[..., 1, :], X[..., 2, :],
                            np.asarray(d1, dtype=float)[..., None], np.asarray(d2, dtype=float)[..., None])
        shp = np.shape(s.Gz)
        return {"u1": s.u1, "u2": s.u2, "u3": s.u3, "Gz": s.Gz, "H": s.H, "r": s.r, "k2": s.k2,
                "delta1": np.broadcast_to(np.asarray(d1, dtype=float)[..., None], shp),
                "delta2": np.broadcast_to(np.asarray(d2, dtype=float)[..., None], shp)}

    def fields_p(self, P: np.ndarray) -> dict[str, np.ndarray]:
        with np.errstate(all="ignore"):
            g = _k.decode_g(_k.ARRAY, self.A, self.C, self.mgl, P[..., 0, :], P[..., 1, :], P[..., 2, :])
            _, w = _k.sincospi(_k.ARRAY, 2.0 * P[..., 1, :])
        return {"u1": g.u1, "u2": g.u2, "u3": g.u3, "Gz": g.Gz, "H": g.H, "r": g.r, "k2": g.k2,
                "delta1": np.where(w >= 0.0, 1.0, -1.0), "delta2": np.where(g.sn >= 0.0, 1.0, -1.0)}


def _roots_or_double(top: Top, Gz: float, H: float, r: float) -> tuple[float, float, float]:
    """Roots of (1.5); a state a hair outside the admissible set next to its regular-precession boundary gets
    the double root at the local maximum of the cubic, ``u1 = u2 = c``."""
    try:
        return roots(top, Gz, H, r)
    except ValueError:
        s1, s2, _ = vieta(top, Gz, H, r)
        disc = s1 * s1 - 3.0 * s2
        if not (math.isfinite(disc) and disc >= 0.0):
            raise ValueError(f"(Gz, H, r) = ({Gz!r}, {H!r}, {r!r}): the cubic (1.5) has one real root") from None
        c = min(max((s1 - math.sqrt(disc)) / 3.0, -1.0), 1.0)
        return c, c, max(s1 - 2.0 * c, 1.0)


def _check_options(tau_span: Any, chart: str, degenerate_tol: Any, switch_tol: Any, rtol: Any, atol: Any,
                   max_segments: Any) -> tuple[float, float, float, float, float, float]:
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
    return t0, t1, degenerate_tol, switch_tol, rtol, atol


def _start_chart(st: _Setup, Gz0: float, H0: float, r0: float) -> tuple[str, float, float, tuple[float, ...]]:
    """The chart a run starts in, its signs and the roots; ValueError for states with no average."""
    u_init = roots(st.top, Gz0, H0, r0)
    d1, d2 = deltas(st.top, Gz0, r0)
    chart, sw, deg = st.chart, st.sw, st.deg
    cur = "GHr" if chart == "GHr" else "u"
    u1i, u2i, u3i = u_init
    if cur == "u":
        s13 = u1i + u2i + u3i + u1i * u2i * u3i
        if s13 <= 0.0:
            b = 0.0
        else:
            R = math.sqrt(max(1 - u1i * u1i, 0.0) * max(1 - u2i * u2i, 0.0) * max(u3i * u3i - 1, 0.0))
            b = min(R / s13, 0.5 * (s13 - d1 * R) / s13)
        if chart == "auto" and b < sw:
            cur = "GHr"
        elif b <= sw:
            raise ValueError(
                "chart='u': the initial state is within switch_tol of a branch point of (2.8) "
                f"(|Gz^2 - C^2 r^2| or C^2 r^2 is {b:.3g} of Gz^2 + C^2 r^2 <= switch_tol = "
                f"{sw:g}), where a sign delta1/delta2 may change; use chart='auto' or 'GHr', or a smaller "
                "switch_tol"
            )
        if chart == "auto" and (u2i - u1i) <= deg * (u3i - u1i):
            cur = "GHr"  # a regular precession: (2.10) is singular, the (2.7)-averaged chart is not
    if (u2i - u1i) <= deg * (u3i - u1i) and cur == "u":
        raise ValueError(
            "chart='u': the initial state is (numerically) a regular precession, u1 = u2: the averaged system "
            "in (u1, u2, u3) is singular there (determinant of (2.10)); use chart='auto' or 'GHr'"
        )
    if (u3i - u2i) <= deg * (u3i - u1i):
        raise ValueError("the initial state is a sleeping top on the separatrix (u2 = u3 = 1): "
                         "infinite nutation period, no average")
    s1, s2, _ = vieta(st.top, Gz0, H0, r0)
    if math.sqrt(max(s1 * s1 - 3.0 * s2, 0.0)) - _TRIPLE_TOL <= 0.0:
        raise ValueError(f"the initial state has a (nearly) triple root u1 = u2 = u3 = 1 (root spread below "
                         f"{_TRIPLE_TOL:g}): a sleeping top at its stability limit C^2 r^2 = 4 A mgl, infinite "
                         "nutation period, no average")
    return cur, d1, d2, u_init


# ==================================================================================================
# one run
# ==================================================================================================
def _single(st: _Setup, Gz0: float, H0: float, r0: float, t0: float, t1: float, te_all: np.ndarray | None,
            method: str, max_segments: int) -> Solution:
    SC = _k.SCALAR
    chart = st.chart
    cur, d1, d2, u_init = _start_chart(st, Gz0, H0, r0)
    nan3 = [math.nan, math.nan, math.nan]

    # a stage outside the charts' domain (overflow, a root order violated) gets NaN: the step is rejected
    A, C, mgl = st.A, st.C, st.mgl
    drag = st.drag
    kd = None if drag is None else _k.drag_constants(A, C, mgl, drag.a, drag.b)

    def rhs_x(tau: float, y: Any, d1: float, d2: float) -> Any:
        x1, x2, th = y
        if not x1 < x2:
            return nan3
        try:
            if kd is not None:
                return _k.u_drag_rates(SC, kd, x1, x2, th, d1, d2)
            return st.rhs_x(SC, x1, x2, th, d1, d2)
        except (ZeroDivisionError, OverflowError, ValueError):
            return nan3

    # the GHr chart integrates psi - n (n the integer nearest psi at the segment's start, so that psi - n is
    # small when r is, and relative control of it keeps r's relative accuracy); n rides along as an argument
    def rhs_p(tau: float, y: Any, n_off: float) -> Any:
        sig, psi, kap = y
        try:
            return list(st.rhs_p(SC, sig, psi + n_off, kap))
        except (ZeroDivisionError, OverflowError, ValueError):
            return nan3

    def rhs_plain(tau: float, y: Any) -> list[float]:
        return list(st.engine_ghr(float(y[0]), float(y[1]), float(y[2])))

    def unpack(f: Callable[..., Any]) -> Callable[..., float]:
        def ev(tau: float, y: Any, *a: Any) -> float:
            try:
                return float(f(SC, *y, *a))
            except (ZeroDivisionError, OverflowError, ValueError):
                return math.nan
        return ev

    # the three u-chart events at one state share one decoding (solve_ivp calls them in turn at each step)
    cache: dict[str, Any] = {"key": None, "val": (math.nan, math.nan, math.nan)}

    def u_events(y: Any, d1: float, d2: float) -> tuple[float, float, float]:
        key = (*y, d1, d2)
        if cache["key"] != key:
            try:
                cache["val"] = st.u_events(SC, key[0], key[1], key[2], d1)
            except (ZeroDivisionError, OverflowError, ValueError):
                cache["val"] = (math.nan, math.nan, math.nan)
            cache["key"] = key
        return cache["val"]

    def ev_deg(tau: float, y: Any, d1: float, d2: float) -> float:
        return u_events(y, d1, d2)[0]

    def ev_sep(tau: float, y: Any, d1: float, d2: float) -> float:
        return u_events(y, d1, d2)[1]

    def ev_branch(tau: float, y: Any, d1: float, d2: float) -> float:
        return u_events(y, d1, d2)[2]

    # the five GHr-chart events at one state share one decoding
    gcache: dict[str, Any] = {"key": None, "val": (math.nan, math.nan)}

    def g_roots(y: Any, n_off: float) -> tuple[float, ...]:
        key = (*y, n_off)
        if gcache["key"] != key:
            try:
                gcache["val"] = tuple(float(v) for v in st.ev_roots_g(SC, key[0], key[1] + n_off, key[2]))
            except (ZeroDivisionError, OverflowError, ValueError):
                gcache["val"] = (math.nan, math.nan)
            gcache["key"] = key
        return gcache["val"]

    def ev_w(tau: float, y: Any, n_off: float) -> float:
        return float(st.ev_w(SC, y[1] + n_off))

    def ev_r(tau: float, y: Any, n_off: float) -> float:
        return float(st.ev_r(SC, y[1] + n_off))

    def ev_sep_p(tau: float, y: Any, n_off: float) -> float:
        return g_roots(y, n_off)[0]

    def ev_triple(tau: float, y: Any, n_off: float) -> float:
        return g_roots(y, n_off)[1]

    def ev_leave(tau: float, y: Any, n_off: float) -> float:
        return float(st.ev_leave(SC, y[1] + n_off))

    # the (Gz, H, r) chart in plain variables, for Gz = r = 0 (no direction in the (Gz, C r) plane)
    def evp_w(tau: float, y: Any) -> float:
        g2, c2 = float(y[0] * y[0]), float((st.C * y[2]) ** 2)
        w = g2 - c2
        return w if abs(w) > _FLIP_NOISE * (g2 + c2) else 1e-300

    def evp_r(tau: float, y: Any) -> float:
        return float(y[2]) if y[2] != 0.0 else 1e-300

    def evp_sep(tau: float, y: Any) -> float:
        try:
            u1, u2, u3 = _roots_or_double(st.top, float(y[0]), float(y[1]), float(y[2]))
        except ValueError:
            return -1.0
        return (u3 - u2) / (u3 - u1) - st.deg if u3 - u1 > 0.0 else -1.0

    def evp_triple(tau: float, y: Any) -> float:
        s1, s2, _ = vieta(st.top, float(y[0]), float(y[1]), float(y[2]))
        return math.sqrt(max(s1 * s1 - 3.0 * s2, 0.0)) - _TRIPLE_TOL

    def evp_leave(tau: float, y: Any) -> float:
        s = float(y[0] * y[0] + (st.C * y[2]) ** 2)
        if s == 0.0:
            return -1.0
        b1 = abs(float(y[0] * y[0] - (st.C * y[2]) ** 2)) / s
        b2 = float((st.C * y[2]) ** 2) / s
        return min(b1, b2) - 2.0 * st.sw

    pieces: list[dict[str, np.ndarray]] = []
    taus: list[np.ndarray] = []
    t_events: dict[str, list[float]] = {"delta1_flip": [], "delta2_flip": [], "chart_switch": []}
    status, message, event, nfev = 0, _MSG_END, None, 0
    tau = t0
    Gz, H, r = Gz0, H0, r0
    del u_init  # the u chart starts from roots_g (the batch computes the same)
    last_out = -math.inf
    atol_x = np.full(3, st.rtol)
    engine = "python" if method == "DOP853" else "scipy"
    h_next: float | None = None  # a continued run starts with the step size its predecessor reached
    for _ in range(max_segments):
        tev = None if te_all is None else te_all[(te_all >= tau) & (te_all > last_out)]
        if cur == "u":
            x0 = np.array(st.slow_to_x(SC, Gz, H, r, *st.roots_g(SC, Gz, H, r)))
            evs = [Event(ev_deg, "u1_eq_u2", True, -1.0, _MSG_DEG), Event(ev_sep, "separatrix", True, -1.0, _MSG_SEP)]
            if chart in ("auto", "u"):
                evs.append(Event(ev_branch, "branch_point", True, -1.0, _MSG_BRANCH))
            sol = integrate(rhs_x, (tau, t1), x0, t_eval=tev, rtol=_RTOL_FLOOR, atol=atol_x, method=method,
                            events=evs, time_name="tau", args=(d1, d2), engine=engine, first_step=h_next)
            nfev += sol.nfev
            h_next = sol.last_step
            if sol.tau.size:
                f = st.fields_x(sol.y, d1, d2)
                f["chart"] = np.zeros(sol.tau.size)
                pieces.append(f)
                taus.append(sol.tau)
                last_out = sol.tau[-1]
            if sol.status == 1 and sol.event == "branch_point" and chart == "auto":
                te = float(sol.t_events["branch_point"][-1])
                ye = sol.y_events["branch_point"][-1]
                s = _k.decode_u(_k.SCALAR, st.A, st.C, st.mgl, float(ye[0]), float(ye[1]), float(ye[2]), d1, d2)
                Gz, H, r = s.Gz, s.H, s.r
                tau = te
                cur = "GHr"
                t_events["chart_switch"].append(te)
                continue
            status, message, event = sol.status, sol.message, sol.event
            if sol.event is not None:
                t_events[sol.event] = list(sol.t_events[sol.event])
            break
        # ---- chart GHr ----
        polar = Gz != 0.0 or r != 0.0
        if polar:
            y0 = np.array(_k.slow_to_polar(_k.SCALAR, st.C, Gz, H, r, st.mgl))
            n_off = float(round(y0[1]))
            y0[1] -= n_off
            rtol_p, atol_p = st.polar_tolerances(y0[2], engine)
            evs = [Event(ev_w, "delta1_flip", False, 0.0), Event(ev_r, "delta2_flip", False, 0.0),
                   Event(ev_sep_p, "separatrix", True, -1.0, _MSG_SEP),
                   Event(ev_triple, "triple_root", True, -1.0, _MSG_TRIPLE)]
            if chart == "auto":
                evs.append(Event(ev_leave, "leave_branch", True, 1.0))
            sol = integrate(rhs_p, (tau, t1), y0, t_eval=tev, rtol=rtol_p, atol=atol_p, method=method,
                            events=evs, time_name="tau", engine=engine, first_step=h_next, args=(n_off,))
        else:
            evs = [Event(evp_w, "delta1_flip", False, 0.0), Event(evp_r, "delta2_flip", False, 0.0),
                   Event(evp_sep, "separatrix", True, -1.0, _MSG_SEP),
                   Event(evp_triple, "triple_root", True, -1.0, _MSG_TRIPLE)]
            if chart == "auto":
                evs.append(Event(evp_leave, "leave_branch", True, 1.0))
            sol = integrate(rhs_plain, (tau, t1), np.array([Gz, H, r]), t_eval=tev, rtol=st.rtol, atol=st.atol,
                            method=method, events=evs, time_name="tau", engine=engine, first_step=h_next)
        nfev += sol.nfev
        h_next = sol.last_step
        t_events["delta1_flip"].extend(sol.t_events["delta1_flip"].tolist())
        t_events["delta2_flip"].extend(sol.t_events["delta2_flip"].tolist())
        if sol.tau.size:
            if polar:
                f = st.fields_p(sol.y + np.array([[0.0], [n_off], [0.0]]))
            else:
                yy = sol.y
                U = np.array([_roots_or_double(st.top, *yy[:, j]) for j in range(sol.tau.size)]).T
                dd = np.array(deltas(st.top, yy[0], yy[2])).reshape(2, -1)
                d31 = U[2] - U[0]
                f = {"u1": U[0], "u2": U[1], "u3": U[2], "Gz": yy[0], "H": yy[1], "r": yy[2],
                     "k2": np.where(d31 > 0, (U[1] - U[0]) / np.where(d31 > 0, d31, 1.0), 0.0),
                     "delta1": dd[0], "delta2": dd[1]}
            f["chart"] = np.ones(sol.tau.size)
            pieces.append(f)
            taus.append(sol.tau)
            last_out = sol.tau[-1]
        if sol.status == 1 and sol.event == "leave_branch":
            te = float(sol.t_events["leave_branch"][-1])
            ye = sol.y_events["leave_branch"][-1]
            if polar:
                g = _k.decode_g(_k.SCALAR, st.A, st.C, st.mgl, float(ye[0]), float(ye[1]) + n_off, float(ye[2]))
                Gz, H, r = g.Gz, g.H, g.r
            else:
                Gz, H, r = (float(v) for v in ye)
            tau = te
            d1, d2 = deltas(st.top, Gz, r)
            cur = "u"
            t_events["chart_switch"].append(te)
            u1, u2, u3 = st.roots_g(SC, Gz, H, r)
            if (u2 - u1) <= st.deg * (u3 - u1):
                status, event = 1, "u1_eq_u2"
                message = f"stopped by event 'u1_eq_u2' at tau = {te:.6g}: {_MSG_DEG}"
                break
            continue
        status, message, event = sol.status, sol.message, sol.event
        if sol.event is not None:
            t_events[sol.event] = list(sol.t_events[sol.event])
        break
    else:
        status, message = -1, f"more than max_segments={max_segments} chart switches (chattering)"
    if status == 0:
        message = _MSG_END

    names = ("u1", "u2", "u3", "Gz", "H", "r", "k2", "delta1", "delta2", "chart")
    if taus:
        tau_a = np.concatenate(taus)
        cols = {k: np.concatenate([np.asarray(p[k], dtype=float).reshape(-1) for p in pieces]) for k in names}
        # drop duplicated switching points (kept once, from the later segment)
        keep = np.append(np.diff(tau_a) > 0.0, True)
        tau_a = tau_a[keep]
        cols = {k: v[keep] for k, v in cols.items()}
    else:
        tau_a = np.empty(0)
        cols = {k: np.empty(0) for k in names}
    U_a = np.array([cols["u1"], cols["u2"], cols["u3"]]).reshape(3, -1)
    data = {"u": U_a, **cols}
    tev_out = {k: np.asarray(v, dtype=float) for k, v in t_events.items()}
    return Solution("tau", tau_a, U_a, data, int(status), message, event, tev_out, {}, None, nfev)


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

    A batch of initial states (``initial`` of shape ``batch_shape + (3,)``) is integrated together, each
    member with its own charts, signs, events and status (see Notes).

    Parameters
    ----------
    top : Top
    torque : Torque
        :class:`LinearDrag` (closed form (3.4) by default) or any admissible torque (general engine).
    initial : (Gz, H, r) or array_like of shape ``batch_shape + (3,)``
        Initial slow variables (1.2), one triple per member for a batch.
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
        ``'chart_switch'``, and the terminal event). For a batch every field has shape
        ``batch_shape + (len(tau_eval),)`` (``u``: ``batch_shape + (3, len(tau_eval))``), NaN after a
        member's end, and ``status``, ``message``, ``event`` are per member; ``sol[i]`` is member ``i``.

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

    *Batches.* ``top``, ``torque`` and the options are shared by all members. Members in the same chart
    are integrated together by :func:`rigidbody.core.batch.integrate_batch` (vectorised right-hand sides
    for :class:`LinearDrag`; the general engine evaluates its nutation means member by member); a member
    that needs the other chart continues in a follow-up batch of that chart from its switching point.
    Every member equals its single run within the tolerance.
    """
    top = _check_top(top)
    torque = check_torque(torque)
    t0, t1, degenerate_tol, switch_tol, rtol, atol = _check_options(
        tau_span, chart, degenerate_tol, switch_tol, rtol, atol, max_segments)
    st = _Setup(top, torque, rtol, atol, n, chart, closed_form, degenerate_tol, switch_tol)
    te_all = None if tau_eval is None else np.atleast_1d(np.asarray(tau_eval, dtype=float))
    if te_all is not None and te_all.size and (te_all.min() < t0 or te_all.max() > t1):
        raise ValueError("tau_eval must lie within tau_span")
    try:
        ndim = np.ndim(initial)
    except ValueError:  # ragged input
        ndim = 1
    if ndim >= 2:
        from ._avgbatch import averaged_batch  # the batch module builds on this one

        return averaged_batch(st, initial, t0, t1, te_all, max_segments)
    try:
        Gz0, H0, r0 = (float(x) for x in initial)
    except (TypeError, ValueError):
        raise ValueError(f"initial must be (Gz, H, r), got {initial!r}") from None
    return _single(st, Gz0, H0, r0, t0, t1, te_all, method, max_segments)
