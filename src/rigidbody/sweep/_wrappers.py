"""Batched sweep functions over the library's vectorised calls (one call per chunk)."""

from __future__ import annotations

from math import pi
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

    See Also
    --------
    rigidbody.gyrostat.stability_map : the function it wraps.
    lagrange_averaged, euler_poinsot_averaged : the other wrappers.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eqs. (2.3)-(2.5).

    Examples
    --------
    Where the three Sylvester quantities of (2.5) are positive the motion is stable (code 0):

    >>> from functools import partial
    >>> from rigidbody import gyrostat
    >>> from rigidbody.sweep import gyrostat_stability, sweep
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    >>> ds = sweep(partial(gyrostat_stability, sat=sat, R0=1.0), {"theta0": [0.3], "k2": [0.02]},
    ...            executor="serial", progress=False)
    >>> [bool(ds[s].item() > 0) for s in ("s1", "s2", "s3")], int(ds["code"].item())
    ([True, True, True], 0)
    """
    from .. import gyrostat

    if R0 is None:
        raise TypeError("gyrostat_stability needs R0 (fixed with functools.partial, or swept)")
    computed = "k3" if "k2" in params else "k2"
    m = gyrostat.stability_map(sat, R0, params.pop("theta0"), params.pop("k2", None), params.pop("k3", None),
                               omega_sign=omega_sign, grid=False, rtol=rtol, **params)
    return {"code": m.code, "degree": m.degree, "s1": m.s1, "s2": m.s2, "s3": m.s3, "kappa0": m.kappa0,
            "omega0": m.omega0, computed: getattr(m, computed)}


#: the sweep status of a point whose integration failed or was refused at its start (its message says why)
RUN_FAILED = 2


def _evolution_outputs(sol: Any, outputs: tuple[str, ...], end_only: bool) -> dict[str, np.ndarray]:
    """The outputs of a batch of averaged evolutions, one row per point: the requested fields (at the end of the
    span, or over ``tau_eval``), ``run_status`` (the integration's -1/0/1), ``tau_end`` (where the run ended), and
    the sweep's ``status`` (0, or :data:`RUN_FAILED` for a failed or refused run) and ``message``."""
    n = int(np.prod(sol.batch_shape))
    out: dict[str, np.ndarray] = {}
    for name in outputs:
        a = np.asarray(getattr(sol, name), dtype=float).reshape(n, -1)
        out[name] = a[:, -1] if end_only else a
    run_status = np.asarray(sol.status).reshape(n)
    out["run_status"] = run_status.astype(float)
    out["tau_end"] = np.asarray(sol.t_final, dtype=float).reshape(n)
    out["status"] = np.where(run_status < 0, RUN_FAILED, 0)
    out["message"] = np.asarray(sol.message, dtype=object).reshape(n)
    return out


@batched
def euler_poinsot_averaged(*, body: Any, torque: Any, eps: Any = 0.0, G0: Any = 1.0, k2_0: Any = 0.99,
                           delta0: Any = pi / 4, lam0: Any = pi / 4, nu0: Any = 0.0,
                           tau_span: tuple[float, float] = (0.0, 3.0), tau_eval: Any = None,
                           outputs: tuple[str, ...] = ("G", "T", "k2", "delta", "lam"),
                           **options: Any) -> dict[str, np.ndarray]:
    """Averaged Euler--Poinsot evolutions (Rachinskaya's (9)), a chunk of points per batched call.

    A batched wrapper of :func:`rigidbody.euler_poinsot.averaged` for :func:`rigidbody.sweep.sweep`: the grid
    names are any of its per-member inputs ``eps, G0, k2_0, delta0, lam0, nu0``; fix the rest (the body, the
    torque, options such as ``rtol``, ``kind``, ``orbit``) with :func:`functools.partial`::

        sweep(partial(euler_poinsot_averaged, body=body, torque=I), {"k2_0": k2, "delta0": d})

    Each chunk is one batch call (the closed forms of a drag tensor vectorised over the chunk's points).

    Parameters
    ----------
    body : rigidbody.euler_poinsot.Body
    torque : array_like, Drag, torque object or callable
        As in :func:`~rigidbody.euler_poinsot.averaged`.
    eps, G0, k2_0, delta0, lam0, nu0 : float or array_like
        Swept (arrays of the chunk's points) or fixed.
    tau_span : (float, float)
    tau_eval : array_like, optional
        Output times: each output is then an array over them (a dimension ``<output>_dim_0`` of the Dataset).
        Default: the values at the end of ``tau_span`` (NaN for a run that ended earlier).
    outputs : tuple of str
        Fields of the result to return (``G``, ``T``, ``k2``, ``delta``, ``lam``, ``nu``).
    **options
        Keyword options of :func:`~rigidbody.euler_poinsot.averaged`.

    Returns
    -------
    dict
        One value (or row) per point: the ``outputs``, ``run_status`` (0 end of the span, 1 ended by an event),
        ``tau_end`` (when the run ended), and the sweep's ``status`` (0; :data:`RUN_FAILED` where the run failed
        or was refused, e.g. a start outside the theory: its outputs are then NaN) and ``message`` (the
        integration's message).

    See Also
    --------
    rigidbody.euler_poinsot.averaged : the function it wraps.
    lagrange_averaged, gyrostat_stability : the other wrappers.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, eq. (9).

    Examples
    --------
    A drag tensor equal to the inertia tensor (all decay rates 1) gives ``dG/dtau = -G`` and leaves ``k2``
    where it starts (the torque ``-I omega = -G``, and ``T`` decays as ``G²``): ``G = 1/e`` at ``tau = 1``:

    >>> import math
    >>> from functools import partial
    >>> import numpy as np
    >>> from rigidbody import euler_poinsot
    >>> from rigidbody.sweep import euler_poinsot_averaged, sweep
    >>> body = euler_poinsot.Body(A1=3.2, A2=2.6, A3=1.67)
    >>> f = partial(euler_poinsot_averaged, body=body, torque=np.diag([3.2, 2.6, 1.67]), tau_span=(0.0, 1.0))
    >>> ds = sweep(f, {"k2_0": [0.3, 0.6]}, executor="serial", progress=False)
    >>> print(" ".join(f"{x:.6f}" for x in ds["G"].values), f"{1 / math.e:.6f}")
    0.367879 0.367879 0.367879
    >>> print(" ".join(f"{x:.6f}" for x in ds["k2"].values))
    0.300000 0.600000
    """
    from .. import euler_poinsot as ep

    t1 = float(tau_span[1])
    te = np.array([t1]) if tau_eval is None else tau_eval
    # the grid's arrays go straight in (they broadcast); a call with scalars only is a batch of one
    sol = ep.averaged(body, torque, np.atleast_1d(eps), G0, k2_0, delta0, lam0, tau_span, te, nu0, **options)
    return _evolution_outputs(sol, tuple(outputs), tau_eval is None)


@batched
def lagrange_averaged(*, top: Any, torque: Any, Gz0: Any, H0: Any, r0: Any, tau_span: tuple[float, float],
                      tau_eval: Any = None, outputs: tuple[str, ...] = ("Gz", "H", "r", "k2"),
                      **options: Any) -> dict[str, np.ndarray]:
    """Averaged evolutions of the Lagrange top (2.15), a chunk of points per batched call.

    A batched wrapper of :func:`rigidbody.lagrange.averaged` for :func:`rigidbody.sweep.sweep`: the grid
    names are the initial slow variables ``Gz0, H0, r0`` (any of them, the others fixed); fix the top, the
    torque, ``tau_span`` and options with :func:`functools.partial`. Each chunk is one batch call (the chunk's
    arrays passed as the components ``initial=(Gz0, H0, r0)``).

    Parameters
    ----------
    top : rigidbody.lagrange.Top
    torque : rigidbody.lagrange.Torque
    Gz0, H0, r0 : float or array_like
        Initial :math:`G_z`, :math:`H`, :math:`r` (1.2), swept or fixed.
    tau_span : (float, float)
    tau_eval : array_like, optional
        Output times (each output an array over them); default the values at the end of ``tau_span``.
    outputs : tuple of str
        Fields of the result (``Gz``, ``H``, ``r``, ``u1``, ``u2``, ``u3``, ``k2``, ``delta1``, ``delta2``).
    **options
        Keyword options of :func:`~rigidbody.lagrange.averaged`.

    Returns
    -------
    dict
        As :func:`euler_poinsot_averaged`: the ``outputs``, ``run_status``, ``tau_end``, ``status``, ``message``.

    See Also
    --------
    rigidbody.lagrange.averaged : the function it wraps.
    euler_poinsot_averaged, gyrostat_stability : the other wrappers.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, eqs. (2.15), (3.3).

    Examples
    --------
    The paper's case 2 (``Gz = sqrt(3)/2``, ``H = 7/4``, ``r = sqrt(3)``) under its drag: the spin ends at
    ``r0 exp(-b tau / C) = sqrt(3)/e`` (3.3) at ``tau = 10``:

    >>> import math
    >>> from functools import partial
    >>> from rigidbody import lagrange
    >>> from rigidbody.sweep import lagrange_averaged, sweep
    >>> f = partial(lagrange_averaged, top=lagrange.PAPER_TOP, torque=lagrange.PAPER_DRAG,
    ...             Gz0=math.sqrt(3) / 2, H0=1.75, tau_span=(0.0, 10.0))
    >>> ds = sweep(f, {"r0": [math.sqrt(3)]}, executor="serial", progress=False)
    >>> print(f"{float(ds['r'][0]):.6f} {math.sqrt(3) / math.e:.6f}")
    0.637186 0.637186
    """
    from .. import lagrange

    t1 = float(tau_span[1])
    te = np.array([t1]) if tau_eval is None else tau_eval
    # the grid's arrays go straight in as the components of initial (they broadcast); scalars only: a batch of one
    sol = lagrange.averaged(top, torque, (np.atleast_1d(Gz0), H0, r0), tau_span, tau_eval=te, **options)
    return _evolution_outputs(sol, tuple(outputs), tau_eval is None)
