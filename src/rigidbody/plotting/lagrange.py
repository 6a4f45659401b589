"""Plotting helpers for :mod:`rigidbody.lagrange` (take an ``ax``, return artists)."""

from __future__ import annotations

from typing import Any

import numpy as np

from .common import get_ax

__all__ = ["plot_averaged", "plot_integrals", "plot_roots", "plot_top_motion", "slow_time_axis"]


def slow_time_axis(sol: Any, x: str = "tau") -> tuple[np.ndarray, str]:
    """The abscissa of a slow-variable plot: ``'tau'`` or ``'xi'`` (``xi = ln(1 + tau)``, as the paper)."""
    if x == "tau":
        return np.asarray(sol.tau), r"$\tau = \varepsilon t$"
    if x == "xi":
        return np.log1p(np.asarray(sol.tau)), r"$\xi = \ln(1 + \tau)$"
    raise ValueError(f"x must be 'tau' or 'xi', got {x!r}")


def plot_roots(sol: Any, ax: Any = None, x: str = "tau") -> list:
    """Draw u1, u2, u3 of an averaged solution against tau or xi; mark sign switches of delta1."""
    ax = get_ax(ax)
    xs, label = slow_time_axis(sol, x)
    arts = []
    for i, (name, c) in enumerate(zip(("u_1", "u_2", "u_3"), ("C0", "C1", "C2"))):
        arts += ax.plot(xs, sol.u[i], color=c, lw=1.4, label=f"${name}$")
    for te in np.asarray(sol.t_events.get("delta1_flip", [])):
        xv = te if x == "tau" else np.log1p(te)
        arts.append(ax.axvline(xv, color="0.6", ls=":", lw=1.0))
    ax.axhline(1.0, color="0.8", lw=0.8)
    ax.axhline(-1.0, color="0.8", lw=0.8)
    ax.set_xlabel(label)
    ax.set_ylabel("roots of Q(u)")
    ax.legend(loc="best", fontsize=8)
    ax.grid(alpha=0.3)
    return arts


def plot_integrals(sol: Any, ax: Any = None, x: str = "tau", mgl: float | None = None) -> list:
    """Draw Gz, H, r of an averaged solution against tau or xi (and the limit H = -mgl if given)."""
    ax = get_ax(ax)
    xs, label = slow_time_axis(sol, x)
    arts = []
    arts += ax.plot(xs, sol.Gz, color="C3", lw=1.4, label="$G_z$")
    arts += ax.plot(xs, sol.H, color="C4", lw=1.4, label="$H$")
    arts += ax.plot(xs, sol.r, color="C5", lw=1.4, label="$r$")
    if mgl is not None:
        arts.append(ax.axhline(-mgl, color="C4", ls="--", lw=0.8))
    ax.axhline(0.0, color="0.8", lw=0.8)
    ax.set_xlabel(label)
    ax.set_ylabel("slow variables")
    ax.legend(loc="best", fontsize=8)
    ax.grid(alpha=0.3)
    return arts


def _panels(ax: Any, n: int, figsize: tuple[float, float]) -> np.ndarray:
    if ax is not None:
        axes = np.asarray(ax, dtype=object).ravel()
        if axes.size != n:
            raise ValueError(f"ax must hold {n} Axes, got {axes.size}")
        return axes
    import matplotlib.pyplot as plt

    _, axes = plt.subplots(1, n, figsize=figsize)
    return np.asarray(axes, dtype=object)


def plot_averaged(sol: Any, ax: Any = None, x: str = "tau") -> np.ndarray:
    """The standard figure of :func:`rigidbody.lagrange.averaged`: :func:`plot_roots` and
    :func:`plot_integrals` side by side (two Axes, created when ``ax`` is None); returns the Axes."""
    axes = _panels(ax, 2, (11.0, 4.0))
    plot_roots(sol, axes[0], x=x)
    plot_integrals(sol, axes[1], x=x)
    if ax is None:
        axes[0].figure.tight_layout()
    return axes


def plot_top_motion(sol: Any, ax: Any = None, **kw: Any) -> np.ndarray:
    """The standard figure of a full motion (:func:`rigidbody.lagrange.simulate`,
    :func:`rigidbody.lagrange.lagrange_motion`): the nutation ``u = cos(theta)`` and the integrals
    ``Gz, H, r`` against the time (two Axes, created when ``ax`` is None); returns the Axes.

    ``u`` moves between the roots ``u1`` and ``u2`` of the unperturbed motion; ``Gz, H, r`` are its
    integrals, constant without a torque and slowly changing under one.
    """
    axes = _panels(ax, 2, (11.0, 4.0))
    t = np.asarray(sol.time)
    axes[0].plot(t, sol.u, lw=0.8, **kw)
    axes[0].set_ylabel(r"$u = \cos\theta$")
    for name, label, c in (("Gz", "$G_z$", "C3"), ("H", "$H$", "C4"), ("r", "$r$", "C5")):
        # lagrange_motion keeps the constant integrals as single values
        axes[1].plot(t, np.broadcast_to(np.asarray(getattr(sol, name), dtype=float), t.shape), color=c, lw=1.0,
                     label=label)
    axes[1].set_ylabel("integrals (1.2)")
    axes[1].legend(loc="best", fontsize=8)
    for a in axes:
        a.set_xlabel(f"${sol.time_name}$")
        a.grid(alpha=0.3)
    if ax is None:
        axes[0].figure.tight_layout()
    return axes
