"""Plots for :mod:`rigidbody.viscous`: axis paths on a shaded unit sphere, one turn with its solid
angle, and time histories of k, R, s, ξ, ζ (Krivtsov 2000, figs 2-5)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .common import get_ax, time_series, unit_sphere

__all__ = [
    "ball_and_rod_sketch",
    "look_from",
    "plot_axis_path",
    "quasi_coordinate_histories",
    "sphere_path",
    "turn_solid_angle",
]


def look_from(ax: Any, direction: Any) -> Any:
    """Turn a 3-D axes so that the viewer looks at the sphere from ``direction`` (a 3-vector).

    Parameters
    ----------
    ax : Axes3D
    direction : array_like, shape (3,)
        Where the viewer stands (any length).

    Returns
    -------
    Axes3D

    See Also
    --------
    sphere_path : draws a path seen from a direction.

    Examples
    --------
    From the ``y`` axis: azimuth 90 degrees, elevation 0; from the ``z`` axis: elevation 90:

    >>> from rigidbody.plotting import get_ax, look_from
    >>> ax = look_from(get_ax(projection="3d"), [0.0, 2.0, 0.0])
    >>> print(f"{ax.azim:.1f} {ax.elev:.1f}")
    90.0 0.0
    >>> print(f"{look_from(ax, [0.0, 0.0, 1.0]).elev:.1f}")
    90.0
    """
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

    See Also
    --------
    plot_axis_path : the standard figure of :func:`rigidbody.viscous.simulate`.
    rigidbody.viscous.axis_path : a path to draw.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, figs 2-3.

    Examples
    --------
    By default the view is from the mean of the path; a quarter of the equator is seen from azimuth 45
    degrees:

    >>> import numpy as np
    >>> from rigidbody.plotting import sphere_path
    >>> t = np.linspace(0.0, np.pi / 2, 50)
    >>> ax = sphere_path(np.array([np.cos(t), np.sin(t), 0 * t]))
    >>> print(f"{ax.azim:.1f} {ax.elev:.1f}")
    45.0 0.0
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
    enclosed solid angle χ (filled), seen from the turn's centre (figs 4-5).

    Parameters
    ----------
    turn : rigidbody.viscous.Turn
    ax : Axes3D, optional
    color, fill : str
        Colours of the path and of the solid angle.
    view : array_like (3,), optional
        Direction to look from (default: the turn's centre).

    Returns
    -------
    Axes3D

    See Also
    --------
    rigidbody.viscous.turn : the turn drawn.
    sphere_path : a whole path.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, section 5, figs 4-5.

    Examples
    --------
    The title gives the solid angle and its cap approximation (equal on Routh's circle):

    >>> from rigidbody import viscous
    >>> body, medium = viscous.Body(theta12=2.0, theta3=1.0), viscous.Medium(B12=0.4, B3=0.1)
    >>> from rigidbody.plotting import turn_solid_angle
    >>> tr = viscous.turn(body, viscous.Medium(B12=0.2, B3=0.1), [1, 0, 0], [0, 2, 0], 6.0)
    >>> print(turn_solid_angle(tr).get_title())
    χ = 1.055 (cap approx. 1.055),  Δζ = 10.46
    """
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
    """Time histories (one panel each) of e.g. ``{'k': k, 'R': R, 's': s, 'ξ': xi, 'ζ': zeta}``.

    A curvature ``k`` that grows by more than a factor 100 gets a logarithmic axis.

    Parameters
    ----------
    t : array_like
    data : dict of str to array_like
    axes : sequence of Axes, optional
    title : str, optional

    Returns
    -------
    numpy.ndarray of Axes

    See Also
    --------
    rigidbody.viscous.quasi_coordinates, rigidbody.viscous.curvature : the data.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, eqs. (4.5), (5.1)-(5.2).

    Examples
    --------
    The curvature of the contracting spiral grows like ``exp(0.1 t)``, a factor ``e^8`` by ``t = 80``:

    >>> import numpy as np
    >>> from rigidbody import viscous
    >>> body, medium = viscous.Body(theta12=2.0, theta3=1.0), viscous.Medium(B12=0.4, B3=0.1)
    >>> from rigidbody.plotting import quasi_coordinate_histories
    >>> t = np.linspace(0.0, 80.0, 161)
    >>> s, xi, zeta = viscous.quasi_coordinates(body, medium, 6.0, 2.0, t)
    >>> axes = quasi_coordinate_histories(t, {"k": viscous.curvature(body, medium, 6.0, 2.0, t), "s": s})
    >>> axes[0].get_yscale(), axes[1].get_yscale()
    ('log', 'linear')
    """
    axes = time_series(t, data, axes=axes, title=title)
    if "k" in data:
        k = np.asarray(data["k"])
        if np.all(k > 0) and k.max() / k.min() > 100:
            axes[0].set_yscale("log")
    return axes


