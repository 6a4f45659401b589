"""The torque argument at the public boundary: converted once to a torque object, with the capability the runs
below it choose by (the drag tensor whose closed forms (9) apply), so nothing below re-decides what it was given."""

from __future__ import annotations

from typing import Any

import numpy as np

from ._model import Body, Drag, Orbit
from ._protocol import Torque
from ._symbody import SymmetricBody
from ._torques import GravityGradient, LinearDrag, drag_as_torque, resolve

__all__ = ["as_torque", "drag_equivalent"]


def as_torque(torque: Any, body: Body | SymmetricBody, orbit: Orbit, omega0: float = 1.0) -> tuple[Torque, Drag | None]:
    """The ``torque`` argument of :func:`averaged` and :func:`simulate` as a torque object: a drag tensor (3x3, its
    diagonal or a :class:`Drag`) becomes its meaning, linear drag plus the gravity gradient of ``body`` on ``orbit``
    (returned with the :class:`Drag`: the paper's closed forms (9) apply to it; ``omega0``: the orbital rate of its
    gravity gradient); a torque object or a callable is the whole perturbation (returned with None). ``TypeError``
    for anything else, naming what is expected."""
    what, tq = resolve(torque)
    if what == "drag":
        return drag_as_torque(tq, body, orbit, omega0), tq
    return tq, None


def drag_equivalent(torque: Any, body: Body | SymmetricBody, orbit: Orbit) -> np.ndarray | None:
    """The drag tensor whose meaning (linear drag plus the gravity gradient) a torque object has, or None: a sum
    of :class:`LinearDrag` parts and one :class:`GravityGradient` of this body and orbit in the module's scaling
    (``omega0 = 1``). Its averages have the closed forms (9), and its torque the written-out formula of the full
    equations."""
    parts = torque.parts()
    gg = [p for p in parts if isinstance(p, GravityGradient)]
    lin = [p for p in parts if isinstance(p, LinearDrag)]
    if len(gg) != 1 or not lin or len(gg) + len(lin) != len(parts):
        return None
    g = gg[0]
    if g.omega0 != 1.0 or g.body != body or g.orbit != orbit:
        return None
    return np.sum([np.asarray(p.I, dtype=float) for p in lin], axis=0)
