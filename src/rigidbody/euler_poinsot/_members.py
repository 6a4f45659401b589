"""The members of a batch: per-member inputs broadcast to one batch shape, the checks every member shares, and a
batch result assembled from single runs (the members that run one by one).

The batch convention of :func:`averaged` and :func:`simulate`: the per-member inputs (``eps``, ``G0``, ``k2_0`` or
``T0``, ``delta0``, ``lam0``, ``nu0``, for :func:`simulate` also ``u0``, ``psi0``, for :func:`averaged` a batch of drag
tensors) broadcast to one batch shape; everything else is shared.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..core.ode import Solution
from ..core.validate import span
from ._checks import check_tol
from ._model import Body, check_body, check_kind
from ._start import StartRules, check_start, initial_kind

__all__ = ["FIELDS", "Members", "assemble", "batch_grid", "check_members", "common_checks", "drag_batch", "grid_checks",
           "is_batch", "member_inputs"]


#: the output fields of an averaged run
FIELDS = ("G", "T", "k2", "delta", "lam", "nu", "n", "kind", "sigma")


# --------------------------------------------------------------------------------------------------
# members
# --------------------------------------------------------------------------------------------------
@dataclass
class Members:
    """Broadcast per-member inputs (flat arrays of the batch), their initial kind, and the members refused at
    the start (index -> the single call's message)."""

    batch_shape: tuple[int, ...]
    eps: np.ndarray
    G0: np.ndarray
    k2_0: np.ndarray
    delta0: np.ndarray
    lam0: np.ndarray
    nu0: np.ndarray
    kind: np.ndarray
    refused: dict[int, str] = field(default_factory=dict)


def _as_real_array(v: Any, name: str) -> np.ndarray:
    if isinstance(v, (bool, np.bool_, str, bytes)) or v is None:
        raise TypeError(f"{name} must be a real number or an array of them, got {v!r}")
    try:
        return np.asarray(v, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a real number or an array of them, got {v!r}") from None


def member_inputs(body: Body, eps: Any, G0: Any, k2_0: Any, delta0: Any, lam0: Any, nu0: Any, T0: Any = None,
                  kind: Any = None, shape: tuple[int, ...] = (), shape_of: str = "drag tensors") -> Members:
    """Broadcast the per-member inputs (and ``shape``, that of ``shape_of``: a batch of drag tensors, the phases
    of a full batch) to one batch shape
    (``TypeError``/``ValueError`` naming what does not broadcast or is not real); the initial kind and ``k2_0``
    of each member from ``T0`` as the single run finds them (a member whose ``T0`` it refuses is refused)."""
    if T0 is not None and (k2_0 is not None or kind is not None):
        raise ValueError("give the initial state either by T0 or by k2_0 and kind, not both")
    named = {"eps": eps, "G0": G0, "k2_0": 0.99 if k2_0 is None else k2_0, "delta0": delta0, "lam0": lam0,
             "nu0": nu0}
    if T0 is not None:
        named["T0"] = T0
    arrays = {k: _as_real_array(v, k) for k, v in named.items()}
    try:
        bshape = np.broadcast_shapes(shape, *(a.shape for a in arrays.values()))
    except ValueError:
        shapes = ", ".join(f"{k} {a.shape}" for k, a in arrays.items() if a.ndim)
        raise ValueError(f"the per-member inputs do not broadcast to one batch shape: {shapes}"
                         + (f", {shape_of} {shape}" if shape else "")) from None
    if not bshape:
        raise ValueError("a batch needs at least one array input")
    if 0 in bshape:
        raise ValueError(f"the batch is empty (shape {bshape})")
    flat = {k: np.broadcast_to(a, bshape).reshape(-1).copy() for k, a in arrays.items()}
    B = flat["eps"].size
    kinds = np.empty(B, dtype=object)
    mem = Members(tuple(int(v) for v in bshape), flat["eps"], flat["G0"], flat["k2_0"], flat["delta0"],
                  flat["lam0"], flat["nu0"], kinds)
    if T0 is None:

        kd = "max" if kind is None else kind
        check_kind(kd)
        kinds[:] = kd
        return mem
    for i in range(B):
        try:
            G = float(flat["G0"][i])
            if not (math.isfinite(G) and G > 0):  # T0's range needs G0: its own check comes later
                kinds[i] = "max"
                continue
            mem.k2_0[i], kinds[i] = initial_kind(body, G, None, None, float(flat["T0"][i]))
        except ValueError as exc:
            kinds[i] = "max"
            mem.refused[i] = str(exc)
    return mem


def check_members(mem: Members, rules: StartRules, u0: Any = None, psi0: Any = None) -> None:
    """The single run's start checks (:func:`._start.check_start`), member by member: a refused member gets the
    single call's message (``rules.full``: those of :func:`simulate`, with the members' phases ``u0``, ``psi0``)."""
    for i in range(mem.eps.size):
        if i in mem.refused:
            continue
        phase = (float(u0[i]), float(psi0[i])) if rules.full else (0.0, 0.0)
        try:
            check_start(rules, mem.kind[i], float(mem.eps[i]), float(mem.G0[i]), float(mem.k2_0[i]),
                        float(mem.delta0[i]), float(mem.lam0[i]), float(mem.nu0[i]), *phase)
        except ValueError as exc:
            mem.refused[i] = str(exc)


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


#: the reports a single run may carry besides its fields (optional fields of its Solution)
_REPORTS = ("quad_error", "resonances", "crossings")


def assemble(solutions: list[Solution | str], batch_shape: tuple[int, ...], te: np.ndarray,
             names: tuple[str, ...], producer: str) -> Solution:
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
    extras = {k: np.empty(B, dtype=object) for k in _REPORTS}
    reported: set[str] = set()
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
        r = min(ys.shape[1], s.y.shape[0])  # raw rows: the leading ones are common (e.g. G, k2, n [, nu])
        ys[i][:r, cols] = s.y[:r]
        for k in names:
            v = np.asarray(getattr(s, k))
            if k not in data:
                fill: Any = "" if v.dtype.kind == "U" else np.nan
                data[k] = np.full((B, *v.shape[:-1], nt), fill, dtype=v.dtype if v.dtype.kind == "U" else float)
            data[k][i][..., cols] = v
        for k, v in s.t_events.items():
            if k not in events:
                events[k] = np.empty(B, dtype=object)
                none = np.empty(0)
                none.setflags(write=False)
                events[k].fill(none)
            events[k][i] = np.asarray(v, dtype=float)
        reported.update(k for k in _REPORTS if k in s.__dict__)
        for k in _REPORTS:  # per-run reports (a run that records none: the declared default)
            extras[k][i] = getattr(s, k)
    if ys is None:  # no member ran: the raw rows G, k2, n
        ys = np.full((B, 5, nt), np.nan)
    for k in names:  # fields no member produced (all refused): NaN, as a refused member's
        if k not in data:
            data[k] = np.full((B, 3, nt), np.nan) if k == "n" else (
                np.full((B, nt), "", dtype="<U3") if k == "kind" else np.full((B, nt), np.nan))
    fields_ = {k: v.reshape(batch_shape + v.shape[1:]) for k, v in data.items()}
    reports: dict[str, Any] = {k: extras[k].reshape(batch_shape) for k in sorted(reported)}
    return Solution.build(producer=producer, time_name="tau", time=te, y=ys.reshape(batch_shape + ys.shape[1:]),
                          fields=fields_, status=status.reshape(batch_shape), message=message.reshape(batch_shape),
                          event=event.reshape(batch_shape),
                          t_events={k: v.reshape(batch_shape) for k, v in events.items()},
                          nfev=nfev.reshape(batch_shape), t_final=t_final.reshape(batch_shape),
                          **reports)


def common_checks(body: Any, tau_span: Any, tau_eval: Any, opts: dict[str, Any]) -> tuple[float, float, np.ndarray]:
    """The checks a batch of a triaxial :class:`Body` shares: the body, then :func:`grid_checks`."""
    check_body(body)
    return grid_checks(tau_span, tau_eval, opts)


def grid_checks(tau_span: Any, tau_eval: Any, opts: dict[str, Any]) -> tuple[float, float, np.ndarray]:
    """``tau_span``, the common output grid in it, the tolerances and the method (DOP853) of a batch."""
    t0, t1 = span(tau_span, "tau_span")
    te = batch_grid(tau_eval, (t0, t1))
    if te.size and (te[0] < t0 or te[-1] > t1):
        raise ValueError(f"tau_eval must lie within tau_span = {tuple(tau_span)!r}, got [{te[0]}, {te[-1]}]")
    check_tol(opts["rtol"], opts["atol"])
    if opts["method"] != "DOP853":
        raise ValueError(f"a batch integrates with method='DOP853' (integrate_batch), got {opts['method']!r}")
    return t0, t1, te
