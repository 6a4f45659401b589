r"""Resonance crossings of an averaged run: where :math:`j\rho = N` and the jump each passage predicts.

Along a run with :math:`\varepsilon > 0` the rotation number :math:`\rho = \langle\dot\psi\rangle P/2\pi` (a
function of :math:`k^2`) crosses the resonances :math:`j\rho = N`, :math:`j = 1, 2`. A passage changes the slow
variables by the jump :math:`2|c_{j,-N}|\varepsilon\sqrt{P/|j\dot\rho|}` (stationary phase; :math:`c_{jm}` the
Fourier coefficient of the torque's effect on the torus of the motion, :func:`harmonic`).

Cost. One coefficient costs a grid of :math:`8\times 2\max(n_u, 4N + 8)` nodes: its phase factor
:math:`e^{iN\vartheta}` has to be resolved. Near a symmetric body (:math:`A_2 \approx A_3` or
:math:`A_1 \approx A_2`) the period is long, :math:`\rho` is large (:math:`\propto 1/\sqrt{A_2 - A_3}`) and a
run crosses thousands of orders :math:`N` in the thousands: one coefficient each made the check cost minutes.
And there the coefficients do *not* decay with the order: in the Euler angles of the motion the body's third
axis sweeps past :math:`\mathbf G` twice a period in a time of order :math:`1/\omega`, so the functions on
the torus have about :math:`\rho` harmonics. What makes the jumps small there is the passage: it is fast.

So above :data:`EXACT_ORDERS` a crossing is first bounded. Parseval's identity over the harmonics of the phase
gives, for every :math:`m`, :math:`|c_{jm}|^2 \le \sum_{m'}|c_{jm'}|^2 = \langle|W_j|^2\rangle`, the mean over
the period of the squared :math:`j`-th harmonic :math:`W_j(t)` of the torque's effect over the precession angle
(:func:`harmonic_bound`). :math:`|W_j(t)|` does not depend on where :math:`\psi` is counted from (a shift
multiplies :math:`W_j` by :math:`e^{ij\Delta}`): it is a function of the body's attitude relative to
:math:`\mathbf G` and of :math:`\boldsymbol\omega`, both smooth elliptic functions, so the engine's ordinary
phase grid gives its mean; the bound costs the same whatever the order. It is evaluated at the two ends of each
integrator step that holds such crossings (a step over which the integrator kept the slow state smooth) and
applied to the crossings inside with the margin :data:`MARGIN`: a crossing whose bounded jump, times the
margin, stays within ``resonance_tol`` cannot stop the run and is listed with the bound (``bound: True``);
any other one gets its coefficient computed, as below the threshold.

The crossing times are found for all crossings together, by Newton's method on Chebyshev series of
:math:`\rho(\tau)` fitted (to rounding) to the dense output over each step that holds crossings; the rate
:math:`\dot\rho` and the period at a bounded crossing come from the same fits. The bookkeeping costs a few passes
over arrays, not a root search (dense output and elliptic integrals at every iterate) per crossing; what remains
per crossing is its entry in the list (a few microseconds).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from ..core.ode import Solution
from ._engine import Grid, motion_nodes, quantities, torque_grid
from ._state import State, frame

#: orders |m| <= EXACT_ORDERS get their coefficient at the crossing, as before the bound (so every crossing of a
#: body whose moments differ by 3 per cent or more: its rotation number stays below 20); above, the bound first
EXACT_ORDERS = 64
#: a bounded crossing is accepted when MARGIN times its bound stays within resonance_tol: the margin covers
#: how much the bound (relative to G and T) may change between the ends of an integrator step and the crossing
MARGIN = 10.0
#: above this order even an unbounded crossing is not computed (its grid, 2 (4N + 8) x 8 nodes, would exceed
#: the engine's largest grid): it is listed with its bound
_MAX_ORDER = 2**19 // 64
#: nodes of the precession angle (harmonics j = 1, 2 of torques up to cubic in the attitude, as the engine's)
_N_PSI = 8
#: the root search ends when the bracket is this wide (plus 4 ulp of tau), as brentq's xtol
_XTOL = 1e-12
#: the fit of a step: Chebyshev series of degree _FIT_DEGREE on Chebyshev--Lobatto nodes, halved until its last
#: three coefficients fall below _FIT_TOL of its largest (at most _FIT_DEPTH times)
_FIT_DEGREE, _FIT_TOL, _FIT_DEPTH = 16, 1e-13, 30


def _chebyshev(values: np.ndarray) -> np.ndarray:
    """Chebyshev coefficients (last axis) of the interpolant of values on the Lobatto nodes cos(pi k/n), k = 0..n."""
    n = values.shape[-1] - 1
    c = np.fft.rfft(np.concatenate([values, values[..., -2:0:-1]], axis=-1), axis=-1).real / n
    c[..., 0] /= 2.0
    c[..., n] /= 2.0
    return c[..., :n + 1]


class _StepFit:
    """The rotation number rho(k2(tau)) and the period P(G(tau), k2(tau)) over the integrator steps that hold
    crossings, as piecewise Chebyshev series
    accurate to rounding: the root searches and the rates then cost array operations, not evaluations of the
    dense output (a Python loop over the points), of rho or of the period (elliptic integrals) for every crossing."""

    def __init__(self, res: Solution, rho: Callable[[Any], Any], period: Callable[[float, float], float],
                 steps: np.ndarray) -> None:
        x = np.cos(np.pi * np.arange(_FIT_DEGREE + 1) / _FIT_DEGREE)
        todo = [(float(res.time[i]), float(res.time[i + 1]), 0) for i in steps.tolist()]
        pieces: list[tuple[float, float, np.ndarray]] = []
        while todo:
            a, b = np.array([p[0] for p in todo]), np.array([p[1] for p in todo])
            t = 0.5 * (a + b)[:, None] + 0.5 * (b - a)[:, None] * x
            y = res.sol(t.ravel())
            k2 = np.clip(y[1], 0.0, 1.0 - 1e-12)
            P = [period(g, k) for g, k in zip(y[0].tolist(), k2.tolist())]
            coef = _chebyshev(np.stack([rho(k2), np.array(P)]).reshape(2, a.size, x.size))
            big = np.abs(coef).max(axis=2)
            done = np.all(np.abs(coef[..., -3:]).max(axis=2) <= _FIT_TOL * big, axis=0)
            nxt = []
            for k, (lo, hi, depth) in enumerate(todo):
                if done[k] or depth >= _FIT_DEPTH or hi - lo <= 0.0:
                    pieces.append((lo, hi, coef[:, k]))
                else:
                    mid = 0.5 * (lo + hi)
                    nxt += [(lo, mid, depth + 1), (mid, hi, depth + 1)]
            todo = nxt
        pieces.sort(key=lambda p: p[0])
        self.lo = np.array([p[0] for p in pieces])
        self.hi = np.array([p[1] for p in pieces])
        self.coef = np.stack([p[2] for p in pieces], axis=1)  # (row, piece, coefficient)
        self.dcoef = np.polynomial.chebyshev.chebder(self.coef, axis=2)

    def __call__(self, t: np.ndarray, row: int, derivative: bool = False) -> np.ndarray:
        """Row 0 (rho) or 1 (P) at the times t (or its derivative in tau)."""
        return self._eval(t, row, (derivative,))[0]

    def value_slope(self, t: np.ndarray, row: int) -> tuple[np.ndarray, np.ndarray]:
        """A row and its derivative in tau at the times t."""
        v, d = self._eval(t, row, (False, True))
        return v, d

    def _eval(self, t: np.ndarray, row: int, which: tuple[bool, ...]) -> list[np.ndarray]:
        k = np.clip(np.searchsorted(self.lo, t, side="right") - 1, 0, self.lo.size - 1)
        w = self.hi[k] - self.lo[k]
        safe = np.where(w > 0.0, w, 1.0)
        x = np.where(w > 0.0, (2.0 * t - self.lo[k] - self.hi[k]) / safe, 0.0)
        T = np.cos(np.arccos(np.clip(x, -1.0, 1.0))[:, None] * np.arange(self.coef.shape[2]))  # T_n(x)
        out = []
        for derivative in which:
            c = (self.dcoef if derivative else self.coef)[row][k]
            v = np.einsum("pn,pn->p", c, T[:, :c.shape[1]])
            out.append(v * (2.0 / safe) if derivative else v)
        return out


def harmonic(torque: Any, st: State, j: int, m: int) -> np.ndarray:
    r"""The Fourier coefficient :math:`c_{jm}` of the six quantities on the torus of the motion.

    In the angle variables of the Euler--Poinsot motion, :math:`\tilde\psi = \psi - \chi(t)` (:math:`\chi`
    the periodic part of the precession angle) and the phase :math:`\vartheta = 2\pi t/P`, the flow is
    linear: :math:`\dot{\tilde\psi} = \langle\dot\psi\rangle`, :math:`\dot\vartheta = 2\pi/P`. The
    coefficient of :math:`e^{i(j\tilde\psi + m\vartheta)}` drives a resonance where
    :math:`j\langle\dot\psi\rangle + 2\pi m/P = 0`. The nu of ``st`` is held (it must be a number).
    """
    from ._motion import EulerPoinsot

    mot = EulerPoinsot(st.body, st.G, st.k2, st.kind, st.sigma, mc=st.mc)
    n_u = 2 * max(Grid().n_u(st.mc), 4 * abs(m) + 8)
    n_u += (-n_u) % 4
    n_psi = max(8, 4 * abs(j))
    omega, al = motion_nodes(st, n_u)
    t = np.arange(n_u) * (mot.period / n_u)
    psi_t, _, _ = mot.angles(t)
    chi = np.asarray(psi_t) - mot.psi_rate_mean() * t
    ang = np.arange(n_psi)[:, None] * (2.0 * math.pi / n_psi) + chi[None, :]
    c, s = np.cos(ang), np.sin(ang)
    Y = frame(st.n)
    B = np.empty((n_psi, n_u, 3, 3))  # Y R3(psi)
    B[..., 0] = Y[:, 0] * c[..., None] + Y[:, 1] * s[..., None]
    B[..., 1] = Y[:, 1] * c[..., None] - Y[:, 0] * s[..., None]
    B[..., 2] = Y[:, 2]
    C = B @ al[None]
    shape = (n_psi, n_u)
    assert st.nu is not None
    M = np.asarray(torque(np.broadcast_to(omega, (*shape, 3)), C, np.full(shape, st.nu)), dtype=float)
    V = quantities(st, omega, C, np.broadcast_to(M, (*shape, 3)))
    F = np.fft.fft2(V, axes=(0, 1)) / (n_psi * n_u)
    return F[j % n_psi, m % n_u]


def harmonic_bound(torque: Any, st: Any) -> np.ndarray:
    r"""Bounds on the resonant coefficients at a state, for every order: shape (2, 3), rows
    :math:`j = 1, 2`, columns the bounds of :math:`|\mathbf n\cdot\mathbf c_L|/G`, :math:`|c_T|/T` and
    :math:`|\mathbf c_L - (\mathbf n\cdot\mathbf c_L)\mathbf n|/G` (Parseval: the root mean square over the period
    of the :math:`j`-th harmonic over the precession angle of each). The nu of ``st`` is held."""
    grid = Grid(n_psi=_N_PSI)
    M, _, omega, C = torque_grid(torque, st, grid)
    V = quantities(st, omega, C, M[0])
    W = np.fft.fft(V, axis=0) / _N_PSI  # (psi harmonic, phase node, quantity)
    n = np.asarray(st.n, dtype=float)
    out = np.empty((2, 3))
    for j in (1, 2):
        L = W[j, :, 0:3]
        par = L @ n
        perp = L - par[:, None] * n
        out[j - 1] = (math.sqrt(float(np.mean(np.abs(par) ** 2))) / st.G,
                      math.sqrt(float(np.mean(np.abs(W[j, :, 3]) ** 2))) / st.T,
                      math.sqrt(float(np.mean(np.sum(np.abs(perp) ** 2, axis=1)))) / st.G)
    return out


def _crossings(rho: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(step index, j, N) of every crossing j rho = N (j = 1, 2) between successive nodes, N in (lo, hi]."""
    steps, js, Ns = [], [], []
    for j in (1, 2):
        jr = j * rho
        lo, hi = np.minimum(jr[:-1], jr[1:]), np.maximum(jr[:-1], jr[1:])
        first = np.floor(lo).astype(np.int64) + 1
        count = np.maximum(np.floor(hi).astype(np.int64) - first + 1, 0)
        i = np.repeat(np.arange(lo.size), count)
        start = np.cumsum(count) - count
        steps.append(i)
        js.append(np.full(i.size, j))
        Ns.append(first[i] + np.arange(i.size) - start[i])
    return np.concatenate(steps), np.concatenate(js), np.concatenate(Ns)


