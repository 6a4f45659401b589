"""Plots for :mod:`rigidbody.euler_poinsot`: the hodograph of the angular momentum in the orbital axes
(3-D, projections, view along the spiral axis) and the slow variables against tau (Rachinskaya, figs 1-6)."""

from __future__ import annotations

from typing import Any

import numpy as np

from .common import get_ax

__all__ = ["hodograph", "hodograph_3d", "hodograph_projection", "slow_variables", "spiral_axis"]


def hodograph(sol: Any) -> np.ndarray:
    """The points of the hodograph, :math:`\\mathbf G = G\\mathbf n` in the orbital axes, shape (3, n)."""
    return np.asarray(sol.G) * np.asarray(sol.n)


def spiral_axis(sol: Any) -> np.ndarray:
    r"""Direction of the spiral's axis: the mean of :math:`\mathbf n` weighted by the turning :math:`|d\lambda|`.

    In the orbit-averaged limit this is :math:`x_3` exactly (:math:`\delta` is constant); with :math:`\nu`
    kept it wobbles by :math:`O(\varepsilon)`.
    """
    n = np.asarray(sol.n)
    lam = np.asarray(sol.lam)
    if lam.size < 2:
        return np.array([0.0, 0.0, 1.0])
    w = np.abs(np.gradient(lam))
    a = (n * w).sum(axis=1)
    nrm = np.linalg.norm(a)
    return a / nrm if nrm > 0 else np.array([0.0, 0.0, 1.0])


def hodograph_3d(sol: Any, ax: Any = None, **kw: Any) -> Any:
    """Draw the hodograph in the axes :math:`Ox_1x_2x_3` (paper's figs 1 and 4); returns the line."""
    ax = get_ax(ax, projection="3d")
    h = hodograph(sol)
    (line,) = ax.plot(h[0], h[1], h[2], **kw)
    ax.scatter([h[0, 0]], [h[1, 0]], [h[2, 0]], color=line.get_color(), s=12)
    ax.set_xlabel("$x_1$")
    ax.set_ylabel("$x_2$")
    ax.set_zlabel("$x_3$")
    return line


def hodograph_projection(sol: Any, ax: Any = None, normal: Any = (0.0, 0.0, 1.0), **kw: Any) -> Any:
    """Project the hodograph on the plane orthogonal to ``normal`` (``(0, 0, 1)``: the plane :math:`Ox_1x_2`,
    fig. 2; :func:`spiral_axis`: the view along the spiral, fig. 3). Returns the line."""
    ax = get_ax(ax)
    d = np.asarray(normal, dtype=float)
    d = d / np.linalg.norm(d)
    # in-plane basis: e1 = x1 projected (or x2 if x1 is the normal), e2 = d x e1
    ref = np.array([1.0, 0.0, 0.0]) if abs(d[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    e1 = ref - d * (ref @ d)
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(d, e1)
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


def slow_variables(sol: Any, axes: Any = None, label: str | None = None, **kw: Any) -> Any:
    """Plot G, T, k², δ, λ against τ on five axes (created when ``axes`` is None); returns the axes."""
    if axes is None:
        import matplotlib.pyplot as plt

        _, axes = plt.subplots(5, 1, figsize=(6.0, 9.0), sharex=True)
    names = [("G", "$G$"), ("T", "$T$"), ("k2", "$k^2$"), ("delta", "$\\delta$"), ("lam", "$\\lambda$")]
    for ax, (f, lab) in zip(axes, names):
        ax.plot(sol.tau, getattr(sol, f), label=label, **kw)
        ax.set_ylabel(lab)
    axes[-1].set_xlabel("$\\tau$")
    if label is not None:
        axes[0].legend(fontsize=8)
    return axes


