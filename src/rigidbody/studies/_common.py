"""What the studies share: the paper's body and drag, the grids of the maps, and how a batch reports the points
whose single call would have raised."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from .. import euler_poinsot as ep
from ..core.validate import finite_array, real

__all__ = ["GRIDS", "PAPER_BODY", "PAPER_DRAG_CASE1", "call_errors", "checked", "first_errors", "k2_start"]

#: Rachinskaya's body (section 3), nondimensional principal moments A1 > A2 > A3
PAPER_BODY = ep.Body(A1=3.2, A2=2.6, A3=1.67)
#: Rachinskaya's drag tensor of case 1 (section 3), its diagonal
PAPER_DRAG_CASE1 = (2.322, 1.31, 1.425)

#: the studies' grids: ``quick`` for the figures command (seconds on 2 cores), ``full`` for a cluster
GRIDS: dict[str, dict[str, dict[str, np.ndarray]]] = {
    "averaging_euler_poinsot": {
        "quick": {"eps": np.array([0.04, 0.02, 0.01]), "k2_0": 1.0 - np.array([0.9, 0.5, 0.2, 0.05, 0.01])},
        "full": {"eps": np.geomspace(0.0025, 0.08, 11), "k2_0": 1.0 - np.geomspace(0.95, 0.002, 40)},
    },
    "averaging_lagrange": {
        "quick": {"eps": np.array([0.04, 0.02, 0.01]), "theta0": np.radians([5.0, 30, 60, 90, 120, 150, 170])},
        "full": {"eps": np.geomspace(0.001, 0.08, 13), "theta0": np.radians(np.linspace(2.0, 178.0, 45))},
    },
    "spin_end": {
        "quick": {"r1": np.linspace(0.1, 2.5, 13), "r3": np.linspace(0.1, 2.5, 13)},
        "full": {"r1": np.linspace(0.05, 3.0, 120), "r3": np.linspace(0.05, 3.0, 120)},
    },
}


def checked(value: Any, name: str, ok: Callable[[np.ndarray], np.ndarray], rule: str) -> np.ndarray:
    """``value`` (a real number or an array of them) as an array, or a ``ValueError``: "``name`` must ``rule``".

    ``ok`` maps the array to where it is valid; the message quotes the first invalid value.
    """
    a = finite_array(value, name) if np.ndim(value) else np.asarray(real(value, name))
    bad = ~np.asarray(ok(a), dtype=bool)
    if np.any(bad):
        raise ValueError(f"{name} must {rule}, got {float(a[bad].flat[0]) if a.ndim else float(a)}")
    return a


def k2_start(value: Any) -> np.ndarray:
    """The initial modulus squared ``k2_0`` (a number or an array), which must lie in (0, 1)."""
    return checked(value, "k2_0", lambda a: (a > 0.0) & (a < 1.0), "lie in (0, 1)")


def call_errors(sol: Any, failed: np.ndarray, field: str, prefix: str = "") -> np.ndarray:
    """The exception each member's single call would raise, as ``'Type: message'`` ('' where it returns).

    Parameters
    ----------
    sol : rigidbody.core.ode.Solution
        A batch result (flat members).
    failed : numpy.ndarray of bool
        The members whose single call raises.
    field : str
        A field of ``sol``: a member without its first value was refused at its start (status -1), where its
        single call raises the ``ValueError`` whose message the batch records; the others raise a
        ``RuntimeError``.
    prefix : str
        Put before the batch's message in a ``RuntimeError``.

    Returns
    -------
    numpy.ndarray of str (object)
    """
    status = np.asarray(sol.status).reshape(-1)
    message = [str(m) for m in np.asarray(sol.message, dtype=object).reshape(-1)]
    started = np.isfinite(np.asarray(getattr(sol, field), dtype=float).reshape(status.size, -1)[:, 0])
    out = np.full(status.size, "", dtype=object)
    for i in np.nonzero(np.asarray(failed).reshape(-1))[0]:
        refused = status[i] < 0 and not started[i]
        out[i] = f"ValueError: {message[i]}" if refused else f"RuntimeError: {prefix}{message[i]}"
    return out


def first_errors(*errors: np.ndarray) -> np.ndarray:
    """Per member, the first exception of several runs made in turn (:func:`call_errors` of each), where all
    runs start before any is checked: a refusal (``ValueError``) at a start comes before a run ending early."""
    out = np.full(errors[0].shape, "", dtype=object)
    for kind in ("ValueError", "RuntimeError"):
        for e in errors:
            pick = (out == "") & np.array([str(m).startswith(kind) for m in e], dtype=bool)
            out[pick] = e[pick]
    return out
