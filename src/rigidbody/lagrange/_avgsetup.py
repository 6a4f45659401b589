r"""What the charts of the averaged system (2.15) share: thresholds, the stop messages, the validated options with
the charts' right-hand sides and events (scalar and vectorised, by :class:`ChartSetup`), and the start of a run.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from ..core.validate import positive, span
from . import _kernel as _k
from ._averaging import averaged_slow_rates
from ._top import Top, deltas, roots, vieta
from ._torques import LinearDrag, Torque, closed_form_choice

__all__ = [
    "CHARTS", "FLIP_NOISE", "KAPPA_FLOOR", "MSG_BRANCH", "MSG_DEG", "MSG_END", "MSG_SEP", "MSG_TRIPLE", "PSI_FLOOR",
    "RTOL_FLOOR", "TRIPLE_TOL", "ChartSetup", "check_options", "double_root_at", "per_member", "roots_or_double",
    "spread_event", "start_chart",
]

CHARTS = ("auto", "u", "GHr")
#: spread of the three roots below which they count as a triple root u1 = u2 = u3 = 1 (there the roots are
#: only (machine eps)^(1/3)-conditioned and the nutation period diverges)
TRIPLE_TOL = 1e-3
#: the smallest rtol SciPy accepts without a warning; the charts' coordinates are controlled through atol
RTOL_FLOOR = 100.0 * np.finfo(float).eps
#: kappa = K/S below which the GHr chart's absolute tolerance on kappa stops shrinking with it (K -> 0 only
#: for a top hanging at rest about its spin, where K = 0 exactly stays 0)
KAPPA_FLOOR = 1e-2
#: |psi - n| below which the GHr chart controls psi absolutely (relative accuracy of r down to r ~ 1e-3 S)
PSI_FLOOR = 1e-3
#: a sign-change function below this fraction of its scale counts as zero (no flip): integration noise
FLIP_NOISE = 1e-10

# the stops of an averaged run; each names the option that relaxes it where one does
MSG_DEG = ("u2 - u1 reached degenerate_tol (u3 - u1): regular precession, the determinant "
            "(u1-u2)(u1-u3)(u2-u3) of (2.10) vanishes; pass chart='GHr' to go on through it (the (2.7)-averaged "
            "system is regular there), or a smaller degenerate_tol to stop later")
MSG_SEP = ("u3 - u2 reached degenerate_tol (u3 - u1): sleeping top / separatrix k -> 1, the nutation "
            "period is infinite and the averaging does not hold; a smaller degenerate_tol goes closer to it")
MSG_TRIPLE = (f"the roots of (1.5) merge, u1 = u2 = u3 = 1 (spread below {TRIPLE_TOL:g}): a sleeping top at "
               "its stability limit C^2 r^2 = 4 A mgl, the nutation period is infinite")
MSG_BRANCH = ("Gz^2 - C^2 r^2 or r is near zero: a sign delta1/delta2 of (2.8) may change; use "
               "chart='auto' to continue through it")
MSG_END = "the end of tau_span was reached"


def per_member(fn: Callable[..., tuple[float, float, float]], *cols: Any) -> tuple[Any, Any, Any]:
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
class ChartSetup:
    """Validated options and the charts' right-hand sides and events (scalar and vectorised)."""

    def __init__(self, top: Top, torque: Torque, rtol: float, atol: float, n: int | None, chart: str,
                 closed_form: bool | None, degenerate_tol: float, switch_tol: float) -> None:
        self.top = top
        self.torque = torque
        self.A, self.C, self.mgl = top.A, top.C, top.mgl
        #: the torque whose closed-form means are used (None: the averaging engine)
        self.closed = torque if closed_form_choice(torque, closed_form) else None
        # linear drag's closed form has also a fused pass through the u chart (decoding, means and chart rates)
        self.kd = (_k.drag_constants(self.A, self.C, self.mgl, torque.a, torque.b)
                   if self.closed is not None and type(torque) is LinearDrag else None)
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
        if self.closed is not None:
            return self.closed.closed_means(xp, self.top, s)  # type: ignore[return-value]  # it has one
        if xp.array:
            return per_member(lambda Gz, H, r, u1, u2, u3: averaged_slow_rates(
                self.top, self.torque, Gz, H, r, (u1, u2, u3), n=self.n), s.Gz, s.H, s.r, s.u1, s.u2, s.u3)
        return averaged_slow_rates(self.top, self.torque, s.Gz, s.H, s.r, (s.u1, s.u2, s.u3), n=self.n)

    def means_g(self, xp: Any, g: _k.GState) -> tuple[Any, Any, Any]:
        if self.closed is not None:
            return self.closed.closed_means(xp, self.top, g)  # type: ignore[return-value]  # it has one
        if xp.array:
            return per_member(self.engine_ghr, g.Gz, g.H, g.r)
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
        c = double_root_at(top, Gz, H, r)
        if c is None:
            return math.nan, math.nan, math.nan
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

    def polar_tolerances(self, kap0: Any, engine: str) -> tuple[Any, np.ndarray]:
        """``(rtol, atol)`` of the GHr chart's ``(ln S, psi - n, kappa)``: ``ln S`` absolutely (``rtol`` is the
        relative accuracy of ``S``), ``psi - n`` relatively down to 1e-3 (so ``sin(pi psi)``, hence ``r`` near
        its zero, keeps its relative accuracy), ``kappa`` absolutely on its own scale (``rtol`` relative accuracy
        of the energy ``K``). SciPy's solvers take one ``rtol``: there ``psi`` is controlled absolutely. ``kap0``
        is one start (``atol`` of shape ``(3,)``) or one per member (``atol`` of shape ``(m, 3)``)."""
        kap = np.maximum(np.abs(np.asarray(kap0, dtype=float)), KAPPA_FLOOR)
        atol = np.empty((*kap.shape, 3))
        atol[..., 0], atol[..., 1], atol[..., 2] = self.rtol, self.rtol * PSI_FLOOR, self.rtol * kap
        if engine == "python":
            return np.array([RTOL_FLOOR, self.rtol, RTOL_FLOOR]), atol
        atol[..., 1] = self.rtol / math.pi
        return RTOL_FLOOR, atol

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
        return w + FLIP_NOISE

    def ev_r(self, xp: Any, psi: Any) -> Any:
        s, _ = _k.sincospi(xp, psi)
        return xp.where(s != 0.0, s, 1e-300)

    def ev_roots_g(self, xp: Any, sig: Any, psi: Any, kap: Any) -> tuple[Any, Any]:
        """The separatrix event ``mc - degenerate_tol`` and the triple-root event (root spread
        ``sqrt(s1^2 - 3 s2) = sqrt(((u1-u2)^2 + (u1-u3)^2 + (u2-u3)^2)/2)`` minus 1e-3, smooth in (Gz, H, r))."""
        g = _k.decode_g(xp, self.A, self.C, self.mgl, sig, psi, kap)
        return xp.where(g.u3 - g.u1 > 0.0, g.mc - self.deg, -1.0), g.spread - TRIPLE_TOL

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