def ball_and_rod_sketch(
    N: int, a: float, b: float, ball_radius: float, ax: Any = None, *, view: Any = (1.0, -0.55, 0.45)
) -> Any:
    """Draw the ball-and-rod structure of Krivtsov's fig. 1 (the model of :func:`rigidbody.viscous.ball_and_rod`).

    The rod ``AB`` (length ``2b``) is the symmetry axis ``n``; ``N`` equal balls sit on a circle of radius
    ``a`` about its centre ``C`` in the plane normal to it, joined to ``C`` by spokes; two more balls at
    ``A`` and ``B``. Balls are drawn to scale with radius ``ball_radius``.

    Parameters
    ----------
    N : int
        Number of balls on the circle (>= 3).
    a, b : float
        Circle radius and half-length of the rod.
    ball_radius : float
        Radius of the balls as drawn.
    ax : Axes3D, optional
    view : array_like (3,)
        Direction to look from.

    Returns
    -------
    Axes3D

    See Also
    --------
    rigidbody.viscous.ball_and_rod : the body and medium of this structure.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, section 2, fig. 1.

    Examples
    --------
    The balls on the circle are numbered 1 to N, the rod's ends are A and B:

    >>> from rigidbody.plotting import ball_and_rod_sketch
    >>> ax = ball_and_rod_sketch(4, 1.0, 1.5, 0.3)
    >>> sorted(t.get_text() for t in ax.texts)
    ['1', '2', '3', '4', 'A', 'B', 'C', 'n']
    """
    if N < 3:
        raise ValueError(f"N must be >= 3, got {N!r}")
    ax = get_ax(ax, projection="3d")
    u = np.linspace(0.0, 2.0 * np.pi, 24)
    w = np.linspace(0.0, np.pi, 12)
    sx = np.outer(np.cos(u), np.sin(w))
    sy = np.outer(np.sin(u), np.sin(w))
    sz = np.outer(np.ones_like(u), np.cos(w))

    def ball(c: np.ndarray, color: str) -> None:
        ax.plot_surface(c[0] + ball_radius * sx, c[1] + ball_radius * sy, c[2] + ball_radius * sz,
                        color=color, linewidth=0, shade=True)

    ax.plot([0, 0], [0, 0], [-b, b], color="0.2", lw=2.0)
    ang = 2.0 * np.pi * np.arange(N) / N
    ring = np.linspace(0.0, 2.0 * np.pi, 200)
    ax.plot(a * np.cos(ring), a * np.sin(ring), 0 * ring, color="0.6", lw=0.8, ls=":")
    for k, t in enumerate(ang):
        c = np.array([a * np.cos(t), a * np.sin(t), 0.0])
        ax.plot([0, c[0]], [0, c[1]], [0, 0], color="0.35", lw=1.2)
        ball(c, "C0")
        ax.text(*(c * (1 + 2.2 * ball_radius / a)), str(k + 1), fontsize=9, ha="center", va="center")
    # labels of A and B to the left of their balls as seen from ``view``
    d = np.asarray(view, dtype=float)
    left = np.cross(d, [0.0, 0.0, 1.0])
    left = left / np.linalg.norm(left) if np.linalg.norm(left) > 0 else np.array([1.0, 0.0, 0.0])
    for z, name in ((b, "A"), (-b, "B")):
        ball(np.array([0.0, 0.0, z]), "C3")
        ax.text(*(2.2 * ball_radius * left + [0.0, 0.0, z]), name, fontsize=10, ha="center", va="center")
    ax.text(0.15 * a, 0.0, 0.12 * a, "C", fontsize=10)
    ax.plot([0, 0], [0, 0], [b + 1.5 * ball_radius, b + 0.45 * a + 1.5 * ball_radius], color="k", lw=1.0)
    ax.text(0.05 * a, 0, b + 0.5 * a + 1.5 * ball_radius, "n", fontsize=10, style="italic")
    lim = max(a, b) + 2.0 * ball_radius
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    ax.set_zlim(-lim, lim)
    ax.set_box_aspect((1, 1, 1), zoom=1.25)
    look_from(ax, view)
    ax.set_axis_off()
    return ax


def plot_axis_path(sol: Any, ax: Any = None, **kw: Any) -> Any:
    """The standard figure of :func:`rigidbody.viscous.simulate`: the path of the symmetry axis ``sol.n`` on
    the unit sphere (:func:`sphere_path`; the sphere is drawn once, on an empty Axes). Returns the Axes3D.

    Parameters
    ----------
    sol : Solution
        A run of :func:`rigidbody.viscous.simulate`.
    ax : Axes3D, optional
    **kw
        Passed to :func:`sphere_path`.

    Returns
    -------
    Axes3D

    See Also
    --------
    rigidbody.plotting.plot_solution : ``sol.plot()``, which calls it.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, figs 2-3.

    Examples
    --------
    >>> import numpy as np
    >>> from rigidbody import viscous
    >>> body, medium = viscous.Body(theta12=2.0, theta3=1.0), viscous.Medium(B12=0.4, B3=0.1)
    >>> from rigidbody.plotting import plot_axis_path
    >>> sim = viscous.simulate(body, medium, [1, 0, 0], [0, 2, 0], 6.0, (0.0, 20.0), t_eval=np.linspace(0, 20, 201))
    >>> ax = plot_axis_path(sim)
    >>> ax is plot_axis_path(sim, ax, color="C0")
    True
    """
    sphere = ax is None or not ax.collections
    return sphere_path(sol.n, ax, sphere=sphere, **kw)
