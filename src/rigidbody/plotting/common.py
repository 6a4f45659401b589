"""Shared plotting helpers (axes, unit sphere, time series) and the standard plot of a result."""

from __future__ import annotations

import importlib
from collections.abc import Callable
from typing import Any

import numpy as np

__all__ = ["STANDARD_PLOTS", "get_ax", "plot_solution", "standard_plot", "time_series", "unit_sphere"]

#: The standard figure of each kind of result: (fields the result carries, ``"module:function"`` that draws
#: it). The first row whose fields a result has wins, so a more specific row comes first. A new analysis
#: module adds its row here; the function takes ``(sol, ax=None, **kwargs)`` and returns what it drew on
#: (an Axes or an array of Axes) and accepts that back as ``ax``, so members of a batch share the panels.
STANDARD_PLOTS: tuple[tuple[frozenset[str], str], ...] = (
    (frozenset({"u1", "u2", "u3", "Gz", "H", "r", "delta1"}), "rigidbody.plotting.lagrange:plot_averaged"),
    (frozenset({"theta", "u", "Gz", "H", "r"}), "rigidbody.plotting.lagrange:plot_top_motion"),
    (frozenset({"G", "T", "k2", "delta", "lam"}), "rigidbody.plotting.euler_poinsot:slow_variables"),
    (frozenset({"R", "kappa", "gamma"}), "rigidbody.plotting.gyrostat:plot_satellite_motion"),
    (frozenset({"n", "k", "zeta", "Omega"}), "rigidbody.plotting.viscous:plot_axis_path"),
)


def get_ax(ax: Any = None, projection: str | None = None, figsize: tuple[float, float] = (6.0, 4.5)) -> Any:
    """Return ``ax`` or a new ``Axes`` (``projection='3d'`` for 3-D) on a new figure.

    Parameters
    ----------
    ax : matplotlib.axes.Axes, optional
        Returned as it is when given.
    projection : str, optional
        ``'3d'`` for a 3-D axes.
    figsize : (float, float)
        Size of the new figure (inches).

    Returns
    -------
    matplotlib.axes.Axes

    See Also
    --------
    unit_sphere : a 3-D axes with the unit sphere.

    Examples
    --------
    >>> from rigidbody.plotting import get_ax
    >>> ax = get_ax()
    >>> get_ax(ax) is ax, get_ax(projection="3d").name
    (True, '3d')
    """
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt

    fig = plt.figure(figsize=figsize)
    return fig.add_subplot(111, projection=projection) if projection else fig.add_subplot(111)


