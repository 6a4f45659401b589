"""Plotting helpers for :mod:`rigidbody.lagrange` (take an ``ax``, return artists)."""

from __future__ import annotations

from typing import Any

import numpy as np

from .common import get_ax

__all__ = ["plot_integrals", "plot_roots", "slow_time_axis"]


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
