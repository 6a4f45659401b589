"""Plotting helpers for the parameter studies of :mod:`rigidbody.studies`.

Each takes a study's map: a :class:`rigidbody.studies.StudyMap` (from :func:`rigidbody.studies.evaluate`) or
the ``xarray.Dataset`` of a sweep, read through :func:`rigidbody.studies.grid_values`.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .common import get_ax

__all__ = ["REGIME_COLORS", "averaging_error_plot", "scaled_error_map", "spin_end_map"]

#: colours of the regimes of :func:`rigidbody.studies.spin_end` (0, 1, 2)
REGIME_COLORS = ("#4c72b0", "#55a868", "#c44e52")


def _other_dim(ds: Any, var: str, over: str) -> str:
    others = [d for d in ds[var].dims if d != over]
    if len(others) != 1:
        raise ValueError(f"{var!r} must have exactly one dimension besides {over!r}, has {ds[var].dims}")
    return others[0]


def averaging_error_plot(
    ds: Any, order: float, *, var: str = "error", over: str = "eps", ax: Any = None, label: str | None = None
) -> list[Any]:
    r"""The error of averaging against :math:`\varepsilon` (log-log), one line per value of the other axis.

    A dashed line of slope ``order`` (the theory's) through the median of ``error / eps**order`` is drawn
    for comparison.

    Parameters
    ----------
    ds : rigidbody.studies.StudyMap or xarray.Dataset
        A map of :func:`rigidbody.studies.averaging_error_euler_poinsot` or
        :func:`~rigidbody.studies.averaging_error_lagrange` (two dimensions, one of them ``over``).
    order : float
        The theory's order (2 for Rachinskaya's (9), 1 for the Lagrange first approximation).
    var, over : str
        The error variable and the small-parameter dimension.
    ax : matplotlib.axes.Axes, optional
    label : str, optional
        Name of the other dimension in the legend (default its name).

    Returns
    -------
    list
        The lines drawn (the reference line last).

    See Also
    --------
    scaled_error_map : the same errors divided by ``eps**order``, over the plane.
    rigidbody.studies.fitted_order : the order fitted to the errors.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, eq. (9) (order eps^2);
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, eq. (3.4)
    (order eps).

    Examples
    --------
    A map whose errors are exactly ``3 eps²`` and ``5 eps²``: the reference line of slope 2 passes through
    the median ratio, 4:

    >>> import numpy as np
    >>> from rigidbody.studies import StudyMap
    >>> eps = np.array([0.001, 0.002, 0.004])
    >>> m = StudyMap({"k2_0": np.array([0.3, 0.6]), "eps": eps}, {"error": np.outer([3.0, 5.0], eps**2)})
    >>> from rigidbody.plotting import averaging_error_plot
    >>> lines = averaging_error_plot(m, 2.0)
    >>> [ln.get_label() for ln in lines[:2]], np.allclose(lines[-1].get_ydata(), 4 * lines[-1].get_xdata()**2)
    (['k2_0 = 0.3', 'k2_0 = 0.6'], True)
    """
    import matplotlib.pyplot as plt

    from ..studies import grid_values

    ax = get_ax(ax)
    across = _other_dim(ds, var, over)
    err = grid_values(ds, var, (across, over))
    eps = grid_values(ds, over)
    values = grid_values(ds, across)
    cmap = plt.get_cmap("viridis")
    lines = []
    for i, v in enumerate(values):
        y = err[i]
        ok = np.isfinite(y)
        (ln,) = ax.loglog(eps[ok], y[ok], "o-", ms=3.5, lw=1.2, color=cmap(i / max(1, len(values) - 1)),
                          label=f"{label or across} = {v:.3g}")
        lines.append(ln)
    ratio = err / eps[None, :] ** order
    c = float(np.nanmedian(ratio))
    xs = np.geomspace(eps.min(), eps.max(), 50)
    (ref,) = ax.loglog(xs, c * xs**order, "k--", lw=2.0, label=rf"theory: $\propto\varepsilon^{{{order:g}}}$")
    lines.append(ref)
    ax.set_xlabel(r"$\varepsilon$")
    ax.set_ylabel(f"max |full - averaged| ({var})")
    ax.legend(fontsize=7, ncol=2)
    ax.grid(True, which="both", alpha=0.3)
    return lines


def _edges(v: np.ndarray, log: bool) -> np.ndarray:
    """Cell edges around the (sorted) centres ``v``: arithmetic or geometric midpoints."""
    w = np.log(v) if log else np.asarray(v, dtype=float)
    mid = 0.5 * (w[1:] + w[:-1])
    e = np.concatenate([[w[0] - (mid[0] - w[0])], mid, [w[-1] + (w[-1] - mid[-1])]]) if w.size > 1 else \
        np.array([w[0] - 0.5, w[0] + 0.5])
    return np.exp(e) if log else e


def scaled_error_map(ds: Any, order: float, *, var: str = "error", over: str = "eps", ax: Any = None,
                     ylog: bool = False) -> Any:
    r"""``log10(error / eps**order)`` over the sweep's plane: flat where the theory's order holds.

    Points that failed (the full run refused because the rotation is not fast, a run ended early) are
    left blank and marked "failed".

    Parameters
    ----------
    ds : rigidbody.studies.StudyMap or xarray.Dataset
        As for :func:`averaging_error_plot`.
    order : float
    var, over : str
    ax : matplotlib.axes.Axes, optional
    ylog : bool
        A logarithmic axis for the other dimension (e.g. the distance ``1 - k2_0`` to the separatrix).

    Returns
    -------
    matplotlib.collections.QuadMesh

    See Also
    --------
    averaging_error_plot : the errors against eps, one line per value of the other axis.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, eq. (9) (order eps^2);
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, eq. (3.4)
    (order eps).

    Examples
    --------
    Errors exactly ``3 eps²`` and ``5 eps²``: the map is flat along eps, at ``log10 3`` and ``log10 5``:

    >>> import numpy as np
    >>> from rigidbody.studies import StudyMap
    >>> eps = np.array([0.001, 0.002, 0.004])
    >>> m = StudyMap({"k2_0": np.array([0.3, 0.6]), "eps": eps}, {"error": np.outer([3.0, 5.0], eps**2)})
    >>> from rigidbody.plotting import scaled_error_map
    >>> z = scaled_error_map(m, 2.0).get_array()
    >>> print(np.round(z, 9), f"{np.log10(3):.9f} {np.log10(5):.9f}")
    [[0.477121255 0.477121255 0.477121255]
     [0.698970004 0.698970004 0.698970004]] 0.477121255 0.698970004
    """
    from matplotlib.ticker import NullFormatter

    from ..studies import grid_values

    ax = get_ax(ax)
    across = _other_dim(ds, var, over)
    eps, values = grid_values(ds, over), grid_values(ds, across)
    scaled = grid_values(ds, var, (across, over)) / eps[None, :] ** order
    order_x, order_y = np.argsort(eps), np.argsort(values)
    z = np.log10(scaled)[np.ix_(order_y, order_x)]
    x, y = eps[order_x], values[order_y]
    mesh = ax.pcolormesh(_edges(x, True), _edges(y, ylog), np.ma.masked_invalid(z), cmap="magma")
    failed = ~np.isfinite(z)
    for i, j in zip(*np.nonzero(failed)):
        ax.text(x[j], y[i], "failed", ha="center", va="center", fontsize=7, color="0.3")
    ax.figure.colorbar(mesh, ax=ax, label=rf"$\log_{{10}}$({var} / $\varepsilon^{{{order:g}}}$)")
    ax.set_xscale("log")
    ax.xaxis.set_minor_formatter(NullFormatter())  # a narrow eps range: the minor labels would collide
    if ylog:
        ax.set_yscale("log")
    ax.set_xlabel(r"$\varepsilon$")
    ax.set_ylabel(across)
    return mesh


def spin_end_map(ds: Any, *, k2_0: float = 0.5, ax: Any = None, cases: dict[str, tuple[float, float]] | None = None
                 ) -> list[Any]:
    r"""The final regime of :math:`k^2` over the plane of decay-rate ratios, with the lines of (7)-(8).

    Draws the regimes of :func:`rigidbody.studies.spin_end` (blue: :math:`k^2 \to 0`, green: an interior
    :math:`k_*^2`, red: the separatrix), the line :math:`\chi = -3` (:func:`rigidbody.studies.chi_minus_3_line`),
    the line ``r3 = r1`` (below it :math:`k^2` reaches the separatrix) and, where it splits two regimes, the
    line where ``k2_0`` is an equilibrium (:func:`~rigidbody.studies.equilibrium_line`).

    Parameters
    ----------
    ds : rigidbody.studies.StudyMap or xarray.Dataset
        A map of :func:`rigidbody.studies.spin_end` over ``r1`` and ``r3``.
    k2_0 : float
        The initial :math:`k^2` of that sweep.
    ax : matplotlib.axes.Axes, optional
    cases : dict, optional
        Labelled points ``{label: (r1, r3)}`` to mark (e.g. the paper's drag cases).

    Returns
    -------
    list
        The mesh and the lines drawn.

    See Also
    --------
    rigidbody.paperfigs.studies.spin_end : the figure drawn with it.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, eqs. (7)-(8).

    Examples
    --------
    On any map over ``r1`` and ``r3`` the line :math:`\chi = -3` is :math:`r_3 = 2r_1 - 1`:

    >>> import numpy as np
    >>> from rigidbody.studies import StudyMap
    >>> from rigidbody.plotting import spin_end_map
    >>> r1, r3 = np.linspace(0.2, 1.8, 5), np.linspace(0.2, 1.8, 4)
    >>> out = spin_end_map(StudyMap({"r1": r1, "r3": r3}, {"regime": np.zeros((5, 4))}))
    >>> chi3 = out[1]
    >>> print(chi3.get_label(), np.allclose(chi3.get_ydata(), 2 * chi3.get_xdata() - 1, rtol=0, atol=1e-15))
    $\chi=-3$: $r_3 = 2r_1 - 1$ True
    """
    from matplotlib.colors import BoundaryNorm, ListedColormap
    from matplotlib.patches import Patch

    from ..studies import chi_minus_3_line, equilibrium_line, grid_values

    ax = get_ax(ax)
    r1, r3 = grid_values(ds, "r1"), grid_values(ds, "r3")
    reg = grid_values(ds, "regime", ("r3", "r1"))
    mesh = ax.pcolormesh(r1, r3, reg, shading="nearest", cmap=ListedColormap(REGIME_COLORS),
                         norm=BoundaryNorm([-0.5, 0.5, 1.5, 2.5], 3), alpha=0.75)
    xs = np.linspace(r1.min(), r1.max(), 200)
    out: list[Any] = [mesh]
    out += ax.plot(xs, chi_minus_3_line(xs), "k-", lw=2, label=r"$\chi=-3$: $r_3 = 2r_1 - 1$")
    out += ax.plot(xs, xs, "k--", lw=1.5, label=r"$r_3 = r_1$ ($a_1 = a_3$)")
    low = xs[xs < 1.0]
    out += ax.plot(low, equilibrium_line(low, k2_0), "k:", lw=2, label=rf"$k^2_0 = {k2_0:g}$ an equilibrium")
    for name, (x, y) in (cases or {}).items():
        out += ax.plot([x], [y], "w*", ms=14, mec="k")
        ax.annotate(name, (x, y), xytext=(6, 6), textcoords="offset points", fontsize=8)
    ax.set_xlim(r1.min(), r1.max())
    ax.set_ylim(r3.min(), r3.max())
    ax.set_xlabel(r"$r_1 = a_1/a_2$   ($a_i = I_{ii}/A_i$)")
    ax.set_ylabel(r"$r_3 = a_3/a_2$")
    patches = [Patch(color=c, alpha=0.75, label=t) for c, t in
               zip(REGIME_COLORS, (r"$k^2\to 0$", r"$k^2\to k_*^2$ (interior)", r"$k^2\to 1$ (separatrix)"))]
    handles, _ = ax.get_legend_handles_labels()
    ax.legend(handles=patches + handles, fontsize=7, loc="upper left")
    return out
