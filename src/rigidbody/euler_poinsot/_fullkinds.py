r"""What the full equations' run depends on the body for: the start, the events and the body-shape output fields.

The body-frame equations (Euler's equations and the attitude quaternion) hold for any moments; the driver
(:mod:`._fullrun`) and the one-member equations (:mod:`._full`) ask a *kinds* object for what differs between a
triaxial :class:`Body` and a :class:`SymmetricBody`:

- ``start(i, G0, delta0, lam0)``: member ``i``'s start (body components ``g`` of G, the attitude ``R`` and its
  quaternion ``q``; for the triaxial body also the paper's angles and the energy, the start of
  ``formulation='angles'``);
- ``scalar_events(i, eps, G_D)`` and ``vector_events(idx, GD)``: the terminal and recorded events of one member
  on floats and of a group of members on arrays (``G_D(y)``, ``GD(y)``: the magnitude of G and
  :math:`D = G^2/2T` of the state);
- ``scalar_fields(G, T, gb)`` and ``vector_fields(g, G, T)``: the output fields that depend on the body's shape
  (``k2, kind, sigma`` of the osculating Euler--Poinsot motion; the nutation angle ``theta`` of the symmetric
  body);
- ``event_names`` and ``field_names``: the events a run records and the fields of a batch result.

:class:`TriaxialKinds` is the triaxial body's (the osculating modulus (5), the separatrix); the symmetric body's is
:class:`._symfull.SymmetricKinds`.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..core.ode import Event
from . import _kernel as _k
from ._full import initial_state
from ._model import Body, relabel
from ._spin import K2_SPIN_CAP, nutation_frequency
from ._stops import stop_message

__all__ = ["TriaxialKinds"]


def _k2_osc(A: tuple[float, float, float], D: float) -> float:
    """Osculating k2 of (5) from D = G^2/2T, with the moments in the labelling of the kind ('max' formula)."""
    A1, A2, A3 = A
    den = (A1 - A2) * (D - A3)
    return (A2 - A3) * (A1 - D) / den if den > 0 else math.inf


def _osculating_one(A: tuple[float, float, float], D: float) -> tuple[tuple[float, float, float], float]:
    """Moments labelled for the kind of motion D = G^2/2T belongs to, and its osculating k2 (in [0, 1])."""
    Alab = A if D >= A[1] else (A[2], A[1], A[0])
    return Alab, min(max(_k2_osc(Alab, D), 0.0), 1.0)


def _osculating(A: tuple[float, float, float], D: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Labelled moments (arrays) of the kind D = G^2/2T belongs to and its osculating k2 in [0, 1]."""
    A1, A2, A3 = A
    mx = D >= A2
    a1 = np.where(mx, A1, A3)
    a3 = np.where(mx, A3, A1)
    den = (a1 - A2) * (D - a3)
    with np.errstate(divide="ignore", invalid="ignore"):
        k2 = np.where(den > 0.0, (A2 - a3) * (a1 - D) / np.where(den > 0.0, den, 1.0), np.inf)
    return a1, a3, np.clip(k2, 0.0, 1.0)


def _k2_initial_kind(A1: Any, A2: float, A3: Any, D: np.ndarray) -> np.ndarray:
    """The osculating k2 by the formula of the initial kind (labelled moments, per member), unclipped (inf beyond
    the separatrix)."""
    den = (A1 - A2) * (D - A3)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(den > 0.0, (A2 - A3) * (A1 - D) / np.where(den > 0.0, den, 1.0), np.inf)


