"""An averaged run through the separatrix: what happens at a crossing (once, for every run and every member of a
batch) and one single-run result stitched from the pieces of the run."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core.ode import Solution
from ._branches import choose_region
from ._model import Body, Orbit
from ._output import PiecewiseDense
from ._regions import Region
from ._separatrix import K2_SWITCH, separatrix_crossing
from ._stops import MAX_CROSSINGS, stop_message

__all__ = ["Piece", "assemble_pieces", "cross_separatrix"]


def cross_separatrix(body: Body, torque: Any, orbit: Orbit, source: Region, tc: float, G: float, delta: float,
                     lam: float, n: np.ndarray, nu: float | None, branch: Any, rng: np.random.Generator | None,
                     crossings: list[dict[str, Any]], dk2_at: Callable[..., float]) -> tuple[Region | None, str]:
    """A run at a separatrix crossing: the capture probabilities at the crossing state, the region the branch
    rule chooses, its drift checked (``dk2_at(region, G, n, nu)``: the averaged dk2/dtau next to the separatrix
    there, which must point away from it), the crossing appended to ``crossings``, and the stall guard
    (:data:`._stops.MAX_CROSSINGS`, a crossing that does not advance in time).

    Returns
    -------
    region, why
        The region the run continues in and ``''``; or None and why the run cannot go on (the stop's text).
    """
    c = separatrix_crossing(body, torque, G, delta, lam, nu, source, orbit=orbit)
    region, why = choose_region(c, branch, len(crossings), rng)
    if region is not None and dk2_at(region, G, n, nu) >= 0.0:
        why = stop_message("attracts", region=region)
        region = None
    crossings.append({"tau": tc, "source": source, "region": region, "probabilities": dict(c.probabilities),
                      "drifts": dict(c.drifts), "G": G, "n": n})
    if region is None:
        return None, why
    if len(crossings) > MAX_CROSSINGS or (len(crossings) > 1 and tc <= crossings[-2]["tau"]):
        return None, stop_message("stall", n=len(crossings), tau=tc)
    return region, ""


@dataclass
class Piece:
    """One piece of an averaged run (a kind of motion): its raw result, its region (kind, sigma), how to evaluate
    its output fields at given times (``finish(tau_eval, lam_start)``), its state as rows G, k2, n
    (``common(y)``), and the lambda it starts from."""

    res: Solution
    region: Region
    finish: Any
    common: Any
    lam_start: float


def assemble_pieces(pieces: list[Piece], crossings: list[dict[str, Any]], tau_eval: Any, producer: str,
                    stop: str = "") -> Solution:
    """One single-run Solution from the pieces: fields at the requested times (each from its piece's dense
    output), lambda continuous, the kind and sense at every time, the crossings as events; ``stop``: why the run
    ended at its last crossing (empty: it ended as its last piece did)."""
    if len(pieces) == 1 and not crossings:
        one: Solution = pieces[0].finish(tau_eval, pieces[0].lam_start)
        return one
    outs: list[Solution] = []
    last = len(pieces) - 1
    for i, p in enumerate(pieces):
        a, b = float(p.res.time[0]), float(p.res.time[-1])
        if tau_eval is None:
            te = p.res.time if i == 0 else p.res.time[1:]
        else:
            t = np.asarray(tau_eval, dtype=float)
            te = t[(t >= a) & ((t <= b) if i == last else (t < b))]
        outs.append(p.finish(te, p.lam_start))
    names = [f for f in outs[-1].fields if all(f in o.fields for o in outs)]
    data = {f: np.concatenate([np.asarray(getattr(o, f)) for o in outs], axis=-1) for f in names}
    tau = np.concatenate([o.time for o in outs])
    res = pieces[-1].res
    status, message, event = res.status, res.message, res.event
    if stop:
        status, event = 1, "separatrix"
        message = stop_message("crossing", tau=crossings[-1]["tau"], why=stop)
    t_events = dict(res.t_events)
    y_events = dict(res.y_events)
    t_events["separatrix"] = np.array([c["tau"] for c in crossings])
    y_events["separatrix"] = (np.array([[c["G"], K2_SWITCH, *c["n"]] for c in crossings]) if crossings
                              else np.empty((0, 5)))
    dense = PiecewiseDense([p.res.time[0] for p in pieces], [lambda t, p=p: p.common(p.res.sol(t)) for p in pieces],
                           5)
    return Solution.build(producer=producer, time_name=res.time_name, time=tau,
                          y=np.vstack([data["G"], data["k2"], data["n"]]), fields=data, status=status,
                          message=message, event=event, t_events=t_events, y_events=y_events, dense=dense,
                          nfev=sum(p.res.nfev for p in pieces), crossings=crossings,
                          quad_error=max(o.quad_error for o in outs),
                          resonances=[r for o in outs for r in o.resonances])