def roots_or_double(top: Top, Gz: float, H: float, r: float) -> tuple[float, float, float]:
    """Roots of (1.5); a state a hair outside the admissible set next to its regular-precession boundary gets
    the double root at the local maximum of the cubic, ``u1 = u2 = c``."""
    try:
        return roots(top, Gz, H, r)
    except ValueError:
        c = double_root_at(top, Gz, H, r)
        if c is None:
            raise ValueError(f"(Gz, H, r) = ({Gz!r}, {H!r}, {r!r}): the cubic (1.5) has one real root") from None
        s1 = vieta(top, Gz, H, r)[0]
        c = min(max(c, -1.0), 1.0)
        return c, c, max(s1 - 2.0 * c, 1.0)


def double_root_at(top: Top, Gz: float, H: float, r: float) -> float | None:
    """The local maximum of the cubic (1.5) at (Gz, H, r) (the double root of a regular precession), None where
    the cubic has a single real root."""
    s1, s2, _ = vieta(top, Gz, H, r)
    disc = s1 * s1 - 3.0 * s2
    if not (math.isfinite(disc) and disc >= 0.0):
        return None
    return float(_k.double_root(s1, _k.cubic_spread(_k.SCALAR, s1, s2)))


def spread_event(top: Top, Gz: float, H: float, r: float) -> float:
    """The triple-root event of the plain (Gz, H, r) chart: the root spread minus :data:`TRIPLE_TOL`."""
    s1, s2, _ = vieta(top, Gz, H, r)
    return float(_k.cubic_spread(_k.SCALAR, s1, s2)) - TRIPLE_TOL


def check_options(tau_span: Any, chart: str, degenerate_tol: Any, switch_tol: Any, rtol: Any, atol: Any,
                   max_segments: Any) -> tuple[float, float, float, float, float, float]:
    t0, t1 = span(tau_span, "tau_span")
    if chart not in CHARTS:
        raise ValueError(f"chart must be one of {CHARTS}, got {chart!r}")
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


def start_chart(st: ChartSetup, Gz0: float, H0: float, r0: float) -> tuple[str, float, float, tuple[float, ...]]:
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
    if spread_event(st.top, Gz0, H0, r0) <= 0.0:
        raise ValueError(f"the initial state has a (nearly) triple root u1 = u2 = u3 = 1 (root spread below "
                         f"{TRIPLE_TOL:g}): a sleeping top at its stability limit C^2 r^2 = 4 A mgl, infinite "
                         "nutation period, no average")
    return cur, d1, d2, u_init


