"""Plotting helpers for :mod:`rigidbody.gyrostat`: stability maps, kappa0 curves, the dumbbell figure."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .common import get_ax, time_series

__all__ = ["VERDICT_COLORS", "dumbbell_side_view", "normalized_map_plot", "plot_satellite_motion", "stability_map_plot"]

#: colours of the verdict codes -1 (invalid), 0 (stable), 1 (unstable), 2 (undecided)
VERDICT_COLORS = {-1: "0.85", 0: "#7fc97f", 1: "#e7298a", 2: "#fdc086"}


def stability_map_plot(
    x: Any,
    y: Any,
    code: Any,
    ax: Any = None,
    *,
    boundaries: dict[str, tuple[Any, Any]] | None = None,
    restricted: dict[str, tuple[Any, Any]] | None = None,
    vlines: dict[str, Any] | None = None,
    legend: bool = True,
) -> Any:
    """Draw verdict regions of a stability map with boundary curves overlaid.

    Parameters
    ----------
    x, y : 1-D arrays
        Grid coordinates (first and second axis of ``code``).
    code : 2-D int array, shape (len(x), len(y))
        Verdict codes of :class:`rigidbody.gyrostat.StabilityMap` (0 stable, 1 unstable, 2 undecided,
        -1 invalid).
    boundaries : dict label -> (xs, ys)
        Exact boundary curves (solid black lines), e.g. s2 = 0, s3 = 0.
    restricted : dict label -> (xs, ys)
        Restricted-problem boundaries (dashed blue lines).
    vlines : dict label -> x positions
        Vertical boundaries (s1 = 0 or r1 = 0, independent of the y parameter).

    Returns
    -------
    Axes

    See Also
    --------
    normalized_map_plot : computes a map and draws it with this function.
    rigidbody.gyrostat.stability_map : the verdict codes.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eq. (2.5).

    Examples
    --------
    >>> from rigidbody.plotting import stability_map_plot
    >>> code = [[0, 1], [1, 2], [2, -1]]
    >>> ax = stability_map_plot([0.0, 1.0, 2.0], [0.0, 1.0], code, boundaries={"s2 = 0": ([0.0, 2.0], [0.5, 0.5])})
    >>> [t.get_text() for t in ax.get_legend().get_texts()]
    ['stable', 'unstable', 'undecided', 's2 = 0']
    """
    from matplotlib.colors import BoundaryNorm, ListedColormap
    from matplotlib.patches import Patch

    ax = get_ax(ax)
    cmap = ListedColormap([VERDICT_COLORS[c] for c in (-1, 0, 1, 2)])
    norm = BoundaryNorm([-1.5, -0.5, 0.5, 1.5, 2.5], cmap.N)
    ax.pcolormesh(np.asarray(x), np.asarray(y), np.asarray(code).T, cmap=cmap, norm=norm, shading="nearest",
                  rasterized=True)
    ylim = (float(np.min(y)), float(np.max(y)))
    styles = ["-", "-."]
    for i, (lab, (xs, ys)) in enumerate((boundaries or {}).items()):
        ax.plot(xs, ys, "k", ls=styles[i % 2], lw=1.2, label=lab)
    for i, (lab, (xs, ys)) in enumerate((restricted or {}).items()):
        ax.plot(xs, ys, color="tab:blue", ls="--" if i % 2 == 0 else ":", lw=1.2, label=lab)
    for i, (lab, xs) in enumerate((vlines or {}).items()):
        for j, xv in enumerate(np.atleast_1d(xs)):
            ax.axvline(xv, color="k" if i == 0 else "tab:blue", ls="-" if i == 0 else "--", lw=0.9,
                       label=lab if j == 0 else None)
    ax.set_ylim(*ylim)
    ax.set_xlim(float(np.min(x)), float(np.max(x)))
    if legend:
        handles = [Patch(color=VERDICT_COLORS[c], label=n) for c, n in ((0, "stable"), (1, "unstable"),
                                                                         (2, "undecided"))]
        h, lbl = ax.get_legend_handles_labels()
        ax.legend(handles=handles + h, labels=["stable", "unstable", "undecided", *lbl], fontsize=6, loc="best",
                  framealpha=0.8)
    return ax


def normalized_map_plot(
    sat: Any, R0: float, theta0: Any, u: Any, ax: Any = None, *, legend: bool = True, data: Any = None
) -> tuple:
    """Compute and draw the map in the plane (theta0, u = k2 / (omega0 Abar)) with all boundaries.

    Exact boundaries s2 = 0, s3 = 0 (explicit curves, :func:`rigidbody.gyrostat.exact_boundaries`) and
    s1 = 0 (sign changes on the theta0 grid) in black; the restricted ones r2 = 0, r3 = 0, r1 = 0 (closed
    form) in blue.

    Parameters
    ----------
    sat, R0, theta0, u
        The satellite, the orbit radius and the grid, as for
        :func:`rigidbody.gyrostat.normalized_stability_map`.
    ax : Axes, optional
    legend : bool
        Draw the legend of the verdicts and the curves.
    data : (StabilityMap, dict), optional
        The result of ``normalized_stability_map(sat, R0, theta0, u)`` computed already: drawn as it is
        (``sat`` and ``R0`` are then not used).

    Returns
    -------
    (Axes, StabilityMap, boundaries dict)

    See Also
    --------
    rigidbody.gyrostat.normalized_stability_map : the map and the curves drawn.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eq. (2.5) and the restricted conditions after it.

    Examples
    --------
    >>> import numpy as np
    >>> from rigidbody import gyrostat
    >>> from rigidbody.plotting import normalized_map_plot
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    >>> ax, mp, b = normalized_map_plot(sat, 1.0, np.linspace(-1.2, 1.2, 25), np.linspace(-6.0, 6.0, 25))
    >>> mp.shape, ax.get_xlabel(), ax.get_ylabel()
    ((25, 25), 'θ0 (rad)', 'k2 / (ω0 Ā)')
    """
    from rigidbody import gyrostat

    th = np.asarray(theta0, dtype=float)
    mp, b = gyrostat.normalized_stability_map(sat, R0, th, u) if data is None else data
    s1 = b["s1"]
    s1_zero = th[:-1][np.sign(s1[:-1]) != np.sign(s1[1:])]
    r1_zero = b["theta_r1"][(b["theta_r1"] >= th.min()) & (b["theta_r1"] <= th.max())]
    ax = stability_map_plot(
        th, u, mp.code, ax,
        boundaries={"s2 = 0": (th, b["u_s2"]), "s3 = 0": (th, b["u_s3"])},
        restricted={"restricted r3 = 0": (th, b["u_r3"]), "restricted r2 = 0": (th, b["u_r2"])},
        vlines={"s1 = 0": s1_zero, "restricted r1 = 0": r1_zero},
        legend=legend,
    )
    ax.set_xlabel("θ0 (rad)")
    ax.set_ylabel("k2 / (ω0 Ā)")
    return ax, mp, b


def dumbbell_side_view(
    R0: float, kappa0: float, theta0: float, arm: float, ax: Any = None, *, elevation_deg: float = 12.0
) -> Any:
    r"""The paper's figure, to scale: a dumbbell satellite whose circular orbit plane misses the centre.

    The view is the plane through the orbit normal zeta2 (vertical) and the radius vector OG.  The
    orbit (radius ``R0 cos kappa0``, in the horizontal plane at height ``R0 sin kappa0``) is drawn as an
    ellipse seen from ``elevation_deg`` above its plane; the dumbbell axis x3 makes the angle
    ``theta0`` with OG (y3) in the plane y2 y3, its balls at distance ``arm`` from G.

    Parameters
    ----------
    R0, kappa0, theta0 : float
        The motion (orbit radius, latitude of G, tilt of x3 from OG), e.g. of
        :func:`rigidbody.gyrostat.symmetric_stationary_motion`.
    arm : float
        Distance of each ball from G.
    ax : matplotlib.axes.Axes, optional
    elevation_deg : float
        Elevation of the view above the orbit plane.

    Returns
    -------
    matplotlib.axes.Axes

    See Also
    --------
    rigidbody.paperfigs.gyrostat.fig1_dumbbell : the paper's figure drawn with it.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, section 5 and its figure.

    Examples
    --------
    The displacement of the orbit plane is marked with its value :math:`R_0\sin\kappa_0`:

    >>> import math
    >>> from rigidbody import gyrostat
    >>> from rigidbody.plotting import dumbbell_side_view
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    >>> m = gyrostat.stationary_motion(sat, 1.0, math.pi / 4, k2=0.0)
    >>> ax = dumbbell_side_view(m.R0, m.kappa0, m.theta0, 0.3)
    >>> [t.get_text() for t in ax.texts if t.get_text().startswith("R0")], f"{m.R0 * math.sin(m.kappa0):.3g}"
    (['R0 sin κ0 = 0.00299'], '0.00299')
    """
    from matplotlib.patches import Circle

    ax = get_ax(ax, figsize=(7.0, 5.0))
    ck, sk = math.cos(kappa0), math.sin(kappa0)
    h = R0 * sk
    rho = R0 * ck
    e = math.sin(math.radians(elevation_deg))
    t = np.linspace(0, 2 * np.pi, 400)
    ax.plot(rho * np.cos(t), h + e * rho * np.sin(t), color="tab:blue", lw=1.0, label="orbit of G")
    ax.plot([-1.15 * rho, 1.15 * rho], [0, 0], color="0.6", lw=0.8, ls=":", label="plane through O")
    ax.plot([-1.15 * rho, 1.15 * rho], [h, h], color="tab:blue", lw=0.8, ls="--", label="orbit plane")
    ax.plot([0, 0], [-0.25 * R0, 0.45 * R0], color="0.3", lw=0.8)
    ax.annotate("ζ2", (0, 0.45 * R0), textcoords="offset points", xytext=(4, -8), fontsize=9)
    ax.plot(0, 0, "ko", ms=6)
    ax.annotate("O", (0, 0), textcoords="offset points", xytext=(-12, -12), fontsize=10)
    G = np.array([rho, h])
    ax.plot([0, G[0]], [0, G[1]], color="k", lw=0.8, ls="-")
    y3 = np.array([ck, sk])
    y2 = np.array([-sk, ck])
    x3 = math.sin(theta0) * y2 + math.cos(theta0) * y3
    p1, p2 = G + arm * x3, G - arm * x3
    ax.plot([p1[0], p2[0]], [p1[1], p2[1]], color="0.2", lw=2.0)
    for p in (p1, p2):
        ax.add_patch(Circle(tuple(p), 0.06 * arm + 0.01 * R0, color="tab:red", zorder=3))
    ax.plot(*G, "k.", ms=5)
    ax.annotate("G", tuple(G), textcoords="offset points", xytext=(6, -12), fontsize=10)
    # the displacement of the orbit plane
    xd = -0.85 * rho
    ax.annotate("", xy=(xd, h), xytext=(xd, 0), arrowprops={"arrowstyle": "<->", "lw": 0.9})
    ax.annotate(f"R0 sin κ0 = {h:.3g}", (xd, h / 2), textcoords="offset points", xytext=(5, 0), fontsize=8)
    ax.set_aspect("equal")
    ax.set_xlabel("distance from the ζ2 axis (units of R0)")
    ax.legend(fontsize=7, loc="lower right")
    return ax


def plot_satellite_motion(sol: Any, ax: Any = None, **kw: Any) -> Any:
    """The standard figure of :func:`rigidbody.gyrostat.simulate`: the distance ``R`` of the centre of mass
    from the attracting centre, the latitude ``kappa`` of G and the direction cosines ``gamma`` of OG in the
    body axes against ``t`` (three Axes, created when ``ax`` is None; a stationary motion keeps all
    constant). Returns the Axes.

    Parameters
    ----------
    sol : Solution
        A run of :func:`rigidbody.gyrostat.simulate`.
    ax : sequence of three Axes, optional
    **kw
        Line style of the ``gamma`` curves.

    Returns
    -------
    numpy.ndarray of Axes

    See Also
    --------
    rigidbody.plotting.plot_solution : ``sol.plot()``, which calls it.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, sections 1-2.

    Examples
    --------
    >>> import math
    >>> import numpy as np
    >>> from rigidbody import gyrostat
    >>> from rigidbody.plotting import plot_satellite_motion
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    >>> m = gyrostat.stationary_motion(sat, 1.0, math.pi / 4, k2=0.0)
    >>> sol = gyrostat.simulate(m.satellite, m, (0.0, 2 * math.pi), t_eval=np.linspace(0.0, 2 * math.pi, 50))
    >>> import matplotlib.pyplot as plt
    >>> [ax.get_ylabel() for ax in plot_satellite_motion(sol, plt.subplots(3, 1, sharex=True)[1])]
    ['R', 'κ', 'γ (OG in body axes)']
    """
    import matplotlib.pyplot as plt

    new = ax is None
    if new:
        _, ax = plt.subplots(3, 1, figsize=(6.5, 6.5), sharex=True)
    axes = np.asarray(ax, dtype=object).ravel()
    if axes.size != 3:
        raise ValueError(f"ax must hold 3 Axes, got {axes.size}")
    time_series(sol.t, {"R": sol.R, "κ": sol.kappa}, axes=axes[:2], xlabel="")
    gamma = np.asarray(sol.gamma)
    for i in range(3):
        axes[2].plot(sol.t, gamma[i], lw=1.0, label=f"$\\gamma_{i + 1}$", **kw)
    axes[2].set_ylabel("γ (OG in body axes)")
    axes[2].legend(loc="best", fontsize=8)
    axes[2].grid(alpha=0.3)
    axes[2].set_xlabel("t")
    if new:
        axes[0].figure.tight_layout()
    return axes
