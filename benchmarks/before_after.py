"""The cases of ``run_all.py --against REV``: one process times them all against one tree of the package.

``run_all.py`` runs this script once per tree (the reference commit and the current tree, alternately, each a
few times) with ``PYTHONPATH`` pointing at that tree's ``src``; it prints one JSON line per case and
``run_all.py`` puts the two sides side by side. The cases use only the public API that both sides have (the
stacked ``(n, 3)`` form of ``lagrange.averaged``, the per-member arguments of ``euler_poinsot.averaged``, the
sweep wrappers), so the same script measures both.

Each case returns ``(error, value)``: ``error`` its accuracy against a reference (a closed form where one
exists: the spin ``r = r0 exp(-b tau / C)`` of linear drag (3.3) of the Lagrange top, ``G = exp(-tau)`` of a
drag tensor equal to the inertia tensor, the closed-form drag rates (6) for the averaging engine; else the same
side at ``rtol = 1e-13``), and ``value``, numbers the two sides must agree on (a change of behaviour shows as
their difference). Times are CPU seconds of the process, the best of the repeats.

Run directly (one tree): ``PYTHONPATH=src python benchmarks/before_after.py [repeat]``.
"""

from __future__ import annotations

import json
import math
import sys
from collections.abc import Callable
from functools import partial
from typing import Any

import numpy as np
from common import cpu_time

import rigidbody
from rigidbody import euler_poinsot as ep
from rigidbody import lagrange as L

BODY = ep.Body(A1=3.2, A2=2.6, A3=1.67)
INERTIA = np.diag([3.2, 2.6, 1.67])  # a drag tensor equal to the inertia tensor: dG/dtau = -G, k2 fixed
PAPER_DRAG = [2.322, 1.31, 1.425]  # the diagonal of the paper's drag tensor (k2 evolves)
TOP, DRAG = L.PAPER_TOP, L.PAPER_DRAG

Case = Callable[[], tuple[float, list[float]]]


def _spun(theta: Any, r0: float = 1.7) -> np.ndarray:
    """Stacked slow variables (1.2) of tops spun with r0 about their axis, tilted by theta (radians)."""
    return np.stack(np.broadcast_arrays(*L.integrals(TOP, 0.0, 0.0, r0, 0.0, theta)), axis=-1)


def _spin_error(r: np.ndarray, r0: np.ndarray, tau: np.ndarray) -> float:
    """Largest relative error of the spin against (3.3), over members and output times."""
    exact = np.asarray(r0)[..., None] * np.exp(-DRAG.b * tau / TOP.C)
    return float(np.nanmax(np.abs(r - exact) / exact))


def lagrange_single() -> tuple[float, list[float]]:
    ini = _spun(math.radians(60.0))
    s = L.averaged(TOP, DRAG, ini, (0.0, 10.0))
    return _spin_error(s.r[-1:], ini[2], s.tau[-1:]), [float(s.Gz[-1]), float(s.H[-1]), float(s.r[-1])]


#: the linear drag (3.1) as a general torque of class (2.4): its nutation means come from quadrature
ENGINE_DRAG = L.ProportionalTorque(f=lambda Gz, H, r, th: -DRAG.a + 0.0 * th,
                                   M3=lambda Gz, H, r, th: -DRAG.b * r + 0.0 * th)


def lagrange_engine() -> tuple[float, list[float]]:
    ini = _spun(math.radians(60.0))
    s = L.averaged(TOP, ENGINE_DRAG, ini, (0.0, 5.0), rtol=1e-10)
    return _spin_error(s.r[-1:], ini[2], s.tau[-1:]), [float(s.Gz[-1]), float(s.H[-1]), float(s.r[-1])]


def lagrange_batch() -> tuple[float, list[float]]:
    ini = _spun(np.radians(np.linspace(20.0, 160.0, 200)))
    te = np.linspace(0.0, 10.0, 11)
    s = L.averaged(TOP, DRAG, ini, (0.0, 10.0), tau_eval=te)
    return _spin_error(s.r, ini[:, 2], te), [float(np.nansum(s.Gz[:, -1])), float(np.nansum(s.H[:, -1]))]


def _ep_single(rtol: float) -> Any:
    return ep.averaged(BODY, np.diag(PAPER_DRAG), 0.1, 1.0, 0.5, tau_span=(0.0, 3.0), rtol=rtol)


def ep_single() -> tuple[float, list[float]]:
    s = _ep_single(1e-10)
    ref = _REF.setdefault("ep_single", _ep_single(1e-13))
    return float(abs(s.k2[-1] - ref.k2[-1]) / ref.k2[-1]), [float(s.G[-1]), float(s.k2[-1])]


def ep_batch() -> tuple[float, list[float]]:
    k2 = np.linspace(0.05, 0.95, 200)
    s = ep.averaged(BODY, INERTIA, 0.0, 1.0, k2, tau_span=(0.0, 3.0), tau_eval=np.linspace(0.0, 3.0, 7))
    err = float(np.nanmax(np.abs(s.G - np.exp(-s.tau)) / np.exp(-s.tau)))
    return err, [float(np.nansum(s.G[:, -1])), float(np.nansum(s.k2[:, -1]))]


