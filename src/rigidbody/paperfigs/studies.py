"""The two parameter studies of :mod:`rigidbody.studies` as figures, on their quick grids.

*Where averaging holds*: the error of the averaged against the full evolution over (eps, k2_0) for the
Euler--Poinsot module (order eps^2) and over (eps, theta0) for the Lagrange top (order eps).
*Where the spin ends*: the final regime of k2 over the plane of drag-rate ratios, with the chi = -3 line.

Each figure function takes the study's map (from :func:`study_data`) or computes it on the study's quick
grid in this process with :func:`rigidbody.studies.evaluate` (batch integrations, seconds; the base install
suffices). The full grids (``rigidbody.studies.GRIDS[...]['full']``) are for a sweep on a cluster
(:doc:`/sweeps`): pass its Dataset.
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
    """The map behind a study figure: the study ``name`` over its grid ``rigidbody.studies.GRIDS[name][size]``.

    Without keyword arguments it is computed in this process by :func:`rigidbody.studies.evaluate` (the
    study integrates all the points as batches; no optional dependency). With keyword arguments of
    :func:`rigidbody.sweep.sweep` (``executor``, ``store``, ``chunk_size``, ...) the same function is swept
    with them instead (the ``sweep`` extra; no progress bar unless ``progress=True``): the same numbers, on
    local processes or a Dask cluster, resumable.

    Parameters
    ----------
    name : {'averaging_euler_poinsot', 'averaging_lagrange', 'spin_end'}
    size : {'quick', 'full'}
        The study's grid; 'full' is meant for a cluster (``executor=`` a Dask client or address).
    **sweep_kw
        Keyword arguments of :func:`rigidbody.sweep.sweep`.

    Returns
    -------
    rigidbody.studies.StudyMap or xarray.Dataset
        A :class:`~rigidbody.studies.StudyMap` without keyword arguments, else the sweep's Dataset.

    See Also
    --------
    rigidbody.studies.evaluate : the in-process evaluation.
    rigidbody.sweep.sweep : the same on workers.

    Examples
    --------
    The quick grid of the spin-end study, 13 x 13 drag tensors, in this process:

    >>> from rigidbody.paperfigs import studies as figs
    >>> figs.study_data("spin_end")
    StudyMap(r1: 13, r3: 13; outputs ['regime', 'k2_end', 'tau_end', 'chi']; 0 failed)
    """
    from rigidbody import studies

    func: dict[str, Callable[..., dict[str, Any]]] = {
        "averaging_euler_poinsot": studies.averaging_error_euler_poinsot,
        "averaging_lagrange": studies.averaging_error_lagrange,
        "spin_end": studies.spin_end,
    }
    if name not in func:
        raise ValueError(f"name must be one of {sorted(func)}, got {name!r}")
    if size not in studies.GRIDS[name]:
        raise ValueError(f"size must be one of {sorted(studies.GRIDS[name])}, got {size!r}")
    grid = studies.GRIDS[name][size]
    if not sweep_kw:
        return studies.evaluate(func[name], grid)
    from rigidbody.sweep import sweep

    sweep_kw.setdefault("progress", False)
    return sweep(func[name], grid, **sweep_kw)


def paper_cases() -> dict[str, tuple[float, float]]:
    """Rachinskaya's drag cases 1 and 2 in the plane (r1, r3) of decay-rate ratios a_i = I_ii / A_i.

    Returns
    -------
    dict of str to (float, float)

    See Also
    --------
    spin_end : the figure that marks them.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, section 3 (the body and the two drag tensors).

    Examples
    --------
    Case 1: :math:`a = (2.322/3.2, 1.31/2.6, 1.425/1.67)`:

    >>> from rigidbody.paperfigs import studies as figs
    >>> r1, r3 = figs.paper_cases()["case 1"]
    >>> print(f"{r1:.9f} {(2.322 / 3.2) / (1.31 / 2.6):.9f} {r3:.9f} {(1.425 / 1.67) / (1.31 / 2.6):.9f}")
    1.440171756 1.440171756 1.693559446 1.693559446
    """
    from rigidbody import studies

    A = np.array([studies.PAPER_BODY.A1, studies.PAPER_BODY.A2, studies.PAPER_BODY.A3])
    out = {}
    for label, diag in (("case 1", studies.PAPER_DRAG_CASE1), ("case 2", (0.919, 5.228, 1.666))):
        a = np.asarray(diag) / A
        out[label] = (float(a[0] / a[1]), float(a[2] / a[1]))
    return out


def _recoord(m: Any, name: str, new: str, values: np.ndarray) -> Any:
    """The map with its grid coordinate ``name`` replaced by ``new`` with ``values`` (the same points)."""
    from rigidbody.studies import StudyMap

    coords = {(new if k == name else k): (values if k == name else v) for k, v in m.coords.items()}
    return StudyMap(coords, m.data)


def _averaging_figure(name: str, ds: Any) -> Any:
    import matplotlib.pyplot as plt

    from rigidbody import studies
    from rigidbody.plotting import studies as sp

    m = studies.as_study_map(study_data(name) if ds is None else ds)
    if name == "averaging_lagrange":
        order, label = 1.0, "theta0 (deg)"
        m = _recoord(m, "theta0", "theta0_deg", np.degrees(m.coords["theta0"]))
        title = "Lagrange top: first approximation (3.4) vs full (1.1), tau in [0, 2]"
    else:  # the distance to the separatrix, on a log axis
        order, label = 2.0, "1 - k2_0"
        m = _recoord(m, "k2_0", "one_minus_k2_0", 1.0 - m.coords["k2_0"])
        title = "Euler-Poinsot: averaged (9) with nu kept vs full, tau in [0, 0.5]"
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(12, 4.8))
    sp.averaging_error_plot(m, order, ax=a1, label=label)
    sp.scaled_error_map(m, order, ax=a2, ylog=name == "averaging_euler_poinsot")
    a2.set_ylabel(label)
    fig.suptitle(title)
    fig.tight_layout()
    return fig


def where_averaging_holds_euler_poinsot(ds: Any = None) -> Any:
    """Averaged (9) against full motion over (eps, k2_0), with the theory's order eps^2 overlaid.

    Parameters
    ----------
    ds : rigidbody.studies.StudyMap or xarray.Dataset, optional
        A map of :func:`rigidbody.studies.averaging_error_euler_poinsot` over ``eps`` and ``k2_0``
        (:func:`study_data`; default: the quick grid).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    rigidbody.plotting.averaging_error_plot, rigidbody.plotting.scaled_error_map : the two panels.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, eq. (9) (an approximation of order eps^2).

    Examples
    --------
    Any map over ``eps`` and ``k2_0`` with an ``error`` will do (here errors exactly ``eps²``, which the
    right panel shows flat at 0); the default is the study's quick grid:

    >>> import numpy as np
    >>> from rigidbody.studies import StudyMap
    >>> from rigidbody.paperfigs import studies as figs
    >>> eps = np.array([0.01, 0.02, 0.04])
    >>> m = StudyMap({"eps": eps, "k2_0": np.array([0.5, 0.9])}, {"error": np.outer(eps**2, [1.0, 1.0])})
    >>> fig = figs.where_averaging_holds_euler_poinsot(m)
    >>> print(np.round(np.asarray(fig.axes[1].collections[0].get_array()).ravel(), 12) + 0.0)
    [0. 0. 0. 0. 0. 0.]
    """
    return _averaging_figure("averaging_euler_poinsot", ds)


def where_averaging_holds_lagrange(ds: Any = None) -> Any:
    """First approximation (3.4) against the full equations (1.1) over (eps, theta0), order eps overlaid.

    Parameters
    ----------
    ds : rigidbody.studies.StudyMap or xarray.Dataset, optional
        A map of :func:`rigidbody.studies.averaging_error_lagrange` over ``eps`` and ``theta0``
        (:func:`study_data`; default: the quick grid).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    rigidbody.plotting.averaging_error_plot, rigidbody.plotting.scaled_error_map : the two panels.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, eqs. (1.1) and
    (3.4).

    Examples
    --------
    Any map over ``eps`` and ``theta0`` (radians, shown in degrees) with an ``error`` will do; the default is
    the study's quick grid:

    >>> import numpy as np
    >>> from rigidbody.studies import StudyMap
    >>> from rigidbody.paperfigs import studies as figs
    >>> eps = np.array([0.01, 0.02, 0.04])
    >>> m = StudyMap({"eps": eps, "theta0": np.radians([30.0, 60.0])}, {"error": np.outer(eps, [1.0, 2.0])})
    >>> fig = figs.where_averaging_holds_lagrange(m)
    >>> [line.get_label() for line in fig.axes[0].lines[:2]]
    ['theta0 (deg) = 30', 'theta0 (deg) = 60']
    """
    return _averaging_figure("averaging_lagrange", ds)


def spin_end(ds: Any = None) -> Any:
    """Final regime of k2 over the plane of drag-rate ratios (r1, r3), with the chi = -3 line of (7)-(8).

    Parameters
    ----------
    ds : rigidbody.studies.StudyMap or xarray.Dataset, optional
        A map of :func:`rigidbody.studies.spin_end` over ``r1`` and ``r3`` (:func:`study_data`; default: the
        full grid, 120 x 120 drag tensors in one batch, a few seconds in this process, from ``k2_0 = K2_0``:
        fine enough that the regime boundaries are lines, not staircases).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    rigidbody.plotting.spin_end_map : the left panel.
    study_data : the map.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, eqs. (7)-(8).

    Examples
    --------
    The paper's two drag cases are marked: case 1 (:math:`\\chi < -3`) ends at an interior :math:`k_*^2`,
    case 2 (:math:`\\chi > 0`) at :math:`k^2 = 0`, as the studies find at those points:

    >>> import numpy as np
    >>> from rigidbody import studies
    >>> from rigidbody.paperfigs import studies as figs
    >>> [int(studies.spin_end(*rr)["regime"]) for rr in figs.paper_cases().values()]
    [1, 0]

    Any map over ``r1`` and ``r3`` with ``regime`` and ``k2_end`` will do (by default the study's quick grid,
    :func:`study_data`):

    >>> r = np.array([0.5, 1.0, 1.5])
    >>> m = studies.StudyMap({"r1": r, "r3": r}, {"regime": np.ones((3, 3)), "k2_end": np.full((3, 3), 0.5)})
    >>> fig = figs.spin_end(m)
    >>> sorted(t.get_text() for t in fig.axes[0].texts)
    ['case 1', 'case 2']
    """
    import matplotlib.pyplot as plt

    from rigidbody.plotting import studies as sp
    from rigidbody.studies import chi_minus_3_line, grid_values

    if ds is None:
        ds = study_data("spin_end", "full")
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(12, 5.2))
    sp.spin_end_map(ds, k2_0=K2_0, ax=a1, cases=paper_cases())
    a1.set_title(f"final regime of k2 from k2_0 = {K2_0:g} (averaged (8)/(9), eps = 0)")
    r1, r3 = grid_values(ds, "r1"), grid_values(ds, "r3")
    inside = grid_values(ds, "regime", ("r3", "r1")) == 1
    k2 = np.where(inside, grid_values(ds, "k2_end", ("r3", "r1")), np.nan)
    mesh = a2.pcolormesh(r1, r3, k2, shading="nearest", cmap="viridis", vmin=0.0, vmax=1.0)
    fig.colorbar(mesh, ax=a2, label="interior equilibrium k*2 reached")
    xs = np.linspace(float(r1.min()), float(r1.max()), 100)
    a2.plot(xs, chi_minus_3_line(xs), "k-", lw=2)
    a2.plot(xs, xs, "k--", lw=1.5)
    a2.set_xlim(xs[0], xs[-1])
    a2.set_ylim(float(r3.min()), float(r3.max()))
    a2.set_xlabel(r"$r_1 = a_1/a_2$")
    a2.set_ylabel(r"$r_3 = a_3/a_2$")
    a2.set_title("where k2 settles inside (0, 1): k*2 -> 0 at chi = -3, -> 1 at r3 = r1")
    fig.tight_layout()
    return fig


register_figures(
    "studies", "Parameter studies: where averaging holds, where the spin ends (rigidbody.studies)",
    {"where_averaging_holds_euler_poinsot": where_averaging_holds_euler_poinsot,
     "where_averaging_holds_lagrange": where_averaging_holds_lagrange,
     "spin_end": spin_end},
)