def _roots(f: Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]], a: np.ndarray,
           b: np.ndarray) -> np.ndarray:
    """Roots of ``f(t, idx) -> (value, slope)`` (members ``idx`` of a vectorised function) bracketed by [a, b],
    all together: Newton's method from the secant point, a bisection wherever a step leaves the bracket or does
    not halve the previous one (quadratic convergence, never slower than bisection)."""
    idx = np.arange(a.size)
    fa, fb = f(a, idx)[0], f(b, idx)[0]
    x = np.where(fa == 0.0, a, np.where(fb == 0.0, b, a - fa * (b - a) / np.where(fb != fa, fb - fa, 1.0)))
    x = np.where((x > np.minimum(a, b)) & (x < np.maximum(a, b)), x, 0.5 * (a + b))
    live = (fa != 0.0) & (fb != 0.0)
    last = np.abs(b - a)
    for _ in range(100):
        idx = np.flatnonzero(live)
        if idx.size == 0:
            break
        xi = x[idx]
        fx, dx = f(xi, idx)
        move_a = np.sign(fx) == np.sign(fa[idx])
        a[idx], fa[idx] = np.where(move_a, xi, a[idx]), np.where(move_a, fx, fa[idx])
        b[idx] = np.where(move_a, b[idx], xi)
        with np.errstate(divide="ignore", invalid="ignore"):
            xn = np.where(fx == 0.0, xi, xi - fx / dx)
        lo, hi = np.minimum(a[idx], b[idx]), np.maximum(a[idx], b[idx])
        step = np.abs(xn - xi)
        bisect = ~((xn >= lo) & (xn <= hi)) | ~(step <= 0.5 * last[idx])
        xn = np.where(bisect, 0.5 * (lo + hi), xn)
        last[idx] = np.abs(xn - xi)
        x[idx] = xn
        live[idx] = (fx != 0.0) & (last[idx] > _XTOL + 8.9e-16 * np.abs(xn)) & (hi - lo > _XTOL)
    return x