def _ep_function_torque(omega: Any, C: Any, nu: Any) -> Any:
    return -np.asarray(PAPER_DRAG) * omega  # the paper's drag as a plain function: the engine averages it


def engine_rates() -> tuple[float, list[float]]:
    err, vals = 0.0, []
    for k2 in (0.1, 0.3, 0.5, 0.7, 0.9, 0.97):
        a = ep.average_torque(BODY, _ep_function_torque, 1.0, k2, 0.7, 0.3, None)
        dG, dT = ep.drag_rates(BODY, PAPER_DRAG, 1.0, k2)
        err = max(err, abs(a.rates["dG"] - dG) / abs(dG), abs(a.rates["dT"] - dT) / abs(dT))
        vals += [a.rates["dG"], a.rates["dT"]]
    return err, vals


def engine_run() -> tuple[float, list[float]]:
    s = ep.averaged(BODY, _ep_function_torque, 0.0, 1.0, 0.5, tau_span=(0.0, 1.0))
    ref = _REF.setdefault("engine_run", ep.averaged(BODY, ep.LinearDrag(PAPER_DRAG), 0.0, 1.0, 0.5,
                                                    tau_span=(0.0, 1.0), rtol=1e-13))
    return float(abs(s.k2[-1] - ref.k2[-1]) / ref.k2[-1]), [float(s.G[-1]), float(s.k2[-1])]


def sweep_lagrange() -> tuple[float, list[float]]:
    from rigidbody.sweep import lagrange_averaged, sweep

    Gz1, H1, r1 = L.integrals(TOP, 0.0, 0.0, 1.7, 0.0, math.radians(70.0))
    r0 = r1 * np.linspace(0.9, 1.0, 10)
    f = partial(lagrange_averaged, top=TOP, torque=DRAG, H0=H1, tau_span=(0.0, 5.0))
    ds = sweep(f, {"Gz0": Gz1 * np.linspace(0.9, 1.1, 10), "r0": r0}, executor="serial", progress=False)
    ok = ds["status"].values == 0
    r = ds["r"].values
    err = _spin_error(np.where(ok, r, np.nan)[..., None], np.broadcast_to(r0, r.shape), np.array([5.0]))
    return err, [float(np.nansum(np.where(ok, ds["Gz"].values, np.nan))), float(ok.sum())]


def sweep_euler_poinsot() -> tuple[float, list[float]]:
    from rigidbody.sweep import euler_poinsot_averaged, sweep

    f = partial(euler_poinsot_averaged, body=BODY, torque=INERTIA, tau_span=(0.0, 2.0))
    ds = sweep(f, {"k2_0": np.linspace(0.05, 0.95, 10), "delta0": np.linspace(0.1, 1.5, 10)}, executor="serial",
               progress=False)
    G = ds["G"].values
    return float(np.nanmax(np.abs(G - math.exp(-2.0)) / math.exp(-2.0))), [float(np.nansum(ds["k2"].values))]


_REF: dict[str, Any] = {}

#: name -> (what it measures, the case)
CASES: dict[str, tuple[str, Case]] = {
    "lagrange_single": ("lagrange.averaged, one run (scalar DOP853), case 2 to tau = 10", lagrange_single),
    "ep_single": ("euler_poinsot.averaged, one run (scalar DOP853), paper's drag tensor, eps = 0.1", ep_single),
    "lagrange_engine": ("lagrange.averaged, one run, linear drag as a general torque (quadrature)",
                        lagrange_engine),
    "lagrange_batch": ("lagrange.averaged, batch of 200 (vectorised DOP853)", lagrange_batch),
    "ep_batch": ("euler_poinsot.averaged, batch of 200, drag tensor", ep_batch),
    "engine_rates": ("averaging engine: average_torque of a function torque at 6 states", engine_rates),
    "engine_run": ("euler_poinsot.averaged, one run on the engine (function torque)", engine_run),
    "sweep_lagrange": ("sweep of lagrange_averaged, 10 x 10 grid, serial", sweep_lagrange),
    "sweep_ep": ("sweep of euler_poinsot_averaged, 10 x 10 grid, serial", sweep_euler_poinsot),
}


def main(argv: list[str]) -> int:
    repeat = int(argv[0]) if argv else 3
    print(json.dumps({"tree": str(rigidbody.__file__)}), flush=True)
    for name, (what, case) in CASES.items():
        error, value = case()  # the first call also warms the caches (imports, compiled stages)
        number = max(1, int(0.15 / max(cpu_time(case, repeat=1), 1e-6)))  # ~0.15 s a repeat: above the noise
        seconds = cpu_time(case, repeat=repeat, number=number)
        print(json.dumps({"case": name, "what": what, "seconds": seconds, "error": error, "value": value}),
              flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
