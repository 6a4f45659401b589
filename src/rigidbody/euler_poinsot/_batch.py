r"""A batch of averaged evolutions (9) integrated together, and the single run of the same equations.

The members share the body, the torque, the orbit, ``tau_span`` and the options; their initial slow variables
``G0, k2_0, delta0, lam0``, the true anomaly ``nu0`` and ``eps`` are arrays broadcast to one batch shape. The
closed forms of a drag tensor (:mod:`._kernel`) are evaluated on all active members at once by
:func:`rigidbody.core.batch.integrate_batch` (per-member DOP853 step control, events and status); the members
with ``eps = 0`` (orbit-averaged, state ``(ln G, ln k^2, lambda)``) and those with ``eps > 0`` (state
``(ln G, ln k^2, delta, lambda[, nu])``) form two sub-batches. A member ends on its own events
(``'separatrix'``, ``'slow_rotation'``) with its own status and message, which are those of its single run;
a member whose start is refused by the single run (a ``ValueError`` there) gets ``status = -1`` and that
message, and the others go on.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core.batch import integrate_batch
from ..core.kernel import ARRAY, SCALAR
from ..core.ode import Event, Solution, integrate
from . import _kernel as _k
from ._model import Orbit

__all__ = ["ClosedRun", "closed_batch", "closed_single", "member_inputs"]

_AX = ARRAY
_SC = SCALAR

#: the order of the output fields of an averaged run
FIELDS = ("G", "T", "k2", "delta", "lam", "nu", "n")


def separatrix_message(k2_max: float) -> str:
    return (f"k2 reached {k2_max:g}: the Euler-Poinsot motion approaches the separatrix 2T A2 = G^2, "
            "where the averaging (6) does not hold")


def slow_message(r: float) -> str:
    return (f"the rotation is no longer fast: (2 pi / Euler-Poinsot period) / omega0 fell to {r:g}; "
            "the averaging over the Euler-Poinsot motion (eps << 1) no longer holds")


@dataclass
class ClosedRun:
    """What the closed-form runs of one kind of motion share: labelled moments and drag, orbit, options."""

    A: tuple[float, float, float]
    Id: tuple[Any, Any, Any]
    orbit: Orbit
    rtol: float
    k2_max: float
    min_spin_ratio: float

    @property
    def coefficients(self) -> _k.DragCoefficients:
        return _k.DragCoefficients(self.A, self.Id)


# --------------------------------------------------------------------------------------------------
# initial state and output fields, shared by one run and a batch
# --------------------------------------------------------------------------------------------------
def initial_state(eps: Any, G0: Any, k2_0: Any, delta0: Any, lam0: Any, nu0: Any, e: float) -> tuple[Any, Any]:
    """The state vector(s) and the factor ``z`` (0 where ``k2_0 = 0``); arrays of members or floats."""
    z = np.where(np.asarray(k2_0) > 0.0, 1.0, 0.0)
    with np.errstate(divide="ignore"):
        s0 = np.where(z > 0.0, np.log(np.where(z > 0.0, k2_0, 1.0)), 0.0)
    lnG = np.log(G0)
    if np.ndim(eps) == 0 and float(eps) == 0.0:
        y = [lnG, s0, lam0]
    else:
        y = [lnG, s0, delta0, lam0] + ([nu0] if e != 0.0 else [])
    return np.stack(np.broadcast_arrays(*y), axis=-1), z


def fields(run: ClosedRun, tau: np.ndarray, y: np.ndarray, z: Any, limit: bool, delta0: Any, nu0: Any,
           ie: Any) -> dict[str, np.ndarray]:
    """Output fields from raw states ``y`` of shape ``(..., n_state, n_t)`` (members on the leading axes)."""
    lnG, s = y[..., 0, :], y[..., 1, :]
    G = np.exp(lnG)
    k2 = np.exp(s)
    k2 *= np.asarray(z, dtype=float)[..., None]
    np.minimum(k2, 1.0, out=k2)
    A1, A2, A3 = run.A
    T = A1 * (A2 - A3) + A3 * (A1 - A2) * k2  # G^2 S/(2R), in place
    np.divide(A2 - A3 + (A1 - A2) * k2, T, out=T)
    T *= 0.5 * G * G
    if limit:
        nan = np.isnan(lnG)
        delta = np.where(nan, np.nan, np.asarray(delta0, dtype=float)[..., None])
        lam = y[..., 2, :]
        nu = np.where(nan, np.nan, np.asarray(nu0, dtype=float)[..., None])
    else:
        delta, lam = y[..., 2, :], y[..., 3, :]
        if run.orbit.e != 0.0:
            nu = y[..., 4, :]
        else:  # NaN where the state is (0 * NaN)
            nu = tau * np.asarray(ie, dtype=float)[..., None] + np.asarray(nu0, dtype=float)[..., None] + 0.0 * lnG
    n = np.empty((*lam.shape[:-1], 3, lam.shape[-1]))
    sd = np.sin(delta)
    np.cos(lam, out=n[..., 0, :])
    n[..., 0, :] *= sd
    np.sin(lam, out=n[..., 1, :])
    n[..., 1, :] *= sd
    np.cos(delta, out=n[..., 2, :])
    return {"G": G, "T": T, "k2": k2, "delta": delta, "lam": lam, "nu": nu, "n": n}


# --------------------------------------------------------------------------------------------------
# one run
# --------------------------------------------------------------------------------------------------
def closed_single(run: ClosedRun, eps: float, G0: float, k2_0: float, delta0: float, lam0: float, nu0: float,
                  tau_span: tuple[float, float], tau_eval: Any, method: str = "DOP853") -> Solution:
    """One closed-form run from valid inputs: the raw state ``(ln G, ln k^2, [delta,] lambda[, nu])`` with the
    output fields. DOP853 runs on Python floats (``core.ode.integrate(engine='python')``)."""
    A, e = run.A, run.orbit.e
    co = run.coefficients
    g1, g2, g3, c3, c1 = (float(v) for v in co.args())
    limit = eps == 0.0
    y0, z_a = initial_state(eps, G0, k2_0, delta0, lam0, nu0, e)
    z = float(z_a)
    lnk_max = math.log(run.k2_max)
    if limit:
        hl = 0.75 * run.orbit.mean_factor * math.cos(delta0)

        def rhs(tau: float, y: Any) -> list[float]:
            return _k.rhs_limit(_SC, A, tau, y, g1, g2, g3, c3, c1, z, hl)
    else:
        ie = 1.0 / eps

        def rhs(tau: float, y: Any) -> list[float]:
            return _k.rhs_orbit(_SC, A, e, tau, y, g1, g2, g3, c3, c1, z, ie, nu0)

    events = [Event((lambda t, y: y[1] - lnk_max) if z > 0.0 else (lambda t, y: -1.0), "separatrix", True, 1.0,
                    separatrix_message(run.k2_max))]
    if not limit:
        r = run.min_spin_ratio
        events.append(Event(lambda t, y: _k.nut_freq(_SC, A, math.exp(y[0]), min(z * math.exp(y[1]), 1.0)) * ie - r,
                            "slow_rotation", True, -1.0, slow_message(r)))
    rt: Any
    rt, at = _k.tolerances(run.rtol, y0.size)
    py = method == "DOP853"
    te = None if tau_eval is None else np.asarray(tau_eval, dtype=float)
    sol = integrate(rhs, tau_span, y0, t_eval=te, rtol=rt if py else _k.RTOL_FLOOR, atol=at, method=method,
                    events=events, time_name="tau", engine="python" if py else "scipy",
                    fields=lambda t, y: fields(run, t, y, z, limit, delta0, nu0, 0.0 if limit else 1.0 / eps))
    return sol


# --------------------------------------------------------------------------------------------------
# a batch
# --------------------------------------------------------------------------------------------------
@dataclass
class Members:
    """Broadcast per-member inputs (flat arrays of the batch) and the members refused at the start."""

    batch_shape: tuple[int, ...]
    eps: np.ndarray
    G0: np.ndarray
    k2_0: np.ndarray
    delta0: np.ndarray
    lam0: np.ndarray
    nu0: np.ndarray
    refused: dict[int, str]


def member_inputs(eps: Any, G0: Any, k2_0: Any, delta0: Any, lam0: Any, nu0: Any) -> Members:
    """Broadcast the per-member inputs to one batch shape (``TypeError``/``ValueError`` naming the parameter
    that does not broadcast or is not real)."""
    arrays = {}
    for name, v in (("eps", eps), ("G0", G0), ("k2_0", k2_0), ("delta0", delta0), ("lam0", lam0), ("nu0", nu0)):
        if isinstance(v, (bool, np.bool_, str, bytes)) or v is None:
            raise TypeError(f"{name} must be a real number or an array of them, got {v!r}")
        try:
            a = np.asarray(v, dtype=float)
        except (TypeError, ValueError):
            raise TypeError(f"{name} must be a real number or an array of them, got {v!r}") from None
        arrays[name] = a
    try:
        shape = np.broadcast_shapes(*(a.shape for a in arrays.values()))
    except ValueError:
        shapes = ", ".join(f"{k} {a.shape}" for k, a in arrays.items() if a.ndim)
        raise ValueError(f"the per-member inputs do not broadcast to one batch shape: {shapes}") from None
    if not shape:
        raise ValueError("a batch needs at least one array input")
    if 0 in shape:
        raise ValueError(f"the batch is empty (shape {shape})")
    flat = {k: np.broadcast_to(a, shape).reshape(-1).copy() for k, a in arrays.items()}
    return Members(tuple(int(s) for s in shape), flat["eps"], flat["G0"], flat["k2_0"], flat["delta0"],
                   flat["lam0"], flat["nu0"], {})


def check_members(mem: Members, run: ClosedRun) -> None:
    """The single run's input checks, member by member: a refused member gets the single call's message."""
    A = run.A
    for i in range(mem.eps.size):
        eps, G0, k2_0, d0 = mem.eps[i], mem.G0[i], mem.k2_0[i], mem.delta0[i]
        msg = None
        if not all(math.isfinite(v) for v in (eps, G0, k2_0, d0, mem.lam0[i], mem.nu0[i])):
            msg = "the initial values must be finite"
        elif eps < 0:
            msg = f"eps must be >= 0 (eps = omega0/omega), got {eps}"
        elif G0 <= 0:
            msg = f"G0 must be positive, got {G0}"
        elif not (0.0 <= k2_0 < 1.0):
            msg = f"k2_0 must lie in [0, 1) (k2 = 1 is the separatrix), got {k2_0}"
        elif not (0.0 <= d0 <= math.pi):
            msg = f"delta0 (polar angle of G from x3) must lie in [0, pi], got {d0}"
        elif not k2_0 < run.k2_max:
            msg = (f"k2_max (the separatrix stop) must lie in (k2_0, 1] = ({k2_0}, 1], got {run.k2_max}: "
                   "raise k2_max or start further from the separatrix")
        elif eps > 0 and run.min_spin_ratio > 0:
            ratio = float(_k.nut_freq(_SC, A, G0, k2_0)) / eps
            if ratio <= run.min_spin_ratio:
                msg = (f"eps = {eps:g} is too large for this state: the Euler-Poinsot frequency over the orbital "
                       f"rate is {ratio:.3g} <= min_spin_ratio = {run.min_spin_ratio:g} (the rotation is not "
                       "fast); lower eps, or pass min_spin_ratio=0 to integrate anyway outside the theory")
        if msg is not None:
            mem.refused[i] = msg


def closed_batch(run: ClosedRun, mem: Members, tau_span: tuple[float, float], te: np.ndarray) -> Solution:
    """The batch of closed-form runs (``te`` the common output grid); ``mem.refused`` members end at once."""
    B = mem.eps.size
    nt = te.size
    t0, t1 = float(tau_span[0]), float(tau_span[1])
    e = run.orbit.e
    A = run.A
    status = np.full(B, -1, dtype=int)
    message = np.empty(B, dtype=object)
    event = np.empty(B, dtype=object)
    event[:] = None
    nfev = np.zeros(B, dtype=int)
    t_final = np.full(B, t0)
    ymax = 5 if e != 0.0 else 4
    done: list[tuple[np.ndarray, dict[str, np.ndarray], np.ndarray]] = []  # members, fields, raw rows
    none = np.empty(0)
    none.setflags(write=False)
    tev: dict[str, np.ndarray] = {}
    for name in ("separatrix", "slow_rotation"):
        tev[name] = np.empty(B, dtype=object)
        tev[name].fill(none)
    for i, msg in mem.refused.items():
        message[i] = msg
    ok = np.ones(B, dtype=bool)
    ok[list(mem.refused)] = False
    lnk_max = math.log(run.k2_max)
    Id = tuple(np.broadcast_to(np.asarray(v, dtype=float), (B,)) for v in run.Id)
    co = _k.DragCoefficients(A, Id)  # type: ignore[arg-type]  # arrays of members
    cf = co.args()

    r = run.min_spin_ratio

    def sep(t: np.ndarray, y: np.ndarray, *a: np.ndarray) -> np.ndarray:
        return np.where(a[5] > 0.0, y[:, 1] - lnk_max, -1.0)

    def rhs_lim(t: np.ndarray, y: np.ndarray, *a: np.ndarray) -> np.ndarray:
        return np.stack(_k.rhs_limit(_AX, A, t, y.T, *a), axis=1)

    def rhs_orb(t: np.ndarray, y: np.ndarray, *a: np.ndarray) -> np.ndarray:
        return np.stack(_k.rhs_orbit(_AX, A, e, t, y.T, *a), axis=1)

    def slow(t: np.ndarray, y: np.ndarray, *a: np.ndarray) -> np.ndarray:
        return _k.nut_freq(_AX, A, np.exp(y[:, 0]), _k.k2_of(_AX, y[:, 1], a[5])) * a[6] - r

    groups = [(np.nonzero(ok & (mem.eps == 0.0))[0], True), (np.nonzero(ok & (mem.eps > 0.0))[0], False)]
    for idx, limit in groups:
        if not idx.size:
            continue
        y0, z = initial_state(0.0 if limit else mem.eps[idx], mem.G0[idx], mem.k2_0[idx], mem.delta0[idx],
                              mem.lam0[idx], mem.nu0[idx], e)
        args: tuple[np.ndarray, ...] = (*(c[idx] for c in cf), z)
        events = [Event(sep, "separatrix", True, 1.0, separatrix_message(run.k2_max))]
        if limit:
            args = (*args, 0.75 * run.orbit.mean_factor * np.cos(mem.delta0[idx]))
            ie = np.zeros(idx.size)
            rhs = rhs_lim
        else:
            ie = 1.0 / mem.eps[idx]
            args = (*args, ie, mem.nu0[idx])
            rhs = rhs_orb
            events.append(Event(slow, "slow_rotation", True, -1.0, slow_message(r)))
        ns = y0.shape[1]
        rt, at = _k.tolerances(run.rtol, ns)
        sol = integrate_batch(rhs, (t0, t1), y0, t_eval=te, rtol=rt, atol=at, events=events, args=args,
                              time_name="tau")
        f = fields(run, te, sol.y, z, limit, mem.delta0[idx], mem.nu0[idx], ie)
        if limit:  # the raw rows (ln G, ln k2, delta, lambda[, nu]) of every member
            y = np.empty((idx.size, ymax, nt))
            y[:, 0:2], y[:, 2], y[:, 3] = sol.y[:, 0:2], f["delta"], sol.y[:, 2]
            if ymax == 5:
                y[:, 4] = f["nu"]
        else:
            y = sol.y
        done.append((idx, f, y))
        status[idx] = sol.status
        message[idx] = sol.message
        event[idx] = sol.event
        nfev[idx] = sol.nfev
        t_final[idx] = sol.t_final
        for name in tev:
            if name in sol.t_events:
                tev[name][idx] = sol.t_events[name]
    shape = mem.batch_shape
    if len(done) == 1 and done[0][0].size == B:  # one group of every member: its arrays as they are
        out, Y = done[0][1], done[0][2]
    else:
        out = {k: np.full((B, 3, nt) if k == "n" else (B, nt), np.nan) for k in FIELDS}
        Y = np.full((B, ymax, nt), np.nan)
        for idx, f, y in done:
            for k in FIELDS:
                out[k][idx] = f[k]
            Y[idx] = y
    data = {k: v.reshape(shape + v.shape[1:]) for k, v in out.items()}
    t_events = {name: arr.reshape(shape) for name, arr in tev.items()}
    return Solution("tau", te, Y.reshape(shape + Y.shape[1:]), data, status.reshape(shape), message.reshape(shape),
                    event.reshape(shape), t_events, {}, None, nfev.reshape(shape), batch_shape=shape,
                    t_final=t_final.reshape(shape))


# --------------------------------------------------------------------------------------------------
# the public batch entries (averaged and simulate dispatch here when an input is an array)
# --------------------------------------------------------------------------------------------------
def is_batch(*values: Any) -> bool:
    """Whether any per-member input is an array (a batch call)."""
    return any(np.ndim(v) > 0 for v in values)


def drag_batch(torque: Any) -> np.ndarray | None:
    """A batch of drag tensors (an array of shape ``batch_shape + (3, 3)``, ``batch_shape`` non-empty), or None."""
    if isinstance(torque, (str, bytes)) or callable(torque) or torque is None:
        return None
    try:
        a = np.asarray(torque, dtype=float)
    except (TypeError, ValueError):
        return None
    return a if a.ndim >= 3 and a.shape[-2:] == (3, 3) else None


def batch_grid(tau_eval: Any, tau_span: tuple[float, float]) -> np.ndarray:
    """The common output grid of a batch: ``tau_eval`` (strictly increasing) or 101 points over the span."""
    t0, t1 = float(tau_span[0]), float(tau_span[1])
    if tau_eval is None:
        return np.linspace(t0, t1, 101)
    te = np.atleast_1d(np.asarray(tau_eval, dtype=float))
    if te.ndim != 1 or (te.size > 1 and np.any(np.diff(te) <= 0.0)):
        raise ValueError("tau_eval of a batch must be a strictly increasing 1-D array (the common output grid)")
    return te


def drag_members(run: ClosedRun, mem: Members, tensors: np.ndarray, kind: str) -> None:
    """Per-member drag tensors (validated like :class:`Drag`; an invalid one refuses its member) into ``run.Id``
    in the labelling of ``kind``."""
    from ._model import Drag

    shape = tensors.shape[:-2]
    try:
        np.broadcast_shapes(shape, mem.batch_shape)
    except ValueError:
        raise ValueError(f"the batch of drag tensors (shape {tensors.shape}) does not broadcast against the batch "
                         f"shape {mem.batch_shape} of the other inputs") from None
    full = np.broadcast_shapes(shape, mem.batch_shape)
    if full != mem.batch_shape:
        raise ValueError(f"the batch of drag tensors (shape {tensors.shape}) has more members than the other inputs "
                         f"(batch shape {mem.batch_shape}): give the per-member inputs that shape")
    T = np.broadcast_to(tensors, (*full, 3, 3)).reshape(-1, 3, 3)
    diag = np.full((T.shape[0], 3), np.nan)
    for i in range(T.shape[0]):
        try:
            diag[i] = Drag(T[i]).diag
        except ValueError as exc:
            mem.refused.setdefault(i, str(exc))
    d = (diag[:, 0], diag[:, 1], diag[:, 2])
    run.Id = d if kind == "max" else (d[2], d[1], d[0])


def assemble(solutions: list[Solution | str], batch_shape: tuple[int, ...], te: np.ndarray,
             names: tuple[str, ...]) -> Solution:
    """A batch Solution from single runs evaluated on ``te`` (a str: the message of a member refused at the
    start, status -1). The engine path of :func:`averaged` and the ``'angles'`` formulation of :func:`simulate`
    go member by member this way."""
    B = len(solutions)
    nt = te.size
    status = np.full(B, -1, dtype=int)
    message = np.empty(B, dtype=object)
    event = np.empty(B, dtype=object)
    event[:] = None
    nfev = np.zeros(B, dtype=int)
    t_final = np.full(B, np.nan)
    data: dict[str, np.ndarray] = {}
    ys: np.ndarray | None = None
    events: dict[str, np.ndarray] = {}
    extras: dict[str, np.ndarray] = {}
    for i, s in enumerate(solutions):
        if isinstance(s, str):
            message[i] = s
            continue
        status[i], message[i], event[i], nfev[i] = int(s.status), str(s.message), s.event, int(s.nfev)
        ev_t = s.t_events.get(s.event, np.empty(0)) if s.event is not None else np.empty(0)
        t_final[i] = float(ev_t[-1]) if np.size(ev_t) else (float(s.time[-1]) if s.time.size else np.nan)
        cols = np.searchsorted(te, s.time)
        if ys is None:
            ys = np.full((B, s.y.shape[0], nt), np.nan)
        ys[i][:, cols] = s.y
        for k in names:
            v = np.asarray(getattr(s, k))
            if k not in data:
                fill: Any = "" if v.dtype.kind == "U" else np.nan
                data[k] = np.full((B, *v.shape[:-1], nt), fill, dtype=v.dtype if v.dtype.kind == "U" else float)
            data[k][i][..., cols] = v
        for k, v in s.t_events.items():
            if k not in events:
                events[k] = np.empty(B, dtype=object)
                events[k].fill(np.empty(0))
            events[k][i] = np.asarray(v, dtype=float)
        for k in ("quad_error", "resonances", "crossings"):  # per-run reports of the engine path
            if k in s.__dict__:
                extras.setdefault(k, np.empty(B, dtype=object))[i] = s.__dict__[k]
    if ys is None:
        ys = np.full((B, 1, nt), np.nan)
    fields_ = {k: v.reshape(batch_shape + v.shape[1:]) for k, v in data.items()}
    sol = Solution("tau", te, ys.reshape(batch_shape + ys.shape[1:]), fields_, status.reshape(batch_shape),
                   message.reshape(batch_shape), event.reshape(batch_shape),
                   {k: v.reshape(batch_shape) for k, v in events.items()}, {}, None, nfev.reshape(batch_shape),
                   batch_shape=batch_shape, t_final=t_final.reshape(batch_shape))
    for k, v in extras.items():
        setattr(sol, k, v.reshape(batch_shape))
    return sol


def one_by_one(call: Any, mem: Members, te: np.ndarray, names: tuple[str, ...], **per_member: np.ndarray) -> Solution:
    """Each member by its own single call ``call(eps, G0, k2_0, delta0, lam0, nu0, tau_eval=..., **extra)``; a
    ``ValueError`` refuses that member (status -1, its message)."""
    out: list[Solution | str] = []
    for i in range(mem.eps.size):
        if i in mem.refused:
            out.append(mem.refused[i])
            continue
        extra = {k: float(v[i]) for k, v in per_member.items()}
        try:
            out.append(call(float(mem.eps[i]), float(mem.G0[i]), float(mem.k2_0[i]), float(mem.delta0[i]),
                            float(mem.lam0[i]), float(mem.nu0[i]), te, **extra))
        except ValueError as exc:
            out.append(str(exc))
    return assemble(out, mem.batch_shape, te, names)


def averaged_batch(body: Any, torque: Any, eps: Any, G0: Any, k2_0: Any, delta0: Any, lam0: Any,
                   tau_span: Any, tau_eval: Any, nu0: Any, opts: dict[str, Any], single: Any) -> Solution:
    """The batch branch of :func:`rigidbody.euler_poinsot.averaged`.

    ``opts`` holds the keyword options of the call (validated here as the single run validates them), ``single``
    is :func:`averaged` itself (members of the engine path run one by one through it).
    """
    from ..core.validate import positive, real, span
    from ._averaged import _check_method, _check_sigma, _check_tol
    from ._model import _as_orbit, _check_body, _check_kind, _labels
    from ._torques import resolve

    _check_body(body)
    t0, t1 = span(tau_span, "tau_span")
    te = batch_grid(tau_eval, (t0, t1))
    if te.size and (te[0] < t0 or te[-1] > t1):
        raise ValueError(f"tau_eval must lie within tau_span = {tuple(tau_span)!r}, got [{te[0]}, {te[-1]}]")
    rtol, atol = opts["rtol"], opts["atol"]
    _check_tol(rtol, atol)
    kind = opts["kind"]
    _check_kind(kind)
    orb = _as_orbit(opts["orbit"])
    _check_method(opts["averaging"], "averaging")
    _check_sigma(opts["sigma"])
    if opts["method"] != "DOP853":
        raise ValueError(f"a batch integrates with method='DOP853' (integrate_batch), got {opts['method']!r}")
    k2_max = real(opts["k2_max"], "k2_max")
    if not 0.0 < k2_max <= 1.0:
        raise ValueError(f"k2_max (the separatrix stop) must lie in (0, 1], got {k2_max}")
    min_spin = real(opts["min_spin_ratio"], "min_spin_ratio")
    positive(opts["quad_tol"], "quad_tol")
    mem = member_inputs(eps, G0, k2_0, delta0, lam0, nu0)
    tensors = drag_batch(torque)
    run = ClosedRun(_labels(body, kind), (0.0, 0.0, 0.0), orb, float(rtol), k2_max, min_spin)
    if tensors is not None:
        if opts["averaging"] != "auto":
            raise ValueError("a batch of drag tensors is integrated with the closed forms (averaging='auto')")
        drag_members(run, mem, tensors, kind)
        check_members(mem, run)
        return closed_batch(run, mem, (t0, t1), te)
    what, tq = resolve(torque)
    if what == "drag" and opts["averaging"] == "auto":
        run.Id = _labels(body, kind, tq.diag)[1]
        check_members(mem, run)
        return closed_batch(run, mem, (t0, t1), te)

    # the engine path: member by member through the single run (its adaptive quadrature is per state)
    def call(eps_: float, G0_: float, k2_: float, d0: float, l0: float, n0: float, te_: np.ndarray) -> Solution:
        return single(body, torque, eps_, G0_, k2_, d0, l0, (t0, t1), te_, n0, **opts)

    return one_by_one(call, mem, te, FIELDS)


def simulate_batch(body: Any, torque: Any, eps: Any, G0: Any, k2_0: Any, delta0: Any, lam0: Any, tau_span: Any,
                   tau_eval: Any, nu0: Any, u0: Any, psi0: Any, opts: dict[str, Any], single: Any) -> Solution:
    """The batch branch of :func:`rigidbody.euler_poinsot.simulate` (``opts``: its keyword options; ``single``:
    :func:`simulate`, through which the ``'angles'`` formulation runs member by member)."""
    from ..core.validate import real, span
    from ._averaged import _check_sigma, _check_tol
    from ._fullbatch import FullRun, full_batch
    from ._model import _as_orbit, _check_body, _check_kind, _labels
    from ._torques import probe, resolve

    _check_body(body)
    t0, t1 = span(tau_span, "tau_span")
    te = batch_grid(tau_eval, (t0, t1))
    if te.size and (te[0] < t0 or te[-1] > t1):
        raise ValueError(f"tau_eval must lie within tau_span = {tuple(tau_span)!r}, got [{te[0]}, {te[-1]}]")
    _check_tol(opts["rtol"], opts["atol"])
    kind = opts["kind"]
    _check_kind(kind)
    sigma = _check_sigma(opts["sigma"])
    orb = _as_orbit(opts["orbit"])
    if opts["formulation"] not in ("body", "angles"):
        raise ValueError(f"formulation must be 'body' or 'angles', got {opts['formulation']!r}")
    k2_max = None if opts["k2_max"] is None else real(opts["k2_max"], "k2_max")
    min_spin = real(opts["min_spin_ratio"], "min_spin_ratio")
    mem = member_inputs(eps, G0, k2_0, delta0, lam0, nu0)
    try:
        ph = np.broadcast_to(np.asarray(u0, dtype=float), mem.batch_shape).reshape(-1)
        ps = np.broadcast_to(np.asarray(psi0, dtype=float), mem.batch_shape).reshape(-1)
    except ValueError:
        raise ValueError(f"u0 and psi0 must broadcast to the batch shape {mem.batch_shape}") from None
    what, tq = resolve(torque)
    if what == "torque":
        tq._check_setup(body, orb)
    if opts["formulation"] == "angles" or opts["method"] != "DOP853":
        def call(eps_: float, G0_: float, k2_: float, d0: float, l0: float, n0: float, te_: np.ndarray,
                 u0: float, psi0: float) -> Solution:
            return single(body, torque, eps_, G0_, k2_, d0, l0, (t0, t1), te_, n0, u0=u0, psi0=psi0, **opts)

        names = ("G", "T", "k2", "delta", "lam", "nu", "n")
        return one_by_one(call, mem, te, names, u0=ph, psi0=ps)
    run = FullRun(body, what, tq, orb, kind, sigma, float(opts["rtol"]), float(opts["atol"]), k2_max, min_spin)
    # the single run's checks, member by member (eps > 0 here: the full equations need a fast rotation)
    crun = ClosedRun(_labels(body, kind), (0.0, 0.0, 0.0), orb, float(opts["rtol"]),
                     1.0 if k2_max is None else k2_max, min_spin)
    check_members(mem, crun)
    for i in range(mem.eps.size):
        if i not in mem.refused and not mem.eps[i] > 0.0:
            mem.refused[i] = "eps must be positive for the full equations (eps = 0 has no fast rotation to resolve)"
    if what == "torque":  # one evaluation at a valid member's start, with the single run's message on failure
        from ._full import initial_state

        good = [i for i in range(mem.eps.size) if i not in mem.refused]
        if good:
            i = good[0]
            st = initial_state(body, float(mem.G0[i]), float(mem.k2_0[i]), float(mem.delta0[i]), float(mem.lam0[i]),
                               kind=kind, u0=float(ph[i]), psi0=float(ps[i]), sigma=sigma)
            probe(tq, st["g"] / body.A, st["R"], float(mem.nu0[i]))
    return full_batch(run, mem, ph, ps, (t0, t1), te)
