"""The two parameter studies of :mod:`rigidbody.studies` as figures, on their quick grids.

*Where averaging holds*: the error of the averaged against the full evolution over (eps, k2_0) for the
Euler--Poinsot module (order eps^2) and over (eps, theta0) for the Lagrange top (order eps).
*Where the spin ends*: the final regime of k2 over the plane of drag-rate ratios, with the chi = -3 line.

Each figure function takes the swept ``xarray.Dataset`` (from :func:`study_data`) or computes it on the
study's quick grid (seconds on 2 cores, local processes). The full grids
(``rigidbody.studies.GRIDS[...]['full']``) are for a sweep on a cluster (docs/sweeps.md): pass their Dataset.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from rigidbody.paperfigs import register_figures

__all__ = ["K2_0", "paper_cases", "spin_end", "study_data", "where_averaging_holds_euler_poinsot",
           "where_averaging_holds_lagrange"]

#: the spin-end map starts every drag tensor from this k2
K2_0 = 0.5


def study_data(name: str, size: str = "quick", **sweep_kw: Any) -> Any:
    """The Dataset behind a study figure: ``name`` in ``rigidbody.studies.GRIDS``, swept with
    :func:`rigidbody.sweep.sweep` (keyword arguments go to it; default on local processes, no progress bar).

    Parameters
    ----------
    name : {'averaging_euler_poinsot', 'averaging_lagrange', 'spin_end'}
    size : {'quick', 'full'}
        The study's grid; 'full' is meant for a cluster (``executor=`` a Dask client or address).

    Returns
    -------
    xarray.Dataset
    """
    from rigidbody import studies
    from rigidbody.sweep import sweep

    func: dict[str, Callable[..., dict[str, float]]] = {
        "averaging_euler_poinsot": studies.averaging_error_euler_poinsot,
        "averaging_lagrange": studies.averaging_error_lagrange,
        "spin_end": studies.spin_end,
    }
    if name not in func:
        raise ValueError(f"name must be one of {sorted(func)}, got {name!r}")
    sweep_kw.setdefault("progress", False)
    return sweep(func[name], studies.GRIDS[name][size], **sweep_kw)


def paper_cases() -> dict[str, tuple[float, float]]:
    """Rachinskaya's drag cases 1 and 2 in the plane (r1, r3) of decay-rate ratios a_i = I_ii / A_i."""
    from rigidbody import studies

    A = np.array([studies.PAPER_BODY.A1, studies.PAPER_BODY.A2, studies.PAPER_BODY.A3])
    out = {}
    for label, diag in (("case 1", studies.PAPER_DRAG_CASE1), ("case 2", (0.919, 5.228, 1.666))):
        a = np.asarray(diag) / A
        out[label] = (float(a[0] / a[1]), float(a[2] / a[1]))
    return out


def _averaging_figure(name: str, ds: Any) -> Any:
    import matplotlib.pyplot as plt

    from rigidbody.plotting import studies as sp

    if ds is None:
        ds = study_data(name)
    if name == "averaging_lagrange":
        order, label = 1.0, "theta0 (deg)"
        ds = ds.assign_coords(theta0=np.degrees(ds.theta0)).rename(theta0="theta0_deg")
        title = "Lagrange top: first approximation (3.4) vs full (1.1), tau in [0, 2]"
    else:  # the distance to the separatrix, on a log axis
        order, label = 2.0, "1 - k2_0"
        ds = ds.assign_coords(k2_0=1.0 - ds.k2_0).rename(k2_0="one_minus_k2_0")
        title = "Euler-Poinsot: averaged (9) with nu kept vs full, tau in [0, 0.5]"
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(12, 4.8))
    sp.averaging_error_plot(ds, order, ax=a1, label=label)
    sp.scaled_error_map(ds, order, ax=a2, ylog=name == "averaging_euler_poinsot")
    fig.suptitle(title)
    fig.tight_layout()
    return fig


def where_averaging_holds_euler_poinsot(ds: Any = None) -> Any:
    """Averaged (9) against full motion over (eps, k2_0), with the theory's order eps^2 overlaid.

    Parameters
    ----------
    ds : xarray.Dataset, optional
        A sweep of :func:`rigidbody.studies.averaging_error_euler_poinsot` (default: the quick grid).

    Returns
    -------
    matplotlib.figure.Figure
    """
    return _averaging_figure("averaging_euler_poinsot", ds)


def where_averaging_holds_lagrange(ds: Any = None) -> Any:
    """First approximation (3.4) against the full equations (1.1) over (eps, theta0), order eps overlaid.

    Parameters
    ----------
    ds : xarray.Dataset, optional
        A sweep of :func:`rigidbody.studies.averaging_error_lagrange` (default: the quick grid).

    Returns
    -------
    matplotlib.figure.Figure
    """
    return _averaging_figure("averaging_lagrange", ds)


def spin_end(ds: Any = None) -> Any:
    """Final regime of k2 over the plane of drag-rate ratios (r1, r3), with the chi = -3 line of (7)-(8).

    Parameters
    ----------
    ds : xarray.Dataset, optional
        A sweep of :func:`rigidbody.studies.spin_end` (default: the quick grid, from ``k2_0 = K2_0``).

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    from rigidbody.plotting import studies as sp
    from rigidbody.studies import chi_minus_3_line

    if ds is None:
        ds = study_data("spin_end")
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(12, 5.2))
    sp.spin_end_map(ds, k2_0=K2_0, ax=a1, cases=paper_cases())
    a1.set_title(f"final regime of k2 from k2_0 = {K2_0:g} (averaged (8)/(9), eps = 0)")
    k2 = ds["k2_end"].where(ds["regime"] == 1).transpose("r3", "r1")
    mesh = a2.pcolormesh(ds["r1"].values, ds["r3"].values, k2.values, shading="nearest", cmap="viridis",
                         vmin=0.0, vmax=1.0)
    fig.colorbar(mesh, ax=a2, label="interior equilibrium k*2 reached")
    xs = np.linspace(float(ds.r1.min()), float(ds.r1.max()), 100)
    a2.plot(xs, chi_minus_3_line(xs), "k-", lw=2)
    a2.plot(xs, xs, "k--", lw=1.5)
    a2.set_xlim(xs[0], xs[-1])
    a2.set_ylim(float(ds.r3.min()), float(ds.r3.max()))
    a2.set_xlabel(r"$r_1 = a_1/a_2$")
    a2.set_ylabel(r"$r_3 = a_3/a_2$")
    a2.set_title("where k2 settles inside (0, 1): k*2 -> 0 at chi = -3, -> 1 at r3 = r1")
    fig.tight_layout()
    return fig


register_figures(
    "studies", "Parameter studies: where averaging holds, where the spin ends (rigidbody.sweep)",
    {"where_averaging_holds_euler_poinsot": where_averaging_holds_euler_poinsot,
     "where_averaging_holds_lagrange": where_averaging_holds_lagrange,
     "spin_end": spin_end},
)
