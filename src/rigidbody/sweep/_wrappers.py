"""Batched sweep functions over the library's vectorised calls (one call per chunk)."""

from __future__ import annotations

from typing import Any

import numpy as np

from ._run import batched


@batched
def gyrostat_stability(*, sat: Any, R0: Any = None, omega_sign: int = 1, rtol: float = 1e-12,
                       **params: Any) -> dict[str, np.ndarray]:
    """Stability of the stationary motions (2.3)-(2.4) of a gyrostat satellite, a chunk per call.

    A batched wrapper of :func:`rigidbody.gyrostat.stability_map` (Stepanov 1968, verdicts of (2.5)) for
    :func:`rigidbody.sweep.sweep`: fix the satellite (and anything else) with :func:`functools.partial`
    and sweep the rest::

        sweep(partial(gyrostat_stability, sat=sat, R0=7e6), {"theta0": th, "k2": k2})

    Parameters
    ----------
    sat : rigidbody.gyrostat.Satellite
        Supplies ``M, A1, A2, A3, mu`` unless they are swept.
    R0 : float or array_like
        Orbit radius (swept or fixed).
    omega_sign : {+1, -1}
    rtol : float
        Zero-eigenvalue threshold, as in :func:`~rigidbody.gyrostat.stability_map`.
    **params : array_like
        ``theta0`` and exactly one of ``k2``, ``k3`` (the motion's parameters), and optionally any of
        ``M, A1, A2, A3, mu``; arrays of the chunk's points.

    Returns
    -------
    dict
        ``code`` (0 stable, 1 unstable, 2 undecided, -1 no valid motion), ``degree`` (degree of
        instability), ``s1, s2, s3`` (Sylvester quantities of (2.5)), ``kappa0``, ``omega0`` and the one of
        ``k2``, ``k3`` that was not given (the motion, from (2.4)), one value per point.
    """
    from .. import gyrostat

    if R0 is None:
        raise TypeError("gyrostat_stability needs R0 (fixed with functools.partial, or swept)")
    computed = "k3" if "k2" in params else "k2"
    m = gyrostat.stability_map(sat, R0, params.pop("theta0"), params.pop("k2", None), params.pop("k3", None),
                               omega_sign=omega_sign, grid=False, rtol=rtol, **params)
    return {"code": m.code, "degree": m.degree, "s1": m.s1, "s2": m.s2, "s3": m.s3, "kappa0": m.kappa0,
            "omega0": m.omega0, computed: getattr(m, computed)}