def _rate_of_rho(rho: Callable[[Any], Any], k2: np.ndarray, dk2: np.ndarray) -> np.ndarray:
    """d rho/d tau = (d rho/d k2) dk2/dtau, the k2 derivative by central differences (step 1e-6 k2)."""
    h = 1e-6 * np.maximum(k2, 1e-3)
    up, down = np.minimum(k2 + h, 1.0 - 1e-12), np.maximum(k2 - h, 0.0)
    return (rho(up) - rho(down)) / (up - down) * dk2


def _entry(tau: float, j: int, m: int, rho: float, jump: float, jump_G: float, jump_T: float, jump_n: float,
           bound: bool) -> dict[str, Any]:
    """One listed crossing."""
    return {"tau": tau, "j": j, "m": m, "rho": rho, "jump": jump, "jump_G": jump_G, "jump_T": jump_T,
            "jump_n": jump_n, "bound": bound}


def _exact(st: Any, j: int, N: int, tau: float, rho: Callable[[Any], Any], averager: Any, eps: float,
           period: Callable[[float, float], float]) -> dict[str, Any]:
    """The predicted jump of one crossing from its coefficient, computed at the crossing."""
    rate = abs(j * float(_rate_of_rho(rho, np.array([st.k2]), np.array([averager.mean(st).dk2]))[0]))
    c = harmonic(averager.torque, st, j, -N)
    amp = 2.0 * eps * math.sqrt(period(st.G, st.k2) / rate) if rate > 0 else math.inf
    par = complex(st.n @ c[0:3])
    jumps = (amp * abs(par) / st.G, amp * abs(complex(c[3])) / st.T,
             amp * float(np.linalg.norm(c[0:3] - par * st.n)) / st.G)
    return _entry(tau, j, -N, N / j, max(jumps), *jumps, False)


