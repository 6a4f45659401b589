"""The checks of a run's start, each rule once: a single run raises them, a batch refuses its member with them.

:func:`check_start` checks the values one member of a run starts from (``eps``, ``G0``, ``k2_0``, ``delta0``,
``lam0``, ``nu0`` and, for the full equations, ``u0``, ``psi0``) against :class:`StartRules` (the body and the
options they are checked against, already validated): :func:`~rigidbody.euler_poinsot.averaged` and
:func:`~rigidbody.euler_poinsot.simulate` call it for their one run, their batches for each member (a member it
refuses gets ``status = -1`` and the message the single call raises).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from ..core.validate import real
from ._algebra import k2_from, kind_of
from ._model import Body, check_kind, labelled
from ._separatrix import K2_SWITCH
from ._spin import K2_SPIN_CAP, nutation_frequency

__all__ = ["StartRules", "check_direction", "check_eps_G0", "check_full_eps", "check_spin", "check_start",
           "initial_kind"]


@dataclass(frozen=True)
class StartRules:
    """What the checks of a start need besides the member's values: the body, the separatrix stop ``k2_max``
    (None: a run through the separatrix), ``min_spin_ratio`` (both validated reals), and whether the run is of
    the full equations (``eps > 0``; no margin at the separatrix when it goes through)."""

    body: Body
    k2_max: float | None
    min_spin_ratio: float
    full: bool = False


def check_start(rules: StartRules, kind: str, eps: Any, G0: Any, k2_0: Any, delta0: Any, lam0: Any, nu0: Any,
                u0: Any = 0.0, psi0: Any = 0.0) -> tuple[float, float, float, float, float, float]:
    """The start values as floats, checked in the single call's order.

    Returns
    -------
    tuple of float
        ``eps, G0, k2_0, delta0, lam0, nu0``.

    Raises
    ------
    TypeError
        If a value is not a real number.
    ValueError
        Naming the first value that is not finite or out of its range, a start at (or beyond the stop next to)
        the separatrix, or a rotation too slow for ``eps`` (the way out in the message).
    """
    eps, G0 = check_eps_G0(eps, G0)
    k2_0 = real(k2_0, "k2_0")
    if not (0.0 <= k2_0 < 1.0):
        raise ValueError(f"k2_0 must lie in [0, 1) (k2 = 1 is the separatrix), got {k2_0}")
    delta0, lam0, nu0 = check_direction(delta0, lam0, nu0)
    if rules.full:
        check_full_eps(eps)
    if rules.k2_max is None:
        if not rules.full and k2_0 >= K2_SWITCH:
            raise ValueError(f"k2_0 = {k2_0!r} lies within 1e-9 of the separatrix: start on either side of it "
                             "(T0 slightly off G0^2/(2 A2))")
    elif not (k2_0 < rules.k2_max <= 1.0):
        raise ValueError(f"k2_max (the separatrix stop) must lie in (k2_0, 1] = ({k2_0}, 1], got {rules.k2_max}: "
                         "raise k2_max or start further from the separatrix")
    r = rules.min_spin_ratio
    if eps > 0 and r > 0:
        # within 0.01 of the separatrix a run through it takes the period at K2_SPIN_CAP (see there)
        cap = K2_SPIN_CAP if rules.k2_max is None else 1.0
        ratio = nutation_frequency(labelled(rules.body, kind), G0, min(k2_0, cap)) / eps
        check_spin(eps, ratio, r, "the Euler-Poinsot frequency")
    if rules.full:
        real(u0, "u0")
        real(psi0, "psi0")
    return eps, G0, k2_0, delta0, lam0, nu0


def check_eps_G0(eps: Any, G0: Any) -> tuple[float, float]:
    """``eps >= 0`` and ``G0 > 0`` as floats (the first checks of every start)."""
    eps = real(eps, "eps")
    if eps < 0:
        raise ValueError(f"eps must be >= 0 (eps = omega0/omega), got {eps}")
    G0 = real(G0, "G0")
    if G0 <= 0:
        raise ValueError(f"G0 must be positive, got {G0}")
    return eps, G0


def check_direction(delta0: Any, lam0: Any, nu0: Any) -> tuple[float, float, float]:
    """The direction of G (``delta0`` in [0, pi], ``lam0``) and the true anomaly ``nu0`` as floats."""
    delta0 = real(delta0, "delta0")
    if not (0.0 <= delta0 <= math.pi):
        raise ValueError(f"delta0 (polar angle of G from x3) must lie in [0, pi], got {delta0}")
    return delta0, real(lam0, "lam0"), real(nu0, "nu0")


def check_full_eps(eps: float) -> None:
    """The full equations need ``eps > 0``."""
    if eps <= 0:
        raise ValueError("eps must be positive for the full equations (eps = 0 has no fast rotation to resolve)")


def check_spin(eps: float, ratio: float, min_spin_ratio: float, what: str) -> None:
    """The start's rotation must be fast: ``ratio`` (``what``, the body's frequency, over the orbital rate ``eps``)
    above ``min_spin_ratio``."""
    if ratio <= min_spin_ratio:
        raise ValueError(
            f"eps = {eps:g} is too large for this state: {what} over the orbital rate is {ratio:.3g} <= "
            f"min_spin_ratio = {min_spin_ratio:g} (the rotation is not fast); lower eps, or pass min_spin_ratio=0 to "
            "integrate anyway outside the theory"
        )


def initial_kind(body: Body, G0: float, k2_0: float | None, kind: str | None, T0: float | None
                  ) -> tuple[float, str]:
    """(k2_0, kind) from k2_0 and kind (defaults 0.99, 'max') or from the energy T0."""
    if T0 is None:
        kind = "max" if kind is None else kind
        check_kind(kind)
        return (0.99 if k2_0 is None else k2_0), kind
    if k2_0 is not None or kind is not None:
        raise ValueError("give the initial state either by T0 or by k2_0 and kind, not both")
    T0 = real(T0, "T0")
    if T0 <= 0:
        raise ValueError(f"T0 must be positive, got {T0}")
    lo, hi = G0**2 / (2 * body.A1), G0**2 / (2 * body.A3)
    if not (lo * (1 - 1e-12) <= T0 <= hi * (1 + 1e-12)):
        raise ValueError(f"T0 must lie in [G0^2/(2 A1), G0^2/(2 A3)] = [{lo:.6g}, {hi:.6g}] (a rigid body), got {T0}")
    k = kind_of(body, G0, T0)
    if k == "separatrix":
        raise ValueError(f"T0 = {T0} lies on the separatrix G0^2 = 2 T0 A2: start on either side of it")
    return float(k2_from(body, G0, T0, k)), k
