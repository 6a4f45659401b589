"""The keyword options of :func:`averaged` and :func:`simulate`, grouped by what they control.

The options that belong together are small frozen values: :class:`Solver` (how the equations are integrated)
and :class:`Stops` (where a run ends because its theory stops holding). A call passes either the group
(``stops=Stops(k2_max=None)``) or its fields one by one as keywords (``k2_max=None``), as before the groups
existed; :func:`collect` resolves both to one flat set of options, and names an unknown keyword (or a field
given twice, alone and in its group) in a ``TypeError``.
"""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Any

__all__ = ["Solver", "Stops", "averaged_options", "collect", "simulate_options"]


@dataclass(frozen=True)
class Solver:
    """How a run integrates its equations.

    Parameters
    ----------
    rtol, atol : float
        Tolerances of the integrator (their meaning for each system: :func:`averaged`, :func:`simulate`).
    method : str
        ``'DOP853'`` (default; run on Python floats) or another :func:`scipy.integrate.solve_ivp` method (single
        runs only: a batch uses DOP853).

    See Also
    --------
    Stops : the other option group.
    averaged, simulate : the runs that take it (``solver=Solver(...)`` or its fields by keyword).

    Examples
    --------
    A looser tolerance for a quick run; the fields not given keep their defaults:

    >>> from rigidbody import euler_poinsot as ep
    >>> ep.Solver(rtol=1e-8)
    Solver(rtol=1e-08, atol=1e-12, method='DOP853')
    """

    rtol: float = 1e-10
    atol: float = 1e-12
    method: str = "DOP853"


@dataclass(frozen=True)
class Stops:
    """Where a run ends (status 1, with a message naming the option that relaxes the stop).

    Parameters
    ----------
    k2_max : float or None
        The separatrix stop on :math:`k^2` (default :math:`1 - 10^{-6}`); ``None`` goes on through the separatrix.
    min_spin_ratio : float
        The rotation must stay fast: the run ends where :func:`spin_ratio` falls to this value (0: no check).
    drift_tol : float or None
        :func:`averaged` with a torque object: the largest change of the slow variables in one Euler--Poinsot
        period (``None``: no check). :func:`simulate` has no such stop and refuses a value other than the default.
    resonance_tol : float or None
        :func:`averaged` with a torque object: the largest predicted jump at a resonance crossing (``None``: no
        check). :func:`simulate` refuses a value other than the default.

    See Also
    --------
    Solver : the other option group.
    averaged, simulate : the runs that take it (``stops=Stops(...)`` or its fields by keyword).

    Examples
    --------
    An averaged run that stops at :math:`k^2 = 0.95`: for the drag ``diag(3, 2, 1)`` the only equilibrium of
    (8) is the unstable :math:`k^2 = 0` (:func:`k2_equilibria`), so :math:`k^2` grows from 0.9 until the stop,
    which the run locates as an event (status 1, the last :math:`k^2` is the threshold):

    >>> from rigidbody import euler_poinsot as ep
    >>> body = ep.Body(3.2, 2.6, 1.67)
    >>> sol = ep.averaged(body, [3.0, 2.0, 1.0], 0.0, k2_0=0.9, tau_span=(0, 50), stops=ep.Stops(k2_max=0.95))
    >>> print(sol.status, f"{sol.k2[-1]:.6f}")
    1 0.950000
    """

    k2_max: float | None = 1.0 - 1e-6
    min_spin_ratio: float = 1.0
    drift_tol: float | None = 0.5
    resonance_tol: float | None = 0.05


#: the option groups: keyword of the group -> its class
GROUPS: dict[str, type] = {"solver": Solver, "stops": Stops}
_DEFAULTS = {name: cls() for name, cls in GROUPS.items()}
#: the fields each entry uses: averaged all of both groups, simulate the stops of the full equations only
_AVERAGED = {"solver": tuple(f.name for f in fields(Solver)), "stops": tuple(f.name for f in fields(Stops))}
_SIMULATE = {"solver": _AVERAGED["solver"], "stops": ("k2_max", "min_spin_ratio")}


def collect(func: str, options: dict[str, Any], groups: dict[str, tuple[str, ...]], other: dict[str, Any]
            ) -> dict[str, Any]:
    """The flat options of a call to ``func`` from its keyword ``options``.

    ``groups`` maps a group keyword of :data:`GROUPS` to the fields of that group ``func`` uses; ``other`` holds the
    remaining keywords of ``func`` with their defaults. A group may be given as an object (of its class) or by its
    fields one by one, not both for one field.
    """
    out = dict(other)
    given: dict[str, str] = {}
    for name, cls in GROUPS.items():
        if name not in groups:
            continue
        value = options.pop(name, None)
        if value is None:
            value = _DEFAULTS[name]
        elif not isinstance(value, cls):
            raise TypeError(f"{func}() {name} must be a {cls.__name__}, got {value!r}")
        else:
            given.update({f: name for f in groups[name]})
            unused = [f.name for f in fields(cls) if f.name not in groups[name]
                      and getattr(value, f.name) != getattr(_DEFAULTS[name], f.name)]
            if unused:
                raise TypeError(f"{func}() does not use {name}.{unused[0]} (it has no such stop); leave it at its "
                                "default")
        out.update({f: getattr(value, f) for f in groups[name]})
    for key, value in options.items():
        if key in given:
            raise TypeError(f"{func}() got {key!r} both alone and in {given[key]}=: pass it once")
        if key not in out:
            known = sorted([*out, *(g for g in GROUPS if g in groups)])
            raise TypeError(f"{func}() got an unexpected keyword argument {key!r}; its options are {known}")
        out[key] = value
    return out


def averaged_options(**options: Any) -> dict[str, Any]:
    """The flat keyword options of :func:`averaged` (its defaults where not given)."""
    other = {"kind": None, "T0": None, "orbit": None, "sigma": 1, "averaging": "auto", "quad_tol": 1e-12,
             "branch": "likely", "seed": None, "theta0": None}
    return collect("averaged", options, _AVERAGED, other)


def simulate_options(**options: Any) -> dict[str, Any]:
    """The flat keyword options of :func:`simulate` (its defaults where not given)."""
    other = {"kind": None, "T0": None, "orbit": None, "u0": None, "psi0": 0.0, "sigma": 1, "formulation": "body",
             "theta0": None, "phi0": None}
    return collect("simulate", options, _SIMULATE, other)
