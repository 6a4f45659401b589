"""Plots for :mod:`rigidbody.viscous`: axis paths on a shaded unit sphere, one turn with its solid
angle, and time histories of k, R, s, ξ, ζ (Krivtsov 2000, figs 2-5)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .common import get_ax, time_series, unit_sphere

__all__ = ["look_from", "quasi_coordinate_histories", "sphere_path", "turn_solid_angle"]


def look_from(ax: Any, direction: Any) -> Any:
    """Turn a 3-D axes so that the viewer looks at the sphere from ``direction`` (a 3-vector)."""
    d = np.asarray(direction, dtype=float)
    d = d / np.linalg.norm(d)
    ax.view_init(elev=math.degrees(math.asin(max(-1.0, min(1.0, d[2])))), azim=math.degrees(math.atan2(d[1], d[0])))
    return ax


def _view_vector(ax: Any) -> np.ndarray:
    el, az = math.radians(ax.elev), math.radians(ax.azim)
    return np.array([math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)])


def sphere_path(
    n: Any,
    ax: Any = None,
    *,
    view: Any = None,
    sphere: bool = True,
    color: str = "C3",
    lw: float = 1.2,
    label: str | None = None,
    mark_ends: bool = True,
) -> Any:
    """Draw a path ``n`` (shape (3, m)) of unit vectors on a shaded unit sphere.

    Parameters
    ----------
    n : array_like, shape (3, m)
        Points on the unit sphere (e.g. ``sim.n`` or :func:`rigidbody.viscous.axis_path`).
    ax : Axes3D, optional
    view : array_like (3,), optional
        Direction to look from (default: the mean of the path). Parts of the path on the far side of the
        sphere are drawn dashed and faint.
    sphere : bool
        Draw the shaded unit sphere (:func:`rigidbody.plotting.common.unit_sphere`).
    color, lw, label
        Line style.
    mark_ends : bool
        Mark the start (circle) and the end (cross).

    Returns
    -------
    Axes3D
    """
    n = np.asarray(n, dtype=float)
    if n.ndim != 2 or n.shape[0] != 3:
        raise ValueError(f"n must have shape (3, m), got {n.shape}")
    ax = unit_sphere(ax) if sphere else get_ax(ax, projection="3d")
    look_from(ax, n.mean(axis=1) if view is None else view)
    d = _view_vector(ax)
    front = d @ n >= 0.0
    r = 1.003  # lift the line off the surface so it is not hidden by it
    for mask, style in ((front, {"ls": "-", "alpha": 1.0}), (~front, {"ls": "--", "alpha": 0.35})):
        if not np.any(mask):
            continue
        seg = np.where(mask, 1.0, np.nan)
        ax.plot(*(r * n * seg), color=color, lw=lw, zorder=5, **style)
    if label is not None:
        ax.plot([], [], color=color, lw=lw, label=label)
    if mark_ends:
        ax.scatter(*(r * n[:, :1]), color=color, marker="o", s=18, zorder=6)
        ax.scatter(*(r * n[:, -1:]), color="k", marker="x", s=24, zorder=6)
    ax.set_axis_off()
    return ax


def turn_solid_angle(turn: Any, ax: Any = None, *, color: str = "C0", fill: str = "C1", view: Any = None) -> Any:
    """Draw one turn of the spiral (:func:`rigidbody.viscous.turn`), the closing meridian arc and the
    enclosed solid angle χ (filled), seen from the turn's centre (figs 4-5)."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    n = np.asarray(turn.n)
    c = np.asarray(turn.centre)
    ax = unit_sphere(ax, alpha=0.15)
    look_from(ax, c if view is None else view)
    # fan of thin spherical triangles from the centre, lifted slightly above the sphere
    m = n.shape[1]
    tris = []
    lift = 1.002
    for j in range(m - 1):
        tris.append(lift * np.stack([c, n[:, j], n[:, j + 1]]))
    ax.add_collection3d(Poly3DCollection(tris, facecolor=fill, edgecolor="none", alpha=0.35))
    r = 1.004
    ax.plot(*(r * n), color=color, lw=1.6, zorder=5, label="one turn")
    # closing arc n(t2) -> n(t1) along the meridian through the centre
    a, b = n[:, -1], n[:, 0]
    w = np.linspace(0.0, 1.0, 50)
    ang = math.acos(max(-1.0, min(1.0, float(a @ b))))
    if ang > 0:
        arc = (np.sin((1 - w) * ang)[None, :] * a[:, None] + np.sin(w * ang)[None, :] * b[:, None]) / math.sin(ang)
        ax.plot(*(r * arc), color="k", lw=1.2, ls=":", zorder=5, label="closing arc")
    ax.scatter(*(r * c[:, None]), color="k", marker="+", s=30, zorder=6)
    ax.set_axis_off()
    ax.set_title(f"χ = {turn.chi:.4g} (cap approx. {turn.chi_approx:.4g}),  Δζ = {turn.dzeta:.4g}", fontsize=9)
    # zoom on the turn
    half = 1.3 * max(float(np.max(np.linalg.norm(n - c[:, None], axis=0))), 0.05)
    for setter, ci in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), c):
        setter(ci - half, ci + half)
    return ax


def quasi_coordinate_histories(t: Any, data: dict[str, Any], axes: Any = None, title: str | None = None) -> Any:
    """Time histories (one panel each) of e.g. ``{'k': k, 'R': R, 's': s, 'ξ': xi, 'ζ': zeta}``."""
    axes = time_series(t, data, axes=axes, title=title)
    if "k" in data:
        k = np.asarray(data["k"])
        if np.all(k > 0) and k.max() / k.min() > 100:
            axes[0].set_yscale("log")
    return axes