class TriaxialKinds:
    """The triaxial body's part of a full run: each member's start on its Euler--Poinsot motion (``k2_0``,
    ``kind``, phase ``u0``, ``psi0``: flat arrays of the members; ``sigma`` shared), the separatrix event (a stop at
    ``k2_max``, or the passages recorded when it is None), the slow-rotation stop and the osculating
    ``k2, kind, sigma``."""

    event_names: tuple[str, ...] = ("separatrix", "slow_rotation")
    field_names: tuple[str, ...] = ("G", "T", "k2", "delta", "lam", "nu", "n", "kind", "sigma")

    def __init__(self, body: Body, k2_0: np.ndarray, kind: np.ndarray, u0: np.ndarray, psi0: np.ndarray, sigma: int,
                 k2_max: float | None, min_spin_ratio: float) -> None:
        self.body, self.k2_0, self.kind, self.u0, self.psi0 = body, k2_0, kind, u0, psi0
        self.sigma, self.k2_max, self.min_spin_ratio = sigma, k2_max, min_spin_ratio
        # see K2_SPIN_CAP: only a run through the separatrix takes the period at min(k2, 0.99)
        self.spin_cap = K2_SPIN_CAP if k2_max is None else 1.0

    def start(self, i: int, G0: float, delta0: float, lam0: float) -> dict[str, Any]:
        return initial_state(self.body, G0, float(self.k2_0[i]), delta0, lam0, kind=str(self.kind[i]),
                             u0=float(self.u0[i]), psi0=float(self.psi0[i]), sigma=self.sigma)

    def scalar_events(self, i: int, eps: float, G_D: Any) -> list[Event]:
        A = (self.body.A1, self.body.A2, self.body.A3)
        cap, r = self.spin_cap, self.min_spin_ratio

        def ev_spin(tau: float, y: np.ndarray) -> float:
            G, D = G_D(y)
            Ak, k2 = _osculating_one(A, D)
            return nutation_frequency(Ak, G, min(k2, cap)) / eps - r

        if self.k2_max is None:  # every passage of D = G^2/2T through A2 is recorded; the run goes on
            ev_sep = Event(lambda t, y: G_D(y)[1] - A[1], "separatrix", False, 0.0, "")
        else:
            stop, Alab = self.k2_max, relabel(str(self.kind[i]), A)
            ev_sep = Event(lambda t, y: _k2_osc(Alab, G_D(y)[1]) - stop, "separatrix", True, 1.0,
                           stop_message("separatrix_full", k2_max=stop))
        return [ev_sep, Event(ev_spin, "slow_rotation", True, -1.0, stop_message("slow_rotation", min_spin_ratio=r))]

    def scalar_fields(self, G: Any, T: Any, gb: np.ndarray) -> dict[str, np.ndarray]:
        A = (self.body.A1, self.body.A2, self.body.A3)
        D = np.atleast_1d(G**2 / (2 * T))
        k2 = np.array([_osculating_one(A, float(d))[1] for d in D])
        mx = D >= A[1]
        return {"k2": k2, "kind": np.where(mx, "max", "min"), "sigma": np.where(np.where(mx, gb[0], gb[2]) >= 0, 1, -1)}

    def vector_events(self, idx: np.ndarray, GD: Any) -> tuple[list[Event], tuple[np.ndarray, ...]]:
        """The events of the members ``idx`` and the arguments they take after ``(ie, ie2, nu0, idx)``: the labelled
        moments A1, A3 of each member's initial kind (the ``k2_max`` stop)."""
        A1, A2, A3 = A = (self.body.A1, self.body.A2, self.body.A3)
        r, cap = self.min_spin_ratio, self.spin_cap
        mx = self.kind[idx] == "max"

        def ev_spin(t: np.ndarray, y: np.ndarray, ie: np.ndarray, *a: np.ndarray) -> np.ndarray:
            G, D = GD(y)
            a1, a3, k2 = _osculating(A, D)
            out = np.empty(G.shape)
            for lab in (True, False):  # the two labellings
                sel = (a1 == A1) if lab else (a1 != A1)
                if np.any(sel):
                    Al = (A1, A2, A3) if lab else (A3, A2, A1)
                    out[sel] = _k.nut_freq(np, Al, G[sel], np.minimum(k2[sel], cap)) * ie[sel] - r
            return out

        if self.k2_max is None:
            ev_sep = Event(lambda t, y, *a: GD(y)[1] - A2, "separatrix", False, 0.0, "")
        else:
            stop = self.k2_max
            ev_sep = Event(lambda t, y, *a: _k2_initial_kind(a[4], A2, a[5], GD(y)[1]) - stop, "separatrix", True,
                           1.0, stop_message("separatrix_full", k2_max=stop))
        events = [ev_sep, Event(ev_spin, "slow_rotation", True, -1.0, stop_message("slow_rotation", min_spin_ratio=r))]
        return events, (np.where(mx, A1, A3), np.where(mx, A3, A1))

    def vector_fields(self, g: np.ndarray, G: np.ndarray, T: np.ndarray) -> dict[str, np.ndarray]:
        """``k2, kind, sigma`` from the rows ``g`` (shape ``(B, 3, nt)``; NaN after a member's end)."""
        A = (self.body.A1, self.body.A2, self.body.A3)
        with np.errstate(invalid="ignore", divide="ignore"):
            D = G * G / (2.0 * T)
            _, _, k2 = _osculating(A, D)
            mx = D >= A[1]
            sig = np.where(np.where(mx, g[:, 0], g[:, 2]) >= 0.0, 1.0, -1.0)
        nan = np.isnan(G)
        return {"k2": np.where(nan, np.nan, k2), "kind": np.where(nan, "", np.where(mx, "max", "min")),
                "sigma": np.where(nan, np.nan, sig)}
