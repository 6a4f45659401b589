"""The output of a run on the requested times: lambda unwrapped along the solver's steps, dense output of pieces."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..core.ode import Solution

__all__ = ["PiecewiseDense", "finish_output", "lam_unwrapped", "unit_of_angles"]


def unit_of_angles(delta: float, lam: float) -> tuple[float, float, float]:
    return (math.sin(delta) * math.cos(lam), math.sin(delta) * math.sin(lam), math.cos(delta))


def lam_unwrapped(tau_fine: np.ndarray, n_fine: np.ndarray, lam0: float) -> np.ndarray:
    lam = np.unwrap(np.arctan2(n_fine[1], n_fine[0]))
    # choose the branch of the initial value given by the user
    return lam + 2.0 * math.pi * round((lam0 - lam[0]) / (2.0 * math.pi))


def finish_output(
    res: Solution,
    tau_eval: Any,
    make_fields: Any,
    lam0: float,
    nvec: Any,
    lam_direct: Any = None,
    *,
    producer: str,
    **optional: Any,
) -> Solution:
    """Evaluate on tau_eval (through dense output) and unwrap lambda along the solver's own steps.

    ``lam_direct(tau, y)``, when given, returns the continuous lambda at the output times (from the state itself);
    ``producer`` and the ``optional`` fields (``quad_error``, ``resonances``, ...) go to the result.
    """
    tau_steps = res.time
    y_steps = res.y
    if lam_direct is not None:
        if tau_eval is None:
            tau_out, y_out = tau_steps, y_steps
        else:
            te = np.asarray(tau_eval, dtype=float)
            tau_out = te[(te >= tau_steps[0]) & (te <= tau_steps[-1])] if tau_steps.size else te[:0]
            y_out = res.sol(tau_out) if tau_out.size else np.empty((y_steps.shape[0], 0))
        lam = lam_direct(tau_out, y_out)
    elif tau_eval is None:
        tau_out, y_out = tau_steps, y_steps
        lam = lam_unwrapped(tau_steps, nvec(y_steps), lam0)
    else:
        te = np.asarray(tau_eval, dtype=float)
        te = te[(te >= tau_steps[0]) & (te <= tau_steps[-1])] if tau_steps.size else te[:0]
        if te.size:
            y_out = res.sol(te)
            tt = np.concatenate([tau_steps, te])
            order = np.argsort(tt, kind="stable")
            yy = np.concatenate([y_steps, y_out], axis=1)[:, order]
            lam_all = lam_unwrapped(tt[order], nvec(yy), lam0)
            pos = np.empty_like(order)
            pos[order] = np.arange(order.size)
            lam = lam_all[pos[tau_steps.size:]]
        else:
            y_out = np.empty((y_steps.shape[0], 0))
            lam = np.empty(0)
        tau_out = te
    data = make_fields(tau_out, y_out)
    data["lam"] = lam
    return Solution.build(producer=producer, time_name=res.time_name, time=tau_out, y=y_out, fields=data,
                          status=res.status, message=res.message, event=res.event, t_events=res.t_events,
                          y_events=res.y_events, dense=res.sol, nfev=res.nfev, **optional)


class PiecewiseDense:
    """Dense output of a run made of pieces (segments through the separatrix, charts of a segment): ``n_rows`` rows
    (G, k2, n[, nu]) at any times, from the piece that starts last before each; ``parts[i](t)`` evaluates piece i
    at an array of its times."""

    def __init__(self, starts: list[float], parts: list[Any], n_rows: int) -> None:
        self.starts = np.array(starts, dtype=float)
        self.parts = parts
        self.n_rows = n_rows

    def __call__(self, t: Any) -> np.ndarray:
        tt = np.atleast_1d(np.asarray(t, dtype=float))
        out = np.empty((self.n_rows, tt.size))
        idx = np.clip(np.searchsorted(self.starts, tt, side="right") - 1, 0, len(self.parts) - 1)
        for i in np.unique(idx).tolist():
            sel = idx == i
            out[:, sel] = self.parts[i](tt[sel])
        return out[:, 0] if np.ndim(t) == 0 else out
