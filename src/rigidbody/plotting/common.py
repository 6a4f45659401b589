"""Shared plotting helpers (axes, unit sphere, time series)."""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["get_ax", "time_series", "unit_sphere"]


def get_ax(ax: Any = None, projection: str | None = None, figsize: tuple[float, float] = (6.0, 4.5)) -> Any:
    """Return ``ax`` or a new ``Axes`` (``projection='3d'`` for 3-D) on a new figure."""
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
    ax.set_box_aspect((1, 1, 1))
    lim = (-1.05, 1.05)
    ax.set_xlim(lim)
    ax.set_ylim(lim)
    ax.set_zlim(lim)
    return ax


def time_series(
    t: Any, series: dict[str, Any], *, xlabel: str = "t", axes: Any = None, title: str | None = None
) -> Any:
    """Plot named arrays against ``t``, one panel each; return the array of axes."""
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
