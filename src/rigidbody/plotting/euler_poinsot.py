"""Plots for :mod:`rigidbody.euler_poinsot`: the hodograph of the angular momentum in the orbital axes
(3-D, projections, view along the spiral axis) and the slow variables against tau (Rachinskaya, figs 1-6)."""

from __future__ import annotations

from typing import Any

import numpy as np

from .common import get_ax

__all__ = [
    "equal_3d",
    "hodograph",
    "hodograph_3d",
    "hodograph_projection",
    "hodograph_side_view",
    "plane_basis",
    "slow_variables",
    "spiral_axis",
]


def hodograph(sol: Any) -> np.ndarray:
    """The points of the hodograph, :math:`\\mathbf G = G\\mathbf n` in the orbital axes, shape (3, n)."""
    return np.asarray(sol.G) * np.asarray(sol.n)


def spiral_axis(sol: Any) -> np.ndarray:
    r"""Direction of the spiral's axis: the axis of the cone that best fits the directions :math:`\mathbf n`.

    The hodograph :math:`G\mathbf n` lies on a cone of half-angle :math:`\delta` about its axis when
    :math:`\mathbf a\cdot\mathbf n` is constant. The axis :math:`\mathbf a` is taken as the eigenvector of the
    smallest eigenvalue of the covariance of :math:`\mathbf n`, the samples weighted by the arc length
    they cover (so a dense output grid does not pull the fit towards a slow part of the path). It is exact
    for a circular cone however few of its turns are sampled: in the orbit-averaged limit
    (:math:`\delta` constant) it is :math:`x_3`; with :math:`\nu` kept it wobbles by :math:`O(\varepsilon)`.
    Oriented so that the mean of :math:`\mathbf a\cdot\mathbf n` is positive; :math:`x_3` if the path is
    too short to define a cone.
    """
    n = np.asarray(sol.n, dtype=float)
    if n.ndim != 2 or n.shape[1] < 3:
        return np.array([0.0, 0.0, 1.0])
    seg = np.linalg.norm(np.diff(n, axis=1), axis=0)
    w = np.zeros(n.shape[1])
    w[:-1] += seg / 2
    w[1:] += seg / 2
    if w.sum() <= 0:
        return np.array([0.0, 0.0, 1.0])
    mean = (n * w).sum(axis=1) / w.sum()
    d = n - mean[:, None]
    cov = (d * w) @ d.T / w.sum()
    vals, vecs = np.linalg.eigh(cov)
    if vals[1] <= 1e-12 * max(vals[2], 1e-300):  # the samples (nearly) lie on one line: no plane, no axis
        return np.array([0.0, 0.0, 1.0])
    a = vecs[:, 0]
    return a if a @ mean >= 0 else -a


def hodograph_3d(sol: Any, ax: Any = None, **kw: Any) -> Any:
    """Draw the hodograph in the axes :math:`Ox_1x_2x_3` (paper's figs 1 and 4); returns the line.

    The start is marked by a dot; the axes get equal scales (:func:`equal_3d`) so that the cone on which the
    hodograph lies is not distorted.
    """
    ax = get_ax(ax, projection="3d")
    h = hodograph(sol)
    (line,) = ax.plot(h[0], h[1], h[2], **kw)
    ax.scatter([h[0, 0]], [h[1, 0]], [h[2, 0]], color=line.get_color(), s=12)
    ax.set_xlabel("$x_1$")
    ax.set_ylabel("$x_2$")
    ax.set_zlabel("$x_3$")
    equal_3d(ax)
    return line


def equal_3d(ax: Any) -> Any:
    """Give a 3-D axes equal scales on its three axes (a box around everything drawn so far)."""
    pts = [np.asarray(line.get_data_3d(), dtype=float) for line in ax.lines]
    if not pts:
        return ax
    p = np.concatenate(pts, axis=1)
    lo, hi = np.nanmin(p, axis=1), np.nanmax(p, axis=1)
    span = np.maximum(hi - lo, 1e-12)
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_zlim(lo[2], hi[2])
    ax.set_box_aspect(tuple(span / span.max()))
    return ax


def plane_basis(normal: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Unit ``normal`` and an in-plane basis ``(e1, e2)``: ``e1`` is :math:`x_1` projected on the plane (or
    :math:`x_2` when the normal is close to :math:`x_1`), ``e2 = normal x e1``."""
    d = np.asarray(normal, dtype=float)
    if d.shape != (3,) or not np.all(np.isfinite(d)) or np.linalg.norm(d) == 0:
        raise ValueError(f"normal must be a finite nonzero 3-vector, got {normal!r}")
    d = d / np.linalg.norm(d)
    ref = np.array([1.0, 0.0, 0.0]) if abs(d[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    e1 = ref - d * (ref @ d)
    e1 /= np.linalg.norm(e1)
    return d, e1, np.cross(d, e1)


def hodograph_projection(sol: Any, ax: Any = None, normal: Any = (0.0, 0.0, 1.0), **kw: Any) -> Any:
    """Project the hodograph on the plane orthogonal to ``normal`` (``(0, 0, 1)``: the plane :math:`Ox_1x_2`,
    fig. 2; :func:`spiral_axis`: the view along the spiral, fig. 3). Returns the line.

    The in-plane coordinates are those of :func:`plane_basis`; the start is marked by a dot.
    """
    ax = get_ax(ax)
    d, e1, e2 = plane_basis(normal)
    h = hodograph(sol)
    (line,) = ax.plot(e1 @ h, e2 @ h, **kw)
    ax.plot([e1 @ h[:, 0]], [e2 @ h[:, 0]], "o", color=line.get_color(), ms=3)
    ax.set_aspect("equal", adjustable="datalim")
    if np.allclose(d, [0, 0, 1]):
        ax.set_xlabel("$x_1$")
        ax.set_ylabel("$x_2$")
    else:
        ax.set_xlabel("along $x_1$ projected")
        ax.set_ylabel("normal $\\times$ that")
    return line


def hodograph_side_view(sol: Any, ax: Any = None, axis: Any = (0.0, 0.0, 1.0), **kw: Any) -> Any:
    """The hodograph seen from the side of ``axis``: distance from the axis against the height along it.

    A hodograph on a cone about ``axis`` (constant angle :math:`\\delta` to it) is a straight line through
    the origin here, so a bent spiral axis shows as a curved line. Returns the line.
    """
    ax = get_ax(ax)
    d, _, _ = plane_basis(axis)
    h = hodograph(sol)
    along = d @ h
    across = np.linalg.norm(h - np.outer(d, along), axis=0)
    (line,) = ax.plot(across, along, **kw)
    ax.set_xlabel("distance from the axis")
    ax.set_ylabel("height along the axis")
    return line


def slow_variables(sol: Any, axes: Any = None, label: str | None = None, **kw: Any) -> Any:
    """Plot G, T, k², δ, λ against τ on five axes (created when ``axes`` is None); returns the axes."""
    new = axes is None
    if new:
        import matplotlib.pyplot as plt

        _, axes = plt.subplots(5, 1, figsize=(6.0, 9.0), sharex=True)
    names = [("G", "$G$"), ("T", "$T$"), ("k2", "$k^2$"), ("delta", "$\\delta$"), ("lam", "$\\lambda$")]
    for ax, (f, lab) in zip(axes, names):
        ax.plot(sol.tau, getattr(sol, f), label=label, **kw)
        ax.set_ylabel(lab)
    axes[-1].set_xlabel("$\\tau$")
    if label is not None:
        axes[0].legend(fontsize=8)
    if new:
        axes[0].figure.tight_layout()
    return axes