def unit_sphere(
    ax: Any = None,
    *,
    alpha: float = 0.25,
    color: str = "0.8",
    shade: bool = True,
    resolution: int = 60,
    light: tuple[float, float, float] = (1.0, -1.0, 1.0),
) -> Any:
    """Draw a (lightly shaded) unit sphere on a 3-D axes and set an equal aspect.

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.Axes3D, optional
        Target axes (a new 3-D axes if None).
    alpha, color : float, str
        Surface transparency and base colour.
    shade : bool
        Lambertian shading from the direction ``light``.
    resolution : int
        Grid points per angle.

    Returns
    -------
    Axes3D

    See Also
    --------
    rigidbody.plotting.sphere_path : a path drawn on this sphere.

    Examples
    --------
    >>> from rigidbody.plotting import unit_sphere
    >>> ax = unit_sphere()
    >>> print(*(f"{x:.2f}" for x in ax.get_xlim()), *(f"{z:.2f}" for z in ax.get_zlim()))
    -1.05 1.05 -1.05 1.05
    """
    ax = get_ax(ax, projection="3d")
    u = np.linspace(0.0, 2.0 * np.pi, resolution)
    v = np.linspace(0.0, np.pi, resolution // 2)
    x = np.outer(np.cos(u), np.sin(v))
    y = np.outer(np.sin(u), np.sin(v))
    z = np.outer(np.ones_like(u), np.cos(v))
    if shade:
        from matplotlib import colors

        ld = np.asarray(light, dtype=float)
        ld = ld / np.linalg.norm(ld)
        inten = np.clip(x * ld[0] + y * ld[1] + z * ld[2], 0.0, 1.0)
        base = np.array(colors.to_rgb(color))
        rgb = (0.45 + 0.55 * inten)[..., None] * base
        ax.plot_surface(x, y, z, facecolors=np.clip(rgb, 0, 1), rstride=1, cstride=1, linewidth=0,
                        antialiased=False, alpha=alpha, shade=False)
    else:
        ax.plot_surface(x, y, z, color=color, linewidth=0, alpha=alpha)
    ax.set_box_aspect((1, 1, 1), zoom=1.25)  # the sphere fills the axes' box
    lim = (-1.05, 1.05)
    ax.set_xlim(lim)
    ax.set_ylim(lim)
    ax.set_zlim(lim)
    return ax


def time_series(
    t: Any, series: dict[str, Any], *, xlabel: str = "t", axes: Any = None, title: str | None = None
) -> Any:
    """Plot named arrays against ``t``, one panel each; return the array of axes.

    Parameters
    ----------
    t : array_like
        The abscissa.
    series : dict of str to array_like
        Name (the panel's label) to the values at ``t``.
    xlabel : str
        Label of the shared abscissa.
    axes : sequence of Axes, optional
        One per series (new ones, sharing the abscissa, by default).
    title : str, optional
        Title of a new figure.

    Returns
    -------
    numpy.ndarray of Axes

    See Also
    --------
    rigidbody.plotting.quasi_coordinate_histories : the histories of the viscous module.

    Examples
    --------
    >>> import numpy as np
    >>> from rigidbody.plotting import time_series
    >>> t = np.linspace(0.0, 10.0, 101)
    >>> axes = time_series(t, {"v": np.exp(-0.2 * t), "Ω": 6 * np.exp(-0.1 * t)})
    >>> len(axes), [ax.get_ylabel() for ax in axes], axes[-1].get_xlabel()
    (2, ['v', 'Ω'], 't')
    """
    import matplotlib.pyplot as plt

    n = len(series)
    if axes is None:
        fig, axes = plt.subplots(n, 1, figsize=(6.0, 1.8 * n + 0.6), sharex=True, squeeze=False)
        axes = axes[:, 0]
        if title:
            fig.suptitle(title)
    for ax, (name, val) in zip(axes, series.items()):
        ax.plot(t, val, lw=1.2)
        ax.set_ylabel(name)
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel(xlabel)
    return axes


def standard_plot(sol: Any) -> Callable[..., Any]:
    """The function that draws the standard figure of ``sol`` (a row of :data:`STANDARD_PLOTS`).

    Parameters
    ----------
    sol : rigidbody.core.ode.Solution
        A result (its ``fields`` select the row).

    Returns
    -------
    callable
        ``func(sol, ax=None, **kwargs)``.

    Raises
    ------
    ValueError
        If no row matches the fields of ``sol``.

    See Also
    --------
    plot_solution : calls it.

    Examples
    --------
    >>> import numpy as np
    >>> from rigidbody import viscous
    >>> body, medium = viscous.Body(theta12=2.0, theta3=1.0), viscous.Medium(B12=0.4, B3=0.1)
    >>> sim = viscous.simulate(body, medium, [1, 0, 0], [0, 2, 0], 6.0, (0.0, 10.0), t_eval=np.linspace(0, 10, 51))
    >>> from rigidbody.plotting import standard_plot
    >>> standard_plot(sim).__name__
    'plot_axis_path'
    """
    fields = set(getattr(sol, "fields", ()))
    for needed, target in STANDARD_PLOTS:
        if needed <= fields:
            module, _, name = target.partition(":")
            func: Callable[..., Any] = getattr(importlib.import_module(module), name)
            return func
    raise ValueError(f"no standard plot for a result with fields {sorted(fields)}; draw its arrays with "
                     "rigidbody.plotting.time_series or Matplotlib")


def plot_solution(sol: Any, ax: Any = None, **kwargs: Any) -> Any:
    """Draw the standard figure of a result (``sol.plot()``): the function :func:`standard_plot` picks.

    Parameters
    ----------
    sol : rigidbody.core.ode.Solution
        A single run, or a batch run (``sol.batch_shape`` non-empty): then every member
        (``sol.member(index)``) is drawn on the same panels.
    ax : Axes or array of Axes, optional
        Where to draw (as many panels as the figure has); new ones by default.
    **kwargs
        Passed to the drawing function (line style, ``label``, ...).

    Returns
    -------
    Axes or numpy.ndarray of Axes
        What was drawn on.

    See Also
    --------
    standard_plot : the function it calls.
    STANDARD_PLOTS : the table of standard figures.

    Examples
    --------
    The standard figure of :func:`rigidbody.viscous.simulate` is the axis path on the unit sphere; a second
    result can be drawn on the same Axes:

    >>> import numpy as np
    >>> from rigidbody import viscous
    >>> body, medium = viscous.Body(theta12=2.0, theta3=1.0), viscous.Medium(B12=0.4, B3=0.1)
    >>> sim = viscous.simulate(body, medium, [1, 0, 0], [0, 2, 0], 6.0, (0.0, 10.0), t_eval=np.linspace(0, 10, 51))
    >>> from rigidbody.plotting import plot_solution
    >>> ax = plot_solution(sim)
    >>> ax.name, plot_solution(sim, ax, color="C0") is ax
    ('3d', True)
    """
    func = standard_plot(sol)
    batch_shape = tuple(getattr(sol, "batch_shape", ()))
    if not batch_shape:
        return func(sol, ax, **kwargs)
    for index in np.ndindex(*batch_shape):
        ax = func(sol.member(index), ax, **kwargs)
    return ax