def resonance_crossings(res: Solution, rho: Callable[[Any], Any], state_at: Callable[[float, np.ndarray], Any],
                        period: Callable[[float, float], float], averager: Any, eps: float,
                        tol: float, k2_cap: float) -> list[dict[str, Any]]:
    r"""The resonance crossings :math:`j\rho = N` (:math:`j = 1, 2`) of one segment of an averaged run, sorted
    by time, up to the first whose predicted jump exceeds ``tol`` (inclusive; later ones are not computed).

    Parameters
    ----------
    res : Solution
        The segment's raw solution: rows ``G, k2, ...`` at the integrator's steps and its dense output.
    rho : callable
        The rotation number as a function of :math:`k^2` (vectorised).
    state_at : callable
        ``state_at(tau, y)``: the engine's slow state at a time from a raw state column.
    period : callable
        ``period(G, k2)``: the Euler--Poinsot period :math:`P`.
    averager : Averager
        The run's averager (its torque and its means).
    eps, tol : float
        :math:`\varepsilon > 0` and ``resonance_tol``.
    k2_cap : float
        The search stops there (next to the separatrix the passage is the separatrix crossing's business).

    Returns
    -------
    list of dict
        ``tau, j, m, rho, jump, jump_G, jump_T, jump_n, bound`` (``bound``: the jumps are upper bounds).
    """
    tau = res.time
    if tau.size < 2:
        return []
    step, js, Ns = _crossings(rho(np.clip(res.y[1], 0.0, k2_cap)))
    if step.size == 0:
        return []

    fit = _StepFit(res, rho, period, np.unique(step))
    # j = 1, N and j = 2, 2N are one crossing (rho = N): one root, the same time for both
    twice = 2 * Ns // js
    key, back = np.unique(step * (int(twice.max()) + 1) + twice, return_inverse=True)
    first = step[np.unique(back, return_index=True)[1]]
    half = (key - first * (int(twice.max()) + 1)) / 2.0

    def target(t: np.ndarray, i: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        v, d = fit.value_slope(t, 0)
        return v - half[i], d

    ts = _roots(target, tau[first].astype(float), tau[first + 1].astype(float))[back]
    out = _bounded(res, fit, ts, step, js, Ns, state_at, averager, eps, tol)
    exact = sorted((float(ts[i]), i) for i in range(ts.size) if i not in out)
    cut = min((e["tau"] for e in out.values() if e["jump"] > tol), default=math.inf)
    for t, i in exact:
        if t > cut:
            break
        y = res.sol(t)
        e = _exact(state_at(t, y), int(js[i]), int(Ns[i]), t, rho, averager, eps, period)
        out[i] = e
        if e["jump"] > tol:
            cut = min(cut, t)
    return sorted((e for e in out.values() if e["tau"] <= cut), key=lambda e: (e["tau"], e["j"]))


def _bounded(res: Solution, fit: _StepFit, ts: np.ndarray, step: np.ndarray, js: np.ndarray, Ns: np.ndarray,
             state_at: Callable[[float, np.ndarray], Any], averager: Any, eps: float, tol: float,
             ) -> dict[int, dict[str, Any]]:
    """The crossings above EXACT_ORDERS that the Parseval bound shows harmless ({index: entry}), and those
    beyond _MAX_ORDER (listed with their bound whatever it is)."""
    high = np.flatnonzero(Ns > EXACT_ORDERS)
    if high.size == 0:
        return {}
    tau = res.time
    ends = np.unique(np.concatenate([step[high], step[high] + 1]))
    b = np.stack([harmonic_bound(averager.torque, state_at(float(tau[i]), res.y[:, i])) for i in ends.tolist()])
    j = js[high]
    left = np.searchsorted(ends, step[high])
    bj = np.maximum(b[left, j - 1], b[left + 1, j - 1])  # (crossing, G/T/n); step + 1 follows step in ends
    th = ts[high]
    rate, P = np.abs(j * fit(th, 0, derivative=True)), fit(th, 1)
    with np.errstate(divide="ignore", invalid="ignore"):
        amp = np.where(rate > 0, 2.0 * eps * np.sqrt(P / np.where(rate > 0, rate, 1.0)), np.inf)
        jumps = amp[:, None] * bj
    big = jumps.max(axis=1)
    keep = (MARGIN * big <= tol) | (Ns[high] > _MAX_ORDER)
    N = Ns[high][keep]
    cols = [c.tolist() for c in (high[keep], th[keep], j[keep], -N, N / j[keep], big[keep], *jumps[keep].T)]
    return {i: _entry(t, jj, m, r, jump, g, T, n, True) for i, t, jj, m, r, jump, g, T, n in zip(*cols)}
