"""Vectorised stability maps over parameter grids (the family (2.3), verdicts of (2.5))."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core.validate import positive
from ._model import Satellite
from ._stability import VERDICTS, a_matrix, hessian_entries, restricted_conditions, stability_arrays
from ._stationary import (
    SINGULAR_TOL,
    broadcast_shape,
    check_fits,
    check_omega_sign,
    family_arrays,
    float_arrays,
)

__all__ = ["StabilityMap", "exact_boundaries", "normalized_stability_map", "stability_map"]

_MAP_ORDER = ("theta0", "R0", "k2", "k3", "M", "A1", "A2", "A3", "mu")


@dataclass(frozen=True)
class StabilityMap:
    """Verdicts over a grid.  All arrays have the grid's shape (``minors``: plus a trailing axis of 5); they
    may be read-only broadcast views (copy before writing).

    ``code``: 0 stable, 1 unstable (odd degree), 2 undecided, -1 invalid (no motion of the family,
    singular chart, k2 ill-conditioned (abs(sin(theta0 + kappa0)) <= 1e-6 with k3 given), a non-physical
    body, or one that does not fit inside its orbit, ``R0^2 <= (A1 + A2 + A3) / (2 M)``);
    :attr:`verdict` gives the strings.  ``r1, r2, r3`` are the restricted-problem quantities and
    ``restricted_stable`` their conjunction.
    """

    params: dict[str, np.ndarray]
    kappa0: np.ndarray
    omega0: np.ndarray
    k2: np.ndarray
    k3: np.ndarray
    s1: np.ndarray
    s2: np.ndarray
    s3: np.ndarray
    minors: np.ndarray
    degree: np.ndarray
    code: np.ndarray
    r1: np.ndarray
    r2: np.ndarray
    r3: np.ndarray

    @property
    def verdict(self) -> np.ndarray:
        """Verdict strings ('stable', 'unstable', 'undecided', 'invalid')."""
        names = np.array([VERDICTS[0], VERDICTS[1], VERDICTS[2], VERDICTS[-1]])
        return names[np.where(self.code < 0, 3, self.code)]

    @property
    def theta0(self) -> np.ndarray:
        return self.params["theta0"]

    @property
    def restricted_stable(self) -> np.ndarray:
        return (self.r1 > 0) & (self.r2 > 0) & (self.r3 > 0)

    @property
    def shape(self) -> tuple[int, ...]:
        return self.code.shape


def stability_map(
    sat: Satellite,
    R0: Any,
    theta0: Any,
    k2: Any = None,
    k3: Any = None,
    *,
    omega_sign: int = 1,
    grid: bool = True,
    rtol: float = 1e-12,
    **overrides: Any,
) -> StabilityMap:
    """Verdicts for the motions (2.3) over arrays of parameters, in one vectorised call.

    Parameters
    ----------
    sat : Satellite
        Supplies M, A1, A2, A3, mu unless overridden.
    R0, theta0 : float or array_like
    k2, k3 : float or array_like
        Exactly one (the other is computed from (2.4)).
    omega_sign : {+1, -1}
    grid : bool
        If True (default), the 1-D arrays among the parameters are combined into an outer grid
        (``indexing='ij'``, axes in the order theta0, R0, k2, k3, M, A1, A2, A3, mu); if False the
        arrays are broadcast against each other as given.
    rtol : float
        Zero-eigenvalue threshold of the equilibrated second variation (see
        :func:`rigidbody.core.quadform.inertia`).
    **overrides : float or array_like
        Any of ``M, A1, A2, A3, mu`` to vary the body (e.g. ``A1=np.linspace(...)``).

    Returns
    -------
    StabilityMap

    Examples
    --------
    >>> import numpy as np
    >>> from rigidbody import gyrostat
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    >>> mp = gyrostat.stability_map(sat, 1.0, np.linspace(-1.2, 1.2, 5), k2=np.linspace(-0.05, 0.05, 4))
    >>> mp.code.shape
    (5, 4)
    """
    if not isinstance(sat, Satellite):
        raise TypeError(f"sat must be a Satellite; got {type(sat).__name__}")
    bad = set(overrides) - {"M", "A1", "A2", "A3", "mu"}
    if bad:
        raise TypeError(f"unknown parameter(s) {sorted(bad)}; overridable: M, A1, A2, A3, mu")
    if (k2 is None) == (k3 is None):
        raise TypeError("give exactly one of k2 and k3")
    omega_sign = check_omega_sign(omega_sign)
    vals: dict[str, Any] = {
        "theta0": theta0, "R0": R0, "k2": k2, "k3": k3,
        "M": overrides.get("M", sat.M), "A1": overrides.get("A1", sat.A1), "A2": overrides.get("A2", sat.A2),
        "A3": overrides.get("A3", sat.A3), "mu": overrides.get("mu", sat.mu),
    }
    arrs = float_arrays(vals)
    if grid:
        axes = [n for n in _MAP_ORDER if n in arrs and arrs[n].ndim == 1 and arrs[n].size != 1]
        if any(arrs[n].ndim > 1 for n in arrs):
            raise ValueError("with grid=True pass 1-D arrays (or use grid=False and broadcastable arrays)")
        # sparse: trigonometry runs on the 1-D axes, broadcasting does the rest
        mesh = np.meshgrid(*[arrs[n] for n in axes], indexing="ij", sparse=True) if axes else []
        for n, m in zip(axes, mesh):
            arrs[n] = m
    shape = broadcast_shape(arrs)
    P = {n: np.broadcast_to(v, shape) for n, v in arrs.items()}
    M, A1, A2, A3, mu, Rv = arrs["M"], arrs["A1"], arrs["A2"], arrs["A3"], arrs["mu"], arrs["R0"]
    physical = (
        (M > 0) & (A1 > 0) & (A2 > 0) & (A3 > 0) & (mu > 0) & (Rv > 0)
        & (A1 <= (A2 + A3) * (1 + 1e-12)) & (A2 <= (A1 + A3) * (1 + 1e-12)) & (A3 <= (A1 + A2) * (1 + 1e-12))
    )
    with np.errstate(all="ignore"):  # the body fits inside its orbit (see _stationary.check_fits)
        physical = physical & (Rv**2 > (A1 + A2 + A3) / (2 * M))
    with np.errstate(invalid="ignore", divide="ignore"):
        f = family_arrays(M, A1, A2, A3, mu, Rv, arrs["theta0"], k2=arrs.get("k2"), k3=arrs.get("k3"),
                          omega_sign=omega_sign)
        f = {key: np.broadcast_to(v, shape) if key in ("exists", "sin_tk", "cos_tk", "cos_t", "sin_t") else v
             for key, v in f.items()}
        f["exists"] = f["exists"] & physical
        if "k3" in arrs:  # k2 from k3 divides by sin(theta0 + kappa0): ill-conditioned near theta0 = 0, pi
            f["exists"] = f["exists"] & (np.abs(f["sin_tk"]) > SINGULAR_TOL)
        d = stability_arrays(f, M, A1, A2, A3, mu, Rv, rtol=rtol)
        r1, r2, r3 = restricted_conditions(A1, A2, A3, f["theta0"], f["k2"], f["omega0"])
    def full(x: Any) -> np.ndarray:
        return np.broadcast_to(x, shape)

    return StabilityMap(
        params=P, kappa0=full(f["kappa0"]), omega0=full(f["omega0"]), k2=full(f["k2"]), k3=full(f["k3"]),
        s1=full(d["s1"]), s2=full(d["s2"]), s3=full(d["s3"]), minors=d["minors"], degree=full(d["n_neg"]),
        code=full(d["code"]), r1=full(r1), r2=full(r2), r3=full(r3),
    )


def exact_boundaries(sat: Satellite, R0: float, theta0: Any, *, omega_sign: int = 1) -> dict[str, np.ndarray]:
    """The curves s2 = 0, s3 = 0 (exact) and r2 = 0, r3 = 0 (restricted) as k2(theta0).

    For fixed theta0 the motion's kappa0 and omega0 do not depend on k2, and k2 enters only W_b1b1
    (as ``omega0 k2 / cos(theta0 + kappa0)``) and W_b3b3 (as ``omega0 k2 / cos^3(theta0 + kappa0)``), so
    s2 and s3 = det a are *linear* in k2 and each boundary is one explicit curve.  ``s1`` and ``r1``
    do not depend on k2: their zeros are vertical lines, returned as ``s1`` and ``r1`` arrays over
    theta0 for the caller to locate sign changes (``theta_r1``: the closed-form roots of r1).

    Returns
    -------
    dict with keys ``theta0, s1, k2_s2, k2_s3, r1, k2_r2, k2_r3, theta_r1, omega0`` (NaN where undefined).
    """
    if not isinstance(sat, Satellite):
        raise TypeError(f"sat must be a Satellite; got {type(sat).__name__}")
    R0 = positive(R0, "R0")
    check_fits(sat, R0)
    omega_sign = check_omega_sign(omega_sign)
    th = np.asarray(theta0, dtype=float)
    f = family_arrays(sat.M, sat.A1, sat.A2, sat.A3, sat.mu, R0, th, k2=0.0, omega_sign=omega_sign)
    e = hessian_entries(sat.M, sat.A1, sat.A2, sat.A3, sat.mu, R0, th, f["kappa0"], f["omega0"], 0.0, f["S0"])
    a = a_matrix(e, th, f["kappa0"])
    om, cp = f["omega0"], f["cos_tk"]
    with np.errstate(divide="ignore", invalid="ignore"):
        s1 = e["g1g1"]
        s2_0 = e["g1g1"] * e["b1b1"] - e["b1g1"] ** 2
        k2_s2 = -s2_0 * cp / (s1 * om)
        C33 = a[..., 0, 0] * a[..., 1, 1] - a[..., 0, 1] ** 2
        k2_s3 = -np.linalg.det(a) * cp**3 / (om * C33)
        A1, A2, A3 = sat.A1, sat.A2, sat.A3
        ct, st2 = np.cos(th), np.sin(th) ** 2
        r1 = A1 - A2 * st2 - A3 * ct**2
        k2_r2 = -4 * om * ct**3 * (A2 - A3)
        k2_r3 = om * ct * (A1 - A2 - 3 * (A1 - A2) * (A2 - A3) * st2 / r1)
        x = (A1 - A3) / (A2 - A3) if A2 != A3 else np.nan
    roots = np.array([])
    if np.isfinite(x) and 0 <= x <= 1:
        t = np.arcsin(np.sqrt(x))
        roots = np.array([-np.pi + t, -t, t, np.pi - t])
    return {"theta0": th, "s1": s1, "k2_s2": k2_s2, "k2_s3": k2_s3, "r1": r1, "k2_r2": k2_r2,
            "k2_r3": k2_r3, "theta_r1": roots, "omega0": om}


def normalized_stability_map(
    sat: Satellite, R0: float, theta0: Any, u: Any, *, omega_sign: int = 1, rtol: float = 1e-12
) -> tuple[StabilityMap, dict[str, np.ndarray]]:
    """Verdicts on the grid ``theta0 x u`` with ``u = k2 / (omega0 Abar)`` (the plane of the paper-style maps).

    omega0 depends on theta0 (not on k2), so ``k2 = u omega0(theta0) Abar`` column by column.

    Returns
    -------
    (StabilityMap, boundaries)
        The map has shape ``(len(theta0), len(u))``; ``boundaries`` is :func:`exact_boundaries` with the
        k2-curves divided by ``omega0 Abar`` (keys ``u_s2, u_s3, u_r2, u_r3`` added).
    """
    if not isinstance(sat, Satellite):
        raise TypeError(f"sat must be a Satellite; got {type(sat).__name__}")
    R0 = positive(R0, "R0")
    check_fits(sat, R0)
    omega_sign = check_omega_sign(omega_sign)
    th = np.asarray(theta0, dtype=float).ravel()
    uu = np.asarray(u, dtype=float).ravel()
    om = family_arrays(sat.M, sat.A1, sat.A2, sat.A3, sat.mu, R0, th, k2=0.0, omega_sign=omega_sign)["omega0"]
    k2 = uu[None, :] * (om * sat.Abar)[:, None]
    mp = stability_map(sat, R0, th[:, None], k2=k2, omega_sign=omega_sign, grid=False, rtol=rtol)
    b = exact_boundaries(sat, R0, th, omega_sign=omega_sign)
    for key in ("s2", "s3", "r2", "r3"):
        b[f"u_{key}"] = b[f"k2_{key}"] / (b["omega0"] * sat.Abar)
    return mp, b
